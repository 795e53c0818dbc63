// One policy's simulated run of the figure-8 scenario in SUMO (libsumo), and
// the whole experiment (every listed policy) with its outputs.
#pragma once

#include "taebp/config/config.h"
#include "taebp/junction/design.h"
#include "taebp/scenario/figure8.h"
#include "taebp/junction/intersection.h"
#include "taebp/report/results.h"
#include "taebp/persuasion/outcomes.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace taebp {

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

}  // namespace taebp
