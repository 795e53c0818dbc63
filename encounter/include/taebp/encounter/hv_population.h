// The HV population as the AVs meet it, beyond the paper's setting: each HV's
// trust (static, or a Beta state updated by its encounters), the AV fleet's
// beliefs about each HV (ta_ebp_learned), the HV's noisy reading of the nudge,
// and per encounter the design, the exact theory, the oracle and the regret.
// SUMO-free: the network controller calls it from its hooks (a vehicle
// registers, an AV draws, an HV reads, an encounter is recorded, once a
// simulated second), and tests drive it with made-up encounters.
//
// With the paper's setting (static trust known to the AV, no noise, a paper
// policy) it computes exactly what the controller computed before: the same
// scheme per HV, the same reading (ReadNudge), the same theory, and it draws
// no random number; the encounter stream (DrawAv) stays the controller's.
//
// The two kinds of game (GameKind): one population plays both, each with its
// own payoffs (the major-road game at r_eff when scenario.major_road is on),
// so an HV's trust state, its experience and the fleet's belief about it carry
// over from one kind to the other (docs/beyond/major-road.md, "One HV, two
// games"): trust and experience are about what the AVs' nudges mean, the same
// in both; each reading and each design uses its own game's p*.
//
// Randomness: three streams of its own, seeded from scenario.seed and a salt
// per purpose: the noise of the HVs' readings (one uniform per reading, when
// model.noise is set), the probes of ta_ebp_learned (one uniform per
// encounter of that policy) and random_nudge's magnitudes (one uniform per
// nudge of that policy: Magnitude). No other policy draws from the last two,
// so their common random numbers are those of a run without them. Same
// config and seed, same draws.
#pragma once

#include "taebp/config/config.h"
#include "taebp/encounter/encounter.h"
#include "taebp/persuasion/experience.h"
#include "taebp/persuasion/noise.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/trust_dynamics.h"
#include "taebp/persuasion/trust_learning.h"
#include "taebp/report/results.h"

#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace taebp {

class HvPopulation {
 public:
  // `policy`: the run's persuasion policy. Throws ConfigError for settings
  // the models cannot take (e.g. ta_ebp_learned with lambda >= p*).
  HvPopulation(const ExperimentConfig& config, persuasion::Policy policy);
  ~HvPopulation();
  HvPopulation(const HvPopulation&) = delete;
  HvPopulation& operator=(const HvPopulation&) = delete;

  // What the AV commits to for an HV of the population's mean trust (an HV
  // never met, for ta_ebp_learned), and the theory over the trust
  // distribution (exact over the noise) where one exists a priori.
  const persuasion::CommittedScheme& PopulationScheme(GameKind kind = GameKind::kStopLines) const {
    return kinds_[Index(kind)].population_scheme;
  }
  // The a-priori theory of the run's encounters: each kind's, weighted by how
  // many counted encounters it had (the stop lines' before any).
  persuasion::PredictedOutcome Theory() const;
  // True when the run plays the major-road game (scenario.major_road on a network).
  bool MajorRoad() const { return major_; }
  // True when the outputs gain the columns and sections of BeyondRun.
  bool Beyond() const { return beyond_; }

  // An HV entered the network with its drawn trust.
  void Add(const std::string& hv, double trust);
  // It left (its trust state goes; the fleet's belief about it stays).
  void Remove(const std::string& hv);
  bool Has(const std::string& hv) const { return hvs_.count(hv) > 0; }
  // The trust the HV uses now (its Beta mean under dynamics).
  double Trust(const std::string& hv) const;
  // model.experience: the HV's prior strength k (one of strengths, by a hash
  // of its id and scenario.seed; `strength` when they are not given).
  double Strength(const std::string& hv) const;

