#include "taebp/junction/interception.h"

#include <algorithm>
#include <stdexcept>

namespace taebp::junction {

namespace {
// s after the major-road HV left the junction during which a vehicle SUMO
// held for it may still start (SUMO releases it in the step after at most).
constexpr double kStarterGrace = 1.0;
}  // namespace

const char* ToString(Rule rule) { return rule == Rule::kAllWay ? "all_way_stop" : "two_way_stop"; }

int GamePairs(const JunctionSpec& spec, bool major_road) {
  int pairs = 0;
  const int n = static_cast<int>(spec.movements.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const Movement& a = spec.movements[i];
      const Movement& b = spec.movements[j];
      if (!spec.Conflict(i, j)) continue;
      if (a.controlled && b.controlled)
        pairs += a.approach != b.approach;
      else if (major_road && a.controlled != b.controlled)
        ++pairs;
    }
  }
  return pairs;
}

void JunctionSpec::Validate() const {
  const std::size_t n = movements.size();
  if (conflict.size() != n)
    throw std::invalid_argument("junction " + id + ": conflict matrix has " +
                                std::to_string(conflict.size()) + " rows for " +
                                std::to_string(n) + " movements");
  for (const auto& row : conflict)
    if (row.size() != n)
      throw std::invalid_argument("junction " + id + ": conflict matrix is not square");
  for (const Movement& m : movements)
    if (m.approach < 0 || m.approach >= approaches)
      throw std::invalid_argument("junction " + id + ": movement approach out of range");
}

Interception::Interception(JunctionSpec spec, Timing timing)
    : spec_(std::move(spec)), timing_(timing) {
  spec_.Validate();
}

bool Interception::ConflictsWithEncounter(int movement) const {
  if (!encounter_) return false;
  const EncounterOutcome& e = encounter_->out;
  return movement == e.av_movement || movement == e.hv_movement ||
         spec_.Conflict(movement, e.av_movement) || spec_.Conflict(movement, e.hv_movement);
}

void Interception::Form(double now, const AtLine& av, const AtLine& hv,
                        std::vector<Command>* out) {
  Active e;
  e.out.av = av.vehicle;
  e.out.hv = hv.vehicle;
  e.out.av_movement = av.movement;
  e.out.hv_movement = hv.movement;
  e.out.time = now;
  e.av_held = av.waiting;
  e.hv_held = hv.waiting;
  encounter_ = std::move(e);
  if (av.waiting) out->push_back({Command::Kind::kHold, av.vehicle});
  if (hv.waiting) out->push_back({Command::Kind::kHold, hv.vehicle});
  last_activity_ = now;
}

std::vector<Command> Interception::Step(double now, const std::vector<AtLine>& at_line,
                                        Environment& env, EncounterModel& model,
                                        const std::vector<MajorAt>& major) {
  std::vector<Command> out;
  Forget(at_line, &out);
  // A new meeting only once every vehicle of the encounters before is inside
  // the junction or out of it: one still at its line (a move not yet begun)
  // is not at the lines the meeting looks at, nor yet inside where the new
  // moves' ways are checked.
  const bool all_inside = std::all_of(leaving_.begin(), leaving_.end(), [](const Active& e) {
    return e.av_entered && e.hv_entered;
  });
  if (!encounter_ && all_inside) Meet(now, at_line, env, model, &out);
  if (timing_.major_road && spec_.rule == Rule::kTwoWay) {
    ForgetMajor(at_line, major);
    if (!encounter_ && all_inside) FormMajor(now, at_line, major, env, model, &out);
  }
  if (!encounter_) return out;

  HoldThirds(at_line, &out);
  if (encounter_->major) {
    StepMajor(now, env, &out);
    return out;
  }
  if (!encounter_->drawn && !Arrive(now, at_line, model, &out)) return out;
  StartNudge(env, &out);
  if (encounter_->sequence) Release(now, env, &out);
  return out;
}

void Interception::Forget(const std::vector<AtLine>& at_line, std::vector<Command>* out) {
  // The encounter ended: its held third vehicles go back to SUMO.
  if (!encounter_ && !thirds_.empty()) {
    for (int v : thirds_) out->push_back({Command::Kind::kHandBack, v});
    thirds_.clear();
  }
  // Pairs judged not the game are forgotten once either left its line.
  for (auto it = not_game_.begin(); it != not_game_.end();) {
    auto here = [&](int v) {
      return std::any_of(at_line.begin(), at_line.end(),
                         [&](const AtLine& a) { return a.vehicle == v; });
    };
    it = here(it->first) && here(it->second) ? std::next(it) : not_game_.erase(it);
  }
}

