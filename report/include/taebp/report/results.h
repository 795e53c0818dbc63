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
  std::string junction;     // SUMO junction id
  std::string av, hv;
  std::string av_movement, hv_movement;  // "from_lane>to_lane" of each vehicle's link
  char av_dir = 's', hv_dir = 's';       // SUMO link directions (s, l, r, ...)
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

// A controlled junction's totals over the measured time (after the warm-up).
struct ApproachStats {
  std::string lane;          // the incoming lane
  double queue_max = 0;      // halting vehicles (< 0.1 m/s) on the lane, sampled each second
  double queue_sum = 0;
  long samples = 0;
};
struct JunctionRun {
  std::string id;
  std::string type;           // as SUMO ran it (allway_stop, priority_stop)
  std::string original_type;  // in the user's network
  std::string rule;           // all_way_stop, two_way_stop
  long crossings_av = 0, crossings_hv = 0;  // vehicles through the junction
  long held = 0;                            // vehicles held at a stop line and released
  double wait_sum = 0, wait_max = 0;        // their waits at the line (s)
  std::vector<ApproachStats> approaches;
};
// Network-wide totals over the measured time (kind: network).
struct NetworkRun {
  long departed = 0, arrived = 0;    // vehicles that entered / left the network
  long pending_max = 0;              // most vehicles waiting to be inserted at once
  long vehicles_max = 0;             // most vehicles in the network at once (sampled each second)
  long pending_end = 0;              // waiting to be inserted at the end (demand not served)
  long trips = 0;                    // SUMO tripinfo records of the vehicles that arrived
  double duration_sum = 0, time_loss_sum = 0, waiting_time_sum = 0;  // their sums (s)
  double time_loss_max = 0;
};

// A junction where traffic stalled (scenario.stall_action: record).
struct StallRecord {
  std::string junction;
  double since = 0;     // last time a vehicle passed it
  double detected = 0;  // when the safety net noticed
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
  long held = 0;                          // vehicles held at a stop line and released
  double wait_sum = 0, wait_max = 0;      // their stop-line waits (s)
  long other_collisions = 0;              // collisions outside AV-HV encounters
  long teleports = 0;
  double longest_gap_without_crossing = 0;  // s, a deadlock indicator
  std::string sumo_version;
  double measured_seconds = 0;            // simulated time after the warm-up
  long nudges_unrealised = 0;             // nudges SUMO did not realise (nudge_check: count)
  // Encounters that formed after the warm-up, and those still in progress at
  // the end: encounters.size() == formed - unfinished (tools/soak checks it).
  long encounters_formed = 0, encounters_unfinished = 0;
  std::vector<JunctionRun> junctions;     // every controlled junction
  std::vector<StallRecord> stalls;        // scenario.stall_action: record
  NetworkRun network;
  std::string scenario_kind = "figure8";
  // SUMO's own outputs when the config asks for them (scenario.tripinfo_output,
  // summary_output): the files' text, written next to the results.
  std::string sumo_tripinfo_xml, sumo_summary_xml;
};

}  // namespace taebp
