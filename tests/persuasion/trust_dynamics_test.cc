// Dynamic (Beta) trust: the update, the expected drift, and the long-run trust
// per policy, checked against hand-derived closed forms and against direct
// simulation of the Beta recursion (encounters drawn with the portable uniform,
// the HV deciding through HvDrivesIfClear, not through OutcomeProbabilities).
#include "taebp/persuasion/trust_dynamics.h"
#include "taebp/config/policies.h"

#include "taebp/persuasion/random.h"
#include "test_util.h"
#include "trust_dynamics_support.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

using trust_test::kPaper;
using trust_test::Weights;

// ------------------------------------------------------------------ outcomes

TEST(EncounterOutcome, NamesRoundTripAndUnknownNamesAreErrors) {
  for (EncounterOutcome outcome : kAllEncounterOutcomes) {
    EXPECT_EQ(ParseEncounterOutcome(ToString(outcome)), outcome);
  }
  EXPECT_STREQ(ToString(EncounterOutcome::kNudgeStop), "nudge_stop");
  EXPECT_THAT(InvalidArgumentMessage([] { ParseEncounterOutcome("false_alarm"); }),
              HasSubstr("encounter outcome 'false_alarm' is unknown"));
}

TEST(EncounterOutcome, ClassifiesWhatTheHvSaw) {
  EXPECT_EQ(ClassifyEncounter(true, true, false, false), EncounterOutcome::kNudgeGo);
  EXPECT_EQ(ClassifyEncounter(true, false, false, false), EncounterOutcome::kNudgeStop);
  EXPECT_EQ(ClassifyEncounter(false, false, false, false), EncounterOutcome::kStillStop);
  EXPECT_EQ(ClassifyEncounter(false, true, false, false), EncounterOutcome::kStillGo);
  // A collision wins over everything, a near miss over the signal/action pair.
  for (bool nudged : {false, true}) {
    for (bool went : {false, true}) {
      EXPECT_EQ(ClassifyEncounter(nudged, went, true, true), EncounterOutcome::kCollision);
      EXPECT_EQ(ClassifyEncounter(nudged, went, false, true), EncounterOutcome::kNearMiss);
    }
  }
}

TEST(OutcomeQuality, DefaultsAndValidation) {
  const OutcomeQuality q;
  EXPECT_EQ(q.Of(EncounterOutcome::kNudgeGo), 1.0);
  EXPECT_EQ(q.Of(EncounterOutcome::kNudgeStop), 0.0);
  EXPECT_EQ(q.Of(EncounterOutcome::kStillStop), 1.0);
  EXPECT_EQ(q.Of(EncounterOutcome::kStillGo), 0.0);
  EXPECT_EQ(q.Of(EncounterOutcome::kCollision), 0.0);
  EXPECT_EQ(q.Of(EncounterOutcome::kNearMiss), 0.0);
  OutcomeQuality bad;
  bad.nudge_stop = 1.5;
  EXPECT_THAT(InvalidArgumentMessage([&] { bad.Validate(); }),
              HasSubstr("quality.nudge_stop = 1.5 is outside [0, 1]"));
  bad = OutcomeQuality{};
  bad.near_miss = -0.25;
  EXPECT_THAT(InvalidArgumentMessage([&] { bad.Validate(); }),
              HasSubstr("quality.near_miss = -0.25 is outside [0, 1]"));
}

TEST(TrustUpdateRule, Validation) {
  EXPECT_THAT(InvalidArgumentMessage([] { Weights(-1.0, 1.0).Validate(); }),
              HasSubstr("success_weight w_s = -1 is outside [0, 1e+09]"));
  EXPECT_THAT(InvalidArgumentMessage([] { Weights(1.0, INFINITY).Validate(); }),
              HasSubstr("failure_weight w_f = inf is outside [0, 1e+09]"));
  // Issue 45 item 10: a weight of 1e308 overflowed alpha + beta to inf mid-run.
  EXPECT_THAT(InvalidArgumentMessage([] { Weights(1e308, 1.0).Validate(); }),
              HasSubstr("success_weight w_s = 1e+308 is outside [0, 1e+09]"));
  EXPECT_NO_THROW(Weights(TrustUpdateRule::kMaxWeight, TrustUpdateRule::kMaxWeight).Validate());
  EXPECT_THAT(InvalidArgumentMessage([] { Weights(1.0, 1.0, 1.5).Validate(); }),
              HasSubstr("forgetting rho = 1.5 is outside [0, 1]"));
  EXPECT_TRUE(Weights(0.0, 0.0, 0.0).IsStatic());
  EXPECT_FALSE(Weights(0.0, 0.0, 0.1).IsStatic());
}

