// SUMO as the project sees it, in two interfaces written once:
// - SumoWorld: what the network controller reads from, and commands in, a
//   running simulation. A test drives the controller with a fake world
//   (tests/controller/fake_world_test.cc: who is held, who is released with
//   which speed mode, and how many calls each step costs).
// - SumoSimulation: a SumoWorld that also starts, steps and closes SUMO and
//   answers what runs, tools and tests ask besides (the network's geometry,
//   sumo-gui's view). Its two implementations, libsumo in process and
//   libtraci driving sumo-gui, are one body (controller/src/
//   sumo_adapter_impl.inc) compiled twice; sumo_adapter.h selects one (Sumo()).
// So a SUMO call is written twice: declared here, defined in the .inc.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace taebp {

// What every call throws when SUMO fails: libsumo's TraCIException (and any
// other exception SUMO throws) caught at the boundary, with the call and its
// arguments as context.
class SumoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SumoCollision {
  std::string collider, victim, type, lane;
  double collider_speed = 0, victim_speed = 0, pos = 0;
};

struct XY {
  double x = 0, y = 0;
};

struct VehicleTypeSpec {
  std::string id;
  double max_speed, min_gap, length, width, accel, decel;
  int r, g, b;
};

class SumoWorld {
 public:
  virtual ~SumoWorld() = default;

  // The simulation, this step.
  virtual std::string Version() = 0;
  virtual double Time() = 0;
  virtual int TeleportNumber() = 0;  // vehicles starting a teleport this step
  virtual int DepartedNumber() = 0;
  virtual std::vector<std::string> DepartedIDs() = 0;
  virtual int ArrivedNumber() = 0;
  virtual std::vector<std::string> ArrivedIDs() = 0;
  virtual int CollidingNumber() = 0;  // vehicles in a collision that started this step
  // Collisions this step. libsumo: one entry per colliding pair for every
  // step they overlap. sumo-gui (libtraci 1.15 has no getCollisions): one
  // entry per pair of vehicles whose collision started this step, type
  // "unknown", no lane or speeds.
  virtual std::vector<SumoCollision> Collisions() = 0;
  virtual long PendingNumber() = 0;  // loaded, not yet inserted

  // Lanes, this step (ids from the lane's start to its end: the last is the front).
  virtual std::vector<std::string> LaneVehicleIDs(const std::string& lane) = 0;
  virtual int LaneVehicleNumber(const std::string& lane) = 0;
  virtual int LaneHaltingNumber(const std::string& lane) = 0;

  // A vehicle, this step.
  virtual double Speed(const std::string& veh) = 0;
  virtual double Distance(const std::string& veh) = 0;  // odometer (m)
  virtual double LanePosition(const std::string& veh) = 0;
  virtual std::string LaneID(const std::string& veh) = 0;
  virtual std::string RoadID(const std::string& veh) = 0;
  virtual int RouteIndex(const std::string& veh) = 0;  // the current edge's index in Route()
  virtual XY Position(const std::string& veh) = 0;      // its front's centre
  virtual double Angle(const std::string& veh) = 0;     // degrees, 0 = north, clockwise
  // A vehicle as it departs (its SUMO type's and its route's).
  virtual std::vector<std::string> Route(const std::string& veh) = 0;
  virtual std::string TypeID(const std::string& veh) = 0;
  virtual double Length(const std::string& veh) = 0;
  virtual double MinGap(const std::string& veh) = 0;
  virtual double Width(const std::string& veh) = 0;
  virtual double Accel(const std::string& veh) = 0;
  virtual double Decel(const std::string& veh) = 0;           // car following's (m/s^2)
  virtual double EmergencyDecel(const std::string& veh) = 0;  // the hardest it brakes (m/s^2)
  virtual double Imperfection(const std::string& veh) = 0;    // Krauss's sigma (0: none)
  virtual double MaxSpeed(const std::string& veh) = 0;
  virtual double SpeedFactor(const std::string& veh) = 0;  // at most this times a lane's limit

  // Commands.
  virtual void SetSpeed(const std::string& veh, double speed) = 0;  // < 0: car-following again
  virtual void SetSpeedMode(const std::string& veh, int mode) = 0;
  // SUMO's right of way toward these vehicles only is disregarded (empty: none).
  virtual void SetIgnoredFoes(const std::string& veh, const std::vector<std::string>& foes) = 0;
  // SUMO's lane-change mode bits (1621: SUMO's default; 0: none of its own).
  virtual void SetLaneChangeMode(const std::string& veh, int mode) = 0;
  virtual void SetColor(const std::string& veh, int r, int g, int b) = 0;
  // Replaces the route by one added with AddRoute that holds the current edge
  // (SUMO swaps the route; nothing accumulates, unlike SetRoute).
  virtual void SetRouteID(const std::string& veh, const std::string& route) = 0;

  // Set-up (the figure-8's vehicles, placed at the start).
  virtual void AddVehicleType(const VehicleTypeSpec& spec) = 0;
  virtual void AddRoute(const std::string& id, const std::vector<std::string>& edges) = 0;
  virtual void AddVehicle(const std::string& id, const std::string& route, const std::string& type,
                          double depart_pos) = 0;
};

// SumoWorld, and what else drives SUMO: the simulation's lifetime, the
// network's geometry and sumo-gui's view. sumo_adapter.h: which one runs.
class SumoSimulation : public SumoWorld {
 public:
  // args[0] = "sumo". libsumo: SUMO's own errors on stderr as it loads, the
  // first one leading the SumoError. sumo-gui: runs "sumo-gui" in place of
  // args[0], with "--start", "--quit-on-end" and the backend's gui_args.
  virtual void Start(const std::vector<std::string>& args) = 0;
  virtual void Close() = 0;  // nothing loaded: nothing to do
  virtual bool IsLoaded() = 0;
  virtual void Step() = 0;
  // Vehicles loaded but not yet inserted (the demand waiting to depart).
  virtual std::vector<std::string> PendingVehicles() = 0;
  virtual std::vector<std::string> VehicleIDs() = 0;  // vehicles in the network

  // The network.
  virtual double LaneLength(const std::string& lane) = 0;
  virtual std::vector<XY> LaneShape(const std::string& lane) = 0;
  virtual XY JunctionPosition(const std::string& junction) = 0;
  virtual std::pair<XY, XY> NetBoundary() = 0;  // bounding box (min, max) of its shapes
  virtual std::vector<std::string> LaneInternalFoes(const std::string& lane) = 0;  // internal lanes

  // Replaces the route by `edges`, from the vehicle's current edge on (SUMO
  // keeps the edges already driven; SetRouteID swaps the whole route).
  virtual void SetRoute(const std::string& veh, const std::vector<std::string>& edges) = 0;

  // sumo-gui's view ("View #0"); SumoError under libsumo.
  virtual void GuiSetSchema(const std::string& scheme) = 0;  // e.g. "real world", "standard"
  virtual void GuiSetBoundary(XY min, XY max) = 0;           // fit this box into the view
  // Written by sumo-gui during the next Step(); format from the extension
  // (.png); -1: the view's size.
  virtual void GuiScreenshot(const std::string& file, int width = -1, int height = -1) = 0;
};

}  // namespace taebp
