// Running SUMO's command-line tools (netconvert, netgenerate, python3) from
// the scenario builder. Private to scenario/.
#pragma once

#include <string>
#include <vector>

namespace taebp::scenario_internal {

// Runs a program (no shell) with stdout/stderr appended to `log`; returns its
// exit code (-1 if it could not run or was killed).
int RunProgram(const std::vector<std::string>& args, const std::string& log);

// The last lines of a log file, for error messages.
std::string LogTail(const std::string& log, int lines = 5);

}  // namespace taebp::scenario_internal
