// Where two movements through a junction conflict, from their centrelines
// (the internal lanes' shapes): how far a vehicle on one must have driven,
// from its stop line, before its rear is clear of the other's path. SUMO-free.
#pragma once

#include <vector>

namespace taebp::junction {

struct Point2 {
  double x = 0, y = 0;
};

// Length of a polyline.
double PathLength(const std::vector<Point2>& path);

// The distance along `a` (from its start, the stop line) that the rear of a
// vehicle on `a` must pass before a vehicle on `b` may cross: the first point
// where the centrelines cross, plus the half-width of b's lane across a's
// path at that angle, plus `margin`. Paths that merge, run side by side or
// cross at a shallow angle (< 20 degrees) give the whole of `a` (the vehicle
// must leave the junction). `width_a`, `width_b`: lane widths.
double ClearDistance(const std::vector<Point2>& a, double width_a, const std::vector<Point2>& b,
                     double width_b, double margin = 0.5);

}  // namespace taebp::junction
