// Bad input and faults at the command line, run as a user would: exit codes
// as documented (2 bad configuration or argument, 3 SUMO, 1 anything else),
// messages that name the path or key, --out problems found before the first
// simulation step, and results already written never lost or half-written
// (a corrupt network, a read-only or full output folder).
// taebp-tests: sanitize (also run under the sanitizers; tests/CMakeLists.txt)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "fault_support.h"
#include "test_support.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::ReadText;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
const std::string kSource = TAEBP_SOURCE_DIR;
const std::string kPaper = kSource + "/configs/paper.yaml";
const std::string kSweepTrust = kSource + "/configs/sweep_trust.yaml";

constexpr int kExitConfig = 2;  // README: 2 bad configuration or argument
constexpr int kExitSumo = 3;    // README: 3 SUMO failed

CliResult RunCli(const std::vector<std::string>& args) {
  return taebp::test::RunProgram(kCli, args);
}

// Every file under `dir` (relative path -> content), but the folder's lock
// file (it names its last holder, not a result).
std::map<std::string, std::string> Snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != ".taebp.lock")
      files[fs::relative(e.path(), dir).string()] = ReadText(e.path());
  return files;
}

// A progress line `run` prints after each simulated policy: its absence shows
// that an error came before the first simulation.
constexpr const char* kSimulated = "simulated s in";

// ------------------------------------------------------------------ arguments

TEST(CliExitCodes, ArgumentErrorsExitTwoHelpAndVersionZero) {
  struct Case {
    std::vector<std::string> args;
    std::string expected;  // in stderr
  };
  const std::vector<Case> cases = {
      {{}, "subcommand"},
      {{"run"}, "CONFIG"},
      {{"solve"}, "PROBLEM"},
      {{"theory", "--trust", "abc"}, "--trust"},
      {{"run", kPaper, "--no-such-flag"}, "--no-such-flag"},
      {{"sweep", kSweepTrust, "--jobs", "many"}, "--jobs"},
      {{"sweep", kSweepTrust, "--jobs", "0", "--list"}, "--jobs"},  // as -1: no worker is none
      {{"sweep", kSweepTrust, "--jobs", "-1", "--list"}, "--jobs"},
      {{"merge"}, "OUT"},
      {{"snapshot", kPaper}, "--out"},
  };
  for (const Case& c : cases) {
    std::string joined;
    for (const auto& a : c.args) joined += a + " ";
    SCOPED_TRACE("taebp " + joined);
    const CliResult r = RunCli(c.args);
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr(c.expected)) << r.Describe();
  }
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--help"}, {"run", "--help"}, {"sweep", "--help"},
        {"--version"}}) {
    const CliResult r = RunCli(args);
    EXPECT_EQ(r.exit_code, 0) << r.Describe();
    EXPECT_FALSE(r.out.empty());
  }
}

TEST(CliExitCodes, UnknownSubcommandIsNamed) {
  const CliResult r = RunCli({"bogus", "configs/paper.yaml"});
  EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("unknown subcommand 'bogus'"));
  EXPECT_THAT(r.err, HasSubstr("theory"));  // the list of subcommands
  EXPECT_THAT(r.err, HasSubstr("sweep"));
  // A misspelt one too.
  const CliResult s = RunCli({"rnu", kPaper});
  EXPECT_EQ(s.exit_code, kExitConfig) << s.Describe();
  EXPECT_THAT(s.err, HasSubstr("'rnu'"));
}

// ------------------------------------------------------------------ CONFIG

