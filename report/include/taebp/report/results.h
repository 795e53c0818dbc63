// What a run produced, as plain data: one record per AV-HV encounter and the
// per-policy totals. The controller fills them; report/ turns them into files.
#pragma once

#include "taebp/persuasion/outcomes.h"
#include "taebp/report/ssm.h"

#include <limits>
#include <memory>
#include <algorithm>
#include <string>
#include <vector>

namespace taebp {

class SampleSpool;  // report/sample_spool.h

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();  // an empty cell

// What a run beyond the paper adds to an encounter (dynamic trust, noise,
// learned trust, population_mean): written as extra encounters.csv columns
// only by such runs. NaN / empty: not applicable to the policy.
struct BeyondEncounter {
  double design_trust = kNoValue;    // theta_hat of this encounter's design
  double scheme_b = 0;               // its P(nudge | Stop)
  double reading = 0;                // what the HV read: clamp(observed + bias + noise, 0, s_max)
  double trust_after = 0;            // the HV's trust after the encounter (hv_trust: before)
  std::string outcome;               // nudge_go | nudge_stop | still_stop | still_go | collision
  double quality = kNoValue;         // q of the outcome (trust dynamics)
  double oracle_dc = 0, oracle_collision = 0;  // TA-EBP for the HV's exact trust, same noise
  double regret = 0;                 // (oracle_dc - theory_dc) + r (theory_collision - oracle_collision)
  // ta_ebp_learned
  std::string mode;                  // design | probe | fallback
  double risk_level = kNoValue;      // eps of this encounter
  double failure_probability = kNoValue;  // posterior P(the nudge does not persuade)
  double belief_lower = kNoValue, belief_upper = kNoValue;  // [L, U) before the encounter
  std::string observation;           // narrowed | consistent | uninformative | contradiction
};

// A nudge is realised when SUMO's reported displacement d satisfies
// s <= d <= s + kNudgeTolerance (the controller aims at s + kNudgeOvershoot).
inline constexpr double kNudgeTolerance = 1e-3;  // m
inline constexpr double kNudgeOvershoot = 1e-6;  // m

// Is an AV-HV meeting on a network the paper's game (README "Only meetings
// that are the game")? kHolds: both proceeding collides on the junction's
// geometry and the AV waiting, nudged or not, is out of the HV's way. Not
// the game: kNoCollision (both proceeding would not collide), kUncertainMerge
// (a merge whose outcome depends on SUMO's car following), kNudgeInHvWay (the
// AV standing nudged is in the way of the HV driving recklessly). Recorded at
// a major-road HV's decision only, kGrazing: the verdict turns with the HV's
// front moved 0.5 m either way (a grazing pass SUMO's check and the
// prediction's boxes may judge differently), so SUMO's check is held to neither.
enum class Premise { kHolds, kNoCollision, kUncertainMerge, kNudgeInHvWay, kGrazing };
const char* ToString(Premise p);

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
  // Both proceeding would collide on the junction's geometry (network
  // scenarios: the meeting is the paper's game; conflict_geometry.h).
  bool both_proceed_collides = true;
  Premise premise = Premise::kHolds;  // network scenarios
  // SUMO reported a collision between the two after one of them had been
  // handed back to SUMO's rules (its junction model, not a move of the game:
  // not in `collision`).
  bool collision_after_handback = false;
  double decided_at = 0;    // when the HV decided (after the nudge)
  // The major-road encounter (scenario.major_road: the HV approached on the
  // major road of a two-way stop); else both stopped at lines.
  bool major_road = false;
  double theory_dc = 0;         // library prediction for this AV-HV pair's design and HV
  double theory_collision = 0;
  // scenario.outputs.ssm: the worst surrogate measures between this game's AV
  // and HV over the game's window (report/ssm.h SsmPair; NaN: none logged).
  SsmPair ssm;
  BeyondEncounter beyond;
};

