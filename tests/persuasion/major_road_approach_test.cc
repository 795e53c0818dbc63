// When the major-road meeting is a game at all (the approach window of the HV
// on the major road: braking distance, reaction, the window against closed forms)
// and the approach's own checks. Expected values are worked by hand or closed forms.
#include "taebp/persuasion/major_road.h"
#include "taebp/config/policies.h"

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/outcomes.h"
#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(MajorRoadApproach, IsValidRejectsOutOfRangeNamingTheField) {
  std::string why;
  EXPECT_TRUE(MajorRoadApproach().IsValid(&why)) << why;
  struct Case {
    double MajorRoadApproach::*field;
    double value;
    const char* message;
  };
  const std::vector<Case> cases = {
      {&MajorRoadApproach::hv_distance, -1.0, "hv_distance = -1 must be >= 0"},
      {&MajorRoadApproach::hv_distance, kInf, "hv_distance = inf must be finite"},
      {&MajorRoadApproach::hv_speed, 0.0, "hv_speed = 0 must be > 0"},
      {&MajorRoadApproach::hv_speed, kNaN, "hv_speed = nan must be finite"},
      {&MajorRoadApproach::comfortable_deceleration, 0.0, "comfortable_deceleration = 0 must be > 0"},
      {&MajorRoadApproach::comfortable_deceleration, -3.0, "comfortable_deceleration"},
      {&MajorRoadApproach::reaction_time, -0.5, "reaction_time = -0.5 must be >= 0"},
      {&MajorRoadApproach::hv_occupancy_length, -2.0, "hv_occupancy_length = -2 must be >= 0"},
      {&MajorRoadApproach::av_enter_time, -1.0, "av_enter_time = -1 must be >= 0"},
      {&MajorRoadApproach::av_clear_time, 1.0, "av_clear_time = 1 must be > av_enter_time = 1"},
      {&MajorRoadApproach::av_clear_time, 0.5, "av_clear_time = 0.5 must be > av_enter_time"},
      {&MajorRoadApproach::av_clear_time, kInf, "av_clear_time = inf must be finite"},
  };
  for (const Case& c : cases) {
    MajorRoadApproach approach;
    approach.*c.field = c.value;
    EXPECT_FALSE(approach.IsValid(&why)) << c.message;
    EXPECT_THAT(why, HasSubstr(c.message));
    EXPECT_THAT(InvalidArgumentMessage([&] { ClassifyMajorRoadApproach(approach); }),
                HasSubstr(c.message));
  }
}

// ----------------------------------------------------- when is it a game at all

// x(T): the distance an HV at speed v covers by T when it keeps v until t_r and
// then brakes at a down to a stop (written with clamps, not the library's cases).
double BrakingDistance(double v, double a, double t_r, double T) {
  const double braking = std::clamp(T - t_r, 0.0, v / a);
  return v * std::min(T, t_r) + v * braking - 0.5 * a * braking * braking;
}

MajorRoadApproach Approach(double d, double v, double a, double t_r, double l, double t_in,
                           double t_out) {
  MajorRoadApproach approach;
  approach.hv_distance = d;
  approach.hv_speed = v;
  approach.comfortable_deceleration = a;
  approach.reaction_time = t_r;
  approach.hv_occupancy_length = l;
  approach.av_enter_time = t_in;
  approach.av_clear_time = t_out;
  return approach;
}

TEST(MajorRoadApproach, HandComputedWindow) {
  // v = 10, a = 2.5, t_r = 0, l = 8, t_in = 1, t_out = 3: collide iff 10 - 8 = 2 < d < 30;
  // t_out = 3 < v/a = 4, so the HV is still braking at t_out: yield distance
  // 10*3 - 2.5*9/2 = 18.75 (in time to arrival: t_out - a t_out^2/(2v) = 1.875 s);
  // stopping distance 100/5 = 20. The game: 18.75 <= d < 30.
  const auto at = [](double d) { return ClassifyMajorRoadApproach(Approach(d, 10, 2.5, 0, 8, 1, 3)); };
  const ApproachWindow w = at(25.0);
  EXPECT_EQ(w.kind, ApproachKind::kGame);
  EXPECT_TRUE(w.IsGame());
  EXPECT_DOUBLE_EQ(w.time_to_arrival, 2.5);
  EXPECT_DOUBLE_EQ(w.conflict_min_distance, 2.0);
  EXPECT_DOUBLE_EQ(w.conflict_max_distance, 30.0);
  EXPECT_DOUBLE_EQ(w.yield_distance, 18.75);
  EXPECT_DOUBLE_EQ(w.stopping_distance, 20.0);
  EXPECT_EQ(at(18.75).kind, ApproachKind::kGame);  // just able to yield
  EXPECT_EQ(at(18.7).kind, ApproachKind::kCannotYield);
  EXPECT_EQ(at(2.5).kind, ApproachKind::kCannotYield);
  EXPECT_EQ(at(2.0).kind, ApproachKind::kHvPassesFirst);  // its tail leaves as the AV enters
  EXPECT_EQ(at(0.0).kind, ApproachKind::kHvPassesFirst);
  EXPECT_EQ(at(29.9).kind, ApproachKind::kGame);
  EXPECT_EQ(at(30.0).kind, ApproachKind::kAvClearsFirst);  // arrives as the AV leaves
  EXPECT_EQ(at(100.0).kind, ApproachKind::kAvClearsFirst);
  EXPECT_FALSE(at(100.0).IsGame());
}

