// Output folders: checked before any work, written atomically, and locked for
// the whole life of a command that owns one (sweep, merge).
#pragma once

#include <stdexcept>
#include <string>

namespace taebp {

// An output folder that cannot be used (a file in the way, no permission, a
// read-only file system) or is in use by another command. The CLI exits 2
// (a bad argument). The message names the folder.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Checks, before any work, that `dir` is a folder or can be made one and that
// files can be created in it: no file at `dir` or at one of its parents, and
// a probe file can be created (and is removed) in `dir` or, when `dir` does
// not exist yet, in its nearest existing parent. Creates nothing. `option`
// names the argument in the message (e.g. "--out"). Throws OutputError.
void CheckOutputDir(const std::string& dir, const std::string& option = "--out");

// An exclusive lock on a folder for as long as the object lives: flock(2) on
// DIR/.taebp.lock (created if missing, never removed or renamed), whose text
// names the holder: pid, host, command line and start time. A second command
// on the same folder gets an OutputError naming that holder. The lock goes
// away with the process however it ends. The descriptor is close-on-exec;
// a forked child that does not exec should close fd().
class FolderLock {
 public:
  static constexpr const char* kFileName = ".taebp.lock";
  // `required` false: a folder where the lock file cannot be created (read-
  // only) is used unlocked; another holder is still an error.
  explicit FolderLock(const std::string& dir, bool required = true);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
};

}  // namespace taebp
