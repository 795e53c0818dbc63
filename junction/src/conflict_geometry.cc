#include "taebp/junction/conflict_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace taebp::junction {

double PathLength(const std::vector<Point2>& path) {
  double len = 0;
  for (std::size_t i = 1; i < path.size(); ++i)
    len += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
  return len;
}

}  // namespace taebp::junction

namespace taebp::junction {
namespace {

struct Arcs {
  const std::vector<Point2>* path;
  std::vector<double> at;  // cumulative arc length at each vertex
  explicit Arcs(const std::vector<Point2>& p) : path(&p), at(p.size(), 0.0) {
    for (std::size_t i = 1; i < p.size(); ++i)
      at[i] = at[i - 1] + std::hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y);
  }
  double Total() const { return at.empty() ? 0 : at.back(); }
  Point2 PointAt(double s) const {
    const std::vector<Point2>& p = *path;
    if (p.size() < 2 || s <= 0) return p.empty() ? Point2{} : p.front();
    if (s >= Total()) {  // extend the last segment straight on
      const Point2 u = p[p.size() - 2], v = p.back();
      const double seg = at.back() - at[at.size() - 2];
      const double k = seg > 0 ? (s - at.back()) / seg : 0;
      return {v.x + k * (v.x - u.x), v.y + k * (v.y - u.y)};
    }
    const std::size_t i = std::upper_bound(at.begin(), at.end(), s) - at.begin();
    const double seg = at[i] - at[i - 1];
    const double k = seg > 0 ? (s - at[i - 1]) / seg : 0;
    return {p[i - 1].x + k * (p[i].x - p[i - 1].x), p[i - 1].y + k * (p[i].y - p[i - 1].y)};
  }
};

// A vehicle's body as SUMO's collision check sees it: the rectangle of its
// width around the straight line from its rear point to its front point.
struct Box {
  std::array<Point2, 4> c;
};
Box BoxOf(Point2 rear, Point2 front, double width) {
  const double dx = front.x - rear.x, dy = front.y - rear.y;
  const double len = std::hypot(dx, dy);
  const double nx = len > 0 ? -dy / len * 0.5 * width : 0, ny = len > 0 ? dx / len * 0.5 * width : 0;
  return {{{{rear.x + nx, rear.y + ny}, {front.x + nx, front.y + ny}, {front.x - nx, front.y - ny},
            {rear.x - nx, rear.y - ny}}}};
}
// Separating axes: two convex quadrilaterals overlap unless some edge normal
// separates their projections.
bool Overlap(const Box& a, const Box& b) {
  for (const Box* box : {&a, &b}) {
    for (int i = 0; i < 4; ++i) {
      const Point2 p = box->c[i], q = box->c[(i + 1) % 4];
      const double ax = -(q.y - p.y), ay = q.x - p.x;
      if (ax == 0 && ay == 0) continue;
      double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
      for (const Point2& v : a.c) {
        const double d = v.x * ax + v.y * ay;
        amin = std::min(amin, d);
        amax = std::max(amax, d);
      }
      for (const Point2& v : b.c) {
        const double d = v.x * ax + v.y * ay;
        bmin = std::min(bmin, d);
        bmax = std::max(bmax, d);
      }
      if (amax <= bmin || bmax <= amin) return false;
    }
  }
  return true;
}

// Two movements into the same exit lane: their paths end at the same point.
bool Merge(const Mover& a, const Mover& b) {
  if (a.path.empty() || b.path.empty()) return false;
  return std::hypot(a.path.back().x - b.path.back().x, a.path.back().y - b.path.back().y) < 0.01;
}

double Limit(const Mover& m, double front) {
  double v = m.max_speed;
  for (const auto& [from, limit] : m.limits)
    if (from <= front) v = std::min(m.max_speed, limit);
  return v;
}

}  // namespace

