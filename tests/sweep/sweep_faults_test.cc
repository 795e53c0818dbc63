// `taebp sweep` / `taebp merge` under faults and misuse, run as a user would:
// a bad grid refused before any task, one folder per (sweep, shard), one
// command per folder (the holder named), a killed worker, lost task folders,
// corrupt journal lines, a full disk. Nothing already written is lost.
#include "sweep_fixture.h"

#include "fault_support.h"
#include "stall_support.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using taebp::test::Quote;
using taebp::test::ReadFile;
using taebp::test::SweepCli;
using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Starts `taebp ARGS...` in its own process group, output to `log`.
pid_t Start(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> all = {TAEBP_CLI};
  all.insert(all.end(), args.begin(), args.end());
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  return pid;
}

int Wait(pid_t pid) {
  int st = 0;
  while (::waitpid(pid, &st, 0) < 0) {
  }
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

// Polls `ready` every 5 ms for up to `seconds`.
template <typename F>
bool WaitFor(F&& ready, int seconds = 60) {
  const auto deadline = Clock::now() + std::chrono::seconds(seconds);
  while (Clock::now() < deadline) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// The first child process of `pid` (its sweep worker), or -1.
pid_t FirstChild(pid_t pid) {
  const std::string children =
      ReadFile("/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) + "/children");
  return children.empty() ? -1 : static_cast<pid_t>(std::stol(children));
}

// ------------------------------------------------------------------ the grid

// A misspelt grid key, or a value out of range at one point, is refused
// before anything runs (it used to run every task and fail each one), with
// the point and the key named.
TEST_F(SweepCli, BadGridKeyOrValueIsRefusedBeforeAnyTask) {
  const fs::path out = dir_ / "out";
  const fs::path typo = Config("    model.trsut: [0.2, 0.4]\n", 1);
  EXPECT_EQ(Sweep(typo, out), 2) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("sweep.grid point 0 (model.trsut=0.2)"));
  EXPECT_THAT(last_log_, HasSubstr("unknown key 'model.trsut'"));
  EXPECT_THAT(last_log_, HasSubstr("and 1 more invalid grid point"));
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(Taebp("sweep " + Quote(typo.string()) + " --list"), 2) << last_log_;

  const fs::path range = Config("    model.trust: [0.5, 1.5]\n", 1);
  EXPECT_EQ(Sweep(range, out), 2) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("sweep.grid point 1 (model.trust=1.5)"));
  EXPECT_THAT(last_log_, HasSubstr("model.trust = 1.5 is outside [0, 1]"));
  EXPECT_FALSE(fs::exists(out));
}

// ------------------------------------------------------------------ one folder, one (sweep, shard)

TEST_F(SweepCli, ShardIntoAnotherShardsOrTheUnshardedFolderIsRefused) {
  const fs::path cfg = Config("    model.trust: [0.5]\n", 2);
  const fs::path out = dir_ / "out";
  ASSERT_EQ(Sweep(cfg, out), 0) << last_log_;
  const std::string header = ReadFile(out / "sweep.json");
  const std::string results = ReadFile(out / "results.csv");
  EXPECT_EQ(Sweep(cfg, out, "--shard 0/2"), 2) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("holds the unsharded sweep of this sweep, and this is shard 0/2"));
  EXPECT_EQ(ReadFile(out / "sweep.json"), header);
  EXPECT_EQ(ReadFile(out / "results.csv"), results);

  const fs::path s0 = dir_ / "s0";
  ASSERT_EQ(Sweep(cfg, s0, "--shard 0/2"), 0) << last_log_;
  EXPECT_EQ(Sweep(cfg, s0), 2) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("holds shard 0/2 of this sweep, and this is the unsharded sweep"));
  EXPECT_EQ(Sweep(cfg, s0, "--shard 1/2"), 2) << last_log_;
  EXPECT_EQ(Sweep(cfg, s0, "--shard 0/3"), 2) << last_log_;
  EXPECT_EQ(Sweep(cfg, s0, "--shard 0/2"), 0) << last_log_;  // the same shard resumes
}

// ------------------------------------------------------------------ one command per folder

