// The one metric table (report/metrics.h) against the outputs report/ makes
// from it: summary.json (policy and junction objects), junctions.csv, the
// aggregate fixtures' headers, the manual's generated table and CHANGELOG.md's
// renames (the sweep's results and aggregate: tests/sweep/metric_pooling_test.cc).
// A metric added to the table but missing from an output, or an output key not
// in the table, fails here.
#include "taebp/report/metrics.h"
#include "taebp/report/report.h"

#include "metric_runs.h"

#include <gmock/gmock.h>
#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace taebp {
namespace {

using ::testing::ElementsAreArray;
using test::Figure8Run;
using test::Keys;
using test::Lines;
using test::NetworkRun;
using test::SplitCsvLine;
using test::Summary;
using ::testing::HasSubstr;

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// What the table says a policy (junction) object of `run` holds, in order.
std::vector<std::string> Expected(const PolicyRun& run, MetricLevel level) {
  std::vector<std::string> keys;
  if (level == kJunctionLevel)
    for (const MetricSection& s : RunSections())
      if (s.junction && std::string(s.name) != "approaches") keys.emplace_back(s.name);
  for (const Metric& m : RunMetrics()) {
    if (!(m.levels & level)) continue;
    const bool in_scope = m.scope == MetricScope::kAll ||
                          (m.scope == MetricScope::kNetwork && run.scenario_kind == "network") ||
                          (m.scope == MetricScope::kBeyond && run.beyond.on &&
                           run.policy != "sumo_native") ||
                          (m.scope == MetricScope::kSsm && run.ssm.on);
    if (!in_scope) continue;
    for (const std::string& c : MetricColumns(m, false)) keys.push_back(c);
  }
  for (const MetricSection& s : RunSections()) {
    if (s.junction != (level == kJunctionLevel)) continue;
    if (level == kJunctionLevel && std::string(s.name) != "approaches") continue;
    if (s.scope == MetricScope::kBeyond && !(run.beyond.on && run.policy != "sumo_native"))
      continue;
    keys.emplace_back(s.name);
  }
  return keys;
}

TEST(MetricTable, IsWellFormed) {
  std::set<std::string> names;
  for (const Metric& m : RunMetrics()) {
    SCOPED_TRACE(m.name);
    std::set<std::string> own;  // its columns in runs and pooled
    for (bool aggregate : {false, true})
      for (const std::string& c : MetricColumns(m, aggregate)) own.insert(c);
    for (const std::string& c : own)
      EXPECT_TRUE(names.insert(c).second) << c << " is declared twice";
    EXPECT_NE(m.levels, 0u);
    EXPECT_GT(std::string(m.description).size(), 10u);
    EXPECT_EQ(std::string(m.description).find('|'), std::string::npos) << "breaks the table";
    if (m.pool == Pool::kRate) {
      ASSERT_NE(m.count, nullptr);
    }
    if (m.pool == Pool::kRate || m.pool == Pool::kWeighted || m.pool == Pool::kPrediction) {
      ASSERT_NE(m.per, nullptr);
    }
    for (const char* ref : {m.count, m.per}) {
      if (!ref) continue;
      const Metric* r = FindMetric(ref);
      ASSERT_NE(r, nullptr) << ref;
      EXPECT_EQ(r->levels & m.levels, m.levels) << ref << " is not reported where " << m.name << " is";
      EXPECT_NE(r->type, MetricType::kReal) << ref << " is not a count";
    }
  }
  for (const MetricSection& s : RunSections())
    EXPECT_EQ(FindMetric(s.name), nullptr) << s.name << " is both a metric and a section";
}

TEST(MetricTable, SummaryJsonHoldsExactlyTheTable) {
  const std::vector<PolicyRun> runs = {NetworkRun(), Figure8Run()};
  const auto s = Summary(runs);
  for (const PolicyRun& r : runs) {
    SCOPED_TRACE(r.policy);
    const auto& p = s["policies"][r.policy];
    EXPECT_THAT(Keys(p), ElementsAreArray(Expected(r, kPolicyLevel)));
    for (const auto& j : p["junctions"])
      EXPECT_THAT(Keys(j), ElementsAreArray(Expected(r, kJunctionLevel)));
  }
  // Values computed independently of the table.
  const auto& p = s["policies"]["ta_ebp"];
  EXPECT_EQ(p["encounters"], 3);
  EXPECT_DOUBLE_EQ(p["collision_rate"].get<double>(), 1.0 / 3);
  const Interval ci = Wilson(1, 3);
  EXPECT_DOUBLE_EQ(p["collision_rate_lo"].get<double>(), ci.low);
  EXPECT_DOUBLE_EQ(p["collision_rate_hi"].get<double>(), ci.high);
  EXPECT_DOUBLE_EQ(p["served_flow"].get<double>(), 84 * 3600.0 / 600);
  EXPECT_DOUBLE_EQ(p["throughput_all"].get<double>(), 80 / (600 / 3600.0));
  EXPECT_DOUBLE_EQ(p["time_loss_mean"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(p["wait_mean"].get<double>(), 2.5);
  EXPECT_EQ(p["nudges"], 2);
  EXPECT_EQ(p["failures"], 1);  // the first encounter: nudged, then the HV drove recklessly
  EXPECT_EQ(p["stalled"], true);
  EXPECT_DOUBLE_EQ(p["regret_per_encounter"].get<double>(), 0.025);
  EXPECT_DOUBLE_EQ(p["oracle_dc_rate"].get<double>(), 0.4);
  EXPECT_EQ(p["last_hour_encounters"], 3);
  const auto& j1 = p["junctions"][0];
  EXPECT_EQ(j1["junction"], "J1");
  EXPECT_DOUBLE_EQ(j1["throughput_all"].get<double>(), 50 * 3600.0 / 600);
  EXPECT_DOUBLE_EQ(j1["queue_mean"].get<double>(), 180.0 / 1200);
  EXPECT_DOUBLE_EQ(j1["queue_max"].get<double>(), 5);
  EXPECT_EQ(j1["collisions"], 1);
  EXPECT_TRUE(p["junctions"][1]["wait_mean"].is_null()) << "nobody held at J2";
  EXPECT_EQ(p["ssm_conflicts"], 7);
  EXPECT_DOUBLE_EQ(p["ssm_conflicts_per_hour"].get<double>(), 7 * 6.0);
  EXPECT_DOUBLE_EQ(p["ssm_conflicts_per_1000_crossings"].get<double>(), 4 * 1000.0 / 80);
  EXPECT_EQ(p["ssm_ttc_conflicts"], 5);
  EXPECT_TRUE(p["ssm_pet_conflicts"].is_null()) << "PET was not measured";
  EXPECT_DOUBLE_EQ(p["ssm_ttc_min"].get<double>(), 0.8);
  EXPECT_TRUE(p["ssm_drac_max"].is_null()) << "no DRAC value given";
  EXPECT_EQ(j1["ssm_conflicts"], 4);
  EXPECT_DOUBLE_EQ(j1["ssm_drac_conflicts_per_1000_crossings"].get<double>(), 2 * 1000.0 / 50);
  EXPECT_EQ(p["junctions"][1]["ssm_conflicts"], 0);
  const auto& f8 = s["policies"]["no_ebp"];
  EXPECT_FALSE(f8.contains("ssm_conflicts")) << "an SSM metric in a run without SSM";
  EXPECT_FALSE(f8.contains("served_flow")) << "a network metric on the figure-8";
  EXPECT_FALSE(f8.contains("regret")) << "a beyond metric in a paper run";
}

TEST(MetricTable, JunctionsCsvIsTheSummarysJunctionsRowForRow) {
  const std::vector<PolicyRun> runs = {NetworkRun(), Figure8Run()};
  const auto s = Summary(runs);
  const std::vector<std::string> lines = Lines(JunctionsCsv(runs));
  std::vector<std::string> header = {"policy", "junction", "type", "original_type", "rule",
                                     "game_pairs"};
  for (const std::string& c : MetricColumns(kJunctionLevel, false)) header.push_back(c);
  ASSERT_THAT(SplitCsvLine(lines[0]), ElementsAreArray(header));
  ASSERT_EQ(lines.size(), 4u);
  std::size_t row = 1;
  for (const PolicyRun& r : runs) {
    const std::vector<std::string> in_scope = Expected(r, kJunctionLevel);
    for (const auto& j : s["policies"][r.policy]["junctions"]) {
      const std::vector<std::string> cells = SplitCsvLine(lines[row++]);
      ASSERT_EQ(cells.size(), header.size());
      EXPECT_EQ(cells[0], r.policy);
      for (std::size_t c = 1; c < header.size(); ++c) {
        SCOPED_TRACE(header[c]);
        // A metric out of this run's scope (SSM without scenario.outputs.ssm,
        // ...) is absent from summary.json and its cell empty; one in scope
        // must be in both. (j is const: operator[] on a missing key would read
        // past the object, hence contains/at.)
        if (!j.contains(header[c])) {
          EXPECT_EQ(cells[c], "");
          EXPECT_THAT(in_scope, ::testing::Not(::testing::Contains(header[c])))
              << "in scope yet missing from summary.json's junction";
          continue;
        }
        const auto& v = j.at(header[c]);
        if (v.is_null()) {
          EXPECT_EQ(cells[c], "");
        } else if (v.is_string()) {
          EXPECT_EQ(cells[c], v.get<std::string>());
        } else {
          EXPECT_DOUBLE_EQ(std::stod(cells[c]), v.get<double>());
        }
      }
    }
  }
}

TEST(MetricTable, TheFixturesHaveTheAggregatesColumns) {
  for (const char* name : {"aggregate_mismatch.csv", "aggregate_penetration.csv",
                           "aggregate_trust.csv"}) {
    SCOPED_TRACE(name);
    const std::string text = ReadFile(std::string(TAEBP_SOURCE_DIR) + "/tests/data/" + name);
    ASSERT_FALSE(text.empty());
    const std::vector<std::string> header = SplitCsvLine(Lines(text)[0]);
    const auto policy = std::find(header.begin(), header.end(), "policy");
    ASSERT_NE(policy, header.end());
    const std::vector<std::string> metrics(policy + 3, header.end());
    EXPECT_THAT(metrics, ElementsAreArray(MetricColumns(kPolicyLevel, true)))
        << "the fixture's header differs from the table: run tools/refresh-docs";
  }
}

std::string Block(const std::string& doc, const std::string& marker) {
  const std::string begin = "<!-- " + marker + ":begin";
  const std::string end = "<!-- " + marker + ":end -->";
  const auto b = doc.find(begin);
  const auto e = doc.find(end);
  if (b == std::string::npos || e == std::string::npos) return "(no " + marker + " block)";
  const auto first = doc.find('\n', b) + 1;
  return doc.substr(first, e - first);
}

// The manual's metric page (docs/metrics.md; the test keeps its name from
// when the table was in README.md).
TEST(MetricTable, ReadmeTableIsGenerated) {
  const std::string readme = ReadFile(std::string(TAEBP_SOURCE_DIR) + "/docs/metrics.md");
  EXPECT_EQ(Block(readme, "metrics"), MetricsMarkdown() + "\n" + SampleColumnsMarkdown())
      << "docs/metrics.md's metric table differs from the table: run tools/refresh-docs";
  const std::string changelog = ReadFile(std::string(TAEBP_SOURCE_DIR) + "/CHANGELOG.md");
  EXPECT_EQ(Block(changelog, "renames"), RenamesMarkdown())
      << "CHANGELOG.md's renames differ from the table: run tools/refresh-docs";
  // Every metric is in the page's table under its name.
  for (const Metric& m : RunMetrics())
    EXPECT_THAT(readme, HasSubstr(std::string("| `") + m.name + "`")) << m.name;
}

}  // namespace
}  // namespace taebp