namespace {

// A mover's front and speed, stepped by SUMO's Euler update.
struct Motion {
  double x = 0, v = 0;
};
// Full acceleration capped by the limit under the front.
void Drive(const Mover& m, Motion& s, double dt) {
  s.v = std::min(s.v + m.accel * dt, Limit(m, s.x));
  s.x += s.v * dt;
}
// Braking at `decel` (never below 0, never above the limit).
void Brake(const Mover& m, Motion& s, double decel, double dt) {
  s.v = std::min(std::max(0.0, s.v - decel * dt), Limit(m, s.x));
  s.x += s.v * dt;
}
bool BodiesOverlap(const Arcs& arcs_a, const Mover& a, double xa, const Arcs& arcs_b,
                   const Mover& b, double xb) {
  return Overlap(BoxOf(arcs_a.PointAt(xa - a.length), arcs_a.PointAt(xa), a.width),
                 BoxOf(arcs_b.PointAt(xb - b.length), arcs_b.PointAt(xb), b.width));
}

// A merge from the step the leader's front is on the shared exit lane: the
// leader drives on, the follower brakes at `decel` from `delay` steps on,
// until both rears have left the junction (or the follower stands, or
// neither moves any more). kSeen: the bodies touch with the follower's front
// on the exit lane too, a rear-end on one lane, which SUMO's lane check
// reports; kUnseen: they touch only while the follower's front is still on
// its own lanes, beside the leader partly on the exit lane, which SUMO 1.15
// was seen to report between cars but to miss between a car and a 12 m
// truck turning beside it; kNone: never.
enum class Touch { kNone, kUnseen, kSeen };
struct MergeSide {
  const Mover* m;
  const Arcs* arcs;
  Motion s;
};
Touch MergeTouches(MergeSide lead, MergeSide follow, double decel, int delay, double dt) {
  Touch touch = Touch::kNone;
  for (int step = 0; step < 100000; ++step) {
    if (BodiesOverlap(*lead.arcs, *lead.m, lead.s.x, *follow.arcs, *follow.m, follow.s.x)) {
      if (follow.s.x >= follow.m->exit) return Touch::kSeen;
      touch = Touch::kUnseen;
    }
    const bool lead_off = lead.s.x - lead.m->length >= lead.m->exit;
    if (lead_off && follow.s.x - follow.m->length >= follow.m->exit) break;
    if (step >= delay && follow.s.v <= 0) break;  // stands; the leader moves away
    if (lead.s.v <= 0 && lead.m->accel <= 0 && follow.s.v <= 0) break;
    Drive(*lead.m, lead.s, dt);
    if (step >= delay) {
      Brake(*follow.m, follow.s, decel, dt);
    } else {
      Drive(*follow.m, follow.s, dt);
    }
  }
  return touch;
}

// The verdict on a merge once a front is on the shared exit lane (the
// leader's: the one farther past its exit): kCollide when even the hardest
// braking ends in a rear-end on the exit lane, kClear when the weakest
// braking never touches, else kUncertain.
BothProceed PredictMerge(const MergeSide& a, const MergeSide& b, double dt) {
  if (a.m->sigma > 0 || b.m->sigma > 0) return BothProceed::kUncertain;
  const bool a_leads = a.s.x - a.m->exit >= b.s.x - b.m->exit;
  const MergeSide& lead = a_leads ? a : b;
  const MergeSide& follow = a_leads ? b : a;
  const double strongest = std::max(follow.m->decel, follow.m->emergency_decel);
  const Touch hard = MergeTouches(lead, follow, strongest, 0, dt);
  const Touch soft = MergeTouches(lead, follow, follow.m->decel, 1, dt);
  if (hard == Touch::kSeen && soft != Touch::kNone) return BothProceed::kCollide;
  if (hard == Touch::kNone && soft == Touch::kNone) return BothProceed::kClear;
  return BothProceed::kUncertain;
}

}  // namespace

