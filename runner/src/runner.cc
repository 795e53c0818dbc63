#include "taebp/runner/runner.h"

#include "taebp/controller/sumo_adapter.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/report/paired.h"

#include "taebp/persuasion/outcomes.h"
#include "taebp/scenario/scenario.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <unistd.h>

namespace taebp {

namespace fs = std::filesystem;

std::vector<std::pair<std::string, std::string>> ExperimentResult::Files() const {
  nlohmann::ordered_json timing;
  timing["wall_seconds_total"] = wall_seconds;
  for (const PolicyRun& r : runs) {  // where each policy's time went
    nlohmann::ordered_json& p = timing["policies"][r.policy];
    p["wall_seconds_start"] = r.wall_seconds_start;
    p["wall_seconds_sumo_steps"] = r.wall_seconds_sumo_steps;
    p["wall_seconds_controller_steps"] = r.wall_seconds_controller_steps;
  }
  std::vector<std::pair<std::string, std::string>> files = {
      {"summary.json", SummaryJson(runs, provenance, stopped)},
      {"encounters.csv", EncountersCsv(runs)},
      {"junctions.csv", JunctionsCsv(runs)},
      {"collisions.csv", CollisionsCsv(runs)},
      {"config.yaml", ToYaml(config)},
      {"timing.json", timing.dump(2) + "\n"}};
  for (const PolicyRun& r : runs) {
    if (!r.sumo_tripinfo_xml.empty())
      files.emplace_back("tripinfo-" + r.policy + ".xml", r.sumo_tripinfo_xml);
    if (!r.sumo_summary_xml.empty())
      files.emplace_back("summary-" + r.policy + ".xml", r.sumo_summary_xml);
  }
  if (config.scenario.paired)  // each game under every game policy (docs/paired.md)
    files.emplace_back("paired.csv", PairedCsv(runs));
  return files;
}

std::vector<std::pair<std::string, std::string>> ExperimentResult::CopiedFiles() const {
  std::vector<std::pair<std::string, std::string>> files = sample_files;
  for (const PolicyRun& r : runs)
    files.insert(files.end(), r.sumo_output_files.begin(), r.sumo_output_files.end());
  if (!network_ran.empty()) files.emplace_back("network.net.xml", network_ran);
  return files;
}

std::string ExperimentResult::Table() const {
  std::ostringstream out;
  PrintTable(out, runs, warnings);
  return out.str();
}

namespace {
// The process holding the simulation slot (0: free). A pid rather than a flag:
// a child forked while its parent held the slot (a sweep's worker) starts free.
std::atomic<pid_t> g_slot_owner{0};
}  // namespace

SimulationSlot::SimulationSlot(const std::string& what) {
  const pid_t self = ::getpid();
  pid_t current = g_slot_owner.load();
  for (;;) {
    if (current == self)
      throw SimulationBusy(
          what + ": another simulation is already running in this process (libsumo runs one "
                 "simulation per process); run experiments in parallel in separate processes: "
                 "taebp sweep --jobs N, or from Python taebp.sweep(..., jobs=N) or multiprocessing");
    if (g_slot_owner.compare_exchange_weak(current, self)) return;
  }
}

SimulationSlot::~SimulationSlot() { g_slot_owner.store(0); }

namespace {

// A warning: into the result, and to the observer.
void Warn(const std::string& w, ExperimentResult* result, const ExperimentObserver& observer) {
  result->warnings.push_back(w);
  if (observer.warning) observer.warning(w);
}

// What policy `name`'s run (the last in `result`) says to look at: a run
// that measured nothing, SUMO's warnings, the junctions that stalled.
void WarnOfRun(const std::string& name, ExperimentResult* result,
               const ExperimentObserver& observer) {
  {
    // A run that measured nothing says so (it used to pass unremarked).
    const PolicyRun& run = result->runs.back();
    std::string w;
    if (run.scenario_kind == "network" && run.network.departed == 0)
      w = name + ": no vehicle departed after the warm-up: the demand is empty (check "
                 "scenario.routes or scenario.demand, scenario.routes_scale, the departure "
                 "times against scenario.warmup and scenario.duration)";
    else if (PlaysGame(name) && run.held == 0)
      w = name + ": the controller held no vehicle: no AV and HV met at a controlled "
                 "junction, so this run is SUMO's own traffic (too few AVs or HVs, or too "
                 "little traffic at the junctions)";
    if (!w.empty()) Warn(w, result, observer);
    // SUMO's own warnings (its collision reports left out: counted by taebp).
    const long others = run.sumo_warnings - run.sumo_collision_warnings;
    if (others > 0) {
      // One line (the table lists warnings a line each); the first few are
      // in summary.json.
      std::string s = name + ": SUMO warned " + std::to_string(others) +
                      (others == 1 ? " time" : " times") + ", first: " +
                      (run.sumo_warnings_first.empty() ? std::string("?")
                                                       : run.sumo_warnings_first.front()) +
                      " (summary.json: sumo_warnings)";
      Warn(s, result, observer);
    }
  }
  for (const StallRecord& st : result->runs.back().stalls) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s: traffic stalled at junction '%s' from t = %.1f s",
                  name.c_str(), st.junction.c_str(), st.since);
    Warn(buf, result, observer);
  }
}

