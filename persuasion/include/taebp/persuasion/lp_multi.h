// Trust-aware persuasion of several receivers by one PUBLIC signal, as a
// linear program (GLPK): the general finite case behind multi_receiver.h
// (derivation and the revelation-principle argument in
// docs/beyond/multi-receiver.md).
//
// Receivers i = 1..N share the states and the prior; each has its own actions,
// utility u_i (a Game's receiver_utility) and trust theta_i, and reads the
// common signal s with p_i(w|s) = (1 - theta_i) p0(w) + theta_i p_FT(w|s). The
// sender's utility is additive: v(w, profile) = sum_i v_i(w, a_i) (each Game's
// sender_utility). The signals are recommended action PROFILES sigma = (a_1..a_N),
// shown to everyone; the variables are x(w, sigma) = pi(sigma | w). Receiver i's
// obedience to sigma against a' is, multiplied by P(sigma) (linear in x),
//   sum_w p0(w) [(1 - theta_i) dU0_i(sigma_i, a') + theta_i D_i(w; sigma_i, a')] x(w, sigma) >= 0
// -- the single-receiver row of lp.h for (sigma_i, a'), applied to every profile
// recommending sigma_i to i. Maximise sum_w p0(w) sum_sigma x(w, sigma) v(w, sigma)
// subject to obedience, sum_sigma x(w, sigma) = 1 and x >= 0. With N = 1 this
// is SolveTrustAwarePersuasion's LP.
//
// The number of profiles is prod_i m_i: the LP is for small meetings (the
// all-way stop: 2 actions, 2-4 receivers). It is built whole (no lazy rows)
// and refused above lp.h's kMaxLpVariables and kMaxLpObedienceEntries.
#pragma once

#include "taebp/persuasion/lp.h"
#include "taebp/persuasion/persuasion.h"

#include <string>
#include <vector>

namespace taebp::persuasion {

struct PublicLpResult {
  LpResult::Status status = LpResult::Status::kSolverError;
  std::string message;        // solver detail when not optimal
  double sender_value = 0.0;  // sum_w p0(w) sum_sigma pi(sigma|w) sum_i v_i(w, sigma_i)
  // profiles[k][i]: the action recommended to receiver i by profile k (receiver
  // 0 varies fastest); scheme column k is pi(profile k | w).
  std::vector<std::vector<int>> profiles;
  Eigen::MatrixXd scheme;              // states x profiles
  Eigen::VectorXd signal_probability;  // P(profile k)
  // Row i, column a: P(receiver i is recommended a) = P(receiver i plays a).
  Eigen::MatrixXd action_probability;
  // Profiles GLPK's round-off left disobedient for some receiver beyond
  // kObedienceTolerance, merged into the profile with that receiver's best
  // response (lp.h, the tolerance policy).
  int merged_recommendations = 0;
};

// receivers and trusts: the same size N >= 1; every Game valid, all with the
// same state names and prior (within kProbabilityTolerance); trusts in [0, 1].
// Throws InvalidArgument naming the field and value (also when the LP is above
// the size limits). GLPK failures are reported in the result.
PublicLpResult SolvePublicPersuasion(const std::vector<Game>& receivers,
                                     const std::vector<double>& trusts);

}  // namespace taebp::persuasion
