// HVs who learn what a signal meant (experience.h): the learning rule, the
// fixed points of each policy, the knife edge, the design against it and the
// exact mean-field path, against closed forms (docs/influence.md).
#include "taebp/persuasion/experience.h"

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/random.h"
#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;

const AvHvParams kPaper{0.2, 3.0};
constexpr double kTheta = 0.6;

// Binomial pmf by lgamma (exact to ~1e-13 relative for these sizes).
double Pmf(long n, long k, double p) {
  if (k < 0 || k > n) return 0.0;
  if (p == 0.0) return k == 0 ? 1.0 : 0.0;
  if (p == 1.0) return k == n ? 1.0 : 0.0;
  return std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) +
                  k * std::log(p) + (n - k) * std::log1p(-p));
}

CommittedScheme AlwaysNudge(double s) {
  CommittedScheme sc;
  sc.av_may_go = true;
  sc.nudge = s;
  sc.a = 1.0;
  sc.b = 1.0;
  return sc;
}

TEST(ExperiencedPosterior, BetaBernoulliMeanAndItsLimits) {
  EXPECT_DOUBLE_EQ(ExperiencedPosterior(0.4, {0, 0}, 20.0), 0.4);
  EXPECT_DOUBLE_EQ(ExperiencedPosterior(0.4, {10, 3}, 20.0), (20 * 0.4 + 3) / 30.0);
  EXPECT_DOUBLE_EQ(ExperiencedPosterior(0.4, {10, 3}, std::numeric_limits<double>::infinity()),
                   0.4);
  // k -> 0: the frequency.
  EXPECT_NEAR(ExperiencedPosterior(0.4, {10, 3}, 1e-12), 0.3, 1e-12);
  EXPECT_THAT(testing::InvalidArgumentMessage([] { ExperiencedPosterior(0.4, {2, 3}, 1.0); }),
              HasSubstr("g = 3"));
  EXPECT_THAT(testing::InvalidArgumentMessage([] { ExperiencedPosterior(0.4, {2, 1}, 0.0); }),
              HasSubstr("strength k = 0"));
}

TEST(ExperiencedBelief, IsEqPpWithTheExperiencedPosterior) {
  const LinearLikelihood model(2.0);
  const CommittedScheme sc = CommitScheme(Policy::kTaEbp, kPaper, kTheta, model);
  // No experience: exactly the paper's HV.
  for (double s : {0.0, 0.5, sc.nudge, 2.0})
    EXPECT_NEAR(ExperiencedBelief(sc, kPaper, kTheta, model, s, {}, 20.0),
                HvPosteriorGo(sc, kPaper, kTheta, model, s), 1e-15);
  const double q = HvPosteriorGo(kPaper, 1.0, model, 1.0);
  EXPECT_DOUBLE_EQ(ExperiencedBelief(sc, kPaper, kTheta, model, 1.0, {5, 1}, 10.0),
                   0.4 * 0.2 + 0.6 * (10 * q + 1) / 15.0);
  // A scheme that does not signal: the intuitive posterior is the prior.
  const CommittedScheme none;
  EXPECT_DOUBLE_EQ(ExperiencedBelief(none, kPaper, kTheta, model, 0.0, {4, 0}, 4.0),
                   0.4 * 0.2 + 0.6 * (4 * 0.2) / 8.0);
}

TEST(SignalExperience, CountsPerLevelOfTheReading) {
  SignalExperience e(0.1);
  EXPECT_EQ(e.Level(0.0), 0);
  EXPECT_EQ(e.Level(1.6406), 16);
  e.Record(1.6406, true);
  e.Record(1.6499, false);
  e.Record(1.45, false);
  EXPECT_EQ(e.At(1.61).readings, 2);
  EXPECT_EQ(e.At(1.61).went, 1);
  EXPECT_EQ(e.At(1.45).readings, 1);
  EXPECT_EQ(e.At(0.0).readings, 0);
  EXPECT_EQ(e.Readings(), 3);
  EXPECT_THAT(testing::InvalidArgumentMessage([&] { e.Level(-0.1); }), HasSubstr("reading"));
}

