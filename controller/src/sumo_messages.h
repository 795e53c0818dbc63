// SUMO's warnings during one policy's simulation (issue 17, item 4). libsumo
// prints them on this process's stderr; from construction to Finish() that
// stream goes to a temporary file, whose lines are then sorted: SUMO's
// "Warning: " lines are counted and kept (the first few), every other line
// (SUMO's errors, anything else written meanwhile) goes back to stderr as it
// was. Warnings that change the demand SUMO simulates (a route file not
// sorted by departure time, whose later vehicles SUMO drops; a vehicle
// without a valid route) are named apart, so that the run can fail on them.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace taebp::control {

struct SumoWarnings {
  long count = 0;            // every "Warning: " line
  long collisions = 0;       // of those, SUMO's collision reports (taebp counts collisions itself)
  // The SSM device's remarks (scenario.outputs.ssm): not counted above (the
  // device only observes; its "detected collision" is no collision report).
  long ssm = 0;
  std::vector<std::string> first;           // the first few others, without "Warning: "
  std::vector<std::string> demand_changed;  // those that change the demand (all of them)
};

// Patterns of SUMO 1.15 warnings after which SUMO runs another demand than
// the files hold.
const std::vector<std::string>& DemandChangingWarnings();

// Sorts SUMO's output: warnings into `into`, every other line into `rest`.
void SortSumoOutput(const std::string& text, SumoWarnings* into, std::string* rest);

// SUMO's error `message` during (or at the start of) a run of `policy`, made
// to name what to fix: the policy and, where SUMO names a vehicle, route or
// vehicle type, the input file that defines it (`files`: the route files,
// then the additional files, as SUMO was given them; one under
// `generated_dir` is scenario.demand's) or "not defined in any of FILES", and
// the usual fix (routes: randomTrips.py --validate or duarouter). E.g.
// "SUMO step failed: Vehicle '16' has no valid route. (policy ta_ebp;
// vehicle '16' is defined in routes.rou.xml; ...)".
std::string ExplainSumoError(const std::string& message, const std::string& policy,
                             const std::vector<std::string>& files,
                             const std::string& generated_dir = "");

class SumoMessages {
 public:
  static constexpr std::size_t kFirst = 5;
  SumoMessages();
  ~SumoMessages();  // (without Finish) puts stderr back, passing everything on
  SumoMessages(const SumoMessages&) = delete;
  SumoMessages& operator=(const SumoMessages&) = delete;

  // Puts stderr back; SUMO's warnings sorted, every other line passed on.
  SumoWarnings Finish();

  // For a handler of SUMO's abort: the file collecting stderr and the
  // descriptor of the real stderr (-1 when nothing is collected).
  int capture_fd() const { return file_ ? ::fileno(file_) : -1; }
  int real_stderr() const { return saved_; }

 private:
  std::string Restore();  // stderr back; what was captured
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

}  // namespace taebp::control
