// Finite Bayesian persuasion with a trust-weighted receiver (paper Sections II-IV).
#include "taebp/persuasion/persuasion.h"

#include "internal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

namespace taebp::persuasion {


namespace {

std::string Shape(const Eigen::MatrixXd& m) {
  return std::to_string(m.rows()) + "x" + std::to_string(m.cols());
}

// Checks that `v` has only finite, non-negative entries; `name` is used in the
// message, e.g. "prior[1] = -0.2 is negative".
void CheckNonNegative(const Eigen::VectorXd& v, const char* name) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v(i))) {
      throw InvalidArgument(std::string(name) + "[" + std::to_string(i) + "] = " + NumberText(v(i)) +
                            " is not finite");
    }
    if (v(i) < 0.0) {
      throw InvalidArgument(std::string(name) + "[" + std::to_string(i) + "] = " + NumberText(v(i)) +
                            " is negative");
    }
  }
}

}  // namespace

// ---------------------------------------------------------------------------
// Game validation (Section II-A: finite Omega and A, prior in int(Delta(Omega))).
// ---------------------------------------------------------------------------
bool Game::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  const auto n = static_cast<Eigen::Index>(states.size());
  const auto m = static_cast<Eigen::Index>(actions.size());
  if (n < 2) return fail("a game needs at least 2 states (got " + std::to_string(n) + ")");
  if (m < 2) return fail("a game needs at least 2 actions (got " + std::to_string(m) + ")");
  // Names identify rows and columns in every output: a repeated one is ambiguous.
  for (const auto& [key, names] : {std::pair{"states", &states}, std::pair{"actions", &actions}}) {
    std::map<std::string, std::size_t> first;
    for (std::size_t i = 0; i < names->size(); ++i) {
      const auto [it, inserted] = first.emplace((*names)[i], i);
      if (!inserted) {
        return fail(std::string(key) + ": the name '" + (*names)[i] + "' appears twice (entries " +
                    std::to_string(it->second) + " and " + std::to_string(i) + ")");
      }
    }
  }
  if (prior.size() != n) {
    return fail("prior has " + std::to_string(prior.size()) + " entries but there are " +
                std::to_string(n) + " states");
  }
  const struct {
    const char* name;
    const Eigen::MatrixXd* matrix;
  } tables[] = {{"receiver_utility", &receiver_utility}, {"sender_utility", &sender_utility}};
  for (const auto& table : tables) {
    if (table.matrix->rows() != n) {
      return fail(std::string(table.name) + " has " + std::to_string(table.matrix->rows()) +
                  " rows but there are " + std::to_string(n) + " states");
    }
    if (table.matrix->cols() != m) {
      return fail(std::string(table.name) + " has " + std::to_string(table.matrix->cols()) +
                  " columns but there are " + std::to_string(m) + " actions");
    }
    if (!table.matrix->allFinite()) {
      return fail(std::string(table.name) + " (" + Shape(*table.matrix) +
                  ") has a non-finite entry");
    }
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const double p = prior(i);
    const std::string entry = "prior[" + std::to_string(i) + "] = " + NumberText(p);
    if (!std::isfinite(p)) return fail(entry + " is not finite");
    if (p < 0.0) return fail(entry + " is negative");
    if (p == 0.0) return fail(entry + " is not in the interior of the simplex (must be > 0)");
  }
  const double sum = prior.sum();
  if (std::abs(sum - 1.0) > kProbabilityTolerance) return fail("prior must sum to 1 (sum = " + NumberText(sum) + ")");
  return true;
}

void Game::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

// ---------------------------------------------------------------------------
// eq:bayes_update: p(w|s) = pi(s|w) p0(w) / sum_w' pi(s|w') p0(w').
// ---------------------------------------------------------------------------
Eigen::VectorXd BayesPosterior(const Eigen::VectorXd& prior, const Eigen::VectorXd& likelihood) {
  if (prior.size() != likelihood.size()) {
    throw InvalidArgument("likelihood has " + std::to_string(likelihood.size()) +
                          " entries but prior has " + std::to_string(prior.size()));
  }
  CheckNonNegative(prior, "prior");
  CheckNonNegative(likelihood, "likelihood");
  const Eigen::VectorXd joint = likelihood.cwiseProduct(prior);
  const double evidence = joint.sum();
  if (!(evidence > 0.0)) {
    throw InvalidArgument("the signal has zero probability under the prior (sum_w pi(s|w) p0(w) = " +
                          NumberText(evidence) + ")");
  }
  return joint / evidence;
}

