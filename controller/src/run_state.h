// What the parts of the network controller share during one policy run: the
// config, the SUMO world, the topology, the vehicles, each controlled
// junction's interception logic and counters, the clock and the outputs.
// Data only; each part (route_progress.h, stop_lines.h, vehicle_commands.h,
// encounter_game.h, collisions.h, stalls.h, figure8.h) does one job on it,
// and network_controller.cc runs them in the order of a step.
#pragma once

#include "taebp/controller/network_controller.h"
#include "taebp/controller/sumo_world.h"
#include "taebp/encounter/hv_population.h"
#include "taebp/junction/interception.h"
#include "taebp/base/number_text.h"
#include "topology.h"
#include "vehicles.h"

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

namespace taebp::control {

// Speed modes (bits: 1 safe speed, 2 max accel, 4 max decel, 8 right of way,
// 16 red light, 32 ignore foes already in the junction).
constexpr int kModeDefault = 31;   // SUMO's own rules (stop signs included)
// A move of the game (VehicleCommands::GameMove): right of way off, its
// partner named (SetIgnoredFoes). Issue 30 item 1 is open: keeping SUMO's
// right of way at the link toward third vehicles at two-way stops (mode 63 or
// 31 + the partner ignored) was measured and not kept (docs/encounter-rules.md:
// the grid stalled, both-proceed pairs stopped colliding, game moves still hit
// third vehicles).
constexpr int kModeReleased = 55;  // the controller decided the junction; keep car-following
constexpr int kModeCreep = 0;      // exact commanded speeds during a nudge
constexpr int kModeUnblocked = 63; // SUMO's rules, foes already in the junction disregarded
// Lane-change modes: a held vehicle stays in its lane (SUMO would otherwise
// move a standing vehicle to the next lane, off the movement its encounter
// was predicted on); released, SUMO's default again.
constexpr int kLaneChangeHeld = 0;
constexpr int kLaneChangeDefault = 1621;

constexpr double kHaltSpeed = 0.1;  // m/s: SUMO's halting threshold

struct ApproachState {
  int front = -1;  // the vehicle at its front last time it was looked at
  // The first step at which a vehicle may be near its line: not looked at
  // before (stop_lines.cc, Observe).
  long next_look = 0;
  ApproachStats stats;
};

struct JunctionState {
  std::unique_ptr<junction::Interception> logic;
  JunctionRun run;
  int near_av = 0, near_hv = 0;  // vehicles that may reach its stop lines before the next sample
  std::vector<junction::AtLine> at_line;  // this step
  std::vector<junction::MajorAt> major;    // this step: HVs approaching on the major road
  double last_progress = 0;     // a vehicle last passed it (route progress)
  bool waiting = false;         // vehicles halted on its incoming lanes (last sample)
  bool watched = false;         // looked at this step
  double waiting_since = 0;     // since when (an idle junction is not stalled)
  bool stall_recorded = false;  // this stall episode is in the outputs
  double stall_since = -1;
};

struct RunState {
  RunState(const ExperimentConfig& config, std::optional<persuasion::Policy> policy,
           const Scenario& scenario, const net::NetFile& net, const ControllerOptions& options,
           SumoWorld& world);

  bool measuring() const { return now >= sc.warmup; }
  int Index(const JunctionState& j) const { return static_cast<int>(&j - junctions.data()); }

  const ExperimentConfig& cfg;
  const ScenarioConfig& sc;
  std::optional<persuasion::Policy> policy;  // empty: sumo_native
  const Scenario& scenario;
  const net::NetFile& net;
  ControllerOptions opts;
  SumoWorld& sumo;
  double dt = 0.1;
  long sample_every = 10;  // steps between two samples (about a second)
  double now = 0;
  long step = 0;  // steps simulated
  double last_crossing = 0;
  // The largest speed factor of any vehicle so far: nobody drives faster than
  // this times a lane's speed limit.
  double max_speed_factor = 0;
  double stall_limit = 120;
  // Approach lanes' halting numbers read at this step (ApproachHalting): each once.
  std::vector<int> halting;  // as approaches; -1: not read
  long halting_step = -1;

  Topology topo;
  VehicleRegistry vehicles;
  std::vector<JunctionState> junctions;    // as topo.junctions()
  std::vector<ApproachState> approaches;   // as topo.approaches()
  std::vector<int> crossing, nudging;      // vehicles released and not out / creeping
  std::vector<int> unblocked;              // let past a nudged AV, still in the junction
  std::vector<int> yielding;               // major-road HVs braking for an AV (DC)
  // Policy runs only: both kinds of game (the major road's, scenario.major_road:
  // the paper's game at r_eff = 2 (r - c) / (2 + c), persuasion/major_road.h).
  std::unique_ptr<HvPopulation> population;
  std::unordered_set<std::string> avs;       // every vehicle that departed as an AV
  PolicyRun out;
};

// The HV population of game policy `policy` (s.population): each HV's trust,
// the AV's design for it in each kind of game, its reading
// (hv_population.h); no HV added yet.
void MakePopulations(RunState& s, persuasion::Policy policy);
std::unique_ptr<HvPopulation> MakePopulation(const RunState& s, persuasion::Policy policy);


}  // namespace taebp::control
