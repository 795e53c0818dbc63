// The network controller's step: the parts, in the order they run.
//   vehicles.h          who is in the network (registered on departure)
//   route_progress.h    junctions passed and near (which junctions are watched)
//   stop_lines.h        what SUMO shows at a watched junction's stop lines
//   junction/interception.h   who meets whom, and the commands (SUMO-free)
//   vehicle_commands.h  holds, nudges, releases, hand-backs in SUMO
//   encounter_game.h    the paper's game for each pair, and its record
//   collisions.h        SUMO's collisions attributed
//   stalls.h            the safety net
//   figure8.h           every special case of the paper's track
#include "taebp/controller/network_controller.h"
#include "taebp/controller/sumo_adapter.h"

#include "collisions.h"
#include "encounter_game.h"
#include "figure8.h"
#include "paired.h"
#include "route_progress.h"
#include "run_state.h"
#include "stalls.h"
#include "stop_lines.h"
#include "vehicle_commands.h"

#include "taebp/config/model.h"

#include "taebp/report/sample_spool.h"

#include <algorithm>
#include <cmath>

namespace taebp {
namespace control {

std::unique_ptr<HvPopulation> MakePopulation(const RunState& s, persuasion::Policy policy) {
  return std::make_unique<HvPopulation>(s.cfg, policy);
}

void MakePopulations(RunState& s, persuasion::Policy policy) {
  // Each HV's trust, the AV's design for it, its reading (hv_population.h).
  s.population = MakePopulation(s, policy);
  // Its time series go to disk as sampled (report/sample_spool.h), beside
  // SUMO's outputs in the scenario's scratch folder.
  if (s.population->Beyond())
    s.population->SampleInto(std::make_shared<SampleSpool>(
        PolicyName(policy), s.scenario.scratch ? s.scenario.scratch->path() : std::string()));
}

RunState::RunState(const ExperimentConfig& config, std::optional<persuasion::Policy> policy,
                   const Scenario& scenario, const net::NetFile& net,
                   const ControllerOptions& options, SumoWorld& world)
    : cfg(config),
      sc(config.scenario),
      policy(policy),
      scenario(scenario),
      net(net),
      opts(options),
      sumo(world),
      dt(config.scenario.step_length),
      sample_every(std::max(1L, std::lround(1.0 / config.scenario.step_length))),
      topo(config.scenario, scenario, net, sample_every * config.scenario.step_length) {
  out.policy = policy ? PolicyName(*policy) : SumoNative().name;
  out.scenario_kind = EnumName(sc.kind);
  if (policy) {
    MakePopulations(*this, *policy);
    out.scheme = population->PopulationScheme();
    out.theory = population->Theory();
  }
  approaches.resize(topo.approaches().size());
  for (std::size_t a = 0; a < approaches.size(); ++a)
    approaches[a].stats.lane = topo.approaches()[a].lane;
  for (const JunctionInfo& info : topo.junctions()) {
    JunctionState j;
    junction::Timing timing;
    timing.confirm_delay = sc.confirm_delay;
    if (sc.MajorRoadGame() && policy) {
      timing.major_road = true;
      timing.yield_decel = sc.major_road.comfortable_decel;
      timing.reaction_time = sc.major_road.reaction_time;
    }
    j.logic = std::make_unique<junction::Interception>(info.spec, timing);
    j.run.id = info.info.id;
    j.run.type = info.info.type;
    j.run.original_type = info.info.original_type;
    j.run.rule = junction::ToString(info.spec.rule);
    j.run.game_pairs = junction::GamePairs(info.spec, sc.MajorRoadGame());
    for (int a : info.approaches) j.run.approaches.push_back(approaches[a].stats);
    junctions.push_back(std::move(j));
  }
}

}  // namespace control

using control::RunState;

struct NetworkController::Impl {
  Impl(const ExperimentConfig& config, std::optional<persuasion::Policy> policy,
       const Scenario& scenario, const net::NetFile& net, const ControllerOptions& options,
       SumoWorld& world)
      : s(config, policy, scenario, net, options, world),
        game(s),
        commands(s, game),
        collisions(s, commands),
        pairing(s) {
    game.set_commands(&commands);
    game.set_pairing(&pairing);
  }

