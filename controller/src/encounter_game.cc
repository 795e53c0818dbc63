#include "encounter_game.h"

#include "figure8.h"
#include "paired.h"
#include "taebp/config/model.h"
#include "vehicle_commands.h"

namespace taebp::control {

EncounterGame::EncounterGame(RunState& s)
    : s_(s), params_(ToModel(s.cfg.model)), rng_(s.sc.seed) {}

AvDraw EncounterGame::Draw(int av, int hv) {
  // Paired games: branches fork here, before anything of the policy is used.
  if (pairing_) pairing_->GameForms(av, hv, *this);
  ++s_.vehicles[av].open_encounters;
  ++s_.vehicles[hv].open_encounters;
  HvPopulation& population = PopulationOf(av, hv);
  const persuasion::CommittedScheme& scheme =
      population.Commit(s_.vehicles[av].id, s_.vehicles[hv].id, KindOf(av, hv));
  AvDraw d = DrawAv(scheme, params_.prior_go, rng_);
  // random_nudge: the magnitude from the population's own stream (the
  // encounter stream's two draws stay every policy's).
  if (d.nudge) d.nudge_distance = population.Magnitude(scheme);
  if (pairing_) pairing_->Drawn(av, hv, d);
  return d;
}

// Whether a meeting is the game must not depend on the policy being run, or
// the policies would be compared on different meetings: every rule of the
// game's geometry takes the AV where the largest nudge any policy may command
// leaves it, the likelihood's s_max (no design nudges farther: the nudge that
// persuades an HV of trust theta* is s_max, Theorem 2), and the major-road
// signal lasts as long as that nudge's creep under every policy (a shorter
// nudge, or none, stands the rest of it). docs/encounter-rules.md.
double EncounterGame::LargestNudge() const { return s_.cfg.model.likelihood.s_max; }

namespace {

// How long the AV's creep of `distance` m takes in SUMO (VehicleCommands'
// StartNudge and UpdateNudges, step by step): the signal's duration.
double NudgeSeconds(const RunState& s, double distance) {
  if (distance <= 0) return 0;
  const double target = distance + kNudgeOvershoot;
  double v = CreepSpeed(target, 0.0, 0.0, s.dt, s.sc.accel, s.sc.decel, s.sc.creep_speed);
  double covered = 0;
  long steps = 0;
  for (; steps < 100000; ) {
    covered += v * s.dt;
    ++steps;
    const double next = CreepSpeed(target, covered, v, s.dt, s.sc.accel, s.sc.decel, s.sc.creep_speed);
    if (next <= 0.0 && v <= 0.0) break;
    v = next;
  }
  return steps * s.dt;
}

junction::Mover Sized(junction::Mover m, const Vehicle& v) {
  m.length = v.length;
  m.width = v.width;
  m.accel = v.accel;
  m.max_speed = v.max_speed;
  m.decel = v.decel;
  m.emergency_decel = v.emergency_decel;
  m.sigma = v.sigma;
  return m;
}

// An HV keeping its speed `v` from arc `front` on (DR).
junction::Mover Cruising(junction::Mover m, double front, double v) {
  m.front = front;
  m.speed = v;
  m.accel = 0;
  m.max_speed = v;
  m.limits.clear();
  return m;
}

// Does SUMO slow the major-road HV at `front` with speed `v` on its way
// through the junction: a lane's limit ahead (a turn's) below the one it
// drives on (its commanded speed is capped by SUMO's safe speed, which
// keeps the lanes' limits; the cruising kinematics keeps v)?
bool SlowsOnItsWay(const junction::Mover& m, double front) {
  if (m.limits.empty()) return false;
  double now = m.limits.front().second;  // upstream of its approach: the approach's
  for (const auto& [from, limit] : m.limits)
    if (from <= front) now = limit;
  for (const auto& [from, limit] : m.limits)
    if (from > front && from < m.exit + m.length && limit < now - 0.1) return true;
  return false;
}

Premise FromPrediction(junction::BothProceed p) {
  switch (p) {
    case junction::BothProceed::kCollide: return Premise::kHolds;
    case junction::BothProceed::kClear: return Premise::kNoCollision;
    case junction::BothProceed::kUncertain: return Premise::kUncertainMerge;
  }
  return Premise::kNoCollision;
}

// The Go positions any policy may start from, past where the AV stands:
// 0 to `largest` every kNudgeGrid m (the bodies' own resolution) and
// `largest` itself.
constexpr double kNudgeGrid = 0.25;  // m
// How far the major-road HV's front may be off for a verdict to count
// (MajorPremiseNow): two of the bodies' resolution steps.
constexpr double kGrazingBand = 2 * kNudgeGrid;  // m
std::vector<double> GoPositions(double largest) {
  std::vector<double> out;
  for (int k = 0; k * kNudgeGrid < largest; ++k) out.push_back(k * kNudgeGrid);
  out.push_back(largest);
  return out;
}

// The premise for every policy: "AV goes, HV keeps its way" collides from
// every Go position (`av` with front at `av_line` + s), and the HV keeping
// its way passes the AV standing at every one of them. The worst verdict
// over the positions: a merge (unpredictable), else no collision, else the
// nudge in the HV's way, else it holds.
Premise PremiseForEveryPolicy(junction::Mover av, double av_line, const junction::Mover& hv,
                              double largest, double dt) {
  bool uncertain = false, clear = false;
  std::vector<double> fronts;
  for (double s : GoPositions(largest)) {
    av.front = av_line + s;
    fronts.push_back(av.front);
    const Premise p = FromPrediction(junction::PredictBothProceed(av, hv, dt));
    uncertain = uncertain || p == Premise::kUncertainMerge;
    clear = clear || p == Premise::kNoCollision;
  }
  const bool in_way = !junction::PassedWayOfEveryStand(hv, av, fronts);
  if (uncertain) return Premise::kUncertainMerge;
  if (clear) return Premise::kNoCollision;
  return in_way ? Premise::kNudgeInHvWay : Premise::kHolds;
}

}  // namespace

// The major-road approach (docs/beyond/major-road.md, "When is an approach the
// game"), measured on SUMO's state this step and the junction's geometry:
// - the HV's distance d to the conflict zone and the zone's length l on its
//   path (ZoneOnPath: its front positions at which its body can touch the
//   AV's on the AV's way through the junction), at the HV's decision: the
//   signal lasts `signal` s (the scheme's nudge), during which it keeps its
//   speed v (kCruise), so d = zone start - (its front now + v signal);
// - t_in and t_out: when the AV, going from its Go signal (s* ahead of where
//   it stands when the scheme nudges on Go) from rest with its type's
//   acceleration, reaches the zone on its own path and leaves it;
// - a and t_r: scenario.major_road's comfortable deceleration and reaction time.
// ClassifyMajorRoadApproach says which it is. The encounter forms once d is in
// the window's lower half (not at its upper edge, where "both proceed
// collides" is marginal) and "both proceed" (the AV going, the HV at v)
// collides on the geometry (PredictBothProceed) while the DR HV passes the
// AV standing at its Go signal (PassedWay).
junction::MajorVerdict EncounterGame::MajorRoad(int av, const junction::MajorAt& at, int av_movement) {
  using Kind = junction::MajorVerdict::Kind;
  const int hv = at.vehicle;
  const Vehicle& a = s_.vehicles[av];
  const Vehicle& h = s_.vehicles[hv];
  const JunctionInfo& info = s_.topo.junctions()[a.junction];
  const auto key = std::make_pair(av, hv);
  const MajorGeometry& g = GeometryOf(av, at, av_movement);
  if (!g.hv_zone.conflict || !g.av_zone.conflict) return {Kind::kNever, 0};
  const double v = at.speed;
  const double front_now = g.hv.entry - at.gap;
  const double front_decision = front_now + v * g.signal;
  persuasion::MajorRoadApproach ap;
  ap.hv_distance = g.hv_zone.first - front_decision;
  if (ap.hv_distance < 0) return {Kind::kNever, 0};
  ap.hv_speed = v;
  ap.comfortable_deceleration = s_.sc.major_road.comfortable_decel;
  ap.reaction_time = s_.sc.major_road.reaction_time;
  ap.hv_occupancy_length = g.hv_zone.last - g.hv_zone.first;
  // Every policy's AV (LargestNudge): it enters the zone at the earliest
  // from the largest nudge, and leaves it at the latest from its line.
  junction::Mover from_line = g.av;
  from_line.front = g.line;
  ap.av_enter_time = junction::TimeToReach(g.av, g.av_zone.first, s_.dt);
  ap.av_clear_time = junction::TimeToReach(from_line, g.av_zone.last + 0.25, s_.dt);
  if (!ap.IsValid(nullptr)) return {Kind::kNever, 0};
  const persuasion::ApproachWindow w = persuasion::ClassifyMajorRoadApproach(ap);
  // encounter_pairs: all (checking the prediction against SUMO): approaches
  // up to kAllBeyond s of the HV's speed beyond the game window are
  // encounters too, each engaged at a point drawn per pair between the
  // window's lower edge and that, so that "both proceed" both collides and
  // does not.
  const bool all = s_.sc.encounter_pairs == EncounterPairs::kAll;
  constexpr double kAllBeyond = 1.5;  // s
  switch (w.kind) {
    case persuasion::ApproachKind::kAvClearsFirst:
      if (!all) return {Kind::kNotYet, 0};
      break;
    case persuasion::ApproachKind::kCannotYield:
    case persuasion::ApproachKind::kHvPassesFirst: return {Kind::kNever, 0};
    case persuasion::ApproachKind::kGame: break;
  }
  const double lower = std::max(w.yield_distance, w.conflict_min_distance);
  const double engage =
      all ? lower + HashUniform(s_.sc.seed, a.id + "/" + h.id, 0x6d616a6f72ULL) *
                        (w.conflict_max_distance + v * kAllBeyond - lower)
          : lower + 0.5 * (w.conflict_max_distance - lower);
  if (ap.hv_distance > engage) return {Kind::kNotYet, 0};
  // Nothing ahead of the HV on its way that would make it brake or that it
  // could clip: the internal lanes of every movement from its lane empty,
  // its exit clear for a while.
  const MovementInfo& hm = info.movements[at.movement];
  if (!HvWayClear(info, hm, v)) return {Kind::kNotYet, 0};
  // The premise at the decision, on the geometry, from every Go position a
  // policy may command (PremiseForEveryPolicy). On a merge (the HV's movement
  // ends on the AV's exit lane) SUMO's car following brakes the one behind
  // for the one ahead once a front is on the shared exit lane: predicted
  // from the follower's deceleration and emergency deceleration
  // (PredictBothProceed), uncertain only where the two differ.
  // A merge the HV turns into slows it for the turn, which the cruising
  // kinematics does not: uncertain (checked: predicted collisions SUMO did
  // not have, right-turning HVs behind the AV).
  const junction::Mover hv_dec = Cruising(g.hv, front_decision, v);
  Premise premise = PremiseForEveryPolicy(g.av, g.line, hv_dec, LargestNudge(), s_.dt);
  if (info.movements[av_movement].to_lane == hm.to_lane && SlowsOnItsWay(g.hv, front_decision))
    premise = Premise::kUncertainMerge;
  if (premise != Premise::kHolds && (!all || premise == Premise::kUncertainMerge)) {
    if (s_.measuring()) {
      JunctionRun& run = s_.junctions[a.junction].run;
      ++(premise == Premise::kNoCollision ? run.meetings_not_game : run.meetings_unpredictable);
    }
    return {Kind::kNever, 0};
  }
  verdicts_[key] = premise;
  major_.insert(key);
  return {Kind::kGame, g.signal};
}

// The geometry of a major-road pair for these movements (cached per pair).
const EncounterGame::MajorGeometry& EncounterGame::GeometryOf(int av, const junction::MajorAt& at,
                                                              int av_movement) {
  const Vehicle& a = s_.vehicles[av];
  const Vehicle& h = s_.vehicles[at.vehicle];
  const JunctionInfo& info = s_.topo.junctions()[a.junction];
  const auto key = std::make_pair(av, at.vehicle);
  auto it = major_geometry_.find(key);
  if (it == major_geometry_.end() || it->second.av_movement != av_movement ||
      it->second.hv_movement != at.movement) {
    if (major_geometry_.size() > 256) major_geometry_.clear();
    MajorGeometry g;
    g.av_movement = av_movement;
    g.hv_movement = at.movement;
    const double signal = LargestNudge();
    g.signal = NudgeSeconds(s_, signal);
    g.av = Sized(info.movements[av_movement].mover, a);
    g.line = g.av.entry - a.line_gap;
    g.av.front = g.line + signal;
    g.hv = Sized(info.movements[at.movement].mover, h);
    g.hv.front = 0;
    g.hv_zone = junction::ZoneOnPath(g.hv, g.av);
    g.av_zone = junction::ZoneOnPath(g.av, g.hv);
    it = major_geometry_.insert_or_assign(key, g).first;
  }
  return it->second;
}

// Nothing ahead of the major-road HV (at speed v) on its way that would make
// it brake: its movement's internal lanes empty, its exit clear for a while.
// The vehicle ahead of the HV (it is its lane's front) may still be inside
// the junction on another movement from its lane: their paths share the
// junction's entry, and the HV, its right of way off, was seen to run into
// the rear of a right turn crawling ahead of it onto its exit (two-way grid,
// seed 3, No Trust: the major HV at 1.7 m/s behind a right turn at 0.8 m/s,
// SUMO's collision on the HV's straight internal lane). So every movement
// from its lane must have left the junction, not its own alone.
bool EncounterGame::HvWayClear(const JunctionInfo& info, const MovementInfo& hm, double v) const {
  for (const MovementInfo& m : info.movements) {
    if (m.from_lane != hm.from_lane) continue;
    for (const std::string& in : m.internal)
      if (s_.sumo.LaneVehicleNumber(in) > 0) return false;
  }
  if (s_.sumo.LaneVehicleNumber(hm.to_lane) > 0) {
    const std::vector<std::string> ids = s_.sumo.LaneVehicleIDs(hm.to_lane);
    if (!ids.empty() && s_.sumo.LanePosition(ids.front()) - s_.sumo.Length(ids.front()) < 30.0 &&
        s_.sumo.Speed(ids.front()) < v - 0.5)
      return false;
  }
  return true;
}

Premise EncounterGame::MajorPremiseNow(int av, int hv) const {
  const auto it = major_geometry_.find({av, hv});
  if (it == major_geometry_.end()) return Premise::kHolds;
  const MajorGeometry& g = it->second;
  const Vehicle& a = s_.vehicles[av];
  const Vehicle& h = s_.vehicles[hv];
  const JunctionInfo& info = s_.topo.junctions()[a.junction];
  junction::Mover ma = g.av;
  ma.front = info.movements[g.av_movement].ArcOf(s_.sumo.LaneID(a.id), s_.sumo.LanePosition(a.id));
  // The HV may still be upstream of its approach lane (negative arcs).
  const std::optional<double> hf =
      info.movements[g.hv_movement].PathArc(s_.sumo.LaneID(h.id), s_.sumo.LanePosition(h.id));
  if (ma.front < 0 || !hf) return Premise::kNoCollision;
  // The verdict must not turn within kGrazingBand either side of the HV's
  // front: at a grazing pass SUMO's collision check and these boxes can
  // differ by centimetres (measured: a pair predicted to collide that SUMO
  // had pass 0.2 m apart; the HV 0.3 m further back, the prediction was
  // clear too). Such a pair is recorded `grazing`, not held to SUMO's check
  // either way.
  const junction::Mover mh = Cruising(g.hv, *hf, h.major_speed);
  const junction::BothProceed p = junction::PredictBothProceed(ma, mh, s_.dt);
  for (const double shift : {-kGrazingBand, kGrazingBand}) {
    junction::Mover shifted = mh;
    shifted.front += shift;
    if (junction::PredictBothProceed(ma, shifted, s_.dt) != p) return Premise::kGrazing;
  }
  return FromPrediction(p);
}

// The paper's game needs "AV goes, HV drives recklessly" to be a collision
// and "AV waits" not to be one: predicted on the two movements' geometry
// from where the two vehicles would start, each with its own SUMO type's
// size and acceleration. Whether the meeting is the game does not depend on
// the policy (LargestNudge): it must hold from every Go position a policy
// may command, 0 to s_max past where the AV is held. Not the game: both
// proceeding would not collide (meetings_not_game); or the prediction cannot
// be trusted (meetings_unpredictable): a merge whose outcome depends on
// SUMO's car following, or an AV standing nudged in the way of the HV
// driving recklessly (waiting would not keep it safe). The record's premise
// (what SUMO's collision check is held to) is the one from this policy's own
// Go signal (s* ahead of where it is held when its scheme nudges on Go). The
// figure-8's crossing is always the game.
bool EncounterGame::Game(int av, int hv, int av_movement, int hv_movement) {
  if (figure8::IsFigure8(s_)) return true;
  const Vehicle& a = s_.vehicles[av];
  const Vehicle& h = s_.vehicles[hv];
  const JunctionInfo& info = s_.topo.junctions()[a.junction];
  junction::Mover ma = Sized(info.movements[av_movement].mover, a);
  junction::Mover mh = Sized(info.movements[hv_movement].mover, h);
  mh.front = mh.entry - h.line_gap;
  const double line = ma.entry - a.line_gap;
  const Premise rule = PremiseForEveryPolicy(ma, line, mh, LargestNudge(), s_.dt);
  // The record: from this policy's Go signal.
  const double signal = s_.population->GoSignal(h.id);
  ma.front = line + signal;
  Premise premise = FromPrediction(junction::PredictBothProceed(ma, mh, s_.dt));
  // The HV driving recklessly from its line must not touch the AV standing
  // where its scheme's largest nudge leaves it.
  if (premise == Premise::kHolds && signal > 0 && !junction::PassedWay(mh, ma, -1.0, 0.0))
    premise = Premise::kNudgeInHvWay;
  verdicts_[{av, hv}] = premise;
  if (rule == Premise::kHolds || s_.sc.encounter_pairs == EncounterPairs::kAll) return true;
  if (s_.measuring()) {
    JunctionRun& run = s_.junctions[a.junction].run;
    ++(rule == Premise::kNoCollision ? run.meetings_not_game : run.meetings_unpredictable);
  }
  return false;
}

HvReading EncounterGame::Read(int av, int hv, double observed) {
  // A major-road pair: the premise as SUMO has the two at the decision (the
  // record's both_proceed_collides; what SUMO's collision check is held to).
  if (major_.count({av, hv})) verdicts_[{av, hv}] = MajorPremiseNow(av, hv);
  const HvReading r = PopulationOf(av, hv).Read(s_.vehicles[av].id, s_.vehicles[hv].id, observed);
  if (commands_) commands_->SetPaint(hv, r.drives_if_clear ? Paint::kDc : Paint::kDr);
  return r;
}

void EncounterGame::Record(const JunctionState& j, const junction::EncounterOutcome& e) {
  EncounterRecord r;
  if (const auto it = verdicts_.find({e.av, e.hv}); it != verdicts_.end()) {
    r.premise = it->second;
    r.both_proceed_collides = it->second == Premise::kHolds || it->second == Premise::kNudgeInHvWay;
    verdicts_.erase(it);
  }
  // The HV's trust (before), the theory, and the updates of trust and beliefs.
  PopulationOf(e.av, e.hv).Finish(s_.vehicles[e.av].id, s_.vehicles[e.hv].id, e.draw, e.reading,
                                  e.collision, e.time >= s_.sc.warmup, &r);
  r.major_road = e.major_road;
  major_.erase({e.av, e.hv});
  major_geometry_.erase({e.av, e.hv});
  if (e.time >= s_.sc.warmup) {
    const JunctionInfo& info = s_.topo.junctions()[s_.Index(j)];
    r.time = e.time;
    r.junction = info.info.id;
    r.av = s_.vehicles[e.av].id;
    r.hv = s_.vehicles[e.hv].id;
    const MovementInfo& am = info.movements[e.av_movement];
    const MovementInfo& hm = info.movements[e.hv_movement];
    r.av_movement = am.from_lane + ">" + am.to_lane;
    r.hv_movement = hm.from_lane + ">" + hm.to_lane;
    r.av_dir = am.dir;
    r.hv_dir = hm.dir;
    r.intent_go = e.draw.intent_go;
    r.commanded = e.draw.nudge_distance;
    r.observed = e.reading.observed;
    r.posterior = e.reading.posterior;
    r.hv_dc = e.reading.drives_if_clear;
    r.av_first = e.draw.goes_first;
    r.collision = e.collision;
    r.collision_after_handback = e.collision_after_handback;
    r.decided_at = e.decided_at;
    if (pairing_) pairing_->Recorded(e.av, e.hv, r);
    s_.out.encounters.push_back(r);
  }
  s_.vehicles.EncounterDone(e.av);
  s_.vehicles.EncounterDone(e.hv);
}

}  // namespace taebp::control
