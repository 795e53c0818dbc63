#include "taebp/report/report.h"

#include "taebp/config/policies.h"
#include "taebp/base/number_text.h"

#include "metric_facts.h"
#include "taebp/report/clustered.h"
#include "taebp/report/metrics.h"
#include "taebp/report/paired.h"
#include "taebp/report/sample_spool.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

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

// One metric's value as summary.json writes it (metrics.h): null where undefined.
json MetricJson(const Metric& m, double v) {
  if (!std::isfinite(v)) return nullptr;
  switch (m.type) {
    case MetricType::kCount: return static_cast<long long>(v);
    case MetricType::kFlag: return v != 0;
    case MetricType::kReal: return v;
  }
  return v;
}

// A CSV cell of a metric's JSON value: empty for null, 1 / 0 for a flag.
std::string JsonCell(const json& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return NumberText(v.get<double>());
  return CsvCell(v.get<std::string>());
}

constexpr double kNoPer = std::numeric_limits<double>::quiet_NaN();

// Every metric of `level` in scope for the run, in table order, with a rate's
// 95 % interval clustered by HV (clustered.h) as NAME_lo / NAME_hi, its design
// effect NAME_deff and the HVs it was estimated from NAME_clusters.
void PutMetrics(const MetricFacts& f, MetricLevel level, json* out) {
  std::optional<std::vector<MetricFacts>> hvs;  // the rates' clusters, once
  for (const Metric& m : RunMetrics()) {
    if (!(m.levels & level) || !InScope(m.scope, *f.run)) continue;
    const double per = m.per ? FindMetric(m.per)->value(f) : kNoPer;
    // Undefined (no encounter, no game, ...): null, with its interval.
    const bool undefined = MetricUndefined(m, f.run->policy, per);
    const double value = m.value(f);
    (*out)[m.name] = undefined ? json(nullptr) : MetricJson(m, value);
    if (m.pool == Pool::kRate) {
      const std::string name = m.name;
      if (undefined || !std::isfinite(value)) {
        for (const char* c : {"_lo", "_hi", "_deff", "_clusters"}) (*out)[name + c] = nullptr;
        continue;
      }
      if (!hvs) hvs = HvFacts(f);
      const RateInterval ci = MetricInterval(m, *hvs, kZ95);
      (*out)[name + "_lo"] = ci.low;
      (*out)[name + "_hi"] = ci.high;
      (*out)[name + "_deff"] = ci.deff;
      (*out)[name + "_clusters"] = ci.clusters;
    }
  }
}

json JunctionJson(const PolicyRun& r, const JunctionRun& jr) {
  json j;
  j["junction"] = jr.id;
  j["type"] = jr.type;
  j["original_type"] = jr.original_type;
  j["rule"] = jr.rule;
  j["game_pairs"] = jr.game_pairs;
  PutMetrics(JunctionFacts(r, jr), kJunctionLevel, &j);
  json approaches = json::array();
  for (const ApproachStats& a : jr.approaches)
    approaches.push_back({{"lane", a.lane},
                          {"queue_max", a.queue_max},
                          {"queue_mean", a.samples ? a.queue_sum / a.samples : 0.0}});
  j["approaches"] = approaches;
  return j;
}

