#include "stalls.h"

#include "figure8.h"

#include <algorithm>
#include <optional>

namespace taebp::control {
namespace {

// What waits at a stalled junction: each incoming lane with halted vehicles,
// its front vehicle and who holds it.
std::string StallDetail(RunState& s, JunctionState& j) {
  std::string out;
  for (const std::string& lane : s.topo.junctions()[s.Index(j)].incoming) {
    const int halting = s.sumo.LaneHaltingNumber(lane);
    if (halting == 0) continue;
    const std::vector<std::string> ids = s.sumo.LaneVehicleIDs(lane);
    if (ids.empty()) continue;
    const std::string& front = ids.back();
    const int h = s.vehicles.Find(front);
    std::string state = "driven by SUMO";
    if (h >= 0) {
      const Vehicle& v = s.vehicles[h];
      state = v.state == State::kHeld       ? "held by the controller"
              : v.state == State::kCrossing ? "released by the controller"
              : v.state == State::kFree     ? "driven by SUMO"
                                            : "nudging";
    }
    const net::Lane* l = s.net.FindLane(lane);
    out += "; lane " + lane + ": " + std::to_string(halting) + " halted, front " + front + " " +
           NumberText((l ? l->length : 0) - s.sumo.LanePosition(front), 6) + " m before the line (" +
           state + ")";
  }
  const std::string held = j.logic->Describe([&](int h) { return s.vehicles[h].id; });
  if (!held.empty()) out += "; " + held;
  return out;
}

}  // namespace

int ApproachHalting(RunState& s, int a) {
  if (s.halting_step != s.step) {
    s.halting.assign(s.approaches.size(), -1);
    s.halting_step = s.step;
  }
  int& n = s.halting[a];
  if (n < 0) n = s.sumo.LaneHaltingNumber(s.topo.approaches()[a].lane);
  return n;
}

void SampleWaiting(RunState& s) {
  for (std::size_t i = 0; i < s.junctions.size(); ++i) {
    JunctionState& j = s.junctions[i];
    const bool was_waiting = j.waiting;
    j.waiting = false;
    const JunctionInfo& info = s.topo.junctions()[i];
    for (std::size_t k = 0; k < info.incoming.size(); ++k)
      if ((info.incoming_approach[k] >= 0 ? ApproachHalting(s, info.incoming_approach[k])
                                          : s.sumo.LaneHaltingNumber(info.incoming[k])) > 0) {
        j.waiting = true;
        break;
      }
    if (j.waiting && !was_waiting) j.waiting_since = s.now;
  }
}

void CheckStalls(RunState& s) {
  std::optional<StallError> error;  // the first, once every stalled junction is recorded
  for (JunctionState& j : s.junctions) {
    const double progress = std::max({j.last_progress, j.logic->LastActivity(), j.waiting_since});
    if (!j.waiting || s.now - progress <= s.stall_limit) {
      if (!j.waiting) j.stall_recorded = false;
      continue;
    }
    if (progress > j.stall_since) j.stall_recorded = false;
    if (j.stall_recorded) continue;
    const JunctionInfo& info = s.topo.junctions()[s.Index(j)];
    const std::string what = "junction '" + info.info.id + "' (" + j.run.rule +
                             "): traffic stalled, vehicles waiting on its incoming lanes and "
                             "none passed it between t = " +
                             NumberText(progress, 6) + " s and t = " + NumberText(s.now, 6) + " s" +
                             figure8::StallAdvice(s);
    j.stall_recorded = true;
    j.stall_since = progress;
    s.out.stalls.push_back({info.info.id, progress, s.now});
    if (s.sc.stall_action == StallAction::kError && s.policy && !error)
      error.emplace(what + StallDetail(s, j), info.info.id, progress, s.now);
  }
  if (error) throw *error;
}

}  // namespace taebp::control
