// The game's premise on SUMO's own geometry: SUMO collides exactly where both
// proceeding is predicted to collide, for the car and for vehicles that are not
// the car (trucks, buses, motorcycles); every encounter on the grid is the game.
#include "taebp/config/config.h"
#include "taebp/controller/policy_run.h"
#include "taebp/report/report.h"
#include "taebp/scenario/demand.h"
#include "taebp/scenario/net_file.h"
#include "taebp/scenario/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../scenario/net_support.h"
#include "grid_support.h"
#include "stall_support.h"
#include "test_support.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace taebp {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

using test::GridConfig;
// ------------------------------------------------------------------ the game's premise

// SUMO against the predictor: with scenario.encounter_pairs = all every
// conflicting AV-HV meeting is an encounter, and with trust 0 every HV drives
// recklessly, so each encounter where the AV went is "both proceed". SUMO's
// junction collision check must collide on exactly those the geometry
// predicts (both_proceed_collides; uncertain merges aside), and both verdicts must occur (merges the
// AV leads, opposite left turns). Faking either side (a predictor that always
// says yes, a collision read from the actions instead of SUMO) turns this red.
TEST(NetworkGame, SumoCollidesExactlyWhereBothProceedingIsPredictedToCollide) {
  const ExperimentConfig cfg = GridConfig(
      {"scenario.demand.flow=250", "scenario.duration=1500", "scenario.encounter_pairs=all",
       "model.trust=0.0", "policies=[no_trust]", "scenario.stall_action=record"});
  const Scenario sc = BuildScenario(cfg, "");
  const PolicyRun r = RunPolicy(cfg, "no_trust", sc);
  long both = 0, predicted = 0, collided = 0, uncertain = 0;
  std::map<std::string, long> missed;  // pairs SUMO did not collide, by directions
  for (const EncounterRecord& e : r.encounters) {
    EXPECT_FALSE(e.hv_dc) << "trust 0: the HV always drives recklessly";
    if (!e.av_first) {
      EXPECT_FALSE(e.collision) << e.av << "/" << e.hv << " at " << e.time;
      continue;
    }
    if (e.premise == Premise::kUncertainMerge) {  // excluded from the game (README)
      ++uncertain;
      continue;
    }
    ++both;
    predicted += e.both_proceed_collides;
    collided += e.collision;
    EXPECT_EQ(e.collision, e.both_proceed_collides)
        << e.junction << " " << e.av_movement << " (AV) / " << e.hv_movement << " at " << e.time;
    if (!e.collision) ++missed[std::string(1, e.av_dir) + "/" + e.hv_dir];
  }
  EXPECT_GT(both, 60);
  EXPECT_GT(collided, both / 2);
  EXPECT_GT(both - collided, 5) << "no pair where both proceeding does not collide";
  long not_game = 0;
  for (const JunctionRun& j : r.junctions) not_game += j.meetings_not_game;
  EXPECT_EQ(not_game, 0) << "encounter_pairs: all forms every meeting";
  std::cout << "both proceed " << both << " (and " << uncertain << " uncertain merges)"
            << ", predicted to collide " << predicted
            << ", SUMO collided " << collided << "; not colliding:";
  for (const auto& [d, k] : missed) std::cout << " " << d << " " << k;
  std::cout << "\n";
}

