// A sweep folder's state and tables (sweep_folder.h).
#include "sweep_folder.h"

#include "workers.h"
#include "taebp/config/config.h"
#include "taebp/report/report.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/rundir/synced_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace taebp::sweep::internal {

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string NoSpaceIn(const fs::path& dir) {
  const fs::path probe = dir / (".taebp-space-probe." + std::to_string(::getpid()));
  std::string why;
  try {
    WriteSynced(probe.string(), std::string(256 * 1024, '\0'));
  } catch (const std::exception& e) {
    const std::string message = e.what();
    for (const int err : {ENOSPC, EDQUOT})
      if (why.empty() && message.find(std::strerror(err)) != std::string::npos)
        why = std::string(std::strerror(err)) + " in " + dir.string();
  }
  std::error_code ec;
  fs::remove(probe, ec);
  return why;
}

void ParseShard(const std::string& text, int* index, int* count) {
  *index = 0;
  *count = 1;
  if (text.empty()) return;
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    std::size_t a = 0, b = 0;
    *index = std::stoi(text.substr(0, slash), &a);
    *count = std::stoi(text.substr(slash + 1), &b);
    if (a != slash || b != text.size() - slash - 1) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw ConfigError("--shard " + text + ": expected I/N, e.g. --shard 0/4");
  }
  if (*count < 1 || *index < 0 || *index >= *count)
    throw ConfigError("--shard " + text + ": expected I/N with 0 <= I < N");
}

std::string SumoVersionOf(const Journal& journal) {
  for (const auto& [i, e] : journal.entries) {
    const std::string v = e.value("sumo_version", "");
    if (!v.empty()) return v;
  }
  return "";
}

namespace {

using KnownHeaders = std::map<std::string, std::vector<std::string>>;

std::string JoinColumns(const std::vector<std::string>& cols) {
  std::string h;
  for (const std::string& c : cols) h += (h.empty() ? "" : ",") + c;
  return h;
}

// The headers a task's encounters.csv may have (report.h
// EncounterCsvColumns: the paper's columns, then a network's, a run beyond
// the paper's and the SSM device's where they apply).
KnownHeaders EncounterHeaders() {
  KnownHeaders known;
  for (bool beyond : {false, true})
    for (bool network : {false, true})
      for (bool ssm : {false, true}) {
        std::vector<std::string> cols = EncounterCsvColumns(beyond, network, ssm);
        known[JoinColumns(cols)] = cols;
      }
  return known;
}

// What is pooled into the sweep's encounters.csv.
struct Pooling {
  const fs::path& out;
  const Plan& plan;
  const Journal& journal;
  KnownHeaders known;
  bool network = false;              // network tasks (not the figure-8)
  std::vector<std::string> pooled;  // the pooled file's columns after the task's
};

// The header line of each ok task's encounters.csv, read once. The pooled
// file has every group any task has, in that order; a task without a group
// gets empty cells there.
void FindColumns(Pooling* p) {
  bool network = false, beyond = false, ssm = false;
  const std::vector<std::string> paper = EncounterCsvColumns(false, false, false);
  for (const Task& t : p->plan.tasks) {
    const auto it = p->journal.entries.find(t.index);
    if (it == p->journal.entries.end() || !IsOk(it->second) || t.runs.empty()) continue;
    std::ifstream in(TaskDir(p->out, t) / "encounters.csv", std::ios::binary);
    std::string line;
    if (!(in && std::getline(in, line))) continue;
    const auto k = p->known.find(line);
    if (k == p->known.end()) continue;
    auto has = [&](const std::vector<std::string>& group) {
      return std::find(k->second.begin(), k->second.end(), group.front()) != k->second.end();
    };
    network = network || has(EncounterCsvColumnGroup("network"));
    beyond = beyond || has(EncounterCsvColumnGroup("beyond"));
    ssm = ssm || has(EncounterCsvColumnGroup("ssm"));
  }
  p->network = network;
  p->pooled = EncounterCsvColumns(beyond, network, ssm);
}

// Task `t`'s point, replicate, seed and swept values: the front of its rows.
std::string RowPrefix(const Plan& plan, const Task& t) {
  std::string prefix = std::to_string(t.point) + ',' + std::to_string(t.replicate) + ',' +
                       std::to_string(t.seed);
  for (const std::string& v : plan.points[static_cast<std::size_t>(t.point)].values)
    prefix += ',' + CsvCell(v);
  return prefix;
}

// The rows of one policy of one task, from `source`'s encounters.csv (the
// task itself or the one whose run it reuses), one task file at a time.
void WritePolicyRows(const Pooling& p, std::ostream& f, const Task& t, const Task& source,
                     const std::string& policy) {
  const auto it = p.journal.entries.find(source.index);
  if (it == p.journal.entries.end() || !IsOk(it->second) || source.runs.empty()) return;
  const fs::path file = TaskDir(p.out, source) / "encounters.csv";
  std::ifstream in(file, std::ios::binary);
  std::string line;
  const bool read = in && std::getline(in, line);
  const auto k = read ? p.known.find(line) : p.known.end();
  // Network and figure-8 tasks do not mix in one sweep: the first says.
  const bool fits =
      k != p.known.end() &&
      (std::find(k->second.begin(), k->second.end(), EncounterCsvColumnGroup("network").front()) !=
       k->second.end()) == p.network;
  if (!fits) {
    std::fprintf(stderr, "taebp sweep: warning: %s %s; its encounters are not in %s\n",
                 file.c_str(), in ? "has other columns (another taebp version?)" : "is missing",
                 (p.out / "encounters.csv").c_str());
    return;
  }
  // Where each pooled column comes from in this file's rows (-1: empty).
  const std::vector<std::string>& cols = k->second;
  std::vector<int> from;
  for (const std::string& c : p.pooled) {
    const auto at = std::find(cols.begin(), cols.end(), c);
    from.push_back(at == cols.end() ? -1 : static_cast<int>(at - cols.begin()));
  }
  const std::size_t policy_at = static_cast<std::size_t>(
      std::find(cols.begin(), cols.end(), "policy") - cols.begin());
  const bool same = cols == p.pooled;
  const std::string prefix = RowPrefix(p.plan, t);
  const std::string lead = CsvCell(policy) + ',';  // the policy is the first column
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (policy_at == 0 ? line.compare(0, lead.size(), lead) != 0 : false) continue;
    if (same && policy_at == 0) {
      f << prefix << ',' << line << '\n';
      continue;
    }
    const std::vector<std::string> cells = SplitCsvRow(line);
    if (policy_at >= cells.size() || cells[policy_at] != CsvCell(policy)) continue;
    f << prefix;
    for (int i : from) f << ',' << (i >= 0 && i < static_cast<int>(cells.size()) ? cells[i] : "");
    f << '\n';
  }
}

