// A run's scenario: which SUMO network it loads, which files bring its
// vehicles, which junctions the controller takes over, and (figure-8) which
// vehicles are placed at t = 0. Built once per experiment, shared by every
// policy, without SUMO running (networks are read with net::NetFile; grids,
// patched networks and demand are generated with SUMO's command-line tools).
#pragma once

#include "taebp/config/config.h"
#include "taebp/scenario/net_file.h"

#include <memory>
#include <string>
#include <vector>

namespace taebp {

// A junction the controller takes over, as SUMO runs it.
struct ControlledJunction {
  std::string id;
  std::string type;           // allway_stop or priority_stop in the network SUMO loads
  std::string original_type;  // its type in the user's network (before patching)
};

// A figure-8 vehicle inserted at t = 0.
struct PlacedVehicle {
  std::string id;
  bool is_av = false;
  std::vector<std::string> route;  // edges from its start edge
  double depart_pos = 0;           // m on the first edge
};

// A per-run directory for generated files, removed with the object.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

struct Scenario {
  ScenarioKind kind = ScenarioKind::kFigure8;
  std::string net;                      // the .net.xml SUMO loads
  // The user's own network file when `net` is it unchanged; empty when taebp
  // generated or patched the network SUMO loads (a run keeps that one in its
  // folder: network.net.xml).
  std::string user_net;
  std::shared_ptr<const net::NetFile> topology;  // `net`, read
  std::vector<std::string> route_files;       // -r
  std::vector<std::string> additional_files;  // -a
  std::vector<ControlledJunction> junctions;
  // figure-8
  std::vector<PlacedVehicle> placed;
  std::vector<std::string> lap;         // one lap's edges, in driving order
  double loop_length = 0;               // m (0: a user's network)
  // network: the generated demand (a routes file in `scratch`), for outputs
  long generated_trips = 0;
  std::vector<std::string> notes;       // remarks for stderr and summary.json
  // What in this scenario is known to make SUMO abort (it then takes the
  // process with it), for the message when it does; empty: nothing known.
  std::string abort_hint;
  std::shared_ptr<ScratchDir> scratch;  // generated files live here
};

// Builds the scenario of `config` (relative paths resolved against
// `config_dir`). Throws ConfigError naming the key, value and file for a
// missing or invalid network, an unknown junction id, a selection matching no
// junction, a junction type the rules do not cover, or vehicles that do not
// fit the figure-8.
Scenario BuildScenario(const ExperimentConfig& config, const std::string& config_dir);

// `config` with its input files (scenario.network, scenario.sumocfg,
// scenario.routes, scenario.additional) named by absolute paths: relative ones
// resolved against `config_dir` (and the working directory), $SUMO_HOME/...
// kept. A run folder's config.yaml is this, so it reruns from any directory.
ExperimentConfig WithAbsoluteInputs(ExperimentConfig config, const std::string& config_dir);

// Non-fatal remarks about a config (e.g. a nudge that can reach into the
// crossing path), for stderr and summary.json.
std::vector<std::string> ScenarioWarnings(const ExperimentConfig& config);

// ---------------------------------------------------------------- figure-8
// Loop length (m) that fits the figure-8's vehicles of the scenario's length and gap.
double RequiredLoopLength(const ScenarioConfig& scenario);
// The built-in figure-8 network built with the project (build/sumo_net).
std::string DefaultNetworkPath();
// The figure-8 with `loop_length` m loops and vehicles held `stop_distance` m
// before the centre (make_figure8.py + netconvert), generated once into
// build/sumo_net/cache; returns its .net.xml. Throws ConfigError naming the
// keys when generating fails.
std::string GeneratedFigure8(double loop_length, double stop_distance);

}  // namespace taebp