  // A vehicle entered the network: AV or HV (the HV's trust, the AV's
  // design for it), its type's size and kinematics, its route.
  void Register(const std::string& id) {
    control::Vehicle v;
    v.id = id;
    v.alive = true;
    const bool av = control::IsAv(s.sc, id, [&] { return s.sumo.TypeID(id); });
    v.kind = av ? VehicleKind::kAV : VehicleKind::kHV;
    if (av) s.avs.insert(id);
    if (!av) {
      v.trust = control::HvTrust(s.cfg, id);
      if (s.policy) s.population->Add(id, v.trust);
      if (s.out.hv_trust.size() < kTrustListMax) s.out.hv_trust.push_back(v.trust);
    }
    v.length = s.sumo.Length(id);
    v.min_gap = s.sumo.MinGap(id);
    v.width = s.sumo.Width(id);
    v.accel = s.sumo.Accel(id);
    v.decel = s.sumo.Decel(id);
    v.emergency_decel = s.sumo.EmergencyDecel(id);
    v.sigma = s.sumo.Imperfection(id);
    v.max_speed = s.sumo.MaxSpeed(id);
    for (const std::string& e : s.sumo.Route(id)) v.route.push_back(s.topo.EdgeIndex(e));
    v.route_pos = std::max(0, s.sumo.RouteIndex(id));
    if (s.policy) {  // the stop lines it may now reach sooner than thought
      control::SpeedFactorSeen(s, s.sumo.SpeedFactor(id));
      if (v.route_pos < static_cast<int>(v.route.size()))
        control::ApproachDeparture(s, s.topo.EdgeName(v.route[v.route_pos]));
    }
    const int h = s.vehicles.Add(std::move(v));
    control::UpdateNear(s, h);
    if (s.opts.colour_states) {
      s.vehicles[h].paint = control::Paint::kNudging;  // force the first paint
      commands.SetPaint(h, control::Paint::kType);
    }
    if (s.measuring()) ++s.out.network.departed;
  }

  void Unregister(const std::string& id) {
    const int h = s.vehicles.Find(id);
    if (h < 0) return;
    control::Vehicle& v = s.vehicles[h];
    control::CountProgress(s, h, static_cast<int>(v.route.size()) - 1);
    v.alive = false;
    if (s.population && v.kind == VehicleKind::kHV) s.population->Remove(id);
    if (v.state == control::State::kCrossing) commands.Clear(h);  // left inside a junction
    pairing.Left(h);
    control::SetNear(s, h, {});
    if (s.measuring()) ++s.out.network.arrived;
    s.vehicles.Remove(h);
  }

  // One watched junction's step: what SUMO shows at its lines, then the
  // interception's commands, then the encounters that finished.
  void Decide(control::JunctionState& j) {
    control::Observe(s, j);
    if (s.policy && s.sc.MajorRoadGame()) control::ObserveMajor(s, j);
    control::StopLineEnvironment env(s, j);
    const long abandoned = j.logic->AbandonedMeetings();
    const std::vector<junction::Command> todo =
        j.logic->Step(s.now, j.at_line, env, game, j.major);
    if (s.measuring()) j.run.meetings_abandoned += j.logic->AbandonedMeetings() - abandoned;
    for (const junction::Command& c : todo) commands.Execute(j, c);
    for (const junction::EncounterOutcome& e : j.logic->TakeFinished()) game.Record(j, e);
  }

  // Once a simulated second: route progress (junction crossings, the
  // figure-8's circulation, which junctions each vehicle is near), queues,
  // the demand waiting to depart, stalls.
  void Sample() {
    for (const auto& [id, h] : s.vehicles.in_network()) {
      control::CountProgress(s, h, s.sumo.RouteIndex(id));
      control::figure8::KeepCirculating(s, h);
      control::UpdateNear(s, h);
    }
    control::SampleWaiting(s);
    if (s.measuring()) {
      for (std::size_t a = 0; a < s.approaches.size(); ++a) {
        ApproachStats& st = s.approaches[a].stats;
        const double q = control::ApproachHalting(s, static_cast<int>(a));
        st.queue_max = std::max(st.queue_max, q);
        st.queue_sum += q;
        ++st.samples;
      }
    }
    control::CheckStalls(s);
    if (s.population) s.population->Sample(s.now);
    if (!s.measuring()) return;
    if (s.sc.IsNetwork()) {
      s.out.network.vehicles_max = std::max(
          s.out.network.vehicles_max, static_cast<long>(s.vehicles.in_network().size()));
      const long pending = s.sumo.PendingNumber();
      s.out.network.pending_max = std::max(s.out.network.pending_max, pending);
      s.out.network.pending_end = pending;
    }
  }

