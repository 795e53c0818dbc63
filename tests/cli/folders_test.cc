// Results never lost, round two (issue 32), tried through the built program
// as a user would, each with its reproduction's smallest form:
// - a sweep or merge into a run's folder is refused, the run untouched (1);
// - a lock file that is a symbolic link is refused, its target untouched (2);
// - a folder or file named like a run's that no run of ours wrote is refused
//   and kept, also a user's file in a policy's folder a run wrote (3); a
//   rerun says in one line what it replaced (issue 26);
// - YAML 1.1 octal and a second YAML document are refused (5, 6);
// - a config asking for more vehicles than a run can handle is refused (7);
// - SIGTERM and SIGHUP on a sweep: 143 and 129, tables written, the same
//   command resumes it (10);
// - a shard folder given twice to merge says so (11);
// - a killed table write's temporary is removed by the next sweep there (13);
// - a run into a sweep's task folder, an out-of-range or huge value, a
//   too-long folder name: clear, short errors (14).
// taebp-tests: sanitize (also run under the sanitizers; tests/CMakeLists.txt)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::Process;
using taebp::test::ReadText;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
constexpr const char* kLock = ".taebp.lock";

CliResult RunCli(const std::vector<std::string>& args) {
  return taebp::test::RunProgram(kCli, args);
}

// A short figure-8 run (about a second).
std::vector<std::string> RunArgs(const std::string& config, const fs::path& out) {
  return {"run", config, "--out", out.string(), "--quiet"};
}

constexpr const char* kBase =
    "scenario: {avs: 2, hvs: 2, stop_distance: 3.0, duration: 30, seed: 5}\n"
    "policies: [no_trust, ta_ebp]\n";
constexpr const char* kSweep =
    "scenario: {avs: 2, hvs: 2, stop_distance: 3.0, duration: 30, seed: 5}\n"
    "policies: [ta_ebp]\n"
    "sweep:\n  replicates: 1\n  grid:\n    model.trust: [0.3, 0.9]\n";

// The folder's files (name -> content), recursively, the lock file left out.
std::map<std::string, std::string> Tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(e.path(), dir).string();
    if (name == kLock || e.is_directory()) continue;
    files[name] = ReadText(e.path());
  }
  return files;
}

// ------------------------------------------------------------------ item 1

TEST(Folders, ASweepOrMergeIntoARunsFolderIsRefusedAndTheRunUntouched) {
  TempDir dir;
  const std::string base = dir.Write("base.yaml", kBase);
  const std::string sweep = dir.Write("sweep.yaml", kSweep);
  const fs::path run_dir = dir.path() / "R";
  ASSERT_EQ(RunCli(RunArgs(base, run_dir)).exit_code, 0);
  const auto before = Tree(run_dir);
  const CliResult s = RunCli({"sweep", sweep, "--out", run_dir.string(), "--jobs", "1", "--quiet"});
  EXPECT_EQ(s.exit_code, 2) << s.Describe();
  EXPECT_THAT(s.err, HasSubstr("holds a run's results")) << s.Describe();
  EXPECT_EQ(Tree(run_dir), before) << "the run's folder changed";

  const fs::path shard = dir.path() / "S";
  ASSERT_EQ(RunCli({"sweep", sweep, "--out", shard.string(), "--jobs", "1", "--quiet"}).exit_code, 0);
  const CliResult m = RunCli({"merge", run_dir.string(), shard.string(), "--quiet"});
  EXPECT_EQ(m.exit_code, 2) << m.Describe();
  EXPECT_THAT(m.err, HasSubstr("holds a run's results")) << m.Describe();
  EXPECT_EQ(Tree(run_dir), before) << "the run's folder changed";
}

// ------------------------------------------------------------------ item 2

TEST(Folders, ALockFileThatIsASymbolicLinkIsRefusedAndItsTargetUntouched) {
  TempDir dir;
  const std::string base = dir.Write("base.yaml", kBase);
  const std::string sweep = dir.Write("sweep.yaml", kSweep);
  const std::string victim = dir.Write("victim.txt", "precious\n");
  for (const char* command : {"run", "sweep", "merge"}) {
    SCOPED_TRACE(command);
    const fs::path folder = dir.path() / (std::string("L-") + command);
    fs::create_directories(folder);
    fs::create_symlink(victim, folder / kLock);
    CliResult r;
    if (std::string(command) == "run") r = RunCli(RunArgs(base, folder));
    else if (std::string(command) == "sweep")
      r = RunCli({"sweep", sweep, "--out", folder.string(), "--jobs", "1", "--quiet"});
    else r = RunCli({"merge", folder.string(), (dir.path() / "L-sweep").string(), "--quiet"});
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("is not a regular file")) << r.Describe();
    EXPECT_EQ(ReadText(victim), "precious\n") << "the link's target was written";
    EXPECT_TRUE(fs::is_symlink(folder / kLock));
  }
}