// Theorem 2's consistency condition, exactly: the scheme's Bayes posterior
// after s*, lambda / (lambda + b (1 - lambda)), equals the intuitive one, i.e.
// L(s*) = pi(s*|Go) / pi(s*|Stop) = 1 / b, for every trust in (theta*, 1].
TEST(ExperienceFixedPoints, TaebpAtSStarIsConsistentAndSitsOnTheKnifeEdge) {
  const LinearLikelihood model(2.0);
  for (double theta : {0.3, 0.45, 0.6, 0.8, 1.0}) {
    const TaebpDesign d = DesignTaebp(kPaper, theta, model);
    ASSERT_TRUE(d.persuadable);
    EXPECT_NEAR(model.Ratio(d.s_star), 1.0 / d.b, 1e-9 / d.b) << theta;
    const CommittedScheme sc = CommitScheme(Policy::kTaEbp, kPaper, theta, model);
    const ExperienceLongRun lr = LongRunUnderExperience(sc, kPaper, theta, model);
    EXPECT_NEAR(lr.went_after_nudge, HvPosteriorGo(kPaper, 1.0, model, d.s_star), 1e-12);
    EXPECT_NEAR(lr.belief_after_nudge, AvHvPStar(3.0), 1e-12);
    EXPECT_TRUE(lr.knife_edge) << theta;
    EXPECT_EQ(lr.dc_after_nudge, 0.5);
    EXPECT_DOUBLE_EQ(lr.went_after_still, 0.0);
    const double nu = 0.2 + 0.8 * d.b;
    EXPECT_NEAR(lr.outcome.dc_rate, nu / 2, 1e-12);
    EXPECT_NEAR(lr.outcome.collision_rate, 0.2 / 2, 1e-12);
  }
}

TEST(ExperienceFixedPoints, AlwaysNudgeNoTrustFullRevealNoEbp) {
  const LinearLikelihood model(2.0);
  const double s_star = MinimalNudge(kPaper, kTheta, model);
  // Always nudging: the nudge's go-frequency is lambda; the HV drives
  // recklessly and every Go the AV acts on collides.
  ExperienceLongRun lr = LongRunUnderExperience(AlwaysNudge(s_star), kPaper, kTheta, model);
  EXPECT_DOUBLE_EQ(lr.went_after_nudge, 0.2);
  EXPECT_FALSE(lr.knife_edge);
  EXPECT_DOUBLE_EQ(lr.outcome.dc_rate, 0.0);
  EXPECT_DOUBLE_EQ(lr.outcome.collision_rate, 0.2);
  EXPECT_DOUBLE_EQ(lr.outcome.nudge_rate, 1.0);
  // No Trust (designed for theta = 1): consistent at its own nudge (p*), which
  // an HV of trust 0.6 reads as 0.08 + 0.6 * 0.4 = 0.32 < p*: what it always did.
  lr = LongRunUnderExperience(CommitScheme(Policy::kNoTrust, kPaper, 1.0, model), kPaper, kTheta,
                              model);
  EXPECT_NEAR(lr.went_after_nudge, 0.4, 1e-12);
  EXPECT_NEAR(lr.belief_after_nudge, 0.32, 1e-12);
  EXPECT_DOUBLE_EQ(lr.outcome.dc_rate, 0.0);
  EXPECT_DOUBLE_EQ(lr.outcome.collision_rate, 0.2);
  // Full revelation: s_max always means Go.
  lr = LongRunUnderExperience(CommitScheme(Policy::kFullReveal, kPaper, kTheta, model), kPaper,
                              kTheta, model);
  EXPECT_DOUBLE_EQ(lr.went_after_nudge, 1.0);
  EXPECT_DOUBLE_EQ(lr.outcome.dc_rate, 0.2);
  EXPECT_DOUBLE_EQ(lr.outcome.collision_rate, 0.0);
  // No EBP: the AV never goes; nothing to learn but that.
  lr = LongRunUnderExperience(CommitScheme(Policy::kNoEbp, kPaper, kTheta, model), kPaper, kTheta,
                              model);
  EXPECT_TRUE(std::isnan(lr.went_after_nudge));
  EXPECT_DOUBLE_EQ(lr.went_after_still, 0.0);
  EXPECT_DOUBLE_EQ(lr.outcome.dc_rate, 0.0);
  EXPECT_DOUBLE_EQ(lr.outcome.collision_rate, 0.0);
}

