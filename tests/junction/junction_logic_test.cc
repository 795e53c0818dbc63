// The SUMO-free state machine of one controlled junction (junction_logic.h),
// driven with fake time, fake vehicles, a fake Environment (keep-clear, major
// road gaps) and a fake EncounterModel (scripted AV draws and HV readings).
//
// The junction is a real one: B1 of
//   netgenerate --grid --grid.number 4 --default-junction-type allway_stop
//               --no-turnarounds true
// whose 12 links (request index = movement index) and <request foes> are
// copied below; tests/scenario/net_file_test.cc reads the same junction from
// a freshly generated net and checks these strings against it.
#include "taebp/junction/junction_logic.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace taebp::junction {
namespace {

using ::testing::HasSubstr;
using Kind = Command::Kind;
constexpr VehicleKind kAV = VehicleKind::kAV;
constexpr VehicleKind kHV = VehicleKind::kHV;

// ------------------------------------------------------------------ the junction
// Approaches (incLanes order): 0 = from the north (B2B1_0), 1 = east (C1B1_0),
// 2 = south (B0B1_0), 3 = west (A1B1_0). Exits: A1 (west), B0 (south),
// C1 (east), B2 (north).
enum Mv {
  kNr = 0, kNs = 1, kNl = 2,   // north: right -> A1, straight -> B0, left -> C1
  kEr = 3, kEs = 4, kEl = 5,   // east:  right -> B2, straight -> A1, left -> B0
  kSr = 6, kSs = 7, kSl = 8,   // south: right -> C1, straight -> B2, left -> A1
  kWr = 9, kWs = 10, kWl = 11  // west:  right -> B0, straight -> C1, left -> B2
};
// SUMO's <request index="i" foes="..."/>: the last character is link 0.
const char* const kB1Foes[12] = {
    "000100010000", "111100110000", "110111110000", "100010000000",
    "100110000111", "111110000110", "010000000100", "110000111100",
    "110000110111", "000000100010", "000111100110", "000110111110"};
const char kDirs[12] = {'r', 's', 'l', 'r', 's', 'l', 'r', 's', 'l', 'r', 's', 'l'};
const int kExit[12] = {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3};  // A1, B0, C1, B2

JunctionSpec B1(Rule rule = Rule::kAllWay) {
  JunctionSpec s;
  s.id = "B1";
  s.rule = rule;
  s.approaches = 4;
  for (int m = 0; m < 12; ++m) {
    Movement mv;
    mv.approach = m / 3;
    mv.dir = kDirs[m];
    s.movements.push_back(mv);
  }
  s.conflict.assign(12, std::vector<bool>(12, false));
  for (int i = 0; i < 12; ++i)
    for (int k = 0; k < 12; ++k) s.conflict[i][k] = kB1Foes[i][11 - k] == '1';
  return s;
}

TEST(B1Matrix, IsTheJunctionTheTestsAssume) {
  const JunctionSpec s = B1();
  int pairs = 0;
  for (int i = 0; i < 12; ++i) {
    for (int k = 0; k < 12; ++k) {
      EXPECT_EQ(s.conflict[i][k], s.conflict[k][i]) << i << "," << k;  // symmetric here
      if (s.movements[i].approach == s.movements[k].approach) {
        EXPECT_FALSE(s.Conflict(i, k)) << "same approach " << i << "," << k;
      }
      pairs += s.conflict[i][k];
    }
  }
  EXPECT_EQ(pairs / 2, 30);
  // Opposite straights pass each other; crossing straights conflict.
  EXPECT_FALSE(s.Conflict(kNs, kSs));
  EXPECT_FALSE(s.Conflict(kEs, kWs));
  EXPECT_TRUE(s.Conflict(kNs, kEs));
  EXPECT_TRUE(s.Conflict(kNs, kWs));
  // A left turn crosses the opposite straight and the opposite left.
  EXPECT_TRUE(s.Conflict(kNl, kSs));
  EXPECT_TRUE(s.Conflict(kNl, kSl));
  // Merges into one exit are conflicts: right turn N->A1 with E straight and S left.
  EXPECT_TRUE(s.Conflict(kNr, kEs));
  EXPECT_TRUE(s.Conflict(kNr, kSl));
  // ... and a right turn conflicts with nothing else.
  for (int m = 0; m < 12; ++m) {
    if (m != kEs && m != kSl) {
      EXPECT_FALSE(s.Conflict(kNr, m)) << m;
    }
  }
  for (int a = 0; a < 12; ++a) {
    for (int b = 0; b < 12; ++b) {
      if (a != b && kExit[a] == kExit[b]) {
        EXPECT_TRUE(s.Conflict(a, b)) << a << "," << b;
      }
    }
  }
}

TEST(JunctionSpec, ValidateRejectsMismatchedSizes) {
  JunctionSpec s = B1();
  s.conflict.pop_back();
  EXPECT_THROW(JunctionLogic(s, Timing{}), std::invalid_argument);
  s = B1();
  s.conflict[3].pop_back();
  EXPECT_THROW(JunctionLogic(s, Timing{}), std::invalid_argument);
  s = B1();
  s.movements[5].approach = 4;
  try {
    JunctionLogic logic(s, Timing{});
    ADD_FAILURE() << "accepted an approach out of range";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("B1"));
  }
}

// ------------------------------------------------------------------ fakes
struct FakeEnv : Environment {
  // Keep-clear: return false for these vehicles / movements.
  std::set<int> no_room_vehicles, no_room_movements;
  std::set<int> major_busy;  // movements whose major road is not clear
  std::function<bool(int movement, int vehicle)> room;  // overrides the sets when set
  int room_calls = 0, major_calls = 0;
  bool ExitHasRoom(int movement, int vehicle, int /*also*/) override {
    ++room_calls;
    if (room) return room(movement, vehicle);
    return !no_room_vehicles.count(vehicle) && !no_room_movements.count(movement);
  }
  bool MajorClear(int movement) override {
    ++major_calls;
    return !major_busy.count(movement);
  }
};

