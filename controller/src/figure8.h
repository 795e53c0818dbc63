// Every special case of the paper's figure-8 track, in one place. The track is
// two closed loops through one junction; its 16 vehicles are placed at the
// start and circulate for ever:
// - set-up: the AV and HV types, one lap route per starting edge, the
//   vehicles at their places (PlaceVehicles);
// - circulation: a vehicle on the last edge of its route switches to the lap
//   starting there, so it always reaches past the next stop line and nothing
//   accumulates however long the run (KeepCirculating);
// - watching: the centre is always near every vehicle (AddCentre);
// - keep clear: vehicles leave a loop only through the centre, so every
//   vehicle headed into a loop counts as if queued at its end (ExitHasRoom);
// - the game: its crossing is always the paper's game (no premise check);
// - stalls: free flow crosses at least once per loop, so the default stall
//   limit is a lap and a minute, and the advice names the track's length.
// A network run has none of these (IsFigure8 false).
#pragma once

#include "run_state.h"

#include <string>
#include <vector>

namespace taebp::control::figure8 {

bool IsFigure8(const RunState& s);
void PlaceVehicles(RunState& s);
// Called after CountProgress for the vehicle's position this step (its route
// fully counted), so the new lap starts with nothing of the old one owed.
void KeepCirculating(RunState& s, int h);
void AddCentre(const RunState& s, std::vector<int>* near);
// Keep clear on a closed loop: the exit's lanes hold `inflight` vehicles
// headed there and those on them; room for one more of vehicle `h`'s size?
bool ExitHasRoom(RunState& s, const Exit& exit, long inflight, int h);
// The stall limit without scenario's own, and the advice a stall message ends
// with (a network's where the track has no loop length).
double DefaultStallLimit(const RunState& s);
std::string StallAdvice(const RunState& s);

}  // namespace taebp::control::figure8