// The mean field of always-nudge: the nudge level's g after t encounters is
// Binomial(t, lambda); the HV drives if clear at encounter t iff
// k q + g >= q_thr (k + t), q_thr = (p* - (1 - theta) lambda) / theta.
TEST(ExperiencePath, AlwaysNudgeIsABinomialTail) {
  const LinearLikelihood model(2.0);
  const double k = 10.5, s = 2.0;  // q(s_max) = 1: a high start; 8 t - 73.5 never / 15
  ExperiencePath path(AlwaysNudge(s), kPaper, kTheta, model, k, /*guarded=*/false);
  const double q_thr = (0.4 - 0.4 * 0.2) / 0.6;
  for (long t : {0L, 1L, 5L, 10L, 17L, 30L, 60L, 120L}) {
    const double need = q_thr * (k + t) - k * 1.0;
    ASSERT_GT(std::abs(need - std::round(need)), 1e-6) << "a tie at t = " << t;
    double tail = 0.0;
    for (long g = std::max(0L, static_cast<long>(std::ceil(need))); g <= t; ++g)
      tail += Pmf(t, g, 0.2);
    const PredictedOutcome o = path.At(t);
    EXPECT_NEAR(o.dc_rate, tail, 1e-12) << t;
    EXPECT_NEAR(o.collision_rate, 0.2 * (1.0 - tail), 1e-12) << t;
    EXPECT_NEAR(o.nudge_rate, 1.0, 1e-12);  // the DP drops states below 1e-15
  }
  EXPECT_DOUBLE_EQ(path.At(0).dc_rate, 1.0);  // the intuitive model is persuaded
  EXPECT_LT(path.At(200).dc_rate, 1e-6);      // and unlearns it
}

// The paper's TA-EBP against a learner: DC at encounter t iff the nudge
// level's walk g - q* n is >= 0 (tie included: 15 g >= 8 n at the paper point),
// n ~ Binomial(t, nu), g | n ~ Binomial(n, q*).
TEST(ExperiencePath, PaperTaebpIsAZeroMeanWalkAroundPStar) {
  const LinearLikelihood model(2.0);
  const CommittedScheme sc = CommitScheme(Policy::kTaEbp, kPaper, kTheta, model);
  const double nu = 0.2 + 0.8 * sc.b;  // 0.375
  const double q = 8.0 / 15.0;
  ExperiencePath path(sc, kPaper, kTheta, model, 20.0, false);
  for (long t : {0L, 3L, 20L, 60L, 150L}) {
    double p_dc = 0.0;  // P(DC after a nudge at t)
    for (long n = 0; n <= t; ++n) {
      double tail = 0.0;
      for (long g = 0; g <= n; ++g)
        if (15 * g >= 8 * n) tail += Pmf(n, g, q);
      p_dc += Pmf(t, n, nu) * tail;
    }
    const PredictedOutcome o = path.At(t);
    EXPECT_NEAR(o.dc_rate, nu * p_dc, 1e-10) << t;
    EXPECT_NEAR(o.collision_rate, 0.2 * (1.0 - p_dc), 1e-10) << t;
  }
  // Half the nudges read as DR in the long run: the arcsine law's mean.
  const PredictedOutcome late = path.At(1000);
  EXPECT_NEAR(late.dc_rate, nu / 2, 0.01);
  EXPECT_NEAR(late.collision_rate, 0.1, 0.01);
}