struct FakeModel : EncounterModel {
  std::map<int, AvDraw> draws;  // by AV; default: intent stop, no nudge
  std::map<int, bool> dc;       // by HV; default: DR
  std::vector<std::pair<int, int>> drawn, read;
  std::vector<double> observed;
  AvDraw Draw(int av, int hv) override {
    drawn.emplace_back(av, hv);
    const auto it = draws.find(av);
    return it == draws.end() ? AvDraw{} : it->second;
  }
  HvReading Read(int av, int hv, double obs) override {
    read.emplace_back(av, hv);
    observed.push_back(obs);
    HvReading r;
    r.observed = obs;
    r.posterior = 0.5;
    const auto it = dc.find(hv);
    r.drives_if_clear = it != dc.end() && it->second;
    return r;
  }
};

AvDraw Draw(bool go, double nudge) {
  AvDraw d;
  d.intent_go = go;
  d.goes_first = go;
  d.nudge = nudge > 0;
  d.nudge_distance = nudge;
  return d;
}

// Exact times on a 0.1 s grid.
double T(int tenths) { return tenths / 10.0; }

// The commands of one Decide as (kind, vehicle, reckless) for comparisons.
struct Cmd {
  Kind kind;
  int vehicle;
  bool reckless;
  bool operator==(const Cmd& o) const {
    return kind == o.kind && vehicle == o.vehicle && reckless == o.reckless;
  }
};
std::ostream& operator<<(std::ostream& os, const Cmd& c) {
  return os << (c.kind == Kind::kRelease ? "Release(" : "Nudge(") << c.vehicle
            << (c.reckless ? ", reckless)" : ")");
}
Cmd Rel(int v, bool reckless = false) { return {Kind::kRelease, v, reckless}; }
Cmd Nudge(int v) { return {Kind::kStartNudge, v, false}; }

std::vector<Cmd> Simplify(const std::vector<Command>& cs) {
  std::vector<Cmd> out;
  for (const Command& c : cs) out.push_back({c.kind, c.vehicle, c.reckless});
  return out;
}

// Drives a JunctionLogic on a 0.1 s clock and records every command.
class Bench {
 public:
  explicit Bench(JunctionSpec spec = B1(), Timing timing = Timing{})
      : logic(std::move(spec), timing) {}

  // Decide at tenths t0..t1 inclusive; returns the commands with their time.
  std::vector<std::pair<int, Cmd>> Run(int t0, int t1) {
    std::vector<std::pair<int, Cmd>> out;
    for (int t = t0; t <= t1; ++t)
      for (const Cmd& c : Simplify(logic.Decide(T(t), env, model))) out.emplace_back(t, c);
    return out;
  }
  std::vector<Cmd> At(int t) { return Simplify(logic.Decide(T(t), env, model)); }

  JunctionLogic logic;
  FakeEnv env;
  FakeModel model;
};

using Timed = std::vector<std::pair<int, Cmd>>;

// ------------------------------------------------------------------ one head

TEST(JunctionLogic, ALoneHeadLooksForTheArrivalWindowThenGoes) {
  for (double window : {1.0, 2.5}) {
    Bench b(B1(), Timing{window, 1.0});
    b.logic.Arrive(7, kHV, kNs, T(20));
    EXPECT_EQ(b.logic.Waiting(), 1);
    const int due = 20 + static_cast<int>(window * 10 + 0.5);
    EXPECT_TRUE(b.Run(20, due - 1).empty()) << window;
    EXPECT_EQ(b.At(due), std::vector<Cmd>{Rel(7)}) << window;
    EXPECT_EQ(b.logic.Waiting(), 0);
    EXPECT_EQ(b.logic.InJunction(), 1);
    EXPECT_DOUBLE_EQ(b.logic.LastActivity(), T(due));
    EXPECT_TRUE(b.Run(due + 1, due + 100).empty());  // released once
    b.logic.Cleared(7, T(due + 30));
    EXPECT_EQ(b.logic.InJunction(), 0);
    EXPECT_TRUE(b.model.drawn.empty());
    EXPECT_EQ(b.env.major_calls, 0);  // all-way stop: no gap check
  }
}

// A head blocked by a vehicle inside is ready again from the moment that
// vehicle cleared (Cleared), and looks for the window from then.
TEST(JunctionLogic, AHeadArrivingBehindAClearedVehicleLooksAgain) {
  // Two conflicting HVs 3 s apart: the first goes at 1 s; the second arrives
  // while it is inside, and looks for the window once the first has cleared.
  Bench b;
  b.logic.Arrive(1, kHV, kNs, T(0));
  EXPECT_EQ(b.Run(0, 10), (Timed{{10, Rel(1)}}));
  b.logic.Arrive(2, kHV, kEs, T(30));
  EXPECT_TRUE(b.Run(30, 50).empty());
  b.logic.Cleared(1, T(51));
  EXPECT_EQ(b.Run(51, 70), (Timed{{61, Rel(2)}}));
}

// ------------------------------------------------------------------ AV-HV encounter
struct EncounterCase {
  const char* name;
  bool av_goes, hv_dc;
};
std::ostream& operator<<(std::ostream& os, const EncounterCase& c) { return os << c.name; }

class Encounter : public ::testing::TestWithParam<EncounterCase> {};

