// Experiment configuration: plain structs with defaults at the field, one schema
// (Serialize) used for loading, saving and provenance, and IsValid() checks.
// All YAML parsing lives in config_yaml.cc (the one loader); this header has no
// yaml-cpp include.
#pragma once

#include "taebp/config/enums.h"
#include "taebp/config/policies.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace taebp {

// A configuration error. The message names the file (or --set), the key and
// the offending value.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

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

// scenario.major_road (network scenarios; unset: off): the major-road
// encounter of docs/beyond/major-road.md at two-way stops (priority_stop). An
// AV waiting at a minor road's stop line and an HV approaching on a
// conflicting major movement (right of way, not stopping) play the paper's
// game at the effective penalty r_eff = 2 (r - c) / (2 + c), when
// ClassifyMajorRoadApproach (persuasion/major_road.h) says the approach is a
// game: both proceeding collides on the junction's geometry and the HV can
// still yield braking at `comfortable_decel` after `reaction_time`. The AV
// nudges, the HV reads SUMO's displacement and yields (DC: brakes so the AV
// goes first) or keeps its speed (DR). Pairs where both wait at stop lines
// stay as they are. Written `scenario.major_road: {}` for the defaults. In the
// paper's setting only (not with trust dynamics, noise, learning,
// population_mean or ta_ebp_learned).
struct MajorRoadConfig {
  double yield_cost = 0.0;         // c in [0, model.collision_penalty): the cost of yielding
  double comfortable_decel = 3.0;  // m/s^2 a > 0, at most the HV's SUMO decel: how a DC HV brakes
  double reaction_time = 0.0;      // s t_r >= 0: from the HV's decision until it brakes

  template <typename Archive>
  void Serialize(Archive* a) {
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
  // the minor stop line, an HV approaching on the major road); unset: off,
  // only pairs that both stop at lines meet (see MajorRoadConfig).
  std::optional<MajorRoadConfig> major_road;
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
};

struct LikelihoodConfig {
  LikelihoodType type = LikelihoodType::kLinear;
  double s_max = 2.0;           // m
  double steepness = 4.0;       // logistic only
  double midpoint = 1.0;        // logistic only

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("type", &type);
    a->Visit("s_max", &s_max);
    a->Visit("steepness", &steepness);
    a->Visit("midpoint", &midpoint);
  }
};

// The HVs' trust: one number for every HV, or a distribution from which each
// HV draws its own theta at the start of a run (with the run's seed).
// YAML: `trust: 0.6`, `trust: {dist: uniform, low: 0.2, high: 0.9}`,
// `trust: {dist: beta, alpha: 2, beta: 5}`,
// `trust: {dist: discrete, values: [0.2, 0.8], weights: [1, 3]}`.
struct TrustSpec {
  TrustDist dist = TrustDist::kFixed;
  double value = 0.6;          // fixed
  double low = 0.0, high = 1.0;         // uniform
  double alpha = 1.0, beta = 1.0;       // beta
  std::vector<double> values, weights;  // discrete (weights default to equal)

  static TrustSpec Fixed(double v) {
    TrustSpec t;
    t.value = v;
    return t;
  }
  bool IsFixed() const { return dist == TrustDist::kFixed; }
  double Mean() const;
  // dist discrete: the weight of values[i] (1 when no weights are given) and
  // the sum of all weights.
  double Weight(std::size_t i) const { return weights.empty() ? 1.0 : weights[i]; }
  double TotalWeight() const;
  // theta with cumulative probability q in (0, 1) (the quantile function).
  double Quantile(double q) const;
  // One draw from a uniform u in [0, 1) (inverse-CDF sampling).
  double Draw(double u) const { return Quantile(u); }
  // Checks ranges; `key` names the config key in the message.
  bool IsValid(const std::string& key, std::string* why) const;
  std::string ToString() const;  // compact, for tables and file names
};
// The keys of a `model.trust` distribution map besides `dist` (the loader
// accepts these and no others; the generated reference lists them).
std::vector<std::string> TrustDistKeys(TrustDist dist);