TEST(MajorRoadApproach, HandComputedStopAndReaction) {
  // a = 5: v/a = 2 < t_out = 3, the HV can stop: yield distance = stopping = 100/10 = 10.
  const ApproachWindow stop = ClassifyMajorRoadApproach(Approach(10.0, 10, 5, 0, 8, 1, 3));
  EXPECT_DOUBLE_EQ(stop.yield_distance, 10.0);
  EXPECT_DOUBLE_EQ(stop.stopping_distance, 10.0);
  EXPECT_EQ(stop.kind, ApproachKind::kGame);
  EXPECT_EQ(ClassifyMajorRoadApproach(Approach(9.9, 10, 5, 0, 8, 1, 3)).kind,
            ApproachKind::kCannotYield);
  // t_r = 1, a = 2.5: 10 m before braking, then 2 s of braking: 20 - 2.5*4/2 = 15,
  // yield distance 25; stopping 10 + 20 = 30. The game: 25 <= d < 30.
  const ApproachWindow react = ClassifyMajorRoadApproach(Approach(27.0, 10, 2.5, 1, 8, 1, 3));
  EXPECT_DOUBLE_EQ(react.yield_distance, 25.0);
  EXPECT_DOUBLE_EQ(react.stopping_distance, 30.0);
  EXPECT_EQ(react.kind, ApproachKind::kGame);
  EXPECT_EQ(ClassifyMajorRoadApproach(Approach(24.9, 10, 2.5, 1, 8, 1, 3)).kind,
            ApproachKind::kCannotYield);
  // t_r >= t_out: the HV cannot start braking before the AV has crossed: never a game.
  for (double d = 0.0; d <= 40.0; d += 0.25) {
    const ApproachWindow late = ClassifyMajorRoadApproach(Approach(d, 10, 2.5, 3, 8, 1, 3));
    EXPECT_DOUBLE_EQ(late.yield_distance, 30.0);
    EXPECT_FALSE(late.IsGame()) << d;
  }
}

TEST(MajorRoadApproach, WindowAgainstClosedFormsOnAGrid) {
  int games = 0;
  for (double v : {5.0, 10.0, 13.89, 20.0}) {
    for (double a : {1.5, 3.0, 6.0}) {
      for (double t_r : {0.0, 0.5, 1.5}) {
        for (double l : {0.0, 8.0}) {
          for (double t_in : {0.0, 1.0}) {
            for (double t_out : {1.2, 3.0, 6.0}) {
              const double y = BrakingDistance(v, a, t_r, t_out);
              for (double d = 0.0; d <= 130.0; d += 0.7) {
                const ApproachWindow w = ClassifyMajorRoadApproach(Approach(d, v, a, t_r, l, t_in, t_out));
                const std::string where = "v = " + std::to_string(v) + " a = " + std::to_string(a) +
                                          " t_r = " + std::to_string(t_r) + " l = " + std::to_string(l) +
                                          " t_in = " + std::to_string(t_in) +
                                          " t_out = " + std::to_string(t_out) + " d = " + std::to_string(d);
                EXPECT_NEAR(w.yield_distance, y, 1e-12 * (1.0 + y)) << where;
                EXPECT_NEAR(w.stopping_distance, v * t_r + v * v / (2.0 * a), 1e-12 * (1.0 + y)) << where;
                EXPECT_LE(w.yield_distance, w.stopping_distance + 1e-12) << where;
                EXPECT_NEAR(w.time_to_arrival, d / v, 1e-15 * (1.0 + d)) << where;
                // Skip distances within round-off of a boundary.
                const double lo = v * t_in - l;
                const double hi = v * t_out;
                if (std::abs(d - lo) < 1e-9 || std::abs(d - hi) < 1e-9 || std::abs(d - y) < 1e-9) continue;
                const bool collide = d > lo && d < hi;   // DR: the occupancies overlap
                const bool can_yield = d >= y;           // DC: arrives after the AV has left
                const ApproachKind want = !collide ? (d <= lo ? ApproachKind::kHvPassesFirst
                                                              : ApproachKind::kAvClearsFirst)
                                                   : (can_yield ? ApproachKind::kGame
                                                                : ApproachKind::kCannotYield);
                EXPECT_EQ(w.kind, want) << where << " got " << ToString(w.kind);
                if (w.IsGame()) ++games;
              }
              // Non-empty iff t_out > t_r: yield distance < v t_out exactly then.
              EXPECT_EQ(y < v * t_out, t_out > t_r);
            }
          }
        }
      }
    }
  }
  EXPECT_GT(games, 1000);
}

TEST(MajorRoadApproach, KindNames) {
  EXPECT_STREQ(ToString(ApproachKind::kHvPassesFirst), "hv_passes_first");
  EXPECT_STREQ(ToString(ApproachKind::kAvClearsFirst), "av_clears_first");
  EXPECT_STREQ(ToString(ApproachKind::kCannotYield), "cannot_yield");
  EXPECT_STREQ(ToString(ApproachKind::kGame), "game");
}

}  // namespace
}  // namespace taebp::persuasion
