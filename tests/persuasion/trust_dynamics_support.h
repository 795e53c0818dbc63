// What the dynamic-trust tests share (trust_dynamics_test.cc,
// trust_dynamics_simulation_test.cc): the paper's game and a Beta update rule.
#pragma once

#include "taebp/persuasion/trust_dynamics.h"

namespace taebp::persuasion::trust_test {

inline const AvHvParams kPaper{0.2, 3.0};  // p* = 0.4, theta* = 0.25

inline TrustUpdateRule Weights(double w_s, double w_f, double rho = 0.0) {
  TrustUpdateRule rule;
  rule.success_weight = w_s;
  rule.failure_weight = w_f;
  rule.forgetting = rho;
  return rule;
}

}  // namespace taebp::persuasion::trust_test
