// What a run produced, as plain data: one record per AV-HV encounter and the
// per-policy totals. The controller fills them; report/ turns them into files.
#pragma once

#include "taebp/persuasion/outcomes.h"

#include <string>
#include <vector>

namespace taebp {

// A nudge is realised when SUMO's reported displacement d satisfies
// s <= d <= s + kNudgeTolerance (the controller aims at s + kNudgeOvershoot).
inline constexpr double kNudgeTolerance = 1e-3;  // m
inline constexpr double kNudgeOvershoot = 1e-6;  // m

struct EncounterRecord {
  double time = 0;          // simulated time the encounter formed (s)
  std::string av, hv;
  bool intent_go = false;
  double commanded = 0;     // commanded nudge s (0: no nudge)
  double observed = 0;      // displacement SUMO reported when the HV decided
  double hv_trust = 0;      // the HV's true theta
  double posterior = 0;     // HV's p_theta(Go | observed)
  bool hv_dc = false;       // HV action: drive if clear (else drive recklessly)
  bool av_first = false;    // AV action: go first (else wait)
  bool collision = false;   // SUMO reported a collision between the two
  double decided_at = 0;    // when the HV decided (after the nudge)
  double theory_dc = 0;         // library prediction for this AV-HV pair's design and HV
  double theory_collision = 0;
};

struct PolicyRun {
  std::string policy;
  persuasion::CommittedScheme scheme;     // the design for the population's theta_hat
  // Library prediction: expectation over the trust distribution of the per-HV
  // predictions (for a fixed trust, the prediction itself).
  persuasion::PredictedOutcome theory;
  std::vector<double> hv_trust;           // each HV's drawn theta, in HV order
  std::vector<EncounterRecord> encounters;
  double simulated_seconds = 0;
  long crossings_av = 0, crossings_hv = 0;
  double wait_sum = 0, wait_max = 0;      // stop-line waits (s) over crossings
  long other_collisions = 0;              // collisions outside AV-HV encounters
  long teleports = 0;
  double longest_gap_without_crossing = 0;  // s, a deadlock indicator
  std::string sumo_version;
};

}  // namespace taebp
