// The sweep's worker pool (workers.h).
#include "workers.h"

#include "sweep_folder.h"
#include "taebp/config/config.h"
#include "taebp/report/report.h"
#include "taebp/rundir/output_dir.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include <fcntl.h>
#include <sched.h>
#include <sys/prctl.h>
#include <unistd.h>

namespace taebp::sweep::internal {
namespace {

int g_journal_fd = -1;  // closed in forked workers
int g_lock_fd = -1;     // the output folder's lock: closed in forked workers

// The last non-empty line of a (log) file, without the "taebp: " prefix.
std::string LastLine(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff from = std::max<std::streamoff>(0, size - 8192);
  in.seekg(from);
  std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream lines(tail);
  std::string line, last;
  while (std::getline(lines, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) last = line;
  }
  if (last.rfind("taebp: ", 0) == 0) last = last.substr(7);
  return last;
}

std::string Hostname() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

// In a forked worker: `run`'s code path in this process (`run` reports its
// errors and returns main's exit codes); never returns.
[[noreturn]] void RunInChild(const RunFunction& run, const std::string& config,
                             const std::vector<std::string>& overrides, const std::string& out) {
  int code = 1;
  try {
    code = run(config, overrides, out);
  } catch (const std::exception& e) {  // not expected: `run` reports its own errors
    std::fprintf(stderr, "taebp: error: %s\n", e.what());
  }
  std::fflush(nullptr);
  ::_exit(code);
}

}  // namespace

fs::path TaskDir(const fs::path& out, const Task& t) {
  return out / "tasks" / (std::to_string(t.point) + "-" + std::to_string(t.replicate));
}

void KeepFromWorkers(int journal_fd, int lock_fd) {
  g_journal_fd = journal_fd;
  g_lock_fd = lock_fd;
}

void BlockChildSignal() {
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  sigprocmask(SIG_BLOCK, &chld, nullptr);
}

void WaitForChild(long ms) {
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  struct timespec ts {};
  ts.tv_sec = ms / 1000;
  ts.tv_nsec = (ms % 1000) * 1000000L;
  ::sigtimedwait(&chld, nullptr, &ts);
}

int Cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

pid_t Launch(const Plan& plan, const Task& task, const fs::path& dir, const RunFunction& run) {
  std::error_code ec;
  fs::remove_all(dir, ec);  // stale outputs of an interrupted or failed attempt
  fs::create_directories(dir);
  const std::vector<std::string> overrides = plan.TaskOverrides(task);
  std::vector<std::string> args = {"taebp", "run", plan.config_path};
  for (const std::string& o : overrides) args.insert(args.end(), {"--set", o});
  args.insert(args.end(), {"--out", dir.string(), "--quiet"});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log = (dir / "stderr.log").string();
  const std::string out = dir.string();
  std::error_code abs_ec;
  const std::string task_dir = fs::weakly_canonical(fs::absolute(dir), abs_ec).string();
  const pid_t parent = ::getpid();
  std::fflush(nullptr);

  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // the worker dies with its driver
    if (::getppid() != parent) ::_exit(127);
    InterruptGuard::ResetInChild();
    ::setenv(RunFolder::kSweepTaskVariable, task_dir.c_str(), 1);  // its folder: see RunFolder
    if (g_journal_fd >= 0) ::close(g_journal_fd);
    if (g_lock_fd >= 0) ::close(g_lock_fd);  // the folder's lock stays with the driver
    const int null_fd = ::open("/dev/null", O_RDWR);
    const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (null_fd >= 0) {
      ::dup2(null_fd, STDIN_FILENO);
      ::dup2(null_fd, STDOUT_FILENO);
    }
    if (log_fd >= 0) ::dup2(log_fd, STDERR_FILENO);
    if (run) RunInChild(run, plan.config_path, overrides, out);
    // Only async-signal-safe calls from here (the parent may have threads).
    ::execv("/proc/self/exe", argv.data());
    static const char msg[] = "taebp: cannot exec /proc/self/exe\n";
    ssize_t ignored = ::write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)ignored;
    ::_exit(127);
  }
  return pid;
}

Json Collect(const Plan& plan, const Running& r, int wait_status, int rank) {
  const double wall = std::chrono::duration<double>(Clock::now() - r.start).count();
  std::string status = "failed", error, sumo_version;
  Json metrics = Json::object();
  if (WIFSIGNALED(wait_status)) {
    const int sig = WTERMSIG(wait_status);
    if (sig == SIGINT || sig == SIGTERM || sig == SIGHUP || PendingInterrupt()) return nullptr;
    error = "killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
    const std::string last = LastLine(r.dir / "stderr.log");
    if (!last.empty() && last.rfind("warning:", 0) != 0) error += ": " + last;
  } else if (WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 0) {
    try {
      const Json s = ParseSummary(ReadText(r.dir / "summary.json"));
      metrics = MetricsFromSummary(s, r.task.runs);  // the policies it ran
      if (s.contains("provenance")) sumo_version = s["provenance"].value("sumo_version", "");
      status = "ok";
    } catch (const std::exception& e) {
      error = e.what();
      metrics = Json::object();
    }
  } else {
    if (PendingInterrupt()) return nullptr;
    error = LastLine(r.dir / "stderr.log");
    if (error.empty()) error = "exit code " + std::to_string(WEXITSTATUS(wait_status));
  }
  Json e = JournalEntry(plan, r.task, status, error, metrics);
  e["wall_seconds"] = std::round(wall * 1000) / 1000;
  e["sumo_version"] = sumo_version;
  e["host"] = Hostname();
  e["rank"] = rank;
  return e;
}

}  // namespace taebp::sweep::internal
