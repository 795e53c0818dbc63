#include "taebp/report/report.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

#if __has_include("taebp_git.h")
#include "taebp_git.h"
#endif
#ifndef TAEBP_GIT_REVISION
#define TAEBP_GIT_REVISION "unknown"
#endif
#ifndef TAEBP_VERSION
#define TAEBP_VERSION "0.1.0"
#endif

namespace taebp {
namespace {

using json = nlohmann::ordered_json;

std::string PolicyLabel(const std::string& p) {
  if (p == "no_ebp") return "No EBP";
  if (p == "no_trust") return "No Trust";
  if (p == "ta_ebp") return "TA-EBP";
  if (p == "full_reveal") return "Full reveal";
  return p;
}

struct Stats {
  long n = 0, collisions = 0, dc = 0, nudges = 0;
  double commanded_sum = 0, observed_sum = 0, max_abs_error = 0;
  double min_excess = 0;  // min over nudges of observed - commanded
  double theory_dc_sum = 0, theory_collision_sum = 0;  // per-encounter predictions
};

Stats Compute(const PolicyRun& r) {
  Stats s;
  s.n = static_cast<long>(r.encounters.size());
  bool first = true;
  for (const EncounterRecord& e : r.encounters) {
    s.collisions += e.collision;
    s.dc += e.hv_dc;
    s.theory_dc_sum += e.theory_dc;
    s.theory_collision_sum += e.theory_collision;
    if (e.commanded > 0) {
      ++s.nudges;
      s.commanded_sum += e.commanded;
      s.observed_sum += e.observed;
      const double excess = e.observed - e.commanded;
      s.max_abs_error = std::max(s.max_abs_error, std::abs(excess));
      s.min_excess = first ? excess : std::min(s.min_excess, excess);
      first = false;
    }
  }
  return s;
}

double Rate(long k, long n) { return n > 0 ? static_cast<double>(k) / n : 0.0; }

// The encounter statistics of one junction.
Stats ComputeAt(const PolicyRun& r, const std::string& junction) {
  PolicyRun only;
  for (const EncounterRecord& e : r.encounters)
    if (e.junction == junction) only.encounters.push_back(e);
  return Compute(only);
}

double PerHour(double count, double seconds) { return seconds > 0 ? count * 3600.0 / seconds : 0.0; }

json RatesJson(const Stats& s) {
  const Interval ci_c = Wilson(s.collisions, s.n);
  const Interval ci_d = Wilson(s.dc, s.n);
  json j;
  j["encounters"] = s.n;
  j["collisions"] = s.collisions;
  j["collision_rate"] = Rate(s.collisions, s.n);
  j["collision_rate_ci95"] = {ci_c.low, ci_c.high};
  j["dc"] = s.dc;
  j["dc_rate"] = Rate(s.dc, s.n);
  j["dc_rate_ci95"] = {ci_d.low, ci_d.high};
  j["theory_given_hvs"] = {{"collision_rate", s.n ? s.theory_collision_sum / s.n : 0.0},
                           {"dc_rate", s.n ? s.theory_dc_sum / s.n : 0.0}};
  return j;
}

json JunctionJson(const PolicyRun& r, const JunctionRun& jr) {
  json j;
  j["id"] = jr.id;
  j["type"] = jr.type;
  j["original_type"] = jr.original_type;
  j["rule"] = jr.rule;
  const long all = jr.crossings_av + jr.crossings_hv;
  j["crossings"] = {{"av", jr.crossings_av}, {"hv", jr.crossings_hv}, {"all", all}};
  j["throughput_per_hour"] = PerHour(static_cast<double>(all), r.measured_seconds);
  j["held"] = jr.held;
  j["longest_gap_without_crossing"] = jr.longest_gap_without_crossing;
  // No vehicle held (sumo_native, or nobody met): no mean wait (null), not 0.
  j["wait_at_stop_line"] = {{"mean", jr.held ? json(jr.wait_sum / jr.held) : json()},
                            {"max", jr.wait_max}};
  json approaches = json::array();
  for (const ApproachStats& a : jr.approaches)
    approaches.push_back({{"lane", a.lane},
                          {"queue_max", a.queue_max},
                          {"queue_mean", a.samples ? a.queue_sum / a.samples : 0.0}});
  j["approaches"] = approaches;
  j["meetings_not_game"] = jr.meetings_not_game;
  j["meetings_unpredictable"] = jr.meetings_unpredictable;
  j["meetings_abandoned"] = jr.meetings_abandoned;
  const json rates = RatesJson(ComputeAt(r, jr.id));
  for (auto it = rates.begin(); it != rates.end(); ++it) j[it.key()] = it.value();
  return j;
}

json NetworkJson(const PolicyRun& r) {
  const NetworkRun& n = r.network;
  json j;
  j["departed"] = n.departed;
  j["arrived"] = n.arrived;
  j["served_flow_per_hour"] = PerHour(static_cast<double>(n.arrived), r.measured_seconds);
  j["offered"] = n.Offered();
  j["offered_flow_per_hour"] = PerHour(static_cast<double>(n.Offered()), r.measured_seconds);
  j["waiting_to_depart"] = {{"max", n.pending_max}, {"end", n.pending_end}};
  j["vehicles_max"] = n.vehicles_max;
  j["trips"] = n.trips;
  j["trips_unfinished"] = n.trips_unfinished;
  j["trip_duration_mean"] = n.trips ? n.duration_sum / n.trips : 0.0;
  j["time_loss_mean"] = n.trips ? n.time_loss_sum / n.trips : 0.0;
  j["time_loss_max"] = n.time_loss_max;
  j["waiting_time_mean"] = n.trips ? n.waiting_time_sum / n.trips : 0.0;
  return j;
}

json Value(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// Encounters from `from` on (the last hour's window).
struct Window {
  double from = 0;
  long n = 0, dc = 0, collisions = 0;
  double theory_dc = 0, oracle_dc = 0, theory_collisions = 0;
};
Window LastHour(const PolicyRun& r) {
  Window w;
  const double start = r.simulated_seconds - r.measured_seconds;
  w.from = std::max(start, r.simulated_seconds - 3600.0);
  for (const EncounterRecord& e : r.encounters) {
    if (e.time < w.from) continue;
    ++w.n;
    w.dc += e.hv_dc;
    w.collisions += e.collision;
    w.theory_dc += e.theory_dc;
    w.theory_collisions += e.theory_collision;
    w.oracle_dc += e.beyond.oracle_dc;
  }
  return w;
}

// The sections of a run beyond the paper (README "Outputs").
void BeyondJson(const PolicyRun& r, json* out) {
  json& j = *out;
  const BeyondRun& b = r.beyond;
  const Stats s = Compute(r);
  double oracle_dc = 0, oracle_c = 0, lost = 0, coll = 0, regret = 0;
  long failures = 0;
  for (const EncounterRecord& e : r.encounters) {
    oracle_dc += e.beyond.oracle_dc;
    oracle_c += e.beyond.oracle_collision;
    lost += e.beyond.oracle_dc - e.theory_dc;
    coll += e.theory_collision - e.beyond.oracle_collision;
    regret += e.beyond.regret;
    failures += e.commanded > 0 && !e.hv_dc;
  }
  const double n = static_cast<double>(s.n);
  j["trust"] = {{"hvs", b.hvs},
                {"initial_mean", Value(b.initial_mean_trust)},
                {"final_mean", Value(b.final_mean_trust)}};
  j["oracle"] = {{"dc_rate", s.n ? oracle_dc / n : 0.0},
                 {"collision_rate", s.n ? oracle_c / n : 0.0},
                 {"expected", {{"dc_rate", b.oracle.dc_rate},
                               {"collision_rate", b.oracle.collision_rate}}}};
  j["regret"] = {{"total", regret},
                 {"dc_lost", lost},
                 {"collisions", coll},
                 {"per_encounter", s.n ? regret / n : 0.0}};
  const Window w = LastHour(r);
  const Interval wd = Wilson(w.dc, w.n), wc = Wilson(w.collisions, w.n);
  j["last_hour"] = {{"from", w.from},
                    {"encounters", w.n},
                    {"dc", w.dc},
                    {"dc_rate", Rate(w.dc, w.n)},
                    {"dc_rate_ci95", {wd.low, wd.high}},
                    {"collisions", w.collisions},
                    {"collision_rate", Rate(w.collisions, w.n)},
                    {"collision_rate_ci95", {wc.low, wc.high}},
                    {"theory_dc_rate", w.n ? w.theory_dc / w.n : 0.0},
                    {"theory_collision_rate", w.n ? w.theory_collisions / w.n : 0.0},
                    {"oracle_dc_rate", w.n ? w.oracle_dc / w.n : 0.0}};
  j["failures"] = {{"nudged_then_dr", failures}};
  if (b.long_run) {
    json eq = json::array();
    for (const TrustEquilibriumRecord& e : b.equilibria)
      eq.push_back({{"theta", e.theta}, {"kind", e.kind}, {"stable", e.stable}});
    json attractors = json::array();
    for (const TrustEquilibriumRecord& e : b.equilibria)
      if (e.stable) attractors.push_back(e.theta);
    j["trust_dynamics"] = {{"design_rule", b.design_rule},
                           {"equilibria", eq},
                           {"attractors", attractors},
                           {"expected_long_run_mean", Value(b.expected_long_run_mean)},
                           {"long_run_theory", {{"dc_rate", Value(b.long_run_dc)},
                                                {"collision_rate", Value(b.long_run_collision)}}},
                           {"final_mean_field", Value(b.final_mean_field)}};
  } else {
    j["trust_dynamics"] = nullptr;
  }
  if (b.learning) {
    double expected = 0;
    for (const EncounterRecord& e : r.encounters)
      if (e.commanded > 0 && std::isfinite(e.beyond.failure_probability))
        expected += e.beyond.failure_probability;
    j["learning"] = {{"hvs_met", b.hvs_met},
                     {"observations", b.observations},
                     {"contradictions", b.contradictions},
                     {"probes", b.probes},
                     {"failures", failures},
                     {"expected_failures", expected},
                     {"final_mean_abs_error", Value(b.final_mean_abs_error)}};
  } else {
    j["learning"] = nullptr;
  }
  if (b.noise) {
    j["noise"] = {{"kind", b.noise_kind},
                  {"scale", b.noise_scale},
                  {"bias", b.noise_bias},
                  {"delta", b.noise_delta},
                  {"design", b.noise_design},
                  {"population_design", {{"status", b.noise_status},
                                         {"nudge", b.noise_nudge},
                                         {"b", b.noise_b},
                                         {"credible", b.noise_credible},
                                         {"density_ratio", b.noise_density_ratio},
                                         {"persuasion_probability", b.noise_persuasion}}}};
  } else {
    j["noise"] = nullptr;
  }
}

}  // namespace

std::string JunctionsCsv(const std::vector<PolicyRun>& runs) {
  std::ostringstream out;
  out << "policy,junction,type,original_type,rule,crossings_av,crossings_hv,"
         "throughput_per_hour,held,wait_mean,wait_max,queue_max,queue_mean,encounters,dc,"
         "dc_rate,collisions,collision_rate,theory_dc_rate,theory_collision_rate,"
         "meetings_not_game,meetings_unpredictable,meetings_abandoned,"
         "longest_gap_without_crossing\n";
  for (const PolicyRun& r : runs) {
    for (const JunctionRun& jr : r.junctions) {
      const Stats s = ComputeAt(r, jr.id);
      double qmax = 0, qsum = 0;
      long samples = 0;
      for (const ApproachStats& a : jr.approaches) {
        qmax = std::max(qmax, a.queue_max);
        qsum += a.queue_sum;
        samples += a.samples;
      }
      // Mean queue per approach lane.
      const double qmean = samples ? qsum / samples : 0.0;
      out << CsvCell(r.policy) << ',' << CsvCell(jr.id) << ',' << jr.type << ','
          << jr.original_type << ',' << jr.rule << ',' << jr.crossings_av << ','
          << jr.crossings_hv << ','
          << FormatDouble(PerHour(static_cast<double>(jr.crossings_av + jr.crossings_hv),
                                  r.measured_seconds))
          << ',' << jr.held << ',' << (jr.held ? FormatDouble(jr.wait_sum / jr.held) : "") << ','
          << FormatDouble(jr.wait_max) << ',' << FormatDouble(qmax) << ','
          << FormatDouble(qmean) << ',' << s.n << ',' << s.dc << ','
          << FormatDouble(Rate(s.dc, s.n)) << ',' << s.collisions << ','
          << FormatDouble(Rate(s.collisions, s.n)) << ','
          << FormatDouble(s.n ? s.theory_dc_sum / s.n : 0.0) << ','
          << FormatDouble(s.n ? s.theory_collision_sum / s.n : 0.0) << ','
          << jr.meetings_not_game << ',' << jr.meetings_unpredictable << ','
          << jr.meetings_abandoned << ',' << FormatDouble(jr.longest_gap_without_crossing)
          << '\n';
    }
  }
  return out.str();
}

std::string FormatDouble(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

Interval Wilson(long k, long n, double z) {
  if (n <= 0) return {0.0, 1.0};
  const double p = static_cast<double>(k) / n;
  const double z2 = z * z;
  const double denom = 1 + z2 / n;
  const double centre = (p + z2 / (2.0 * n)) / denom;
  const double half = z * std::sqrt(p * (1 - p) / n + z2 / (4.0 * n * n)) / denom;
  // At k = 0 (k = n) the bound is exactly 0 (1); avoid round-off residue.
  return {k == 0 ? 0.0 : std::max(0.0, centre - half), k == n ? 1.0 : std::min(1.0, centre + half)};
}

std::string BuildGitRevision() { return TAEBP_GIT_REVISION; }
std::string TaebpVersion() { return TAEBP_VERSION; }

std::string SummaryJson(const std::vector<PolicyRun>& runs, const Provenance& prov,
                        const Stopped& stopped) {
  json root;
  json& p = root["provenance"];
  p["tool"] = "taebp " + prov.taebp_version;
  p["git_revision"] = prov.git_revision;
  p["sumo_version"] = prov.sumo_version;
  p["seed"] = prov.seed;
  p["config_path"] = prov.config_path;
  p["config"] = json::parse(prov.config_json);
  p["warnings"] = prov.warnings;
  if (!stopped.reason.empty()) {
    root["stopped"] = stopped.reason;
    root["stopped_policy"] = stopped.policy;
    root["error"] = stopped.message;
    root["policies_not_run"] = stopped.not_run;
  }
  json& pol = root["policies"];
  pol = json::object();
  for (const PolicyRun& r : runs) {
    const Stats s = Compute(r);
    const Interval ci_c = Wilson(s.collisions, s.n);
    const Interval ci_d = Wilson(s.dc, s.n);
    const double hours = r.measured_seconds / 3600.0;
    json j;
    j["encounters"] = s.n;
    j["collisions"] = s.collisions;
    j["collision_rate"] = Rate(s.collisions, s.n);
    j["collision_rate_ci95"] = {ci_c.low, ci_c.high};
    j["dc"] = s.dc;
    j["dc_rate"] = Rate(s.dc, s.n);
    j["dc_rate_ci95"] = {ci_d.low, ci_d.high};
    j["theory"] = {{"collision_rate", r.theory.collision_rate},
                   {"dc_rate", r.theory.dc_rate},
                   {"nudge_rate", r.theory.nudge_rate},
                   {"av_first_rate", r.theory.av_first_rate}};
    // Mean of the per-encounter predictions for the HVs actually met (equals
    // `theory` for a fixed trust; the fair comparison for a drawn population).
    j["theory_given_hvs"] = {{"collision_rate", s.n ? s.theory_collision_sum / s.n : 0.0},
                             {"dc_rate", s.n ? s.theory_dc_sum / s.n : 0.0}};
    j["hv_trust"] = r.hv_trust;
    j["scheme"] = {{"av_may_go", r.scheme.av_may_go},
                   {"nudge", r.scheme.nudge},
                   {"p_nudge_given_go", r.scheme.a},
                   {"p_nudge_given_stop", r.scheme.b}};
    const long all = r.crossings_av + r.crossings_hv;
    j["throughput_per_hour"] = {{"av", hours > 0 ? r.crossings_av / hours : 0.0},
                                {"hv", hours > 0 ? r.crossings_hv / hours : 0.0},
                                {"all", hours > 0 ? all / hours : 0.0}};
    j["crossings"] = {{"av", r.crossings_av}, {"hv", r.crossings_hv}, {"all", all}};
    j["wait_at_stop_line"] = {{"mean", r.held > 0 ? json(r.wait_sum / r.held) : json()},
                              {"max", r.wait_max}};
    j["nudges"] = {{"count", s.nudges},
                   {"mean_commanded", s.nudges ? s.commanded_sum / s.nudges : 0.0},
                   {"mean_observed", s.nudges ? s.observed_sum / s.nudges : 0.0},
                   {"max_abs_error", s.max_abs_error},
                   {"min_observed_minus_commanded", s.min_excess},
                   {"tolerance", kNudgeTolerance}};
    j["other_collisions"] = r.other_collisions;
    j["other_collisions_game_move"] = r.other_collisions_game_move;
    if (r.scenario_kind == "network")
      j["collisions_after_handback"] = std::count_if(
          r.encounters.begin(), r.encounters.end(),
          [](const EncounterRecord& e) { return e.collision_after_handback; });
    j["unblocked"] = r.unblocked;
    j["teleports"] = r.teleports;
    j["sumo_warnings"] = {{"count", r.sumo_warnings},
                          {"collisions", r.sumo_collision_warnings},
                          {"first", r.sumo_warnings_first}};
    j["longest_gap_without_crossing"] = r.longest_gap_without_crossing;
    j["simulated_seconds"] = r.simulated_seconds;
    j["measured_seconds"] = r.measured_seconds;
    j["nudges_unrealised"] = r.nudges_unrealised;
    j["encounters_formed"] = r.encounters_formed;
    j["encounters_unfinished"] = r.encounters_unfinished;
    json stalls = json::array();
    for (const StallRecord& st : r.stalls)
      stalls.push_back({{"junction", st.junction}, {"since", st.since}, {"detected", st.detected}});
    j["stalls"] = stalls;
    j["stalled"] = !r.stalls.empty();
    j["stall_error"] = r.stall_error.empty() ? json(nullptr) : json(r.stall_error);
    json junctions = json::array();
    for (const JunctionRun& jr : r.junctions) junctions.push_back(JunctionJson(r, jr));
    j["junctions"] = junctions;
    if (r.scenario_kind == "network") j["network"] = NetworkJson(r);
    if (r.beyond.on && r.policy != "sumo_native") BeyondJson(r, &j);
    pol[r.policy] = j;
  }
  return root.dump(2) + "\n";
}

namespace {

// The encounters.csv columns: name and how a record prints. A new column is
// one line here (and one in the README's Outputs).
struct EncounterColumn {
  const char* name;
  std::string (*cell)(const PolicyRun& run, const EncounterRecord& e);
};
const std::vector<EncounterColumn>& EncounterColumns() {
  static const std::vector<EncounterColumn> cols = {
      {"policy", [](const PolicyRun& r, const EncounterRecord&) { return r.policy; }},
      {"time", [](const PolicyRun&, const EncounterRecord& e) { return FormatDouble(e.time); }},
      {"junction", [](const PolicyRun&, const EncounterRecord& e) { return e.junction; }},
      {"av", [](const PolicyRun&, const EncounterRecord& e) { return e.av; }},
      {"hv", [](const PolicyRun&, const EncounterRecord& e) { return e.hv; }},
      {"av_movement", [](const PolicyRun&, const EncounterRecord& e) { return e.av_movement; }},
      {"hv_movement", [](const PolicyRun&, const EncounterRecord& e) { return e.hv_movement; }},
      {"av_dir", [](const PolicyRun&, const EncounterRecord& e) { return std::string(1, e.av_dir); }},
      {"hv_dir", [](const PolicyRun&, const EncounterRecord& e) { return std::string(1, e.hv_dir); }},
      {"intent", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.intent_go ? "go" : "stop"); }},
      {"commanded_nudge", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.commanded); }},
      {"observed_displacement", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.observed); }},
      {"hv_trust", [](const PolicyRun&, const EncounterRecord& e) { return FormatDouble(e.hv_trust); }},
      {"hv_posterior", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.posterior); }},
      {"hv_action", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.hv_dc ? "DC" : "DR"); }},
      {"av_action", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.av_first ? "go" : "wait"); }},
      {"collision", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.collision ? "1" : "0"); }},
  };
  return cols;
}

