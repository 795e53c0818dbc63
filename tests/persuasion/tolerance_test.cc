// The tolerance policy (persuasion.h) at the boundaries: every decision about
// the receiver -- persuadable or not, drives if clear or not, which action is a
// best response, whether Theorem 1 counts an action -- is the same weak
// preference with ties toward the sender, so no two functions can disagree at
// theta*, at p* or at a zero gain.
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/lp.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/persuasion.h"

#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

const std::vector<double> kLambdas = {0.01, 0.05, 0.1, 0.2, 0.3, 0.35, 0.5, 0.7, 0.9, 0.99};
const std::vector<double> kPenalties = {0.01, 0.1, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 50.0};
// Offsets from theta*: exact, round-off sized, around the tolerance, and clear gaps.
const std::vector<double> kOffsets = {0.0,   1e-15, -1e-15, 1e-12, -1e-12, 1e-10, -1e-10,
                                      1e-9,  -1e-9, 5e-9,   -5e-9, 1e-8,   -1e-8,  5e-8,
                                      -5e-8, 1e-7,  -1e-7,  1e-6,  -1e-6,  1e-4,   -1e-4};

std::string Where(const LikelihoodModel& model, double lambda, double r, double theta) {
  std::ostringstream s;
  s.precision(17);
  s << model.Name() << " lambda = " << lambda << ", r = " << r << ", theta = " << theta;
  return s.str();
}

// The definition: the HV drives if clear iff DC is its best response (ties toward
// the AV, who prefers DC) in the general game.
bool DcIsBestResponse(const AvHvParams& params, double p_go) {
  return BestResponse(AvHvGame(params), Eigen::Vector2d(p_go, 1.0 - p_go)) == kDC;
}

// The reproduction: eq:pp at s_max is p* - 5e-10 (a tie), yet eq:b used
// to compare theta with theta* - 1e-9 and threw.
TEST(TolerancePolicy, DesignAtThetaStarMinus5e8DoesNotThrow) {
  const AvHvParams params{0.99, 0.01};
  const LinearLikelihood linear(2.0);
  const double theta = AvHvThetaStar(params) - 5e-8;
  TaebpDesign d;
  ASSERT_NO_THROW(d = DesignTaebp(params, theta, linear));
  EXPECT_TRUE(d.persuadable);
  EXPECT_EQ(d.s_star, 2.0);
  EXPECT_GE(d.b, 0.0);
  EXPECT_LE(d.b, 1.0);
  EXPECT_NO_THROW(StopNudgeProbability(params, theta));
  EXPECT_NO_THROW(PredictOutcome(Policy::kTaEbp, params, theta, linear));
}

// Around theta* on a grid of (lambda, r), for both likelihood models: DesignTaebp
// never throws, "persuadable" is the receiver's best response at the strongest
// nudge, and every part of the design (s*, b, the predicted outcome) agrees.
TEST(TolerancePolicy, DesignAgreesWithItselfAroundThetaStar) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 3.0, 1.0);
  int persuadable = 0, fallback = 0;
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (double lambda : kLambdas) {
      for (double r : kPenalties) {
        const AvHvParams params{lambda, r};
        const TrustThreshold threshold = AvHvModelTrustThreshold(params, *model);
        if (!threshold.persuadable) continue;
        bool previous = false;
        for (double offset : {-1e-4, -1e-6, -1e-7, -5e-8, -1e-8, -5e-9, -1e-9, -1e-10, -1e-12,
                              -1e-15, 0.0, 1e-15, 1e-12, 1e-10, 1e-9, 5e-9, 1e-8, 5e-8, 1e-7,
                              1e-6, 1e-4}) {
          const double theta = threshold.theta_star + offset;
          if (theta < 0.0 || theta > 1.0) continue;
          const std::string where = Where(*model, lambda, r, theta);
          TaebpDesign d;
          ASSERT_NO_THROW(d = DesignTaebp(params, theta, *model)) << where;
          const double strongest = HvPosteriorGo(params, theta, *model, model->SMax());
          EXPECT_EQ(d.persuadable, DcIsBestResponse(params, strongest)) << where;
          EXPECT_EQ(d.persuadable, AvHvPersuadable(params, theta, *model)) << where;
          // Persuadability is monotone in theta, and certain from theta* on.
          EXPECT_TRUE(d.persuadable || !previous) << where;
          previous = d.persuadable;
          if (offset >= 0.0) {
            EXPECT_TRUE(d.persuadable) << where;
          }
          if (!d.persuadable) {
            ++fallback;
            EXPECT_THAT(InvalidArgumentMessage([&] { MinimalNudge(params, theta, *model); }),
                        HasSubstr("below the minimum persuadable trust"))
                << where;
            continue;
          }
          ++persuadable;
          // The nudge persuades, read through the HV's model and through the scheme.
          EXPECT_TRUE(DcIsBestResponse(params, HvPosteriorGo(params, theta, *model, d.s_star)))
              << where;
          const double scheme_posterior =
              (1.0 - theta) * lambda + theta * lambda / (lambda + d.b * (1.0 - lambda));
          EXPECT_TRUE(DcIsBestResponse(params, scheme_posterior)) << where;
          EXPECT_GE(d.b, 0.0) << where;
          EXPECT_LE(d.b, 1.0) << where;
          EXPECT_EQ(MinimalNudge(params, theta, *model), d.s_star) << where;
          EXPECT_EQ(StopNudgeProbability(params, theta), d.b) << where;
          PredictedOutcome o;
          ASSERT_NO_THROW(o = PredictOutcome(Policy::kTaEbp, params, theta, *model)) << where;
          EXPECT_EQ(o.collision_rate, 0.0) << where;
        }
      }
    }
  }
  EXPECT_GT(persuadable, 500);
  EXPECT_GT(fallback, 100);
}