// ------------------------------------------------------------------ item 3

TEST(Folders, WhatNoRunOfOursWroteIsRefusedAndKeptWhatARunWroteIsReplacedInOneLine) {
  TempDir dir;
  const std::string base = dir.Write("base.yaml", kBase);
  const fs::path run_dir = dir.path() / "R";
  ASSERT_EQ(RunCli(RunArgs(base, run_dir)).exit_code, 0);
  // A rerun says what it replaced (issue 26), in one line.
  const CliResult again = RunCli({"run", base, "--out", run_dir.string()});
  ASSERT_EQ(again.exit_code, 0) << again.Describe();
  EXPECT_THAT(again.err, HasSubstr("replaced the results of 2 policies (no_trust, ta_ebp) from "))
      << again.Describe();
  EXPECT_THAT(again.err, HasSubstr(" in " + run_dir.string() + "\n")) << again.Describe();
  const CliResult fresh = RunCli({"run", base, "--out", (dir.path() / "fresh").string()});
  EXPECT_THAT(fresh.err, Not(HasSubstr("replaced"))) << fresh.Describe();

  // A user's folder named like a policy, and user files named like a run's.
  struct Case {
    std::string path, text;
  };
  for (const Case& c : {Case{"full_reveal/mydata.txt", "x\n"}, Case{"ta_ebp/notes.txt", "n\n"},
                        Case{"network.net.xml", "<net/>\n"},
                        Case{"tripinfo-ta_ebp.xml", "<mine/>\n"},
                        Case{"summary-no_trust.xml", "<mine/>\n"}}) {
    SCOPED_TRACE(c.path);
    const fs::path file = run_dir / c.path;
    fs::create_directories(file.parent_path());
    dir.Write(fs::relative(file, dir.path()).string(), c.text);
    const auto before = Tree(run_dir);
    const CliResult r = RunCli(RunArgs(base, run_dir));
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr(fs::path(c.path).begin()->string())) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("no taebp run wrote")) << r.Describe();
    EXPECT_EQ(Tree(run_dir), before) << "the folder changed";
    EXPECT_EQ(ReadText(file), c.text);
    fs::remove(file);
    if (file.parent_path() != run_dir && fs::is_empty(file.parent_path()))
      fs::remove(file.parent_path());
  }
  // With the user's files gone, the rerun works again.
  EXPECT_EQ(RunCli(RunArgs(base, run_dir)).exit_code, 0);

  // The issue's reproduction: a policy's folder that a run did write (SUMO's
  // queue output in R/ta_ebp/), a user's notes.txt added to it, the same run
  // again: refused, naming the file, and the folder as it was.
  const std::vector<std::string> with_outputs = {
      "run", base, "--set", "scenario.outputs={queue: true}", "--out", run_dir.string(), "--quiet"};
  const CliResult wrote = RunCli(with_outputs);
  ASSERT_EQ(wrote.exit_code, 0) << wrote.Describe();
  ASSERT_TRUE(fs::is_regular_file(run_dir / "ta_ebp" / "queue.xml"))
      << "the run wrote no ta_ebp folder: the case would prove nothing";
  const fs::path notes = run_dir / "ta_ebp" / "notes.txt";
  dir.Write(fs::relative(notes, dir.path()).string(), "n\n");
  const auto before = Tree(run_dir);
  const CliResult rerun = RunCli(with_outputs);
  EXPECT_EQ(rerun.exit_code, 2) << rerun.Describe();
  EXPECT_THAT(rerun.err, HasSubstr("ta_ebp/notes.txt")) << rerun.Describe();
  EXPECT_THAT(rerun.err, HasSubstr("no taebp run wrote")) << rerun.Describe();
  EXPECT_EQ(Tree(run_dir), before) << "the folder changed";
  EXPECT_EQ(ReadText(notes), "n\n");
}

// ------------------------------------------------------------------ items 5, 6, 7, 14