TEST_P(Encounter, ReleasesInTheDocumentedOrder) {
  const EncounterCase c = GetParam();
  for (bool av_first_to_arrive : {true, false}) {
    SCOPED_TRACE(av_first_to_arrive ? "AV arrived first" : "HV arrived first");
    Bench b(B1(), Timing{1.0, 1.5});
    const int av = 11, hv = 22;
    b.model.draws[av] = Draw(c.av_goes, 1.64);
    b.model.dc[hv] = c.hv_dc;
    b.logic.Arrive(av_first_to_arrive ? av : hv, av_first_to_arrive ? kAV : kHV,
                   av_first_to_arrive ? kNs : kEs, T(0));
    b.logic.Arrive(av_first_to_arrive ? hv : av, av_first_to_arrive ? kHV : kAV,
                   av_first_to_arrive ? kEs : kNs, T(6));
    // The first head looks 1 s; the second became ready within the window: they meet.
    EXPECT_TRUE(b.Run(0, 9).empty());
    EXPECT_EQ(b.At(10), std::vector<Cmd>{Nudge(av)});
    ASSERT_EQ(b.model.drawn.size(), 1u);
    EXPECT_EQ(b.model.drawn[0], std::make_pair(av, hv));
    EXPECT_EQ(b.logic.Encounters(), 1);
    EXPECT_EQ(b.logic.Waiting(), 0);
    // Nothing happens until the nudge is done.
    EXPECT_TRUE(b.Run(11, 40).empty());
    EXPECT_TRUE(b.logic.TakeFinished().empty());
    b.logic.NudgeDone(av, 1.6410004, T(41), b.model);
    ASSERT_EQ(b.model.read.size(), 1u);
    EXPECT_EQ(b.model.read[0], std::make_pair(av, hv));
    EXPECT_DOUBLE_EQ(b.model.observed[0], 1.6410004);

    Timed log;
    auto run = [&](int t0, int t1) {
      for (auto& x : b.Run(t0, t1)) log.push_back(x);
    };
    if (c.av_goes && !c.hv_dc) {  // both at once: the game's collision
      run(41, 41);
      EXPECT_EQ(log, (Timed{{41, Rel(av)}, {41, Rel(hv, true)}}));
      b.logic.Cleared(hv, T(60));
      b.logic.Cleared(av, T(62));
    } else if (c.av_goes && c.hv_dc) {  // HV after the AV cleared
      run(41, 70);
      EXPECT_EQ(log, (Timed{{41, Rel(av)}}));
      b.logic.Cleared(av, T(71));
      run(71, 100);
      EXPECT_EQ(log, (Timed{{41, Rel(av)}, {71, Rel(hv)}}));
      b.logic.Cleared(hv, T(101));
    } else if (!c.av_goes && !c.hv_dc) {  // HV at once, the AV after it cleared
      run(41, 70);
      EXPECT_EQ(log, (Timed{{41, Rel(hv, true)}}));
      b.logic.Cleared(hv, T(71));
      run(71, 100);
      EXPECT_EQ(log, (Timed{{41, Rel(hv, true)}, {71, Rel(av)}}));
      b.logic.Cleared(av, T(101));
    } else {  // HV after confirm_delay (1.5 s), the AV after it cleared
      run(41, 80);
      EXPECT_EQ(log, (Timed{{56, Rel(hv)}}));
      b.logic.Cleared(hv, T(81));
      run(81, 100);
      EXPECT_EQ(log, (Timed{{56, Rel(hv)}, {81, Rel(av)}}));
      b.logic.Cleared(av, T(101));
    }
    // Finished once, after both cleared, with what happened.
    const std::vector<EncounterOutcome> done = b.logic.TakeFinished();
    ASSERT_EQ(done.size(), 1u);
    const EncounterOutcome& e = done[0];
    EXPECT_EQ(e.av, av);
    EXPECT_EQ(e.hv, hv);
    EXPECT_EQ(e.av_movement, kNs);
    EXPECT_EQ(e.hv_movement, kEs);
    EXPECT_DOUBLE_EQ(e.time, T(10));
    EXPECT_DOUBLE_EQ(e.decided_at, T(41));
    EXPECT_EQ(e.draw.goes_first, c.av_goes);
    EXPECT_DOUBLE_EQ(e.draw.nudge_distance, 1.64);
    EXPECT_DOUBLE_EQ(e.reading.observed, 1.6410004);
    EXPECT_EQ(e.reading.drives_if_clear, c.hv_dc);
    EXPECT_FALSE(e.collision);
    EXPECT_TRUE(b.logic.TakeFinished().empty());
    EXPECT_EQ(b.logic.Encounters(), 0);
    EXPECT_TRUE(b.Run(101, 150).empty());  // nobody released twice
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllFourOutcomes, Encounter,
    ::testing::Values(EncounterCase{"AvGoesHvDr", true, false},
                      EncounterCase{"AvGoesHvDc", true, true},
                      EncounterCase{"AvWaitsHvDr", false, false},
                      EncounterCase{"AvWaitsHvDc", false, true}),
    [](const ::testing::TestParamInfo<EncounterCase>& i) { return std::string(i.param.name); });

TEST(JunctionLogic, AnUnnudgedEncounterStillWaitsForNudgeDone) {
  // A draw without a nudge commands a creep of 0 m; the HV decides only once
  // the controller reports the (zero) displacement.
  Bench b;
  b.logic.Arrive(1, kAV, kNs, T(0));
  b.logic.Arrive(2, kHV, kWs, T(2));
  const std::vector<Command> cs = b.logic.Decide(T(10), b.env, b.model);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_EQ(cs[0].kind, Kind::kStartNudge);
  EXPECT_EQ(cs[0].vehicle, 1);
  EXPECT_EQ(cs[0].distance, 0.0);
  EXPECT_TRUE(b.Run(11, 30).empty());
  b.logic.NudgeDone(1, 0.0, T(31), b.model);
  EXPECT_EQ(b.At(31), std::vector<Cmd>{Rel(2, true)});  // intent stop, DR
}

TEST(JunctionLogic, NudgeDoneForAVehicleInNoEncounterIsALogicError) {
  Bench b;
  b.logic.Arrive(1, kAV, kNs, T(0));
  try {
    b.logic.NudgeDone(1, 0.0, T(1), b.model);
    ADD_FAILURE() << "no exception";
  } catch (const std::logic_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("B1"));
  }
}

