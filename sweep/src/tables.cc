// The sweep's tables from its journal (plan.h): results.csv and
// results.jsonl (a row per task and policy; reused runs name their source)
// and aggregate.csv (a row per point and policy, pooled over replicates).
#include "taebp/sweep/plan.h"

#include "plan_values.h"
#include "taebp/config/policies.h"
#include "taebp/base/number_text.h"
#include "taebp/report/clustered.h"
#include "taebp/report/metrics.h"
#include "taebp/report/report.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace taebp::sweep {

using namespace internal;

namespace {

// CSV text of a JSON value (null: empty cell).
std::string Cell(const Json& v) {
  if (v.is_null()) return "";
  if (v.is_number_unsigned()) return std::to_string(v.get<unsigned long long>());
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number_float()) {
    const double d = v.get<double>();
    return std::isfinite(d) ? NumberText(d) : "";
  }
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_string()) return CsvCell(v.get<std::string>());
  return CsvCell(Dump(v));
}

double Number(const Json& v) {
  if (v.is_number()) return v.get<double>();
  return std::nan("");
}

// The entries' rows for every task of the plan that has one, in task order.
template <typename F>
void ForEachRow(const Plan& plan, const Journal& journal, F&& emit) {
  for (const Task& task : plan.tasks) {
    const auto it = journal.entries.find(task.index);
    if (it == journal.entries.end()) continue;
    const Point& point = plan.points[static_cast<std::size_t>(task.point)];
    for (const std::string& policy : point.policies) {
      // A reused run: the earlier task's entry, named in reused_from.
      const auto reused = task.reused_from.find(policy);
      const Json* entry = &it->second;
      std::string reused_from;
      if (reused != task.reused_from.end()) {
        const auto source = journal.entries.find(reused->second);
        if (source == journal.entries.end()) continue;  // not run yet: missing
        entry = &source->second;
        const Task& from = plan.tasks[static_cast<std::size_t>(reused->second)];
        reused_from = std::to_string(from.point) + "-" + std::to_string(from.replicate);
      }
      const Json& e = *entry;
      const bool ok = IsOk(e);
      Json metrics = Json::object();
      const Json* m = nullptr;
      if (ok && e.contains("policies") && e["policies"].contains(policy))
        m = &e["policies"][policy];
      for (const Metric& metric : RunMetrics()) {
        if (!(metric.levels & kPolicyLevel)) continue;
        // Undefined where what it is per (encounters, held, ...) is 0, or a
        // prediction of a policy without a game: empty (metrics.h).
        const bool undefined =
            m && MetricUndefined(metric, policy,
                                 metric.per && m->contains(metric.per)
                                     ? Number((*m)[metric.per])
                                     : std::nan(""));
        for (const std::string& col : MetricColumns(metric, false)) {
          if (!m || !m->contains(col) || undefined)
            metrics[col] = nullptr;
          else
            metrics[col] = (*m)[col];
        }
      }
      const std::string status = ok && !m ? "failed" : e.value("status", "failed");
      const std::string error = ok && !m ? "policy " + policy + " missing from summary.json"
                                         : e.value("error", "");
      emit(task, point, policy, status, error, metrics, reused_from);
    }
  }
}

}  // namespace

const std::vector<std::string>& MetricColumns() {
  static const std::vector<std::string> cols = taebp::MetricColumns(kPolicyLevel, false);
  return cols;
}

std::string ResultsCsv(const Plan& plan, const Journal& journal) {
  std::ostringstream out;
  out << "point,replicate,seed";
  for (const auto& c : plan.columns) out << ',' << CsvCell(c);
  out << ",policy,status,error,reused_from";
  for (const auto& c : MetricColumns()) out << ',' << c;
  out << '\n';
  ForEachRow(plan, journal, [&](const Task& t, const Point& p, const std::string& policy,
                                const std::string& status, const std::string& error,
                                const Json& metrics, const std::string& reused_from) {
    out << t.point << ',' << t.replicate << ',' << t.seed;
    for (const auto& v : p.values) out << ',' << CsvCell(v);
    out << ',' << CsvCell(policy) << ',' << status << ',' << CsvCell(error) << ','
        << reused_from;
    for (const auto& c : MetricColumns()) out << ',' << Cell(metrics[c]);
    out << '\n';
  });
  return out.str();
}

