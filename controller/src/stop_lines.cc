#include "stop_lines.h"

#include "figure8.h"
#include "route_progress.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace taebp::control {
namespace {

constexpr double kMajorNear = 3.0;  // m: a major-road vehicle this near the line is entering

// A free vehicle that was the front of a watched lane (approach `a`) is no
// longer (SUMO let it go, it changed lanes, or the junction is no longer
// watched). Already the front of another lane: that lane's now.
void LeftLine(RunState& s, int h, int a) {
  Vehicle& v = s.vehicles[h];
  if (v.state != State::kFree || v.approach != a) return;
  v.line_since = -1;
  v.movement = v.junction = v.approach = -1;
}

}  // namespace

void ApproachDeparture(RunState& s, const std::string& edge) {
  for (int a : s.topo.ApproachesOfEdge(edge)) s.approaches[a].next_look = 0;
}

void SpeedFactorSeen(RunState& s, double factor) {
  if (factor <= s.max_speed_factor) return;
  s.max_speed_factor = factor;
  for (ApproachState& ap : s.approaches) ap.next_look = 0;  // the bounds were too tight
}

bool Watched(RunState& s, JunctionState& j) {
  const bool watched = (j.near_av > 0 && j.near_hv > 0) || j.logic->Busy();
  if (!watched && j.watched) {
    for (int a : s.topo.junctions()[s.Index(j)].approaches) {
      if (s.approaches[a].front >= 0) LeftLine(s, s.approaches[a].front, a);
      s.approaches[a].front = -1;
    }
  }
  j.watched = watched;
  return watched;
}

// The steps until a vehicle `dist` metres farther from the line than the
// reach of a meeting can be within it: nobody drives faster than the lane's
// limit times the largest speed factor of any vehicle.
long StepsAway(const RunState& s, const ApproachInfo& info, double dist) {
  const double vmax = info.speed * s.max_speed_factor;
  if (vmax <= 0 || dist <= 0) return 1;
  return std::max(1L, static_cast<long>(std::floor(dist / (vmax * s.dt))));
}

void Observe(RunState& s, JunctionState& j) {
  j.at_line.clear();
  const int jx = s.Index(j);
  const double reach = std::max(s.sc.meeting_distance, kAtLine);
  for (int a : s.topo.junctions()[jx].approaches) {
    const ApproachInfo& info = s.topo.approaches()[a];
    ApproachState& ap = s.approaches[a];
    // Nobody can be near this line yet (a vehicle departing onto its edge
    // brings the look forward: ApproachDeparture).
    if (s.step < ap.next_look) continue;
    ap.next_look = s.step + 1;
    int h = -1;
    // One read of the lane (its ids: none when empty), not a count and then the ids.
    const std::vector<std::string> ids = s.sumo.LaneVehicleIDs(info.lane);
    const bool empty = ids.empty();
    if (!empty) h = s.vehicles.Find(ids.back());
    // Only lanes no vehicle can change into ahead of their front.
    if (empty && info.only_lane) ap.next_look = s.step + StepsAway(s, info, info.length - reach);
    if (ap.front >= 0 && ap.front != h) LeftLine(s, ap.front, a);
    ap.front = h;
    if (h < 0) continue;
    Vehicle& v = s.vehicles[h];
    if (v.state == State::kHeld) {
      if (v.movement >= 0) j.at_line.push_back({h, v.kind, v.movement, true, v.line_since});
      continue;
    }
    if (v.state != State::kFree) continue;
    // New at the front of this lane: coming to this junction, or having
    // changed lanes on its way (its movement is the new lane's).
    if (v.junction != jx || v.approach != a) {
      if (v.junction != jx) {
        CountProgress(s, h, s.sumo.RouteIndex(v.id));
        figure8::KeepCirculating(s, h);
      }
      v.junction = jx;
      v.approach = a;
      const int next = v.route_pos + 1;
      v.movement = next < static_cast<int>(v.route.size())
                       ? s.topo.MovementFor(jx, info.lane, s.topo.EdgeName(v.route[next]))
                       : -1;
      v.line_since = -1;
    }
    if (v.movement < 0) continue;  // e.g. needs another lane for its next edge
    const double gap = info.length - s.sumo.LanePosition(v.id);
    if (gap > reach) {
      if (info.only_lane) ap.next_look = s.step + StepsAway(s, info, gap - reach);
      continue;
    }
    const bool waiting = gap <= kAtLine && s.sumo.Speed(v.id) < kSlow;
    if (waiting && v.line_since < 0) v.line_since = s.now;
    if (!waiting) v.line_since = -1;
    v.line_gap = waiting ? gap : kStopGap;
    j.at_line.push_back({h, v.kind, v.movement, waiting, v.line_since});
  }
}

