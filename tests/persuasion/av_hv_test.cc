// The AV-HV game: eq:ppp, eq:tt, eq:pp, Theorem 2 (eq:s^*), eq:b and the TA-EBP
// design of Section IV-C, with the paper's numbers (Section V-A) worked by hand.
#include "taebp/persuasion/av_hv.h"

#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

const AvHvParams kPaper{0.2, 3.0};  // lambda = 0.2, r = 3 (Section V-A)

const std::vector<double> kLambdas = {0.01, 0.05, 0.1, 0.2, 0.3, 0.35, 0.4, 0.5, 0.7, 0.9, 0.99};
const std::vector<double> kPenalties = {0.1, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 50.0};

// eq:tt written out independently of the implementation.
double EqTt(double lambda, double r) {
  return (2.0 * (1.0 - lambda) - r * lambda) / ((1.0 - lambda) * (r + 2.0));
}

// ------------------------------------------------------------ paper numbers

TEST(AvHvPaperNumbers, ThresholdsNudgesAndB) {
  const LinearLikelihood linear(2.0);
  EXPECT_DOUBLE_EQ(AvHvPStar(3.0), 0.4);      // 2 / (2 + 3)
  EXPECT_DOUBLE_EQ(AvHvThetaStar(kPaper), 0.25);  // (1.6 - 0.6) / (0.8 * 5)
  // Required ratio at theta = 0.6: 0.8 (0.4 - 0.08) / (0.2 (0.6 + 0.08 - 0.4)) = 32/7,
  // s* = 2R / (1 + R) = 64/39 = 1.641025...
  EXPECT_NEAR(RequiredRatio(kPaper, 0.6), 32.0 / 7.0, 1e-13);
  EXPECT_NEAR(MinimalNudge(kPaper, 0.6, linear), 64.0 / 39.0, 1e-13);
  EXPECT_NEAR(MinimalNudge(kPaper, 0.6, linear), 1.6410256, 1e-7);
  // The trust-agnostic nudge: R = 0.8 * 0.4 / (0.2 * 0.6) = 8/3, s = 16/11 = 1.4545...
  EXPECT_NEAR(RequiredRatio(kPaper, 1.0), 8.0 / 3.0, 1e-13);
  EXPECT_NEAR(MinimalNudge(kPaper, 1.0, linear), 16.0 / 11.0, 1e-13);
  // eq:b: 0.2 (0.6 - 0.4 + 0.08) / (0.8 (0.4 - 0.08)) = 0.056 / 0.256 = 7/32.
  EXPECT_NEAR(StopNudgeProbability(kPaper, 0.6), 7.0 / 32.0, 1e-15);
  EXPECT_NEAR(StopNudgeProbability(kPaper, 1.0), 0.375, 1e-15);  // 0.2*0.6 / (0.8*0.4)
}

TEST(AvHvPaperNumbers, Design) {
  const TaebpDesign d = DesignTaebp(kPaper, 0.6, LinearLikelihood(2.0));
  EXPECT_TRUE(d.persuadable);
  EXPECT_DOUBLE_EQ(d.theta_star, 0.25);
  EXPECT_DOUBLE_EQ(d.p_star, 0.4);
  EXPECT_NEAR(d.s_star, 64.0 / 39.0, 1e-13);
  EXPECT_EQ(d.a, 1.0);
  EXPECT_NEAR(d.b, 0.21875, 1e-15);
  // P(s*) = 0.2 + 0.8 * 7/32 = 0.375 (the paper's prose says 37.6%).
  EXPECT_NEAR(d.p_nudge, 0.375, 1e-15);
}