std::string Opt(double v) { return std::isfinite(v) ? FormatDouble(v) : std::string(); }

// The columns a run beyond the paper adds after those (README "Outputs").
const std::vector<EncounterColumn>& BeyondColumns() {
  static const std::vector<EncounterColumn> cols = {
      {"design_trust", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.design_trust); }},
      {"scheme_b", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.beyond.scheme_b); }},
      {"hv_reading", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.beyond.reading); }},
      {"hv_trust_after", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.beyond.trust_after); }},
      {"outcome", [](const PolicyRun&, const EncounterRecord& e) { return e.beyond.outcome; }},
      {"quality", [](const PolicyRun&, const EncounterRecord& e) { return Opt(e.beyond.quality); }},
      {"theory_dc", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.theory_dc); }},
      {"theory_collision", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.theory_collision); }},
      {"oracle_dc", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.beyond.oracle_dc); }},
      {"oracle_collision", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.beyond.oracle_collision); }},
      {"regret", [](const PolicyRun&, const EncounterRecord& e) {
         return FormatDouble(e.beyond.regret); }},
      {"learn_mode", [](const PolicyRun&, const EncounterRecord& e) { return e.beyond.mode; }},
      {"risk_level", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.risk_level); }},
      {"failure_probability", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.failure_probability); }},
      {"belief_lower", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.belief_lower); }},
      {"belief_upper", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.belief_upper); }},
      {"observation", [](const PolicyRun&, const EncounterRecord& e) {
         return e.beyond.observation; }},
  };
  return cols;
}

