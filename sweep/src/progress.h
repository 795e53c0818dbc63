// The sweep's progress line on stderr: a bar redrawn at most 5 times a
// second on a terminal, else a line every 5 s; tasks done, failed, elapsed
// time and an ETA from this run's pace.
#pragma once

#include <chrono>
#include <string>

namespace taebp::sweep::internal {

// h:mm:ss (or m:ss under an hour); "?" for a negative or NaN time.
std::string Hms(double seconds);

class Progress {
 public:
  Progress(bool enabled, int total, int done_before);

  void Finished(bool ok);
  int failed() const { return failed_; }
  int this_run() const { return this_run_; }
  double Elapsed() const;
  void Update(bool final = false);

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_, tty_;
  int total_, done_, this_run_ = 0, failed_ = 0;
  Clock::time_point start_, last_;
};

}  // namespace taebp::sweep::internal
