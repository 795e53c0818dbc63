// The sweep's worker pool: each task is a process (a fork of this one that
// calls `run`, or an exec of this binary), at most --jobs at once; a finished
// worker's folder becomes its journal entry. SIGCHLD is blocked and waited for;
// a pending SIGINT/SIGTERM/SIGHUP (rundir/interrupt.h) stops the pool: workers
// get SIGTERM, then SIGKILL after 5 s, and an interrupted task is not recorded.
#pragma once

#include "taebp/rundir/interrupt.h"
#include "taebp/sweep/engine.h"
#include "taebp/sweep/plan.h"

#include <chrono>
#include <cstddef>
#include <deque>
#include <filesystem>
#include <vector>

#include <sys/types.h>
#include <sys/wait.h>

namespace taebp::sweep::internal {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Running {
  pid_t pid = -1;
  Task task;
  fs::path dir;
  Clock::time_point start;
};

// OUT/tasks/POINT-REPLICATE.
fs::path TaskDir(const fs::path& out, const Task& t);

// The cores this process may run on (its affinity mask).
int Cores();

// File descriptors a forked worker closes (the journal, the folder's lock,
// which stays with the driver); -1 for none.
void KeepFromWorkers(int journal_fd, int lock_fd);

// SIGCHLD blocked, to be waited for by WaitForChild; SIGINT/SIGTERM/SIGHUP
// are the InterruptGuard's (interrupt.h), which puts the mask back.
void BlockChildSignal();

// Sleeps until a child exits, a signal arrives or `ms` passed.
void WaitForChild(long ms);

// Starts one task: `taebp run CONFIG --set ... --out DIR --quiet`, either by
// calling `run` in a fork of this process or (no `run`) by exec'ing this binary.
pid_t Launch(const Plan& plan, const Task& task, const fs::path& dir, const RunFunction& run);

// The journal entry of a finished worker; null if it was interrupted (killed
// by SIGINT/SIGTERM or exited while we are stopping): such a task is not
// recorded and runs again next time.
Json Collect(const Plan& plan, const Running& r, int wait_status, int rank);

// Runs `tasks` with up to `jobs` workers. `done` gets each finished task's
// journal entry; `poll` runs every turn of the loop and may ask to stop.
// Returns false if stopped early (signal or poll).
template <typename Done, typename Poll>
bool RunTasks(const Plan& plan, const fs::path& out, const std::vector<Task>& tasks, int jobs,
              int rank, const RunFunction& run, Done&& done, Poll&& poll) {
  std::deque<Task> queue(tasks.begin(), tasks.end());
  std::vector<Running> running;
  bool stop = false;
  Clock::time_point stop_time;
  bool killed_hard = false;
  for (;;) {
    if ((PendingInterrupt() || poll()) && !stop) {
      stop = true;
      stop_time = Clock::now();
      for (const Running& r : running) ::kill(r.pid, SIGTERM);
    }
    if (stop && !killed_hard && Clock::now() - stop_time > std::chrono::seconds(5)) {
      for (const Running& r : running) ::kill(r.pid, SIGKILL);
      killed_hard = true;
    }
    while (!stop && static_cast<int>(running.size()) < jobs && !queue.empty()) {
      Running r;
      r.task = queue.front();
      queue.pop_front();
      if (r.task.runs.empty()) {  // every policy reused: nothing to simulate
        done(JournalEntry(plan, r.task, "ok", "", Json::object()));
        continue;
      }
      r.dir = TaskDir(out, r.task);
      r.start = Clock::now();
      r.pid = Launch(plan, r.task, r.dir, run);
      running.push_back(r);
    }
    if (running.empty() && (stop || queue.empty())) break;
    bool reaped = false;
    for (std::size_t i = 0; i < running.size();) {
      int st = 0;
      const pid_t p = ::waitpid(running[i].pid, &st, WNOHANG);
      if (p == running[i].pid) {
        reaped = true;
        Json e = Collect(plan, running[i], st, rank);
        running.erase(running.begin() + static_cast<std::ptrdiff_t>(i));
        if (e.is_null()) {
          stop = stop || PendingInterrupt();
          continue;
        }
        done(e);
      } else {
        ++i;
      }
    }
    if (!reaped) WaitForChild(20);
  }
  return !stop;
}

}  // namespace taebp::sweep::internal
