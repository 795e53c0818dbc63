// The sweep's plan (plan.h): the grid of a config expanded into points and
// tasks, each policy run keyed by what can change its result (a run is reused
// where nothing it reads differs), and the sweep folder's header. The
// journal's entries are journal.cc, the tables tables.cc.
#include "taebp/sweep/plan.h"

#include "plan_values.h"
#include "taebp/config/policies.h"
#include "taebp/report/metrics.h"
#include "taebp/report/report.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

namespace taebp::sweep {

namespace internal {

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
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

}  // namespace internal

using namespace internal;

namespace {

constexpr const char* kFormat = "taebp-sweep/1";
constexpr std::size_t kMaxPoints = 100000;  // each one is validated up front (~0.15 ms)
constexpr std::size_t kMaxTasks = 10000000;

std::string JoinKeys(const std::vector<std::string>& keys) {
  std::string out;
  for (const auto& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
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

namespace {

// Why a sweep refuses scenario.outputs (in its config or swept into the grid).
constexpr const char* kOutputsRefused =
    "scenario.outputs: SUMO's outputs are kept by `taebp run` (a folder per run, "
    "DIR/<policy>/...); a sweep keeps its tables only: run the point you want to look at "
    "with `taebp run CONFIG --set KEY=VALUE...`";

// The key names of one grid entry ("a" or "a, b"), each new to the grid (`seen`).
std::vector<std::string> AxisKeys(const std::string& key_spec, const std::string& where,
                                  std::set<std::string>* seen) {
  std::vector<std::string> keys;
  std::stringstream ss(key_spec);
  for (std::string k; std::getline(ss, k, ',');) {
    k = Trim(k);
    if (k.empty()) throw ConfigError(where + " has an empty key name");
    if (k == "sweep" || k.rfind("sweep.", 0) == 0)
      throw ConfigError(where + " cannot sweep the sweep section");
    if (!seen->insert(k).second)
      throw ConfigError(where + ": key '" + k + "' appears twice in the grid");
    keys.push_back(k);
  }
  if (!key_spec.empty() && key_spec.back() == ',') throw ConfigError(where + " has an empty key name");
  if (keys.empty()) throw ConfigError(where + " has no key name");
  return keys;
}

// Value #i+1 of a grid entry with `keys`: the text itself for one key, a flow
// list of one entry per key for several.
std::vector<std::string> AxisValue(const std::vector<std::string>& keys, const std::string& v,
                                   std::size_t i, const std::string& where) {
  if (keys.size() == 1) {
    if (Trim(v).empty() || v == "~" || v == "null")
      throw ConfigError(where + ": value #" + std::to_string(i + 1) + " is empty");
    return {v};
  }
  std::vector<std::string> items;
  const std::string expected = "a list of " + std::to_string(keys.size()) +
                               " values (one per key: " + JoinKeys(keys) + ")";
  if (!SplitFlowSequence(v, &items))
    throw ConfigError(where + ": value #" + std::to_string(i + 1) + " " + v + " is not " +
                      expected);
  if (items.size() != keys.size())
    throw ConfigError(where + ": value #" + std::to_string(i + 1) + " " + v + " has " +
                      std::to_string(items.size()) + " entries, expected " + expected);
  for (std::size_t k = 0; k < items.size(); ++k)
    if (items[k].empty() || items[k] == "~" || items[k] == "null")
      throw ConfigError(where + ": value #" + std::to_string(i + 1) + " " + v +
                        " has an empty entry for key '" + keys[k] + "'");
  return items;
}

// The grid's axes and columns into `plan`; returns the number of points.
std::size_t ReadGrid(const SweepConfig& spec, const std::string& config_path, Plan* plan) {
  std::set<std::string> seen;
  std::size_t total = 1;
  for (const auto& [key_spec, values] : spec.grid) {
    const std::string where = config_path + ": sweep.grid key '" + key_spec + "'";
    Axis axis;
    axis.keys = AxisKeys(key_spec, where, &seen);
    if (values.empty()) throw ConfigError(where + " has no values");
    for (std::size_t i = 0; i < values.size(); ++i)
      axis.values.push_back(AxisValue(axis.keys, values[i], i, where));
    total *= axis.values.size();
    if (total > kMaxPoints)
      throw ConfigError(config_path + ": sweep.grid has more than " + std::to_string(kMaxPoints) +
                        " points");
    for (const auto& k : axis.keys) plan->columns.push_back(k);
    plan->axes.push_back(std::move(axis));
  }
  return total;
}

// Grid point `idx`'s values, one per column (the last axis varies fastest).
std::vector<std::string> PointValues(const Plan& plan, std::size_t idx) {
  std::vector<std::string> values;
  std::vector<std::size_t> pick(plan.axes.size());
  std::size_t rest = idx;
  for (std::size_t a = plan.axes.size(); a-- > 0;) {
    pick[a] = rest % plan.axes[a].values.size();
    rest /= plan.axes[a].values.size();
  }
  for (std::size_t a = 0; a < plan.axes.size(); ++a)
    for (std::size_t k = 0; k < plan.axes[a].keys.size(); ++k)
      values.push_back(plan.axes[a].values[pick[a]][k]);
  return values;
}

// What a point's config says of its runs.
struct PointRuns {
  std::map<std::string, std::string> identities;  // policy -> RunIdentity at this point
  bool beyond = false, beyond_by_config = false;
  std::uint64_t seed = 0;
};

// Loads `point`'s config from the template: its policies into the point, its
// runs' identities and seed into `runs`. Throws ConfigError if it is invalid.
void LoadPoint(const Plan& plan, const ExperimentTemplate& config_template, Point* point,
               PointRuns* runs) {
  // Without its sweep: section (the same for every point, checked with
  // the base config); the point's own values only (the rest is in the template).
  std::vector<std::string> point_overrides;
  for (std::size_t k = 0; k < plan.columns.size(); ++k)
    point_overrides.push_back(plan.columns[k] + "=" + point->values[k]);
  ExperimentConfig c = config_template.Load(point_overrides);
  if (c.scenario.outputs.Any()) throw ConfigError(kOutputsRefused);  // swept into the grid
  point->policies = c.policies;
  runs->seed = c.scenario.seed;
  const std::uint64_t seed = runs->seed;
  if (static_cast<std::uint64_t>(plan.replicates) - 1 > kMaxSeed - seed)
    throw ConfigError("scenario.seed = " + std::to_string(seed) + " with sweep.replicates = " +
                      std::to_string(plan.replicates) + " would reach seed " +
                      std::to_string(seed + plan.replicates - 1) + ", above " +
                      std::to_string(kMaxSeed) + " (SUMO takes its seed modulo 2147483647)");
  runs->beyond = c.BeyondPaper();
  const Json config_json = Json::parse(ToJson(c));  // once per point
  for (const std::string& p : c.policies)
    runs->identities[p] = IdentityOf(config_json, runs->beyond, p);
  c.policies.clear();  // what else makes a run beyond the paper
  runs->beyond_by_config = c.BeyondPaper();
}

// The error naming the first invalid grid point.
std::string InvalidPoint(const Plan& plan, const std::string& config_path, const Point& point,
                         std::size_t idx, const char* what) {
  std::string values;
  for (std::size_t k = 0; k < plan.columns.size(); ++k)
    values += (k ? ", " : "") + plan.columns[k] + "=" + point.values[k];
  return config_path + ": sweep.grid point " + std::to_string(idx) + " (" + values +
         ") is not a valid config: " + what;
}

// Replicate `r` of `point`: the policies it runs and those whose run it
// reuses from an earlier task. `first_run`: each run's identity and seed ->
// the first task that runs it.
Task MakeTask(const Plan& plan, const Point& point, int r, const PointRuns& runs,
              std::map<std::string, int>* first_run) {
  Task t;
  t.point = point.index;
  t.replicate = r;
  t.index = point.index * plan.replicates + r;
  t.seed = runs.seed + static_cast<std::uint64_t>(r);
  bool beyond_left = runs.beyond_by_config;  // the runs' subset still beyond the paper?
  // A run: its identity and its seed.
  auto run_key = [&t](const std::string& identity) {
    return identity + "\nseed " + std::to_string(t.seed);
  };
  for (const std::string& p : point.policies) {
    const auto id = runs.identities.find(p);
    const auto earlier = id == runs.identities.end() || !plan.reuse
                             ? first_run->end()
                             : first_run->find(run_key(id->second));
    if (earlier != first_run->end()) {
      t.reused_from[p] = earlier->second;
    } else {
      t.runs.push_back(p);
      const PolicyInfo* info = FindPolicy(p);
      beyond_left = beyond_left || (info && info->beyond_paper);
    }
  }
  // Running a subset must not change the runs' columns (BeyondPaper):
  // then the beyond-the-paper policies run again.
  if (runs.beyond && !beyond_left && !t.runs.empty()) {
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
    const auto id = runs.identities.find(p);
    if (id != runs.identities.end())
      first_run->emplace(run_key(id->second), t.index);
  }
  return t;
}

}  // namespace

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
  if (plan.base.scenario.outputs.Any()) throw ConfigError(config_path + ": " + kOutputsRefused);
  plan.hash = ConfigHash(plan.base);
  const SweepConfig& spec = *plan.base.sweep;
  plan.replicates = spec.replicates;
  if (plan.replicates < 1)
    throw ConfigError(config_path + ": sweep.replicates = " + std::to_string(plan.replicates) +
                      " must be >= 1");

  const std::size_t total = ReadGrid(spec, config_path, &plan);
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
    point.values = PointValues(plan, idx);
    // The point's own policies and seed (a grid may sweep either).
    point.policies = plan.base.policies;
    PointRuns runs;
    runs.seed = plan.base.scenario.seed;
    try {
      LoadPoint(plan, config_template, &point, &runs);
    } catch (const ConfigError& e) {
      if (invalid++ == 0) first_error = InvalidPoint(plan, config_path, point, idx, e.what());
    }
    for (int r = 0; r < plan.replicates; ++r)
      plan.tasks.push_back(MakeTask(plan, point, r, runs, &first_run));
    plan.points.push_back(std::move(point));
  }
  if (invalid > 0)
    throw ConfigError(first_error + (invalid > 1 ? " (and " + std::to_string(invalid - 1) +
                                                       " more invalid grid points)"
                                                 : std::string()) +
                      "; nothing was run");
  return plan;
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