// ------------------------------------------------------------------ the state

TEST(BetaTrust, UpdateArithmetic) {
  BetaTrust t(6.0, 4.0);
  EXPECT_EQ(t.Mean(), 0.6);
  const TrustUpdateRule rule = Weights(2.0, 3.0);
  t.Update(EncounterOutcome::kNudgeGo, rule);  // q = 1: alpha += 2
  EXPECT_EQ(t.Alpha(), 8.0);
  EXPECT_EQ(t.Beta(), 4.0);
  t.Update(EncounterOutcome::kNudgeStop, rule);  // q = 0: beta += 3
  EXPECT_EQ(t.Alpha(), 8.0);
  EXPECT_EQ(t.Beta(), 7.0);
  t.Update(0.25, rule);  // alpha += 0.5, beta += 2.25
  EXPECT_EQ(t.Alpha(), 8.5);
  EXPECT_EQ(t.Beta(), 9.25);
  EXPECT_DOUBLE_EQ(t.Mean(), 8.5 / 17.75);
}

TEST(BetaTrust, ForgettingDecaysTowardTheInitialState) {
  BetaTrust t(6.0, 4.0);
  const TrustUpdateRule rule = Weights(1.0, 1.0, 0.5);
  t.Update(1.0, rule);  // alpha = 6 + 0.5 * 0 + 1
  EXPECT_EQ(t.Alpha(), 7.0);
  EXPECT_EQ(t.Beta(), 4.0);
  t.Update(0.0, rule);  // alpha = 6 + 0.5 * 1, beta = 4 + 0.5 * 0 + 1
  EXPECT_EQ(t.Alpha(), 6.5);
  EXPECT_EQ(t.Beta(), 5.0);
  // With no new evidence (weights 0) the state relaxes to (alpha0, beta0) geometrically.
  const TrustUpdateRule decay_only = Weights(0.0, 0.0, 0.5);
  t.Update(0.3, decay_only);
  EXPECT_EQ(t.Alpha(), 6.25);
  EXPECT_EQ(t.Beta(), 4.5);
  for (int i = 0; i < 200; ++i) t.Update(0.3, decay_only);
  EXPECT_EQ(t.Mean(), 0.6);
}

TEST(BetaTrust, StaticRuleLeavesTrustUnchangedExactly) {
  BetaTrust t = BetaTrust::FromMean(0.6, 10.0);
  const double alpha = t.Alpha(), beta = t.Beta(), mean = t.Mean();
  std::mt19937_64 rng(7);
  const TrustUpdateRule rule = Weights(0.0, 0.0, 0.0);
  for (int i = 0; i < 1000; ++i) {
    t.Update(kAllEncounterOutcomes[static_cast<int>(Uniform01(rng) * kEncounterOutcomeCount)],
             rule);
  }
  EXPECT_EQ(t.Alpha(), alpha);
  EXPECT_EQ(t.Beta(), beta);
  EXPECT_EQ(t.Mean(), mean);
  // ... and the long-run analysis says every trust is stationary.
  const LinearLikelihood linear(2.0);
  for (double theta = 0.0; theta <= 1.0; theta += 0.05) {
    EXPECT_EQ(MeanDrift(theta, {Policy::kTaEbp, {}}, kPaper, linear, rule, 6.0, 4.0), 0.0);
  }
  EXPECT_TRUE(
      FindLongRunTrust({Policy::kTaEbp, {}}, kPaper, linear, rule, 6.0, 4.0).equilibria.empty());
}

