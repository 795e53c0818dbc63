// Ctrl-C (SIGINT), SIGTERM and SIGHUP during a run. While an InterruptGuard
// lives, these signals only note themselves; the run notices at its next
// simulation step (ThrowIfInterrupted in the step loop) or before it writes,
// and unwinds as an error (Interrupted), so that its scratch folder in the
// temporary directory and its staging folder are removed and no results are
// half written. The command then exits with 128 + the signal's number (130
// for Ctrl-C). SIGKILL cannot be caught: what it leaves beside a run folder
// is removed by the next run there (RunFolder).
#pragma once

#include <csignal>
#include <stdexcept>
#include <string>

namespace taebp {

class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return signal_; }
  int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

// The one signal guard of taebp (run, sweep, merge, snapshot, Python):
// installs the handlers for its life; the previous handlers and the signal
// mask (a sweep blocks SIGCHLD meanwhile) are put back when it ends, so a
// Python session's own Ctrl-C handling returns after a run or a sweep.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // In a forked child that will run or exec a command of its own: the
  // default actions and an empty mask.
  static void ResetInChild();

 private:
  struct sigaction int_ {}, term_ {}, hup_ {};
  sigset_t mask_{};
};

// The signal noted (0: none); throws Interrupted when there is one.
int PendingInterrupt();
void ThrowIfInterrupted();

}  // namespace taebp
