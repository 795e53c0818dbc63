// The sweep engine's pure parts (no processes, no MPI): grid expansion, the
// config hash, journal lines and the final tables. `taebp sweep` and
// `taebp merge` (sweep_cmd.cc) drive them; tests/sweep links them directly.
#pragma once

#include "taebp/config/config.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace taebp::sweep {

using Json = nlohmann::ordered_json;

// One axis of the grid: a key, or several comma-separated keys zipped together
// ("scenario.avs,scenario.hvs": [[0,16],[8,8]]): values[i][k] is the i-th value
// of keys[k], as YAML flow text.
struct Axis {
  std::vector<std::string> keys;
  std::vector<std::vector<std::string>> values;
};

struct Point {
  int index = 0;
  std::vector<std::string> values;     // one per Plan::columns, YAML text as given
  std::vector<std::string> policies;   // the point's resolved policies (base ones if invalid)
};

struct Task {
  int index = 0;  // point * replicates + replicate
  int point = 0;
  int replicate = 0;
  std::uint64_t seed = 0;
  // Never simulate the same thing twice: the point's policies this task runs
  // in SUMO, and those it reuses (policy -> the index of the earlier task
  // whose run it takes): a policy whose run at this task would differ from an
  // earlier task's in no config key it reads (config/policies.h
  // PolicyReads), with the same seed, is not run again. Empty `runs`: the
  // task runs nothing (no worker, no task folder).
  std::vector<std::string> runs;
  std::map<std::string, int> reused_from;
};

struct Plan {
  std::string config_text;               // the YAML file as read
  std::string config_path;               // origin in messages, CONFIG for the workers
  std::vector<std::string> overrides;    // the user's --set, applied to every task
  ExperimentConfig base;                 // resolved, without point overrides
  std::string hash;                      // ConfigHash(base)
  std::vector<Axis> axes;
  std::vector<std::string> columns;      // individual keys, axis order
  std::vector<Point> points;             // Cartesian product, last axis fastest
  int replicates = 1;
  std::vector<Task> tasks;               // point-major, replicate fastest
  bool reuse = true;                     // ExpandSweep's `reuse`

  // The --set overrides of a point: the user's, then the point's values.
  std::vector<std::string> PointOverrides(const Point& point) const;
  // Those of a task: its point's, then scenario.seed (and `policies` when
  // it reuses some of the point's policies).
  std::vector<std::string> TaskOverrides(const Task& task) const;
  // Policy runs in SUMO the plan makes, and those it reuses instead.
  std::size_t Runs() const;
  std::size_t Reused() const;
};

// Builds the plan from the config text and the user's --set overrides. Throws
// ConfigError naming the key for a missing `sweep:` section, a zipped value of
// the wrong length, empty values or a key given twice.
// `reuse` false: every task runs every policy of its point (Task::runs), to
// measure the reuse or check it (the tables are the same but reused_from).
Plan ExpandSweep(const std::string& config_text, const std::string& config_path,
                 const std::vector<std::string>& overrides, bool reuse = true);

// Splits a YAML flow sequence "[a, [b, c], {d: e}]" into its top-level items'
// text. Returns false if `text` is not a flow sequence.
bool SplitFlowSequence(const std::string& text, std::vector<std::string>* items);

// What decides `policy`'s run under `config` (whose policies are the run's):
// the config as JSON without the keys the policy does not read, the
// `policies` list and the sweep section, with whether the run writes the
// columns beyond the paper. Two runs with the same identity and seed give
// the same results.
std::string RunIdentity(const ExperimentConfig& config, const std::string& policy);

// 16 hex digits identifying the resolved sweep: the config with the user's
// overrides and the grid, but not sweep.replicates (so a sweep can be extended
// with more replicates and resume).
std::string ConfigHash(const ExperimentConfig& config);

// The metric columns of results.csv, in order (after policy, status, error).
const std::vector<std::string>& MetricColumns();

// A task's summary.json text, parsed. Throws std::runtime_error when it is not
// valid JSON.
Json ParseSummary(const std::string& summary_json);

// Per-policy metrics (the MetricColumns keys) from a task's parsed summary.json.
// Throws std::runtime_error naming what is missing.
Json MetricsFromSummary(const Json& summary, const std::vector<std::string>& policies);

// A journal line (no newline) for a finished task.
Json JournalEntry(const Plan& plan, const Task& task, const std::string& status,
                  const std::string& error, const Json& policies_metrics);

// Journal contents by task index: the latest entry per (point, replicate),
// an ok entry winning over failed ones.
struct Journal {
  std::map<int, Json> entries;
  std::size_t lines = 0;         // well-formed lines read
  std::size_t valid_bytes = 0;   // length up to the last complete line
  bool partial_tail = false;     // the file ended in a half-written line
  // Malformed complete lines, skipped: "origin:line: why" each.
  std::vector<std::string> corrupt;
};
// Parses journal text. Lines of another sweep (hash) throw ConfigError naming
// `origin`; malformed complete lines are skipped and listed in `corrupt`.
Journal ParseJournal(const std::string& text, const Plan& plan, const std::string& origin);
// Adds `entry` (a journal line's JSON) to `journal` with the same precedence;
// returns whether it was stored (false: outside the plan, or a failure after
// an ok entry).
bool AddEntry(Journal* journal, const Plan& plan, const Json& entry);

// A journal entry of a task that finished without error.
bool IsOk(const Json& entry);

// How many of `tasks` have an ok entry, a failed one, and none.
struct Tally {
  int ok = 0, failed = 0, missing = 0;
};
Tally CountTasks(const std::vector<Task>& tasks, const Journal& journal);

// The final tables, byte-identical for the same entries.
std::string ResultsCsv(const Plan& plan, const Journal& journal);
std::string ResultsJsonl(const Plan& plan, const Journal& journal);
std::string AggregateCsv(const Plan& plan, const Journal& journal);

// sweep.json: the resolved base config, the plan's shape and provenance.
Json SweepHeader(const Plan& plan, const std::string& shard, const std::string& sumo_version);

// JSON text of `j` (indent < 0: one line) in which bytes that are not UTF-8
// (a task's error message, a path) become U+FFFD instead of throwing.
std::string Dump(const Json& j, int indent = -1);


}  // namespace taebp::sweep
