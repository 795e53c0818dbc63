// The network controller driven through a fake SUMO (SumoWorld): no
// simulation runs. The test places vehicles on the lanes of a real junction
// (a 4-way all-way stop built by netconvert), moves them by hand, and reads
// what the controller commands and how many calls each step costs:
// - where no AV-HV pair can meet, the controller reads nothing between its
//   once-a-second samples and commands nothing;
// - a pair that does not conflict is never commanded;
// - an AV and an HV waiting at conflicting lines are held, the game runs and
//   the two are released in the paper's order (the reckless HV disregarding
//   the AV's right of way alone, junctionModel.ignoreIDs; the AV handed back under SUMO's rules,
//   mode 31, once the HV is inside the junction), and a third vehicle on a
//   conflicting movement is held meanwhile and handed back afterwards;
// - on a two-way stop, a major vehicle halted at its line is traffic for a
//   move of the game (one halted farther back is not, nor one SUMO holds
//   for an AV nudged past its line).
#include "taebp/config/config.h"
#include "taebp/controller/network_controller.h"
#include "taebp/controller/sumo_world.h"
#include "taebp/scenario/net_file.h"
#include "taebp/scenario/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../scenario/net_support.h"
#include "test_support.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace taebp {
namespace {

using ::testing::Contains;
using ::testing::ElementsAre;
using ::testing::IsEmpty;
using ::testing::Not;

struct Car {
  std::string id, type, lane;
  double pos = 0, speed = 0, odometer = 0;
  std::vector<std::string> route;
  int route_index = 0;
};

// A world the test moves by hand. Every read is counted; every command is
// logged as "<call> <vehicle> <value>".
class FakeWorld : public SumoWorld {
 public:
  double time = 0;
  std::map<std::string, Car> cars;
  std::vector<std::string> departed, arrived;
  long reads = 0;
  std::vector<std::string> commands;
  std::map<std::string, int> lane_change_modes;

  void Depart(const Car& c) {
    cars[c.id] = c;
    departed.push_back(c.id);
  }
  // The next step: time advances; departures and arrivals are this step's.
  void Next() {
    time += 0.1;
    departed.clear();
    arrived.clear();
  }
  void Move(const std::string& id, const std::string& lane, double pos, double speed) {
    Car& c = cars.at(id);
    c.odometer += lane == c.lane ? pos - c.pos : pos;
    c.lane = lane;
    c.pos = pos;
    c.speed = speed;
  }
  void Arrive(const std::string& id) {
    cars.erase(id);
    arrived.push_back(id);
  }

  std::string Version() override { return "fake"; }
  double Time() override { return time; }
  int TeleportNumber() override { return 0; }
  int DepartedNumber() override { return static_cast<int>(departed.size()); }
  std::vector<std::string> DepartedIDs() override { return departed; }
  int ArrivedNumber() override { return static_cast<int>(arrived.size()); }
  std::vector<std::string> ArrivedIDs() override { return arrived; }
  int CollidingNumber() override { return 0; }
  std::vector<SumoCollision> Collisions() override { return {}; }
  long PendingNumber() override { return 0; }

