#include "figure8.h"


#include <algorithm>
#include <array>

namespace taebp::control::figure8 {
namespace {

std::string LapRoute(const std::string& edge) { return "lap_" + edge; }

std::vector<std::string> LapFrom(const RunState& s, std::size_t start) {
  std::vector<std::string> route;
  for (std::size_t i = 0; i < 4; ++i) route.push_back(s.scenario.lap[(start + i) % 4]);
  return route;
}

}  // namespace

bool IsFigure8(const RunState& s) { return !s.scenario.lap.empty(); }

void PlaceVehicles(RunState& s) {
  if (s.scenario.placed.empty()) return;
  const ScenarioConfig& sc = s.sc;
  s.sumo.AddVehicleType({"AV", sc.cruise_speed, sc.min_gap, sc.vehicle_length, sc.vehicle_width,
                         sc.accel, sc.decel, kAvRgb[0], kAvRgb[1], kAvRgb[2]});
  s.sumo.AddVehicleType({"HV", sc.cruise_speed, sc.min_gap, sc.vehicle_length, sc.vehicle_width,
                         sc.accel, sc.decel, kHvRgb[0], kHvRgb[1], kHvRgb[2]});
  for (std::size_t i = 0; i < s.scenario.lap.size(); ++i)
    s.sumo.AddRoute(LapRoute(s.scenario.lap[i]), LapFrom(s, i));
  for (const PlacedVehicle& v : s.scenario.placed)
    s.sumo.AddVehicle(v.id, LapRoute(v.route.front()), v.is_av ? "AV" : "HV", v.depart_pos);
}

void KeepCirculating(RunState& s, int h) {
  Vehicle& v = s.vehicles[h];
  if (!IsFigure8(s) || v.route_pos + 1 < static_cast<int>(v.route.size())) return;
  const std::string edge = s.sumo.RoadID(v.id);
  const auto it = std::find(s.scenario.lap.begin(), s.scenario.lap.end(), edge);
  if (it == s.scenario.lap.end()) return;
  s.sumo.SetRouteID(v.id, LapRoute(edge));
  v.route.clear();
  for (const std::string& e : LapFrom(s, static_cast<std::size_t>(it - s.scenario.lap.begin())))
    v.route.push_back(s.topo.EdgeIndex(e));
  v.route_pos = 0;
}

void AddCentre(const RunState& s, std::vector<int>* near) {
  if (IsFigure8(s) && near->empty()) near->push_back(0);
}

bool ExitHasRoom(RunState& s, const Exit& exit, long inflight, int h) {
  const Vehicle& v = s.vehicles[h];
  const double unit = v.length + v.min_gap;
  long ahead = inflight;
  for (const std::string& lane : exit.lanes) ahead += s.sumo.LaneVehicleNumber(lane);
  return ahead * unit + v.length <= exit.capacity;
}

// (A figure-8 from a user's network file has no loop length: a network's
// limit and advice.)
double DefaultStallLimit(const RunState& s) {
  if (s.scenario.loop_length <= 0) return 120.0;
  // Free flow crosses at least once per loop; allow a full lap, the
  // controller's own waits and a minute.
  return 2 * s.scenario.loop_length / s.sc.cruise_speed + s.sc.confirm_delay + 60.0;
}

std::string StallAdvice(const RunState& s) {
  if (s.scenario.loop_length <= 0)
    return " (gridlock: lower the demand, or set scenario.stall_action: record to measure it)";
  return " (scenario.loop_length = " + NumberText(s.scenario.loop_length, 6) +
         " m; try a longer track or fewer vehicles)";
}

}  // namespace taebp::control::figure8
