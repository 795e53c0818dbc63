// What SUMO shows at a controlled junction's stop lines, for its
// interception logic (junction/interception.h):
// - Watched: a junction is looked at in a step only while an AV and an HV may
//   both be at its lines (route_progress.h), or while its logic is busy;
// - Observe: the front vehicles of its stop-controlled lanes that wait at
//   their lines (front within kAtLine, below kSlow) or are coming to a stop
//   there (front within scenario.meeting_distance);
// - StopLineEnvironment: the logic's questions about the world (is a
//   vehicle's way through the junction clear, does a vehicle stand, has its exit room, is the
//   major road clear, is a vehicle's front past its line, has one passed the
//   other's way).
#pragma once

#include "run_state.h"

namespace taebp::control {

constexpr double kAtLine = 1.0;   // m: a front this near the lane end is at the line
constexpr double kSlow = 0.5;     // m/s: a front at its line slower than this waits there
constexpr double kStopGap = 0.1;  // m: SUMO halts a front this far before the lane end

// Is junction `j` looked at this step? On leaving that, what it saw is forgotten.
bool Watched(RunState& s, JunctionState& j);
// Fills j.at_line with SUMO's view of its stop lines this step. A lane is
// read only from the first step at which a vehicle can be within reach of a
// meeting at its line (an empty lane: its length away; else its front's gap),
// driving at its speed limit times the largest speed factor seen; lanes of
// edges with several lanes every step (a vehicle may change into them ahead
// of their front). So the per-step work is in proportion to what waits at,
// or comes to, the stop lines.
void Observe(RunState& s, JunctionState& j);
// scenario.major_road, two-way stops: fills j.major with the HVs at the front
// of the major approach lanes, driven by SUMO, moving towards the line, on a
// movement with the right of way over every foe (SUMO's 'M' links; only
// while an AV waits at a minor line here: nothing is read otherwise).
void ObserveMajor(RunState& s, JunctionState& j);
// A vehicle departed onto `edge`: its approaches are looked at again at once.
void ApproachDeparture(RunState& s, const std::string& edge);
// A vehicle's speed factor: a larger one than any before makes every lane be
// looked at again.
void SpeedFactorSeen(RunState& s, double factor);

class StopLineEnvironment : public junction::Environment {
 public:
  StopLineEnvironment(RunState& s, const JunctionState& j);
  bool WayClear(int vehicle, int partner) override;
  bool WayClearOfStarters(int vehicle, int partner) override;
  bool Standing(int vehicle) override;
  bool ExitHasRoom(int movement, int vehicle) override;
  bool MajorClear(int movement) override;
  bool MajorClearBut(int movement, int hv, int hv_movement, double extra) override;
  bool PastLine(int vehicle) override;
  bool Passed(int first, int second) override;
  std::vector<int> Unblockable(int vehicle, int partner) override;
  std::vector<int> UnblockableStarters(int vehicle, int partner) override;

 private:
  bool WayClearAgainst(int vehicle, int partner, bool starters);
  std::vector<int> UnblockableAgainst(int vehicle, int partner, bool starters);
  // A vehicle inside the junction: its slot, its movement, where it is.
  struct Inside {
    int vehicle = -1;  // -1: not one the controller knows
    int movement = -1;
    junction::Mover mover;  // its front where it is now
    bool still = false;
  };
  // Every vehicle on an internal lane of this junction (read once: the
  // environment lives for one junction's step, in which SUMO does not move).
  const std::vector<Inside>& VehiclesInside();
  // The vehicle's path through the junction with its front where it is now.
  junction::Mover MoverNow(int vehicle);
  // An AV nudged past its line stands here on a movement in conflict with
  // `movement` (MajorClear).
  bool NudgedAvInConflictWith(int movement);
  // The front vehicle of `lane`, feeding major movement `k`, may enter
  // within `gap` s (MajorClear, MajorClearBut).
  bool MajorComes(int k, const std::string& lane, double offset, double gap);

  RunState& s_;
  const JunctionInfo& info_;
  std::optional<std::vector<Inside>> inside_;
};

}  // namespace taebp::control