void Interception::Meet(double now, const std::vector<AtLine>& at_line, Environment& env,
                        EncounterModel& model, std::vector<Command>* out) {
  // Who meets whom: the head first at its line picks its earliest partner.
  std::vector<const AtLine*> order;
  for (const AtLine& a : at_line)
    if (a.movement >= 0 && spec_.movements[a.movement].controlled) order.push_back(&a);
  std::sort(order.begin(), order.end(), [&](const AtLine* x, const AtLine* y) {
    if (x->waiting != y->waiting) return x->waiting;
    if (x->waiting && x->since != y->since) return x->since < y->since;
    const int ax = spec_.movements[x->movement].approach;
    const int ay = spec_.movements[y->movement].approach;
    if (ax != ay) return ax < ay;
    return x->vehicle < y->vehicle;
  });
  for (std::size_t i = 0; i < order.size() && !encounter_ && order[i]->waiting; ++i) {
    for (std::size_t k = 0; k < order.size(); ++k) {
      const AtLine& a = *order[i];
      const AtLine& b = *order[k];
      if (a.kind == b.kind || !spec_.Conflict(a.movement, b.movement)) continue;
      const AtLine& av = a.kind == VehicleKind::kAV ? a : b;
      const AtLine& hv = a.kind == VehicleKind::kAV ? b : a;
      if (not_game_.count({av.vehicle, hv.vehicle})) continue;
      // Keep clear: a head whose exit cannot take it does not enter under
      // SUMO's rules either; it meets nobody until there is room.
      if (!env.ExitHasRoom(av.movement, av.vehicle) || !env.ExitHasRoom(hv.movement, hv.vehicle))
        continue;
      if (!model.Game(av.vehicle, hv.vehicle, av.movement, hv.movement)) {
        not_game_.insert({av.vehicle, hv.vehicle});
        ++non_game_;
        continue;
      }
      Form(now, av, hv, out);
      break;
    }
  }
}

void Interception::ForgetMajor(const std::vector<AtLine>& at_line,
                               const std::vector<MajorAt>& major) {
  // Pairs judged never the game are forgotten once the AV has left its
  // line or the HV is no longer approaching.
  for (auto it = major_never_.begin(); it != major_never_.end();) {
    const bool av_here = std::any_of(at_line.begin(), at_line.end(), [&](const AtLine& a) {
      return a.vehicle == it->first;
    });
    const bool hv_here = std::any_of(major.begin(), major.end(), [&](const MajorAt& m) {
      return m.vehicle == it->second;
    });
    it = av_here && hv_here ? std::next(it) : major_never_.erase(it);
  }
}

void Interception::HoldThirds(const std::vector<AtLine>& at_line, std::vector<Command>* out) {
  const Active& e = *encounter_;
  // Third vehicles at the line on conflicting movements wait for the encounter.
  for (const AtLine& a : at_line) {
    if (a.vehicle == e.out.av || a.vehicle == e.out.hv || a.movement < 0) continue;
    if (std::find(thirds_.begin(), thirds_.end(), a.vehicle) != thirds_.end()) continue;
    if (!a.waiting || !ConflictsWithEncounter(a.movement)) continue;
    thirds_.push_back(a.vehicle);
    out->push_back({Command::Kind::kHold, a.vehicle});
  }
}

bool Interception::Arrive(double now, const std::vector<AtLine>& at_line, EncounterModel& model,
                          std::vector<Command>* out) {
  Active& e = *encounter_;
  // The arriving partner: held once at its line; gone or too late, the
  // meeting ends.
  for (bool av : {true, false}) {
    bool& held = av ? e.av_held : e.hv_held;
    if (held) continue;
    const int who = av ? e.out.av : e.out.hv;
    const auto it = std::find_if(at_line.begin(), at_line.end(),
                                 [&](const AtLine& a) { return a.vehicle == who; });
    if (it != at_line.end() && it->waiting) {
      held = true;
      out->push_back({Command::Kind::kHold, who});
    } else if (it == at_line.end() || now - e.out.time > kArrivalLimit) {
      ++abandoned_;
      for (int v : {e.out.av, e.out.hv})
        if (v != who) out->push_back({Command::Kind::kHandBack, v});
      encounter_.reset();
      return false;
    }
  }
  if (!e.av_held || !e.hv_held) return false;  // still arriving
  e.drawn = true;
  e.out.time = now;
  e.out.draw = model.Draw(e.out.av, e.out.hv);
  return true;
}