// The column a network scenario adds after those (README "Outputs").
const std::vector<EncounterColumn>& NetworkColumns() {
  static const std::vector<EncounterColumn> cols = {
      {"both_proceed_collides", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.both_proceed_collides ? "1" : "0"); }},
      {"premise", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(ToString(e.premise)); }},
      {"collision_after_handback", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.collision_after_handback ? "1" : "0"); }},
  };
  return cols;
}

bool AnyNetwork(const std::vector<PolicyRun>& runs) {
  return std::any_of(runs.begin(), runs.end(),
                     [](const PolicyRun& r) { return r.scenario_kind == "network"; });
}

bool AnyBeyond(const std::vector<PolicyRun>& runs) {
  return std::any_of(runs.begin(), runs.end(), [](const PolicyRun& r) { return r.beyond.on; });
}

}  // namespace

const char* ToString(Premise p) {
  switch (p) {
    case Premise::kHolds: return "holds";
    case Premise::kNoCollision: return "no_collision";
    case Premise::kUncertainMerge: return "uncertain_merge";
    case Premise::kNudgeInHvWay: return "nudge_in_hv_way";
  }
  return "?";
}

std::string CsvCell(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::vector<std::string> EncounterCsvColumns(bool beyond, bool network) {
  std::vector<std::string> names;
  for (const EncounterColumn& c : EncounterColumns()) names.emplace_back(c.name);
  if (network)
    for (const EncounterColumn& c : NetworkColumns()) names.emplace_back(c.name);
  if (beyond)
    for (const EncounterColumn& c : BeyondColumns()) names.emplace_back(c.name);
  return names;
}

bool BeyondPaper(const std::vector<PolicyRun>& runs) { return AnyBeyond(runs); }

std::string EncountersCsv(const std::vector<PolicyRun>& runs) {
  std::vector<EncounterColumn> cols = EncounterColumns();
  if (AnyNetwork(runs))
    cols.insert(cols.end(), NetworkColumns().begin(), NetworkColumns().end());
  if (AnyBeyond(runs))
    cols.insert(cols.end(), BeyondColumns().begin(), BeyondColumns().end());
  std::string out;
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + std::string(cols[i].name);
  out += '\n';
  for (const PolicyRun& r : runs) {
    for (const EncounterRecord& e : r.encounters) {
      for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + CsvCell(cols[i].cell(r, e));
      out += '\n';
    }
  }
  return out;
}

std::vector<std::string> TimeseriesCsvColumns() {
  return {"policy",    "time",       "hvs",       "mean_trust",       "mean_field_trust",
          "encounters", "dc",        "collisions", "nudges",          "failures",
          "theory_dc", "theory_collisions", "oracle_dc", "oracle_collisions", "regret",
          "expected_failures"};
}

std::string TimeseriesCsv(const std::vector<PolicyRun>& runs) {
  std::string out;
  const auto cols = TimeseriesCsvColumns();
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i];
  out += '\n';
  for (const PolicyRun& r : runs) {
    for (const TimeSample& t : r.beyond.series) {
      out += CsvCell(r.policy) + ',' + FormatDouble(t.time) + ',' + std::to_string(t.hvs) + ',' +
             Opt(t.mean_trust) + ',' + Opt(t.mean_field_trust) + ',' +
             std::to_string(t.encounters) + ',' + std::to_string(t.dc) + ',' +
             std::to_string(t.collisions) + ',' + std::to_string(t.nudges) + ',' +
             std::to_string(t.failures) + ',' + FormatDouble(t.theory_dc) + ',' +
             FormatDouble(t.theory_collisions) + ',' + FormatDouble(t.oracle_dc) + ',' +
             FormatDouble(t.oracle_collisions) + ',' + FormatDouble(t.regret) + ',' +
             FormatDouble(t.expected_failures) + '\n';
    }
  }
  return out;
}

