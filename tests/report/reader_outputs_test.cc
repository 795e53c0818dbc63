// What a reader looks for in a run's files (issue 44): collisions.csv, one
// row per collision SUMO reported, each in the count of summary.json it is in;
// encounters_per_hour in the metric table (none for a policy without a game);
// rows of the printed table only where they mean something.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "metric_runs.h"
#include "taebp/report/metrics.h"
#include "taebp/report/report.h"

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using taebp::CollisionRecord;
using taebp::EncounterRecord;
using taebp::PolicyRun;
using taebp::test::Lines;
using taebp::test::SplitCsvLine;

CollisionRecord Collision(double t, const std::string& lane, const std::string& a,
                          const std::string& b, bool pair, bool move) {
  CollisionRecord c;
  c.time = t;
  c.lane = lane;
  c.type = "junction";
  c.collider = a;
  c.victim = b;
  c.collider_av = a.rfind("av", 0) == 0;
  c.victim_av = b.rfind("av", 0) == 0;
  c.collider_in_game = pair || move;
  c.victim_in_game = pair;
  c.encounter_pair = pair;
  c.game_move = move;
  return c;
}

EncounterRecord Met(const std::string& av, const std::string& hv, bool collision,
                    bool after_handback = false) {
  EncounterRecord e;
  e.av = av;
  e.hv = hv;
  e.junction = "J1";
  e.collision = collision;
  e.collision_after_handback = after_handback;
  return e;
}

// A run whose SUMO reported five collisions: two encounters' (one of them
// after its pair went back to SUMO), a game move hitting a third vehicle,
// SUMO's own, and an encounter pair whose encounter is not on record.
PolicyRun Collided() {
  PolicyRun r;
  r.policy = "no_trust";
  r.measured_seconds = 600;
  r.simulated_seconds = 600;
  r.encounters = {Met("av0", "hv1", true), Met("av2", "hv3", false, true), Met("av4", "hv5", false)};
  r.collisions = {Collision(10, ":J1_3_0", "hv1", "av0", true, false),
                  Collision(20, ":J1_0_0", "av2", "hv3", true, false),
                  Collision(30, ":J2_12_1", "hv5", "hv9", false, true),
                  Collision(40, "E_C_0", "hv7", "hv8", false, false),
                  Collision(50, ":J1_3_0", "hv1", "av0", true, false)};
  r.other_collisions = 2;
  r.other_collisions_game_move = 1;
  return r;
}

std::vector<std::map<std::string, std::string>> Rows(const std::string& csv) {
  const std::vector<std::string> lines = Lines(csv);
  const std::vector<std::string> header = SplitCsvLine(lines.at(0));
  std::vector<std::map<std::string, std::string>> out;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> cells = SplitCsvLine(lines[i]);
    EXPECT_EQ(cells.size(), header.size()) << lines[i];
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
    out.push_back(row);
  }
  return out;
}

