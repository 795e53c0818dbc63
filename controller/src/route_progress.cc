#include "route_progress.h"

#include "figure8.h"

#include <algorithm>
#include <utility>

namespace taebp::control {

void CountProgress(RunState& s, int h, int new_pos) {
  Vehicle& v = s.vehicles[h];
  const int last = static_cast<int>(v.route.size()) - 1;
  new_pos = std::min(new_pos, last);
  for (int k = v.route_pos; k < new_pos; ++k) {
    const int j = s.topo.JunctionAtEnd(v.route[k]);
    if (j < 0) continue;
    JunctionState& at = s.junctions[j];
    if (s.measuring())
      at.run.longest_gap_without_crossing = std::max(
          at.run.longest_gap_without_crossing, s.now - std::max(at.last_progress, s.sc.warmup));
    at.last_progress = s.now;
    s.last_crossing = s.now;
    if (!s.measuring()) continue;
    (v.kind == VehicleKind::kAV ? at.run.crossings_av : at.run.crossings_hv)++;
  }
  v.route_pos = std::max(v.route_pos, new_pos);
}

void UpdateNear(RunState& s, int h) {
  Vehicle& v = s.vehicles[h];
  std::vector<int> near;
  double ahead = 0;
  for (std::size_t k = v.route_pos; k < v.route.size(); ++k) {
    if (k > static_cast<std::size_t>(v.route_pos)) ahead += s.topo.EdgeLength(v.route[k]);
    if (ahead > s.topo.reach()) break;
    const int j = s.topo.JunctionAtEnd(v.route[k]);
    if (j >= 0 && std::find(near.begin(), near.end(), j) == near.end()) near.push_back(j);
  }
  figure8::AddCentre(s, &near);
  SetNear(s, h, std::move(near));
}

void SetNear(RunState& s, int h, std::vector<int> near) {
  Vehicle& v = s.vehicles[h];
  const bool av = v.kind == VehicleKind::kAV;
  for (int j : v.near) (av ? s.junctions[j].near_av : s.junctions[j].near_hv)--;
  v.near = std::move(near);
  for (int j : v.near) (av ? s.junctions[j].near_av : s.junctions[j].near_hv)++;
}

}  // namespace taebp::control
