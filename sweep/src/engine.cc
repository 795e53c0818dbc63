// The sweep engine's driver behind `taebp sweep`: every task (one grid point
// x one seed) is a separate process, `taebp run CONFIG --set ... --out
// TASKDIR` (libsumo runs one simulation per process); up to --jobs of them at
// once (workers.h), optionally spread over MPI ranks (mpi.h) or Slurm-array
// shards. Finished tasks are appended to DIR/journal.jsonl (journal_file.h),
// which makes the sweep resumable; the tables are rebuilt from the journal at
// the end (sweep_folder.h). `taebp merge` is merge.cc.
#include "taebp/sweep/engine.h"

#include "journal_file.h"
#include "mpi.h"
#include "progress.h"
#include "sweep_folder.h"
#include "workers.h"
#include "taebp/config/config.h"
#include "taebp/base/exit_codes.h"
#include "taebp/report/report.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/rundir/synced_file.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace taebp::sweep {

using namespace internal;

namespace {

// base/exit_codes.h: kExitFailed (a failed or missing task); interrupted:
// 128 + the signal (130 Ctrl-C, 143 SIGTERM, 129 SIGHUP), as `run`.
int ExitInterrupted() { return kExitSignalBase + (PendingInterrupt() ? PendingInterrupt() : SIGINT); }

// This shard's tasks.
std::vector<Task> ShardScope(const Plan& plan, const std::string& shard) {
  int shard_index = 0, shard_count = 1;
  ParseShard(shard, &shard_index, &shard_count);
  std::vector<Task> scope;
  for (const Task& t : plan.tasks)
    if (t.index % shard_count == shard_index) scope.push_back(t);
  return scope;
}

// --list: the plan's size and this shard's tasks, one a line.
void PrintList(const Plan& plan, const std::vector<Task>& scope, const std::string& shard) {
  std::printf("%zu points x %d replicates = %zu tasks, %zu policy runs (%zu reused)%s\n",
              plan.points.size(), plan.replicates, plan.tasks.size(), plan.Runs(), plan.Reused(),
              shard.empty() ? "" : (", shard " + shard + ": " + std::to_string(scope.size())).c_str());
  for (const Task& t : scope) {
    std::printf("%d point=%d replicate=%d seed=%llu", t.index, t.point, t.replicate,
                static_cast<unsigned long long>(t.seed));
    const Point& p = plan.points[static_cast<std::size_t>(t.point)];
    for (std::size_t k = 0; k < plan.columns.size(); ++k)
      std::printf(" %s=%s", plan.columns[k].c_str(), p.values[k].c_str());
    for (const auto& [policy, from] : t.reused_from) {  // runs it does not make again
      const Task& f = plan.tasks[static_cast<std::size_t>(from)];
      std::printf(" %s:reuses=%d-%d", policy.c_str(), f.point, f.replicate);
    }
    std::printf("\n");
  }
}

// What rank 0 holds while the sweep runs: the folder's lock (until the sweep
// ends), the journal file and what it says, and sweep.json's header.
struct RootFolder {
  std::unique_ptr<FolderLock> lock;
  std::unique_ptr<JournalFile> journal_file;
  Journal journal;
  Json header;
};

// Rank 0: prepares the directory (lock, journal, sweep.json) and returns the
// indices of the tasks left to do.
Json PrepareFolder(const SweepOptions& o, const Plan& plan, const std::vector<Task>& scope,
                   const fs::path& out, bool show, RootFolder* f) {
  CheckOutputDir(out.string());
  RefuseRunResults(out.string(), "--out " + out.string());
  fs::create_directories(out);
  f->lock = std::make_unique<FolderLock>(out.string());
  RemoveWriterTemporaries(out.string(), kSweepFiles);  // a killed table write's
  CheckHeader(out, plan.hash, true, o.shard);
  fs::create_directories(out / "tasks");
  f->journal_file = std::make_unique<JournalFile>(out / "journal.jsonl");
  const std::string text = f->journal_file->ReadAll();
  f->journal = ParseJournal(text, plan, (out / "journal.jsonl").string());
  if (show) WarnCorrupt(f->journal, "sweep");
  if (f->journal.partial_tail) {
    if (show)
      std::fprintf(stderr, "taebp sweep: dropping a half-written last line of %s\n",
                   (out / "journal.jsonl").c_str());
    f->journal_file->Truncate(f->journal.valid_bytes);
  }
  f->header = SweepHeader(plan, o.shard, SumoVersionOf(f->journal));
  if (!fs::exists(out / "sweep.json"))
    WriteFilesAtomically(out.string(), {{"sweep.json", Dump(f->header, 2) + "\n"}});
  Json pending = Json::array();
  int lost = 0;
  for (const Task& t : Pending(scope, f->journal, out, &lost)) pending.push_back(t.index);
  if (lost > 0 && show)
    std::fprintf(stderr,
                 "taebp sweep: %d finished task(s) lost their outputs in %s/tasks: running "
                 "them again\n",
                 lost, out.c_str());
  return pending;
}

// Rank 0's setup as the JSON it sends the other ranks: {"error", "code",
// "pending": [...]}.
std::string Setup(const SweepOptions& o, const Plan& plan, const std::vector<Task>& scope,
                  const fs::path& out, bool show, RootFolder* f) {
  Json s;
  try {
    s["pending"] = PrepareFolder(o, plan, scope, out, show, f);
  } catch (const ConfigError& e) {
    s["error"] = e.what();
    s["code"] = 2;
  } catch (const OutputError& e) {
    s["error"] = e.what();
    s["code"] = 4;
  } catch (const std::exception& e) {
    s["error"] = e.what();
    s["code"] = 1;
  }
  return Dump(s);
}

// A setup that failed: rank 0 throws its error again; the other ranks return
// its exit code.
int SetupFailed(const Json& s, bool root) {
  if (!root) return s.value("code", 1) == 4 ? 2 : s.value("code", 1);
  if (s.value("code", 1) == 2) throw ConfigError(s["error"].get<std::string>());
  if (s.value("code", 1) == 4) throw OutputError(s["error"].get<std::string>());
  throw std::runtime_error(s["error"].get<std::string>());
}

// This rank's share of the pending tasks.
std::vector<Task> MyTasks(const Json& pending, const Plan& plan, const Mpi& mpi) {
  std::vector<Task> mine;
  for (std::size_t k = 0; k < pending.size(); ++k)
    if (static_cast<int>(k % static_cast<std::size_t>(mpi.size())) == mpi.rank())
      mine.push_back(plan.tasks[pending[k].get<std::size_t>()]);
  return mine;
}

// Rank 0's record of a finished task: the journal and the progress line.
class Recorder {
 public:
  Recorder(const fs::path& out, const Plan& plan, RootFolder* folder, Progress* progress)
      : out_(out), plan_(plan), folder_(folder), progress_(progress) {}

