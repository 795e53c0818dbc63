// SUMO runs beyond the paper (dynamic trust, perception noise, learned trust,
// population_mean) through the runner, as `taebp run` does them: the paper's
// results unchanged, each capability reducing to the paper with static known
// trust and no noise, the measured rates against the exact theory (99.9%
// Wilson intervals), the dynamic trust against its mean-field path and fixed
// point, the learner's failures against its posterior, and determinism.
#include "taebp/config/config.h"
#include "taebp/report/clustered.h"
#include "taebp/report/report.h"
#include "taebp/report/sample_spool.h"
#include "taebp/runner/runner.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace taebp {
namespace {

using test::TempDir;

const std::string kSource = TAEBP_SOURCE_DIR;
const std::string kPaper = kSource + "/configs/paper.yaml";
std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// What a run writes: its files, and those copied beside them that taebp
// assembled (the time series, streamed to disk during the run).
std::vector<std::pair<std::string, std::string>> WrittenFiles(const ExperimentResult& r) {
  std::vector<std::pair<std::string, std::string>> files = r.Files();
  for (const auto& [name, path] : r.sample_files) files.emplace_back(name, ReadText(path));
  return files;
}

// The paper's columns of encounters.csv for one policy's rows, with the policy
// cell dropped (to compare runs of different policy names).
std::vector<std::string> PaperRows(const PolicyRun& run) {
  PolicyRun copy = run;
  copy.beyond.on = false;
  std::istringstream in(EncountersCsv({copy}));
  std::vector<std::string> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) rows.push_back(line.substr(line.find(',')));
  return rows;
}

// ------------------------------------------------------------------ the paper

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Beyond, PaperEncountersAreByteIdenticalToThoseBeforeTheBeyondFeatures) {
  // tests/data/paper_encounters.csv is `taebp run configs/paper.yaml`'s
  // encounters.csv from the revision before the beyond-the-paper code
  // (HvPopulation) existed, regenerated when SUMO came to decide right of way
  // (the controller intercepting AV-HV encounters only). If the controller's behaviour changes on purpose
  // (e.g. junction logic), regenerate it with:
  //   build/taebp run configs/paper.yaml --out /tmp/p && cp /tmp/p/encounters.csv tests/data/paper_encounters.csv
  const ExperimentResult r = RunExperiment(kPaper, {});
  EXPECT_EQ(EncountersCsv(r.runs), ReadText(kSource + "/tests/data/paper_encounters.csv"));
  for (const PolicyRun& p : r.runs) EXPECT_FALSE(p.beyond.on);
  std::vector<std::string> names;
  for (const auto& [name, text] : r.Files()) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"summary.json", "encounters.csv", "junctions.csv",
                                             "collisions.csv", "config.yaml", "timing.json"}));
}

TEST(Beyond, EachCapabilityReducesToThePaperWithStaticKnownTrustAndNoNoise) {
  // Trust dynamics with zero weights (static), noise of kind none, the
  // population_mean design for a population of one trust, and the learner
  // whose prior is that trust (it knows it): every one is TA-EBP, so SUMO
  // runs the same encounters on the same seed.
  const std::vector<std::string> common = {"scenario.duration=1200", "scenario.seed=4"};
  std::vector<std::string> beyond = common;
  beyond.insert(beyond.end(),
                {"policies=[ta_ebp, population_mean, ta_ebp_learned]",
                 "model.trust_dynamics={success_weight: 0, failure_weight: 0, forgetting: 0}",
                 "model.noise={kind: none}"});
  std::vector<std::string> plain = common;
  plain.push_back("policies=[ta_ebp]");
  const ExperimentResult paper = RunExperiment(kPaper, plain);
  const ExperimentResult more = RunExperiment(kPaper, beyond);
  const std::vector<std::string> want = PaperRows(paper.runs.front());
  ASSERT_GT(want.size(), 100u);
  for (const PolicyRun& p : more.runs) {
    SCOPED_TRACE(p.policy);
    EXPECT_TRUE(p.beyond.on);
    EXPECT_EQ(PaperRows(p), want);
    EXPECT_EQ(p.theory.dc_rate, paper.runs.front().theory.dc_rate);
    for (const EncounterRecord& e : p.encounters) {
      EXPECT_EQ(e.beyond.regret, 0.0);
      EXPECT_EQ(e.beyond.trust_after, 0.6);
    }
  }
}

