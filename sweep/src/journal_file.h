// journal.jsonl of a sweep folder, opened O_APPEND: one finished task a line,
// each appended with one write(2) and an fsync, so a crash leaves either the
// whole line or a torn tail that the next run truncates. The folder's
// FolderLock (not this file, which `merge` replaces) keeps a second command out.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace taebp::sweep::internal {

class JournalFile {
 public:
  explicit JournalFile(const std::filesystem::path& path);  // throws when it cannot open it
  ~JournalFile();
  JournalFile(const JournalFile&) = delete;
  JournalFile& operator=(const JournalFile&) = delete;

  std::string ReadAll() const;
  int fd() const { return fd_; }
  void Truncate(std::size_t size);           // to `size` bytes, then fsync
  void Append(const std::string& line);      // the line and "\n", then fsync

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace taebp::sweep::internal
