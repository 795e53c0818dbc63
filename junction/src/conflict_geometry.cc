#include "taebp/junction/conflict_geometry.h"

#include <algorithm>
#include <cmath>

namespace taebp::junction {

double PathLength(const std::vector<Point2>& path) {
  double len = 0;
  for (std::size_t i = 1; i < path.size(); ++i)
    len += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
  return len;
}

double ClearDistance(const std::vector<Point2>& a, double width_a, const std::vector<Point2>& b,
                     double width_b, double margin) {
  const double whole = PathLength(a);
  double along = 0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const Point2 p = a[i - 1], q = a[i];
    const double rx = q.x - p.x, ry = q.y - p.y;
    const double seg = std::hypot(rx, ry);
    for (std::size_t j = 1; j < b.size(); ++j) {
      const Point2 u = b[j - 1], v = b[j];
      const double sx = v.x - u.x, sy = v.y - u.y;
      const double denom = rx * sy - ry * sx;
      if (std::abs(denom) < 1e-12) continue;  // parallel
      const double t = ((u.x - p.x) * sy - (u.y - p.y) * sx) / denom;
      const double s = ((u.x - p.x) * ry - (u.y - p.y) * rx) / denom;
      if (t < 0 || t > 1 || s < 0 || s > 1) continue;
      const double sin_angle = std::abs(denom) / (seg * std::hypot(sx, sy));
      if (sin_angle < std::sin(20.0 * M_PI / 180.0)) return whole;  // shallow: a merge
      const double cos_angle = std::sqrt(std::max(0.0, 1 - sin_angle * sin_angle));
      // b's lane band, seen along a: its half-width over sin, plus the slant
      // of a's own width.
      const double band = 0.5 * width_b / sin_angle + 0.5 * width_a * cos_angle / sin_angle;
      return std::min(whole, along + t * seg + band + margin);
    }
    along += seg;
  }
  return whole;  // no crossing: they merge (or meet at the exit)
}

}  // namespace taebp::junction
