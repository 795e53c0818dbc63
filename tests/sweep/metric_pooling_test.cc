// The one metric table (report/metrics.h) against the sweep's tables: every run
// metric read under its name, and results.csv and aggregate.csv pooled as the
// table declares (the run's own outputs: tests/report/metric_table_test.cc).
#include "taebp/report/metrics.h"
#include "taebp/report/clustered.h"
#include "taebp/report/report.h"
#include "taebp/sweep/plan.h"

#include "metric_runs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace taebp::sweep {
namespace {

using ::testing::ElementsAreArray;
using test::Figure8Run;
using test::Keys;
using test::Lines;
using test::NetworkRun;
using test::SplitCsvLine;
using test::Summary;
using ::testing::HasSubstr;

TEST(MetricTable, TheSweepReadsEveryRunMetricUnderItsName) {
  const std::vector<PolicyRun> runs = {NetworkRun(), Figure8Run()};
  const auto s = Summary(runs);
  const Json m = MetricsFromSummary(Json::parse(s.dump()), {"ta_ebp", "no_ebp"});
  EXPECT_THAT(MetricColumns(), ElementsAreArray(MetricColumns(kPolicyLevel, false)));
  for (const char* p : {"ta_ebp", "no_ebp"}) {
    SCOPED_TRACE(p);
    EXPECT_THAT(Keys(m[p]), ElementsAreArray(MetricColumns()));
    for (const std::string& c : MetricColumns()) {
      const auto& in_summary = s["policies"][p];
      if (!in_summary.contains(c)) {
        EXPECT_TRUE(m[p][c].is_null()) << c;
      } else if (in_summary[c].is_boolean()) {
        EXPECT_EQ(m[p][c], in_summary[c].get<bool>() ? 1 : 0) << c;
      } else {
        EXPECT_EQ(m[p][c].dump(), in_summary[c].dump()) << c;
      }
    }
  }
}

// One point, three seeds: each metric pooled as the table says, against sums
// and means written out here.
TEST(MetricTable, TheAggregatePoolsEachMetricAsDeclared) {
  const Plan plan = ExpandSweep(
      "scenario: {avs: 8, hvs: 8, duration: 60}\npolicies: [ta_ebp]\n"
      "sweep:\n  replicates: 3\n  grid:\n    model.trust: [0.6]\n",
      "test.yaml", {});
  auto run = [](long enc, long coll, long dc, double served, double given, bool stalled,
                double wait_max) {
    Json m;
    for (const std::string& c : MetricColumns()) m[c] = nullptr;
    m["encounters"] = enc;
    m["collisions"] = coll;
    m["dc"] = dc;
    m["collision_rate"] = enc ? static_cast<double>(coll) / enc : 0.0;
    m["theory_dc_rate"] = 0.375;
    m["theory_given_hvs_dc_rate"] = given;
    m["served_flow"] = served;
    m["stalled"] = stalled ? 1 : 0;
    m["wait_max"] = wait_max;
    m["simulated_seconds"] = 60.0;
    return Json{{"ta_ebp", m}};
  };
  Journal journal;
  AddEntry(&journal, plan, JournalEntry(plan, plan.tasks[0], "ok", "", run(10, 1, 4, 100, 0.3, false, 5)));
  AddEntry(&journal, plan, JournalEntry(plan, plan.tasks[1], "ok", "", run(30, 2, 12, 130, 0.4, true, 9)));
  AddEntry(&journal, plan, JournalEntry(plan, plan.tasks[2], "ok", "", run(0, 0, 0, 160, 0.9, false, 2)));
  const std::vector<std::string> lines = Lines(AggregateCsv(plan, journal));
  ASSERT_EQ(lines.size(), 2u);
  std::vector<std::string> header = {"point", "model.trust", "policy", "runs_ok", "runs_failed"};
  for (const std::string& c : MetricColumns(kPolicyLevel, true)) header.push_back(c);
  ASSERT_THAT(SplitCsvLine(lines[0]), ElementsAreArray(header));
  const std::vector<std::string> cells = SplitCsvLine(lines[1]);
  ASSERT_EQ(cells.size(), header.size());
  std::map<std::string, std::string> row;
  for (std::size_t i = 0; i < header.size(); ++i) row[header[i]] = cells[i];
  EXPECT_EQ(row["runs_ok"], "3");
  EXPECT_EQ(row["encounters"], "40");                              // sum
  EXPECT_EQ(row["collisions"], "3");
  const Interval ci = Wilson(3, 40);                               // pooled rate
  EXPECT_DOUBLE_EQ(std::stod(row["collision_rate"]), 3.0 / 40);
  EXPECT_DOUBLE_EQ(std::stod(row["collision_rate_lo"]), ci.low);
  EXPECT_DOUBLE_EQ(std::stod(row["collision_rate_hi"]), ci.high);
  // Runs of an older taebp without a design effect: taken as 1 with no
  // cluster known; the runs' own spread is below the binomial's: Wilson.
  EXPECT_EQ(row["collision_rate_clusters"], "0");
  EXPECT_DOUBLE_EQ(std::stod(row["dc_rate"]), 16.0 / 40);
  // Weighted by encounters; the run without encounters does not count.
  EXPECT_NEAR(std::stod(row["theory_given_hvs_dc_rate"]), (10 * 0.3 + 30 * 0.4) / 40, 1e-15);
  EXPECT_DOUBLE_EQ(std::stod(row["theory_dc_rate"]), 0.375);
  EXPECT_DOUBLE_EQ(std::stod(row["served_flow"]), 130);            // mean and SD
  EXPECT_DOUBLE_EQ(std::stod(row["served_flow_sd"]), 30);
  EXPECT_EQ(row["stalled"], "1");                                   // runs that stalled
  EXPECT_EQ(row["wait_max"], "9");                                  // max
  EXPECT_EQ(row.count("simulated_seconds"), 0u) << "not pooled";
  EXPECT_EQ(row["time_loss_mean"], "") << "absent in every run: empty";
}

// A rate pooled over seeds is clustered by HV within each run and by run
// (report/clustered.h PooledRate): two runs of 10 HVs each, design effect 4
// within each, at rates 0.10 and 0.15: the runs disagree more than their HVs
// explain, so the runs' level (2 clusters, t with 1 degree of freedom) sets
// the interval. Worked by hand: p = 50/400, the binomial variance p(1-p)/400,
// the runs' CR1 variance 2 (5^2 + 5^2) / 400^2, design effect 16/7.
TEST(MetricTable, TheAggregatesRateIsClusteredByHvAndByRun) {
  const Plan plan = ExpandSweep(
      "scenario: {avs: 8, hvs: 8, duration: 60}\npolicies: [ta_ebp]\n"
      "sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.6]\n",
      "test.yaml", {});
  auto run = [](long enc, long coll) {
    Json m;
    for (const std::string& c : MetricColumns()) m[c] = nullptr;
    m["encounters"] = enc;
    m["collisions"] = coll;
    m["collision_rate"] = static_cast<double>(coll) / enc;
    m["collision_rate_deff"] = 4.0;
    m["collision_rate_clusters"] = 10;
    return Json{{"ta_ebp", m}};
  };
  Journal journal;
  AddEntry(&journal, plan, JournalEntry(plan, plan.tasks[0], "ok", "", run(200, 20)));
  AddEntry(&journal, plan, JournalEntry(plan, plan.tasks[1], "ok", "", run(200, 30)));
  const std::vector<std::string> lines = Lines(AggregateCsv(plan, journal));
  const std::vector<std::string> header = SplitCsvLine(lines[0]);
  const std::vector<std::string> cells = SplitCsvLine(lines[1]);
  std::map<std::string, std::string> row;
  for (std::size_t i = 0; i < header.size(); ++i) row[header[i]] = cells[i];
  const double p = 50.0 / 400, binomial = p * (1 - p) / 400;
  const double deff_run = 2.0 * 50.0 / (400.0 * 400.0) / binomial;
  EXPECT_NEAR(deff_run, 16.0 / 7.0, 1e-12);
  const double t1 = 12.7062047361747;  // Student's t, 1 degree of freedom, 97.5 %
  const double adj = 1 + (deff_run - 1) * (t1 / kZ95) * (t1 / kZ95);
  const Interval expected = WilsonAt(p, 400 / adj);
  EXPECT_DOUBLE_EQ(std::stod(row["collision_rate"]), p);
  EXPECT_NEAR(std::stod(row["collision_rate_lo"]), expected.low, 1e-9);
  EXPECT_NEAR(std::stod(row["collision_rate_hi"]), expected.high, 1e-9);
  EXPECT_NEAR(std::stod(row["collision_rate_deff"]), deff_run, 1e-9);
  EXPECT_EQ(row["collision_rate_clusters"], "2");
}

TEST(MetricTable, ThePredictionWithoutEncountersIsThePlainMean) {
  const Plan plan = ExpandSweep(
      "scenario: {avs: 0, hvs: 16, duration: 60}\npolicies: [no_ebp]\n"
      "sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.6]\n",
      "test.yaml", {});
  auto run = [](double theory) {
    Json m;
    for (const std::string& c : MetricColumns()) m[c] = nullptr;
    m["encounters"] = 0;
    m["collision_rate"] = 0.0;
    m["theory_dc_rate"] = theory;
    m["theory_given_hvs_dc_rate"] = 0.0;
    return Json{{"no_ebp", m}};
  };
  Journal journal;
  AddEntry(&journal, plan, JournalEntry(plan, plan.tasks[0], "ok", "", run(0.2)));
  AddEntry(&journal, plan, JournalEntry(plan, plan.tasks[1], "ok", "", run(0.4)));
  const std::vector<std::string> lines = Lines(AggregateCsv(plan, journal));
  const std::vector<std::string> header = SplitCsvLine(lines[0]);
  const std::vector<std::string> cells = SplitCsvLine(lines[1]);
  std::map<std::string, std::string> row;
  for (std::size_t i = 0; i < header.size(); ++i) row[header[i]] = cells[i];
  EXPECT_DOUBLE_EQ(std::stod(row["theory_dc_rate"]), 0.3);
  EXPECT_EQ(row["theory_given_hvs_dc_rate"], "") << "no HV met";
  EXPECT_EQ(row["collision_rate"], "") << "no encounter";
  // In results.csv the undefined rates are empty too.
  const std::string results = ResultsCsv(plan, journal);
  const std::vector<std::string> rh = SplitCsvLine(Lines(results)[0]);
  const std::vector<std::string> r1 = SplitCsvLine(Lines(results)[1]);
  for (std::size_t i = 0; i < rh.size(); ++i)
    if (rh[i] == "collision_rate" || rh[i] == "theory_given_hvs_dc_rate") {
      EXPECT_EQ(r1[i], "") << rh[i];
    }
}

// Only games have per-encounter rates (issue 26): sumo_native's rates and
// theory are empty in results.csv and aggregate.csv, also from a journal of
// an older taebp that wrote them as 0 (with [0, 1]).
TEST(MetricTable, APolicyWithoutAGameHasNoRatesOrTheory) {
  const Plan plan = ExpandSweep(
      "scenario: {avs: 8, hvs: 8, duration: 60}\npolicies: [sumo_native, ta_ebp]\n"
      "sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.6]\n",
      "test.yaml", {});
  auto run = [](long enc, long coll) {
    Json m;
    for (const std::string& c : MetricColumns()) m[c] = nullptr;
    m["encounters"] = enc;
    m["collisions"] = coll;
    m["dc"] = 0;
    m["collision_rate"] = enc ? static_cast<double>(coll) / enc : 0.0;
    m["collision_rate_lo"] = 0.0;
    m["collision_rate_hi"] = 1.0;
    m["theory_dc_rate"] = 0.0;
    m["theory_collision_rate"] = 0.0;
    return m;
  };
  Journal journal;
  for (int t = 0; t < 2; ++t)
    AddEntry(&journal, plan, JournalEntry(plan, plan.tasks[static_cast<std::size_t>(t)], "ok", "",
                                          Json{{"sumo_native", run(0, 0)}, {"ta_ebp", run(10, 1)}}));
  const std::vector<std::string> lines = Lines(AggregateCsv(plan, journal));
  ASSERT_EQ(lines.size(), 3u);
  const std::vector<std::string> header = SplitCsvLine(lines[0]);
  std::map<std::string, std::map<std::string, std::string>> rows;
  for (std::size_t l = 1; l < lines.size(); ++l) {
    const std::vector<std::string> cells = SplitCsvLine(lines[l]);
    ASSERT_EQ(cells.size(), header.size());
    for (std::size_t i = 0; i < header.size(); ++i) rows[cells[2]][header[i]] = cells[i];
  }
  for (const char* k : {"collision_rate", "collision_rate_lo", "collision_rate_hi",
                        "theory_dc_rate", "theory_collision_rate"})
    EXPECT_EQ(rows["sumo_native"][k], "") << k;
  EXPECT_EQ(rows["sumo_native"]["encounters"], "0");
  EXPECT_DOUBLE_EQ(std::stod(rows["ta_ebp"]["collision_rate"]), 2.0 / 20);
  EXPECT_DOUBLE_EQ(std::stod(rows["ta_ebp"]["theory_dc_rate"]), 0.0) << "a game's prediction";
  const std::vector<std::string> results = Lines(ResultsCsv(plan, journal));
  const std::vector<std::string> rh = SplitCsvLine(results[0]);
  for (std::size_t l = 1; l < results.size(); ++l) {
    const std::vector<std::string> cells = SplitCsvLine(results[l]);
    const bool native = std::find(cells.begin(), cells.end(), "sumo_native") != cells.end();
    for (std::size_t i = 0; i < rh.size(); ++i)
      if (rh[i] == "collision_rate_hi" || rh[i] == "theory_dc_rate") {
        EXPECT_EQ(cells[i] == "", native) << rh[i] << ": " << results[l];
      }
  }
}

}  // namespace
}  // namespace taebp::sweep