TEST(JunctionLogic, TheWindowDecidesWhetherTwoHeadsMeet) {
  // The second head ready 0.9 s after the first: they meet. 1.2 s after: the
  // first had looked long enough and went alone.
  {
    Bench b;
    b.logic.Arrive(1, kAV, kNs, T(0));
    b.logic.Arrive(2, kHV, kEs, T(9));
    EXPECT_EQ(b.Run(0, 10), (Timed{{10, Nudge(1)}}));
  }
  {
    Bench b;
    b.logic.Arrive(1, kAV, kNs, T(0));
    EXPECT_EQ(b.Run(0, 11), (Timed{{10, Rel(1)}}));
    b.logic.Arrive(2, kHV, kEs, T(12));
    EXPECT_TRUE(b.Run(12, 60).empty());  // the AV is inside
    b.logic.Cleared(1, T(61));
    EXPECT_EQ(b.Run(61, 80), (Timed{{71, Rel(2)}}));
    EXPECT_TRUE(b.model.drawn.empty());
  }
}

// ------------------------------------------------------------------ two of a kind
TEST(JunctionLogic, TwoOfAKindGoByArrivalTheSecondAfterTheFirstCleared) {
  for (VehicleKind kind : {kAV, kHV}) {
    Bench b;
    b.logic.Arrive(5, kind, kEs, T(0));
    b.logic.Arrive(4, kind, kNs, T(5));
    EXPECT_EQ(b.Run(0, 40), (Timed{{10, Rel(5)}}));
    b.logic.Cleared(5, T(41));
    EXPECT_EQ(b.Run(41, 60), (Timed{{51, Rel(4)}}));
    EXPECT_TRUE(b.model.drawn.empty());
  }
  // Same arrival time: the lower approach first (north before east).
  Bench b;
  b.logic.Arrive(5, kHV, kEs, T(0));
  b.logic.Arrive(4, kHV, kNs, T(0));
  EXPECT_EQ(b.Run(0, 10), (Timed{{10, Rel(4)}}));
}

// ------------------------------------------------------------------ concurrency
TEST(JunctionLogic, NonConflictingMovementsGoConcurrently) {
  // Opposite straights, a right turn beside a straight, right turns of all four
  // approaches: each goes after its own window, whatever the kinds, no encounter.
  const std::vector<std::vector<int>> sets = {
      {kNs, kSs}, {kEs, kWs}, {kNr, kSs}, {kNr, kEr, kSr, kWr}, {kNl, kEr}};
  for (const auto& set : sets) {
    for (int a : set)
      for (int c : set) ASSERT_FALSE(B1().Conflict(a, c));
    Bench b;
    Timed expect;
    for (std::size_t k = 0; k < set.size(); ++k) {
      b.logic.Arrive(static_cast<int>(k), k % 2 ? kHV : kAV, set[k], T(static_cast<int>(3 * k)));
      expect.push_back({10 + static_cast<int>(3 * k), Rel(static_cast<int>(k))});
    }
    EXPECT_EQ(b.Run(0, 30), expect);
    EXPECT_EQ(b.logic.InJunction(), static_cast<int>(set.size()));
    EXPECT_TRUE(b.model.drawn.empty());
  }
}

TEST(JunctionLogic, TurnsAndMergesFormEncountersOnlyWhenTheyConflict) {
  // Every pair of movements from different approaches, AV first by 0.5 s:
  // an encounter exactly when SUMO's foes say they conflict.
  const JunctionSpec spec = B1();
  int encounters = 0, concurrent = 0;
  for (int a = 0; a < 12; ++a) {
    for (int h = 0; h < 12; ++h) {
      if (spec.movements[a].approach == spec.movements[h].approach) continue;
      Bench b;
      b.logic.Arrive(1, kAV, a, T(0));
      b.logic.Arrive(2, kHV, h, T(5));
      const Timed log = b.Run(0, 20);
      if (spec.Conflict(a, h)) {
        EXPECT_EQ(log, (Timed{{10, Nudge(1)}})) << a << " vs " << h;
        ++encounters;
      } else {
        EXPECT_EQ(log, (Timed{{10, Rel(1)}, {15, Rel(2)}})) << a << " vs " << h;
        EXPECT_TRUE(b.model.drawn.empty());
        ++concurrent;
      }
    }
  }
  EXPECT_EQ(encounters, 60);  // 30 conflicting pairs, both ways round
  EXPECT_EQ(concurrent, 108 - 60);
  // Named cases: a left turn against the opposite straight; a right turn and a
  // left turn merging into the same exit.
  for (auto [a, h] : {std::pair{kNl, kSs}, std::pair{kSr, kNl}, std::pair{kNr, kSl}}) {
    Bench b;
    b.logic.Arrive(1, kAV, a, T(0));
    b.logic.Arrive(2, kHV, h, T(5));
    EXPECT_EQ(b.Run(0, 10), (Timed{{10, Nudge(1)}})) << a << " vs " << h;
  }
}