namespace {

// Whether vehicle `cv`, on feeder lane `fl` `offset` m upstream of the
// approach lane (0: on it), has `edge` (the approach lane's) ahead on its
// route; `k`: where `edge` is on it.
bool GoesThrough(const RunState& s, const Vehicle& cv, const net::Lane* fl, double offset,
                 const std::string& edge, std::size_t* k) {
  const std::size_t from = static_cast<std::size_t>(std::max(0, cv.route_pos));
  *k = from;
  while (*k < cv.route.size() && s.topo.EdgeName(cv.route[*k]) != edge) ++*k;
  bool through = *k < cv.route.size();
  // On a node's internal lane upstream: on its way into the feeders
  // (the lane leads there) when its route goes on through `lane`.
  const bool connector = fl && !fl->edge.empty() && fl->edge[0] == ':';
  if (through && offset > 0 && !connector) {  // upstream: its own edge comes before `lane`'s
    through = false;
    for (std::size_t q = from; q < *k; ++q)
      if (fl && s.topo.EdgeName(cv.route[q]) == fl->edge) through = true;
  }
  return through;
}

}  // namespace

void ObserveMajor(RunState& s, JunctionState& j) {
  j.major.clear();
  if (!s.sc.MajorRoadGame()) return;
  const bool av_waits = std::any_of(j.at_line.begin(), j.at_line.end(), [](const junction::AtLine& a) {
    return a.kind == VehicleKind::kAV && a.waiting;
  });
  if (!av_waits) return;
  const int jx = s.Index(j);
  const JunctionInfo& info = s.topo.junctions()[jx];
  for (const std::string& lane : info.major_lanes) {
    const net::Lane* l = s.net.FindLane(lane);
    if (!l) continue;
    // The first vehicle coming to this lane's line: its front vehicle, or,
    // with the lane empty, the nearest front of the lanes feeding it whose
    // route goes on through it (OSM approach lanes are often shorter than the
    // game's window: the HV is still upstream when the window opens).
    const MovementInfo* feeds = nullptr;
    for (const MovementInfo& m : info.movements)
      if (!m.controlled && m.from_lane == lane) feeds = &m;
    if (!feeds) continue;
    int h = -1;
    std::size_t on_route = 0;  // where `lane`'s edge is on its route
    double gap = 0;
    bool blocked = false;  // the nearest vehicle is not one the controller knows
    bool upstream = false;  // it is on a feeder, not the approach lane
    std::string on_lane;
    for (const auto& [feeder, offset] : feeds->feeders) {
      const std::vector<std::string> ids = s.sumo.LaneVehicleIDs(feeder);
      if (ids.empty()) continue;
      const net::Lane* fl = s.net.FindLane(feeder);
      // Front first: the first vehicle on this lane whose route goes on
      // through `lane` (on the approach lane itself, its front vehicle).
      for (auto id = ids.rbegin(); id != ids.rend(); ++id) {
        const double d = offset + (fl ? fl->length : 0) - s.sumo.LanePosition(*id);
        if ((h >= 0 || blocked) && d >= gap) break;
        const int c = s.vehicles.Find(*id);
        if (c < 0) {
          blocked = true;
          h = -1;
          gap = d;
          break;
        }
        std::size_t k = 0;
        const bool through = GoesThrough(s, s.vehicles[c], fl, offset, l->edge, &k);
        if (offset > 0 && !through) continue;  // turns off before: not in the way
        blocked = false;
        h = c;
        gap = d;
        on_route = k;
        upstream = offset > 0;
        on_lane = feeder;
        break;
      }
    }
    if (h < 0 || blocked) continue;
    // Upstream only where its way to the approach lane has the right of way.
    if (upstream && !feeds->IsUpstream(on_lane)) continue;
    const Vehicle& v = s.vehicles[h];
    if (v.kind != VehicleKind::kHV || v.state != State::kFree) continue;
    // Its next edge after this lane's.
    int movement = -1;
    if (on_route + 1 < v.route.size())
      movement = s.topo.MajorMovementFor(jx, lane, s.topo.EdgeName(v.route[on_route + 1]));
    // Only a movement with the right of way over every foe (SUMO's 'M'): an
    // HV keeping its way there does what SUMO's rules let it (a major left
    // turn yields to the oncoming major road, which a cruising HV would ignore).
    if (movement < 0 || s.topo.junctions()[jx].movements[movement].state != 'M') continue;
    const double speed = s.sumo.Speed(v.id);
    if (speed < kSlow) continue;  // a halted major vehicle yields under SUMO's rules
    j.major.push_back({h, movement, gap, speed});
  }
}