TEST(Folders, OctalMultiDocumentHugeAndOutOfRangeValuesAreRefusedNamingKeyValueAndFile) {
  TempDir dir;
  const std::string base = dir.Write("base.yaml", kBase);
  const std::string sweep = dir.Write("sweep.yaml", kSweep);
  const fs::path out = dir.path() / "out";
  {  // 5: YAML 1.1 octal in a grid: 010 would run 8 AVs while the tables say 010
    const CliResult r =
        RunCli({"sweep", sweep, "--list", "--set", "sweep.grid={scenario.avs: [010, 012]}"});
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("scenario.avs")) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("'010'")) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("leading zero")) << r.Describe();
    const CliResult hex = RunCli({"run", base, "--set", "scenario.avs=0x2", "--out", out.string()});
    EXPECT_EQ(hex.exit_code, 2) << hex.Describe();
    EXPECT_THAT(hex.err, HasSubstr("'0x2'")) << hex.Describe();
  }
  {  // 6: a second YAML document, in a file and in a --set value
    const std::string two = dir.Write(
        "two.yaml", "---\nscenario: {duration: 60}\n---\nscenario: {duration: 120}\n");
    const CliResult r = RunCli({"run", two, "--out", out.string()});
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr(two)) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("2 YAML documents")) << r.Describe();
    const CliResult set = RunCli({"run", base, "--set", "model.trust=0.3\n---\n0.9", "--out", out.string()});
    EXPECT_EQ(set.exit_code, 2) << set.Describe();
    EXPECT_THAT(set.err, HasSubstr("--set model.trust=0.3")) << set.Describe();
    EXPECT_THAT(set.err, HasSubstr("2 YAML documents")) << set.Describe();
  }
  {  // 7: more vehicles than SUMO's (uninterruptible) first step can take
    for (const char* v : {"scenario.avs=1000000000", "scenario.hvs=1000000"}) {
      const auto start = std::chrono::steady_clock::now();
      const CliResult r = RunCli({"run", base, "--set", v, "--out", out.string()});
      EXPECT_EQ(r.exit_code, 2) << r.Describe();
      EXPECT_THAT(r.err, HasSubstr("is above 10000")) << r.Describe();
      EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
    }
  }
  {  // 14: out of an int's range; a huge value; a too-long folder name
    const CliResult r = RunCli({"sweep", sweep, "--list", "--set", "sweep.replicates=100000000000"});
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("sweep.replicates")) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("out of range")) << r.Describe();
    const std::string huge = dir.Write(
        "huge.yaml", "scenario: {avs: '" + std::string(10 * 1000 * 1000, 'x') + "'}\n");
    const CliResult h = RunCli({"run", huge, "--out", out.string()});
    EXPECT_EQ(h.exit_code, 2);
    EXPECT_THAT(h.err, HasSubstr("scenario.avs"));
    EXPECT_THAT(h.err, HasSubstr("(10000000 characters)"));
    EXPECT_LT(h.err.size(), 2000u) << "an error message of " << h.err.size() << " bytes";
    const std::string name(256, 'n');
    const CliResult l = RunCli({"run", base, "--out", (dir.path() / name).string()});
    EXPECT_EQ(l.exit_code, 2) << l.Describe();
    EXPECT_THAT(l.err, HasSubstr("256 characters long")) << l.Describe();
  }
}

// ------------------------------------------------------------------ item 14

TEST(Folders, ARunIntoASweepsTaskFolderIsRefusedAndTheTaskUntouched) {
  TempDir dir;
  const std::string base = dir.Write("base.yaml", kBase);
  const std::string sweep = dir.Write("sweep.yaml", kSweep);
  const fs::path out = dir.path() / "S";
  ASSERT_EQ(RunCli({"sweep", sweep, "--out", out.string(), "--jobs", "1", "--quiet"}).exit_code, 0);
  const fs::path task = out / "tasks" / "0-0";
  const auto before = Tree(task);
  const CliResult r = RunCli(RunArgs(base, task));
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("is a task folder of the sweep in " + out.string())) << r.Describe();
  EXPECT_EQ(Tree(task), before);
}

// ------------------------------------------------------------------ items 11, 13

