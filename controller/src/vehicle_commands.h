// Everything the controller commands of a vehicle, carrying out its
// junction's interception commands in SUMO:
// - Hold: keep it where it is (setSpeed 0);
// - the nudge: the AV creeps the drawn distance under speed mode 0 with
//   exact commanded speeds (CreepSpeed), and once it stands again the HV
//   reads the displacement SUMO reports (the logic's NudgeDone);
// - Release: an encounter vehicle drives on, with SUMO's right of way off
//   (a move of the game: GameMove, speed mode 55, car-following kept) or under
//   SUMO's own rules (a careful move: mode 31); watched until it has left the
//   junction (UpdateCrossing: the logic learns when it has entered the
//   junction and when it has left it), then SUMO's again;
// - HandBack: a third vehicle held for an encounter is SUMO's again;
// - Unblock: a vehicle SUMO keeps waiting inside the junction for a nudged AV
//   may pass it (speed mode 63: foes already in the junction disregarded)
//   until it has left the junction (UpdateUnblocked);
// - colours by state under colour_states (sumo-gui).
#pragma once

#include "run_state.h"

namespace taebp::control {

class VehicleCommands {
 public:
  VehicleCommands(RunState& s, junction::EncounterModel& model) : s_(s), model_(model) {}

  // Executes one command of junction j's logic.
  void Execute(JunctionState& j, const junction::Command& c);
  // Per step: nudges in progress, released vehicles leaving their junctions,
  // vehicles let past a nudged AV leaving theirs (SUMO's rules in full again).
  void UpdateNudges();
  void UpdateCrossing();
  void UpdateUnblocked();
  // Major-road HVs yielding (DC): their braking, step by step.
  void UpdateYields();
  // A released vehicle's rear left the junction (or it left the network
  // inside it): SUMO's rules again.
  void Clear(int h);
  void SetPaint(int h, Paint paint);

 private:
  void Hold(JunctionState& j, int h);
  void CountWait(JunctionState& j, const Vehicle& v);
  void Release(JunctionState& j, int h, int partner);
  void GameMove(Vehicle& v, int partner, const JunctionState& j);
  void StopIgnoring(Vehicle& v);
  void HandBack(JunctionState& j, int h);
  void Unblock(int h);
  void StartNudge(int h, double distance, double duration);
  void Cruise(JunctionState& j, int h, int movement, double speed, int partner);
  void Yield(int h, double decel, double delay);
  void StopYield(int h);
  void YieldStep(Vehicle& v);
  void FinishNudge(int h, double observed);
  bool ClearedJunction(const Vehicle& v, const std::string& lane);

  RunState& s_;
  junction::EncounterModel& model_;
};

}  // namespace taebp::control
