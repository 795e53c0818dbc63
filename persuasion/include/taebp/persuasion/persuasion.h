// Finite Bayesian persuasion with a trust-weighted receiver (paper Sections II-IV).
//
// Pure math: no SUMO include may ever appear under persuasion/.
// Conventions: matrices have one row per state and one column per action.
// Every function that takes user-facing parameters validates them and throws
// taebp::persuasion::InvalidArgument whose message names the parameter and value.
#pragma once

#include "taebp/persuasion/tolerance.h"

#include <Eigen/Dense>

#include <stdexcept>
#include <string>
#include <vector>

namespace taebp::persuasion {

// max u - min u over the table (0 for a constant table, where every action ties).
double UtilityScale(const Eigen::MatrixXd& utility);

// A finite persuasion game.
struct Game {
  std::vector<std::string> states;   // size n
  std::vector<std::string> actions;  // size m
  Eigen::VectorXd prior;             // n, in the interior of the simplex
  Eigen::MatrixXd receiver_utility;  // n x m, u(w, a)
  Eigen::MatrixXd sender_utility;    // n x m, v(w, a)

  // True if shapes agree, n >= 2, m >= 2, state and action names are unique,
  // prior entries are > 0 and sum to 1 (within kProbabilityTolerance).
  // Otherwise false with a message naming the field and value.
  bool IsValid(std::string* why) const;
  // Throws InvalidArgument with the IsValid message.
  void Validate() const;
};

// eq:bayes_update. likelihood(w) = pi(s | w) for the observed signal s.
// Throws if sizes differ, entries are negative, or the signal has zero
// probability under the prior.
Eigen::VectorXd BayesPosterior(const Eigen::VectorXd& prior,
                               const Eigen::VectorXd& likelihood);

// Section III: p_theta = (1 - theta) p0 + theta p_FT. theta must be in [0, 1].
Eigen::VectorXd TrustPosterior(const Eigen::VectorXd& prior,
                               const Eigen::VectorXd& full_trust_posterior,
                               double theta);

// U(a | p) for every action: utility^T * belief.
Eigen::VectorXd ExpectedUtilities(const Eigen::MatrixXd& utility,
                                  const Eigen::VectorXd& belief);

// eq:receiver_action: argmax_a U(a | belief). Among the actions the receiver
// weakly prefers to every other (WeaklyPrefers: within tolerance * UtilityScale
// of the maximum), picks the one the sender likes best under `belief` (ties
// toward the sender; sender values within tolerance * UtilityScale(v) tie too);
// remaining ties: lowest index. `tolerance` is relative, like kTieTolerance.
int BestResponse(const Game& game, const Eigen::VectorXd& belief,
                 double tolerance = kTieTolerance);

// The receiver's default action a0* = BestResponse(game, game.prior).
int DefaultAction(const Game& game);

// Theorem 1 (eq:theta_star) over a finite signal set: `signals` is n x k, column
// j holding pi(s_j | w). Result in [0, 1]: 0 when some non-default action is
// already weakly preferred at the prior, 1 when no signal in the set can ever
// persuade (also reported by `persuadable = false`). "Persuade" is the paper's
// weak inequality U(a'|p_theta) >= U(a0|p_theta) under the tolerance policy: an
// action whose best full-trust gain is a tie (0) is persuadable at theta* = 1,
// one whose best full-trust gain is a clear loss never is.
TrustThreshold MinPersuadableTrust(const Game& game, const Eigen::MatrixXd& signals);

// Theorem 1 with an unrestricted signal set (the sender may fully reveal any
// state), i.e. max_s Delta U_FT(a', a0; s) = max_w Delta u(w).
TrustThreshold MinPersuadableTrust(const Game& game);

// Corollary (eq:theta_two_states): two states, two actions, default action a2.
// delta_u1 = u(w1,a1) - u(w1,a2), delta_u2 = u(w2,a1) - u(w2,a2),
// prior_w1 = p0(w1). Returns the unclamped value of the formula.
double TwoStateTrustThreshold(double prior_w1, double delta_u1, double delta_u2);

// eq:ppp for any 2x2 receiver utility table (rows w1, w2; columns a1, a2):
// the posterior of w1 at which the receiver is indifferent between a1 and a2.
// Throws if the table has no interior indifference point.
double IndifferencePosterior(const Eigen::Matrix2d& receiver_utility);

}  // namespace taebp::persuasion