// The sections of a run beyond the paper (metrics.h RunSections).
void BeyondSectionsJson(const PolicyRun& r, json* out) {
  json& j = *out;
  const BeyondRun& b = r.beyond;
  if (b.long_run) {
    json eq = json::array();
    for (const TrustEquilibriumRecord& e : b.equilibria)
      eq.push_back({{"theta", e.theta}, {"kind", e.kind}, {"stable", e.stable}});
    json attractors = json::array();
    for (const TrustEquilibriumRecord& e : b.equilibria)
      if (e.stable) attractors.push_back(e.theta);
    j["trust_dynamics"] = {{"design_rule", b.design_rule},
                           {"equilibria", eq},
                           {"attractors", attractors}};
  } else {
    j["trust_dynamics"] = nullptr;
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
  out << "policy,junction,type,original_type,rule,game_pairs";
  for (const std::string& c : MetricColumns(kJunctionLevel, false)) out << ',' << c;
  out << '\n';
  for (const PolicyRun& r : runs) {
    for (const JunctionRun& jr : r.junctions) {
      // The same values as summary.json's junctions[] (one writer for both).
      const json j = JunctionJson(r, jr);
      out << CsvCell(r.policy) << ',' << CsvCell(jr.id) << ',' << CsvCell(jr.type) << ','
          << CsvCell(jr.original_type) << ',' << CsvCell(jr.rule) << ',' << jr.game_pairs;
      for (const std::string& c : MetricColumns(kJunctionLevel, false))
        out << ',' << JsonCell(j.contains(c) ? j[c] : json());
      out << '\n';
    }
  }
  return out.str();
}

Interval Wilson(long k, long n, double z) {
  if (n <= 0) return {0.0, 1.0};
  return WilsonAt(static_cast<double>(k) / static_cast<double>(n), static_cast<double>(n), z);
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
  p["sumo_patches"] = prov.sumo_patches;
  if (!stopped.reason.empty()) {
    root["stopped"] = stopped.reason;
    root["stopped_policy"] = stopped.policy;
    root["error"] = stopped.message;
    root["policies_not_run"] = stopped.not_run;
  }
  json& pol = root["policies"];
  pol = json::object();
  for (const PolicyRun& r : runs) {
    json j;
    PutMetrics(PolicyFacts(r), kPolicyLevel, &j);
    // The sections (metrics.h RunSections), in their order.
    j["hv_trust"] = r.hv_trust;
    j["scheme"] = {{"av_may_go", r.scheme.av_may_go},
                   {"nudge", r.scheme.nudge},
                   {"p_nudge_given_go", r.scheme.a},
                   {"p_nudge_given_stop", r.scheme.b}};
    j["sumo_warnings_first"] = r.sumo_warnings_first;
    json stalls = json::array();
    for (const StallRecord& st : r.stalls)
      stalls.push_back({{"junction", st.junction}, {"since", st.since}, {"detected", st.detected}});
    j["stalls"] = stalls;
    j["stall_error"] = r.stall_error.empty() ? json(nullptr) : json(r.stall_error);
    json junctions = json::array();
    for (const JunctionRun& jr : r.junctions) junctions.push_back(JunctionJson(r, jr));
    j["junctions"] = junctions;
    if (InScope(MetricScope::kBeyond, r)) BeyondSectionsJson(r, &j);
    pol[r.policy] = j;
  }
  if (AnyPaired(runs)) root["paired"] = PairedSummary(runs);
  return root.dump(2) + "\n";
}

namespace {

// The columns of timeseries.csv and hv_trust.csv: name, meaning and how a
// sample prints (README "Outputs" is generated from these: `taebp metrics`).
template <typename Sample>
struct SampleColumn {
  const char* name;
  const char* description;
  std::string (*cell)(const std::string& policy, const Sample& s);
};
std::string Int(long v) { return std::to_string(v); }
std::string Opt(double v) { return std::isfinite(v) ? NumberText(v) : std::string(); }

const std::vector<SampleColumn<TimeSample>>& TimeseriesColumns() {
  using C = SampleColumn<TimeSample>;
  static const std::vector<C> cols = {
      {"policy", "the policy", [](const std::string& policy, const TimeSample&) { return CsvCell(policy); }},
      {"time", "simulated time (s)", [](const std::string&, const TimeSample& t) { return NumberText(t.time); }},
      {"hvs", "HVs in the network", [](const std::string&, const TimeSample& t) { return Int(t.hvs); }},
      {"mean_trust", "their mean current trust",
       [](const std::string&, const TimeSample& t) { return Opt(t.mean_trust); }},
      {"mean_field_trust", "the mean-field prediction for the same HVs (dynamic trust)",
       [](const std::string&, const TimeSample& t) { return Opt(t.mean_field_trust); }},
      {"encounters", "encounters so far", [](const std::string&, const TimeSample& t) { return Int(t.encounters); }},
      {"dc", "DC choices so far", [](const std::string&, const TimeSample& t) { return Int(t.dc); }},
      {"collisions", "collisions so far", [](const std::string&, const TimeSample& t) { return Int(t.collisions); }},
      {"nudges", "nudges so far", [](const std::string&, const TimeSample& t) { return Int(t.nudges); }},
      {"failures", "nudged-then-DR encounters so far",
       [](const std::string&, const TimeSample& t) { return Int(t.failures); }},
      {"theory_dc", "sum of the encounters' predicted DC rates",
       [](const std::string&, const TimeSample& t) { return Opt(t.theory_dc); }},
      {"theory_collisions", "sum of their predicted collision rates",
       [](const std::string&, const TimeSample& t) { return Opt(t.theory_collisions); }},
      {"oracle_dc", "sum of the oracle's predicted DC rates",
       [](const std::string&, const TimeSample& t) { return NumberText(t.oracle_dc); }},
      {"oracle_collisions", "sum of the oracle's predicted collision rates",
       [](const std::string&, const TimeSample& t) { return NumberText(t.oracle_collisions); }},
      {"regret", "regret so far", [](const std::string&, const TimeSample& t) { return Opt(t.regret); }},
      {"expected_failures", "the fleet's predicted failures so far",
       [](const std::string&, const TimeSample& t) { return NumberText(t.expected_failures); }},
  };
  return cols;
}

const std::vector<SampleColumn<HvSample>>& HvTrustColumns() {
  using C = SampleColumn<HvSample>;
  static const std::vector<C> cols = {
      {"policy", "the policy", [](const std::string& policy, const HvSample&) { return CsvCell(policy); }},
      {"time", "simulated time (s)", [](const std::string&, const HvSample& h) { return NumberText(h.time); }},
      {"hv", "the HV's SUMO id", [](const std::string&, const HvSample& h) { return CsvCell(h.hv); }},
      {"trust", "its current trust", [](const std::string&, const HvSample& h) { return NumberText(h.trust); }},
      {"encounters", "its encounters so far", [](const std::string&, const HvSample& h) { return Int(h.encounters); }},
      {"belief_lower", "the fleet's lower bound on its trust (learned trust)",
       [](const std::string&, const HvSample& h) { return Opt(h.belief_lower); }},
      {"belief_upper", "the fleet's upper bound",
       [](const std::string&, const HvSample& h) { return Opt(h.belief_upper); }},
      {"belief_mean", "the fleet's posterior mean",
       [](const std::string&, const HvSample& h) { return Opt(h.belief_mean); }},
      {"design_trust", "the trust its next design would assume",
       [](const std::string&, const HvSample& h) { return Opt(h.design_trust); }},
      {"observations", "its responses the fleet learned from",
       [](const std::string&, const HvSample& h) { return Int(h.observations); }},
      {"contradictions", "of those, contradicting the belief",
       [](const std::string&, const HvSample& h) { return Int(h.contradictions); }},
  };
  return cols;
}

template <typename Sample>
std::vector<std::string> Names(const std::vector<SampleColumn<Sample>>& cols) {
  std::vector<std::string> names;
  for (const auto& c : cols) names.emplace_back(c.name);
  return names;
}

template <typename Sample>
std::string Header(const std::vector<SampleColumn<Sample>>& cols) {
  std::string out;
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + std::string(cols[i].name);
  return out + '\n';
}

template <typename Sample>
std::string Row(const std::vector<SampleColumn<Sample>>& cols, const std::string& policy,
                const Sample& s) {
  std::string out;
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i].cell(policy, s);
  return out + '\n';
}

// The header, then each run's spooled rows in the runs' order, streamed.
template <typename Copy>
void WriteSampleCsv(const std::vector<PolicyRun>& runs, const std::string& header,
                    const std::string& path, Copy copy) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) throw std::runtime_error("cannot create " + path + ": " + std::strerror(errno));
  try {
    if (std::fwrite(header.data(), 1, header.size(), out) != header.size())
      throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    for (const PolicyRun& r : runs)
      if (r.beyond.samples) copy(*r.beyond.samples, out);
  } catch (...) {
    std::fclose(out);
    throw;
  }
  if (std::fclose(out) != 0)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

