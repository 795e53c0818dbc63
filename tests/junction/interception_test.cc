// The SUMO-free interception logic of one controlled junction
// (interception.h), driven with fake time, fake vehicles, a fake Environment
// (conflict area, standstill, keep-clear, major road gaps) and a fake
// EncounterModel (scripted AV draws and HV readings): who meets whom, that
// nobody else is ever commanded, and the paper's order of releases.
//
// The junction is a real one: B1 of
//   netgenerate --grid --grid.number 4 --default-junction-type allway_stop
//               --no-turnarounds true
// whose 12 links (request index = movement index) and <request foes> are
// copied below; tests/scenario/net_file_test.cc reads the same junction from
// a freshly generated net and checks these strings against it.
#include "taebp/junction/interception.h"

#include "interception_fixture.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace taebp::junction {
namespace {

using ::testing::HasSubstr;
using namespace fixture;  // NOLINT: the fixture is the tests' vocabulary

// Conflicts the tests rely on (the full matrix is checked against a freshly
// generated net in tests/scenario/net_file_test.cc).
TEST(B1Matrix, IsTheJunctionTheTestsAssume) {
  const JunctionSpec s = B1();
  EXPECT_FALSE(s.Conflict(kNs, kSs));  // opposite straights pass
  EXPECT_FALSE(s.Conflict(kEs, kWs));
  EXPECT_TRUE(s.Conflict(kNs, kEs));   // crossing straights
  EXPECT_TRUE(s.Conflict(kNs, kWs));
  EXPECT_TRUE(s.Conflict(kSs, kWs));
  EXPECT_TRUE(s.Conflict(kNr, kEs));   // merge into A1
  EXPECT_FALSE(s.Conflict(kNr, kSs));
  for (int i = 0; i < 12; ++i)
    for (int k = 0; k < 12; ++k)
      if (s.movements[i].approach == s.movements[k].approach) {
        EXPECT_FALSE(s.Conflict(i, k));
      }
}

TEST(JunctionSpec, ValidateRejectsMismatchedSizes) {
  JunctionSpec s = B1();
  s.conflict.pop_back();
  EXPECT_THROW(Interception(s, Timing{}), std::invalid_argument);
  s = B1();
  s.conflict[3].pop_back();
  EXPECT_THROW(Interception(s, Timing{}), std::invalid_argument);
  s = B1();
  s.movements[5].approach = 4;
  try {
    Interception logic(s, Timing{});
    ADD_FAILURE() << "accepted an approach out of range";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("B1"));
  }
}


// ------------------------------------------------------------------ nobody meets
// Where no AV and HV meet, the logic commands nothing at all: SUMO decides.
TEST(Interception, NoCommandWhereNoAvHvPairMeets) {
  Interception logic(B1(), Timing{});
  FakeEnv env;
  FakeModel model;
  const std::vector<std::vector<AtLine>> cases = {
      {},
      {Wait(kAv, kAV, kNs, 0)},                           // alone
      {Wait(kHv, kHV, kNs, 0), Wait(kHv2, kHV, kEs, 0)},  // two HVs crossing
      {Wait(kAv, kAV, kNs, 0), Wait(kAv2, kAV, kEs, 0)},  // two AVs crossing
      {Wait(kAv, kAV, kNs, 0), Wait(kHv, kHV, kSs, 0)},   // opposite straights
      {Wait(kAv, kAV, kNr, 0), Wait(kHv, kHV, kSs, 0)},   // right turn, no conflict
      {Coming(kAv, kAV, kNs), Coming(kHv, kHV, kEs)},     // both still arriving
  };
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (int t = 0; t < 30; ++t)
      EXPECT_TRUE(logic.Step(t / 10.0, cases[i], env, model).empty()) << "case " << i;
  EXPECT_TRUE(model.drawn.empty());
  EXPECT_FALSE(logic.Busy());
}

