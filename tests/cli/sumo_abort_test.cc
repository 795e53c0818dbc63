// SUMO 1.15 aborts the process (MSLink.cpp:740, assertion 'waitingTime > 0')
// when pedestrians cross at an all-way stop (issue 17, item 7). taebp says
// so beforehand (a warning), and when SUMO aborts: its own message passed
// on, what in the scenario causes it and what to do, exit 3 (SUMO failed),
// the scratch folder removed, no results written.
// taebp-tests: sanitize (also run under the sanitizers; tests/CMakeLists.txt)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;

int Shell(const std::string& command) {
  const int rc = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(SumoAbort, PedestriansAtAllWayCrossingsExitThreeSayingWhyAndLeaveNoScratch) {
  TempDir dir;
  const fs::path d = dir.path();
  const std::string net = (d / "walk.net.xml").string();
  ASSERT_EQ(Shell("netgenerate --grid --grid.number 3 --grid.length 100 --grid.attach-length 100 "
                  "--default-junction-type allway_stop --sidewalks.guess true "
                  "--crossings.guess true -o " + net),
            0);
  const std::string trips = "python3 /usr/share/sumo/tools/randomTrips.py -n " + net + " -e 600 ";
  ASSERT_EQ(Shell(trips + "-p 3 --seed 2 --prefix c -o " + (d / "cars.rou.xml").string()), 0);
  ASSERT_EQ(Shell(trips + "-p 2 --seed 1 --pedestrians -o " + (d / "walkers.rou.xml").string()),
            0);
  const std::string config = dir.Write(
      "walk.yaml", "scenario:\n  kind: network\n  network: walk.net.xml\n"
                   "  routes: [cars.rou.xml, walkers.rou.xml]\n  av_share: 0.5\n"
                   "  duration: 600\npolicies: [sumo_native, ta_ebp]\n");
  const fs::path tmp = d / "tmp";
  fs::create_directories(tmp);
  const CliResult r = taebp::test::RunProgram(
      kCli, {"run", config, "--out", (d / "out").string()},
      [&] { ::setenv("TMPDIR", tmp.c_str(), 1); });
  EXPECT_EQ(r.exit_code, 3) << r.Describe();
  // Said before SUMO starts, then SUMO's own message, then ours.
  EXPECT_THAT(r.err, HasSubstr("taebp: warning: SUMO may abort: pedestrians (")) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("MSLink.cpp:740")) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("taebp: SUMO aborted: pedestrians (" +
                               (d / "walkers.rou.xml").string() + ") cross at 9 all-way-stop"))
      << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("Run without pedestrians")) << r.Describe();
  EXPECT_TRUE(fs::is_empty(tmp)) << "taebp-run-* scratch left in TMPDIR";
  EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
}

}  // namespace
