#include "taebp/controller/policy_run.h"

#include "taebp/controller/network_controller.h"
#include "taebp/controller/sumo_adapter.h"
#include "taebp/base/number_text.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/synced_file.h"
#include "taebp/base/exit_codes.h"
#include "taebp/report/ssm.h"
#include "taebp/scenario/ssm_args.h"

#include "sumo_messages.h"
#include "sumo_run_outputs.h"
#include "vehicles.h"

#include <pugixml.hpp>

#include <csignal>
#include <cstdio>
#include <cstring>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

namespace taebp {
namespace {

namespace fs = std::filesystem;
using control::kSsmSumoFile;
using control::PolicyOutputDir;
using control::TripinfoPath;

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ",") + s;
  return out;
}

// Elements of an additional file whose `file` attribute is an output SUMO
// writes (detectors, mean data, probes); any other `file` or `href` is an
// input (a rerouter's definitions, an include).
bool IsOutputElement(const std::string& name) {
  static const char* const kOutputs[] = {
      "edgeData", "laneData", "edgeRelation", "tazRelation", "e1Detector", "inductionLoop",
      "e2Detector", "laneAreaDetector", "e3Detector", "entryExitDetector",
      "instantInductionLoop", "routeProbe", "vTypeProbe"};
  for (const char* o : kOutputs)
    if (name == o) return true;
  return false;
}

// A copy of the additional file `path` for one policy: its outputs go into
// `dir` (their own file names; each policy its own, none overwriting the
// user's folder), its inputs stay where they were (made absolute). Returns
// the copy, or `path` itself when it names no output. `names` collects the
// outputs' file names.
std::string PolicyAdditional(const std::string& path, const fs::path& dir, int index,
                             std::vector<std::string>* names) {
  pugi::xml_document doc;
  if (!doc.load_file(path.c_str())) return path;  // SUMO reports what is wrong with it
  const fs::path base = fs::absolute(fs::path(path)).parent_path();
  bool any = false;
  for (pugi::xpath_node n : doc.select_nodes("//*[@file or @href]")) {
    pugi::xml_node e = n.node();
    for (const char* attr : {"file", "href"}) {
      pugi::xml_attribute a = e.attribute(attr);
      if (!a) continue;
      const std::string value = a.value();
      if (std::string(attr) == "file" && IsOutputElement(e.name())) {
        std::string name = fs::path(value).filename().string();
        // Two outputs of one name: the second gets its element's id.
        if (std::find(names->begin(), names->end(), name) != names->end())
          name = std::string(e.attribute("id").value()) + "-" + name;
        names->push_back(name);
        a.set_value((dir / name).c_str());
        any = true;
      } else if (!value.empty() && fs::path(value).is_relative()) {
        a.set_value((base / value).c_str());
      }
    }
  }
  if (!any) return path;
  const fs::path copy = dir / (".additional-" + std::to_string(index) + "-" +
                               fs::path(path).filename().string());
  if (!doc.save_file(copy.c_str()))
    throw ConfigError("scenario.additional: cannot write " + copy.string());
  return copy.string();
}

