// The scenario section of an experiment config (scenario:): the network and
// vehicles of a run, its demand, the junctions the controller takes over, SUMO's
// outputs and safety measures. Plain structs with defaults at the field and one
// schema (Serialize); checked by ExperimentConfig::IsValid (config.h).
#pragma once

#include "taebp/config/enums.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace taebp {

// Which junctions of a network the controller takes over (kind: network).
// A junction is selected when its id is listed or its SUMO type is; SUMO
// types without stop signs are turned into stop-controlled junctions for the
// run (the net is patched with netconvert, geometry unchanged): `priority`
// junctions become two-way stops (minor roads stop, SUMO's priorities), and
// `right_before_left` / `unregulated` ones all-way stops, unless said here.
struct JunctionSelection {
  std::vector<std::string> ids;    // junction ids
  std::vector<std::string> types = {"allway_stop", "priority_stop"};
  StopRule priority = StopRule::kTwoWay;
  StopRule right_before_left = StopRule::kAllWay;
  StopRule unregulated = StopRule::kAllWay;
  // Only junctions whose incoming lanes all have speed limits at most this
  // (m/s; 0: any), e.g. 13.9 keeps an OSM import's town streets and leaves
  // its motorway and trunk junctions to SUMO. Applies to `types`, not `ids`.
  double max_speed = 0.0;
  // Only junctions where at least this many roads open to cars meet (arms:
  // the distinct junctions their car edges lead to or come from; 0: any),
  // e.g. 3 keeps an OSM import's intersections and leaves to SUMO the nodes
  // along one street (a lane added or dropped, a footway or a cycle path
  // crossing), whose stop signs would stop the street's own traffic. Applies
  // to `types`, not `ids`.
  int min_arms = 0;
  // Junctions left to SUMO although `types` selects them (e.g. the two
  // halves of a dual carriageway a few metres apart, where two stop lines
  // leave no room to queue between them).
  std::vector<std::string> exclude;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("ids", &ids);
    a->Visit("types", &types);
    a->Visit("max_speed", &max_speed);
    a->Visit("min_arms", &min_arms);
    a->Visit("exclude", &exclude);
    a->Visit("priority", &priority);
    a->Visit("right_before_left", &right_before_left);
    a->Visit("unregulated", &unregulated);
  }
};

// A grid generated with SUMO's netgenerate at run time (cached): columns x
// rows junctions `length` m apart, fringe edges `attach_length` m long.
struct GridConfig {
  int columns = 4;
  int rows = 4;
  double length = 100.0;         // m between junctions
  double attach_length = 100.0;  // m of the fringe edges (0: none)
  int lanes = 1;                 // per direction
  double speed = 13.89;          // m/s speed limit
  GridJunctionType junction_type = GridJunctionType::kAllwayStop;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("columns", &columns);
    a->Visit("rows", &rows);
    a->Visit("length", &length);
    a->Visit("attach_length", &attach_length);
    a->Visit("lanes", &lanes);
    a->Visit("speed", &speed);
    a->Visit("junction_type", &junction_type);
  }
};

// Generated demand: every origin edge gets `flow` vehicles per hour (random
// arrivals, seeded), each bound for a random destination it can reach
// (routing: random) and routed by SUMO on the fastest path. Origins: fringe,
// the edges entering the network from a dead end, bound for the fringe exits
// (not the way back); minor_roads, the minor approaches of the controlled
// junctions (a link from the edge yields or stops there and none goes
// straight on with the right of way), bound for another junction's minor
// approach or a fringe exit: a city's side streets, where a two-way stop's
// minor road meets its major road.
struct DemandConfig {
  double flow = 300.0;           // veh/h departing per origin edge
  Routing routing = Routing::kRandom;  // random: a uniformly random reachable destination
  double end = -1.0;             // s, last departure (< 0: scenario.duration)
  DemandOrigins origins = DemandOrigins::kFringe;
  double major_flow = 0.0;       // veh/h per major approach of the controlled junctions

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("flow", &flow);
    a->Visit("routing", &routing);
    a->Visit("end", &end);
    a->Visit("origins", &origins);
    a->Visit("major_flow", &major_flow);
  }
};

// scenario.outputs.ssm.thresholds: SUMO's SSM thresholds (SUMO 1.15's
// defaults). A conflict record counts for a measure when its value passes the
// threshold as SUMO's own test does: TTC <= TTC, DRAC >= DRAC, PET <= PET.
struct SsmThresholds {
  double ttc = 3.0;   // s, time to collision
  double drac = 3.0;  // m/s^2, deceleration rate to avoid a crash
  double pet = 2.0;   // s, post-encroachment time

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("TTC", &ttc);
    a->Visit("DRAC", &drac);
    a->Visit("PET", &pet);
  }
};

