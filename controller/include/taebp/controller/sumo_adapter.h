// The one thin adapter around SUMO: which simulation runs (Sumo()) and how.
// Nothing else in the project includes a libsumo or libtraci header; what a
// call does and throws is in sumo_world.h (SumoSimulation), its one body in
// controller/src/sumo_adapter_impl.inc.
//
// Two backends with the same calls (SetBackend): libsumo, in process (the
// default and the fast path), and libtraci driving a sumo-gui process (for
// watching a run and for screenshots).
//
// libsumo runs one simulation per process: a second Start replaces the first.
// Sweeps therefore run simulations in separate processes, never threads.
#pragma once

#include "taebp/controller/sumo_world.h"

#include <string>
#include <vector>

namespace taebp {
namespace sumo {

enum class Backend {
  kLibsumo,      // in process (libsumo); the default
  kLibtraciGui,  // a sumo-gui process driven over a socket (libtraci)
};

// Selects the backend Sumo() returns from now on; throws SumoError while a
// simulation is loaded. With kLibtraciGui, Start runs "sumo-gui" in place of
// args[0] and appends "--start", "--quit-on-end" and `gui_args` (e.g.
// {"--delay", "100"}).
void SetBackend(Backend backend, std::vector<std::string> gui_args = {});
// The backend selected.
Backend CurrentBackend();

// SUMO 1.15's SSM device (scenario.outputs.ssm) asserts that two vehicles it
// saw inside their conflict area at once never leave it in the same step
// (MSDevice_SSM.cpp:1870); Debian builds SUMO with assertions on, so such a
// run aborted. Upstream's release builds (NDEBUG) have no assertion there and
// classify the encounter as both having left. The same for determinePET's
// check of the previous type of an encounter both have left
// (MSDevice_SSM.cpp:1172: a collided merge without a crossing point reaches it).
// This makes the SUMO library of
// this process do the same, after checking that its code is Debian 12's sumo
// 1.15.0 build byte for byte (sumo_ssm_release.cc; docs/ssm.md). Returns
// "applied" or why not (then the device may still abort).
std::string SsmReleaseBehaviour();

}  // namespace sumo

// This process's SUMO, under the backend selected (libsumo unless
// sumo::SetBackend said otherwise). A caller that keeps the reference (the
// network controller) keeps the backend it was made under.
SumoSimulation& Sumo();

}  // namespace taebp
