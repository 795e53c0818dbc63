// Outcome prediction per AV-HV encounter for the policies of the paper's
// simulation (Section V-B) plus full revelation.
//
// The AV designs with an assumed trust theta_hat; the HV's true trust is theta
// and it reads the observed nudge with its intuitive likelihood model.
// The AV's action: if the design is persuadable, Go intent -> go, Stop intent
// -> wait; if not (fallback) or under no_ebp, the AV always yields (it predicts
// from the prior that the HV drives recklessly). A collision happens when the
// AV goes and the HV drives recklessly.
#pragma once

#include "taebp/persuasion/av_hv.h"

#include <optional>
#include <string>

namespace taebp::persuasion {

enum class Policy { kNoEbp, kNoTrust, kTaEbp, kFullReveal };
const char* ToString(Policy policy);
// Accepts "no_ebp", "no_trust", "ta_ebp", "full_reveal"; throws otherwise.
Policy ParsePolicy(const std::string& name);

// What the AV commits to for one policy.
struct CommittedScheme {
  bool av_may_go = false;  // false: always yields
  double nudge = 0.0;      // s emitted when signalling
  double a = 0.0;          // P(nudge | Go)
  double b = 0.0;          // P(nudge | Stop)
};
// theta_hat: the AV's assumed trust (ignored for full_reveal; no_trust forces 1).
// For no_ebp, av_may_go is true only if the HV would drive if clear after seeing
// no nudge (s = 0), as predicted with trust theta_hat.
CommittedScheme CommitScheme(Policy policy, const AvHvParams& params, double theta_hat,
                             const LikelihoodModel& model);

struct PredictedOutcome {
  double dc_rate = 0.0;         // P(HV drives if clear) per encounter
  double collision_rate = 0.0;  // P(AV goes and HV drives recklessly)
  double nudge_rate = 0.0;      // P(AV nudges); 0 when the committed nudge is s = 0
  double av_first_rate = 0.0;   // P(AV crosses before the HV): AV goes and HV drives
                                // if clear (collisions are not counted)
};
PredictedOutcome PredictOutcome(const CommittedScheme& scheme, const AvHvParams& params,
                                double theta_true, const LikelihoodModel& hv_model);
// Convenience: theta_hat defaults to theta_true (ta_ebp) and is forced to 1 for no_trust.
PredictedOutcome PredictOutcome(Policy policy, const AvHvParams& params, double theta_true,
                                const LikelihoodModel& model,
                                std::optional<double> theta_hat = std::nullopt);

}  // namespace taebp::persuasion
