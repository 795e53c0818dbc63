// SUMO's errors name what to fix (issue 26): the policy that ran, the route
// file that defines the vehicle SUMO names, and the usual fix, whether SUMO
// fails while loading (a vehicle type nobody defined) or during a step (a
// vehicle departing later whose route its edges do not connect).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"

#include <filesystem>
#include <string>
#include <vector>

namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
const std::string kGrid = std::string(TAEBP_SOURCE_DIR) + "/configs/grid_throughput.yaml";
constexpr int kExitSumo = 3;

// The grid study's config on a 2 x 2 grid with `routes` instead of its demand.
CliResult RunWithRoutes(const std::string& routes, const fs::path& out) {
  return taebp::test::RunProgram(
      kCli, {"run", kGrid, "--set", "scenario.grid.columns=2", "--set", "scenario.grid.rows=2",
             "--set", "scenario.warmup=0", "--set", "scenario.duration=400", "--set",
             "scenario.demand=null", "--set", "scenario.routes=[" + routes + "]", "--set",
             "policies=[ta_ebp]", "--out", out.string()});
}

constexpr const char* kGood =
    "  <vehicle id=\"1\" depart=\"0\"><route edges=\"left0A0 A0B0 B0right0\"/></vehicle>\n";

TEST(SumoRouteErrors, AVehicleWithoutAValidRouteNamesItsFileAndTheFix) {
  TempDir dir;
  // Vehicle 16 departs after SUMO's first route-loading window (200 s):
  // SUMO reads it, and fails, during a step.
  const std::string routes = dir.Write(
      "routes.rou.xml", std::string("<routes>\n") + kGood +
                            "  <vehicle id=\"16\" depart=\"300\"><route edges=\"left0A0 "
                            "B1top1\"/></vehicle>\n</routes>\n");
  const CliResult r = RunWithRoutes(routes, dir.path() / "out");
  EXPECT_EQ(r.exit_code, kExitSumo) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("taebp: SUMO step failed: Vehicle '16' has no valid route."))
      << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("(policy ta_ebp; vehicle '16' is defined in " + routes +
                               "; randomTrips.py --validate or duarouter repair such routes)"))
      << r.Describe();
}

TEST(SumoRouteErrors, AnUnknownVehicleTypeNamesTheFileOfItsVehicle) {
  TempDir dir;
  const std::string other = dir.Write("other.rou.xml", std::string("<routes>\n") + kGood +
                                                           "</routes>\n");
  const std::string routes = dir.Write(
      "trucks.rou.xml",
      "<routes>\n  <vehicle id=\"4\" depart=\"2\" type=\"truck\"><route edges=\"left0A0 A0B0 "
      "B0right0\"/></vehicle>\n</routes>\n");
  const CliResult r = RunWithRoutes(other + ", " + routes, dir.path() / "out");
  EXPECT_EQ(r.exit_code, kExitSumo) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("The vehicle type 'truck' for vehicle '4' is not known."))
      << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("(policy ta_ebp; vehicle '4' is defined in " + routes +
                               "; define the vehicle type 'truck'"))
      << r.Describe();
}

}  // namespace
