// Right of way at the figure-8's two-approach all-way stop, through the
// general junction::JunctionLogic: a lone head looks both ways for
// `arrival_window`; heads ready within the window meet (AV + HV: an
// encounter; two of a kind: by arrival, ties to approach 0); readiness
// starts when the junction becomes free for a head.
#include "taebp/junction/junction_logic.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace taebp::junction {
namespace {

// Two crossing movements, one per approach (E_C -> C_W, W_C -> C_E).
JunctionSpec Figure8() {
  JunctionSpec s;
  s.id = "C";
  s.rule = Rule::kAllWay;
  s.approaches = 2;
  s.movements = {Movement{0, true, 's', "E_C_0", "C_W_0"}, Movement{1, true, 's', "W_C_0", "C_E_0"}};
  s.conflict = {{false, true}, {true, false}};
  return s;
}

struct OpenWorld : Environment {
  bool ExitHasRoom(int, int, int) override { return true; }
  bool MajorClear(int) override { return true; }
};

// Draws "Stop, no nudge" (or "Go" with go = true) and reads "drive
// recklessly"; counts the calls.
struct FixedModel : EncounterModel {
  int draws = 0;
  bool go = false;
  bool game = true;  // what Game answers
  std::vector<std::pair<int, int>> asked;  // (AV, HV) Game was asked about
  bool Game(int av, int hv, int, int) override {
    asked.emplace_back(av, hv);
    return game;
  }
  AvDraw Draw(int, int) override {
    ++draws;
    AvDraw d;
    d.intent_go = d.goes_first = go;
    return d;
  }
  HvReading Read(int, int, double observed) override {
    HvReading r;
    r.observed = observed;
    return r;
  }
};

struct Harness {
  JunctionLogic logic{Figure8(), Timing{1.0, 1.0}};
  OpenWorld env;
  FixedModel model;
  std::vector<Command> Decide(double now) { return logic.Decide(now, env, model); }
};

bool Released(const std::vector<Command>& cmds, int vehicle) {
  for (const Command& c : cmds)
    if (c.kind == Command::Kind::kRelease && c.vehicle == vehicle) return true;
  return false;
}
bool Nudges(const std::vector<Command>& cmds, int vehicle) {
  for (const Command& c : cmds)
    if (c.kind == Command::Kind::kStartNudge && c.vehicle == vehicle) return true;
  return false;
}

TEST(RightOfWay, NobodyWaitingDoesNothing) {
  Harness h;
  EXPECT_TRUE(h.Decide(100.0).empty());
  EXPECT_EQ(h.model.draws, 0);
}

TEST(RightOfWay, LoneHeadWaitsTheWindowThenGoes) {
  for (VehicleKind kind : {VehicleKind::kAV, VehicleKind::kHV}) {
    for (int movement : {0, 1}) {
      Harness h;
      h.logic.Arrive(7, kind, movement, 12.0);
      // Looking both ways: still waiting until arrival + window.
      for (double now : {12.0, 12.5, 12.99}) EXPECT_TRUE(h.Decide(now).empty()) << now;
      const std::vector<Command> cmds = h.Decide(13.0);
      ASSERT_EQ(cmds.size(), 1u);
      EXPECT_TRUE(Released(cmds, 7));
      EXPECT_FALSE(cmds[0].reckless);
      EXPECT_EQ(h.logic.Waiting(), 0);
      EXPECT_EQ(h.logic.InJunction(), 1);
    }
  }
  // A zero window releases at once.
  JunctionLogic zero(Figure8(), Timing{0.0, 1.0});
  OpenWorld env;
  FixedModel model;
  zero.Arrive(3, VehicleKind::kHV, 0, 5.0);
  EXPECT_TRUE(Released(zero.Decide(5.0, env, model), 3));
}

TEST(RightOfWay, AvAndHvWithinTheWindowMeetAndTheAvSignals) {
  for (int av_movement : {0, 1}) {
    for (double gap : {0.0, 0.4, 1.0}) {
      for (bool av_earlier : {true, false}) {
        Harness h;
        const double t_av = av_earlier ? 20.0 : 20.0 + gap;
        const double t_hv = av_earlier ? 20.0 + gap : 20.0;
        h.logic.Arrive(1, VehicleKind::kAV, av_movement, t_av);
        h.logic.Arrive(2, VehicleKind::kHV, 1 - av_movement, t_hv);
        const std::vector<Command> cmds = h.Decide(21.0);
        ASSERT_EQ(cmds.size(), 1u) << gap;
        EXPECT_TRUE(Nudges(cmds, 1));
        EXPECT_EQ(h.model.draws, 1);
        EXPECT_EQ(h.logic.Encounters(), 1);
        EXPECT_EQ(h.logic.Waiting(), 0);
      }
    }
  }
}

// An AV and an HV that meet where both proceeding would not collide
// (EncounterModel::Game: false) are not the paper's game: no draw, no nudge;
// the earlier goes as two of a kind would, the other after it cleared.
TEST(RightOfWay, AvHvMeetingThatIsNotAGameGoesByArrival) {
  for (bool av_earlier : {true, false}) {
    Harness h;
    h.model.game = false;
    h.logic.Arrive(1, VehicleKind::kAV, 0, av_earlier ? 20.0 : 20.3);
    h.logic.Arrive(2, VehicleKind::kHV, 1, av_earlier ? 20.3 : 20.0);
    std::vector<Command> cmds = h.Decide(21.0);
    ASSERT_EQ(cmds.size(), 1u);
    const int first = av_earlier ? 1 : 2, second = av_earlier ? 2 : 1;
    EXPECT_TRUE(Released(cmds, first));
    EXPECT_EQ(h.model.draws, 0);
    EXPECT_EQ(h.logic.Encounters(), 0);
    EXPECT_EQ(h.logic.NonGameMeetings(), 1);
    ASSERT_EQ(h.model.asked.size(), 1u);
    EXPECT_EQ(h.model.asked[0], std::make_pair(1, 2)) << "asked with the AV first";
    h.logic.Cleared(first, 23.0);
    EXPECT_TRUE(h.Decide(23.5).empty());
    EXPECT_TRUE(Released(h.Decide(24.0), second));
    EXPECT_EQ(h.model.draws, 0);
  }
  // The same meeting as a game is an encounter.
  Harness g;
  g.logic.Arrive(1, VehicleKind::kAV, 0, 20.0);
  g.logic.Arrive(2, VehicleKind::kHV, 1, 20.3);
  EXPECT_TRUE(Nudges(g.Decide(21.0), 1));
  EXPECT_EQ(g.logic.NonGameMeetings(), 0);
  // Two of a kind never ask.
  Harness k;
  k.logic.Arrive(1, VehicleKind::kHV, 0, 20.0);
  k.logic.Arrive(2, VehicleKind::kHV, 1, 20.3);
  EXPECT_TRUE(Released(k.Decide(21.0), 1));
  EXPECT_TRUE(k.model.asked.empty());
}

TEST(RightOfWay, BeyondTheWindowTheEarlierGoes) {
  for (VehicleKind ka : {VehicleKind::kAV, VehicleKind::kHV}) {
    for (VehicleKind kb : {VehicleKind::kAV, VehicleKind::kHV}) {
      for (bool early_on_0 : {true, false}) {
        Harness h;
        h.logic.Arrive(10, ka, early_on_0 ? 0 : 1, 30.0);
        EXPECT_TRUE(h.Decide(30.9).empty());
        h.logic.Arrive(11, kb, early_on_0 ? 1 : 0, 31.2);
        // The early head had looked long enough before the other arrived.
        const std::vector<Command> cmds = h.Decide(31.2);
        ASSERT_EQ(cmds.size(), 1u);
        EXPECT_TRUE(Released(cmds, 10));
        EXPECT_EQ(h.model.draws, 0);
        // The other waits until the first has cleared, then looks again.
        EXPECT_TRUE(h.Decide(33.0).empty());
        h.logic.Cleared(10, 34.0);
        EXPECT_TRUE(h.Decide(34.0).empty());
        EXPECT_TRUE(h.Decide(34.9).empty());
        EXPECT_TRUE(Released(h.Decide(35.0), 11));
      }
    }
  }
}

TEST(RightOfWay, ReadinessNotArrivalDecidesWhoMeets) {
  // The AV arrives while a vehicle of the other approach is inside the
  // junction; the HV arrives long after, behind that vehicle (same movement,
  // not blocked) but after the AV (first come, first served: it waits).
  // When the junction clears at 40 the AV looks both ways and they meet.
  Harness h;
  h.logic.Arrive(9, VehicleKind::kHV, 1, 29.0);
  ASSERT_TRUE(Released(h.Decide(30.0), 9));
  h.logic.Arrive(1, VehicleKind::kAV, 0, 30.5);
  h.logic.Arrive(2, VehicleKind::kHV, 1, 38.0);
  EXPECT_TRUE(h.Decide(39.0).empty());
  h.logic.Cleared(9, 40.0);
  EXPECT_TRUE(h.Decide(40.5).empty());
  const std::vector<Command> cmds = h.Decide(41.0);
  EXPECT_TRUE(Nudges(cmds, 1));
  EXPECT_EQ(h.model.draws, 1);
}

TEST(RightOfWay, SameKindCrossByArrivalTiesToApproachZero) {
  for (VehicleKind kind : {VehicleKind::kAV, VehicleKind::kHV}) {
    for (bool first_on_1 : {true, false}) {
      // Both wait while an earlier encounter's AV (Go) and reckless HV are
      // both inside (each blocks the other movement's head) and are ready
      // together when both clear at 50; one arrived first.
      Harness h;
      h.model.go = true;
      h.logic.Arrive(98, VehicleKind::kAV, 0, 39.0);
      h.logic.Arrive(99, VehicleKind::kHV, 1, 39.0);
      ASSERT_TRUE(Nudges(h.Decide(40.0), 98));
      h.logic.NudgeDone(98, 0.0, 40.0, h.model);  // Go, DR: both at once
      const std::vector<Command> both = h.Decide(40.1);
      ASSERT_TRUE(Released(both, 98));
      ASSERT_TRUE(Released(both, 99));
      h.logic.Arrive(4, kind, 0, first_on_1 ? 48.0 : 44.0);
      h.logic.Arrive(5, kind, 1, 45.0);
      EXPECT_TRUE(h.Decide(46.6).empty());
      h.logic.Cleared(98, 50.0);
      h.logic.Cleared(99, 50.0);
      EXPECT_TRUE(h.Decide(50.0).empty());
      const std::vector<Command> cmds = h.Decide(51.0);
      ASSERT_EQ(cmds.size(), 1u);
      EXPECT_TRUE(Released(cmds, first_on_1 ? 5 : 4));
      EXPECT_EQ(h.model.draws, 1);  // only the earlier encounter drew
    }
    // A tie: approach 0 first, whatever the arrival order of the calls.
    for (bool zero_first : {true, false}) {
      Harness h;
      if (zero_first) h.logic.Arrive(8, kind, 0, 47.0);
      h.logic.Arrive(9, kind, 1, 47.0);
      if (!zero_first) h.logic.Arrive(8, kind, 0, 47.0);
      const std::vector<Command> cmds = h.Decide(48.0);
      ASSERT_EQ(cmds.size(), 1u);
      EXPECT_TRUE(Released(cmds, 8));
    }
  }
}

}  // namespace
}  // namespace taebp::junction