// One collision SUMO reported after the warm-up (collisions.csv), each
// episode once (the step it started). The controller records what it saw;
// report/ says which count it is in (CollisionsCsv: the encounters' rows).
struct CollisionRecord {
  double time = 0;            // simulated time SUMO reported it (s)
  std::string lane;           // where (SUMO's lane; empty when SUMO gave none)
  double pos = 0;             // m along the lane
  std::string type;           // SUMO's collision type (collision, frontal, junction, ...)
  std::string collider, victim;
  bool collider_av = false, victim_av = false;
  // In a game: part of an AV-HV encounter formed and not yet recorded.
  bool collider_in_game = false, victim_in_game = false;
  // The two are one encounter's AV and HV (that encounter's collision).
  bool encounter_pair = false;
  // Not that pair, and one of the two was making a move of the game (released
  // with SUMO's right of way off): other_collisions_game_move.
  bool game_move = false;
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
  // Movement pairs on which an AV and an HV can ever meet as a game under the
  // run's settings (junction::GamePairs; the same under every policy): 0, no
  // game can form here whatever the traffic.
  int game_pairs = 0;
  long crossings_av = 0, crossings_hv = 0;  // vehicles through the junction
  long held = 0;                            // vehicles held at a stop line and released
  double wait_sum = 0, wait_max = 0;        // their waits at the line (s)
  long held_av = 0;                         // of those, AVs
  double wait_sum_av = 0;
  // AV-HV meetings on conflicting movements where both proceeding would not
  // collide (a merge the AV leads, ...): not the paper's game, they went by
  // arrival (scenario.encounter_pairs: colliding).
  long meetings_not_game = 0;
  // AV-HV meetings whose premise cannot be predicted (Premise
  // kUncertainMerge, kNudgeInHvWay): not the game either.
  long meetings_unpredictable = 0;
  // Meetings whose arriving partner never came to its line (the waiting one,
  // held for it, went back to SUMO; no game was drawn).
  long meetings_abandoned = 0;
  // The longest time over the measured period in which no vehicle passed
  // this junction (s; from the warm-up's end or the last crossing to the next
  // crossing or the run's end): a deadlock here, or a quiet junction.
  double longest_gap_without_crossing = 0;
  std::vector<ApproachStats> approaches;
};
// Network-wide totals over the measured time (kind: network).
struct NetworkRun {
  long departed = 0, arrived = 0;    // vehicles that entered / left the network
  long pending_max = 0;              // most vehicles waiting to be inserted at once
  long vehicles_max = 0;             // most vehicles in the network at once (sampled each second)
  long pending_end = 0;              // waiting to be inserted at the end (demand not served)
  long pending_start = -1;           // waiting to be inserted at the warm-up's last step (-1: none)
  // The demand offered in the measured time: the vehicles due to depart in
  // it (departed + still waiting at the end - already waiting at its start).
  long Offered() const { return departed + pending_end - std::max(0L, pending_start); }
  // SUMO's tripinfo records (--tripinfo-output.write-unfinished) of the
  // vehicles that departed after the warm-up, finished or not: a trip still
  // in the network at the end (arrival -1) counts with its time so far.
  long trips = 0;
  long trips_unfinished = 0;         // of those, still in the network at the end
  double duration_sum = 0, time_loss_sum = 0, waiting_time_sum = 0;  // their sums (s)
  long trips_av = 0;                 // of the trips, AVs' (scenario.av_types / av_share)
  double time_loss_sum_av = 0, waiting_time_sum_av = 0;
  double time_loss_max = 0;
};

// A junction where traffic stalled (scenario.stall_action: record, or the
// stall that stopped a run under stall_action: error).
struct StallRecord {
  std::string junction;
  double since = 0;     // last time a vehicle passed it
  double detected = 0;  // when the safety net noticed
};

