// A gridlock under scenario.stall_action: error, run as a user would: the
// experiment stops after the stalled policy, writes everything measured up to
// the stall (summary.json saying so, encounters.csv, junctions.csv, SUMO's
// tripinfo) and exits 4 ("stalled", README), never 2 (config error). A
// gridlock under stall_action: record runs every policy to its end, each
// stalled junction flagged in the table and summary.json.
// taebp-tests: sanitize (also run under the sanitizers; tests/CMakeLists.txt)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "stall_support.h"
#include "test_support.h"

#include <filesystem>
#include <string>
#include <vector>

namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::ReadText;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
constexpr int kExitStall = 4;  // README: 4 stalled under stall_action: error

CliResult RunCli(const std::vector<std::string>& args) {
  return taebp::test::RunProgram(kCli, args);
}

std::string LastLine(const std::string& text) {
  std::string t = text;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  const std::size_t nl = t.rfind('\n');
  return nl == std::string::npos ? t : t.substr(nl + 1);
}

std::string Config(const TempDir& dir) {
  dir.Write("blocked.rou.xml", taebp::test::BlockedGridRoutes());
  return dir.Write("blocked.yaml", taebp::test::BlockedGridConfig("blocked.rou.xml"));
}

TEST(CliStall, GridlockUnderStallActionErrorWritesWhatRanAndExitsFour) {
  TempDir dir;
  const std::string config = Config(dir);
  const fs::path out = dir.path() / "out";
  const CliResult r = RunCli({"run", config, "--set", "policies=[sumo_native, no_ebp, ta_ebp]",
                              "--set", "scenario.stall_action=error", "--set",
                              "scenario.tripinfo_output=true", "--out", out.string()});
  ASSERT_EQ(r.exit_code, kExitStall) << r.Describe();
  EXPECT_THAT(r.err, Not(HasSubstr("config error"))) << r.Describe();
  // The stall's message is the last line on stderr (a sweep records it).
  EXPECT_THAT(LastLine(r.err), StartsWith("taebp: stalled: no_ebp: junction '")) << r.Describe();
  EXPECT_THAT(LastLine(r.err), HasSubstr("traffic stalled")) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("not run: ta_ebp")) << r.Describe();

  // Everything of what ran, through the usual writer.
  for (const char* name : {"summary.json", "encounters.csv", "junctions.csv", "config.yaml",
                           "timing.json", "tripinfo-sumo_native.xml", "tripinfo-no_ebp.xml"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name << "\n" << r.Describe();
  EXPECT_FALSE(fs::exists(out / "tripinfo-ta_ebp.xml"));
  const nlohmann::json s = nlohmann::json::parse(ReadText(out / "summary.json"));
  EXPECT_EQ(s.value("stopped", ""), "stall");
  EXPECT_EQ(s.value("stopped_policy", ""), "no_ebp");
  EXPECT_THAT(s.value("error", ""), HasSubstr("traffic stalled"));
  EXPECT_EQ(s["policies_not_run"], nlohmann::json::array({"ta_ebp"}));
  ASSERT_TRUE(s["policies"].contains("sumo_native"));
  ASSERT_TRUE(s["policies"].contains("no_ebp"));
  EXPECT_FALSE(s["policies"].contains("ta_ebp"));

  const nlohmann::json& native = s["policies"]["sumo_native"];
  EXPECT_TRUE(native["stalled"].get<bool>()) << "SUMO's own logic gridlocks too (recorded)";
  EXPECT_TRUE(native["stall_error"].is_null());
  EXPECT_DOUBLE_EQ(native["simulated_seconds"].get<double>(), 900.0);

  const nlohmann::json& p = s["policies"]["no_ebp"];
  EXPECT_TRUE(p["stalled"].get<bool>());
  ASSERT_TRUE(p["stall_error"].is_string());
  ASSERT_FALSE(p["stalls"].empty());
  const nlohmann::json& last = p["stalls"].back();
  const std::string junction = last["junction"].get<std::string>();
  EXPECT_THAT(s.value("error", ""), HasSubstr("junction '" + junction + "'"));
  EXPECT_LE(last["since"].get<double>(), last["detected"].get<double>());
  // Measured up to the stall: the run ended there, not at scenario.duration.
  EXPECT_NEAR(p["simulated_seconds"].get<double>(), last["detected"].get<double>(), 1.0);
  EXPECT_LT(p["simulated_seconds"].get<double>(), 900.0);
  EXPECT_GT(p["departed"].get<long>(), 20);
  EXPECT_GT(p["trips_unfinished"].get<long>(), 10) << "the queue is still there";
  EXPECT_EQ(p["trips"].get<long>(), p["departed"].get<long>());

  // junctions.csv: rows of both policies run; encounters.csv: its header.
  const std::string junctions = ReadText(out / "junctions.csv");
  EXPECT_THAT(junctions, HasSubstr("\nno_ebp,A0,"));
  EXPECT_THAT(junctions, HasSubstr("\nsumo_native,B0,"));
  EXPECT_THAT(junctions, Not(HasSubstr("\nta_ebp,")));
  EXPECT_THAT(ReadText(out / "encounters.csv"), StartsWith("policy,time,junction,"));
  // SUMO's tripinfo of the stopped run has the vehicles still in the network.
  EXPECT_THAT(ReadText(out / "tripinfo-no_ebp.xml"), HasSubstr("arrival=\"-1.00\""));

  // The table flags the stalls.
  EXPECT_THAT(r.out, HasSubstr("Stalled junctions")) << r.out;
  EXPECT_THAT(r.out, HasSubstr("(run stopped)")) << r.out;
  EXPECT_THAT(r.out, HasSubstr("stalled: No EBP at")) << r.out;
  EXPECT_THAT(r.out, HasSubstr("stalled: SUMO native at")) << r.out;  // the label (config/policies.h)
  EXPECT_THAT(r.out, HasSubstr(" stalled ")) << r.out;  // flow / delay cells marked
}

// stall_action: record: every policy to its end (exit 0), each stall in
// summary.json and the table, no "stopped".
TEST(CliStall, GridlockUnderStallActionRecordRunsEveryPolicyFlagged) {
  TempDir dir;
  const std::string config = Config(dir);
  const fs::path out = dir.path() / "out";
  const CliResult r =
      RunCli({"run", config, "--set", "policies=[no_ebp, ta_ebp]", "--set",
              "scenario.stall_action=record", "--set", "scenario.duration=500", "--out",
              out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json s = nlohmann::json::parse(ReadText(out / "summary.json"));
  EXPECT_FALSE(s.contains("stopped"));
  for (const char* policy : {"no_ebp", "ta_ebp"}) {
    SCOPED_TRACE(policy);
    const nlohmann::json& p = s["policies"][policy];
    EXPECT_TRUE(p["stalled"].get<bool>());
    EXPECT_FALSE(p["stalls"].empty());
    EXPECT_TRUE(p["stall_error"].is_null());
    EXPECT_DOUBLE_EQ(p["simulated_seconds"].get<double>(), 500.0);
    for (const auto& st : p["stalls"])
      EXPECT_THAT(r.out, HasSubstr(st["junction"].get<std::string>() + " since t = "));
  }
  EXPECT_THAT(r.out, HasSubstr("stalled: TA-EBP at")) << r.out;
  EXPECT_THAT(r.out, HasSubstr("(recorded)")) << r.out;
}

// Encounters formed and unfinished are counted as the rows are (drawn after
// the warm-up): rows = formed - unfinished for every warm-up. On the
// figure-8 a run of these lengths ends during an encounter; with the
// warm-up 2 s before the end, that encounter was drawn before it and is
// neither a row nor unfinished (it used to count as unfinished: "formed 0,
// unfinished 4").
TEST(CliStall, UnfinishedEncountersAreThoseFormedAfterTheWarmup) {
  TempDir dir;
  const std::string paper = std::string(TAEBP_SOURCE_DIR) + "/configs/paper.yaml";
  long unfinished_no_warmup = 0;
  for (const int duration : {40, 47, 53, 61}) {
    for (const int warmup : {0, duration - 2}) {
      SCOPED_TRACE("duration " + std::to_string(duration) + ", warmup " + std::to_string(warmup));
      const fs::path out = dir.path() / "out";
      const CliResult r = RunCli({"run", paper, "--set", "policies=[no_trust, ta_ebp]", "--set",
                                  "scenario.duration=" + std::to_string(duration), "--set",
                                  "scenario.warmup=" + std::to_string(warmup), "--out",
                                  out.string(), "--quiet"});
      ASSERT_EQ(r.exit_code, 0) << r.Describe();
      const nlohmann::json s = nlohmann::json::parse(ReadText(out / "summary.json"));
      const std::string rows = ReadText(out / "encounters.csv");
      for (const char* p : {"no_trust", "ta_ebp"}) {
        SCOPED_TRACE(p);
        long n = 0;
        for (std::size_t at = rows.find(std::string("\n") + p + ","); at != std::string::npos;
             at = rows.find(std::string("\n") + p + ",", at + 1))
          ++n;
        const nlohmann::json& run = s["policies"][p];
        const long formed = run["encounters_formed"], unfinished = run["encounters_unfinished"];
        EXPECT_GE(unfinished, 0);
        EXPECT_LE(unfinished, formed);
        EXPECT_EQ(formed - unfinished, n) << "rows = formed - unfinished";
        EXPECT_EQ(run["encounters"].get<long>(), n);
        if (warmup == 0) unfinished_no_warmup += unfinished;
        if (warmup > 0) {
          EXPECT_EQ(unfinished, 0) << "drawn before the warm-up's end";
        }
      }
    }
  }
  EXPECT_GT(unfinished_no_warmup, 0) << "these runs end during an encounter";
}

// The longest gap without a crossing is set per junction, and for
// sumo_native too: on the gridlocking grid every junction's gap is long.
TEST(CliStall, LongestGapWithoutCrossingPerJunctionAndForSumoNative) {
  TempDir dir;
  const std::string config = Config(dir);
  const fs::path out = dir.path() / "out";
  const CliResult r = RunCli({"run", config, "--set", "policies=[sumo_native, no_ebp]", "--set",
                              "scenario.stall_action=record", "--set", "scenario.warmup=100",
                              "--out", out.string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json s = nlohmann::json::parse(ReadText(out / "summary.json"));
  for (const char* p : {"sumo_native", "no_ebp"}) {
    SCOPED_TRACE(p);
    const nlohmann::json& run = s["policies"][p];
    EXPECT_GT(run["longest_gap_without_crossing"].get<double>(), 300.0);
    ASSERT_EQ(run["junctions"].size(), 4u);
    double longest = 0;
    for (const auto& j : run["junctions"]) {
      const double gap = j["longest_gap_without_crossing"].get<double>();
      EXPECT_GT(gap, 0.0) << j["junction"];
      EXPECT_LE(gap, 800.0 + 1e-6) << j["junction"] << ": within the measured 800 s";
      longest = std::max(longest, gap);
    }
    EXPECT_GT(longest, 300.0) << "the stalled junction's gap";
  }
  const std::string csv = ReadText(out / "junctions.csv");
  EXPECT_THAT(csv.substr(0, csv.find('\n')), HasSubstr(",longest_gap_without_crossing"));
}

}  // namespace
