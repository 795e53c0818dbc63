#include "taebp/controller/sumo_world.h"

namespace taebp {
namespace {

// Every call goes to the adapter (sumo_adapter.h), which catches SUMO's
// exceptions at the boundary.
class AdapterWorld final : public SumoWorld {
 public:
  std::string Version() override { return sumo::Version(); }
  double Time() override { return sumo::Time(); }
  int TeleportNumber() override { return sumo::TeleportNumber(); }
  int DepartedNumber() override { return sumo::DepartedNumber(); }
  std::vector<std::string> DepartedIDs() override { return sumo::DepartedIDs(); }
  int ArrivedNumber() override { return sumo::ArrivedNumber(); }
  std::vector<std::string> ArrivedIDs() override { return sumo::ArrivedIDs(); }
  int CollidingNumber() override { return sumo::CollidingNumber(); }
  std::vector<SumoCollision> Collisions() override { return sumo::Collisions(); }
  long PendingNumber() override { return static_cast<long>(sumo::PendingVehicles().size()); }

  std::vector<std::string> LaneVehicleIDs(const std::string& lane) override {
    return sumo::LaneVehicleIDs(lane);
  }
  int LaneVehicleNumber(const std::string& lane) override { return sumo::LaneVehicleNumber(lane); }
  int LaneHaltingNumber(const std::string& lane) override { return sumo::LaneHaltingNumber(lane); }

  double Speed(const std::string& veh) override { return sumo::Speed(veh); }
  double Distance(const std::string& veh) override { return sumo::Distance(veh); }
  double LanePosition(const std::string& veh) override { return sumo::LanePosition(veh); }
  std::string LaneID(const std::string& veh) override { return sumo::LaneID(veh); }
  std::string RoadID(const std::string& veh) override { return sumo::RoadID(veh); }
  int RouteIndex(const std::string& veh) override { return sumo::RouteIndex(veh); }
  std::vector<std::string> Route(const std::string& veh) override { return sumo::Route(veh); }
  std::string TypeID(const std::string& veh) override { return sumo::TypeID(veh); }
  double Length(const std::string& veh) override { return sumo::Length(veh); }
  double MinGap(const std::string& veh) override { return sumo::MinGap(veh); }
  double Width(const std::string& veh) override { return sumo::Width(veh); }
  double Accel(const std::string& veh) override { return sumo::Accel(veh); }
  double MaxSpeed(const std::string& veh) override { return sumo::MaxSpeed(veh); }
  double SpeedFactor(const std::string& veh) override { return sumo::SpeedFactor(veh); }

  void SetSpeed(const std::string& veh, double speed) override { sumo::SetSpeed(veh, speed); }
  void SetSpeedMode(const std::string& veh, int mode) override { sumo::SetSpeedMode(veh, mode); }
  void SetIgnoredFoes(const std::string& veh, const std::vector<std::string>& foes) override {
    sumo::SetIgnoredFoes(veh, foes);
  }
  void SetLaneChangeMode(const std::string& veh, int mode) override {
    sumo::SetLaneChangeMode(veh, mode);
  }
  void SetColor(const std::string& veh, int r, int g, int b) override {
    sumo::SetColor(veh, r, g, b);
  }
  void SetRouteID(const std::string& veh, const std::string& route) override {
    sumo::SetRouteID(veh, route);
  }

  void AddVehicleType(const VehicleTypeSpec& spec) override { sumo::AddVehicleType(spec); }
  void AddRoute(const std::string& id, const std::vector<std::string>& edges) override {
    sumo::AddRoute(id, edges);
  }
  void AddVehicle(const std::string& id, const std::string& route, const std::string& type,
                  double depart_pos) override {
    sumo::AddVehicle(id, route, type, depart_pos);
  }
};

}  // namespace

SumoWorld& LibsumoWorld() {
  static AdapterWorld world;
  return world;
}

}  // namespace taebp