  // The AV `av` meets `hv` in a game of `kind`: the scheme it commits to for
  // this encounter (draw the intent and signal from it).
  const persuasion::CommittedScheme& Commit(const std::string& av, const std::string& hv,
                                            GameKind kind = GameKind::kStopLines);
  // The magnitude of the nudge the AV drew under `scheme` (Commit's): for a
  // random magnitude (random_nudge) one draw of the magnitude stream, else
  // scheme.nudge without a draw.
  double Magnitude(const persuasion::CommittedScheme& scheme);
  // Where the AV stands when it goes, relative to its stop line, under the
  // scheme it would commit to for `hv` now: the Go signal's nudge (s*) when
  // the scheme nudges on Go, else 0. No side effects (Commit's probe draw is
  // not made: ta_ebp_learned answers for the population's scheme).
  double GoSignal(const std::string& hv, GameKind kind = GameKind::kStopLines) const;
  // The HV reads the displacement SUMO reported (plus noise) under the
  // committed scheme with its current trust.
  HvReading Read(const std::string& av, const std::string& hv, double observed);
  // The encounter finished: fills the record's hv_trust (before), theory and
  // `beyond` fields, then updates the HV's trust and the fleet's belief.
  // Regret charges the collision penalty r in both kinds (a collision costs
  // the same wherever it happens; r_eff only prices the HV's choice).
  // `counted`: after the warm-up (totals and time series count it); the
  // updates happen either way.
  void Finish(const std::string& av, const std::string& hv, const AvDraw& draw,
              const HvReading& reading, bool collision, bool counted, EncounterRecord* record);

  // Once a simulated second (cheap when no sample is due): a time-series row
  // every outputs.interval seconds from the warm-up on, written to the spool
  // (SampleInto; without one, to unnamed temporary files with no policy).
  void Sample(double now);
  // The rows go to `spool` (a run's: its policy, the scenario's scratch folder).
  void SampleInto(std::shared_ptr<SampleSpool> spool) { spool_ = std::move(spool); }
  // The totals; `end`: the simulated time at the end.
  BeyondRun Results(double end);
  // Mean of the per-encounter predictions so far (the theory of runs whose
  // a-priori expectation does not exist: dynamic or learned trust).
  persuasion::PredictedOutcome EncounterTheory() const;

 private:
  // The parts of Results, each for its model (hv_population_results.cc).
  void ExperienceLongRun(BeyondRun* out) const;
  void DynamicsLongRun(BeyondRun* out) const;
  void LearningResults(BeyondRun* out) const;
  void NoiseResults(BeyondRun* out) const;
  static int Index(GameKind kind) { return static_cast<int>(kind); }
  // What the AVs commit to for an HV of static trust in one kind of game.
  struct KindDesign {
    persuasion::CommittedScheme scheme;
    double design_trust = 0;
    persuasion::PredictedOutcome theory, oracle;
  };
  struct Hv {
    double trust0 = 0;
    std::optional<persuasion::BetaTrust> state;       // trust dynamics
    std::optional<persuasion::BetaTrust> mean_field;  // its mean-field twin
    long encounters = 0;
    // Static trust, not learned: the design and predictions, fixed per HV
    // and kind of game.
    bool cached = false;
    KindDesign design[kGameKinds];
    int kinds_met = 0;  // bit per GameKind of the games it finished
    // model.experience: what this HV learned per signal level.
    std::optional<persuasion::SignalExperience> experience;
    double strength = 0;  // its prior strength k (model.experience.strengths)
    // The guarded design's view of it when the HV forgets: the public history
    // of the AVs' signals and actions, counted exactly (the AV is not told
    // the HV's forgetting; with rho = 1 it is `experience` itself).
    std::optional<persuasion::SignalExperience> history;
  };
  struct Pending {
    GameKind kind = GameKind::kStopLines;
    persuasion::CommittedScheme scheme;
    double trust = 0;
    double design_trust = kNoValue;
    persuasion::PredictedOutcome theory, oracle;
    double reading = 0;
    std::optional<persuasion::LearnedDesign> learned;
    double belief_lower = kNoValue, belief_upper = kNoValue;
  };
  struct Totals {
    long encounters = 0, dc = 0, collisions = 0, nudges = 0, failures = 0;
    long of_kind[kGameKinds] = {0, 0};
    double theory_dc = 0, theory_collisions = 0, oracle_dc = 0, oracle_collisions = 0;
    double regret = 0, expected_failures = 0;
  };

