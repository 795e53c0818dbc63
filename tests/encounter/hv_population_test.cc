// HvPopulation: the HVs' trust, the fleet's beliefs and the noisy readings the
// controller asks for per encounter, driven here with made-up encounters (no
// SUMO). The paper's setting must be exactly the controller's old computation;
// each capability is checked against the persuasion library's closed forms,
// its own arithmetic, and binomial bands of many simulated readings.
#include "taebp/encounter/hv_population.h"
#include "taebp/config/policies.h"

#include "taebp/config/config.h"
#include "taebp/encounter/design.h"
#include "taebp/encounter/encounter.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/noise.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/trust_dynamics.h"
#include "taebp/report/report.h"
#include "taebp/report/sample_spool.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace taebp {
namespace {

namespace per = persuasion;
using per::Policy;

ExperimentConfig Config(const std::string& yaml) { return ParseExperimentConfig(yaml, "test.yaml"); }

// The spooled rows of timeseries.csv (or hv_trust.csv), each a map from the
// column's name to its cell, read back from the spool's files.
std::vector<std::map<std::string, std::string>> SpooledRows(const std::string& text,
                                                            const std::vector<std::string>& cols) {
  std::vector<std::map<std::string, std::string>> rows;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    const std::vector<std::string> cells = SplitCsvRow(text.substr(at, end - at));
    EXPECT_EQ(cells.size(), cols.size());
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size() && i < cols.size(); ++i) row[cols[i]] = cells[i];
    rows.push_back(row);
    at = end == std::string::npos ? text.size() : end + 1;
  }
  return rows;
}

void ExpectSameScheme(const per::CommittedScheme& a, const per::CommittedScheme& b) {
  EXPECT_EQ(a.av_may_go, b.av_may_go);
  EXPECT_EQ(a.nudge, b.nudge);
  EXPECT_EQ(a.a, b.a);
  EXPECT_EQ(a.b, b.b);
}

// One encounter as the controller runs it: Commit, the draw from the
// encounter stream, SUMO's realised displacement (the commanded nudge plus the
// controller's overshoot), Read, Finish.
struct Played {
  AvDraw draw;
  HvReading reading;
  EncounterRecord record;
};
Played Play(HvPopulation& pop, const std::string& av, const std::string& hv, std::mt19937_64& rng,
            double prior_go, bool collision_if_dr = true) {
  Played p;
  p.draw = DrawAv(pop.Commit(av, hv), prior_go, rng);
  const double observed = p.draw.nudge_distance > 0 ? p.draw.nudge_distance + 1e-6 : 0.0;
  p.reading = pop.Read(av, hv, observed);
  const bool collision = collision_if_dr && p.draw.goes_first && !p.reading.drives_if_clear;
  pop.Finish(av, hv, p.draw, p.reading, collision, true, &p.record);
  return p;
}

// ------------------------------------------------------------------ the paper