TEST(AvHvPaperNumbers, TrustAgnosticNudgeFailsOnTheRealHv) {
  const LinearLikelihood linear(2.0);
  // At s = 16/11: L = 8/3, p_FT = (8/3 * 0.2) / (8/3 * 0.2 + 0.8) = 0.4,
  // p_0.6 = 0.4 * 0.2 + 0.6 * 0.4 = 0.32 < p* = 0.4 -> DR.
  const double p = HvPosteriorGo(kPaper, 0.6, linear, 16.0 / 11.0);
  EXPECT_NEAR(p, 0.32, 1e-15);
  EXPECT_FALSE(HvDrivesIfClear(kPaper, p));
  // A fully trusting HV would be exactly at p*.
  EXPECT_NEAR(HvPosteriorGo(kPaper, 1.0, linear, 16.0 / 11.0), 0.4, 1e-15);
  EXPECT_TRUE(HvDrivesIfClear(kPaper, HvPosteriorGo(kPaper, 1.0, linear, 16.0 / 11.0)));
}

TEST(AvHvGame, MatchesUtilityTable) {
  const Game g = AvHvGame(kPaper);
  EXPECT_NO_THROW(g.Validate());
  EXPECT_EQ(g.states[kGo], "Go");
  EXPECT_EQ(g.actions[kDC], "DC");
  EXPECT_EQ(g.receiver_utility(kGo, kDR), -3.0);
  EXPECT_EQ(g.receiver_utility(kStop, kDR), 1.0);
  EXPECT_EQ(g.receiver_utility(kGo, kDC), 0.0);
  EXPECT_EQ(g.receiver_utility(kStop, kDC), -1.0);
  EXPECT_EQ(g.sender_utility(kGo, kDR), -1.0);
  EXPECT_EQ(g.sender_utility(kStop, kDC), 1.0);
  EXPECT_DOUBLE_EQ(g.prior(kGo), 0.2);
  // eq:ppp from the general 2x2 formula; rows (Go, Stop), columns (DC, DR).
  Eigen::Matrix2d u;
  u << g.receiver_utility(kGo, kDC), g.receiver_utility(kGo, kDR),  //
      g.receiver_utility(kStop, kDC), g.receiver_utility(kStop, kDR);
  for (double r : kPenalties) {
    u(0, 1) = -r;
    EXPECT_NEAR(IndifferencePosterior(u), AvHvPStar(r), 1e-15) << "r = " << r;
  }
  EXPECT_EQ(DefaultAction(g), kDR);
}

TEST(HvPosteriorGo, ExactAtTheEndsOfTheNudgeRange) {
  const LinearLikelihood linear(2.0);
  for (double theta : {0.0, 0.3, 0.6, 1.0}) {
    EXPECT_EQ(HvPosteriorGo(kPaper, theta, linear, 0.0), (1.0 - theta) * 0.2);
    EXPECT_EQ(HvPosteriorGo(kPaper, theta, linear, 2.0), (1.0 - theta) * 0.2 + theta);
  }
}

// ----------------------------------------------------- Theorem 1 invariants

TEST(AvHvThetaStar, InvariantsOverGrid) {
  for (double lambda : kLambdas) {
    for (double r : kPenalties) {
      const AvHvParams params{lambda, r};
      const double p_star = AvHvPStar(r);
      const double theta_star = AvHvThetaStar(params);
      EXPECT_GE(theta_star, 0.0);
      EXPECT_LE(theta_star, 1.0);
      if (lambda >= p_star) {
        EXPECT_EQ(theta_star, 0.0) << lambda << " " << r;
        continue;
      }
      EXPECT_NEAR(theta_star, EqTt(lambda, r), 1e-15);
      EXPECT_GT(theta_star, 0.0);
      // Remark: p* = (1 - theta*) lambda + theta* p_FT(Go | s_max), p_FT = 1.
      EXPECT_NEAR(p_star, (1.0 - theta_star) * lambda + theta_star, 1e-12) << lambda << " " << r;
    }
  }
}

