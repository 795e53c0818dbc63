// One policy's simulated run of the figure-8 scenario in SUMO (libsumo), and
// the whole experiment (every listed policy) with its outputs.
#pragma once

#include "taebp/controller/config.h"
#include "taebp/controller/intersection.h"
#include "taebp/persuasion/outcomes.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace taebp {

// A nudge is realised when SUMO's reported displacement d satisfies
// s <= d <= s + kNudgeTolerance (the controller aims at s + kNudgeOvershoot).
inline constexpr double kNudgeTolerance = 1e-3;  // m
inline constexpr double kNudgeOvershoot = 1e-6;  // m

struct EncounterRecord {
  double time = 0;          // simulated time the encounter formed (s)
  std::string av, hv;
  bool intent_go = false;
  double commanded = 0;     // commanded nudge s (0: no nudge)
  double observed = 0;      // displacement SUMO reported when the HV decided
  double hv_trust = 0;      // the HV's true theta
  double posterior = 0;     // HV's p_theta(Go | observed)
  bool hv_dc = false;       // HV action: drive if clear (else drive recklessly)
  bool av_first = false;    // AV action: go first (else wait)
  bool collision = false;   // SUMO reported a collision between the two
  double decided_at = 0;    // when the HV decided (after the nudge)
  double theory_dc = 0;         // library prediction for this AV-HV pair's design and HV
  double theory_collision = 0;
};

struct PolicyRun {
  std::string policy;
  persuasion::CommittedScheme scheme;     // the design for the population's theta_hat
  // Library prediction: expectation over the trust distribution of the per-HV
  // predictions (for a fixed trust, the prediction itself).
  persuasion::PredictedOutcome theory;
  std::vector<double> hv_trust;           // each HV's drawn theta, in HV order
  std::vector<EncounterRecord> encounters;
  double simulated_seconds = 0;
  long crossings_av = 0, crossings_hv = 0;
  double wait_sum = 0, wait_max = 0;      // stop-line waits (s) over crossings
  long other_collisions = 0;              // collisions outside AV-HV encounters
  long teleports = 0;
  double longest_gap_without_crossing = 0;  // s, a deadlock indicator
  std::string sumo_version;
};

// Paths of the scenario's SUMO files.
struct ScenarioFiles {
  std::string net;           // .net.xml
  double loop_length = 0;    // m per loop of the figure-8 actually used (0: custom network)
  std::vector<std::string> notes;  // e.g. "loops grown to 95 m to fit 24 vehicles"
};

// Loop length (m) that fits `vehicles` of the scenario's length and gap.
double RequiredLoopLength(const ScenarioConfig& scenario);

// The built-in figure-8 network built with the project (build/sumo_net).
std::string DefaultNetworkPath();

// The figure-8 with `loop_length` m loops (make_figure8.py + netconvert),
// generated once into build/sumo_net/cache; returns its .net.xml. Throws
// ConfigError naming scenario.loop_length when generating fails.
std::string GeneratedFigure8(double loop_length);

// Resolves scenario.network (relative to `config_dir` when relative) or the
// figure-8: the built-in one for the default loop length, else one generated
// (make_figure8.py + netconvert, cached in build/sumo_net/cache) for
// scenario.loop_length, grown to RequiredLoopLength when scenario.auto_length.
// Throws ConfigError naming the key and value when a file is missing or the
// vehicles cannot fit.
ScenarioFiles ResolveScenarioFiles(const ExperimentConfig& config, const std::string& config_dir);

// Extras for watching a run (sumo-gui); the defaults add no SUMO calls.
struct RunOptions {
  // Colour vehicles by state: nudging AV yellow, HV that chose DR orange / DC
  // green, both vehicles of a collided encounter magenta; back to the type
  // colour (AV blue, HV red) once they have cleared the junction.
  bool colour_states = false;
  std::function<void()> after_start;   // SUMO started, vehicles added (e.g. frame the view)
  std::function<void()> before_close;  // after the last step, SUMO still open (e.g. screenshot)
  // A safety net: the run stops with a ConfigError when no vehicle has crossed
  // the centre for this many simulated seconds (< 0: one lap at cruise speed
  // + confirm_delay + arrival_window + 60 s). The keep-clear release rule
  // prevents gridlock on the figure-8; this catches what it cannot foresee
  // (e.g. a custom scenario.network).
  double stall_limit = -1.0;
};

// Runs one policy for scenario.duration simulated seconds. Throws SumoError
// (SUMO failed) or ConfigError (scenario does not fit the network).
PolicyRun RunPolicy(const ExperimentConfig& config, persuasion::Policy policy,
                    const ScenarioFiles& files, const RunOptions& options = {});

// The speed floor: the same network, vehicles, types and step, with SUMO's own
// junction logic and no controller (only Simulation::step in the loop). For
// tools/bench. Returns the simulated seconds.
double RunBareSumo(const ExperimentConfig& config, const ScenarioFiles& files);

// The AV's design trust theta_hat for an HV of true trust `theta` under
// `policy` and the config's trust_knowledge (no_trust: 1).
double DesignTrust(const ModelConfig& model, persuasion::Policy policy, double theta);

// Expected outcome over the trust distribution (quantile midpoint rule with
// `points` nodes; exact for fixed and discrete trust).
persuasion::PredictedOutcome ExpectedOutcome(const ModelConfig& model, persuasion::Policy policy,
                                             int points = 4000);

// Non-fatal remarks about a config (e.g. a nudge that can reach into the
// crossing path), for stderr and summary.json.
std::vector<std::string> ScenarioWarnings(const ExperimentConfig& config);

// The HV likelihood model named by the config; throws persuasion::InvalidArgument
// naming the type when it is not linear or logistic.
std::unique_ptr<persuasion::LikelihoodModel> MakeLikelihood(const LikelihoodConfig& config);

}  // namespace taebp