// Runs the config's policies in turn; scenario.stall_action: error: stops
// at a stalled run, keeping what ran.
void RunPolicies(const ExperimentConfig& config, const Scenario& scenario,
                 const RunOptions& options, const ExperimentObserver& observer,
                 ExperimentResult* result) {
  for (const std::string& name : config.policies) {
    const auto t0 = std::chrono::steady_clock::now();
    result->runs.push_back(RunPolicy(config, name, scenario, options));
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    result->wall_seconds += wall;
    if (observer.policy_done) observer.policy_done(result->runs.back(), wall);
    WarnOfRun(name, result, observer);
    // scenario.stall_action: error: stop here, keep what ran.
    if (!result->runs.back().stall_error.empty()) {
      result->stopped.reason = "stall";
      result->stopped.policy = name;
      result->stopped.message = name + ": " + result->runs.back().stall_error;
      for (std::size_t k = result->runs.size(); k < config.policies.size(); ++k)
        result->stopped.not_run.push_back(config.policies[k]);
      break;
    }
  }
}

// Junctions where no game can ever form under these settings (junctions.csv
// game_pairs 0; the same under every policy): said, with the usual cause.
void WarnOfGamelessJunctions(const ExperimentConfig& config, ExperimentResult* result,
                             const ExperimentObserver& observer) {
  if (!(!result->runs.empty() && result->runs.front().scenario_kind == "network" &&
        std::any_of(config.policies.begin(), config.policies.end(),
                    [](const std::string& p) { return PlaysGame(p); })))
    return;
  const std::vector<JunctionRun>& js = result->runs.front().junctions;
  std::vector<std::string> none;
  bool two_way = false;
  for (const JunctionRun& j : js)
    if (j.game_pairs == 0) {
      none.push_back(j.id);
      two_way = two_way || j.rule == "two_way_stop";
    }
  if (none.empty()) return;
  std::string list;
  for (std::size_t k = 0; k < none.size() && k < 8; ++k)
    list += (k ? ", " : "") + none[k];
  if (none.size() > 8) list += ", ...";
  std::string w = std::to_string(none.size()) + " of " + std::to_string(js.size()) +
                  " controlled junctions can host no game under these settings (" + list +
                  "; junctions.csv game_pairs 0): no two conflicting movements there both "
                  "have a stop line";
  if (two_way && !config.scenario.major_road.enabled)
    w += "; at a two-way stop with one stop-controlled approach, scenario.major_road.enabled: "
         "true lets an AV at its line play against a major-road HV";
  Warn(w, result, observer);
}

// Where the run came from (summary.json's provenance), from its config as
// the result keeps it (inputs by absolute paths).
void FillProvenance(const std::string& config_path, ExperimentResult* result) {
  const ExperimentConfig& config = result->config;
  Provenance& prov = result->provenance;
  prov.config_path = config_path;
  prov.config_json = ToJson(config);
  prov.seed = config.scenario.seed;
  prov.git_revision = BuildGitRevision();
  prov.sumo_version = result->runs.empty() ? "" : result->runs.front().sumo_version;
  prov.taebp_version = TaebpVersion();
  prov.warnings = result->warnings;
  if (config.scenario.outputs.ssm && sumo::CurrentBackend() == sumo::Backend::kLibsumo)
    prov.sumo_patches.push_back("MSDevice_SSM.cpp:1870 and 1172 assertions as in SUMO's release builds: " +
                                sumo::SsmReleaseBehaviour());
}

}  // namespace

ExperimentResult RunExperiment(const std::string& config_path,
                               const std::vector<std::string>& overrides,
                               const RunOptions& options, const ExperimentObserver& observer) {
  ExperimentResult result;
  result.config = LoadExperimentConfig(config_path, overrides);
  const SimulationSlot slot("run " + config_path);
  const ExperimentConfig& config = result.config;
  const std::string config_dir = fs::path(config_path).parent_path().string();
  const Scenario scenario = BuildScenario(config, config_dir);
  result.scratch = scenario.scratch;
  if (scenario.kind == ScenarioKind::kNetwork && scenario.net != scenario.user_net)
    result.network_ran = scenario.net;
  result.warnings = ScenarioWarnings(config);
  result.warnings.insert(result.warnings.end(), scenario.notes.begin(), scenario.notes.end());
  if (observer.warning)
    for (const std::string& w : result.warnings) observer.warning(w);

  RunPolicies(config, scenario, options, observer, &result);
  WarnOfGamelessJunctions(config, &result, observer);
  // Runs beyond the paper: their time series, assembled on disk from the
  // runs' spools (report/sample_spool.h), copied into the run folder.
  if (BeyondPaper(result.runs)) {
    const fs::path dir = scenario.scratch->path();
    result.sample_files = {{"timeseries.csv", (dir / "timeseries.csv").string()},
                           {"hv_trust.csv", (dir / "hv_trust.csv").string()}};
    WriteTimeseriesCsv(result.runs, result.sample_files[0].second);
    WriteHvTrustCsv(result.runs, result.sample_files[1].second);
  }
  // Its inputs by absolute paths: config.yaml (and summary.json's
  // provenance.config) rerun and find the network from any directory.
  result.config = WithAbsoluteInputs(result.config, config_dir);
  FillProvenance(config_path, &result);
  return result;
}

std::string WriteExperiment(const ExperimentResult& result, RunFolder& folder) {
  ThrowIfInterrupted();
  std::string names;
  for (const PolicyRun& r : result.runs) names += (names.empty() ? "" : ", ") + r.policy;
  const std::string about = std::to_string(result.runs.size()) +
                            (result.runs.size() == 1 ? " policy (" : " policies (") + names + ")";
  return folder.Replace(result.Files(), result.CopiedFiles(), about);
}

std::string WriteExperiment(const ExperimentResult& result, const std::string& out_dir) {
  RunFolder folder(out_dir);
  return WriteExperiment(result, folder);
}

std::string DefaultOutDir(const std::string& config_path) {
  return (fs::path("results") / fs::path(config_path).stem()).string();
}

}  // namespace taebp
