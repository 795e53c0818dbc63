// Where each vehicle is on its route: the controlled junctions it has passed
// (junction crossings, and the progress the stall check looks for) and those
// whose stop lines it may reach before the next sample (a junction is watched
// in a step only while an AV and an HV may both be at its lines, so a run
// without AVs or without HVs reads nothing per step).
#pragma once

#include "run_state.h"

#include <vector>

namespace taebp::control {

// Counts the controlled junctions vehicle `h` passed since the last count,
// its route index now being `new_pos`.
void CountProgress(RunState& s, int h, int new_pos);

// Which controlled junctions' stop lines the vehicle may reach before the
// next sample: those its route reaches within the farthest a vehicle drives
// in that time, counted from the end of its current edge (so the junction
// ending its current edge always counts). The figure-8's centre always.
void UpdateNear(RunState& s, int h);
void SetNear(RunState& s, int h, std::vector<int> near);

}  // namespace taebp::control
