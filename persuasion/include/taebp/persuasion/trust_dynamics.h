// Dynamic trust on the HV side: trust as a Beta distribution updated by each
// AV-HV encounter (Guo & Yang 2021), and its long-run behaviour under each
// policy. Pure math; see docs/beyond/derivations.md, "Dynamic trust".
//
// State: theta ~ Beta(alpha, beta); the HV uses the mean theta = alpha / (alpha + beta).
// After an encounter with quality q in [0, 1] (how well the AV's signal matched
// what the AV did), with forgetting rate rho in [0, 1]:
//   alpha <- alpha0 + (1 - rho)(alpha - alpha0) + w_s q
//   beta  <- beta0  + (1 - rho)(beta  - beta0)  + w_f (1 - q)
// (rho = 0: no forgetting; the decay toward the initial (alpha0, beta0) comes
// first, then the new evidence). w_s = w_f = rho = 0 is static trust.
//
// Long run: with Q(theta) = E[q] for the scheme the policy commits at trust
// theta, the mean-field drift of the mean is proportional to
//   G(theta) = rho (alpha0 (1 - theta) - beta0 theta)
//            + w_s Q(theta) (1 - theta) - w_f (1 - Q(theta)) theta,
// the expected change of alpha (1 - theta) - beta theta. Its zeros are the
// long-run trust (rho = 0: the limit of the mean; rho > 0: the stationary point
// of the mean-field recursion). Q jumps where the HV's response or the AV's
// scheme switches, so G may change sign across a jump instead of at a zero.
#pragma once

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/outcomes.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace taebp::persuasion {

// What the HV saw of one encounter: whether the AV nudged, whether it then took
// the right of way, and whether it ended in a collision or a near miss.
enum class EncounterOutcome {
  kNudgeGo,    // nudged, then went: the nudge meant Go (confirmed)
  kNudgeStop,  // nudged, then yielded: a false alarm
  kStillStop,  // stood still, then yielded: standing still meant Stop (confirmed)
  kStillGo,    // stood still, then went: an unannounced Go
  kCollision,
  kNearMiss,
};
inline constexpr int kEncounterOutcomeCount = 6;
inline constexpr std::array<EncounterOutcome, kEncounterOutcomeCount> kAllEncounterOutcomes = {
    EncounterOutcome::kNudgeGo, EncounterOutcome::kNudgeStop, EncounterOutcome::kStillStop,
    EncounterOutcome::kStillGo, EncounterOutcome::kCollision, EncounterOutcome::kNearMiss};
// "nudge_go", "nudge_stop", "still_stop", "still_go", "collision", "near_miss".
const char* ToString(EncounterOutcome outcome);
// Throws InvalidArgument naming the text and the accepted names.
EncounterOutcome ParseEncounterOutcome(const std::string& name);

// A collision wins over a near miss, which wins over the signal/action pair.
// `av_went` is "the AV took the right of way" (crossed first or tried to);
// a nudge of distance 0 is standing still.
EncounterOutcome ClassifyEncounter(bool nudged, bool av_went, bool collision, bool near_miss);

// q for each outcome. Defaults (reasoning in docs/beyond/derivations.md): the signal told the
// truth -> 1; it told the opposite of what the AV did, or the encounter ended
// in a collision or a near miss -> 0.
struct OutcomeQuality {
  double nudge_go = 1.0;
  double nudge_stop = 0.0;
  double still_stop = 1.0;
  double still_go = 0.0;
  double collision = 0.0;
  double near_miss = 0.0;
  double Of(EncounterOutcome outcome) const;
  // Each in [0, 1]; the message names the outcome, e.g. "quality.nudge_stop = 1.5 is outside [0,
  // 1]".
  bool IsValid(std::string* why) const;
  void Validate() const;
};

struct TrustUpdateRule {
  // A weight's bound: 10^9 encounters' worth of evidence per encounter sets the
  // trust to 0 or 1 at once already, and keeps α + β finite over any run (a
  // weight of 1e308 overflowed it to inf, and θ to NaN, mid-run).
  static constexpr double kMaxWeight = 1e9;
  double success_weight = 1.0;  // w_s in [0, kMaxWeight]
  double failure_weight = 1.0;  // w_f in [0, kMaxWeight]
  double forgetting = 0.0;      // rho in [0, 1]
  OutcomeQuality quality;
  // Static trust: nothing ever changes the state.
  bool IsStatic() const {
    return success_weight == 0.0 && failure_weight == 0.0 && forgetting == 0.0;
  }
  bool IsValid(std::string* why) const;
  void Validate() const;  // throws InvalidArgument naming the field and value
};

// One HV's trust state.
class BetaTrust {
 public:
  // alpha0, beta0 > 0 and finite (the initial state, kept for forgetting).
  BetaTrust(double alpha0, double beta0);
  // alpha0 = mean * strength, beta0 = (1 - mean) * strength; mean in (0, 1), strength > 0.
  static BetaTrust FromMean(double mean, double strength);

  double Alpha() const { return alpha_; }
  double Beta() const { return beta_; }
  double InitialAlpha() const { return alpha0_; }
  double InitialBeta() const { return beta0_; }
  double Mean() const { return alpha_ / (alpha_ + beta_); }  // the trust the HV uses
  double InitialMean() const { return alpha0_ / (alpha0_ + beta0_); }

  void Update(double q, const TrustUpdateRule& rule);  // q in [0, 1]
  void Update(EncounterOutcome outcome, const TrustUpdateRule& rule);

 private:
  double alpha0_, beta0_, alpha_, beta_;
};

// ------------------------------------------------------------------ long run

// The scheme a policy commits to when the HV's (mean) trust is theta:
// CommitScheme(policy, theta_hat) with theta_hat = assumed_trust if given (an AV
// that keeps one design however trust moves), else theta (an AV that tracks the
// HV's current trust; no_trust forces 1 either way).
struct DesignRule {
  Policy policy = Policy::kTaEbp;
  std::optional<double> assumed_trust;
};
CommittedScheme SchemeFor(const DesignRule& rule, const AvHvParams& params, double theta,
                          const LikelihoodModel& model);

// P(outcome) for one encounter, indexed by the order of kAllEncounterOutcomes;
// the HV has trust theta_true and reads the nudge exactly. The model has no
// geometry, so P(near miss) = 0. Consistent with PredictOutcome: P(collision) =
// collision_rate, P(nudge_go) + P(still_go) = av_first_rate.
std::array<double, kEncounterOutcomeCount> OutcomeProbabilities(const CommittedScheme& scheme,
                                                                const AvHvParams& params,
                                                                double theta_true,
                                                                const LikelihoodModel& model);

// Q(theta) = E[q] when the policy commits at trust theta and the HV has trust theta.
double ExpectedQuality(const DesignRule& rule, const AvHvParams& params, double theta,
                       const LikelihoodModel& model, const OutcomeQuality& quality);

// E[delta alpha], E[delta beta] for one encounter from `state` (the HV's trust is its mean).
struct ExpectedUpdate {
  double quality = 0.0;  // Q at the state's mean
  double alpha = 0.0;    // rho (alpha0 - alpha) + w_s Q
  double beta = 0.0;     // rho (beta0 - beta) + w_f (1 - Q)
  double mean = 0.0;     // E[mean after] - mean before, exact over the outcomes
};
ExpectedUpdate ExpectedStep(const BetaTrust& state, const DesignRule& rule,
                            const AvHvParams& params, const LikelihoodModel& model,
                            const TrustUpdateRule& update);

// G(theta) above; alpha0, beta0 matter only with forgetting.
double MeanDrift(double theta, const DesignRule& rule, const AvHvParams& params,
                 const LikelihoodModel& model, const TrustUpdateRule& update, double alpha0,
                 double beta0);

// Closed forms.
// Where Q is constant on a stretch of theta, G = 0 at
//   theta = (rho alpha0 + w_s Q) / (rho (alpha0 + beta0) + w_s Q + w_f (1 - Q))
// (NaN when the denominator is 0: static trust, every theta is stationary).
double ConstantQualityEquilibrium(double quality, const TrustUpdateRule& update, double alpha0,
                                  double beta0);
// Where the AV tracks the HV's trust with TA-EBP (theta >= the model's theta*:
// a = 1, b(theta) of eq:b, the HV drives if clear after the nudge and not when
// the AV stands still), (1 - lambda) b(theta) = lambda ((1 - lambda) theta - D) /
// (D + lambda theta) with D = p* - lambda, so Q is a Moebius function of theta
// and G (D + lambda theta) is a quadratic. Returns its real roots in [lo, hi],
// ascending (lambda < p* required).
std::vector<double> TaebpEquilibria(const AvHvParams& params, const TrustUpdateRule& update,
                                    double alpha0, double beta0, double lo, double hi);

// Every point where the long-run drift changes sign.
struct TrustEquilibrium {
  enum class Kind {
    kRoot,      // G = 0 inside a stretch where Q is continuous
    kJump,      // G changes sign across a jump of Q (the mean hovers about it)
    kBoundary,  // theta = 0 or 1 with G(theta) = 0 there
  };
  double theta = 0.0;
  Kind kind = Kind::kRoot;
  bool stable = false;  // G > 0 just below and G < 0 just above (attracts the mean)
};
const char* ToString(TrustEquilibrium::Kind kind);

struct LongRunTrust {
  std::vector<TrustEquilibrium> equilibria;  // ascending theta
  std::vector<double> breakpoints;           // where Q jumps (HV response or scheme switches)
  // The stable equilibria (the possible long-run means).
  std::vector<double> Attractors() const;
};
// Q is piecewise continuous; its jumps are found by scanning `grid` cells and
// bisecting where the scheme's shape or the HV's responses change, each piece
// is scanned for sign changes of G and each bracket refined with TOMS 748 to
// ~1e-14. Two sign changes within one grid cell (a tangency) can be missed;
// TaebpEquilibria gives the exact roots of the TA-EBP piece.
LongRunTrust FindLongRunTrust(const DesignRule& rule, const AvHvParams& params,
                              const LikelihoodModel& model, const TrustUpdateRule& update,
                              double alpha0, double beta0, int grid = 1024);

}  // namespace taebp::persuasion
