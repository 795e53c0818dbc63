// The one synced file writer: every file taebp puts in place goes through
// here (a run folder's staging set, a sweep's tables, its header, merge's
// journal, the pooled encounters.csv, SUMO's outputs rewritten, a snapshot's
// picture, the network cache), so that a file counts only once it is on
// disk. tests/layers checks that nothing else renames a file into place.
#pragma once

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace taebp {

// Writes `content` to `path` (created or truncated, never through a symbolic
// link), then fsync and close; write(2) interrupted by a signal continues.
// Throws std::runtime_error "cannot write PATH: open|write|fsync|close: why"
// (an I/O failure, exit 1).
void WriteSynced(const std::string& path, const std::string& content);

// fsync of a folder's entries (after renames into it); best effort.
void SyncFolder(const std::string& dir);

// A file written in pieces (a table too large to hold, a streamed rewrite)
// and put in place only once complete and on disk: written to PATH.tmp.PID
// (IsWriterTemporary), then flushed, fsynced, renamed over PATH and the folder
// synced by Commit. Destroyed before Commit: the temporary is removed and
// PATH is as it was. Errors: std::runtime_error "cannot write PATH: ...".
// `sync` false: a scratch file (SUMO's output rewritten in the scratch
// folder), put in place by the rename alone; what lands in a results folder
// is copied there with fsync (output_dir.h), so the scratch copy is not
// synced twice.
class SyncedWriter {
 public:
  explicit SyncedWriter(std::string path, bool sync = true);
  ~SyncedWriter();
  SyncedWriter(const SyncedWriter&) = delete;
  SyncedWriter& operator=(const SyncedWriter&) = delete;
  std::ostream& Stream() { return out_; }
  void Commit();

 private:
  std::string path_, tmp_;
  std::ofstream out_;
  bool sync_ = true;
  bool committed_ = false;
};

// Puts a finished file that another program wrote (sumo-gui's picture) in
// place at `to`: fsync, rename, folder synced.
void PutInPlace(const std::string& from, const std::string& to);

// Puts a finished folder in place at `to` unless a folder is there already
// (another process finished first: `from` is removed and false returned).
bool PutFolderInPlace(const std::string& from, const std::string& to);

// Writes `files` (name -> content) into `dir` atomically: each is written
// with WriteSynced to NAME.tmp.PID in `dir` and renamed into place only after
// all were written, so a failure never leaves a half-written result (the
// temporaries are removed). Creates `dir`.
void WriteFilesAtomically(const std::string& dir,
                          const std::vector<std::pair<std::string, std::string>>& files);

// A temporary of an interrupted WriteFilesAtomically: NAME.tmp.DIGITS; NAME
// is set to the file it stood for.
bool IsWriterTemporary(const std::string& file_name, std::string* name = nullptr);

// Removes from `dir` (not below) the temporaries WriteFilesAtomically left
// when killed, of the files named in `names` only (a user's file that merely
// looks like one stays). Called by a process holding the folder's lock: no
// other writer is at work there. Returns how many were removed.
int RemoveWriterTemporaries(const std::string& dir, const std::vector<std::string>& names);

}  // namespace taebp
