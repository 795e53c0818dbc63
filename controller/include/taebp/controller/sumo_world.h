// What the network controller reads from, and commands in, a running SUMO
// simulation: one interface, so that a test can drive the controller with a
// fake world (tests/controller/fake_world_test.cc: who is held, who is
// released with which speed mode, and how many calls each step costs) while a
// real run uses LibsumoWorld(), which forwards every call to sumo_adapter.h
// (still the only code that includes libsumo).
//
// Only what the controller needs is here; tools that drive SUMO directly
// (snapshots, the GUI) keep using sumo_adapter.h.
#pragma once

#include "taebp/controller/sumo_adapter.h"

#include <string>
#include <vector>

namespace taebp {

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
  virtual int RouteIndex(const std::string& veh) = 0;
  // A vehicle as it departs (its SUMO type's and its route's).
  virtual std::vector<std::string> Route(const std::string& veh) = 0;
  virtual std::string TypeID(const std::string& veh) = 0;
  virtual double Length(const std::string& veh) = 0;
  virtual double MinGap(const std::string& veh) = 0;
  virtual double Width(const std::string& veh) = 0;
  virtual double Accel(const std::string& veh) = 0;
  virtual double MaxSpeed(const std::string& veh) = 0;
  virtual double SpeedFactor(const std::string& veh) = 0;  // at most this times a lane's limit

  // Commands.
  virtual void SetSpeed(const std::string& veh, double speed) = 0;  // < 0: car-following again
  virtual void SetSpeedMode(const std::string& veh, int mode) = 0;
  // SUMO's right of way toward these vehicles only is disregarded (empty: none).
  virtual void SetIgnoredFoes(const std::string& veh, const std::vector<std::string>& foes) = 0;
  virtual void SetLaneChangeMode(const std::string& veh, int mode) = 0;
  virtual void SetColor(const std::string& veh, int r, int g, int b) = 0;
  virtual void SetRouteID(const std::string& veh, const std::string& route) = 0;

  // Set-up (the figure-8's vehicles, placed at the start).
  virtual void AddVehicleType(const VehicleTypeSpec& spec) = 0;
  virtual void AddRoute(const std::string& id, const std::vector<std::string>& edges) = 0;
  virtual void AddVehicle(const std::string& id, const std::string& route, const std::string& type,
                          double depart_pos) = 0;
};

// The running simulation of this process (sumo_adapter.h's backend).
SumoWorld& LibsumoWorld();

}  // namespace taebp
