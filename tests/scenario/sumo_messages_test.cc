// SUMO's error messages made to name what to fix (controller's
// ExplainSumoError): the input file defining what SUMO names, found by id in
// the route and additional files, or "not defined in any of" them.
#include "../../controller/src/sumo_messages.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"

#include <string>

namespace taebp::control {
namespace {

using test::TempDir;

class ExplainSumoErrorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    routes_ = dir_.Write("a.rou.xml",
                         "<routes>\n"
                         "  <vType id=\"car\"/>\n"
                         "  <route id=\"r1\" edges=\"x y\"/>\n"
                         "  <vehicle id=\"16\" depart=\"0\" route=\"r1\"/>\n"
                         "  <flow id=\"f\" begin=\"0\" end=\"9\" number=\"3\" route=\"r1\"/>\n"
                         "</routes>\n");
    types_ = dir_.Write("b.add.xml",
                        "<additional>\n  <vTypeDistribution id=\"mix\">\n"
                        "    <vType id=\"truck\" probability=\"1\"/>\n"
                        "  </vTypeDistribution>\n</additional>\n");
  }
  TempDir dir_{"taebp_sumo_messages"};
  std::string routes_, types_;
};

TEST_F(ExplainSumoErrorTest, NamesTheFileDefiningWhatSumoNames) {
  EXPECT_EQ(ExplainSumoError("SUMO step failed: Vehicle '16' has no valid route.", "ta_ebp",
                             {routes_, types_}),
            "SUMO step failed: Vehicle '16' has no valid route. (policy ta_ebp; vehicle '16' is "
            "defined in " + routes_ + "; randomTrips.py --validate or duarouter repair such routes)");
  // A flow's vehicle FLOW.N: the flow's file.
  EXPECT_EQ(ExplainSumoError("SUMO step failed: Vehicle 'f.2' has no valid route.", "no_ebp",
                             {routes_, types_}),
            "SUMO step failed: Vehicle 'f.2' has no valid route. (policy no_ebp; vehicle 'f.2' is "
            "defined in " + routes_ + "; randomTrips.py --validate or duarouter repair such routes)");
  // Only a route named; only a type named (inside a distribution, in an
  // additional file).
  EXPECT_EQ(ExplainSumoError("SUMO step failed: Route 'r1' has a loop.", "ta_ebp",
                             {types_, routes_}),
            "SUMO step failed: Route 'r1' has a loop. (policy ta_ebp; route 'r1' is defined in " +
                routes_ + "; randomTrips.py --validate or duarouter repair such routes)");
  const std::string t = ExplainSumoError("SUMO step failed: Invalid vehicle type 'truck' ...",
                                         "ta_ebp", {routes_, types_});
  EXPECT_THAT(t, ::testing::HasSubstr("vehicle type 'truck' is defined in " + types_));
}

TEST_F(ExplainSumoErrorTest, SaysWhereItIsNotDefinedAndKeepsTheCommandLast) {
  EXPECT_EQ(ExplainSumoError("SUMO failed to start: Vehicle '99' has no valid route.; the "
                             "command was: sumo -n x.net.xml",
                             "sumo_native", {routes_, types_}),
            "SUMO failed to start: Vehicle '99' has no valid route. (policy sumo_native; vehicle "
            "'99' is not defined in any of " + routes_ + ", " + types_ +
            "; randomTrips.py --validate or duarouter repair such routes); the command was: "
            "sumo -n x.net.xml");
  // The generated demand is named as such, not by its scratch path.
  EXPECT_THAT(ExplainSumoError("SUMO step failed: Vehicle '16' has no valid route.", "ta_ebp",
                               {routes_}, dir_.path().string()),
              ::testing::HasSubstr("vehicle '16' is defined in the trips scenario.demand generated"));
  // Nothing named: the policy only.
  EXPECT_EQ(ExplainSumoError("SUMO step failed: something else\n", "ta_ebp", {routes_}),
            "SUMO step failed: something else (policy ta_ebp)");
}

}  // namespace
}  // namespace taebp::control
