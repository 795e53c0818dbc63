// The rows of timeseries.csv and hv_trust.csv of one policy's run, streamed
// to files as they are sampled, so that a run's memory does not grow with
// simulated time (issue 45 item 7: an 8-HV learning run sampled every second
// held 320,000 per-HV rows in memory at 40,000 s and died with bad_alloc
// further on). The run folder's two files are assembled from the spools of
// its runs (WriteTimeseriesCsv, WriteHvTrustCsv in report.h) and copied into
// place like SUMO's outputs.
#pragma once

#include "taebp/report/results.h"

#include <cstdio>
#include <string>

namespace taebp {

class SampleSpool {
 public:
  // Rows go to DIR/POLICY.timeseries.rows and DIR/POLICY.hv_trust.rows
  // (removed with the spool); an empty `dir`: unnamed temporary files.
  // Throws std::runtime_error naming the file it cannot create.
  SampleSpool(std::string policy, const std::string& dir);
  ~SampleSpool();
  SampleSpool(const SampleSpool&) = delete;
  SampleSpool& operator=(const SampleSpool&) = delete;

  const std::string& Policy() const { return policy_; }
  // One row each, formatted by the files' column tables (report.cc); throws
  // std::runtime_error naming the file when it cannot be written (a full disk).
  void Add(const TimeSample& s);
  void Add(const HvSample& s);
  long TimeRows() const { return time_.rows; }
  long HvRows() const { return hv_.rows; }
  // The rows as written (no header), appended to `out`; throws
  // std::runtime_error naming both files when reading or writing fails.
  void CopyTimeRows(std::FILE* out, const std::string& out_name) const;
  void CopyHvRows(std::FILE* out, const std::string& out_name) const;
  // The rows' text (tests; Python reads the assembled files instead).
  std::string TimeRowsText() const;
  std::string HvRowsText() const;

 private:
  struct Rows {
    std::FILE* file = nullptr;
    std::string path;  // empty: unnamed
    long rows = 0;
  };
  static void Open(Rows* rows, const std::string& dir, const std::string& name);
  static void Close(Rows* rows);
  static void Append(Rows* rows, const std::string& line);
  template <typename Chunk>
  static void ForEachChunk(const Rows& rows, Chunk chunk);
  static void Copy(const Rows& rows, std::FILE* out, const std::string& out_name);
  static std::string Text(const Rows& rows);

  std::string policy_;
  Rows time_, hv_;
};

}  // namespace taebp