TEST(CliConfigFile, DirectoryEmptyOrMissingIsAnErrorNamingThePathForEveryCommand) {
  TempDir dir;
  const std::string folder = (dir.path() / "a_folder").string();
  fs::create_directories(folder);
  const std::string empty = dir.Write("empty.yaml", "");
  const std::string missing = (dir.path() / "missing.yaml").string();
  // A FIFO is refused at once (it used to block until a writer came).
  const std::string fifo = (dir.path() / "config.fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const fs::path out = dir.path() / "out";
  for (const std::string& config : {folder, empty, missing, fifo}) {
    for (const std::string cmd : {"run", "sweep", "solve"}) {
      SCOPED_TRACE(cmd + " " + config);
      std::vector<std::string> args = {cmd, config};
      if (cmd != "solve") args.insert(args.end(), {"--out", out.string()});
      const CliResult r = RunCli(args);
      EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
      EXPECT_THAT(r.err, HasSubstr(config)) << r.Describe();
      EXPECT_THAT(r.err, Not(HasSubstr(kSimulated)));
      EXPECT_FALSE(fs::exists(out));
    }
  }
}

TEST(CliConfigFile, StepLengthSumoRefusesIsAConfigError) {
  TempDir dir;
  const CliResult r = RunCli({"run", kPaper, "--set", "scenario.step_length=1e-9", "--out",
                              (dir.path() / "out").string()});
  EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("scenario.step_length = 1e-09"));
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

// ------------------------------------------------------------------ --out

// --out that is a file, lies below a file, or cannot be written: refused
// before the first simulation step (the config asks for a full simulated hour
// per policy, so a late check would be slow and print progress lines), for
// `run` and `sweep` alike; nothing is written.
TEST(CliOut, UnusableOutIsRefusedBeforeSimulating) {
  TempDir dir;
  const std::string file = dir.Write("a_file", "precious\n");
  struct Case {
    fs::path out;
    std::string expected;
  };
  std::vector<Case> cases = {
      {file, "is a file"},
      {fs::path(file) / "below", "is a file"},
      {fs::path(file) / "deeper/below", "is a file"},
  };
  // A read-only folder: a read-only tmpfs as root, else a folder without
  // write permission.
  const fs::path ro = dir.path() / "read_only";
  fs::create_directories(ro);
  std::string why;
  auto mount = taebp::test::Tmpfs::Mount(ro, 1 << 20, /*read_only=*/true, &why);
  if (mount || taebp::test::MakeReadOnly(ro, &why)) {
    cases.push_back({ro, "cannot create files in"});
    cases.push_back({ro / "new", "cannot create files in"});
  } else {
    std::printf("[ SKIPPED  ] the read-only case: %s\n", why.c_str());
  }
  for (const Case& c : cases) {
    for (const std::string cmd : {"run", "sweep"}) {
      SCOPED_TRACE(cmd + " --out " + c.out.string());
      const std::string config = cmd == "run" ? kPaper : kSweepTrust;
      const CliResult r = RunCli({cmd, config, "--out", c.out.string()});
      EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
      EXPECT_THAT(r.err, HasSubstr(c.out.string())) << r.Describe();
      EXPECT_THAT(r.err, HasSubstr(c.expected)) << r.Describe();
      EXPECT_THAT(r.err, Not(HasSubstr(kSimulated))) << r.Describe();
      EXPECT_THAT(r.err, Not(HasSubstr("tasks done"))) << r.Describe();
    }
  }
  EXPECT_EQ(ReadText(file), "precious\n");
}

// ------------------------------------------------------------------ faults

// Results already in --out; a run that fails must leave them byte-identical.
class CliFaults : public ::testing::Test {
 protected:
  // A finished run's files in `out`.
  void WriteEarlierResults(const fs::path& out) {
    const CliResult r = RunCli({"run", kPaper, "--set", "scenario.duration=30", "--set",
                                "policies=[ta_ebp]", "--out", out.string(), "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.Describe();
    earlier_ = Snapshot(out);
    ASSERT_TRUE(earlier_.count("summary.json"));
  }
  void ExpectEarlierResultsUntouched(const fs::path& out) {
    EXPECT_EQ(Snapshot(out), earlier_) << "the earlier results in " << out << " changed";
  }
  std::map<std::string, std::string> earlier_;
};

// A network that cannot be read: a file that is not XML and the shipped
// figure-8 cut in the middle of an element are refused when the scenario is
// built (exit 2, config error naming the file); well-formed XML that SUMO
// rejects (a lane speed that is not a number) fails at SUMO's start (exit 3,
// the file named). No results written, earlier results untouched.
TEST_F(CliFaults, CorruptNetworkIsASumoErrorNamingTheFile) {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  WriteEarlierResults(out);
  const std::string net = ReadText(fs::path(kCli).parent_path() / "sumo_net/figure8.net.xml");
  ASSERT_GT(net.size(), 4000u);
  std::string bad_speed = net;
  const std::size_t at = bad_speed.find("speed=\"");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = bad_speed.find('"', at + 7);
  bad_speed.replace(at, end - at + 1, "speed=\"fast\"");
  const std::vector<std::pair<std::string, int>> networks = {
      {dir.Write("garbage.net.xml", "<<< not a SUMO network\n\x01\x02\n"), kExitConfig},
      {dir.Write("truncated.net.xml", net.substr(0, net.size() / 2)), kExitConfig},
      {dir.Write("bad_speed.net.xml", bad_speed), kExitSumo},
  };
  for (const auto& [network, code] : networks) {
    SCOPED_TRACE(network);
    const CliResult r = RunCli({"run", kPaper, "--set", "scenario.duration=30", "--set",
                                "scenario.network=" + network, "--out", out.string()});
    EXPECT_EQ(r.exit_code, code) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr(network)) << r.Describe();
    if (code == kExitSumo) {
      // SUMO's own message leads ours, the command comes last (the first
      // line used to be the whole sumo command).
      EXPECT_THAT(r.err, HasSubstr("taebp: SUMO failed to start: Attribute 'speed' in "
                                   "definition of lane"))
          << r.Describe();
      EXPECT_THAT(r.err, HasSubstr("; the command was: sumo -n " + network)) << r.Describe();
    }
    ExpectEarlierResultsUntouched(out);
  }
}

// The output folder fills up while the results are written (a 64 KiB tmpfs
// as root; else a file size limit): the run fails naming the file and the
// cause, and the earlier results are neither lost nor half-written.
TEST_F(CliFaults, FullOutputFolderFailsCleanlyAndKeepsEarlierResults) {
  TempDir dir;
  const fs::path out = dir.path() / "small";
  fs::create_directories(out);
  std::string why;
  auto mount = taebp::test::Tmpfs::Mount(out, 64 << 10, /*read_only=*/false, &why);
  std::function<void()> limit;
  if (!mount) {
    // RLIMIT_FSIZE: a write past the limit fails with EFBIG (SIGXFSZ ignored).
    std::printf("[   NOTE   ] no tmpfs (%s): using a file size limit instead\n", why.c_str());
    limit = [] { taebp::test::LimitFileSize(4096); };
  }
  WriteEarlierResults(out);
  if (mount) taebp::test::FillDisk(out / "filler");
  const CliResult r = taebp::test::RunProgram(
      kCli,
      {"run", kPaper, "--set", "scenario.duration=120", "--set", "policies=[no_trust, ta_ebp]",
       "--out", out.string()},
      limit);
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr(out.string())) << r.Describe();
  EXPECT_THAT(r.err, testing::AnyOf(HasSubstr("No space left on device"),
                                    HasSubstr("File too large")))
      << r.Describe();
  if (mount) fs::remove(out / "filler");
  ExpectEarlierResultsUntouched(out);
}

}  // namespace

namespace {

// The disk fills while SUMO's own outputs are copied in (fcd.xml, the
// largest; a 256 KiB tmpfs, root only): the error says the disk is full, as
// write(2) does ("No space left on device", not the kernel copy's
// "Input/output error"), and the earlier results stay.
TEST_F(CliFaults, AFullDiskWhileCopyingSumosOutputsSaysSo) {
  TempDir dir;
  const fs::path out = dir.path() / "small";
  fs::create_directories(out);
  std::string why;
  auto mount = taebp::test::Tmpfs::Mount(out, 256 << 10, /*read_only=*/false, &why);
  if (!mount) GTEST_SKIP() << "cannot mount a small tmpfs: " << why;
  WriteEarlierResults(out);
  const CliResult r = RunCli({"run", kPaper, "--set", "scenario.duration=120", "--set",
                              "policies=[ta_ebp]", "--set", "scenario.outputs.fcd=true", "--out",
                              out.string(), "--quiet"});
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("fcd.xml")) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("No space left on device")) << r.Describe();
  EXPECT_THAT(r.err, testing::Not(HasSubstr("Input/output error"))) << r.Describe();
  ExpectEarlierResultsUntouched(out);
}

}  // namespace
