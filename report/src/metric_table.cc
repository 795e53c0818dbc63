// The table of the result metrics (RunMetrics(), declared in metrics.h): one
// row per metric, in the order every file writes them; the parts below are
// that order cut into readable pieces (the game, traffic at the controlled
// junctions, the network's own counts, beyond the paper), SSM's rows last.
#include "taebp/report/metrics.h"

#include "taebp/config/policies.h"

#include "metric_facts.h"

#include <limits>
#include <vector>

namespace taebp {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr unsigned kP = kPolicyLevel;
constexpr unsigned kJ = kJunctionLevel;
constexpr unsigned kPJ = kPolicyLevel | kJunctionLevel;
using T = MetricType;
using S = MetricScope;

double D(long v) { return static_cast<double>(v); }
double Hours(const MetricFacts& f) { return f.run->measured_seconds / 3600.0; }
// A per-hour rate of a policy's count (count / hours, as taebp 0.1 wrote it).
double PolicyPerHour(const MetricFacts& f, long count) {
  const double h = Hours(f);
  return h > 0 ? count / h : 0.0;
}
long CrossingsAv(const MetricFacts& f) { return f.junction ? f.junction->crossings_av : f.run->crossings_av; }
long CrossingsHv(const MetricFacts& f) { return f.junction ? f.junction->crossings_hv : f.run->crossings_hv; }
long Held(const MetricFacts& f) { return f.junction ? f.junction->held : f.run->held; }
double WaitSum(const MetricFacts& f) { return f.junction ? f.junction->wait_sum : f.run->wait_sum; }
long HeldAv(const MetricFacts& f) { return f.junction ? f.junction->held_av : f.run->held_av; }
double WaitSumAv(const MetricFacts& f) {
  return f.junction ? f.junction->wait_sum_av : f.run->wait_sum_av;
}
double Mean(double sum, long n) { return n > 0 ? sum / n : kNaN; }
const NetworkRun& Net(const MetricFacts& f) { return f.run->network; }
double PerTrip(const MetricFacts& f, double sum) {
  return Net(f).trips ? sum / Net(f).trips : 0.0;
}
double PerEncounter(const MetricFacts& f, double sum) { return f.s.n ? sum / f.s.n : 0.0; }
double PerNudge(const MetricFacts& f, double sum) { return f.s.nudges ? sum / f.s.nudges : 0.0; }
double LastHourMean(const MetricFacts& f, double sum) {
  return f.last_hour.n ? sum / f.last_hour.n : 0.0;
}
const BeyondRun& B(const MetricFacts& f) { return f.run->beyond; }
double Dynamics(const MetricFacts& f, double v) { return B(f).long_run ? v : kNaN; }
// The long run of dynamic trust or of experience (model.experience).
double LongRun(const MetricFacts& f, double v) {
  return B(f).long_run || B(f).experience ? v : kNaN;
}
double Learning(const MetricFacts& f, double v) { return B(f).learning ? v : kNaN; }

// clang-format off
std::vector<Metric> GameMetrics() {
  return {
    // The game, per AV-HV encounter.
    {"encounters", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "AV-HV encounters played as the paper's game (after the warm-up)",
     [](const MetricFacts& f) { return D(f.s.n); }},
    {"collisions", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "encounters in which SUMO reported the AV and the HV colliding",
     [](const MetricFacts& f) { return D(f.s.collisions); }},
    {"collision_rate", T::kReal, "", kPJ, S::kAll, Pool::kRate, "collisions", "encounters",
     "collision_rate_ci95", "collisions per encounter",
     [](const MetricFacts& f) { return Rate(f.s.collisions, f.s.n); }},
    {"collisions_total", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "every collision a move of the game took part in: the encounters' AV-HV collisions plus "
     "other_collisions_game_move (the headline beside collision_rate)",
     [](const MetricFacts& f) { return D(f.s.collisions + f.run->other_collisions_game_move); }},
    {"dc", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "encounters in which the HV chose Drive if Clear",
     [](const MetricFacts& f) { return D(f.s.dc); }},
    {"dc_rate", T::kReal, "", kPJ, S::kAll, Pool::kRate, "dc", "encounters", "dc_rate_ci95",
     "Drive-if-Clear choices per encounter",
     [](const MetricFacts& f) { return Rate(f.s.dc, f.s.n); }},
    {"theory_collision_rate", T::kReal, "", kP, S::kAll, Pool::kPrediction, nullptr, "encounters",
     "theory.collision_rate",
     "the library's predicted collision rate (over the trust distribution)",
     [](const MetricFacts& f) { return f.run->theory.collision_rate; }},
    {"theory_dc_rate", T::kReal, "", kP, S::kAll, Pool::kPrediction, nullptr, "encounters",
     "theory.dc_rate", "the library's predicted DC rate (over the trust distribution)",
     [](const MetricFacts& f) { return f.run->theory.dc_rate; }},
    {"theory_nudge_rate", T::kReal, "", kP, S::kAll, Pool::kPrediction, nullptr, "encounters",
     "theory.nudge_rate", "the library's predicted share of encounters with a nudge",
     [](const MetricFacts& f) { return f.run->theory.nudge_rate; }},
    {"theory_av_first_rate", T::kReal, "", kP, S::kAll, Pool::kPrediction, nullptr, "encounters",
     "theory.av_first_rate", "the library's predicted share of encounters the AV crosses first",
     [](const MetricFacts& f) { return f.run->theory.av_first_rate; }},
    {"theory_given_hvs_collision_rate", T::kReal, "", kPJ, S::kAll, Pool::kWeighted, nullptr,
     "encounters", "theory_given_hvs.collision_rate",
     "mean predicted collision rate of the HVs actually met (the fair comparison for a drawn "
     "trust)",
     [](const MetricFacts& f) { return PerEncounter(f, f.s.theory_collision_sum); }},
    {"theory_given_hvs_dc_rate", T::kReal, "", kPJ, S::kAll, Pool::kWeighted, nullptr,
     "encounters", "theory_given_hvs.dc_rate (junctions.csv: theory_dc_rate)",
     "mean predicted DC rate of the HVs actually met",
     [](const MetricFacts& f) { return PerEncounter(f, f.s.theory_dc_sum); }},
    {"nudges", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr, "nudges.count",
     "encounters in which the AV nudged",
     [](const MetricFacts& f) { return D(f.s.nudges); }},
    {"nudge_mean_commanded", T::kReal, "m", kP, S::kAll, Pool::kMean, nullptr, "nudges",
     "nudges.mean_commanded", "mean nudge the controller commanded",
     [](const MetricFacts& f) { return PerNudge(f, f.s.commanded_sum); }},
    {"nudge_mean_observed", T::kReal, "m", kP, S::kAll, Pool::kMean, nullptr, "nudges",
     "nudges.mean_observed", "mean displacement SUMO reported when the HV decided",
     [](const MetricFacts& f) { return PerNudge(f, f.s.observed_sum); }},
    {"nudge_max_abs_error", T::kReal, "m", kP, S::kAll, Pool::kMax, nullptr, nullptr,
     "nudges.max_abs_error", "largest absolute difference between observed and commanded nudge",
     [](const MetricFacts& f) { return f.s.max_abs_error; }},
    {"nudge_min_observed_minus_commanded", T::kReal, "m", kP, S::kAll, Pool::kNone, nullptr,
     nullptr, "nudges.min_observed_minus_commanded",
     "smallest observed - commanded nudge (negative: SUMO fell short)",
     [](const MetricFacts& f) { return f.s.min_excess; }},
    {"nudge_tolerance", T::kReal, "m", kP, S::kAll, Pool::kNone, nullptr, nullptr,
     "nudges.tolerance", "how far a realised nudge may miss the commanded one",
     [](const MetricFacts&) { return kNudgeTolerance; }},
    {"nudges_unrealised", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "nudges SUMO did not realise within the tolerance",
     [](const MetricFacts& f) { return D(f.run->nudges_unrealised); }},
    {"encounters_formed", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "encounters that formed after the warm-up (= encounters + encounters_unfinished)",
     [](const MetricFacts& f) { return D(f.run->encounters_formed); }},
  };
}

std::vector<Metric> UnfinishedGameMetrics() {
  return {
    {"encounters_unfinished", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "encounters still in progress at the end",
     [](const MetricFacts& f) { return D(f.run->encounters_unfinished); }},
    {"encounters_per_hour", T::kReal, "1/h", kPJ, S::kAll, Pool::kMean, nullptr, nullptr,
     nullptr,
     "AV-HV encounters per measured hour (none for a policy that plays no game)",
     [](const MetricFacts& f) {
       return PlaysGame(f.run->policy) ? PerHour(D(f.s.n), f.run->measured_seconds) : kNaN;
     }},
  };
}

std::vector<Metric> JunctionTrafficMetrics() {
  return {
    // Traffic at the controlled junctions.
    {"crossings_av", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, "crossings.av",
     "AVs through the controlled junctions",
     [](const MetricFacts& f) { return D(CrossingsAv(f)); }},
    {"crossings_hv", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, "crossings.hv",
     "HVs through the controlled junctions",
     [](const MetricFacts& f) { return D(CrossingsHv(f)); }},
    {"crossings_all", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, "crossings.all",
     "vehicles through the controlled junctions",
     [](const MetricFacts& f) { return D(CrossingsAv(f) + CrossingsHv(f)); }},
    {"throughput_av", T::kReal, "veh/h", kP, S::kAll, Pool::kMean, nullptr, nullptr,
     "throughput_per_hour.av", "AV junction crossings per hour",
     [](const MetricFacts& f) { return PolicyPerHour(f, CrossingsAv(f)); }},
    {"throughput_hv", T::kReal, "veh/h", kP, S::kAll, Pool::kMean, nullptr, nullptr,
     "throughput_per_hour.hv", "HV junction crossings per hour",
     [](const MetricFacts& f) { return PolicyPerHour(f, CrossingsHv(f)); }},
    {"throughput_all", T::kReal, "veh/h", kPJ, S::kAll, Pool::kMean, nullptr, nullptr,
     "throughput_per_hour.all (junctions: throughput_per_hour)", "junction crossings per hour",
     [](const MetricFacts& f) {
       const long all = CrossingsAv(f) + CrossingsHv(f);
       return f.junction ? PerHour(D(all), f.run->measured_seconds) : PolicyPerHour(f, all);
     }},
    {"held", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "vehicles the controller held at a stop line and released",
     [](const MetricFacts& f) { return D(Held(f)); }},
    {"wait_mean", T::kReal, "s", kPJ, S::kAll, Pool::kMean, nullptr, "held",
     "wait_at_stop_line.mean", "mean wait of the held vehicles at the stop line",
     [](const MetricFacts& f) { return Held(f) > 0 ? WaitSum(f) / Held(f) : kNaN; }},
    {"wait_max", T::kReal, "s", kPJ, S::kAll, Pool::kMax, nullptr, nullptr,
     "wait_at_stop_line.max", "longest wait of a held vehicle at the stop line",
     [](const MetricFacts& f) { return f.junction ? f.junction->wait_max : f.run->wait_max; }},
    {"held_av", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "of the held vehicles, AVs",
     [](const MetricFacts& f) { return D(HeldAv(f)); }},
    {"held_hv", T::kCount, "", kPJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "of the held vehicles, HVs",
     [](const MetricFacts& f) { return D(Held(f) - HeldAv(f)); }},
    {"wait_mean_av", T::kReal, "s", kPJ, S::kAll, Pool::kMean, nullptr, "held_av", nullptr,
     "mean wait of the held AVs at the stop line",
     [](const MetricFacts& f) { return Mean(WaitSumAv(f), HeldAv(f)); }},
    {"wait_mean_hv", T::kReal, "s", kPJ, S::kAll, Pool::kMean, nullptr, "held_hv", nullptr,
     "mean wait of the held HVs at the stop line",
     [](const MetricFacts& f) { return Mean(WaitSum(f) - WaitSumAv(f), Held(f) - HeldAv(f)); }},
    {"queue_max", T::kReal, "veh", kJ, S::kAll, Pool::kMax, nullptr, nullptr, nullptr,
     "longest queue of halting vehicles on an approach lane (sampled each second)",
     [](const MetricFacts& f) {
       double q = 0;
       for (const ApproachStats& a : f.junction->approaches) q = std::max(q, a.queue_max);
       return q;
     }},
    {"queue_mean", T::kReal, "veh", kJ, S::kAll, Pool::kMean, nullptr, nullptr, nullptr,
     "mean queue of halting vehicles per approach lane",
     [](const MetricFacts& f) {
       double sum = 0;
       long samples = 0;
       for (const ApproachStats& a : f.junction->approaches) {
         sum += a.queue_sum;
         samples += a.samples;
       }
       return samples ? sum / samples : 0.0;
     }},
    {"meetings_not_game", T::kCount, "", kJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "AV-HV meetings left to SUMO because both proceeding would not collide",
     [](const MetricFacts& f) { return D(f.junction->meetings_not_game); }},
    {"meetings_unpredictable", T::kCount, "", kJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "AV-HV meetings left to SUMO because the premise could not be predicted exactly",
     [](const MetricFacts& f) { return D(f.junction->meetings_unpredictable); }},
  };
}

std::vector<Metric> MeetingMetrics() {
  return {
    {"meetings_abandoned", T::kCount, "", kJ, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "meetings whose pair was held and then handed back to SUMO without a game",
     [](const MetricFacts& f) { return D(f.junction->meetings_abandoned); }},
    {"other_collisions", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "collisions outside AV-HV encounters",
     [](const MetricFacts& f) { return D(f.run->other_collisions); }},
    {"other_collisions_game_move", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr,
     nullptr, "of those, between a vehicle making a move of the game and a third vehicle",
     [](const MetricFacts& f) { return D(f.run->other_collisions_game_move); }},
    {"collisions_after_handback", T::kCount, "", kP, S::kNetwork, Pool::kSum, nullptr, nullptr,
     nullptr, "encounters whose pair collided after the controller handed them back to SUMO",
     [](const MetricFacts& f) {
       return D(std::count_if(f.run->encounters.begin(), f.run->encounters.end(),
                              [](const EncounterRecord& e) { return e.collision_after_handback; }));
     }},
    {"unblocked", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "vehicles SUMO kept waiting in a junction for a nudged AV that the controller let past",
     [](const MetricFacts& f) { return D(f.run->unblocked); }},
    {"teleports", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr, nullptr,
     "vehicles SUMO teleported (a jam it resolved by moving a vehicle)",
     [](const MetricFacts& f) { return D(f.run->teleports); }},
    {"sumo_warnings", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr,
     "sumo_warnings.count", "warnings SUMO printed",
     [](const MetricFacts& f) { return D(f.run->sumo_warnings); }},
    {"sumo_collision_warnings", T::kCount, "", kP, S::kAll, Pool::kSum, nullptr, nullptr,
     "sumo_warnings.collisions", "of those, SUMO's collision reports",
     [](const MetricFacts& f) { return D(f.run->sumo_collision_warnings); }},
    {"longest_gap_without_crossing", T::kReal, "s", kPJ, S::kAll, Pool::kMax, nullptr, nullptr,
     nullptr, "longest time no vehicle crossed a controlled junction (a deadlock indicator)",
     [](const MetricFacts& f) {
       return f.junction ? f.junction->longest_gap_without_crossing
                         : f.run->longest_gap_without_crossing;
     }},
    {"stalled", T::kFlag, "", kP, S::kAll, Pool::kSum, nullptr, nullptr,
     "aggregate.csv: stalled_runs",
     "the run stalled (its flow and delay are a gridlock's); aggregate.csv: runs that stalled",
     [](const MetricFacts& f) { return f.run->stalls.empty() ? 0.0 : 1.0; }},
    {"simulated_seconds", T::kReal, "s", kP, S::kAll, Pool::kNone, nullptr, nullptr, nullptr,
     "simulated time, warm-up included",
     [](const MetricFacts& f) { return f.run->simulated_seconds; }},
    {"measured_seconds", T::kReal, "s", kP, S::kAll, Pool::kNone, nullptr, nullptr, nullptr,
     "simulated time after the warm-up (what every count and rate covers)",
     [](const MetricFacts& f) { return f.run->measured_seconds; }},
  };
}

std::vector<Metric> NetworkMetrics() {
  return {
    // scenario.kind: network (SUMO's own counts and tripinfo).
    {"departed", T::kCount, "", kP, S::kNetwork, Pool::kSum, nullptr, nullptr,
     "network.departed", "vehicles that entered the network",
     [](const MetricFacts& f) { return D(Net(f).departed); }},
    {"arrived", T::kCount, "", kP, S::kNetwork, Pool::kSum, nullptr, nullptr, "network.arrived",
     "vehicles that left the network",
     [](const MetricFacts& f) { return D(Net(f).arrived); }},
    {"served_flow", T::kReal, "veh/h", kP, S::kNetwork, Pool::kMean, nullptr, nullptr,
     "network.served_flow_per_hour", "vehicles that left the network per hour",
     [](const MetricFacts& f) { return PerHour(D(Net(f).arrived), f.run->measured_seconds); }},
    {"offered", T::kCount, "", kP, S::kNetwork, Pool::kSum, nullptr, nullptr, "network.offered",
     "vehicles the demand asked to insert (departed + still waiting to depart)",
     [](const MetricFacts& f) { return D(Net(f).Offered()); }},
    {"offered_flow", T::kReal, "veh/h", kP, S::kNetwork, Pool::kMean, nullptr, nullptr,
     "network.offered_flow_per_hour", "the offered demand per hour",
     [](const MetricFacts& f) { return PerHour(D(Net(f).Offered()), f.run->measured_seconds); }},
    {"waiting_to_depart_max", T::kCount, "", kP, S::kNetwork, Pool::kMax, nullptr, nullptr,
     "network.waiting_to_depart.max", "most vehicles waiting to be inserted at once",
     [](const MetricFacts& f) { return D(Net(f).pending_max); }},
    {"waiting_to_depart_end", T::kCount, "", kP, S::kNetwork, Pool::kMean, nullptr, nullptr,
     "network.waiting_to_depart.end", "vehicles still waiting to be inserted at the end",
     [](const MetricFacts& f) { return D(Net(f).pending_end); }},
    {"vehicles_max", T::kCount, "", kP, S::kNetwork, Pool::kMax, nullptr, nullptr,
     "network.vehicles_max", "most vehicles in the network at once",
     [](const MetricFacts& f) { return D(Net(f).vehicles_max); }},
    {"trips", T::kCount, "", kP, S::kNetwork, Pool::kSum, nullptr, nullptr, "network.trips",
     "trips departed after the warm-up (SUMO's tripinfo)",
     [](const MetricFacts& f) { return D(Net(f).trips); }},
    {"trips_unfinished", T::kCount, "", kP, S::kNetwork, Pool::kSum, nullptr, nullptr,
     "network.trips_unfinished", "of those, still in the network at the end",
     [](const MetricFacts& f) { return D(Net(f).trips_unfinished); }},
    {"trip_duration_mean", T::kReal, "s", kP, S::kNetwork, Pool::kMean, nullptr, nullptr,
     "network.trip_duration_mean", "mean trip duration",
     [](const MetricFacts& f) { return PerTrip(f, Net(f).duration_sum); }},
    {"time_loss_mean", T::kReal, "s", kP, S::kNetwork, Pool::kMean, nullptr, nullptr,
     "network.time_loss_mean", "mean delay per trip against free flow (SUMO's timeLoss)",
     [](const MetricFacts& f) { return PerTrip(f, Net(f).time_loss_sum); }},
    {"time_loss_max", T::kReal, "s", kP, S::kNetwork, Pool::kMax, nullptr, nullptr,
     "network.time_loss_max", "largest delay of a trip",
     [](const MetricFacts& f) { return Net(f).time_loss_max; }},
    {"waiting_time_mean", T::kReal, "s", kP, S::kNetwork, Pool::kMean, nullptr, nullptr,
     "network.waiting_time_mean", "mean time per trip spent standing (SUMO's waitingTime)",
     [](const MetricFacts& f) { return PerTrip(f, Net(f).waiting_time_sum); }},
    {"trips_av", T::kCount, "", kP, S::kNetwork, Pool::kSum, nullptr, nullptr, nullptr,
     "of the trips, AVs'",
     [](const MetricFacts& f) { return D(Net(f).trips_av); }},
    {"trips_hv", T::kCount, "", kP, S::kNetwork, Pool::kSum, nullptr, nullptr, nullptr,
     "of the trips, HVs'",
     [](const MetricFacts& f) { return D(Net(f).trips - Net(f).trips_av); }},
    {"time_loss_mean_av", T::kReal, "s", kP, S::kNetwork, Pool::kMean, nullptr, "trips_av",
     nullptr, "mean delay of an AV's trip (SUMO's timeLoss)",
     [](const MetricFacts& f) { return Mean(Net(f).time_loss_sum_av, Net(f).trips_av); }},
    {"time_loss_mean_hv", T::kReal, "s", kP, S::kNetwork, Pool::kMean, nullptr, "trips_hv",
     nullptr, "mean delay of an HV's trip (SUMO's timeLoss)",
     [](const MetricFacts& f) {
       return Mean(Net(f).time_loss_sum - Net(f).time_loss_sum_av, Net(f).trips - Net(f).trips_av);
     }},
    {"waiting_time_mean_av", T::kReal, "s", kP, S::kNetwork, Pool::kMean, nullptr, "trips_av",
     nullptr, "mean time an AV's trip spent standing (SUMO's waitingTime)",
     [](const MetricFacts& f) { return Mean(Net(f).waiting_time_sum_av, Net(f).trips_av); }},
    {"waiting_time_mean_hv", T::kReal, "s", kP, S::kNetwork, Pool::kMean, nullptr, "trips_hv",
     nullptr, "mean time an HV's trip spent standing (SUMO's waitingTime)",
     [](const MetricFacts& f) {
       return Mean(Net(f).waiting_time_sum - Net(f).waiting_time_sum_av,
                   Net(f).trips - Net(f).trips_av);
     }},
  };
}

std::vector<Metric> TrustMetrics() {
  return {
    // Beyond the paper: trust, the oracle, regret, learning, the last hour.
    {"trust_hvs", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr, "trust.hvs",
     "HVs registered (each with its drawn trust)",
     [](const MetricFacts& f) { return D(B(f).hvs); }},
    {"initial_mean_trust", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr,
     "trust.initial_mean", "mean drawn trust of the HVs",
     [](const MetricFacts& f) { return B(f).initial_mean_trust; }},
    {"final_mean_trust", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr,
     "trust.final_mean", "mean trust of the HVs in the network at the end",
     [](const MetricFacts& f) { return B(f).final_mean_trust; }},
    {"expected_long_run_trust", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr,
     "trust_dynamics.expected_long_run_mean",
     "the dynamics' long-run mean trust over the trust distribution (dynamic trust only)",
     [](const MetricFacts& f) { return Dynamics(f, B(f).expected_long_run_mean); }},
    {"final_mean_field_trust", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr,
     "trust_dynamics.final_mean_field",
     "the mean-field prediction of the final mean trust (dynamic trust only)",
     [](const MetricFacts& f) { return Dynamics(f, B(f).final_mean_field); }},
    {"long_run_theory_dc_rate", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr,
     "trust_dynamics.long_run_theory.dc_rate",
     "predicted DC rate at the long-run trusts (dynamic trust), or of the learned beliefs "
     "(model.experience)",
     [](const MetricFacts& f) { return LongRun(f, B(f).long_run_dc); }},
    {"long_run_theory_collision_rate", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr,
     nullptr, "trust_dynamics.long_run_theory.collision_rate",
     "predicted collision rate at the long-run trusts (dynamic trust), or of the learned "
     "beliefs (model.experience)",
     [](const MetricFacts& f) { return LongRun(f, B(f).long_run_collision); }},
    {"oracle_dc_rate", T::kReal, "", kP, S::kBeyond, Pool::kWeighted, nullptr, "encounters",
     "oracle.dc_rate", "predicted DC rate of the oracle (TA-EBP for each HV's exact trust)",
     [](const MetricFacts& f) { return PerEncounter(f, f.beyond.oracle_dc); }},
    {"oracle_collision_rate", T::kReal, "", kP, S::kBeyond, Pool::kWeighted, nullptr,
     "encounters", "oracle.collision_rate", "predicted collision rate of the oracle",
     [](const MetricFacts& f) { return PerEncounter(f, f.beyond.oracle_collision); }},
    {"oracle_expected_dc_rate", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr,
     "oracle.expected.dc_rate", "the oracle's DC rate over the trust distribution",
     [](const MetricFacts& f) { return B(f).oracle.dc_rate; }},
    {"oracle_expected_collision_rate", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr,
     nullptr, "oracle.expected.collision_rate",
     "the oracle's collision rate over the trust distribution",
     [](const MetricFacts& f) { return B(f).oracle.collision_rate; }},
    {"regret", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr, "regret.total",
     "DC lost + r x collisions against the oracle, summed over the encounters",
     [](const MetricFacts& f) { return f.beyond.regret; }},
    {"regret_dc_lost", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr,
     "regret.dc_lost", "predicted DC lost against the oracle, summed",
     [](const MetricFacts& f) { return f.beyond.dc_lost; }},
    {"regret_collisions", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, nullptr,
     "regret.collisions", "predicted collisions above the oracle's, summed",
     [](const MetricFacts& f) { return f.beyond.collisions; }},
    {"regret_per_encounter", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr, "encounters",
     "regret.per_encounter", "regret per encounter",
     [](const MetricFacts& f) { return PerEncounter(f, f.beyond.regret); }},
    {"failures", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "failures.nudged_then_dr (and learning.failures)",
     "encounters in which the AV nudged and the HV still drove recklessly",
     [](const MetricFacts& f) { return D(f.beyond.failures); }},
    {"expected_failures", T::kReal, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "learning.expected_failures",
     "the fleet's predicted number of failures (learned trust only)",
     [](const MetricFacts& f) { return Learning(f, f.beyond.expected_failures); }},
    {"learning_hvs_met", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "learning.hvs_met", "HVs the fleet met (learned trust only)",
     [](const MetricFacts& f) { return Learning(f, D(B(f).hvs_met)); }},
    {"learning_observations", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "learning.observations", "HV responses the fleet learned from (learned trust only)",
     [](const MetricFacts& f) { return Learning(f, D(B(f).observations)); }},
  };
}

std::vector<Metric> LearningMetrics() {
  return {
    {"learning_contradictions", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "learning.contradictions",
     "responses that contradicted the fleet's belief (learned trust only)",
     [](const MetricFacts& f) { return Learning(f, D(B(f).contradictions)); }},
    {"learning_probes", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "learning.probes", "encounters designed to learn rather than to persuade",
     [](const MetricFacts& f) { return Learning(f, D(B(f).probes)); }},
    {"learning_final_mean_abs_error", T::kReal, "", kP, S::kBeyond, Pool::kMean, nullptr,
     nullptr, "learning.final_mean_abs_error",
     "mean absolute error of the belief mean against the trust, over the HVs met, at the end (learned trust only)",
     [](const MetricFacts& f) { return Learning(f, B(f).final_mean_abs_error); }},
    {"last_hour_from", T::kReal, "s", kP, S::kBeyond, Pool::kNone, nullptr, nullptr,
     "last_hour.from", "start of the last hour's window (or of the measurement)",
     [](const MetricFacts& f) { return f.last_hour.from; }},
    {"last_hour_encounters", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "last_hour.encounters", "encounters in the last hour",
     [](const MetricFacts& f) { return D(f.last_hour.n); }},
    {"last_hour_dc", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "last_hour.dc", "DC choices in the last hour",
     [](const MetricFacts& f) { return D(f.last_hour.dc); }},
    {"last_hour_dc_rate", T::kReal, "", kP, S::kBeyond, Pool::kRate, "last_hour_dc",
     "last_hour_encounters", "last_hour.dc_rate, last_hour.dc_rate_ci95",
     "DC rate in the last hour (after trust has moved)",
     [](const MetricFacts& f) { return Rate(f.last_hour.dc, f.last_hour.n); }},
    {"last_hour_collisions", T::kCount, "", kP, S::kBeyond, Pool::kSum, nullptr, nullptr,
     "last_hour.collisions", "collisions in the last hour",
     [](const MetricFacts& f) { return D(f.last_hour.collisions); }},
    {"last_hour_collision_rate", T::kReal, "", kP, S::kBeyond, Pool::kRate,
     "last_hour_collisions", "last_hour_encounters",
     "last_hour.collision_rate, last_hour.collision_rate_ci95", "collision rate in the last hour",
     [](const MetricFacts& f) { return Rate(f.last_hour.collisions, f.last_hour.n); }},
    {"last_hour_theory_dc_rate", T::kReal, "", kP, S::kBeyond, Pool::kWeighted, nullptr,
     "last_hour_encounters", "last_hour.theory_dc_rate",
     "mean predicted DC rate of the last hour's encounters",
     [](const MetricFacts& f) { return LastHourMean(f, f.last_hour.theory_dc); }},
    {"last_hour_theory_collision_rate", T::kReal, "", kP, S::kBeyond, Pool::kWeighted, nullptr,
     "last_hour_encounters", "last_hour.theory_collision_rate",
     "mean predicted collision rate of the last hour's encounters",
     [](const MetricFacts& f) { return LastHourMean(f, f.last_hour.theory_collisions); }},
    {"last_hour_oracle_dc_rate", T::kReal, "", kP, S::kBeyond, Pool::kWeighted, nullptr,
     "last_hour_encounters", "last_hour.oracle_dc_rate",
     "the oracle's predicted DC rate on the last hour's encounters",
     [](const MetricFacts& f) { return LastHourMean(f, f.last_hour.oracle_dc); }},
  };
}
// clang-format on

}  // namespace

const std::vector<Metric>& RunMetrics() {
  // SUMO's surrogate safety measures (ssm.cc), last.
  static const std::vector<Metric> all = [] {
    std::vector<Metric> t;
    for (const auto& part : {GameMetrics, UnfinishedGameMetrics, JunctionTrafficMetrics,
                             MeetingMetrics, NetworkMetrics, TrustMetrics, LearningMetrics,
                             SsmMetricRows}) {
      const std::vector<Metric> rows = part();
      t.insert(t.end(), rows.begin(), rows.end());
    }
    return t;
  }();
  return all;
}

}  // namespace taebp