TEST(AvHvThetaStar, GeneralTheoremCorollaryAndClosedFormAgree) {
  const LinearLikelihood linear(2.0);
  for (double lambda : kLambdas) {
    for (double r : kPenalties) {
      const AvHvParams params{lambda, r};
      if (lambda >= AvHvPStar(r)) continue;  // see LambdaAboveThreshold below
      const Game game = AvHvGame(params);
      const TrustThreshold unrestricted = MinPersuadableTrust(game);
      EXPECT_TRUE(unrestricted.persuadable);
      EXPECT_EQ(unrestricted.default_action, kDR);
      EXPECT_EQ(unrestricted.target_action, kDC);
      // eq:theta_two_states with w1 = Go, a1 = DC, a2 = DR: du(Go) = 0 - (-r), du(Stop) = -1 - 1.
      const double corollary = TwoStateTrustThreshold(lambda, r, -2.0);
      EXPECT_NEAR(unrestricted.theta_star, corollary, 1e-12) << lambda << " " << r;
      EXPECT_NEAR(corollary, AvHvThetaStar(params), 1e-12) << lambda << " " << r;
      // Finite signal set {s = 0, s = s_max} of the linear model: s_max reveals Go.
      Eigen::Matrix2d signals;
      signals << linear.PiGo(0.0), linear.PiGo(2.0),  //
          linear.PiStop(0.0), linear.PiStop(2.0);
      EXPECT_NEAR(MinPersuadableTrust(game, signals).theta_star, EqTt(lambda, r), 1e-12);
      EXPECT_NEAR(AvHvModelTrustThreshold(params, linear).theta_star, EqTt(lambda, r), 1e-12);
    }
  }
}

// For lambda >= p* the HV already drives if clear: AvHvThetaStar is 0, while the
// general theorem (which asks how to move the receiver off her default) now has
// DC as the default and reports the trust needed to push her to DR instead.
TEST(AvHvThetaStar, LambdaAboveThreshold) {
  for (const AvHvParams& params : {AvHvParams{0.5, 3.0}, AvHvParams{0.4, 3.0}, AvHvParams{0.3, 5.0}}) {
    EXPECT_EQ(AvHvThetaStar(params), 0.0);
    const TrustThreshold model = AvHvModelTrustThreshold(params, LinearLikelihood(2.0));
    EXPECT_EQ(model.theta_star, 0.0);
    EXPECT_TRUE(model.persuadable);
    EXPECT_EQ(model.target_action, kDC);
    EXPECT_EQ(DefaultAction(AvHvGame(params)), kDC);  // lambda = p* = 0.4 ties toward the AV
    EXPECT_EQ(MinPersuadableTrust(AvHvGame(params)).target_action, kDR);
  }
}

TEST(AvHvThetaStar, DecreasingInLambdaAndR) {
  for (double r : kPenalties) {
    double previous = 2.0;
    for (double lambda = 0.005; lambda < AvHvPStar(r); lambda += 0.005) {
      const double t = AvHvThetaStar({lambda, r});
      EXPECT_LT(t, previous) << "lambda = " << lambda << ", r = " << r;
      previous = t;
    }
  }
  for (double lambda : {0.01, 0.1, 0.2, 0.35}) {
    double previous = 2.0;
    for (double r = 0.05; AvHvPStar(r) > lambda; r += 0.05) {
      const double t = AvHvThetaStar({lambda, r});
      EXPECT_LT(t, previous) << "lambda = " << lambda << ", r = " << r;
      previous = t;
    }
  }
}

// The paper's partial derivatives of eq:tt against central differences.
TEST(AvHvThetaStar, PartialDerivativesMatchThePaper) {
  const double h = 1e-6;
  for (double lambda : {0.05, 0.1, 0.2, 0.3}) {
    for (double r : {0.5, 1.0, 2.0, 3.0}) {
      if (lambda + h >= AvHvPStar(r + h)) continue;
      const double d_lambda = (AvHvThetaStar({lambda + h, r}) - AvHvThetaStar({lambda - h, r})) / (2 * h);
      const double d_r = (AvHvThetaStar({lambda, r + h}) - AvHvThetaStar({lambda, r - h})) / (2 * h);
      EXPECT_NEAR(d_lambda, -r / ((r + 2.0) * (1.0 - lambda) * (1.0 - lambda)), 1e-7);
      EXPECT_NEAR(d_r, 2.0 / ((lambda - 1.0) * (r + 2.0) * (r + 2.0)), 1e-7);
      EXPECT_LT(d_lambda, 0.0);
      EXPECT_LT(d_r, 0.0);
    }
  }
}

// ------------------------------------------------------- the tie at p*

