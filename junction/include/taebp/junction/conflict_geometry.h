// Conflict geometry of two movements through a junction, from their
// centrelines (the lanes' shapes): would two vehicles released together
// collide on the junction (the game's premise)? SUMO-free.
#pragma once

#include <utility>
#include <vector>

namespace taebp::junction {

struct Point2 {
  double x = 0, y = 0;
};

// Length of a polyline.
double PathLength(const std::vector<Point2>& path);

}  // namespace taebp::junction

namespace taebp::junction {

// A vehicle released from rest on its way through a junction: its path (the
// approach lane, the internal lanes, the exit lane, as one centreline), the
// speed limits along it, and where the junction begins and ends on it.
struct Mover {
  std::vector<Point2> path;
  // (arc length from which it holds, speed limit m/s), ascending; empty: none.
  std::vector<std::pair<double, double>> limits;
  double entry = 0;   // arc length of the stop line
  double exit = 0;    // arc length where the junction ends (the exit lane begins)
  double front = 0;   // arc length of the front at release
  double length = 5.0, width = 1.8;
  double accel = 2.6, max_speed = 13.89;
  // Its SUMO type's deceleration and emergency deceleration (m/s^2): how hard
  // SUMO's car following may brake it behind a leader on a merge.
  double decel = 4.5, emergency_decel = 9.0;
  // Its SUMO type's driver imperfection (Krauss's sigma): > 0, SUMO dawdles
  // it at random, slower than this kinematics.
  double sigma = 0;
  double speed = 0;   // m/s at release (0: from rest; a major-road HV keeps its speed:
                      //   accel 0, no limits, max_speed = speed)
};

// The theory's collision event made physical: do two vehicles released from
// rest at the same instant, each driving its path at full acceleration
// without regard to the other (an AV going, an HV driving recklessly), touch
// while both are on the junction? A body is what SUMO's collision check
// compares: the rectangle of the vehicle's width around the straight line
// from its rear point to its front point on the path (on a curve it cuts
// the corner); speeds follow SUMO's Euler update v += accel*dt capped by the
// limit under the front. Paths that only merge
// behind each other, or cross where one has passed before the other comes,
// do not collide. `dt`: SUMO's step length.
//
// On a merge (both paths end on the same exit lane), from the step the
// first front is on the shared exit lane (the leader's) SUMO's car following
// makes the other (the follower) brake for it, by at most its emergency
// deceleration a step (MSCFModel::finalizeSpeed), by at most its
// deceleration while a speed command holds it (speed mode value 4, "regard
// maximum deceleration", set in the controller's 55). From that
// step on both are followed until both rears have left the junction (the
// encounter is over) or the follower stands, in two ways:
// - the follower braking at max(decel, emergency_decel) from the next step
//   (the earliest and hardest SUMO can brake it) still runs into the
//   leader's rear with its own front on the exit lane (a rear-end on one
//   lane, which SUMO's lane check reports) -> kCollide;
// - the follower braking at decel from one step later (the latest and
//   weakest braking that would stop it): the bodies never touch -> kClear
//   (SUMO's car following brakes at least that much once it must);
// otherwise kUncertain: it stops only braking harder than its decel, or the
// bodies touch only while the follower's front is still beside the leader,
// off the exit lane (SUMO 1.15 was seen to report such touches between cars
// but to miss them between a car and a 12 m truck turning beside it). A
// touch before any front is on the exit lane is kCollide as on a crossing.
// The leader drives on at full acceleration. A merge that does not touch
// before then is kUncertain when either dawdles (sigma > 0): who is on the
// exit lane first, and how far ahead, is then SUMO's random draw.
// BothProceedCollide: kCollide.
enum class BothProceed { kCollide, kClear, kUncertain };
BothProceed PredictBothProceed(const Mover& a, const Mover& b, double dt);
bool BothProceedCollide(const Mover& a, const Mover& b, double dt);
const char* ToString(BothProceed p);

// Has `first` (moving on along its path) passed `second`'s way through the
// junction, whatever their speeds from now on: no body of `first` from where
// it is (its front at first.front) until its rear has left the junction
// overlaps any body of `second` from where it stands until its rear has left
// the junction? Bodies as in BothProceedCollide, sampled every `step` metres
// of arc. (On a merge the first must be on the shared exit lane farther ahead
// than the second reaches before its rear leaves the junction.)
// A reach >= 0: only that many metres ahead of the vehicle's front (0: where
// it is now: a vehicle standing still).
// The major-road encounter (docs/beyond/major-road.md, "When is an approach the
// game"): where on `m`'s path its body can touch `other` on its way through
// the junction. `first`..`last`: the arcs of m's front at which its body (as
// in BothProceedCollide) overlaps some body of `other` between other.front
// and other's rear leaving the junction, sampled every `step` m of m's front
// from m.front until its rear has left the junction. `conflict` false: never.
struct ConflictZone {
  bool conflict = false;
  double first = 0, last = 0;
};
ConflictZone ZoneOnPath(const Mover& m, const Mover& other, double step = 0.25);

// Seconds until m's front, released at m.front with m.speed and driving as in
// BothProceedCollide (SUMO's Euler update), reaches arc `arc` (0 when it is
// there); a large number when it never does.
double TimeToReach(const Mover& m, double arc, double dt);

bool PassedWay(const Mover& first, const Mover& second, double first_reach = -1,
               double second_reach = -1, double step = 0.25);
// PassedWay as written first: every body of both built, then compared. The
// same answer, always (PassedWay builds only the bodies that can meet); kept
// for the test that says so.
bool PassedWayReference(const Mover& first, const Mover& second, double first_reach = -1,
                        double second_reach = -1, double step = 0.25);

// PassedWay(first, second standing with its front at f, -1, 0) for every f in
// `fronts` at once: true when `first` passes `second` standing at each of them
// (its bodies are built once for all).
bool PassedWayOfEveryStand(const Mover& first, Mover second, const std::vector<double>& fronts,
                           double step = 0.25);

}  // namespace taebp::junction