// ------------------------------------------------------------------ noise

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Beyond, NoiseAwareDesignKeepsCollisionsWithinDeltaLambdaThePapersDoesNot) {
  std::map<std::string, PolicyRun> runs;
  for (const char* design : {"aware", "paper"}) {
    const ExperimentResult r = RunExperiment(
        kPaper, {"scenario.duration=14400", "scenario.seed=7", "policies=[ta_ebp]",
                 std::string("model.noise={kind: gaussian, scale: 0.1, delta: 0.01, design: ") +
                     design + "}"});
    runs[design] = r.runs.front();
  }
  for (const auto& [design, p] : runs) {
    SCOPED_TRACE(design);
    const long n = static_cast<long>(p.encounters.size());
    ASSERT_GT(n, 1000);
    long dc = 0, collisions = 0, noisy = 0;
    for (const EncounterRecord& e : p.encounters) {
      dc += e.hv_dc;
      collisions += e.collision;
      // The noise is on the reading, never on the command: SUMO realised the nudge.
      if (e.commanded > 0) {
        EXPECT_GE(e.observed, e.commanded - 1e-9);
        EXPECT_LE(e.observed, e.commanded + kNudgeTolerance);
      }
      noisy += e.beyond.reading != std::clamp(e.observed, 0.0, 2.0);
    }
    EXPECT_GT(noisy, n / 2);
    EXPECT_EQ(p.nudges_unrealised, 0);
    // The exact theory over the noise inside the 99.9% intervals (clustered by HV).
    const RateInterval ci_c = RunRateInterval(p, "collision_rate", kZ999);
    const RateInterval ci_d = RunRateInterval(p, "dc_rate", kZ999);
    EXPECT_LE(ci_d.low, p.theory.dc_rate);
    EXPECT_GE(ci_d.high, p.theory.dc_rate);
    EXPECT_LE(ci_c.low, p.theory.collision_rate);
    EXPECT_GE(ci_c.high, p.theory.collision_rate);
    if (design == "aware") {
      EXPECT_NEAR(p.theory.collision_rate, 0.01 * 0.2, 1e-8);
      EXPECT_LE(ci_c.low, 0.01 * 0.2);  // collisions <= delta lambda within the interval
      EXPECT_EQ(p.beyond.noise_status, "ok");
    } else {
      EXPECT_NEAR(p.theory.collision_rate, 0.1, 1e-6);  // the paper's s* read low half the time
      EXPECT_GT(ci_c.low, 0.01 * 0.2 * 10);
    }
  }
}

// ------------------------------------------------------------------ dynamic trust

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Beyond, DynamicTrustFollowsItsMeanFieldToTheFixedPoint) {
  const ExperimentResult r = RunExperiment(
      kSource + "/configs/dynamic_trust.yaml",
      {"scenario.duration=14400", "scenario.seed=3", "policies=[no_trust, ta_ebp]"});
  // The fixed points of docs/beyond/derivations.md at the paper's point (w_s = w_f,
  // rho = 0): No Trust 1/2, TA-EBP tracking trust the root of
  // theta^2 + 0.8 theta - 1.2.
  const std::map<std::string, double> fixed = {{"no_trust", 0.5},
                                               {"ta_ebp", (-0.8 + std::sqrt(5.44)) / 2}};
  for (const PolicyRun& p : r.runs) {
    SCOPED_TRACE(p.policy);
    const BeyondRun& b = p.beyond;
    ASSERT_TRUE(b.long_run);
    EXPECT_NEAR(b.expected_long_run_mean, fixed.at(p.policy), 1e-9);
    // Each HV's mean is (alpha0 + sum q) / (strength + n): its deviation from
    // the mean-field path is a sum of n bounded martingale steps over
    // (strength + n); over the 8 HVs, within 4 standard deviations (q in [0, 1]).
    const double hvs = static_cast<double>(b.hvs);
    const double n = static_cast<double>(p.encounters.size()) / hvs;
    const double sd = std::sqrt(n / 4.0) / (10.0 + n) / std::sqrt(hvs);
    EXPECT_NEAR(b.final_mean_trust, b.final_mean_field, 4 * sd) << n << " encounters per HV";
    // It approaches the fixed point: from 0.6 to within a sixth of the way.
    EXPECT_LT(std::abs(b.final_mean_trust - fixed.at(p.policy)),
              std::abs(0.6 - fixed.at(p.policy)) / 6 + 4 * sd);
    EXPECT_LT(std::abs(b.final_mean_field - fixed.at(p.policy)),
              std::abs(0.6 - fixed.at(p.policy)) / 6);
    // The per-encounter theory (given each trust state) inside the 99.9% interval,
    // clustered by HV: each HV's trust walks on its own.
    const RateInterval ci_d = RunRateInterval(p, "dc_rate", kZ999);
    const RateInterval ci_c = RunRateInterval(p, "collision_rate", kZ999);
    EXPECT_LE(ci_d.low, p.theory.dc_rate);
    EXPECT_GE(ci_d.high, p.theory.dc_rate);
    EXPECT_LE(ci_c.low, p.theory.collision_rate);
    EXPECT_GE(ci_c.high, p.theory.collision_rate);
    // The first time-series row (as timeseries.csv holds it): the drawn mean trust.
    ASSERT_NE(b.samples, nullptr);
    ASSERT_GT(b.samples->TimeRows(), 0);
    const std::string rows = b.samples->TimeRowsText();
    const std::vector<std::string> first = SplitCsvRow(rows.substr(0, rows.find('\n')));
    const std::vector<std::string> cols = TimeseriesCsvColumns();
    const auto at = std::find(cols.begin(), cols.end(), "mean_trust") - cols.begin();
    ASSERT_LT(static_cast<std::size_t>(at), first.size());
    EXPECT_EQ(first[static_cast<std::size_t>(at)], "0.6");
  }
}

