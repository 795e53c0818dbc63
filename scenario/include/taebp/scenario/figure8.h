// The figure-8 scenario's network: the built-in track, tracks generated for
// other loop lengths, or a user's network file, and the geometry warnings.
#pragma once

#include "taebp/config/config.h"

#include <string>
#include <vector>

namespace taebp {

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

// Non-fatal remarks about a config (e.g. a nudge that can reach into the
// crossing path), for stderr and summary.json.
std::vector<std::string> ScenarioWarnings(const ExperimentConfig& config);

}  // namespace taebp
