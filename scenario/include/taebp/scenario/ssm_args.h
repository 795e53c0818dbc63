// SUMO's command-line options for scenario.outputs.ssm (docs/ssm.md): the SSM
// device on every vehicle, the configured measures and thresholds, one output
// file. The same options under every policy, sumo_native included.
#pragma once

#include "taebp/config/config.h"

#include <string>
#include <vector>

namespace taebp {

// The options equipping every vehicle with SUMO's SSM device writing `file`
// (measures and thresholds always explicit: SUMO 1.15 warns once per vehicle
// when they are left out).
std::vector<std::string> SsmSumoArgs(const SsmConfig& ssm, const std::string& file);

// What is known to make SUMO 1.15 abort with the SSM device on (for the
// message when it does; Scenario::abort_hint).
std::string SsmAbortHint();

}  // namespace taebp
