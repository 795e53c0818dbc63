// The AV-HV two-way-stop game of the paper (Table "utility") and the TA-EBP
// design of Section IV-C.
//   States: Go (index 0), Stop (1). HV actions: DR (0), DC (1).
//   u: DR -> (-r, 1), DC -> (0, -1);  v: DR -> -1, DC -> +1.
#pragma once

#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/tolerance.h"

namespace taebp::persuasion {

enum AvState : int { kGo = 0, kStop = 1 };
enum HvAction : int { kDR = 0, kDC = 1 };

struct AvHvParams {
  double prior_go = 0.2;           // lambda, in (0, 1)
  double collision_penalty = 3.0;  // r > 0
  bool IsValid(std::string* why) const;
  void Validate() const;  // throws InvalidArgument naming the parameter and value
};

// The paper's game as a Game (states {Go, Stop}, actions {DR, DC}).
Game AvHvGame(const AvHvParams& params);

// eq:ppp for the AV-HV table: p* = 2 / (2 + r).
double AvHvPStar(double collision_penalty);

// eq:tt: theta* = (2(1-lambda) - r lambda) / ((1-lambda)(r+2)), clamped to
// [0, 1]. When lambda >= p* the HV already drives if clear at the prior: no
// persuasion is needed and theta* = 0.
double AvHvThetaStar(const AvHvParams& params);

// eq:pp: p_theta(Go | s) under the HV's intuitive likelihood model, reading s
// (0 included) as a signal. Whether a still AV is a signal at all depends on the
// AV's scheme: see HvPosteriorGo(scheme, ...) in outcomes.h.
double HvPosteriorGo(const AvHvParams& params, double theta,
                     const LikelihoodModel& model, double s);

// True if the HV drives if clear at posterior p_go: DC is a best response in
// AvHvGame (p_go >= p*, ties toward the AV, under the tolerance policy of
// persuasion.h). Every AV-HV decision (theta*, s*, b, the design, the outcomes,
// the runner's HV) goes through this one function.
bool HvDrivesIfClear(const AvHvParams& params, double p_go);

// The likelihood ratio required by Theorem 2 (the argument of L^{-1} in
// eq:s^*). Only meaningful for theta >= theta*: +infinity at theta = theta*.
double RequiredRatio(const AvHvParams& params, double theta);

// True if the model's strongest nudge s_max persuades an HV with trust theta:
// HvDrivesIfClear(p_theta(Go | s_max)). Equivalent to theta >= theta*_model.
bool AvHvPersuadable(const AvHvParams& params, double theta, const LikelihoodModel& model);

// Theorem 1 for the nudges `model` can produce, s in [0, s_max]. eq:pp is monotone
// in s, so this is MinPersuadableTrust on the two-column signal set
// {pi(.|0), pi(.|s_max)}: eq:tt when L(s_max) = +infinity (linear model), and
// (p* - lambda) / (p_FT(Go|s_max) - lambda) for a bounded L (logistic model).
// For lambda >= p* it returns theta* = 0, persuadable, target DC (no persuasion
// needed), like AvHvThetaStar.
TrustThreshold AvHvModelTrustThreshold(const AvHvParams& params, const LikelihoodModel& model);

// Theorem 2 (eq:s^*): the minimal nudge that makes p_theta(Go|s) >= p*.
// 0 when the required ratio is <= L(0) (no nudge needed). Throws
// InvalidArgument when theta < theta* or the ratio is unreachable by `model`.
double MinimalNudge(const AvHvParams& params, double theta, const LikelihoodModel& model);

// eq:b: pi(s*|Stop), clamped to [0, 1]. Requires theta >= theta*.
double StopNudgeProbability(const AvHvParams& params, double theta);

// The TA-EBP design (Section IV-C), for an AV that assumes trust theta_hat.
struct TaebpDesign {
  bool persuadable = false;  // false -> fallback "always yield", no nudge
  double theta_star = 1.0;   // of the likelihood model (equals eq:tt for unbounded L)
  double p_star = 0.0;
  double s_star = 0.0;       // nudge magnitude (0 when not persuadable)
  double a = 0.0;            // pi(s*|Go): 1 when persuadable
  double b = 0.0;            // pi(s*|Stop), eq:b
  double p_nudge = 0.0;      // lambda * a + (1 - lambda) * b
};
TaebpDesign DesignTaebp(const AvHvParams& params, double theta_hat,
                        const LikelihoodModel& model);

}  // namespace taebp::persuasion