TEST(BetaTrust, Validation) {
  EXPECT_THAT(InvalidArgumentMessage([] { BetaTrust(0.0, 1.0); }),
              HasSubstr("trust alpha0 = 0 must be > 0 and finite"));
  EXPECT_THAT(InvalidArgumentMessage([] { BetaTrust(1.0, NAN); }),
              HasSubstr("trust beta0 = nan must be > 0 and finite"));
  EXPECT_THAT(InvalidArgumentMessage([] { BetaTrust::FromMean(1.0, 10.0); }),
              HasSubstr("initial trust mean = 1 is outside (0, 1)"));
  EXPECT_THAT(InvalidArgumentMessage([] { BetaTrust::FromMean(0.5, -2.0); }),
              HasSubstr("trust strength alpha0 + beta0 = -2 must be > 0 and finite"));
  BetaTrust t(1.0, 1.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { t.Update(1.2, TrustUpdateRule{}); }),
              HasSubstr("encounter quality q = 1.2 is outside [0, 1]"));
}

// ------------------------------------------------------------------ one encounter

TEST(SchemeFor, DefinedAtEveryTrustDownToTheToleranceBelowThetaStar) {
  // The long-run scan bisects the TA-EBP switch at theta*, so it evaluates the
  // design within round-off of theta*, where the p-space tie tolerance still
  // persuades (down to theta* - kTieTolerance / (1 - lambda)).
  const LinearLikelihood linear(2.0);
  const double theta_star = AvHvThetaStar(kPaper);
  for (int k = -20; k <= 20; ++k) {
    const double theta = theta_star + k * 1e-10;
    const CommittedScheme scheme = SchemeFor({Policy::kTaEbp, {}}, kPaper, theta, linear);
    EXPECT_EQ(scheme.av_may_go, AvHvPersuadable(kPaper, theta, linear)) << "k " << k;
    if (scheme.av_may_go) {
      EXPECT_NEAR(scheme.nudge, 2.0, 1e-6);
      EXPECT_LE(scheme.b, 1e-8);  // b(theta*) = 0, db/dtheta = 0.8 there
    }
  }
}

TEST(OutcomeProbabilities, PaperTaebpByHand) {
  // theta = 0.6, the AV designs for it: s* = 64/39, a = 1, b = 7/32.
  const LinearLikelihood linear(2.0);
  const auto p =
      OutcomeProbabilities(CommitScheme(Policy::kTaEbp, kPaper, 0.6, linear), kPaper, 0.6, linear);
  EXPECT_NEAR(p[static_cast<int>(EncounterOutcome::kNudgeGo)], 0.2, 1e-15);
  EXPECT_NEAR(p[static_cast<int>(EncounterOutcome::kNudgeStop)], 0.8 * 7.0 / 32.0, 1e-15);
  EXPECT_NEAR(p[static_cast<int>(EncounterOutcome::kStillStop)], 0.8 * 25.0 / 32.0, 1e-15);
  EXPECT_EQ(p[static_cast<int>(EncounterOutcome::kStillGo)], 0.0);
  EXPECT_EQ(p[static_cast<int>(EncounterOutcome::kCollision)], 0.0);
  EXPECT_EQ(p[static_cast<int>(EncounterOutcome::kNearMiss)], 0.0);
  // No Trust against theta = 0.6: every Go intent collides (Table I's 0.2).
  const auto q = OutcomeProbabilities(CommitScheme(Policy::kNoTrust, kPaper, 0.6, linear), kPaper,
                                      0.6, linear);
  EXPECT_NEAR(q[static_cast<int>(EncounterOutcome::kCollision)], 0.2, 1e-15);
  EXPECT_NEAR(q[static_cast<int>(EncounterOutcome::kNudgeStop)], 0.8 * 0.375, 1e-15);
}