StopLineEnvironment::StopLineEnvironment(RunState& s, const JunctionState& j)
    : s_(s), info_(s.topo.junctions()[s.Index(j)]) {}

// A held vehicle has come to a standstill: the nudge is measured from here.
bool StopLineEnvironment::Standing(int h) {
  Vehicle& v = s_.vehicles[h];
  if (s_.sumo.Speed(v.id) > 0.0) return false;
  v.hold_odometer = s_.sumo.Distance(v.id);
  return true;
}

// Every vehicle inside the junction on a movement conflicting with the
// vehicle's own (SUMO's foes: crossing or merging) has passed its way, or
// stands still clear of it (its body where it stands) and was not let past
// a nudged AV. Vehicles ahead on its own movement are its leaders:
// car-following keeps it behind them, whatever its speed mode.
bool StopLineEnvironment::WayClear(int vehicle, int partner) {
  return WayClearAgainst(vehicle, partner, false);
}

bool StopLineEnvironment::WayClearOfStarters(int vehicle, int partner) {
  return WayClearAgainst(vehicle, partner, true);
}

bool StopLineEnvironment::WayClearAgainst(int vehicle, int partner, bool starters) {
  const int movement = s_.vehicles[vehicle].movement;
  std::optional<junction::Mover> mine;  // read once someone is inside
  for (const Inside& x : VehiclesInside()) {
    if (x.vehicle == vehicle || x.vehicle == partner) continue;
    if (!info_.spec.Conflict(x.movement, movement)) continue;
    if (x.vehicle < 0 || x.mover.front < 0) return false;
    if (!mine) mine = MoverNow(vehicle);
    // One let past a nudged AV (Unblockable) goes though it stands yet: it
    // may start any step (issue 30: the left turn at D1 let past at 341.8 s
    // still stood when the HV was released, then went into it). `starters`:
    // so may one standing clear of `vehicle` as it stands (not held by it).
    bool stays = x.still && !s_.vehicles[x.vehicle].unblocked;
    if (stays && starters) stays = !junction::PassedWay(*mine, x.mover, 0.0);
    if (!junction::PassedWay(x.mover, *mine, stays ? 0.0 : -1.0)) return false;
  }
  return true;
}

// Keep clear: a head enters only if its exit can take it with its rear off
// the junction. Two forms of one rule, by what the exit can be relied on to
// do: closed loops (the figure-8: figure8::ExitHasRoom) and open networks,
// where vehicles on the exit move on through the next junction, so the exit
// needs room behind its last vehicle now, less the vehicles already released
// towards it (SUMO's own keepClear does the same). Either way, the vehicles
// headed into this exit and not yet on it count: those inside the junction on
// a movement into it (whoever drives them), and encounter vehicles released
// towards it still on their approach lanes.
bool StopLineEnvironment::ExitHasRoom(int movement, int vehicle) {
  const MovementInfo& m = info_.movements[movement];
  const Vehicle& v = s_.vehicles[vehicle];
  long inflight = 0;
  for (const MovementInfo& k : info_.movements) {
    if (k.exit != m.exit) continue;
    for (const std::string& in : k.internal) {
      for (const std::string& id : s_.sumo.LaneVehicleIDs(in)) inflight += id != v.id;  // a nudged AV
    }
  }
  for (int h : s_.crossing) {
    const Vehicle& w = s_.vehicles[h];
    if (w.junction < 0) continue;
    const MovementInfo& wm = s_.topo.junctions()[w.junction].movements[w.movement];
    if (wm.exit == m.exit && w.lane == wm.from_lane) ++inflight;
  }
  if (figure8::IsFigure8(s_)) return figure8::ExitHasRoom(s_, s_.topo.exit(m.exit), inflight, vehicle);
  const double unit = v.length + v.min_gap;
  const std::vector<std::string> ids = s_.sumo.LaneVehicleIDs(m.to_lane);
  const net::Lane* exit = s_.net.FindLane(m.to_lane);
  double free = exit ? exit->length : 0;
  if (ids.empty() && inflight == 0) return true;  // an empty exit, however short
  if (!ids.empty()) free = s_.sumo.LanePosition(ids.front()) - s_.sumo.Length(ids.front());
  return free - inflight * unit >= unit;
}