// HvDrivesIfClear is the general best response of the AV-HV game, point for
// point, on a dense grid around p* (in ulps, and around the tolerance).
TEST(TolerancePolicy, HvDrivesIfClearIsTheBestResponse) {
  for (double lambda : {0.2, 0.5}) {
    for (double r : kPenalties) {
      const AvHvParams params{lambda, r};
      const double p_star = AvHvPStar(r);
      std::vector<double> points = {p_star, 0.0, 1.0};
      double up = p_star, down = p_star;
      for (int k = 0; k < 64; ++k) {
        up = std::nextafter(up, 2.0);
        down = std::nextafter(down, -1.0);
        points.push_back(up);
        points.push_back(down);
      }
      for (double f = 0.01; f < 4.0; f *= 1.07) points.push_back(p_star - f * kTieTolerance);
      int dc = 0, dr = 0;
      for (double p : points) {
        const bool drives = HvDrivesIfClear(params, p);
        EXPECT_EQ(drives, DcIsBestResponse(params, p)) << "r = " << r << ", p = " << p;
        (drives ? dc : dr) += 1;
      }
      EXPECT_GT(dc, 0);
      EXPECT_GT(dr, 0);
      // p* itself is a tie and goes to the AV; a clear gap below it does not.
      EXPECT_TRUE(HvDrivesIfClear(params, p_star));
      EXPECT_FALSE(HvDrivesIfClear(params, p_star - 1e-6));
    }
  }
}

// lambda exactly at p* (exact in binary: r = 2, p* = 1/2; r = 6, p* = 1/4) and a
// round-off below it: the HV drives if clear at the prior, so every function says
// "no persuasion needed": default DC, theta* = 0, s*(0) = 0, b = 1.
TEST(TolerancePolicy, LambdaTiedWithPStar) {
  const LinearLikelihood linear(2.0);
  for (const AvHvParams& params :
       {AvHvParams{0.5, 2.0}, AvHvParams{0.25, 6.0}, AvHvParams{0.5 - 1e-12, 2.0},
        AvHvParams{0.25 - 1e-12, 6.0}, AvHvParams{AvHvPStar(3.0), 3.0},
        AvHvParams{std::nextafter(AvHvPStar(3.0), 0.0), 3.0}}) {
    std::ostringstream where;
    where.precision(17);
    where << "lambda = " << params.prior_go << ", r = " << params.collision_penalty;
    EXPECT_TRUE(HvDrivesIfClear(params, params.prior_go)) << where.str();
    EXPECT_EQ(DefaultAction(AvHvGame(params)), kDC) << where.str();
    EXPECT_EQ(AvHvThetaStar(params), 0.0) << where.str();
    const TrustThreshold t = AvHvModelTrustThreshold(params, linear);
    EXPECT_EQ(t.theta_star, 0.0) << where.str();
    EXPECT_EQ(t.default_action, kDC) << where.str();
    EXPECT_EQ(MinimalNudge(params, 0.0, linear), 0.0) << where.str();
    EXPECT_EQ(StopNudgeProbability(params, 0.0), 1.0) << where.str();
    const TaebpDesign d = DesignTaebp(params, 0.0, linear);
    EXPECT_TRUE(d.persuadable) << where.str();
    EXPECT_EQ(d.s_star, 0.0) << where.str();
    EXPECT_EQ(d.b, 1.0) << where.str();
    // With trust the still AV reads as Stop; the designed nudge lands on p*.
    for (double theta : {0.25, 0.5, 1.0}) {
      const TaebpDesign dt = DesignTaebp(params, theta, linear);
      EXPECT_TRUE(dt.persuadable) << where.str();
      EXPECT_TRUE(HvDrivesIfClear(params, HvPosteriorGo(params, theta, linear, dt.s_star)))
          << where.str() << ", theta = " << theta;
    }
  }
}

