#include "taebp/rundir/interrupt.h"

#include <cstring>

namespace taebp {
namespace {

volatile std::sig_atomic_t g_pending = 0;
extern "C" void NoteSignal(int sig) { g_pending = sig; }

}  // namespace

Interrupted::Interrupted(int signal)
    : std::runtime_error(std::string("interrupted by ") +
                         (signal == SIGINT    ? "SIGINT (Ctrl-C)"
                          : signal == SIGTERM ? "SIGTERM"
                          : signal == SIGHUP  ? "SIGHUP"
                                              : "signal " + std::to_string(signal)) +
                         ": nothing written, scratch files removed"),
      signal_(signal) {}

InterruptGuard::InterruptGuard() {
  g_pending = 0;
  sigprocmask(SIG_SETMASK, nullptr, &mask_);
  struct sigaction sa {};
  sa.sa_handler = NoteSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, &int_);
  sigaction(SIGTERM, &sa, &term_);
  sigaction(SIGHUP, &sa, &hup_);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &int_, nullptr);
  sigaction(SIGTERM, &term_, nullptr);
  sigaction(SIGHUP, &hup_, nullptr);
  sigprocmask(SIG_SETMASK, &mask_, nullptr);
}

void InterruptGuard::ResetInChild() {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  std::signal(SIGHUP, SIG_DFL);
  sigset_t none;
  sigemptyset(&none);
  sigprocmask(SIG_SETMASK, &none, nullptr);
}

int PendingInterrupt() { return g_pending; }

void ThrowIfInterrupted() {
  if (g_pending != 0) throw Interrupted(g_pending);
}

}  // namespace taebp
