#include "taebp/sweep/plan.h"

#include "taebp/config/policies.h"
#include "taebp/report/metrics.h"
#include "taebp/report/report.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

namespace taebp::sweep {
namespace {

constexpr const char* kFormat = "taebp-sweep/1";
constexpr std::size_t kMaxPoints = 100000;  // each one is validated up front (~0.15 ms)
constexpr std::size_t kMaxTasks = 10000000;

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::string JoinKeys(const std::vector<std::string>& keys) {
  std::string out;
  for (const auto& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
}

// A grid value as JSON with its YAML type (results.jsonl, sweep.json):
// 0.5 -> 0.5, ta_ebp -> "ta_ebp", [8, 8] -> [8, 8]; unparsable text stays text.
Json ValueJson(const std::string& text) {
  try {
    return Json::parse(YamlValueAsJson(text));
  } catch (const std::exception&) {
    return text;
  }
}

// CSV text of a JSON value (null: empty cell).
std::string Cell(const Json& v) {
  if (v.is_null()) return "";
  if (v.is_number_unsigned()) return std::to_string(v.get<unsigned long long>());
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number_float()) {
    const double d = v.get<double>();
    return std::isfinite(d) ? FormatDouble(d) : "";
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

std::string Dump(const Json& j, int indent) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}


bool SplitFlowSequence(const std::string& raw, std::vector<std::string>* items) {
  const std::string text = Trim(raw);
  items->clear();
  if (text.size() < 2 || text.front() != '[' || text.back() != ']') return false;
  int depth = 0;
  char quote = 0;
  std::string cur;
  bool any = false;
  for (std::size_t i = 1; i + 1 < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      cur += c;
      if (quote == '"' && c == '\\' && i + 2 < text.size()) {
        cur += text[++i];
      } else if (c == quote) {
        if (quote == '\'' && i + 2 < text.size() && text[i + 1] == '\'') cur += text[++i];
        else quote = 0;
      }
      continue;
    }
    if (c == '"' || c == '\'') quote = c;
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') --depth;
    if (depth < 0) return false;
    if (c == ',' && depth == 0) {
      items->push_back(Trim(cur));
      cur.clear();
      any = true;
      continue;
    }
    cur += c;
  }
  if (quote || depth != 0) return false;
  const std::string last = Trim(cur);
  if (any || !last.empty()) items->push_back(last);
  return true;
}

std::string ConfigHash(const ExperimentConfig& config) {
  ExperimentConfig c = config;
  if (c.sweep) c.sweep->replicates = 1;
  const std::string text = ToJson(c);
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a 64
  for (unsigned char ch : text) {
    h ^= ch;
    h *= 1099511628211ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::vector<std::string> Plan::PointOverrides(const Point& point) const {
  std::vector<std::string> out = overrides;
  for (std::size_t k = 0; k < columns.size(); ++k)
    out.push_back(columns[k] + "=" + point.values[k]);
  return out;
}

std::vector<std::string> Plan::TaskOverrides(const Task& task) const {
  std::vector<std::string> out = PointOverrides(points[static_cast<std::size_t>(task.point)]);
  out.push_back("scenario.seed=" + std::to_string(task.seed));
  if (!task.reused_from.empty() && !task.runs.empty()) {
    std::string list;
    for (const std::string& p : task.runs) list += (list.empty() ? "" : ", ") + p;
    out.push_back("policies=[" + list + "]");
  }
  return out;
}

std::size_t Plan::Runs() const {
  std::size_t n = 0;
  for (const Task& t : tasks) n += t.runs.size();
  return n;
}

std::size_t Plan::Reused() const {
  std::size_t n = 0;
  for (const Task& t : tasks) n += t.reused_from.size();
  return n;
}

namespace {

// Removes the dotted `key` ("scenario.major_road") from `j`, if there.
void EraseKey(Json* j, const std::string& key) {
  Json* at = j;
  std::size_t from = 0;
  for (;;) {
    const std::size_t dot = key.find('.', from);
    const std::string part = key.substr(from, dot == std::string::npos ? dot : dot - from);
    if (!at->is_object() || !at->contains(part)) return;
    if (dot == std::string::npos) {
      at->erase(part);
      return;
    }
    at = &(*at)[part];
    from = dot + 1;
  }
}

}  // namespace

namespace {

// RunIdentity of `policy` from the config already as JSON (`config_json`).
std::string IdentityOf(const Json& config_json, bool beyond, const std::string& policy) {
  Json j = config_json;
  j.erase("policies");
  j.erase("sweep");
  if (const PolicyInfo* info = FindPolicy(policy))
    for (const std::string& key : info->ignores) EraseKey(&j, key);
  Json id;
  id["policy"] = policy;
  id["beyond"] = beyond;
  id["config"] = j;
  return id.dump();
}

}  // namespace

std::string RunIdentity(const ExperimentConfig& config, const std::string& policy) {
  return IdentityOf(Json::parse(ToJson(config)), config.BeyondPaper(), policy);
}

Plan ExpandSweep(const std::string& config_text, const std::string& config_path,
                 const std::vector<std::string>& overrides, bool reuse) {
  Plan plan;
  plan.reuse = reuse;
  plan.config_text = config_text;
  plan.config_path = config_path;
  plan.overrides = overrides;
  plan.base = ParseExperimentConfig(config_text, config_path, overrides);
  if (!plan.base.sweep)
    throw ConfigError(config_path +
                      ": no 'sweep:' section (taebp sweep needs sweep.grid and sweep.replicates)");
  if (plan.base.scenario.outputs.Any())
    throw ConfigError(config_path +
                      ": scenario.outputs: SUMO's outputs are kept by `taebp run` (a folder per "
                      "run, DIR/<policy>/...); a sweep keeps its tables only: run the point you "
                      "want to look at with `taebp run CONFIG --set KEY=VALUE...`");
  plan.hash = ConfigHash(plan.base);
  const SweepConfig& spec = *plan.base.sweep;
  plan.replicates = spec.replicates;
  if (plan.replicates < 1)
    throw ConfigError(config_path + ": sweep.replicates = " + std::to_string(plan.replicates) +
                      " must be >= 1");

  std::set<std::string> seen;
  std::size_t total = 1;
  for (const auto& [key_spec, values] : spec.grid) {
    const std::string where = config_path + ": sweep.grid key '" + key_spec + "'";
    Axis axis;
    std::stringstream ss(key_spec);
    for (std::string k; std::getline(ss, k, ',');) {
      k = Trim(k);
      if (k.empty()) throw ConfigError(where + " has an empty key name");
      if (k == "sweep" || k.rfind("sweep.", 0) == 0)
        throw ConfigError(where + " cannot sweep the sweep section");
      if (!seen.insert(k).second)
        throw ConfigError(where + ": key '" + k + "' appears twice in the grid");
      axis.keys.push_back(k);
    }
    if (!key_spec.empty() && key_spec.back() == ',') throw ConfigError(where + " has an empty key name");
    if (axis.keys.empty()) throw ConfigError(where + " has no key name");
    if (values.empty()) throw ConfigError(where + " has no values");
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::string& v = values[i];
      if (axis.keys.size() == 1) {
        if (Trim(v).empty() || v == "~" || v == "null")
          throw ConfigError(where + ": value #" + std::to_string(i + 1) + " is empty");
        axis.values.push_back({v});
        continue;
      }
      std::vector<std::string> items;
      const std::string expected = "a list of " + std::to_string(axis.keys.size()) +
                                   " values (one per key: " + JoinKeys(axis.keys) + ")";
      if (!SplitFlowSequence(v, &items))
        throw ConfigError(where + ": value #" + std::to_string(i + 1) + " " + v + " is not " +
                          expected);
      if (items.size() != axis.keys.size())
        throw ConfigError(where + ": value #" + std::to_string(i + 1) + " " + v + " has " +
                          std::to_string(items.size()) + " entries, expected " + expected);
      for (std::size_t k = 0; k < items.size(); ++k)
        if (items[k].empty() || items[k] == "~" || items[k] == "null")
          throw ConfigError(where + ": value #" + std::to_string(i + 1) + " " + v +
                            " has an empty entry for key '" + axis.keys[k] + "'");
      axis.values.push_back(items);
    }
    total *= axis.values.size();
    if (total > kMaxPoints)
      throw ConfigError(config_path + ": sweep.grid has more than " + std::to_string(kMaxPoints) +
                        " points");
    for (const auto& k : axis.keys) plan.columns.push_back(k);
    plan.axes.push_back(std::move(axis));
  }

  if (total * static_cast<std::size_t>(plan.replicates) > kMaxTasks)
    throw ConfigError(config_path + ": sweep.replicates = " + std::to_string(plan.replicates) +
                      " times " + std::to_string(total) + " grid points is more than " +
                      std::to_string(kMaxTasks) + " tasks");

  // Every point's config is loaded and checked here, before any task runs: a
  // misspelt grid key or a bad value is refused up front, naming the point.
  // The text is parsed once (ExperimentTemplate).
  // The user's overrides are applied once and the sweep: section dropped
  // (ExperimentTemplate), so that each point costs the same however many
  // points there are (planning is linear in the points).
  const ExperimentTemplate config_template(config_text, config_path, overrides);
  std::size_t invalid = 0;
  std::string first_error;
  // Each run's identity and seed -> the first task that runs it.
  std::map<std::string, int> first_run;
  for (std::size_t idx = 0; idx < total; ++idx) {
    Point point;
    point.index = static_cast<int>(idx);
    std::vector<std::size_t> pick(plan.axes.size());
    std::size_t rest = idx;
    for (std::size_t a = plan.axes.size(); a-- > 0;) {
      pick[a] = rest % plan.axes[a].values.size();
      rest /= plan.axes[a].values.size();
    }
    for (std::size_t a = 0; a < plan.axes.size(); ++a)
      for (std::size_t k = 0; k < plan.axes[a].keys.size(); ++k)
        point.values.push_back(plan.axes[a].values[pick[a]][k]);
    // The point's own policies and seed (a grid may sweep either).
    point.policies = plan.base.policies;
    std::map<std::string, std::string> identities;  // policy -> RunIdentity at this point
    bool beyond = false, beyond_by_config = false;
    std::uint64_t seed = plan.base.scenario.seed;
    try {
      // Without its sweep: section (the same for every point, checked with
      // the base config); the point's own values only (the rest is in the template).
      std::vector<std::string> point_overrides;
      for (std::size_t k = 0; k < plan.columns.size(); ++k)
        point_overrides.push_back(plan.columns[k] + "=" + point.values[k]);
      ExperimentConfig c = config_template.Load(point_overrides);
      point.policies = c.policies;
      seed = c.scenario.seed;
      beyond = c.BeyondPaper();
      const Json config_json = Json::parse(ToJson(c));  // once per point
      for (const std::string& p : c.policies) identities[p] = IdentityOf(config_json, beyond, p);
      c.policies.clear();  // what else makes a run beyond the paper
      beyond_by_config = c.BeyondPaper();
    } catch (const ConfigError& e) {
      if (invalid++ == 0) {
        std::string values;
        for (std::size_t k = 0; k < plan.columns.size(); ++k)
          values += (k ? ", " : "") + plan.columns[k] + "=" + point.values[k];
        first_error = config_path + ": sweep.grid point " + std::to_string(idx) + " (" + values +
                      ") is not a valid config: " + e.what();
      }
    }
    for (int r = 0; r < plan.replicates; ++r) {
      Task t;
      t.point = point.index;
      t.replicate = r;
      t.index = point.index * plan.replicates + r;
      t.seed = seed + static_cast<std::uint64_t>(r);
      bool beyond_left = beyond_by_config;  // the runs' subset still beyond the paper?
      // A run: its identity and its seed.
      auto run_key = [&t](const std::string& identity) {
        return identity + "\nseed " + std::to_string(t.seed);
      };
      for (const std::string& p : point.policies) {
        const auto id = identities.find(p);
        const auto earlier = id == identities.end() || !reuse
                                 ? first_run.end()
                                 : first_run.find(run_key(id->second));
        if (earlier != first_run.end()) {
          t.reused_from[p] = earlier->second;
        } else {
          t.runs.push_back(p);
          const PolicyInfo* info = FindPolicy(p);
          beyond_left = beyond_left || (info && info->beyond_paper);
        }
      }
      // Running a subset must not change the runs' columns (BeyondPaper):
      // then the beyond-the-paper policies run again.
      if (beyond && !beyond_left && !t.runs.empty()) {
        for (auto it = t.reused_from.begin(); it != t.reused_from.end();) {
          const PolicyInfo* info = FindPolicy(it->first);
          if (info && info->beyond_paper) it = t.reused_from.erase(it);
          else ++it;
        }
        t.runs.clear();
        for (const std::string& p : point.policies)
          if (!t.reused_from.count(p)) t.runs.push_back(p);
      }
      for (const std::string& p : t.runs) {
        const auto id = identities.find(p);
        if (id != identities.end())
          first_run.emplace(run_key(id->second), t.index);
      }
      plan.tasks.push_back(t);
    }
    plan.points.push_back(std::move(point));
  }
  if (invalid > 0)
    throw ConfigError(first_error + (invalid > 1 ? " (and " + std::to_string(invalid - 1) +
                                                       " more invalid grid points)"
                                                 : std::string()) +
                      "; nothing was run");
  return plan;
}

const std::vector<std::string>& MetricColumns() {
  static const std::vector<std::string> cols = taebp::MetricColumns(kPolicyLevel, false);
  return cols;
}

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

std::string AggregateCsv(const Plan& plan, const Journal& journal) {
  struct Acc {
    long ok = 0, failed = 0;
    std::vector<Json> runs;  // the metrics of each run that finished
  };
  // (point, policy) in point order, then the point's policy order.
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
  auto num = [](double v) { return std::isfinite(v) ? FormatDouble(v) : std::string(); };
  // One metric pooled over runs (metrics.h Pool): its aggregate cells.
  auto pooled = [&](const Metric& metric, const std::vector<Json>& runs) {
    std::vector<std::string> cells;
    const std::string name = metric.name;
    auto value = [](const Json& m, const std::string& key) {
      return m.contains(key) ? Number(m[key]) : std::nan("");
    };
    std::vector<double> xs;  // the runs' defined values
    for (const Json& m : runs)
      if (const double x = value(m, name); std::isfinite(x)) xs.push_back(x);
    switch (metric.pool) {
      case Pool::kSum: {
        if (xs.empty()) return std::vector<std::string>{""};
        if (metric.type == MetricType::kReal) {
          double sum = 0;
          for (double x : xs) sum += x;
          return std::vector<std::string>{num(sum)};
        }
        long long sum = 0;
        for (double x : xs) sum += std::llround(x);
        return std::vector<std::string>{std::to_string(sum)};
      }
      case Pool::kRate: {
        long k = 0, n = 0;
        for (const Json& m : runs) {
          const double c = value(m, metric.count), t = value(m, metric.per);
          if (std::isfinite(c) && std::isfinite(t)) k += std::lround(c), n += std::lround(t);
        }
        if (n <= 0) return std::vector<std::string>{"", "", ""};
        const Interval ci = Wilson(k, n);
        return std::vector<std::string>{num(static_cast<double>(k) / static_cast<double>(n)),
                                        num(ci.low), num(ci.high)};
      }
      case Pool::kWeighted:
      case Pool::kPrediction: {
        // ref + sum w (x - ref) / sum w: exact when every run has the same
        // value (a fixed trust's prediction).
        bool has_ref = false;
        double ref = 0, wsum = 0, dev = 0;
        for (const Json& m : runs) {
          const double w = value(m, metric.per), x = value(m, name);
          if (!std::isfinite(w) || w <= 0 || !std::isfinite(x)) continue;
          if (!has_ref) has_ref = true, ref = x;
          wsum += w;
          dev += w * (x - ref);
        }
        if (wsum > 0) return std::vector<std::string>{num(ref + dev / wsum)};
        if (metric.pool == Pool::kWeighted || xs.empty()) return std::vector<std::string>{""};
        double sum = 0;  // no encounter anywhere: the prediction's plain mean
        for (double x : xs) sum += x;
        return std::vector<std::string>{num(sum / static_cast<double>(xs.size()))};
      }
      case Pool::kMean: {
        if (xs.empty()) return std::vector<std::string>{"", ""};
        double sum = 0;
        for (double x : xs) sum += x;
        const double mean = sum / static_cast<double>(xs.size());
        if (xs.size() < 2) return std::vector<std::string>{num(mean), ""};
        double ss = 0;
        for (double x : xs) ss += (x - mean) * (x - mean);
        return std::vector<std::string>{
            num(mean), num(std::sqrt(ss / static_cast<double>(xs.size() - 1)))};
      }
      case Pool::kMax: {
        if (xs.empty()) return std::vector<std::string>{""};
        return std::vector<std::string>{num(*std::max_element(xs.begin(), xs.end()))};
      }
      case Pool::kNone: break;
    }
    return std::vector<std::string>{};
  };

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
        const std::vector<std::string> cells = pooled(metric, a.runs);
        for (const std::string& c : cells) out << ',' << c;
      }
      out << '\n';
    }
  }
  return out.str();
}

