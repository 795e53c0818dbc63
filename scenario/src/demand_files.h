// The demand's files of a network scenario, checked before SUMO sees them.
#pragma once

#include "taebp/config/config.h"
#include "taebp/scenario/scenario.h"

namespace taebp {

// Throws ConfigError naming the file for a route file that holds a SUMO
// network (<net>: a network given as scenario.routes) and, without
// scenario.demand, for route and additional files with no vehicle, trip,
// flow or person at all: SUMO would run either with exit 0 and nothing in
// the network. Files that do not parse are left to SUMO's own message.
void CheckDemandFiles(const ScenarioConfig& sc, const Scenario& s);

}  // namespace taebp