std::vector<std::string> HvTrustCsvColumns() {
  return {"policy",       "time",         "hv",          "trust",        "encounters",
          "belief_lower", "belief_upper", "belief_mean", "design_trust", "observations",
          "contradictions"};
}

std::string HvTrustCsv(const std::vector<PolicyRun>& runs) {
  std::string out;
  const auto cols = HvTrustCsvColumns();
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i];
  out += '\n';
  for (const PolicyRun& r : runs) {
    for (const HvSample& h : r.beyond.hv_series) {
      out += CsvCell(r.policy) + ',' + FormatDouble(h.time) + ',' + CsvCell(h.hv) + ',' +
             FormatDouble(h.trust) + ',' + std::to_string(h.encounters) + ',' +
             Opt(h.belief_lower) + ',' + Opt(h.belief_upper) + ',' + Opt(h.belief_mean) + ',' +
             Opt(h.design_trust) + ',' + std::to_string(h.observations) + ',' +
             std::to_string(h.contradictions) + '\n';
    }
  }
  return out;
}

void PrintTable(std::ostream& out, const std::vector<PolicyRun>& runs,
                const std::vector<std::string>& warnings) {
  const int w0 = 22, w = 34;
  out << std::left << std::setw(w0) << "Metric";
  for (const PolicyRun& r : runs) out << std::setw(w) << PolicyLabel(r.policy);
  out << "\n";
  bool flagged = false;
  auto cell = [&](long k, long n, double theory) {
    const Interval ci = Wilson(k, n);
    char buf[96];
    if (n == 0 && theory < 0) return std::string("- (SUMO's own logic)");
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "n/a (no AV-HV encounter) th %.3f", theory);
      return std::string(buf);
    }
    // The theory outside the measured rate's 95% interval: worth a look.
    const bool outside = theory < ci.low || theory > ci.high;
    flagged = flagged || outside;
    std::snprintf(buf, sizeof buf, "%.3f [%.3f,%.3f] th %.3f%s", Rate(k, n), ci.low, ci.high,
                  theory, outside ? " !" : "");
    return std::string(buf);
  };
  std::vector<Stats> stats;
  for (const PolicyRun& r : runs) stats.push_back(Compute(r));
  out << std::setw(w0) << "Collision Rate";
  for (std::size_t i = 0; i < runs.size(); ++i)
    out << std::setw(w)
        << cell(stats[i].collisions, stats[i].n,
                runs[i].policy == "sumo_native" ? -1.0 : runs[i].theory.collision_rate);
  out << "\n" << std::setw(w0) << "DC Rate";
  for (std::size_t i = 0; i < runs.size(); ++i)
    out << std::setw(w)
        << cell(stats[i].dc, stats[i].n, runs[i].policy == "sumo_native" ? -1.0 : runs[i].theory.dc_rate);
  out << "\n" << std::setw(w0) << "AV-HV encounters";
  for (std::size_t i = 0; i < runs.size(); ++i) out << std::setw(w) << stats[i].n;
  const bool network = !runs.empty() && runs.front().scenario_kind == "network";
  out << "\n" << std::setw(w0) << (network ? "Junction crossings/h" : "Crossings / hour");
  for (const PolicyRun& r : runs) {
    const double h = r.measured_seconds / 3600.0;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f (AV %.0f, HV %.0f)",
                  h > 0 ? (r.crossings_av + r.crossings_hv) / h : 0.0,
                  h > 0 ? r.crossings_av / h : 0.0, h > 0 ? r.crossings_hv / h : 0.0);
    out << std::setw(w) << buf;
  }
  out << "\n" << std::setw(w0) << "Mean / max wait (s)";
  for (const PolicyRun& r : runs) {
    char buf[64];
    if (r.held == 0)
      std::snprintf(buf, sizeof buf, "%s",
                    r.policy == "sumo_native" ? "n/a (SUMO's own logic)" : "no vehicle held");
    else
      std::snprintf(buf, sizeof buf, "%.1f / %.1f", r.wait_sum / r.held, r.wait_max);
    out << std::setw(w) << buf;
  }
  out << "\n";
  if (network) {
    auto row = [&](const char* label, auto cell) {
      out << std::setw(w0) << label;
      for (const PolicyRun& r : runs) out << std::setw(w) << cell(r);
      out << "\n";
    };
    // A stalled run's flow and delay are those of a gridlock (see the
    // footnote), not of the junction logic: marked.
    auto mark = [](const PolicyRun& r) { return r.stalls.empty() ? "" : " stalled"; };
    row("Served flow (veh/h)", [&](const PolicyRun& r) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.0f (%ld in, %ld out)%s",
                    PerHour(static_cast<double>(r.network.arrived), r.measured_seconds),
                    r.network.departed, r.network.arrived, mark(r));
      return std::string(buf);
    });
    row("Mean delay (s)", [&](const PolicyRun& r) {
      char buf[96];
      const NetworkRun& n = r.network;
      std::snprintf(buf, sizeof buf, "%.1f loss, %.1f waiting%s",
                    n.trips ? n.time_loss_sum / n.trips : 0.0,
                    n.trips ? n.waiting_time_sum / n.trips : 0.0, mark(r));
      return std::string(buf);
    });
    row("Trips (unfinished)", [](const PolicyRun& r) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%ld (%ld unfinished)", r.network.trips,
                    r.network.trips_unfinished);
      return std::string(buf);
    });
    row("Waiting to depart", [](const PolicyRun& r) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%ld at end (max %ld)", r.network.pending_end,
                    r.network.pending_max);
      return std::string(buf);
    });
  }
  if (AnyBeyond(runs)) {
    auto row = [&](const char* label, auto cell) {
      out << std::setw(w0) << label;
      for (const PolicyRun& r : runs) out << std::setw(w) << cell(r);
      out << "\n";
    };
    row("Last hour DC rate", [](const PolicyRun& r) {
      if (r.policy == "sumo_native") return std::string("-");
      const Window win = LastHour(r);
      const Interval ci = Wilson(win.dc, win.n);
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.3f [%.3f,%.3f] or %.3f", Rate(win.dc, win.n), ci.low,
                    ci.high, win.n ? win.oracle_dc / win.n : 0.0);
      return std::string(buf);
    });
    row("Regret / encounter", [](const PolicyRun& r) {
      if (r.policy == "sumo_native" || r.encounters.empty()) return std::string("-");
      double regret = 0;
      for (const EncounterRecord& e : r.encounters) regret += e.beyond.regret;
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.4f (total %.1f)", regret / r.encounters.size(), regret);
      return std::string(buf);
    });
    row("Mean trust start/end", [](const PolicyRun& r) {
      if (r.policy == "sumo_native") return std::string("-");
      char buf[96];
      if (r.beyond.long_run)
        std::snprintf(buf, sizeof buf, "%.3f / %.3f (long run %.3f)", r.beyond.initial_mean_trust,
                      r.beyond.final_mean_trust, r.beyond.expected_long_run_mean);
      else
        std::snprintf(buf, sizeof buf, "%.3f / %.3f", r.beyond.initial_mean_trust,
                      r.beyond.final_mean_trust);
      return std::string(buf);
    });
  }
  const bool stalled = std::any_of(runs.begin(), runs.end(),
                                   [](const PolicyRun& r) { return !r.stalls.empty(); });
  if (stalled) {
    out << std::setw(w0) << "Stalled junctions";
    for (const PolicyRun& r : runs)
      out << std::setw(w)
          << (r.stalls.empty() ? std::string("none")
                               : std::to_string(r.stalls.size()) +
                                     (r.stall_error.empty() ? " (recorded)" : " (run stopped)"));
    out << "\n";
  }
  out << "(rate [95% Wilson interval] th = library theory for the same parameters)\n";
  if (network)
    out << "(delay: SUMO's tripinfo of every trip departed after the warm-up, finished or "
           "still in the network at the end)\n";
  for (const PolicyRun& r : runs) {
    if (r.stalls.empty()) continue;
    out << "stalled: " << PolicyLabel(r.policy) << " at";
    for (std::size_t k = 0; k < r.stalls.size(); ++k) {
      char buf[64];
      std::snprintf(buf, sizeof buf, " since t = %.1f s", r.stalls[k].since);
      out << (k ? ", " : " ") << r.stalls[k].junction << buf;
    }
    out << (r.stall_error.empty()
                ? "; its figures are from a stalled run"
                : "; the run stopped there (scenario.stall_action: error): its figures are up to "
                  "the stall")
        << "\n";
  }
  if (AnyBeyond(runs))
    out << "(or = the oracle, TA-EBP for each HV's exact trust, on the same encounters; regret "
           "= DC lost + r x collisions against it)\n";
  if (flagged) out << "! the theory lies outside the measured rate's 95% interval\n";
  for (const std::string& warning : warnings) out << "warning: " << warning << "\n";
}

