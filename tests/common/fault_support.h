// Faults for tests: a small tmpfs (full or read-only output folders), a
// folder without write permission, a file size limit, a disk filled up.
#pragma once

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

#include <fcntl.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

namespace taebp::test {

// A tmpfs of `bytes` mounted on an existing empty folder for the object's
// life (root only). Mount returns null and says why when it cannot.
class Tmpfs {
 public:
  static std::unique_ptr<Tmpfs> Mount(const std::filesystem::path& dir, long bytes, bool read_only,
                                      std::string* why) {
    if (::geteuid() != 0) {
      *why = "not root, cannot mount a tmpfs";
      return nullptr;
    }
    const std::string options = "size=" + std::to_string(bytes) + ",mode=0755";
    const unsigned long flags = read_only ? MS_RDONLY : 0;
    if (::mount("tmpfs", dir.c_str(), "tmpfs", flags, options.c_str()) != 0) {
      *why = std::string("mount -t tmpfs failed: ") + std::strerror(errno);
      return nullptr;
    }
    return std::unique_ptr<Tmpfs>(new Tmpfs(dir));
  }
  ~Tmpfs() { ::umount2(dir_.c_str(), MNT_DETACH); }
  Tmpfs(const Tmpfs&) = delete;
  Tmpfs& operator=(const Tmpfs&) = delete;

 private:
  explicit Tmpfs(std::filesystem::path dir) : dir_(std::move(dir)) {}
  std::filesystem::path dir_;
};

// Removes write permission from `dir`; false (with why) when that does not
// stop this process from creating a file there (root).
inline bool MakeReadOnly(const std::filesystem::path& dir, std::string* why) {
  ::chmod(dir.c_str(), 0555);
  const std::string probe = (dir / "probe").string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd >= 0) {
    ::close(fd);
    ::unlink(probe.c_str());
    ::chmod(dir.c_str(), 0755);
    *why = "permissions do not stop this user (root) from writing, and no tmpfs";
    return false;
  }
  return true;
}

// In a child before exec: files cannot grow past `bytes`; a write past it
// fails with EFBIG instead of killing the process (SIGXFSZ ignored, which
// survives exec).
inline void LimitFileSize(rlim_t bytes) {
  ::signal(SIGXFSZ, SIG_IGN);
  struct rlimit r {};
  r.rlim_cur = r.rlim_max = bytes;
  ::setrlimit(RLIMIT_FSIZE, &r);
}

// Writes `path` until the file system is full.
inline void FillDisk(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return;
  static const char block[4096] = {};
  while (::write(fd, block, sizeof block) > 0) {
  }
  ::close(fd);
}

}  // namespace taebp::test