// ---------------------------------------------------------------------------
// Section III: p_theta(w|s) = (1 - theta) p0(w) + theta p_FT(w|s).
// ---------------------------------------------------------------------------
Eigen::VectorXd TrustPosterior(const Eigen::VectorXd& prior,
                               const Eigen::VectorXd& full_trust_posterior, double theta) {
  internal::CheckTrust(theta);
  if (prior.size() != full_trust_posterior.size()) {
    throw InvalidArgument("full_trust_posterior has " +
                          std::to_string(full_trust_posterior.size()) +
                          " entries but prior has " + std::to_string(prior.size()));
  }
  return (1.0 - theta) * prior + theta * full_trust_posterior;
}

double UtilityScale(const Eigen::MatrixXd& utility) {
  if (utility.size() == 0) return 0.0;
  return utility.maxCoeff() - utility.minCoeff();
}

// U(a|p) = sum_w p(w) u(w, a) for every a.
Eigen::VectorXd ExpectedUtilities(const Eigen::MatrixXd& utility, const Eigen::VectorXd& belief) {
  if (utility.rows() != belief.size()) {
    throw InvalidArgument("utility has " + std::to_string(utility.rows()) +
                          " rows but belief has " + std::to_string(belief.size()) + " entries");
  }
  return utility.transpose() * belief;
}

// ---------------------------------------------------------------------------
// eq:receiver_action with sender-favourable tie breaking (the tolerance policy).
// ---------------------------------------------------------------------------
int BestResponse(const Game& game, const Eigen::VectorXd& belief, double tolerance) {
  game.Validate();
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) {
    throw InvalidArgument("tolerance = " + NumberText(tolerance) + " must be finite and >= 0");
  }
  if (!belief.allFinite()) throw InvalidArgument("belief has a non-finite entry");
  const Eigen::VectorXd receiver = ExpectedUtilities(game.receiver_utility, belief);
  const Eigen::VectorXd sender = ExpectedUtilities(game.sender_utility, belief);
  const double receiver_scale = UtilityScale(game.receiver_utility);
  const double sender_scale = UtilityScale(game.sender_utility);
  const double best = receiver.maxCoeff();
  int chosen = -1;
  for (Eigen::Index a = 0; a < receiver.size(); ++a) {
    if (!WeaklyPrefers(receiver(a) - best, receiver_scale, tolerance)) continue;  // not optimal
    // Among the receiver's optimal actions the sender's favourite wins; sender
    // values that tie under the same policy keep the lowest index.
    if (chosen < 0 || !WeaklyPrefers(sender(chosen) - sender(a), sender_scale, tolerance)) {
      chosen = static_cast<int>(a);
    }
  }
  return chosen;
}

int DefaultAction(const Game& game) { return BestResponse(game, game.prior); }

// ---------------------------------------------------------------------------
// Theorem 1 (eq:theta_star).
//   theta*(a') = -dU0(a') / (max_s dU_FT(a'; s) - dU0(a')),  theta* = min_a' theta*(a').
// The per-action bound comes from theta dU_FT >= -(1 - theta) dU0 (proof of
// Theorem 1). Under the tolerance policy (persuasion.h): an action a' weakly
// preferred at the prior needs no trust, theta*(a') = 0; an action whose best
// full-trust gain is a clear loss can never be induced (not even at theta = 1)
// and is skipped; a best full-trust gain that ties (max dU_FT = 0, up to
// round-off) is induced at theta = 1 exactly, where the receiver breaks the tie
// toward the sender like BestResponse and the LP do: theta*(a') = 1.
// ---------------------------------------------------------------------------
namespace {

TrustThreshold ThresholdFromBestGains(const Eigen::VectorXd& prior_gain,
                                      const Eigen::VectorXd& best_full_trust_gain,
                                      int default_action, double scale) {
  TrustThreshold result;
  result.default_action = default_action;
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index a = 0; a < prior_gain.size(); ++a) {
    if (a == default_action) continue;
    const double du0 = prior_gain(a);
    const double ft = best_full_trust_gain(a);
    double theta_a;
    if (WeaklyPrefers(du0, scale)) {
      theta_a = 0.0;
    } else if (!WeaklyPrefers(ft, scale)) {
      continue;  // no signal in the set makes a' attractive, whatever theta
    } else {
      // du0 < -tol * scale <= ft, so ft - du0 > 0; a tie (ft <= 0) gives >= 1.
      theta_a = std::min(1.0, -du0 / (ft - du0));
    }
    if (theta_a < best) {
      best = theta_a;
      result.target_action = static_cast<int>(a);
    }
  }
  if (result.target_action >= 0) {
    result.persuadable = true;
    result.theta_star = std::clamp(best, 0.0, 1.0);
  } else {
    result.persuadable = false;
    result.theta_star = 1.0;
  }
  return result;
}

// dU(a', a0 | belief) for every a' (entry a0 is 0).
Eigen::VectorXd GainsOver(const Game& game, const Eigen::VectorXd& belief, int default_action) {
  const Eigen::VectorXd u = ExpectedUtilities(game.receiver_utility, belief);
  return u.array() - u(default_action);
}

}  // namespace

