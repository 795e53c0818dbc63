#include "taebp/rundir/synced_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace taebp {

namespace fs = std::filesystem;

void WriteSynced(const std::string& path, const std::string& content) {
  auto fail = [&](const char* what) {
    return std::runtime_error("cannot write " + path + ": " + what + ": " + std::strerror(errno));
  };
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) throw fail("open");
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::runtime_error e = fail("write");
      ::close(fd);
      throw e;
    }
    done += static_cast<std::size_t>(n);
  }
  int rc;
  while ((rc = ::fsync(fd)) != 0 && errno == EINTR) {
  }
  if (rc != 0) {
    const std::runtime_error e = fail("fsync");
    ::close(fd);
    throw e;
  }
  if (::close(fd) != 0 && errno != EINTR) throw fail("close");
}

void SyncFolder(const std::string& dir) {
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

namespace {

void FsyncFile(const std::string& path, const std::string& named) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  int rc = fd < 0 ? -1 : 0;
  if (fd >= 0)
    while ((rc = ::fsync(fd)) != 0 && errno == EINTR) {
    }
  if (rc != 0) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    throw std::runtime_error("cannot write " + named + ": fsync: " + why);
  }
  ::close(fd);
}

std::string ParentOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

}  // namespace

SyncedWriter::SyncedWriter(std::string path, bool sync)
    : path_(std::move(path)), tmp_(path_ + ".tmp." + std::to_string(::getpid())), sync_(sync) {
  std::error_code ec;
  fs::remove(tmp_, ec);  // a stale temporary (or a link planted there) goes first
  errno = 0;
  out_.open(tmp_, std::ios::binary | std::ios::trunc);
  if (!out_)
    throw std::runtime_error("cannot write " + path_ + ": open: " +
                             (errno ? std::strerror(errno) : "cannot create " + tmp_));
}

SyncedWriter::~SyncedWriter() {
  if (committed_) return;
  out_.close();
  std::error_code ec;
  fs::remove(tmp_, ec);
}

void SyncedWriter::Commit() {
  errno = 0;
  out_.flush();
  const int err = errno;  // set by the failed write (ENOSPC on a full disk)
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail())
    throw std::runtime_error("cannot write " + path_ + ": write: " +
                             (err != 0 ? std::strerror(err) : "the stream failed (disk full?)"));
  if (sync_) FsyncFile(tmp_, path_);
  fs::rename(tmp_, path_);
  committed_ = true;
  if (sync_) SyncFolder(ParentOf(path_));
}

void PutInPlace(const std::string& from, const std::string& to) {
  FsyncFile(from, to);
  fs::rename(from, to);
  SyncFolder(ParentOf(to));
}

bool PutFolderInPlace(const std::string& from, const std::string& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) {
    fs::remove_all(from, ec);
    return false;
  }
  SyncFolder(ParentOf(to));
  return true;
}

void WriteFilesAtomically(const std::string& dir,
                          const std::vector<std::pair<std::string, std::string>>& files) {
  fs::create_directories(dir);
  const std::string suffix = ".tmp." + std::to_string(::getpid());
  std::vector<fs::path> temps;
  try {
    // Each file in full, on disk, under a temporary name ...
    for (const auto& [name, content] : files) {
      const fs::path tmp = fs::path(dir) / (name + suffix);
      temps.push_back(tmp);
      WriteSynced(tmp.string(), content);
    }
  } catch (...) {
    std::error_code ec;
    for (const fs::path& t : temps) fs::remove(t, ec);
    throw;
  }
  // ... then renamed into place, and the folder's entries synced.
  for (std::size_t i = 0; i < files.size(); ++i)
    fs::rename(temps[i], fs::path(dir) / files[i].first);
  SyncFolder(dir);
}

bool IsWriterTemporary(const std::string& file_name, std::string* name) {
  const std::size_t tmp = file_name.rfind(".tmp.");
  if (tmp == std::string::npos || tmp == 0 || tmp + 5 >= file_name.size() ||
      file_name.find_first_not_of("0123456789", tmp + 5) != std::string::npos)
    return false;
  if (name) *name = file_name.substr(0, tmp);
  return true;
}

int RemoveWriterTemporaries(const std::string& dir, const std::vector<std::string>& names) {
  int removed = 0;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    std::string name;
    if (!IsWriterTemporary(e.path().filename().string(), &name)) continue;
    if (std::find(names.begin(), names.end(), name) == names.end()) continue;
    std::error_code ec2;
    if (!e.is_regular_file(ec2) || e.is_symlink(ec2)) continue;
    if (fs::remove(e.path(), ec2)) ++removed;
  }
  return removed;
}

}  // namespace taebp
