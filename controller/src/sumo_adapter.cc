#include "taebp/controller/sumo_adapter.h"

#include "sumo_adapter_backend.h"

#include <libsumo/libsumo.h>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

// The in-process backend: the adapter's body over ::libsumo.
namespace taebp::sumo::libsumo_backend {
namespace S = ::libsumo;
#include "sumo_adapter_impl.inc"
}  // namespace taebp::sumo::libsumo_backend

namespace taebp::sumo {
namespace {

Backend g_backend = Backend::kLibsumo;
std::vector<std::string> g_gui_args;
bool g_started = false;  // between a successful Start and Close
constexpr const char* kView = "View #0";

bool Gui() { return g_backend == Backend::kLibtraciGui; }

void RequireGui(const char* call) {
  if (!Gui())
    throw SumoError(std::string("SUMO GUI::") + call +
                    " needs the sumo-gui backend (sumo::SetBackend(Backend::kLibtraciGui))");
}

}  // namespace

// One predictable branch per call; the libsumo side is in this translation
// unit and inlines as before.
#define TAEBP_SUMO_CALL(call) (Gui() ? libtraci_backend::call : libsumo_backend::call)

void SetBackend(Backend backend, std::vector<std::string> gui_args) {
  if (g_started) throw SumoError("SUMO backend cannot change while a simulation is loaded");
  g_backend = backend;
  g_gui_args = std::move(gui_args);
  // libtraci writes to the socket without MSG_NOSIGNAL: when sumo-gui is gone
  // (window closed, bad option) the write must fail with an error we report,
  // not kill the process with SIGPIPE.
  if (backend == Backend::kLibtraciGui) std::signal(SIGPIPE, SIG_IGN);
}

void Start(const std::vector<std::string>& args) {
  if (Gui()) {
    std::vector<std::string> cmd = args;
    if (cmd.empty()) cmd.emplace_back();
    cmd[0] = "sumo-gui";
    cmd.insert(cmd.end(), {"--start", "--quit-on-end"});
    cmd.insert(cmd.end(), g_gui_args.begin(), g_gui_args.end());
    // libtraci prints "Could not connect ... Retrying" on stdout while sumo-gui
    // starts: keep stdout (results tables) clean. sumo-gui inherits the
    // redirection; its errors still go to stderr.
    std::cout.flush();
    std::fflush(stdout);
    const int saved = dup(1);
    const int devnull = open("/dev/null", O_WRONLY);
    if (saved >= 0 && devnull >= 0) dup2(devnull, 1);
    if (devnull >= 0) close(devnull);
    auto restore = [&] {
      std::cout.flush();
      std::fflush(stdout);
      if (saved >= 0) {
        dup2(saved, 1);
        close(saved);
      }
    };
    try {
      libtraci_backend::Start(cmd);
    } catch (...) {
      restore();
      throw;
    }
    restore();
  } else {
    // SUMO prints its own errors on stderr as it loads; they still go there,
    // and the first one leads our message (not the whole command line).
    std::cerr.flush();
    std::fflush(stderr);
    FILE* capture = std::tmpfile();
    const int saved = capture ? dup(2) : -1;
    if (saved >= 0) dup2(fileno(capture), 2);
    auto restore = [&]() -> std::string {
      std::string text;
      if (saved < 0) return text;
      std::cerr.flush();
      std::fflush(stderr);
      dup2(saved, 2);
      close(saved);
      std::rewind(capture);
      char buf[4096];
      for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, capture)) > 0;) text.append(buf, n);
      std::fclose(capture);
      for (std::size_t done = 0; done < text.size();) {
        const ssize_t n = write(2, text.data() + done, text.size() - done);
        if (n <= 0) break;
        done += static_cast<std::size_t>(n);
      }
      return text;
    };
    try {
      libsumo_backend::Start(args);
    } catch (const SumoError&) {
      std::istringstream lines(restore());
      std::vector<std::string> errors;
      for (std::string line; std::getline(lines, line);)
        if (line.rfind("Error: ", 0) == 0) errors.push_back(line.substr(7));
      if (errors.empty()) throw;
      std::string cmd;
      for (const auto& a : args) cmd += (cmd.empty() ? "" : " ") + a;
      throw SumoError("SUMO failed to start: " + errors.front() +
                      (errors.size() > 1 ? " (and " + std::to_string(errors.size() - 1) +
                                               " more error(s) from SUMO, above)"
                                         : std::string()) +
                      "; the command was: " + cmd);
    }
    restore();
  }
  g_started = true;
}
void Close() {
  g_started = false;
  TAEBP_SUMO_CALL(Close());
}
bool IsLoaded() { return TAEBP_SUMO_CALL(IsLoaded()); }
void Step() { TAEBP_SUMO_CALL(Step()); }
double Time() { return TAEBP_SUMO_CALL(Time()); }
std::string Version() { return TAEBP_SUMO_CALL(Version()); }
std::vector<SumoCollision> Collisions() { return TAEBP_SUMO_CALL(Collisions()); }
int TeleportNumber() { return TAEBP_SUMO_CALL(TeleportNumber()); }
int CollidingNumber() { return TAEBP_SUMO_CALL(CollidingNumber()); }
int DepartedNumber() { return TAEBP_SUMO_CALL(DepartedNumber()); }
std::vector<std::string> DepartedIDs() { return TAEBP_SUMO_CALL(DepartedIDs()); }
int ArrivedNumber() { return TAEBP_SUMO_CALL(ArrivedNumber()); }
std::vector<std::string> ArrivedIDs() { return TAEBP_SUMO_CALL(ArrivedIDs()); }
std::vector<std::string> PendingVehicles() { return TAEBP_SUMO_CALL(PendingVehicles()); }
std::vector<std::string> VehicleIDs() { return TAEBP_SUMO_CALL(VehicleIDs()); }