  void operator()(const Json& e) {
    // A task failed on a full disk: the sweep stops (README) rather than run
    // and fail every remaining task; the task is not recorded (a resume redoes it).
    if (!IsOk(e)) {
      const std::string why = NoSpaceIn(out_);
      if (!why.empty()) {
        if (disk_full_.empty())
          disk_full_ = why + " (task " + std::to_string(e.value("point", -1)) + "-" +
                       std::to_string(e.value("replicate", -1)) + ": " + e.value("error", "") + ")";
        return;
      }
    }
    folder_->journal_file->Append(Dump(e));
    AddEntry(&folder_->journal, plan_, e);
    progress_->Finished(IsOk(e));
    progress_->Update();
  }

  const std::string& disk_full() const { return disk_full_; }

 private:
  const fs::path& out_;
  const Plan& plan_;
  RootFolder* folder_;
  Progress* progress_;
  std::string disk_full_;  // why the sweep stopped for want of space ("" = it did not)
};

// Rank 0: runs its tasks, then gathers the other ranks' results until each
// reports done. Returns whether the sweep ran to the end.
bool RunRoot(const Plan& plan, const fs::path& out, const std::vector<Task>& mine, int jobs,
             const RunFunction& worker, Mpi& mpi, Recorder& record, Progress& progress,
             const RootFolder& folder) {
  int ranks_done = 1;
  bool stop_sent = false;
  auto poll = [&]() {
    std::string msg;
    int tag = 0, source = 0;
    while (mpi.Receive(-1, &msg, &tag, &source)) {
      if (tag == kTagResult) record(Json::parse(msg));
      else if (tag == kTagDone) ++ranks_done;
    }
    progress.Update();
    return !record.disk_full().empty();
  };
  bool completed = RunTasks(plan, out, mine, jobs, 0, worker, record, poll);
  // Gather the other ranks' results until each reports done.
  const auto wait_from = Clock::now();
  while (ranks_done < mpi.size()) {
    if (PendingInterrupt() && !stop_sent) {
      for (int r = 1; r < mpi.size(); ++r) mpi.Send("", r, kTagStop);
      stop_sent = true;
    }
    poll();
    if (PendingInterrupt() && Clock::now() - wait_from > std::chrono::seconds(30)) {
      std::fprintf(stderr, "taebp sweep: ranks did not stop in time, aborting\n");
      WriteOutputs(out, plan, folder.journal, folder.header);
      mpi.Abort(ExitInterrupted());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
  }
  return completed && !PendingInterrupt();
}

// Another rank: runs its tasks, sends rank 0 each result and then whether it
// finished; returns its exit code.
int RunOtherRank(const Plan& plan, const fs::path& out, const std::vector<Task>& mine, int jobs,
                 const RunFunction& worker, Mpi& mpi) {
  bool stop = false;
  auto poll = [&]() {
    std::string msg;
    int tag = 0, source = 0;
    while (mpi.Receive(0, &msg, &tag, &source))
      if (tag == kTagStop) stop = true;
    return stop;
  };
  auto send = [&](const Json& e) { mpi.Send(Dump(e), 0, kTagResult); };
  const bool completed = RunTasks(plan, out, mine, jobs, mpi.rank(), worker, send, poll);
  mpi.Send(completed ? "ok" : "stopped", 0, kTagDone);
  return completed ? 0 : ExitInterrupted();
}

// Rank 0, at the end: the tasks' count and failures on stderr (unless
// --quiet), and the exit code.
int Finish(const SweepOptions& o, const std::vector<Task>& scope, const Journal& journal,
           const Progress& progress, const fs::path& out, bool completed) {
  const auto [ok, failed, missing] = CountTasks(scope, journal);
  if (!o.quiet) {
    std::fprintf(stderr, "taebp sweep: %d of %zu tasks ok, %d failed%s (this run: %d in %s)\n", ok,
                 scope.size(), failed,
                 missing ? (", " + std::to_string(missing) + " not run").c_str() : "",
                 progress.this_run(), Hms(progress.Elapsed()).c_str());
    for (const Task& t : scope) {
      const auto it = journal.entries.find(t.index);
      if (it != journal.entries.end() && !IsOk(it->second))
        std::fprintf(stderr, "taebp sweep: task %d-%d failed: %s\n", t.point, t.replicate,
                     it->second.value("error", "").c_str());
    }
    std::fprintf(stderr, "taebp sweep: results in %s\n", out.c_str());
  }
  if (!completed) {
    if (!o.quiet)
      std::fprintf(stderr, "taebp sweep: interrupted; the same command resumes the sweep\n");
    return ExitInterrupted();
  }
  return failed || missing ? kExitFailed : 0;
}

}  // namespace

int RunSweep(const SweepOptions& o, const RunFunction& run_function) {
  const Plan plan = ExpandSweep(ReadConfigFile(o.config), o.config, o.overrides, o.reuse);
  const std::vector<Task> scope = ShardScope(plan, o.shard);  // this shard's tasks
  if (o.list) {
    PrintList(plan, scope, o.shard);
    return 0;
  }
  if (o.jobs < 0) throw ConfigError("--jobs " + std::to_string(o.jobs) + ": must be >= 1");

  Mpi mpi(o.mpi || MpiLaunchDetected());
  const fs::path out = o.out.empty() ? fs::path("results") / fs::path(o.config).stem() : fs::path(o.out);
  const int jobs = o.jobs > 0 ? o.jobs : (mpi.active() ? 1 : Cores());
  const bool root = mpi.rank() == 0;
  const bool show = root && !o.quiet;

  // Rank 0 prepares the directory and decides what is left to do; it holds
  // the folder's lock until the sweep ends.
  RootFolder folder;
  std::string setup;  // JSON: {"error", "code", "pending": [...]}
  if (root) setup = Setup(o, plan, scope, out, show, &folder);
  mpi.Bcast(&setup);
  const Json s = Json::parse(setup);
  if (s.contains("error")) return SetupFailed(s, root);
  const std::vector<Task> mine = MyTasks(s["pending"], plan, mpi);
  const int already_ok = root ? CountTasks(scope, folder.journal).ok : 0;
  if (show && already_ok > 0)
    std::fprintf(stderr, "taebp sweep: resuming in %s: %d of %zu tasks already done\n",
                 out.c_str(), already_ok, scope.size());

  // Forked workers only without MPI: MPI's threads make fork-without-exec unsafe.
  const RunFunction worker = mpi.active() || o.exec ? RunFunction() : run_function;
  KeepFromWorkers(folder.journal_file ? folder.journal_file->fd() : -1,
                  folder.lock ? folder.lock->fd() : -1);
  const InterruptGuard interrupts;  // the handlers and mask as they were, after
  BlockChildSignal();
  Progress progress(show, static_cast<int>(scope.size()), already_ok);
  Recorder record(out, plan, &folder, &progress);  // rank 0
  bool completed = false;
  try {
    if (root) completed = RunRoot(plan, out, mine, jobs, worker, mpi, record, progress, folder);
    else return RunOtherRank(plan, out, mine, jobs, worker, mpi);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "taebp sweep: error (rank %d): %s\n", mpi.rank(), e.what());
    if (root) WriteOutputs(out, plan, folder.journal, folder.header);
    if (mpi.active() && mpi.size() > 1) mpi.Abort(kExitFailed);
    throw;
  }

  if (!record.disk_full().empty()) {
    std::fprintf(stderr,
                 "taebp sweep: stopped: %s; every finished task is kept: free some space, then "
                 "the same command resumes the sweep\n",
                 record.disk_full().c_str());
    WriteOutputs(out, plan, folder.journal, folder.header);  // may fail for the same reason, naming it
    return kExitFailed;
  }
  // Rank 0: the final tables from the journal.
  WriteOutputs(out, plan, folder.journal, folder.header);
  progress.Update(true);
  return Finish(o, scope, folder.journal, progress, out, completed);
}

}  // namespace taebp::sweep
