// Trust-aware optimal signaling for any finite game as a linear program (GLPK).
//
// Derivation (see also lp.h). By the revelation principle the signals can be
// taken to be action recommendations, with variables x(w, a) = pi(a | w).
// With P(a) = sum_w x(w, a) p0(w), the trust-weighted posterior after
// recommendation a is p_theta(w|a) = (1 - theta) p0(w) + theta x(w, a) p0(w) / P(a).
// Obedience, i.e. a is a best response to p_theta(.|a) (eq:receiver_action):
//   sum_w p_theta(w|a) D(w; a, a') >= 0 for all a' != a,  D(w; a, a') = u(w,a) - u(w,a').
// Multiplying by P(a) >= 0 removes the division:
//   sum_w [(1 - theta) p0(w) P(a) + theta x(w, a) p0(w)] D(w; a, a') >= 0.
// Substituting P(a) = sum_w' x(w', a) p0(w') and collecting the coefficient of each
// x(w', a) gives the linear row
//   sum_w' p0(w') [(1 - theta) dU0(a, a') + theta D(w'; a, a')] x(w', a) >= 0,
// where dU0(a, a') = sum_w p0(w) D(w; a, a') is the gain of a over a' at the prior.
// (When P(a) = 0 every x(., a) is 0 and the row holds trivially: an action that
// is never recommended imposes nothing, as it should.)
// Objective: maximise sum_w p0(w) sum_a x(w, a) v(w, a), subject to obedience,
// sum_a x(w, a) = 1 for every w and x >= 0. The scheme "always recommend the
// default action" is feasible, so the LP is feasible and (being bounded) has an
// optimum; kInfeasible is reported only if GLPK says so.
//
// Numerics.
// - Differences first: every coefficient is built from D(w; a, a') and dU0 is
//   the p0-weighted sum of those differences, never U(a|p0) - U(a'|p0), which
//   cancels catastrophically when a state's utilities are large (1e17 and 1e17
//   next to 0 and 1 used to give a disobedient "optimum").
// - Both tables are divided by a power of two near their largest |entry| (exact,
//   decision-neutral: obedience is homogeneous in u, the optimum in v), so
//   |u|, |v| < 2, |D| < 4, and entries like +-1e308 cannot overflow to inf;
//   each obedience row is then divided by its largest |coefficient|.
// - GLPK reports a fatal error by calling abort() unless an error hook is set;
//   every GLPK call here runs under glp_error_hook (RunGlpkGuarded), which
//   longjmps back, frees GLPK's environment and returns GLPK's message.
//
// Scaling. There are n m variables and m (m - 1) obedience rows of n entries
// each: for n = m = 100 that is 9900 dense rows, which GLPK's simplex took 103 s
// to solve. At an optimum only a few obedience rows bind, so they are generated
// lazily (a cutting-plane loop): solve with the rows found so far, add every
// row the solution violates by more than kRowViolation, re-solve with the dual
// simplex from the previous basis, until none is violated. Each round adds at
// least one of the finitely many rows, so the loop ends, and its answer is an
// optimum of the full LP (a relaxation's optimum that is feasible for the full
// LP is optimal for it). LpOptions::lazy_obedience = false builds the full LP
// at once (tests compare both). Measured limits: see lp.h and bench/lp_scaling.cc.
#include "taebp/persuasion/lp.h"

#include "internal.h"

#include <glpk.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <limits>
#include <string>
#include <vector>

