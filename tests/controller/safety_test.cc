// Issue 30, in SUMO: a game never overrides SUMO's right of way against a
// vehicle outside it, and whether a meeting is a game does not depend on the
// policy being run (docs/encounter-rules.md).
// - The shipped two-way-stop grid (configs/grid_two_way.yaml, 1800 s, seeds
//   1-3): where sumo_native has no collision, no move of the game hits a third
//   vehicle under any policy (other_collisions_game_move 0), and the
//   encounters' collision and DC rates hold their theory inside 99.9 %
//   intervals.
// - A grid where the nudge reaches the HV's path (s_max 6 m): the first game
//   is the same pair at the same time under No EBP, No Trust and TA-EBP, and
//   some meetings are left to SUMO for it (the rule could fail).
#include "taebp/config/config.h"
#include "taebp/controller/policy_run.h"
#include "taebp/report/report.h"
#include "taebp/scenario/scenario.h"

#include "clustered_support.h"
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace taebp {
namespace {

const std::string kSource = TAEBP_SOURCE_DIR;


// The reckless HV waits for the major road's gap; a vehicle halted inside
// the junction is traffic unless a nudged AV holds it; the moves of the game
// wait a step for the vehicles let past that AV (Unblockable), which then
// move (docs/encounter-rules.md §1).
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Safety, GridTwoWayNoGameMoveHitsAThirdVehicleWhereSumoNativeHasNoCollision) {
  struct Pooled {
    long encounters = 0, collisions = 0, dc = 0;
    double theory_collisions = 0, theory_dc = 0;
    std::vector<std::vector<EncounterRecord>> runs;  // each seed's
  };
  std::map<std::string, Pooled> pooled;
  for (const char* seed : {"scenario.seed=1", "scenario.seed=2", "scenario.seed=3"}) {
    SCOPED_TRACE(seed);
    const ExperimentConfig cfg = LoadExperimentConfig(kSource + "/configs/grid_two_way.yaml",
                                                      {"scenario.duration=1800", seed});
    const Scenario sc = BuildScenario(cfg, "");
    const PolicyRun native = RunPolicy(cfg, "sumo_native", sc);
    if (native.other_collisions > 0) {
      std::cout << seed << ": sumo_native collided " << native.other_collisions
                << " times, not checked\n";
      continue;
    }
    for (const char* policy : {"no_ebp", "no_trust", "ta_ebp"}) {
      SCOPED_TRACE(policy);
      const PolicyRun r = RunPolicy(cfg, policy, sc);
      EXPECT_EQ(r.other_collisions_game_move, 0) << "a move of the game hit a third vehicle";
      Pooled& p = pooled[policy];
      p.runs.push_back(r.encounters);
      for (const EncounterRecord& e : r.encounters) {
        ++p.encounters;
        p.collisions += e.collision;
        p.dc += e.hv_dc;
        p.theory_collisions += e.theory_collision;
        p.theory_dc += e.theory_dc;
        // The game's premise, decided by SUMO's collision check.
        EXPECT_EQ(e.collision, e.av_first && !e.hv_dc) << e.av << "/" << e.hv << " at " << e.time;
      }
      std::cout << seed << " " << policy << ": " << r.encounters.size() << " encounters, "
                << r.other_collisions << " other collisions, " << r.other_collisions_game_move
                << " of a game move\n";
    }
  }
  ASSERT_EQ(pooled.size(), 3u) << "sumo_native collided in every seed: nothing checked";
  for (const auto& [policy, p] : pooled) {
    SCOPED_TRACE(policy);
    ASSERT_GT(p.encounters, 100);
    // Theory per encounter (the mean of each encounter's own prediction)
    // inside the 99.9 % interval of the seeds' pooled rates, clustered by HV
    // and by run (report/clustered.h).
    const double th_c = p.theory_collisions / p.encounters, th_dc = p.theory_dc / p.encounters;
    const RateInterval ci_c =
        test::PooledEncounterRate(p.runs, [](const EncounterRecord& e) { return e.collision; }, kZ999);
    const RateInterval ci_dc =
        test::PooledEncounterRate(p.runs, [](const EncounterRecord& e) { return e.hv_dc; }, kZ999);
    EXPECT_TRUE(test::Holds(ci_c, th_c)) << p.collisions << " / " << p.encounters << " vs " << th_c;
    EXPECT_TRUE(test::Holds(ci_dc, th_dc)) << p.dc << " / " << p.encounters << " vs " << th_dc;
  }
}

// A vehicle let past the nudged AV (Unblockable) is traffic for the moves of
// the game until it has passed, though it stands yet: the two-way study's
// point where TA-EBP's careful HV (d270, released at t = 341.9 s) met the
// left turn let past the AV a step before (d247 at D1, which stood 0.8 s
// more and then went). Seed 2 of flow 200, AV share 0.25, 1200 s: about 5 s.
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Safety, AVehicleLetPastTheNudgedAvIsTrafficUntilItHasPassed) {
  const ExperimentConfig cfg = LoadExperimentConfig(
      kSource + "/configs/grid_two_way.yaml",
      {"scenario.seed=2", "scenario.demand.flow=200", "scenario.av_share=0.25"});
  const Scenario sc = BuildScenario(cfg, "");
  const PolicyRun r = RunPolicy(cfg, "ta_ebp", sc);
  std::cout << r.encounters.size() << " encounters, " << r.unblocked << " let past a nudged AV, "
            << r.other_collisions << " other collisions, " << r.other_collisions_game_move
            << " of a game move\n";
  ASSERT_GT(r.unblocked, 0) << "nobody was let past a nudged AV: the test checks nothing";
  EXPECT_EQ(r.other_collisions_game_move, 0) << "a move of the game hit a vehicle let past the AV";
}