void Interception::StartNudge(Environment& env, std::vector<Command>* out) {
  Active& e = *encounter_;
  // The nudge, once nobody inside the junction can touch the AV on its way
  // and, at a two-way stop, the major road is clear on both movements for
  // the critical gap: SUMO makes every vehicle that reaches the AV nudged
  // into the junction stop for it, inside the junction too, where it could
  // block the moves of the game for good. A still AV: at once.
  const bool creeps = e.out.draw.nudge_distance > 0;
  if (!e.nudge_started && env.Standing(e.out.av) && env.Standing(e.out.hv) &&
      (!creeps || env.WayClear(e.out.av, e.out.hv)) &&
      (!creeps || spec_.rule == Rule::kAllWay ||
       (env.MajorClear(e.out.av_movement) && env.MajorClear(e.out.hv_movement)))) {
    e.nudge_started = true;
    Command c{Command::Kind::kStartNudge, e.out.av};
    c.distance = e.out.draw.nudge_distance;
    out->push_back(c);
  }
}

// After the HV decided: the releases as the paper orders them. A move of
// the game (the AV that goes, the HV that drives recklessly, a careful one
// while the other still stands in the junction or at its line, yielding)
// goes with SUMO's right of way off once nobody inside the junction can
// touch it on its way; a careful one whose partner is on its way is handed
// back to SUMO's rules.
void Interception::Release(double now, Environment& env, std::vector<Command>* out) {
  Active& e = *encounter_;
  const bool av_goes = e.out.draw.goes_first;
  const bool hv_dc = e.out.reading.drives_if_clear;
  // Its nudge took the still AV's front past its line (read while it stands).
  const bool av_past = !e.av_released && env.PastLine(e.out.av);
  Ways w = WaysOf(env, av_past);
  // A standoff: the AV stands nudged inside the junction and vehicles SUMO
  // stopped there for it block a move of the game: those free to go may
  // pass it. They go first: a move of the game released in the same step
  // would meet them on its way (at a two-way stop MajorClear took them for
  // vehicles SUMO holds for the AV: issue 30, the left turn at C3).
  if (av_past && (!w.av_way || !w.hv_way) && Unblock(env, w, out)) return;
  // The AV goes and the HV drives recklessly: the game's premise is that
  // both start together, so each waits with the other for both ways and,
  // at a two-way stop, the major road on both movements.
  const bool together = av_goes && !hv_dc && !e.av_released && !e.hv_released;
  if (together) {
    if (spec_.rule == Rule::kTwoWay) w.av_may = w.av_may && env.MajorClear(e.out.hv_movement);
    if (!w.av_may || !w.av_way || !w.hv_way) return;
  }
  // The HV drives recklessly while the AV waits: reckless toward the AV
  // alone. At a two-way stop it waits for the major road's gap like every
  // other move (released with SUMO's right of way off, it would enter in
  // front of the major road's traffic: issue 30). The AV waits for it.
  const bool reckless_alone = !av_goes && !hv_dc && !e.hv_released;
  if (reckless_alone && spec_.rule == Rule::kTwoWay && !env.MajorClear(e.out.hv_movement))
    return;
  // The AV follows the HV once the HV is inside the junction (SUMO makes
  // it yield at the crossing point), unless its nudge took it past its own
  // line: once the HV has passed its way or left.
  const bool hv_ahead =
      e.hv_cleared || (e.hv_entered && (!av_past || env.Passed(e.out.hv, e.out.av)));
  for (const auto& rel : e.sequence->Update(now, e.av_entered, hv_ahead, w.av_may, w.hv_may,
                                            w.av_way, w.hv_way)) {
    // A careful move after its partner (released, inside the junction) is
    // SUMO's; before it (the partner still standing), the game's.
    const bool partner_released = rel.av ? e.hv_released : e.av_released;
    (rel.av ? e.av_released : e.hv_released) = true;
    const bool game = rel.reckless || (rel.av && av_goes) || !partner_released;
    if (!game) (rel.av ? e.av_handed_back : e.hv_handed_back) = true;
    Command c{game ? Command::Kind::kRelease : Command::Kind::kHandBack,
              rel.av ? e.out.av : e.out.hv};
    c.in_encounter = true;
    c.partner = rel.av ? e.out.hv : e.out.av;
    out->push_back(c);
    last_activity_ = now;
  }
  // Both on their way: the game holds nobody any more; the junction is
  // SUMO's again (third vehicles are handed back next step, and SUMO's own
  // logic makes them yield to the two), the two are watched until they
  // have left it (collisions, the record).
  if (e.av_released && e.hv_released) Hand();
}

