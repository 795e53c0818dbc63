#include "taebp/junction/junction_logic.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace taebp::junction {

const char* ToString(Rule rule) { return rule == Rule::kAllWay ? "all_way_stop" : "two_way_stop"; }

void JunctionSpec::Validate() const {
  const std::size_t n = movements.size();
  if (conflict.size() != n)
    throw std::invalid_argument("junction " + id + ": conflict matrix has " +
                                std::to_string(conflict.size()) + " rows for " +
                                std::to_string(n) + " movements");
  for (const auto& row : conflict)
    if (row.size() != n)
      throw std::invalid_argument("junction " + id + ": conflict matrix is not square");
  if (!clear_at.empty()) {
    if (clear_at.size() != n)
      throw std::invalid_argument("junction " + id + ": clear_at has the wrong size");
    for (const auto& row : clear_at)
      if (row.size() != n) throw std::invalid_argument("junction " + id + ": clear_at is not square");
  }
  for (const Movement& m : movements)
    if (m.approach < 0 || m.approach >= approaches)
      throw std::invalid_argument("junction " + id + ": movement approach out of range");
}

JunctionLogic::JunctionLogic(JunctionSpec spec, Timing timing)
    : spec_(std::move(spec)), timing_(timing) {
  spec_.Validate();
}

void JunctionLogic::Arrive(int vehicle, VehicleKind kind, int movement, double now) {
  heads_.push_back({vehicle, kind, movement, now, now});
}

bool JunctionLogic::Blocks(const Inside& in, int movement) const {
  if (!spec_.Conflict(in.movement, movement)) return false;
  return spec_.clear_at.empty() || in.rear < spec_.clear_at[in.movement][movement];
}

void JunctionLogic::Progress(int vehicle, double rear, double now) {
  for (Inside& in : inside_) {
    if (in.vehicle != vehicle) continue;
    const double before = in.rear;
    in.rear = rear;
    if (spec_.clear_at.empty()) return;
    // Heads whose conflict with this vehicle just ended.
    for (HeadState& h : heads_) {
      if (!spec_.Conflict(in.movement, h.movement)) continue;
      const double at = spec_.clear_at[in.movement][h.movement];
      if (before < at && rear >= at) h.ready = std::max(h.ready, now);
    }
    return;
  }
}

void JunctionLogic::Cleared(int vehicle, double now) {
  last_activity_ = now;
  for (auto it = inside_.begin(); it != inside_.end();) {
    if (it->vehicle == vehicle) {
      const Inside gone = *it;
      it = inside_.erase(it);
      // The heads it still blocked are ready from now on.
      for (HeadState& h : heads_)
        if (Blocks(gone, h.movement)) h.ready = std::max(h.ready, now);
    } else {
      ++it;
    }
  }
  for (auto it = encounters_.begin(); it != encounters_.end(); ++it) {
    Active& e = *it;
    if (e.out.av == vehicle) e.av_cleared = true;
    if (e.out.hv == vehicle) e.hv_cleared = true;
    if (e.av_cleared && e.hv_cleared) {
      finished_.push_back(e.out);
      encounters_.erase(it);
      return;
    }
  }
}

void JunctionLogic::NudgeDone(int av, double observed, double now, EncounterModel& model) {
  for (Active& e : encounters_) {
    if (e.out.av != av || e.nudged) continue;
    e.nudged = true;
    e.out.reading = model.Read(e.out.av, e.out.hv, observed);
    e.out.decided_at = now;
    e.sequence.emplace(e.out.draw.goes_first, e.out.reading.drives_if_clear, now,
                       timing_.confirm_delay);
    return;
  }
  throw std::logic_error("junction " + spec_.id + ": NudgeDone for a vehicle in no encounter");
}

bool JunctionLogic::Collided(int a, int b) {
  for (Active& e : encounters_) {
    if ((e.out.av == a && e.out.hv == b) || (e.out.av == b && e.out.hv == a)) {
      e.out.collision = true;
      return true;
    }
  }
  return false;
}

