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

namespace taebp {
namespace sumo {
namespace {

Backend g_backend = Backend::kLibsumo;
std::vector<std::string> g_gui_args;
bool g_started = false;  // between a successful Start and Close

}  // namespace

const std::vector<std::string>& GuiArgs() { return g_gui_args; }
void SetStarted(bool started) { g_started = started; }

Backend CurrentBackend() { return g_backend; }

void SetBackend(Backend backend, std::vector<std::string> gui_args) {
  if (g_started) throw SumoError("SUMO backend cannot change while a simulation is loaded");
  g_backend = backend;
  g_gui_args = std::move(gui_args);
  // libtraci writes to the socket without MSG_NOSIGNAL: when sumo-gui is gone
  // (window closed, bad option) the write must fail with an error we report,
  // not kill the process with SIGPIPE.
  if (backend == Backend::kLibtraciGui) std::signal(SIGPIPE, SIG_IGN);
}

}  // namespace sumo

SumoSimulation& Sumo() {
  return sumo::g_backend == sumo::Backend::kLibtraciGui ? sumo::libtraci_backend::Instance()
                                                        : sumo::libsumo_backend::Instance();
}

}  // namespace taebp