double LaneLength(const std::string& lane) { return TAEBP_SUMO_CALL(LaneLength(lane)); }
std::vector<XY> LaneShape(const std::string& lane) { return TAEBP_SUMO_CALL(LaneShape(lane)); }
XY JunctionPosition(const std::string& junction) {
  return TAEBP_SUMO_CALL(JunctionPosition(junction));
}
std::pair<XY, XY> NetBoundary() { return TAEBP_SUMO_CALL(NetBoundary()); }
std::vector<std::string> LaneInternalFoes(const std::string& lane) {
  return TAEBP_SUMO_CALL(LaneInternalFoes(lane));
}
std::vector<std::string> LaneVehicleIDs(const std::string& lane) {
  return TAEBP_SUMO_CALL(LaneVehicleIDs(lane));
}
int LaneVehicleNumber(const std::string& lane) { return TAEBP_SUMO_CALL(LaneVehicleNumber(lane)); }
int LaneHaltingNumber(const std::string& lane) { return TAEBP_SUMO_CALL(LaneHaltingNumber(lane)); }

void AddVehicleType(const VehicleTypeSpec& spec) { TAEBP_SUMO_CALL(AddVehicleType(spec)); }
void AddRoute(const std::string& id, const std::vector<std::string>& edges) {
  TAEBP_SUMO_CALL(AddRoute(id, edges));
}

void AddVehicle(const std::string& id, const std::string& route, const std::string& type,
                double depart_pos) {
  TAEBP_SUMO_CALL(AddVehicle(id, route, type, depart_pos));
}
void SetSpeedMode(const std::string& veh, int mode) { TAEBP_SUMO_CALL(SetSpeedMode(veh, mode)); }
void SetLaneChangeMode(const std::string& veh, int mode) {
  TAEBP_SUMO_CALL(SetLaneChangeMode(veh, mode));
}
void SetSpeed(const std::string& veh, double speed) { TAEBP_SUMO_CALL(SetSpeed(veh, speed)); }
void SetIgnoredFoes(const std::string& veh, const std::vector<std::string>& foes) {
  TAEBP_SUMO_CALL(SetIgnoredFoes(veh, foes));
}
void SetColor(const std::string& veh, int r, int g, int b) {
  TAEBP_SUMO_CALL(SetColor(veh, r, g, b));
}
double Distance(const std::string& veh) { return TAEBP_SUMO_CALL(Distance(veh)); }
double Speed(const std::string& veh) { return TAEBP_SUMO_CALL(Speed(veh)); }
std::string RoadID(const std::string& veh) { return TAEBP_SUMO_CALL(RoadID(veh)); }
double LanePosition(const std::string& veh) { return TAEBP_SUMO_CALL(LanePosition(veh)); }
std::string LaneID(const std::string& veh) { return TAEBP_SUMO_CALL(LaneID(veh)); }
std::string TypeID(const std::string& veh) { return TAEBP_SUMO_CALL(TypeID(veh)); }
double Length(const std::string& veh) { return TAEBP_SUMO_CALL(Length(veh)); }
double MinGap(const std::string& veh) { return TAEBP_SUMO_CALL(MinGap(veh)); }
double Width(const std::string& veh) { return TAEBP_SUMO_CALL(Width(veh)); }
double Accel(const std::string& veh) { return TAEBP_SUMO_CALL(Accel(veh)); }
double MaxSpeed(const std::string& veh) { return TAEBP_SUMO_CALL(MaxSpeed(veh)); }
double SpeedFactor(const std::string& veh) { return TAEBP_SUMO_CALL(SpeedFactor(veh)); }
int RouteIndex(const std::string& veh) { return TAEBP_SUMO_CALL(RouteIndex(veh)); }
std::vector<std::string> Route(const std::string& veh) { return TAEBP_SUMO_CALL(Route(veh)); }
void SetRoute(const std::string& veh, const std::vector<std::string>& edges) {
  TAEBP_SUMO_CALL(SetRoute(veh, edges));
}
void SetRouteID(const std::string& veh, const std::string& route) {
  TAEBP_SUMO_CALL(SetRouteID(veh, route));
}

#undef TAEBP_SUMO_CALL

namespace gui {
void SetSchema(const std::string& scheme) {
  RequireGui("setSchema");
  libtraci_backend::gui::SetSchema(kView, scheme);
}
void SetBoundary(XY min, XY max) {
  RequireGui("setBoundary");
  libtraci_backend::gui::SetBoundary(kView, min, max);
}
void Screenshot(const std::string& file, int width, int height) {
  RequireGui("screenshot");
  libtraci_backend::gui::Screenshot(kView, file, width, height);
}
}  // namespace gui

}  // namespace taebp::sumo