Interception::Ways Interception::WaysOf(Environment& env, bool av_past) const {
  const Active& e = *encounter_;
  const bool av_goes = e.out.draw.goes_first;
  const bool hv_dc = e.out.reading.drives_if_clear;
  // SUMO's once released: a careful move after its partner from its line
  // (the still AV after the HV, the HV driving if clear after the AV).
  // SUMO's rules decide when it enters (its own gap acceptance and keep
  // clear). A still AV that its nudge took past its line has passed its
  // link, where SUMO no longer makes it yield: the controller checks for it.
  const bool av_sumos = !e.av_released && !av_goes && !av_past;
  const bool hv_sumos = !e.hv_released && av_goes && hv_dc;
  // The others: room at the exit (not the reckless HV: EncounterSequence)
  // and, at a two-way stop, a gap in the major road; and the way.
  auto may = [&](int movement, int vehicle) {
    return env.ExitHasRoom(movement, vehicle) &&
           (spec_.rule == Rule::kAllWay || env.MajorClear(movement));
  };
  Ways w;
  w.av_may = e.av_released || av_sumos || may(e.out.av_movement, e.out.av);
  w.hv_may = e.hv_released || hv_sumos || may(e.out.hv_movement, e.out.hv);
  w.av_way = e.av_released || av_sumos || env.WayClear(e.out.av, e.out.hv);
  w.hv_way = e.hv_released || hv_sumos || env.WayClear(e.out.hv, e.out.av);
  return w;
}

bool Interception::Unblock(Environment& env, const Ways& w, std::vector<Command>* out) {
  const Active& e = *encounter_;
  std::vector<int> blockers;
  if (!w.av_way) blockers = env.Unblockable(e.out.av, e.out.hv);
  if (!w.hv_way)
    for (int b : env.Unblockable(e.out.hv, e.out.av))
      if (std::find(blockers.begin(), blockers.end(), b) == blockers.end()) blockers.push_back(b);
  for (int b : blockers) out->push_back({Command::Kind::kUnblock, b});
  return !blockers.empty();
}

void Interception::Hand() {
  Active& e = *encounter_;
  if (e.av_cleared && e.hv_cleared) {
    finished_.push_back(e.out);
  } else {
    leaving_.push_back(std::move(e));
  }
  encounter_.reset();
}

void Interception::FormMajor(double now, const std::vector<AtLine>& at_line,
                             const std::vector<MajorAt>& major, Environment& env,
                             EncounterModel& model, std::vector<Command>* out) {
  // AVs standing at their minor lines, first come first; HVs nearest first.
  std::vector<const AtLine*> avs;
  for (const AtLine& a : at_line)
    if (a.kind == VehicleKind::kAV && a.waiting && a.movement >= 0 &&
        spec_.movements[a.movement].controlled)
      avs.push_back(&a);
  if (avs.empty() || major.empty()) return;
  std::sort(avs.begin(), avs.end(), [](const AtLine* x, const AtLine* y) {
    return x->since != y->since ? x->since < y->since : x->vehicle < y->vehicle;
  });
  std::vector<const MajorAt*> hvs;
  for (const MajorAt& m : major)
    if (m.movement >= 0 && !spec_.movements[m.movement].controlled) hvs.push_back(&m);
  std::sort(hvs.begin(), hvs.end(), [](const MajorAt* x, const MajorAt* y) {
    return x->gap != y->gap ? x->gap < y->gap : x->vehicle < y->vehicle;
  });
  for (const AtLine* av : avs) {
    for (const MajorAt* hv : hvs) {
      if (!spec_.Conflict(av->movement, hv->movement)) continue;
      if (major_never_.count({av->vehicle, hv->vehicle})) continue;
      if (!env.ExitHasRoom(av->movement, av->vehicle)) continue;
      const MajorVerdict v = model.MajorRoad(av->vehicle, *hv, av->movement);
      if (v.kind == MajorVerdict::Kind::kNever) major_never_.insert({av->vehicle, hv->vehicle});
      if (v.kind != MajorVerdict::Kind::kGame) continue;
      // Nobody inside the junction can touch the AV on its way, and no other
      // major vehicle comes within the critical gap while the signal lasts;
      // the AV stands (the nudge is measured from here).
      if (!env.WayClear(av->vehicle, hv->vehicle) ||
          !env.MajorClearBut(av->movement, hv->vehicle, hv->movement, v.signal) || !env.Standing(av->vehicle))
        continue;
      Active e;
      e.major = true;
      e.out.major_road = true;
      e.out.av = av->vehicle;
      e.out.hv = hv->vehicle;
      e.out.av_movement = av->movement;
      e.out.hv_movement = hv->movement;
      e.out.time = now;
      e.av_held = e.hv_held = true;
      e.drawn = true;
      e.nudge_started = true;
      encounter_ = std::move(e);
      out->push_back({Command::Kind::kHold, av->vehicle});
      Command cruise{Command::Kind::kCruise, hv->vehicle};
      cruise.speed = hv->speed;
      cruise.movement = hv->movement;
      cruise.partner = av->vehicle;
      out->push_back(cruise);
      encounter_->out.draw = model.Draw(av->vehicle, hv->vehicle);
      Command nudge{Command::Kind::kStartNudge, av->vehicle};
      nudge.distance = encounter_->out.draw.nudge_distance;
      nudge.duration = v.signal;
      out->push_back(nudge);
      last_activity_ = now;
      return;
    }
  }
}