// ------------------------------------------------------------------ the game
// Both waiting: held at once, drawn, the nudge once both stand and nobody
// inside the junction can touch the AV where it creeps, the HV's reading,
// then the releases.
TEST(Interception, BothWaitingAreHeldNudgeWhenStandingAndClearThenTheGame) {
  Sim r;
  r.model.draws[kAv] = Draw(true, 1.5);
  const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 1.0), Wait(kHv, kHV, kSs, 1.2)};
  r.env.moving = {kHv};
  r.env.way_blocked = {kAv};
  EXPECT_EQ(r.Step(1.2, at), (std::vector<Cmd>{Hold(kAv), Hold(kHv)}));
  ASSERT_EQ(r.model.drawn.size(), 1u);
  EXPECT_EQ(r.Step(1.3, at), kNone);  // the HV still rolls, a third vehicle inside
  r.env.moving.clear();
  EXPECT_EQ(r.Step(1.4, at), kNone);  // a third vehicle inside can touch the creeping AV
  ASSERT_FALSE(r.env.way_asked.empty());
  EXPECT_EQ(r.env.way_asked.back(), kAv);
  r.env.way_blocked.clear();
  EXPECT_EQ(r.Step(1.5, at), std::vector<Cmd>{Nudge(kAv)});
  EXPECT_EQ(r.Step(1.6, at), kNone);  // nudging: nothing until NudgeDone
  r.logic.NudgeDone(kAv, 1.5, 2.5, r.model);
  // AV goes, HV drives recklessly: both released, right of way off.
  EXPECT_EQ(r.Step(2.5, {}), (std::vector<Cmd>{Rel(kAv), Rel(kHv)}));
  EXPECT_TRUE(r.logic.Collided(kHv, kAv));
  EXPECT_FALSE(r.logic.Collided(kHv, kThird));
  r.logic.Cleared(kAv, 4.0);
  EXPECT_TRUE(r.logic.TakeFinished().empty());
  r.logic.Cleared(kHv, 4.5);
  EXPECT_TRUE(r.logic.Busy()) << "a finished encounter not yet taken keeps the junction watched";
  const std::vector<EncounterOutcome> done = r.logic.TakeFinished();
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].av, kAv);
  EXPECT_EQ(done[0].hv, kHv);
  EXPECT_TRUE(done[0].collision);
  EXPECT_DOUBLE_EQ(done[0].time, 1.2);
  EXPECT_DOUBLE_EQ(done[0].decided_at, 2.5);
  EXPECT_DOUBLE_EQ(done[0].reading.observed, 1.5);
  EXPECT_FALSE(r.logic.Busy());
}

// Each release of a move of the game names the other vehicle of the game
// (VehicleCommands::GameMove hands it to SUMO as the vehicle the move
// disregards: docs/encounter-rules.md).
TEST(Interception, EveryMoveOfTheGameNamesItsPartnerAlone) {
  for (const bool go : {true, false}) {
    SCOPED_TRACE(go ? "the AV goes" : "the AV waits");
    Sim r;
    r.model.draws[kAv] = Draw(go, go ? 1.5 : 0.0);
    const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 1.0), Wait(kHv, kHV, kSs, 1.2)};
    r.Step(1.2, at);
    r.Step(1.5, at);
    r.logic.NudgeDone(kAv, go ? 1.5 : 0.0, 2.5, r.model);
    const std::vector<Command> rel = r.logic.Step(2.5, {}, r.env, r.model);
    ASSERT_EQ(rel.size(), go ? 2u : 1u);
    for (const Command& c : rel) {
      EXPECT_EQ(c.kind, Kind::kRelease);
      EXPECT_EQ(c.partner, c.vehicle == kAv ? kHv : kAv) << "vehicle " << c.vehicle;
    }
  }
}