TEST(HvDrivesIfClear, TieToleranceAtPStar) {
  const double p_star = AvHvPStar(3.0);
  EXPECT_TRUE(HvDrivesIfClear(kPaper, p_star));
  EXPECT_TRUE(HvDrivesIfClear(kPaper, p_star - 1e-12));
  EXPECT_FALSE(HvDrivesIfClear(kPaper, p_star - 1e-6));
  EXPECT_TRUE(HvDrivesIfClear(kPaper, 1.0));
  EXPECT_FALSE(HvDrivesIfClear(kPaper, 0.0));
  // The same tie through the general best response (utility gap 5e-12 vs 5e-6).
  const Game g = AvHvGame(kPaper);
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(p_star - 1e-12, 1.0 - p_star + 1e-12)), kDC);
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(p_star - 1e-6, 1.0 - p_star + 1e-6)), kDR);
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(p_star, 1.0 - p_star)), kDC);
}

// -------------------------------------------------------- Theorem 2 (eq:s^*)

TEST(MinimalNudge, PosteriorAtSStarIsPStarAndPersuades) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 3.0, 1.0);
  int checked_logistic = 0;
  for (double lambda : kLambdas) {
    for (double r : kPenalties) {
      const AvHvParams params{lambda, r};
      const double p_star = AvHvPStar(r);
      if (lambda >= p_star) continue;
      const double theta_star = AvHvThetaStar(params);
      for (int i = 1; i <= 20; ++i) {
        const double theta = std::min(1.0, theta_star + (1.0 - theta_star) * i / 20.0);
        const double s = MinimalNudge(params, theta, linear);
        EXPECT_GE(s, 0.0);
        EXPECT_LE(s, 2.0);
        const double p = HvPosteriorGo(params, theta, linear, s);
        EXPECT_NEAR(p, p_star, 1e-12) << lambda << " " << r << " " << theta;
        EXPECT_TRUE(HvDrivesIfClear(params, p));
        if (AvHvPersuadable(params, theta, logistic)) {
          const double s_log = MinimalNudge(params, theta, logistic);
          const double p_log = HvPosteriorGo(params, theta, logistic, s_log);
          EXPECT_TRUE(HvDrivesIfClear(params, p_log));
          if (s_log < 2.0) {
            EXPECT_NEAR(p_log, p_star, 2e-12) << lambda << " " << r << " " << theta;
          }
          ++checked_logistic;
        }
      }
    }
  }
  EXPECT_GT(checked_logistic, 100);
}

TEST(MinimalNudge, StrictlyDecreasingInTrustAboveThreshold) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 3.0, 1.0);
  // (All three are persuadable under both models: p_FT(Go|s_max) > p* for the logistic.)
  for (const AvHvParams& params : {kPaper, AvHvParams{0.1, 3.0}, AvHvParams{0.35, 3.0}}) {
    for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                         static_cast<const LikelihoodModel*>(&logistic)}) {
      const double theta_star = AvHvModelTrustThreshold(params, *model).theta_star;
      double previous = MinimalNudge(params, theta_star, *model);
      for (int i = 1; i <= 50; ++i) {
        const double theta = std::min(1.0, theta_star + (1.0 - theta_star) * i / 50.0);
        const double s = MinimalNudge(params, theta, *model);
        EXPECT_LT(s, previous) << model->Name() << " theta = " << theta;
        previous = s;
      }
    }
  }
}

TEST(MinimalNudge, AtTheThresholdOnlyTheStrongestNudgeWorks) {
  const LinearLikelihood linear(2.0);
  EXPECT_EQ(RequiredRatio(kPaper, 0.25), kInf);
  EXPECT_EQ(MinimalNudge(kPaper, 0.25, linear), 2.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { MinimalNudge(kPaper, 0.2, linear); }),
              HasSubstr("trust theta = 0.2 is below the minimum persuadable trust theta* = 0.25"));
}

