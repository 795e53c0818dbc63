#include "taebp/rundir/output_dir.h"

#include "taebp/rundir/synced_file.h"

#include "taebp/config/policies.h"

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <set>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>
#include <algorithm>

#include <cstdio>  // renameat2

#include <climits>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace taebp {
namespace {

namespace fs = std::filesystem;

std::string Errno() { return std::strerror(errno); }

// This process's command line, arguments separated by spaces.
std::string CommandLine() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!raw.empty() && raw.back() == '\0') raw.pop_back();
  for (char& c : raw)
    if (c == '\0') c = ' ';
  return raw.empty() ? "?" : raw;
}

std::string Hostname() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "?";
  return buf;
}

std::string Now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::localtime_r(&t, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S %z", &tm);
  return buf;
}

std::string ReadFd(int fd) {
  std::string out;
  char buf[4096];
  off_t off = 0;
  for (;;) {
    const ssize_t n = ::pread(fd, buf, sizeof buf, off);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
    off += n;
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\0')) out.pop_back();
  return out;
}

}  // namespace

void CheckOutputDir(const std::string& dir, const std::string& option) {
  const std::string what = option.empty() ? dir : option + " " + dir;
  if (dir.empty()) throw OutputError(what + ": an empty path");
  for (const fs::path& part : fs::path(dir))
    if (part.string().size() > static_cast<std::size_t>(NAME_MAX))
      throw OutputError(what + ": the folder name " + part.string().substr(0, 40) + "... is " +
                        std::to_string(part.string().size()) +
                        " characters long; a file system allows at most " +
                        std::to_string(NAME_MAX));
  const fs::path target = fs::absolute(fs::path(dir)).lexically_normal();
  // The nearest existing path: the folder itself or where it would be made.
  fs::path existing = target;
  for (;;) {
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(existing, ec);
    if (st.type() != fs::file_type::not_found && st.type() != fs::file_type::none) break;
    if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory)
      throw OutputError(what + ": cannot access " + existing.string() + ": " + ec.message());
    if (!existing.has_parent_path() || existing.parent_path() == existing)
      throw OutputError(what + ": no existing parent folder");
    existing = existing.parent_path();
  }
  std::error_code ec;
  if (!fs::is_directory(existing, ec)) {
    if (fs::is_symlink(existing) && !fs::exists(existing, ec))
      throw OutputError(what + ": " + existing.string() + " is a dangling symbolic link");
    throw OutputError(what + ": " + (existing == target ? std::string("it") : existing.string()) +
                      " is a file, not a folder");
  }
  // Can files be created there? (Permissions, a read-only file system.)
  std::string probe = (existing / ".taebp-write-test.XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0)
    throw OutputError(what + ": cannot create files in " + existing.string() + ": " + Errno());
  ::close(fd);
  ::unlink(probe.c_str());
}