void WriteFilesAtomically(const std::string& dir,
                          const std::vector<std::pair<std::string, std::string>>& files) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const std::string suffix = ".tmp." + std::to_string(::getpid());
  std::vector<fs::path> temps;
  auto fail = [](const fs::path& p, const char* what) {
    return std::runtime_error("cannot write " + p.string() + ": " + what + ": " +
                              std::strerror(errno));
  };
  try {
    // Each file in full, on disk (fsync), under a temporary name ...
    for (const auto& [name, content] : files) {
      const fs::path tmp = fs::path(dir) / (name + suffix);
      const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (fd < 0) throw fail(tmp, "open");
      temps.push_back(tmp);
      std::size_t done = 0;
      while (done < content.size()) {
        const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
          const std::runtime_error e = fail(tmp, "write");
          ::close(fd);
          throw e;
        }
        done += static_cast<std::size_t>(n);
      }
      if (::fsync(fd) != 0) {
        const std::runtime_error e = fail(tmp, "fsync");
        ::close(fd);
        throw e;
      }
      if (::close(fd) != 0) throw fail(tmp, "close");
    }
  } catch (...) {
    std::error_code ec;
    for (const fs::path& t : temps) fs::remove(t, ec);
    throw;
  }
  // ... then renamed into place, and the folder's entries synced.
  for (std::size_t i = 0; i < files.size(); ++i)
    fs::rename(temps[i], fs::path(dir) / files[i].first);
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace taebp
