// Never simulate the same thing twice (issue 26): a sweep runs a policy once
// for every set of grid points that differ only in keys it does not read
// (config/policies.h), per seed, and reuses that run at the other points,
// marked in results.csv's reused_from. The plan is checked linked; the
// program's sweep by the SUMO runs it makes (task folders, sweep.json's
// policy_runs), and a reused result against a fresh run of its point.
#include "sweep_fixture.h"
#include "taebp/sweep/plan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using taebp::sweep::ExpandSweep;
using taebp::sweep::Plan;
using taebp::test::Quote;
using taebp::test::ReadFile;
using taebp::test::SweepCli;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

std::string Yaml(const std::string& policies, const std::string& grid, int replicates) {
  return "scenario: {avs: 4, hvs: 4, duration: 30, seed: 5}\n"
         "policies: " + policies + "\n"
         "sweep:\n  replicates: " + std::to_string(replicates) + "\n  grid:\n" + grid;
}

const std::string kTenTrusts =
    "    model.trust: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]\n";

TEST(SweepReuse, SumoNativeRunsOncePerSeedOverKeysItDoesNotRead) {
  const Plan plan = ExpandSweep(Yaml("[sumo_native, ta_ebp]", kTenTrusts, 2), "t.yaml", {});
  ASSERT_EQ(plan.tasks.size(), 20u);
  EXPECT_EQ(plan.Runs(), 2u + 20u);  // sumo_native once per seed, ta_ebp everywhere
  EXPECT_EQ(plan.Reused(), 18u);
  for (const auto& t : plan.tasks) {
    if (t.point == 0) {
      EXPECT_EQ(t.runs, (std::vector<std::string>{"sumo_native", "ta_ebp"}));
      EXPECT_TRUE(t.reused_from.empty());
      continue;
    }
    EXPECT_EQ(t.runs, std::vector<std::string>{"ta_ebp"});
    ASSERT_EQ(t.reused_from.count("sumo_native"), 1u);
    const auto& from = plan.tasks[static_cast<std::size_t>(t.reused_from.at("sumo_native"))];
    EXPECT_EQ(from.point, 0);
    EXPECT_EQ(from.seed, t.seed) << "a replicate reuses only its own seed";
    EXPECT_THAT(plan.TaskOverrides(t), ::testing::Contains("policies=[ta_ebp]"));
  }
}

TEST(SweepReuse, KeysAPolicyReadsAreRunAgain) {
  // av_share decides sumo_native's AV/HV split: read.
  const Plan share = ExpandSweep(
      "scenario: {kind: network, grid: {columns: 2, rows: 2}, demand: {flow: 100}, "
      "duration: 30}\npolicies: [sumo_native]\nsweep:\n  grid:\n"
      "    scenario.av_share: [0.2, 0.5, 0.8]\n",
      "t.yaml", {});
  EXPECT_EQ(share.Runs(), 3u);
  EXPECT_EQ(share.Reused(), 0u);
  // ta_ebp reads the trust; every policy reads the demand.
  const Plan trust = ExpandSweep(Yaml("[ta_ebp]", kTenTrusts, 1), "t.yaml", {});
  EXPECT_EQ(trust.Runs(), 10u);
  const Plan seeds = ExpandSweep(Yaml("[sumo_native]", "    scenario.seed: [1, 2, 3]\n", 1),
                                 "t.yaml", {});
  EXPECT_EQ(seeds.Runs(), 3u);
}