// ------------------------------------------------------------------ three and four heads
TEST(JunctionLogic, AThirdHeadWaitsForThePairwiseEncounterThenGoes) {
  // HV east straight meets the AV north straight; the AV south straight also
  // conflicts with the HV (not with the other AV): it waits for the encounter
  // to clear, then looks again and goes alone.
  Bench b;
  b.model.draws[1] = Draw(false, 0);
  b.logic.Arrive(3, kHV, kEs, T(0));
  b.logic.Arrive(1, kAV, kNs, T(2));
  b.logic.Arrive(2, kAV, kSs, T(4));
  EXPECT_EQ(b.Run(0, 10), (Timed{{10, Nudge(1)}}));
  EXPECT_EQ(b.model.drawn, (std::vector<std::pair<int, int>>{{1, 3}}));
  EXPECT_EQ(b.logic.Waiting(), 1);
  EXPECT_TRUE(b.Run(11, 11).empty());
  b.logic.NudgeDone(1, 0.0, T(12), b.model);
  EXPECT_EQ(b.Run(12, 30), (Timed{{12, Rel(3, true)}}));
  b.logic.Cleared(3, T(31));
  // The waiting AV goes once the HV cleared; AV 2 was blocked by the HV until
  // then, looks 1 s and goes (AV 1's movement does not conflict with it).
  EXPECT_EQ(b.Run(31, 45), (Timed{{31, Rel(1)}, {41, Rel(2)}}));
  EXPECT_EQ(b.logic.Waiting(), 0);
  EXPECT_EQ(b.logic.InJunction(), 2);  // the encounter's AV and AV 2
  b.logic.Cleared(1, T(46));
  ASSERT_EQ(b.logic.TakeFinished().size(), 1u);
  EXPECT_EQ(b.model.drawn.size(), 1u);
}

TEST(JunctionLogic, AThirdHeadWaitsWhileAnEncounterBlocksItsMovement) {
  // HV E straight meets AV N straight; the AV S straight conflicts with the
  // HV's movement: it may go only after the HV has cleared, then looks 1 s.
  Bench b;
  b.model.draws[1] = Draw(true, 1.64);
  b.model.dc[3] = true;
  b.logic.Arrive(3, kHV, kEs, T(0));
  b.logic.Arrive(1, kAV, kNs, T(2));
  b.logic.Arrive(2, kAV, kSs, T(4));
  EXPECT_EQ(b.Run(0, 10), (Timed{{10, Nudge(1)}}));
  EXPECT_TRUE(b.Run(11, 19).empty());
  b.logic.NudgeDone(1, 1.64, T(20), b.model);
  EXPECT_EQ(b.Run(20, 30), (Timed{{20, Rel(1)}}));
  b.logic.Cleared(1, T(31));
  EXPECT_EQ(b.Run(31, 40), (Timed{{31, Rel(3)}}));
  b.logic.Cleared(3, T(41));
  EXPECT_EQ(b.Run(41, 60), (Timed{{51, Rel(2)}}));
  EXPECT_EQ(b.model.drawn.size(), 1u);
  ASSERT_EQ(b.logic.TakeFinished().size(), 1u);
}

TEST(JunctionLogic, FourWayMeetingFormsTwoPairwiseEncountersInTurn) {
  // Four straights: N (AV), E (HV), S (AV), W (HV). Crossing pairs conflict,
  // opposite ones do not. The first two meet; the other two are blocked by
  // that encounter and meet each other once it cleared.
  Bench b;
  b.logic.Arrive(1, kAV, kNs, T(0));
  b.logic.Arrive(2, kHV, kEs, T(1));
  b.logic.Arrive(3, kAV, kSs, T(2));
  b.logic.Arrive(4, kHV, kWs, T(3));
  b.model.draws[1] = Draw(true, 1.64);  // the AV goes, the HV drives recklessly
  EXPECT_EQ(b.Run(0, 30), (Timed{{10, Nudge(1)}}));
  EXPECT_EQ(b.model.drawn, (std::vector<std::pair<int, int>>{{1, 2}}));
  EXPECT_EQ(b.logic.Waiting(), 2);
  b.logic.NudgeDone(1, 1.64, T(31), b.model);
  EXPECT_EQ(b.Run(31, 50), (Timed{{31, Rel(1)}, {31, Rel(2, true)}}));
  b.logic.Cleared(1, T(51));
  b.logic.Cleared(2, T(51));
  // AV 3 and HV 4 were both blocked until then: they meet 1 s later.
  EXPECT_EQ(b.Run(51, 61), (Timed{{61, Nudge(3)}}));
  EXPECT_EQ(b.model.drawn, (std::vector<std::pair<int, int>>{{1, 2}, {3, 4}}));
  b.model.dc[4] = true;
  b.logic.NudgeDone(3, 0.0, T(62), b.model);
  EXPECT_EQ(b.Run(62, 80), (Timed{{72, Rel(4)}}));  // confirm_delay after deciding
  b.logic.Cleared(4, T(81));
  EXPECT_EQ(b.Run(81, 90), (Timed{{81, Rel(3)}}));
  b.logic.Cleared(3, T(91));
  EXPECT_EQ(b.logic.Waiting() + b.logic.InJunction() + b.logic.Encounters(), 0);
  EXPECT_EQ(b.logic.TakeFinished().size(), 2u);
}