BothProceed PredictBothProceed(const Mover& a, const Mover& b, double dt) {
  const Arcs arcs_a(a.path), arcs_b(b.path);
  const bool merge = Merge(a, b);
  Motion sa{a.front, a.speed}, sb{b.front, b.speed};
  for (int step = 0; step < 100000; ++step) {
    Drive(a, sa, dt);
    Drive(b, sb, dt);
    // On a merge, once a front is on the shared exit lane the other sees it
    // as its leader and SUMO's car following brakes for it (PredictMerge).
    if (merge && (sa.x >= a.exit || sb.x >= b.exit))
      return PredictMerge({&a, &arcs_a, sa}, {&b, &arcs_b, sb}, dt);
    // Once either has left the junction they can no longer meet on it.
    if (sa.x - a.length >= a.exit || sb.x - b.length >= b.exit) return BothProceed::kClear;
    if (sa.x <= a.entry || sb.x <= b.entry) continue;  // not both on the junction yet
    if (BodiesOverlap(arcs_a, a, sa.x, arcs_b, b, sb.x)) return BothProceed::kCollide;
  }
  return BothProceed::kClear;
}

bool BothProceedCollide(const Mover& a, const Mover& b, double dt) {
  return PredictBothProceed(a, b, dt) == BothProceed::kCollide;
}

const char* ToString(BothProceed p) {
  switch (p) {
    case BothProceed::kCollide: return "collide";
    case BothProceed::kClear: return "clear";
    case BothProceed::kUncertain: return "uncertain";
  }
  return "?";
}

