// Perception noise: the HV reads the AV's displacement with noise and a bias,
// and a noise-aware TA-EBP design that still persuades with probability
// 1 - delta. See docs/beyond/derivations.md, "Perception noise".
//
// The HV reads r = clamp(d + bias + eps, 0, s_max) for a realised displacement
// d (what SUMO reports) and decides with eq:pp at r, as if r were the nudge: it
// drives if clear iff r >= r*(theta) = MinReadingForDc(theta) (Theorem 2's s*,
// up to the tie tolerance). So with noise CDF F,
//   P(DC | d) = 1 - F(r* - d - bias)          (continuous noise; r* in (0, s_max])
// exactly, clamping included (a reading clamped to s_max >= r* persuades, one
// clamped to 0 < r* does not). The noise-aware nudge is the least d with
// P(DC | d) >= 1 - delta:  s_delta = s* - bias - F^-1(delta).
#pragma once

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/outcomes.h"

#include <string>

namespace taebp::persuasion {

struct PerceptionNoise {
  enum class Kind { kNone, kGaussian, kUniform };
  Kind kind = Kind::kNone;
  double scale =
      0.0;            // Gaussian sigma or uniform half-width w (m); > 0 unless kNone (ignored then)
  double bias = 0.0;  // added to every reading (m); finite
  bool IsValid(std::string* why) const;
  void Validate() const;  // throws InvalidArgument naming the field and value
  // The distribution of eps (without the bias). kNone: a point mass at 0
  // (Cdf a step at 0, Quantile 0, Density 0).
  double Cdf(double e) const;
  double Quantile(double p) const;  // p in (0, 1)
  double Density(double e) const;
};
// "none", "gaussian", "uniform".
const char* ToString(PerceptionNoise::Kind kind);
PerceptionNoise::Kind ParseNoiseKind(const std::string& name);  // throws on an unknown name

// The HV's reading of a realised displacement `observed` from one uniform draw
// u in [0, 1) (eps = Quantile(u'), u' = min(u + 2^-54, 1 - 2^-53) in (0, 1)):
// portable, and one draw per reading whatever the kind.
double NoisyReading(const PerceptionNoise& noise, double observed, double s_max, double u01);

// P(an HV of trust theta drives if clear) when the AV's realised displacement
// is s (s = 0: the AV stands still, which noise may still show as a nudge).
// kNone: 0 or 1 from the HV's decision at clamp(s + bias), as PredictOutcome.
double PersuasionProbability(const PerceptionNoise& noise, const AvHvParams& params, double theta,
                             const LikelihoodModel& model, double s);

// PredictOutcome with the HV's responses averaged over the noise: DC after the
// nudge with probability PersuasionProbability(nudge), after standing still
// with PersuasionProbability(0). Equals PredictOutcome for kNone with bias 0.
PredictedOutcome PredictOutcomeUnderNoise(const CommittedScheme& scheme, const AvHvParams& params,
                                          double theta_true, const LikelihoodModel& model,
                                          const PerceptionNoise& noise);

// The noise-aware TA-EBP design for an HV of (assumed) trust theta_hat.
//   nudge: s_delta = max(0, s* - bias - F^-1(delta)) (kNone: s* - bias), so that
//     P(DC | s_delta) >= 1 - delta.
//   b: the largest P(nudge | Stop) for which a rational HV of trust theta_hat
//     who knew the scheme and the noise would still be indifferent at the
//     reading s* (the paper's consistency condition at the DC boundary):
//     with rho = f(s* - bias) / f(s* - s_delta - bias) (a still AV's density of
//     producing the reading s* over the nudging AV's), b = (b0 - rho) / (1 - rho),
//     b0 = eq:b. rho = 0 without noise, so b = b0; rho > b0: no b >= 0 is
//     credible (credible = false, b = 0).
struct NoiseAwareDesign {
  enum class Status {
    kOk,
    kNotPersuadable,  // theta_hat below the model's theta*: always yield
    kUnachievable,    // s_delta > s_max: no nudge reaches 1 - delta; always yield
  };
  Status status = Status::kNotPersuadable;
  TaebpDesign nominal;  // the paper's design for theta_hat
  double nudge = 0.0;   // s_delta (0 unless kOk)
  double b = 0.0;
  double b_nominal = 0.0;      // eq:b
  double density_ratio = 0.0;  // rho
  bool credible = true;
  double persuasion_probability = 0.0;      // P(DC | nudge) (kOk: >= 1 - delta)
  double max_persuasion_probability = 0.0;  // P(DC | s_max)
  CommittedScheme scheme;                   // kOk: {go, nudge, a = 1, b}; else always yield
};
const char* ToString(NoiseAwareDesign::Status status);
NoiseAwareDesign DesignUnderNoise(const AvHvParams& params, double theta_hat,
                                  const LikelihoodModel& model, const PerceptionNoise& noise,
                                  double delta);

}  // namespace taebp::persuasion
