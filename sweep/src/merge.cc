// `taebp merge OUT SHARD...`: joins the folders of a sharded sweep (each the
// --out of `taebp sweep --shard I/N`) into one sweep folder, journal, task
// folders and tables, as if the sweep had run unsharded.
#include "taebp/sweep/engine.h"

#include "sweep_folder.h"
#include "workers.h"
#include "taebp/config/config.h"
#include "taebp/base/exit_codes.h"
#include "taebp/report/report.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/rundir/synced_file.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace taebp::sweep {

using namespace internal;

namespace {

// Each shard once: the same folder twice (or through a link) is an error.
void CheckShardDirs(const std::vector<std::string>& dirs) {
  std::map<fs::path, std::string> seen;
  for (const std::string& d : dirs) {
    std::error_code ec;
    if (!fs::is_directory(d, ec))
      throw ConfigError(d + ": not a folder (is it the --out of a taebp sweep --shard?)");
    const fs::path real = fs::canonical(d, ec);
    const auto [it, fresh] = seen.emplace(ec ? fs::absolute(d) : real, d);
    if (!fresh)
      throw ConfigError("taebp merge: " + d + " is given twice" +
                        (it->second == d ? std::string() : " (as " + it->second + ")") +
                        "; name each shard folder once");
  }
}

// The locks of the shard folders other than OUT.
std::vector<std::unique_ptr<FolderLock>> LockShards(const fs::path& out,
                                                    const std::vector<std::string>& dirs) {
  std::vector<std::unique_ptr<FolderLock>> shard_locks;
  for (const std::string& d : dirs) {
    std::error_code ec;
    if (fs::equivalent(out, d, ec)) continue;
    shard_locks.push_back(std::make_unique<FolderLock>(d, /*required=*/false));
  }
  return shard_locks;
}

// Appends the shard header `p` to `headers` and checks its fields' types.
void ReadHeader(const fs::path& p, std::vector<Json>* headers) {
  try {
    headers->push_back(Json::parse(ReadText(p)));
    const Json& h = headers->back();
    if (!h.is_object() || !h.contains("config_hash") || !h["config_hash"].is_string() ||
        !h.contains("config_text") || !h["config_text"].is_string())
      throw std::runtime_error("no config_hash or config_text");
    for (const char* k : {"config_path"})
      if (h.contains(k) && !h[k].is_string()) throw std::runtime_error(std::string(k) + " is not a string");
    if (h.contains("replicates") &&
        !(h["replicates"].is_number_integer() && h["replicates"].get<std::int64_t>() >= 1 &&
          h["replicates"].get<std::int64_t>() <= 10000000))
      throw std::runtime_error("replicates is not an integer in [1, 10000000]");
    if (h.contains("overrides") &&
        !(h["overrides"].is_array() &&
          std::all_of(h["overrides"].begin(), h["overrides"].end(),
                      [](const Json& v) { return v.is_string(); })))
      throw std::runtime_error("overrides is not a list of strings");
  } catch (const std::exception& e) {
    throw ConfigError(p.string() + ": unreadable: " + e.what());
  }
}

// Every shard's sweep.json, each of the same sweep (config hash).
std::vector<Json> ReadHeaders(const std::vector<std::string>& dirs) {
  std::vector<Json> headers;
  for (const std::string& d : dirs) {
    const fs::path p = fs::path(d) / "sweep.json";
    if (!fs::exists(p))
      throw ConfigError(p.string() + ": missing (is " + d + " the --out of a taebp sweep?)");
    ReadHeader(p, &headers);
    const std::string h = headers.back()["config_hash"].get<std::string>();
    if (h != headers.front()["config_hash"].get<std::string>())
      throw ConfigError(p.string() + ": " + d + " holds a different sweep (config hash " + h +
                        ") than " + dirs.front() + " (" +
                        headers.front()["config_hash"].get<std::string>() + ")");
  }
  return headers;
}

// The sweep's plan from the shards' headers (the most replicates any shard
// ran), with the recorded config hash.
Plan MergedPlan(const std::vector<Json>& headers, const std::vector<std::string>& dirs) {
  const Json& first = headers.front();
  int replicates = 0;
  for (const Json& h : headers) replicates = std::max(replicates, h.value("replicates", 1));
  std::vector<std::string> overrides = first.value("overrides", std::vector<std::string>{});
  if (replicates != first.value("replicates", 1))
    overrides.push_back("sweep.replicates=" + std::to_string(replicates));
  const std::string origin = first.value("config_path", (fs::path(dirs.front()) / "sweep.json").string());
  Plan plan = ExpandSweep(first["config_text"].get<std::string>(), origin, overrides,
                          first.value("reuse", true));
  const std::string hash = first["config_hash"].get<std::string>();
  if (plan.hash != hash) {
    std::fprintf(stderr,
                 "taebp merge: warning: this taebp computes config hash %s for the sweep "
                 "recorded as %s (another version?); using the recorded one\n",
                 plan.hash.c_str(), hash.c_str());
    plan.hash = hash;
  }
  return plan;
}

// Adds the shards' journals to `journal` (OUT's own); returns the shard
// folder holding each added task's outputs (task index -> shard dir).
std::map<int, fs::path> MergeJournals(const MergeOptions& o, const fs::path& out, const Plan& plan,
                                      Journal* journal) {
  std::map<int, fs::path> source;  // task index -> shard dir holding its outputs
  for (const std::string& d : o.dirs) {
    std::error_code ec;
    if (fs::equivalent(out, d, ec)) continue;
    const fs::path jp = fs::path(d) / "journal.jsonl";
    if (!fs::exists(jp)) continue;
    const Journal shard = ParseJournal(ReadText(jp), plan, jp.string());
    if (!o.quiet) WarnCorrupt(shard, "merge");
    for (const auto& [index, e] : shard.entries) {
      // The task's outputs come from the shard whose entry the journal keeps.
      if (AddEntry(journal, plan, e)) source[index] = d;
    }
  }
  return source;
}

// Per-task outputs next to the merged tables. An ok task whose folder is
// missing in its shard is reported (its row is in the tables, its files
// are not): running that shard's sweep again redoes it. Returns the
// missing folders.
std::vector<std::string> CopyTaskFolders(const Plan& plan, const fs::path& out,
                                         const Journal& journal,
                                         const std::map<int, fs::path>& source) {
  std::vector<std::string> lost;
  for (const auto& [index, dir] : source) {
    ThrowIfInterrupted();  // OUT's tables as they were; copied task folders are redone
    const Task& t = plan.tasks[static_cast<std::size_t>(index)];
    const fs::path from = TaskDir(dir, t), to = TaskDir(out, t);
    if (t.runs.empty()) continue;  // every policy reused: no folder
    if (!HasTaskOutputs(from)) {
      if (IsOk(journal.entries.at(index))) lost.push_back(from.string());
      continue;
    }
    std::error_code ec;
    fs::remove_all(to, ec);
    fs::create_directories(to.parent_path());
    fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  }
  for (const auto& [index, e] : journal.entries) {  // already in OUT: check it is there
    if (source.count(index) || !IsOk(e) || plan.tasks[static_cast<std::size_t>(index)].runs.empty())
      continue;
    const fs::path here = TaskDir(out, plan.tasks[static_cast<std::size_t>(index)]);
    if (!HasTaskOutputs(here)) lost.push_back(here.string());
  }
  return lost;
}

// The merge's outcome on stderr; returns the exit code.
int ReportMerge(const MergeOptions& o, const fs::path& out, const Plan& plan,
                const Journal& journal, const std::vector<std::string>& lost) {
  const auto [ok, failed, missing] = CountTasks(plan.tasks, journal);
  for (const std::string& l : lost)
    std::fprintf(stderr, "taebp merge: error: a finished task's outputs are missing: %s/summary.json\n",
                 l.c_str());
  if (!lost.empty())
    std::fprintf(stderr,
                 "taebp merge: %zu task folder(s) missing: run the shards' `taebp sweep` again "
                 "(it redoes tasks whose folders are gone), then merge again\n",
                 lost.size());
  if (!o.quiet)
    std::fprintf(stderr,
                 "taebp merge: %zu shard dirs, %d of %zu tasks ok (%zu without their task "
                 "folder), %d failed, %d missing; results in %s\n",
                 o.dirs.size(), ok, plan.tasks.size(), lost.size(), failed, missing, out.c_str());
  return failed || missing || !lost.empty() ? kExitFailed : 0;
}

}  // namespace