TEST(HvPopulation, PaperSettingIsTheControllersOwnComputation) {
  const per::LinearLikelihood model(2.0);
  const per::AvHvParams params{0.2, 3.0};
  for (const char* knowledge : {"exact", "population_mean", "assumed"}) {
    for (Policy policy : {Policy::kNoEbp, Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
      const ExperimentConfig c = Config(std::string("model: {trust: {dist: uniform, low: 0, high: 1}, "
                                                    "trust_knowledge: ") +
                                        knowledge + ", assumed_trust: 0.45}");
      HvPopulation pop(c, policy);
      EXPECT_FALSE(pop.Beyond());
      ExpectSameScheme(pop.PopulationScheme(),
                       per::CommitScheme(policy, params, DesignTrust(c.model, policy, 0.5), model));
      const per::PredictedOutcome expected = ExpectedOutcome(c.model, policy);
      EXPECT_EQ(pop.Theory().dc_rate, expected.dc_rate);
      EXPECT_EQ(pop.Theory().collision_rate, expected.collision_rate);
      for (double theta : {0.0, 0.1, 0.25, 0.6, 0.9, 1.0}) {
        const std::string hv = "hv" + std::to_string(theta);
        pop.Add(hv, theta);
        const per::CommittedScheme want =
            per::CommitScheme(policy, params, DesignTrust(c.model, policy, theta), model);
        ExpectSameScheme(pop.Commit("av", hv), want);
        for (double observed : {0.0, 0.5, 1.4545464545454543, 1.6410266410256411, 2.0, 2.0005}) {
          const HvReading got = pop.Read("av", hv, observed);
          const HvReading old = ReadNudge(want, params, theta, model, observed);
          EXPECT_EQ(got.observed, old.observed);
          EXPECT_EQ(got.posterior, old.posterior);
          EXPECT_EQ(got.drives_if_clear, old.drives_if_clear);
        }
        EncounterRecord r;
        AvDraw d;
        pop.Finish("av", hv, d, pop.Read("av", hv, 0.0), false, true, &r);
        const per::PredictedOutcome th = per::PredictOutcome(want, params, theta, model);
        EXPECT_EQ(r.hv_trust, theta);
        EXPECT_EQ(r.theory_dc, th.dc_rate);
        EXPECT_EQ(r.theory_collision, th.collision_rate);
      }
      const BeyondRun results = pop.Results(100.0);
      EXPECT_FALSE(results.on);
      EXPECT_EQ(results.samples, nullptr);
    }
  }
}

TEST(HvPopulation, PopulationMeanDesignsForTheMeanTrustOfThePopulation) {
  const per::LinearLikelihood model(2.0);
  const per::AvHvParams params{0.2, 3.0};
  const ExperimentConfig c = Config("model: {trust: {dist: beta, alpha: 4, beta: 2}}\n"
                                    "policies: [population_mean, ta_ebp]\n");
  HvPopulation pop(c, Policy::kPopulationMean);
  EXPECT_TRUE(pop.Beyond());
  const per::CommittedScheme mean_design = per::CommitScheme(Policy::kTaEbp, params, 4.0 / 6.0, model);
  ExpectSameScheme(pop.PopulationScheme(), mean_design);
  for (double theta : {0.3, 0.55, 0.95}) {
    pop.Add("h", theta);
    ExpectSameScheme(pop.Commit("a", "h"), mean_design);
    EncounterRecord r;
    AvDraw d;
    pop.Finish("a", "h", d, pop.Read("a", "h", 0.0), false, true, &r);
    EXPECT_DOUBLE_EQ(r.beyond.design_trust, 4.0 / 6.0);
    // The oracle designs for the HV's own trust; regret = DC lost + r x collisions.
    const per::PredictedOutcome mine = per::PredictOutcome(mean_design, params, theta, model);
    const per::PredictedOutcome oracle = per::PredictOutcome(Policy::kTaEbp, params, theta, model);
    EXPECT_DOUBLE_EQ(r.beyond.oracle_dc, oracle.dc_rate);
    EXPECT_NEAR(r.beyond.regret,
                per::ExpectedRegret(mean_design, params, theta, model).regret, 1e-15);
    EXPECT_NEAR(r.beyond.regret,
                oracle.dc_rate - mine.dc_rate + 3.0 * (mine.collision_rate - oracle.collision_rate),
                1e-15);
    pop.Remove("h");
  }
  // Below the mean the HV is not persuaded by the mean's nudge: collisions at rate lambda.
  pop.Add("low", 0.3);
  pop.Commit("a", "low");
  EncounterRecord r;
  AvDraw d;
  pop.Finish("a", "low", d, pop.Read("a", "low", 0.0), false, true, &r);
  EXPECT_DOUBLE_EQ(r.theory_collision, 0.2);
}

// ------------------------------------------------------------------ dynamic trust

TEST(HvPopulation, DynamicTrustWithZeroWeightsIsStaticTrustBitForBit) {
  const ExperimentConfig plain = Config("model: {trust: 0.6}");
  const ExperimentConfig zero = Config(
      "model: {trust: 0.6, trust_dynamics: {success_weight: 0, failure_weight: 0, forgetting: 0}}");
  for (Policy policy : {Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
    HvPopulation a(plain, policy), b(zero, policy);
    a.Add("h", 0.6);
    b.Add("h", 0.6);
    std::mt19937_64 ra(7), rb(7);
    for (int k = 0; k < 300; ++k) {
      const Played pa = Play(a, "av", "h", ra, 0.2), pb = Play(b, "av", "h", rb, 0.2);
      EXPECT_EQ(pa.draw.nudge_distance, pb.draw.nudge_distance);
      EXPECT_EQ(pa.reading.posterior, pb.reading.posterior);
      EXPECT_EQ(pa.record.theory_dc, pb.record.theory_dc);
      EXPECT_EQ(pb.record.hv_trust, 0.6);
      EXPECT_EQ(pb.record.beyond.trust_after, 0.6);
    }
  }
}

TEST(HvPopulation, DynamicTrustUpdatesFromWhatTheHvSaw) {
  // w_s = 1, w_f = 2, rho = 0, alpha0 = 6, beta0 = 4; q defaults.
  const ExperimentConfig c =
      Config("model: {trust: 0.6, trust_dynamics: {strength: 10, success_weight: 1, "
             "failure_weight: 2}}\npolicies: [ta_ebp]\n");
  HvPopulation pop(c, Policy::kTaEbp);
  pop.Add("h", 0.6);
  double alpha = 6, beta = 4;
  struct Case {
    bool nudge, go, collision;
    const char* outcome;
    double q;
  };
  for (const Case& k : {Case{true, true, false, "nudge_go", 1}, Case{true, false, false, "nudge_stop", 0},
                        Case{false, false, false, "still_stop", 1},
                        Case{false, true, false, "still_go", 0}, Case{true, true, true, "collision", 0}}) {
    const double before = alpha / (alpha + beta);
    EXPECT_DOUBLE_EQ(pop.Trust("h"), before);
    pop.Commit("a", "h");
    AvDraw d;
    d.nudge = k.nudge;
    d.nudge_distance = k.nudge ? 1.6 : 0.0;
    d.intent_go = d.goes_first = k.go;
    EncounterRecord r;
    pop.Finish("a", "h", d, pop.Read("a", "h", d.nudge_distance), k.collision, true, &r);
    alpha += 1.0 * k.q;
    beta += 2.0 * (1 - k.q);
    EXPECT_EQ(r.beyond.outcome, k.outcome);
    EXPECT_EQ(r.beyond.quality, k.q);
    EXPECT_DOUBLE_EQ(r.hv_trust, before);
    EXPECT_DOUBLE_EQ(r.beyond.trust_after, alpha / (alpha + beta));
  }
  // The AV tracks the HV's trust (ta_ebp, exact knowledge): its design is for the current mean.
  const per::LinearLikelihood model(2.0);
  const per::AvHvParams params{0.2, 3.0};
  ExpectSameScheme(pop.Commit("a", "h"),
                   per::CommitScheme(Policy::kTaEbp, params, alpha / (alpha + beta), model));
}

TEST(HvPopulation, LongRunTrustIsTheClosedFormFixedPoint) {
  // Paper point, w_s = w_f, rho = 0 (docs/beyond/derivations.md): TA-EBP tracking
  // trust settles where theta^2 + 0.8 theta - 1.2 = 0; No Trust where its
  // constant quality Q = 1/2 puts it (w_s Q / (w_s Q + w_f (1 - Q)) = 1/2);
  // full revelation never raises a false alarm: trust goes to 1.
  const std::string yaml = "model: {trust: 0.6, trust_dynamics: {strength: 10}}\n";
  struct Case {
    Policy policy;
    double expected;
  };
  for (const Case& k : {Case{Policy::kTaEbp, (-0.8 + std::sqrt(0.64 + 4.8)) / 2},
                        Case{Policy::kNoTrust, 0.5}, Case{Policy::kFullReveal, 1.0}}) {
    HvPopulation pop(Config(yaml), k.policy);
    pop.Add("h", 0.6);
    const BeyondRun r = pop.Results(0.0);
    ASSERT_TRUE(r.long_run) << taebp::PolicyName(k.policy);
    EXPECT_NEAR(r.expected_long_run_mean, k.expected, 1e-9) << taebp::PolicyName(k.policy);
  }
  // With forgetting the attractor depends on the initial state: where Q is
  // constant (No Trust) it is ConstantQualityEquilibrium's closed form.
  const ExperimentConfig c =
      Config("model: {trust: 0.6, trust_dynamics: {strength: 10, forgetting: 0.1}}\n");
  HvPopulation pop(c, Policy::kNoTrust);
  pop.Add("h", 0.6);
  const double rho = 0.1, a0 = 6, b0 = 4, q = 0.5;
  EXPECT_NEAR(pop.Results(0.0).expected_long_run_mean,
              (rho * a0 + q) / (rho * (a0 + b0) + q + (1 - q)), 1e-9);
}

TEST(HvPopulation, MeanFieldFollowsTheExpectedUpdateAtEachEncounter) {
  const ExperimentConfig c = Config(
      "model: {trust: 0.6, trust_dynamics: {strength: 10, failure_weight: 3}}\n"
      "outputs: {interval: 1}\n");
  const per::LinearLikelihood model(2.0);
  const per::AvHvParams params{0.2, 3.0};
  HvPopulation pop(c, Policy::kTaEbp);
  pop.Add("h", 0.6);
  per::BetaTrust twin = per::BetaTrust::FromMean(0.6, 10);
  per::TrustUpdateRule rule;
  rule.failure_weight = 3;
  std::mt19937_64 rng(3);
  for (int k = 0; k < 50; ++k) {
    Play(pop, "a", "h", rng, 0.2);
    twin.Update(per::ExpectedQuality(per::DesignRule{}, params, twin.Mean(), model, rule.quality),
                rule);
    pop.Sample(k);
  }
  const BeyondRun r = pop.Results(49.0);
  ASSERT_NE(r.samples, nullptr);
  const auto series = SpooledRows(r.samples->TimeRowsText(), TimeseriesCsvColumns());
  ASSERT_EQ(series.size(), 50u);
  EXPECT_EQ(r.samples->TimeRows(), 50);
  EXPECT_NEAR(std::stod(series.back().at("mean_field_trust")), twin.Mean(), 1e-12);
  EXPECT_NEAR(r.final_mean_field, twin.Mean(), 1e-12);
}

// ------------------------------------------------------------------ noise

TEST(HvPopulation, NoisyReadingIsSumosDisplacementPlusNoiseAndPersuadesAsDesigned) {
  const per::AvHvParams params{0.2, 3.0};
  const double sigma = 0.1, delta = 0.01, z = 2.3263478740408408;  // z_{0.99}
  const double s_star = 64.0 / 39.0;
  for (const char* design : {"aware", "paper"}) {
    const ExperimentConfig c = Config(
        std::string("model: {trust: 0.6, noise: {kind: gaussian, scale: 0.1, delta: 0.01, design: ") +
        design + "}}\npolicies: [ta_ebp]\n");
    HvPopulation pop(c, Policy::kTaEbp);
    pop.Add("h", 0.6);
    const bool aware = std::string(design) == "aware";
    const per::CommittedScheme& s = pop.Commit("a", "h");
    EXPECT_NEAR(s.nudge, aware ? s_star + z * sigma : s_star, 1e-9);
    EXPECT_NEAR(s.b, 7.0 / 32.0, 1e-12);  // the density ratio is ~1e-58 here
    const double observed = s.nudge + 1e-6;
    const int n = 40000;
    int dc = 0;
    for (int i = 0; i < n; ++i) {
      const HvReading r = pop.Read("a", "h", observed);
      EXPECT_EQ(r.observed, observed);  // SUMO's displacement, as the records show it
      dc += r.drives_if_clear;
    }
    // P(DC | nudge) = 1 - Phi((s* - observed) / sigma): 0.99 (aware), 1/2 (paper).
    const double p = 1.0 - 0.5 * std::erfc(-((s_star - observed) / sigma) / std::sqrt(2.0));
    EXPECT_NEAR(p, aware ? 1 - delta : 0.5, 1e-4);
    EXPECT_NEAR(static_cast<double>(dc) / n, p, 3.29 * std::sqrt(p * (1 - p) / n));
    // The theory is the exact expectation over the noise.
    const per::PerceptionNoise noise{per::PerceptionNoise::Kind::kGaussian, sigma, 0.0};
    const per::LinearLikelihood model(2.0);
    const per::PredictedOutcome th = per::PredictOutcomeUnderNoise(s, params, 0.6, model, noise);
    EXPECT_EQ(pop.Theory().collision_rate, th.collision_rate);
    EXPECT_EQ(pop.Theory().dc_rate, th.dc_rate);
    EXPECT_NEAR(th.collision_rate, aware ? 0.2 * delta : 0.1, 1e-8);
  }
}

TEST(HvPopulation, NoNoiseKindReadsExactlyAsThePaper) {
  const per::AvHvParams params{0.2, 3.0};
  const per::LinearLikelihood model(2.0);
  HvPopulation pop(Config("model: {trust: 0.6, noise: {kind: none}}"), Policy::kTaEbp);
  pop.Add("h", 0.6);
  const per::CommittedScheme s = pop.Commit("a", "h");
  ExpectSameScheme(s, per::CommitScheme(Policy::kTaEbp, params, 0.6, model));
  for (double observed : {0.0, 1.0, 1.6410266410256411, 1.64102, 2.5}) {
    const HvReading got = pop.Read("a", "h", observed);
    const HvReading old = ReadNudge(s, params, 0.6, model, observed);
    EXPECT_EQ(got.posterior, old.posterior);
    EXPECT_EQ(got.drives_if_clear, old.drives_if_clear);
  }
}

TEST(HvPopulation, StreamsAreSeededPerPurpose) {
  auto readings = [](const std::string& yaml, Policy policy) {
    HvPopulation pop(Config(yaml), policy);
    pop.Add("h", 0.6);
    std::vector<double> out;
    for (int i = 0; i < 200; ++i) {
      pop.Commit("a", "h");
      pop.Read("a", "h", 1.8);
      EncounterRecord r;
      pop.Finish("a", "h", AvDraw{}, HvReading{}, false, true, &r);
      out.push_back(r.beyond.reading);
    }
    return out;
  };
  const std::string noisy = "model: {trust: 0.6, noise: {kind: uniform, scale: 0.2}}\n";
  const auto a = readings(noisy + "scenario: {seed: 5}\npolicies: [ta_ebp]", Policy::kTaEbp);
  EXPECT_EQ(a, readings(noisy + "scenario: {seed: 5}\npolicies: [ta_ebp]", Policy::kTaEbp));
  EXPECT_NE(a, readings(noisy + "scenario: {seed: 6}\npolicies: [ta_ebp]", Policy::kTaEbp));
  // The learner's probe draws come from their own stream: the noise is the same.
  EXPECT_EQ(a, readings(noisy + "scenario: {seed: 5}\npolicies: [ta_ebp_learned]",
                        Policy::kTaEbpLearned));
  for (double r : a) {
    EXPECT_GE(r, 1.6);
    EXPECT_LE(r, 2.0);  // clamped to s_max
  }
}

// ------------------------------------------------------------------ learned trust

TEST(HvPopulation, LearnerWithAPointPriorIsTheOracle) {
  const per::AvHvParams params{0.2, 3.0};
  const per::LinearLikelihood model(2.0);
  HvPopulation pop(Config("model: {trust: 0.6}\npolicies: [ta_ebp_learned]"), Policy::kTaEbpLearned);
  pop.Add("h", 0.6);
  std::mt19937_64 rng(11);
  for (int k = 0; k < 100; ++k) {
    const Played p = Play(pop, "a", "h", rng, 0.2);
    EXPECT_EQ(p.record.beyond.design_trust, 0.6);
    EXPECT_EQ(p.record.beyond.regret, 0.0);
    EXPECT_FALSE(p.record.collision);
  }
  ExpectSameScheme(pop.Commit("a", "h"), per::CommitScheme(Policy::kTaEbp, params, 0.6, model));
}

TEST(HvPopulation, LearnerIsSafeCalibratedAndApproachesTheOracle) {
  // 24 HVs drawn from Beta(4, 2), the fleet starting from that prior; 300
  // encounters each (about six simulated hours of an HV on the figure-8).
  const ExperimentConfig c = Config(
      "model: {trust: {dist: beta, alpha: 4, beta: 2}, learning: {delta: 0.01, decay: 1}}\n"
      "policies: [ta_ebp_learned]\noutputs: {interval: 1}\n");
  HvPopulation pop(c, Policy::kTaEbpLearned);
  std::mt19937_64 rng(2024);
  std::vector<std::string> ids;
  for (int h = 0; h < 24; ++h) {
    ids.push_back("hv" + std::to_string(h));
    pop.Add(ids.back(), c.model.trust.Draw((h + 0.5) / 24));
  }
  long nudges = 0, failures = 0, contradictions = 0;
  double expected = 0, early_regret = 0, late_regret = 0, late_oracle = 0, late_dc = 0;
  for (int k = 0; k < 300; ++k) {
    for (const std::string& id : ids) {
      const Played p = Play(pop, "av", id, rng, 0.2);
      const BeyondEncounter& b = p.record.beyond;
      EXPECT_LE(b.risk_level, 0.01);
      if (b.mode == "design") {
        EXPECT_LE(b.failure_probability, b.risk_level + 1e-12);
      }
      // Without noise or dynamics the HV responds deterministically: the
      // posterior interval always holds its trust.
      contradictions += b.observation == "contradiction";
      EXPECT_LE(b.belief_lower, p.record.hv_trust);
      if (p.draw.nudge_distance > 0) {
        ++nudges;
        failures += !p.reading.drives_if_clear;
        expected += b.failure_probability;
      }
      if (k < 30) early_regret += b.regret;
      if (k >= 270) {
        late_regret += b.regret;
        late_oracle += b.oracle_dc;
        late_dc += p.record.theory_dc;
      }
    }
  }
  EXPECT_EQ(contradictions, 0);
  // Calibrated: the failures are a sum of Bernoullis with the posterior's
  // probabilities (the HVs' trust drawn from the prior): within 4 sd.
  EXPECT_NEAR(failures, expected, 4 * std::sqrt(expected) + 1) << nudges << " nudges";
  EXPECT_LE(failures, 0.01 * nudges + 4 * std::sqrt(0.01 * nudges));
  // Learning: the last 30 rounds lose far less than the first 30, and keep at
  // least 90 % of the oracle's DC.
  EXPECT_LT(late_regret, 0.25 * early_regret);
  EXPECT_GE(late_dc, 0.9 * late_oracle);
  const BeyondRun r = pop.Results(300.0);
  EXPECT_TRUE(r.learning);
  EXPECT_EQ(r.hvs_met, 24);
  EXPECT_EQ(r.contradictions, 0);
  EXPECT_LT(r.final_mean_abs_error, 0.05);
}

// ------------------------------------------------------------------ time series

TEST(HvPopulation, TimeSeriesEveryIntervalFromTheWarmUp) {
  const ExperimentConfig c = Config(
      "scenario: {warmup: 20, duration: 200}\n"
      "model: {trust: 0.6, trust_dynamics: {}}\noutputs: {interval: 30}\n");
  HvPopulation pop(c, Policy::kTaEbp);
  pop.Add("a1", 0.6);
  pop.Add("b2", 0.6);
  for (int t = 1; t <= 100; ++t) pop.Sample(t);
  const BeyondRun r = pop.Results(105.0);
  // The rows are on disk (report/sample_spool.h), as the files will hold them.
  ASSERT_NE(r.samples, nullptr);
  const auto series = SpooledRows(r.samples->TimeRowsText(), TimeseriesCsvColumns());
  const auto hv_series = SpooledRows(r.samples->HvRowsText(), HvTrustCsvColumns());
  std::vector<double> times;
  for (const auto& row : series) times.push_back(std::stod(row.at("time")));
  EXPECT_EQ(times, (std::vector<double>{20, 50, 80, 105}));
  ASSERT_EQ(hv_series.size(), 8u);
  EXPECT_EQ(r.samples->HvRows(), 8);
  EXPECT_EQ(hv_series[0].at("hv"), "a1");
  EXPECT_EQ(hv_series[1].at("hv"), "b2");
  EXPECT_EQ(hv_series[7].at("time"), "105");
  EXPECT_DOUBLE_EQ(std::stod(series[0].at("mean_trust")), 0.6);
  EXPECT_DOUBLE_EQ(std::stod(series[0].at("mean_field_trust")), 0.6);
}

TEST(HvPopulation, AnHvThatLeftBeforeItsEncounterWasRecordedKeepsItsRecord) {
  HvPopulation pop(Config("model: {trust: 0.6, trust_dynamics: {}}"), Policy::kTaEbp);
  pop.Add("h", 0.6);
  pop.Commit("a", "h");
  const HvReading r = pop.Read("a", "h", 0.0);
  pop.Remove("h");
  EncounterRecord rec;
  AvDraw d;
  pop.Finish("a", "h", d, r, false, true, &rec);
  EXPECT_EQ(rec.hv_trust, 0.6);
  EXPECT_EQ(rec.beyond.trust_after, 0.6);
  EXPECT_FALSE(pop.Has("h"));
}

}  // namespace
}  // namespace taebp
