#include "gui_cmd.h"

#include "taebp/rundir/synced_file.h"
#include "taebp/config/config.h"
#include "taebp/controller/policy_run.h"
#include "taebp/controller/sumo_adapter.h"
#include "taebp/base/number_text.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/persuasion.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/scenario/net_file.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

namespace taebp::gui {
namespace {

namespace fs = std::filesystem;

// Set in the environment of the re-execution under xvfb-run (no second try):
// the file the copy writes its exit code into (Snapshot::HandBack).
constexpr const char* kUnderXvfbEnv = "TAEBP_SNAPSHOT_UNDER_XVFB";
constexpr const char* kExitCodeFile = "taebp-exit-code";
constexpr const char* kXvfbScreen = "-screen 0 1280x1024x24";
// The sumo-gui window for snapshots: the view inside it is about 1270 x 535
// pixels, the figure-8's aspect ratio (about 2.4 : 1).
constexpr const char* kSnapshotWindow = "1280,720";
constexpr double kViewWidthPx = 1270, kViewHeightPx = 535;
// A junction framed by --junction: this many metres each side of its centre
// (its approaches and the vehicles queued on them), divided by --zoom.
constexpr double kJunctionHalfView = 40.0;
// Vehicles are drawn at least this long (pixels; a 5 m car): sumo-gui's
// vehicle exaggeration grows them when the view is wide (a city).
constexpr double kMinCarPixels = 14.0;
constexpr double kCarLength = 5.0;

// Absolute path of an executable found on PATH, or "".
std::string FindOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) dir = ".";
    const fs::path p = fs::path(dir) / name;
    if (access(p.c_str(), X_OK) == 0 && fs::is_regular_file(p)) return fs::absolute(p).string();
  }
  return "";
}

bool HasDisplay() {
  const char* d = std::getenv("DISPLAY");
  return d && *d;
}

void RequireSumoGui() {
  if (FindOnPath("sumo-gui").empty())
    throw GuiError("sumo-gui is not on PATH: install the Debian package 'sumo' (it ships sumo-gui)");
}


// Width and height from a PNG's IHDR chunk; {0, 0} when not a PNG.
std::pair<unsigned, unsigned> PngSize(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  unsigned char h[24] = {};
  if (!in.read(reinterpret_cast<char*>(h), sizeof h)) return {0, 0};
  static const unsigned char kSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!std::equal(kSig, kSig + 8, h)) return {0, 0};
  auto be32 = [&](int o) {
    return (unsigned(h[o]) << 24) | (unsigned(h[o + 1]) << 16) | (unsigned(h[o + 2]) << 8) | h[o + 3];
  };
  return {be32(16), be32(20)};
}

// The legend of the vehicle colours of RunOptions::colour_states (the same RGB
// as the controller's palette) for the strip below a snapshot.
const char* const kLegend[] = {
    "0,0,255=AV",
    "255,0,0=HV",
    "255,220,0=AV nudging, or holding after its nudge",
    "0,200,0=HV chose DC (drive if clear)",
    "255,140,0=HV chose DR (drive recklessly)",
    "255,0,255=collision (both vehicles)",
};

std::string PolicyTitle(const std::string& p) { return PolicyLabel(p); }  // config/policies.h