// encounters.csv of the sweep: every ok task's encounters.csv rows, with the
// task's point, replicate, seed and swept values in front. Streamed (a large
// grid's rows need not fit in memory) into a temporary file renamed into place.
void WritePooledEncounters(const fs::path& out, const Plan& plan, const Journal& journal) {
  Pooling p{out, plan, journal, EncounterHeaders(), false, {}};
  FindColumns(&p);
  // Streamed (a long study's rows need not fit in memory), in place once on disk.
  SyncedWriter writer((out / "encounters.csv").string());
  std::ostream& f = writer.Stream();
  f << "point,replicate,seed";
  for (const std::string& c : plan.columns) f << ',' << CsvCell(c);
  f << ',' << JoinColumns(p.pooled) << '\n';
  // Each task's rows, policy by policy in its point's order: a policy it ran
  // from its own encounters.csv, a policy it reused from the earlier task's
  // (Task::reused_from), so that the file is the one a sweep without reuse
  // writes (docs/results-folders.md). The rows of one policy of one task
  // file at a time.
  for (const Task& t : plan.tasks) {
    if (journal.entries.find(t.index) == journal.entries.end()) continue;
    for (const std::string& policy : plan.points[static_cast<std::size_t>(t.point)].policies) {
      const auto reused = t.reused_from.find(policy);
      const Task& source = reused == t.reused_from.end()
                               ? t
                               : plan.tasks[static_cast<std::size_t>(reused->second)];
      WritePolicyRows(p, f, t, source, policy);
    }
  }
  writer.Commit();
}

}  // namespace

void WriteOutputs(const fs::path& out, const Plan& plan, const Journal& journal, Json header) {
  WritePooledEncounters(out, plan, journal);
  header["sumo_version"] = SumoVersionOf(journal);
  WriteFilesAtomically(out.string(), {{"results.csv", ResultsCsv(plan, journal)},
                                      {"results.jsonl", ResultsJsonl(plan, journal)},
                                      {"aggregate.csv", AggregateCsv(plan, journal)},
                                      {"sweep.json", Dump(header, 2) + "\n"}});
}

std::string ShardName(const std::string& shard) {
  return shard.empty() ? "the unsharded sweep" : "shard " + shard;
}

void CheckHeader(const fs::path& dir, const std::string& hash, bool check_shard,
                 const std::string& shard) {
  const fs::path p = dir / "sweep.json";
  if (!fs::exists(p)) return;
  Json h;
  try {
    h = Json::parse(ReadText(p));
    if (!h.is_object()) throw std::runtime_error("not a JSON object");
  } catch (const std::exception& e) {
    throw ConfigError(p.string() + ": unreadable (" + e.what() + "); remove it or use another --out");
  }
  const std::string other =
      h.contains("config_hash") && h["config_hash"].is_string() ? h["config_hash"].get<std::string>() : "";
  if (other != hash)
    throw ConfigError(p.string() + ": " + dir.string() + " holds a different sweep (config hash " +
                      other + ", this one " + hash +
                      "): the config, its grid or the --set overrides differ; use another --out "
                      "or remove that directory");
  if (!check_shard) return;
  const std::string held = h.contains("shard") && h["shard"].is_string() ? h["shard"].get<std::string>() : "";
  if (held != shard)
    throw ConfigError(p.string() + ": " + dir.string() + " holds " + ShardName(held) +
                      " of this sweep, and this is " + ShardName(shard) +
                      ": use another --out (shards go to their own folders; `taebp merge` "
                      "joins them)");
}

bool HasTaskOutputs(const fs::path& task_dir) {
  std::error_code ec;
  return fs::is_regular_file(task_dir / "summary.json", ec);
}

void WarnCorrupt(const Journal& journal, const char* who) {
  for (const std::string& c : journal.corrupt)
    std::fprintf(stderr, "taebp %s: warning: skipping a corrupt journal line: %s\n", who, c.c_str());
}

std::vector<Task> Pending(const std::vector<Task>& scope, const Journal& j, const fs::path& out,
                          int* lost) {
  std::vector<Task> pending;
  *lost = 0;
  for (const Task& t : scope) {
    const auto it = j.entries.find(t.index);
    if (it == j.entries.end() || !IsOk(it->second)) {
      pending.push_back(t);
    } else if (!t.runs.empty() && !HasTaskOutputs(TaskDir(out, t))) {
      pending.push_back(t);
      ++*lost;
    }
  }
  return pending;
}

}  // namespace taebp::sweep::internal