// scenario.outputs.ssm (unset: off; `ssm: {}` for SUMO's defaults): SUMO's
// surrogate-safety device on every vehicle under every policy, sumo_native
// included (docs/ssm.md). SUMO writes DIR/POLICY/ssm.xml; the run reports its
// conflicts by measure per policy and per controlled junction (the ssm_*
// metrics). A conflict is at a controlled junction when its point lies within
// junction_radius of one of the junction's internal lanes (the nearest wins).
struct SsmConfig {
  std::vector<std::string> measures = {"TTC", "DRAC", "PET"};  // of TTC, DRAC, PET
  SsmThresholds thresholds;
  double junction_radius = 10.0;  // m

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("measures", &measures);
    a->Visit("thresholds", &thresholds);
    a->Visit("junction_radius", &junction_radius);
  }
  bool Measures(const std::string& m) const {
    for (const std::string& x : measures)
      if (x == m) return true;
    return false;
  }
};
// The measures SUMO 1.15's SSM device computes that have a conflict threshold.
inline const std::vector<std::string>& SsmMeasures() {
  static const std::vector<std::string> kMeasures = {"TTC", "DRAC", "PET"};
  return kMeasures;
}

// SUMO's own outputs, per policy, in the run folder as DIR/POLICY/NAME
// (README "Outputs"): fcd.xml (every vehicle's position each step),
// edgedata.xml / lanedata.xml (SUMO's edge / lane means over the measured
// time), queue.xml (queues per lane each step).
struct OutputsConfig {
  bool fcd = false;
  bool edgedata = false;
  bool lanedata = false;
  bool queue = false;
  std::optional<SsmConfig> ssm;  // surrogate safety measures (above); a sweep keeps them too

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("fcd", &fcd);
    a->Visit("edgedata", &edgedata);
    a->Visit("lanedata", &lanedata);
    a->Visit("queue", &queue);
    a->Visit("ssm", &ssm);
  }
  // The outputs kept only as files (a sweep refuses them); ssm is a metric too.
  bool Any() const { return fcd || edgedata || lanedata || queue; }
};

// scenario.major_road (network scenarios; on by default, `enabled: false`
// turns it off): the major-road encounter of docs/beyond/major-road.md at
// two-way stops (priority_stop). An
// AV waiting at a minor road's stop line and an HV approaching on a
// conflicting major movement (right of way, not stopping) play the paper's
// game at the effective penalty r_eff = 2 (r - c) / (2 + c), when
// ClassifyMajorRoadApproach (persuasion/major_road.h) says the approach is a
// game: both proceeding collides on the junction's geometry and the HV can
// still yield braking at `comfortable_decel` after `reaction_time`. The AV
// nudges, the HV reads SUMO's displacement and yields (DC: brakes so the AV
// goes first) or keeps its speed (DR). Pairs where both wait at stop lines
// stay as they are. With every policy and model: one HV population plays both
// kinds of game (encounter/hv_population.h), its trust carried over.
struct MajorRoadConfig {
  bool enabled = true;             // false: only pairs that both stop at lines meet
  double yield_cost = 0.0;         // c in [0, model.collision_penalty): the cost of yielding
  double comfortable_decel = 3.0;  // m/s^2 a > 0, at most the HV's SUMO decel: how a DC HV brakes
  double reaction_time = 0.0;      // s t_r >= 0: from the HV's decision until it brakes

  // `major_road: ~` is how result folders written while the section was
  // optional (unset: off) say it was off: they rerun as they ran.
  void ReadNull() { enabled = false; }

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("enabled", &enabled);
    a->Visit("yield_cost", &yield_cost);
    a->Visit("comfortable_decel", &comfortable_decel);
    a->Visit("reaction_time", &reaction_time);
  }
};

