// The one thin adapter around libsumo. Nothing else in the project includes a
// libsumo header. Every call catches libsumo::TraCIException (and any other
// exception libsumo throws) at this boundary and rethrows SumoError with the
// call and its arguments as context.
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

// Simulation
void Start(const std::vector<std::string>& args);  // args[0] = "sumo"
void Close();
bool IsLoaded();
void Step();
double Time();
std::string Version();  // e.g. "SUMO 1.15.0"
std::vector<SumoCollision> Collisions();
int StopStartingNumber();
std::vector<std::string> StopStartingIDs();
int TeleportNumber();  // vehicles starting a teleport this step
int CollidingNumber();  // vehicles in a collision that started this step

// Network
double LaneLength(const std::string& lane);
std::vector<XY> LaneShape(const std::string& lane);
XY JunctionPosition(const std::string& junction);

// Types and routes
void AddVehicleType(const VehicleTypeSpec& spec);
void AddRoute(const std::string& id, const std::vector<std::string>& edges);

// Vehicles
void AddVehicle(const std::string& id, const std::string& route, const std::string& type,
                double depart_pos);
void SetStop(const std::string& veh, const std::string& edge, double pos, double duration);
void Resume(const std::string& veh);
void SetSpeedMode(const std::string& veh, int mode);
void SetSpeed(const std::string& veh, double speed);  // < 0: back to car-following
void SetColor(const std::string& veh, int r, int g, int b);
double Distance(const std::string& veh);  // odometer (m)
double Speed(const std::string& veh);
std::string RoadID(const std::string& veh);
double LanePosition(const std::string& veh);

}  // namespace sumo
}  // namespace taebp