std::string ResultsJsonl(const Plan& plan, const Journal& journal) {
  std::string out;
  ForEachRow(plan, journal, [&](const Task& t, const Point& p, const std::string& policy,
                                const std::string& status, const std::string& error,
                                const Json& metrics, const std::string& reused_from) {
    Json row;
    row["point"] = t.point;
    row["replicate"] = t.replicate;
    row["seed"] = t.seed;
    for (std::size_t k = 0; k < plan.columns.size(); ++k)
      row[plan.columns[k]] = ValueJson(p.values[k]);
    row["policy"] = policy;
    row["status"] = status;
    row["error"] = error;
    row["reused_from"] = reused_from;
    for (const auto& c : MetricColumns()) row[c] = metrics[c];
    out += Dump(row) + "\n";
  });
  return out;
}

namespace {

// A (point, policy)'s runs in the journal.
struct Acc {
  long ok = 0, failed = 0;
  std::vector<Json> runs;  // the metrics of each run that finished
};

// (point, policy) in point order, then the point's policy order.
std::map<int, std::map<std::string, Acc>> Accumulate(const Plan& plan, const Journal& journal) {
  std::map<int, std::map<std::string, Acc>> acc;
  ForEachRow(plan, journal, [&](const Task& t, const Point&, const std::string& policy,
                                const std::string& status, const std::string&,
                                const Json& m, const std::string&) {
    Acc& a = acc[t.point][policy];
    if (status != "ok") {
      ++a.failed;
      return;
    }
    ++a.ok;
    a.runs.push_back(m);
  });
  return acc;
}

std::string NumCell(double v) { return std::isfinite(v) ? NumberText(v) : std::string(); }

double MetricValue(const Json& m, const std::string& key) {
  return m.contains(key) ? Number(m[key]) : std::nan("");
}

std::vector<std::string> PooledSum(const Metric& metric, const std::vector<double>& xs) {
  if (xs.empty()) return std::vector<std::string>{""};
  if (metric.type == MetricType::kReal) {
    double sum = 0;
    for (double x : xs) sum += x;
    return std::vector<std::string>{NumCell(sum)};
  }
  long long sum = 0;
  for (double x : xs) sum += std::llround(x);
  return std::vector<std::string>{std::to_string(sum)};
}

std::vector<std::string> RateCells(const Metric& metric, const std::vector<Json>& runs) {
  const std::string name = metric.name;
  // Clustered by HV within each run and by run (report/clustered.h).
  std::vector<RunRate> rates;
  for (const Json& m : runs) {
    const double c = MetricValue(m, metric.count), t = MetricValue(m, metric.per);
    if (!std::isfinite(c) || !std::isfinite(t)) continue;
    const double deff = MetricValue(m, name + "_deff");
    const double clusters = MetricValue(m, name + "_clusters");
    rates.push_back({c, t, std::isfinite(deff) ? deff : 1.0,
                     std::isfinite(clusters) ? std::lround(clusters) : 0L});
  }
  double trials = 0;
  for (const RunRate& r : rates) trials += r.n;
  if (!(trials > 0)) return std::vector<std::string>{"", "", "", "", ""};
  const RateInterval ci = PooledRate(rates);
  return std::vector<std::string>{NumCell(ci.rate), NumCell(ci.low), NumCell(ci.high),
                                  NumCell(ci.deff), std::to_string(ci.clusters)};
}

std::vector<std::string> PooledWeighted(const Metric& metric, const std::vector<Json>& runs,
                                        const std::vector<double>& xs) {
  const std::string name = metric.name;
  // ref + sum w (x - ref) / sum w: exact when every run has the same
  // value (a fixed trust's prediction).
  bool has_ref = false;
  double ref = 0, wsum = 0, dev = 0;
  for (const Json& m : runs) {
    const double w = MetricValue(m, metric.per), x = MetricValue(m, name);
    if (!std::isfinite(w) || w <= 0 || !std::isfinite(x)) continue;
    if (!has_ref) has_ref = true, ref = x;
    wsum += w;
    dev += w * (x - ref);
  }
  if (wsum > 0) return std::vector<std::string>{NumCell(ref + dev / wsum)};
  if (metric.pool == Pool::kWeighted || xs.empty()) return std::vector<std::string>{""};
  double sum = 0;  // no encounter anywhere: the prediction's plain mean
  for (double x : xs) sum += x;
  return std::vector<std::string>{NumCell(sum / static_cast<double>(xs.size()))};
}

std::vector<std::string> PooledMean(const std::vector<double>& xs) {
  if (xs.empty()) return std::vector<std::string>{"", ""};
  double sum = 0;
  for (double x : xs) sum += x;
  const double mean = sum / static_cast<double>(xs.size());
  if (xs.size() < 2) return std::vector<std::string>{NumCell(mean), ""};
  double ss = 0;
  for (double x : xs) ss += (x - mean) * (x - mean);
  return std::vector<std::string>{
      NumCell(mean), NumCell(std::sqrt(ss / static_cast<double>(xs.size() - 1)))};
}

// One metric pooled over runs (metrics.h Pool): its aggregate cells.
std::vector<std::string> Pooled(const Metric& metric, const std::vector<Json>& runs) {
  const std::string name = metric.name;
  std::vector<double> xs;  // the runs' defined values
  for (const Json& m : runs)
    if (const double x = MetricValue(m, name); std::isfinite(x)) xs.push_back(x);
  switch (metric.pool) {
    case Pool::kSum: return PooledSum(metric, xs);
    case Pool::kRate: return RateCells(metric, runs);
    case Pool::kWeighted:
    case Pool::kPrediction: return PooledWeighted(metric, runs, xs);
    case Pool::kMean: return PooledMean(xs);
    case Pool::kMax: {
      if (xs.empty()) return std::vector<std::string>{""};
      return std::vector<std::string>{NumCell(*std::max_element(xs.begin(), xs.end()))};
    }
    case Pool::kNone: break;
  }
  return std::vector<std::string>{};
}

}  // namespace

std::string AggregateCsv(const Plan& plan, const Journal& journal) {
  const std::map<int, std::map<std::string, Acc>> acc = Accumulate(plan, journal);
  std::ostringstream out;
  out << "point";
  for (const auto& c : plan.columns) out << ',' << CsvCell(c);
  out << ",policy,runs_ok,runs_failed";
  for (const std::string& c : taebp::MetricColumns(kPolicyLevel, true)) out << ',' << c;
  out << '\n';
  for (const auto& [point_index, by_policy] : acc) {
    const Point& p = plan.points[static_cast<std::size_t>(point_index)];
    for (const std::string& policy : p.policies) {
      const auto it = by_policy.find(policy);
      if (it == by_policy.end()) continue;
      const Acc& a = it->second;
      out << point_index;
      for (const auto& v : p.values) out << ',' << CsvCell(v);
      out << ',' << CsvCell(policy) << ',' << a.ok << ',' << a.failed;
      for (const Metric& metric : RunMetrics()) {
        if (!(metric.levels & kPolicyLevel)) continue;
        const std::vector<std::string> cells = Pooled(metric, a.runs);
        for (const std::string& c : cells) out << ',' << c;
      }
      out << '\n';
    }
  }
  return out.str();
}

}  // namespace taebp::sweep
