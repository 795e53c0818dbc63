#include "taebp/report/sample_spool.h"

#include "taebp/report/report.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <unistd.h>

namespace taebp {

namespace {

std::string Errno() { return std::strerror(errno); }

std::string Named(const std::string& path) {
  return path.empty() ? std::string("a temporary file of the time series") : path;
}

}  // namespace

SampleSpool::SampleSpool(std::string policy, const std::string& dir) : policy_(std::move(policy)) {
  Open(&time_, dir, policy_ + ".timeseries.rows");
  try {
    Open(&hv_, dir, policy_ + ".hv_trust.rows");
  } catch (...) {
    Close(&time_);
    throw;
  }
}

SampleSpool::~SampleSpool() {
  Close(&time_);
  Close(&hv_);
}

void SampleSpool::Close(Rows* rows) {
  if (rows->file) std::fclose(rows->file);
  rows->file = nullptr;
  if (!rows->path.empty()) ::unlink(rows->path.c_str());
  rows->path.clear();
}

void SampleSpool::Open(Rows* rows, const std::string& dir, const std::string& name) {
  if (dir.empty()) {
    rows->file = std::tmpfile();
    if (!rows->file)
      throw std::runtime_error("cannot create a temporary file for the time series: " + Errno());
    return;
  }
  rows->path = (std::filesystem::path(dir) / name).string();
  rows->file = std::fopen(rows->path.c_str(), "w+");
  if (!rows->file) {
    const std::string why = Errno();
    const std::string path = rows->path;
    rows->path.clear();  // not ours to remove
    throw std::runtime_error("cannot create " + path + ": " + why);
  }
}

void SampleSpool::Append(Rows* rows, const std::string& line) {
  if (std::fwrite(line.data(), 1, line.size(), rows->file) != line.size())
    throw std::runtime_error("cannot write " + Named(rows->path) + ": " + Errno());
  ++rows->rows;
}

void SampleSpool::Add(const TimeSample& s) { Append(&time_, TimeseriesCsvRow(policy_, s)); }
void SampleSpool::Add(const HvSample& s) { Append(&hv_, HvTrustCsvRow(policy_, s)); }

// The rows as written, chunk by chunk (pread: the spool's own writing
// position stays where it is).
template <typename Chunk>
void SampleSpool::ForEachChunk(const Rows& rows, Chunk chunk) {
  if (std::fflush(rows.file) != 0)
    throw std::runtime_error("cannot write " + Named(rows.path) + ": " + Errno());
  std::vector<char> buffer(1 << 16);
  for (off_t at = 0;;) {
    const ssize_t n = ::pread(::fileno(rows.file), buffer.data(), buffer.size(), at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error("cannot read " + Named(rows.path) + ": " + Errno());
    if (n == 0) break;
    chunk(buffer.data(), static_cast<std::size_t>(n));
    at += n;
  }
}

void SampleSpool::Copy(const Rows& rows, std::FILE* out, const std::string& out_name) {
  ForEachChunk(rows, [&](const char* data, std::size_t n) {
    if (std::fwrite(data, 1, n, out) != n)
      throw std::runtime_error("cannot write " + out_name + ": " + Errno());
  });
}

void SampleSpool::CopyTimeRows(std::FILE* out, const std::string& out_name) const {
  Copy(time_, out, out_name);
}
void SampleSpool::CopyHvRows(std::FILE* out, const std::string& out_name) const {
  Copy(hv_, out, out_name);
}

std::string SampleSpool::Text(const Rows& rows) {
  std::string text;
  ForEachChunk(rows, [&](const char* data, std::size_t n) { text.append(data, n); });
  return text;
}

std::string SampleSpool::TimeRowsText() const { return Text(time_); }
std::string SampleSpool::HvRowsText() const { return Text(hv_); }

}  // namespace taebp
