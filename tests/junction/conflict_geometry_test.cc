// Conflict geometry without SUMO: whether two vehicles released
// together collide on the junction (BothProceedCollide): symmetric crossings
// do, a crossing one vehicle has passed before the other comes does not, lanes
// side by side do only when closer than a vehicle's width, a merge the leader
// reaches first does not; and SUMO's own opposite left turns from a
// netgenerate grid (shapes copied from its .net.xml) pass each other while
// perpendicular left turns collide. The SUMO cross-check of the same
// predictor on every encounter of a grid is in tests/controller/network_test.cc.
#include "taebp/junction/conflict_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace taebp::junction {
namespace {

// A straight movement along `dir` (unit) through a junction box of half-size
// 5 m centred on the origin: 25 m of approach, the box, 25 m of exit.
Mover Straight(double dx, double dy, double front_offset = 0.0) {
  Mover m;
  m.path = {{-30 * dx, -30 * dy}, {30 * dx, 30 * dy}};
  m.entry = 25;
  m.exit = 35;
  m.front = m.entry + front_offset;
  return m;
}

TEST(BothProceedCollide, SymmetricCrossingCollides) {
  EXPECT_TRUE(BothProceedCollide(Straight(1, 0), Straight(0, 1), 0.1));
  EXPECT_TRUE(BothProceedCollide(Straight(0, 1), Straight(1, 0), 0.1));
}

// Starting b further and further back: once a has passed the crossing before
// b comes it never collides again (monotone in b's head start), and the
// switch lies where the kinematics put it. From rest at 2.6 m/s^2, a's rear
// passes b's band (half-width 0.9 m past the centre) after 5 + 0.9 + 5 m:
// t_a = sqrt(2 * 10.9 / 2.6) = 2.896 s; b, starting d m before the box, first
// touches a's band (0.9 m before the centre) after d + 5 - 0.9 m:
// t_b = sqrt(2 (d + 4.1) / 2.6). They meet only while t_b < t_a, i.e.
// d < 6.8 m (continuous time; Euler steps and the box corners move it a little).
TEST(BothProceedCollide, ACrossingPassedBeforeTheOtherComesDoesNotCollide) {
  bool collided_before = true;
  double switch_at = -1;
  for (double d = 0; d <= 20.0; d += 0.25) {
    const bool c = BothProceedCollide(Straight(1, 0), Straight(0, 1, -d), 0.1);
    if (!collided_before) {
      EXPECT_FALSE(c) << "collides again at d = " << d;
    }
    if (collided_before && !c) switch_at = d;
    collided_before = c;
  }
  EXPECT_GT(switch_at, 6.8 - 1.5);
  EXPECT_LT(switch_at, 6.8 + 1.5);
}

TEST(BothProceedCollide, SideBySideLanesTouchOnlyCloserThanAVehicleWidth) {
  for (double sep : {1.0, 1.7, 1.9, 3.2}) {
    Mover a = Straight(1, 0), b = Straight(1, 0);
    for (Point2& p : b.path) p.y += sep;
    EXPECT_EQ(BothProceedCollide(a, b, 0.1), sep < 1.8) << sep;
  }
}

// b joins a's line from 30 degrees below at the end of the box (x = 5): a
// straight on, b merging behind. The leader that reaches the join first by
// more than its length is not hit; arriving together, they collide.
TEST(BothProceedCollide, AMergeTheLeaderReachesFirstDoesNotCollide) {
  auto merging = [](double front_offset) {
    Mover m;
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    // From 30 m before the join along the 30-degree line, then along +x.
    m.path = {{5 - 30 * c, -30 * s}, {5, 0}, {35, 0}};
    m.entry = 30 - 10 / c;  // enters the box (x = -5) 10/cos m before the join
    m.exit = 30;
    m.front = m.entry + front_offset;
    return m;
  };
  Mover a = Straight(1, 0);
  a.path = {{-30, 0}, {35, 0}};
  EXPECT_TRUE(BothProceedCollide(a, merging(10 / std::cos(M_PI / 6) - 10.0), 0.1))
      << "both 10 m from the join: they arrive together";
  Mover ahead = a;
  ahead.front = ahead.entry + 9.0;  // 1 m from the join, b 11.5 m
  EXPECT_FALSE(BothProceedCollide(ahead, merging(0.0), 0.1));
}

// The same touch on a crossing and on a merge: a's front already 1 m past
// its exit, its rear (4 m back) still on the junction; b 2 m before its own
// exit, its front corner inside a's body, both accelerating alike (the touch
// holds from the first step). On a crossing SUMO's junction check sees it:
// kCollide. On a merge the two share the exit lane a's front is on: b, beside
// a and not yet on that lane, brakes for a and stops before it reaches it;
// a touch only beside the leader is not one SUMO's checks were seen to
// report: kUncertain (BothProceedCollide: false).
TEST(BothProceedCollide, AMergeTouchingOnlyBesideTheLeaderIsUncertain) {
  Mover a = Straight(1, 0);  // along y = 0, exit at arc 35 (x = 5)
  a.path = {{-30, 0}, {35, 0}};  // ending where the merge's path ends: one exit lane
  a.front = a.exit + 1.0;        // front at x = 6, rear at x = 1
  // b along x = 2, crossing a's path: front at y = -0.5 (b's arc 29.5).
  Mover cross = Straight(0, 1);
  for (Point2& p : cross.path) p.x += 2.0;
  cross.front = 29.5;
  EXPECT_EQ(PredictBothProceed(a, cross, 0.1), BothProceed::kCollide);
  // b merging into a's exit from 30 degrees below, joining at (5, 0), its
  // front 2 m before the join: (5 - 2 cos 30, -2 sin 30) = (3.27, -1.0); its
  // left front corner 0.9 m across its heading, (2.82, -0.22), lies inside
  // a's body (x in [1, 6], |y| <= 0.9).
  Mover merge;
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  merge.path = {{5 - 30 * c, -30 * s}, {5, 0}, {35, 0}};
  merge.entry = 30 - 10 / c;
  merge.exit = 30;
  merge.front = 28;
  EXPECT_EQ(PredictBothProceed(a, merge, 0.1), BothProceed::kUncertain);
  EXPECT_EQ(PredictBothProceed(merge, a, 0.1), BothProceed::kUncertain);
  EXPECT_FALSE(BothProceedCollide(a, merge, 0.1));
  // Arriving at the join together (both fronts on the junction when they
  // touch) is certain.
  Mover together = Straight(1, 0);
  together.path = {{-30, 0}, {35, 0}};
  merge.front = merge.entry + 10 / c - 10.0;
  EXPECT_EQ(PredictBothProceed(together, merge, 0.1), BothProceed::kCollide);
}

// A merge decided by SUMO's car following. a: the straight line y = 0, its
// exit lane from x = 5 (arc 35) on, crawling at 2 m/s (its limit) with its
// front 0.1 m before the exit: in the first step its front is on the exit
// lane, its rear 4.9 m before the join. b: joining a's line at (5, 0) from 30
// degrees below (the same exit lane), at 13.89 m/s without accelerating, its
// front `before` m before the join. From then b follows a: closing at
// 11.89 m/s on a's rear, it must shed that within about before - 4.9 m:
// 11.89^2 / (2 * 9) = 7.9 m at 9 m/s^2, 15.7 m (+ a step's 1.4 m) at
// 4.5 m/s^2.
Mover Crawler() {
  Mover a = Straight(1, 0);
  a.path = {{-30, 0}, {35, 0}};
  a.front = a.exit - 0.1;
  a.speed = 2.0;
  a.max_speed = 2.0;
  return a;
}
Mover Joining(double before, double decel, double emergency_decel) {
  Mover b;
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  b.path = {{5 - 30 * c, -30 * s}, {5, 0}, {35, 0}};
  b.entry = 30 - 10 / c;
  b.exit = 30;
  b.front = 30 - before;
  b.speed = b.max_speed = 13.89;
  b.accel = 0;
  b.decel = decel;
  b.emergency_decel = emergency_decel;
  return b;
}

// Too close to stop even at its emergency deceleration (it runs into a's
// rear on the exit lane): kCollide; far enough
// to stop at its deceleration a step late: kClear; in between (it stops only
// braking harder than its deceleration, as SUMO may or may not): kUncertain.
// Either order of the movers gives the same verdict.
TEST(BothProceedCollide, AMergeIsDecidedByTheFollowersBraking) {
  const Mover a = Crawler();
  for (const auto& [before, want] :
       {std::pair{8.0, BothProceed::kCollide}, std::pair{18.0, BothProceed::kUncertain},
        std::pair{25.0, BothProceed::kClear}}) {
    const Mover b = Joining(before, 4.5, 9.0);
    EXPECT_EQ(PredictBothProceed(a, b, 0.1), want) << before;
    EXPECT_EQ(PredictBothProceed(b, a, 0.1), want) << before;
    EXPECT_EQ(BothProceedCollide(a, b, 0.1), want == BothProceed::kCollide) << before;
  }
  // The uncertain one decided by the type: a follower that brakes at most
  // 4.5 m/s^2 collides, one that brakes at 9 m/s^2 as a rule stops.
  EXPECT_EQ(PredictBothProceed(a, Joining(18.0, 4.5, 4.5), 0.1), BothProceed::kCollide);
  EXPECT_EQ(PredictBothProceed(a, Joining(18.0, 9.0, 9.0), 0.1), BothProceed::kClear);
  // Without braking (no decel at all) the far one collides too: the verdict
  // comes from the braking, not from the geometry alone.
  EXPECT_EQ(PredictBothProceed(a, Joining(25.0, 0.0, 0.0), 0.1), BothProceed::kCollide);
}

// SUMO 1.15 netgenerate grid, junction B1 (4-way all-way stop, 3.2 m lanes):
// the internal lanes of the four left turns.
Mover Left(const std::vector<Point2>& internal) {
  // 20 m of straight approach before the first point and of exit after the last.
  Mover m;
  const Point2 p0 = internal.front(), q1 = internal.back();
  // The roads are axis-aligned: the approach arrives along the axis the
  // first point lies on (x = 198.4 / 201.6: north-south; else east-west).
  const bool ns_in = std::abs(p0.x - 198.4) < 1e-9 || std::abs(p0.x - 201.6) < 1e-9;
  const Point2 dir_in = ns_in ? Point2{0, p0.y > 200 ? -1.0 : 1.0} : Point2{p0.x > 200 ? -1.0 : 1.0, 0};
  const bool ns_out = std::abs(q1.x - 198.4) < 1e-9 || std::abs(q1.x - 201.6) < 1e-9;
  const Point2 dir_out =
      ns_out ? Point2{0, q1.y > 200 ? 1.0 : -1.0} : Point2{q1.x > 200 ? 1.0 : -1.0, 0};
  m.path.push_back({p0.x - 20 * dir_in.x, p0.y - 20 * dir_in.y});
  for (const Point2& p : internal) m.path.push_back(p);
  m.path.push_back({q1.x + 20 * dir_out.x, q1.y + 20 * dir_out.y});
  m.entry = 20;
  m.exit = 20 + PathLength(internal);
  m.front = m.entry - 0.1;  // SUMO holds 0.1 m before the line
  return m;
}
const std::vector<Point2> kNorthToEast = {
    {198.4, 207.2}, {198.95, 203.35}, {200.6, 200.6}, {203.35, 198.95}, {207.2, 198.4}};
const std::vector<Point2> kSouthToWest = {
    {201.6, 192.8}, {201.05, 196.65}, {199.4, 199.4}, {196.65, 201.05}, {192.8, 201.6}};
const std::vector<Point2> kEastToSouth = {
    {207.2, 201.6}, {203.35, 201.05}, {200.6, 199.4}, {198.95, 196.65}, {198.4, 192.8}};

// Opposite left turns pass 1.70 m apart at their middles ((200.6, 200.6) and
// (199.4, 199.4)), closer than a vehicle's width (1.8 m) along the centrelines;
// but a 5 m body on an arc of radius 8.8 m is a chord that cuts the corner by
// the sagitta 8.8 - sqrt(8.8^2 - 2.5^2) = 0.36 m, away from the other turn, so
// the bodies stay 1.70 + 2 * 0.36 = 2.43 m apart: SUMO reports no collision.
// Perpendicular left turns cross: they collide. Whatever head start the AV
// has from a nudge (0 .. 2 m).
TEST(BothProceedCollide, SumoGridLeftTurnsOppositePassPerpendicularCollide) {
  for (double s : {0.0, 0.5, 1.4545, 2.0}) {
    Mover av = Left(kNorthToEast);
    av.front += s;
    EXPECT_FALSE(BothProceedCollide(av, Left(kSouthToWest), 0.1)) << s;
    EXPECT_TRUE(BothProceedCollide(av, Left(kEastToSouth), 0.1)) << s;
  }
}

// PassedWay: b stands at its line on a straight crossing a's. a has passed
// b's way once its rear is past the band b's body sweeps (a's path runs
// along y = 0, b's along x = 0, each 1.8 m wide: the band |x| <= 0.9 m, at
// arc 29.1..30.9 of a's path). Exactly then, to the sampling step, and for
// good after.
TEST(PassedWay, ACrossingIsPassedOnceTheRearIsPastTheOthersBand) {
  Mover b = Straight(0, 1);
  for (double front = 25.0; front <= 45.0; front += 0.1) {
    Mover a = Straight(1, 0);
    a.front = front;
    const double rear = front - a.length;
    if (rear < 30.9 - 0.26) {
      EXPECT_FALSE(PassedWay(a, b)) << front;
    }
    if (rear > 30.9 + 0.01) {
      EXPECT_TRUE(PassedWay(a, b)) << front;
    }
  }
  // b's own position matters only through where its way begins: a b that has
  // itself crept past the band can no longer be touched by a behind it.
  Mover a = Straight(1, 0);
  a.front = 28;  // rear at 23: before the crossing
  b.front = 30.9 + 5 + 0.2;  // b's rear past a's band (|y| <= 0.9: arc 29.1..30.9)
  EXPECT_TRUE(PassedWay(a, b));
}

// Side by side lanes farther apart than a vehicle's width never touch: each
// has passed the other's way wherever they are; closer, neither has while
// they are alongside.
TEST(PassedWay, SideBySideLanes) {
  for (double sep : {1.0, 3.2}) {
    Mover a = Straight(1, 0), b = Straight(1, 0);
    for (Point2& p : b.path) p.y += sep;
    EXPECT_EQ(PassedWay(a, b), sep > 1.8) << sep;
    EXPECT_EQ(PassedWay(b, a), sep > 1.8) << sep;
  }
}

// PassedWayOfEveryStand (the premise's "the HV passes the AV standing at each
// Go position") against PassedWay one position at a time: the HV a on y = 0,
// the AV b on x = 0 standing with its front at each of `fronts`. Stands short
// of a's band and stands inside it give both answers; every set gives the
// same answer as the positions taken one by one.
TEST(PassedWay, EveryStandIsPassedWayAtEachStand) {
  for (double a_front : {20.0, 33.0, 37.0}) {
    Mover a = Straight(1, 0);
    a.front = a_front;
    const Mover b = Straight(0, 1);
    for (const std::vector<double>& fronts :
         {std::vector<double>{25.0}, {25.0, 26.0, 27.0}, {25.0, 29.5}, {29.5, 31.0},
          {30.0}, {37.0, 38.0}}) {
      bool each = true;
      for (double f : fronts) {
        Mover at = b;
        at.front = f;
        each = each && PassedWay(a, at, -1.0, 0.0);
      }
      EXPECT_EQ(PassedWayOfEveryStand(a, b, fronts), each)
          << "a.front " << a_front << ", " << fronts.size() << " stands from " << fronts.front();
    }
  }
  // Both answers occur, or the comparison proves nothing.
  Mover a = Straight(1, 0);
  a.front = 20.0;
  Mover b = Straight(0, 1);
  EXPECT_TRUE(PassedWayOfEveryStand(a, b, {25.0}));   // b short of a's band (y <= -0.9)
  EXPECT_FALSE(PassedWayOfEveryStand(a, b, {25.0, 30.0}));  // b's body in a's way
}


// PassedWay builds only the bodies that can meet; PassedWayReference builds
// them all. The same answer on random curved paths through one junction box
// (arcs, kinks, zero-length segments, fronts beyond the path's end, every
// reach), both answers many times over.
Mover RandomMover(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Mover m;
  const double a0 = 2 * M_PI * u(rng), bend = (u(rng) - 0.5) * 2.0;
  Point2 p{-25 * std::cos(a0) + (u(rng) - 0.5) * 6, -25 * std::sin(a0) + (u(rng) - 0.5) * 6};
  double heading = a0;
  const int n = 2 + static_cast<int>(u(rng) * 14);
  for (int i = 0; i < n; ++i) {
    m.path.push_back(p);
    if (u(rng) < 0.1) m.path.push_back(p);  // a zero-length segment
    const double seg = 50.0 / n;
    heading += bend / n;
    p = {p.x + seg * std::cos(heading), p.y + seg * std::sin(heading)};
  }
  m.path.push_back(p);
  m.entry = 20 + u(rng) * 5;
  m.exit = m.entry + 5 + u(rng) * 15;
  m.front = u(rng) * 60;  // before the line to beyond the path's end
  m.length = 2 + u(rng) * 10;
  m.width = 0.6 + u(rng) * 2.0;
  return m;
}

TEST(PassedWay, PrunedIsTheReferenceOnRandomPaths) {
  std::mt19937 rng(20261207);
  std::uniform_int_distribution<int> pick(0, 3);
  const double reaches[] = {-1.0, 0.0, 2.5, 40.0};
  int passed = 0, blocked = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Mover a = RandomMover(rng), b = RandomMover(rng);
    const double ra = reaches[pick(rng)], rb = reaches[pick(rng)];
    const bool want = PassedWayReference(a, b, ra, rb);
    ASSERT_EQ(PassedWay(a, b, ra, rb), want) << "trial " << trial;
    ++(want ? passed : blocked);
  }
  EXPECT_GT(passed, 400);
  EXPECT_GT(blocked, 400);
}

}  // namespace
}  // namespace taebp::junction
