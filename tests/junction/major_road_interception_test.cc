// The major-road encounter's interception logic (interception.h, Timing::
// major_road), SUMO-free, with fake time, vehicles, world and model: it forms
// only at a two-way stop with the option on, between an AV standing at a
// minor line and an HV approaching on a conflicting major movement when the
// model says the approach is the game; the commands (hold, cruise, nudge for
// the signal's duration) and, after the HV's reading, the moves of each
// (intent, response): the AV that goes at once, the DR HV untouched (it keeps
// its speed), the DC HV braking and handed back once the AV passed its way or
// driving on past the waiting AV after confirm_delay, the waiting AV handed
// back once the HV is inside. And the conflict zone and time to reach on a
// plain crossing against closed forms.
#include "taebp/junction/conflict_geometry.h"
#include "taebp/junction/interception.h"

#include "interception_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace taebp::junction {
namespace {

using fixture::Cmd;
using fixture::Kind;
using fixture::kAV;
using fixture::Simple;
using namespace fixture;  // B1's movements: kNr .. kWl

// B1 of a netgenerate grid (interception_fixture.h), with the west and east
// approaches as the major road of a two-way stop.
JunctionSpec TwoWay(Rule rule = Rule::kTwoWay) {
  JunctionSpec s = fixture::B1(rule);
  for (Movement& mv : s.movements)
    mv.controlled = rule == Rule::kAllWay || (mv.approach != 1 && mv.approach != 3);
  return s;
}

struct Env : Environment {
  std::set<std::pair<int, int>> passed;
  std::set<int> past_line, moving;
  bool major_busy = false;
  bool WayClear(int, int) override { return true; }
  bool Standing(int v) override { return !moving.count(v); }
  bool ExitHasRoom(int, int) override { return true; }
  bool MajorClear(int) override { return !major_busy; }
  bool PastLine(int v) override { return past_line.count(v); }
  bool Passed(int a, int b) override { return passed.count({a, b}); }
};

struct Model : EncounterModel {
  MajorVerdict::Kind verdict = MajorVerdict::Kind::kGame;
  AvDraw draw;
  bool dc = false;
  int asked = 0;
  AvDraw Draw(int, int) override { return draw; }
  HvReading Read(int, int, double observed) override {
    HvReading r;
    r.observed = observed;
    r.drives_if_clear = dc;
    return r;
  }
  MajorVerdict MajorRoad(int, const MajorAt&, int) override {
    ++asked;
    return {verdict, 2.0};
  }
};

const std::vector<AtLine> kAtLine = {{kAv, kAV, kNs, true, 0.0}};
const std::vector<MajorAt> kMajor = {{kHv, kWs, 60.0, 12.0}};

Timing On() {
  Timing t;
  t.confirm_delay = 1.0;
  t.major_road = true;
  t.yield_decel = 3.0;
  t.reaction_time = 0.5;
  return t;
}


// Which junctions can host a game at all (junctions.csv game_pairs), counted
// by hand from B1's foe matrix: N's right conflicts with S's left and E's
// straight (2), N's straight with W's three, S's left and E's straight and
// left (6), N's left with W's straight and left, S's three and E's straight
// and left (7); of those, 5 are with S (right-left, straight-left, left-left,
// left-straight, left-right).
TEST(GamePairs, CountedByHandOnB1) {
  JunctionSpec one = TwoWay();
  for (Movement& m : one.movements) m.controlled = m.approach == 0;  // N alone has a stop line
  EXPECT_EQ(GamePairs(one, false), 0);  // the spider network's junctions: no game by default
  EXPECT_EQ(GamePairs(one, true), 15);  // the AV at N's line against the other three
  EXPECT_EQ(GamePairs(TwoWay(), false), 5);  // N against S, both at their lines
  EXPECT_GT(GamePairs(TwoWay(), true), 5);
  // All-way: every conflicting pair from two approaches; never 0 with two stop lines.
  EXPECT_GT(GamePairs(TwoWay(Rule::kAllWay), false), 15);
  EXPECT_EQ(GamePairs(TwoWay(Rule::kAllWay), false), GamePairs(TwoWay(Rule::kAllWay), true));
}

TEST(MajorRoadInterception, FormsOnlyAtATwoWayStopWithTheOptionOnWhenTheModelSaysSo) {
  Env env;
  Model model;
  {  // the option off: nobody is asked, nothing commanded
    Interception off(TwoWay(), Timing{});
    for (int t = 0; t < 20; ++t) EXPECT_TRUE(off.Step(t * 0.1, kAtLine, env, model, kMajor).empty());
    EXPECT_EQ(model.asked, 0);
  }
  {  // an all-way stop has no major road
    Interception all_way(TwoWay(Rule::kAllWay), On());
    for (int t = 0; t < 20; ++t) EXPECT_TRUE(all_way.Step(t * 0.1, kAtLine, env, model, kMajor).empty());
    EXPECT_EQ(model.asked, 0);
  }
  {  // movements that do not conflict (north straight, east right turn) never meet
    Interception logic(TwoWay(), On());
    EXPECT_TRUE(logic.Step(0, kAtLine, env, model, {{kHv, kEr, 60.0, 12.0}}).empty());
    EXPECT_EQ(model.asked, 0);
  }
  Interception logic(TwoWay(), On());
  model.verdict = MajorVerdict::Kind::kNotYet;
  EXPECT_TRUE(logic.Step(0.0, kAtLine, env, model, kMajor).empty());
  EXPECT_TRUE(logic.Step(0.1, kAtLine, env, model, kMajor).empty());
  EXPECT_EQ(model.asked, 2);
  model.verdict = MajorVerdict::Kind::kNever;  // judged never: not asked again while both are there
  EXPECT_TRUE(logic.Step(0.2, kAtLine, env, model, kMajor).empty());
  model.verdict = MajorVerdict::Kind::kGame;
  EXPECT_TRUE(logic.Step(0.3, kAtLine, env, model, kMajor).empty());
  EXPECT_EQ(model.asked, 3);
  EXPECT_TRUE(logic.Step(0.4, {}, env, model, kMajor).empty());  // the AV left its line
  // The AV still rolling: no encounter yet.
  env.moving = {kAv};
  EXPECT_TRUE(logic.Step(0.5, kAtLine, env, model, kMajor).empty());
  env.moving.clear();
  model.draw.nudge = true;
  model.draw.nudge_distance = 1.6;
  const std::vector<Command> c = logic.Step(0.6, kAtLine, env, model, kMajor);
  EXPECT_EQ(Simple(c), (std::vector<Cmd>{{Kind::kHold, kAv}, {Kind::kCruise, kHv}, {Kind::kStartNudge, kAv}}));
  ASSERT_EQ(c.size(), 3u);
  EXPECT_DOUBLE_EQ(c[1].speed, 12.0);
  EXPECT_EQ(c[1].movement, kWs);
  EXPECT_EQ(c[1].partner, kAv) << "the cruising HV names the AV as its partner";
  EXPECT_DOUBLE_EQ(c[2].distance, 1.6);
  EXPECT_DOUBLE_EQ(c[2].duration, 2.0);
  EXPECT_TRUE(logic.Busy());
  EXPECT_EQ(logic.Encounters(), 1);
}

// The moves after the HV's reading, for each (intent, response).
TEST(MajorRoadInterception, TheMovesOfEachIntentAndResponse) {
  struct Case {
    bool go, dc, past_line;
  };
  for (const Case k : {Case{true, false, false}, Case{true, true, false}, Case{false, false, false},
                       Case{false, true, false}, Case{false, false, true}}) {
    SCOPED_TRACE(std::string(k.go ? "go" : "wait") + (k.dc ? " DC" : " DR") +
                 (k.past_line ? " past its line" : ""));
    Env env;
    Model model;
    model.draw.intent_go = model.draw.goes_first = k.go;
    model.dc = k.dc;
    Interception logic(TwoWay(), On());
    ASSERT_EQ(logic.Step(0.0, kAtLine, env, model, kMajor).size(), 3u);
    EXPECT_TRUE(logic.Step(1.0, kAtLine, env, model, kMajor).empty()) << "the signal";
    if (k.past_line) env.past_line = {kAv};
    logic.NudgeDone(kAv, 0.0, 2.0, model);
    std::vector<Command> at = logic.Step(2.0, kAtLine, env, model, kMajor);
    std::vector<Cmd> expected;
    if (k.go) {
      expected.push_back({Kind::kRelease, kAv});
      EXPECT_EQ(at.front().partner, kHv) << "the AV that goes names the HV as its partner";
    }
    if (k.dc) expected.push_back({Kind::kYield, kHv});
    EXPECT_EQ(Simple(at), expected);
    if (k.dc) {
      EXPECT_DOUBLE_EQ(at.back().speed, 3.0);
      EXPECT_DOUBLE_EQ(at.back().delay, 0.5);
    }
    if (k.go && k.dc) {  // the DC HV waits until the AV has passed its way
      logic.Entered(kAv, 2.5);
      EXPECT_TRUE(logic.Step(2.5, {}, env, model, kMajor).empty());
      env.passed.insert({kAv, kHv});
      EXPECT_EQ(Simple(logic.Step(3.0, {}, env, model, kMajor)), (std::vector<Cmd>{{Kind::kHandBack, kHv}}));
    }
    if (!k.go && k.dc) {  // slowed for nothing: on after confirm_delay, right of way off
      EXPECT_TRUE(logic.Step(2.5, kAtLine, env, model, kMajor).empty());
      EXPECT_EQ(Simple(logic.Step(3.0, kAtLine, env, model, kMajor)), (std::vector<Cmd>{{Kind::kRelease, kHv}}));
    }
    if (!k.go) {  // the waiting AV after the HV
      EXPECT_TRUE(logic.Step(3.1, kAtLine, env, model, kMajor).empty());
      logic.Entered(kHv, 3.2);
      if (k.past_line) {  // inside the junction itself: once the HV has passed its way
        EXPECT_TRUE(logic.Step(3.2, kAtLine, env, model, kMajor).empty());
        env.passed.insert({kHv, kAv});
        EXPECT_EQ(Simple(logic.Step(3.3, kAtLine, env, model, kMajor)), (std::vector<Cmd>{{Kind::kRelease, kAv}}));
      } else {
        EXPECT_EQ(Simple(logic.Step(3.2, kAtLine, env, model, kMajor)), (std::vector<Cmd>{{Kind::kHandBack, kAv}}));
      }
    }
    // Both on their way: recorded once both have left the junction.
    logic.Cleared(kAv, 5.0);
    logic.Cleared(kHv, 5.0);
    const std::vector<EncounterOutcome> done = logic.TakeFinished();
    ASSERT_EQ(done.size(), 1u);
    EXPECT_TRUE(done[0].major_road);
    EXPECT_EQ(done[0].hv_movement, kWs);
    EXPECT_FALSE(logic.Busy());
    // The game's collision: the AV went and the HV kept its way (neither handed back).
    EXPECT_FALSE(done[0].collision);
  }
}

// A world where vehicles stand inside the junction clear of the AV that may
// start (WayClearOfStarters says no until `starters_clear`; vehicle 7 may be
// let past), and a major-road game whose AV, intent Stop and nudged past its
// line, waits while the HV drives recklessly, the HV inside and past the AV's
// way at 3.2 s.
struct StartersEnv : Env {
  bool starters_clear = false;
  std::vector<int> let_past = {7};
  int asked_starters = 0;
  bool WayClearOfStarters(int, int) override { return starters_clear; }
  std::vector<int> UnblockableStarters(int, int) override {
    ++asked_starters;
    return let_past;
  }
};
void HvPastTheNudgedAv(Interception& logic, StartersEnv& env, Model& model) {
  ASSERT_EQ(logic.Step(0.0, kAtLine, env, model, kMajor).size(), 3u);
  env.past_line = {kAv};
  logic.NudgeDone(kAv, 0.0, 2.0, model);
  EXPECT_TRUE(logic.Step(2.0, kAtLine, env, model, kMajor).empty());
  logic.Entered(kHv, 3.2);
  env.passed.insert({kHv, kAv});
}

// The waiting AV its nudge took past its line goes after the major HV only
// once a third vehicle standing in the junction clear of it, which SUMO may
// release as the HV passes, has passed its way too (WayClearOfStarters; the
// random_nudge collision at B0 of the two-way grid, issue 43); such a vehicle
// is let past it (UnblockableStarters). WayClear alone says yes throughout.
TEST(MajorRoadInterception, TheNudgedAvWaitsForAThirdVehicleThatMayStart) {
  StartersEnv env;
  Model model;
  Interception logic(TwoWay(), On());
  HvPastTheNudgedAv(logic, env, model);
  EXPECT_EQ(Simple(logic.Step(3.3, kAtLine, env, model, kMajor)), (std::vector<Cmd>{{Kind::kUnblock, 7}}))
      << "the third vehicle is let past the AV, which waits";
  EXPECT_EQ(env.asked_starters, 1);
  env.starters_clear = true;
  EXPECT_EQ(Simple(logic.Step(3.4, kAtLine, env, model, kMajor)), (std::vector<Cmd>{{Kind::kRelease, kAv}}));
}

// Bounded: once the HV has left the junction (and a second more), a vehicle
// still standing was not waiting for it; the AV no longer waits for it (it
// would wait for ever for one SUMO holds for the AV itself).
TEST(MajorRoadInterception, TheNudgedAvStopsWaitingForStartersOnceTheHvHasLeft) {
  StartersEnv env;
  env.let_past.clear();
  Model model;
  Interception logic(TwoWay(), On());
  HvPastTheNudgedAv(logic, env, model);
  EXPECT_TRUE(logic.Step(3.3, kAtLine, env, model, kMajor).empty()) << "waits while the HV is inside";
  logic.Cleared(kHv, 4.0);
  EXPECT_TRUE(logic.Step(4.5, kAtLine, env, model, kMajor).empty()) << "and a second after it left";
  EXPECT_EQ(Simple(logic.Step(5.1, kAtLine, env, model, kMajor)), (std::vector<Cmd>{{Kind::kRelease, kAv}}));
}

// A straight crossing at right angles (a along x, b along y, through the
// origin, 30 m of approach each): a's body (5 m x 1.8 m) overlaps the band b
// sweeps (|x| <= 0.9, from b's start until its rear has left) for fronts in
// (30 - 0.9, 30 + 0.9 + 5) on a's path; time to reach: Euler from rest,
// x_k = a dt^2 k (k + 1) / 2, and at constant speed d / v.
TEST(MajorRoadGeometry, ZoneOnPathAndTimeToReachOnAPlainCrossing) {
  Mover a, b;
  a.path = {{-30, 0}, {30, 0}};
  b.path = {{0, -30}, {0, 30}};
  for (Mover* m : {&a, &b}) {
    m->entry = 25;
    m->exit = 35;
    m->front = 0;
  }
  const ConflictZone z = ZoneOnPath(a, b);
  ASSERT_TRUE(z.conflict);
  EXPECT_NEAR(z.first, 29.1, 0.25);
  EXPECT_NEAR(z.last, 35.9, 0.25);
  Mover far = b;
  far.path = {{20, -30}, {20, 30}};  // beyond where a leaves the junction: never
  EXPECT_FALSE(ZoneOnPath(a, far).conflict);
  const double dt = 0.1;
  for (double d : {1.0, 7.3, 25.0}) {
    long k = 0;
    while (a.accel * dt * dt * k * (k + 1) / 2 < d) ++k;
    EXPECT_NEAR(TimeToReach(a, d, dt), k * dt, 1e-9) << d;
  }
  Mover cruise = a;
  cruise.speed = 10;
  cruise.accel = 0;
  cruise.max_speed = 10;
  cruise.limits.clear();
  EXPECT_NEAR(TimeToReach(cruise, 25.0, dt), 2.5, dt + 1e-9);
  Mover still = a;
  still.accel = 0;
  EXPECT_GT(TimeToReach(still, 5.0, dt), 1e8) << "standing, accel 0: never";
}

}  // namespace
}  // namespace taebp::junction
