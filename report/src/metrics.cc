#include "taebp/report/metrics.h"

#include "taebp/config/policies.h"

#include "metric_facts.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace taebp {

double Rate(long k, long n) { return n > 0 ? static_cast<double>(k) / n : 0.0; }
double PerHour(double count, double seconds) { return seconds > 0 ? count * 3600.0 / seconds : 0.0; }

void AddEncounter(const PolicyRun& r, const EncounterRecord& e, EncounterStats* s) {
  ++s->n;
  s->collisions += e.collision;
  s->dc += e.hv_dc;
  s->theory_dc_sum += e.theory_dc;
  s->theory_collision_sum += e.theory_collision;
  if (e.commanded > 0) {
    ++s->nudges;
    s->commanded_sum += e.commanded;
    s->observed_sum += e.observed;
    const double excess = e.observed - e.commanded;
    s->max_abs_error = std::max(s->max_abs_error, std::abs(excess));
    s->min_excess = s->any_nudge ? std::min(s->min_excess, excess) : excess;
    s->any_nudge = true;
  }
  if (r.ssm.on && !e.collision) {
    bool any = false;
    for (int k = 0; k < kSsmMeasures; ++k) {
      const SsmMeasure m = static_cast<SsmMeasure>(k);
      if (!SsmPasses(r.ssm.rules, m, e.ssm.Value(m))) continue;
      any = true;
      ++s->near_misses_by[k];
    }
    s->near_misses += any;
  }
}

EncounterStats ComputeEncounterStats(const PolicyRun& r, const std::string& junction) {
  EncounterStats s;
  for (const EncounterRecord& e : r.encounters)
    if (junction.empty() || e.junction == junction) AddEncounter(r, e, &s);
  return s;
}

double LastHourFrom(const PolicyRun& r) {
  const double start = r.simulated_seconds - r.measured_seconds;
  return std::max(start, r.simulated_seconds - 3600.0);
}

void AddLastHour(const EncounterRecord& e, LastHourWindow* w) {
  if (e.time < w->from) return;
  ++w->n;
  w->dc += e.hv_dc;
  w->collisions += e.collision;
  w->theory_dc += e.theory_dc;
  w->theory_collisions += e.theory_collision;
  w->oracle_dc += e.beyond.oracle_dc;
}

LastHourWindow LastHour(const PolicyRun& r) {
  LastHourWindow w;
  w.from = LastHourFrom(r);
  for (const EncounterRecord& e : r.encounters) AddLastHour(e, &w);
  return w;
}

std::vector<MetricFacts> HvFacts(const MetricFacts& f) {
  const PolicyRun& r = *f.run;
  std::map<std::string, MetricFacts> by_hv;
  for (const EncounterRecord& e : r.encounters) {
    if (f.junction && e.junction != f.junction->id) continue;
    auto [it, fresh] = by_hv.try_emplace(e.hv);
    MetricFacts& c = it->second;
    if (fresh) {
      c.run = f.run;
      c.junction = f.junction;
      c.last_hour.from = LastHourFrom(r);
    }
    AddEncounter(r, e, &c.s);
    if (!f.junction) AddLastHour(e, &c.last_hour);
  }
  std::vector<MetricFacts> out;
  out.reserve(by_hv.size());
  for (auto& [hv, c] : by_hv) out.push_back(c);
  return out;
}

RateInterval MetricInterval(const Metric& m, const std::vector<MetricFacts>& hvs, double z) {
  const Metric* count = FindMetric(m.count);
  const Metric* per = FindMetric(m.per);
  std::vector<ClusterCount> clusters;
  clusters.reserve(hvs.size());
  for (const MetricFacts& h : hvs) clusters.push_back({count->value(h), per->value(h)});
  return ClusteredRate(clusters, z);
}

RateInterval RunRateInterval(const PolicyRun& r, const std::string& name, double z) {
  const Metric* m = FindMetric(name);
  if (!m || m->pool != Pool::kRate)
    throw std::invalid_argument("RunRateInterval: '" + name + "' is not a rate metric");
  return MetricInterval(*m, HvFacts(PolicyFacts(r)), z);
}

MetricFacts PolicyFacts(const PolicyRun& r) {
  MetricFacts f;
  f.run = &r;
  f.s = ComputeEncounterStats(r);
  f.last_hour = LastHour(r);
  BeyondSums& b = f.beyond;
  for (const EncounterRecord& e : r.encounters) {
    b.oracle_dc += e.beyond.oracle_dc;
    b.oracle_collision += e.beyond.oracle_collision;
    b.dc_lost += e.beyond.oracle_dc - e.theory_dc;
    b.collisions += e.theory_collision - e.beyond.oracle_collision;
    b.regret += e.beyond.regret;
    b.failures += e.commanded > 0 && !e.hv_dc;
    if (e.commanded > 0 && std::isfinite(e.beyond.failure_probability))
      b.expected_failures += e.beyond.failure_probability;
  }
  return f;
}

