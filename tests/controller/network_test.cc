// Short SUMO runs of kind: network through taebp::RunPolicy: the AV share of
// the departing vehicles against scenario.av_share (99.9% intervals), the
// extremes, the same AV/HV assignment and trust draws per vehicle id across
// policies; and every AV-HV encounter on movements that conflict in SUMO's
// own foes matrix (read back with net::NetFile), at all-way stops with
// turning demand and at two-way stops.
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
using test::kModel;

long AvDeparted(const PolicyRun& r) {
  return r.network.departed - static_cast<long>(r.hv_trust.size());
}

// ------------------------------------------------------------------ selection and demand

// junctions.exclude leaves junctions that `types` selects to SUMO, and names
// a junction that is not in the network; junctions.ids and exclude cannot
// name the same junction.
TEST(NetworkSelection, ExcludeLeavesJunctionsToSumo) {
  const Scenario all = BuildScenario(GridConfig({}), "");
  ASSERT_EQ(all.junctions.size(), 9u);
  std::set<std::string> ids;
  for (const ControlledJunction& j : all.junctions) ids.insert(j.id);
  const std::string a = *ids.begin(), b = *ids.rbegin();
  const Scenario some =
      BuildScenario(GridConfig({"scenario.junctions.exclude=[" + a + ", " + b + "]"}), "");
  std::set<std::string> left;
  for (const ControlledJunction& j : some.junctions) left.insert(j.id);
  ids.erase(a);
  ids.erase(b);
  EXPECT_EQ(left, ids);
  try {
    BuildScenario(GridConfig({"scenario.junctions.exclude=[nowhere]"}), "");
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("scenario.junctions.exclude: junction 'nowhere'"));
  }
  try {
    BuildScenario(GridConfig({"scenario.junctions.ids=[" + a + "]",
                              "scenario.junctions.exclude=[" + a + "]"}), "");
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("is also in scenario.junctions.ids"));
  }
}

// scenario.routes_scale is SUMO's --scale: twice the demand departs about
// twice the vehicles (SUMO's own seeded sampling), the same seed the same count.
TEST(NetworkDemand, RoutesScaleMultipliesTheDemand) {
  const ExperimentConfig one = GridConfig({"scenario.demand.flow=150"});
  const ExperimentConfig two = GridConfig({"scenario.demand.flow=150", "scenario.routes_scale=2"});
  const long n1 = RunPolicy(one, "sumo_native", BuildScenario(one, "")).network.departed;
  const long n2 = RunPolicy(two, "sumo_native", BuildScenario(two, "")).network.departed;
  const long again = RunPolicy(two, "sumo_native", BuildScenario(two, "")).network.departed;
  ASSERT_GT(n1, 100);
  EXPECT_EQ(n2, again);
  // Scaling by 2 duplicates every trip (SUMO inserts floor(scale) copies).
  EXPECT_NEAR(static_cast<double>(n2) / n1, 2.0, 0.1) << n1 << " vs " << n2;
}