Json SweepHeader(const Plan& plan, const std::string& shard, const std::string& sumo_version) {
  Json h;
  h["format"] = kFormat;
  h["config_hash"] = plan.hash;
  h["config_path"] = plan.config_path;
  h["overrides"] = plan.overrides;
  h["config_text"] = plan.config_text;
  h["config"] = Json::parse(ToJson(plan.base));
  Json axes = Json::array();
  for (const Axis& a : plan.axes) {
    Json values = Json::array();  // one list per grid value: one entry per key, typed
    for (const auto& value : a.values) {
      Json typed = Json::array();
      for (const std::string& v : value) typed.push_back(ValueJson(v));
      values.push_back(typed);
    }
    axes.push_back({{"keys", a.keys}, {"values", values}});
  }
  h["axes"] = axes;
  h["columns"] = plan.columns;
  h["points"] = plan.points.size();
  h["replicates"] = plan.replicates;
  h["tasks"] = plan.tasks.size();
  h["policies"] = plan.base.policies;
  // Policy runs simulated and reused (Task::runs, Task::reused_from).
  h["policy_runs"] = plan.Runs();
  h["policy_runs_reused"] = plan.Reused();
  h["reuse"] = plan.reuse;
  h["shard"] = shard.empty() ? Json(nullptr) : Json(shard);
  h["git_revision"] = BuildGitRevision();
  h["taebp_version"] = TaebpVersion();
  h["sumo_version"] = sumo_version;
  return h;
}

}  // namespace taebp::sweep
