// Outcome prediction per AV-HV encounter for the policies of the paper's
// simulation (Section V-B) plus full revelation.
//
// The AV designs with an assumed trust theta_hat; the HV's true trust is theta
// and it reads the observed nudge with its intuitive likelihood model.
// The AV's action: if the design is persuadable, Go intent -> go, Stop intent
// -> wait; if not (fallback), the AV always yields; under no_ebp it goes on Go
// intent iff the HV drives if clear at the prior. A collision happens when the
// AV goes and the HV drives recklessly.
//
// What a still AV means (the choice behind HvPosteriorGo(scheme, ...)):
// - With a signalling scheme -- the AV nudges with positive probability in some
//   state (a > 0 or b > 0: TA-EBP, No Trust, full revelation) -- the HV knows
//   the AV may nudge, so every motion is a signal, standing still included: a
//   still AV is the signal s = 0, read like any nudge through eq:pp and the HV's
//   intuitive likelihood (linear model: p_FT(Go | 0) = 0, "it would have nudged
//   if it meant to go"). This is the paper's signal space S = {s*, 0} (Step 2 of
//   Section IV-C).
// - Without one (no_ebp, and TA-EBP's fallback "always yield": a = b = 0) the
//   AV never nudges, so its standing still carries no information -- under the
//   scheme pi(0 | Go) = pi(0 | Stop) = 1 and Bayes' rule returns the prior. The
//   HV decides "from the prior" (the paper's description of No EBP, Section
//   V-B): p = lambda whatever its trust, DC iff lambda >= p*. The AV predicts
//   the same, so No EBP never collides, and for lambda >= p* every HV drives if
//   clear. (Below p*, the paper's setting, both readings give DR.)
#pragma once

#include "taebp/persuasion/av_hv.h"

#include <optional>
#include <string>
#include <vector>

namespace taebp::persuasion {

// The paper's policies (no_ebp, no_trust, ta_ebp), full revelation, and two
// TA-EBP variants that differ only in which trust theta_hat the AV designs
// for: population_mean (the mean trust of the HV population, one design for
// every HV) and ta_ebp_learned (a safe lower bound of the HV's trust learned
// from its responses; trust_learning.h). For both, CommitScheme is TA-EBP's
// design for the theta_hat the caller passes. always_nudge (issue 29, the
// deterministic strategy of the paper's Section I): nudges TA-EBP's s* for
// theta_hat in every encounter whatever its intent (a = b = 1) and goes on its
// Go intent, believing the nudge persuades, as No Trust's AV does.
// random_nudge (issue 42, the randomised baseline in the spirit of Sagheb et
// al. 2023: noise on the robot's action): nudges in every encounter (a = b =
// 1) a magnitude drawn uniformly on (0, s_max], independent of its intent, and
// goes on its Go intent.
enum class Policy {
  kNoEbp, kNoTrust, kTaEbp, kFullReveal, kPopulationMean, kTaEbpLearned, kAlwaysNudge,
  kRandomNudge
};
// Their names, labels and the rest are the config's (config/policies.h: the
// one table of policies); the math knows them by this enum only.

// What the AV commits to for one policy.
struct CommittedScheme {
  bool av_may_go = false;  // false: always yields
  double nudge = 0.0;      // s emitted when signalling
  double a = 0.0;          // P(nudge | Go)
  double b = 0.0;          // P(nudge | Stop)
  // random_nudge: the magnitude of each nudge is drawn uniformly on
  // (0, nudge], independent of the intent (NudgeMagnitude); false: it is `nudge`.
  bool random_magnitude = false;
  // True when the AV nudges with positive probability in some state: then the
  // AV's motion, standing still included, is a signal (see the top of the file).
  bool Signals() const { return a > 0.0 || b > 0.0; }
};
// theta_hat: the AV's assumed trust (ignored for full_reveal and no_ebp;
// no_trust forces 1). For no_ebp, av_may_go is true iff the HV drives if clear
// at the prior (lambda >= p*), which is what a still AV leaves it with.
CommittedScheme CommitScheme(Policy policy, const AvHvParams& params, double theta_hat,
                             const LikelihoodModel& model);

// The magnitude of one nudge under `scheme`, given a uniform u in [0, 1) from
// the drawing stream: (1 - u) * nudge (uniform on (0, nudge]) for a random
// magnitude, `nudge` otherwise (u unused).
double NudgeMagnitude(const CommittedScheme& scheme, double u);

// The HV's belief p(Go) after seeing the AV move s metres (0: stood still)
// under `scheme`: eq:pp (HvPosteriorGo in av_hv.h) when the scheme signals, the
// prior lambda when it does not. s must be in [0, s_max] either way. The
// runner's HV (controller ReadNudge) reads SUMO's displacement through this.
double HvPosteriorGo(const CommittedScheme& scheme, const AvHvParams& params, double theta,
                     const LikelihoodModel& model, double s);

struct PredictedOutcome {
  double dc_rate = 0.0;         // P(HV drives if clear) per encounter
  double collision_rate = 0.0;  // P(AV goes and HV drives recklessly)
  double nudge_rate = 0.0;      // P(AV nudges); 0 when the committed nudge is s = 0
  double av_first_rate = 0.0;   // P(AV crosses before the HV): AV goes and HV drives
                                // if clear (collisions are not counted)
};
// A random magnitude is averaged over its uniform distribution: the HV's DC
// share is the measure of the magnitudes it reads as DC (exact where the DC set
// changes at most once per 1/1024 of the range, located by bisection).
PredictedOutcome PredictOutcome(const CommittedScheme& scheme, const AvHvParams& params,
                                double theta_true, const LikelihoodModel& hv_model);
// Convenience: theta_hat defaults to theta_true (ta_ebp) and is forced to 1 for no_trust.
PredictedOutcome PredictOutcome(Policy policy, const AvHvParams& params, double theta_true,
                                const LikelihoodModel& model,
                                std::optional<double> theta_hat = std::nullopt);

}  // namespace taebp::persuasion