// ------------------------------------------------------------------ AV share

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(NetworkAvShare, AvFractionOfDepartedVehiclesAgreesWithTheShare) {
  for (double p : {0.3, 0.75}) {
    SCOPED_TRACE("av_share " + std::to_string(p));
    const ExperimentConfig cfg =
        GridConfig({"scenario.av_share=" + std::to_string(p), "scenario.duration=900"});
    const Scenario sc = BuildScenario(cfg, "");
    const PolicyRun r = RunPolicy(cfg, "sumo_native", sc);
    const long n = r.network.departed;
    const long av = AvDeparted(r);
    ASSERT_GT(n, 500);  // the grid saturates: not every trip departs
    ASSERT_GE(av, 0);
    const auto [lo, hi] = Wilson(av, n, kZ999);
    EXPECT_GE(p, lo) << av << " AVs of " << n;
    EXPECT_LE(p, hi) << av << " AVs of " << n;
    long cav = 0, chv = 0;
    for (const JunctionRun& j : r.junctions) {
      cav += j.crossings_av;
      chv += j.crossings_hv;
    }
    EXPECT_GT(cav, 0);
    EXPECT_GT(chv, 0);
    std::cout << "av_share " << p << ": " << av << " AVs of " << n << " departed ("
              << static_cast<double>(av) / n << "); junction crossings AV " << cav << ", HV "
              << chv << "\n";
  }
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(NetworkAvShare, ZeroAndOneGiveOnlyHvsOrOnlyAvs) {
  for (const std::string& policy : {std::string("sumo_native"), std::string("ta_ebp")}) {
    for (double p : {0.0, 1.0}) {
      SCOPED_TRACE(policy + ", av_share " + std::to_string(p));
      const ExperimentConfig cfg = GridConfig({"scenario.av_share=" + std::to_string(p),
                                               "scenario.duration=300",
                                               "policies=[" + policy + "]"});
      const PolicyRun r = RunPolicy(cfg, policy, BuildScenario(cfg, ""));
      ASSERT_GT(r.network.departed, 100);
      EXPECT_EQ(AvDeparted(r), p == 0.0 ? 0 : r.network.departed);
      EXPECT_TRUE(r.encounters.empty()) << "an AV-HV encounter with one kind of vehicle";
      long cav = 0, chv = 0;
      for (const JunctionRun& j : r.junctions) {
        cav += j.crossings_av;
        chv += j.crossings_hv;
      }
      EXPECT_GT(cav + chv, 100);
      EXPECT_EQ(p == 0.0 ? cav : chv, 0);
    }
  }
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(NetworkAvShare, SameSeedSameAssignmentAndTrustPerVehicleAcrossPolicies) {
  // Each vehicle's kind and trust depend on (seed, id) only: across policies
  // (whose traffic differs) an id is always the same kind, an HV always has
  // the same trust.
  struct Seen {
    bool av;
    double trust;
  };
  auto collect = [](const ExperimentConfig& cfg, const std::vector<std::string>& policies) {
    std::map<std::string, std::vector<Seen>> seen;
    const Scenario sc = BuildScenario(cfg, "");
    for (const std::string& policy : policies) {
      const PolicyRun r = RunPolicy(cfg, policy, sc);
      EXPECT_GT(r.encounters.size(), 50u) << policy;
      for (const EncounterRecord& e : r.encounters) {
        seen[e.av].push_back({true, 0});
        seen[e.hv].push_back({false, e.hv_trust});
      }
    }
    return seen;
  };
  const ExperimentConfig cfg = GridConfig({"scenario.duration=600"});
  const auto a = collect(cfg, {"no_ebp", "no_trust", "ta_ebp"});
  long ids = 0, repeated = 0;
  for (const auto& [id, list] : a) {
    ++ids;
    repeated += list.size() > 1;
    for (const Seen& s : list) {
      EXPECT_EQ(s.av, list.front().av) << id << " is an AV in one policy and an HV in another";
      if (!s.av) {
        EXPECT_EQ(s.trust, list.front().trust) << id;
      }
    }
  }
  EXPECT_GT(repeated, ids / 4) << "too few vehicles met in several policies to compare";
  // Another seed draws afresh (and generates other demand under the same ids).
  const auto b = collect(GridConfig({"scenario.duration=600", "scenario.seed=12"}),
                         {"ta_ebp"});
  long common = 0, differ = 0;
  for (const auto& [id, list] : b) {
    const auto it = a.find(id);
    if (it == a.end()) continue;
    ++common;
    const Seen& x = it->second.front();
    const Seen& y = list.front();
    differ += x.av != y.av || (!x.av && x.trust != y.trust);
  }
  EXPECT_GT(common, 50);
  EXPECT_GT(differ, common / 4);
}

// ------------------------------------------------------------------ conflicts from SUMO
// Every encounter's two movements, looked up as links of the net SUMO ran,
// conflict in SUMO's foes matrix; with the link directions recorded.
struct MovementCheck {
  long encounters = 0, turning = 0;
  long major = 0;  // major-road games (the HV on a link with the right of way)
  std::map<std::string, long> dirs;  // "s/l" etc.
};

const net::Link* FindLink(const net::NetFile& net, const std::string& movement) {
  const auto gt = movement.find('>');
  if (gt == std::string::npos) return nullptr;
  const std::string from = movement.substr(0, gt), to = movement.substr(gt + 1);
  for (int id : net.LinksFrom(from))
    if (net.links()[id].to_lane == to) return &net.links()[id];
  return nullptr;
}

MovementCheck CheckEncounterMovements(const PolicyRun& r, const net::NetFile& net,
                                      char stop_state) {
  MovementCheck out;
  for (const EncounterRecord& e : r.encounters) {
    const net::Link* a = FindLink(net, e.av_movement);
    const net::Link* h = FindLink(net, e.hv_movement);
    if (!a || !h) {
      ADD_FAILURE() << "no link for " << e.av_movement << " or " << e.hv_movement;
      continue;
    }
    EXPECT_EQ(a->junction, e.junction);
    EXPECT_EQ(h->junction, e.junction);
    EXPECT_NE(a->from_lane, h->from_lane) << "an encounter on one approach";
    const net::Junction* j = net.FindJunction(e.junction);
    if (!j || a->index < 0 || h->index < 0) {
      ADD_FAILURE() << e.junction << ": unindexed links " << e.av_movement << " / "
                    << e.hv_movement;
      continue;
    }
    EXPECT_TRUE(j->foes[a->index][h->index] || j->foes[h->index][a->index])
        << e.junction << ": " << e.av_movement << " / " << e.hv_movement
        << " met but do not conflict";
    EXPECT_EQ(e.av_dir, a->dir);
    EXPECT_EQ(e.hv_dir, h->dir);
    // Only vehicles on stop links are ever held (the major road never): the
    // AV always; the HV too, but in a major-road game (on by default since
    // issue 43), where it approaches on a link with the right of way.
    EXPECT_EQ(a->state, stop_state) << e.av_movement;
    EXPECT_EQ(h->state, e.major_road ? 'M' : stop_state) << e.hv_movement;
    out.major += e.major_road;
    ++out.encounters;
    out.turning += a->dir != 's' || h->dir != 's';
    ++out.dirs[std::string(1, a->dir) + "/" + h->dir];
  }
  return out;
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(NetworkConflicts, FourWayAllWayStopWithTurnsEncountersConflictInSumosMatrix) {
  TempDir dir("taebp_network");
  const std::string net = test::FourWay(dir, "x", "allway_stop");
  const std::string yaml = std::string(
                               "scenario:\n"
                               "  kind: network\n"
                               "  network: ") +
                           net +
                           "\n"
                           "  demand: {flow: 450}\n"
                           "  av_share: 0.5\n"
                           "  cruise_speed: 8\n"
                           "  duration: 1200\n"
                           "  seed: 5\n" +
                           "model:\n  prior_go: 0.2\n  collision_penalty: 3.0\n  trust: 0.6\n" +
                           "policies: [no_trust, ta_ebp]\n";
  const ExperimentConfig cfg = ParseExperimentConfig(yaml, "network_test 4-way");
  const Scenario sc = BuildScenario(cfg, "");
  ASSERT_EQ(sc.junctions.size(), 1u);
  EXPECT_EQ(sc.junctions[0].id, "C");
  for (const std::string& policy : cfg.policies) {
    SCOPED_TRACE(policy);
    const PolicyRun r = RunPolicy(cfg, policy, sc);
    MovementCheck c = CheckEncounterMovements(r, *sc.topology, 'w');
    EXPECT_GT(c.encounters, 50);
    EXPECT_GT(c.turning, c.encounters / 4) << "the demand turns";
    EXPECT_GT(c.dirs["l/s"] + c.dirs["s/l"] + c.dirs["l/l"], 0) << "no left-turn encounter";
    // The turns onto a shared exit (a right turn beside a straight or a left
    // turn) are met, and a game only where "both proceed" collides before
    // either front is on the shared exit from every Go position any policy
    // may command; the others are refused as unpredictable (SUMO's car
    // following decides there; docs/encounter-rules.md, section 3).
    long unpredictable = 0;
    for (const JunctionRun& j : r.junctions) unpredictable += j.meetings_unpredictable;
    EXPECT_GT(unpredictable, 0) << "no merge met";
    EXPECT_EQ(r.teleports, 0);
    std::cout << policy << ": " << c.encounters << " encounters, " << c.turning
              << " with a turn;";
    for (const auto& [d, k] : c.dirs) std::cout << " " << d << " " << k;
    std::cout << "; merges refused " << unpredictable << "; other collisions "
              << r.other_collisions << "\n";
  }
}

// Three seeds pooled: a two-way-stop grid at this demand saturates after a
// while (minor roads wait for 5 s gaps), so one long run adds few encounters.
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(NetworkConflicts, TwoWayStopGridEncountersAreBetweenStopLinksThatConflict) {
  MovementCheck c;
  long other = 0;
  for (const char* seed : {"scenario.seed=11", "scenario.seed=12", "scenario.seed=13"}) {
    SCOPED_TRACE(seed);
    const ExperimentConfig cfg =
        GridConfig({"scenario.grid.junction_type=priority_stop", "scenario.duration=1500",
                    "scenario.demand.flow=150", "policies=[ta_ebp]", seed,
                    // minor roads wait for 5 s gaps: the grid may saturate
                    "scenario.stall_action=record"});
    const Scenario sc = BuildScenario(cfg, "");
    ASSERT_EQ(sc.junctions.size(), 9u);
    const PolicyRun r = RunPolicy(cfg, "ta_ebp", sc);
    for (const JunctionRun& j : r.junctions) EXPECT_EQ(j.rule, "two_way_stop") << j.id;
    const MovementCheck one = CheckEncounterMovements(r, *sc.topology, 's');
    c.encounters += one.encounters;
    c.turning += one.turning;
    c.major += one.major;
    for (const auto& [d, k] : one.dirs) c.dirs[d] += k;
    // Careful moves wait for a gap in the major road: every collision outside
    // an encounter is a move of the game (an HV driving recklessly) with a
    // third vehicle, none is the controller's careful moves' or SUMO's.
    EXPECT_EQ(r.other_collisions, r.other_collisions_game_move);
    other += r.other_collisions;
    for (const EncounterRecord& e : r.encounters)
      EXPECT_EQ(e.collision, e.av_first && !e.hv_dc) << e.av << "/" << e.hv << " at " << e.time;
  }
  EXPECT_GT(c.encounters, 20);
  EXPECT_GT(c.major, 0) << "the major-road game is on by default";
  EXPECT_LT(c.major, c.encounters) << "and the stop lines' games go on";
  EXPECT_LT(other, c.encounters / 10) << "reckless HVs hit the major road that often?";
  std::cout << "two-way grid: " << c.encounters << " encounters (" << c.major << " major road), " << c.turning
            << " with a turn, " << other << " collisions of a reckless move with a third vehicle;";
  for (const auto& [d, k] : c.dirs) std::cout << " " << d << " " << k;
  std::cout << "\n";
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(NetworkConflicts, AllWayGridEncountersConflictInSumosMatrix) {
  const ExperimentConfig cfg = GridConfig({"scenario.duration=600", "policies=[ta_ebp]"});
  const Scenario sc = BuildScenario(cfg, "");
  const PolicyRun r = RunPolicy(cfg, "ta_ebp", sc);
  const MovementCheck c = CheckEncounterMovements(r, *sc.topology, 'w');
  EXPECT_GT(c.encounters, 50);
  std::set<std::string> junctions;
  for (const EncounterRecord& e : r.encounters) junctions.insert(e.junction);
  EXPECT_GE(junctions.size(), 5u);
}

// ------------------------------------------------------------------ delay of unfinished trips

// The delay as an independent reader computes it from SUMO's tripinfo file
// (a plain scan of the records, not the XML parser the run uses): every record of
// a vehicle departed at or after `warmup`, finished or not (arrival -1).
struct TripinfoDelay {
  long trips = 0, unfinished = 0, finished = 0;
  double loss = 0, waiting = 0, finished_loss = 0;
};
TripinfoDelay DelayFromTripinfo(const std::string& xml, double warmup) {
  TripinfoDelay d;
  auto attr = [](const std::string& rec, const std::string& name) {
    const std::string key = " " + name + "=\"";
    const auto at = rec.find(key);
    if (at == std::string::npos) {
      ADD_FAILURE() << "no " << name << " in " << rec;
      return 0.0;
    }
    const auto begin = at + key.size();
    return std::stod(rec.substr(begin, rec.find('"', begin) - begin));
  };
  for (auto open = xml.find("<tripinfo "); open != std::string::npos;
       open = xml.find("<tripinfo ", open + 1)) {
    const std::string rec = xml.substr(open, xml.find('>', open) - open + 1);
    if (attr(rec, "depart") < warmup) continue;
    ++d.trips;
    d.loss += attr(rec, "timeLoss");
    d.waiting += attr(rec, "waitingTime");
    if (attr(rec, "arrival") < 0) {
      ++d.unfinished;
    } else {
      ++d.finished;
      d.finished_loss += attr(rec, "timeLoss");
    }
  }
  return d;
}

// Vehicles still in the network at the end count in the delay: on a short
// grid run (trips in flight at the end) and on a gridlocked one (nothing
// finishes), trips_unfinished > 0 and the mean time loss and waiting time are
// those of every trip departed after the warm-up in SUMO's own tripinfo file.
TEST(NetworkDelay, UnfinishedTripsCountInTheDelay) {
  TempDir dir;
  const std::string routes = dir.Write("blocked.rou.xml", test::BlockedGridRoutes());
  const ExperimentConfig short_run =
      GridConfig({"scenario.duration=240", "scenario.warmup=30", "scenario.tripinfo_output=true",
                  "policies=[no_ebp]"});
  const ExperimentConfig gridlock = ParseExperimentConfig(
      test::BlockedGridConfig(routes), "network_test blocked grid",
      {"scenario.duration=500", "scenario.warmup=20", "scenario.tripinfo_output=true",
       "scenario.stall_action=record", "policies=[no_ebp]"});
  for (const ExperimentConfig* cfg : {&short_run, &gridlock}) {
    const bool stalled = cfg == &gridlock;
    SCOPED_TRACE(stalled ? "gridlock" : "short run");
    const PolicyRun r = RunPolicy(*cfg, "no_ebp", BuildScenario(*cfg, ""));
    ASSERT_FALSE(r.sumo_tripinfo_xml.empty());
    const TripinfoDelay d = DelayFromTripinfo(r.sumo_tripinfo_xml, cfg->scenario.warmup);
    const NetworkRun& n = r.network;
    EXPECT_GT(n.trips_unfinished, 0);
    EXPECT_EQ(n.trips, d.trips);
    EXPECT_EQ(n.trips_unfinished, d.unfinished);
    ASSERT_GT(n.trips, 0);
    EXPECT_NEAR(n.time_loss_sum / n.trips, d.loss / d.trips, 1e-9 * (1 + d.loss / d.trips));
    EXPECT_NEAR(n.waiting_time_sum / n.trips, d.waiting / d.trips,
                1e-9 * (1 + d.waiting / d.trips));
    EXPECT_EQ(!r.stalls.empty(), stalled);
    if (stalled) {
      EXPECT_EQ(d.finished, 0) << "every trip heads for the blocked exit";
      // Only the vehicles that never got in are missing: every departed one is a trip.
      EXPECT_EQ(n.trips_unfinished, n.trips);
      EXPECT_GT(n.time_loss_sum / n.trips, 100.0);
    } else {
      ASSERT_GT(d.finished, 0);
      // Counted over finished trips only, the delay would differ.
      EXPECT_NE(d.finished_loss / d.finished, d.loss / d.trips);
    }
    std::cout << (stalled ? "gridlock" : "short run") << ": " << n.trips << " trips, "
              << n.trips_unfinished << " unfinished, mean time loss " << d.loss / d.trips
              << " s (finished only: "
              << (d.finished ? d.finished_loss / d.finished : 0.0) << " s)\n";
  }
}

}  // namespace
}  // namespace taebp

namespace taebp {
namespace {

// ------------------------------------------------------------------ SUMO decides
// Where no AV-HV pair meets, every controller policy leaves SUMO's traffic
// exactly as SUMO makes it: the same tripinfo records (same vehicles, same
// departure, arrival, time loss, waiting) as sumo_native, byte for byte. On
// the grid study's all-way grid and on a priority_stop grid with
// randomTrips.py demand, at AV share 0 and 1; and on a corridor where AVs
// drive east and HVs west (opposite straights never conflict, so the
// junctions are watched but nobody meets), also with every conflicting
// meeting taken for an encounter (encounter_pairs: all). A controller that
// held a vehicle meeting nobody (a lone head looking both ways, a pair that
// does not conflict) changes some trip and turns this red (mutation
// pair-that-does-not-conflict-meets).
struct IdentityCase {
  std::string name;
  std::string yaml;
  std::vector<std::string> shares;  // scenario.av_share values; empty: by type
};

std::string Tripinfo(const ExperimentConfig& cfg, const Scenario& sc, const std::string& policy,
                     long* trips) {
  const PolicyRun r = RunPolicy(cfg, policy, sc);
  *trips = r.network.trips;
  EXPECT_EQ(r.encounters_formed, 0) << policy;
  EXPECT_TRUE(r.stalls.empty()) << policy;
  return r.sumo_tripinfo_xml;
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(SumoDecides, WhereNoAvHvPairMeetsEveryPolicyGivesSumoNativesTripinfo) {
  const TempDir dir("identity");
  // A priority_stop grid with randomTrips.py demand from its fringe.
  const std::string pnet = test::Netgenerate(dir, "prio", 3, "priority_stop", 100);
  const std::string trips = (dir.path() / "prio.trips.xml").string();
  const std::string tools = std::string(std::getenv("SUMO_HOME") ? std::getenv("SUMO_HOME")
                                                                 : "/usr/share/sumo") +
                            "/tools";
  ASSERT_EQ(test::Shell("python3 " + tools + "/randomTrips.py -n " + pnet + " -o " + trips +
                            " --fringe-factor 1000 -p 2.5 -e 500 --seed 3",
                        (dir.path() / "trips.log").string()),
            0)
      << test::ReadText((dir.path() / "trips.log").string());
  // The corridor: a 3 x 3 all-way grid, AVs west to east along the middle
  // row, HVs east to west.
  const std::string cnet = test::Netgenerate(dir, "corr", 3, "allway_stop", 100);
  const std::string croutes = dir.Write(
      "corr.rou.xml",
      "<routes>\n"
      "  <vType id=\"AV\" length=\"5\" minGap=\"2\" maxSpeed=\"13.89\" speedDev=\"0\"/>\n"
      "  <vType id=\"HV\" length=\"5\" minGap=\"2\" maxSpeed=\"13.89\" speedDev=\"0\"/>\n"
      "  <flow id=\"av\" type=\"AV\" begin=\"0\" end=\"500\" period=\"4\" from=\"left1A1\" "
      "to=\"C1right1\"/>\n"
      "  <flow id=\"hv\" type=\"HV\" begin=\"0\" end=\"500\" period=\"4\" from=\"right1C1\" "
      "to=\"A1left1\"/>\n"
      "</routes>\n");
  const std::string common =
      "  duration: 500\n  warmup: 0\n  tripinfo_output: true\n  stall_action: record\n";
  const std::vector<IdentityCase> cases = {
      {"all-way grid (the grid study's)",
       "scenario:\n  kind: network\n  grid: {columns: 4, rows: 4, length: 100, attach_length: 100,"
       " lanes: 1, speed: 13.89, junction_type: allway_stop}\n  demand: {flow: 200}\n"
       "  cruise_speed: 13.89\n" + common,
       {"0", "1"}},
      {"priority_stop grid, randomTrips.py demand",
       "scenario:\n  kind: network\n  network: " + pnet + "\n  routes: [" + trips + "]\n" + common,
       {"0", "1"}},
      {"corridor, AVs east and HVs west",
       "scenario:\n  kind: network\n  network: " + cnet + "\n  routes: [" + croutes + "]\n" +
           common,
       {}},
      // Every conflicting AV-HV meeting an encounter, premise or not: the
      // corridor's pairs still do not conflict, so still nobody meets (a
      // non-conflicting pair that met would be held here: no premise check
      // stops it).
      {"corridor, encounter_pairs: all",
       "scenario:\n  kind: network\n  network: " + cnet + "\n  routes: [" + croutes + "]\n" +
           "  encounter_pairs: all\n" + common,
       {}},
  };
  for (const IdentityCase& c : cases) {
    const std::vector<std::string> shares =
        c.shares.empty() ? std::vector<std::string>{""} : c.shares;
    for (const std::string& share : shares) {
      SCOPED_TRACE(c.name + (share.empty() ? "" : ", AV share " + share));
      std::vector<std::string> overrides;
      if (!share.empty()) overrides.push_back("scenario.av_share=" + share);
      const ExperimentConfig cfg =
          ParseExperimentConfig(c.yaml + kModel + "policies: [sumo_native]\n", c.name, overrides);
      const Scenario sc = BuildScenario(cfg, "");
      long native_trips = 0;
      const std::string native = Tripinfo(cfg, sc, "sumo_native", &native_trips);
      EXPECT_GT(native_trips, 100);
      ASSERT_NE(native.find("<tripinfo "), std::string::npos);
      for (const char* policy : {"no_ebp", "no_trust", "ta_ebp"}) {
        long trips_policy = 0;
        const std::string mine = Tripinfo(cfg, sc, policy, &trips_policy);
        EXPECT_EQ(trips_policy, native_trips) << policy;
        EXPECT_TRUE(mine == native) << policy << ": tripinfo differs from sumo_native's";
      }
    }
  }
}

}  // namespace
}  // namespace taebp