// While a sweep runs in a folder, a second sweep or a merge into it is
// refused, naming the holder; while a merge runs (held up reading a shard's
// journal from a FIFO), a sweep or merge into its folder is refused too.
// `merge` used to rename a new journal over the one whose lock it held.
TEST_F(SweepCli, SecondCommandOnAFolderIsRefusedNamingTheHolder) {
  const fs::path cfg = Config("    model.trust: [0.5]\n", 4);
  const fs::path out = dir_ / "out";
  const pid_t sweep = Start({"sweep", cfg.string(), "--out", out.string(), "--jobs", "1",
                             "--quiet", "--set", "scenario.duration=600"},
                            dir_ / "sweep.log");
  ASSERT_TRUE(WaitFor([&] { return !ReadFile(out / ".taebp.lock").empty(); })) << "no lock";
  const std::string holder = "pid " + std::to_string(sweep) + " on host ";
  EXPECT_EQ(Sweep(cfg, out, "--set scenario.duration=600"), 2) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("is in use by another taebp command (" + holder));
  EXPECT_THAT(last_log_, HasSubstr(" sweep " + cfg.string()));
  EXPECT_EQ(Taebp("merge " + Quote(out.string()) + " " + Quote(out.string())), 2) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr(holder));
  EXPECT_EQ(Wait(sweep), 0) << ReadFile(dir_ / "sweep.log");
  EXPECT_EQ(Journal(out).size(), 4u);

  // Shards, and a merge that blocks on shard 1's journal (a FIFO).
  const fs::path s0 = dir_ / "s0", s1 = dir_ / "s1", merged = dir_ / "merged";
  ASSERT_EQ(Sweep(cfg, s0, "--shard 0/2 --set scenario.duration=600"), 0) << last_log_;
  ASSERT_EQ(Sweep(cfg, s1, "--shard 1/2 --set scenario.duration=600"), 0) << last_log_;
  const std::string journal1 = ReadFile(s1 / "journal.jsonl");
  fs::remove(s1 / "journal.jsonl");
  ASSERT_EQ(::mkfifo((s1 / "journal.jsonl").c_str(), 0644), 0);
  const pid_t merge = Start({"merge", merged.string(), s0.string(), s1.string()},
                            dir_ / "merge.log");
  ASSERT_TRUE(WaitFor([&] { return !ReadFile(merged / ".taebp.lock").empty(); })) << "no lock";
  EXPECT_EQ(Sweep(cfg, merged, "--set scenario.duration=600"), 2) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("pid " + std::to_string(merge) + " on host "));
  EXPECT_THAT(last_log_, HasSubstr(" merge " + merged.string()));
  EXPECT_EQ(Taebp("merge " + Quote(merged.string()) + " " + Quote(s0.string())), 2) << last_log_;
  // A shard's own sweep cannot start while the merge reads it.
  EXPECT_EQ(Sweep(cfg, s0, "--shard 0/2 --set scenario.duration=600"), 2) << last_log_;
  {
    std::ofstream fifo(s1 / "journal.jsonl", std::ios::binary);  // unblocks the merge
    fifo << journal1;
  }
  EXPECT_EQ(Wait(merge), 0) << ReadFile(dir_ / "merge.log");
  ExpectSameTables(out, merged);
}

// ------------------------------------------------------------------ workers and task folders

