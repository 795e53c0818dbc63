// The sweep's progress line (progress.h).
#include "progress.h"

#include <cstdio>

#include <unistd.h>

namespace taebp::sweep::internal {

std::string Hms(double seconds) {
  if (!(seconds >= 0)) return "?";
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

Progress::Progress(bool enabled, int total, int done_before)
    : enabled_(enabled), tty_(::isatty(STDERR_FILENO) == 1), total_(total), done_(done_before),
      start_(Clock::now()), last_(start_) {}

void Progress::Finished(bool ok) {
  ++done_;
  ++this_run_;
  if (!ok) ++failed_;
}

double Progress::Elapsed() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void Progress::Update(bool final) {
  if (!enabled_) return;
  const auto now = Clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (!final && since < (tty_ ? 0.2 : 5.0)) return;
  last_ = now;
  const double elapsed = Elapsed();
  const int remaining = total_ - done_;
  const double eta = this_run_ > 0 ? elapsed / this_run_ * remaining : -1;
  std::string eta_text = remaining == 0 ? "0:00" : Hms(eta);
  char line[256];
  if (tty_) {
    constexpr int kWidth = 24;
    const int filled = total_ > 0 ? kWidth * done_ / total_ : kWidth;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::snprintf(line, sizeof line, "\rtaebp sweep [%s] %d/%d tasks, %d failed, %s elapsed, ETA %s\033[K",
                  bar.c_str(), done_, total_, failed_, Hms(elapsed).c_str(), eta_text.c_str());
    std::fputs(line, stderr);
    if (final) std::fputc('\n', stderr);
  } else {
    std::snprintf(line, sizeof line, "taebp sweep: %d/%d tasks done, %d failed, %s elapsed, ETA %s\n",
                  done_, total_, failed_, Hms(elapsed).c_str(), eta_text.c_str());
    std::fputs(line, stderr);
  }
  std::fflush(stderr);
}

}  // namespace taebp::sweep::internal