TEST(DesignForExperience, GuardsTheNudgeAgainstAFalseAlarm) {
  const LinearLikelihood model(2.0);
  const CommittedScheme paper = CommitScheme(Policy::kTaEbp, kPaper, kTheta, model);
  const double k = 20.0;
  auto at = [&](SignalCounts c) {
    return [c](double) { return c; };
  };
  // n = 0: persuaded (the tie), but one false alarm would leave it at
  // k q / (k + 1) < q: guard (b = 0).
  ExperiencedDesign d = DesignForExperience(paper, kPaper, kTheta, model, k, at({0, 0}));
  EXPECT_EQ(d.mode, ExperiencedDesign::Mode::kGuard);
  EXPECT_EQ(d.scheme.b, 0.0);
  EXPECT_EQ(d.scheme.nudge, paper.nudge);
  // g >= q (n + 1): a false alarm keeps it at or above q: the paper's b.
  d = DesignForExperience(paper, kPaper, kTheta, model, k, at({14, 8}));  // 8 >= 8/15 * 15
  EXPECT_EQ(d.mode, ExperiencedDesign::Mode::kPaper);
  EXPECT_EQ(d.scheme.b, paper.b);
  d = DesignForExperience(paper, kPaper, kTheta, model, k, at({15, 8}));  // 8 < 8/15 * 16
  EXPECT_EQ(d.mode, ExperiencedDesign::Mode::kGuard);
  // Not persuaded by s* (an HV taught otherwise): s_max if that persuades.
  d = DesignForExperience(paper, kPaper, kTheta, model, k, [](double s) {
    return s < 1.9 ? SignalCounts{40, 0} : SignalCounts{};
  });
  EXPECT_EQ(d.mode, ExperiencedDesign::Mode::kStronger);
  EXPECT_EQ(d.scheme.nudge, 2.0);
  EXPECT_EQ(d.scheme.b, 0.0);
  d = DesignForExperience(paper, kPaper, kTheta, model, k, at({40, 0}));
  EXPECT_EQ(d.mode, ExperiencedDesign::Mode::kYield);
  EXPECT_FALSE(d.scheme.av_may_go);
  EXPECT_FALSE(d.scheme.Signals());
}

// The guarded design never lets a nudge be read as DR (no collision at any
// t), and its DC rate climbs from lambda to the paper's lambda + (1 - lambda) b.
TEST(ExperiencePath, GuardedTaebpNeverCollidesAndRecoversThePaperRate) {
  const LinearLikelihood model(2.0);
  const CommittedScheme paper = CommitScheme(Policy::kTaEbp, kPaper, kTheta, model);
  const double target = 0.2 + 0.8 * paper.b;
  for (double k : {5.0, 20.0}) {
    ExperiencePath path(paper, kPaper, kTheta, model, k, true);
    EXPECT_NEAR(path.At(0).dc_rate, 0.2, 1e-15);  // guard at n = 0
    double last = 0.0;
    for (long t = 0; t <= 1000; ++t) {
      const PredictedOutcome o = path.At(t);
      ASSERT_EQ(o.collision_rate, 0.0) << t;
      ASSERT_LE(o.dc_rate, target + 1e-12) << t;
      if (t % 100 == 0) {
        EXPECT_GE(o.dc_rate, last - 1e-12) << t;  // sampled: non-decreasing
        last = o.dc_rate;
      }
    }
    EXPECT_GT(path.At(1000).dc_rate, target - 0.02) << k;
  }
}

// ---------------------------------------------------------------- issue 42
// A learner that forgets: every encounter multiplies every level's weights by
// rho before the new reading is added (closed form by hand).
TEST(SignalExperience, ForgettingWeighsThePastByRhoPerEncounter) {
  SignalExperience e(0.1, 0.5);
  e.Record(1.61, true);   // level 16: n = 1, g = 1
  e.Record(1.63, false);  // level 16: n = 0.5 + 1, g = 0.5
  e.Record(0.0, false);   // level 0: n = 1; level 16: n = 0.75, g = 0.25
  EXPECT_DOUBLE_EQ(e.At(1.6).readings, 0.75);
  EXPECT_DOUBLE_EQ(e.At(1.6).went, 0.25);
  EXPECT_DOUBLE_EQ(e.At(0.05).readings, 1.0);
  EXPECT_EQ(e.Readings(), 3);
  // rho = 1 keeps the exact counts of issue 29.
  SignalExperience exact(0.1, 1.0);
  for (int i = 0; i < 5; ++i) exact.Record(1.61, i % 2 == 0);
  EXPECT_DOUBLE_EQ(exact.At(1.6).readings, 5.0);
  EXPECT_DOUBLE_EQ(exact.At(1.6).went, 3.0);
  for (double bad : {0.0, -0.5, 1.0 + 1e-12, std::nan("")})
    EXPECT_THAT(testing::InvalidArgumentMessage([&] { SignalExperience(0.1, bad); }),
                HasSubstr("forgetting rho = "));
}