// Merges (both movements ending on the same exit lane) against SUMO: with
// every conflicting meeting an encounter and every HV reckless, on an
// all-way-stop grid and on a two-way-stop grid (the AV turning from the
// minor road onto the major road ahead of or behind major HVs), every merge
// where both proceeded and the prediction is certain (PredictBothProceed:
// the follower braking for the leader once the leader's front is on the
// shared exit lane) collided in SUMO exactly where predicted, and merges of
// both verdicts occur. A merge predicted to collide whatever the braking
// (tests/mutations/controller.txt, merges-always-collide) turns this red.
TEST(NetworkGame, MergesCollideInSumoExactlyWhereTheFollowersBrakingSays) {
  const auto exit_of = [](const std::string& m) { return m.substr(m.find('>')); };
  std::map<std::string, long> n;
  for (const std::string junction_type : {"allway_stop", "priority_stop"}) {
    SCOPED_TRACE(junction_type);
    const ExperimentConfig cfg = GridConfig(
        {"scenario.grid={columns: 4, rows: 4, length: 100, attach_length: 100, junction_type: " +
             junction_type + "}",
         "scenario.demand.flow=200", "scenario.cruise_speed=13.89", "scenario.duration=1200",
         "scenario.encounter_pairs=all", "model.trust=0.0", "policies=[no_trust]",
         "scenario.stall_action=record"});
    const PolicyRun r = RunPolicy(cfg, "no_trust", BuildScenario(cfg, ""));
    for (const EncounterRecord& e : r.encounters) {
      if (exit_of(e.av_movement) != exit_of(e.hv_movement) || !e.av_first || e.hv_dc) continue;
      const std::string kind = e.major_road ? "major " : "stop ";
      ++n[kind + ToString(e.premise) + (e.collision ? " collided" : " passed")];
      if (e.premise == Premise::kUncertainMerge || e.premise == Premise::kGrazing) continue;
      EXPECT_EQ(e.collision, e.both_proceed_collides)
          << e.junction << " " << e.av_movement << " (AV) / " << e.hv_movement << " at " << e.time
          << " " << ToString(e.premise);
    }
    long unpredictable = 0;
    for (const JunctionRun& j : r.junctions) unpredictable += j.meetings_unpredictable;
    n[junction_type + " meetings_unpredictable"] += unpredictable;
  }
  std::cout << "merges where both proceeded:";
  for (const auto& [k, v] : n) std::cout << " " << k << " " << v << ";";
  std::cout << "\n";
  EXPECT_GT(n["stop holds collided"], 5) << "merges predicted to collide";
  // Drivers that do not dawdle (sigma 0): the follower's braking decides
  // most merges (before issue 43 every merge touching once a front was on
  // the exit lane was uncertain); those left uncertain touch only beside the
  // leader (measured: 5 here, all collided in SUMO, while 12 m trucks turning
  // beside a car did not: PremiseOnOtherVehicles).
  const long certain = n["stop holds collided"] + n["stop no_collision passed"];
  EXPECT_LE(3 * (n["stop uncertain_merge collided"] + n["stop uncertain_merge passed"]), certain);
  EXPECT_GT(n["stop no_collision passed"] + n["major no_collision passed"], 2)
      << "merges predicted to pass";
}

// ------------------------------------------------------------------ vehicles that are not the car

// Fringe trips on `net` (the grid's), each vehicle an AV (type AV, the
// generated car) or an HV of the given SUMO type, drawn half and half.
std::string MixedRoutes(const std::string& net_path, const std::string& hv_type, double end,
                        const std::string& dir) {
  DemandSpec spec;
  spec.flow = 150;
  spec.end = end;
  spec.seed = 3;
  const std::vector<Trip> trips = DemandTrips(net::NetFile::Load(net_path), spec);
  const std::string path = dir + "/mixed.rou.xml";
  std::ofstream out(path);
  out << "<routes>\n"
         "  <vType id=\"AV\" length=\"5\" width=\"1.8\" accel=\"2.6\" decel=\"4.5\" "
         "minGap=\"2\" maxSpeed=\"13.89\" sigma=\"0\" speedDev=\"0\"/>\n  "
      << hv_type << "\n";
  std::mt19937_64 rng(7);
  for (const Trip& t : trips)
    out << "  <trip id=\"" << t.id << "\" type=\"" << (rng() % 2 ? "AV" : "HV") << "\" depart=\""
        << t.depart << "\" from=\"" << t.from << "\" to=\"" << t.to
        << "\" departLane=\"best\" departSpeed=\"max\"/>\n";
  out << "</routes>\n";
  return path;
}

struct Mix {
  std::string name;
  std::string hv_type;  // empty: generated cars on a 2-lane grid
  int duration = 1200;  // s simulated per run
};
std::ostream& operator<<(std::ostream& os, const Mix& m) { return os << m.name; }