// model.trust_dynamics: each HV's trust is a Beta(alpha, beta) state whose
// mean it uses, updated after every AV-HV encounter it is in (Guo & Yang;
// persuasion/trust_dynamics.h). alpha0 + beta0 = strength with the mean the
// HV's drawn model.trust. q per outcome (what the HV saw: did the AV nudge,
// did it then go, did they collide) is the quality mapping; SUMO's collision
// flag decides `collision`. No near misses are defined (the HV cannot tell a
// close call in SUMO from a clean encounter).
struct TrustQualityConfig {
  double nudge_go = 1.0;    // nudged, then went: the nudge meant Go
  double nudge_stop = 0.0;  // nudged, then yielded: a false alarm
  double still_stop = 1.0;  // stood still, then yielded
  double still_go = 0.0;    // stood still, then went: an unannounced Go
  double collision = 0.0;   // SUMO reported a collision between the two

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("nudge_go", &nudge_go);
    a->Visit("nudge_stop", &nudge_stop);
    a->Visit("still_stop", &still_stop);
    a->Visit("still_go", &still_go);
    a->Visit("collision", &collision);
  }
};
struct TrustDynamicsConfig {
  double strength = 10.0;       // alpha0 + beta0: encounters' worth of initial evidence
  double success_weight = 1.0;  // w_s: alpha += w_s q
  double failure_weight = 1.0;  // w_f: beta += w_f (1 - q)
  double forgetting = 0.0;      // rho in [0, 1]: decay toward (alpha0, beta0) per encounter
  TrustQualityConfig quality;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("strength", &strength);
    a->Visit("success_weight", &success_weight);
    a->Visit("failure_weight", &failure_weight);
    a->Visit("forgetting", &forgetting);
    a->Visit("quality", &quality);
  }
};

// model.noise: the HV reads SUMO's displacement plus noise and a bias
// (persuasion/noise.h). The nudge SUMO realises is unchanged (and still
// checked against its tolerance). design: aware = the AV's TA-EBP designs
// (ta_ebp, population_mean, ta_ebp_learned) nudge s* - bias - F^-1(delta) so
// that the noisy reading still persuades with probability >= 1 - delta;
// paper = they keep the paper's s* (to measure what noise does to it).
struct NoiseConfig {
  NoiseKind kind = NoiseKind::kGaussian;
  double scale = 0.05;            // m: Gaussian sigma, or the uniform half-width
  double bias = 0.0;              // m, added to every reading
  double delta = 0.01;            // the noise-aware design's failure budget, in (0, 1)
  NoiseDesign design = NoiseDesign::kAware;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("kind", &kind);
    a->Visit("scale", &scale);
    a->Visit("bias", &bias);
    a->Visit("delta", &delta);
    a->Visit("design", &design);
  }
};

// model.learning: the policy ta_ebp_learned (persuasion/trust_learning.h).
// The AVs share a posterior over each HV's trust (by HV id), start from
// `prior` (default: model.trust, the population's distribution) and design
// TA-EBP for the lower credible bound at risk level
// eps_m = min(delta, decay / (m + 1)) after m observed responses of that HV
// (constant_level: eps = delta for ever).
struct LearningConfig {
  double delta = 0.01;  // in (0, 1): P(a nudge fails to persuade) per encounter
  double decay = 1.0;   // c > 0 (regret O(log T) needs c > 1/2)
  bool constant_level = false;  // eps = delta for ever (regret linear in T)
  bool probe = true;    // test the strongest nudge with probability eps / P(theta < theta*)
  std::optional<TrustSpec> prior;  // the population prior; unset: model.trust

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("delta", &delta);
    a->Visit("decay", &decay);
    a->Visit("constant_level", &constant_level);
    a->Visit("probe", &probe);
    a->Visit("prior", &prior);
  }
};