// The robust design against the closed forms of experience.h at the paper's
// figure-8 (lambda = 0.2, r = 3, p* = 0.4, theta = 0.6): pi_m = (p* + m -
// 0.08) / 0.6, b = lambda (1 - pi_m) / (pi_m (1 - lambda)).
TEST(DesignRobust, LargestBWithTheMarginAndTheLongRunDc) {
  const LinearLikelihood model(2.0);
  const RobustDesign d = DesignRobust(kPaper, kTheta, model, 0.1);
  ASSERT_TRUE(d.persuades);
  EXPECT_NEAR(d.pi_target, 0.7, 1e-12);
  EXPECT_NEAR(d.scheme.b, 0.2 * 0.3 / (0.7 * 0.8), 1e-12);
  EXPECT_EQ(d.scheme.nudge, 2.0);
  EXPECT_EQ(d.scheme.a, 1.0);
  // The exact learner settles on pi_b = 0.7: belief 0.08 + 0.6 * 0.7 = 0.5,
  // the margin 0.1 above p*; DC lambda / pi_b, no collision.
  const ExperienceLongRun lr = LongRunUnderExperience(d.scheme, kPaper, kTheta, model);
  EXPECT_NEAR(lr.belief_after_nudge, 0.5, 1e-12);
  EXPECT_FALSE(lr.knife_edge);
  EXPECT_NEAR(lr.outcome.dc_rate, 0.2 / 0.7, 1e-12);
  EXPECT_EQ(lr.outcome.collision_rate, 0.0);
  // Margin 0: eq:b's b, the paper's DC (a second method: DesignTaebp).
  const RobustDesign edge = DesignRobust(kPaper, kTheta, model, 0.0);
  EXPECT_NEAR(edge.scheme.b, DesignTaebp(kPaper, kTheta, model).b, 1e-12);
  // A margin no scheme can keep (pi_m > 1): it yields.
  EXPECT_FALSE(DesignRobust(kPaper, kTheta, model, 0.6).persuades);
  EXPECT_FALSE(DesignRobust(kPaper, kTheta, model, 0.6).scheme.av_may_go);
  EXPECT_THAT(testing::InvalidArgumentMessage([&] { DesignRobust(kPaper, kTheta, model, -0.01); }),
              HasSubstr("robust margin m = -0.01"));
}

// A Monte Carlo of the forgetting learner (a cross-check, never the product):
// the share of nudges read as DR in the long run and at encounter t against
// the normal approximation of RobustRiskUnderForgetting / ExperiencePath.
double SimulatedDrAfterNudge(const CommittedScheme& sc, double k, double rho, long t_from,
                             long t_to, unsigned seed) {
  const LinearLikelihood model(2.0);
  std::mt19937_64 rng(seed);
  const double q = HvPosteriorGo(kPaper, 1.0, model, sc.nudge);
  long nudges = 0, dr = 0;
  for (int hv = 0; hv < 400; ++hv) {
    SignalExperience e(0.1, rho);
    for (long t = 0; t < t_to; ++t) {
      const bool go = Uniform01(rng) < kPaper.prior_go;
      const bool nudge = go ? true : Uniform01(rng) < sc.b;
      if (!nudge) {
        e.Record(0.0, false);
        continue;
      }
      const double belief = (1.0 - kTheta) * kPaper.prior_go +
                            kTheta * ExperiencedPosterior(q, e.At(sc.nudge), k);
      if (t >= t_from) {
        ++nudges;
        dr += HvDrivesIfClear(kPaper, belief) ? 0 : 1;
      }
      e.Record(sc.nudge, go);
    }
  }
  return static_cast<double>(dr) / static_cast<double>(nudges);
}