// The game's premise on vehicles that are not the configured car and on
// 2-lane approaches, checked against SUMO: HV trucks (12 m, 2.5 m wide,
// accel 1.0), HV bicycles (1.6 m, 0.65 m, accel 1.2, 5.56 m/s), and cars on
// a grid with two lanes per direction. With encounter_pairs: all and trust 0
// (every HV reckless), on every pair where the AV went SUMO collided exactly
// where the premise holds for certain; where the AV waited, SUMO never
// collided on a pair whose premise holds (the HV's way misses the AV nudged
// or not); uncertain merges are excluded from the game and counted; a
// collision after one vehicle went back to SUMO's rules is not the game's.
// Then in the default mode every encounter is the game: collision iff the AV
// went and the HV drove recklessly, none under TA-EBP.
class PremiseOnOtherVehicles : public ::testing::TestWithParam<Mix> {};

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST_P(PremiseOnOtherVehicles, SumoCollidesExactlyWherePredicted) {
  const Mix& mix = GetParam();
  TempDir dir("taebp_premise");
  const std::string duration = "scenario.duration=" + std::to_string(mix.duration);
  std::vector<std::string> common = {duration, "scenario.stall_action=record"};
  if (mix.hv_type.empty()) {
    common.push_back("scenario.grid.lanes=2");
    common.push_back("scenario.demand.flow=250");
  } else {
    const Scenario grid = BuildScenario(GridConfig({}), "");
    common = {duration, "scenario.stall_action=record",
              "scenario.grid=null", "scenario.demand=null", "scenario.av_share=null",
              "scenario.network=" + grid.net,
              "scenario.routes=[" + MixedRoutes(grid.net, mix.hv_type, mix.duration, dir.path()) + "]",
              "scenario.av_types=[AV]"};
  }
  auto with = [&](std::vector<std::string> more) {
    more.insert(more.begin(), common.begin(), common.end());
    return GridConfig(more);
  };
  // Every conflicting meeting an encounter, every HV reckless.
  {
    const ExperimentConfig cfg = with({"scenario.encounter_pairs=all", "model.trust=0.0",
                                       "policies=[no_trust]"});
    const Scenario sc = BuildScenario(cfg, "");
    const PolicyRun r = RunPolicy(cfg, "no_trust", sc);
    std::map<std::string, long> n;
    for (const EncounterRecord& e : r.encounters) {
      const std::string where = e.junction + " " + e.av_movement + " (AV) / " + e.hv_movement +
                                " at " + std::to_string(e.time);
      ++n[std::string(ToString(e.premise)) + (e.av_first ? " go" : " wait")];
      n["after hand-back"] += e.collision_after_handback;
      if (e.premise == Premise::kUncertainMerge) continue;
      if (e.av_first) {
        EXPECT_EQ(e.collision, e.premise == Premise::kHolds) << ToString(e.premise) << " " << where;
      } else if (e.premise == Premise::kHolds) {
        EXPECT_FALSE(e.collision) << "the AV waited: " << where;
      }
    }
    EXPECT_GT(n["holds go"], 8) << "too few both-proceed pairs to check";
    EXPECT_GT(n["holds wait"], 20);
    EXPECT_GT(n["no_collision go"], 5) << "no pair where both proceeding does not collide";
    // A waiting AV handed back to SUMO's rules follows a 12 m truck into the
    // small junction and SUMO's own model collides (sumo_native does too):
    // recorded as such, not as the game's collision.
    if (mix.name == "trucks") { EXPECT_GT(n["after hand-back"], 0); }
    for (const EncounterRecord& e : r.encounters)
      if (e.collision_after_handback) { EXPECT_FALSE(e.av_first && e.premise == Premise::kHolds); }
    std::cout << mix.name << ":";
    for (const auto& [k, v] : n) std::cout << " " << k << " " << v << ";";
    std::cout << "\n";
  }
  // The default: only meetings whose premise holds are the game.
  const ExperimentConfig cfg = with({"model.trust=0.6", "policies=[no_trust, ta_ebp]"});
  const Scenario sc = BuildScenario(cfg, "");
  for (const std::string policy : {"no_trust", "ta_ebp"}) {
    SCOPED_TRACE(mix.name + " " + policy);
    const PolicyRun r = RunPolicy(cfg, policy, sc);
    long collisions = 0, unpredictable = 0, not_game = 0;
    for (const EncounterRecord& e : r.encounters) {
      EXPECT_EQ(e.premise, Premise::kHolds);
      EXPECT_EQ(e.collision, e.av_first && !e.hv_dc) << e.junction << " " << e.av_movement
                                                      << " / " << e.hv_movement << " at " << e.time;
      collisions += e.collision;
    }
    for (const JunctionRun& j : r.junctions) {
      unpredictable += j.meetings_unpredictable;
      not_game += j.meetings_not_game;
    }
    EXPECT_GT(r.encounters.size(), 40u);
    EXPECT_GT(not_game, 0);
    if (policy == "ta_ebp") { EXPECT_EQ(collisions, 0); }
    if (policy == "no_trust") { EXPECT_GT(collisions, 3); }
    std::cout << mix.name << " " << policy << ": " << r.encounters.size() << " encounters, "
              << collisions << " collisions, not the game " << not_game << ", unpredictable "
              << unpredictable << "\n";
  }
}

