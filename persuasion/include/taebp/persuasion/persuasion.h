// Finite Bayesian persuasion with a trust-weighted receiver (paper Sections II-IV).
//
// Pure math: no SUMO include may ever appear under persuasion/.
// Conventions: matrices have one row per state and one column per action.
// Every function that takes user-facing parameters validates them and throws
// taebp::persuasion::InvalidArgument whose message names the parameter and value.
#pragma once

#include <Eigen/Dense>

#include <stdexcept>
#include <string>
#include <vector>

namespace taebp::persuasion {

// Thrown on bad input. The message names the parameter and the offending value,
// e.g. "trust theta = 1.3 is outside [0, 1]".
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Tolerance used when comparing expected utilities / posteriors against an
// indifference threshold. Ties break toward the sender: a posterior computed at
// exactly p* that lands up to kTieTolerance below it through round-off still
// counts as persuaded.
inline constexpr double kTieTolerance = 1e-9;

// A finite persuasion game.
struct Game {
  std::vector<std::string> states;   // size n
  std::vector<std::string> actions;  // size m
  Eigen::VectorXd prior;             // n, in the interior of the simplex
  Eigen::MatrixXd receiver_utility;  // n x m, u(w, a)
  Eigen::MatrixXd sender_utility;    // n x m, v(w, a)

  // True if shapes agree, n >= 2, m >= 2, prior entries are > 0 and sum to 1
  // (within 1e-9). Otherwise false with a message naming the field and value.
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

// eq:receiver_action: argmax_a U(a | belief). Among the actions whose receiver
// utility is within `tolerance` of the maximum, picks the one the sender likes
// best under `belief` (ties toward the sender); remaining ties: lowest index.
int BestResponse(const Game& game, const Eigen::VectorXd& belief,
                 double tolerance = kTieTolerance);

// The receiver's default action a0* = BestResponse(game, game.prior).
int DefaultAction(const Game& game);

// Theorem 1 (eq:theta_star) over a finite signal set: `signals` is n x k, column
// j holding pi(s_j | w). Result in [0, 1]: 0 when some non-default action is
// already (weakly) preferred at the prior, 1 when no signal in the set can ever
// persuade (also reported by `persuadable = false`).
struct TrustThreshold {
  double theta_star = 1.0;
  bool persuadable = false;  // some theta in [0,1] persuades to a non-default action
  int default_action = 0;
  int target_action = -1;    // argmin action a' in eq:theta_star, -1 if none
};
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
