// SUMO's outputs of one policy's run (policy_run.cc): where SUMO writes them
// and how they are read into the run once SUMO has closed them. Private to
// controller/src.
#pragma once

#include "taebp/config/config.h"
#include "taebp/report/results.h"
#include "taebp/scenario/scenario.h"

#include <filesystem>
#include <functional>
#include <string>

namespace taebp::control {

// The file SUMO's SSM device writes, copied to ssm.xml once the policy's
// simulation is closed: SUMO 1.15 keeps the names of the SSM files it created
// across simulations in one process and reopens (empties) them when the next
// one ends, so the policies run before the last would keep an empty file.
inline constexpr const char* kSsmSumoFile = ".ssm-sumo.xml";

// SUMO's tripinfo of one policy, in the scenario's scratch folder.
std::string TripinfoPath(const Scenario& scenario, const std::string& policy);

// SUMO's outputs of one policy (scenario.outputs, and those the user's
// additional files name) are written into scratch/<policy>/ and end up in
// the run folder as <policy>/NAME.
std::filesystem::path PolicyOutputDir(const Scenario& scenario, const std::string& policy);

// Reads SUMO's outputs of `policy` into `r` (needs the scenario's scratch
// folder; none: nothing): the output files (sumo_output_files), SSM
// (scenario.outputs.ssm: ssm.xml, per game), tripinfo (AVs as
// `departed_as_av` says) and the tripinfo and summary XML when asked for.
void ReadSumoOutputs(const ExperimentConfig& config, const Scenario& scenario,
                     const std::string& policy,
                     const std::function<bool(const std::string&)>& departed_as_av,
                     long ssm_device_warnings, PolicyRun* r);

}  // namespace taebp::control