  static constexpr std::size_t kTrustListMax = 100000;
  RunState s;
  control::EncounterGame game;
  control::VehicleCommands commands;
  control::CollisionAttribution collisions;
  control::Pairing pairing;  // scenario.paired
  long steps = 0;
};

NetworkController::NetworkController(const ExperimentConfig& config,
                                     std::optional<persuasion::Policy> policy,
                                     const Scenario& scenario, const net::NetFile& net,
                                     const ControllerOptions& options, SumoWorld* world)
    : impl_(std::make_unique<Impl>(config, policy, scenario, net, options,
                                   world ? *world : Sumo())) {}

NetworkController::~NetworkController() = default;

void NetworkController::Start() {
  RunState& s = impl_->s;
  s.out.sumo_version = s.sumo.Version();
  control::figure8::PlaceVehicles(s);
  s.stall_limit =
      s.opts.stall_limit >= 0 ? s.opts.stall_limit : control::figure8::DefaultStallLimit(s);
  s.now = s.sumo.Time();
  s.last_crossing = s.now;
  for (control::JunctionState& j : s.junctions) j.last_progress = s.now;
}

void NetworkController::Step() {
  Impl& c = *impl_;
  RunState& s = c.s;
  s.now = s.sumo.Time();
  ++c.steps;
  s.step = c.steps;
  if (s.sumo.TeleportNumber() > 0 && s.measuring()) ++s.out.teleports;
  // The vehicles already waiting to depart when the measured time begins
  // (the offered demand is counted from there): read each warm-up step, the
  // last one's stays.
  if (!s.measuring() && s.sc.IsNetwork()) s.out.network.pending_start = s.sumo.PendingNumber();
  if (s.sumo.DepartedNumber() > 0)
    for (const std::string& id : s.sumo.DepartedIDs()) c.Register(id);
  if (s.sumo.ArrivedNumber() > 0)
    for (const std::string& id : s.sumo.ArrivedIDs()) c.Unregister(id);
  if (c.collisions.Due()) c.collisions.Attribute();
  if (s.policy) {
    if (!s.crossing.empty()) c.commands.UpdateCrossing();
    if (!s.nudging.empty()) c.commands.UpdateNudges();
    if (!s.unblocked.empty()) c.commands.UpdateUnblocked();
    if (!s.yielding.empty()) c.commands.UpdateYields();
    for (control::JunctionState& j : s.junctions)
      if (control::Watched(s, j)) c.Decide(j);
  }
  if (c.steps % s.sample_every == 0) c.Sample();
  s.out.longest_gap_without_crossing =
      std::max(s.out.longest_gap_without_crossing, s.now - s.last_crossing);
  c.pairing.Step();  // a branch whose game is over ends here
}

bool NetworkController::InBranch() const { return impl_->pairing.InBranch(); }
void NetworkController::EndBranch(const std::string& status, const std::string& error) {
  impl_->pairing.EndBranch(status, error);
}

bool NetworkController::DepartedAsAv(const std::string& id) const {
  return impl_->s.avs.count(id) > 0;
}
long NetworkController::VehiclesNow() const {
  return static_cast<long>(impl_->s.vehicles.in_network().size());
}
long NetworkController::EncountersSoFar() const {
  return static_cast<long>(impl_->s.out.encounters.size());
}

PolicyRun NetworkController::Finish() {
  RunState& s = impl_->s;
  s.now = s.sumo.Time();
  for (const auto& [id, h] : s.vehicles.in_network())
    control::CountProgress(s, h, s.sumo.RouteIndex(id));
  s.out.simulated_seconds = s.now;
  s.out.measured_seconds = std::max(0.0, s.now - s.sc.warmup);
  if (s.population) {
    s.out.beyond = s.population->Results(s.now);
    // Each kind's theory weighted by its encounters (each record has its own).
    s.out.theory = s.population->Theory();
  } else {
    s.out.beyond.on = s.cfg.BeyondPaper();  // sumo_native: the same columns as the others
  }
  for (std::size_t i = 0; i < s.junctions.size(); ++i) {
    control::JunctionState& j = s.junctions[i];
    const std::vector<int>& approaches = s.topo.junctions()[i].approaches;
    for (std::size_t k = 0; k < approaches.size(); ++k)
      j.run.approaches[k] = s.approaches[approaches[k]].stats;
    s.out.crossings_av += j.run.crossings_av;
    s.out.crossings_hv += j.run.crossings_hv;
    s.out.wait_sum += j.run.wait_sum;
    s.out.wait_max = std::max(s.out.wait_max, j.run.wait_max);
    s.out.held += j.run.held;
    s.out.held_av += j.run.held_av;
    s.out.wait_sum_av += j.run.wait_sum_av;
    // Of the encounters drawn after the warm-up (as the rows): those still
    // running at the end.
    s.out.encounters_unfinished += j.logic->Encounters(s.sc.warmup);
    if (s.now > s.sc.warmup)
      j.run.longest_gap_without_crossing = std::max(
          j.run.longest_gap_without_crossing, s.now - std::max(j.last_progress, s.sc.warmup));
    s.out.junctions.push_back(j.run);
  }
  // Formed = a row in encounters.csv (drawn after the warm-up, finished) or
  // still running: rows = formed - unfinished.
  s.out.encounters_formed =
      static_cast<long>(s.out.encounters.size()) + s.out.encounters_unfinished;
  return std::move(s.out);
}

}  // namespace taebp
