// The sumo-gui backend of the adapter: the same calls as sumo_adapter.cc, over
// libtraci (a sumo-gui process, socket). Selected with
// sumo::SetBackend(Backend::kLibtraciGui); see sumo_adapter_impl.inc for why
// this is a second translation unit.
#include "sumo_adapter_backend.h"

#include <libsumo/libtraci.h>

#include <cstdio>
#include <iostream>
#include <sstream>
#include <utility>

#include <fcntl.h>
#include <unistd.h>

namespace taebp::sumo::libtraci_backend {
namespace S = ::libtraci;
#include "sumo_adapter_impl.inc"
}  // namespace taebp::sumo::libtraci_backend