// ------------------------------------------------------------------ learned trust

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Beyond, LearnedTrustIsSafeAndItsFailuresMatchItsPosterior) {
  const ExperimentResult r =
      RunExperiment(kSource + "/configs/learned_trust.yaml",
                    {"scenario.duration=10800", "scenario.seed=2", "policies=[ta_ebp_learned]"});
  const PolicyRun& p = r.runs.front();
  long collisions = 0, dc = 0, failures = 0;
  double expected = 0;
  for (const EncounterRecord& e : p.encounters) {
    collisions += e.collision;
    dc += e.hv_dc;
    if (e.commanded > 0) {
      failures += !e.hv_dc;
      expected += e.beyond.failure_probability;
    }
    EXPECT_LE(e.beyond.risk_level, 0.01);
    EXPECT_NE(e.beyond.observation, "contradiction");
  }
  const long n = static_cast<long>(p.encounters.size());
  ASSERT_GT(n, 1000);
  EXPECT_LE(static_cast<double>(collisions) / n, 0.01);
  EXPECT_NEAR(failures, expected, 4 * std::sqrt(expected) + 1);
  // The per-encounter theory (the design chosen, the HV's trust) inside the 99.9% interval,
  // clustered by HV (the fleet's belief about each HV is its own).
  const RateInterval ci = RunRateInterval(p, "dc_rate", kZ999);
  EXPECT_LE(ci.low, p.theory.dc_rate);
  EXPECT_GE(ci.high, p.theory.dc_rate);
  EXPECT_EQ(p.beyond.hvs_met, 8);
  EXPECT_EQ(p.beyond.contradictions, 0);
}

// ------------------------------------------------------------------ determinism

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Beyond, SameConfigAndSeedGiveIdenticalFiles) {
  TempDir dir;
  const std::string cfg = dir.Write(
      "all.yaml",
      "scenario: {duration: 1800, seed: 9}\n"
      "model:\n"
      "  trust: {dist: beta, alpha: 4, beta: 2}\n"
      "  trust_dynamics: {strength: 8, failure_weight: 2, forgetting: 0.01}\n"
      "  noise: {kind: uniform, scale: 0.05, bias: 0.01}\n"
      "  learning: {delta: 0.02}\n"
      "outputs: {interval: 120}\n"
      "policies: [no_trust, ta_ebp, population_mean, ta_ebp_learned]\n");
  const ExperimentResult a = RunExperiment(cfg, {});
  const ExperimentResult b = RunExperiment(cfg, {});
  const auto fa = WrittenFiles(a), fb = WrittenFiles(b);
  ASSERT_EQ(fa.size(), fb.size());
  std::vector<std::string> names;
  for (const auto& f : fa) names.push_back(f.first);
  // The run's own files, + timeseries.csv (outputs.interval) and hv_trust.csv (trust dynamics).
  EXPECT_THAT(names, ::testing::UnorderedElementsAre("summary.json", "encounters.csv",
                                                     "junctions.csv", "collisions.csv",
                                                     "config.yaml", "timing.json",
                                                     "timeseries.csv", "hv_trust.csv"));
  for (std::size_t i = 0; i < fa.size(); ++i) {
    if (fa[i].first == "timing.json") continue;  // the only wall-clock output
    EXPECT_EQ(fa[i].second, fb[i].second) << fa[i].first;
  }
  EXPECT_EQ(fa[0].first, "summary.json");
  EXPECT_EQ(fa[0].second, fb[0].second);  // no wall time inside
  // Every CSV has its header first and the same number of cells in every row.
  for (const auto& [name, text] : fa) {
    if (name.size() < 4 || name.substr(name.size() - 4) != ".csv") continue;
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    const auto cells = [](const std::string& l) { return std::count(l.begin(), l.end(), ','); };
    const long header = cells(line);
    long rows = 0;
    while (std::getline(in, line)) {
      EXPECT_EQ(cells(line), header) << name << ": " << line;
      ++rows;
    }
    EXPECT_GT(rows, 0) << name;
  }
}

}  // namespace
}  // namespace taebp
