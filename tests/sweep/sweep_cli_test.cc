// `taebp sweep` / `taebp merge` driven as a user would (build/taebp): failing
// points, resume after kill -9, shards + merge, --jobs and MPI ranks all give
// byte-identical tables.
#include "sweep_fixture.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using taebp::test::Quote;
using taebp::test::ReadFile;
using taebp::test::SweepCli;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A point whose config is valid but cannot run (too many vehicles for loops
// that may not grow: found when the scenario is built) fails in its task; the
// other points complete.
TEST_F(SweepCli, FailingPointIsRecordedOthersCompleteExitCodeNonZero) {
  const fs::path cfg = Config("    \"scenario.avs,scenario.hvs\": [[4, 4], [40, 40]]\n", 1);
  const fs::path out = dir_ / "out";
  EXPECT_EQ(Sweep(cfg, out, "--jobs 2 --set scenario.auto_length=false"), 1) << last_log_;
  const std::string csv = ReadFile(out / "results.csv");
  EXPECT_THAT(csv, HasSubstr("\n0,0,5,4,4,no_trust,ok,,"));
  EXPECT_THAT(csv, HasSubstr("\n0,0,5,4,4,ta_ebp,ok,,"));
  EXPECT_THAT(csv, HasSubstr("\n1,0,5,40,40,ta_ebp,failed,"));
  EXPECT_THAT(csv, HasSubstr("scenario.loop_length = 80 m is too short for 80 vehicles"));
  EXPECT_THAT(ReadFile(out / "aggregate.csv"), HasSubstr("\n1,40,40,no_trust,0,1,"));
  const auto journal = Journal(out);
  ASSERT_EQ(journal.size(), 2u);
  // A re-run retries only the failed task (and fails again).
  EXPECT_EQ(Sweep(cfg, out, "--set scenario.auto_length=false"), 1);
  EXPECT_EQ(Journal(out).size(), 3u);
  EXPECT_EQ(Journal(out).back()["point"], 1);
  EXPECT_TRUE(fs::exists(out / "tasks/0-0/summary.json"));
}

TEST_F(SweepCli, ResumeAfterKillNineEqualsUninterruptedRun) {
  const fs::path cfg = Config();
  const fs::path ref = dir_ / "ref", out = dir_ / "killed";
  ASSERT_EQ(Sweep(cfg, ref, "--jobs 2"), 0) << last_log_;

  // The driver in its own process group; kill -9 the group after >= 1 task.
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    const int null_fd = ::open("/dev/null", O_WRONLY);
    ::dup2(null_fd, STDOUT_FILENO);
    ::dup2(null_fd, STDERR_FILENO);
    ::execl(TAEBP_CLI, "taebp", "sweep", cfg.c_str(), "--out", out.c_str(), "--jobs", "1",
            "--quiet", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  std::size_t lines = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string j = ReadFile(out / "journal.jsonl");
    lines = static_cast<std::size_t>(std::count(j.begin(), j.end(), '\n'));
    if (lines >= 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(-pid, SIGKILL);
  int st = 0;
  ::waitpid(pid, &st, 0);
  ASSERT_GE(lines, 1u);
  const std::size_t before = Journal(out).size();
  EXPECT_LT(before, 8u) << "the sweep finished before it could be killed";
  EXPECT_FALSE(fs::exists(out / "results.csv"));
  // As if killed in the middle of a journal write.
  std::ofstream(out / "journal.jsonl", std::ios::app) << "{\"hash\":\"0123\",\"point\":3,\"repl";

  ASSERT_EQ(Sweep(cfg, out, "--jobs 2"), 0) << last_log_;
  ExpectSameTables(ref, out);
  const auto journal = Journal(out);  // every line parses: the torn tail is gone
  EXPECT_EQ(journal.size(), 8u);
  std::set<std::pair<int, int>> seen;
  for (const auto& e : journal) {
    EXPECT_EQ(e["status"], "ok");
    EXPECT_TRUE(seen.insert({e["point"].get<int>(), e["replicate"].get<int>()}).second)
        << "duplicate journal entry " << e["point"] << "-" << e["replicate"];
  }
  // Nothing left to do: a third run adds nothing.
  ASSERT_EQ(Sweep(cfg, out), 0) << last_log_;
  EXPECT_EQ(Journal(out).size(), 8u);
  ExpectSameTables(ref, out);
}

TEST_F(SweepCli, ShardsMergedAndJobsCountGiveTheSameTables) {
  const fs::path cfg = Config();
  const fs::path ref = dir_ / "ref";
  ASSERT_EQ(Sweep(cfg, ref, "--jobs 2"), 0) << last_log_;
  ASSERT_EQ(Sweep(cfg, dir_ / "one", "--jobs 1"), 0) << last_log_;
  ExpectSameTables(ref, dir_ / "one");

  ASSERT_EQ(Sweep(cfg, dir_ / "s0", "--shard 0/2"), 0) << last_log_;
  ASSERT_EQ(Sweep(cfg, dir_ / "s1", "--shard 1/2"), 0) << last_log_;
  EXPECT_EQ(Journal(dir_ / "s0").size(), 4u);
  for (const auto& e : Journal(dir_ / "s1"))
    EXPECT_EQ((e["point"].get<int>() * 2 + e["replicate"].get<int>()) % 2, 1);
  ASSERT_EQ(Taebp("merge " + Quote((dir_ / "merged").string()) + " " +
                  Quote((dir_ / "s0").string()) + " " + Quote((dir_ / "s1").string())),
            0)
      << last_log_;
  ExpectSameTables(ref, dir_ / "merged");
  EXPECT_TRUE(fs::exists(dir_ / "merged/tasks/3-1/summary.json"));

  // A merge with a shard missing says so and exits non-zero.
  EXPECT_EQ(Taebp("merge " + Quote((dir_ / "half").string()) + " " + Quote((dir_ / "s0").string())),
            1);
  EXPECT_THAT(last_log_, HasSubstr("4 missing"));
}

TEST_F(SweepCli, RefusesToResumeIntoAnotherSweepsDirectory) {
  const fs::path cfg = Config("    model.trust: [0.5]\n", 1);
  const fs::path out = dir_ / "out";
  ASSERT_EQ(Sweep(cfg, out), 0) << last_log_;
  EXPECT_EQ(Sweep(cfg, out, "--set scenario.duration=60"), 2);
  EXPECT_THAT(last_log_, HasSubstr("holds a different sweep"));
  // More replicates of the same sweep extend it.
  ASSERT_EQ(Sweep(cfg, out, "--set sweep.replicates=2"), 0) << last_log_;
  EXPECT_EQ(Journal(out).size(), 2u);
}

TEST_F(SweepCli, MpiRanksGiveTheSameTables) {
  ASSERT_EQ(Taebp("sweep --help"), 0);
  if (last_log_.find("--mpi") == std::string::npos)
    GTEST_FAIL() << "taebp was built without MPI (packages openmpi-bin libopenmpi-dev; tools/setup.sh installs them)";
  const fs::path cfg = Config();
  const fs::path ref = dir_ / "ref", out = dir_ / "mpi";
  ASSERT_EQ(Sweep(cfg, ref, "--jobs 2"), 0) << last_log_;
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  ASSERT_EQ(Shell("mpirun --allow-run-as-root --oversubscribe -np 2 " + Quote(TAEBP_CLI) +
                  " sweep " + Quote(cfg.string()) + " --out " + Quote(out.string()) + " --quiet"),
            0)
      << last_log_;
  ExpectSameTables(ref, out);
  std::set<int> ranks;
  for (const auto& e : Journal(out)) ranks.insert(e["rank"].get<int>());
  EXPECT_EQ(ranks, (std::set<int>{0, 1}));
}

// A network study (a generated grid with fringe demand, SUMO's own logic and
// a controller policy) gives the same tables and the same pooled
// encounters.csv with one and two worker processes.
TEST_F(SweepCli, NetworkStudyIsTheSameAtAnyJobsCount) {
  const fs::path cfg = dir_ / "grid.yaml";
  std::ofstream(cfg) << "scenario:\n"
                        "  kind: network\n"
                        "  grid: {columns: 3, rows: 3, length: 100, attach_length: 50}\n"
                        "  demand: {flow: 300}\n"
                        "  av_share: 0.5\n"
                        "  cruise_speed: 10\n"
                        "  duration: 240\n"
                        "  stall_action: record\n"
                        "model: {trust: 0.6}\n"
                        "policies: [sumo_native, ta_ebp]\n"
                        "sweep:\n  replicates: 2\n  grid:\n    scenario.demand.flow: [200, 500]\n";
  ASSERT_EQ(Sweep(cfg, dir_ / "two", "--jobs 2"), 0) << last_log_;
  ASSERT_EQ(Sweep(cfg, dir_ / "one", "--jobs 1"), 0) << last_log_;
  ExpectSameTables(dir_ / "two", dir_ / "one");
  EXPECT_EQ(ReadFile(dir_ / "two" / "encounters.csv"), ReadFile(dir_ / "one" / "encounters.csv"));
  EXPECT_GT(Journal(dir_ / "one").size(), 3u);
  EXPECT_NE(ReadFile(dir_ / "one" / "encounters.csv").find("\n0,"), std::string::npos)
      << "no encounter in the study";
}

}  // namespace
