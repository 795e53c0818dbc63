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
#include "taebp/persuasion/lp.h"

#include "internal.h"

#include <glpk.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
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

namespace {

struct ProbDeleter {
  void operator()(glp_prob* lp) const { glp_delete_prob(lp); }
};
using ProbPtr = std::unique_ptr<glp_prob, ProbDeleter>;

}  // namespace

LpResult SolveTrustAwarePersuasion(const Game& game, double theta) {
  game.Validate();
  internal::CheckTrust(theta);
  const int n = static_cast<int>(game.prior.size());
  const int m = static_cast<int>(game.actions.size());
  const Eigen::VectorXd& p0 = game.prior;
  const Eigen::MatrixXd& u = game.receiver_utility;
  const Eigen::VectorXd prior_utility = ExpectedUtilities(u, p0);  // U(a | p0)

  ProbPtr lp(glp_create_prob());
  glp_set_obj_dir(lp.get(), GLP_MAX);

  // Column index (1-based) of x(w, a).
  auto col = [m](int w, int a) { return 1 + w * m + a; };
  glp_add_cols(lp.get(), n * m);
  for (int w = 0; w < n; ++w) {
    for (int a = 0; a < m; ++a) {
      glp_set_col_bnds(lp.get(), col(w, a), GLP_LO, 0.0, 0.0);
      glp_set_obj_coef(lp.get(), col(w, a), p0(w) * game.sender_utility(w, a));
    }
  }

  // GLPK's sparse triplets are 1-based; entry 0 is unused.
  std::vector<int> ia(1, 0), ja(1, 0);
  std::vector<double> ar(1, 0.0);
  auto add = [&](int row, int column, double value) {
    ia.push_back(row);
    ja.push_back(column);
    ar.push_back(value);
  };

  // Rows 1..n: sum_a x(w, a) = 1.
  glp_add_rows(lp.get(), n);
  for (int w = 0; w < n; ++w) {
    glp_set_row_bnds(lp.get(), 1 + w, GLP_FX, 1.0, 1.0);
    for (int a = 0; a < m; ++a) add(1 + w, col(w, a), 1.0);
  }
  // Rows n+1..n+m(m-1): obedience of recommendation a against deviation a'.
  if (m > 1) glp_add_rows(lp.get(), m * (m - 1));
  int row = n;
  for (int a = 0; a < m; ++a) {
    for (int alt = 0; alt < m; ++alt) {
      if (alt == a) continue;
      ++row;
      glp_set_row_bnds(lp.get(), row, GLP_LO, 0.0, 0.0);
      const double du0 = prior_utility(a) - prior_utility(alt);
      for (int w = 0; w < n; ++w) {
        const double coefficient = p0(w) * ((1.0 - theta) * du0 + theta * (u(w, a) - u(w, alt)));
        if (coefficient != 0.0) add(row, col(w, a), coefficient);
      }
    }
  }
  glp_load_matrix(lp.get(), static_cast<int>(ar.size()) - 1, ia.data(), ja.data(), ar.data());

  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.presolve = GLP_ON;
  const int code = glp_simplex(lp.get(), &parm);

  LpResult result;
  if (code == GLP_ENOPFS) {
    result.status = LpResult::Status::kInfeasible;
    result.message = "GLPK presolver: the LP has no primal feasible solution";
    return result;
  }
  if (code != 0) {
    result.status = LpResult::Status::kSolverError;
    result.message = "glp_simplex failed with code " + std::to_string(code);
    return result;
  }
  const int status = glp_get_status(lp.get());
  if (status == GLP_NOFEAS) {
    result.status = LpResult::Status::kInfeasible;
    result.message = "GLPK: the LP has no primal feasible solution";
    return result;
  }
  if (status != GLP_OPT) {
    result.status = LpResult::Status::kSolverError;
    result.message = "GLPK solution status " + std::to_string(status) + " is not optimal";
    return result;
  }

  result.status = LpResult::Status::kOptimal;
  result.sender_value = glp_get_obj_val(lp.get());
  result.scheme.resize(n, m);
  for (int w = 0; w < n; ++w) {
    for (int a = 0; a < m; ++a) {
      // Clip the solver's round-off below zero.
      result.scheme(w, a) = std::max(0.0, glp_get_col_prim(lp.get(), col(w, a)));
    }
  }
  result.signal_probability = result.scheme.transpose() * p0;
  result.posteriors.resize(n, m);
  for (int a = 0; a < m; ++a) {
    const double pa = result.signal_probability(a);
    if (pa < kMinSignalProbability) {
      result.posteriors.col(a).setConstant(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const Eigen::VectorXd full_trust = result.scheme.col(a).cwiseProduct(p0) / pa;
    result.posteriors.col(a) = TrustPosterior(p0, full_trust, theta);
  }
  return result;
}

}  // namespace taebp::persuasion
