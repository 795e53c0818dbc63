// The rate intervals clustered by HV and by run (report/clustered.h): exact
// cases, a bootstrap over HVs as a second method, the coverage a simulation
// with a known rate measures, and the Table I printout's '!' that follows them.
#include "taebp/report/clustered.h"

#include "taebp/report/report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace taebp {
namespace {

// The DC counts of the 8 HVs (of 464 encounters each) that a reader found in
// `taebp run configs/influence.yaml --set model.experience.design=paper --set
// 'policies=[ta_ebp]' --set scenario.seed=41` (issue 41): each HV follows its
// own learning walk, so its encounters are far from independent.
const std::vector<double> kInfluenceDc = {7, 11, 23, 28, 78, 116, 118, 161};
constexpr double kInfluenceN = 464;

std::vector<ClusterCount> Influence() {
  std::vector<ClusterCount> c;
  for (double y : kInfluenceDc) c.push_back({y, kInfluenceN});
  return c;
}

// The percentile bootstrap over HVs (resampling whole HVs with replacement):
// the second method the clustered interval is held against.
Interval BootstrapOverHvs(const std::vector<ClusterCount>& c, int draws, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, c.size() - 1);
  std::vector<double> rates;
  for (int b = 0; b < draws; ++b) {
    double y = 0, n = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const ClusterCount& x = c[pick(rng)];
      y += x.y;
      n += x.n;
    }
    rates.push_back(y / n);
  }
  std::sort(rates.begin(), rates.end());
  return {rates[static_cast<std::size_t>(0.025 * draws)],
          rates[static_cast<std::size_t>(0.975 * draws)]};
}

TEST(ClusteredRate, HvsOfEqualRatesGiveWilsonExactly) {
  // Every HV at the same rate: no spread between them (design effect 0), so
  // nothing beyond the binomial: Wilson's interval, bit for bit.
  const RateInterval r = ClusteredRate({{3, 10}, {6, 20}, {9, 30}, {3, 10}, {6, 20}});
  const Interval w = Wilson(27, 90);
  EXPECT_DOUBLE_EQ(r.rate, 0.3);
  EXPECT_EQ(r.low, w.low);
  EXPECT_EQ(r.high, w.high);
  EXPECT_EQ(r.clusters, 5);
  EXPECT_FALSE(r.few_clusters);
  EXPECT_LT(r.deff, 1e-12);
}

TEST(ClusteredRate, NoSuccessIsWilsonsZeroAtTheBottom) {
  const RateInterval r = ClusteredRate({{0, 50}, {0, 60}, {0, 70}, {0, 80}, {0, 90}, {0, 100}});
  const Interval w = Wilson(0, 450);
  EXPECT_EQ(r.low, 0.0);
  EXPECT_EQ(r.high, w.high);
  EXPECT_EQ(r.deff, 1.0);
}

TEST(ClusteredRate, OneHvCannotEstimateItsDependence) {
  const RateInterval r = ClusteredRate({{12, 40}, {0, 0}});  // an empty cluster is skipped
  const Interval w = Wilson(12, 40);
  EXPECT_EQ(r.clusters, 1);
  EXPECT_TRUE(r.few_clusters);
  EXPECT_EQ(r.low, w.low);
  EXPECT_EQ(r.high, w.high);
  EXPECT_EQ(ClusteredRate({}).clusters, 0);
  EXPECT_EQ(ClusteredRate({}).high, 1.0);
}

TEST(ClusteredRate, DesignEffectByHand) {
  // Two HVs, 10 encounters each, 2 and 8 successes: p = 0.5; the CR1
  // variance is 2/1 * ((2-5)^2 + (8-5)^2) / 20^2 = 0.09, the binomial's
  // 0.25 / 20 = 0.0125: design effect 7.2.
  const RateInterval r = ClusteredRate({{2, 10}, {8, 10}});
  EXPECT_NEAR(r.deff, 7.2, 1e-12);
  // Its excess scaled by (t_1 / z)^2, t_1 = 12.7062047361747 (the 97.5 %
  // point of Student's t with 1 degree of freedom).
  const double adj = 1 + 6.2 * (12.7062047361747 / kZ95) * (12.7062047361747 / kZ95);
  const Interval w = WilsonAt(0.5, 20 / adj);
  EXPECT_NEAR(r.low, w.low, 1e-9);
  EXPECT_NEAR(r.high, w.high, 1e-9);
  EXPECT_TRUE(r.few_clusters);
}

