// One policy's run in SUMO (libsumo, or sumo-gui through libtraci): starts
// SUMO on the scenario, steps it with the network controller, and returns
// the run's results.
#pragma once

#include "taebp/config/config.h"
#include "taebp/encounter/design.h"
#include "taebp/encounter/encounter.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/report/results.h"
#include "taebp/scenario/scenario.h"

#include <functional>
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
  // A safety net: a stall is recorded (scenario.stall_action: error: the run
  // stops with a StallError naming the junction) when vehicles are halted on
  // one of a controlled junction's incoming lanes and no vehicle has passed
  // it for this many simulated seconds (< 0: on the figure-8 two loops at
  // cruise speed + confirm_delay + 60 s; on a network 120 s).
  double stall_limit = -1.0;
  // Called once every simulated minute with the policy and the simulated time
  // (e.g. `taebp run --rss-log` for tools/soak); nothing when empty.
  std::function<void(const std::string& policy, double simulated_seconds)> every_minute;
  // Called every 10 simulated seconds (and after the last step) with where
  // the policy's run stands (e.g. the progress line of `taebp run`).
  struct Progress {
    std::string policy;
    double simulated = 0, duration = 0;  // s
    long vehicles = 0, encounters = 0;
  };
  std::function<void(const Progress&)> progress;
};

// Runs one policy (a persuasion policy name or "sumo_native") for
// scenario.duration simulated seconds. Throws SumoError (SUMO failed),
// ConfigError (the scenario does not fit) or NudgeError. A stall under
// scenario.stall_action: error ends the run early and returns it measured up
// to the stall, with PolicyRun::stall_error set (the message) and the stall
// in PolicyRun::stalls.
PolicyRun RunPolicy(const ExperimentConfig& config, const std::string& policy,
                    const Scenario& scenario, const RunOptions& options = {});

// The speed floor for tools/bench on a network (kind: network): the same net,
// demand and step with SUMO's own junction logic and nothing but
// Simulation::step in the loop (the figure-8 needs the controller to keep its
// vehicles circulating: compare it against sumo_native). ConfigError otherwise.
// Returns the simulated seconds.
double RunBareSumo(const ExperimentConfig& config, const Scenario& scenario);

}  // namespace taebp