TEST(DesignRobust, RiskUnderForgettingAgainstASimulatedLearner) {
  const LinearLikelihood model(2.0);
  const RobustDesign d = DesignRobust(kPaper, kTheta, model, 0.1);
  // The shipped learner (k = 20) forgetting 0.95: the intuitive reading of
  // s_max (q = 1) keeps it persuaded; no simulated DR either.
  EXPECT_LT(RobustRiskUnderForgetting(d, kPaper, kTheta, 20.0, 0.95), 1e-6);
  EXPECT_EQ(SimulatedDrAfterNudge(d.scheme, 20.0, 0.95, 200, 400, 1), 0.0);
  // A learner that trusts its frequency (k = 1) and forgets fast (0.9):
  // the margin is not enough; the approximation within 0.03 of the simulation.
  const double approx = RobustRiskUnderForgetting(d, kPaper, kTheta, 1.0, 0.9);
  const double sim = SimulatedDrAfterNudge(d.scheme, 1.0, 0.9, 200, 400, 2);
  EXPECT_GT(sim, 0.05);
  EXPECT_NEAR(approx, sim, 0.03);
  // The exact learner: no risk in the long run.
  EXPECT_EQ(RobustRiskUnderForgetting(d, kPaper, kTheta, 1.0, 1.0), 0.0);
  // The path's per-encounter collision rate at t = 300 is lambda times it.
  ExperiencePath path(d.scheme, kPaper, kTheta, model, 1.0, false, 0.9);
  EXPECT_NEAR(path.At(300).collision_rate, 0.2 * approx, 1e-9);
  EXPECT_NEAR(path.At(5).collision_rate / 0.2,
              SimulatedDrAfterNudge(d.scheme, 1.0, 0.9, 5, 6, 3), 0.08);
}

// ------------------------------------------------------------ random_nudge
// The randomised baseline (issue 42): a nudge uniform on (0, s_max] in every
// encounter, independent of the intent.
TEST(RandomNudge, DcIsTheShareOfMagnitudesAtOrAboveSStar) {
  const LinearLikelihood model(2.0);
  const CommittedScheme sc = CommitScheme(Policy::kRandomNudge, kPaper, kTheta, model);
  EXPECT_TRUE(sc.random_magnitude);
  EXPECT_TRUE(sc.av_may_go);
  EXPECT_EQ(sc.nudge, 2.0);
  EXPECT_EQ(sc.a, 1.0);
  EXPECT_EQ(sc.b, 1.0);
  // The magnitude: (1 - u) s_max; a fixed scheme ignores u.
  EXPECT_EQ(NudgeMagnitude(sc, 0.0), 2.0);
  EXPECT_EQ(NudgeMagnitude(sc, 0.75), 0.5);
  EXPECT_EQ(NudgeMagnitude(AlwaysNudge(1.5), 0.75), 1.5);
  // Theorem 2's s* for the HV's trust is the least persuasive magnitude, so
  // DC = 1 - s*/s_max and the AV, going on every Go, collides at lambda s*/s_max.
  for (double theta : {0.45, 0.6, 0.9, 1.0}) {
    const TaebpDesign d = DesignTaebp(kPaper, theta, model);
    ASSERT_TRUE(d.persuadable) << theta;
    const PredictedOutcome o = PredictOutcome(sc, kPaper, theta, model);
    EXPECT_NEAR(o.dc_rate, 1.0 - d.s_star / 2.0, 1e-9) << theta;
    EXPECT_NEAR(o.collision_rate, 0.2 * d.s_star / 2.0, 1e-9) << theta;
    EXPECT_NEAR(o.av_first_rate, 0.2 * (1.0 - d.s_star / 2.0), 1e-9) << theta;
    EXPECT_EQ(o.nudge_rate, 1.0);
  }
  // Below theta* no magnitude persuades: DR always, collisions at lambda.
  const PredictedOutcome low = PredictOutcome(sc, kPaper, 0.05, model);  // theta* = 0.0625
  EXPECT_EQ(low.dc_rate, 0.0);
  EXPECT_NEAR(low.collision_rate, 0.2, 1e-12);
  // A logistic model against a Monte Carlo over the magnitude (4 sd of 2e5 draws).
  const LogisticLikelihood logistic(2.0, 4.0, 1.0);
  const CommittedScheme lsc = CommitScheme(Policy::kRandomNudge, kPaper, kTheta, logistic);
  std::mt19937_64 rng(7);
  long dc = 0;
  const long n = 200000;
  for (long i = 0; i < n; ++i)
    dc += HvDrivesIfClear(kPaper, HvPosteriorGo(lsc, kPaper, kTheta, logistic,
                                                NudgeMagnitude(lsc, Uniform01(rng))));
  const double p = PredictOutcome(lsc, kPaper, kTheta, logistic).dc_rate;
  EXPECT_GT(p, 0.05);
  EXPECT_LT(p, 0.95);
  EXPECT_NEAR(static_cast<double>(dc) / n, p, 4.0 * std::sqrt(p * (1 - p) / n));
}