TEST(Folders, MergeNamesAShardGivenTwiceAndASweepRemovesAKilledWritesTemporaries) {
  TempDir dir;
  const std::string sweep = dir.Write("sweep.yaml", kSweep);
  const fs::path s0 = dir.path() / "S0", s1 = dir.path() / "S1";
  ASSERT_EQ(RunCli({"sweep", sweep, "--out", s0.string(), "--shard", "0/2", "--quiet"}).exit_code, 0);
  ASSERT_EQ(RunCli({"sweep", sweep, "--out", s1.string(), "--shard", "1/2", "--quiet"}).exit_code, 0);
  fs::create_directory_symlink(s1, dir.path() / "S1-link");
  for (const std::string& again : {s1.string(), (dir.path() / "S1-link").string()}) {
    const CliResult r =
        RunCli({"merge", (dir.path() / "OUT").string(), s0.string(), s1.string(), again});
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr(again + " is given twice")) << r.Describe();
    EXPECT_THAT(r.err, Not(HasSubstr("in use"))) << r.Describe();
  }
  // 13: what kill -9 during a table write leaves; a user's look-alike stays.
  dir.Write("S0/encounters.csv.tmp.99999", "half");
  dir.Write("S0/results.csv.tmp.12", "half");
  dir.Write("S0/mine.csv.tmp.5", "mine");
  const CliResult r = RunCli({"sweep", sweep, "--out", s0.string(), "--shard", "0/2", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_FALSE(fs::exists(s0 / "encounters.csv.tmp.99999"));
  EXPECT_FALSE(fs::exists(s0 / "results.csv.tmp.12"));
  EXPECT_EQ(ReadText(s0 / "mine.csv.tmp.5"), "mine");
}

// ------------------------------------------------------------------ item 10

// Each task's status in a sweep's results.csv, in its rows' order.
std::vector<std::string> TaskStatuses(const fs::path& results_csv) {
  std::istringstream in(ReadText(results_csv));
  std::string line;
  std::vector<std::string> statuses;
  std::size_t column = std::string::npos;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (column == std::string::npos) {
      column = static_cast<std::size_t>(std::find(cells.begin(), cells.end(), "status") -
                                        cells.begin());
      continue;
    }
    statuses.push_back(column < cells.size() ? cells[column] : "?");
  }
  return statuses;
}

TEST(Folders, SigtermAndSighupOnASweepExit143And129WithItsTablesAndItResumes) {
  for (const int sig : {SIGTERM, SIGHUP}) {
    SCOPED_TRACE(sig == SIGTERM ? "SIGTERM" : "SIGHUP");
    TempDir dir;
    // 12000 simulated seconds: about 1.5 s of work per task here, so the
    // first task cannot finish in the moment between its start and the signal.
    const std::string sweep = dir.Write(
        "sweep.yaml",
        "scenario: {avs: 2, hvs: 2, stop_distance: 3.0, duration: 12000, seed: 5}\n"
        "policies: [ta_ebp]\n"
        "sweep:\n  replicates: 1\n  grid:\n    model.trust: [0.3, 0.9]\n");
    const fs::path out = dir.path() / "S";
    const std::vector<std::string> command = {"sweep", sweep, "--out", out.string(), "--jobs", "1"};
    Process p(kCli, command);
    // The signal as soon as the first task has started (its worker opened
    // its stderr.log).
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(out / "tasks" / "0-0" / "stderr.log") &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(fs::exists(out / "tasks" / "0-0" / "stderr.log")) << "the first task never started";
    ::kill(p.pid(), sig);
    const CliResult r = p.Wait();
    EXPECT_EQ(r.exit_code, 128 + sig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("interrupted; the same command resumes the sweep")) << r.Describe();
    ASSERT_TRUE(fs::exists(out / "results.csv")) << r.Describe();
    const std::vector<std::string> interrupted = TaskStatuses(out / "results.csv");
    ASSERT_LT(std::count(interrupted.begin(), interrupted.end(), "ok"), 2)
        << "both tasks finished before the signal: the resume would prove nothing\n"
        << r.Describe();
    // The same command resumes it: every task ok.
    const CliResult resumed = RunCli(command);
    EXPECT_EQ(resumed.exit_code, 0) << resumed.Describe();
    EXPECT_EQ(TaskStatuses(out / "results.csv"), (std::vector<std::string>{"ok", "ok"}))
        << ReadText(out / "results.csv");
  }
}

}  // namespace

// ------------------------------------------------------------------ issue 45, items 2-4

