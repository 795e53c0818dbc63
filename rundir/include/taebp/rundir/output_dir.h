// Output folders: checked before any work, written atomically, and locked for
// the whole life of a command that owns one (run, sweep, merge). What each
// command refuses, keeps and replaces: docs/results-folders.md.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

// A file a run writes into its folder (summary.json, encounters.csv,
// junctions.csv, collisions.csv, config.yaml, timing.json, timeseries.csv, hv_trust.csv,
// tripinfo-*.xml, summary-*.xml) or a temporary one of an earlier version's
// writer (NAME.tmp.PID).
bool IsRunFile(const std::string& name);
// A folder named after a policy: that policy's SUMO outputs (a run file).
bool IsPolicyFolder(const std::string& name);

// A sweep or merge into a folder holding a run's results (summary.json or a
// run's manifest, and no sweep.json) would replace the run's encounters.csv
// with the sweep's pooled one: refused (OutputError naming `what`).
void RefuseRunResults(const std::string& dir, const std::string& what);

// A run's output folder (taebp run, taebp.run(..., out=...)) for the life of
// the run. On construction, before any simulation:
// - checked as CheckOutputDir does;
// - not a sweep's folder (sweep.json or journal.jsonl in it: a run would
//   replace the sweep's pooled encounters.csv beside its tables);
// - not a sweep's task folder (DIR/tasks/P-R beside sweep.json), unless
//   this process is the sweep's worker for it (kSweepTaskVariable = its path);
// - holding nothing named like a run's file or a policy's folder that no
//   taebp run wrote there: the manifest (kManifest) of the last run lists
//   what is its; an older taebp's folder (summary.json, no manifest) counts
//   its run files as a run's but not its policy folders; any other folder
//   is refused (the whole folder is replaced at the end); other files (a
//   user's notes) are kept;
// - created if missing and locked (FolderLock) for the object's life, so two
//   runs, or a run and a sweep, never write one folder at once;
// - what runs killed while replacing it left beside it (see Replace) removed.
// Throws OutputError naming the folder and why. Destroyed without a Replace
// (the run failed), it leaves the folder as it found it: a folder it made is
// removed again when still empty, a lock file it made too.
class RunFolder {
 public:
  // The list of the files the last run wrote here, one per line after a
  // "# description" line; part of each set it writes.
  static constexpr const char* kManifest = ".taebp-files";
  // Set by a sweep for its worker: the task folder it may write.
  static constexpr const char* kSweepTaskVariable = "TAEBP_SWEEP_TASK";

  explicit RunFolder(const std::string& dir, const std::string& option = "--out");
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  // Replaces the folder's run files with `files` as one set: the new set is
  // written in full (fsync) into a staging folder beside it
  // (.NAME.taebp-new-PID), the folder's other files (a user's notes,
  // pictures) are linked into it, and the two folders are swapped in one
  // rename (renameat2 RENAME_EXCHANGE), then the old one is removed. A
  // reader sees the old set or the new one, never a mix; run files of the
  // old set that the new one lacks (a rerun with fewer policies) are gone.
  // Where the file system cannot swap folders, the files are renamed into
  // place one by one and stale run files removed.
  // `copies`: files copied into the set (name -> the file), e.g. SUMO's
  // outputs; a name may hold one folder level (POLICY/NAME: a policy's
  // folder, a run file like the others).
  // `about` describes the set in the manifest (e.g. "2 policies (no_trust,
  // ta_ebp)"). Returns one line saying what was replaced ("replaced the
  // results of 3 policies (...) from 2026-12-03 18:00 in R"), "" when the
  // folder held no results.
  std::string Replace(const std::vector<std::pair<std::string, std::string>>& files,
                      const std::vector<std::pair<std::string, std::string>>& copies = {},
                      const std::string& about = "");

  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::unique_ptr<FolderLock> lock_;
  bool made_dir_ = false, made_lock_ = false, replaced_ = false;
};

}  // namespace taebp