// The paper's order for each (intent, response), and which moves are the
// game's (right of way off) and which go back to SUMO's rules.
TEST(Interception, ReleaseOrderAndRightOfWayForEachIntentAndResponse) {
  struct Case {
    bool go, dc;
    std::vector<Cmd> at_decision, after_confirm, after_first_entered;
    int first;  // who enters the junction first
  };
  // The second move, once the first is inside the junction, is SUMO's (it
  // yields to the first at their crossing point).
  const std::vector<Case> cases = {
      {true, false, {Rel(kAv), Rel(kHv)}, {}, {}, kAv},
      {true, true, {Rel(kAv)}, {}, {Back(kHv)}, kAv},    // DC after the AV: SUMO's
      {false, false, {Rel(kHv)}, {}, {Back(kAv)}, kHv},  // the still AV after the HV: SUMO's
      {false, true, {}, {Rel(kHv)}, {Back(kAv)}, kHv},   // DC past the yielding AV: the game's
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.go ? "go" : "stop") + (c.dc ? "/DC" : "/DR"));
    Sim r;
    r.model.draws[kAv] = Draw(c.go, c.go ? 1.0 : 0.0);
    r.model.dc[kHv] = c.dc;
    const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
    EXPECT_EQ(r.Step(0.0, at), (std::vector<Cmd>{Hold(kAv), Hold(kHv), Nudge(kAv)}));
    r.logic.NudgeDone(kAv, 0.0, 1.0, r.model);
    EXPECT_EQ(r.Step(1.0, {}), c.at_decision);
    EXPECT_EQ(r.Step(1.5, {}), kNone);
    EXPECT_EQ(r.Step(2.0, {}), c.after_confirm);  // confirm_delay = 1 s
    EXPECT_EQ(r.Step(2.5, {}), kNone) << "the first has not entered the junction";
    r.logic.Entered(c.first, 3.0);
    EXPECT_EQ(r.Step(3.0, {}), c.after_first_entered);
    r.logic.Cleared(c.first, 3.5);
    EXPECT_EQ(r.Step(3.5, {}), kNone);
    EXPECT_TRUE(r.logic.TakeFinished().empty());
    r.logic.Cleared(c.first == kAv ? kHv : kAv, 4.0);
    EXPECT_EQ(r.logic.TakeFinished().size(), 1u);
  }
}

// A still AV whose nudge took its front past its line is inside the junction,
// where SUMO no longer makes it yield (it has passed its link): it follows the
// HV only once the HV has passed its way or left the junction, not once it
// has entered.
TEST(Interception, AStillAvNudgedPastItsLineFollowsOnlyOnceTheHvHasLeft) {
  for (bool dc : {false, true}) {
    SCOPED_TRACE(dc ? "DC" : "DR");
    Sim r;
    r.model.draws[kAv] = Draw(false, 1.0);  // nudges, then stays
    r.model.dc[kHv] = dc;
    const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
    EXPECT_EQ(r.Step(0.0, at), (std::vector<Cmd>{Hold(kAv), Hold(kHv), Nudge(kAv)}));
    r.logic.NudgeDone(kAv, 1.0, 1.0, r.model);
    r.env.past_line = {kAv};
    EXPECT_EQ(r.Step(1.0, {}), dc ? kNone : std::vector<Cmd>{Rel(kHv)});
    EXPECT_EQ(r.Step(2.0, {}), dc ? std::vector<Cmd>{Rel(kHv)} : kNone);
    r.logic.Entered(kHv, 3.0);
    EXPECT_EQ(r.Step(3.0, {}), kNone) << "the HV is inside; the AV too";
    r.env.passed = {{kAv, kHv}};
    EXPECT_EQ(r.Step(3.2, {}), kNone) << "the AV has not passed the HV's way: that is not it";
    if (dc) {
      r.logic.Cleared(kHv, 4.0);  // left the junction
    } else {
      r.env.passed = {{kHv, kAv}};  // past the AV's way, still inside
    }
    // Past its link, SUMO will not make it yield to anyone: its way first.
    r.env.way_blocked = {kAv};
    EXPECT_EQ(r.Step(4.0, {}), kNone);
    r.env.way_blocked.clear();
    EXPECT_EQ(r.Step(4.1, {}), std::vector<Cmd>{Back(kAv)});
  }
}

// A move of the game (SUMO's right of way off: it would not yield) waits
// until nobody inside the junction can touch it on its way; when the AV goes
// and the HV drives recklessly each waits for both ways; a move handed back
// to SUMO does not wait (SUMO makes it yield).
TEST(Interception, MovesOfTheGameWaitForTheirWayHandBacksDoNot) {
  struct Case {
    bool go, dc;
    int blocked;
    std::vector<Cmd> blocked_now, then;
  };
  const std::vector<Case> cases = {
      {true, false, kHv, {}, {Rel(kAv), Rel(kHv)}},  // together: both wait
      {true, false, kAv, {}, {Rel(kAv), Rel(kHv)}},
      {false, false, kAv, {Rel(kHv)}, {}},           // the still AV's way is not the HV's
      {false, false, kHv, {}, {Rel(kHv)}},
      {true, true, kAv, {}, {Rel(kAv)}},             // the AV that goes
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.go ? "go" : "stop") + (c.dc ? "/DC" : "/DR") + " blocked " +
                 std::to_string(c.blocked));
    Sim r;
    r.model.draws[kAv] = Draw(c.go, 0.0);
    r.model.dc[kHv] = c.dc;
    const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
    EXPECT_EQ(r.Step(0.0, at), (std::vector<Cmd>{Hold(kAv), Hold(kHv), Nudge(kAv)}));
    r.logic.NudgeDone(kAv, 0.0, 1.0, r.model);
    r.env.way_blocked = {c.blocked};
    EXPECT_EQ(r.Step(1.0, {}), c.blocked_now);
    r.env.way_blocked.clear();
    EXPECT_EQ(r.Step(1.1, {}), c.then);
  }
  // Hand-backs: the still AV after the HV, the careful HV after the AV.
  for (bool go : {false, true}) {
    Sim r;
    r.model.draws[kAv] = Draw(go, 0.0);
    r.model.dc[kHv] = go;
    const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
    r.Step(0.0, at);
    r.logic.NudgeDone(kAv, 0.0, 1.0, r.model);
    const int first = go ? kAv : kHv, second = go ? kHv : kAv;
    EXPECT_EQ(r.Step(1.0, {}), std::vector<Cmd>{Rel(first)});
    r.env.way_blocked = {second};
    r.logic.Entered(first, 1.5);
    EXPECT_EQ(r.Step(1.5, {}), std::vector<Cmd>{Back(second)}) << (go ? "go" : "stop");
  }
}