TEST(MinimalNudge, LambdaAtOrAbovePStar) {
  const LinearLikelihood linear(2.0);
  // lambda = p* = 0.4: R = 0.6 * 0.4 theta / (0.4 * 0.6 theta) = 1 -> s = 1 for any theta > 0
  // (a still AV reads as Stop, so some nudge is needed to keep the HV at p*).
  for (double theta : {0.1, 0.5, 1.0}) {
    EXPECT_NEAR(RequiredRatio({0.4, 3.0}, theta), 1.0, 1e-12);
    EXPECT_NEAR(MinimalNudge({0.4, 3.0}, theta, linear), 1.0, 1e-12);
  }
  EXPECT_EQ(MinimalNudge({0.4, 3.0}, 0.0, linear), 0.0);  // no trust: the prior already ties
  // lambda = 0.5 > p*: at theta = 0.1 the prior weight alone gives 0.45 >= 0.4, no nudge.
  EXPECT_LE(RequiredRatio({0.5, 3.0}, 0.1), 0.0);
  EXPECT_EQ(MinimalNudge({0.5, 3.0}, 0.1, linear), 0.0);
  // At theta = 0.5, p_FT must reach (0.4 - 0.25) / 0.5 = 0.3: R = 3/7, s = 2R/(1+R) = 0.6.
  EXPECT_NEAR(MinimalNudge({0.5, 3.0}, 0.5, linear), 0.6, 1e-12);
}

// ------------------------------------------------------------------- eq:b

TEST(StopNudgeProbability, SchemePosteriorIsPStarAndBIsOneOverR) {
  for (double lambda : kLambdas) {
    for (double r : kPenalties) {
      const AvHvParams params{lambda, r};
      const double p_star = AvHvPStar(r);
      if (lambda >= p_star) {
        EXPECT_EQ(StopNudgeProbability(params, 0.0), 1.0);
        EXPECT_EQ(StopNudgeProbability(params, 0.7), 1.0);
        continue;
      }
      const double theta_star = AvHvThetaStar(params);
      EXPECT_NEAR(StopNudgeProbability(params, theta_star), 0.0, 1e-12);
      for (int i = 1; i <= 10; ++i) {
        const double theta = std::min(1.0, theta_star + (1.0 - theta_star) * i / 10.0);
        const double b = StopNudgeProbability(params, theta);
        EXPECT_GE(b, 0.0);
        EXPECT_LE(b, 1.0);
        EXPECT_NEAR(b, 1.0 / RequiredRatio(params, theta), 1e-12);
        // Scheme posterior with pi(s*|Go) = 1, pi(s*|Stop) = b equals p*.
        const double scheme_posterior =
            (1.0 - theta) * lambda + theta * lambda / (lambda + b * (1.0 - lambda));
        EXPECT_NEAR(scheme_posterior, p_star, 1e-12);
      }
    }
  }
}

TEST(StopNudgeProbability, ThrowsBelowThreshold) {
  EXPECT_THAT(InvalidArgumentMessage([] { StopNudgeProbability(kPaper, 0.1); }),
              HasSubstr("trust theta = 0.1 is below the minimum persuadable trust theta* = 0.25"));
}

// ----------------------------------------------------------------- design

TEST(DesignTaebp, FallbackBelowThreshold) {
  const TaebpDesign d = DesignTaebp(kPaper, 0.2, LinearLikelihood(2.0));
  EXPECT_FALSE(d.persuadable);
  EXPECT_DOUBLE_EQ(d.theta_star, 0.25);
  EXPECT_DOUBLE_EQ(d.p_star, 0.4);
  EXPECT_EQ(d.s_star, 0.0);
  EXPECT_EQ(d.a, 0.0);
  EXPECT_EQ(d.b, 0.0);
  EXPECT_EQ(d.p_nudge, 0.0);
}

TEST(DesignTaebp, AtThresholdIsFullRevelation) {
  const TaebpDesign d = DesignTaebp(kPaper, 0.25, LinearLikelihood(2.0));
  EXPECT_TRUE(d.persuadable);
  EXPECT_EQ(d.s_star, 2.0);
  EXPECT_NEAR(d.b, 0.0, 1e-12);
  EXPECT_NEAR(d.p_nudge, 0.2, 1e-12);
}