TEST(SweepReuse, PolicySpecificKeysAreReusedByThePoliciesThatIgnoreThem) {
  // model.assumed_trust: read by ta_ebp only.
  const Plan plan = ExpandSweep(
      Yaml("[no_trust, ta_ebp]", "    model.assumed_trust: [0.3, 0.6, 0.9]\n", 1), "t.yaml", {});
  EXPECT_EQ(plan.Runs(), 1u + 3u);
  // A subset that would lose the columns beyond the paper runs them again:
  // population_mean ignores assumed_trust, but ta_ebp alone would be a paper
  // run with other columns; no_trust is reused.
  const Plan beyond = ExpandSweep(
      Yaml("[no_trust, ta_ebp, population_mean]", "    model.assumed_trust: [0.3, 0.6]\n", 1),
      "t.yaml", {});
  ASSERT_EQ(beyond.tasks.size(), 2u);
  const auto& second = beyond.tasks[1];
  EXPECT_EQ(second.runs, (std::vector<std::string>{"ta_ebp", "population_mean"}));
  EXPECT_EQ(second.reused_from.size(), 1u);
  EXPECT_EQ(second.reused_from.count("no_trust"), 1u);
  // Both policies ignoring the key: the second point runs nothing.
  const Plan none = ExpandSweep(
      Yaml("[no_trust, population_mean]", "    model.assumed_trust: [0.3, 0.6]\n", 1), "t.yaml",
      {});
  EXPECT_TRUE(none.tasks[1].runs.empty());
  EXPECT_EQ(none.tasks[1].reused_from.size(), 2u);
}

// The acceptance: sumo_native over 10 points that cannot change it costs one
// SUMO run; its 10 rows are the same, 9 marked reused, and equal a fresh run
// of the last point.
TEST_F(SweepCli, SumoNativeOverTenPointsThatCannotChangeItRunsSumoOnce) {
  const fs::path cfg = dir_ / "native.yaml";
  std::ofstream(cfg) << Yaml("[sumo_native]", kTenTrusts, 1);
  const fs::path out = dir_ / "out";
  ASSERT_EQ(Sweep(cfg, out, "--jobs 2"), 0) << last_log_;
  int folders = 0;
  for (const auto& e : fs::directory_iterator(out / "tasks")) folders += e.is_directory();
  EXPECT_EQ(folders, 1);
  const nlohmann::json header = nlohmann::json::parse(ReadFile(out / "sweep.json"));
  EXPECT_EQ(header.at("policy_runs"), 1);
  EXPECT_EQ(header.at("policy_runs_reused"), 9);

  std::istringstream csv(ReadFile(out / "results.csv"));
  std::string line, first_metrics;
  std::getline(csv, line);
  ASSERT_THAT(line, HasSubstr(",policy,status,error,reused_from,"));
  int rows = 0, reused = 0;
  while (std::getline(csv, line)) {
    ++rows;
    // point,replicate,seed,model.trust,policy,status,error,reused_from,metrics...
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    ASSERT_GE(cells.size(), 9u) << line;
    EXPECT_EQ(cells[5], "ok") << line;
    reused += cells[7] == "0-0";
    std::size_t at = 0;  // after the 8 leading cells: the metrics
    for (int k = 0; k < 8; ++k) at = line.find(',', at) + 1;
    const std::string metrics = line.substr(at);
    if (rows == 1) first_metrics = metrics;
    EXPECT_EQ(metrics, first_metrics) << "point " << cells[0];
  }
  EXPECT_EQ(rows, 10);
  EXPECT_EQ(reused, 9);

  // The claim behind the reuse: a fresh run at the last point (trust 1.0)
  // gives sumo_native the same results (every metric of results.csv) as the
  // run the sweep reused. (Not its summary's hv_trust: the HVs' drawn trust,
  // which no sumo_native metric reads, is the source point's.)
  const fs::path fresh = dir_ / "fresh";
  ASSERT_EQ(Taebp("run " + Quote(cfg.string()) + " --set model.trust=1.0 --set sweep=~ --out " +
                  Quote(fresh.string()) + " --quiet"),
            0)
      << last_log_;
  const auto a = nlohmann::json::parse(ReadFile(out / "tasks/0-0/summary.json"));
  const auto b = nlohmann::json::parse(ReadFile(fresh / "summary.json"));
  for (const std::string& metric : taebp::sweep::MetricColumns()) {
    const auto& pa = a.at("policies").at("sumo_native");
    const auto& pb = b.at("policies").at("sumo_native");
    EXPECT_EQ(pa.contains(metric), pb.contains(metric)) << metric;
    if (pa.contains(metric) && pb.contains(metric)) {
      EXPECT_EQ(pa[metric], pb[metric]) << metric;
    }
  }
  EXPECT_NE(a["policies"]["sumo_native"]["hv_trust"], b["policies"]["sumo_native"]["hv_trust"]);
}