int RunMerge(const MergeOptions& o) {
  if (o.dirs.empty()) throw ConfigError("taebp merge: no shard directories given");
  // OUT is locked for the whole merge, and so is every shard folder (a shard's
  // sweep still running there is refused rather than merged half-done).
  const fs::path out(o.out);
  CheckOutputDir(out.string(), "OUT");
  RefuseRunResults(out.string(), "OUT " + out.string());
  CheckShardDirs(o.dirs);
  const InterruptGuard interrupts;  // a signal now waits until the merge is written
  fs::create_directories(out);
  FolderLock lock(out.string());
  RemoveWriterTemporaries(out.string(), kSweepFiles);
  const std::vector<std::unique_ptr<FolderLock>> shard_locks = LockShards(out, o.dirs);

  const std::vector<Json> headers = ReadHeaders(o.dirs);
  const Plan plan = MergedPlan(headers, o.dirs);

  CheckHeader(out, plan.hash);
  const fs::path journal_path = out / "journal.jsonl";
  Journal journal;
  if (fs::exists(journal_path)) {
    journal = ParseJournal(ReadText(journal_path), plan, journal_path.string());
    if (!o.quiet) WarnCorrupt(journal, "merge");
  }
  const std::map<int, fs::path> source = MergeJournals(o, out, plan, &journal);
  const std::vector<std::string> lost = CopyTaskFolders(plan, out, journal, source);
  std::string lines;
  for (const auto& [index, e] : journal.entries) lines += Dump(e) + "\n";
  Json header = SweepHeader(plan, "", SumoVersionOf(journal));
  header["merged_from"] = o.dirs;
  ThrowIfInterrupted();
  WriteFilesAtomically(out.string(), {{"journal.jsonl", lines}});
  WriteOutputs(out, plan, journal, header);
  return ReportMerge(o, out, plan, journal, lost);
}

}  // namespace taebp::sweep