TEST(DesignTaebp, LambdaAbovePStarAlwaysNudges) {
  const TaebpDesign d = DesignTaebp({0.5, 3.0}, 0.5, LinearLikelihood(2.0));
  EXPECT_TRUE(d.persuadable);
  EXPECT_EQ(d.theta_star, 0.0);
  EXPECT_EQ(d.b, 1.0);
  EXPECT_EQ(d.p_nudge, 1.0);
  EXPECT_NEAR(d.s_star, 0.6, 1e-12);
}

// --------------------------------------------------------------- logistic

TEST(LogisticModel, ThresholdIsHigherAndMatchesBoundedForm) {
  const LogisticLikelihood logistic(2.0, 3.0, 1.0);
  for (double lambda : kLambdas) {
    for (double r : kPenalties) {
      const AvHvParams params{lambda, r};
      const double p_star = AvHvPStar(r);
      if (lambda >= p_star) continue;
      // p_FT(Go|s_max) with L(s_max) = e^3; theta* = (p* - lambda) / (q - lambda).
      const double q = std::exp(3.0) * lambda / (std::exp(3.0) * lambda + 1.0 - lambda);
      const double expected = std::min(1.0, (p_star - lambda) / (q - lambda));
      const TrustThreshold t = AvHvModelTrustThreshold(params, logistic);
      EXPECT_NEAR(t.theta_star, expected, 1e-12) << lambda << " " << r;
      EXPECT_EQ(t.persuadable, q > p_star) << lambda << " " << r;  // else theta* = 1
      EXPECT_GT(t.theta_star, AvHvThetaStar(params));
      EXPECT_NEAR(DesignTaebp(params, 1.0, logistic).theta_star, t.theta_star, 1e-15);
    }
  }
}

TEST(LogisticModel, PaperParameters) {
  const LogisticLikelihood logistic(2.0, 3.0, 1.0);
  const double q = std::exp(3.0) * 0.2 / (std::exp(3.0) * 0.2 + 0.8);
  const double theta_star = (0.4 - 0.2) / (q - 0.2);  // ~0.3155
  EXPECT_NEAR(AvHvModelTrustThreshold(kPaper, logistic).theta_star, theta_star, 1e-12);
  // Between the linear and the logistic thresholds no nudge in [0, 2] suffices.
  EXPECT_THAT(InvalidArgumentMessage([&] { MinimalNudge(kPaper, 0.3, logistic); }),
              HasSubstr("trust theta = 0.3 is below the minimum persuadable trust"));
  EXPECT_THAT(InvalidArgumentMessage([&] { MinimalNudge(kPaper, 0.3, logistic); }),
              HasSubstr("logistic likelihood model"));
  const TaebpDesign fallback = DesignTaebp(kPaper, 0.3, logistic);
  EXPECT_FALSE(fallback.persuadable);
  EXPECT_NEAR(fallback.theta_star, theta_star, 1e-12);
  // Exactly at the threshold: s_max, and the HV is persuaded there.
  EXPECT_NEAR(MinimalNudge(kPaper, theta_star, logistic), 2.0, 1e-9);
  const TaebpDesign d = DesignTaebp(kPaper, 0.6, logistic);
  EXPECT_TRUE(d.persuadable);
  EXPECT_NEAR(HvPosteriorGo(kPaper, 0.6, logistic, d.s_star), 0.4, 1e-12);
  // Same required ratio (32/7) as the linear model, read through L^{-1} = m + log(R)/k.
  EXPECT_NEAR(d.s_star, 1.0 + std::log(32.0 / 7.0) / 3.0, 1e-11);
  EXPECT_NEAR(d.b, 7.0 / 32.0, 1e-15);
}

TEST(LogisticModel, MidpointAtSMaxNeverPersuades) {
  const LogisticLikelihood flat_top(2.0, 3.0, 2.0);  // L(s_max) = 1: uninformative at best
  const TrustThreshold t = AvHvModelTrustThreshold(kPaper, flat_top);
  EXPECT_FALSE(t.persuadable);
  EXPECT_EQ(t.theta_star, 1.0);
  EXPECT_FALSE(DesignTaebp(kPaper, 1.0, flat_top).persuadable);
  EXPECT_THAT(InvalidArgumentMessage([&] { MinimalNudge(kPaper, 1.0, flat_top); }),
              HasSubstr("below the minimum persuadable trust"));
}