// A simulated population of learners (bins of 0.1 m, strength k, forgetting
// rho) under random_nudge: the DC share of each HV's encounter t.
std::vector<double> SimulatedRandomNudgeDc(double k, double rho, const std::vector<long>& at,
                                           int hvs, unsigned seed) {
  const LinearLikelihood model(2.0);
  const CommittedScheme sc = CommitScheme(Policy::kRandomNudge, kPaper, kTheta, model);
  std::mt19937_64 rng(seed);
  std::vector<double> dc(at.size(), 0.0);
  const long last = at.back();
  for (int hv = 0; hv < hvs; ++hv) {
    SignalExperience e(0.1, rho);
    std::size_t next = 0;
    for (long t = 0; t <= last; ++t) {
      const bool go = Uniform01(rng) < kPaper.prior_go;
      const double s = NudgeMagnitude(sc, Uniform01(rng));
      if (t == at[next]) {
        dc[next] += HvDrivesIfClear(kPaper, ExperiencedBelief(sc, kPaper, kTheta, model, s, e.At(s), k));
        ++next;
      }
      e.Record(s, go);
    }
  }
  for (double& x : dc) x /= hvs;
  return dc;
}

TEST(ExperiencePath, RandomNudgeSpreadsTheDecayOverLevelsAgainstASimulatedLearner) {
  const LinearLikelihood model(2.0);
  const CommittedScheme sc = CommitScheme(Policy::kRandomNudge, kPaper, kTheta, model);
  EXPECT_THAT(testing::InvalidArgumentMessage([&] { ExperiencePath(sc, kPaper, kTheta, model, 20.0, false); }),
              HasSubstr("bin_width"));
  ExperiencePath exact(sc, kPaper, kTheta, model, 20.0, false, 1.0, 0.1);
  // t = 0: the HV without experience.
  EXPECT_NEAR(exact.At(0).dc_rate, PredictOutcome(sc, kPaper, kTheta, model).dc_rate, 1e-9);
  const std::vector<long> at = {1, 5, 20, 60, 150};
  const int hvs = 20000;
  const std::vector<double> sim = SimulatedRandomNudgeDc(20.0, 1.0, at, hvs, 11);
  for (std::size_t i = 0; i < at.size(); ++i) {
    const PredictedOutcome o = exact.At(at[i]);
    const double p = o.dc_rate;
    EXPECT_NEAR(sim[i], p, 4.0 * std::sqrt(std::max(p * (1 - p), 1e-4) / hvs) + 1e-3) << "t = " << at[i];
    EXPECT_NEAR(o.collision_rate, 0.2 * (1.0 - p), 1e-12);
  }
  // Spread over 20 levels the decay is slower than always-nudge's at one
  // level, and it still goes: every level learns lambda < p*.
  ExperiencePath always(AlwaysNudge(1.0), kPaper, kTheta, model, 20.0, false);
  EXPECT_GT(exact.At(20).dc_rate, always.At(20).dc_rate + 0.05);
  EXPECT_LT(exact.At(1000).dc_rate, 0.01);
  // A learner that forgets (rho = 0.95): the normal approximation per level.
  ExperiencePath forgetting(sc, kPaper, kTheta, model, 20.0, false, 0.95, 0.1);
  const std::vector<double> fsim = SimulatedRandomNudgeDc(20.0, 0.95, at, hvs, 12);
  for (std::size_t i = 0; i < at.size(); ++i)
    EXPECT_NEAR(fsim[i], forgetting.At(at[i]).dc_rate, 0.03) << "t = " << at[i];
}

