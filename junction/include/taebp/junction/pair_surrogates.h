// Surrogate safety measures of one pair of vehicles from their sampled
// states, SUMO-free (a paired game's branch measures its AV and HV with them:
// controller/src/paired.cc; docs/paired.md). A vehicle is the rectangle of
// its length and width behind its front point, along its heading.
//
// - TTC, time to collision: at each sample at which the two do not overlap,
//   both carried on at their speed and heading (straight lines) until their
//   rectangles first touch, within `horizon` s; the least over the samples.
//   (SUMO's SSM device carries them along their routes' lanes instead: on a
//   turn the two differ.)
// - PET, post-encroachment time: over every two samples, one of each
//   vehicle, whose rectangles overlap, the least time between them: the time
//   from the last moment the first occupied a place to the first moment the
//   second did (0 when they overlapped at once: a collision). Resolved to
//   the samples' spacing.
// NaN where there is none (no collision course in the horizon; the two never
// occupied the same place).
#pragma once

#include <limits>
#include <vector>

namespace taebp::junction {

struct BodySample {
  double t = 0;         // s
  double x = 0, y = 0;  // the front's centre (m)
  double heading = 0;   // rad, the direction of travel (x axis = 0, counterclockwise)
  double speed = 0;     // m/s
  double length = 5, width = 1.8;
};

struct PairSurrogates {
  double min_ttc = std::numeric_limits<double>::quiet_NaN();
  double min_pet = std::numeric_limits<double>::quiet_NaN();
};

// `a` and `b` sampled at the same instants (the same length, times equal).
PairSurrogates MeasurePair(const std::vector<BodySample>& a, const std::vector<BodySample>& b,
                           double horizon = 10.0, double resolution = 0.05);

// Do the two rectangles overlap (their interiors; touching edges do not)?
bool BodiesOverlap(const BodySample& a, const BodySample& b);

// SUMO's vehicle angle (degrees, 0 = north, clockwise) as a heading.
double HeadingFromSumoAngle(double degrees);

}  // namespace taebp::junction