// A worker killed mid-task: its task is recorded as failed with the signal,
// the sweep exits 1, and running it again completes it with the same tables
// as an undisturbed sweep.
TEST_F(SweepCli, KilledWorkerIsRecordedAndTheRerunCompletes) {
  const fs::path cfg = Config("    model.trust: [0.5]\n", 2);
  const fs::path ref = dir_ / "ref", out = dir_ / "out";
  ASSERT_EQ(Sweep(cfg, ref, "--set scenario.duration=900"), 0) << last_log_;
  const pid_t sweep = Start({"sweep", cfg.string(), "--out", out.string(), "--jobs", "1",
                             "--quiet", "--set", "scenario.duration=900"},
                            dir_ / "sweep.log");
  pid_t worker = -1;
  ASSERT_TRUE(WaitFor([&] { return (worker = FirstChild(sweep)) > 0; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // into its simulation
  ASSERT_EQ(::kill(worker, SIGKILL), 0);
  EXPECT_EQ(Wait(sweep), 1) << ReadFile(dir_ / "sweep.log");
  const auto journal = Journal(out);
  ASSERT_FALSE(journal.empty());
  EXPECT_EQ(journal.front()["status"], "failed");
  EXPECT_THAT(journal.front()["error"].get<std::string>(), HasSubstr("killed by signal 9"));
  ASSERT_EQ(Sweep(cfg, out, "--set scenario.duration=900"), 0) << last_log_;
  ExpectSameTables(ref, out);
}

// A task that stalls under scenario.stall_action: error (`run` exits 4,
// "stalled") is a failed task with the stall's message, not a config error:
// the sweep runs the other tasks (the same gridlock recorded is ok), exits 1,
// and the failed task's folder keeps what ran (summary.json says it stopped).
TEST_F(SweepCli, StalledTaskFailsWithItsMessageAndTheOthersRun) {
  std::ofstream(dir_ / "blocked.rou.xml") << taebp::test::BlockedGridRoutes();
  const fs::path cfg = dir_ / "stall.yaml";
  std::ofstream(cfg) << taebp::test::BlockedGridConfig("blocked.rou.xml")
                     << "policies: [no_ebp]\n"
                        "sweep:\n  replicates: 1\n  grid:\n"
                        "    scenario.stall_action: [record, error]\n";
  const fs::path out = dir_ / "out";
  EXPECT_EQ(Sweep(cfg, out, "--set scenario.duration=500"), 1) << last_log_;
  EXPECT_THAT(last_log_, Not(HasSubstr("config error"))) << last_log_;
  const auto journal = Journal(out);
  ASSERT_EQ(journal.size(), 2u) << last_log_;
  for (const auto& e : journal) {
    if (e["point"] == 0) {
      EXPECT_EQ(e["status"], "ok") << e.dump();
      continue;
    }
    EXPECT_EQ(e["status"], "failed") << e.dump();
    EXPECT_THAT(e["error"].get<std::string>(), HasSubstr("stalled: no_ebp: junction 'B0'"))
        << e.dump();
    const std::string summary = ReadFile(out / "tasks" / "1-0" / "summary.json");
    EXPECT_THAT(summary, HasSubstr("\"stopped\": \"stall\"")) << summary;
  }
}

// A finished task whose folder is lost: `merge` reports it by name and exits
// 1 (it used to report every task ok); the shard's sweep run again redoes
// that task, and the merge then succeeds. Corrupt journal lines are named
// (file:line) instead of being dropped silently.
TEST_F(SweepCli, MergeReportsLostTaskFoldersAndCorruptJournalLines) {
  const fs::path cfg = Config("    model.trust: [0.5]\n", 2);
  const fs::path ref = dir_ / "ref", s0 = dir_ / "s0", s1 = dir_ / "s1";
  ASSERT_EQ(Sweep(cfg, ref), 0) << last_log_;
  ASSERT_EQ(Sweep(cfg, s0, "--shard 0/2"), 0) << last_log_;
  ASSERT_EQ(Sweep(cfg, s1, "--shard 1/2"), 0) << last_log_;
  fs::remove_all(s1 / "tasks/0-1");
  {
    std::ofstream j(s1 / "journal.jsonl", std::ios::app | std::ios::binary);
    j << "this line is not JSON\n";
    j << "{\"hash\":\"" << Journal(s0).front()["hash"].get<std::string>()
      << "\",\"point\":0,\"replicate\":1,\"status\":7}\n";
  }
  const std::string merge = "merge " + Quote((dir_ / "m").string()) + " " + Quote(s0.string()) +
                            " " + Quote(s1.string());
  EXPECT_EQ(Taebp(merge), 1) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr((s1 / "tasks/0-1").string() + "/summary.json"));
  EXPECT_THAT(last_log_, HasSubstr("1 task folder(s) missing"));
  EXPECT_THAT(last_log_, HasSubstr((s1 / "journal.jsonl").string() + ":2: not valid JSON"));
  EXPECT_THAT(last_log_, HasSubstr((s1 / "journal.jsonl").string() + ":3: \"status\""));
  ExpectSameTables(ref, dir_ / "m");  // the tables come from the journals

  EXPECT_EQ(Taebp("sweep " + Quote(cfg.string()) + " --out " + Quote(s1.string()) +
                  " --shard 1/2"),
            0)
      << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("1 finished task(s) lost their outputs"));
  EXPECT_TRUE(fs::exists(s1 / "tasks/0-1/summary.json"));
  EXPECT_EQ(Taebp(merge), 0) << last_log_;
  ExpectSameTables(ref, dir_ / "m");
  EXPECT_TRUE(fs::exists(dir_ / "m/tasks/0-1/summary.json"));
}

// A shard's sweep.json whose fields have the wrong type or range is refused
// naming the file (replicates = 2^32 + 1 used to wrap around to 1).
TEST_F(SweepCli, MergeRefusesABrokenSweepJson) {
  const fs::path cfg = Config("    model.trust: [0.5]\n", 1);
  const fs::path s0 = dir_ / "s0";
  ASSERT_EQ(Sweep(cfg, s0, "--set scenario.duration=10"), 0) << last_log_;
  const std::string header = ReadFile(s0 / "sweep.json");
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"\"replicates\": 1", "\"replicates\": 4294967297"},
           {"\"replicates\": 1", "\"replicates\": \"1\""},
           {"\"overrides\": [", "\"overrides\": [7, "},
           {"\"config_hash\": \"", "\"config_hash\": 1, \"x\": \""}}) {
    std::string broken = header;
    const auto at = broken.rfind(from);  // the top-level key: the last one
    ASSERT_NE(at, std::string::npos) << from;
    broken.replace(at, from.size(), to);
    std::ofstream(s0 / "sweep.json", std::ios::binary) << broken;
    EXPECT_EQ(Taebp("merge " + Quote((dir_ / "m").string()) + " " + Quote(s0.string())), 2)
        << to << "\n" << last_log_;
    EXPECT_THAT(last_log_, HasSubstr((s0 / "sweep.json").string() + ": unreadable")) << to;
  }
}

