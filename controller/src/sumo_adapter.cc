#include "taebp/controller/sumo_adapter.h"

#include <libsumo/libsumo.h>

#include <sstream>

namespace taebp::sumo {
namespace {

// `describe` builds the context message only when a call fails (hot path).
template <typename D, typename F>
auto Guard(D&& describe, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const libsumo::TraCIException& e) {
    throw SumoError("SUMO " + std::string(describe()) + " failed: " + e.what());
  } catch (const SumoError&) {
    throw;
  } catch (const std::exception& e) {
    throw SumoError("SUMO " + std::string(describe()) + " failed: " + e.what());
  }
}

std::string Args(const std::string& veh, double v) {
  std::ostringstream os;
  os.precision(10);
  os << "(" << veh << ", " << v << ")";
  return os.str();
}

}  // namespace

void Start(const std::vector<std::string>& args) {
  std::string cmd;
  for (const auto& a : args) cmd += (cmd.empty() ? "" : " ") + a;
  Guard([&] { return std::string("start [" + cmd + "]"); }, [&] {
    libsumo::Simulation::start(args);
    return 0;
  });
}
void Close() {
  Guard([&] { return std::string("close"); }, [] {
    if (libsumo::Simulation::isLoaded()) libsumo::Simulation::close();
    return 0;
  });
}
bool IsLoaded() {
  return Guard([&] { return std::string("isLoaded"); }, [] { return libsumo::Simulation::isLoaded(); });
}
void Step() {
  Guard([&] { return std::string("step"); }, [] {
    libsumo::Simulation::step();
    return 0;
  });
}
double Time() {
  return Guard([&] { return std::string("getTime"); }, [] { return libsumo::Simulation::getTime(); });
}
std::string Version() {
  return Guard([&] { return std::string("getVersion"); }, [] { return libsumo::Simulation::getVersion().second; });
}
std::vector<SumoCollision> Collisions() {
  return Guard([&] { return std::string("getCollisions"); }, [] {
    std::vector<SumoCollision> out;
    for (const auto& c : libsumo::Simulation::getCollisions()) {
      out.push_back({c.collider, c.victim, c.type, c.lane, c.colliderSpeed, c.victimSpeed, c.pos});
    }
    return out;
  });
}
int StopStartingNumber() {
  return Guard([&] { return std::string("getStopStartingVehiclesNumber"); },
               [] { return libsumo::Simulation::getStopStartingVehiclesNumber(); });
}
std::vector<std::string> StopStartingIDs() {
  return Guard([&] { return std::string("getStopStartingVehiclesIDList"); },
               [] { return libsumo::Simulation::getStopStartingVehiclesIDList(); });
}
int TeleportNumber() {
  return Guard([&] { return std::string("getStartingTeleportNumber"); },
               [] { return libsumo::Simulation::getStartingTeleportNumber(); });
}

int CollidingNumber() {
  return Guard([&] { return std::string("getCollidingVehiclesNumber"); },
               [] { return libsumo::Simulation::getCollidingVehiclesNumber(); });
}

double LaneLength(const std::string& lane) {
  return Guard([&] { return std::string("Lane::getLength(" + lane + ")"); }, [&] { return libsumo::Lane::getLength(lane); });
}
std::vector<XY> LaneShape(const std::string& lane) {
  return Guard([&] { return std::string("Lane::getShape(" + lane + ")"); }, [&] {
    std::vector<XY> out;
    for (const auto& p : libsumo::Lane::getShape(lane).value) out.push_back({p.x, p.y});
    return out;
  });
}
XY JunctionPosition(const std::string& junction) {
  return Guard([&] { return std::string("Junction::getPosition(" + junction + ")"); }, [&] {
    const auto p = libsumo::Junction::getPosition(junction);
    return XY{p.x, p.y};
  });
}

void AddVehicleType(const VehicleTypeSpec& s) {
  Guard([&] { return std::string("VehicleType setup(" + s.id + ")"); }, [&] {
    libsumo::VehicleType::copy("DEFAULT_VEHTYPE", s.id);
    libsumo::VehicleType::setMaxSpeed(s.id, s.max_speed);
    libsumo::VehicleType::setMinGap(s.id, s.min_gap);
    libsumo::VehicleType::setLength(s.id, s.length);
    libsumo::VehicleType::setWidth(s.id, s.width);
    libsumo::VehicleType::setAccel(s.id, s.accel);
    libsumo::VehicleType::setDecel(s.id, s.decel);
    libsumo::VehicleType::setImperfection(s.id, 0.0);
    libsumo::VehicleType::setSpeedDeviation(s.id, 0.0);
    libsumo::VehicleType::setColor(s.id, libsumo::TraCIColor(s.r, s.g, s.b, 255));
    return 0;
  });
}
void AddRoute(const std::string& id, const std::vector<std::string>& edges) {
  Guard([&] { return std::string("Route::add(" + id + ")"); }, [&] {
    libsumo::Route::add(id, edges);
    return 0;
  });
}

void AddVehicle(const std::string& id, const std::string& route, const std::string& type,
                double depart_pos) {
  Guard([&] { return std::string("Vehicle::add" + Args(id, depart_pos)); }, [&] {
    std::ostringstream pos;
    pos.precision(17);
    pos << depart_pos;
    libsumo::Vehicle::add(id, route, type, "0", "0", pos.str(), "0");
    return 0;
  });
}
void SetStop(const std::string& veh, const std::string& edge, double pos, double duration) {
  Guard([&] { return std::string("Vehicle::setStop(" + veh + ", " + edge + ")" + Args("pos", pos)); }, [&] {
    libsumo::Vehicle::setStop(veh, edge, pos, 0, duration);
    return 0;
  });
}
void Resume(const std::string& veh) {
  Guard([&] { return std::string("Vehicle::resume(" + veh + ")"); }, [&] {
    libsumo::Vehicle::resume(veh);
    return 0;
  });
}
void SetSpeedMode(const std::string& veh, int mode) {
  Guard([&] { return std::string("Vehicle::setSpeedMode" + Args(veh, mode)); }, [&] {
    libsumo::Vehicle::setSpeedMode(veh, mode);
    return 0;
  });
}
void SetSpeed(const std::string& veh, double speed) {
  Guard([&] { return std::string("Vehicle::setSpeed" + Args(veh, speed)); }, [&] {
    libsumo::Vehicle::setSpeed(veh, speed);
    return 0;
  });
}
void SetColor(const std::string& veh, int r, int g, int b) {
  Guard([&] { return std::string("Vehicle::setColor(" + veh + ")"); }, [&] {
    libsumo::Vehicle::setColor(veh, libsumo::TraCIColor(r, g, b, 255));
    return 0;
  });
}
double Distance(const std::string& veh) {
  return Guard([&] { return std::string("Vehicle::getDistance(" + veh + ")"); },
               [&] { return libsumo::Vehicle::getDistance(veh); });
}
double Speed(const std::string& veh) {
  return Guard([&] { return std::string("Vehicle::getSpeed(" + veh + ")"); }, [&] { return libsumo::Vehicle::getSpeed(veh); });
}
std::string RoadID(const std::string& veh) {
  return Guard([&] { return std::string("Vehicle::getRoadID(" + veh + ")"); }, [&] { return libsumo::Vehicle::getRoadID(veh); });
}
double LanePosition(const std::string& veh) {
  return Guard([&] { return std::string("Vehicle::getLanePosition(" + veh + ")"); },
               [&] { return libsumo::Vehicle::getLanePosition(veh); });
}

}  // namespace taebp::sumo
