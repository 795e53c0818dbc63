#include "collisions.h"

#include "vehicle_commands.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace taebp::control {

bool CollisionAttribution::Due() const {
  return s_.sumo.CollidingNumber() > 0 || !colliding_.empty();
}

void CollisionAttribution::Attribute() {
  std::set<std::pair<std::string, std::string>> pairs;
  std::map<std::pair<std::string, std::string>, const SumoCollision*> first;
  const std::vector<SumoCollision> collisions = s_.sumo.Collisions();
  for (const SumoCollision& c : collisions) {
    const auto pair = std::minmax(c.collider, c.victim);
    pairs.insert(pair);
    first.emplace(pair, &c);
  }
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
    auto game_move = [&](int h) {
      if (h < 0) return false;
      const Vehicle& w = s_.vehicles[h];
      return w.state == State::kCrossing && w.reckless;
    };
    const bool move = !matched && (game_move(a) || game_move(b));
    if (!matched && s_.measuring()) {
      ++s_.out.other_collisions;
      if (move) ++s_.out.other_collisions_game_move;
    }
    if (s_.measuring()) Record(*first.at(pair), matched, move);
  }
  colliding_ = std::move(pairs);
}

// collisions.csv's row: what SUMO reported and what the controller knew of
// the two vehicles at that step.
void CollisionAttribution::Record(const SumoCollision& c, bool encounter_pair, bool game_move) {
  CollisionRecord r;
  r.time = s_.now;
  r.lane = c.lane;
  r.pos = c.pos;
  r.type = c.type;
  r.collider = c.collider;
  r.victim = c.victim;
  r.encounter_pair = encounter_pair;
  r.game_move = game_move;
  for (auto [id, av, in_game] : {std::tuple{&c.collider, &r.collider_av, &r.collider_in_game},
                                 std::tuple{&c.victim, &r.victim_av, &r.victim_in_game}}) {
    const int h = s_.vehicles.Find(*id);
    if (h < 0) continue;
    *av = s_.vehicles[h].kind == VehicleKind::kAV;
    *in_game = s_.vehicles[h].open_encounters > 0;
  }
  s_.out.collisions.push_back(std::move(r));
}

}  // namespace taebp::control
