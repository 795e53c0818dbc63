// The sweep engine: the driver behind `taebp sweep` / `taebp merge`. Every task (one grid point x one
// seed) is a separate process, `taebp run CONFIG --set ... --out TASKDIR`
// (libsumo runs one simulation per process); up to --jobs of them at once,
// optionally spread over MPI ranks or Slurm-array shards. Finished tasks are
// appended to DIR/journal.jsonl (one write(2) + fsync each), which makes the
// sweep resumable; the tables are rebuilt from the journal at the end.
#include "taebp/report/exit_codes.h"
#include "taebp/sweep/engine.h"

#include "taebp/sweep/plan.h"
#include "taebp/config/config.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/rundir/synced_file.h"
#include "taebp/report/report.h"
#include "taebp/persuasion/persuasion.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sched.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#ifdef TAEBP_HAVE_MPI
#define OMPI_SKIP_MPICXX 1  // the C API only
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

// A sanitizer build (tools/test --sanitize) ignores what OpenMPI allocates in
// MPI_Init and never frees, and runs an MPI rank's leak check just before
// MPI_Finalize: OpenMPI's plug-ins are unloaded there and its libevent thread
// leaks with "<unknown module>" frames that tools/sanitizers/lsan.supp cannot
// name. Everything the sweep allocated is checked all the same.
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define TAEBP_THIRD_PARTY_ALLOCATIONS __lsan::ScopedDisabler lsan_disabled
#define TAEBP_LEAK_CHECK_NOW() __lsan_do_leak_check()
#else
#define TAEBP_THIRD_PARTY_ALLOCATIONS
#define TAEBP_LEAK_CHECK_NOW()
#endif

namespace taebp::sweep {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// report/exit_codes.h: kExitFailed (a failed or missing task); interrupted:
// 128 + the signal (130 Ctrl-C, 143 SIGTERM, 129 SIGHUP), as `run`.
int ExitInterrupted() { return kExitSignalBase + (PendingInterrupt() ? PendingInterrupt() : SIGINT); }

int g_journal_fd = -1;  // closed in forked workers
int g_lock_fd = -1;     // the output folder's lock: closed in forked workers

// The files a sweep writes into its folder with WriteFilesAtomically (their
// temporaries, left by a kill, are removed when the folder is next locked).
const std::vector<std::string> kSweepFiles = {"sweep.json",    "journal.jsonl", "results.csv",
                                              "aggregate.csv", "encounters.csv"};

// "no space left on device in DIR" when a file of a task's size cannot be
// written into `dir` (a full disk or quota), else "".
std::string NoSpaceIn(const fs::path& dir) {
  const fs::path probe = dir / (".taebp-space-probe." + std::to_string(::getpid()));
  std::string why;
  try {
    WriteSynced(probe.string(), std::string(256 * 1024, '\0'));
  } catch (const std::exception& e) {
    const std::string message = e.what();
    for (const int err : {ENOSPC, EDQUOT})
      if (why.empty() && message.find(std::strerror(err)) != std::string::npos)
        why = std::string(std::strerror(err)) + " in " + dir.string();
  }
  std::error_code ec;
  fs::remove(probe, ec);
  return why;
}

// SIGCHLD blocked and waited for (WaitForChild); SIGINT/SIGTERM/SIGHUP are
// the InterruptGuard's (interrupt.h), which puts the mask back.
void BlockChildSignal() {
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  sigprocmask(SIG_BLOCK, &chld, nullptr);
}

// Sleeps until a child exits, a signal arrives or `ms` passed.
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

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

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

std::string Hms(double seconds) {
  if (!(seconds >= 0)) return "?";
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

std::string Hostname() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

// ------------------------------------------------------------------ MPI
// Rank 0 owns the output directory; the others run their share of the tasks
// and send each finished task's journal line to rank 0.
enum Tag { kTagResult = 1, kTagDone = 2, kTagStop = 3 };

bool MpiLaunchDetected() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}

class Mpi {
 public:
  explicit Mpi(bool use) {
#ifdef TAEBP_HAVE_MPI
    if (!use) return;
    TAEBP_THIRD_PARTY_ALLOCATIONS;
    MPI_Init(nullptr, nullptr);
    active_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
#else
    (void)use;
#endif
  }
  ~Mpi() {
#ifdef TAEBP_HAVE_MPI
    if (!active_) return;
    TAEBP_LEAK_CHECK_NOW();
    MPI_Finalize();
#endif
  }
  Mpi(const Mpi&) = delete;
  Mpi& operator=(const Mpi&) = delete;

  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }

  void Bcast(std::string* s) {
#ifdef TAEBP_HAVE_MPI
    if (!active_) return;
    long n = static_cast<long>(s->size());
    MPI_Bcast(&n, 1, MPI_LONG, 0, MPI_COMM_WORLD);
    s->resize(static_cast<std::size_t>(n));
    MPI_Bcast(s->data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
#else
    (void)s;
#endif
  }
  void Send(const std::string& s, int to, int tag) {
#ifdef TAEBP_HAVE_MPI
    if (!active_) return;
    MPI_Send(s.data(), static_cast<int>(s.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
#else
    (void)s, (void)to, (void)tag;
#endif
  }
  // A waiting message from `from` (-1: anyone), if any.
  bool Receive(int from, std::string* msg, int* tag, int* source) {
#ifdef TAEBP_HAVE_MPI
    if (!active_) return false;
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(from < 0 ? MPI_ANY_SOURCE : from, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (!flag) return false;
    int count = 0;
    MPI_Get_count(&st, MPI_CHAR, &count);
    msg->assign(static_cast<std::size_t>(count), '\0');
    MPI_Recv(msg->data(), count, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    *tag = st.MPI_TAG;
    *source = st.MPI_SOURCE;
    return true;
#else
    (void)from, (void)msg, (void)tag, (void)source;
    return false;
#endif
  }
  [[noreturn]] void Abort(int code) {
#ifdef TAEBP_HAVE_MPI
    if (active_) MPI_Abort(MPI_COMM_WORLD, code);
#endif
    std::_Exit(code);
  }

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
};

// ------------------------------------------------------------------ journal file
// journal.jsonl, opened O_APPEND. The folder's FolderLock (not this file,
// which `merge` replaces) keeps a second command out.
class JournalFile {
 public:
  explicit JournalFile(const fs::path& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw std::runtime_error(path.string() + ": cannot open the journal: " + std::strerror(errno));
  }
  ~JournalFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  JournalFile(const JournalFile&) = delete;
  JournalFile& operator=(const JournalFile&) = delete;

  std::string ReadAll() const {
    std::string out;
    char buf[65536];
    off_t off = 0;
    for (;;) {
      const ssize_t n = ::pread(fd_, buf, sizeof buf, off);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw std::runtime_error(path_.string() + ": read failed: " + std::strerror(errno));
      if (n == 0) break;
      out.append(buf, static_cast<std::size_t>(n));
      off += n;
    }
    return out;
  }
  int fd() const { return fd_; }
  void Truncate(std::size_t size) {
    if (::ftruncate(fd_, static_cast<off_t>(size)) != 0 || ::fsync(fd_) != 0)
      throw std::runtime_error(path_.string() + ": truncate failed: " + std::strerror(errno));
  }
  // One line, one write(2) on the O_APPEND descriptor, then fsync: a crash
  // leaves either the whole line or a torn tail that the next run truncates.
  void Append(const std::string& line) {
    const std::string data = line + "\n";
    std::size_t done = 0;
    while (done < data.size()) {
      const ssize_t n = ::write(fd_, data.data() + done, data.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0)
        throw std::runtime_error(path_.string() + ": write failed: " + std::strerror(errno));
      done += static_cast<std::size_t>(n);
    }
    while (::fsync(fd_) != 0 && errno == EINTR) {
    }
  }

 private:
  fs::path path_;
  int fd_ = -1;
};

// ------------------------------------------------------------------ progress
class Progress {
 public:
  Progress(bool enabled, int total, int done_before)
      : enabled_(enabled), tty_(::isatty(STDERR_FILENO) == 1), total_(total),
        done_(done_before), start_(Clock::now()), last_(start_) {}

  void Finished(bool ok) {
    ++done_;
    ++this_run_;
    if (!ok) ++failed_;
  }
  int failed() const { return failed_; }
  int this_run() const { return this_run_; }
  double Elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  void Update(bool final = false) {
    if (!enabled_) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (!final && since < (tty_ ? 0.2 : 5.0)) return;
    last_ = now;
    const double elapsed = Elapsed();
    const int remaining = total_ - done_;
    const double eta = this_run_ > 0 ? elapsed / this_run_ * remaining : -1;
    std::string eta_text = remaining == 0 ? "0:00" : Hms(eta);
    char line[256];
    if (tty_) {
      constexpr int kWidth = 24;
      const int filled = total_ > 0 ? kWidth * done_ / total_ : kWidth;
      std::string bar(static_cast<std::size_t>(filled), '#');
      bar.resize(kWidth, '.');
      std::snprintf(line, sizeof line, "\rtaebp sweep [%s] %d/%d tasks, %d failed, %s elapsed, ETA %s\033[K",
                    bar.c_str(), done_, total_, failed_, Hms(elapsed).c_str(), eta_text.c_str());
      std::fputs(line, stderr);
      if (final) std::fputc('\n', stderr);
    } else {
      std::snprintf(line, sizeof line, "taebp sweep: %d/%d tasks done, %d failed, %s elapsed, ETA %s\n",
                    done_, total_, failed_, Hms(elapsed).c_str(), eta_text.c_str());
      std::fputs(line, stderr);
    }
    std::fflush(stderr);
  }

 private:
  bool enabled_, tty_;
  int total_, done_, this_run_ = 0, failed_ = 0;
  Clock::time_point start_, last_;
};

// ------------------------------------------------------------------ workers
struct Running {
  pid_t pid = -1;
  Task task;
  fs::path dir;
  Clock::time_point start;
};

fs::path TaskDir(const fs::path& out, const Task& t) {
  return out / "tasks" / (std::to_string(t.point) + "-" + std::to_string(t.replicate));
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

// Starts one task: `taebp run CONFIG --set ... --out DIR --quiet`, either by
// calling `run` in a fork of this process or (no `run`) by exec'ing this binary.
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

// The journal entry of a finished worker; null if it was interrupted (killed
// by SIGINT/SIGTERM or exited while we are stopping): such a task is not
// recorded and runs again next time.
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

// Runs `tasks` with up to `jobs` workers. `done` gets each finished task's
// journal entry; `poll` runs every turn of the loop and may ask to stop.
// Returns false if stopped early (signal or poll).
template <typename Done, typename Poll>
bool RunTasks(const Plan& plan, const fs::path& out, const std::vector<Task>& tasks, int jobs,
              int rank, const RunFunction& run, Done&& done, Poll&& poll) {
  std::deque<Task> queue(tasks.begin(), tasks.end());
  std::vector<Running> running;
  bool stop = false;
  Clock::time_point stop_time;
  bool killed_hard = false;
  for (;;) {
    if ((PendingInterrupt() || poll()) && !stop) {
      stop = true;
      stop_time = Clock::now();
      for (const Running& r : running) ::kill(r.pid, SIGTERM);
    }
    if (stop && !killed_hard && Clock::now() - stop_time > std::chrono::seconds(5)) {
      for (const Running& r : running) ::kill(r.pid, SIGKILL);
      killed_hard = true;
    }
    while (!stop && static_cast<int>(running.size()) < jobs && !queue.empty()) {
      Running r;
      r.task = queue.front();
      queue.pop_front();
      if (r.task.runs.empty()) {  // every policy reused: nothing to simulate
        done(JournalEntry(plan, r.task, "ok", "", Json::object()));
        continue;
      }
      r.dir = TaskDir(out, r.task);
      r.start = Clock::now();
      r.pid = Launch(plan, r.task, r.dir, run);
      running.push_back(r);
    }
    if (running.empty() && (stop || queue.empty())) break;
    bool reaped = false;
    for (std::size_t i = 0; i < running.size();) {
      int st = 0;
      const pid_t p = ::waitpid(running[i].pid, &st, WNOHANG);
      if (p == running[i].pid) {
        reaped = true;
        Json e = Collect(plan, running[i], st, rank);
        running.erase(running.begin() + static_cast<std::ptrdiff_t>(i));
        if (e.is_null()) {
          stop = stop || PendingInterrupt();
          continue;
        }
        done(e);
      } else {
        ++i;
      }
    }
    if (!reaped) WaitForChild(20);
  }
  return !stop;
}

// ------------------------------------------------------------------ sweep
void ParseShard(const std::string& text, int* index, int* count) {
  *index = 0;
  *count = 1;
  if (text.empty()) return;
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    std::size_t a = 0, b = 0;
    *index = std::stoi(text.substr(0, slash), &a);
    *count = std::stoi(text.substr(slash + 1), &b);
    if (a != slash || b != text.size() - slash - 1) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw ConfigError("--shard " + text + ": expected I/N, e.g. --shard 0/4");
  }
  if (*count < 1 || *index < 0 || *index >= *count)
    throw ConfigError("--shard " + text + ": expected I/N with 0 <= I < N");
}

std::string SumoVersionOf(const Journal& journal) {
  for (const auto& [i, e] : journal.entries) {
    const std::string v = e.value("sumo_version", "");
    if (!v.empty()) return v;
  }
  return "";
}

// encounters.csv of the sweep: every ok task's encounters.csv rows, with the
// task's point, replicate, seed and swept values in front. Streamed (a large
// grid's rows need not fit in memory) into a temporary file renamed into place.
void WritePooledEncounters(const fs::path& out, const Plan& plan, const Journal& journal) {
  auto join = [](const std::vector<std::string>& cols) {
    std::string h;
    for (const std::string& c : cols) h += (h.empty() ? "" : ",") + c;
    return h;
  };
  // The header line of each ok task's encounters.csv, read once.
  std::vector<std::string> headers;
  for (const Task& t : plan.tasks) {
    const auto it = journal.entries.find(t.index);
    if (it == journal.entries.end() || !IsOk(it->second) || t.runs.empty()) continue;
    std::ifstream in(TaskDir(out, t) / "encounters.csv", std::ios::binary);
    std::string line;
    if (in && std::getline(in, line)) headers.push_back(line);
  }
  // A network scenario's tasks have its column (EncounterCsvColumns(..., true)),
  // the first readable task says which. A task of a run beyond the paper has
  // the extra columns (EncounterCsvColumns(true, ...)); when any has, the
  // pooled file has them and the other tasks' rows get empty cells.
  const bool network = !headers.empty() && (headers[0] == join(EncounterCsvColumns(false, true)) ||
                                            headers[0] == join(EncounterCsvColumns(true, true)));
  const std::string paper_header = join(EncounterCsvColumns(false, network));
  const std::string beyond_header = join(EncounterCsvColumns(true, network));
  const std::string padding(
      EncounterCsvColumns(true, network).size() - EncounterCsvColumns(false, network).size(), ',');
  const bool any_beyond =
      std::find(headers.begin(), headers.end(), beyond_header) != headers.end();
  const std::string task_header = any_beyond ? beyond_header : paper_header;
  const fs::path tmp = out / ("encounters.csv.tmp." + std::to_string(::getpid()));
  std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
  errno = 0;
  if (!f) throw std::runtime_error("cannot write " + tmp.string());
  f << "point,replicate,seed";
  for (const std::string& c : plan.columns) f << ',' << CsvCell(c);
  f << ',' << task_header << '\n';
  for (const Task& t : plan.tasks) {
    const auto it = journal.entries.find(t.index);
    if (it == journal.entries.end() || !IsOk(it->second) || t.runs.empty()) continue;
    const fs::path file = TaskDir(out, t) / "encounters.csv";
    std::ifstream in(file, std::ios::binary);
    std::string line;
    const bool read = in && std::getline(in, line);
    const bool pad = any_beyond && read && line == paper_header;
    if (!read || (line != task_header && !pad)) {
      std::fprintf(stderr, "taebp sweep: warning: %s %s; its encounters are not in %s\n",
                   file.c_str(), in ? "has other columns (another taebp version?)" : "is missing",
                   (out / "encounters.csv").c_str());
      continue;
    }
    std::string prefix = std::to_string(t.point) + ',' + std::to_string(t.replicate) + ',' +
                         std::to_string(t.seed);
    for (const std::string& v : plan.points[static_cast<std::size_t>(t.point)].values)
      prefix += ',' + CsvCell(v);
    while (std::getline(in, line))
      if (!line.empty()) f << prefix << ',' << line << (pad ? padding : std::string()) << '\n';
  }
  f.flush();
  if (!f) {
    const int err = errno;  // set by the failed write (ENOSPC on a full disk)
    f.close();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write " + tmp.string() + ": " +
                             (err != 0 ? std::strerror(err) : "the stream failed (disk full?)"));
  }
  f.close();
  fs::rename(tmp, out / "encounters.csv");
}

void WriteOutputs(const fs::path& out, const Plan& plan, const Journal& journal, Json header) {
  WritePooledEncounters(out, plan, journal);
  header["sumo_version"] = SumoVersionOf(journal);
  WriteFilesAtomically(out.string(), {{"results.csv", ResultsCsv(plan, journal)},
                                      {"results.jsonl", ResultsJsonl(plan, journal)},
                                      {"aggregate.csv", AggregateCsv(plan, journal)},
                                      {"sweep.json", Dump(header, 2) + "\n"}});
}

std::string ShardName(const std::string& shard) {
  return shard.empty() ? "the unsharded sweep" : "shard " + shard;
}

// Refuses a directory that holds another sweep or, for `sweep` (check_shard),
// another shard of this one: a folder belongs to one (sweep, shard).
void CheckHeader(const fs::path& dir, const std::string& hash, bool check_shard = false,
                 const std::string& shard = "") {
  const fs::path p = dir / "sweep.json";
  if (!fs::exists(p)) return;
  Json h;
  try {
    h = Json::parse(ReadText(p));
    if (!h.is_object()) throw std::runtime_error("not a JSON object");
  } catch (const std::exception& e) {
    throw ConfigError(p.string() + ": unreadable (" + e.what() + "); remove it or use another --out");
  }
  const std::string other =
      h.contains("config_hash") && h["config_hash"].is_string() ? h["config_hash"].get<std::string>() : "";
  if (other != hash)
    throw ConfigError(p.string() + ": " + dir.string() + " holds a different sweep (config hash " +
                      other + ", this one " + hash +
                      "): the config, its grid or the --set overrides differ; use another --out "
                      "or remove that directory");
  if (!check_shard) return;
  const std::string held = h.contains("shard") && h["shard"].is_string() ? h["shard"].get<std::string>() : "";
  if (held != shard)
    throw ConfigError(p.string() + ": " + dir.string() + " holds " + ShardName(held) +
                      " of this sweep, and this is " + ShardName(shard) +
                      ": use another --out (shards go to their own folders; `taebp merge` "
                      "joins them)");
}

// The files a finished task leaves in its folder.
bool HasTaskOutputs(const fs::path& task_dir) {
  std::error_code ec;
  return fs::is_regular_file(task_dir / "summary.json", ec);
}

void WarnCorrupt(const Journal& journal, const char* who) {
  for (const std::string& c : journal.corrupt)
    std::fprintf(stderr, "taebp %s: warning: skipping a corrupt journal line: %s\n", who, c.c_str());
}

// The tasks of `scope` (a shard's tasks) still to run: no ok entry yet, or
// an ok entry whose task folder lost its outputs (`lost` counts those).
std::vector<Task> Pending(const std::vector<Task>& scope, const Journal& j, const fs::path& out,
                          int* lost) {
  std::vector<Task> pending;
  *lost = 0;
  for (const Task& t : scope) {
    const auto it = j.entries.find(t.index);
    if (it == j.entries.end() || !IsOk(it->second)) {
      pending.push_back(t);
    } else if (!t.runs.empty() && !HasTaskOutputs(TaskDir(out, t))) {
      pending.push_back(t);
      ++*lost;
    }
  }
  return pending;
}

}  // namespace

bool HaveMpi() {
#ifdef TAEBP_HAVE_MPI
  return true;
#else
  return false;
#endif
}

int RunSweep(const SweepOptions& o, const RunFunction& run_function) {
  const Plan plan = ExpandSweep(ReadConfigFile(o.config), o.config, o.overrides, o.reuse);
  int shard_index = 0, shard_count = 1;
  ParseShard(o.shard, &shard_index, &shard_count);
  std::vector<Task> scope;  // this shard's tasks
  for (const Task& t : plan.tasks)
    if (t.index % shard_count == shard_index) scope.push_back(t);

  if (o.list) {
    std::printf("%zu points x %d replicates = %zu tasks, %zu policy runs (%zu reused)%s\n",
                plan.points.size(), plan.replicates, plan.tasks.size(), plan.Runs(), plan.Reused(),
                o.shard.empty() ? "" : (", shard " + o.shard + ": " + std::to_string(scope.size())).c_str());
    for (const Task& t : scope) {
      std::printf("%d point=%d replicate=%d seed=%llu", t.index, t.point, t.replicate,
                  static_cast<unsigned long long>(t.seed));
      const Point& p = plan.points[static_cast<std::size_t>(t.point)];
      for (std::size_t k = 0; k < plan.columns.size(); ++k)
        std::printf(" %s=%s", plan.columns[k].c_str(), p.values[k].c_str());
      for (const auto& [policy, from] : t.reused_from) {  // runs it does not make again
        const Task& f = plan.tasks[static_cast<std::size_t>(from)];
        std::printf(" %s:reuses=%d-%d", policy.c_str(), f.point, f.replicate);
      }
      std::printf("\n");
    }
    return 0;
  }
  if (o.jobs < 0) throw ConfigError("--jobs " + std::to_string(o.jobs) + ": must be >= 1");

  Mpi mpi(o.mpi || MpiLaunchDetected());
  const fs::path out = o.out.empty() ? fs::path("results") / fs::path(o.config).stem() : fs::path(o.out);
  const int jobs = o.jobs > 0 ? o.jobs : (mpi.active() ? 1 : Cores());
  const bool root = mpi.rank() == 0;
  const bool show = root && !o.quiet;

  // Rank 0 prepares the directory and decides what is left to do; it holds
  // the folder's lock until the sweep ends.
  std::unique_ptr<FolderLock> lock;
  std::unique_ptr<JournalFile> journal_file;
  Journal journal;
  Json header;
  std::string setup;  // JSON: {"error", "code", "pending": [...]}
  if (root) {
    Json s;
    try {
      CheckOutputDir(out.string());
      RefuseRunResults(out.string(), "--out " + out.string());
      fs::create_directories(out);
      lock = std::make_unique<FolderLock>(out.string());
      RemoveWriterTemporaries(out.string(), kSweepFiles);  // a killed table write's
      CheckHeader(out, plan.hash, true, o.shard);
      fs::create_directories(out / "tasks");
      journal_file = std::make_unique<JournalFile>(out / "journal.jsonl");
      const std::string text = journal_file->ReadAll();
      journal = ParseJournal(text, plan, (out / "journal.jsonl").string());
      if (show) WarnCorrupt(journal, "sweep");
      if (journal.partial_tail) {
        if (show)
          std::fprintf(stderr, "taebp sweep: dropping a half-written last line of %s\n",
                       (out / "journal.jsonl").c_str());
        journal_file->Truncate(journal.valid_bytes);
      }
      header = SweepHeader(plan, o.shard, SumoVersionOf(journal));
      if (!fs::exists(out / "sweep.json"))
        WriteFilesAtomically(out.string(), {{"sweep.json", Dump(header, 2) + "\n"}});
      Json pending = Json::array();
      int lost = 0;
      for (const Task& t : Pending(scope, journal, out, &lost)) pending.push_back(t.index);
      if (lost > 0 && show)
        std::fprintf(stderr,
                     "taebp sweep: %d finished task(s) lost their outputs in %s/tasks: running "
                     "them again\n",
                     lost, out.c_str());
      s["pending"] = pending;
    } catch (const ConfigError& e) {
      s["error"] = e.what();
      s["code"] = 2;
    } catch (const OutputError& e) {
      s["error"] = e.what();
      s["code"] = 4;
    } catch (const std::exception& e) {
      s["error"] = e.what();
      s["code"] = 1;
    }
    setup = Dump(s);
  }
  mpi.Bcast(&setup);
  const Json s = Json::parse(setup);
  if (s.contains("error")) {
    if (!root) return s.value("code", 1) == 4 ? 2 : s.value("code", 1);
    if (s.value("code", 1) == 2) throw ConfigError(s["error"].get<std::string>());
    if (s.value("code", 1) == 4) throw OutputError(s["error"].get<std::string>());
    throw std::runtime_error(s["error"].get<std::string>());
  }
  std::vector<Task> mine;
  {
    const Json& pending = s["pending"];
    for (std::size_t k = 0; k < pending.size(); ++k)
      if (static_cast<int>(k % static_cast<std::size_t>(mpi.size())) == mpi.rank())
        mine.push_back(plan.tasks[pending[k].get<std::size_t>()]);
  }
  const int already_ok = root ? CountTasks(scope, journal).ok : 0;
  if (show && already_ok > 0)
    std::fprintf(stderr, "taebp sweep: resuming in %s: %d of %zu tasks already done\n",
                 out.c_str(), already_ok, scope.size());

  // Forked workers only without MPI: MPI's threads make fork-without-exec unsafe.
  const RunFunction worker = mpi.active() || o.exec ? RunFunction() : run_function;
  if (journal_file) g_journal_fd = journal_file->fd();
  if (lock) g_lock_fd = lock->fd();
  const InterruptGuard interrupts;  // the handlers and mask as they were, after
  BlockChildSignal();
  Progress progress(show, static_cast<int>(scope.size()), already_ok);
  std::string disk_full;  // why the sweep stopped for want of space ("" = it did not)
  auto record = [&](const Json& e) {  // rank 0
    // A task failed on a full disk: the sweep stops (README) rather than run
    // and fail every remaining task; the task is not recorded (a resume redoes it).
    if (!IsOk(e)) {
      const std::string why = NoSpaceIn(out);
      if (!why.empty()) {
        if (disk_full.empty())
          disk_full = why + " (task " + std::to_string(e.value("point", -1)) + "-" +
                      std::to_string(e.value("replicate", -1)) + ": " + e.value("error", "") + ")";
        return;
      }
    }
    journal_file->Append(Dump(e));
    AddEntry(&journal, plan, e);
    progress.Finished(IsOk(e));
    progress.Update();
  };
  int ranks_done = 1;
  bool stop_sent = false;
  bool completed = false;
  try {
    if (root) {
      auto poll = [&]() {
        std::string msg;
        int tag = 0, source = 0;
        while (mpi.Receive(-1, &msg, &tag, &source)) {
          if (tag == kTagResult) record(Json::parse(msg));
          else if (tag == kTagDone) ++ranks_done;
        }
        progress.Update();
        return !disk_full.empty();
      };
      completed = RunTasks(plan, out, mine, jobs, 0, worker, record, poll);
      // Gather the other ranks' results until each reports done.
      const auto wait_from = Clock::now();
      while (ranks_done < mpi.size()) {
        if (PendingInterrupt() && !stop_sent) {
          for (int r = 1; r < mpi.size(); ++r) mpi.Send("", r, kTagStop);
          stop_sent = true;
        }
        poll();
        if (PendingInterrupt() && Clock::now() - wait_from > std::chrono::seconds(30)) {
          std::fprintf(stderr, "taebp sweep: ranks did not stop in time, aborting\n");
          WriteOutputs(out, plan, journal, header);
          mpi.Abort(ExitInterrupted());
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(15));
      }
      completed = completed && !PendingInterrupt();
    } else {
      bool stop = false;
      auto poll = [&]() {
        std::string msg;
        int tag = 0, source = 0;
        while (mpi.Receive(0, &msg, &tag, &source))
          if (tag == kTagStop) stop = true;
        return stop;
      };
      auto send = [&](const Json& e) { mpi.Send(Dump(e), 0, kTagResult); };
      completed = RunTasks(plan, out, mine, jobs, mpi.rank(), worker, send, poll);
      mpi.Send(completed ? "ok" : "stopped", 0, kTagDone);
      return completed ? 0 : ExitInterrupted();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "taebp sweep: error (rank %d): %s\n", mpi.rank(), e.what());
    if (root) WriteOutputs(out, plan, journal, header);
    if (mpi.active() && mpi.size() > 1) mpi.Abort(kExitFailed);
    throw;
  }

  if (!disk_full.empty()) {
    std::fprintf(stderr,
                 "taebp sweep: stopped: %s; every finished task is kept: free some space, then "
                 "the same command resumes the sweep\n",
                 disk_full.c_str());
    WriteOutputs(out, plan, journal, header);  // may fail for the same reason, naming it
    return kExitFailed;
  }
  // Rank 0: the final tables from the journal.
  WriteOutputs(out, plan, journal, header);
  progress.Update(true);
  const auto [ok, failed, missing] = CountTasks(scope, journal);
  if (!o.quiet) {
    std::fprintf(stderr, "taebp sweep: %d of %zu tasks ok, %d failed%s (this run: %d in %s)\n", ok,
                 scope.size(), failed,
                 missing ? (", " + std::to_string(missing) + " not run").c_str() : "",
                 progress.this_run(), Hms(progress.Elapsed()).c_str());
    for (const Task& t : scope) {
      const auto it = journal.entries.find(t.index);
      if (it != journal.entries.end() && !IsOk(it->second))
        std::fprintf(stderr, "taebp sweep: task %d-%d failed: %s\n", t.point, t.replicate,
                     it->second.value("error", "").c_str());
    }
    std::fprintf(stderr, "taebp sweep: results in %s\n", out.c_str());
  }
  if (!completed) {
    if (!o.quiet)
      std::fprintf(stderr, "taebp sweep: interrupted; the same command resumes the sweep\n");
    return ExitInterrupted();
  }
  return failed || missing ? kExitFailed : 0;
}

// ------------------------------------------------------------------ merge
int RunMerge(const MergeOptions& o) {
  if (o.dirs.empty()) throw ConfigError("taebp merge: no shard directories given");
  // OUT is locked for the whole merge, and so is every shard folder (a shard's
  // sweep still running there is refused rather than merged half-done).
  const fs::path out(o.out);
  CheckOutputDir(out.string(), "OUT");
  RefuseRunResults(out.string(), "OUT " + out.string());
  // Each shard once: the same folder twice (or through a link) is an error.
  std::map<fs::path, std::string> seen;
  for (const std::string& d : o.dirs) {
    std::error_code ec;
    if (!fs::is_directory(d, ec))
      throw ConfigError(d + ": not a folder (is it the --out of a taebp sweep --shard?)");
    const fs::path real = fs::canonical(d, ec);
    const auto [it, fresh] = seen.emplace(ec ? fs::absolute(d) : real, d);
    if (!fresh)
      throw ConfigError("taebp merge: " + d + " is given twice" +
                        (it->second == d ? std::string() : " (as " + it->second + ")") +
                        "; name each shard folder once");
  }
  const InterruptGuard interrupts;  // a signal now waits until the merge is written
  fs::create_directories(out);
  FolderLock lock(out.string());
  RemoveWriterTemporaries(out.string(), kSweepFiles);
  std::vector<std::unique_ptr<FolderLock>> shard_locks;
  for (const std::string& d : o.dirs) {
    std::error_code ec;
    if (fs::equivalent(out, d, ec)) continue;
    shard_locks.push_back(std::make_unique<FolderLock>(d, /*required=*/false));
  }

  std::vector<Json> headers;
  for (const std::string& d : o.dirs) {
    const fs::path p = fs::path(d) / "sweep.json";
    if (!fs::exists(p))
      throw ConfigError(p.string() + ": missing (is " + d + " the --out of a taebp sweep?)");
    try {
      headers.push_back(Json::parse(ReadText(p)));
      const Json& h = headers.back();
      if (!h.is_object() || !h.contains("config_hash") || !h["config_hash"].is_string() ||
          !h.contains("config_text") || !h["config_text"].is_string())
        throw std::runtime_error("no config_hash or config_text");
      for (const char* k : {"config_path"})
        if (h.contains(k) && !h[k].is_string()) throw std::runtime_error(std::string(k) + " is not a string");
      if (h.contains("replicates") &&
          !(h["replicates"].is_number_integer() && h["replicates"].get<std::int64_t>() >= 1 &&
            h["replicates"].get<std::int64_t>() <= 10000000))
        throw std::runtime_error("replicates is not an integer in [1, 10000000]");
      if (h.contains("overrides") &&
          !(h["overrides"].is_array() &&
            std::all_of(h["overrides"].begin(), h["overrides"].end(),
                        [](const Json& v) { return v.is_string(); })))
        throw std::runtime_error("overrides is not a list of strings");
    } catch (const std::exception& e) {
      throw ConfigError(p.string() + ": unreadable: " + e.what());
    }
    const std::string h = headers.back()["config_hash"].get<std::string>();
    if (h != headers.front()["config_hash"].get<std::string>())
      throw ConfigError(p.string() + ": " + d + " holds a different sweep (config hash " + h +
                        ") than " + o.dirs.front() + " (" +
                        headers.front()["config_hash"].get<std::string>() + ")");
  }
  const Json& first = headers.front();
  int replicates = 0;
  for (const Json& h : headers) replicates = std::max(replicates, h.value("replicates", 1));
  std::vector<std::string> overrides = first.value("overrides", std::vector<std::string>{});
  if (replicates != first.value("replicates", 1))
    overrides.push_back("sweep.replicates=" + std::to_string(replicates));
  const std::string origin = first.value("config_path", (fs::path(o.dirs.front()) / "sweep.json").string());
  Plan plan = ExpandSweep(first["config_text"].get<std::string>(), origin, overrides,
                          first.value("reuse", true));
  const std::string hash = first["config_hash"].get<std::string>();
  if (plan.hash != hash) {
    std::fprintf(stderr,
                 "taebp merge: warning: this taebp computes config hash %s for the sweep "
                 "recorded as %s (another version?); using the recorded one\n",
                 plan.hash.c_str(), hash.c_str());
    plan.hash = hash;
  }

  CheckHeader(out, plan.hash);
  const fs::path journal_path = out / "journal.jsonl";
  Journal journal;
  if (fs::exists(journal_path)) {
    journal = ParseJournal(ReadText(journal_path), plan, journal_path.string());
    if (!o.quiet) WarnCorrupt(journal, "merge");
  }
  std::map<int, fs::path> source;  // task index -> shard dir holding its outputs
  for (const std::string& d : o.dirs) {
    std::error_code ec;
    if (fs::equivalent(out, d, ec)) continue;
    const fs::path jp = fs::path(d) / "journal.jsonl";
    if (!fs::exists(jp)) continue;
    const Journal shard = ParseJournal(ReadText(jp), plan, jp.string());
    if (!o.quiet) WarnCorrupt(shard, "merge");
    for (const auto& [index, e] : shard.entries) {
      // The task's outputs come from the shard whose entry the journal keeps.
      if (AddEntry(&journal, plan, e)) source[index] = d;
    }
  }
  // Per-task outputs next to the merged tables. An ok task whose folder is
  // missing in its shard is reported (its row is in the tables, its files
  // are not): running that shard's sweep again redoes it.
  std::vector<std::string> lost;
  for (const auto& [index, dir] : source) {
    ThrowIfInterrupted();  // OUT's tables as they were; copied task folders are redone
    const Task& t = plan.tasks[static_cast<std::size_t>(index)];
    const fs::path from = TaskDir(dir, t), to = TaskDir(out, t);
    if (t.runs.empty()) continue;  // every policy reused: no folder
    if (!HasTaskOutputs(from)) {
      if (IsOk(journal.entries.at(index))) lost.push_back(from.string());
      continue;
    }
    std::error_code ec;
    fs::remove_all(to, ec);
    fs::create_directories(to.parent_path());
    fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  }
  for (const auto& [index, e] : journal.entries) {  // already in OUT: check it is there
    if (source.count(index) || !IsOk(e) || plan.tasks[static_cast<std::size_t>(index)].runs.empty())
      continue;
    const fs::path here = TaskDir(out, plan.tasks[static_cast<std::size_t>(index)]);
    if (!HasTaskOutputs(here)) lost.push_back(here.string());
  }
  std::string lines;
  for (const auto& [index, e] : journal.entries) lines += Dump(e) + "\n";
  Json header = SweepHeader(plan, "", SumoVersionOf(journal));
  header["merged_from"] = o.dirs;
  ThrowIfInterrupted();
  WriteFilesAtomically(out.string(), {{"journal.jsonl", lines}});
  WriteOutputs(out, plan, journal, header);

  const auto [ok, failed, missing] = CountTasks(plan.tasks, journal);
  for (const std::string& l : lost)
    std::fprintf(stderr, "taebp merge: error: a finished task's outputs are missing: %s/summary.json\n",
                 l.c_str());
  if (!lost.empty())
    std::fprintf(stderr,
                 "taebp merge: %zu task folder(s) missing: run the shards' `taebp sweep` again "
                 "(it redoes tasks whose folders are gone), then merge again\n",
                 lost.size());
  if (!o.quiet)
    std::fprintf(stderr,
                 "taebp merge: %zu shard dirs, %d of %zu tasks ok (%zu without their task "
                 "folder), %d failed, %d missing; results in %s\n",
                 o.dirs.size(), ok, plan.tasks.size(), lost.size(), failed, missing, out.c_str());
  return failed || missing || !lost.empty() ? kExitFailed : 0;
}

}  // namespace taebp::sweep