// ---------------------------------------------------------- bad parameters

TEST(AvHvParams, RejectsLambdaOutsideOpenUnitInterval) {
  for (const auto& bad : {std::pair{0.0, "0"}, std::pair{1.0, "1"}, std::pair{-0.1, "-0.1"},
                          std::pair{kNaN, "nan"}}) {
    const AvHvParams params{bad.first, 3.0};
    const std::string expected = std::string("prior_go (lambda) = ") + bad.second + " is outside (0, 1)";
    std::string why;
    EXPECT_FALSE(params.IsValid(&why));
    EXPECT_THAT(why, HasSubstr(expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { params.Validate(); }), HasSubstr(expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { AvHvThetaStar(params); }), HasSubstr(expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { AvHvGame(params); }), HasSubstr(expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { DesignTaebp(params, 0.5, LinearLikelihood()); }),
                HasSubstr(expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { HvPosteriorGo(params, 0.5, LinearLikelihood(), 1.0); }),
                HasSubstr(expected));
  }
}

TEST(AvHvParams, RejectsNonPositivePenalty) {
  EXPECT_THAT(InvalidArgumentMessage([] { AvHvParams{0.2, -1.0}.Validate(); }),
              HasSubstr("collision_penalty r = -1 must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { AvHvParams{0.2, 0.0}.Validate(); }),
              HasSubstr("collision_penalty r = 0 must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { AvHvParams{0.2, kNaN}.Validate(); }),
              HasSubstr("collision_penalty r = nan must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { AvHvParams{0.2, kInf}.Validate(); }),
              HasSubstr("collision_penalty r = inf must be finite"));
  EXPECT_THAT(InvalidArgumentMessage([] { AvHvPStar(-1.0); }), HasSubstr("collision_penalty r = -1 must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { MinimalNudge({0.2, 0.0}, 0.5, LinearLikelihood()); }),
              HasSubstr("collision_penalty r = 0 must be > 0"));
}

TEST(AvHvParams, RejectsTrustOutsideUnitInterval) {
  const LinearLikelihood linear(2.0);
  for (const auto& bad : {std::pair{-0.1, "-0.1"}, std::pair{1.3, "1.3"}, std::pair{kNaN, "nan"}}) {
    const double theta = bad.first;
    const std::string text = bad.second;
    const std::string expected = "theta = " + text + " is outside [0, 1]";
    EXPECT_THAT(InvalidArgumentMessage([&] { HvPosteriorGo(kPaper, theta, linear, 1.0); }),
                HasSubstr("trust " + expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { RequiredRatio(kPaper, theta); }), HasSubstr("trust " + expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { MinimalNudge(kPaper, theta, linear); }),
                HasSubstr("trust " + expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { StopNudgeProbability(kPaper, theta); }),
                HasSubstr("trust " + expected));
    EXPECT_THAT(InvalidArgumentMessage([&] { DesignTaebp(kPaper, theta, linear); }),
                HasSubstr("trust theta_hat = " + text + " is outside [0, 1]"));
  }
}

TEST(AvHvParams, RejectsSignalsOutsideRangeAndBadPosteriors) {
  const LinearLikelihood linear(2.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { HvPosteriorGo(kPaper, 0.6, linear, 2.5); }),
              HasSubstr("signal s = 2.5 is outside [0, 2]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { HvPosteriorGo(kPaper, 0.6, linear, -1.0); }),
              HasSubstr("signal s = -1 is outside [0, 2]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { HvDrivesIfClear(kPaper, 1.5); }),
              HasSubstr("posterior p_go = 1.5 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { HvDrivesIfClear(kPaper, kNaN); }),
              HasSubstr("posterior p_go = nan is outside [0, 1]"));
}

}  // namespace
}  // namespace taebp::persuasion
