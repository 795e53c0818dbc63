// The sweep's journal entries (plan.h): a finished task's line from its
// summary.json, the checks a line must pass to be read back, and the journal
// parsed into entries (the last entry of a task wins; corrupt lines named).
#include "taebp/sweep/plan.h"

#include "plan_values.h"
#include "taebp/config/policies.h"
#include "taebp/report/metrics.h"
#include "taebp/report/report.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace taebp::sweep {

using namespace internal;

namespace {

// Why a journal line (a JSON object of this sweep) cannot be a task's entry,
// or "" when it can: the fields the tables read, with their types.
std::string EntryProblem(const Json& e) {
  constexpr double kMaxCount = 9007199254740992.0;  // 2^53: exact in a double
  for (const char* k : {"point", "replicate"}) {
    if (!e.contains(k) || !e[k].is_number_integer())
      return std::string("\"") + k + "\" is missing or not an integer";
  }
  if (!e.contains("status") || !e["status"].is_string() ||
      (e["status"] != "ok" && e["status"] != "failed"))
    return "\"status\" is missing or not \"ok\" or \"failed\"";
  for (const char* k : {"error", "sumo_version"})
    if (e.contains(k) && !e[k].is_string()) return std::string("\"") + k + "\" is not a string";
  if (!e.contains("policies")) return IsOk(e) ? "\"policies\" is missing" : "";
  const Json& policies = e["policies"];
  if (!policies.is_object()) return "\"policies\" is not an object";
  for (auto it = policies.begin(); it != policies.end(); ++it) {
    if (!it.value().is_object()) return "\"policies." + it.key() + "\" is not an object";
    for (auto m = it.value().begin(); m != it.value().end(); ++m) {
      const Json& v = m.value();
      const std::string name = "\"policies." + it.key() + "." + m.key() + "\"";
      if (!v.is_null() && !v.is_number()) return name + " is not a number";
      if (v.is_number_float() && !std::isfinite(v.get<double>())) return name + " is not finite";
    }
    for (const Metric& metric : RunMetrics()) {  // counts: summed by AggregateCsv
      if (metric.type != MetricType::kCount) continue;
      const char* count = metric.name;
      if (!it.value().contains(count) || it.value()[count].is_null()) continue;
      const Json& v = it.value()[count];
      const bool ok = v.is_number_unsigned()
                          ? v.get<std::uint64_t>() <= static_cast<std::uint64_t>(kMaxCount)
                          : v.is_number_integer() && v.get<std::int64_t>() >= 0;
      if (!ok)
        return "\"policies." + it.key() + "." + count + "\" is not a count (an integer in [0, 2^53])";
    }
  }
  return "";
}

}  // namespace

Json ParseSummary(const std::string& summary_json) {
  try {
    return Json::parse(summary_json);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("summary.json is not valid JSON: ") + e.what());
  }
}

Json MetricsFromSummary(const Json& s, const std::vector<std::string>& policies) {
  Json out = Json::object();
  for (const std::string& p : policies) {
    if (!s.contains("policies") || !s["policies"].contains(p))
      throw std::runtime_error("summary.json has no results for policy " + p);
    const Json& j = s["policies"][p];
    if (!j.is_object()) throw std::runtime_error("summary.json: policies." + p + " is not an object");
    Json m = Json::object();
    for (const Metric& metric : RunMetrics()) {
      if (!(metric.levels & kPolicyLevel)) continue;
      for (const std::string& col : MetricColumns(metric, false)) {
        if (!j.contains(col)) {
          // Every run has the metrics of its scope (metrics.h); others are empty.
          if (metric.scope == MetricScope::kAll)
            throw std::runtime_error("summary.json: policies." + p + "." + col + " is missing");
          m[col] = nullptr;
          continue;
        }
        const Json& v = j[col];
        // Journal entries hold numbers only: a flag is 1 or 0.
        m[col] = v.is_boolean() ? Json(v.get<bool>() ? 1 : 0) : v;
      }
    }
    out[p] = m;
  }
  return out;
}

Json JournalEntry(const Plan& plan, const Task& task, const std::string& status,
                  const std::string& error, const Json& policies_metrics) {
  Json e;
  e["hash"] = plan.hash;
  e["point"] = task.point;
  e["replicate"] = task.replicate;
  e["seed"] = task.seed;
  Json values = Json::object();
  const Point& p = plan.points[static_cast<std::size_t>(task.point)];
  for (std::size_t k = 0; k < plan.columns.size(); ++k) values[plan.columns[k]] = p.values[k];
  e["values"] = values;
  e["status"] = status;
  e["error"] = error;
  e["policies"] = policies_metrics.is_null() ? Json::object() : policies_metrics;
  return e;
}

bool IsOk(const Json& entry) {
  return entry.is_object() && entry.contains("status") && entry["status"] == "ok";
}

Tally CountTasks(const std::vector<Task>& tasks, const Journal& journal) {
  Tally t;
  for (const Task& task : tasks) {
    const auto it = journal.entries.find(task.index);
    if (it == journal.entries.end()) ++t.missing;
    else if (IsOk(it->second)) ++t.ok;
    else ++t.failed;
  }
  return t;
}

bool AddEntry(Journal* journal, const Plan& plan, const Json& entry) {
  if (!entry.contains("point") || !entry.contains("replicate") ||
      !entry["point"].is_number_integer() || !entry["replicate"].is_number_integer())
    return false;
  const long point = entry["point"].get<long>();
  const long replicate = entry["replicate"].get<long>();
  // Entries outside the plan (e.g. replicates lowered since) stay in the
  // journal but not in the tables.
  if (point < 0 || point >= static_cast<long>(plan.points.size()) || replicate < 0 ||
      replicate >= plan.replicates)
    return false;
  const int index = static_cast<int>(point) * plan.replicates + static_cast<int>(replicate);
  auto it = journal->entries.find(index);
  if (it != journal->entries.end() && IsOk(it->second) && !IsOk(entry)) return false;
  journal->entries[index] = entry;
  return true;
}

Journal ParseJournal(const std::string& text, const Plan& plan, const std::string& origin) {
  Journal j;
  const auto last_newline = text.rfind('\n');
  j.valid_bytes = last_newline == std::string::npos ? 0 : last_newline + 1;
  j.partial_tail = j.valid_bytes < text.size();
  std::size_t start = 0, line_no = 0;
  while (start < j.valid_bytes) {
    const std::size_t end = text.find('\n', start);
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    ++line_no;
    if (Trim(line).empty()) continue;
    const std::string where = origin + ":" + std::to_string(line_no);
    Json e;
    try {
      e = Json::parse(line);
    } catch (const std::exception& ex) {
      // A torn or damaged line: its task simply runs again.
      j.corrupt.push_back(where + ": not valid JSON (" + ex.what() + ")");
      continue;
    }
    if (!e.is_object() || !e.contains("hash") || !e["hash"].is_string()) {
      j.corrupt.push_back(where + ": not a journal entry (no \"hash\")");
      continue;
    }
    const std::string hash = e["hash"].get<std::string>();
    if (hash != plan.hash)
      throw ConfigError(origin + ":" + std::to_string(line_no) +
                        ": the journal belongs to a different sweep (config hash " + hash +
                        ", this sweep " + plan.hash +
                        "): the config, its grid or the --set overrides differ; "
                        "use another --out or remove that directory");
    if (const std::string why = EntryProblem(e); !why.empty()) {
      j.corrupt.push_back(where + ": " + why);
      continue;
    }
    ++j.lines;
    AddEntry(&j, plan, e);
  }
  return j;
}

}  // namespace taebp::sweep