std::vector<std::string> SumoArgs(const ExperimentConfig& config, const Scenario& scenario,
                                  const std::string& policy) {
  const ScenarioConfig& sc = config.scenario;
  std::vector<std::string> args = {
      "sumo", "-n", scenario.net, "--step-length", NumberText(sc.step_length, 17), "--seed",
      std::to_string(sc.seed % 2147483647ULL),
      "--collision.check-junctions", "true", "--collision.action", "warn",
      "--collision.mingap-factor", "0", "--time-to-teleport", "-1", "--no-step-log", "true",
      "--duration-log.disable", "true", "--xml-validation", "never"};
  if (!scenario.route_files.empty()) args.insert(args.end(), {"-r", Join(scenario.route_files)});
  if (sc.routes_scale != 1.0) {
    args.insert(args.end(), {"--scale", NumberText(sc.routes_scale, 17)});
  }
  std::vector<std::string> additional = scenario.additional_files;
  if (scenario.scratch) {
    // SUMO's outputs for this policy, each in its own folder.
    const fs::path dir = PolicyOutputDir(scenario, policy);
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir, ec);
    if (ec) throw ConfigError("cannot create " + dir.string() + ": " + ec.message());
    std::vector<std::string> names;
    for (std::size_t k = 0; k < additional.size(); ++k)
      additional[k] = PolicyAdditional(additional[k], dir, static_cast<int>(k), &names);
    const OutputsConfig& o = sc.outputs;
    if (o.fcd) args.insert(args.end(), {"--fcd-output", (dir / "fcd.xml").string()});
    if (o.queue) args.insert(args.end(), {"--queue-output", (dir / "queue.xml").string()});
    if (o.ssm) {  // under every policy, sumo_native included
      const std::vector<std::string> ssm = SsmSumoArgs(*o.ssm, (dir / kSsmSumoFile).string());
      args.insert(args.end(), ssm.begin(), ssm.end());
    }
    if (o.edgedata || o.lanedata) {
      // Means over the measured time (from the warm-up's end).
      std::ostringstream add;
      add << "<additional>\n";
      if (o.edgedata)
        add << "  <edgeData id=\"taebp_edgedata\" file=\"" << (dir / "edgedata.xml").string()
            << "\" begin=\"" << NumberText(sc.warmup, 17) << "\"/>\n";
      if (o.lanedata)
        add << "  <laneData id=\"taebp_lanedata\" file=\"" << (dir / "lanedata.xml").string()
            << "\" begin=\"" << NumberText(sc.warmup, 17) << "\"/>\n";
      add << "</additional>\n";
      const fs::path file = dir / ".taebp-meandata.add.xml";
      std::ofstream(file) << add.str();
      additional.push_back(file.string());
    }
  }
  if (!additional.empty()) args.insert(args.end(), {"-a", Join(additional)});
  if (scenario.scratch && scenario.kind == ScenarioKind::kNetwork) {
    // Vehicles still in the network at the end (or at a stall that stops the
    // run) get a record too (arrival -1, their times so far): the delay
    // counts them (ReadTripinfo).
    args.insert(args.end(), {"--tripinfo-output", TripinfoPath(scenario, policy),
                             "--tripinfo-output.write-unfinished", "true"});
    if (sc.summary_output)
      args.insert(args.end(),
                  {"--summary-output",
                   (fs::path(scenario.scratch->path()) / ("summary-" + policy + ".xml")).string()});
  }
  return args;
}

// SUMO aborting (a failed assertion inside libsumo) takes this process with
// it. While SUMO runs, SIGABRT passes SUMO's own output on, says what is
// known to cause it, removes the scratch folder and exits 3 (SUMO failed).
struct AbortState {
  int capture = -1, stderr_fd = 2;
  char message[4096] = {};
  char scratch[4096] = {};
};
AbortState g_abort;

extern "C" void OnSumoAbort(int) {
  const AbortState& a = g_abort;
  char buf[4096];
  if (a.capture >= 0 && ::lseek(a.capture, 0, SEEK_SET) == 0)
    for (ssize_t n; (n = ::read(a.capture, buf, sizeof buf)) > 0;)
      if (::write(a.stderr_fd, buf, static_cast<std::size_t>(n)) < 0) break;
  if (::write(a.stderr_fd, a.message, std::strlen(a.message)) < 0) {
  }
  // Not async-signal-safe; the process ends here either way.
  std::error_code ec;
  if (a.scratch[0]) fs::remove_all(a.scratch, ec);
  ::_exit(kExitSumo);
}