// The reuse changes no number: a sweep with and without it (--no-reuse) has
// the same tables but the reused_from column, on a network where the model
// and the assumed trust are swept (sumo_native reads neither, no_trust not
// the assumed trust).
TEST_F(SweepCli, ReuseChangesNoNumber) {
  const fs::path cfg = dir_ / "net.yaml";
  std::ofstream(cfg) << "scenario: {kind: network, grid: {columns: 2, rows: 2}, "
                        "demand: {flow: 300}, av_share: 0.5, duration: 120, seed: 3}\n"
                        "policies: [sumo_native, no_trust, ta_ebp]\n"
                        "sweep:\n  replicates: 2\n  grid:\n"
                        "    model.assumed_trust: [0.4, 0.9]\n";
  const fs::path with = dir_ / "with", without = dir_ / "without";
  ASSERT_EQ(Sweep(cfg, with, "--jobs 2"), 0) << last_log_;
  ASSERT_EQ(Sweep(cfg, without, "--jobs 2 --no-reuse"), 0) << last_log_;
  const auto h = nlohmann::json::parse(ReadFile(with / "sweep.json"));
  EXPECT_EQ(h.at("policy_runs"), 2 * (3 + 1));  // per seed: 3 at the first point, ta_ebp again
  EXPECT_EQ(nlohmann::json::parse(ReadFile(without / "sweep.json")).at("policy_runs"), 12);
  // results.csv without the reused_from cells (the 8th column).
  auto strip = [](const std::string& text) {
    std::istringstream in(text);
    std::string out;
    for (std::string line; std::getline(in, line);) {
      std::size_t at = 0;
      for (int k = 0; k < 7; ++k) at = line.find(',', at) + 1;
      out += line.substr(0, at) + line.substr(line.find(',', at) + 1) + "\n";
    }
    return out;
  };
  const std::string a = ReadFile(with / "results.csv"), b = ReadFile(without / "results.csv");
  EXPECT_NE(a, b);  // reused_from is filled where reused
  EXPECT_EQ(strip(a), strip(b));
  EXPECT_EQ(ReadFile(with / "aggregate.csv"), ReadFile(without / "aggregate.csv"));
  // The pooled encounters.csv holds the reused runs' rows too (issue 45 item 1:
  // they were left out), at the task that reuses them: the same file as
  // without the reuse, with no_trust's rows at the second point.
  const std::string ea = ReadFile(with / "encounters.csv"), eb = ReadFile(without / "encounters.csv");
  EXPECT_EQ(ea, eb);
  int no_trust_at_point_1 = 0;
  std::istringstream rows(ea);
  for (std::string line; std::getline(rows, line);)
    no_trust_at_point_1 += line.rfind("1,", 0) == 0 && line.find(",no_trust,") != std::string::npos;
  EXPECT_GT(no_trust_at_point_1, 0) << "no reused run's encounters at point 1";
  // The same after shards and merge, each reusing task in another shard than
  // the task it reuses (tasks 2 and 3 reuse tasks 0 and 1; task k runs in
  // shard k % 3).
  const fs::path merged = dir_ / "merged";
  std::string shards;
  for (int i = 0; i < 3; ++i) {
    const fs::path shard = dir_ / ("s" + std::to_string(i));
    ASSERT_EQ(Sweep(cfg, shard, "--shard " + std::to_string(i) + "/3"), 0) << last_log_;
    shards += " " + Quote(shard.string());
  }
  ASSERT_EQ(Taebp("merge " + Quote(merged.string()) + shards), 0) << last_log_;
  EXPECT_EQ(ReadFile(merged / "encounters.csv"), eb);
  EXPECT_EQ(ReadFile(merged / "aggregate.csv"), ReadFile(without / "aggregate.csv"));
  EXPECT_EQ(strip(ReadFile(merged / "results.csv")), strip(b));
}

}  // namespace
