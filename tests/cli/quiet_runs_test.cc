// Runs that measure nothing say so (issue 17, item 14): a controller policy
// that held no vehicle and a network run without a departure warn on stderr
// and in summary.json; the table says "no vehicle held" for a controller
// policy and "n/a (SUMO's own logic)" for sumo_native; the mean wait is null
// (summary.json) or empty (junctions.csv) where nobody was held, never 0.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "test_support.h"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::ReadText;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
const std::string kGrid = std::string(TAEBP_SOURCE_DIR) + "/configs/grid_throughput.yaml";

CliResult RunGrid(const fs::path& out, const std::vector<std::string>& sets) {
  std::vector<std::string> args = {"run", kGrid, "--set", "scenario.grid.columns=2", "--set",
                                   "scenario.grid.rows=2", "--set", "scenario.warmup=0",
                                   "--set", "scenario.duration=120"};
  for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
  args.insert(args.end(), {"--out", out.string()});
  return taebp::test::RunProgram(kCli, args);
}

// The junctions.csv column `name` of every row.
std::vector<std::string> Column(const std::string& csv, const std::string& name) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  auto split = [](const std::string& l) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream s(l);
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (!l.empty() && l.back() == ',') cells.push_back("");
    return cells;
  };
  const std::vector<std::string> header = split(line);
  const auto at = std::find(header.begin(), header.end(), name) - header.begin();
  std::vector<std::string> out;
  while (std::getline(in, line))
    if (!line.empty()) out.push_back(split(line).at(static_cast<std::size_t>(at)));
  return out;
}

TEST(QuietRuns, AControllerPolicyThatHeldNobodyWarnsAndHasNoMeanWait) {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  // AV share 0: no AV-HV pair can meet, the controller holds nobody.
  const CliResult r = RunGrid(out, {"scenario.av_share=0", "policies=[sumo_native, ta_ebp]"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("taebp: warning: ta_ebp: the controller held no vehicle"))
      << r.Describe();
  EXPECT_THAT(r.err, Not(HasSubstr("warning: sumo_native"))) << r.Describe();
  EXPECT_THAT(r.out, HasSubstr("no vehicle held")) << r.Describe();
  EXPECT_THAT(r.out, HasSubstr("n/a (SUMO's own logic)")) << r.Describe();
  const auto summary = nlohmann::json::parse(ReadText(out / "summary.json"));
  for (const char* p : {"sumo_native", "ta_ebp"}) {
    SCOPED_TRACE(p);
    const auto& policy = summary["policies"][p];
    EXPECT_TRUE(policy["wait_mean"].is_null()) << policy["wait_mean"];
  }
  EXPECT_THAT(summary["provenance"]["warnings"].dump(), HasSubstr("held no vehicle"));
  const std::vector<std::string> waits = Column(ReadText(out / "junctions.csv"), "wait_mean");
  ASSERT_FALSE(waits.empty());
  for (const std::string& w : waits) EXPECT_EQ(w, "") << "wait_mean where nobody was held";
}

TEST(QuietRuns, ANetworkRunWithoutADepartureWarns) {
  TempDir dir;
  // One trip, departing after the run's end.
  const std::string routes = dir.Write(
      "late.rou.xml",
      "<routes>\n  <trip id=\"late\" depart=\"500\" from=\"left0A0\" to=\"A0left0\"/>\n"
      "</routes>\n");
  const CliResult r = RunGrid(dir.path() / "out", {"scenario.demand=null", "scenario.routes=[" + routes + "]",
                                               "policies=[sumo_native, no_ebp]"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  for (const char* p : {"sumo_native", "no_ebp"})
    EXPECT_THAT(r.err, HasSubstr(std::string("taebp: warning: ") + p +
                                 ": no vehicle departed after the warm-up"))
        << r.Describe();
}

// The offered demand (issue 17, item 17) is the number of vehicles due to
// depart in the measured time, whether SUMO could insert them or not: here a
// flow of 2 vehicles a second on one lane (more than SUMO can insert, so
// vehicles wait to depart), due from 0 to 149.5 s, measured from 100 s: 100.
TEST(QuietRuns, OfferedDemandCountsTheVehiclesDueInTheMeasuredTime) {
  TempDir dir;
  const std::string routes = dir.Write(
      "flood.rou.xml",
      "<routes>\n  <flow id=\"f\" begin=\"0\" end=\"150\" period=\"0.5\">"
      "<route edges=\"left0A0 A0B0 B0right0\"/></flow>\n</routes>\n");
  const fs::path out = dir.path() / "out";
  const CliResult r = RunGrid(out, {"scenario.demand=null", "scenario.routes=[" + routes + "]",
                                    "scenario.warmup=100", "scenario.duration=600",
                                    "policies=[sumo_native, no_ebp]"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const auto summary = nlohmann::json::parse(ReadText(out / "summary.json"));
  for (const char* p : {"sumo_native", "no_ebp"}) {
    SCOPED_TRACE(p);
    const auto& net = summary["policies"][p];
    EXPECT_GT(net["waiting_to_depart_max"].get<long>(), 10) << "SUMO cannot insert them all";
    EXPECT_EQ(net["offered"], 100) << net["offered"];
    EXPECT_DOUBLE_EQ(net["offered_flow"].get<double>(), 100 * 3600.0 / 500.0);
  }
}

}  // namespace