// A standoff: vehicles SUMO stopped inside the junction for the AV nudged
// into it block a move of the game. Those free to go are let past it
// (kUnblock); without an AV standing past its line nobody is (a vehicle
// stopped inside then waits for someone else, e.g. oncoming traffic).
TEST(Interception, VehiclesStoppedForANudgedAvInTheWayOfAMoveAreLetPastIt) {
  for (bool past : {true, false}) {
    SCOPED_TRACE(past ? "AV past its line" : "AV at its line");
    Sim r;
    r.model.draws[kAv] = Draw(false, 1.0);  // nudges, stays
    const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
    r.Step(0.0, at);
    r.logic.NudgeDone(kAv, 1.0, 1.0, r.model);
    if (past) r.env.past_line = {kAv};
    r.env.way_blocked = {kHv};
    r.env.unblockable[kHv] = {kThird};
    EXPECT_EQ(r.Step(1.0, {}), past ? std::vector<Cmd>{Unblock(kThird)} : kNone);
    r.env.way_blocked.clear();
    r.env.unblockable.clear();
    EXPECT_EQ(r.Step(1.1, {}), std::vector<Cmd>{Rel(kHv)}) << "its way clear: the reckless HV";
  }
}

// Those let past the nudged AV go first: in the step they are let past, no
// move of the game is released, though its own way is clear (at a two-way
// stop MajorClear took them for vehicles SUMO holds for the AV; released in
// the same step, the reckless HV met the major left turn let past: issue 30).
TEST(Interception, MovesOfTheGameWaitAStepForTheVehiclesLetPastTheNudgedAv) {
  for (Rule rule : {Rule::kAllWay, Rule::kTwoWay}) {
    SCOPED_TRACE(ToString(rule));
    Interception logic(B1(rule), Timing{1.0});
    FakeEnv env;
    FakeModel model;
    model.draws[kAv] = Draw(false, 1.0);  // nudges, stays; the HV drives recklessly
    const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
    logic.Step(0.0, at, env, model);
    logic.NudgeDone(kAv, 1.0, 1.0, model);
    env.past_line = {kAv};
    env.way_blocked = {kAv};  // the third vehicle stands in the still AV's way
    env.unblockable[kAv] = {kThird};
    EXPECT_EQ(Simple(logic.Step(1.0, {}, env, model)), std::vector<Cmd>{Unblock(kThird)})
        << "the HV's way is clear, yet it waits a step";
    env.unblockable.clear();  // let past already
    EXPECT_EQ(Simple(logic.Step(1.1, {}, env, model)), std::vector<Cmd>{Rel(kHv)});
  }
}

// Every release of an encounter vehicle says so: the controller watches it
// out of the junction.
TEST(Interception, EncounterReleasesAreMarkedSoTheControllerWatchesThem) {
  Sim r;
  r.model.draws[kAv] = Draw(true, 1.0);
  const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
  r.logic.Step(0, at, r.env, r.model);
  r.logic.NudgeDone(kAv, 1.0, 1.0, r.model);
  const std::vector<Command> cs = r.logic.Step(1.0, {}, r.env, r.model);
  ASSERT_EQ(cs.size(), 2u);
  for (const Command& c : cs) EXPECT_TRUE(c.in_encounter);
}