// An AV nudged past its line stands here on a movement in conflict with
// `movement`: SUMO may hold that movement's vehicles for it.
bool StopLineEnvironment::NudgedAvInConflictWith(int movement) {
  for (const auto& [id, h] : s_.vehicles.in_network()) {
    const Vehicle& v = s_.vehicles[h];
    if (v.kind != VehicleKind::kAV || v.junction < 0 || v.movement < 0 ||
        &s_.topo.junctions()[v.junction] != &info_)
      continue;
    if (v.state != State::kNudging && v.state != State::kNudged) continue;
    if (info_.spec.Conflict(v.movement, movement) && PastLine(h)) return true;
  }
  return false;
}

// Two-way stops: no major vehicle inside or about to reach a conflicting
// major movement within the critical gap. Inside the junction a halted
// vehicle is traffic too (a major left turn halted at its internal stop
// point goes once the opposing road is clear, and a move released with
// SUMO's right of way off would hit it: issue 30), unless an AV nudged past
// its line stands in its way (SUMO holds it for that AV; waiting for it
// would wait for ever). Approaching: MajorComes.
bool StopLineEnvironment::MajorClear(int movement) {
  auto moving = [&](const std::string& id) { return s_.sumo.Speed(id) >= kHaltSpeed; };
  for (int k : info_.movements[movement].major_foes) {
    const MovementInfo& mk = info_.movements[k];
    for (const std::string& in : mk.internal) {
      for (const std::string& id : s_.sumo.LaneVehicleIDs(in))
        if (moving(id) || !NudgedAvInConflictWith(k)) return false;
    }
    for (const auto& [lane, offset] : mk.feeders)
      if (MajorComes(k, lane, offset, s_.sc.critical_gap)) return false;
  }
  return true;
}

// The front vehicle of `lane` (feeding major movement `k`, `offset` m before
// its approach lane's end) may enter on `k` within `gap` s. At its line it
// may, halted or not: `k` has the right of way over the movement asked
// about, so SUMO starts it whenever its own foes and its exit let it and
// does not hold it for a move of the game (on the two-way grid, seed 3, No
// Trust: a major left turn halted at its line for its full exit was taken
// for a yielding vehicle, the reckless HV was released beside it, and when
// the exit had room both started in the same step and collided), unless an
// AV nudged past its line stands in its way (SUMO holds it for that AV).
// Farther back, a halted front is yielding or queued and comes to the line
// only by moving; a moving one comes when it reaches the line, accelerating
// from its speed now, within `gap`.
bool StopLineEnvironment::MajorComes(int k, const std::string& lane, double offset, double gap) {
  const std::vector<std::string> ids = s_.sumo.LaneVehicleIDs(lane);
  if (ids.empty()) return false;
  const std::string& front = ids.back();
  const double speed = s_.sumo.Speed(front);
  const net::Lane* l = s_.net.FindLane(lane);
  const double dist = offset + (l ? l->length : 0) - s_.sumo.LanePosition(front);
  if (dist < kMajorNear) return speed >= kHaltSpeed || !NudgedAvInConflictWith(k);
  if (speed < kHaltSpeed) return false;
  const double reach = (-speed + std::sqrt(speed * speed + 2.0 * s_.sc.accel * dist)) / s_.sc.accel;
  return reach < gap;
}

// The major-road encounter: MajorClear, but the HV of the encounter and the
// vehicles behind it on its lane (and the lanes feeding it) are its own
// traffic, and the gap must last `extra` s longer (the signal).
bool StopLineEnvironment::MajorClearBut(int movement, int hv, int hv_movement, double extra) {
  const Vehicle& h = s_.vehicles[hv];
  std::vector<std::string> own;  // its approach lane and the lanes feeding it
  for (const auto& [lane, offset] : info_.movements[hv_movement].feeders) own.push_back(lane);
  auto mine = [&](const std::string& lane) {
    return std::find(own.begin(), own.end(), lane) != own.end();
  };
  auto moving = [&](const std::string& id) { return s_.sumo.Speed(id) >= kHaltSpeed; };
  for (int k : info_.movements[movement].major_foes) {
    const MovementInfo& mk = info_.movements[k];
    for (const std::string& in : mk.internal) {
      for (const std::string& id : s_.sumo.LaneVehicleIDs(in))
        if (id != h.id && moving(id)) return false;
    }
    for (const auto& [lane, offset] : mk.feeders)
      if (!mine(lane) && MajorComes(k, lane, offset, s_.sc.critical_gap + extra)) return false;
  }
  return true;
}

