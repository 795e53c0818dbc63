// Heterogeneous trust and penetration: TrustSpec, its YAML form, the expected
// theory over a trust distribution (against an independent integration), the
// per-HV draws in SUMO, and tracks that grow to fit the vehicles.
#include "taebp/report/clustered.h"
#include "taebp/config/config.h"
#include "taebp/controller/policy_run.h"
#include "taebp/report/report.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/outcomes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace taebp {
namespace {

using ::testing::HasSubstr;
namespace per = persuasion;

const std::string kPaper = std::string(TAEBP_SOURCE_DIR) + "/configs/paper.yaml";

std::string ErrorOf(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  try {
    ParseExperimentConfig(yaml, "test.yaml", overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(TrustSpec, UniformMeanAndQuantile) {
  TrustSpec t;
  t.dist = TrustDist::kUniform;
  t.low = 0.2;
  t.high = 0.8;
  EXPECT_DOUBLE_EQ(t.Mean(), 0.5);
  EXPECT_DOUBLE_EQ(t.Quantile(0.25), 0.35);
  EXPECT_DOUBLE_EQ(t.Quantile(0.0), 0.2);
}

TEST(TrustSpec, BetaQuantileInvertsTheCdfAndMeanMatchesIntegration) {
  TrustSpec t;
  t.dist = TrustDist::kBeta;
  t.alpha = 2;
  t.beta = 5;
  EXPECT_DOUBLE_EQ(t.Mean(), 2.0 / 7.0);
  // Beta(2,5) CDF in closed form: I_x(2,5) = 1 - (1-x)^5 (1 + 5x).
  for (double q : {0.05, 0.3, 0.5, 0.9}) {
    const double x = t.Quantile(q);
    EXPECT_NEAR(1 - std::pow(1 - x, 5) * (1 + 5 * x), q, 1e-10) << q;
  }
  // Mean of the quantile midpoint rule converges to the mean.
  double m = 0;
  const int n = 20000;
  for (int j = 0; j < n; ++j) m += t.Quantile((j + 0.5) / n) / n;
  EXPECT_NEAR(m, 2.0 / 7.0, 1e-5);
}

TEST(TrustSpec, DiscreteWeightsAndQuantile) {
  TrustSpec t;
  t.dist = TrustDist::kDiscrete;
  t.values = {0.2, 0.8};
  t.weights = {1, 3};
  EXPECT_DOUBLE_EQ(t.Mean(), 0.65);
  EXPECT_DOUBLE_EQ(t.Quantile(0.24), 0.2);
  EXPECT_DOUBLE_EQ(t.Quantile(0.26), 0.8);
}

TEST(TrustYaml, NumberDistributionsAndRoundTrip) {
  const ExperimentConfig a = ParseExperimentConfig("model: {trust: 0.3}", "t.yaml");
  EXPECT_TRUE(a.model.trust.IsFixed());
  EXPECT_DOUBLE_EQ(a.model.trust.value, 0.3);
  const ExperimentConfig b =
      ParseExperimentConfig("model: {trust: {dist: beta, alpha: 2, beta: 5}}", "t.yaml");
  EXPECT_EQ(b.model.trust.dist, TrustDist::kBeta);
  EXPECT_DOUBLE_EQ(b.model.trust.beta, 5);
  const ExperimentConfig c = ParseExperimentConfig(
      "model: {trust: {dist: discrete, values: [0.2, 0.8], weights: [1, 3]}}", "t.yaml");
  EXPECT_EQ(c.model.trust.values.size(), 2u);
  // One schema for load and save: the YAML we write reads back identically.
  for (const ExperimentConfig& cfg : {a, b, c}) {
    EXPECT_EQ(ToJson(ParseExperimentConfig(ToYaml(cfg), "roundtrip")), ToJson(cfg));
  }
}

TEST(TrustYaml, ErrorsNameTheKeyAndValue) {
  EXPECT_THAT(ErrorOf("model: {trust: {dist: normal, mean: 0.5}}"),
              HasSubstr("model.trust.dist"));
  EXPECT_THAT(ErrorOf("model: {trust: {dist: uniform, low: 0.2}}"),
              HasSubstr("model.trust.high' is missing"));
  EXPECT_THAT(ErrorOf("model: {trust: {dist: beta, alpha: 2, beta: 3, low: 0}}"),
              HasSubstr("unknown key 'model.trust.low' for dist beta"));
  EXPECT_THAT(ErrorOf("model: {trust: {dist: uniform, low: 0.9, high: 0.2}}"),
              HasSubstr("model.trust.low = 0.9 is above model.trust.high = 0.2"));
  EXPECT_THAT(ErrorOf("model: {trust: {dist: uniform, low: 0.2, high: 1.3}}"),
              HasSubstr("model.trust.high = 1.3 is outside [0, 1]"));
  EXPECT_THAT(ErrorOf("model: {trust: {dist: discrete, values: [0.2], weights: [1, 2]}}"),
              HasSubstr("model.trust.weights has 2 entries"));
  EXPECT_THAT(ErrorOf("model: {trust: [0.5]}"), HasSubstr("model.trust"));
  EXPECT_THAT(ErrorOf("model: {trust_knowledge: assumed}"),
              HasSubstr("needs model.assumed_trust"));
  EXPECT_THAT(ErrorOf("model: {trust_knowledge: psychic}"),
              HasSubstr("model.trust_knowledge = 'psychic'"));
  EXPECT_THAT(ErrorOf("{}", {"model.trust={dist: beta, alpha: 2}"}),
              HasSubstr("--set model.trust={dist: beta, alpha: 2}"));
}

TEST(ExpectedOutcome, FixedTrustIsThePrediction) {
  ModelConfig m;
  const per::AvHvParams params{m.prior_go, m.collision_penalty};
  per::LinearLikelihood lik(2.0);
  for (per::Policy p : {per::Policy::kNoEbp, per::Policy::kNoTrust, per::Policy::kTaEbp,
                        per::Policy::kFullReveal}) {
    const auto e = ExpectedOutcome(m, p);
    const auto d = per::PredictOutcome(p, params, 0.6, lik);
    EXPECT_DOUBLE_EQ(e.dc_rate, d.dc_rate);
    EXPECT_DOUBLE_EQ(e.collision_rate, d.collision_rate);
  }
}

// TA-EBP with exact knowledge: DC(theta) = lambda + (1-lambda) b(theta) for
// theta >= theta*, else 0; integrate eq:b over Uniform(low, high) with Simpson's
// rule on [theta*, high] (an independent method from the quantile rule).
TEST(ExpectedOutcome, UniformTrustMatchesSimpsonIntegralOfEqB) {
  ModelConfig m;
  m.trust.dist = TrustDist::kUniform;
  m.trust.low = 0.1;
  m.trust.high = 0.9;
  const double lambda = m.prior_go, p_star = 0.4, theta_star = 0.25;
  auto dc = [&](double t) {
    const double b = lambda * (t - p_star + (1 - t) * lambda) /
                     ((1 - lambda) * (p_star - (1 - t) * lambda));
    return lambda + (1 - lambda) * std::min(1.0, b);
  };
  const int n = 2000;  // even
  const double a = theta_star, bnd = m.trust.high, h = (bnd - a) / n;
  double s = dc(a) + dc(bnd);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * dc(a + i * h);
  const double expected = s * h / 3 / (m.trust.high - m.trust.low);
  const auto e = ExpectedOutcome(m, per::Policy::kTaEbp, 20000);
  EXPECT_NEAR(e.dc_rate, expected, 2e-4);
  EXPECT_EQ(e.collision_rate, 0.0);
  // No Trust: the HV is persuaded by s_hat = s*(1) only when theta >= 1, so it
  // always drives recklessly: collision rate lambda, DC 0.
  const auto nt = ExpectedOutcome(m, per::Policy::kNoTrust);
  EXPECT_NEAR(nt.collision_rate, lambda, 1e-9);
  EXPECT_NEAR(nt.dc_rate, 0.0, 1e-12);
}

// One design for the population mean: HVs below the trust the mean design
// needs drive recklessly while the AV goes.
TEST(ExpectedOutcome, PopulationMeanDesignCollidesWithLowTrustHvs) {
  ModelConfig m;
  m.trust.dist = TrustDist::kDiscrete;
  m.trust.values = {0.3, 0.9};
  m.trust_knowledge = TrustKnowledge::kPopulationMean;  // mean 0.6
  const per::AvHvParams params{m.prior_go, m.collision_penalty};
  per::LinearLikelihood lik(2.0);
  const auto scheme = per::CommitScheme(per::Policy::kTaEbp, params, 0.6, lik);
  const auto low = per::PredictOutcome(scheme, params, 0.3, lik);
  const auto high = per::PredictOutcome(scheme, params, 0.9, lik);
  EXPECT_GT(low.collision_rate, 0.0);
  EXPECT_EQ(high.collision_rate, 0.0);
  const auto e = ExpectedOutcome(m, per::Policy::kTaEbp);
  EXPECT_DOUBLE_EQ(e.collision_rate, 0.5 * low.collision_rate + 0.5 * high.collision_rate);
  EXPECT_DOUBLE_EQ(e.dc_rate, 0.5 * low.dc_rate + 0.5 * high.dc_rate);
}

// In SUMO: each HV draws its own theta (deterministically from the seed), the
// posteriors use that HV's theta, and the measured rates agree with the mean
// prediction for the HVs actually met (99.9% Wilson interval).
TEST(HeterogeneousRun, DrawsPerHvTrustAndAgreesWithTheoryGivenHvs) {
  const ExperimentConfig cfg = LoadExperimentConfig(
      kPaper, {"model.trust={dist: uniform, low: 0.1, high: 0.9}", "scenario.duration=900",
               "policies=[ta_ebp]"});
  const Scenario files = BuildScenario(cfg, "");
  const PolicyRun run = RunPolicy(cfg, "ta_ebp", files);
  ASSERT_EQ(run.hv_trust.size(), 8u);
  double lo = 1, hi = 0;
  for (double t : run.hv_trust) {
    lo = std::min(lo, t);
    hi = std::max(hi, t);
    EXPECT_GE(t, 0.1);
    EXPECT_LE(t, 0.9);
  }
  EXPECT_LT(lo, hi);  // they differ
  const PolicyRun again = RunPolicy(cfg, "ta_ebp", files);
  EXPECT_EQ(run.hv_trust, again.hv_trust);

  ASSERT_GT(run.encounters.size(), 80u);
  const per::AvHvParams params{cfg.model.prior_go, cfg.model.collision_penalty};
  per::LinearLikelihood lik(2.0);
  long dc = 0, col = 0;
  double theory_dc = 0;
  for (const EncounterRecord& e : run.encounters) {
    // Exact knowledge: the AV's scheme for this HV is TA-EBP designed at its trust.
    const per::CommittedScheme scheme = per::CommitScheme(per::Policy::kTaEbp, params, e.hv_trust, lik);
    EXPECT_NEAR(e.posterior,
                per::HvPosteriorGo(scheme, params, e.hv_trust, lik, std::min(e.observed, 2.0)), 1e-12);
    dc += e.hv_dc;
    col += e.collision;
    theory_dc += e.theory_dc;
  }
  EXPECT_EQ(col, 0);  // exact knowledge: never a collision
  const long n = static_cast<long>(run.encounters.size());
  theory_dc /= n;
  // The 99.9% interval around the measured DC rate, clustered by HV (each
  // HV's trust is drawn once: its encounters share it).
  const RateInterval ci = RunRateInterval(run, "dc_rate", kZ999);
  EXPECT_EQ(ci.rate, static_cast<double>(dc) / n);
  EXPECT_GE(theory_dc, ci.low);
  EXPECT_LE(theory_dc, ci.high);
}

TEST(Penetration, TrackGrowsToFitAndSaysSo) {
  const ExperimentConfig cfg = LoadExperimentConfig(
      kPaper, {"scenario.avs=14", "scenario.hvs=14", "scenario.duration=240", "policies=[ta_ebp]"});
  EXPECT_GT(RequiredLoopLength(cfg.scenario), 80.0);
  const Scenario files = BuildScenario(cfg, "");
  EXPECT_DOUBLE_EQ(files.loop_length, RequiredLoopLength(cfg.scenario));
  ASSERT_EQ(files.notes.size(), 1u);
  EXPECT_THAT(files.notes[0], HasSubstr("grown"));
  const PolicyRun run = RunPolicy(cfg, "ta_ebp", files);
  EXPECT_EQ(run.teleports, 0);
  EXPECT_GT(run.crossings_av + run.crossings_hv, 28);
}

TEST(Penetration, TooManyVehiclesWithoutAutoLengthIsAClearError) {
  const ExperimentConfig cfg = LoadExperimentConfig(
      kPaper, {"scenario.avs=14", "scenario.hvs=14", "scenario.auto_length=false"});
  try {
    BuildScenario(cfg, "");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scenario.loop_length = 80"));
    EXPECT_THAT(e.what(), HasSubstr("28 vehicles"));
  }
}

TEST(Penetration, AllHvAndAllAvRunWithoutEncountersOrDeadlock) {
  for (const auto& [avs, hvs] : {std::pair{0, 16}, std::pair{16, 0}}) {
    const ExperimentConfig cfg = LoadExperimentConfig(
        kPaper, {"scenario.avs=" + std::to_string(avs), "scenario.hvs=" + std::to_string(hvs),
                 "scenario.duration=300"});
    const Scenario files = BuildScenario(cfg, "");
    const PolicyRun run = RunPolicy(cfg, "ta_ebp", files);
    EXPECT_TRUE(run.encounters.empty());
    EXPECT_EQ(run.teleports, 0);
    EXPECT_LT(run.longest_gap_without_crossing, 30.0);
    EXPECT_GT(run.crossings_av + run.crossings_hv, 50);
  }
}

TEST(Penetration, PaperTrackFitsSixteenVehiclesWithoutGrowth) {
  const ExperimentConfig cfg = LoadExperimentConfig(kPaper, {});
  EXPECT_LE(RequiredLoopLength(cfg.scenario), cfg.scenario.loop_length);
  const Scenario files = BuildScenario(cfg, "");
  EXPECT_TRUE(files.notes.empty()) << files.notes[0];
  EXPECT_DOUBLE_EQ(files.loop_length, 80.0);
}

// The required length is an estimate; this checks that vehicles are placed
// and keep flowing at exactly that length, from a few vehicles to many.
TEST(Penetration, RequiredLengthPlacesTheVehiclesAndTrafficFlows) {
  for (int n : {2, 12, 24, 40}) {
    const ExperimentConfig cfg = LoadExperimentConfig(
        kPaper, {"scenario.avs=" + std::to_string(n / 2),
                 "scenario.hvs=" + std::to_string(n - n / 2), "scenario.loop_length=10",
                 "scenario.duration=300", "policies=[no_trust]"});
    const Scenario files = BuildScenario(cfg, "");
    ASSERT_DOUBLE_EQ(files.loop_length, RequiredLoopLength(cfg.scenario)) << n << " vehicles";
    const PolicyRun run = RunPolicy(cfg, "no_trust", files);
    EXPECT_EQ(run.teleports, 0) << n << " vehicles";
    EXPECT_LT(run.longest_gap_without_crossing, 30.0) << n << " vehicles";
    // At least one crossing per vehicle-loop travelled at half the cruise speed.
    EXPECT_GT(run.crossings_av + run.crossings_hv,
              std::min(n, 2) * 300.0 * 2.0 / files.loop_length) << n << " vehicles";
  }
}

// Unbalanced mixes on the paper's 80 m track used to gridlock under TA-EBP
// and No Trust (a vehicle released into a full loop stopped in the junction
// while that loop's head waited for the junction). The keep-clear rule
// (release only into a loop with room) must keep every mix flowing.
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(Penetration, UnbalancedMixesOnThePaperTrackNeverGridlock) {
  for (int avs : {2, 6, 10, 14}) {
    for (const char* policy : {"no_trust", "ta_ebp"}) {
      for (int seed : {1, 2, 3}) {
        const ExperimentConfig cfg = LoadExperimentConfig(
            kPaper, {"scenario.avs=" + std::to_string(avs),
                     "scenario.hvs=" + std::to_string(16 - avs), "scenario.duration=900",
                     "scenario.seed=" + std::to_string(seed)});
        const Scenario files = BuildScenario(cfg, "");
        ASSERT_DOUBLE_EQ(files.loop_length, 80.0);
        const PolicyRun run = RunPolicy(cfg, policy, files);
        const std::string what = std::to_string(avs) + " AVs, " + policy + ", seed " +
                                 std::to_string(seed);
        EXPECT_LT(run.longest_gap_without_crossing, 30.0) << what;
        EXPECT_EQ(run.teleports, 0) << what;
        // Free flow crosses ~1000 times an hour; a gridlock stops at a handful.
        EXPECT_GT(run.crossings_av + run.crossings_hv, 100) << what;
      }
    }
  }
}

// A 40 m figure-8 with 8 vehicles gridlocked before the keep-clear rule
// (queues backed up through the centre; 2 crossings in 20 minutes). Given as a
// custom network (the built-in sizing would grow it), it must now flow.
TEST(Penetration, TightCustomNetworkFlowsWithTheKeepClearRule) {
  const std::string net = GeneratedFigure8(40.0, 3.0);
  const ExperimentConfig cfg = LoadExperimentConfig(
      kPaper, {"scenario.network=" + net, "scenario.duration=600",
               "scenario.avs=4", "scenario.hvs=4"});
  const Scenario files = BuildScenario(cfg, "");
  for (const char* policy : {"no_ebp", "ta_ebp"}) {
    const PolicyRun run = RunPolicy(cfg, policy, files);
    EXPECT_LT(run.longest_gap_without_crossing, 30.0);
    EXPECT_GT(run.crossings_av + run.crossings_hv, 100);  // 2 before the rule

    // The stall safety net: with a limit shorter than any wait it must stop
    // the run (stall_action: error) with an error naming the track, and
    // return what it measured up to the stall, the stall recorded.
    RunOptions strict;
    strict.stall_limit = 0.5;
    const PolicyRun stopped = RunPolicy(cfg, policy, files, strict);
    EXPECT_THAT(stopped.stall_error, HasSubstr("traffic stalled"));
    EXPECT_THAT(stopped.stall_error, HasSubstr("junction 'C'"));
    EXPECT_THAT(stopped.stall_error, HasSubstr("vehicles waiting"));
    ASSERT_EQ(stopped.stalls.size(), 1u);
    EXPECT_EQ(stopped.stalls[0].junction, "C");
    EXPECT_LE(stopped.stalls[0].since, stopped.stalls[0].detected);
    EXPECT_LT(stopped.simulated_seconds, cfg.scenario.duration);
  }
}

}  // namespace
}  // namespace taebp
