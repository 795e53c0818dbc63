// The pair surrogate measures of junction/pair_surrogates.h against closed
// forms: two cars crossing at right angles, one a car's length after the
// other (PET), or at the same time (a collision course: TTC falls to the
// step, PET 0), and a car closing on the one ahead (TTC = gap / closing speed).
#include "taebp/junction/pair_surrogates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace taebp::junction {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A car of 5 x 1.8 m whose front starts at (x0, y0), heading `heading`, at
// speed v, sampled every dt for `seconds`.
std::vector<BodySample> Drive(double x0, double y0, double heading, double v, double dt,
                              double seconds) {
  std::vector<BodySample> out;
  for (int k = 0; k * dt <= seconds + 1e-9; ++k) {
    BodySample s;
    s.t = k * dt;
    s.x = x0 + std::cos(heading) * v * s.t;
    s.y = y0 + std::sin(heading) * v * s.t;
    s.heading = heading;
    s.speed = v;
    out.push_back(s);
  }
  return out;
}

TEST(PairSurrogates, CrossingOneAfterTheOtherHasThePetOfTheGapAndNoTtc) {
  // A eastward on y = 0 from x = -50, B northward on x = 0 from y = -30, both
  // at 10 m/s. The 1.8 m wide crossing square: B in it for t in (2.91, 3.59),
  // A for t in (4.91, 5.59); PET = 4.91 - 3.59 = 1.32 s; never both at once.
  const auto a = Drive(-50, 0, 0, 10, 0.01, 10);
  const auto b = Drive(0, -30, kPi / 2, 10, 0.01, 10);
  const PairSurrogates m = MeasurePair(a, b, 10.0, 0.01);
  EXPECT_NEAR(m.min_pet, 1.32, 0.02);
  EXPECT_TRUE(std::isnan(m.min_ttc)) << m.min_ttc;
}

TEST(PairSurrogates, ACollisionCourseHasTtcDownToTheStepAndPetZero) {
  // B from y = -50: both in the crossing square during (4.91, 5.59).
  const auto a = Drive(-50, 0, 0, 10, 0.1, 10);
  const auto b = Drive(0, -50, kPi / 2, 10, 0.1, 10);
  // From the first sample alone: the first touch at 4.91 s (resolution 0.01).
  const PairSurrogates first = MeasurePair({a.front()}, {b.front()}, 10.0, 0.01);
  EXPECT_NEAR(first.min_ttc, 4.91, 0.011);
  EXPECT_TRUE(std::isnan(first.min_pet)) << "one sample each, apart";
  const PairSurrogates all = MeasurePair(a, b, 10.0, 0.01);
  EXPECT_LE(all.min_ttc, 0.1);
  EXPECT_EQ(all.min_pet, 0.0);
}

TEST(PairSurrogates, FollowingClosesTheGapAtTheClosingSpeed) {
  // B ahead, front at x = 20 at 5 m/s; A's front at 0 at 10 m/s: gap 20 - 5
  // = 15 m, closing at 5 m/s: TTC 3 s.
  const PairSurrogates m =
      MeasurePair({Drive(0, 0, 0, 10, 0.1, 0)}, {Drive(20, 0, 0, 5, 0.1, 0)}, 10.0, 0.01);
  EXPECT_NEAR(m.min_ttc, 3.0, 0.011);
}

TEST(PairSurrogates, NeighbouringLanesNeverTouch) {
  const PairSurrogates m =
      MeasurePair(Drive(0, 0, 0, 10, 0.1, 5), Drive(5, 3.2, 0, 8, 0.1, 5));
  EXPECT_TRUE(std::isnan(m.min_ttc));
  EXPECT_TRUE(std::isnan(m.min_pet));
}

TEST(PairSurrogates, SumoAnglesAreCompassBearings) {
  EXPECT_NEAR(HeadingFromSumoAngle(90), 0.0, 1e-12);        // east
  EXPECT_NEAR(HeadingFromSumoAngle(0), kPi / 2, 1e-12);     // north
  EXPECT_NEAR(HeadingFromSumoAngle(180), -kPi / 2, 1e-12);  // south
}

}  // namespace
}  // namespace taebp::junction