TEST(JunctionLogic, TwoDisjointEncountersRunAtOnceAndCollisionsAreAttributedToTheirPair) {
  // N right + E straight merge into A1; S right + W straight merge into C1;
  // neither pair conflicts with the other.
  Bench b;
  b.logic.Arrive(1, kAV, kNr, T(0));
  b.logic.Arrive(2, kHV, kEs, T(1));
  b.logic.Arrive(3, kAV, kSr, T(2));
  b.logic.Arrive(4, kHV, kWs, T(3));
  b.model.draws[1] = Draw(true, 1.64);
  b.model.draws[3] = Draw(true, 1.64);
  EXPECT_EQ(b.Run(0, 12), (Timed{{10, Nudge(1)}, {12, Nudge(3)}}));
  EXPECT_EQ(b.logic.Encounters(), 2);
  EXPECT_FALSE(b.logic.Collided(1, 4));  // not a pair
  EXPECT_FALSE(b.logic.Collided(2, 3));
  EXPECT_FALSE(b.logic.Collided(1, 99));
  EXPECT_TRUE(b.logic.Collided(2, 1));  // either order
  b.logic.NudgeDone(1, 1.64, T(20), b.model);
  b.logic.NudgeDone(3, 1.64, T(20), b.model);
  EXPECT_EQ(b.At(20), (std::vector<Cmd>{Rel(1), Rel(2, true), Rel(3), Rel(4, true)}));
  for (int v : {1, 2, 3, 4}) b.logic.Cleared(v, T(40));
  std::vector<EncounterOutcome> done = b.logic.TakeFinished();
  ASSERT_EQ(done.size(), 2u);
  std::sort(done.begin(), done.end(),
            [](const EncounterOutcome& x, const EncounterOutcome& y) { return x.av < y.av; });
  EXPECT_TRUE(done[0].collision);
  EXPECT_FALSE(done[1].collision);
  EXPECT_FALSE(b.logic.Collided(1, 2));  // finished: no longer in progress
}

// ------------------------------------------------------------------ FCFS, no starvation
TEST(JunctionLogic, AHeadBlockedByAVehicleInsideKeepsItsTurnAgainstALaterStream) {
  // A stream on the north approach: each vehicle moves up to the line 1.5 s
  // after the one before it was released and clears 2.5 s after its release.
  // HV A (east straight, conflicting) arrives while the first north vehicle
  // is inside. A arrived before every later north vehicle, so it goes next:
  // a continuous stream on one approach must not starve a conflicting head.
  Bench b;
  std::map<int, int> released;  // vehicle -> tenth
  int north_at_line = -1, next_north = 100, last_north_release = -1000;
  int north_before_a = 0;
  for (int t = 0; t <= 600; ++t) {
    if (north_at_line < 0 && next_north < 110 && t >= last_north_release + 15) {
      north_at_line = next_north++;
      b.logic.Arrive(north_at_line, kHV, kNs, T(t));
    }
    if (t == 15) b.logic.Arrive(1, kHV, kEs, T(t));
    for (const auto& [veh, at] : released)
      if (t == at + 25) b.logic.Cleared(veh, T(t));
    for (const Cmd& c : b.At(t)) {
      ASSERT_EQ(c.kind, Kind::kRelease);
      released[c.vehicle] = t;
      if (c.vehicle != 1) {
        north_at_line = -1;
        last_north_release = t;
        if (!released.count(1)) ++north_before_a;
      }
    }
  }
  ASSERT_TRUE(released.count(1)) << "never released";
  EXPECT_EQ(north_before_a, 1) << "A waited for " << north_before_a
                               << " north vehicles that arrived after it; released at "
                               << T(released[1]) << " s";
  EXPECT_EQ(released.size(), 11u);
}

// ------------------------------------------------------------------ keep clear
TEST(JunctionLogic, AHeadWithoutRoomIsSkippedBlocksNobodyAndGoesOnceThereIsRoom) {
  Bench b;
  b.env.no_room_vehicles = {1};
  b.logic.Arrive(1, kAV, kNs, T(0));  // its exit is full
  b.logic.Arrive(2, kHV, kEs, T(3));  // conflicting, within the window: no encounter
  EXPECT_EQ(b.Run(0, 30), (Timed{{13, Rel(2)}}));
  EXPECT_TRUE(b.model.drawn.empty());
  EXPECT_EQ(b.logic.Waiting(), 1);
  b.env.no_room_vehicles.clear();
  EXPECT_TRUE(b.Run(31, 50).empty());  // room now, but HV 2 is inside
  b.logic.Cleared(2, T(51));
  EXPECT_EQ(b.Run(51, 70), (Timed{{61, Rel(1)}}));
  // A head without room is never released, however long it waits.
  Bench c;
  c.env.no_room_movements = {kWl};
  c.logic.Arrive(9, kHV, kWl, T(0));
  EXPECT_TRUE(c.Run(0, 3000).empty());
  EXPECT_GT(c.env.room_calls, 0);
  c.env.no_room_movements.clear();
  EXPECT_EQ(c.Run(3001, 3001), (Timed{{3001, Rel(9)}}));
}

// ------------------------------------------------------------------ two-way stop
JunctionSpec TwoWayB1() {
  // East-west is the major road: its links are not stop links.
  JunctionSpec s = B1(Rule::kTwoWay);
  for (Movement& m : s.movements) m.controlled = m.approach == 0 || m.approach == 2;
  return s;
}

TEST(JunctionLogic, TwoWayStopHoldsAMinorHeadUntilTheMajorRoadIsClear) {
  Bench b(TwoWayB1());
  b.env.major_busy = {kNs};
  b.logic.Arrive(1, kHV, kNs, T(0));
  EXPECT_TRUE(b.Run(0, 600).empty());
  EXPECT_GT(b.env.major_calls, 0);
  b.env.major_busy.clear();
  EXPECT_EQ(b.Run(601, 601), (Timed{{601, Rel(1)}}));
  // Minor heads meet each other as at an all-way stop: N left vs S straight.
  Bench c(TwoWayB1());
  c.logic.Arrive(1, kAV, kNl, T(0));
  c.logic.Arrive(2, kHV, kSs, T(4));
  EXPECT_EQ(c.Run(0, 10), (Timed{{10, Nudge(1)}}));
  // A minor head waiting for the gap does not meet a later one nor let it
  // cut in on a conflicting movement.
  Bench d(TwoWayB1());
  d.env.major_busy = {kNl};
  d.logic.Arrive(1, kAV, kNl, T(0));
  d.logic.Arrive(2, kHV, kSs, T(4));
  EXPECT_TRUE(d.Run(0, 100).empty());
  EXPECT_TRUE(d.model.drawn.empty());
  d.env.major_busy.clear();
  EXPECT_EQ(d.Run(101, 101), (Timed{{101, Nudge(1)}}));
}

