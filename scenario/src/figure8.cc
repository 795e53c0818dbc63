#include "taebp/scenario/figure8.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#ifndef TAEBP_DEFAULT_NET
#define TAEBP_DEFAULT_NET "sumo_net/figure8.net.xml"
#endif
#ifndef TAEBP_DEFAULT_LOOP_LENGTH
#define TAEBP_DEFAULT_LOOP_LENGTH 80.0
#endif

namespace taebp {

namespace fs = std::filesystem;

namespace {
std::string Fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}
}  // namespace

std::string DefaultNetworkPath() { return TAEBP_DEFAULT_NET; }

namespace {

// Runs a program (no shell) with stdout/stderr to `log`; returns its exit code.
int RunProgram(const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    if (FILE* f = std::fopen(log.c_str(), "a")) {
      dup2(fileno(f), 1);
      dup2(fileno(f), 2);
    }
    execvp(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

// Generated once into the cache (atomically: built in a private directory,
// then renamed into place).
std::string GeneratedFigure8(double loop) {
  const fs::path built = fs::path(DefaultNetworkPath()).parent_path();
  const fs::path script = built / "make_figure8.py";
  char name[64];
  std::snprintf(name, sizeof name, "figure8-L%.3f", loop);
  const fs::path dir = built / "cache" / name;
  const fs::path net = dir / "figure8.net.xml";
  if (fs::exists(net)) return net.string();
  if (!fs::exists(script))
    throw ConfigError("scenario.loop_length = " + Fmt(loop) + " needs " + script.string() +
                      ", which is missing: rebuild the project");
  fs::create_directories(dir.parent_path());
  const fs::path tmp = dir.parent_path() / (std::string(name) + ".tmp." + std::to_string(getpid()));
  fs::create_directories(tmp);
  const std::string log = (tmp / "generate.log").string();
  char loop_text[32];
  std::snprintf(loop_text, sizeof loop_text, "%.3f", loop);
  if (RunProgram({"python3", script.string(), "--loop-length", loop_text, "--out-dir", tmp.string()},
                 log) != 0 ||
      RunProgram({"netconvert", "--node-files", (tmp / "figure8.nod.xml").string(), "--edge-files",
                  (tmp / "figure8.edg.xml").string(), "--connection-files",
                  (tmp / "figure8.con.xml").string(), "--no-turnarounds", "true",
                  "--offset.disable-normalization", "true", "--precision", "4",
                  "--xml-validation", "never", "--output-file", (tmp / "figure8.net.xml").string()},
                 log) != 0) {
    throw ConfigError("scenario.loop_length = " + Fmt(loop) +
                      ": generating the network failed, see " + log);
  }
  std::error_code ec;
  fs::rename(tmp, dir, ec);  // another process may have won the race: use its copy
  if (ec) fs::remove_all(tmp);
  return net.string();
}

double RequiredLoopLength(const ScenarioConfig& sc) {
  const int n = sc.avs + sc.hvs;
  // Each vehicle needs length + gap (+0.5 m slack); a quarter more covers the
  // zones where none is placed (hold zone, edge starts). Two loops per lap.
  // Measured with 5 m vehicles, 2 m gaps and stop 3 m (tests/controller/
  // trust_test.cc re-checks it): placement first fails at 70 m for 16
  // vehicles (this gives 80, the paper's track), and loops below ~45 m
  // gridlock even with 8 vehicles, hence the 50 m floor.
  return std::max(50.0, std::ceil(1.25 * n * (sc.vehicle_length + sc.min_gap + 0.5) / 2.0 + 5.0));
}

ScenarioFiles ResolveScenarioFiles(const ExperimentConfig& config, const std::string& config_dir) {
  ScenarioFiles files;
  const ScenarioConfig& sc = config.scenario;
  if (sc.network.empty()) {
    double loop = sc.loop_length;
    const double needed = RequiredLoopLength(sc);
    if (loop < needed) {
      if (!sc.auto_length)
        throw ConfigError("scenario.loop_length = " + Fmt(loop) + " m is too short for " +
                          std::to_string(sc.avs + sc.hvs) + " vehicles (needs " + Fmt(needed) +
                          " m); raise it or set scenario.auto_length: true");
      files.notes.push_back("scenario.loop_length grown from " + Fmt(loop) + " to " +
                            Fmt(needed) + " m to fit " + std::to_string(sc.avs + sc.hvs) +
                            " vehicles");
      loop = needed;
    }
    files.loop_length = loop;
    if (std::abs(loop - TAEBP_DEFAULT_LOOP_LENGTH) < 1e-9) {
      files.net = DefaultNetworkPath();
      if (!fs::exists(files.net))
        throw ConfigError("the built-in network " + files.net +
                          " is missing: build the project (tools/run or tools/test) first");
    } else {
      files.net = GeneratedFigure8(loop);
    }
    return files;
  }
  fs::path p = config.scenario.network;
  if (p.is_relative() && !config_dir.empty()) p = fs::path(config_dir) / p;
  if (!fs::is_regular_file(p))
    throw ConfigError("scenario.network = '" + config.scenario.network + "': no such file (" +
                      p.string() + ")");
  files.net = p.string();
  return files;
}

std::vector<std::string> ScenarioWarnings(const ExperimentConfig& config) {
  std::vector<std::string> w;
  const double reach = config.scenario.stop_distance - config.model.likelihood.s_max;
  if (reach < config.scenario.vehicle_width / 2) {
    w.push_back("a nudge of up to model.likelihood.s_max = " + Fmt(config.model.likelihood.s_max) +
                " m from scenario.stop_distance = " + Fmt(config.scenario.stop_distance) +
                " m can put the AV's nose inside the crossing path (needs stop_distance >= s_max + "
                "vehicle_width/2 = " + Fmt(config.model.likelihood.s_max + config.scenario.vehicle_width / 2) +
                " m): a waiting, nudged AV can then be hit");
  }
  return w;
}

}  // namespace taebp
