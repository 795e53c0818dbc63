// Several receivers, one public signal: the LP of lp_multi.h (GLPK).
//
// Columns x(w, k) = pi(profile k | w), column 1 + k S + w (S states). Rows:
// S rows sum_k x(w, k) = 1, then for every profile k, receiver i and action
// a' != sigma_k(i) the obedience row of receiver i (internal::ObedienceRows,
// lp.cc's coefficients for (sigma_k(i), a')) on the columns of profile k. The
// tables are scaled as in lp.cc (powers of two: u_i per receiver, the summed
// sender table once). All rows are built in this frame, in plain arrays,
// before GLPK runs under RunGlpkGuarded (whose frame may be unwound by longjmp).
#include "taebp/persuasion/lp_multi.h"

#include "internal.h"

#include <glpk.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace taebp::persuasion {

namespace {

// The profiles in mixed radix, receiver 0 fastest: profile k's action for
// receiver i is digit i of k in the bases actions[0], actions[1], ...
std::vector<std::vector<int>> Profiles(const std::vector<int>& actions) {
  int count = 1;
  for (int m : actions) count *= m;
  std::vector<std::vector<int>> profiles(count, std::vector<int>(actions.size()));
  for (int k = 0; k < count; ++k) {
    int rest = k;
    for (std::size_t i = 0; i < actions.size(); ++i) {
      profiles[k][i] = rest % actions[i];
      rest /= actions[i];
    }
  }
  return profiles;
}

void CheckInputs(const std::vector<Game>& receivers, const std::vector<double>& trusts) {
  if (receivers.empty()) throw InvalidArgument("receivers is empty: at least one receiver is needed");
  if (trusts.size() != receivers.size()) {
    throw InvalidArgument("trusts has " + std::to_string(trusts.size()) + " entries for " +
                          std::to_string(receivers.size()) + " receivers");
  }
  const Game& first = receivers.front();
  for (std::size_t i = 0; i < receivers.size(); ++i) {
    const std::string name = "receivers[" + std::to_string(i) + "]";
    std::string why;
    if (!receivers[i].IsValid(&why)) throw InvalidArgument(name + ": " + why);
    internal::CheckTrust(trusts[i], ("trusts[" + std::to_string(i) + "]").c_str());
    if (receivers[i].states != first.states) {
      throw InvalidArgument(name + " has other states than receivers[0]: the state is common");
    }
    const double gap = (receivers[i].prior - first.prior).cwiseAbs().maxCoeff();
    if (gap > kProbabilityTolerance) {
      throw InvalidArgument(name + "'s prior differs from receivers[0]'s by " + NumberText(gap) +
                            ": the prior is common");
    }
  }
}

void CheckSize(int states, double profiles, double obedience_entries) {
  if (states * profiles > kMaxLpVariables || obedience_entries > kMaxLpObedienceEntries) {
    throw InvalidArgument("the public LP has " + NumberText(profiles) + " action profiles over " +
                          std::to_string(states) + " states (" + NumberText(states * profiles) +
                          " scheme entries, " + NumberText(obedience_entries) +
                          " obedience coefficients), above the limits of " +
                          NumberText(kMaxLpVariables) + " and " + NumberText(kMaxLpObedienceEntries));
  }
}

// The LP as plain arrays. Row r's entries are index/value[start[r] .. start[r+1]),
// with one unused slot at start[r] so that GLPK's 1-based arrays are
// &index[start[r]] (GLPK reads entries 1..len).
struct Rows {
  std::vector<int> start{0};
  std::vector<int> index;
  std::vector<double> value;
  std::vector<double> lower;  // the row's lower bound
  std::vector<bool> fixed;    // equality (the sum rows) or >= (obedience)
  void Begin(double bound, bool equality) {
    index.push_back(0);
    value.push_back(0.0);
    lower.push_back(bound);
    fixed.push_back(equality);
  }
  void Add(int column, double coefficient) {
    index.push_back(column);
    value.push_back(coefficient);
  }
  void End() { start.push_back(static_cast<int>(index.size())); }
  int Count() const { return static_cast<int>(lower.size()); }
};

struct PublicLpWork {
  int columns = 0;
  const double* objective = nullptr;  // per column
  const Rows* rows = nullptr;
  const int* fixed = nullptr;         // per row: 1 equality, 0 >=
  double* x = nullptr;                // per column
  int code = 0;
  int status = 0;
};

// The GLPK side: locals are ints and a glp_prob* only.
void SolvePublicWithGlpk(void* arg) {
  PublicLpWork* work = static_cast<PublicLpWork*>(arg);
  const Rows& rows = *work->rows;
  glp_prob* lp = glp_create_prob();
  glp_set_obj_dir(lp, GLP_MAX);
  glp_add_cols(lp, work->columns);
  for (int c = 1; c <= work->columns; ++c) {
    glp_set_col_bnds(lp, c, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(lp, c, work->objective[c - 1]);
  }
  glp_add_rows(lp, rows.Count());
  for (int r = 0; r < rows.Count(); ++r) {
    const int len = rows.start[r + 1] - rows.start[r] - 1;
    glp_set_row_bnds(lp, r + 1, work->fixed[r] ? GLP_FX : GLP_LO, rows.lower[r], rows.lower[r]);
    glp_set_mat_row(lp, r + 1, len, rows.index.data() + rows.start[r], rows.value.data() + rows.start[r]);
  }
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.presolve = GLP_ON;
  work->code = glp_simplex(lp, &parm);
  work->status = glp_get_status(lp);
  if (work->code == 0 && work->status == GLP_OPT) {
    for (int c = 1; c <= work->columns; ++c) work->x[c - 1] = glp_get_col_prim(lp, c);
  }
  glp_delete_prob(lp);
}

// The sum rows, then every obedience row (coefficients from ObedienceRows of
// each receiver, zero entries left out).
Rows BuildRows(const std::vector<std::vector<int>>& profiles, int states,
               const std::vector<std::vector<double>>& obedience, const std::vector<int>& actions) {
  Rows rows;
  const int count = static_cast<int>(profiles.size());
  for (int w = 0; w < states; ++w) {
    rows.Begin(1.0, true);
    for (int k = 0; k < count; ++k) rows.Add(1 + k * states + w, 1.0);
    rows.End();
  }
  for (int k = 0; k < count; ++k) {
    for (std::size_t i = 0; i < actions.size(); ++i) {
      const int a = profiles[k][i], m = actions[i];
      for (int alt = 0; alt < m; ++alt) {
        if (alt == a) continue;
        const double* c = obedience[i].data() + (static_cast<std::size_t>(a) * m + alt) * states;
        rows.Begin(0.0, false);
        for (int w = 0; w < states; ++w) {
          if (c[w] != 0.0) rows.Add(1 + k * states + w, c[w]);
        }
        rows.End();
      }
    }
  }
  return rows;
}

// The solver's outcome as the result's status; false unless optimal.
bool Status(const PublicLpWork& work, PublicLpResult* result) {
  if (work.code == GLP_ENOPFS || work.status == GLP_NOFEAS) {
    result->status = LpResult::Status::kInfeasible;
    result->message = "GLPK: the LP has no primal feasible solution";
    return false;
  }
  if (work.code != 0 || work.status != GLP_OPT) {
    result->status = LpResult::Status::kSolverError;
    result->message = "glp_simplex returned " + std::to_string(work.code) + " with status " +
                      std::to_string(work.status);
    return false;
  }
  result->status = LpResult::Status::kOptimal;
  return true;
}

// The index of `profile` (receiver 0 fastest).
int ProfileIndex(const std::vector<int>& profile, const std::vector<int>& actions) {
  int index = 0;
  for (std::size_t i = actions.size(); i-- > 0;) index = index * actions[i] + profile[i];
  return index;
}

// lp.cc's MergeDisobeyed for profiles: a profile some receiver does not weakly
// obey (kObedienceTolerance) moves into the profile with her best response
// there. Receivers whose recommendation is unchanged obey both profiles, hence
// their mixture (beliefs are affine in the Bayes posterior); the moved one's
// best response is optimal at both. Each merge empties a column.
void MergeDisobeyed(const std::vector<Game>& receivers, const std::vector<double>& trusts,
                    const std::vector<int>& actions, PublicLpResult* result) {
  const Eigen::VectorXd& p0 = receivers.front().prior;
  const int count = static_cast<int>(result->profiles.size());
  for (int pass = 0; pass < count; ++pass) {
    bool merged = false;
    for (int k = 0; k < count; ++k) {
      const double pk = result->scheme.col(k).dot(p0);
      if (!(pk > 0.0)) continue;
      const Eigen::VectorXd bayes = result->scheme.col(k).cwiseProduct(p0) / pk;
      for (std::size_t i = 0; i < receivers.size(); ++i) {
        const Eigen::MatrixXd& u = receivers[i].receiver_utility;
        const Eigen::VectorXd utilities = ExpectedUtilities(u, TrustPosterior(p0, bayes, trusts[i]));
        Eigen::Index best = 0;
        const double top = utilities.maxCoeff(&best);
        const int a = result->profiles[k][i];
        if (WeaklyPrefers(utilities(a) - top, UtilityScale(u), kObedienceTolerance)) continue;
        std::vector<int> target = result->profiles[k];
        target[i] = static_cast<int>(best);
        const int j = ProfileIndex(target, actions);
        result->scheme.col(j) += result->scheme.col(k);
        result->scheme.col(k).setZero();
        ++result->merged_recommendations;
        merged = true;
        break;
      }
    }
    if (!merged) break;
  }
}

// The value (unscaled sender tables), profile and action probabilities.
void Summarise(const std::vector<Game>& receivers, PublicLpResult* result) {
  const Eigen::VectorXd& p0 = receivers.front().prior;
  const int n = static_cast<int>(receivers.size());
  const int count = static_cast<int>(result->profiles.size());
  result->signal_probability = result->scheme.transpose() * p0;
  int most_actions = 0;
  for (const Game& g : receivers) most_actions = std::max(most_actions, static_cast<int>(g.actions.size()));
  result->action_probability = Eigen::MatrixXd::Zero(n, most_actions);
  result->sender_value = 0.0;
  for (int k = 0; k < count; ++k) {
    for (int i = 0; i < n; ++i) {
      const int a = result->profiles[k][i];
      result->action_probability(i, a) += result->signal_probability(k);
      for (int w = 0; w < p0.size(); ++w) {
        result->sender_value += p0(w) * result->scheme(w, k) * receivers[i].sender_utility(w, a);
      }
    }
  }
}

}  // namespace

PublicLpResult SolvePublicPersuasion(const std::vector<Game>& receivers,
                                     const std::vector<double>& trusts) {
  CheckInputs(receivers, trusts);
  const int n = static_cast<int>(receivers.size());
  const int states = static_cast<int>(receivers.front().states.size());
  std::vector<int> actions(n);
  double profile_count = 1.0, entries = 0.0;
  for (int i = 0; i < n; ++i) {
    actions[i] = static_cast<int>(receivers[i].actions.size());
    profile_count *= actions[i];
  }
  for (int i = 0; i < n; ++i) entries += profile_count * (actions[i] - 1) * states;
  CheckSize(states, profile_count, entries);

  PublicLpResult result;
  result.profiles = Profiles(actions);
  const int count = static_cast<int>(result.profiles.size());
  std::vector<std::vector<double>> obedience(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::MatrixXd& u = receivers[i].receiver_utility;
    const std::string bad = internal::ObedienceRows(receivers[i], u / internal::PowerOfTwoScale(u),
                                                    trusts[i], &obedience[i]);
    if (!bad.empty()) {
      result.message = "receivers[" + std::to_string(i) + "]: " + bad;
      return result;
    }
  }
  // The summed sender table, scaled once: v(w, k) = sum_i v_i(w, sigma_k(i)).
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(states, count);
  for (int k = 0; k < count; ++k) {
    for (int i = 0; i < n; ++i) v.col(k) += receivers[i].sender_utility.col(result.profiles[k][i]);
  }
  const double v_scale = internal::PowerOfTwoScale(v);
  std::vector<double> objective(static_cast<std::size_t>(states) * count);
  for (int k = 0; k < count; ++k) {
    for (int w = 0; w < states; ++w) objective[k * states + w] = receivers[0].prior(w) * v(w, k) / v_scale;
  }
  const Rows rows = BuildRows(result.profiles, states, obedience, actions);
  std::vector<int> fixed(rows.fixed.begin(), rows.fixed.end());
  std::vector<double> x(objective.size(), 0.0);
  PublicLpWork work;
  work.columns = static_cast<int>(objective.size());
  work.objective = objective.data();
  work.rows = &rows;
  work.fixed = fixed.data();
  work.x = x.data();
  std::string glpk_error;
  if (!RunGlpkGuarded(SolvePublicWithGlpk, &work, &glpk_error)) {
    result.message = "GLPK failed: " + glpk_error;
    return result;
  }
  if (!Status(work, &result)) return result;
  result.scheme.resize(states, count);
  for (int k = 0; k < count; ++k) {
    for (int w = 0; w < states; ++w) result.scheme(w, k) = std::max(0.0, x[k * states + w]);
  }
  MergeDisobeyed(receivers, trusts, actions, &result);
  Summarise(receivers, &result);
  return result;
}

}  // namespace taebp::persuasion
