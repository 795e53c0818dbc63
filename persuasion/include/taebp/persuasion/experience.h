// Beyond the paper: HVs who learn from experience what a signal meant
// (issue 29; derivations in docs/influence.md). SUMO-free.
//
// The paper's HV reads a nudge s with its intuitive likelihood and never
// revises what a nudge means. Here each HV also remembers, per signal level
// (the displacement it read, in bins of `bin_width` metres), how many times it
// read that level (n) and how many of those times the AV then went (g). Its
// full-trust posterior for a reading s blends the intuitive posterior
// q(s) = p_FT(Go|s) with that experience as a Beta-Bernoulli mean with prior
// strength k:
//     p_E(s) = (k q(s) + g) / (k + n),                          (ExperiencedPosterior)
// and trust weighs it as in the paper (eq:pp with p_FT replaced by p_E):
//     p_theta,E(Go|s) = (1 - theta) lambda + theta p_E(s).      (ExperiencedBelief)
// k -> infinity (or n = 0) is the paper's HV. "The AV went" is what the HV
// sees: the AV took the right of way (its intent was Go and its scheme lets it
// go), whether or not the two then collided.
//
// Fixed points (LongRunUnderExperience): under a committed scheme, g/n at the
// nudge's level converges to the scheme's own Bayes posterior of "the AV goes"
// given the nudge, so p_E converges to it whatever k. TA-EBP at s* is the one
// design whose Bayes posterior equals the intuitive one (Theorem 2's
// consistency condition, L(s*) = pi(s*|Go)/pi(s*|Stop) = 1/b), so learning
// changes nothing on average -- but that posterior sits exactly on the HV's
// indifference point, and the count's sampling noise puts it below p* about
// half of the time (the knife edge). DesignForExperience is the fix: TA-EBP
// designed for the HV's experienced belief, from the public history of the
// AV's own signals and actions.
#pragma once

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/outcomes.h"

#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace taebp::persuasion {

// model.experience: the learner's rule (the AV is not told it; see
// RobustScheme below for a design that does not need it).
//   forgetting rho in (0, 1]: the weight each encounter of the HV leaves on
//   everything it remembered before (every level's n and g are multiplied by
//   rho, then the new reading is added); 1 = the exact counts of issue 29.
//   With rho < 1 the counts are weights, not integers: n stays below
//   1 / (1 - rho), so the learned frequency never settles (its variance in the
//   long run is pi (1 - pi) (1 - rho) / (P(level) (1 + rho)); docs/influence.md).
struct ExperienceRule {
  double strength = 20.0;   // k > 0: readings' worth of trust in the intuitive model
  double bin_width = 0.1;   // m > 0: readings in [j w, (j+1) w) are one signal level
  double forgetting = 1.0;  // rho in (0, 1]: weight on the past per encounter
  bool IsValid(std::string* why) const;
  void Validate() const;  // throws InvalidArgument naming the field and value
};

// What one HV remembers of one signal level (weights: integers when it
// forgets nothing).
struct SignalCounts {
  double readings = 0;  // n: (weighted) times it read a displacement in this level
  double went = 0;      // g: of those, (weighted) times the AV then went
};

// One HV's memory: counts per signal level.
class SignalExperience {
 public:
  // forgetting: rho in (0, 1] (ExperienceRule::forgetting).
  explicit SignalExperience(double bin_width, double forgetting = 1.0);
  long Level(double reading) const;  // floor(reading / bin_width), reading >= 0
  SignalCounts At(double reading) const;
  // The HV read `reading` (SUMO's displacement) and then saw the AV go or not:
  // every level's counts are multiplied by rho, then this reading is added.
  void Record(double reading, bool av_went);
  const std::map<long, SignalCounts>& Levels() const { return levels_; }
  long Readings() const { return readings_; }  // encounters recorded (unweighted)

 private:
  double width_, forgetting_;
  std::map<long, SignalCounts> levels_;
  long readings_ = 0;
};

// (k q + g) / (k + n): the Beta(k q, k (1 - q)) prior's posterior mean.
double ExperiencedPosterior(double intuitive_go, const SignalCounts& counts, double strength);

// The HV's belief p(Go) after reading s (in [0, s_max]) with experience
// `counts` at that level: (1 - theta) lambda + theta p_E(s), where q(s) is the
// full-trust posterior HvPosteriorGo(scheme, params, 1, model, s) (the prior
// lambda when the scheme does not signal).
double ExperiencedBelief(const CommittedScheme& scheme, const AvHvParams& params, double theta,
                         const LikelihoodModel& model, double s, const SignalCounts& counts,
                         double strength);

