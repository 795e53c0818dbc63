// The rate intervals a run reports, clustered by HV (report/clustered.h,
// docs/metrics.md), on the run that showed Wilson's to be too narrow (issue
// 41): HVs who learn what a signal meant, each on its own walk. The reported
// DC interval is held against a bootstrap over the run's HVs computed here
// from encounters.csv (a second method), and the printed table marks the
// theory only where it lies outside.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "csv_support.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::ReadText;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;

TEST(ClusteredIntervals, TheInfluenceRunsDcIntervalIsAsWideAsABootstrapOverItsHvs) {
  TempDir tmp;
  const fs::path out = tmp.path() / "influence";
  const CliResult r = taebp::test::RunProgram(
      kCli, {"run", std::string(TAEBP_SOURCE_DIR) + "/configs/influence.yaml", "--set",
             "model.experience.design=paper", "--set", "policies=[ta_ebp]", "--set",
             "scenario.seed=41", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  // Each HV's DC choices and encounters.
  std::map<std::string, std::pair<double, double>> hvs;  // hv -> (dc, encounters)
  for (const auto& row : taebp::test::ReadCsvRows(out / "encounters.csv")) {
    auto& h = hvs[row.at("hv")];
    h.first += row.at("hv_action") == "DC";
    h.second += 1;
  }
  ASSERT_EQ(hvs.size(), 8u);
  std::vector<std::pair<double, double>> c;
  double y = 0, n = 0;
  for (const auto& [hv, h] : hvs) c.push_back(h), y += h.first, n += h.second;
  // The percentile bootstrap over the HVs.
  std::mt19937_64 rng(41);
  std::uniform_int_distribution<std::size_t> pick(0, c.size() - 1);
  std::vector<double> rates;
  for (int b = 0; b < 20000; ++b) {
    double by = 0, bn = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const auto& x = c[pick(rng)];
      by += x.first;
      bn += x.second;
    }
    rates.push_back(by / bn);
  }
  std::sort(rates.begin(), rates.end());
  const double boot_lo = rates[500], boot_hi = rates[19500];
  const nlohmann::json s = nlohmann::json::parse(ReadText(out / "summary.json"));
  const nlohmann::json& p = s["policies"]["ta_ebp"];
  const double lo = p["dc_rate_lo"].get<double>(), hi = p["dc_rate_hi"].get<double>();
  const double theory = p["theory_dc_rate"].get<double>();
  EXPECT_NEAR(p["dc_rate"].get<double>(), y / n, 1e-12);
  EXPECT_GE(hi - lo, 0.6 * (boot_hi - boot_lo)) << "[" << lo << ", " << hi << "] against the bootstrap's ["
                                                << boot_lo << ", " << boot_hi << "]";
  // The binomial interval over the encounters, as if independent (its normal
  // approximation, as wide as Wilson's at n = 3,712): far narrower.
  const double z = 1.959963984540054, pr = y / n;
  EXPECT_GT(hi - lo, 3 * 2 * z * std::sqrt(pr * (1 - pr) / n));
  EXPECT_GT(p["dc_rate_deff"].get<double>(), 10);
  EXPECT_EQ(p["dc_rate_clusters"].get<long>(), 8);
  // The theory inside the bootstrap's interval is not marked outside.
  ASSERT_GT(theory, boot_lo);
  ASSERT_LT(theory, boot_hi);
  std::istringstream table(r.out);
  bool dc_row = false;
  for (std::string line; std::getline(table, line);)
    if (line.rfind("DC Rate", 0) == 0) {
      dc_row = true;
      EXPECT_EQ(line.find('!'), std::string::npos) << line;
    }
  EXPECT_TRUE(dc_row) << r.out;
}

}  // namespace
