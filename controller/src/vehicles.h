// The vehicles the controller knows: one record per vehicle in the network
// (AV or HV, the HV's trust, its SUMO type's size and kinematics, its route,
// what the controller is doing with it), kept in reusable slots so that
// interception logic and records refer to vehicles by a small integer.
#pragma once

#include "taebp/config/config.h"
#include "taebp/encounter/encounter.h"

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

namespace taebp::control {

// kFree: SUMO drives it. kHeld: held at its line (an encounter's vehicle, or a
// third vehicle waiting for one). kNudging/kNudged: the encounter's AV.
// kCrossing: an encounter vehicle released (SUMO's right of way off) or handed
// back, until it has left the junction.
enum class State { kFree, kHeld, kNudging, kNudged, kCrossing };

// Vehicle colours under colour_states: the type's (AV blue, HV red), or the
// state's (vehicle_commands.cc).
enum class Paint { kType, kNudging, kDr, kDc, kCollided };
constexpr int kAvRgb[3] = {0, 0, 255};
constexpr int kHvRgb[3] = {255, 0, 0};

struct Vehicle {
  std::string id;
  bool alive = false;
  VehicleKind kind = VehicleKind::kHV;
  double trust = 0;
  double length = 5, min_gap = 2;
  double width = 1.8, accel = 2.6, max_speed = 13.89;  // its SUMO type's (the game's premise)
  double decel = 4.5, emergency_decel = 9.0, sigma = 0;  // its SUMO type's (a merge's premise)
  std::vector<int> route;  // edge indices (Topology::EdgeIndex)
  int route_pos = 0;       // route index already counted
  State state = State::kFree;
  int junction = -1, movement = -1;
  int approach = -1;  // the approach (lane) whose front it was when `movement` was found
  double held_since = 0, hold_odometer = 0;
  double line_since = -1;  // halted at its stop line since (-1: not there)
  double line_gap = 0;     // m from its front to the stop line when halted there
  bool reckless = false;   // released with SUMO's right of way off
  bool ignoring = false;   // SUMO's junctionModel.ignoreIDs set (GameMove) until it is SUMO's again
  bool entered = false;    // released and past its stop line (reported to the logic)
  bool unblocked = false;  // let past a nudged AV (kModeUnblocked) until out of the junction
  std::vector<int> near;   // controlled junctions whose stop line it may reach before the next sample
  double target = 0, creep_speed = 0, commanded = 0;  // the nudge
  double nudge_until = 0;  // the signal lasts until then (a still AV stands; major road)
  // A major-road HV of an encounter: its speed commanded by the controller
  // (kCruise, kYield) until it is handed back or has left the junction.
  bool major_hv = false;
  bool commanded_speed = false;  // setSpeed in force (cleared by setSpeed -1)
  double major_speed = 0;        // the speed it is held at / braking from
  bool yielding = false;
  double yield_from = 0, yield_decel = 0;
  std::string lane;        // while crossing: the lane it was last seen on
  Paint paint = Paint::kType;
  int open_encounters = 0;  // formed, not yet recorded: the slot is not reused before
};

class VehicleRegistry {
 public:
  // Stores a departed vehicle; returns its slot.
  int Add(Vehicle v);
  // The vehicle left the network: its id is forgotten; its slot is reused
  // once no encounter refers to it any more.
  void Remove(int h);
  // An encounter that referred to the vehicle was recorded.
  void EncounterDone(int h);

  Vehicle& operator[](int h) { return vehs_[h]; }
  const Vehicle& operator[](int h) const { return vehs_[h]; }
  int Find(const std::string& id) const {  // -1: not in the network
    const auto it = index_.find(id);
    return it == index_.end() ? -1 : it->second;
  }
  // The vehicles in the network, by id.
  const std::unordered_map<std::string, int>& in_network() const { return index_; }

 private:
  std::vector<Vehicle> vehs_;
  std::vector<int> free_slots_;
  std::unordered_map<std::string, int> index_;
};

// A uniform in [0, 1) that depends only on (seed, text, salt): each vehicle's
// draws are independent of departure order and of the other vehicles.
double HashUniform(std::uint64_t seed, const std::string& text, std::uint64_t salt);
// Is the vehicle an AV: drawn from scenario.av_share by its id, else by its
// SUMO type (scenario.av_types; `type_of` is asked only then).
bool IsAv(const ScenarioConfig& sc, const std::string& id,
          const std::function<std::string()>& type_of);
// An HV's trust: model.trust, drawn per vehicle by its id when a distribution.
double HvTrust(const ExperimentConfig& cfg, const std::string& id);

}  // namespace taebp::control