FolderLock::FolderLock(const std::string& dir, bool required) {
  const std::string path = (fs::path(dir) / kFileName).string();
  // Never through a symbolic link (it would write the holder's name into
  // whatever file the link names), never anything but a regular file.
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  bool writable = fd_ >= 0;
  if (fd_ < 0 && errno != ELOOP) {
    const std::string why = Errno();
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);  // read-only
    if (fd_ < 0 && errno != ELOOP) {
      if (!required) return;
      throw OutputError(dir + ": cannot create the lock file " + path + ": " + why);
    }
  }
  struct stat st {};
  if (fd_ < 0 || ::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw OutputError(dir + ": its lock file " + path +
                      " is not a regular file (a symbolic link or a special file): taebp "
                      "neither follows nor replaces it; remove it, or use another folder");
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    std::string holder;
    if (err == EWOULDBLOCK) {
      // The holder writes its name right after it locks: wait a moment for it.
      for (int i = 0; i < 20 && holder.empty(); ++i) {
        holder = ReadFd(fd_);
        if (holder.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK)
      throw OutputError(dir + " is in use by another taebp command (" +
                        (holder.empty() ? std::string("holder unknown") : holder) +
                        "); wait until it ends, or use another folder (lock: " + path + ")");
    throw OutputError(dir + ": cannot lock " + path + ": " + std::strerror(err));
  }
  if (writable) {
    const std::string text = "pid " + std::to_string(::getpid()) + " on host " + Hostname() +
                             ": " + CommandLine() + " (since " + Now() + ")\n";
    if (::ftruncate(fd_, 0) == 0) {
      ssize_t ignored = ::pwrite(fd_, text.data(), text.size(), 0);
      (void)ignored;
    }
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

bool IsPolicyFolder(const std::string& name) {
  return FindPolicy(name) != nullptr;  // config/policies.h: every policy
}

bool IsRunFile(const std::string& name) {
  static const char* const kFixed[] = {"summary.json",   "encounters.csv", "junctions.csv",
                                       "collisions.csv", "config.yaml",    "timing.json",
                                       "timeseries.csv", "hv_trust.csv",   "network.net.xml",
                                       "paired.csv"};
  for (const char* f : kFixed)
    if (name == f) return true;
  if (IsPolicyFolder(name)) return true;  // SUMO's outputs of a policy
  auto starts = [&](const char* p) { return name.rfind(p, 0) == 0; };
  auto ends = [&](const char* x) {
    const std::size_t n = std::strlen(x);
    return name.size() >= n && name.compare(name.size() - n, n, x) == 0;
  };
  if ((starts("tripinfo-") || starts("summary-")) && ends(".xml")) return true;
  // An earlier writer's temporary: a run file's name, ".tmp.", digits.
  std::string base;
  if (IsWriterTemporary(name, &base)) return IsRunFile(base);
  return false;
}

namespace {

constexpr const char* kStagingTag = ".taebp-new-";

// The staging folder of process `pid` for the run folder `dir`: a hidden
// sibling, on the same file system, so that the two can be swapped.
fs::path StagingPath(const fs::path& dir, long pid) {
  return dir.parent_path() / ("." + dir.filename().string() + kStagingTag + std::to_string(pid));
}
// Where the folder is a mount point (or its parent cannot take the sibling):
// inside it.
fs::path InnerStagingPath(const fs::path& dir, long pid) {
  return dir / (kStagingTag + std::to_string(pid));
}

// A staging folder's name with `prefix` and a process id; that process's id,
// or -1.
long StagingPid(const std::string& name, const std::string& prefix) {
  if (name.rfind(prefix, 0) != 0) return -1;
  const std::string digits = name.substr(prefix.size());
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::strtol(digits.c_str(), nullptr, 10);
}

// A copy of `from` at `to`, on disk (fsync) before it counts.
// Copied by read and write, not std::filesystem::copy_file: its kernel copy
// (sendfile) reports a full disk as "Input/output error"; write(2) says "No
// space left on device".
void CopySynced(const fs::path& from, const fs::path& to) {
  const auto fail = [&](const std::string& what, int in, int out) {
    const std::string why = Errno();
    if (in >= 0) ::close(in);
    if (out >= 0) ::close(out);
    throw std::runtime_error("cannot copy " + from.string() + " to " + to.string() + ": " + what +
                             why);
  };
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) fail("", -1, -1);
  const int out = ::open(to.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out < 0) fail("", in, -1);
  std::vector<char> buffer(1 << 20);
  for (;;) {
    const ssize_t n = ::read(in, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("read: ", in, out);
    if (n == 0) break;
    for (ssize_t done = 0; done < n;) {
      const ssize_t w = ::write(out, buffer.data() + done, static_cast<std::size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w < 0) fail("", in, out);
      done += w;
    }
  }
  if (::fsync(out) != 0) fail("fsync: ", in, out);
  ::close(in);
  if (::close(out) != 0) fail("close: ", -1, -1);
}

bool SameDevice(const fs::path& a, const fs::path& b) {
  struct stat sa {}, sb {};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev;
}

// The manifest of the set a run wrote into `dir` (RunFolder::kManifest):
// false when there is none; else its names and its first line's description.
bool ReadManifest(const fs::path& dir, std::set<std::string>* names, std::string* about) {
  std::error_code ec;
  const fs::path path = dir / RunFolder::kManifest;
  if (!fs::is_regular_file(fs::symlink_status(path, ec))) return false;
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# ", 0) == 0) {
      if (about->empty()) *about = line.substr(2);
    } else if (!line.empty()) {
      names->insert(line);
    }
  }
  return true;
}

std::string ModifiedAt(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "";
  std::tm tm{};
  ::localtime_r(&st.st_mtime, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M", &tm);
  return buf;
}

// The first entry below `folder` (named `name` in its run folder) that the
// manifest `ours` does not list; "" when all are listed.
std::string FirstUnlisted(const fs::path& folder, const std::string& name,
                          const std::set<std::string>& ours) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const std::string entry = name + "/" + e.path().filename().string();
    if (!ours.count(entry) || e.is_directory(ec) || e.is_symlink(ec)) return entry;
  }
  if (ec) return name + " (unreadable: " + ec.message() + ")";
  return "";
}

bool HoldsSweep(const fs::path& dir) {
  std::error_code ec;
  return fs::exists(dir / "sweep.json", ec) || fs::exists(dir / "journal.jsonl", ec);
}

}  // namespace