// Every move of the controller but the reckless HV's waits for room at its
// exit and, at a two-way stop, a gap in the major road on its own movement: a
// still AV nudged past its line too (SUMO no longer protects it there). The
// reckless HV does not wait for room, but at a two-way stop it waits for the
// major road on its own movement (reckless toward the AV alone: issue 30). A
// careful move from its line is SUMO's once handed back: SUMO's own keep
// clear and gap acceptance decide when it enters, so it is handed back at once.
TEST(Interception, MovesWaitForRoomAndTheMajorRoadTheRecklessHvForTheMajorRoadOnly) {
  for (Rule rule : {Rule::kAllWay, Rule::kTwoWay}) {
    for (bool past : {true, false}) {
      SCOPED_TRACE(std::string(ToString(rule)) + (past ? ", AV past its line" : ", AV at its line"));
      Interception logic(B1(rule), Timing{});
      FakeEnv env;
      FakeModel model;
      model.draws[kAv] = Draw(false, 1.0);  // nudges, then stays
      const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
      logic.Step(0, at, env, model);
      logic.NudgeDone(kAv, 1.0, 1.0, model);
      if (past) env.past_line = {kAv};
      env.no_room_vehicles = {kAv, kHv};
      env.major_busy = {kSs, kWs};
      if (rule == Rule::kTwoWay) {
        EXPECT_EQ(Simple(logic.Step(1.0, {}, env, model)), kNone);  // DR: the major road
        env.major_busy = {kWs};
      }
      EXPECT_EQ(Simple(logic.Step(1.05, {}, env, model)), std::vector<Cmd>{Rel(kHv)});  // DR
      logic.Cleared(kHv, 2.0);
      if (!past) {
        EXPECT_EQ(Simple(logic.Step(2.0, {}, env, model)), std::vector<Cmd>{Back(kAv)});
        continue;
      }
      EXPECT_EQ(Simple(logic.Step(2.0, {}, env, model)), kNone);  // no room
      env.no_room_vehicles.clear();
      const std::vector<Cmd> next = Simple(logic.Step(2.1, {}, env, model));
      if (rule == Rule::kAllWay) {
        EXPECT_EQ(next, std::vector<Cmd>{Back(kAv)});
      } else {
        EXPECT_EQ(next, kNone);  // the major road
        env.major_busy.clear();
        EXPECT_EQ(Simple(logic.Step(2.2, {}, env, model)), std::vector<Cmd>{Back(kAv)});
      }
    }
  }
}

// At a two-way stop the AV nudges into the junction only while the major road
// is clear on both movements for the critical gap (SUMO makes every vehicle
// that reaches a nudged AV stop for it, inside the junction too); a still AV
// and an all-way stop do not wait for it.
TEST(Interception, AtATwoWayStopTheAvNudgesOnlyIntoAClearMajorRoad) {
  for (Rule rule : {Rule::kAllWay, Rule::kTwoWay}) {
    for (int busy : {kWs, kSs}) {
      for (double s : {0.0, 1.5}) {
        SCOPED_TRACE(std::string(ToString(rule)) + " busy " + std::to_string(busy) + " s " +
                     std::to_string(s));
        Interception logic(B1(rule), Timing{});
        FakeEnv env;
        FakeModel model;
        model.draws[kAv] = Draw(false, s);
        env.major_busy = {busy};
        const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
        const bool waits = rule == Rule::kTwoWay && s > 0;
        const std::vector<Cmd> held = {Hold(kAv), Hold(kHv)};
        const std::vector<Cmd> held_nudge = {Hold(kAv), Hold(kHv), Nudge(kAv)};
        const std::vector<Cmd> nudge = {Nudge(kAv)};
        EXPECT_EQ(Simple(logic.Step(0, at, env, model)), waits ? held : held_nudge);
        env.major_busy.clear();
        EXPECT_EQ(Simple(logic.Step(0.1, at, env, model)), waits ? nudge : kNone);
      }
    }
  }
}

