// SUMO's SSM output read into conflicts (report/ssm.h), on a log written here
// whose answer is counted by hand.
#include "taebp/report/ssm.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <string>

namespace taebp {
namespace {

using ::testing::HasSubstr;

std::string Conflict(const std::string& ego, const std::string& foe, double begin, double end,
                     const std::string& ttc, const std::string& drac, const std::string& pet,
                     const std::string& pos) {
  auto m = [&](const char* name, const std::string& v) {
    return std::string("    <") + name + " time=\"" + std::to_string(begin + 1) +
           "\" position=\"" + (v == "NA" ? "NA" : pos) + "\" type=\"" +
           (v == "0.00" ? "111" : "10") + "\" value=\"" + v + "\"/>\n";
  };
  return "  <conflict begin=\"" + std::to_string(begin) + "\" end=\"" + std::to_string(end) +
         "\" ego=\"" + ego + "\" foe=\"" + foe + "\">\n" + m("minTTC", ttc) +
         m("maxDRAC", drac) + m("PET", pet) + "  </conflict>\n";
}

// Junction J: one internal lane from (0, 0) to (10, 0); radius 10 m.
const std::vector<SsmJunctionArea> kAreas = {{"J", {{{0, 0}, {10, 0}}}},
                                             {"K", {{{500, 500}}}}};

SsmRules Rules() {
  SsmRules r;
  r.on = {true, true, true};
  r.threshold = {3.0, 3.0, 2.0};
  r.warmup = 5;
  r.junction_radius = 10;
  return r;
}

std::string Log() {
  return "<?xml version=\"1.0\"?>\n<SSMLog>\n" +
         // A and B, both devices, overlapping spans: one conflict, TTC 1.2 at J.
         Conflict("A", "B", 10, 20, "1.50", "1.00", "NA", "5.00,3.00") +
         Conflict("B", "A", 11, 19, "1.20", "NA", "NA", "5.00,3.00") +
         // A and C standing nose to tail: minTTC 0 (type 111), no conflict.
         Conflict("A", "C", 12, 30, "0.00", "NA", "NA", "5.00,0.00") +
         // B and C far from any junction: a DRAC conflict in the network.
         Conflict("C", "B", 30, 33, "NA", "3.50", "NA", "100.00,100.00") +
         // C and D before the warm-up's end: not counted.
         Conflict("C", "D", 2, 8, "NA", "NA", "1.00", "5.00,0.00") +
         // A and D: PET 2.5 above its threshold: no conflict.
         Conflict("A", "D", 50, 55, "NA", "NA", "2.50", "5.00,0.00") +
         // A and B again later: TTC 2.9 and DRAC 4.0, 8 m beside J's lane.
         Conflict("A", "B", 40, 45, "2.90", "4.00", "NA", "5.00,-8.00") +
         "</SSMLog>\n";
}

TEST(SsmOutput, MergesBothDevicesRecordsAndCountsEachMeasurePastItsThreshold) {
  test::TempDir dir;
  const SsmRun r = ReadSsmOutput(dir.Write("ssm.xml", Log()), Rules(), kAreas);
  EXPECT_TRUE(r.on);
  EXPECT_EQ(r.records, 7);
  EXPECT_EQ(r.network.conflicts, 3);  // A-B, B-C, A-B later
  EXPECT_EQ(r.network.by_measure[0], 2);
  EXPECT_EQ(r.network.by_measure[1], 2);
  EXPECT_EQ(r.network.by_measure[2], 0);
  EXPECT_DOUBLE_EQ(r.network.ttc_min, 1.2);
  EXPECT_DOUBLE_EQ(r.network.drac_max, 4.0);
  EXPECT_EQ(r.at_junctions.conflicts, 2);
  EXPECT_EQ(r.at_junctions.by_measure[0], 2);
  EXPECT_EQ(r.at_junctions.by_measure[1], 1);
  ASSERT_EQ(r.junction.size(), 2u);
  EXPECT_EQ(r.junction.at("J").conflicts, 2);
  EXPECT_DOUBLE_EQ(r.junction.at("J").drac_max, 4.0);
  EXPECT_EQ(r.junction.at("K").conflicts, 0) << "every junction is listed, with 0";
  EXPECT_TRUE(std::isnan(r.junction.at("K").ttc_min));
}

// A conflict over a collision SUMO's check reported between the same two (its
// span, within a second) is that collision, counted once, in the collisions:
// not among the conflicts, by any measure. Another pair's collision, or the
// same pair's at another time, leaves it a conflict.
TEST(SsmOutput, AConflictOverACollisionOfItsPairIsTheCollision) {
  test::TempDir dir;
  const std::string path = dir.Write("ssm.xml", Log());
  // A-B's later conflict (40-45 s: TTC 2.9, DRAC 4.0) over their collision at 45.5 s.
  const SsmRun r = ReadSsmOutput(path, Rules(), kAreas, {}, {{"B", "A", 45.5}});
  EXPECT_EQ(r.collided, 1);
  EXPECT_EQ(r.network.conflicts, 2);  // A-B (10-20 s), B-C
  EXPECT_EQ(r.network.by_measure[0], 1);
  EXPECT_EQ(r.network.by_measure[1], 1);  // B-C's DRAC only
  EXPECT_DOUBLE_EQ(r.network.drac_max, 3.5);
  EXPECT_EQ(r.junction.at("J").conflicts, 1);
  // The same pair long after, or another pair at that time: still a conflict.
  const SsmRun later = ReadSsmOutput(path, Rules(), kAreas, {}, {{"A", "B", 200}});
  EXPECT_EQ(later.collided, 0);
  EXPECT_EQ(later.network.conflicts, 3);
  const SsmRun other = ReadSsmOutput(path, Rules(), kAreas, {}, {{"A", "C", 42}});
  EXPECT_EQ(other.collided, 0);
  EXPECT_EQ(other.network.conflicts, 3);
}

TEST(SsmOutput, OnlyTheMeasuresSumoComputedAndTheRadiusPlaceTheConflicts) {
  test::TempDir dir;
  const std::string path = dir.Write("ssm.xml", Log());
  SsmRules rules = Rules();
  rules.on = {false, true, false};  // DRAC only
  const SsmRun drac = ReadSsmOutput(path, rules, kAreas);
  EXPECT_EQ(drac.network.conflicts, 2);
  EXPECT_EQ(drac.network.by_measure[0], 0);
  EXPECT_TRUE(std::isnan(drac.network.ttc_min));
  rules = Rules();
  rules.junction_radius = 5;  // the later A-B conflict, 8 m off, is no longer at J
  const SsmRun near = ReadSsmOutput(path, rules, kAreas);
  EXPECT_EQ(near.network.conflicts, 3);
  EXPECT_EQ(near.junction.at("J").conflicts, 1);
  rules.warmup = 0;  // C-D's PET 1.0 counts
  EXPECT_EQ(ReadSsmOutput(path, rules, kAreas).network.by_measure[2], 1);
}

TEST(SsmOutput, AMissingOrForeignFileIsAnErrorNamingIt) {
  test::TempDir dir;
  const std::string missing = (dir.path() / "none.xml").string();
  EXPECT_THAT(test::ErrorOf<std::runtime_error>([&] { ReadSsmOutput(missing, Rules(), kAreas); }),
              HasSubstr(missing));
  const std::string other = dir.Write("other.xml", "<tripinfos/>");
  EXPECT_THAT(test::ErrorOf<std::runtime_error>([&] { ReadSsmOutput(other, Rules(), kAreas); }),
              HasSubstr("not SUMO's SSM output"));
}

// A game's pair measures: the worst of each measure over its AV's and HV's
// conflicts with each other in the game's window [formed - 30 s, formed + 60
// s], past its threshold or not; other pairs' conflicts and the pair's other
// times not; NaN where none was logged.
TEST(SsmOutput, AGamesPairMeasuresAreItsPairsWorstInItsWindow) {
  test::TempDir dir;
  const std::string log = Log().substr(0, Log().rfind("</SSMLog>")) +
                          // E and F: TTC 1.0, then DRAC 5.0 (no TTC) a little later.
                          Conflict("E", "F", 100, 102, "1.00", "NA", "NA", "5.00,0.00") +
                          Conflict("F", "E", 110, 112, "NA", "5.00", "NA", "5.00,0.00") +
                          // E and F again, long after the game's window: not its.
                          Conflict("E", "F", 300, 302, "0.50", "9.00", "0.10", "5.00,0.00") +
                          "</SSMLog>\n";
  const std::vector<SsmGame> games = {
      {"B", "A", "J", 12},    // A-B at 10-20 (TTC 1.2) and 40-45 (TTC 2.9, DRAC 4.0)
      {"B", "C", "K", 100},   // B-C's DRAC conflict at 30-33 ends before 100 - 30
      {"E", "F", "J", 105},   // TTC and DRAC in two conflicts
      {"A", "D", "J", 50}};   // A-D: PET 2.5, past no threshold, still its value
  const SsmRun r = ReadSsmOutput(dir.Write("ssm.xml", log), Rules(), kAreas, games);
  ASSERT_EQ(r.games.size(), 4u);
  EXPECT_DOUBLE_EQ(r.games[0].min_ttc, 1.2);
  EXPECT_DOUBLE_EQ(r.games[0].max_drac, 4.0);
  EXPECT_TRUE(std::isnan(r.games[0].min_pet));
  EXPECT_TRUE(std::isnan(r.games[1].min_ttc) && std::isnan(r.games[1].max_drac) &&
              std::isnan(r.games[1].min_pet));
  EXPECT_DOUBLE_EQ(r.games[2].min_ttc, 1.0);
  EXPECT_DOUBLE_EQ(r.games[2].max_drac, 5.0);
  EXPECT_TRUE(std::isnan(r.games[2].min_pet));
  EXPECT_DOUBLE_EQ(r.games[3].min_pet, 2.5);
  EXPECT_FALSE(SsmPasses(Rules(), SsmMeasure::kPet, r.games[3].min_pet));
  EXPECT_TRUE(SsmPasses(Rules(), SsmMeasure::kTtc, r.games[0].min_ttc));
  EXPECT_FALSE(SsmPasses(Rules(), SsmMeasure::kTtc, 0.0)) << "TTC 0: SUMO's standstill";
  // A measure SUMO did not compute: NaN for every game.
  SsmRules no_drac = Rules();
  no_drac.on[1] = false;
  const SsmRun partial = ReadSsmOutput(dir.Write("ssm3.xml", log), no_drac, kAreas, games);
  EXPECT_TRUE(std::isnan(partial.games[0].max_drac));
  EXPECT_DOUBLE_EQ(partial.games[0].min_ttc, 1.2);
  const SsmRun none = ReadSsmOutput(dir.Write("ssm2.xml", log), Rules(), kAreas);
  EXPECT_TRUE(none.games.empty());
}

}  // namespace
}  // namespace taebp
