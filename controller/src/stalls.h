// The safety net of every policy, sumo_native included: a junction with
// vehicles halted on its incoming lanes through which no vehicle has passed
// for the stall limit (route progress, read each second) is stalled. Each
// stall episode is recorded once (PolicyRun::stalls); under
// scenario.stall_action: error a controller policy's first stall throws
// StallError naming the junction, what waits there and who holds it, once
// every junction stalled by then is recorded. SUMO's own logic is the
// baseline: its stalls are recorded, never an error.
#pragma once

#include "run_state.h"

#include <string>

namespace taebp::control {

// Once a second: which junctions have vehicles halted on their incoming lanes
// (an idle junction is not stalled: the clock starts when vehicles begin to wait).
void SampleWaiting(RunState& s);
// Approach `a`'s halting vehicles at this step, read from SUMO once per step
// however often asked (SampleWaiting and the queue samples share it).
int ApproachHalting(RunState& s, int a);
// Throws StallError (stall_action: error, a controller policy).
void CheckStalls(RunState& s);

}  // namespace taebp::control
