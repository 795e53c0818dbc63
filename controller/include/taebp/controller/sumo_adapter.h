// The one thin adapter around SUMO. Nothing else in the project includes a
// libsumo or libtraci header. Every call catches libsumo::TraCIException (and
// any other exception SUMO throws) at this boundary and rethrows SumoError with
// the call and its arguments as context.
//
// Two backends with the same calls (SetBackend): libsumo, in process (the
// default and the fast path), and libtraci driving a sumo-gui process (for
// watching a run and for screenshots). Each call dispatches with one branch.
//
// libsumo runs one simulation per process: a second Start replaces the first.
// Sweeps therefore run simulations in separate processes, never threads.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace taebp {

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

namespace sumo {

enum class Backend {
  kLibsumo,      // in process (libsumo); the default
  kLibtraciGui,  // a sumo-gui process driven over a socket (libtraci)
};

// Selects the backend of the next Start; throws SumoError while a simulation
// is loaded. With kLibtraciGui, Start runs "sumo-gui" in place of args[0] and
// appends "--start", "--quit-on-end" and `gui_args` (e.g. {"--delay", "100"}).
void SetBackend(Backend backend, std::vector<std::string> gui_args = {});

// Simulation
void Start(const std::vector<std::string>& args);  // args[0] = "sumo"
void Close();
bool IsLoaded();
void Step();
double Time();
std::string Version();  // e.g. "SUMO 1.15.0"
// Collisions this step. libsumo: one entry per colliding pair for every step
// they overlap. sumo-gui backend (libtraci 1.15 has no getCollisions): one
// entry per pair of vehicles whose collision started this step, type
// "unknown", no lane/speeds.
std::vector<SumoCollision> Collisions();
int TeleportNumber();  // vehicles starting a teleport this step
int CollidingNumber();  // vehicles in a collision that started this step
int DepartedNumber();   // vehicles that entered the network this step
std::vector<std::string> DepartedIDs();
int ArrivedNumber();    // vehicles that left the network this step
std::vector<std::string> ArrivedIDs();
// Vehicles loaded but not yet inserted (the demand waiting to depart).
std::vector<std::string> PendingVehicles();
std::vector<std::string> VehicleIDs();  // vehicles in the network

// Network
double LaneLength(const std::string& lane);
std::vector<XY> LaneShape(const std::string& lane);
XY JunctionPosition(const std::string& junction);
std::pair<XY, XY> NetBoundary();  // bounding box (min, max) of the network's shapes
std::vector<std::string> LaneInternalFoes(const std::string& lane);  // internal lanes only
// Per step on a lane: vehicles (ids ordered from the lane's start to its end:
// the last one is nearest the end), their number, those halting (< 0.1 m/s).
std::vector<std::string> LaneVehicleIDs(const std::string& lane);
int LaneVehicleNumber(const std::string& lane);
int LaneHaltingNumber(const std::string& lane);

// Types and routes
void AddVehicleType(const VehicleTypeSpec& spec);
void AddRoute(const std::string& id, const std::vector<std::string>& edges);

// Vehicles
void AddVehicle(const std::string& id, const std::string& route, const std::string& type,
                double depart_pos);
void SetSpeedMode(const std::string& veh, int mode);
// SUMO's lane-change mode bits (1621: SUMO's default; 0: no lane change of
// its own).
void SetLaneChangeMode(const std::string& veh, int mode);
void SetSpeed(const std::string& veh, double speed);  // < 0: back to car-following
// The vehicles whose right of way `veh` disregards at junctions (SUMO's
// junctionModel.ignoreIDs; empty: none), every other foe's kept.
void SetIgnoredFoes(const std::string& veh, const std::vector<std::string>& foes);
void SetColor(const std::string& veh, int r, int g, int b);
double Distance(const std::string& veh);  // odometer (m)
double Speed(const std::string& veh);
std::string RoadID(const std::string& veh);
double LanePosition(const std::string& veh);
std::string LaneID(const std::string& veh);
std::string TypeID(const std::string& veh);
double Length(const std::string& veh);
double MinGap(const std::string& veh);
double Width(const std::string& veh);
double Accel(const std::string& veh);
double MaxSpeed(const std::string& veh);
// Its speed factor: it drives at most this times a lane's speed limit.
double SpeedFactor(const std::string& veh);
int RouteIndex(const std::string& veh);  // index of the current edge in its route
std::vector<std::string> Route(const std::string& veh);  // the route's edges
void SetRoute(const std::string& veh, const std::vector<std::string>& edges);  // from its edge
// Replaces the route by a route added with AddRoute that contains the current
// edge (SUMO swaps the route; nothing accumulates, unlike SetRoute, which
// keeps the edges already driven).
void SetRouteID(const std::string& veh, const std::string& route);

// The sumo-gui view ("View #0"). Only with Backend::kLibtraciGui; SumoError
// otherwise.
namespace gui {
void SetSchema(const std::string& scheme);  // e.g. "real world", "standard"
void SetBoundary(XY min, XY max);           // fit this box into the view
// Written by sumo-gui during the next Step(); format from the extension
// (.png); -1: the view's size.
void Screenshot(const std::string& file, int width = -1, int height = -1);
}  // namespace gui

}  // namespace sumo
}  // namespace taebp
