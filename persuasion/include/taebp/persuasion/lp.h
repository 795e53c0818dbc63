// The trust-aware optimal signaling scheme for any finite game, as a linear
// program solved with GLPK.
//
// By the revelation principle the signals are action recommendations: pi(a|w).
// With P(a) = sum_w pi(a|w) p0(w), the trust-weighted posterior after
// recommendation a is p_theta(w|a) = (1-theta) p0(w) + theta pi(a|w) p0(w) / P(a).
// Obedience, sum_w p_theta(w|a) (u(w,a) - u(w,a')) >= 0 for all a', is not linear
// in pi, but multiplying it by P(a) >= 0 gives
//   sum_w [ (1-theta) p0(w) P(a) + theta pi(a|w) p0(w) ] (u(w,a) - u(w,a')) >= 0,
// which is linear in pi because P(a) is. (When P(a) = 0 the action is never
// recommended and the constraint is vacuous, as it should be.)
// Maximise sum_w p0(w) sum_a pi(a|w) v(w,a) subject to obedience, sum_a pi(a|w) = 1
// and pi >= 0.
#pragma once

#include "taebp/persuasion/persuasion.h"

#include <string>
#include <vector>

namespace taebp::persuasion {

struct LpResult {
  enum class Status { kOptimal, kInfeasible, kSolverError };
  Status status = Status::kSolverError;
  std::string message;          // solver detail when not optimal
  double sender_value = 0.0;    // sum_w p0(w) sum_a pi(a|w) v(w,a)
  Eigen::MatrixXd scheme;       // n x m: pi(recommend a | w)
  Eigen::VectorXd signal_probability;  // m: P(a)
  // Column a: the trust-weighted posterior after recommendation a (n entries);
  // NaN for actions recommended with probability 0.
  Eigen::MatrixXd posteriors;
};

const char* ToString(LpResult::Status status);

// theta in [0, 1]; the game is validated first (throws InvalidArgument).
LpResult SolveTrustAwarePersuasion(const Game& game, double theta);

}  // namespace taebp::persuasion
