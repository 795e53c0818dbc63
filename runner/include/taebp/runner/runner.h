// The runner: one experiment config -> every listed policy simulated in SUMO
// -> the result files. `taebp run`, the sweep's tasks and the Python module
// all call this, so they produce the same files for the same inputs.
#pragma once

#include "taebp/config/config.h"
#include "taebp/controller/policy_run.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/report/report.h"

#include <functional>
#include <memory>
#include <stdexcept>
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
  // A policy stalled under scenario.stall_action: error: the experiment
  // stopped after it (runs holds the policies up to and including it; the
  // files say so). Empty reason: every policy ran. Callers write the files,
  // then report the stall (taebp run: exit code 4).
  Stopped stopped;
  // The result files (name -> content), as WriteExperiment writes them.
  std::vector<std::pair<std::string, std::string>> Files() const;
  // The files copied into the run folder beside them (name -> the file):
  // the time series (sample_files), SUMO's outputs per policy (POLICY/NAME)
  // and, where taebp generated or patched the network SUMO ran, that network
  // (network.net.xml).
  std::vector<std::pair<std::string, std::string>> CopiedFiles() const;
  // Runs beyond the paper: timeseries.csv and hv_trust.csv, assembled in the
  // scratch folder from the runs' spools (never all in memory).
  std::vector<std::pair<std::string, std::string>> sample_files;
  // Keeps the scenario's scratch folder (SUMO's outputs) until written.
  std::shared_ptr<void> scratch;
  std::string network_ran;  // the generated or patched network; empty: the user's
  // The Table I printout of `taebp run` (PrintTable with the warnings).
  std::string Table() const;
};

// libsumo runs one simulation per process. RunExperiment holds this process's
// simulation slot while it runs; a second concurrent call (another thread)
// throws SimulationBusy instead of corrupting the first. A forked child starts
// with a free slot (parallel runs: `taebp sweep --jobs N`, multiprocessing).
class SimulationBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
class SimulationSlot {
 public:
  // Takes the slot; throws SimulationBusy naming `what` when it is taken.
  explicit SimulationSlot(const std::string& what);
  ~SimulationSlot();
  SimulationSlot(const SimulationSlot&) = delete;
  SimulationSlot& operator=(const SimulationSlot&) = delete;
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
// fit), persuasion::InvalidArgument, SumoError (SUMO failed), SimulationBusy
// (another simulation is running in this process). A stall under
// scenario.stall_action: error is no exception here: the experiment stops
// after that policy and returns what ran, with `stopped` set.
ExperimentResult RunExperiment(const std::string& config_path,
                               const std::vector<std::string>& overrides,
                               const RunOptions& options = {},
                               const ExperimentObserver& observer = {});

// Replaces the run files of `folder` with the result's, as one set
// (RunFolder::Replace: a reader sees the old set or the new one); throws
// Interrupted, before writing anything, when a signal came during the run.
// Returns the line saying what it replaced ("" for a folder without results).
std::string WriteExperiment(const ExperimentResult& result, RunFolder& folder);
// The same into `out_dir`, locked and checked only now (a sweep's task).
std::string WriteExperiment(const ExperimentResult& result, const std::string& out_dir);

// The default output directory of a config: results/STEM, STEM the config file name without its extension.
std::string DefaultOutDir(const std::string& config_path);

}  // namespace taebp
