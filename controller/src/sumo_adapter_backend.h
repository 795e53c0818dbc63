// Private to the adapter: what its two translation units share.
// sumo_adapter_impl.inc is compiled in namespace taebp::sumo::libsumo_backend
// (sumo_adapter.cc) and taebp::sumo::libtraci_backend
// (sumo_adapter_libtraci.cc); sumo_adapter.cc selects one (SetBackend, Sumo()).
#pragma once

#include "taebp/controller/sumo_adapter.h"
#include "taebp/base/number_text.h"

#include <string>
#include <vector>

namespace taebp::sumo {

namespace libsumo_backend {
SumoSimulation& Instance();
}
namespace libtraci_backend {
SumoSimulation& Instance();
}

// The backend's state, kept by sumo_adapter.cc.
const std::vector<std::string>& GuiArgs();  // appended to sumo-gui's command
void SetStarted(bool started);              // between a successful Start and Close

}  // namespace taebp::sumo
