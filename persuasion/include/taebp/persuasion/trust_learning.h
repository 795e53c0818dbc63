// Learned trust on the AV side: a posterior over one HV's trust from censored
// observations of its responses, a safe (delta-bounded) TA-EBP design from it,
// and regret against the oracle that knows theta. See docs/beyond/derivations.md,
// "Learned trust".
//
// The HV's response is deterministic given its trust: after a reading s it
// drives if clear iff theta lies in DcTrustInterval(s) (hv_response.h), for
// lambda < p* the half-line theta >= theta_needed(s). So a DC says theta >=
// theta_needed(s), a DR says theta < theta_needed(s), and the posterior after
// any number of responses is the prior restricted to one interval [L, U): L the
// largest DC threshold, U the smallest DR threshold. That is exact, needs O(1)
// memory per HV, and every query is a prior CDF (or quantile) evaluation.
#pragma once

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/hv_response.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/outcomes.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace taebp::persuasion {

// A population prior over trust in [0, 1].
class TrustPrior {
 public:
  enum class Kind { kBeta, kHistogram, kDiscrete };
  // Beta(a, b), a, b > 0 and finite.
  static TrustPrior Beta(double a, double b);
  // Piecewise-constant density: cell k of K = weights.size() covers
  // [k/K, (k+1)/K) with probability weights[k] / sum (weights >= 0, sum > 0).
  static TrustPrior Histogram(std::vector<double> weights);
  // Point masses: P(theta = values[i]) = weights[i] / sum, values in [0, 1].
  static TrustPrior Discrete(std::vector<double> values, std::vector<double> weights);

  Kind kind() const { return kind_; }
  double Mean() const { return FirstMoment(0.0, kAboveOne) / Mass(0.0, kAboveOne); }
  // P(lo <= theta < hi); hi may be kAboveOne to include theta = 1.
  double Mass(double lo, double hi) const;
  // E[theta; lo <= theta < hi].
  double FirstMoment(double lo, double hi) const;
  // Quantiles of the prior restricted to [lo, hi) (which must have mass > 0),
  // c = p * Mass(lo, hi), p in [0, 1]:
  //   lower: inf{x : P(lo <= theta <= x) >= c}  (the usual quantile),
  //   upper: sup{x <= hi : P(lo <= theta < x) <= c}  (the largest x with at most
  //   mass c below it; equal to lower where the density is positive).
  // Results are clamped to [lo, min(hi, 1)].
  double QuantileWithin(double lo, double hi, double p, bool upper) const;
  // A draw from the prior given a uniform u in [0, 1): the lower quantile at u.
  double Draw(double u01) const;

  // The double just above 1: [lo, kAboveOne) includes theta = 1.
  static const double kAboveOne;

 private:
  TrustPrior() = default;
  Kind kind_ = Kind::kBeta;
  double a_ = 1.0, b_ = 1.0;              // Beta
  std::vector<double> cells_;             // Histogram: normalised cell masses
  std::vector<double> cell_cumulative_;   // size K + 1
  std::vector<double> values_, weights_;  // Discrete: ascending values, normalised weights
  std::vector<double> atom_cumulative_;   // size n + 1
};

// What an observation did to a belief.
enum class ObservationEffect {
  kNarrowed,       // the posterior interval shrank
  kConsistent,     // informative in principle but already implied
  kUninformative,  // every trust (or none) responds this way to this reading
  kContradiction,  // impossible under the current posterior: ignored, counted
};
const char* ToString(ObservationEffect effect);

// The AV fleet's posterior over one HV's trust: the prior restricted to [L, U).
class TrustBelief {
 public:
  explicit TrustBelief(std::shared_ptr<const TrustPrior> prior);

  // The HV read `reading` (in [0, s_max]) and drove if clear or not.
  ObservationEffect Observe(const AvHvParams& params, const LikelihoodModel& model, double reading,
                            bool drove_if_clear);
  // The same with the DC set of the reading already computed.
  ObservationEffect Observe(const TrustInterval& dc_set, bool drove_if_clear);

  double Lower() const { return lower_; }  // L
  double Upper() const {
    return upper_ > 1.0 ? 1.0 : upper_;
  }                         // U (1 also when theta = 1 is possible)
  double Evidence() const;  // prior mass of [L, U)
  double Mean() const;
  double Quantile(double p) const;          // inf{x : P(theta <= x) >= p}
  double ProbabilityBelow(double x) const;  // P(theta < x)
  // The lower credible bound theta_L(delta) = sup{x : P(theta < x) <= delta}.
  double LowerBound(double delta) const;
  // Responses that split [0, 1] (kNarrowed or kConsistent): the learner's clock.
  int Observations() const { return observations_; }
  int Contradictions() const { return contradictions_; }
  const TrustPrior& Prior() const { return *prior_; }

 private:
  std::shared_ptr<const TrustPrior> prior_;
  double lower_ = 0.0;
  double upper_;  // exclusive
  int observations_ = 0;
  int contradictions_ = 0;
};

// Beliefs about every HV met, keyed by HV id and shared by all AVs, plus the
// population prior for HVs never met.
class FleetTrustBeliefs {
 public:
  explicit FleetTrustBeliefs(TrustPrior population);
  // The belief about `hv_id`, created from the population prior on first use.
  TrustBelief& For(const std::string& hv_id);
  const TrustBelief* Find(const std::string& hv_id) const;  // nullptr if never met
  const TrustPrior& Population() const { return *population_; }
  const std::map<std::string, TrustBelief>& All() const { return beliefs_; }

 private:
  std::shared_ptr<const TrustPrior> population_;
  std::map<std::string, TrustBelief> beliefs_;
};

// ------------------------------------------------------------------ safe design

// The per-encounter risk level after m observations of this HV:
//   eps_m = min(delta, decay / (m + 1)).
// delta bounds the probability that a nudge fails to persuade in any encounter;
// decay = +infinity keeps eps = delta (a failure rate of delta for ever, regret
// linear in T); a finite decay > 1/2 gives regret O(log T) (docs/beyond/derivations.md).
struct ExplorationSchedule {
  double delta = 0.01;  // in (0, 1)
  double decay = 1.0;   // > 0, may be +infinity
  // When even theta_L(eps) is below the model's theta*, probe: with probability
  // kappa = eps / P(theta < theta*) design for theta* (the strongest nudge),
  // else fall back, so the encounter's failure probability is still eps. Off:
  // such an HV is never nudged (and never learned).
  bool probe = true;
  double Level(int observations) const;
  bool IsValid(std::string* why) const;
  void Validate() const;  // throws InvalidArgument naming the field and value
};

struct LearnedDesign {
  enum class Mode {
    kDesign,    // TA-EBP for theta_L(eps) >= theta*
    kProbe,     // a probe was drawn: TA-EBP for theta*
    kFallback,  // always yield, no nudge (no safe design, or the probe was not drawn)
  };
  Mode mode = Mode::kFallback;
  double risk_level = 0.0;         // eps for this encounter
  double design_trust = 0.0;       // theta_L(eps) (kDesign), theta* (probes)
  double probe_probability = 0.0;  // kappa: 1 for kDesign, 0 when nothing is safe
  CommittedScheme scheme;          // the commitment for this encounter
  // Posterior P(the HV does not drive if clear after scheme.nudge) (0 without a nudge).
  double failure_probability = 0.0;
  // Before the probe draw: probe_probability * P(fail | that design) <= eps.
  double encounter_risk = 0.0;
};
const char* ToString(LearnedDesign::Mode mode);

// The design for the next encounter with an HV of belief `belief`. `u01` is a
// uniform draw in [0, 1) that decides a probe (always pass one so the random
// streams do not depend on the mode). Needs lambda < p* (with lambda >= p* the
// HV drives if clear without persuasion).
LearnedDesign ChooseLearnedDesign(const TrustBelief& belief, const AvHvParams& params,
                                  const LikelihoodModel& model, const ExplorationSchedule& schedule,
                                  double u01);

// ------------------------------------------------------------------ regret

// One encounter's expected regret against the oracle, the TA-EBP design for the
// HV's true trust (CommitScheme(kTaEbp, theta_true)):
//   dc_lost = DC rate(oracle) - DC rate(used), collisions = collision rate(used)
//   - collision rate(oracle) (= 0), regret = dc_lost + r * collisions.
struct EncounterRegret {
  double dc_lost = 0.0;
  double collisions = 0.0;
  double regret = 0.0;
};
EncounterRegret ExpectedRegret(const CommittedScheme& used, const AvHvParams& params,
                               double theta_true, const LikelihoodModel& model);
// The same with the oracle's outcome already predicted (PredictOutcome(kTaEbp,
// theta_true)), constant per HV while its trust is.
EncounterRegret ExpectedRegret(const CommittedScheme& used, const PredictedOutcome& oracle,
                               const AvHvParams& params, double theta_true,
                               const LikelihoodModel& model);

struct RegretTally {
  long encounters = 0;
  double dc_lost = 0.0;
  double collisions = 0.0;
  double regret = 0.0;
  void Add(const EncounterRegret& r) {
    ++encounters;
    dc_lost += r.dc_lost;
    collisions += r.collisions;
    regret += r.regret;
  }
};

}  // namespace taebp::persuasion
