// SUMO's collisions (its junction collision check on the vehicles' own
// geometry), each episode counted once: an encounter's AV and HV colliding is
// that encounter's collision (its junction's logic records it); any other is
// counted in other_collisions, and in other_collisions_game_move when one of
// the two was released by the game with SUMO's right of way off. Every
// episode after the warm-up is also a row of collisions.csv (PolicyRun::collisions).
#pragma once

#include "run_state.h"

#include <set>
#include <string>
#include <utility>

namespace taebp::control {

class VehicleCommands;

class CollisionAttribution {
 public:
  CollisionAttribution(RunState& s, VehicleCommands& commands) : s_(s), commands_(commands) {}
  // Per step, when SUMO reports a collision starting or one went on last step.
  bool Due() const;
  void Attribute();

 private:
  void Record(const SumoCollision& c, bool encounter_pair, bool game_move);
  RunState& s_;
  VehicleCommands& commands_;
  std::set<std::pair<std::string, std::string>> colliding_;  // last step's pairs
};

}  // namespace taebp::control