void RefuseRunResults(const std::string& dir, const std::string& what) {
  std::error_code ec;
  const fs::path abs = fs::absolute(fs::path(dir));
  if (HoldsSweep(abs)) return;  // a sweep's folder (its tables are replaced as ever)
  for (const char* marker : {"summary.json", RunFolder::kManifest})
    if (fs::exists(abs / marker, ec))
      throw OutputError(what + " holds a run's results (" + marker +
                        "): a sweep's tables there would replace the run's encounters.csv "
                        "beside its summary.json; choose another folder");
}

namespace {

// A sweep's folder, or a task folder of one other than this sweep worker's
// own, is refused: its results are the sweep's.
void RefuseSweepFolder(const fs::path& abs, const std::string& what) {
  std::error_code ec;
  for (const char* sweep_file : {"sweep.json", "journal.jsonl"})
    if (fs::exists(abs / sweep_file, ec))
      throw OutputError(what + " holds a sweep's results (" + sweep_file +
                        "): a run there would replace the sweep's pooled encounters.csv; "
                        "choose another folder");
  // A sweep's task folder belongs to its sweep (load_sweep reads it as the
  // task's results); only the sweep's own worker writes it.
  if (abs.parent_path().filename() == "tasks" && HoldsSweep(abs.parent_path().parent_path())) {
    const char* task = std::getenv(RunFolder::kSweepTaskVariable);
    if (!task || fs::path(task) != abs)
      throw OutputError(what + " is a task folder of the sweep in " +
                        abs.parent_path().parent_path().string() +
                        ": its results are that sweep's (a run there would replace them); "
                        "choose another folder");
  }
}

// A folder `e` (named `name`) in the run folder: refused unless it is a
// run's staging or a policy's folder the manifest (`ours`) lists whole.
void RefuseUsersFolder(const fs::directory_entry& e, const std::string& name,
                       const std::string& what, bool manifest, const std::set<std::string>& ours) {
  const long pid = StagingPid(name, kStagingTag);
  if (pid >= 0) return;  // a run's staging inside a mount point (below)
  if (!IsPolicyFolder(name))
    throw OutputError(what + " holds a folder, " + name +
                      ", that a run would replace with its own files; choose another "
                      "folder or move it");
  const std::string unlisted = manifest ? FirstUnlisted(e.path(), name, ours) : name;
  if (!unlisted.empty())
    throw OutputError(what + " holds a folder named like a policy, " + name + ", with " +
                      (manifest ? "files no taebp run wrote there (" + unlisted + ")"
                                : std::string("no record that a taebp run wrote it (no ") +
                                      RunFolder::kManifest + ")") +
                      ": a run would replace it; move it, or choose another folder");
}

// What an earlier run wrote here (its manifest) is replaced; nothing else
// is: a folder or a file named like a run's that no run of ours wrote
// (a user's) is refused before any work. An older taebp's results
// (summary.json, no manifest): its run files count as a run's.
void RefuseUsersEntries(const fs::path& abs, const std::string& what) {
  std::error_code ec;
  std::set<std::string> ours;
  std::string about;
  const bool manifest = ReadManifest(abs, &ours, &about);
  const bool legacy = !manifest && fs::exists(abs / "summary.json", ec);
  if (!fs::is_directory(abs, ec)) return;
  for (const fs::directory_entry& e : fs::directory_iterator(abs, ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_directory(ec) && !e.is_symlink(ec)) {
      RefuseUsersFolder(e, name, what, manifest, ours);
      continue;
    }
    if (name == RunFolder::kManifest || !IsRunFile(name)) continue;  // a user's file: kept
    std::string base;
    if (IsWriterTemporary(name, &base)) continue;  // an older writer's leftover
    if (manifest ? !ours.count(name) : !legacy)
      throw OutputError(what + " holds " + name +
                        ", a file named like a run's result that no taebp run wrote there: a "
                        "run would replace it; move or rename it, or choose another folder");
  }
}

// Staging folders of runs killed while replacing this folder: the old or
// the new set of an interrupted swap. Only the lock's holder writes them
// (the lock file goes with the swap), so with the lock held all are stale.
void RemoveStaleStaging(const fs::path& abs) {
  std::error_code ec;
  const std::string sibling = "." + abs.filename().string() + kStagingTag;
  for (const fs::path& where : {abs.parent_path(), abs}) {
    for (const fs::directory_entry& e : fs::directory_iterator(where, ec)) {
      const std::string name = e.path().filename().string();
      const long pid = StagingPid(name, where == abs ? std::string(kStagingTag) : sibling);
      if (pid >= 0) {
        std::error_code rm;
        fs::remove_all(e.path(), rm);
      }
    }
  }
}

}  // namespace