TrustThreshold MinPersuadableTrust(const Game& game, const Eigen::MatrixXd& signals) {
  game.Validate();
  const Eigen::Index n = game.prior.size();
  if (signals.rows() != n) {
    throw InvalidArgument("signals has " + std::to_string(signals.rows()) +
                          " rows but there are " + std::to_string(n) + " states");
  }
  if (signals.cols() < 1) throw InvalidArgument("signals has no columns (empty signal set)");
  for (Eigen::Index j = 0; j < signals.cols(); ++j) {
    for (Eigen::Index w = 0; w < n; ++w) {
      const double x = signals(w, j);
      if (!std::isfinite(x) || x < 0.0) {
        throw InvalidArgument("signals(" + std::to_string(w) + ", " + std::to_string(j) +
                              ") = " + NumberText(x) + " must be finite and >= 0");
      }
    }
  }
  const int a0 = DefaultAction(game);
  const Eigen::VectorXd prior_gain = GainsOver(game, game.prior, a0);
  // max over the signals that can occur (zero-probability columns are never sent).
  Eigen::VectorXd best_ft =
      Eigen::VectorXd::Constant(prior_gain.size(), -std::numeric_limits<double>::infinity());
  bool any_signal = false;
  for (Eigen::Index j = 0; j < signals.cols(); ++j) {
    if (!(signals.col(j).dot(game.prior) > 0.0)) continue;
    any_signal = true;
    const Eigen::VectorXd posterior = BayesPosterior(game.prior, signals.col(j));
    best_ft = best_ft.cwiseMax(GainsOver(game, posterior, a0));
  }
  if (!any_signal) {
    throw InvalidArgument("every signal in the set has zero probability under the prior");
  }
  return ThresholdFromBestGains(prior_gain, best_ft, a0, UtilityScale(game.receiver_utility));
}

TrustThreshold MinPersuadableTrust(const Game& game) {
  game.Validate();
  const int a0 = DefaultAction(game);
  const Eigen::VectorXd prior_gain = GainsOver(game, game.prior, a0);
  // dU_FT is linear in the posterior, so its max over the simplex is attained at a
  // vertex: a fully revealing signal for one state, max_w [u(w,a') - u(w,a0)].
  const Eigen::MatrixXd du =
      game.receiver_utility.colwise() - game.receiver_utility.col(a0);
  const Eigen::VectorXd best_ft = du.colwise().maxCoeff().transpose();
  return ThresholdFromBestGains(prior_gain, best_ft, a0, UtilityScale(game.receiver_utility));
}

// Corollary (eq:theta_two_states):
//   theta* = -(p0(w1) du1 + p0(w2) du2) / (p0(w2) (du1 - du2)).
double TwoStateTrustThreshold(double prior_w1, double delta_u1, double delta_u2) {
  if (!(prior_w1 > 0.0 && prior_w1 < 1.0)) {
    throw InvalidArgument("prior_w1 = " + NumberText(prior_w1) + " is outside (0, 1)");
  }
  if (!std::isfinite(delta_u1) || !std::isfinite(delta_u2)) {
    throw InvalidArgument("delta_u1 = " + NumberText(delta_u1) + ", delta_u2 = " + NumberText(delta_u2) +
                          " must be finite");
  }
  if (delta_u1 == delta_u2) {
    throw InvalidArgument("delta_u1 = delta_u2 = " + NumberText(delta_u1) +
                          ": the threshold is undefined (no signal changes the gain)");
  }
  const double prior_w2 = 1.0 - prior_w1;
  return -(prior_w1 * delta_u1 + prior_w2 * delta_u2) / (prior_w2 * (delta_u1 - delta_u2));
}

// eq:ppp: U(a1|p*) = U(a2|p*) with p* = p(w1):
//   p* d1 + (1 - p*) d2 = 0, d_i = u(w_i, a1) - u(w_i, a2)  =>  p* = d2 / (d2 - d1).
double IndifferencePosterior(const Eigen::Matrix2d& receiver_utility) {
  if (!receiver_utility.allFinite()) {
    throw InvalidArgument("receiver_utility has a non-finite entry");
  }
  const double d1 = receiver_utility(0, 0) - receiver_utility(0, 1);
  const double d2 = receiver_utility(1, 0) - receiver_utility(1, 1);
  // An interior indifference point exists iff d1 and d2 have strictly opposite signs.
  if (!((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))) {
    throw InvalidArgument("receiver_utility has no interior indifference point (u(w1,a1)-u(w1,a2) = " +
                          NumberText(d1) + ", u(w2,a1)-u(w2,a2) = " + NumberText(d2) +
                          "; they must have opposite signs)");
  }
  return d2 / (d2 - d1);
}

}  // namespace taebp::persuasion