// model.experience (issue 29; docs/influence.md, persuasion/experience.h):
// each HV remembers, per signal level (the displacement SUMO reported, in bins
// of bin_width m), how often the AV then went, and reads a nudge with
// p_E = (k q + g) / (k + n) in place of the intuitive posterior q (trust weighs
// it as in eq:pp). Each HV learns from its own encounters only. design: what
// ta_ebp commits to: guarded = TA-EBP for each HV's experienced belief (b = 0
// when a false alarm would leave s* unpersuasive; DesignForExperience), paper
// = the paper's scheme whatever the HV learned (to measure the knife edge),
// robust = s_max with the largest b that keeps a margin above p* without
// knowing the learner's rule (DesignRobust; issue 42). forgetting: the
// learner's weight on its past per encounter (1 = exact counts).
// Unset: the paper's HV, who never learns.
struct ExperienceConfig {
  double strength = 20.0;   // k > 0: readings' worth of trust in the intuitive model
  double bin_width = 0.1;   // m > 0: one signal level
  double forgetting = 1.0;  // rho in (0, 1]: the learner's weight on its past
  ExperienceDesign design = ExperienceDesign::kGuarded;
  double margin = 0.1;      // robust: the belief's margin above p*, in [0, 1)
  // HVs of different k: each HV draws one of these, equally likely, by a hash
  // of its id (the designs keep assuming `strength`); empty: every HV has
  // `strength`.
  std::vector<double> strengths;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("strength", &strength);
    a->Visit("strengths", &strengths);
    a->Visit("bin_width", &bin_width);
    a->Visit("forgetting", &forgetting);
    a->Visit("design", &design);
    a->Visit("margin", &margin);
  }
};

struct ModelConfig {
  double prior_go = 0.2;           // lambda
  double collision_penalty = 3.0;  // r
  TrustSpec trust = TrustSpec::Fixed(0.6);  // theta of the HVs
  // What the AV knows of each HV's trust when it designs its scheme (ta_ebp):
  // exact (that HV's own theta), population_mean (one design for the mean),
  // assumed (one design for assumed_trust). Unset: assumed if assumed_trust is
  // set, else exact.
  std::optional<TrustKnowledge> trust_knowledge;
  std::optional<double> assumed_trust;  // theta_hat for trust_knowledge = assumed
  LikelihoodConfig likelihood;
  // Beyond the paper (unset: the paper's static, exactly seen, known trust).
  std::optional<TrustDynamicsConfig> trust_dynamics;
  std::optional<NoiseConfig> noise;
  std::optional<LearningConfig> learning;
  std::optional<ExperienceConfig> experience;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("prior_go", &prior_go);
    a->Visit("collision_penalty", &collision_penalty);
    a->Visit("trust", &trust);
    a->Visit("trust_knowledge", &trust_knowledge);
    a->Visit("assumed_trust", &assumed_trust);
    a->Visit("likelihood", &likelihood);
    a->Visit("trust_dynamics", &trust_dynamics);
    a->Visit("noise", &noise);
    a->Visit("learning", &learning);
    a->Visit("experience", &experience);
  }
  // trust_knowledge with the default resolved.
  TrustKnowledge Knowledge() const {
    if (trust_knowledge) return *trust_knowledge;
    return assumed_trust ? TrustKnowledge::kAssumed : TrustKnowledge::kExact;
  }
};

// A sweep: a grid over config keys (each point is one `run` of every listed
// policy) times seed replicates. YAML:
//   sweep:
//     replicates: 5            # seeds scenario.seed, +1, ..., +4
//     grid:                    # axes in order; the last varies fastest
//       model.trust: [0.1, 0.2, 0.5]
//       scenario.avs: [0, 8, 16]
// Values are YAML (numbers, lists, maps such as trust distributions).
struct SweepConfig {
  int replicates = 1;
  // (key, values as YAML flow text), in file order.
  std::vector<std::pair<std::string, std::vector<std::string>>> grid;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("replicates", &replicates);
    a->Visit("grid", &grid);
  }
};

// Bounds that keep a run's allocations and SUMO's physics sane.
inline constexpr double kMaxCruiseSpeed = 70.0;  // m/s (252 km/h)
inline constexpr double kMaxDuration = 1e7;      // s (~116 simulated days)
// scenario.avs and scenario.hvs each: SUMO inserts them all in its first
// step, which a signal cannot interrupt (a million took over 10 minutes).
inline constexpr int kMaxVehicles = 10000;
inline constexpr double kMaxSteps = 1e9;
// A config's YAML values with its aliases expanded (a sweep grid of a
// thousand points of a few values each is some ten thousand).
inline constexpr std::size_t kMaxConfigNodes = 1000000;
// scenario.seed (and a sweep's last replicate, seed + replicates - 1): SUMO
// takes its --seed modulo 2^31 - 1, so seeds 1 and 2147483648 would run alike.
inline constexpr std::uint64_t kMaxSeed = 2147483646;


// outputs: the time series written by runs beyond the paper (timeseries.csv,
// hv_trust.csv), sampled every `interval` simulated seconds (>= 1: the
// controller samples once a simulated second).
struct OutputConfig {
  double interval = 60.0;  // s
  bool per_hv = true;      // hv_trust.csv: a row per HV in the network per sample

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("interval", &interval);
    a->Visit("per_hv", &per_hv);
  }
};