TEST(JunctionLogic, AllWayStopNeverAsksForTheMajorRoad) {
  Bench b;
  b.env.major_busy = {kNs, kEs};
  b.logic.Arrive(1, kHV, kNs, T(0));
  b.logic.Arrive(2, kHV, kSs, T(0));
  EXPECT_EQ(b.Run(0, 10), (Timed{{10, Rel(1)}, {10, Rel(2)}}));
  EXPECT_EQ(b.env.major_calls, 0);
}

// ------------------------------------------------------------------ invariants
// Random arrivals on all 12 movements of B1, random kinds, crossing times,
// nudge times, AV draws, HV readings and keep-clear refusals, with a fixed
// seed. Checked at every step:
//  - no two vehicles with conflicting movements are in the junction at once
//    (released and not cleared, or in an encounter), except an encounter's
//    AV and HV both released when the HV drives recklessly (the game's
//    collision);
//  - FCFS: when a head leaves the queue (released, or into an encounter), no
//    head still waiting with room on a conflicting movement arrived before it;
//  - encounters are pairwise, of an AV and an HV on conflicting movements, a
//    vehicle in at most one at a time, each finished exactly once;
// and at the end every vehicle was released and cleared.
struct SimVeh {
  int id = -1;
  VehicleKind kind = kHV;
  int movement = 0;
  double queued = 0;    // joined its approach's queue
  double cross = 0;     // s from release to cleared
  double nudge = 0;     // s a nudge takes
  double arrived = -1;  // at the line (Arrive)
  double released = -1, cleared = -1;
  bool reckless = false;
  int partner = -1;  // the other vehicle of its encounter (while in one)
  double nudge_done_at = -1;
};

struct PropertyStats {
  long encounters = 0, releases = 0, dr_overlaps = 0, refusals = 0;
  double max_head_wait = 0;
};

double U01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

struct RandomModel : EncounterModel {
  std::mt19937_64* rng = nullptr;
  std::vector<SimVeh>* v = nullptr;
  const JunctionSpec* spec = nullptr;
  long formed = 0;
  AvDraw Draw(int av, int hv) override {
    SimVeh& a = (*v)[av];
    SimVeh& h = (*v)[hv];
    EXPECT_EQ(a.kind, kAV);
    EXPECT_EQ(h.kind, kHV);
    EXPECT_TRUE(spec->Conflict(a.movement, h.movement)) << av << " and " << hv;
    EXPECT_EQ(a.partner, -1) << "AV " << av << " in two encounters";
    EXPECT_EQ(h.partner, -1) << "HV " << hv << " in two encounters";
    a.partner = hv;
    h.partner = av;
    ++formed;
    const bool go = U01(*rng) < 0.4;
    return ::taebp::junction::Draw(go, U01(*rng) < 0.5 ? 1.64 : 0.0);
  }
  HvReading Read(int, int, double observed) override {
    HvReading r;
    r.observed = observed;
    r.drives_if_clear = U01(*rng) < 0.5;
    return r;
  }
};