// Composes `shot` with a legend strip into `out` (cli/snapshot_legend.py,
// Debian's python3 and python3-pil): sumo-gui cannot draw a legend itself.
void AddLegend(const fs::path& shot, const fs::path& out, const std::string& title, double at) {
  const std::string python = access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3"
                                                                   : FindOnPath("python3");
  if (python.empty())
    throw GuiError("python3 is not installed: the snapshot's legend needs the Debian packages "
                   "python3 and python3-pil (or use --no-legend)");
  std::vector<std::string> args = {python, TAEBP_SNAPSHOT_LEGEND, shot.string(), out.string(),
                                   "--title", title, "--time", NumberText(at, 6)};
  for (const char* e : kLegend) args.insert(args.end(), {"--entry", e});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw GuiError(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    execv(python.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw GuiError("adding the legend to the snapshot failed (" + std::string(TAEBP_SNAPSHOT_LEGEND) +
                   "; see its message above; --no-legend keeps sumo-gui's picture as it is)");
}

// The margin around a network's bounding box in a framed view: 5 % of its
// larger side, at least 2 m.
double FrameMargin(double width, double height) {
  return std::max(2.0, 0.05 * std::max(width, height));
}

// What the snapshot shows: a box in network coordinates and how much larger
// than life vehicles are drawn.
struct Framing {
  XY lo, hi;
  double exaggeration = 1.0;
};

// The whole network (its convBoundary with FrameTrack's margin) or a box
// around one junction, shrunk about its centre by `zoom`; vehicles drawn
// large enough to be seen at that scale.
Framing FrameFor(const std::string& net_path, const std::string& junction, double zoom) {
  const net::NetFile net = net::NetFile::Load(net_path);
  double cx, cy, hx, hy;
  if (!junction.empty()) {
    const net::Junction* j = net.FindJunction(junction);
    if (!j || j->type == "internal") {
      std::string some;
      int n = 0;
      for (const auto& [id, k] : net.junctions()) {
        if (k.type == "internal" || k.type == "dead_end") continue;
        if (n++ < 8) some += (some.empty() ? "" : ", ") + id;
      }
      throw persuasion::InvalidArgument("--junction " + junction + ": no such junction in " +
                                        net_path + " (its junctions: " + some +
                                        (n > 8 ? ", ... " + std::to_string(n) + " in all" : "") +
                                        ")");
    }
    cx = j->pos.x;
    cy = j->pos.y;
    hx = hy = kJunctionHalfView;
  } else {
    const auto lo = net.boundary_min, hi = net.boundary_max;
    const double margin = FrameMargin(hi.x - lo.x, hi.y - lo.y);
    cx = 0.5 * (lo.x + hi.x);
    cy = 0.5 * (lo.y + hi.y);
    hx = 0.5 * (hi.x - lo.x) + margin;
    hy = 0.5 * (hi.y - lo.y) + margin;
  }
  // Below a car's length across, a picture shows nothing of the junction.
  constexpr double kMinHalfView = 2.5;  // m
  const double max_zoom = std::min(hx, hy) / kMinHalfView;
  if (zoom > max_zoom) {
    throw persuasion::InvalidArgument("--zoom " + NumberText(zoom, 6) + ": the view would be " +
                                      NumberText(2 * std::min(hx, hy) / zoom, 3) +
                                      " m across, less than a car; at most " +
                                      NumberText(max_zoom, 4) + " here");
  }
  hx /= zoom;
  hy /= zoom;
  Framing f;
  f.lo = {cx - hx, cy - hy};
  f.hi = {cx + hx, cy + hy};
  // sumo-gui fits the box into the view: the tighter of the two scales.
  const double px_per_m = std::min(kViewWidthPx / (2 * hx), kViewHeightPx / (2 * hy));
  f.exaggeration = std::max(1.0, kMinCarPixels / (kCarLength * px_per_m));
  return f;
}

// A sumo-gui scheme like "real world" with vehicles drawn `exaggeration`
// times their size (SUMO 1.15's size settings: vehicle_exaggeration).
void WriteGuiSettings(const fs::path& file, double exaggeration) {
  std::ofstream out(file);
  out << "<viewsettings>\n"
         "  <scheme name=\"taebp\">\n"
         "    <background backgroundColor=\"white\" showGrid=\"0\"/>\n"
         "    <vehicles vehicleMode=\"0\" vehicleQuality=\"2\" vehicle_minSize=\"1\" "
         "vehicle_exaggeration=\""
      << exaggeration
      << "\" vehicle_constantSize=\"0\" vehicle_constantSizeSelected=\"0\"/>\n"
         "  </scheme>\n"
         "</viewsettings>\n";
  if (!out) throw GuiError("cannot write sumo-gui's settings to " + file.string());
}

}  // namespace

void FrameTrack() {
  const auto [lo, hi] = Sumo().NetBoundary();
  const double margin = FrameMargin(hi.x - lo.x, hi.y - lo.y);
  Sumo().GuiSetSchema("real world");
  Sumo().GuiSetBoundary({lo.x - margin, lo.y - margin}, {hi.x + margin, hi.y + margin});
}

// ------------------------------------------------------------------ run --gui
struct RunGui::Impl {
  bool gui = false;
  int delay_ms = 0;
};

RunGui::RunGui(CLI::App* run) : impl_(std::make_unique<Impl>()) {
  run->add_flag("--gui", impl_->gui,
                "watch the run in sumo-gui (policies one after another; vehicles coloured by "
                "state; results written as usual)");
  run->add_option("--delay", impl_->delay_ms,
                  "with --gui: sumo-gui's delay per simulation step in ms (100 = real time "
                  "at step 0.1 s)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}
RunGui::~RunGui() = default;

RunOptions RunGui::Prepare() const {
  if (!impl_->gui) return {};
  RequireSumoGui();
  if (!HasDisplay())
    throw GuiError("--gui needs a display and DISPLAY is not set (for a picture without one, "
                   "use `taebp snapshot`)");
  sumo::SetBackend(sumo::Backend::kLibtraciGui, {"--delay", std::to_string(impl_->delay_ms)});
  RunOptions o;
  o.colour_states = true;
  o.after_start = FrameTrack;
  return o;
}

// ------------------------------------------------------------------ snapshot
struct Snapshot::Impl {
  CLI::App* cmd = nullptr;
  std::string config_path, out, policy;
  double at = 60.0;
  std::vector<std::string> overrides;
  bool no_legend = false;
  std::string junction;
  double zoom = 1.0;
};

Snapshot::Snapshot(CLI::App& app) : impl_(std::make_unique<Impl>()) {
  Impl& o = *impl_;
  o.cmd = app.add_subcommand(
      "snapshot",
      "Run a config's scenario in sumo-gui up to a time and save a picture of the track "
      "(uses xvfb-run when DISPLAY is unset)");
  o.cmd->add_option("CONFIG", o.config_path, "experiment YAML (e.g. configs/paper.yaml)")->required();
  o.cmd->add_option("--out", o.out, "the picture to write (PNG)")->required();
  o.cmd->add_option("--at", o.at, "simulated time of the picture (s, > 0)")->capture_default_str();
  o.cmd->add_option("--set", o.overrides,
                    "override a config key, KEY=VALUE with VALUE read as YAML (repeatable)");
  o.cmd->add_option("--policy", o.policy,
                    "the policy to run (default: the config's first listed policy)");
  o.cmd->add_option("--junction", o.junction,
                    "frame this junction (SUMO id) and its approaches, 80 m across (default: "
                    "the whole network)");
  o.cmd->add_option("--zoom", o.zoom,
                    "magnify the framed view this many times about its centre (> 0; 1: as "
                    "framed)")
      ->capture_default_str();
  o.cmd->add_flag("--no-legend", o.no_legend,
                  "keep sumo-gui's picture as it is (default: a strip below it with the "
                  "simulated time and the legend of the vehicle colours)");
}
Snapshot::~Snapshot() = default;

namespace {

// Runs `args` (xvfb-run, this program again) as its own process group, with
// TMPDIR a folder of its own: on SIGINT, SIGTERM or SIGHUP the whole group
// (xvfb-run, Xvfb, this program's copy, sumo-gui) is ended, and xvfb-run's
// temporary files go with that folder. Returns the copy's exit code, or
// 128 + the signal.
int RunUnderXvfb(std::vector<std::string> args) {
  const char* tmp_env = std::getenv("TMPDIR");
  std::string tmpl = (fs::path(tmp_env && *tmp_env ? tmp_env : "/tmp") / "taebp-xvfb-XXXXXX").string();
  if (!::mkdtemp(tmpl.data()))
    throw GuiError("cannot create a temporary folder " + tmpl + ": " + std::strerror(errno));
  const fs::path scratch = tmpl;
  std::vector<char*> cargs;
  for (std::string& a : args) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  const InterruptGuard interrupts;
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    std::error_code ec;
    fs::remove_all(scratch, ec);
    throw GuiError(std::string("fork failed: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::setpgid(0, 0);
    InterruptGuard::ResetInChild();
    ::setenv("TMPDIR", scratch.c_str(), 1);
    ::setenv(kUnderXvfbEnv, (scratch / kExitCodeFile).c_str(), 1);
    ::execv(cargs[0], cargs.data());
    static const char msg[] = "taebp: cannot run xvfb-run\n";
    ssize_t ignored = ::write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)ignored;
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  int status = 0;
  bool stopping = false;
  auto stop_since = std::chrono::steady_clock::now();
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) break;
    if (PendingInterrupt() && !stopping) {
      stopping = true;
      stop_since = std::chrono::steady_clock::now();
      ::kill(-pid, SIGTERM);
    } else if (stopping && std::chrono::steady_clock::now() - stop_since > std::chrono::seconds(5)) {
      ::kill(-pid, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(-pid, SIGKILL);  // whatever of the group is left (Xvfb, sumo-gui)
  // The copy's own exit code where it handed one back: xvfb-run exits with it
  // too, unless its clean-up failed (then 5, which would hide the outcome).
  int handed_back = -1;
  if (std::ifstream in{scratch / kExitCodeFile}; !(in >> handed_back)) handed_back = -1;
  std::error_code ec;
  fs::remove_all(scratch, ec);
  if (PendingInterrupt()) throw Interrupted(PendingInterrupt());
  if (handed_back >= 0) return handed_back;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

// --at, --zoom and --out: a positive time, a positive magnification, a
// .png file in a folder that can be written.
void CheckSnapshotOptions(double at, double zoom, const std::string& out) {
  if (!(std::isfinite(at) && at > 0))
    throw persuasion::InvalidArgument("--at " + NumberText(at, 6) +
                                      ": the time must be a positive number of seconds");
  if (!(std::isfinite(zoom) && zoom > 0))
    throw persuasion::InvalidArgument("--zoom " + NumberText(zoom, 6) +
                                      ": the magnification must be a positive number");
  {
    std::string ext = fs::path(out).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext != ".png")
      throw persuasion::InvalidArgument("--out " + out +
                                        ": the picture must be a .png file (sumo-gui picks the "
                                        "format from the name and writes nothing else here)");
    const fs::path parent = fs::absolute(out).parent_path();
    CheckOutputDir(parent.string(), "--out " + out + ": its folder");
  }
}

// The policy to show (--policy, else the config's first), checked, and
// --at within the scenario.
std::string SnapshotPolicy(const ExperimentConfig& config, const std::string& policy, double at,
                           const std::string& config_path) {
  // IsValid guarantees at least one policy.
  const std::string name = policy.empty() ? config.policies.front() : policy;
  if (name != SumoNative().name) ParseGamePolicy(name);  // throws for an unknown name
  if (at > config.scenario.duration)
    throw persuasion::InvalidArgument("--at " + NumberText(at, 6) + " s is beyond the scenario's end (" +
                                      config_path + ": scenario.duration = " +
                                      NumberText(config.scenario.duration, 6) +
                                      " s): choose a time within it, or --set scenario.duration");
  return name;
}

// Without a display: this command again under xvfb-run; its exit code.
int RerunUnderXvfb(int argc, char** argv) {
  if (std::getenv(kUnderXvfbEnv))
    throw GuiError("DISPLAY is still unset under xvfb-run: cannot open sumo-gui");
  const std::string xvfb = FindOnPath("xvfb-run");
  if (xvfb.empty())
    throw GuiError("DISPLAY is not set and xvfb-run is not installed: install the Debian "
                   "packages 'xvfb' and 'xauth', or run with a display");
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw GuiError("cannot find this program to re-run it under xvfb-run: " + ec.message());
  std::vector<std::string> args = {xvfb, "-a", "-s", kXvfbScreen, self.string()};
  for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
  return RunUnderXvfb(args);
}

// The picture (--out, absolute) and the temporary files beside it.
struct ShotFiles {
  fs::path out, tmp, composed, settings;
};

// --out's folder made, and the names of the temporary files beside it (an
// old temporary picture removed).
ShotFiles ShotFilesFor(const std::string& out_option) {
  ShotFiles f;
  const fs::path out = fs::absolute(out_option);
  f.out = out;
  if (out.has_parent_path()) fs::create_directories(out.parent_path());
  // sumo-gui writes a temporary picture next to --out, renamed over it once
  // complete: a failing run leaves an earlier picture as it was and never an
  // empty or partial file.
  f.tmp = out.parent_path() / ("." + out.stem().string() + ".taebp-" +
                               std::to_string(::getpid()) + ".png");
  std::error_code ec;
  // sumo-gui's picture goes to `tmp`; with the legend, the composed picture
  // goes to a second temporary name; either is renamed over --out.
  f.composed = out.parent_path() / ("." + out.stem().string() + ".taebp-legend-" +
                                    std::to_string(::getpid()) + ".png");
  f.settings = out.parent_path() / ("." + out.stem().string() + ".taebp-gui-" +
                                    std::to_string(::getpid()) + ".xml");
  fs::remove(f.tmp, ec);
  return f;
}

// The policy's run in sumo-gui up to the config's end, framed, with a
// screenshot to `f.tmp` at the end.
PolicyRun RunInGui(const ExperimentConfig& config, const std::string& policy,
                   const Scenario& scenario, const Framing& framing, bool own_frame,
                   const ShotFiles& f) {
  std::error_code ec;
  std::vector<std::string> gui_args = {"--window-size", kSnapshotWindow, "--delay", "0"};
  if (own_frame) {
    WriteGuiSettings(f.settings, framing.exaggeration);
    gui_args.insert(gui_args.end(), {"--gui-settings-file", f.settings.string()});
  }
  sumo::SetBackend(sumo::Backend::kLibtraciGui, gui_args);
  RunOptions ro;
  ro.colour_states = true;
  ro.after_start = FrameTrack;
  if (own_frame)
    ro.after_start = [&] {
      Sumo().GuiSetSchema("taebp");
      Sumo().GuiSetBoundary(framing.lo, framing.hi);
    };
  ro.before_close = [&] {
    Sumo().GuiScreenshot(f.tmp.string());
    Sumo().Step();  // sumo-gui writes the picture during this step
  };
  PolicyRun run = RunPolicy(config, policy, scenario, ro);
  sumo::SetBackend(sumo::Backend::kLibsumo);
  fs::remove(f.settings, ec);
  return run;
}

// sumo-gui has written the file by the end of the step; allow a moment
// for the file system all the same.
void WaitForPicture(const fs::path& tmp) {
  std::error_code ec;
  auto written = [&] {
    return fs::exists(tmp, ec) && fs::file_size(tmp, ec) > 0 && PngSize(tmp.string()).first > 0;
  };
  for (int i = 0; i < 50 && !written(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  if (!written()) throw GuiError("sumo-gui did not write a PNG picture to " + tmp.string());
}

// The legend's title: the config, the policy, the seed, the junction, the
// vehicles' exaggeration.
std::string SnapshotTitle(const std::string& config_path, const std::string& name,
                          const ExperimentConfig& config, const std::string& junction,
                          const Framing& framing) {
  std::string title = config_path + " · " + PolicyTitle(name) + " · seed " +
                      std::to_string(config.scenario.seed);
  if (!junction.empty()) title += " · junction " + junction;
  if (framing.exaggeration > 1.0) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " · vehicles drawn %.1fx their size", framing.exaggeration);
    title += buf;
  }
  return title;
}

}  // namespace

bool Snapshot::Parsed() const { return impl_->cmd->parsed(); }

void Snapshot::HandBack(int exit_code) {
  const char* file = std::getenv(kUnderXvfbEnv);
  if (!file || !*file) return;
  std::ofstream(file, std::ios::trunc) << exit_code << '\n';
}

int Snapshot::Run(int argc, char** argv) {
  const Impl& o = *impl_;
  CheckSnapshotOptions(o.at, o.zoom, o.out);
  RequireSumoGui();
  // Config and policy errors before any re-execution.
  ExperimentConfig config = LoadExperimentConfig(o.config_path, o.overrides);
  const std::string name = SnapshotPolicy(config, o.policy, o.at, o.config_path);
  const std::string policy = name;

  if (!HasDisplay()) return RerunUnderXvfb(argc, argv);

  const std::string config_dir = fs::path(o.config_path).parent_path().string();
  const Scenario scenario = BuildScenario(config, config_dir);
  config.scenario.duration = o.at;
  // The figure-8 as a whole keeps FrameTrack's view; a junction, a zoom or a
  // network too wide for vehicles to be seen gets its own box and scheme.
  const Framing framing = FrameFor(scenario.net, o.junction, o.zoom);
  const bool own_frame = !o.junction.empty() || o.zoom != 1.0 || framing.exaggeration > 1.0;

  const ShotFiles f = ShotFilesFor(o.out);
  const fs::path& out = f.out;
  std::error_code ec;
  PolicyRun run;
  try {
    run = RunInGui(config, policy, scenario, framing, own_frame, f);
    WaitForPicture(f.tmp);
    if (o.no_legend) {
      PutInPlace(f.tmp.string(), out.string());
    } else {
      AddLegend(f.tmp, f.composed, SnapshotTitle(o.config_path, name, config, o.junction, framing),
                o.at);
      fs::remove(f.tmp, ec);
      PutInPlace(f.composed.string(), out.string());
    }
  } catch (...) {
    fs::remove(f.tmp, ec);
    fs::remove(f.composed, ec);
    fs::remove(f.settings, ec);
    throw;
  }
  const auto [w, h] = PngSize(out.string());
  std::fprintf(stderr, "taebp: snapshot of %s at t = %s s (%zu encounters so far): %s", name.c_str(),
               NumberText(o.at, 6).c_str(), run.encounters.size(), out.string().c_str());
  if (w > 0) std::fprintf(stderr, " (%u x %u)", w, h);
  if (framing.exaggeration > 1.0)
    std::fprintf(stderr, "; vehicles drawn %.1fx their size", framing.exaggeration);
  std::fprintf(stderr, "\n");
  return 0;
}

}  // namespace taebp::gui