class AbortGuard {
 public:
  AbortGuard(const Scenario& scenario, const control::SumoMessages& messages) {
    g_abort.capture = messages.capture_fd();
    g_abort.stderr_fd = messages.real_stderr() >= 0 ? messages.real_stderr() : 2;
    const std::string text =
        "taebp: SUMO aborted: " +
        (scenario.abort_hint.empty()
             ? std::string("an assertion inside SUMO failed (its message is above)")
             : scenario.abort_hint) +
        "\n";
    std::snprintf(g_abort.message, sizeof g_abort.message, "%s", text.c_str());
    std::snprintf(g_abort.scratch, sizeof g_abort.scratch, "%s",
                  scenario.scratch ? scenario.scratch->path().c_str() : "");
    struct sigaction sa {};
    sa.sa_handler = OnSumoAbort;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGABRT, &sa, &previous_);
  }
  ~AbortGuard() { ::sigaction(SIGABRT, &previous_, nullptr); }
  AbortGuard(const AbortGuard&) = delete;
  AbortGuard& operator=(const AbortGuard&) = delete;

 private:
  struct sigaction previous_ {};
};

std::optional<persuasion::Policy> PolicyOf(const std::string& name) {
  if (name == SumoNative().name) return std::nullopt;
  return ParseGamePolicy(name);
}

using Clock = std::chrono::steady_clock;

// The run's steps: SUMO's, then the controller's, until the end or a stall
// (scenario.stall_action: error); the time each took is added up.
PolicyRun Simulate(const ExperimentConfig& config, const std::string& policy,
                   const RunOptions& options, NetworkController& controller, SumoSimulation& sumo,
                   Clock::duration* in_sumo, Clock::duration* in_controller) {
  const long steps = std::lround(config.scenario.duration / config.scenario.step_length);
  const long minute = std::max(1L, std::lround(60.0 / config.scenario.step_length));
  const long progress_every = std::max(1L, std::lround(10.0 / config.scenario.step_length));
  try {
    for (long k = 0; k < steps; ++k) {
      ThrowIfInterrupted();  // Ctrl-C, SIGTERM: unwind, scratch removed (interrupt.h)
      const Clock::time_point t0 = Clock::now();
      sumo.Step();
      const Clock::time_point t1 = Clock::now();
      controller.Step();
      *in_sumo += t1 - t0;
      *in_controller += Clock::now() - t1;
      if (options.every_minute && (k + 1) % minute == 0)
        options.every_minute(policy, sumo.Time());
      if (options.progress && ((k + 1) % progress_every == 0 || k + 1 == steps))
        options.progress({policy, sumo.Time(), config.scenario.duration,
                          controller.VehiclesNow(), controller.EncountersSoFar()});
    }
    // A branch of a paired game never gets here but at the run's end.
    if (controller.InBranch()) controller.EndBranch("ok", "the run ended first");
    if (options.before_close) options.before_close();
    return controller.Finish();
  } catch (const StallError& e) {
    if (controller.InBranch()) controller.EndBranch("ok", e.what());
    // scenario.stall_action: error. The run is measured up to the stall
    // (SUMO's tripinfo with every vehicle still in the network, below);
    // the runner stops the experiment after this policy.
    PolicyRun run = controller.Finish();  // every junction stalled by then is in run.stalls
    run.stall_error = e.what();
    return run;
  }
}

// SUMO's warnings of the run into `run`; a warning that SUMO changed the
// demand the route files hold is an error (the run is not the one asked for).
void TakeWarnings(const control::SumoWarnings& warned, const std::string& policy, PolicyRun* r) {
  PolicyRun& run = *r;
  run.sumo_warnings = warned.count;
  run.sumo_collision_warnings = warned.collisions;
  run.sumo_warnings_first = warned.first;
  if (!warned.demand_changed.empty()) {
    const std::size_t n = warned.demand_changed.size();
    throw SumoError(
        "SUMO did not simulate the demand the route files hold (" + std::to_string(n) +
        (n == 1 ? " warning" : " warnings") + " of policy " + policy + "): " +
        warned.demand_changed.front() +
        (n > 1 ? " (and " + std::to_string(n - 1) + " more)" : std::string()) +
        ". Fix the route files (sort them by departure time: SUMO's tools/route/sort_routes.py; "
        "give every vehicle a route its edges connect)");
  }
}

}  // namespace