// The AV goes and the HV drives recklessly: at a two-way stop the two start
// together once the major road is clear on both movements (the game's
// premise is that both proceed at once); at an all-way stop at once.
TEST(Interception, AvThatGoesAndRecklessHvStartTogetherAtATwoWayStop) {
  for (int busy : {kWs, kSs}) {
    Interception logic(B1(Rule::kTwoWay), Timing{});
    FakeEnv env;
    FakeModel model;
    model.draws[kAv] = Draw(true, 1.0);
    const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
    logic.Step(0, at, env, model);
    logic.NudgeDone(kAv, 1.0, 1.0, model);
    env.major_busy = {busy};
    EXPECT_EQ(Simple(logic.Step(1.0, {}, env, model)), kNone) << busy;
    env.major_busy.clear();
    EXPECT_EQ(Simple(logic.Step(1.1, {}, env, model)), (std::vector<Cmd>{Rel(kAv), Rel(kHv)}));
  }
}

// ------------------------------------------------------------------ arriving partners
// One waiting, the other coming to a stop: the waiting one is held at once
// (SUMO would let it go the step the other halts), the other when it waits
// at its line; only then the draw.
TEST(Interception, ArrivingPartnerIsHeldWhenItReachesItsLineThenTheDraw) {
  Sim r;
  EXPECT_EQ(r.Step(0.0, {Wait(kHv, kHV, kSs, 0), Coming(kAv, kAV, kWs)}),
            std::vector<Cmd>{Hold(kHv)});
  EXPECT_TRUE(r.model.drawn.empty());
  EXPECT_EQ(r.logic.Encounters(), 0);
  EXPECT_EQ(r.Step(0.1, {Wait(kHv, kHV, kSs, 0), Coming(kAv, kAV, kWs)}), kNone);
  EXPECT_EQ(r.Step(0.5, {Wait(kHv, kHV, kSs, 0), Wait(kAv, kAV, kWs, 0.5)}),
            (std::vector<Cmd>{Hold(kAv), Nudge(kAv)}));
  ASSERT_EQ(r.model.drawn.size(), 1u);
  EXPECT_EQ(r.logic.Encounters(), 1);
}

// A partner that never arrives (it left the lane's front, or took longer than
// kArrivalLimit) ends the meeting: the held one goes back to SUMO, no draw.
TEST(Interception, PartnerThatDoesNotArriveEndsTheMeetingWithoutADraw) {
  for (bool leaves : {true, false}) {
    SCOPED_TRACE(leaves ? "leaves" : "too late");
    Sim r;
    const std::vector<AtLine> at = {Wait(kHv, kHV, kSs, 0), Coming(kAv, kAV, kWs)};
    r.Step(0.0, at);
    std::vector<Cmd> last;
    if (leaves) {
      last = r.Step(0.1, {Wait(kHv, kHV, kSs, 0)});
    } else {
      int k = 1;
      for (; k / 10.0 <= Interception::kArrivalLimit; ++k) EXPECT_EQ(r.Step(k / 10.0, at), kNone);
      last = r.Step(k / 10.0, at);
    }
    EXPECT_EQ(last, std::vector<Cmd>{Back(kHv)});
    EXPECT_TRUE(r.model.drawn.empty());
    EXPECT_EQ(r.logic.AbandonedMeetings(), 1);
    EXPECT_FALSE(r.logic.Busy());
  }
}

// ------------------------------------------------------------------ premise, order, thirds
// A meeting that is not the game is counted once and commands nothing.
TEST(Interception, MeetingThatIsNotTheGameIsCountedOnceAndLeftToSumo) {
  Sim r;
  r.model.not_game = {{kAv, kHv}};
  const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
  for (int t = 0; t < 10; ++t) EXPECT_EQ(r.Step(t / 10.0, at), kNone);
  EXPECT_EQ(r.logic.NonGameMeetings(), 1);
  EXPECT_EQ(r.model.games.size(), 1u);
  r.Step(1.0, {Wait(kHv, kHV, kSs, 0)});  // the AV went: the pair is forgotten
  r.Step(1.1, at);
  EXPECT_EQ(r.logic.NonGameMeetings(), 2);
}

// Keep clear: a head whose exit has no room meets nobody (it would not enter
// under SUMO's rules either) until there is room.
TEST(Interception, HeadWithoutRoomAtItsExitMeetsNobodyUntilThereIsRoom) {
  Sim r;
  const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
  for (int who : {kAv, kHv}) {
    r.env.no_room_vehicles = {who};
    EXPECT_EQ(r.Step(0.0, at), kNone);
  }
  r.env.no_room_vehicles.clear();
  EXPECT_EQ(r.Step(0.1, at), (std::vector<Cmd>{Hold(kAv), Hold(kHv), Nudge(kAv)}));
}