INSTANTIATE_TEST_SUITE_P(
    NetworkGame, PremiseOnOtherVehicles,
    ::testing::Values(
        Mix{"trucks",
            "<vType id=\"HV\" vClass=\"truck\" length=\"12\" width=\"2.5\" accel=\"1.0\" "
            "decel=\"4.0\" minGap=\"2\" maxSpeed=\"13.89\" sigma=\"0\" speedDev=\"0\"/>",
            2400},
        Mix{"bicycles",
            "<vType id=\"HV\" vClass=\"bicycle\" length=\"1.6\" width=\"0.65\" accel=\"1.2\" "
            "decel=\"3\" minGap=\"0.5\" maxSpeed=\"5.56\" sigma=\"0\" speedDev=\"0\"/>"},
        Mix{"two_lanes", ""}),
    [](const ::testing::TestParamInfo<Mix>& i) { return i.param.name; });

// The default (encounter_pairs: colliding): every encounter is the paper's
// game, so SUMO's collision is exactly "the AV went and the HV drove
// recklessly", and the meetings that were not a game are counted per junction.
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(NetworkGame, EveryEncounterIsTheGameCollisionIffAvGoesAndHvDrivesRecklessly) {
  const ExperimentConfig cfg =
      GridConfig({"scenario.demand.flow=250", "scenario.duration=1500", "model.trust=0.6",
                  "policies=[no_trust, ta_ebp]", "scenario.stall_action=record"});
  const Scenario sc = BuildScenario(cfg, "");
  for (const std::string policy : {"no_trust", "ta_ebp"}) {
    SCOPED_TRACE(policy);
    const PolicyRun r = RunPolicy(cfg, policy, sc);
    long collisions = 0;
    for (const EncounterRecord& e : r.encounters) {
      EXPECT_TRUE(e.both_proceed_collides) << e.av_movement << " / " << e.hv_movement;
      EXPECT_EQ(e.collision, e.av_first && !e.hv_dc)
          << e.junction << " " << e.av_movement << " (AV) / " << e.hv_movement << " at "
          << e.time;
      collisions += e.collision;
    }
    EXPECT_GT(r.encounters.size(), 100u);
    if (policy == "ta_ebp") {
      EXPECT_EQ(collisions, 0);
    } else {
      EXPECT_GT(collisions, 10);
    }
    long not_game = 0;
    for (const JunctionRun& j : r.junctions) not_game += j.meetings_not_game;
    EXPECT_GT(not_game, 0) << "the grid has merges the AV leads";
  }
}

}  // namespace
}  // namespace taebp