MetricFacts JunctionFacts(const PolicyRun& r, const JunctionRun& j) {
  MetricFacts f;
  f.run = &r;
  f.junction = &j;
  f.s = ComputeEncounterStats(r, j.id);
  return f;
}

bool MetricUndefined(const Metric& m, const std::string& policy, double per) {
  if (m.pool == Pool::kPrediction) return !PlaysGame(policy);
  return m.per != nullptr && per == 0;
}

bool InScope(MetricScope s, const PolicyRun& r) {
  switch (s) {
    case MetricScope::kAll: return true;
    case MetricScope::kNetwork: return r.scenario_kind == "network";
    case MetricScope::kBeyond: return r.beyond.on && PlaysGame(r.policy);
    case MetricScope::kSsm: return r.ssm.on;
  }
  return false;
}



const Metric* FindMetric(const std::string& name) {
  static const std::map<std::string, const Metric*> index = [] {
    std::map<std::string, const Metric*> m;
    for (const Metric& x : RunMetrics()) m[x.name] = &x;
    return m;
  }();
  const auto it = index.find(name);
  return it == index.end() ? nullptr : it->second;
}

const std::vector<MetricSection>& RunSections() {
  static const std::vector<MetricSection> sections = {
      {"hv_trust", false, MetricScope::kAll, nullptr, "each HV's drawn trust, in HV order"},
      {"scheme", false, MetricScope::kAll, nullptr,
       "the committed scheme: av_may_go, nudge (m), p_nudge_given_go, p_nudge_given_stop"},
      {"sumo_warnings_first", false, MetricScope::kAll, "sumo_warnings.first",
       "the first few of SUMO's warnings other than its collision reports (those are the "
       "rows of collisions.csv)"},
      {"stalls", false, MetricScope::kAll, nullptr,
       "every stall found: junction, since (last crossing, s), detected (s)"},
      {"stall_error", false, MetricScope::kAll, nullptr,
       "the stall that stopped the run (scenario.stall_action: error), or null"},
      {"junctions", false, MetricScope::kAll, nullptr,
       "one object per controlled junction: its junction-level metrics and the fields below"},
      {"trust_dynamics", false, MetricScope::kBeyond, nullptr,
       "dynamic trust: design_rule, equilibria (theta, kind, stable), attractors; else null"},
      {"noise", false, MetricScope::kBeyond, nullptr,
       "perception noise: kind, scale, bias, delta, design, population_design; else null"},
      {"junction", true, MetricScope::kAll, "junctions[].id", "SUMO's junction id"},
      {"type", true, MetricScope::kAll, nullptr, "the junction type SUMO ran"},
      {"original_type", true, MetricScope::kAll, nullptr, "the type in the user's network"},
      {"rule", true, MetricScope::kAll, nullptr, "all_way_stop or two_way_stop"},
      {"game_pairs", true, MetricScope::kAll, nullptr,
       "movement pairs on which an AV and an HV can ever meet as a game under the run's "
       "settings (two conflicting stop lines; with scenario.major_road also a stop line "
       "against the major road); 0: no game can form here, whatever the traffic"},
      {"approaches", true, MetricScope::kAll, nullptr,
       "summary.json only: per approach lane, queue_max and queue_mean"},
  };
  return sections;
}

std::vector<std::string> MetricColumns(const Metric& m, bool aggregate) {
  if (aggregate && m.pool == Pool::kNone) return {};
  std::vector<std::string> cols = {m.name};
  if (m.pool == Pool::kRate)
    for (const char* c : {"_lo", "_hi", "_deff", "_clusters"}) cols.push_back(m.name + std::string(c));
  if (aggregate && m.pool == Pool::kMean) cols.push_back(std::string(m.name) + "_sd");
  return cols;
}

std::vector<std::string> MetricColumns(MetricLevel level, bool aggregate) {
  std::vector<std::string> cols;
  for (const Metric& m : RunMetrics()) {
    if (!(m.levels & level)) continue;
    for (std::string& c : MetricColumns(m, aggregate)) cols.push_back(std::move(c));
  }
  return cols;
}

const char* ToString(Pool p) {
  switch (p) {
    case Pool::kSum: return "sum";
    case Pool::kRate: return "pooled rate, 95 % interval clustered by HV and run";
    case Pool::kWeighted: return "mean weighted by its per";
    case Pool::kPrediction: return "mean weighted by encounters";
    case Pool::kMean: return "mean and SD over runs";
    case Pool::kMax: return "max";
    case Pool::kNone: return "not pooled";
  }
  return "?";
}