bool JunctionLogic::Blocked(int movement) const {
  for (const Inside& in : inside_)
    if (Blocks(in, movement)) return true;
  // An encounter reserves the movements of its vehicles until they are
  // released (then they are inside, above).
  for (const Active& e : encounters_) {
    if (!e.av_released && spec_.Conflict(e.out.av_movement, movement)) return true;
    if (!e.hv_released && spec_.Conflict(e.out.hv_movement, movement)) return true;
  }
  return false;
}

void JunctionLogic::Release(std::vector<Command>* out, int vehicle, int movement, bool reckless,
                            double now) {
  Command c;
  c.kind = Command::Kind::kRelease;
  c.vehicle = vehicle;
  c.reckless = reckless;
  out->push_back(c);
  if (movement >= 0) inside_.push_back({vehicle, movement});
  last_activity_ = now;
}

std::vector<Command> JunctionLogic::Decide(double now, Environment& env, EncounterModel& model) {
  std::vector<Command> out;
  // Encounters in progress: the releases their sequences make due (a careful
  // release waits for room at its exit: drive if clear).
  for (Active& e : encounters_) {
    if (!e.sequence) continue;
    // (At a two-way stop a careful release also waits for a gap in the major
    // road; a reckless HV does not.)
    auto may_enter = [&](bool released, int movement, int vehicle) {
      if (released) return true;
      if (!env.ExitHasRoom(movement, vehicle)) return false;
      return spec_.rule == Rule::kAllWay || env.MajorClear(movement);
    };
    const bool av_room = may_enter(e.av_released, e.out.av_movement, e.out.av);
    const bool hv_room = may_enter(e.hv_released, e.out.hv_movement, e.out.hv);
    for (const auto& rel : e.sequence->Update(now, e.av_cleared, e.hv_cleared, av_room, hv_room)) {
      (rel.av ? e.av_released : e.hv_released) = true;
      Release(&out, rel.av ? e.out.av : e.out.hv, rel.av ? e.out.av_movement : e.out.hv_movement,
              rel.reckless, now);
    }
  }
  if (heads_.empty()) return out;

  // A head is ready from its arrival, or from when the vehicles it conflicted
  // with cleared (Cleared), whichever is later.
  const std::size_t n = heads_.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  // First come, first served: by arrival at the line, then approach order.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const HeadState& x = heads_[a];
    const HeadState& y = heads_[b];
    if (x.arrival != y.arrival) return x.arrival < y.arrival;
    if (x.ready != y.ready) return x.ready < y.ready;
    const int ax = spec_.movements[x.movement].approach, ay = spec_.movements[y.movement].approach;
    if (ax != ay) return ax < ay;
    return x.vehicle < y.vehicle;
  });
  // Lazily evaluated world checks (they may cost SUMO calls).
  std::vector<signed char> room(n, -1), major(n, -1);
  auto has_room = [&](std::size_t i) {
    if (room[i] < 0) room[i] = env.ExitHasRoom(heads_[i].movement, heads_[i].vehicle) ? 1 : 0;
    return room[i] == 1;
  };
  auto major_clear = [&](std::size_t i) {
    if (spec_.rule == Rule::kAllWay) return true;
    if (major[i] < 0) major[i] = env.MajorClear(heads_[i].movement) ? 1 : 0;
    return major[i] == 1;
  };
  std::vector<char> done(n, 0);
  auto conflict = [&](std::size_t a, std::size_t b) {
    return spec_.Conflict(heads_[a].movement, heads_[b].movement);
  };
  // An earlier waiting head (in `order` before position k, not done, not
  // excluded by keep-clear, other than `except`) that conflicts with head i.
  auto earlier_conflict = [&](std::size_t k, std::size_t i, std::size_t except) {
    for (std::size_t q = 0; q < k; ++q) {
      const std::size_t e = order[q];
      if (e == except || done[e] || !conflict(e, i)) continue;
      if (!has_room(e)) continue;  // keep-clear excluded heads block nobody
      return true;
    }
    return false;
  };
  const double eps = 1e-9;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    if (done[i]) continue;
    const HeadState& h = heads_[i];
    if (Blocked(h.movement)) continue;
    if (earlier_conflict(k, i, n)) continue;
    if (now + eps < h.ready + timing_.arrival_window) continue;
    if (!has_room(i) || !major_clear(i)) continue;
    // The head has looked long enough: does a conflicting head meet it?
    std::size_t partner = n;
    for (std::size_t q = k + 1; q < n; ++q) {
      const std::size_t p = order[q];
      if (done[p] || !conflict(i, p)) continue;
      const HeadState& ph = heads_[p];
      if (ph.ready > h.ready + timing_.arrival_window + eps) continue;  // came too late
      if (Blocked(ph.movement) || earlier_conflict(q, p, i)) continue;
      if (!has_room(p) || !major_clear(p)) continue;
      // Both bound for the same exit: it must take the two of them.
      if (spec_.movements[ph.movement].to_lane == spec_.movements[h.movement].to_lane &&
          !env.ExitHasRoom(ph.movement, ph.vehicle, 1))
        continue;
      partner = p;
      break;
    }
    done[i] = 1;
    bool game = false;
    if (partner != n && heads_[partner].kind != h.kind) {
      const HeadState& av = h.kind == VehicleKind::kAV ? h : heads_[partner];
      const HeadState& hv = h.kind == VehicleKind::kAV ? heads_[partner] : h;
      game = model.Game(av.vehicle, hv.vehicle, av.movement, hv.movement);
      if (!game) ++non_game_;
    }
    if (game) {
      done[partner] = 1;
      const HeadState& av = h.kind == VehicleKind::kAV ? h : heads_[partner];
      const HeadState& hv = h.kind == VehicleKind::kAV ? heads_[partner] : h;
      Active e;
      e.out.av = av.vehicle;
      e.out.hv = hv.vehicle;
      e.out.av_movement = av.movement;
      e.out.hv_movement = hv.movement;
      e.out.time = now;
      e.out.draw = model.Draw(av.vehicle, hv.vehicle);
      Command c;
      c.kind = Command::Kind::kStartNudge;
      c.vehicle = av.vehicle;
      c.distance = e.out.draw.nudge_distance;
      out.push_back(c);
      encounters_.push_back(std::move(e));
      last_activity_ = now;
    } else {
      // Alone, or two of a kind: the earlier (this head) goes.
      Release(&out, h.vehicle, h.movement, false, now);
    }
  }
  // Drop the heads that went or met.
  std::vector<HeadState> rest;
  rest.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!done[i]) rest.push_back(heads_[i]);
  heads_.swap(rest);
  return out;
}

std::string JunctionLogic::Describe(const std::function<std::string(int)>& name) const {
  auto mv = [&](int m) {
    const Movement& x = spec_.movements[m];
    return x.from_lane + ">" + x.to_lane;
  };
  std::string out = "waiting:";
  for (const HeadState& h : heads_)
    out += " " + name(h.vehicle) + " (" + mv(h.movement) + ", arrived " +
           std::to_string(h.arrival) + ")";
  out += "; inside:";
  for (const Inside& in : inside_) out += " " + name(in.vehicle) + " (" + mv(in.movement) + ")";
  for (const Active& e : encounters_) {
    out += "; encounter " + name(e.out.av) + "/" + name(e.out.hv) +
           (e.nudged ? " decided" : " nudging") + (e.av_cleared ? ", AV cleared" : "") +
           (e.hv_cleared ? ", HV cleared" : "");
  }
  return out;
}

std::vector<EncounterOutcome> JunctionLogic::TakeFinished() {
  std::vector<EncounterOutcome> out;
  out.swap(finished_);
  return out;
}

}  // namespace taebp::junction
