#include "taebp/report/output_dir.h"

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
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
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  bool writable = fd_ >= 0;
  if (fd_ < 0) {
    const std::string why = Errno();
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);  // a read-only folder
    if (fd_ < 0) {
      if (!required) return;
      throw OutputError(dir + ": cannot create the lock file " + path + ": " + why);
    }
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

}  // namespace taebp