TEST(OutcomeProbabilities, AgreeWithPredictOutcomeOverAGrid) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 4.0, 1.0);
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (double lambda : {0.1, 0.2, 0.35, 0.5}) {
      for (double r : {1.5, 3.0, 6.0}) {
        const AvHvParams params{lambda, r};
        for (Policy policy :
             {Policy::kNoEbp, Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
          for (double theta_hat : {0.1, 0.3, 0.6, 0.9}) {
            const CommittedScheme scheme = CommitScheme(policy, params, theta_hat, *model);
            for (double theta = 0.0; theta <= 1.0; theta += 0.05) {
              const auto p = OutcomeProbabilities(scheme, params, theta, *model);
              const PredictedOutcome o = PredictOutcome(scheme, params, theta, *model);
              double total = 0.0;
              for (double x : p) {
                EXPECT_GE(x, 0.0);
                EXPECT_LE(x, 1.0);
                total += x;
              }
              EXPECT_NEAR(total, 1.0, 1e-14);
              EXPECT_NEAR(p[static_cast<int>(EncounterOutcome::kCollision)], o.collision_rate,
                          1e-14);
              EXPECT_NEAR(p[static_cast<int>(EncounterOutcome::kNudgeGo)] +
                              p[static_cast<int>(EncounterOutcome::kStillGo)],
                          o.av_first_rate, 1e-14);
              // Nudged then yielded: every nudged Stop intent, and nudged Go intents
              // when the scheme never lets the AV go. A nudge of 0 is standing still.
              const double nudged_yield =
                  scheme.nudge > 0.0
                      ? (1.0 - lambda) * scheme.b + (scheme.av_may_go ? 0.0 : lambda * scheme.a)
                      : 0.0;
              EXPECT_NEAR(p[static_cast<int>(EncounterOutcome::kNudgeStop)], nudged_yield, 1e-14);
              if (scheme.nudge == 0.0) {
                EXPECT_EQ(p[static_cast<int>(EncounterOutcome::kNudgeGo)], 0.0);
              }
              EXPECT_EQ(p[static_cast<int>(EncounterOutcome::kNearMiss)], 0.0);
            }
          }
        }
      }
    }
  }
}