// ---------------------------------------------------------------- fixed points
// Where a committed scheme's learned beliefs go (n -> infinity at each level
// the scheme uses) and the rates that follow for an HV of trust theta.
struct ExperienceLongRun {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double went_after_nudge = kNaN;  // P(AV goes | nudge): the nudge level's fixed point
  double went_after_still = kNaN;  // P(AV goes | still): the level 0's fixed point
  double belief_after_nudge = kNaN;  // (1 - theta) lambda + theta went_after_nudge
  // The learned belief after a nudge sits on p* (within the tie tolerance):
  // the HV's choice is decided by the sign of a zero-mean random walk, DC in
  // half of the encounters in the long run (the arcsine law's mean).
  bool knife_edge = false;
  double dc_after_nudge = kNaN;  // 1, 0, or 1/2 on the knife edge
  PredictedOutcome outcome;      // dc_rate, collision_rate, nudge_rate, av_first_rate
};
// Requires a scheme that signals with a in {0, 1} (the AV never stands still
// on a Go it acts on) or does not signal at all.
ExperienceLongRun LongRunUnderExperience(const CommittedScheme& scheme, const AvHvParams& params,
                                         double theta, const LikelihoodModel& model);

// ---------------------------------------------------------------- the fix
// TA-EBP for an HV that learns (DesignForExperience). The AVs know the public
// history of their own signals and actions, hence each HV's counts. `paper` is
// the paper's design for the HV's trust (s*, a = 1, b from eq:b). Per encounter,
// committed before the intent is drawn:
//   kPaper:    (s*, 1, b) when a false alarm now (nudge, then Stop) would
//              still leave s* persuasive for this HV: eq:b's "largest b that
//              keeps the nudge persuasive", applied to the experienced belief;
//   kGuard:    (s*, 1, 0) when it would not, but s* persuades now;
//   kStronger: (s_max, 1, 0) when s* does not persuade now but s_max does;
//   kYield:    always yield (no signal) when neither does.
// Invariant: an HV persuaded by s* stays persuaded by s* (a Go after the
// nudge only raises p_E), so with the paper's s* (p_E = q(s*) at n = 0) no
// nudge is ever read as DR and no Go collides. In the long run the guard binds
// on a vanishing share of encounters and DC -> lambda + (1 - lambda) b: the
// paper's rate, which is also the most any scheme keeps against a learner
// (its nudge's go-frequency must stay >= the HV's threshold, so
// P(nudge) <= lambda / that threshold = lambda + (1 - lambda) b).
struct ExperiencedDesign {
  enum class Mode { kPaper, kGuard, kStronger, kYield };
  Mode mode = Mode::kYield;
  CommittedScheme scheme;
};
const char* ToString(ExperiencedDesign::Mode mode);
ExperiencedDesign DesignForExperience(const CommittedScheme& paper, const AvHvParams& params,
                                      double theta, const LikelihoodModel& model,
                                      double strength,
                                      const std::function<SignalCounts(double)>& counts_at);

// ---------------------------------------------------------------- robust
// A committed design that does not need the learner's rule
// (model.experience.design: robust; issue 42, docs/influence.md). The AV
// commits, before its intent, from public quantities only (lambda, r, its
// assumed trust theta_hat, the likelihood model): no HV's counts, no k, no rho.
//   nudge s_max (the most persuasive displacement of the intuitive model),
//   a = 1, and the largest b whose own Bayes posterior pi_b = lambda /
//   (lambda + (1 - lambda) b) leaves the HV's belief a margin m above p*:
//       (1 - theta_hat) lambda + theta_hat pi_b >= p* + m,
// provided the intuitive reading of s_max clears the same bar (then a fresh
// HV is persuaded too); else it yields (never nudges, never goes).
// Why it holds against learners it is not told: every learner of the family
// (any k, any forgetting rho, exact or noisy readings of s_max) reads a nudge
// with a belief between the intuitive q(s_max) and a weighted go-frequency
// whose mean is pi_b; both clear p* + m, so the HV drives recklessly after a
// nudge only when the frequency's sampling noise falls more than the margin,
// which RobustRiskUnderForgetting bounds in the long run (an HV of small k can
// still read its first false alarms as DR: ExperiencePath gives that risk per
// encounter; in SUMO, k = 2 HVs cost 0.0003-0.001 collisions per encounter,
// docs/influence.md). The tie rule is explicit: m > 0
// keeps every belief the design relies on m away from p*, so no rounding or
// nudge overshoot decides it. DC in the long run: lambda / pi_b (against any
// learner whose beliefs stay persuaded), at most the paper's lambda + (1 -
// lambda) b_paper at m = 0.
struct RobustDesign {
  bool persuades = false;     // false: the scheme always yields
  double belief_target = 0;   // p* + m
  double pi_target = 0;       // the Bayes posterior pi_b it needs
  double intuitive_max = 0;   // q(s_max)
  CommittedScheme scheme;
};
RobustDesign DesignRobust(const AvHvParams& params, double theta_hat, const LikelihoodModel& model,
                          double margin);