// After the HV decided (NudgeDone): the AV that goes at once; the DR HV keeps
// its speed; the DC HV brakes, then is SUMO's once the AV has passed its way
// (or drives on past the waiting AV after confirm_delay); the waiting AV is
// SUMO's once the HV is inside (nudged past its line: once the HV has passed
// its way and its own way and the major road are clear).
void Interception::StepMajor(double now, Environment& env, std::vector<Command>* out) {
  Active& e = *encounter_;
  if (!e.nudged) return;  // the signal
  const int av = e.out.av, hv = e.out.hv;
  const bool av_goes = e.out.draw.goes_first;
  const bool hv_dc = e.out.reading.drives_if_clear;
  auto move = [&](Command::Kind kind, int vehicle) {
    Command c{kind, vehicle};
    c.in_encounter = true;
    c.partner = vehicle == av ? hv : av;
    out->push_back(c);
    last_activity_ = now;
  };
  if (!e.major_moves) {
    e.major_moves = true;
    if (av_goes) {
      e.av_released = true;
      move(Command::Kind::kRelease, av);
    }
    if (hv_dc) {
      Command y{Command::Kind::kYield, hv};
      y.speed = timing_.yield_decel;
      y.delay = timing_.reaction_time;
      out->push_back(y);
    } else {
      e.hv_released = true;  // keeps its speed, right of way off (kCruise)
    }
  }
  // A standoff (as at stop lines): the AV stands nudged inside the junction
  // and vehicles SUMO stopped there for it block a move of the game: those
  // free to go may pass it.
  const bool av_past = !e.av_released && env.PastLine(av);
  auto unblock = [&](int vehicle, int partner, bool starters = false) {
    if (!av_past) return;
    for (int b : starters ? env.UnblockableStarters(vehicle, partner)
                          : env.Unblockable(vehicle, partner))
      out->push_back({Command::Kind::kUnblock, b});
  };
  if (hv_dc && !e.hv_released) {
    if (av_goes) {
      if (e.av_cleared || (e.av_entered && env.Passed(av, hv))) {
        e.hv_released = e.hv_handed_back = true;
        move(Command::Kind::kHandBack, hv);
      }
    } else if (now >= e.out.decided_at + timing_.confirm_delay - 1e-9) {
      if (env.WayClear(hv, av)) {
        e.hv_released = true;
        move(Command::Kind::kRelease, hv);
      } else {
        unblock(hv, av);
      }
    }
  }
  if (!av_goes && !e.av_released && e.hv_released) {
    if (!av_past) {
      if (e.hv_entered) {
        e.av_released = e.av_handed_back = true;
        move(Command::Kind::kHandBack, av);
      }
    } else if (e.hv_cleared || (e.hv_entered && env.Passed(hv, av))) {
      // Vehicles SUMO held inside the junction for the HV may start as it
      // passes them: until it has left the junction (and kStarterGrace after)
      // the AV waits for those standing clear of it too (WayClearOfStarters);
      // one still standing after that is held by something else (the AV
      // itself, typically) and stays, as WayClear takes it (waiting for it
      // longer held a DC HV at its line for minutes on the two-way grid).
      const bool starters = !e.hv_cleared || now < e.hv_cleared_at + kStarterGrace;
      if (!(starters ? env.WayClearOfStarters(av, hv) : env.WayClear(av, hv))) {
        unblock(av, hv, starters);
      } else if (env.ExitHasRoom(e.out.av_movement, av) && env.MajorClear(e.out.av_movement)) {
        e.av_released = true;
        move(Command::Kind::kRelease, av);
      }
    }
  }
  if (e.av_released && e.hv_released) Hand();
}