// A 3x3 all-way grid with a nudge long enough (s_max 6 m) to reach the
// HV's path from many stop lines: before the rule was policy-independent,
// No EBP (no nudge) formed games No Trust and TA-EBP refused.
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Safety, TheFirstGameIsTheSamePairAtTheSameTimeUnderEveryPolicy) {
  const std::string yaml =
      "scenario:\n"
      "  kind: network\n"
      "  grid: {columns: 3, rows: 3, length: 100, attach_length: 50}\n"
      "  demand: {flow: 400}\n"
      "  av_share: 0.5\n"
      "  cruise_speed: 10\n"
      "  duration: 400\n"
      "  seed: 5\n"
      "model:\n"
      "  prior_go: 0.2\n"
      "  collision_penalty: 3.0\n"
      "  trust: 0.6\n"
      "  likelihood: {type: linear, s_max: 6.0}\n"
      "policies: [no_ebp, no_trust, ta_ebp]\n";
  const ExperimentConfig cfg = ParseExperimentConfig(yaml, "safety_test");
  const Scenario sc = BuildScenario(cfg, "");
  struct First {
    double time = -1;
    std::string junction, av, hv;
  };
  std::vector<First> firsts;
  long in_way = 0;
  for (const char* policy : {"no_ebp", "no_trust", "ta_ebp"}) {
    SCOPED_TRACE(policy);
    const PolicyRun r = RunPolicy(cfg, policy, sc);
    ASSERT_FALSE(r.encounters.empty());
    const auto first = std::min_element(
        r.encounters.begin(), r.encounters.end(),
        [](const EncounterRecord& a, const EncounterRecord& b) { return a.time < b.time; });
    firsts.push_back({first->time, first->junction, first->av, first->hv});
    long unpredictable = 0;
    for (const JunctionRun& j : r.junctions) unpredictable += j.meetings_unpredictable;
    in_way += unpredictable;
    std::cout << policy << ": first game at " << first->time << " s, " << first->junction << " "
              << first->av << "/" << first->hv << "; " << r.encounters.size() << " encounters, "
              << unpredictable << " meetings unpredictable\n";
  }
  EXPECT_GT(in_way, 0) << "no nudge reached an HV's path: the test shows nothing";
  for (std::size_t i = 1; i < firsts.size(); ++i) {
    EXPECT_DOUBLE_EQ(firsts[i].time, firsts[0].time) << "policy " << i;
    EXPECT_EQ(firsts[i].junction, firsts[0].junction);
    EXPECT_EQ(firsts[i].av, firsts[0].av);
    EXPECT_EQ(firsts[i].hv, firsts[0].hv);
  }
}

}  // namespace
}  // namespace taebp