// HVs of a k the guarded design does not assume (model.experience.strengths):
// the path with the design's k apart from the HV's, against simulated HVs
// whose AV runs DesignForExperience with its own k on the exact counts.
TEST(ExperiencePath, GuardedForOneKAgainstHvsOfAnotherAgainstASimulation) {
  const LinearLikelihood model(2.0);
  const CommittedScheme paper = CommitScheme(Policy::kTaEbp, kPaper, kTheta, model);
  const double q = HvPosteriorGo(kPaper, 1.0, model, paper.nudge);
  const std::vector<long> at = {1, 5, 30, 100};
  std::vector<double> dc_at_100;
  for (const double k_hv : {2.0, 20.0, 200.0}) {
    ExperiencePath path(paper, kPaper, kTheta, model, k_hv, /*guarded=*/true, 1.0, 0.0,
                        /*design_strength=*/20.0);
    std::mt19937_64 rng(static_cast<unsigned>(k_hv));
    const int hvs = 20000;
    std::vector<double> dc(at.size(), 0.0), coll(at.size(), 0.0);
    for (int hv = 0; hv < hvs; ++hv) {
      SignalExperience e(0.1);
      std::size_t next = 0;
      for (long t = 0; t <= at.back(); ++t) {
        const ExperiencedDesign d = DesignForExperience(paper, kPaper, kTheta, model, 20.0,
                                                        [&](double s) { return e.At(s); });
        const bool go = Uniform01(rng) < kPaper.prior_go;
        const double u = Uniform01(rng);
        const bool nudge = d.scheme.av_may_go && d.scheme.nudge > 0 && u < (go ? d.scheme.a : d.scheme.b);
        const double s = nudge ? d.scheme.nudge : 0.0;
        const bool hv_dc = nudge && HvDrivesIfClear(kPaper, (1 - kTheta) * kPaper.prior_go +
                                                               kTheta * ExperiencedPosterior(q, e.At(s), k_hv));
        if (t == at[next]) {
          dc[next] += hv_dc;
          coll[next] += go && d.scheme.av_may_go && !hv_dc;
          ++next;
        }
        e.Record(s, go && d.scheme.av_may_go);
      }
    }
    for (std::size_t i = 0; i < at.size(); ++i) {
      const PredictedOutcome o = path.At(at[i]);
      const auto tol = [&](double p) { return 4.0 * std::sqrt(std::max(p * (1 - p), 1e-4) / hvs) + 1e-3; };
      EXPECT_NEAR(dc[i] / hvs, o.dc_rate, tol(o.dc_rate)) << "k = " << k_hv << ", t = " << at[i];
      EXPECT_NEAR(coll[i] / hvs, o.collision_rate, tol(o.collision_rate)) << "k = " << k_hv << ", t = " << at[i];
    }
    // No collision whatever the HV's k: at s* the intuitive posterior sits on
    // the HV's threshold (q = pi_c), so the guard's test (k q + g) / (k + n +
    // 1) >= pi_c is g >= pi_c (n + 1), free of k (docs/influence.md).
    for (const long t : at) EXPECT_EQ(path.At(t).collision_rate, 0.0) << "k = " << k_hv;
    dc_at_100.push_back(path.At(100).dc_rate);
  }
  // The HV's own decision at s* is free of k for the same reason
  // ((k q + g) / (k + n) >= pi_c iff g >= pi_c n): the whole path is.
  EXPECT_NEAR(dc_at_100[0], dc_at_100[2], 1e-9);
  EXPECT_GT(dc_at_100[0], 0.3);
}

}  // namespace
}  // namespace taebp::persuasion
