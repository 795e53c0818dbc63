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

void JunctionLogic::Cleared(int vehicle, double now) {
  last_activity_ = now;
  inside_.erase(std::remove_if(inside_.begin(), inside_.end(),
                               [&](const Inside& in) { return in.vehicle == vehicle; }),
                inside_.end());
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
    if (spec_.Conflict(in.movement, movement)) return true;
  for (const Active& e : encounters_) {
    if (!e.av_cleared && spec_.Conflict(e.out.av_movement, movement)) return true;
    if (!e.hv_cleared && spec_.Conflict(e.out.hv_movement, movement)) return true;
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
  // Encounters in progress: the releases their sequences make due.
  for (Active& e : encounters_) {
    if (!e.sequence) continue;
    for (const auto& rel : e.sequence->Update(now, e.av_cleared, e.hv_cleared)) {
      (rel.av ? e.av_released : e.hv_released) = true;
      Release(&out, rel.av ? e.out.av : e.out.hv, -1, rel.reckless, now);
    }
  }
  if (heads_.empty()) return out;

  // A head that was blocked by a vehicle in the junction is ready again from
  // the moment the junction became free for it.
  const std::size_t n = heads_.size();
  std::vector<char> blocked(n);
  for (std::size_t i = 0; i < n; ++i) {
    HeadState& h = heads_[i];
    blocked[i] = Blocked(h.movement);
    if (blocked[i]) h.ready = std::max(h.ready, now);
  }
  // First come, first served: by arrival. (`ready` only times the look both
  // ways and the meeting window: ordering by it let every later vehicle of a
  // stream that is not blocked overtake a head blocked by the vehicle in
  // front of them, for as long as the stream lasted.)
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
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
      if (ph.ready > h.ready + timing_.arrival_window + eps) continue;
      if (Blocked(ph.movement) || earlier_conflict(q, p, i)) continue;
      if (!has_room(p) || !major_clear(p)) continue;
      partner = p;
      break;
    }
    done[i] = 1;
    if (partner != n && heads_[partner].kind != h.kind) {
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

std::vector<EncounterOutcome> JunctionLogic::TakeFinished() {
  std::vector<EncounterOutcome> out;
  out.swap(finished_);
  return out;
}

}  // namespace taebp::junction