PolicyRun RunPolicy(const ExperimentConfig& config, const std::string& policy,
                    const Scenario& scenario, const RunOptions& options) {
  if (config.scenario.paired && sumo::CurrentBackend() == sumo::Backend::kLibtraciGui)
    throw ConfigError(
        "scenario.paired forks the simulation to play each game under every policy, and under "
        "--gui the simulation is sumo-gui, another process: run without --gui, or set "
        "scenario.paired: false");
  // SUMO's SSM device as in upstream's release builds (no abort when two
  // vehicles it saw collide leave together; sumo_adapter.h).
  if (config.scenario.outputs.ssm && sumo::CurrentBackend() == sumo::Backend::kLibsumo)
    sumo::SsmReleaseBehaviour();
  ControllerOptions copts;
  copts.colour_states = options.colour_states;
  copts.stall_limit = options.stall_limit;
  NetworkController controller(config, PolicyOf(policy), scenario, *scenario.topology, copts);
  // SUMO's warnings (its stderr) from its start to its close.
  std::optional<control::SumoMessages> messages(std::in_place);
  std::optional<AbortGuard> abort_guard(std::in_place, scenario, *messages);
  // SUMO's errors name the policy, the input file and the usual fix.
  auto explained = [&](const SumoError& e) {
    std::vector<std::string> files = scenario.route_files;
    files.insert(files.end(), scenario.additional_files.begin(), scenario.additional_files.end());
    return SumoError(control::ExplainSumoError(
        e.what(), policy, files, scenario.scratch ? scenario.scratch->path() : ""));
  };
  SumoSimulation& sumo = Sumo();  // the backend selected for this run
  const Clock::time_point started = Clock::now();
  Clock::duration in_start{}, in_sumo{}, in_controller{};
  try {
    sumo.Start(SumoArgs(config, scenario, policy));
  } catch (const SumoError& e) {
    throw explained(e);
  }
  PolicyRun run;
  // SUMO is closed on every way out: a scenario that does not fit or a stall
  // leaves no simulation (or sumo-gui window) open.
  try {
    controller.Start();
    in_start = Clock::now() - started;
    if (options.after_start) options.after_start();
    run = Simulate(config, policy, options, controller, sumo, &in_sumo, &in_controller);
  } catch (const SumoError& e) {
    // A branch of a paired game ends here, whatever happened in it.
    if (controller.InBranch()) controller.EndBranch("failed", e.what());
    sumo.Close();
    throw explained(e);
  } catch (const std::exception& e) {
    if (controller.InBranch()) controller.EndBranch("failed", e.what());
    sumo.Close();
    throw;
  } catch (...) {
    if (controller.InBranch()) controller.EndBranch("failed", "an unknown error");
    sumo.Close();
    throw;
  }
  sumo.Close();
  run.wall_seconds_start = std::chrono::duration<double>(in_start).count();
  run.wall_seconds_sumo_steps = std::chrono::duration<double>(in_sumo).count();
  run.wall_seconds_controller_steps = std::chrono::duration<double>(in_controller).count();
  abort_guard.reset();
  const control::SumoWarnings warned = messages->Finish();
  messages.reset();
  TakeWarnings(warned, policy, &run);
  control::ReadSumoOutputs(
      config, scenario, policy,
      [&controller](const std::string& id) { return controller.DepartedAsAv(id); }, warned.ssm,
      &run);
  return run;
}

double RunBareSumo(const ExperimentConfig& config, const Scenario& scenario) {
  if (!config.scenario.IsNetwork())
    throw ConfigError(
        "a bare SUMO run needs scenario.kind = 'network': the figure-8's vehicles keep "
        "circulating only through the controller's lap re-routing (compare against " +
        std::string(SumoNative().name) + " instead)");
  NetworkController controller(config, std::nullopt, scenario, *scenario.topology, {});
  SumoSimulation& sumo = Sumo();
  sumo.Start(SumoArgs(config, scenario, SumoNative().name));
  try {
    controller.Start();
    const long steps = std::lround(config.scenario.duration / config.scenario.step_length);
    for (long k = 0; k < steps; ++k) sumo.Step();
  } catch (...) {
    sumo.Close();
    throw;
  }
  const double t = sumo.Time();
  sumo.Close();
  return t;
}

}  // namespace taebp
