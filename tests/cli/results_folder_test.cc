// A run's results are never mixed up or lost (issue 17, items 1-3), tried
// through the built program as a user would:
// - `taebp run --out` into a sweep's folder is refused, the sweep untouched;
// - two runs on one folder at once: the second is refused, naming the first;
// - a rerun with fewer policies leaves only its own files (a user's are kept);
// - killed (SIGKILL, strace's fault injection) at every step of replacing the
//   folder's files, the folder holds the old set or the new one, never a mix,
//   and the next run there removes what the killed one left;
// - Ctrl-C or SIGTERM: exit 128 + signal, nothing written, scratch removed.
// taebp-tests: sanitize (also run under the sanitizers; tests/CMakeLists.txt)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <csignal>

namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::Process;
using taebp::test::ReadText;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
const std::string kSource = TAEBP_SOURCE_DIR;
const std::string kGrid = kSource + "/configs/grid_throughput.yaml";
constexpr const char* kLock = ".taebp.lock";  // FolderLock::kFileName

CliResult RunCli(const std::vector<std::string>& args) {
  return taebp::test::RunProgram(kCli, args);
}

// `taebp run` of the grid study's config on a 2 x 2 grid for `duration` s
// with `policies`, SUMO's own per-policy outputs kept (tripinfo-*.xml,
// summary-*.xml).
std::vector<std::string> RunArgs(const fs::path& out, const std::string& policies,
                                 int duration = 60) {
  return {"run",   kGrid,
          "--set", "scenario.grid.columns=2",
          "--set", "scenario.grid.rows=2",
          "--set", "scenario.warmup=0",
          "--set", "scenario.duration=" + std::to_string(duration),
          "--set", "policies=[" + policies + "]",
          "--set", "scenario.tripinfo_output=true",
          "--set", "scenario.summary_output=true",
          "--out", out.string(), "--quiet"};
}

// The folder's files (name -> content), not below it; the lock file left
// out (it names its last holder, not a result). timing.json holds wall
// times: its name counts, its content not.
std::map<std::string, std::string> Files(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == kLock) continue;
    files[name] = name == "timing.json" ? "" : ReadText(e.path());
  }
  return files;
}

// What runs left beside `dir` or inside it while replacing it (staging
// folders, an older writer's NAME.tmp.PID).
std::vector<std::string> Leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  const std::string sibling = "." + dir.filename().string() + ".taebp-new-";
  for (const auto& e : fs::directory_iterator(dir.parent_path()))
    if (e.path().filename().string().rfind(sibling, 0) == 0) found.push_back(e.path().string());
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (name.find(".taebp-new-") != std::string::npos || name.find(".tmp.") != std::string::npos)
        found.push_back(e.path().string());
    }
  return found;
}

std::vector<std::string> Names(const std::map<std::string, std::string>& files) {
  std::vector<std::string> names;
  for (const auto& [name, content] : files) names.push_back(name);
  return names;
}

// ------------------------------------------------------------------ item 1

TEST(RunFolder, RunIntoASweepsFolderIsRefusedAndTheSweepUntouched) {
  TempDir dir;
  const std::string config = dir.Write(
      "sweep.yaml",
      "scenario: {avs: 2, hvs: 2, stop_distance: 3.0, duration: 30, seed: 5}\n"
      "policies: [ta_ebp]\n"
      "sweep:\n  replicates: 1\n  grid:\n    model.trust: [0.3, 0.9]\n");
  const fs::path out = dir.path() / "sweep";
  const CliResult s = RunCli({"sweep", config, "--out", out.string(), "--quiet"});
  ASSERT_EQ(s.exit_code, 0) << s.Describe();
  ASSERT_TRUE(fs::exists(out / "encounters.csv"));
  const auto before = Files(out);
  const CliResult r = RunCli(RunArgs(out, "ta_ebp"));
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr(out.string())) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("holds a sweep's results")) << r.Describe();
  EXPECT_EQ(Files(out), before) << "the sweep's folder changed";
  // A task's folder inside it is refused too, as a folder holding folders
  // is: a run replaces the whole folder it is given.
  const CliResult into_parent = RunCli(RunArgs(dir.path(), "ta_ebp"));
  EXPECT_EQ(into_parent.exit_code, 2) << into_parent.Describe();
  EXPECT_THAT(into_parent.err, HasSubstr("holds a folder")) << into_parent.Describe();
}