// ------------------------------------------------------------------ a full disk

// The output folder fills up while a sweep is extended (a 1 MiB tmpfs, root
// only): the sweep fails naming the cause, keeps every journal line and the
// tables it had, and completes once there is space again.
TEST_F(SweepCli, FullDiskDuringASweepLosesNothing) {
  const fs::path cfg = Config("    model.trust: [0.5]\n", 1);
  const fs::path ref = dir_ / "ref", out = dir_ / "small";
  fs::create_directories(out);
  std::string why;
  auto tmpfs = taebp::test::Tmpfs::Mount(out, 1 << 20, /*read_only=*/false, &why);
  if (!tmpfs) GTEST_SKIP() << "cannot mount a small tmpfs: " << why;
  ASSERT_EQ(Sweep(cfg, ref, "--set sweep.replicates=3"), 0) << last_log_;
  ASSERT_EQ(Sweep(cfg, out), 0) << last_log_;
  const std::string journal = ReadFile(out / "journal.jsonl");
  const std::string results = ReadFile(out / "results.csv");
  taebp::test::FillDisk(out / "filler");

  EXPECT_NE(Sweep(cfg, out, "--set sweep.replicates=3"), 0) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("No space left on device"));
  EXPECT_EQ(ReadFile(out / "journal.jsonl").substr(0, journal.size()), journal);
  EXPECT_EQ(ReadFile(out / "results.csv"), results);
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_THAT(e.path().filename().string(), Not(HasSubstr(".tmp."))) << "a temporary file left";

  fs::remove(out / "filler");
  ASSERT_EQ(Sweep(cfg, out, "--set sweep.replicates=3"), 0) << last_log_;
  ExpectSameTables(ref, out);
  EXPECT_EQ(Journal(out).size() >= 3u, true);
}

// Issue 32, item 12: extending a sweep on a full disk stops at the first
// task that cannot write, rather than running every remaining task and
// recording each as failed ("exit code 1"); no task is recorded as failed.
TEST_F(SweepCli, FullDiskStopsTheSweepInsteadOfFailingEveryRemainingTask) {
  const fs::path cfg = Config("    model.trust: [0.5]\n", 1);
  const fs::path out = dir_ / "small";
  fs::create_directories(out);
  std::string why;
  auto tmpfs = taebp::test::Tmpfs::Mount(out, 1 << 20, /*read_only=*/false, &why);
  if (!tmpfs) GTEST_SKIP() << "cannot mount a small tmpfs: " << why;
  ASSERT_EQ(Sweep(cfg, out, "--jobs 1"), 0) << last_log_;
  const std::string journal = ReadFile(out / "journal.jsonl");
  taebp::test::FillDisk(out / "filler");
  EXPECT_EQ(Sweep(cfg, out, "--jobs 1 --set sweep.replicates=8"), 1) << last_log_;
  EXPECT_THAT(last_log_, HasSubstr("stopped: No space left on device in " + out.string()));
  EXPECT_THAT(last_log_, HasSubstr("the same command resumes"));
  EXPECT_EQ(ReadFile(out / "journal.jsonl"), journal) << "tasks recorded as failed on a full disk";
}

}  // namespace