RunFolder::RunFolder(const std::string& dir, const std::string& option) : dir_(dir) {
  const std::string what = option.empty() ? dir : option + " " + dir;
  CheckOutputDir(dir, option);
  std::error_code ec;
  const fs::path abs = fs::weakly_canonical(fs::absolute(fs::path(dir)), ec);
  RefuseSweepFolder(abs, what);
  RefuseUsersEntries(abs, what);
  made_dir_ = !fs::exists(abs, ec);
  fs::create_directories(abs, ec);
  if (ec) throw OutputError(what + ": cannot create it: " + ec.message());
  made_lock_ = !fs::exists(abs / FolderLock::kFileName, ec);
  try {
    lock_ = std::make_unique<FolderLock>(abs.string());
  } catch (...) {
    if (made_dir_) fs::remove(abs, ec);  // empty unless another run got there first
    throw;
  }
  RemoveStaleStaging(abs);
}

RunFolder::~RunFolder() {
  if (replaced_ || !lock_) return;
  // The run failed before writing: the folder as it was. The lock file is
  // unlinked while still held, so a command that opened it meanwhile is
  // refused rather than let in.
  std::error_code ec;
  const fs::path dir = fs::absolute(fs::path(dir_));
  if (made_lock_ || made_dir_) fs::remove(dir / FolderLock::kFileName, ec);
  if (made_dir_) fs::remove(dir, ec);  // only when empty
  lock_.reset();
}

namespace {

using NamedFiles = std::vector<std::pair<std::string, std::string>>;

// What the folder held: said in one line ("" when no run's results).
std::string DescribeReplaced(const fs::path& dir, const std::string& name) {
  std::error_code ec;
  std::set<std::string> old_names;
  std::string old_about;
  const bool manifest = ReadManifest(dir, &old_names, &old_about);
  if (!(manifest || fs::exists(dir / "summary.json", ec))) return "";
  const std::string when = ModifiedAt(dir / (manifest ? RunFolder::kManifest : "summary.json"));
  return "replaced " + (old_about.empty() ? std::string("the results") : "the results of " + old_about) +
         (when.empty() ? "" : " from " + when) + " in " + name;
}

// Beside the folder for a swap; inside it where the folder is a mount
// point or its parent cannot take the staging folder.
fs::path MakeStaging(const fs::path& dir, bool* swap_out) {
  std::error_code ec;
  fs::path staging = StagingPath(dir, ::getpid());
  bool swap = SameDevice(dir, dir.parent_path());
  fs::remove_all(staging, ec);
  if (swap && (!fs::create_directory(staging, ec) || ec)) swap = false;
  if (!swap) {
    staging = InnerStagingPath(dir, ::getpid());
    fs::remove_all(staging, ec);
    if (!fs::create_directory(staging, ec) || ec)
      throw std::runtime_error("cannot write " + staging.string() + ": " +
                               (ec ? ec.message() : std::string("it exists")));
  }
  fs::permissions(staging, fs::status(dir, ec).permissions(), ec);
  *swap_out = swap;
  return staging;
}

// The new set into `staging`; for a swap, the folder's other files too.
void FillStaging(const fs::path& staging, const fs::path& dir, const std::string& name_of_dir,
                 const NamedFiles& files, const NamedFiles& copies, bool swap) {
  std::error_code ec;
  std::set<fs::path> subfolders;
  auto parent = [&](const std::string& name) {
    const fs::path sub = fs::path(name).parent_path();
    if (!sub.empty() && subfolders.insert(sub).second) fs::create_directories(staging / sub);
  };
  for (const auto& [name, content] : files) {
    parent(name);
    WriteSynced((staging / name).string(), content);
  }
  for (const auto& [name, from] : copies) {
    parent(name);
    CopySynced(from, staging / name);
  }
  for (const fs::path& sub : subfolders) SyncFolder((staging / sub).string());
  // For a swap, the folder's other files go with the new set (links).
  if (swap) {
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      // The lock file goes too, as a link to the same file: the lock this
      // object holds stays on the folder's lock file after the swap.
      if (IsRunFile(name) || fs::exists(staging / name)) continue;
      if (e.is_directory(ec) && !e.is_symlink(ec))
        throw OutputError(name_of_dir + " holds a folder, " + name + ", that a run would replace");
      if (::link(e.path().c_str(), (staging / name).c_str()) != 0)
        fs::copy(e.path(), staging / name, fs::copy_options::copy_symlinks);
    }
  }
  SyncFolder(staging.string());
}