void Interception::Entered(int vehicle, double now) {
  last_activity_ = now;
  auto mark = [&](Active& e) {
    if (e.out.av == vehicle) e.av_entered = true;
    if (e.out.hv == vehicle) e.hv_entered = true;
  };
  if (encounter_) mark(*encounter_);
  for (Active& e : leaving_) mark(e);
}

void Interception::Cleared(int vehicle, double now) {
  last_activity_ = now;
  auto mark = [&](Active& e) {
    if (e.out.av == vehicle) e.av_entered = e.av_cleared = true;
    if (e.out.hv == vehicle) {
      if (!e.hv_cleared) e.hv_cleared_at = now;
      e.hv_entered = e.hv_cleared = true;
    }
  };
  if (encounter_) mark(*encounter_);  // its partner not yet released
  for (auto it = leaving_.begin(); it != leaving_.end();) {
    mark(*it);
    if (it->av_cleared && it->hv_cleared) {
      finished_.push_back(it->out);
      it = leaving_.erase(it);
    } else {
      ++it;
    }
  }
}

void Interception::NudgeDone(int av, double observed, double now, EncounterModel& model) {
  if (!encounter_ || encounter_->out.av != av || encounter_->nudged)
    throw std::logic_error("junction " + spec_.id + ": NudgeDone for a vehicle in no encounter");
  Active& e = *encounter_;
  e.nudged = true;
  e.out.reading = model.Read(e.out.av, e.out.hv, observed);
  e.out.decided_at = now;
  if (e.major) return;  // StepMajor
  e.sequence.emplace(e.out.draw.goes_first, e.out.reading.drives_if_clear, now,
                     timing_.confirm_delay);
}

bool Interception::Collided(int a, int b) {
  // A collision after one of the two went back to SUMO's rules is SUMO's
  // (its junction model: e.g. a long vehicle on a small junction), not the
  // game's outcome.
  auto pair = [&](Active& e) {
    EncounterOutcome& o = e.out;
    if ((o.av == a && o.hv == b) || (o.av == b && o.hv == a)) {
      (e.av_handed_back || e.hv_handed_back ? o.collision_after_handback : o.collision) = true;
      return true;
    }
    return false;
  };
  if (encounter_ && encounter_->drawn && pair(*encounter_)) return true;
  for (Active& e : leaving_)
    if (pair(e)) return true;
  return false;
}

std::vector<EncounterOutcome> Interception::TakeFinished() {
  std::vector<EncounterOutcome> out;
  out.swap(finished_);
  return out;
}

std::string Interception::Describe(const std::function<std::string(int)>& name) const {
  std::string out;
  if (encounter_) {
    const Active& e = *encounter_;
    auto mv = [&](int m) {
      const Movement& x = spec_.movements[m];
      return x.from_lane + ">" + x.to_lane;
    };
    out += std::string(e.major ? "major-road encounter" : e.drawn ? "encounter" : "meeting (partner arriving)") + " AV " + name(e.out.av) + " (" + mv(e.out.av_movement) + ") / HV " +
           name(e.out.hv) + " (" + mv(e.out.hv_movement) + ")" +
           (!e.nudge_started ? ", waiting for the conflict area to clear"
            : !e.nudged      ? ", nudging"
                             : std::string(", decided: AV ") +
                                   (e.out.draw.goes_first ? "goes" : "stays") + ", HV " +
                                   (e.out.reading.drives_if_clear ? "drives if clear" : "drives recklessly")) +
           (e.av_released ? ", AV released" : "") + (e.hv_released ? ", HV released" : "") +
           (e.av_cleared ? ", AV cleared" : "") + (e.hv_cleared ? ", HV cleared" : "");
  }
  for (const Active& e : leaving_)
    out += std::string(out.empty() ? "" : "; ") + "encounter " + name(e.out.av) + "/" +
           name(e.out.hv) + " leaving the junction";
  if (!thirds_.empty()) {
    out += std::string(out.empty() ? "" : "; ") + "held for it:";
    for (int v : thirds_) out += " " + name(v);
  }
  return out;
}

}  // namespace taebp::junction