PropertyStats RunRandomJunction(std::uint32_t seed, int vehicles, double rate_per_approach) {
  std::mt19937_64 rng(seed);
  const JunctionSpec spec = B1();
  JunctionLogic logic(spec, Timing{1.0, 1.0});

  std::vector<SimVeh> v(vehicles);
  std::vector<std::vector<int>> queue(4);
  std::vector<double> clock(4, 0.0);
  for (int i = 0; i < vehicles; ++i) {
    const int ap = static_cast<int>(U01(rng) * 4) % 4;
    clock[ap] += -std::log1p(-U01(rng)) / rate_per_approach;
    v[i].id = i;
    v[i].kind = U01(rng) < 0.5 ? kAV : kHV;
    v[i].movement = ap * 3 + static_cast<int>(U01(rng) * 3) % 3;
    v[i].queued = clock[ap];
    v[i].cross = 1.0 + 3.0 * U01(rng);
    v[i].nudge = 0.2 + 2.0 * U01(rng);
    queue[ap].push_back(i);  // in queueing order
  }
  std::vector<std::size_t> next(4, 0);  // next vehicle of each queue to reach the line
  std::vector<int> at_line(4, -1);      // at the line, not yet released
  std::vector<double> last_release(4, -1e9);

  // Keep-clear: each exit refuses in 15% of random 5 s slots.
  auto room = [&](int movement, double t) {
    std::seed_seq s{seed, static_cast<std::uint32_t>(kExit[movement]),
                    static_cast<std::uint32_t>(t / 5.0)};
    std::mt19937 r(s);
    return r() % 100 >= 15;
  };
  double now = 0;
  FakeEnv env;
  env.room = [&](int movement, int) { return room(movement, now); };
  RandomModel model;
  model.rng = &rng;
  model.v = &v;
  model.spec = &spec;

  PropertyStats stats;
  std::set<std::pair<int, int>> finished;
  auto waiting = [&](int ap) {  // a head waiting at the line (not in an encounter)
    const int h = at_line[ap];
    return h >= 0 && v[h].partner < 0 ? h : -1;
  };
  const int max_steps = 300000;  // 30000 s
  int step = 0;
  for (; step < max_steps && !::testing::Test::HasFailure(); ++step) {
    now = step / 10.0;
    // The next vehicle reaches the line 1.5 s after the previous one was released.
    for (int ap = 0; ap < 4; ++ap) {
      if (at_line[ap] >= 0 || next[ap] >= queue[ap].size()) continue;
      const int i = queue[ap][next[ap]];
      if (v[i].queued > now || now < last_release[ap] + 1.5) continue;
      at_line[ap] = i;
      ++next[ap];
      v[i].arrived = now;
      logic.Arrive(i, v[i].kind, v[i].movement, now);
    }
    for (SimVeh& x : v) {
      if (x.released >= 0 && x.cleared < 0 && now >= x.released + x.cross) {
        x.cleared = now;
        logic.Cleared(x.id, now);
      }
      if (x.nudge_done_at >= 0 && now >= x.nudge_done_at) {
        x.nudge_done_at = -1;
        logic.NudgeDone(x.id, 0.0, now, model);
      }
    }
    std::vector<int> waiting_before(4);
    for (int ap = 0; ap < 4; ++ap) waiting_before[ap] = waiting(ap);
    for (const Command& c : logic.Decide(now, env, model)) {
      SimVeh& x = v[c.vehicle];
      const int ap = x.movement / 3;
      if (c.kind == Kind::kStartNudge) {
        EXPECT_EQ(x.kind, kAV);
        EXPECT_GE(x.partner, 0) << "a nudge without an encounter";
        x.nudge_done_at = now + x.nudge;
        ++stats.encounters;
      } else {
        EXPECT_LT(x.released, 0) << "vehicle " << x.id << " released twice";
        EXPECT_EQ(at_line[ap], x.id) << "released a vehicle that is not at the line";
        x.released = now;
        x.reckless = c.reckless;
        at_line[ap] = -1;
        last_release[ap] = now;
        ++stats.releases;
      }
    }
    // FCFS among conflicting heads: what left the queue this step against
    // what still waits.
    std::vector<int> left;
    for (int ap = 0; ap < 4; ++ap)
      if (waiting_before[ap] >= 0 && waiting(ap) != waiting_before[ap])
        left.push_back(waiting_before[ap]);
    for (int id : left) {
      stats.max_head_wait = std::max(stats.max_head_wait, now - v[id].arrived);
      for (int ap = 0; ap < 4; ++ap) {
        const int w = waiting(ap);
        if (w < 0 || !spec.Conflict(v[w].movement, v[id].movement)) continue;
        if (!room(v[w].movement, now)) {
          ++stats.refusals;
          continue;
        }
        EXPECT_GE(v[w].arrived, v[id].arrived)
            << "t = " << now << ": vehicle " << id << " (movement " << v[id].movement
            << ", arrived " << v[id].arrived << ") left the queue before conflicting head " << w
            << " (movement " << v[w].movement << ", arrived " << v[w].arrived << ")";
      }
    }
    // Conflicting vehicles in the junction at once.
    std::vector<int> inside;
    for (const SimVeh& x : v)
      if (x.cleared < 0 && (x.released >= 0 || x.partner >= 0)) inside.push_back(x.id);
    for (std::size_t a = 0; a < inside.size(); ++a) {
      for (std::size_t c = a + 1; c < inside.size(); ++c) {
        const SimVeh& x = v[inside[a]];
        const SimVeh& y = v[inside[c]];
        if (!spec.Conflict(x.movement, y.movement)) continue;
        if (x.partner != y.id) {
          ADD_FAILURE() << "t = " << now << ": " << x.id << " (movement " << x.movement << ") and "
                        << y.id << " (movement " << y.movement << ") in the junction at once";
        } else if (x.released >= 0 && y.released >= 0) {
          const SimVeh& hv = x.kind == kHV ? x : y;
          EXPECT_TRUE(hv.reckless) << "t = " << now << ": encounter " << x.id << "/" << y.id
                                   << " released into the junction together";
          ++stats.dr_overlaps;
        }
      }
    }
    for (const EncounterOutcome& e : logic.TakeFinished()) {
      EXPECT_TRUE(finished.insert({e.av, e.hv}).second) << "finished twice";
      EXPECT_GE(v[e.av].cleared, 0);
      EXPECT_GE(v[e.hv].cleared, 0);
      EXPECT_EQ(v[e.av].partner, e.hv);
      v[e.av].partner = v[e.hv].partner = -1;
    }
    bool all = true;
    for (const SimVeh& x : v) all &= x.cleared >= 0;
    if (all) break;
  }
  EXPECT_LT(step, max_steps) << "not every vehicle cleared within the simulated time";
  for (const SimVeh& x : v) {
    EXPECT_GE(x.released, 0) << "vehicle " << x.id << " never released";
    EXPECT_GE(x.cleared, 0) << "vehicle " << x.id << " never cleared";
  }
  EXPECT_EQ(static_cast<long>(finished.size()), model.formed);
  EXPECT_EQ(stats.encounters, model.formed);
  EXPECT_EQ(logic.Waiting(), 0);
  EXPECT_EQ(logic.InJunction(), 0);
  EXPECT_EQ(logic.Encounters(), 0);
  return stats;
}

TEST(JunctionLogicProperty, RandomArrivalsKeepTheInvariants) {
  // Light, medium and saturated demand (vehicles per second per approach).
  for (auto [seed, rate] : {std::pair{1u, 0.05}, std::pair{2u, 0.15}, std::pair{3u, 0.5}}) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", rate " + std::to_string(rate));
    const PropertyStats s = RunRandomJunction(seed, 600, rate);
    // The run exercised what it checks.
    EXPECT_GT(s.encounters, 20);
    EXPECT_GT(s.refusals, 0);
    EXPECT_EQ(s.releases, 600);
    std::cout << "seed " << seed << " rate " << rate << ": " << s.encounters << " encounters, "
              << s.dr_overlaps << " step-pairs of DR overlap, " << s.refusals
              << " keep-clear exclusions, longest head wait " << s.max_head_wait << " s\n";
  }
}

}  // namespace
}  // namespace taebp::junction