TEST(RunFolder, TwoRunsOnOneFolderAtOnceTheSecondIsRefusedNamingTheFirst) {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  Process first(kCli, RunArgs(out, "no_ebp, no_trust, ta_ebp", 600));
  // The first holds the folder once its lock file names it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (ReadText(out / kLock).find("pid ") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_THAT(ReadText(out / kLock), HasSubstr("pid " + std::to_string(first.pid())));
  const CliResult second = RunCli(RunArgs(out, "ta_ebp"));
  EXPECT_EQ(second.exit_code, 2) << second.Describe();
  EXPECT_THAT(second.err, HasSubstr("in use by another taebp command")) << second.Describe();
  EXPECT_THAT(second.err, HasSubstr("pid " + std::to_string(first.pid()))) << second.Describe();
  EXPECT_THAT(second.err, Not(HasSubstr("simulated"))) << second.Describe();
  const CliResult done = first.Wait();
  ASSERT_EQ(done.exit_code, 0) << done.Describe();
  // The folder holds the first run's results, all three policies.
  const std::string summary = ReadText(out / "summary.json");
  for (const char* policy : {"no_ebp", "no_trust", "ta_ebp"})
    EXPECT_TRUE(fs::exists(out / ("tripinfo-" + std::string(policy) + ".xml"))) << policy;
  EXPECT_THAT(summary, HasSubstr("\"no_ebp\""));
}

// ------------------------------------------------------------------ item 3

TEST(RunFolder, ARerunWithFewerPoliciesLeavesOnlyItsOwnFiles) {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  const fs::path fresh = dir.path() / "fresh";
  ASSERT_EQ(RunCli(RunArgs(out, "no_trust, ta_ebp")).exit_code, 0);
  ASSERT_TRUE(fs::exists(out / "summary-no_trust.xml"));
  ASSERT_TRUE(fs::exists(out / "tripinfo-no_trust.xml"));
  dir.Write("out/notes.txt", "my notes\n");  // a user's own file in the folder
  const CliResult r = RunCli(RunArgs(out, "ta_ebp"));
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  ASSERT_EQ(RunCli(RunArgs(fresh, "ta_ebp")).exit_code, 0);
  auto expected = Files(fresh);
  expected["notes.txt"] = "my notes\n";
  EXPECT_EQ(Files(out), expected) << "the rerun's folder is not the fresh run's plus notes.txt";
  EXPECT_FALSE(fs::exists(out / "summary-no_trust.xml"));
  EXPECT_THAT(Leftovers(out), testing::IsEmpty());
}

// ------------------------------------------------------------------ item 2

// Kills the run with SIGKILL at the `when`-th call of `syscall` (strace's
// fault injection); the exit code of the run (137 when killed).
int RunKilledAt(const std::vector<std::string>& run_args, const std::string& syscall, int when) {
  std::vector<std::string> args = {"-f", "-qq", "-o", "/dev/null", "-e", "trace=" + syscall,
                                   "-e", "inject=" + syscall + ":signal=KILL:when=" +
                                             std::to_string(when),
                                   kCli};
  args.insert(args.end(), run_args.begin(), run_args.end());
  // LeakSanitizer cannot work under ptrace (strace): off for the traced run
  // of the sanitizer build (it would end every run that is not killed with
  // its own fatal error).
  const CliResult r = taebp::test::RunProgram("/usr/bin/strace", args, [] {
    const char* asan = std::getenv("ASAN_OPTIONS");
    const std::string options = std::string(asan && *asan ? asan : "") + ":detect_leaks=0";
    ::setenv("ASAN_OPTIONS", options.c_str(), 1);
  });
  EXPECT_THAT(r.err, Not(HasSubstr("strace:"))) << r.Describe();
  return r.exit_code;
}

