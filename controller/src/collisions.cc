#include "collisions.h"

#include "vehicle_commands.h"

#include <algorithm>

namespace taebp::control {

bool CollisionAttribution::Due() const {
  return s_.sumo.CollidingNumber() > 0 || !colliding_.empty();
}

void CollisionAttribution::Attribute() {
  std::set<std::pair<std::string, std::string>> pairs;
  for (const SumoCollision& c : s_.sumo.Collisions())
    pairs.insert(std::minmax(c.collider, c.victim));
  for (const auto& pair : pairs) {
    if (colliding_.count(pair)) continue;  // the same episode as last step
    const int a = s_.vehicles.Find(pair.first), b = s_.vehicles.Find(pair.second);
    bool matched = false;
    if (a >= 0 && b >= 0) {
      for (JunctionState& j : s_.junctions) {
        if (j.logic->Collided(a, b)) {
          matched = true;
          commands_.SetPaint(a, Paint::kCollided);
          commands_.SetPaint(b, Paint::kCollided);
          break;
        }
      }
    }
    if (!matched && s_.measuring()) {
      ++s_.out.other_collisions;
      auto game_move = [&](int h) {
        if (h < 0) return false;
        const Vehicle& w = s_.vehicles[h];
        return w.state == State::kCrossing && w.reckless;
      };
      if (game_move(a) || game_move(b)) ++s_.out.other_collisions_game_move;
    }
  }
  colliding_ = std::move(pairs);
}

}  // namespace taebp::control
