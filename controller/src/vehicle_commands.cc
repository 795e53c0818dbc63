#include "vehicle_commands.h"

#include <algorithm>
#include <array>

namespace taebp::control {
namespace {

using junction::Command;

constexpr std::array<std::array<int, 3>, 5> kPaintRgb = {
    {{0, 0, 0}, {255, 220, 0}, {255, 140, 0}, {0, 200, 0}, {255, 0, 255}}};

}  // namespace

void VehicleCommands::Execute(JunctionState& j, const Command& c) {
  switch (c.kind) {
    case Command::Kind::kHold:
      Hold(j, c.vehicle);
      break;
    case Command::Kind::kStartNudge:
      StartNudge(c.vehicle, c.distance, c.duration);
      break;
    case Command::Kind::kCruise:
      Cruise(j, c.vehicle, c.movement, c.speed, c.partner);
      break;
    case Command::Kind::kYield:
      Yield(c.vehicle, c.speed, c.delay);
      break;
    case Command::Kind::kRelease:
      Release(j, c.vehicle, c.partner);
      break;
    case Command::Kind::kHandBack:
      if (c.in_encounter) {
        Release(j, c.vehicle, -1);
      } else {
        HandBack(j, c.vehicle);
      }
      break;
    case Command::Kind::kUnblock:
      Unblock(c.vehicle);
      break;
  }
}

void VehicleCommands::Unblock(int h) {
  Vehicle& v = s_.vehicles[h];
  if (v.unblocked || v.state != State::kFree) return;
  s_.sumo.SetSpeedMode(v.id, kModeUnblocked);
  v.unblocked = true;
  s_.unblocked.push_back(h);
  if (s_.measuring()) ++s_.out.unblocked;
}

void VehicleCommands::UpdateUnblocked() {
  const std::vector<int> now_unblocked = s_.unblocked;
  for (int h : now_unblocked) {
    Vehicle& v = s_.vehicles[h];
    if (v.alive) {
      const std::string lane = s_.sumo.LaneID(v.id);
      if (!lane.empty() && lane[0] == ':') continue;  // still inside
      s_.sumo.SetSpeedMode(v.id, kModeDefault);
    }
    v.unblocked = false;
    s_.unblocked.erase(std::remove(s_.unblocked.begin(), s_.unblocked.end(), h),
                       s_.unblocked.end());
  }
}

void VehicleCommands::SetPaint(int h, Paint paint) {
  Vehicle& v = s_.vehicles[h];
  if (!s_.opts.colour_states || v.paint == paint) return;
  const int* rgb = paint != Paint::kType ? kPaintRgb[static_cast<int>(paint)].data()
                   : v.kind == VehicleKind::kAV ? kAvRgb
                                                : kHvRgb;
  s_.sumo.SetColor(v.id, rgb[0], rgb[1], rgb[2]);
  v.paint = paint;
}

void VehicleCommands::Hold(JunctionState& j, int h) {
  Vehicle& v = s_.vehicles[h];
  s_.sumo.SetSpeed(v.id, 0.0);
  if (v.state != State::kHeld) s_.sumo.SetLaneChangeMode(v.id, kLaneChangeHeld);
  v.state = State::kHeld;
  v.junction = s_.Index(j);
  v.held_since = s_.now;
}

void VehicleCommands::CountWait(JunctionState& j, const Vehicle& v) {
  if (!s_.measuring()) return;
  const double wait = s_.now - v.held_since;
  j.run.wait_sum += wait;
  j.run.wait_max = std::max(j.run.wait_max, wait);
  ++j.run.held;
  if (v.kind == VehicleKind::kAV) {
    ++j.run.held_av;
    j.run.wait_sum_av += wait;
  }
}

// A move of the game: SUMO's right of way off (kModeReleased), its partner
// named to SUMO as the vehicle it disregards (junctionModel.ignoreIDs, no
// effect under mode 55; the hook for keeping SUMO's right of way toward
// third vehicles, run_state.h and docs/encounter-rules.md).
void VehicleCommands::GameMove(Vehicle& v, int partner, const JunctionState& j) {
  (void)j;
  s_.sumo.SetSpeedMode(v.id, kModeReleased);
  s_.sumo.SetIgnoredFoes(v.id, {s_.vehicles[partner].id});
  v.ignoring = true;
}

void VehicleCommands::StopIgnoring(Vehicle& v) {
  if (!v.ignoring) return;
  v.ignoring = false;
  if (v.alive) s_.sumo.SetIgnoredFoes(v.id, {});
}

// A major-road HV of an encounter: it keeps `speed` disregarding the AV's
// right of way (it does not brake for the AV nudged into the junction; a
// move of the game: GameMove), in its lane, watched until it has left the
// junction.
void VehicleCommands::Cruise(JunctionState& j, int h, int movement, double speed, int partner) {
  Vehicle& v = s_.vehicles[h];
  v.movement = movement;
  GameMove(v, partner, j);
  s_.sumo.SetLaneChangeMode(v.id, kLaneChangeHeld);
  s_.sumo.SetSpeed(v.id, speed);
  v.major_hv = true;
  v.commanded_speed = true;
  v.major_speed = speed;
  v.state = State::kCrossing;
  v.reckless = true;
  v.entered = false;
  v.junction = s_.Index(j);
  v.lane = s_.topo.junctions()[s_.Index(j)].movements[v.movement].from_lane;
  s_.crossing.push_back(h);
}

// DC: it brakes at `decel` from `delay` s on (UpdateYields), to a stop at most.
void VehicleCommands::Yield(int h, double decel, double delay) {
  Vehicle& v = s_.vehicles[h];
  v.yielding = true;
  v.yield_from = s_.now + delay;
  v.yield_decel = decel;
  s_.yielding.push_back(h);
  SetPaint(h, Paint::kDc);
  YieldStep(v);  // with no reaction time it brakes in the step after its decision
}

void VehicleCommands::YieldStep(Vehicle& v) {
  if (s_.now < v.yield_from - 1e-9 || v.major_speed <= 0) return;
  v.major_speed = std::max(0.0, v.major_speed - v.yield_decel * s_.dt);
  s_.sumo.SetSpeed(v.id, v.major_speed);
}

void VehicleCommands::StopYield(int h) {
  Vehicle& v = s_.vehicles[h];
  if (!v.yielding) return;
  v.yielding = false;
  s_.yielding.erase(std::remove(s_.yielding.begin(), s_.yielding.end(), h), s_.yielding.end());
}

void VehicleCommands::UpdateYields() {
  for (int h : s_.yielding) YieldStep(s_.vehicles[h]);
}

// `partner` >= 0: a move of the game (GameMove); else a careful move under
// SUMO's own rules.
void VehicleCommands::Release(JunctionState& j, int h, int partner) {
  Vehicle& v = s_.vehicles[h];
  const bool reckless = partner >= 0;
  auto rules = [&] {
    if (reckless) {
      GameMove(v, partner, j);
    } else {
      s_.sumo.SetSpeedMode(v.id, kModeDefault);
      StopIgnoring(v);
    }
  };
  if (v.major_hv) {  // already watched (kCruise): its own speed again, right of way as said
    StopYield(h);
    rules();
    s_.sumo.SetLaneChangeMode(v.id, kLaneChangeDefault);
    s_.sumo.SetSpeed(v.id, -1);
    v.commanded_speed = false;
    v.reckless = reckless;
    return;
  }
  rules();
  s_.sumo.SetLaneChangeMode(v.id, kLaneChangeDefault);
  s_.sumo.SetSpeed(v.id, -1);
  CountWait(j, v);
  v.state = State::kCrossing;
  v.reckless = reckless;
  v.entered = false;
  v.lane = s_.topo.junctions()[s_.Index(j)].movements[v.movement].from_lane;
  s_.crossing.push_back(h);
}

void VehicleCommands::HandBack(JunctionState& j, int h) {
  Vehicle& v = s_.vehicles[h];
  s_.sumo.SetLaneChangeMode(v.id, kLaneChangeDefault);
  s_.sumo.SetSpeed(v.id, -1);
  CountWait(j, v);
  v.state = State::kFree;  // still its lane's front: Observe goes on looking
}

void VehicleCommands::Clear(int h) {
  Vehicle& v = s_.vehicles[h];
  s_.junctions[v.junction].logic->Cleared(h, s_.now);
  s_.crossing.erase(std::remove(s_.crossing.begin(), s_.crossing.end(), h), s_.crossing.end());
  v.state = State::kFree;
  v.junction = v.movement = v.approach = -1;
  v.line_since = -1;
  const bool major_hv = v.major_hv, commanded_speed = v.commanded_speed;
  StopYield(h);
  v.major_hv = v.commanded_speed = false;
  StopIgnoring(v);
  if (!v.alive) return;
  if (v.reckless) s_.sumo.SetSpeedMode(v.id, kModeDefault);
  if (major_hv) s_.sumo.SetLaneChangeMode(v.id, kLaneChangeDefault);
  if (commanded_speed) s_.sumo.SetSpeed(v.id, -1);
  v.reckless = false;
  SetPaint(h, Paint::kType);
}

bool VehicleCommands::ClearedJunction(const Vehicle& v, const std::string& lane) {
  const MovementInfo& m = s_.topo.junctions()[v.junction].movements[v.movement];
  if (lane == m.from_lane || m.IsUpstream(lane)) return false;  // a major HV not there yet
  if (std::find(m.internal.begin(), m.internal.end(), lane) != m.internal.end()) return false;
  if (!lane.empty() && lane[0] == ':') return false;  // some other internal lane
  if (lane == m.to_lane) return s_.sumo.LanePosition(v.id) >= v.length;
  return true;
}

void VehicleCommands::UpdateCrossing() {
  const std::vector<int> now_crossing = s_.crossing;
  for (int h : now_crossing) {
    Vehicle& v = s_.vehicles[h];
    v.lane = s_.sumo.LaneID(v.id);
    if (ClearedJunction(v, v.lane)) {
      Clear(h);
    } else if (const MovementInfo& m = s_.topo.junctions()[v.junction].movements[v.movement];
               !v.entered && v.lane != m.from_lane && !m.IsUpstream(v.lane)) {
      v.entered = true;  // inside the junction: a careful partner may follow it under SUMO's rules
      s_.junctions[v.junction].logic->Entered(h, s_.now);
    }
  }
}

void VehicleCommands::StartNudge(int h, double distance, double duration) {
  Vehicle& v = s_.vehicles[h];
  v.commanded = distance;
  v.nudge_until = s_.now + duration;
  if (distance <= 0.0 && duration > 0.0) {  // a still AV: it stands as long as the signal lasts
    v.target = 0;
    v.creep_speed = 0;
    v.state = State::kNudging;
    s_.nudging.push_back(h);
    return;
  }
  if (distance <= 0.0) {
    v.state = State::kNudged;
    FinishNudge(h, s_.sumo.Distance(v.id) - v.hold_odometer);
    return;
  }
  v.target = distance + kNudgeOvershoot;
  s_.sumo.SetSpeedMode(v.id, kModeCreep);
  v.state = State::kNudging;
  SetPaint(h, Paint::kNudging);
  v.creep_speed =
      CreepSpeed(v.target, 0.0, 0.0, s_.dt, s_.sc.accel, s_.sc.decel, s_.sc.creep_speed);
  s_.sumo.SetSpeed(v.id, v.creep_speed);
  s_.nudging.push_back(h);
}

void VehicleCommands::UpdateNudges() {
  const std::vector<int> now_nudging = s_.nudging;
  for (int h : now_nudging) {
    Vehicle& v = s_.vehicles[h];
    const double covered = s_.sumo.Distance(v.id) - v.hold_odometer;
    const double speed =
        v.target <= 0.0 ? 0.0
                        : CreepSpeed(v.target, covered, v.creep_speed, s_.dt, s_.sc.accel,
                                     s_.sc.decel, s_.sc.creep_speed);
    if (speed <= 0.0 && v.creep_speed <= 0.0 && s_.now >= v.nudge_until - 1e-9) {
      s_.nudging.erase(std::remove(s_.nudging.begin(), s_.nudging.end(), h), s_.nudging.end());
      v.state = State::kNudged;
      FinishNudge(h, covered);
    } else {
      v.creep_speed = speed;
      s_.sumo.SetSpeed(v.id, speed);
    }
  }
}

// The run checks every realised nudge: s <= d <= s + tolerance (a still AV:
// |d| <= tolerance). The HV reads what SUMO reported.
void VehicleCommands::FinishNudge(int h, double observed) {
  Vehicle& v = s_.vehicles[h];
  const double s = v.commanded;
  if (!NudgeRealised(s, observed, kNudgeTolerance)) {
    if (s_.sc.nudge_check == NudgeCheck::kError)
      throw NudgeError("junction '" + s_.topo.junctions()[v.junction].info.id + "', AV " + v.id +
                       " at t = " + NumberText(s_.now, 6) + " s: commanded nudge " + NumberText(s, 6) +
                       " m, SUMO reported " + NumberText(observed, 6) + " m (tolerance " +
                       NumberText(kNudgeTolerance, 6) +
                       " m); set scenario.nudge_check: count to record it and go on");
    ++s_.out.nudges_unrealised;
  }
  s_.junctions[v.junction].logic->NudgeDone(h, observed, s_.now, model_);
}

}  // namespace taebp::control