  std::vector<std::string> LaneVehicleIDs(const std::string& lane) override {
    ++reads;
    std::vector<const Car*> on;
    for (const auto& [id, c] : cars)
      if (c.lane == lane) on.push_back(&c);
    std::sort(on.begin(), on.end(), [](const Car* a, const Car* b) { return a->pos < b->pos; });
    std::vector<std::string> ids;
    for (const Car* c : on) ids.push_back(c->id);
    return ids;
  }
  int LaneVehicleNumber(const std::string& lane) override {
    ++reads;
    return static_cast<int>(std::count_if(cars.begin(), cars.end(),
                                           [&](const auto& c) { return c.second.lane == lane; }));
  }
  int LaneHaltingNumber(const std::string& lane) override {
    ++reads;
    return static_cast<int>(std::count_if(cars.begin(), cars.end(), [&](const auto& c) {
      return c.second.lane == lane && c.second.speed < 0.1;
    }));
  }
  double Speed(const std::string& v) override { return ++reads, cars.at(v).speed; }
  double Distance(const std::string& v) override { return ++reads, cars.at(v).odometer; }
  double LanePosition(const std::string& v) override { return ++reads, cars.at(v).pos; }
  XY Position(const std::string& v) override { return ++reads, XY{cars.at(v).pos, 0}; }
  double Angle(const std::string& v) override { return ++reads, (void)cars.at(v), 90.0; }
  std::string LaneID(const std::string& v) override { return ++reads, cars.at(v).lane; }
  std::string RoadID(const std::string& v) override {
    ++reads;
    const std::string& lane = cars.at(v).lane;
    return lane.substr(0, lane.rfind('_'));
  }
  int RouteIndex(const std::string& v) override { return ++reads, cars.at(v).route_index; }
  std::vector<std::string> Route(const std::string& v) override { return cars.at(v).route; }
  std::string TypeID(const std::string& v) override { return cars.at(v).type; }
  double Length(const std::string&) override { return 5; }
  double MinGap(const std::string&) override { return 2.5; }
  double Width(const std::string&) override { return 1.8; }
  double Accel(const std::string&) override { return 2.6; }
  double Decel(const std::string&) override { return 4.5; }
  double EmergencyDecel(const std::string&) override { return 9.0; }
  double Imperfection(const std::string&) override { return 0.0; }
  double MaxSpeed(const std::string&) override { return 13.89; }
  double SpeedFactor(const std::string&) override { return 1.0; }

  void SetSpeed(const std::string& v, double speed) override {
    commands.push_back("speed " + v + " " + Num(speed));
  }
  void SetSpeedMode(const std::string& v, int mode) override {
    commands.push_back("mode " + v + " " + std::to_string(mode));
  }
  void SetIgnoredFoes(const std::string& v, const std::vector<std::string>& foes) override {
    std::string ids;
    for (const std::string& f : foes) ids += (ids.empty() ? "" : " ") + f;
    commands.push_back("ignore " + v + " [" + ids + "]");
  }
  void SetLaneChangeMode(const std::string& v, int mode) override {
    lane_change_modes[v] = mode;
  }
  void SetColor(const std::string&, int, int, int) override {}
  void SetRouteID(const std::string& v, const std::string& route) override {
    commands.push_back("route " + v + " " + route);
  }
  void AddVehicleType(const VehicleTypeSpec&) override {}
  void AddRoute(const std::string&, const std::vector<std::string>&) override {}
  void AddVehicle(const std::string&, const std::string&, const std::string&, double) override {}

  std::vector<std::string> CommandsFor(const std::string& v) const {
    std::vector<std::string> out;
    for (const std::string& c : commands)
      if (c.find(" " + v + " ") != std::string::npos) out.push_back(c);
    return out;
  }

 private:
  static std::string Num(double x) {
    std::ostringstream os;
    os << x;
    return os.str();
  }
};

// A 4-way all-way stop C with 100 m arms, and the controller of one policy on it.
class FakeJunction : public ::testing::Test {
 protected:
  void SetUp() override {
    net_path_ = test::FourWay(dir_, "cross", "allway_stop");
    net_ = net::NetFile::Load(net_path_);
  }

  std::unique_ptr<NetworkController> Controller(const std::string& policy) {
    // The fake world's vehicles are of types AV and HV; its cars come from the
    // tests. The one trip departs after the run's end: the loader refuses a
    // route file without demand (SUMO would run an empty network), and the fake
    // world never reads it.
    const std::string routes = dir_.Write(
        "types.rou.xml",
        "<routes>\n  <vType id=\"AV\"/>\n  <vType id=\"HV\"/>\n"
        "  <trip id=\"after_the_end\" type=\"HV\" depart=\"1000\" from=\"in_w\" to=\"out_e\"/>\n"
        "</routes>\n");
    config_ = ParseExperimentConfig(
        "scenario:\n  kind: network\n  network: " + net_path_ + "\n  routes: [" + routes +
            "]\n  duration: 100\n  warmup: 0\n"
            "model:\n  prior_go: 0.2\n  collision_penalty: 3.0\n  trust: 0.6\n"
            "policies: [" + policy + "]\n",
        "fake.yaml", {});
    scenario_ = BuildScenario(config_, "");
    auto c = std::make_unique<NetworkController>(
        config_, ParseGamePolicy(policy), scenario_, *scenario_.topology,
        ControllerOptions{}, &world_);
    c->Start();
    return c;
  }