namespace {

struct Bounds {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  void Add(Point2 p) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  void Add(const Box& box) {
    for (const Point2& p : box.c) Add(p);
  }
  void Add(const Bounds& o) {
    x0 = std::min(x0, o.x0), y0 = std::min(y0, o.y0);
    x1 = std::max(x1, o.x1), y1 = std::max(y1, o.y1);
  }
  bool Meets(const Bounds& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};

// A mover's bodies from its front on, every `step` m of its front, until its
// rear is off the junction or `reach` ahead (>= 0), each with its front's arc
// and bounding box, and the box of them all.
struct Bodies {
  std::vector<double> at;
  std::vector<Box> boxes;
  std::vector<Bounds> bounds;
  Bounds all;
};
// Where a mover's bodies end: `reach` ahead of its front (>= 0), or with its
// rear off the junction.
double EndOf(const Mover& m, double reach) {
  return reach >= 0 ? m.front + reach : std::max(m.front, m.exit + m.length);
}
// Its fronts from m.front every `step` m until `end` (end included).
std::vector<double> Fronts(const Mover& m, double end, double step) {
  std::vector<double> at;
  for (double x = m.front;; x = std::min(x + step, end)) {
    at.push_back(x);
    if (x >= end) break;
  }
  return at;
}
Bodies BodiesOf(const Mover& m, double reach, double step) {
  const Arcs arcs(m.path);
  Bodies out;
  out.at = Fronts(m, EndOf(m, reach), step);
  for (double x : out.at) {
    out.boxes.push_back(BoxOf(arcs.PointAt(x - m.length), arcs.PointAt(x), m.width));
    out.bounds.emplace_back().Add(out.boxes.back());
    out.all.Add(out.boxes.back());
  }
  return out;
}
// Does some body of `a` overlap some body of `b`?
bool Touch(const Bodies& a, const Bodies& b) {
  if (!a.all.Meets(b.all)) return false;
  for (std::size_t i = 0; i < a.boxes.size(); ++i) {
    if (!a.bounds[i].Meets(b.all)) continue;
    for (std::size_t k = 0; k < b.boxes.size(); ++k)
      if (a.bounds[i].Meets(b.bounds[k]) && Overlap(a.boxes[i], b.boxes[k])) return true;
  }
  return false;
}

}  // namespace

ConflictZone ZoneOnPath(const Mover& m, const Mover& other, double step) {
  const Bodies mine = BodiesOf(m, -1, step), theirs = BodiesOf(other, -1, step);
  ConflictZone z;
  for (std::size_t i = 0; i < mine.boxes.size(); ++i) {
    if (!mine.bounds[i].Meets(theirs.all)) continue;
    for (std::size_t k = 0; k < theirs.boxes.size(); ++k) {
      if (!mine.bounds[i].Meets(theirs.bounds[k]) || !Overlap(mine.boxes[i], theirs.boxes[k]))
        continue;
      if (!z.conflict) z.first = mine.at[i];
      z.conflict = true;
      z.last = mine.at[i];
      break;
    }
  }
  return z;
}

double TimeToReach(const Mover& m, double arc, double dt) {
  double x = m.front, v = m.speed;
  for (long step = 0; step < 1000000; ++step) {
    if (x >= arc) return step * dt;
    v = std::min(v + m.accel * dt, Limit(m, x));
    if (v <= 0 && m.accel <= 0) break;
    x += v * dt;
  }
  return 1e9;
}

bool PassedWayOfEveryStand(const Mover& first, Mover second, const std::vector<double>& fronts,
                           double step) {
  const Bodies a = BodiesOf(first, -1, step);
  for (double f : fronts) {
    second.front = f;
    if (Touch(a, BodiesOf(second, 0, step))) return false;
  }
  return true;
}

namespace {

// A box holding every body of `m` whose front is in [lo, hi] (arcs), however
// SUMO's rounding falls: the path's vertices its rear and front points lie
// between (PointAt is a convex combination of a segment's ends; beyond the
// path's end, the straight extension), widened by half the width and a
// margin far above the rounding of coordinates.
Bounds SweptBounds(const Arcs& arcs, const Mover& m, double lo, double hi) {
  const std::vector<Point2>& p = *arcs.path;
  Bounds b;
  const double from = lo - m.length;
  // The vertices of the segments holding arcs from..hi (PointAt's upper_bound).
  const std::size_t n = p.size();
  const std::size_t first =
      from <= 0 ? 0 : std::upper_bound(arcs.at.begin(), arcs.at.end(), from) - arcs.at.begin() - 1;
  const std::size_t last =
      hi >= arcs.Total() ? n - 1
                         : std::upper_bound(arcs.at.begin(), arcs.at.end(), hi) - arcs.at.begin();
  for (std::size_t i = std::min(first, n - 1); i <= std::min(last, n - 1); ++i) b.Add(p[i]);
  if (hi >= arcs.Total()) b.Add(arcs.PointAt(hi));  // the extension is a straight line
  const double margin = 0.5 * m.width + 1e-6;
  b.x0 -= margin, b.y0 -= margin, b.x1 += margin, b.y1 += margin;
  return b;
}

// PointAt for arcs that never decrease (a mover's bodies, front to back):
// the segment found by walking on from the last, not by a search; the same
// segment and the same arithmetic as PointAt, so the same point.
class ArcWalker {
 public:
  explicit ArcWalker(const Arcs& arcs) : arcs_(arcs) {}
  Point2 At(double s) {
    const std::vector<Point2>& p = *arcs_.path;
    const std::vector<double>& at = arcs_.at;
    if (p.size() < 2 || s <= 0 || s >= arcs_.Total()) return arcs_.PointAt(s);
    while (i_ < at.size() && at[i_] <= s) ++i_;  // upper_bound: the first arc beyond s
    const double seg = at[i_] - at[i_ - 1];
    const double k = seg > 0 ? (s - at[i_ - 1]) / seg : 0;
    return {p[i_ - 1].x + k * (p[i_].x - p[i_ - 1].x), p[i_ - 1].y + k * (p[i_].y - p[i_ - 1].y)};
  }