// The head first at its line picks; waiting partners before arriving ones.
TEST(Interception, FirstAtItsLinePicksItsPartnerWaitingOnesFirst) {
  Sim r;
  const std::vector<AtLine> at = {Coming(kHv2, kHV, kEs), Wait(kHv, kHV, kNs, 2.0),
                                  Wait(kAv, kAV, kWs, 1.0)};
  EXPECT_EQ(r.Step(2.0, at), (std::vector<Cmd>{Hold(kAv), Hold(kHv), Nudge(kAv)}));
  ASSERT_EQ(r.model.drawn.size(), 1u);
  EXPECT_EQ(r.model.drawn[0], std::make_pair(kAv, kHv));
}

// A third vehicle waiting on a movement that conflicts with the encounter is
// held; one that conflicts with neither is not; the held one goes back to
// SUMO once the two encounter vehicles are on their way, before they have left.
TEST(Interception, ThirdVehiclesOnConflictingMovementsWaitUntilBothAreOnTheirWay) {
  Sim r;
  r.model.draws[kAv] = Draw(true, 1.0);
  // AV west straight, HV south straight; third: east straight (crosses the
  // HV's path); kAv2 north right turn (conflicts with neither). Both AVs,
  // so that they do not meet each other once handed back.
  ASSERT_TRUE(r.logic.spec().Conflict(kEs, kSs));
  ASSERT_FALSE(r.logic.spec().Conflict(kNr, kWs) || r.logic.spec().Conflict(kNr, kSs));
  const std::vector<AtLine> at = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0),
                                  Wait(kThird, kAV, kEs, 0.5), Wait(kAv2, kAV, kNr, 0.5)};
  EXPECT_EQ(r.Step(0.0, at), (std::vector<Cmd>{Hold(kAv), Hold(kHv), Hold(kThird), Nudge(kAv)}));
  r.logic.NudgeDone(kAv, 1.0, 1.0, r.model);
  EXPECT_EQ(r.Step(1.0, {at[2], at[3]}), (std::vector<Cmd>{Rel(kAv), Rel(kHv)}));
  EXPECT_EQ(r.logic.HeldThirds(), 1);
  EXPECT_EQ(r.Step(1.1, {at[2], at[3]}), std::vector<Cmd>{Back(kThird)});
  EXPECT_EQ(r.logic.Encounters(), 1);  // still leaving the junction
  r.logic.Cleared(kAv, 2.0);
  r.logic.Cleared(kHv, 2.0);
  EXPECT_EQ(r.logic.TakeFinished().size(), 1u);
}

// A new meeting forms only once both vehicles of the encounter before are
// inside the junction: one handed back but still at its line is neither at
// the lines a meeting looks at (it is SUMO's, on its way) nor yet inside
// where the new moves' ways are checked, so a reckless move of the new
// encounter could start into it.
TEST(Interception, ANewMeetingWaitsUntilTheEncounterBeforeIsInsideTheJunction) {
  Sim r;  // the AV stays, the HV drives recklessly
  const std::vector<AtLine> first = {Wait(kAv, kAV, kWs, 0), Wait(kHv, kHV, kSs, 0)};
  r.Step(0.0, first);
  r.logic.NudgeDone(kAv, 0.0, 0.5, r.model);
  EXPECT_EQ(r.Step(1.0, {}), std::vector<Cmd>{Rel(kHv)});
  r.logic.Entered(kHv, 1.5);
  EXPECT_EQ(r.Step(1.5, {}), std::vector<Cmd>{Back(kAv)});  // the AV: SUMO's, at its line
  ASSERT_TRUE(r.logic.spec().Conflict(kNs, kEs));
  const std::vector<AtLine> next = {Wait(kAv2, kAV, kNs, 1.0), Wait(kHv2, kHV, kEs, 1.2)};
  EXPECT_EQ(r.Step(1.6, next), kNone) << "the AV of the encounter before has not begun to move";
  r.logic.Entered(kAv, 1.7);
  EXPECT_EQ(r.Step(1.7, next), (std::vector<Cmd>{Hold(kAv2), Hold(kHv2), Nudge(kAv2)}));
}

TEST(Interception, NudgeDoneWithoutEncounterThrows) {
  Sim r;
  EXPECT_THROW(r.logic.NudgeDone(kAv, 0, 0, r.model), std::logic_error);
}

}  // namespace
}  // namespace taebp::junction