TEST(ExpectedStep, GainsAndTheExactMeanChangeTendToTheDrift) {
  const LinearLikelihood linear(2.0);
  const TrustUpdateRule rule = Weights(1.0, 3.0);
  for (Policy policy : {Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
    for (double mean : {0.1, 0.3, 0.55, 0.8, 0.95}) {
      // A state with this mean and a large total: N E[mean change] -> G(mean).
      const double n = 1e8;
      const BetaTrust state(mean * n, (1.0 - mean) * n);
      const ExpectedUpdate step = ExpectedStep(state, {policy, {}}, kPaper, linear, rule);
      const double q = ExpectedQuality({policy, {}}, kPaper, state.Mean(), linear, rule.quality);
      EXPECT_EQ(step.quality, q);
      EXPECT_NEAR(step.alpha, q, 1e-15);
      EXPECT_NEAR(step.beta, 3.0 * (1.0 - q), 1e-15);
      const double drift = MeanDrift(state.Mean(), {policy, {}}, kPaper, linear, rule, 1.0, 1.0);
      EXPECT_NEAR(n * step.mean, drift, 1e-6) << taebp::PolicyName(policy) << " mean " << mean;
    }
  }
}

// ------------------------------------------------------------------ long run: closed forms

// The roots of a stretch where Q is constant (closed form) and of the TA-EBP
// stretch (quadratic) against the piecewise scan + TOMS 748.
TEST(LongRunTrust, PaperSettingByHand) {
  const LinearLikelihood linear(2.0);
  const TrustUpdateRule equal = Weights(1.0, 1.0);
  // TA-EBP tracking theta, w_s = w_f: theta = Q(theta) = 1 - (0.8 theta - 0.2)/(1 + theta),
  // i.e. theta^2 + 0.8 theta - 1.2 = 0.
  const double taebp = (-0.8 + std::sqrt(0.64 + 4.8)) / 2.0;
  const LongRunTrust ta = FindLongRunTrust({Policy::kTaEbp, {}}, kPaper, linear, equal, 6.0, 4.0);
  ASSERT_EQ(ta.equilibria.size(), 1u);
  EXPECT_NEAR(ta.equilibria[0].theta, taebp, 1e-12);
  EXPECT_EQ(ta.equilibria[0].kind, TrustEquilibrium::Kind::kRoot);
  EXPECT_TRUE(ta.equilibria[0].stable);
  const std::vector<double> closed = TaebpEquilibria(kPaper, equal, 6.0, 4.0, 0.25, 1.0);
  ASSERT_EQ(closed.size(), 1u);
  EXPECT_NEAR(closed[0], taebp, 1e-15);
  // The AV's design switches at theta* (fallback below it).
  ASSERT_EQ(ta.breakpoints.size(), 1u);
  EXPECT_NEAR(ta.breakpoints[0], 0.25, 1e-8);

  // No Trust: s = 16/11 persuades only theta = 1, so below 1 every Go intent
  // collides (q = 0) and b = 3/8 of the Stop intents are false alarms:
  // Q = 0.8 * 5/8 = 0.5, theta = 0.5.
  const LongRunTrust nt = FindLongRunTrust({Policy::kNoTrust, {}}, kPaper, linear, equal, 6.0, 4.0);
  ASSERT_EQ(nt.Attractors().size(), 1u);
  EXPECT_NEAR(nt.Attractors()[0], 0.5, 1e-12);
  EXPECT_EQ(ConstantQualityEquilibrium(0.5, equal, 6.0, 4.0), 0.5);

  // Full revelation (b = 0) never raises a false alarm: trust grows to 1.
  const LongRunTrust fr =
      FindLongRunTrust({Policy::kFullReveal, {}}, kPaper, linear, equal, 6.0, 4.0);
  ASSERT_EQ(fr.equilibria.size(), 1u);
  EXPECT_EQ(fr.equilibria[0].theta, 1.0);
  EXPECT_EQ(fr.equilibria[0].kind, TrustEquilibrium::Kind::kBoundary);
  EXPECT_TRUE(fr.equilibria[0].stable);
  // No EBP never signals, so every encounter confirms "standing still means Stop".
  const LongRunTrust ne = FindLongRunTrust({Policy::kNoEbp, {}}, kPaper, linear, equal, 6.0, 4.0);
  ASSERT_EQ(ne.Attractors(), std::vector<double>{1.0});
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(LongRunTrust, TaebpClosedFormMatchesTheScanOverAGrid) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 4.0, 1.0);
  int checked = 0;
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (double lambda : {0.1, 0.2, 0.3}) {
      for (double r : {2.0, 3.0, 5.0}) {
        const AvHvParams params{lambda, r};
        if (!(lambda < AvHvPStar(r))) continue;
        const double theta_star = AvHvModelTrustThreshold(params, *model).theta_star;
        for (double w_f : {0.5, 1.0, 4.0}) {
          for (double rho : {0.0, 0.01, 0.2}) {
            for (double false_alarm_q : {0.0, 0.3}) {
              TrustUpdateRule rule = Weights(1.0, w_f, rho);
              rule.quality.nudge_stop = false_alarm_q;
              const double a0 = 3.0, b0 = 2.0;
              const LongRunTrust scan =
                  FindLongRunTrust({Policy::kTaEbp, {}}, params, *model, rule, a0, b0);
              // The roots of the scan inside the TA-EBP stretch are the quadratic's.
              std::vector<double> inside;
              for (const TrustEquilibrium& e : scan.equilibria) {
                if (e.kind == TrustEquilibrium::Kind::kRoot && e.theta > theta_star + 1e-6) {
                  inside.push_back(e.theta);
                }
              }
              const std::vector<double> closed =
                  TaebpEquilibria(params, rule, a0, b0, theta_star + 1e-6, 1.0);
              ASSERT_EQ(inside.size(), closed.size())
                  << model->Name() << " lambda " << lambda << " r " << r << " w_f " << w_f
                  << " rho " << rho;
              for (std::size_t i = 0; i < closed.size(); ++i) {
                EXPECT_NEAR(inside[i], closed[i], 1e-11);
                ++checked;
              }
              // Each reported root is a zero of the drift, and the drift has the
              // sign the stability flag claims on either side.
              for (const TrustEquilibrium& e : scan.equilibria) {
                if (e.kind != TrustEquilibrium::Kind::kRoot) continue;
                EXPECT_NEAR(MeanDrift(e.theta, {Policy::kTaEbp, {}}, params, *model, rule, a0, b0),
                            0.0, 1e-12);
                const double below =
                    MeanDrift(e.theta - 1e-6, {Policy::kTaEbp, {}}, params, *model, rule, a0, b0);
                const double above =
                    MeanDrift(e.theta + 1e-6, {Policy::kTaEbp, {}}, params, *model, rule, a0, b0);
                EXPECT_EQ(e.stable, below > 0.0 && above < 0.0);
              }
            }
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(LongRunTrust, ConstantQualityClosedFormIsAConvexCombination) {
  // theta_rho = (rho N0 theta0 + W theta_0) / (rho N0 + W), W = w_s Q + w_f (1 - Q),
  // theta_0 = w_s Q / W: between the initial mean and the no-forgetting limit,
  // moving toward the initial mean as rho grows.
  const double a0 = 6.0, b0 = 4.0, theta0 = 0.6;
  for (double q : {0.0, 0.2, 0.5, 0.9, 1.0}) {
    for (double w_f : {0.5, 1.0, 5.0}) {
      const double limit = ConstantQualityEquilibrium(q, Weights(1.0, w_f), a0, b0);
      EXPECT_DOUBLE_EQ(limit, q / (q + w_f * (1.0 - q)));
      double previous = limit;
      for (double rho : {0.001, 0.01, 0.1, 0.5, 1.0}) {
        const double theta = ConstantQualityEquilibrium(q, Weights(1.0, w_f, rho), a0, b0);
        EXPECT_GE(theta, std::min(theta0, limit) - 1e-15);
        EXPECT_LE(theta, std::max(theta0, limit) + 1e-15);
        EXPECT_LE(std::abs(theta - theta0), std::abs(previous - theta0) + 1e-15);
        previous = theta;
      }
    }
  }
  EXPECT_TRUE(std::isnan(ConstantQualityEquilibrium(0.5, Weights(0.0, 0.0), a0, b0)));
}

// ------------------------------------------------------------------ false alarms

TEST(LongRunTrust, FalseAlarmsErodeTrust) {
  const LinearLikelihood linear(2.0);
  // Forgiving false alarms (q = 1 for nudge_stop) TA-EBP's trust grows to 1;
  // counting them it settles below 1, the lower the harsher a failure weighs.
  TrustUpdateRule forgiving = Weights(1.0, 1.0);
  forgiving.quality.nudge_stop = 1.0;
  EXPECT_EQ(
      FindLongRunTrust({Policy::kTaEbp, {}}, kPaper, linear, forgiving, 6.0, 4.0).Attractors(),
      std::vector<double>{1.0});
  double previous = 1.0;
  for (double w_f : {0.5, 1.0, 2.0, 4.0, 8.0, 20.0, 100.0}) {
    const auto attractors =
        FindLongRunTrust({Policy::kTaEbp, {}}, kPaper, linear, Weights(1.0, w_f), 6.0, 4.0)
            .Attractors();
    ASSERT_EQ(attractors.size(), 1u) << "w_f " << w_f;
    EXPECT_LT(attractors[0], previous);
    // A TA-EBP AV that tracks trust stops false alarms at theta* (b(theta*) = 0),
    // so its own false alarms can never push trust below theta*.
    EXPECT_GT(attractors[0], 0.25);
    previous = attractors[0];
  }
  // The more false alarms are forgiven, the higher the long-run trust.
  previous = 0.0;
  for (double q : {0.0, 0.25, 0.5, 0.75, 0.99}) {
    TrustUpdateRule rule = Weights(1.0, 4.0);
    rule.quality.nudge_stop = q;
    const auto attractors =
        FindLongRunTrust({Policy::kTaEbp, {}}, kPaper, linear, rule, 6.0, 4.0).Attractors();
    ASSERT_EQ(attractors.size(), 1u);
    EXPECT_GT(attractors[0], previous);
    previous = attractors[0];
  }
}

TEST(LongRunTrust, AFixedHonestDesignCanPushTrustBelowThetaStar) {
  // The paper's static design for theta_hat = 0.6 (s* = 64/39, b = 7/32) kept
  // while trust moves. Above 0.6: Q = 0.2 + 0.8 * 25/32 = 0.825; below: the Go
  // intents collide, Q = 0.625. With w_f = 6 w_s the false alarms pull trust out
  // of the persuaded stretch (0.825 / (0.825 + 6 * 0.175) = 0.44 < 0.6) and it
  // settles at 0.625 / (0.625 + 6 * 0.375) = 0.217 < theta* = 0.25.
  const LinearLikelihood linear(2.0);
  const TrustUpdateRule rule = Weights(1.0, 6.0);
  const LongRunTrust run = FindLongRunTrust({Policy::kTaEbp, 0.6}, kPaper, linear, rule, 6.0, 4.0);
  ASSERT_EQ(run.Attractors().size(), 1u);
  EXPECT_NEAR(run.Attractors()[0], 0.625 / (0.625 + 6.0 * 0.375), 1e-12);
  EXPECT_LT(run.Attractors()[0], AvHvThetaStar(kPaper));
  ASSERT_EQ(run.breakpoints.size(), 1u);
  EXPECT_NEAR(run.breakpoints[0], 0.6, 1e-8);
  // Without false alarms (b = 0: full revelation) the same weights keep trust at 1.
  EXPECT_EQ(
      FindLongRunTrust({Policy::kFullReveal, {}}, kPaper, linear, rule, 6.0, 4.0).Attractors(),
      std::vector<double>{1.0});
}

TEST(LongRunTrust, BistableFullRevealAndDecayToZero) {
  const LinearLikelihood linear(2.0);
  // Full revelation with w_f = 20: below theta* the Go intents collide,
  // Q = 0.8, theta = 0.8 / (0.8 + 20 * 0.2) = 1/6; above, Q = 1 and trust grows
  // to 1. theta* separates the two basins (an unstable jump).
  const LongRunTrust run =
      FindLongRunTrust({Policy::kFullReveal, {}}, kPaper, linear, Weights(1.0, 20.0), 6.0, 4.0);
  ASSERT_EQ(run.equilibria.size(), 3u);
  EXPECT_NEAR(run.equilibria[0].theta, 1.0 / 6.0, 1e-12);
  EXPECT_TRUE(run.equilibria[0].stable);
  EXPECT_NEAR(run.equilibria[1].theta, 0.25, 1e-8);
  EXPECT_EQ(run.equilibria[1].kind, TrustEquilibrium::Kind::kJump);
  EXPECT_FALSE(run.equilibria[1].stable);
  EXPECT_EQ(run.equilibria[2].theta, 1.0);
  EXPECT_TRUE(run.equilibria[2].stable);
  // Only failures count (w_s = 0) under No Trust: trust decays to 0.
  const LongRunTrust decay =
      FindLongRunTrust({Policy::kNoTrust, {}}, kPaper, linear, Weights(0.0, 1.0), 6.0, 4.0);
  ASSERT_EQ(decay.Attractors(), std::vector<double>{0.0});
  EXPECT_EQ(decay.equilibria[0].kind, TrustEquilibrium::Kind::kBoundary);
}

TEST(LongRunTrust, StableJump) {
  // An (unusual) mapping under which Q drops where the fixed design starts to
  // persuade: Go intents that collide count as successes and confirmed Gos as
  // failures. Below 0.6 Q = 0.825, above Q = 0.625; with w_f = 2 the roots of
  // both stretches lie on the other side (0.702, 0.455), so the drift changes
  // sign only across the jump at 0.6, which attracts.
  const LinearLikelihood linear(2.0);
  TrustUpdateRule rule = Weights(1.0, 2.0);
  rule.quality.collision = 1.0;
  rule.quality.nudge_go = 0.0;
  const LongRunTrust run = FindLongRunTrust({Policy::kTaEbp, 0.6}, kPaper, linear, rule, 6.0, 4.0);
  ASSERT_EQ(run.equilibria.size(), 1u);
  EXPECT_EQ(run.equilibria[0].kind, TrustEquilibrium::Kind::kJump);
  EXPECT_TRUE(run.equilibria[0].stable);
  EXPECT_NEAR(run.equilibria[0].theta, 0.6, 1e-8);
}

TEST(LongRunTrust, ErrorsNameTheInput) {
  const LinearLikelihood linear(2.0);
  EXPECT_THAT(
      InvalidArgumentMessage([&] {
        FindLongRunTrust({Policy::kTaEbp, {}}, kPaper, linear, Weights(1.0, 1.0), 6.0, 4.0, 1);
      }),
      HasSubstr("grid = 1 must be >= 2"));
  EXPECT_THAT(
      InvalidArgumentMessage([&] {
        FindLongRunTrust({Policy::kTaEbp, 1.5}, kPaper, linear, Weights(1.0, 1.0), 6.0, 4.0);
      }),
      HasSubstr("assumed trust theta_hat = 1.5 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] {
                TaebpEquilibria(AvHvParams{0.5, 3.0}, Weights(1.0, 1.0), 6.0, 4.0, 0.0, 1.0);
              }),
              HasSubstr("prior_go (lambda) = 0.5 is not below p* = 0.4"));
  EXPECT_THAT(InvalidArgumentMessage([&] {
                MeanDrift(0.5, {Policy::kTaEbp, {}}, kPaper, linear, Weights(1.0, 1.0), -1.0, 4.0);
              }),
              HasSubstr("trust alpha0 = -1 must be > 0 and finite"));
}

}  // namespace
}  // namespace taebp::persuasion