TEST(StudentTQuantile, PublishedValues) {
  // Student's t table, two-sided 95 %: 12.706 (1), 2.365 (7), 2.042 (30);
  // 99.9 %: 636.62 (1), 5.408 (7).
  EXPECT_NEAR(StudentTQuantile(1, 0.95), 12.7062, 1e-4);
  EXPECT_NEAR(StudentTQuantile(7, 0.95), 2.3646, 1e-4);
  EXPECT_NEAR(StudentTQuantile(30, 0.95), 2.0423, 1e-4);
  EXPECT_NEAR(StudentTQuantile(1, 0.999), 636.619, 1e-2);
  EXPECT_NEAR(StudentTQuantile(7, 0.999), 5.4079, 1e-3);
  EXPECT_NEAR(NormalLevel(kZ95), 0.95, 1e-15);
  EXPECT_NEAR(NormalLevel(kZ999), 0.999, 1e-15);
}

// Issue 41's influence run: Wilson's interval is about ten times too narrow
// (0.146 [0.135, 0.158], the theory 0.190 flagged outside); the clustered one
// is as wide as a bootstrap over the HVs and holds the theory.
TEST(ClusteredRate, InfluenceRunIsAsWideAsTheBootstrapOverHvs) {
  const std::vector<ClusterCount> c = Influence();
  const RateInterval r = ClusteredRate(c);
  const Interval w = Wilson(542, 8 * 464);  // 542: the sum of kInfluenceDc
  const Interval boot = BootstrapOverHvs(c, 20000, 41);
  EXPECT_NEAR(r.rate, 542.0 / 3712.0, 1e-15);
  EXPECT_NEAR(boot.low, 0.068, 0.01);   // the reader's [0.068, 0.229]
  EXPECT_NEAR(boot.high, 0.229, 0.01);
  EXPECT_GE(r.high - r.low, 0.6 * (boot.high - boot.low));
  EXPECT_GT(r.high - r.low, 3 * (w.high - w.low));  // where the two differ
  EXPECT_LT(r.low, 0.190);
  EXPECT_GT(r.high, 0.190);
  EXPECT_LT(w.high, 0.190);  // Wilson alone flags the theory as outside
  EXPECT_GT(r.deff, 30);
  EXPECT_EQ(r.clusters, 8);
}

// The coverage of a nominal 95 % interval, measured where the true rate is
// known: G HVs of `per` encounters each, each HV's own rate drawn from
// Beta(a, b) (mean a / (a + b)); b = 0: every HV at the rate a.
struct Coverage {
  double clustered = 0, wilson = 0;
};
Coverage Simulate(int hvs, int per, double a, double b, int reps, unsigned seed) {
  std::mt19937_64 rng(seed);
  const double truth = b > 0 ? a / (a + b) : a;
  std::gamma_distribution<double> ga(b > 0 ? a : 1, 1), gb(b > 0 ? b : 1, 1);
  Coverage c;
  for (int k = 0; k < reps; ++k) {
    std::vector<ClusterCount> clusters;
    double y = 0;
    for (int h = 0; h < hvs; ++h) {
      double p = truth;
      if (b > 0) {
        const double x = ga(rng), z = gb(rng);
        p = x / (x + z);
      }
      std::binomial_distribution<int> draw(per, p);
      const int s = draw(rng);
      clusters.push_back({static_cast<double>(s), static_cast<double>(per)});
      y += s;
    }
    const RateInterval r = ClusteredRate(clusters);
    const Interval w = Wilson(static_cast<long>(y), static_cast<long>(hvs) * per);
    c.clustered += r.low <= truth && truth <= r.high;
    c.wilson += w.low <= truth && truth <= w.high;
  }
  c.clustered /= reps;
  c.wilson /= reps;
  return c;
}

// 2,000 replications: a coverage's Monte Carlo standard error is about 0.005.
TEST(ClusteredRateCoverage, HvsThatDifferAreCoveredWhereWilsonIsNot) {
  // HV rates spread as Beta(1.5, 6) (mean 0.2, SD 0.14), 30 HVs of 50
  // encounters: the clustered interval covers at its nominal 95 %, Wilson's
  // (the encounters taken as independent) in well under two cases of three.
  const Coverage many = Simulate(30, 50, 1.5, 6, 2000, 1);
  EXPECT_GE(many.clustered, 0.93);
  EXPECT_LE(many.clustered, 0.97);
  EXPECT_LT(many.wilson, 0.7);
  // 8 HVs of 100 (an influence run's size): the spread is estimated from 8
  // values, and the t correction brings the coverage near the nominal.
  const Coverage few = Simulate(8, 100, 1.5, 6, 2000, 2);
  EXPECT_GE(few.clustered, 0.91);
  EXPECT_LT(few.wilson, 0.6);
}