TEST(CollisionsCsv, EveryCollisionARowInTheCountItIsIn) {
  const PolicyRun r = Collided();
  const std::string csv = taebp::CollisionsCsv({r});
  std::string header;
  for (const std::string& c : taebp::CollisionCsvColumns()) header += (header.empty() ? "" : ",") + c;
  EXPECT_EQ(Lines(csv).at(0), header);
  const auto rows = Rows(csv);
  ASSERT_EQ(rows.size(), 5u);
  std::vector<std::string> counted;
  for (const auto& row : rows) counted.push_back(row.at("counted_in"));
  EXPECT_EQ(counted, (std::vector<std::string>{"collisions", "collisions_after_handback",
                                               "other_collisions_game_move", "other_collisions",
                                               "none"}));
  // Where: a junction's internal lane names it (ids with underscores too);
  // a lane of an edge is no junction.
  EXPECT_EQ(rows[0].at("junction"), "J1");
  EXPECT_EQ(rows[2].at("junction"), "J2");
  EXPECT_EQ(rows[2].at("lane"), ":J2_12_1");
  EXPECT_EQ(rows[3].at("junction"), "");
  EXPECT_EQ(rows[0].at("collider"), "hv1");
  EXPECT_EQ(rows[0].at("collider_kind"), "hv");
  EXPECT_EQ(rows[0].at("victim_kind"), "av");
  EXPECT_EQ(rows[2].at("collider_in_game"), "1");
  EXPECT_EQ(rows[2].at("victim_in_game"), "0");
  EXPECT_EQ(rows[2].at("game_move"), "1");
  EXPECT_EQ(rows[0].at("policy"), "no_trust");
  // collisions_total = the rows counted in collisions and in
  // other_collisions_game_move; other_collisions = the rows of neither pair.
  const nlohmann::ordered_json s = taebp::test::Summary({r})["policies"]["no_trust"];
  long total = 0, other = 0, encounter = 0;
  for (const auto& row : rows) {
    total += row.at("counted_in") == "collisions" ||
             row.at("counted_in") == "other_collisions_game_move";
    other += row.at("encounter_pair") == "0";
    encounter += row.at("counted_in") == "collisions";
  }
  EXPECT_EQ(s["collisions_total"].get<long>(), total);
  EXPECT_EQ(s["other_collisions"].get<long>(), other);
  EXPECT_EQ(s["collisions"].get<long>(), encounter);
}

TEST(CollisionsCsv, ARunWithoutCollisionsHasTheHeaderOnly) {
  PolicyRun r = taebp::test::Figure8Run();
  EXPECT_EQ(Lines(taebp::CollisionsCsv({r})).size(), 1u);
}

TEST(EncountersPerHour, InTheTableAndNoneWithoutAGame) {
  const taebp::Metric* m = taebp::FindMetric("encounters_per_hour");
  ASSERT_NE(m, nullptr);
  EXPECT_STREQ(m->unit, "1/h");
  PolicyRun game = Collided();  // 3 encounters in 600 measured s
  PolicyRun native = Collided();
  native.policy = "sumo_native";
  native.encounters.clear();
  const auto s = taebp::test::Summary({game, native})["policies"];
  EXPECT_DOUBLE_EQ(s["no_trust"]["encounters_per_hour"].get<double>(), 3 / (600 / 3600.0));
  EXPECT_TRUE(s["sumo_native"]["encounters_per_hour"].is_null());
}

std::string Table(const std::vector<PolicyRun>& runs) {
  std::ostringstream out;
  taebp::PrintTable(out, runs);
  return out.str();
}

PolicyRun Beyond(double measured, bool moves) {
  PolicyRun r = taebp::test::Figure8Run();
  r.policy = "ta_ebp";
  r.measured_seconds = r.simulated_seconds = measured;
  r.beyond.on = true;
  r.beyond.trust_moves = moves;
  r.beyond.initial_mean_trust = 0.6;
  r.beyond.final_mean_trust = moves ? 0.7 : 0.6;
  return r;
}

TEST(PrintedTable, RowsOnlyWhereTheyMeanSomething) {
  // 30 measured minutes, trust fixed (noise or learning): its last hour is
  // the run and its trust does not move.
  const std::string short_fixed = Table({Beyond(1800, false)});
  EXPECT_THAT(short_fixed, Not(HasSubstr("Last hour DC rate")));
  EXPECT_THAT(short_fixed, Not(HasSubstr("Mean trust start/end")));
  EXPECT_THAT(short_fixed, Not(HasSubstr("or = the oracle")));
  EXPECT_THAT(short_fixed, HasSubstr("Regret / encounter"));
  // Two hours, trust dynamic: both rows.
  const std::string long_moving = Table({Beyond(7200, true)});
  EXPECT_THAT(long_moving, HasSubstr("Last hour DC rate"));
  EXPECT_THAT(long_moving, HasSubstr("Mean trust start/end"));
  EXPECT_THAT(long_moving, HasSubstr("or = the oracle"));
  // An hour exactly: the last hour is still the whole run.
  EXPECT_THAT(Table({Beyond(3600, false)}), Not(HasSubstr("Last hour DC rate")));
}

}  // namespace
