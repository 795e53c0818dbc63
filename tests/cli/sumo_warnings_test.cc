// SUMO's warnings are shown, counted and, where they change the demand,
// fatal (issue 17, item 4; SUMO used to run with --no-warnings, so an
// unsorted route file silently lost most of its vehicles).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "test_support.h"

#include <filesystem>
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
constexpr int kExitSumo = 3;

// The grid study's config on a 2 x 2 grid with `routes` instead of its demand.
CliResult RunWithRoutes(const std::string& routes, const fs::path& out) {
  return taebp::test::RunProgram(
      kCli, {"run", kGrid, "--set", "scenario.grid.columns=2", "--set", "scenario.grid.rows=2",
             "--set", "scenario.warmup=0", "--set", "scenario.duration=120", "--set",
             "scenario.demand=null", "--set", "scenario.routes=[" + routes + "]", "--set",
             "policies=[sumo_native, ta_ebp]", "--out", out.string()});
}

TEST(SumoWarnings, AreShownAndCounted) {
  TempDir dir;
  // SUMO warns that 'b' cannot arrive where its route says (it still runs).
  const std::string routes = dir.Write(
      "benign.rou.xml",
      "<routes>\n"
      "  <vehicle id=\"a\" depart=\"0\"><route edges=\"left0A0 A0B0 B0right0\"/></vehicle>\n"
      "  <vehicle id=\"b\" depart=\"1\" arrivalPos=\"9999\">"
      "<route edges=\"left0A0 A0B0 B0right0\"/></vehicle>\n"
      "</routes>\n");
  const fs::path out = dir.path() / "out";
  const CliResult r = RunWithRoutes(routes, out);
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  for (const char* p : {"sumo_native", "ta_ebp"}) {
    SCOPED_TRACE(p);
    EXPECT_THAT(r.err, HasSubstr(std::string("taebp: warning: ") + p + ": SUMO warned 1 time"))
        << r.Describe();
    const auto s = nlohmann::json::parse(ReadText(out / "summary.json"));
    const auto& w = s["policies"][p]["sumo_warnings_first"];
    EXPECT_EQ(s["policies"][p]["sumo_warnings"], 1) << w;
    ASSERT_EQ(w.size(), 1u) << w;
    EXPECT_THAT(w[0].get<std::string>(),
                HasSubstr("Vehicle 'b' will not be able to arrive at the given position"));
  }
  EXPECT_THAT(r.err, HasSubstr("SUMO warned 1 time, first: Vehicle 'b' will not be able to "
                               "arrive at the given position! (summary.json: sumo_warnings)"))
      << r.Describe();
}

TEST(SumoWarnings, ThoseThatChangeTheDemandFailTheRun) {
  TempDir dir;
  // Not sorted by departure time: SUMO drops both flows, simulating one
  // vehicle instead of 22.
  const std::string routes = dir.Write(
      "unsorted.rou.xml",
      "<routes>\n"
      "  <vehicle id=\"late\" depart=\"50\"><route edges=\"left0A0 A0B0 B0right0\"/></vehicle>\n"
      "  <flow id=\"f1\" begin=\"0\" end=\"100\" period=\"10\">"
      "<route edges=\"left0A0 A0B0 B0right0\"/></flow>\n"
      "  <flow id=\"f2\" begin=\"0\" end=\"100\" period=\"10\">"
      "<route edges=\"bottom0A0 A0B0 B0right0\"/></flow>\n"
      "</routes>\n");
  const fs::path out = dir.path() / "out";
  const CliResult r = RunWithRoutes(routes, out);
  EXPECT_EQ(r.exit_code, kExitSumo) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("SUMO did not simulate the demand the route files hold"))
      << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("Route file should be sorted by departure time, ignoring 'f1'!"))
      << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("(and 1 more)")) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("sort_routes.py")) << r.Describe();
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

}  // namespace