// Per-nudge probability (normal approximation, long run) that a learner with
// prior strength k and forgetting rho reads the robust nudge as DR: with
// p_N = P(nudge) and pi = pi_b, the stationary weighted counts have
// E n = p_N / (1 - rho) and Var(g - pi n) = p_N pi (1 - pi) / (1 - rho^2);
// the HV drives recklessly iff k (q - pi_c) + (g - pi_c n) < 0, pi_c the
// full-trust posterior at which its belief meets p*. 0 for rho = 1 (the exact
// learner: the frequency settles on pi_b > pi_c). docs/influence.md.
double RobustRiskUnderForgetting(const RobustDesign& design, const AvHvParams& params,
                                 double theta, double strength, double forgetting);

// ---------------------------------------------------------------- mean field
// The expected learning path of one HV of trust theta whose AVs commit to
// `scheme` (guarded: DesignForExperience around it): At(t) is the expected
// outcome of the HV's encounter t (t = 0: the first), exact over the
// binomial experience at the nudge level (the distribution of (n, g) after t
// encounters, propagated encounter by encounter; states below 1e-15 are
// dropped). The response to standing still is fixed (the scheme has a = 1 or
// does not signal: nothing goes after a still AV, so its level only confirms
// what the intuitive model says). Readings are taken at the commanded nudge.
// A learner that forgets (rho < 1) holds weights, not counts: its path is the
// normal approximation of RobustRiskUnderForgetting at encounter t (E n_t =
// p_N (1 - rho^t) / (1 - rho), Var(g - pi n)_t = p_N pi (1 - pi) (1 - rho^2t)
// / (1 - rho^2)), for the committed scheme as it is: a guard, designed for
// exact counts, is not modelled there (docs/influence.md says so).
// A random magnitude (random_nudge: a nudge uniform on (0, s_max] in every
// encounter, independent of the intent) spreads the readings over the
// learner's levels of `bin_width` metres (required then): level l is read with
// probability w_l (its share of (0, s_max]), so after t encounters its count is
// Binomial(t, w_l) and its Gos Binomial(n, lambda); At(t) is exact over both
// and over the magnitude inside the level (the intuitive posterior q(s) must be
// non-decreasing in s, checked). With rho < 1 each level takes the normal
// approximation above with p_N = w_l and pi = lambda.
class ExperiencePath {
 public:
  // design_strength: the k the guarded design assumes (0: the HV's own
  // `strength`, the AV told the rule); the HV reads with `strength`.
  ExperiencePath(const CommittedScheme& scheme, const AvHvParams& params, double theta,
                 const LikelihoodModel& model, double strength, bool guarded,
                 double forgetting = 1.0, double bin_width = 0.0, double design_strength = 0.0);
  PredictedOutcome At(long t);
  long Computed() const { return static_cast<long>(path_.size()); }

 private:
  struct Level {
    double lo = 0, hi = 0, weight = 0, q_lo = 0, q_hi = 0;
  };
  PredictedOutcome RandomAt(long t) const;
  double RandomLevelDc(const Level& level, long t) const;
  std::vector<Level> levels_;  // random magnitude only
  std::map<long, PredictedOutcome> random_;  // its At(t), computed directly per t
  void Step();
  CommittedScheme scheme_;
  AvHvParams params_;
  PredictedOutcome Forgetting(long t) const;
  double theta_, strength_, forgetting_, design_strength_;
  bool guarded_;
  double q_nudge_ = 0, q_max_ = 0, s_max_ = 0;
  bool dc_still_ = false;
  // dist_[n][g - lo_[n]]: P(n nudge readings, g of them followed by a Go).
  std::vector<std::vector<double>> dist_;
  std::vector<long> lo_;
  std::vector<PredictedOutcome> path_;
  const LikelihoodModel* model_;
};

}  // namespace taebp::persuasion