// A 2x2 game whose best full-trust gain is exactly 0: a1 ties with a0 when w1 is
// revealed. The receiver breaks the tie toward the sender (who likes a1), so a
// fully trusting receiver is persuadable (theta* = 1), exactly where the LP starts
// to gain.
Game ZeroGainGame() {
  Game g;
  g.states = {"w1", "w2"};
  g.actions = {"a0", "a1"};
  g.prior = Eigen::Vector2d(0.5, 0.5);
  g.receiver_utility.resize(2, 2);
  g.receiver_utility << 1.0, 1.0,  // w1: tie
      1.0, 0.0;                    // w2: a0 strictly better
  g.sender_utility.resize(2, 2);
  g.sender_utility << 0.0, 1.0,  //
      0.0, 1.0;
  return g;
}

TEST(TolerancePolicy, ZeroFullTrustGainIsATieTowardTheSender) {
  const Game g = ZeroGainGame();
  EXPECT_EQ(DefaultAction(g), 0);
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(1.0, 0.0)), 1);  // revealed w1: tie -> a1
  for (const TrustThreshold& t : {MinPersuadableTrust(g),
                                  MinPersuadableTrust(g, Eigen::Matrix2d::Identity())}) {
    EXPECT_TRUE(t.persuadable);
    EXPECT_EQ(t.theta_star, 1.0);
    EXPECT_EQ(t.target_action, 1);
    EXPECT_EQ(t.default_action, 0);
  }
  // The LP agrees: recommending a1 in w1 is obedient at theta = 1 (value 1/2), and
  // no scheme gains anything below theta* = 1.
  const LpResult full = SolveTrustAwarePersuasion(g, 1.0);
  ASSERT_EQ(full.status, LpResult::Status::kOptimal) << full.message;
  EXPECT_NEAR(full.sender_value, 0.5, 1e-9);
  for (double theta : {0.0, 0.5, 0.9, 0.999}) {
    const LpResult lp = SolveTrustAwarePersuasion(g, theta);
    ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
    EXPECT_NEAR(lp.sender_value, 0.0, 1e-9) << "theta = " << theta;
  }
  // A gain just below 0 (beyond round-off) is not a tie: never persuadable.
  Game strict = g;
  strict.receiver_utility(0, 1) = 1.0 - 1e-6;
  EXPECT_FALSE(MinPersuadableTrust(strict).persuadable);
  EXPECT_EQ(BestResponse(strict, Eigen::Vector2d(1.0, 0.0)), 0);
  EXPECT_NEAR(SolveTrustAwarePersuasion(strict, 1.0).sender_value, 0.0, 1e-9);
}

// Theorem 1 and the best response across 2x2 games: theta is persuadable (the
// best response to the trust posterior of the most favourable revelation is not
// the default) exactly when theta >= theta*, on both sides of theta* and for
// gains of every sign, including exact zeros.
TEST(TolerancePolicy, TheoremOneMatchesBestResponseOnTwoByTwoGames) {
  int checked = 0;
  for (double d1 : {-1.0, -0.5, 0.0, 0.25, 1.0, 3.0}) {
    for (double d2 : {-2.0, -1.0, 0.0, 0.5}) {
      for (double p1 : {0.2, 0.5, 0.8}) {
        Game g;
        g.states = {"w1", "w2"};
        g.actions = {"a0", "a1"};
        g.prior = Eigen::Vector2d(p1, 1.0 - p1);
        g.receiver_utility.resize(2, 2);
        g.receiver_utility << 0.0, d1,  //
            0.0, d2;
        g.sender_utility.resize(2, 2);
        g.sender_utility << 0.0, 1.0,  //
            0.0, 1.0;
        if (DefaultAction(g) != 0) continue;
        const TrustThreshold t = MinPersuadableTrust(g);
        for (int i = 0; i <= 20; ++i) {
          const double theta = i / 20.0;
          bool persuaded = false;
          for (int w = 0; w < 2; ++w) {
            Eigen::Vector2d reveal = Eigen::Vector2d::Zero();
            reveal(w) = 1.0;
            persuaded = persuaded || BestResponse(g, TrustPosterior(g.prior, reveal, theta)) == 1;
          }
          EXPECT_EQ(persuaded, t.persuadable && theta >= t.theta_star)
              << "d1 = " << d1 << ", d2 = " << d2 << ", p1 = " << p1 << ", theta = " << theta
              << ", theta* = " << t.theta_star;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 300);
}

}  // namespace
}  // namespace taebp::persuasion