// A seed is what SUMO runs: a leading zero (YAML 1.1 octal: the tables would
// say 010, sweep.json 8) and a seed SUMO would take modulo 2^31 - 1 (1 and
// 2147483648 run alike) are refused in a file, by --set and in a sweep's
// grid, naming the key and the value; SUMO's outputs cannot enter a sweep
// through its grid any more than through --set.
TEST(Folders, SeedsSumoCannotTakeAndOutputsInAGridAreRefused) {
  TempDir dir;
  const std::string sweep = dir.Write("sweep.yaml", kSweep);
  const fs::path out = dir.path() / "out";
  const std::string file = dir.Write(
      "seed.yaml", "scenario: {avs: 2, hvs: 2, duration: 30, seed: 010}\npolicies: [ta_ebp]\n");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", file, "--out", out.string()},
        std::vector<std::string>{"sweep", sweep, "--list", "--set",
                                 "sweep.grid={scenario.seed: [010, 12]}"}}) {
    const CliResult r = RunCli(args);
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("scenario.seed")) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("010")) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("leading zero")) << r.Describe();
  }
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"sweep", sweep, "--list", "--set", "scenario.seed=2147483647"},
        std::vector<std::string>{"sweep", sweep, "--list", "--set",
                                 "sweep.grid={scenario.seed: [1, 2147483648]}"},
        std::vector<std::string>{"sweep", sweep, "--list", "--set", "scenario.seed=2147483646",
                                 "--set", "sweep.replicates=2"},
        std::vector<std::string>{"sweep", sweep, "--list", "--set", "scenario.seed=18446744073709551615"}}) {
    const CliResult r = RunCli(args);
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("scenario.seed")) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("2147483646")) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("modulo 2147483647")) << r.Describe();
  }
  {  // the largest seed SUMO takes is a seed
    const CliResult r = RunCli({"sweep", sweep, "--list", "--set", "scenario.seed=2147483646"});
    EXPECT_EQ(r.exit_code, 0) << r.Describe();
  }
  {  // 4: scenario.outputs swept into the grid
    const CliResult r = RunCli({"sweep", sweep, "--list", "--set",
                                "sweep.grid={scenario.outputs.fcd: [false, true]}"});
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("scenario.outputs")) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("taebp run")) << r.Describe();
    EXPECT_FALSE(fs::exists(out));
  }
}

// ------------------------------------------------------------------ issue 45, item 8

// An alias bomb (aliases of aliases: 10^8 values in nine lines) in a sweep's
// grid is a config error naming the file, before anything walks it (it hung
// `sweep --list` at 1.3 GB).
TEST(Folders, AnAliasBombIsAConfigErrorNotAHang) {
  TempDir dir;
  std::string bomb =
      "scenario: {avs: 2, hvs: 2, duration: 30}\npolicies: [ta_ebp]\n"
      "sweep:\n  replicates: 1\n  grid:\n    model.trust: [0.3, &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]";
  for (char name = 'b'; name <= 'h'; ++name) {
    const std::string prev(1, static_cast<char>(name - 1));
    bomb += std::string(", &") + name + " [";
    for (int k = 0; k < 10; ++k) bomb += (k ? ", *" : "*") + prev;
    bomb += "]";
  }
  bomb += "]\n";
  const std::string sweep = dir.Write("bomb.yaml", bomb);
  const CliResult r = RunCli({"sweep", sweep, "--list"});
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr(sweep)) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("aliases")) << r.Describe();
  // The same through --set.
  const std::string base = dir.Write("base.yaml", kSweep);
  const CliResult set = RunCli(
      {"sweep", base, "--list", "--set",
       "sweep.grid={model.trust: [&a [1,1,1,1,1,1,1,1,1,1], &b [*a,*a,*a,*a,*a,*a,*a,*a,*a,*a], "
       "&c [*b,*b,*b,*b,*b,*b,*b,*b,*b,*b], &d [*c,*c,*c,*c,*c,*c,*c,*c,*c,*c], "
       "&e [*d,*d,*d,*d,*d,*d,*d,*d,*d,*d], &f [*e,*e,*e,*e,*e,*e,*e,*e,*e,*e], "
       "&g [*f,*f,*f,*f,*f,*f,*f,*f,*f,*f]]}"});
  EXPECT_EQ(set.exit_code, 2) << set.Describe();
  EXPECT_THAT(set.err, HasSubstr("--set sweep.grid")) << set.Describe();
  EXPECT_THAT(set.err, HasSubstr("aliases")) << set.Describe();
}