  // The internal lane of the movement from `from` to `to` (single internal lane).
  std::string Internal(const std::string& from, const std::string& to) const {
    for (int id : net_.LinksFrom(from)) {
      const net::Link& l = net_.links()[id];
      if (l.to_lane == to && !l.internal.empty()) return l.internal.front();
    }
    ADD_FAILURE() << "no link " << from << " -> " << to;
    return "";
  }

  // A car halted at its stop line (0.3 m before the lane's end).
  Car AtLine(const std::string& id, const std::string& type, const std::string& edge,
             const std::string& next) const {
    Car c;
    c.id = id;
    c.type = type;
    c.lane = edge + "_0";
    c.pos = net_.FindLane(c.lane)->length - 0.3;
    c.route = {edge, next};
    return c;
  }

  // The AV `id` creeps at the speed last commanded (a nudge), onto `inside`
  // past the end of its lane.
  void Creep(const std::string& id, const std::string& inside) {
    double v = 0;
    for (const std::string& cmd : world_.CommandsFor(id))
      if (cmd.rfind("speed ", 0) == 0) v = std::stod(cmd.substr(cmd.rfind(' ') + 1));
    Car& car = world_.cars.at(id);
    if (v <= 0) {
      car.speed = 0;
      return;
    }
    const double length = net_.FindLane(car.lane)->length;
    car.pos += v * 0.1;
    car.odometer += v * 0.1;
    car.speed = v;
    if (car.lane != inside && car.pos > length) {
      car.lane = inside;
      car.pos -= length;
    }
  }
  bool HasCommand(const std::string& id, const std::string& cmd) const {
    const std::vector<std::string> cs = world_.CommandsFor(id);
    return std::find(cs.begin(), cs.end(), cmd) != cs.end();
  }

  // One step: the world's, then the controller's.
  void Step(NetworkController& c) {
    c.Step();
    world_.Next();
  }