// No swap: file by file, then the stale run files (the policies' folders
// of the old set go first: theirs is not a set that can be mixed).
void MoveIn(const fs::path& staging, const fs::path& dir, const NamedFiles& files,
            const NamedFiles& copies) {
  std::error_code ec;
  try {
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
      if (IsPolicyFolder(e.path().filename().string()) && e.is_directory(ec))
        fs::remove_all(e.path(), ec);
    std::vector<std::string> names;
    for (const auto& f : files) names.push_back(f.first);
    for (const auto& f : copies) names.push_back(f.first);
    for (const std::string& name : names) {
      const fs::path sub = fs::path(name).parent_path();
      if (!sub.empty()) fs::create_directories(dir / sub);
      fs::rename(staging / name, dir / name);
    }
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    const bool ours = std::any_of(files.begin(), files.end(),
                                  [&](const auto& f) { return f.first == name; }) ||
                      std::any_of(copies.begin(), copies.end(),
                                  [&](const auto& f) { return f.first == name; });
    if (IsRunFile(name) && !ours && !IsPolicyFolder(name)) fs::remove(e.path(), ec);
  }
}

}  // namespace

std::string RunFolder::Replace(const std::vector<std::pair<std::string, std::string>>& given,
                               const std::vector<std::pair<std::string, std::string>>& copies,
                               const std::string& about) {
  std::error_code ec;
  // The real folder (a symbolic link to it stays a link).
  const fs::path dir = fs::weakly_canonical(fs::absolute(fs::path(dir_)), ec);
  const std::string replaced = DescribeReplaced(dir, dir_);
  // The manifest: every name of the new set, the description first.
  std::vector<std::pair<std::string, std::string>> files = given;
  {
    std::string text = about.empty() ? "" : "# " + about + "\n";
    for (const auto& f : given) text += f.first + "\n";
    for (const auto& f : copies) text += f.first + "\n";
    files.emplace_back(kManifest, text);
  }
  bool swap = false;
  const fs::path staging = MakeStaging(dir, &swap);
  try {
    FillStaging(staging, dir, dir_, files, copies, swap);
  } catch (const OutputError&) {
    fs::remove_all(staging, ec);
    throw;
  } catch (const std::exception& e) {
    fs::remove_all(staging, ec);
    // Named by the run folder (the staging folder is a detail).
    throw std::runtime_error("cannot write the results into " + dir_ + ": " + e.what());
  }
  // One swap: the folder holds the old set until here, the new one after.
  if (swap) {
    if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
      replaced_ = true;
      SyncFolder(dir.parent_path().string());
      fs::remove_all(staging, ec);  // now the old set
      return replaced;
    }
    if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP && errno != EPERM &&
        errno != EXDEV && errno != EBUSY) {
      const std::string why = Errno();
      fs::remove_all(staging, ec);
      throw std::runtime_error("cannot write " + dir_ + ": swapping in the new results: " + why);
    }
  }
  replaced_ = true;  // from the first rename on, the folder holds this run's files
  MoveIn(staging, dir, files, copies);
  SyncFolder(dir.string());
  fs::remove_all(staging, ec);
  return replaced;
}

}  // namespace taebp
