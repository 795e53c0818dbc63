// What BuildScenario makes of a network config (scenario/): which junctions
// it selects and what it says about a .sumocfg's options it does not take. No
// simulation runs; the networks are built with SUMO's netgenerate and
// netconvert.
#include "taebp/config/config.h"
#include "taebp/scenario/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"

#include <cstdlib>
#include <set>
#include <string>

namespace taebp {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using test::ErrorOf;
using test::TempDir;

// scenario.junctions.min_arms: a junction is selected by type only where at
// least that many roads open to cars meet (a 3 x 3 grid without fringe edges:
// 4 corners with 2 arms, 4 sides with 3, the centre with 4); an arm closed to
// cars does not count; a selection it empties says why.
TEST(ScenarioJunctions, MinArmsKeepsJunctionsWhereThatManyCarRoadsMeet) {
  TempDir dir;
  const std::string grid = (dir.path() / "g.net.xml").string();
  ASSERT_EQ(std::system(("netgenerate --grid --grid.number 3 --grid.length 100 "
                         "--grid.attach-length 0 --default-junction-type allway_stop -o " +
                         grid + " >/dev/null 2>&1")
                            .c_str()),
            0);
  // The centre's arm to C1 closed to cars (both directions).
  const std::string patch = dir.Write("p.edg.xml",
                                      "<edges>\n  <edge id=\"B1C1\" disallow=\"passenger\"/>\n"
                                      "  <edge id=\"C1B1\" disallow=\"passenger\"/>\n</edges>\n");
  const std::string closed = (dir.path() / "closed.net.xml").string();
  ASSERT_EQ(std::system(("netconvert -s " + grid + " -e " + patch + " -o " + closed +
                         " >/dev/null 2>&1")
                            .c_str()),
            0);
  const std::string routes = dir.Write(
      "r.rou.xml", "<routes>\n  <trip id=\"a\" depart=\"0\" from=\"A0A1\" to=\"C1C2\"/>\n</routes>\n");
  auto selected = [&](const std::string& net, int min_arms) {
    const std::string path = dir.Write(
        "c.yaml", "scenario: {kind: network, network: " + net + ", routes: [" + routes +
                      "], av_share: 0.5, junctions: {min_arms: " +
                      std::to_string(min_arms) + "}}\n");
    std::set<std::string> ids;
    for (const ControlledJunction& j : BuildScenario(LoadExperimentConfig(path), "").junctions)
      ids.insert(j.id);
    return ids;
  };
  const std::set<std::string> sides = {"A1", "B0", "B1", "B2", "C1"};
  EXPECT_EQ(selected(grid, 3), sides);
  EXPECT_EQ(selected(grid, 4), (std::set<std::string>{"B1"}));
  const std::set<std::string> any = selected(grid, 0);
  for (const std::string& id : sides) EXPECT_TRUE(any.count(id)) << id;
  // C1 keeps 2 arms for cars, B1 3.
  EXPECT_EQ(selected(closed, 3), (std::set<std::string>{"A1", "B0", "B1", "B2"}));
  const std::string path = dir.Write(
      "c.yaml", "scenario: {kind: network, network: " + closed + ", routes: [" + routes +
                    "], av_share: 0.5, junctions: {min_arms: 4}}\n");
  const std::string msg =
      ErrorOf<ConfigError>([&] { BuildScenario(LoadExperimentConfig(path), ""); });
  EXPECT_THAT(msg, HasSubstr("where fewer than scenario.junctions.min_arms = 4 roads open to "
                             "cars meet"));
}

// A .sumocfg's options other than its files are not applied: listed as
// ignored (with taebp's own key where it has one), in the notes that go to
// stderr and summary.json (they used to be dropped without a word).
TEST(ScenarioSumocfg, OptionsTaebpDoesNotTakeAreListedAsIgnored) {
  TempDir dir;
  const std::string net = (dir.path() / "grid.net.xml").string();
  ASSERT_EQ(std::system(("netgenerate --grid --grid.number 2 --grid.length 100 "
                         "--grid.attach-length 100 --default-junction-type allway_stop -o " +
                         net + " >/dev/null 2>&1")
                            .c_str()),
            0);
  dir.Write("cars.rou.xml",
            "<routes>\n  <trip id=\"a\" depart=\"0\" from=\"left0A0\" to=\"A0left0\"/>\n"
            "</routes>\n");
  const std::string cfg = dir.Write(
      "city.sumocfg",
      "<configuration>\n  <input>\n    <net-file value=\"grid.net.xml\"/>\n"
      "    <route-files value=\"cars.rou.xml\"/>\n  </input>\n"
      "  <time>\n    <end value=\"1800\"/>\n    <step-length value=\"0.5\"/>\n  </time>\n"
      "  <processing>\n    <ignore-route-errors value=\"true\"/>\n  </processing>\n"
      "</configuration>\n");
  const std::string yaml = dir.Write(
      "c.yaml", "scenario: {kind: network, sumocfg: " + cfg + ", av_share: 0.5}\n");
  const Scenario s = BuildScenario(LoadExperimentConfig(yaml), "");
  std::string notes;
  for (const std::string& n : s.notes) notes += n + "\n";
  EXPECT_THAT(notes, HasSubstr("scenario.sumocfg = '" + cfg +
                               "': options taebp does not take are ignored"));
  EXPECT_THAT(notes, HasSubstr("end=1800 (scenario.duration), step-length=0.5 "
                               "(scenario.step_length), ignore-route-errors=true"));
  EXPECT_THAT(notes, Not(HasSubstr("net-file=")));
  ASSERT_EQ(s.route_files.size(), 1u);
}

}  // namespace
}  // namespace taebp
