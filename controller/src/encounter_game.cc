#include "encounter_game.h"

#include "figure8.h"
#include "taebp/config/model.h"
#include "vehicle_commands.h"

namespace taebp::control {

EncounterGame::EncounterGame(RunState& s)
    : s_(s), params_(ToModel(s.cfg.model)), rng_(s.sc.seed) {}

AvDraw EncounterGame::Draw(int av, int hv) {
  ++s_.vehicles[av].open_encounters;
  ++s_.vehicles[hv].open_encounters;
  return DrawAv(s_.population->Commit(s_.vehicles[av].id, s_.vehicles[hv].id), params_.prior_go,
                rng_);
}

// The paper's game needs "AV goes, HV drives recklessly" to be a collision
// and "AV waits" not to be one: predicted on the two movements' geometry
// from where the two vehicles would start, each with its own SUMO type's
// size and acceleration, the AV from its Go signal (s* ahead of where it is
// held when its scheme nudges on Go). Not the game: both proceeding would not
// collide (meetings_not_game); or the prediction cannot be trusted
// (meetings_unpredictable): a merge whose outcome depends on SUMO's car
// following, or an AV standing nudged by s* in the way of the HV driving
// recklessly (waiting would not keep it safe). The figure-8's crossing is
// always the game.
bool EncounterGame::Game(int av, int hv, int av_movement, int hv_movement) {
  if (figure8::IsFigure8(s_)) return true;
  const Vehicle& a = s_.vehicles[av];
  const Vehicle& h = s_.vehicles[hv];
  const JunctionInfo& info = s_.topo.junctions()[a.junction];
  junction::Mover ma = info.movements[av_movement].mover;
  junction::Mover mh = info.movements[hv_movement].mover;
  for (auto [m, v] : {std::pair{&ma, &a}, std::pair{&mh, &h}}) {
    m->length = v->length;
    m->width = v->width;
    m->accel = v->accel;
    m->max_speed = v->max_speed;
  }
  const double signal = s_.population->GoSignal(h.id);
  ma.front = ma.entry - a.line_gap + signal;
  mh.front = mh.entry - h.line_gap;
  Premise premise = Premise::kNoCollision;
  switch (junction::PredictBothProceed(ma, mh, s_.dt)) {
    case junction::BothProceed::kCollide: premise = Premise::kHolds; break;
    case junction::BothProceed::kClear: premise = Premise::kNoCollision; break;
    case junction::BothProceed::kUncertain: premise = Premise::kUncertainMerge; break;
  }
  // The HV driving recklessly from its line must not touch the AV standing
  // where the largest nudge of its scheme leaves it.
  if (premise == Premise::kHolds && signal > 0 && !junction::PassedWay(mh, ma, -1.0, 0.0))
    premise = Premise::kNudgeInHvWay;
  verdicts_[{av, hv}] = premise;
  if (premise == Premise::kHolds || s_.sc.encounter_pairs == EncounterPairs::kAll) return true;
  if (s_.measuring()) {
    JunctionRun& run = s_.junctions[a.junction].run;
    ++(premise == Premise::kNoCollision ? run.meetings_not_game : run.meetings_unpredictable);
  }
  return false;
}

HvReading EncounterGame::Read(int av, int hv, double observed) {
  const HvReading r = s_.population->Read(s_.vehicles[av].id, s_.vehicles[hv].id, observed);
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
  s_.population->Finish(s_.vehicles[e.av].id, s_.vehicles[e.hv].id, e.draw, e.reading,
                        e.collision, e.time >= s_.sc.warmup, &r);
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
    s_.out.encounters.push_back(r);
  }
  s_.vehicles.EncounterDone(e.av);
  s_.vehicles.EncounterDone(e.hv);
}

}  // namespace taebp::control