// SUMO moves a vehicle onto the junction's internal lane when its front
// passes the end of its approach lane (the stop line).
bool StopLineEnvironment::PastLine(int vehicle) {
  const Vehicle& v = s_.vehicles[vehicle];
  const MovementInfo& m = info_.movements[v.movement];
  const std::string lane = s_.sumo.LaneID(v.id);
  return lane != m.from_lane && !m.IsUpstream(lane);
}

junction::Mover StopLineEnvironment::MoverNow(int vehicle) {
  const Vehicle& v = s_.vehicles[vehicle];
  const MovementInfo& m = info_.movements[v.movement];
  junction::Mover mv = m.mover;
  mv.length = v.length;
  mv.width = v.width;
  const std::optional<double> arc = m.PathArc(s_.sumo.LaneID(v.id), s_.sumo.LanePosition(v.id));
  // Off its path (e.g. already behind the exit lane): past everything.
  mv.front = arc ? *arc : mv.exit + mv.length;
  return mv;
}

bool StopLineEnvironment::Passed(int first, int second) {
  return junction::PassedWay(MoverNow(first), MoverNow(second));
}

const std::vector<StopLineEnvironment::Inside>& StopLineEnvironment::VehiclesInside() {
  if (inside_) return *inside_;
  std::vector<Inside>& out = inside_.emplace();
  for (std::size_t k = 0; k < info_.movements.size(); ++k) {
    const MovementInfo& mk = info_.movements[k];
    for (const std::string& in : mk.internal) {
      for (const std::string& id : s_.sumo.LaneVehicleIDs(in)) {
        Inside x;
        x.vehicle = s_.vehicles.Find(id);
        x.movement = static_cast<int>(k);
        x.mover = mk.mover;
        if (x.vehicle >= 0) {
          x.mover.length = s_.vehicles[x.vehicle].length;
          x.mover.width = s_.vehicles[x.vehicle].width;
        }
        x.mover.front = mk.ArcOf(in, s_.sumo.LanePosition(id));
        x.still = s_.sumo.Speed(id) < kHaltSpeed;
        out.push_back(x);
      }
    }
  }
  return out;
}

// The still, free vehicles inside the junction on movements conflicting with
// `vehicle`'s that stand in its way, each of which has a clear way itself:
// every other vehicle inside on a movement conflicting with its own, moving
// on its way or still where it stands (the nudged AV among them), does not
// touch it.
std::vector<int> StopLineEnvironment::Unblockable(int vehicle, int partner) {
  return UnblockableAgainst(vehicle, partner, false);
}

std::vector<int> StopLineEnvironment::UnblockableStarters(int vehicle, int partner) {
  return UnblockableAgainst(vehicle, partner, true);
}

// `starters`: in `vehicle`'s way when it moves on (not only where it stands).
std::vector<int> StopLineEnvironment::UnblockableAgainst(int vehicle, int partner, bool starters) {
  std::vector<int> out;
  const int movement = s_.vehicles[vehicle].movement;
  const std::vector<Inside>& inside = VehiclesInside();
  std::optional<junction::Mover> mine;
  for (const Inside& b : inside) {
    if (!b.still || b.vehicle < 0 || b.vehicle == vehicle || b.vehicle == partner) continue;
    const Vehicle& bv = s_.vehicles[b.vehicle];
    if (bv.state != State::kFree || bv.unblocked || b.mover.front < 0) continue;  // let past already
    if (!info_.spec.Conflict(b.movement, movement)) continue;
    if (!mine) mine = MoverNow(vehicle);
    if (junction::PassedWay(b.mover, *mine, starters ? -1.0 : 0.0)) continue;  // not in its way
    bool free = true;
    for (const Inside& x : inside) {
      if (&x == &b || !info_.spec.Conflict(x.movement, b.movement)) continue;
      if (x.mover.front < 0 || !junction::PassedWay(x.mover, b.mover, x.still ? 0.0 : -1.0)) {
        free = false;
        break;
      }
    }
    if (free) out.push_back(b.vehicle);
  }
  return out;
}

}  // namespace taebp::control