const char* ToString(MetricType t) {
  switch (t) {
    case MetricType::kCount: return "count";
    case MetricType::kReal: return "real";
    case MetricType::kFlag: return "flag";
  }
  return "?";
}

const char* ToString(MetricScope s) {
  switch (s) {
    case MetricScope::kAll: return "";
    case MetricScope::kNetwork: return "network";
    case MetricScope::kBeyond: return "beyond";
    case MetricScope::kSsm: return "ssm";
  }
  return "?";
}

namespace {

std::string Pooled(const Metric& m) {
  std::string per = m.per ? m.per : "";
  switch (m.pool) {
    case Pool::kSum: return "sum";
    case Pool::kRate: return std::string("sum ") + m.count + " / sum " + per;
    case Pool::kWeighted: return "mean weighted by " + per;
    case Pool::kPrediction: return "mean weighted by " + per + " (plain mean without any)";
    case Pool::kMean: return "mean, `_sd`";
    case Pool::kMax: return "max";
    case Pool::kNone: return "-";
  }
  return "?";
}

}  // namespace

std::string MetricsMarkdown() {
  std::ostringstream out;
  out << "| metric | unit | where | over seeds | meaning |\n"
         "|---|---|---|---|---|\n";
  for (const Metric& m : RunMetrics()) {
    std::string where;
    if (m.levels & kPolicyLevel) where = "run";
    if (m.levels & kJunctionLevel) where += where.empty() ? "junction" : ", junction";
    if (m.scope != MetricScope::kAll) where += std::string(" (") + ToString(m.scope) + ")";
    std::string name = std::string("`") + m.name + "`";
    if (m.pool == Pool::kRate) name += " `_lo` `_hi` `_deff` `_clusters`";
    std::string meaning = m.description;
    if (m.per && (m.pool == Pool::kRate || m.pool == Pool::kWeighted ||
                  (m.pool == Pool::kMean)))
      meaning += std::string("; empty where `") + m.per + "` is 0";
    if (m.pool == Pool::kPrediction) meaning += std::string("; empty for ") + SumoNative().name + " (it plays no game)";
    out << "| " << name << " | " << m.unit << " | " << where << " | " << Pooled(m) << " | "
        << meaning << " |\n";
  }
  out << "\nSections of `summary.json` (not metrics):\n\n";
  for (const MetricSection& s : RunSections())
    out << "- `" << (s.junction ? "junctions[]." : "") << s.name << "`: " << s.description
        << "\n";
  return out.str();
}

std::string RenamesMarkdown() {
  std::ostringstream out;
  out << "| before 0.2 | now |\n|---|---|\n";
  for (const Metric& m : RunMetrics())
    if (m.was)
      out << "| `" << m.was << "` | `" << m.name << "`"
          << (m.pool == Pool::kRate ? std::string(", `") + m.name + "_lo`, `" + m.name + "_hi`" : "")
          << " |\n";
  for (const MetricSection& s : RunSections())
    if (s.was) out << "| `" << s.was << "` | `" << (s.junction ? "junctions[]." : "") << s.name
                   << "` |\n";
  return out.str();
}

std::string MetricsJson() {
  using json = nlohmann::ordered_json;
  auto text = [](const char* s) { return s ? json(s) : json(nullptr); };
  json metrics = json::array();
  for (const Metric& m : RunMetrics()) {
    json levels = json::array();
    if (m.levels & kPolicyLevel) levels.push_back("run");
    if (m.levels & kJunctionLevel) levels.push_back("junction");
    const char* pools[] = {"sum", "rate", "weighted", "prediction", "mean", "max", "none"};
    metrics.push_back({{"name", m.name},
                       {"type", ToString(m.type)},
                       {"unit", m.unit},
                       {"levels", levels},
                       {"scope", m.scope == MetricScope::kAll ? "all" : ToString(m.scope)},
                       {"pool", pools[static_cast<int>(m.pool)]},
                       {"count", text(m.count)},
                       {"per", text(m.per)},
                       {"was", text(m.was)},
                       {"description", m.description},
                       {"columns", MetricColumns(m, false)},
                       {"aggregate_columns", MetricColumns(m, true)}});
  }
  json sections = json::array();
  for (const MetricSection& s : RunSections())
    sections.push_back({{"name", s.name},
                        {"level", s.junction ? "junction" : "run"},
                        {"scope", s.scope == MetricScope::kAll ? "all" : ToString(s.scope)},
                        {"was", text(s.was)},
                        {"description", s.description}});
  return json{{"metrics", metrics}, {"sections", sections}}.dump(1);
}

}  // namespace taebp