TEST(RunFolder, KilledAtAnyStepOfReplacingTheFolderItHoldsTheOldSetOrTheNew) {
  ASSERT_TRUE(fs::exists("/usr/bin/strace")) << "strace is in tools/setup.sh's packages";
  TempDir dir;
  // The old set: two policies; the new: one (no no_trust files at all).
  const fs::path old_ref = dir.path() / "old_ref";
  const fs::path new_ref = dir.path() / "new_ref";
  ASSERT_EQ(RunCli(RunArgs(old_ref, "no_trust, ta_ebp")).exit_code, 0);
  ASSERT_EQ(RunCli(RunArgs(new_ref, "ta_ebp")).exit_code, 0);
  const auto old_files = Files(old_ref);
  const auto new_files = Files(new_ref);
  ASSERT_NE(Names(old_files), Names(new_files));
  const fs::path out = dir.path() / "out";
  auto reset = [&] {
    fs::remove_all(out);
    fs::create_directories(out);
    for (const auto& e : fs::directory_iterator(old_ref))
      if (e.path().filename() != kLock) fs::copy(e.path(), out / e.path().filename());
  };
  int killed_old = 0, killed_new = 0;
  // Before the one rename that swaps the folders ...
  reset();
  EXPECT_EQ(RunKilledAt(RunArgs(out, "ta_ebp"), "renameat2", 1), 128 + SIGKILL);
  EXPECT_EQ(Files(out), old_files) << "killed before the swap";
  EXPECT_THAT(Leftovers(out), Not(testing::IsEmpty())) << "the killed run's staging folder";
  // ... and at each fsync: every file of the new set, the staging folder, the
  // parent after the swap. The first call that is not made ends the loop.
  int calls = 0;
  for (int when = 1; when <= 40; ++when) {
    SCOPED_TRACE("killed at fsync #" + std::to_string(when));
    reset();
    const int code = RunKilledAt(RunArgs(out, "ta_ebp"), "fsync", when);
    const auto files = Files(out);
    if (code == 0) {
      EXPECT_EQ(files, new_files);
      break;
    }
    ++calls;
    EXPECT_EQ(code, 128 + SIGKILL);
    const bool is_old = files == old_files, is_new = files == new_files;
    EXPECT_TRUE(is_old || is_new) << "a mix: " << testing::PrintToString(Names(files));
    killed_old += is_old;
    killed_new += is_new;
    // The next run there removes what the killed one left and writes its set.
    if (when == 1 || !is_old) {
      const CliResult again = RunCli(RunArgs(out, "ta_ebp"));
      ASSERT_EQ(again.exit_code, 0) << again.Describe();
      EXPECT_EQ(Files(out), new_files);
      EXPECT_THAT(Leftovers(out), testing::IsEmpty());
    }
  }
  // One fsync per new file, the staging folder, the parent after the swap.
  EXPECT_EQ(calls, static_cast<int>(new_files.size()) + 2);
  EXPECT_GT(killed_old, 0);
  EXPECT_EQ(killed_new, 1) << "only the kill after the swap finds the new set";
}

// ------------------------------------------------------------------ signals

TEST(RunFolder, CtrlCOrSigtermStopsTheRunWritesNothingAndRemovesItsScratch) {
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(sig == SIGINT ? "SIGINT" : "SIGTERM");
    TempDir dir;
    const fs::path out = dir.path() / "out";
    const fs::path tmp = dir.path() / "tmp";
    fs::create_directories(tmp);
    ASSERT_EQ(RunCli(RunArgs(out, "ta_ebp")).exit_code, 0);
    const auto before = Files(out);
    Process run(kCli, RunArgs(out, "no_ebp, no_trust, ta_ebp", 3600),
                [&] { ::setenv("TMPDIR", tmp.c_str(), 1); });
    // Signalled once SUMO runs: its scratch folder exists.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (fs::is_empty(tmp) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_FALSE(fs::is_empty(tmp)) << "no taebp-run-* scratch folder in TMPDIR";
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    ::kill(run.pid(), sig);
    const CliResult r = run.Wait();
    EXPECT_EQ(r.exit_code, 128 + sig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("interrupted by")) << r.Describe();
    EXPECT_TRUE(fs::is_empty(tmp)) << "scratch left in TMPDIR";
    EXPECT_EQ(Files(out), before);
    EXPECT_THAT(Leftovers(out), testing::IsEmpty());
  }
}

}  // namespace
