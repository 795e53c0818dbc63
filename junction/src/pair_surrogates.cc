#include "taebp/junction/pair_surrogates.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace taebp::junction {
namespace {

struct Box {
  std::array<double, 2> c;     // centre
  std::array<double, 2> u, v;  // unit axes: along, across
  double hl, hw;               // half length, half width
};

Box BoxOf(const BodySample& s) {
  const double cx = std::cos(s.heading), cy = std::sin(s.heading);
  Box b;
  b.u = {cx, cy};
  b.v = {-cy, cx};
  b.hl = s.length / 2;
  b.hw = s.width / 2;
  b.c = {s.x - cx * b.hl, s.y - cy * b.hl};
  return b;
}

// The projection radius of box `b` on axis `n`.
double Radius(const Box& b, const std::array<double, 2>& n) {
  return b.hl * std::abs(b.u[0] * n[0] + b.u[1] * n[1]) + b.hw * std::abs(b.v[0] * n[0] + b.v[1] * n[1]);
}

bool Overlap(const Box& a, const Box& b) {
  const std::array<double, 2> d = {b.c[0] - a.c[0], b.c[1] - a.c[1]};
  for (const std::array<double, 2>& n : {a.u, a.v, b.u, b.v}) {
    const double dist = std::abs(d[0] * n[0] + d[1] * n[1]);
    if (dist >= Radius(a, n) + Radius(b, n)) return false;  // a separating axis
  }
  return true;
}

BodySample Moved(const BodySample& s, double dt) {
  BodySample m = s;
  m.x += std::cos(s.heading) * s.speed * dt;
  m.y += std::sin(s.heading) * s.speed * dt;
  return m;
}

}  // namespace

bool BodiesOverlap(const BodySample& a, const BodySample& b) { return Overlap(BoxOf(a), BoxOf(b)); }

double HeadingFromSumoAngle(double degrees) {
  constexpr double kPi = 3.14159265358979323846;
  return (90.0 - degrees) * kPi / 180.0;
}

PairSurrogates MeasurePair(const std::vector<BodySample>& a, const std::vector<BodySample>& b,
                           double horizon, double resolution) {
  PairSurrogates out;
  const std::size_t n = std::min(a.size(), b.size());
  // TTC: from each sample at which they are apart, at constant velocities.
  for (std::size_t k = 0; k < n; ++k) {
    if (BodiesOverlap(a[k], b[k])) continue;  // a collision, not a time to one
    if (a[k].speed <= 0 && b[k].speed <= 0) continue;
    // Nothing can touch before they close the gap between their centres.
    const double gap = std::hypot(a[k].x - b[k].x, a[k].y - b[k].y) -
                       (a[k].length + b[k].length) / 2 - (a[k].width + b[k].width) / 2;
    const double closing = a[k].speed + b[k].speed;
    const double start = gap > 0 ? gap / closing : 0.0;
    for (long step = std::max(1L, static_cast<long>(start / resolution)); step * resolution <= horizon;
         ++step) {
      const double t = static_cast<double>(step) * resolution;
      if (!std::isnan(out.min_ttc) && t >= out.min_ttc) break;
      if (BodiesOverlap(Moved(a[k], t), Moved(b[k], t))) {
        out.min_ttc = t;
        break;
      }
    }
  }
  // PET: the least time between two samples whose bodies overlap.
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Box ba = BoxOf(a[i]);
    const double ra = std::hypot(ba.hl, ba.hw);
    for (std::size_t j = 0; j < b.size(); ++j) {
      const double dt = std::abs(a[i].t - b[j].t);
      if (!std::isnan(out.min_pet) && dt >= out.min_pet) continue;
      const Box bb = BoxOf(b[j]);
      if (std::hypot(ba.c[0] - bb.c[0], ba.c[1] - bb.c[1]) >= ra + std::hypot(bb.hl, bb.hw)) continue;
      if (Overlap(ba, bb)) out.min_pet = dt;
    }
  }
  // Times to the millisecond (SUMO's clock), without the round-off of differences.
  for (double* v : {&out.min_ttc, &out.min_pet})
    if (!std::isnan(*v)) *v = std::round(*v * 1000.0) / 1000.0;
  return out;
}

}  // namespace taebp::junction
