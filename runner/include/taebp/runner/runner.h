// The runner: one experiment config -> every listed policy simulated in SUMO
// -> the result files. `taebp run`, the sweep's tasks and the Python module
// all call this, so they produce the same files for the same inputs.
#pragma once

#include "taebp/config/config.h"
#include "taebp/controller/experiment.h"
#include "taebp/report/report.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace taebp {

struct ExperimentResult {
  ExperimentConfig config;
  std::vector<PolicyRun> runs;         // in the config's policy order
  Provenance provenance;
  std::vector<std::string> warnings;   // also printed by the CLI on stderr
  double wall_seconds = 0;             // total, for timing.json only
  // The result files (name -> content), as WriteExperiment writes them.
  std::vector<std::pair<std::string, std::string>> Files() const;
};

// Optional callbacks while an experiment runs.
struct ExperimentObserver {
  // Each warning, before the first policy runs.
  std::function<void(const std::string&)> warning;
  // After each policy, with its run and its wall time in seconds.
  std::function<void(const PolicyRun&, double wall_seconds)> policy_done;
};

// Loads the config (with --set style overrides), resolves its network and
// runs every listed policy. Throws ConfigError (bad config, scenario does not
// fit), persuasion::InvalidArgument, SumoError (SUMO failed).
ExperimentResult RunExperiment(const std::string& config_path,
                               const std::vector<std::string>& overrides,
                               const RunOptions& options = {},
                               const ExperimentObserver& observer = {});

// Writes the result files into `out_dir` atomically (all or nothing).
void WriteExperiment(const ExperimentResult& result, const std::string& out_dir);

// The default output directory of a config: results/<config file stem>.
std::string DefaultOutDir(const std::string& config_path);

}  // namespace taebp
