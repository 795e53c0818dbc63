// One HV population playing both kinds of game (GameKind): the stop lines'
// (the paper's) and the major road's (the paper's game at r_eff, issue 43),
// driven with made-up encounters (no SUMO). Each kind's scheme, reading and
// theory must be the persuasion library's own functions for that game
// (persuasion/major_road.h), for every game policy; and what an HV carries
// from one kind to the other (its trust state, the fleet's belief about it,
// its experience) must be one state, not one per kind.
#include "taebp/encounter/hv_population.h"

#include "taebp/config/config.h"
#include "taebp/config/model.h"
#include "taebp/config/policies.h"
#include "taebp/encounter/design.h"
#include "taebp/encounter/encounter.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/major_road.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/trust_learning.h"
#include "taebp/report/results.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

namespace taebp {
namespace {

namespace per = persuasion;
using per::Policy;

// A network scenario (the major-road game needs one) with yield cost c = 0.5:
// r_eff = 2 (3 - 0.5) / 2.5 = 2, p* = 0.5 (docs/beyond/major-road.md).
ExperimentConfig Config(const std::string& model, const std::string& policy) {
  return ParseExperimentConfig(
      "scenario: {kind: network, grid: {columns: 2, rows: 2}, demand: {flow: 100}, "
      "major_road: {yield_cost: 0.5}}\n"
      "model: {prior_go: 0.2, collision_penalty: 3.0, " + model + "}\npolicies: [" + policy + "]\n",
      "test.yaml");
}

per::MajorRoadParams Major() {
  per::MajorRoadParams m;
  m.prior_go = 0.2;
  m.collision_penalty = 3.0;
  m.yield_cost = 0.5;
  return m;
}
const per::AvHvParams kPaper{0.2, 3.0};

void ExpectSameScheme(const per::CommittedScheme& a, const per::CommittedScheme& b) {
  EXPECT_EQ(a.av_may_go, b.av_may_go);
  EXPECT_EQ(a.nudge, b.nudge);
  EXPECT_EQ(a.a, b.a);
  EXPECT_EQ(a.b, b.b);
  EXPECT_EQ(a.random_magnitude, b.random_magnitude);
}

// One finished encounter of `kind` with the given draw; SUMO realised the
// commanded nudge exactly.
EncounterRecord Finish(HvPopulation& pop, const std::string& hv, GameKind kind, bool nudge,
                       bool go, HvReading* reading = nullptr) {
  const per::CommittedScheme scheme = pop.Commit("a", hv, kind);
  AvDraw d;
  d.nudge = nudge;
  d.nudge_distance = nudge ? scheme.nudge : 0.0;
  d.intent_go = d.goes_first = go;
  const HvReading r = pop.Read("a", hv, d.nudge_distance);
  if (reading) *reading = r;
  EncounterRecord rec;
  pop.Finish("a", hv, d, r, go && !r.drives_if_clear, true, &rec);
  return rec;
}

// Every game policy of static trust: the major road's scheme, the HV's reading
// and the record's theory are CommitMajorRoadScheme, MajorRoadHvYields and
// PredictMajorRoadOutcome at the policy's design trust; the stop lines' stay
// the paper's.
TEST(HvPopulationMajorRoad, EachKindIsItsOwnGameUnderEveryPolicy) {
  const per::LinearLikelihood model(2.0);
  int checked = 0;
  for (const Policy policy : GamePolicies()) {
    if (policy == Policy::kTaEbpLearned) continue;  // LearnerObservesEachKindWithItsOwnThreshold
    SCOPED_TRACE(PolicyName(policy));
    const ExperimentConfig c = Config("trust: 0.6", PolicyName(policy));
    HvPopulation pop(c, policy);
    ASSERT_TRUE(pop.MajorRoad());
    pop.Add("h", 0.6);
    const double theta_hat = DesignTrust(c.model, policy, 0.6);
    ExpectSameScheme(pop.Commit("a", "h", GameKind::kMajorRoad),
                     per::CommitMajorRoadScheme(policy, Major(), theta_hat, model));
    ExpectSameScheme(pop.Commit("a2", "h", GameKind::kStopLines),
                     per::CommitScheme(policy, kPaper, theta_hat, model));
    HvReading read;
    const EncounterRecord rec = Finish(pop, "h", GameKind::kMajorRoad, true, true, &read);
    EXPECT_EQ(read.drives_if_clear, per::MajorRoadHvYields(Major(), read.posterior));
    const per::PredictedOutcome th = per::PredictMajorRoadOutcome(
        policy, Major(), 0.6, model, policy == Policy::kNoTrust ? std::optional<double>() : theta_hat);
    EXPECT_DOUBLE_EQ(rec.theory_dc, th.dc_rate);
    EXPECT_DOUBLE_EQ(rec.theory_collision, th.collision_rate);
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

// A Beta trust state updated by a stop-line game is the one the next
// major-road game starts from, and the other way round; the design follows it.
TEST(HvPopulationMajorRoad, TrustCarriesOverBetweenKinds) {
  const per::LinearLikelihood model(2.0);
  HvPopulation pop(Config("trust: 0.6, trust_dynamics: {strength: 10, success_weight: 1, "
                          "failure_weight: 2}",
                          "ta_ebp"),
                   Policy::kTaEbp);
  pop.Add("h", 0.6);
  double alpha = 6, beta = 4;
  // still_go (q = 0: beta += 2) in a stop-line game, then nudge_go (q = 1) in a
  // major-road game, then still_go again in a major-road game.
  struct Step {
    GameKind kind;
    bool nudge, go;
    double q;
  };
  for (const Step& k : {Step{GameKind::kStopLines, false, true, 0},
                        Step{GameKind::kMajorRoad, true, true, 1},
                        Step{GameKind::kMajorRoad, false, true, 0},
                        Step{GameKind::kStopLines, true, false, 0}}) {
    const double before = alpha / (alpha + beta);
    EXPECT_DOUBLE_EQ(pop.Trust("h"), before);
    const per::CommittedScheme expected =
        k.kind == GameKind::kMajorRoad ? per::CommitMajorRoadScheme(Policy::kTaEbp, Major(), before, model)
                                       : per::CommitScheme(Policy::kTaEbp, kPaper, before, model);
    ExpectSameScheme(pop.Commit("b", "h", k.kind), expected);
    const EncounterRecord r = Finish(pop, "h", k.kind, k.nudge, k.go);
    alpha += 1.0 * k.q;
    beta += 2.0 * (1 - k.q);
    EXPECT_DOUBLE_EQ(r.hv_trust, before);
    EXPECT_DOUBLE_EQ(r.beyond.trust_after, alpha / (alpha + beta));
    EXPECT_EQ(r.beyond.quality, k.q);
  }
}

// ta_ebp_learned: the fleet's one belief about an HV learns from each kind
// with that kind's threshold (the major road's p* = 0.5, not the paper's 0.4).
TEST(HvPopulationMajorRoad, LearnerObservesEachKindWithItsOwnThreshold) {
  const per::LinearLikelihood model(2.0);
  const ExperimentConfig c = Config("trust: {dist: uniform, low: 0.45, high: 1.0}", "ta_ebp_learned");
  HvPopulation pop(c, Policy::kTaEbpLearned);
  pop.Add("h", 0.7);
  // The same observations on a belief of our own, each with its game's params.
  per::TrustBelief mine(std::make_shared<per::TrustPrior>(ToModel(c.model.trust)));
  std::mt19937_64 rng(3);
  int major = 0, stop = 0;
  for (int k = 0; k < 40; ++k) {
    const GameKind kind = k % 3 == 0 ? GameKind::kStopLines : GameKind::kMajorRoad;
    const per::CommittedScheme scheme = pop.Commit("a", "h", kind);
    const AvDraw d = DrawAv(scheme, 0.2, rng);
    const HvReading r = pop.Read("a", "h", d.nudge_distance);
    EncounterRecord rec;
    pop.Finish("a", "h", d, r, d.goes_first && !r.drives_if_clear, true, &rec);
    EXPECT_DOUBLE_EQ(rec.beyond.belief_lower, mine.Lower()) << "encounter " << k;
    if (scheme.Signals()) {
      mine.Observe(kind == GameKind::kMajorRoad ? Major().EquivalentPaperParams() : kPaper, model,
                   d.nudge_distance, r.drives_if_clear);
      ++(kind == GameKind::kMajorRoad ? major : stop);
    }
  }
  EXPECT_GT(major, 5);
  EXPECT_GT(stop, 2);
  EXPECT_GT(mine.Observations(), 0);
}

// The run's theory: each kind's a-priori theory weighted by its counted
// encounters (ExpectedOutcome of the paper's game at each kind's penalty).
TEST(HvPopulationMajorRoad, RunTheoryWeightsEachKindByItsEncounters) {
  const ExperimentConfig c = Config("trust: 0.6", "ta_ebp");
  HvPopulation pop(c, Policy::kTaEbp);
  const per::PredictedOutcome stop = ExpectedOutcome(c.model, Policy::kTaEbp);
  ModelConfig at_r_eff = c.model;
  at_r_eff.collision_penalty = per::MajorRoadEffectivePenalty(Major());
  const per::PredictedOutcome major = ExpectedOutcome(at_r_eff, Policy::kTaEbp);
  ASSERT_NE(stop.dc_rate, major.dc_rate) << "the two kinds must differ for this test to mean anything";
  EXPECT_DOUBLE_EQ(pop.Theory().dc_rate, stop.dc_rate) << "before any encounter: the stop lines'";
  pop.Add("h", 0.6);
  for (int k = 0; k < 3; ++k) Finish(pop, "h", GameKind::kMajorRoad, true, true);
  EXPECT_DOUBLE_EQ(pop.Theory().dc_rate, major.dc_rate);
  Finish(pop, "h", GameKind::kStopLines, true, true);
  EXPECT_DOUBLE_EQ(pop.Theory().dc_rate, 0.25 * stop.dc_rate + 0.75 * major.dc_rate);
  EXPECT_DOUBLE_EQ(pop.Theory().collision_rate,
                   0.25 * stop.collision_rate + 0.75 * major.collision_rate);
}

// model.experience: an HV's experience is one (what the AVs did after each
// level it read, whichever kind); its path theory holds while it has met one
// kind only, and is left empty once it has met both (its path mixes schemes).
TEST(HvPopulationMajorRoad, ExperienceTheoryOnlyWhileOneKindWasMet) {
  HvPopulation pop(Config("trust: 0.6, experience: {strength: 4}", "ta_ebp"), Policy::kTaEbp);
  pop.Add("h", 0.6);
  const EncounterRecord first = Finish(pop, "h", GameKind::kMajorRoad, true, true);
  EXPECT_FALSE(std::isnan(first.theory_dc));
  const EncounterRecord second = Finish(pop, "h", GameKind::kMajorRoad, true, true);
  EXPECT_FALSE(std::isnan(second.theory_dc));
  const EncounterRecord third = Finish(pop, "h", GameKind::kStopLines, true, true);
  EXPECT_TRUE(std::isnan(third.theory_dc)) << "an HV that met both kinds has no path theory";
  EXPECT_EQ(third.beyond.trust_after, third.hv_trust);
}

// Without scenario.major_road (or on the figure-8) a major-road game is a bug.
TEST(HvPopulationMajorRoad, NoMajorRoadGameWhenTheSectionIsOff) {
  ExperimentConfig c = Config("trust: 0.6", "ta_ebp");
  c.scenario.major_road.enabled = false;
  HvPopulation pop(c, Policy::kTaEbp);
  EXPECT_FALSE(pop.MajorRoad());
  pop.Add("h", 0.6);
  EXPECT_THROW(pop.Commit("a", "h", GameKind::kMajorRoad), std::logic_error);
}

}  // namespace
}  // namespace taebp