namespace taebp::persuasion {

const char* ToString(LpResult::Status status) {
  switch (status) {
    case LpResult::Status::kOptimal:
      return "optimal";
    case LpResult::Status::kInfeasible:
      return "infeasible";
    case LpResult::Status::kSolverError:
      return "solver error";
  }
  return "unknown";
}

// ---------------------------------------------------------------------------
// GLPK's error path.
// ---------------------------------------------------------------------------
namespace {

struct GlpkGuard {
  std::jmp_buf env;
  void (*call)(void*);
  void* arg;
  std::string* log;
};

void OnGlpkError(void* info) { std::longjmp(static_cast<GlpkGuard*>(info)->env, 1); }

int OnGlpkTerminal(void* info, const char* text) {
  static_cast<std::string*>(info)->append(text);
  return 1;  // handled: GLPK prints nothing
}

// setjmp returns twice: 0 now, 1 when GLPK's error hook longjmps back. Between
// here and GLPK there are only this frame (a pointer, unchanged after setjmp)
// and guard->call's, which keeps no object with a destructor.
bool CallUnderHook(GlpkGuard* guard) {
  if (setjmp(guard->env) != 0) return false;
  glp_term_hook(OnGlpkTerminal, guard->log);
  glp_error_hook(OnGlpkError, guard);
  guard->call(guard->arg);
  glp_error_hook(nullptr, nullptr);
  glp_term_hook(nullptr, nullptr);
  return true;
}

}  // namespace

bool RunGlpkGuarded(void (*call)(void*), void* arg, std::string* error) {
  std::string scratch;
  GlpkGuard guard;
  guard.call = call;
  guard.arg = arg;
  guard.log = error != nullptr ? error : &scratch;
  guard.log->clear();
  if (CallUnderHook(&guard)) {
    guard.log->clear();  // anything printed without an error is not an error
    return true;
  }
  // GLPK's manual: after an error the environment is undefined; glp_free_env
  // frees every GLPK object of this thread (hooks included) and the next GLPK
  // call starts a fresh one.
  glp_free_env();
  std::string& log = *guard.log;
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  if (log.empty()) log = "GLPK reported an error";
  return false;
}

namespace {

// A generated obedience row counts as violated below -kRowViolation (rows are
// normalised to a largest |coefficient| of 1); GLPK's own rows hold to its
// tol_bnd (1e-7).
constexpr double kRowViolation = 1e-9;

}  // namespace

namespace internal {

// 2^(k-1) with max |entry| in [2^(k-1), 2^k) (1 for an all-zero table):
// dividing by it is exact and leaves every entry below 2 in magnitude (2^k
// itself would overflow to inf for entries near DBL_MAX).
double PowerOfTwoScale(const Eigen::MatrixXd& table) {
  const double top = table.cwiseAbs().maxCoeff();
  if (!(top > 0.0)) return 1.0;
  int exponent = 0;
  std::frexp(top, &exponent);  // top = f 2^exponent, f in [0.5, 1)
  return std::ldexp(1.0, exponent - 1);
}

}  // namespace internal

namespace {

// Everything the GLPK side reads and writes, as plain pointers and numbers: the
// guarded function's frame may be unwound by longjmp, so nothing in it may have
// a destructor. The buffers are owned by SolveTrustAwarePersuasion's frame.
struct LpWork {
  // Inputs.
  int n = 0, m = 0;
  const double* prior = nullptr;          // n
  const double* objective = nullptr;      // n * m, p0(w) v(w, a) / scale, column-major (w fastest)
  const double* obedience = nullptr;      // m * m * n: row (a, a') coefficients of x(., a)
  bool lazy = true;
  // Scratch for one GLPK row (1-based, n + 1 entries each).
  int* index = nullptr;
  double* value = nullptr;
  unsigned char* in_lp = nullptr;         // m * m: row (a, a') added
  // Outputs.
  double* x = nullptr;                    // n * m primal values, x[a * n + w]
  int code = 0;                           // last glp_simplex return code
  int status = 0;                         // last glp_get_status
  int rounds = 0;                         // simplex calls
  int rows = 0;                           // obedience rows in the final LP
};

int Column(const LpWork& work, int w, int a) { return 1 + a * work.n + w; }

const double* RowCoefficients(const LpWork& work, int a, int alt) {
  return work.obedience + (static_cast<std::size_t>(a) * work.m + alt) * work.n;
}

void AddObedienceRow(glp_prob* lp, LpWork* work, int a, int alt) {
  const double* c = RowCoefficients(*work, a, alt);
  int len = 0;
  for (int w = 0; w < work->n; ++w) {
    if (c[w] == 0.0) continue;
    ++len;
    work->index[len] = Column(*work, w, a);
    work->value[len] = c[w];
  }
  const int row = glp_add_rows(lp, 1);
  glp_set_row_bnds(lp, row, GLP_LO, 0.0, 0.0);
  glp_set_mat_row(lp, row, len, work->index, work->value);
  work->in_lp[a * work->m + alt] = 1;
  ++work->rows;
}

// Adds every obedience row (not yet in the LP) that the current solution
// violates; returns how many.
int AddViolatedRows(glp_prob* lp, LpWork* work) {
  const int n = work->n, m = work->m;
  for (int a = 0; a < m; ++a) {
    for (int w = 0; w < n; ++w) work->x[a * n + w] = glp_get_col_prim(lp, Column(*work, w, a));
  }
  int added = 0;
  for (int a = 0; a < m; ++a) {
    const double* xa = work->x + static_cast<std::size_t>(a) * n;
    bool used = false;
    for (int w = 0; w < n && !used; ++w) used = xa[w] > 0.0;
    if (!used) continue;  // never recommended: its rows hold trivially
    int worst = -1;
    double worst_activity = -kRowViolation;
    for (int alt = 0; alt < m; ++alt) {
      if (alt == a || work->in_lp[a * m + alt]) continue;
      const double* c = RowCoefficients(*work, a, alt);
      double activity = 0.0;
      for (int w = 0; w < n; ++w) activity += c[w] * xa[w];
      if (activity < worst_activity) {
        worst_activity = activity;
        worst = alt;
      }
    }
    if (worst >= 0) {
      AddObedienceRow(lp, work, a, worst);
      ++added;
    }
  }
  return added;
}

// The GLPK side, run under RunGlpkGuarded. Locals are ints, doubles and a
// glp_prob* only.
void SolveWithGlpk(void* arg) {
  LpWork* work = static_cast<LpWork*>(arg);
  const int n = work->n, m = work->m;
  glp_prob* lp = glp_create_prob();
  glp_set_obj_dir(lp, GLP_MAX);
  glp_add_cols(lp, n * m);
  for (int a = 0; a < m; ++a) {
    for (int w = 0; w < n; ++w) {
      glp_set_col_bnds(lp, Column(*work, w, a), GLP_LO, 0.0, 0.0);
      glp_set_obj_coef(lp, Column(*work, w, a), work->objective[a * n + w]);
    }
  }
  // sum_a x(w, a) = 1.
  glp_add_rows(lp, n);
  for (int w = 0; w < n; ++w) {
    for (int a = 0; a < m; ++a) {
      work->index[a + 1] = Column(*work, w, a);
      work->value[a + 1] = 1.0;
    }
    glp_set_row_bnds(lp, 1 + w, GLP_FX, 1.0, 1.0);
    glp_set_mat_row(lp, 1 + w, m, work->index, work->value);
  }
  if (!work->lazy) {
    for (int a = 0; a < m; ++a) {
      for (int alt = 0; alt < m; ++alt) {
        if (alt != a) AddObedienceRow(lp, work, a, alt);
      }
    }
  }

  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.presolve = work->lazy ? GLP_OFF : GLP_ON;  // the lazy loop re-uses the basis
  // No glp_scale_prob: the tables are scaled to |u|, |v| <= 1 and every
  // obedience row to a largest |coefficient| of 1 already, and GLPK's own
  // scaling made its dual simplex stall on these degenerate rows (100 x 400:
  // no answer in 10 minutes with it, 6 s without).
  if (work->lazy) glp_adv_basis(lp, 0);
  work->code = glp_simplex(lp, &parm);
  work->status = glp_get_status(lp);
  work->rounds = 1;
  // Re-solves start from the last optimal basis: the new rows' auxiliary
  // variables are basic, so that basis stays dual feasible and the dual simplex
  // only restores primal feasibility.
  parm.meth = GLP_DUALP;
  while (work->lazy && work->code == 0 && work->status == GLP_OPT && AddViolatedRows(lp, work) > 0) {
    work->code = glp_simplex(lp, &parm);
    work->status = glp_get_status(lp);
    ++work->rounds;
  }
  if (work->code == 0 && work->status == GLP_OPT) {
    for (int a = 0; a < m; ++a) {
      for (int w = 0; w < n; ++w) work->x[a * n + w] = glp_get_col_prim(lp, Column(*work, w, a));
    }
  }
  glp_delete_prob(lp);
}

}  // namespace

namespace {

// The LP's size against its limits (lp.h): an InvalidArgument naming both.
void CheckLpSize(int n, int m) {
  const double variables = static_cast<double>(n) * m;
  const double entries = variables * (m - 1);
  if (variables > kMaxLpVariables || entries > kMaxLpObedienceEntries) {
    throw InvalidArgument(
        "the game has " + std::to_string(n) + " states and " + std::to_string(m) +
        " actions: " + std::to_string(static_cast<long long>(variables)) +
        " scheme entries pi(a|w) and " + std::to_string(static_cast<long long>(entries)) +
        " obedience coefficients, above the LP's limits of " +
        std::to_string(static_cast<long long>(kMaxLpVariables)) + " and " +
        std::to_string(static_cast<long long>(kMaxLpObedienceEntries)) +
        " (200 x 200 takes ~15 s, see lp.h)");
  }
}

}  // namespace

namespace internal {

// Obedience coefficients, differences first:
//   c(a, a')(w) = p0(w) [(1 - theta) dU0(a, a') + theta D(w; a, a')],
//   dU0(a, a') = sum_w p0(w) D(w; a, a'),
// each row divided by its largest |c| (c >= 0 does not change; GLPK's
// tolerances then mean the same thing on every row). Returns "" or what is
// wrong with a row.
std::string ObedienceRows(const Game& game, const Eigen::MatrixXd& u, double theta,
                          std::vector<double>* obedience) {
  const Eigen::VectorXd& p0 = game.prior;
  const int n = static_cast<int>(p0.size());
  const int m = static_cast<int>(u.cols());
  obedience->assign(static_cast<std::size_t>(m) * m * n, 0.0);
  std::vector<double> d(n);
  for (int a = 0; a < m; ++a) {
    for (int alt = 0; alt < m; ++alt) {
      if (alt == a) continue;
      double du0 = 0.0;
      for (int w = 0; w < n; ++w) {
        d[w] = u(w, a) - u(w, alt);
        du0 += p0(w) * d[w];
      }
      double* c = obedience->data() + (static_cast<std::size_t>(a) * m + alt) * n;
      double top = 0.0;
      for (int w = 0; w < n; ++w) {
        c[w] = p0(w) * ((1.0 - theta) * du0 + theta * d[w]);
        top = std::max(top, std::abs(c[w]));
      }
      if (top > 0.0) {
        for (int w = 0; w < n; ++w) c[w] /= top;
      }
      // Finite by construction (|u| < 2, p0 <= 1); GLPK would take inf or NaN
      // without complaint and answer nonsense, so never hand it one.
      if (!std::isfinite(top))
        return "obedience row (" + game.actions[a] + ", " + game.actions[alt] +
               ") has a non-finite coefficient";
    }
  }
  return "";
}

}  // namespace internal

namespace {

// GLPK's outcome as the result's status; false unless optimal.
bool SolverStatus(const LpWork& work, LpResult* result) {
  result->simplex_rounds = work.rounds;
  result->obedience_rows = work.rows;
  if (work.code == GLP_ENOPFS || work.status == GLP_NOFEAS) {
    result->status = LpResult::Status::kInfeasible;
    result->message = "GLPK: the LP has no primal feasible solution";
    return false;
  }
  if (work.code != 0) {
    result->status = LpResult::Status::kSolverError;
    result->message = "glp_simplex failed with code " + std::to_string(work.code);
    return false;
  }
  if (work.status != GLP_OPT) {
    result->status = LpResult::Status::kSolverError;
    result->message = "GLPK solution status " + std::to_string(work.status) + " is not optimal";
    return false;
  }
  result->status = LpResult::Status::kOptimal;
  return true;
}

// Obedience at each recommendation's own posterior, under the tolerance
// policy with kObedienceTolerance (persuasion.h): a recommendation a that the
// receiver does not weakly prefer is merged into her best response b there.
// The trust posterior is affine in the Bayes posterior, so the merged
// posterior mixes a's and b's and b, optimal at both, stays optimal. Each
// merge empties a column, so this ends within m passes.
void MergeDisobeyed(const Eigen::VectorXd& p0, const Eigen::MatrixXd& u, double theta,
                    LpResult* result) {
  const int m = static_cast<int>(u.cols());
  const double u_range = UtilityScale(u);
  for (int pass = 0; pass < m; ++pass) {
    bool merged = false;
    for (int a = 0; a < m; ++a) {
      const double pa = result->scheme.col(a).dot(p0);
      if (!(pa > 0.0)) continue;
      const Eigen::VectorXd posterior =
          TrustPosterior(p0, result->scheme.col(a).cwiseProduct(p0) / pa, theta);
      const Eigen::VectorXd utilities = ExpectedUtilities(u, posterior);
      Eigen::Index best = 0;
      const double top = utilities.maxCoeff(&best);
      if (WeaklyPrefers(utilities(a) - top, u_range, kObedienceTolerance)) continue;
      result->scheme.col(best) += result->scheme.col(a);
      result->scheme.col(a).setZero();
      ++result->merged_recommendations;
      merged = true;
    }
    if (!merged) break;
  }
}

// The value of the scheme found, from its definition (in v's own units,
// `v_scale` undone), each signal's probability and the receiver's posterior.
void ValueAndPosteriors(const Eigen::VectorXd& p0, const Eigen::MatrixXd& v, double v_scale,
                        double theta, LpResult* result) {
  const int n = static_cast<int>(p0.size());
  const int m = static_cast<int>(v.cols());
  double value_scaled = 0.0;
  for (int w = 0; w < n; ++w) {
    for (int a = 0; a < m; ++a) value_scaled += p0(w) * result->scheme(w, a) * v(w, a);
  }
  result->sender_value = value_scaled * v_scale;
  result->signal_probability = result->scheme.transpose() * p0;
  result->posteriors.resize(n, m);
  for (int a = 0; a < m; ++a) {
    const double pa = result->signal_probability(a);
    if (pa < kMinSignalProbability) {
      result->posteriors.col(a).setConstant(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const Eigen::VectorXd full_trust = result->scheme.col(a).cwiseProduct(p0) / pa;
    result->posteriors.col(a) = TrustPosterior(p0, full_trust, theta);
  }
}

}  // namespace

LpResult SolveTrustAwarePersuasion(const Game& game, double theta, const LpOptions& options) {
  game.Validate();
  internal::CheckTrust(theta);
  const int n = static_cast<int>(game.prior.size());
  const int m = static_cast<int>(game.actions.size());
  CheckLpSize(n, m);
  const Eigen::VectorXd& p0 = game.prior;
  const double u_scale = internal::PowerOfTwoScale(game.receiver_utility);
  const double v_scale = internal::PowerOfTwoScale(game.sender_utility);
  const Eigen::MatrixXd u = game.receiver_utility / u_scale;  // |u| < 2
  const Eigen::MatrixXd v = game.sender_utility / v_scale;    // |v| < 2

  LpResult result;
  std::vector<double> obedience;
  const std::string bad_row = internal::ObedienceRows(game, u, theta, &obedience);
  if (!bad_row.empty()) {
    result.status = LpResult::Status::kSolverError;
    result.message = bad_row;
    return result;
  }
  std::vector<double> objective(static_cast<std::size_t>(n) * m);
  for (int a = 0; a < m; ++a) {
    for (int w = 0; w < n; ++w) objective[a * n + w] = p0(w) * v(w, a);
  }
  std::vector<int> index(std::max(n, m) + 1);
  std::vector<double> value(std::max(n, m) + 1);
  std::vector<unsigned char> in_lp(static_cast<std::size_t>(m) * m, 0);
  std::vector<double> x(static_cast<std::size_t>(n) * m, 0.0);

  LpWork work;
  work.n = n;
  work.m = m;
  work.prior = p0.data();
  work.objective = objective.data();
  work.obedience = obedience.data();
  work.lazy = options.lazy_obedience;
  work.index = index.data();
  work.value = value.data();
  work.in_lp = in_lp.data();
  work.x = x.data();

  std::string glpk_error;
  if (!RunGlpkGuarded(SolveWithGlpk, &work, &glpk_error)) {
    result.status = LpResult::Status::kSolverError;
    result.message = "GLPK failed: " + glpk_error;
    return result;
  }
  if (!SolverStatus(work, &result)) return result;
  result.scheme.resize(n, m);
  for (int w = 0; w < n; ++w) {
    for (int a = 0; a < m; ++a) {
      // Clip the solver's round-off below zero.
      result.scheme(w, a) = std::max(0.0, x[a * n + w]);
    }
  }
  MergeDisobeyed(p0, u, theta, &result);
  ValueAndPosteriors(p0, v, v_scale, theta, &result);
  return result;
}

}  // namespace taebp::persuasion