  double DesignTrustFor(double theta) const;
  const persuasion::AvHvParams& Params(GameKind kind) const { return kinds_[Index(kind)].params; }
  persuasion::CommittedScheme SchemeAt(double theta_hat, GameKind kind = GameKind::kStopLines) const;
  persuasion::CommittedScheme OracleScheme(double theta, GameKind kind = GameKind::kStopLines) const;
  persuasion::PredictedOutcome Predict(const persuasion::CommittedScheme& scheme, double theta,
                                       GameKind kind = GameKind::kStopLines) const;
  KindDesign DesignFor(double trust, GameKind kind) const;  // static trust's (Hv::design)
  // The population's scheme and a-priori theory for one kind (constructor).
  void SetUpKind(GameKind kind);
  // model.experience: the expected learning path of an HV of trust theta and
  // prior strength k whose AVs design for theta_hat in games of `kind` (one
  // per quadruple).
  persuasion::ExperiencePath& PathFor(double theta_hat, double theta, double strength,
                                      GameKind kind);
  // Both kinds played: the long-run results of a single game do not apply.
  bool MixedKinds() const { return totals_.of_kind[0] > 0 && totals_.of_kind[1] > 0; }
  // The one kind played (the stop lines' when none or both were).
  GameKind PlayedKind() const {
    return totals_.of_kind[0] == 0 && totals_.of_kind[1] > 0 ? GameKind::kMajorRoad
                                                             : GameKind::kStopLines;
  }
  bool encounter_theory_ = false;  // Results: the theory is the encounters' mean
  // model.experience: the prior strength k of HV `hv` (strengths' draw).
  double StrengthOf(const std::string& hv) const;
  // model.experience without a theory: the guarded design against HVs that
  // forget (its path would need the HV's weighted memory beside the exact
  // counts the guard reads), and HVs who read with model.noise (the level a
  // reading is filed under is random).
  bool NoTheory() const;
  static persuasion::PredictedOutcome Unmodelled();  // every rate kNoValue

  const ExperimentConfig config_;  // a copy: callers may pass a temporary
  persuasion::Policy policy_;
  persuasion::AvHvParams params_;  // the stop lines' game (the paper's)
  struct Kind {
    persuasion::AvHvParams params;  // the major road's: the paper's game at r_eff
    persuasion::CommittedScheme population_scheme;
    persuasion::PredictedOutcome theory;
  };
  Kind kinds_[kGameKinds];
  bool major_ = false;
  std::unique_ptr<persuasion::LikelihoodModel> model_;
  bool beyond_ = false;
  bool dynamic_ = false, learned_ = false;
  std::optional<persuasion::ExperienceRule> experience_;  // model.experience set
  bool guarded_ = false;  // ta_ebp designs for each HV's experience
  // ta_ebp commits to DesignRobust (model.experience.design: robust): margin.
  std::optional<double> robust_margin_;
  std::map<std::tuple<double, double, double, int>, std::unique_ptr<persuasion::ExperiencePath>>
      paths_;
  std::optional<persuasion::PerceptionNoise> noise_;  // model.noise set
  bool noise_aware_ = false;
  double noise_delta_ = 0.01;
  persuasion::TrustUpdateRule rule_;
  std::optional<persuasion::DesignRule> design_rule_;  // the mean-field's, when one applies
  std::unique_ptr<persuasion::FleetTrustBeliefs> fleet_;
  persuasion::ExplorationSchedule schedule_;
  std::mt19937_64 noise_rng_, probe_rng_, magnitude_rng_;

  std::map<std::string, Hv> hvs_;                 // the HVs in the network, by id
  std::map<std::string, double> met_trust_;       // ta_ebp_learned: each HV met's drawn trust
  std::map<std::pair<std::string, std::string>, Pending> pending_;
  Totals totals_;
  long hvs_added_ = 0, probes_ = 0;
  double trust_sum_ = 0;  // of the drawn trust of every HV added
  double next_sample_ = 0;
  double last_sample_ = -1;
  // timeseries.csv's and hv_trust.csv's rows, streamed to disk as sampled.
  std::shared_ptr<SampleSpool> spool_;
};

}  // namespace taebp