TEST(ClusteredRateCoverage, IndependentEncountersKeepWilsonsCoverage) {
  // Every HV at the same rate (design effect 1): the clustered interval
  // covers as Wilson's does and is hardly wider.
  const Coverage same = Simulate(8, 60, 0.375, 0, 2000, 3);
  EXPECT_GE(same.clustered, 0.93);
  EXPECT_LE(same.clustered, 0.98);
  EXPECT_NEAR(same.clustered, same.wilson, 0.03);
}

// The same run as the printout shows it: the theory inside the clustered
// interval is not marked '!', and the interval and design effect are those
// of ClusteredRate; summary.json reports the same.
PolicyRun InfluenceRun() {
  PolicyRun r;
  r.policy = "ta_ebp";
  r.theory.dc_rate = 0.190;
  r.theory.collision_rate = 0;
  for (std::size_t h = 0; h < kInfluenceDc.size(); ++h)
    for (int k = 0; k < static_cast<int>(kInfluenceN); ++k) {
      EncounterRecord e;
      e.time = k;
      e.hv = "hv" + std::to_string(h);
      e.av = "av0";
      e.hv_dc = k < kInfluenceDc[h];
      r.encounters.push_back(e);
    }
  return r;
}

TEST(ClusteredRate, TableMarksTheTheoryOnlyOutsideTheClusteredInterval) {
  PolicyRun r = InfluenceRun();
  const RateInterval dc = RunRateInterval(r, "dc_rate");
  const RateInterval direct = ClusteredRate(Influence());
  EXPECT_EQ(dc.low, direct.low);
  EXPECT_EQ(dc.high, direct.high);
  std::ostringstream table;
  PrintTable(table, {r});
  EXPECT_THAT(table.str(), ::testing::HasSubstr("th 0.190"));
  EXPECT_THAT(table.str(), ::testing::Not(::testing::HasSubstr("!")));
  EXPECT_THAT(table.str(), ::testing::HasSubstr("(8 HVs)"));
  // Far outside (0.5): marked.
  r.theory.dc_rate = 0.5;
  std::ostringstream outside;
  PrintTable(outside, {r});
  EXPECT_THAT(outside.str(), ::testing::HasSubstr("th 0.500 !"));
  // summary.json: the same interval, its design effect and clusters.
  Provenance p;
  p.config_json = "{}";
  const std::string json = SummaryJson({r}, p);
  EXPECT_THAT(json, ::testing::HasSubstr("\"dc_rate_clusters\": 8"));
  EXPECT_THAT(json, ::testing::HasSubstr("\"dc_rate_deff\": "));
}

TEST(PooledRate, OneRunIsItsOwnClusteredRate) {
  const RateInterval one = ClusteredRate(Influence());
  const RateInterval pooled = PooledRate({{542, 3712, one.deff, one.clusters}});
  EXPECT_NEAR(pooled.low, one.low, 1e-12);
  EXPECT_NEAR(pooled.high, one.high, 1e-12);
  EXPECT_NEAR(pooled.deff, one.deff, 1e-9);
  EXPECT_EQ(pooled.clusters, 8);
}

TEST(PooledRate, RunsThatDisagreeWidenItAndSaySo) {
  // Two runs each internally binomial (design effect 1, 10 HVs) but at rates
  // 0.1 and 0.5: the runs' spread is the larger level, estimated from 2
  // runs: few clusters, and wider than the HVs' level alone.
  const RateInterval r = PooledRate({{20, 200, 1.0, 10}, {100, 200, 1.0, 10}});
  EXPECT_EQ(r.clusters, 2);
  EXPECT_TRUE(r.few_clusters);
  EXPECT_GT(r.deff, 10);
  const Interval w = Wilson(120, 400);
  EXPECT_GT(r.high - r.low, 5 * (w.high - w.low));
  // Runs that agree: the HVs' level, 20 HVs.
  const RateInterval agree = PooledRate({{20, 200, 1.0, 10}, {21, 200, 1.0, 10}});
  EXPECT_EQ(agree.clusters, 20);
  EXPECT_FALSE(agree.few_clusters);
  EXPECT_NEAR(agree.deff, 1.0, 1e-3);
}

}  // namespace
}  // namespace taebp