// Beyond the paper: the population's state over time and the run's totals.
struct TimeSample {  // timeseries.csv: one row per outputs.interval
  double time = 0;
  long hvs = 0;                       // HVs in the network
  double mean_trust = 0;              // their mean current trust
  double mean_field_trust = kNoValue; // the mean-field prediction for the same HVs (dynamics)
  long encounters = 0, dc = 0, collisions = 0, nudges = 0, failures = 0;  // cumulative
  double theory_dc = 0, theory_collisions = 0;  // cumulative sums of the per-encounter theory
  double oracle_dc = 0, oracle_collisions = 0;  // ... of the oracle's
  double regret = 0, expected_failures = 0;
};
struct HvSample {  // hv_trust.csv: one row per HV in the network per outputs.interval
  double time = 0;
  std::string hv;
  double trust = 0;                  // current trust (the HV's own)
  long encounters = 0;               // its encounters so far
  double belief_lower = kNoValue, belief_upper = kNoValue, belief_mean = kNoValue;
  double design_trust = kNoValue;    // ta_ebp_learned: what its next design would assume
  long observations = 0, contradictions = 0;
};
struct TrustEquilibriumRecord {
  double theta = 0;
  std::string kind;  // root | jump | boundary
  bool stable = false;
};
struct BeyondRun {
  bool on = false;  // the config is beyond the paper (ExperimentConfig::BeyondPaper)
  // timeseries.csv's and hv_trust.csv's rows of this run, on disk
  // (report/sample_spool.h); null when the run sampled nothing.
  std::shared_ptr<const SampleSpool> samples;
  // The HVs' trust moves during the run (model.trust_dynamics or
  // model.experience): the table's mean trust start / end row.
  bool trust_moves = false;
  double initial_mean_trust = 0;  // mean drawn trust of every HV registered
  double final_mean_trust = 0;    // mean trust of the HVs in the network at the end
  long hvs = 0;  // HVs registered
  // Trust dynamics (empty when off or when no closed-form long run applies).
  bool long_run = false;
  std::string design_rule;  // e.g. "ta_ebp tracking", "ta_ebp for 0.6"
  std::vector<TrustEquilibriumRecord> equilibria;  // for the population's mean initial state
  double expected_long_run_mean = kNoValue;        // over the trust distribution, each HV's attractor
  double long_run_dc = kNoValue, long_run_collision = kNoValue;  // theory at those attractors
  double final_mean_field = kNoValue;
  // model.experience: long_run_dc / long_run_collision hold the learned
  // beliefs' long run (persuasion/experience.h).
  bool experience = false;
  // Learned trust.
  bool learning = false;
  long hvs_met = 0, observations = 0, contradictions = 0, probes = 0;
  double final_mean_abs_error = kNoValue;  // |posterior mean - trust| over the HVs met
  // Perception noise: the population design.
  bool noise = false;
  std::string noise_kind, noise_design, noise_status;
  double noise_scale = 0, noise_bias = 0, noise_delta = 0;
  double noise_nudge = 0, noise_b = 0, noise_persuasion = 0, noise_density_ratio = 0;
  bool noise_credible = true;
  // The oracle (TA-EBP for the exact trust) over the trust distribution.
  persuasion::PredictedOutcome oracle;
};

// Paired games (scenario.paired, docs/paired.md): one game of a run played
// from the state it formed in under one game policy (a branch of the run,
// in a forked process). paired.csv's rows.
struct PairedRecord {
  std::string game;      // "HOST-K": the K-th paired game of the run of policy HOST
  std::string host;      // the policy of the run the game formed in
  std::string policy;    // the policy the branch played it under
  double time = 0;       // when it formed (s)
  std::string junction, av, hv;
  // ok: the game finished (its outcome below; a vehicle not past the
  // junction when the window or the run ended has no clearing time);
  // unfinished: the window (kPairedWindow) or the run ended before the game
  // did; failed: the branch ended abnormally (`error`).
  std::string status;
  std::string error;
  bool intent_go = false;
  double nudge = 0;       // commanded nudge (m)
  bool hv_dc = false, av_first = false, collision = false;
  double decided_at = kNoValue;  // when the HV decided (s)
  // Seconds from the game's formation until each vehicle reached the edge
  // after the junction (NaN: not within the window): the pair's delay.
  double av_clear = kNoValue, hv_clear = kNoValue;
  // Collisions between a game move and a third vehicle during the window.
  long third_collisions = 0;
  // The pair's surrogate safety measures over the window, from both
  // vehicles' positions each step (junction/pair_surrogates.h; NaN: none).
  double pair_min_ttc = kNoValue, pair_min_pet = kNoValue;
  double hv_trust = 0, theory_dc = 0, theory_collision = 0;
};
// How long a branch follows its game at most (s after it formed).
inline constexpr double kPairedWindow = 120;