 private:
  const Arcs& arcs_;
  std::size_t i_ = 1;
};

// A mover's bodies as BodiesOf samples them (fronts `at`), in runs of
// kChunk: each run's swept box, and for the runs that can meet the other
// mover, their exact boxes and the box of the run.
constexpr std::size_t kChunk = 8;
struct Runs {
  std::vector<Box> boxes;          // of the runs built, in order
  std::vector<Bounds> bounds;
  std::vector<std::size_t> begin;  // each built run's first body in boxes
  std::vector<Bounds> run_bounds;
  Bounds all;
};
// Walks a mover's bodies as BodiesOf samples them, in runs of kChunk
// fronts: Next() builds the next run whose swept box meets `other` (the
// other mover's region, or the box of its bodies) and skips the rest.
class RunBuilder {
 public:
  RunBuilder(const Arcs& arcs, const Mover& m, double end, double step)
      : arcs_(arcs), m_(m), at_(Fronts(m, end, step)), rear_(arcs), front_(arcs) {}
  // The next run that can meet `other`, appended to `r`; false: none left.
  bool Next(const Bounds& other, Runs* r) {
    for (; c_ < at_.size(); c_ += kChunk) {
      const std::size_t e = std::min(at_.size(), c_ + kChunk);
      if (!other.Meets(SweptBounds(arcs_, m_, at_[c_], at_[e - 1]))) continue;
      r->begin.push_back(r->boxes.size());
      Bounds run;
      for (std::size_t i = c_; i < e; ++i) {
        r->boxes.push_back(BoxOf(rear_.At(at_[i] - m_.length), front_.At(at_[i]), m_.width));
        r->bounds.emplace_back().Add(r->boxes.back());
        run.Add(r->bounds.back());
      }
      r->run_bounds.push_back(run);
      r->all.Add(run);
      c_ = e;
      return true;
    }
    return false;
  }

 private:
  const Arcs& arcs_;
  const Mover& m_;
  std::vector<double> at_;
  ArcWalker rear_, front_;
  std::size_t c_ = 0;
};

// Touch(BodiesOf(a, ra, step), BodiesOf(b, rb, step)), building only the
// bodies that can meet and comparing runs of them before bodies: b's runs
// whose swept box meets a's region, then a's runs one at a time, each
// compared as soon as it is built (the first touch ends the search). Two
// bodies are compared exactly when their boxes meet, as Touch compares them:
// the same answer (PassedWayReference, and the test that says so).
bool TouchPruned(const Mover& a, double ra, const Mover& b, double rb, double step) {
  if (a.path.size() < 2 || b.path.size() < 2) return Touch(BodiesOf(a, ra, step), BodiesOf(b, rb, step));
  const Arcs arcs_a(a.path), arcs_b(b.path);
  const double end_a = EndOf(a, ra), end_b = EndOf(b, rb);
  const Bounds region_a = SweptBounds(arcs_a, a, a.front, end_a);
  if (!region_a.Meets(SweptBounds(arcs_b, b, b.front, end_b))) return false;
  Runs runs_b;
  RunBuilder builder_b(arcs_b, b, end_b, step);
  while (builder_b.Next(region_a, &runs_b)) {
  }
  runs_b.begin.push_back(runs_b.boxes.size());
  if (runs_b.boxes.empty()) return false;
  Runs run_a;  // one run of a at a time
  RunBuilder builder_a(arcs_a, a, end_a, step);
  while (true) {
    run_a.boxes.clear(), run_a.bounds.clear(), run_a.begin.clear(), run_a.run_bounds.clear();
    if (!builder_a.Next(runs_b.all, &run_a)) return false;
    const Bounds& ra_bounds = run_a.run_bounds.front();
    for (std::size_t q = 0; q + 1 < runs_b.begin.size(); ++q) {
      if (!ra_bounds.Meets(runs_b.run_bounds[q])) continue;
      for (std::size_t i = 0; i < run_a.boxes.size(); ++i) {
        if (!run_a.bounds[i].Meets(runs_b.run_bounds[q])) continue;
        for (std::size_t k = runs_b.begin[q]; k < runs_b.begin[q + 1]; ++k)
          if (run_a.bounds[i].Meets(runs_b.bounds[k]) && Overlap(run_a.boxes[i], runs_b.boxes[k]))
            return true;
      }
    }
  }
}

}  // namespace

bool PassedWay(const Mover& first, const Mover& second, double first_reach, double second_reach,
               double step) {
  return !TouchPruned(first, first_reach, second, second_reach, step);
}

bool PassedWayReference(const Mover& first, const Mover& second, double first_reach,
                        double second_reach, double step) {
  return !Touch(BodiesOf(first, first_reach, step), BodiesOf(second, second_reach, step));
}

}  // namespace taebp::junction