struct ScenarioConfig {
  // figure8: the paper's track, vehicles circulating (avs, hvs, loop_length,
  // stop_distance). network: any SUMO network with vehicles entering and
  // leaving (network or sumocfg or grid; routes and/or demand).
  ScenarioKind kind = ScenarioKind::kFigure8;
  int avs = 8;                  // number of autonomous vehicles (blue)
  int hvs = 8;                  // number of human-driven vehicles (red)
  double cruise_speed = 4.0;    // m/s
  double min_gap = 2.0;         // m, SUMO minGap
  double stop_distance = 3.0;   // m from the front to the centre when held (>= s_max + width/2: README "Geometry")
  double step_length = 0.1;     // s
  double duration = 3600.0;     // simulated seconds per policy
  std::uint64_t seed = 1;       // run seed (SUMO --seed and the controller's RNG)
  double vehicle_length = 5.0;  // m
  double vehicle_width = 1.8;   // m
  double accel = 2.6;           // m/s^2
  double decel = 4.5;           // m/s^2
  double meeting_distance = 2.0;  // m: an AV and an HV meet when one waits at its line and the other is this near its own (README)
  double confirm_delay = 1.0;   // s: a DC HV facing a waiting AV waits this long
  double creep_speed = 1.0;     // m/s: top speed of a nudge
  double loop_length = 80.0;    // m per loop of the figure-8 (network generation)
  bool auto_length = true;      // grow the loops when the vehicles do not fit
  std::string network;          // path to a .net.xml; empty: the built-in figure-8
  // kind: network
  std::string sumocfg;                  // a .sumocfg: its net, route and additional files
  std::vector<std::string> routes;      // SUMO route files (vehicles, flows, trips, vTypes)
  // SUMO's --scale: every route file's demand (and the generated demand)
  // multiplied by this factor (seeded by scenario.seed); 1 = as written.
  double routes_scale = 1.0;
  std::vector<std::string> additional;  // SUMO additional files
  std::optional<GridConfig> grid;       // generate the network instead
  std::optional<DemandConfig> demand;   // generate demand on the fringe
  JunctionSelection junctions;
  // Each departing vehicle is an AV with this probability (seeded, by vehicle
  // id); unset: the vehicles whose SUMO type is in av_types are AVs.
  std::optional<double> av_share;
  std::vector<std::string> av_types = {"AV"};
  double warmup = 0.0;          // s: nothing before this counts in the outputs
  double critical_gap = 5.0;    // s: a minor head at a two-way stop needs this gap on the major road
  bool tripinfo_output = false;  // keep SUMO's tripinfo.xml in the output directory
  bool summary_output = false;   // keep SUMO's summary.xml in the output directory
  OutputsConfig outputs;         // SUMO's outputs per policy: DIR/POLICY/...
  // A nudge SUMO did not realise (observed outside [s, s + 1 mm]): error
  // (stop the run) or count (record it and go on).
  NudgeCheck nudge_check = NudgeCheck::kError;
  // Traffic stalled at a junction (vehicles wait, none passes it for the
  // stall limit; see RunOptions): error (stop the run, say where and why) or
  // record (note it in the outputs and go on: a gridlocked network measured
  // as it is, e.g. beyond saturation).
  StallAction stall_action = StallAction::kError;
  // Network scenarios: which AV-HV meetings on conflicting movements are the
  // paper's game. colliding: those where both proceeding would collide on the
  // junction's geometry (the game's premise; a merge the AV leads is not one
  // and goes by arrival); all: every conflicting pair (SUMO then decides
  // collisions that the theory's "AV goes, HV drives recklessly" may not
  // produce). The figure-8's crossing is always the game.
  EncounterPairs encounter_pairs = EncounterPairs::kColliding;
  // Network scenarios: the major-road encounter at two-way stops (an AV at
  // the minor stop line, an HV approaching on the major road); on unless
  // `enabled: false` (see MajorRoadConfig). The figure-8 has no major road.
  MajorRoadConfig major_road;
  // Paired games (docs/paired.md): where a game forms, the run forks and
  // plays it from that same state (SUMO's and the controller's, random
  // number generators included) under each game policy of the run for the
  // game's window; the run goes on under its own policy. paired.csv and
  // summary.json's paired section. `taebp run --paired` sets it.
  bool paired = false;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("kind", &kind);
    a->Visit("avs", &avs);
    a->Visit("hvs", &hvs);
    a->Visit("cruise_speed", &cruise_speed);
    a->Visit("min_gap", &min_gap);
    a->Visit("stop_distance", &stop_distance);
    a->Visit("step_length", &step_length);
    a->Visit("duration", &duration);
    a->Visit("seed", &seed);
    a->Visit("vehicle_length", &vehicle_length);
    a->Visit("vehicle_width", &vehicle_width);
    a->Visit("accel", &accel);
    a->Visit("decel", &decel);
    a->Visit("meeting_distance", &meeting_distance);
    a->Visit("confirm_delay", &confirm_delay);
    a->Visit("creep_speed", &creep_speed);
    a->Visit("loop_length", &loop_length);
    a->Visit("auto_length", &auto_length);
    a->Visit("network", &network);
    a->Visit("sumocfg", &sumocfg);
    a->Visit("routes", &routes);
    a->Visit("routes_scale", &routes_scale);
    a->Visit("additional", &additional);
    a->Visit("grid", &grid);
    a->Visit("demand", &demand);
    a->Visit("junctions", &junctions);
    a->Visit("av_share", &av_share);
    a->Visit("av_types", &av_types);
    a->Visit("warmup", &warmup);
    a->Visit("critical_gap", &critical_gap);
    a->Visit("tripinfo_output", &tripinfo_output);
    a->Visit("summary_output", &summary_output);
    a->Visit("outputs", &outputs);
    a->Visit("nudge_check", &nudge_check);
    a->Visit("stall_action", &stall_action);
    a->Visit("encounter_pairs", &encounter_pairs);
    a->Visit("major_road", &major_road);
    a->Visit("paired", &paired);
  }
  bool IsNetwork() const { return kind == ScenarioKind::kNetwork; }
  // The major-road game is played (a network, scenario.major_road.enabled).
  bool MajorRoadGame() const { return IsNetwork() && major_road.enabled; }
};

}  // namespace taebp