struct ExperimentConfig {
  ScenarioConfig scenario;
  ModelConfig model;
  std::vector<std::string> policies = DefaultPolicies();  // config/policies.h
  std::optional<SweepConfig> sweep;  // only `taebp sweep` uses it
  OutputConfig outputs;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("scenario", &scenario);
    a->Visit("model", &model);
    a->Visit("policies", &policies);
    a->Visit("sweep", &sweep);
    a->Visit("outputs", &outputs);
  }

  // Range checks; on failure returns false and a message naming the key and value.
  bool IsValid(std::string* why) const;
  // True when the run goes beyond the paper's setting: dynamic trust, noise,
  // learning, or a policy only defined here (population_mean,
  // ta_ebp_learned). Such runs write the extra encounter columns, summary
  // sections and time series; the paper's runs write exactly what they did.
  bool BeyondPaper() const;
};

// The text of a config file. Throws ConfigError naming the path when it is
// not a regular file (NotAFile), or unreadable.
std::string ReadConfigFile(const std::string& path);

// Why `path` cannot be read as a file, or "" when it is a regular file (a
// symbolic link to one counts): "no such file", "a folder, not a file", "a
// FIFO (named pipe), not a file" (reading one would wait for a writer
// forever), "a socket, not a file", "a device, not a file", "a dangling
// symbolic link", or the system's reason it cannot be looked at.
std::string NotAFile(const std::string& path);

// Loads a YAML experiment file, applies `overrides` ("key.path=VALUE", VALUE
// parsed as YAML) and validates. Unknown keys, wrong types and out-of-range
// values throw ConfigError naming the file (or the --set), the key and value.
ExperimentConfig LoadExperimentConfig(const std::string& path,
                                      const std::vector<std::string>& overrides = {});
// Same, from YAML text (`origin` names it in messages).
ExperimentConfig ParseExperimentConfig(const std::string& yaml_text, const std::string& origin,
                                       const std::vector<std::string>& overrides = {});
// A config text parsed once, to be loaded many times with different
// overrides (a sweep's grid points): Load(o) equals
// ParseExperimentConfig(yaml_text, origin, base + {"sweep=~"} + o), without
// re-parsing the text or copying the sweep's grid (linear in the points).
class ExperimentTemplate {
 public:
  // `base`: overrides applied once, before each Load's own; the config's
  // sweep: section is dropped (each Load is a point's config without it).
  ExperimentTemplate(const std::string& yaml_text, const std::string& origin,
                     const std::vector<std::string>& base = {});
  ~ExperimentTemplate();
  ExperimentConfig Load(const std::vector<std::string>& overrides) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

// The resolved config as YAML text and as a JSON string (same schema).
std::string ToYaml(const ExperimentConfig& config);
std::string ToJson(const ExperimentConfig& config);

// `taebp solve` problem files: a finite persuasion game and a trust level.
struct ProblemConfig {
  std::vector<std::string> states;
  std::vector<std::string> actions;
  std::vector<double> prior;
  std::vector<std::vector<double>> receiver_utility;  // rows = states
  std::vector<std::vector<double>> sender_utility;    // rows = states
  double trust = 1.0;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("states", &states);
    a->Visit("actions", &actions);
    a->Visit("prior", &prior);
    a->Visit("receiver_utility", &receiver_utility);
    a->Visit("sender_utility", &sender_utility);
    a->Visit("trust", &trust);
  }
};
// Throws ConfigError (file, key, line) on unknown keys, missing keys, bad types.
ProblemConfig LoadProblemConfig(const std::string& path);
// Same, from YAML (or JSON) text; `origin` names it in messages.
ProblemConfig ParseProblemConfig(const std::string& yaml_text, const std::string& origin);

// A YAML value (e.g. a --set or sweep grid value) as JSON text with its YAML
// type: 0.5 -> 0.5, true -> true, ta_ebp -> "ta_ebp", '1' -> "1",
// [8, 8] -> [8,8], {dist: beta, alpha: 2} -> {"dist":"beta","alpha":2}.
// Throws ConfigError for malformed YAML.
std::string YamlValueAsJson(const std::string& yaml_text);

}  // namespace taebp
