// Which junctions of a network the controller takes over
// (scenario.junctions: ids, types, exclude, max_speed, min_arms) and the stop
// type each gets. Private to scenario/.
#pragma once

#include "taebp/config/config.h"
#include "taebp/scenario/net_file.h"
#include "taebp/scenario/scenario.h"

#include <string>

namespace taebp::scenario_internal {

// The stop-controlled SUMO type a junction of `type` becomes under `sel`
// (allway_stop or priority_stop), "" for a type the rules do not cover.
std::string StopType(const std::string& type, const JunctionSelection& sel);

// Appends the selected junctions of `net` to s->junctions; throws a
// ConfigError naming the key for a listed id the net lacks, and, when nothing
// is selected, one saying what the net has and why each candidate was passed over.
void SelectJunctions(const ScenarioConfig& sc, const net::NetFile& net, Scenario* s);

// Turns the selected junctions of other types into stop-controlled ones with
// netconvert (a node patch: geometry unchanged) in s->scratch; s->net becomes
// the patched net. False when no junction changes type.
bool PatchJunctionTypes(Scenario* s);

}  // namespace taebp::scenario_internal