  test::TempDir dir_{"fake_world"};
  std::string net_path_;
  net::NetFile net_;
  ExperimentConfig config_;
  Scenario scenario_;
  FakeWorld world_;
};

TEST_F(FakeJunction, WhereNoAvHvPairCanMeetNothingIsReadBetweenSamplesAndNothingCommanded) {
  auto c = Controller("ta_ebp");
  // Two HVs waiting at conflicting lines (no AV in the network).
  world_.Depart(AtLine("h1", "HV", "WC", "CE"));
  world_.Depart(AtLine("h2", "HV", "SC", "CN"));
  Step(*c);
  for (int k = 0; k < 95; ++k) {
    const long before = world_.reads;
    const bool sample = (k + 2) % 10 == 0;  // the controller's 10th, 20th, ... step
    Step(*c);
    if (!sample) {
      EXPECT_EQ(world_.reads, before) << "step " << k + 2 << " read SUMO";
    }
  }
  EXPECT_THAT(world_.commands, IsEmpty());
}

TEST_F(FakeJunction, AnAvAndAnHvWhoseMovementsDoNotConflictAreNeverCommanded) {
  auto c = Controller("ta_ebp");
  world_.Depart(AtLine("a1", "AV", "WC", "CE"));  // opposite straights
  world_.Depart(AtLine("h1", "HV", "EC", "CW"));
  const long before = world_.reads;
  for (int k = 0; k < 50; ++k) Step(*c);
  EXPECT_GT(world_.reads, before) << "the junction is watched (an AV and an HV near it)";
  EXPECT_THAT(world_.commands, IsEmpty());
}

// An AV and an HV drive towards conflicting lines at the lanes' speed limit
// (the fastest any vehicle there can: speed factor 1). Their lanes are read
// when they start and then not again until they can be within reach of a
// meeting at the line; yet they are held in the very step the second of them
// comes to a halt at its line, as when every lane is read every step.
TEST_F(FakeJunction, LanesAreReadOnlyWhenSomeoneCanBeNearTheLineAndNoMeetingIsLate) {
  auto c = Controller("no_ebp");
  const double vmax = net_.FindLane("WC_0")->speed;
  const double line = net_.FindLane("WC_0")->length - 0.3;
  Car av = AtLine("a1", "AV", "WC", "CE"), hv = AtLine("h1", "HV", "SC", "CN");
  av.pos = hv.pos = 5.0;
  av.speed = hv.speed = vmax;
  world_.Depart(av);
  world_.Depart(hv);
  long reads_far = 0;
  int step = 0, halted_at = -1, held_at = -1;
  while (held_at < 0 && step < 200) {
    const long before = world_.reads;
    Step(*c);
    ++step;
    if (world_.CommandsFor("a1").size() == 1 && held_at < 0) held_at = step;
    for (const char* id : {"a1", "h1"}) {  // drive on at the limit; halt at the line
      const Car& car = world_.cars.at(id);
      const double next = std::min(line, car.pos + vmax * 0.1);
      world_.Move(id, car.lane, next, next < line ? vmax : 0.0);
    }
    if (world_.cars.at("a1").speed == 0 && halted_at < 0) halted_at = step + 1;
    const bool sample = step % 10 == 0;
    // (The step they depart in reads their lanes once.)
    if (step > 1 && !sample && world_.cars.at("a1").pos < line - 20)
      reads_far += world_.reads - before;
  }
  ASSERT_GT(halted_at, 40) << "the test drives them from afar";
  EXPECT_EQ(held_at, halted_at) << "held in the step both wait at their lines";
  EXPECT_EQ(reads_far, 0) << "lanes read while nobody could be near their lines";
}

TEST_F(FakeJunction, TheGameIsExecutedInTheWorldAndBothAreHandedBackInThePapersOrder) {
  // No EBP: the AV stays still (no signal), the HV reads the prior 0.2 < p*
  // = 0.4 and drives recklessly; the AV lets it go first.
  auto c = Controller("no_ebp");
  world_.Depart(AtLine("a1", "AV", "WC", "CE"));
  world_.Depart(AtLine("h1", "HV", "SC", "CN"));
  Step(*c);  // held; no signal to make: the HV decides at once
  EXPECT_THAT(world_.CommandsFor("a1"), ElementsAre("speed a1 0"));
  EXPECT_THAT(world_.CommandsFor("h1"), ElementsAre("speed h1 0"));
  // A third vehicle comes to a halt at a line whose movement crosses the HV's.
  world_.Depart(AtLine("h2", "HV", "EC", "CW"));
  Step(*c);
  EXPECT_THAT(world_.CommandsFor("h2"), ElementsAre("speed h2 0")) << "held for the encounter";
  // The reckless HV goes with SUMO's right of way off; the AV waits.
  // A move of the game at an all-way stop (every third vehicle held): right
  // of way off (mode 55), the AV named as its partner.
  EXPECT_THAT(world_.CommandsFor("h1"),
              ElementsAre("speed h1 0", "mode h1 55", "ignore h1 [a1]", "speed h1 -1"));
  EXPECT_THAT(world_.CommandsFor("a1"), ElementsAre("speed a1 0"));
  // The HV enters the junction: the AV is handed back to SUMO's rules (SUMO
  // makes it yield to the HV at their crossing point); both are on their way,
  // so the third vehicle is SUMO's again at the next step.
  world_.Move("h1", Internal("SC_0", "CN_0"), 2.0, 3.0);
  Step(*c);
  EXPECT_THAT(world_.CommandsFor("a1"), ElementsAre("speed a1 0", "mode a1 31", "speed a1 -1"));
  EXPECT_THAT(world_.CommandsFor("h2"), ElementsAre("speed h2 0"));
  Step(*c);
  EXPECT_THAT(world_.CommandsFor("h2"), ElementsAre("speed h2 0", "speed h2 -1"));
  // The HV's rear leaves the junction: SUMO's rules again for it.
  world_.Move("h1", "CN_0", 6.0, 5.0);
  Step(*c);
  EXPECT_THAT(world_.CommandsFor("h1"),
              ElementsAre("speed h1 0", "mode h1 55", "ignore h1 [a1]", "speed h1 -1",
                          "ignore h1 []", "mode h1 31"));
  // The AV leaves; the encounter is recorded.
  world_.Move("a1", "CE_0", 6.0, 5.0);
  Step(*c);
  world_.Arrive("h1");
  world_.Arrive("a1");
  Step(*c);
  const PolicyRun run = c->Finish();
  ASSERT_EQ(run.encounters.size(), 1u);
  const EncounterRecord& e = run.encounters.front();
  EXPECT_EQ(e.av, "a1");
  EXPECT_EQ(e.hv, "h1");
  EXPECT_FALSE(e.hv_dc);
  EXPECT_FALSE(e.av_first);
  EXPECT_EQ(e.observed, 0.0) << "a still AV: the displacement the world reported";
  EXPECT_FALSE(e.collision) << "no collision reported by the world";
  EXPECT_EQ(run.held, 3);  // the two and the third vehicle
  EXPECT_THAT(world_.commands, Not(Contains(::testing::HasSubstr("ignore h2"))));
}

// A two-way stop (the east-west road major, north and south stopped). The
// AV stands still at the north line (No EBP), the HV at the south line reads
// the prior and drives recklessly while the AV waits: a move of the game,
// released with SUMO's right of way off only when the major road is clear
// (StopLineEnvironment::MajorClear). A major vehicle halted at its line has
// the right of way over the HV's left turn: SUMO starts it whenever its own
// exit lets it, so it is traffic (released beside it, both started in the
// same step on the two-way grid, seed 3, No Trust). Halted farther back it
// is queued or yielding and comes only by moving: no traffic.
TEST_F(FakeJunction, AMajorVehicleStandingAtItsLineIsTrafficForAReleasedMove) {
  net_path_ = test::FourWay(dir_, "two_way", "priority_stop");
  net_ = net::NetFile::Load(net_path_);
  const std::string released = "speed h1 -1";
  for (const bool at_line : {true, false}) {
    SCOPED_TRACE(at_line ? "the major vehicle at its line" : "the major vehicle upstream");
    world_ = FakeWorld{};
    auto c = Controller("no_ebp");
    Car major = AtLine("m1", "HV", "WC", "CE");  // straight on, across the HV's left turn
    if (!at_line) major.pos -= 20.0;
    world_.Depart(major);
    world_.Depart(AtLine("a1", "AV", "NC", "CS"));
    world_.Depart(AtLine("h1", "HV", "SC", "CW"));
    for (int k = 0; k < 5; ++k) Step(*c);
    ASSERT_THAT(world_.CommandsFor("h1"), Contains("speed h1 0")) << "the game was held";
    if (!at_line) {
      EXPECT_THAT(world_.CommandsFor("h1"), Contains(released));
      continue;
    }
    EXPECT_THAT(world_.CommandsFor("h1"), Not(Contains(released)));
    // The major vehicle goes through and leaves: the way is clear.
    world_.Move("m1", Internal("WC_0", "CE_0"), 2.0, 5.0);
    Step(*c);
    EXPECT_THAT(world_.CommandsFor("h1"), Not(Contains(released))) << "inside, moving";
    world_.Arrive("m1");
    Step(*c);
    EXPECT_THAT(world_.CommandsFor("h1"), Contains(released));
  }
  // An AV nudged past its line (Always Nudge) stands in the way of a major
  // vehicle that comes to a halt at its line meanwhile: SUMO holds it for
  // the AV, so it is no traffic (waiting for it would wait for ever). The
  // HV reads the nudge and drives if clear; the AV, drawn to go, is released.
  world_ = FakeWorld{};
  auto c = Controller("always_nudge");
  world_.Depart(AtLine("a1", "AV", "NC", "CS"));
  world_.Depart(AtLine("h1", "HV", "SC", "CW"));
  const std::string av_inside = Internal("NC_0", "CS_0");
  for (int k = 0; k < 100 && !HasCommand("a1", "speed a1 -1"); ++k) {
    Step(*c);
    Creep("a1", av_inside);
    if (world_.cars.at("a1").lane == av_inside && !world_.cars.count("m1"))
      world_.Depart(AtLine("m1", "HV", "WC", "CE"));
  }
  ASSERT_TRUE(world_.cars.count("m1")) << "the AV was nudged past its line";
  EXPECT_THAT(world_.CommandsFor("a1"), Contains("mode a1 55")) << "a move of the game";
  EXPECT_THAT(world_.CommandsFor("a1"), Contains("speed a1 -1"));
}

}  // namespace
}  // namespace taebp
