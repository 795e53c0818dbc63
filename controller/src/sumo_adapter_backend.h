// Private to the adapter: the functions of one SUMO backend, defined by
// sumo_adapter_impl.inc in namespace taebp::sumo::libsumo_backend
// (sumo_adapter.cc) and taebp::sumo::libtraci_backend
// (sumo_adapter_libtraci.cc). The public taebp::sumo functions dispatch to one
// of them (sumo_adapter.h, SetBackend).
#pragma once

#include "taebp/controller/sumo_adapter.h"

#include <string>
#include <utility>
#include <vector>

namespace taebp::sumo::libtraci_backend {

void Start(const std::vector<std::string>& args);
void Close();
bool IsLoaded();
void Step();
double Time();
std::string Version();
std::vector<SumoCollision> Collisions();
int TeleportNumber();
int CollidingNumber();
int DepartedNumber();
std::vector<std::string> DepartedIDs();
int ArrivedNumber();
std::vector<std::string> ArrivedIDs();
std::vector<std::string> PendingVehicles();
std::vector<std::string> VehicleIDs();
double LaneLength(const std::string& lane);
std::vector<XY> LaneShape(const std::string& lane);
XY JunctionPosition(const std::string& junction);
std::pair<XY, XY> NetBoundary();
std::vector<std::string> LaneInternalFoes(const std::string& lane);
std::vector<std::string> LaneVehicleIDs(const std::string& lane);
int LaneVehicleNumber(const std::string& lane);
int LaneHaltingNumber(const std::string& lane);
void AddVehicleType(const VehicleTypeSpec& spec);
void AddRoute(const std::string& id, const std::vector<std::string>& edges);
void AddVehicle(const std::string& id, const std::string& route, const std::string& type,
                double depart_pos);
void SetSpeedMode(const std::string& veh, int mode);
void SetLaneChangeMode(const std::string& veh, int mode);
void SetSpeed(const std::string& veh, double speed);
void SetIgnoredFoes(const std::string& veh, const std::vector<std::string>& foes);
void SetColor(const std::string& veh, int r, int g, int b);
double Distance(const std::string& veh);
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
double SpeedFactor(const std::string& veh);
int RouteIndex(const std::string& veh);
std::vector<std::string> Route(const std::string& veh);
void SetRoute(const std::string& veh, const std::vector<std::string>& edges);
void SetRouteID(const std::string& veh, const std::string& route);

namespace gui {
void SetSchema(const std::string& view, const std::string& scheme);
void SetBoundary(const std::string& view, XY min, XY max);
void Screenshot(const std::string& view, const std::string& file, int width, int height);
}  // namespace gui

}  // namespace taebp::sumo::libtraci_backend