template <typename Sample>
std::string ColumnsMarkdown(const char* file, const std::vector<SampleColumn<Sample>>& cols) {
  std::string out = std::string("`") + file + "`: ";
  for (std::size_t i = 0; i < cols.size(); ++i)
    out += (i ? "; " : "") + std::string("`") + cols[i].name + "` " + cols[i].description;
  return out + ".\n";
}

}  // namespace

std::vector<std::string> TimeseriesCsvColumns() { return Names(TimeseriesColumns()); }
std::vector<std::string> HvTrustCsvColumns() { return Names(HvTrustColumns()); }

std::string TimeseriesCsvRow(const std::string& policy, const TimeSample& s) {
  return Row(TimeseriesColumns(), policy, s);
}
std::string HvTrustCsvRow(const std::string& policy, const HvSample& s) {
  return Row(HvTrustColumns(), policy, s);
}

void WriteTimeseriesCsv(const std::vector<PolicyRun>& runs, const std::string& path) {
  WriteSampleCsv(runs, Header(TimeseriesColumns()), path,
                 [&](const SampleSpool& spool, std::FILE* out) { spool.CopyTimeRows(out, path); });
}

void WriteHvTrustCsv(const std::vector<PolicyRun>& runs, const std::string& path) {
  WriteSampleCsv(runs, Header(HvTrustColumns()), path,
                 [&](const SampleSpool& spool, std::FILE* out) { spool.CopyHvRows(out, path); });
}

std::string SampleColumnsMarkdown() {
  return ColumnsMarkdown("timeseries.csv", TimeseriesColumns()) + "\n" +
         ColumnsMarkdown("hv_trust.csv", HvTrustColumns());
}

}  // namespace taebp
