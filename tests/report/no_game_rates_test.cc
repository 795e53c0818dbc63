// Only games have per-encounter rates (issue 26): a policy that plays no game
// (sumo_native) has its per-encounter rates, their intervals and every theory
// null in summary.json and empty in junctions.csv, never 0 with [0, 1]; a game
// policy without an encounter has no measured rate but keeps its prediction;
// a game policy with encounters has k / n and the Wilson interval.
#include "taebp/report/metrics.h"
#include "taebp/report/report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace taebp {
namespace {

using Json = nlohmann::json;

PolicyRun Run(const std::string& policy, int encounters, int collisions, int dc) {
  PolicyRun r;
  r.policy = policy;
  r.scenario_kind = "network";
  r.simulated_seconds = r.measured_seconds = 600;
  r.theory.dc_rate = policy == "sumo_native" ? 0.0 : 0.375;
  r.theory.collision_rate = 0.0;
  JunctionRun j;
  j.id = "C";
  j.type = j.original_type = "allway_stop";
  j.rule = "all_way_stop";
  r.junctions.push_back(j);
  for (int i = 0; i < encounters; ++i) {
    EncounterRecord e;
    e.junction = "C";
    e.collision = i < collisions;
    e.hv_dc = i < dc;
    e.theory_dc = 0.4;
    r.encounters.push_back(e);
  }
  return r;
}

std::vector<PolicyRun> Runs() {
  return {Run("sumo_native", 0, 0, 0), Run("ta_ebp", 0, 0, 0), Run("no_trust", 8, 2, 3)};
}

const char* const kRates[] = {"collision_rate", "collision_rate_lo", "collision_rate_hi",
                              "dc_rate",        "dc_rate_lo",        "dc_rate_hi",
                              "theory_given_hvs_collision_rate", "theory_given_hvs_dc_rate"};
const char* const kTheory[] = {"theory_collision_rate", "theory_dc_rate", "theory_nudge_rate",
                               "theory_av_first_rate"};

TEST(NoGameRates, SummaryJsonHasNullsWhereNoGameWasPlayed) {
  Provenance prov;
  prov.config_json = "{}";
  const Json s = Json::parse(SummaryJson(Runs(), prov));
  const Json& native = s["policies"]["sumo_native"];
  const Json& idle = s["policies"]["ta_ebp"];
  const Json& game = s["policies"]["no_trust"];
  for (const char* k : kRates) {
    EXPECT_TRUE(native.at(k).is_null()) << k << " " << native.at(k);
    EXPECT_TRUE(idle.at(k).is_null()) << k << " " << idle.at(k);
    EXPECT_TRUE(native["junctions"][0].at(k).is_null()) << k;
  }
  for (const char* k : kTheory) {
    EXPECT_TRUE(native.at(k).is_null()) << k << ": sumo_native plays no game";
    EXPECT_TRUE(idle.at(k).is_number()) << k << ": a game's prediction needs no encounter";
  }
  EXPECT_DOUBLE_EQ(idle["theory_dc_rate"].get<double>(), 0.375);
  EXPECT_EQ(native["encounters"], 0);
  // The game: k / n and the Wilson interval, at the policy and the junction.
  const Interval ci = Wilson(2, 8);
  for (const Json* g : {&game, &game["junctions"][0]}) {
    EXPECT_DOUBLE_EQ((*g)["collision_rate"].get<double>(), 0.25);
    EXPECT_DOUBLE_EQ((*g)["collision_rate_lo"].get<double>(), ci.low);
    EXPECT_DOUBLE_EQ((*g)["collision_rate_hi"].get<double>(), ci.high);
    EXPECT_DOUBLE_EQ((*g)["dc_rate"].get<double>(), 3.0 / 8);
    EXPECT_DOUBLE_EQ((*g)["theory_given_hvs_dc_rate"].get<double>(), 0.4);
  }
}

TEST(NoGameRates, JunctionsCsvLeavesThemEmpty) {
  std::istringstream csv(JunctionsCsv(Runs()));
  std::string line;
  std::getline(csv, line);
  std::vector<std::string> header;
  {
    std::stringstream h(line);
    for (std::string c; std::getline(h, c, ',');) header.push_back(c);
  }
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    ASSERT_EQ(cells.size(), header.size()) << line;
    ++rows;
    for (std::size_t i = 0; i < header.size(); ++i) {
      bool rate = false;
      for (const char* k : kRates) rate |= header[i] == k;
      if (!rate) continue;
      if (cells[0] == "no_trust")
        EXPECT_NE(cells[i], "") << header[i];
      else
        EXPECT_EQ(cells[i], "") << cells[0] << " " << header[i];
    }
  }
  EXPECT_EQ(rows, 3);
}

TEST(NoGameRates, ThePrintedTableSaysSoInsteadOfZero) {
  std::ostringstream out;
  PrintTable(out, Runs());
  EXPECT_THAT(out.str(), ::testing::HasSubstr("- (SUMO's own logic)"));
  EXPECT_THAT(out.str(), ::testing::HasSubstr("n/a (no AV-HV encounter) th 0.375"));
  EXPECT_THAT(out.str(), ::testing::Not(::testing::HasSubstr("0.000 [0.000,1.000]")));
}

}  // namespace
}  // namespace taebp