struct PolicyRun {
  std::string policy;
  // SUMO's warnings in this policy's simulation: all, SUMO's collision
  // reports among them, the first few others (text without "Warning: ").
  long sumo_warnings = 0, sumo_collision_warnings = 0;
  std::vector<std::string> sumo_warnings_first;
  persuasion::CommittedScheme scheme;     // the design for the population's theta_hat
  // Library prediction: expectation over the trust distribution of the per-HV
  // predictions (for a fixed trust, the prediction itself).
  persuasion::PredictedOutcome theory;
  std::vector<double> hv_trust;           // each HV's drawn theta, in HV order
  std::vector<EncounterRecord> encounters;
  double simulated_seconds = 0;
  // Where this policy's wall time went (timing.json only, never compared):
  // SUMO's start and the controller's set-up; SUMO's steps
  // (Simulation::step); the controller's steps (what it reads, decides and
  // commands between two of SUMO's).
  double wall_seconds_start = 0, wall_seconds_sumo_steps = 0, wall_seconds_controller_steps = 0;
  long crossings_av = 0, crossings_hv = 0;
  long held = 0;                          // vehicles held at a stop line and released
  double wait_sum = 0, wait_max = 0;      // their stop-line waits (s)
  long held_av = 0;                       // of those, AVs
  double wait_sum_av = 0;
  long other_collisions = 0;              // collisions outside AV-HV encounters
  // ... of which one vehicle was an encounter's, released with SUMO's right
  // of way off (the HV driving recklessly, the AV that goes) and the other a
  // third vehicle (at a two-way stop: the major road)
  long other_collisions_game_move = 0;
  std::vector<CollisionRecord> collisions;  // every SUMO collision after the warm-up
  // Vehicles SUMO kept waiting inside a junction for a nudged AV, in the way
  // of a move of the game, that the controller let past it (after the warm-up)
  long unblocked = 0;
  long teleports = 0;
  double longest_gap_without_crossing = 0;  // s, a deadlock indicator
  std::string sumo_version;
  double measured_seconds = 0;            // simulated time after the warm-up
  long nudges_unrealised = 0;             // nudges SUMO did not realise (nudge_check: count)
  // Encounters that formed after the warm-up, and those still in progress at
  // the end: encounters.size() == formed - unfinished (tools/soak checks it).
  long encounters_formed = 0, encounters_unfinished = 0;
  std::vector<JunctionRun> junctions;     // every controlled junction
  std::vector<StallRecord> stalls;        // every stall found (the run is "stalled")
  // Under scenario.stall_action: error, the stall that stopped this run (its
  // message; the run's figures are up to then, its last stall in `stalls`).
  // Empty: the run went to its end.
  std::string stall_error;
  NetworkRun network;
  std::string scenario_kind = "figure8";
  // SUMO's own outputs when the config asks for them (scenario.tripinfo_output,
  // summary_output): the files' text, written next to the results.
  std::string sumo_tripinfo_xml, sumo_summary_xml;
  // SUMO's outputs of this policy (scenario.outputs and those of the user's
  // additional files): (name in the run folder, "POLICY/NAME"; the file SUMO
  // wrote, in the scenario's scratch folder).
  std::vector<std::pair<std::string, std::string>> sumo_output_files;
  BeyondRun beyond;
  SsmRun ssm;  // scenario.outputs.ssm: SUMO's SSM conflicts (report/ssm.h)
  // scenario.paired: this run's games played under each game policy.
  std::vector<PairedRecord> paired;
};

}  // namespace taebp
