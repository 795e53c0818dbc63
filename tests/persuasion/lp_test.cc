// The trust-aware persuasion LP (GLPK) against closed forms: the prosecutor
// example of Section II-B and the TA-EBP design of Section IV-C.
#include "taebp/persuasion/lp.h"

#include "taebp/persuasion/av_hv.h"
#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

enum { kInnocent = 0, kGuilty = 1 };
enum { kConvict = 0, kAcquit = 1 };

// Judge: 1 for a correct verdict; prosecutor: 1 for a conviction.
Game Prosecutor() {
  Game g;
  g.states = {"innocent", "guilty"};
  g.actions = {"convict", "acquit"};
  g.prior = Eigen::Vector2d(0.7, 0.3);
  g.receiver_utility.resize(2, 2);
  g.receiver_utility << 0.0, 1.0,  //
      1.0, 0.0;
  g.sender_utility.resize(2, 2);
  g.sender_utility << 1.0, 0.0,  //
      1.0, 0.0;
  return g;
}

TEST(TrustAwareLp, ProsecutorWithFullTrust) {
  const LpResult lp = SolveTrustAwarePersuasion(Prosecutor(), 1.0);
  ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
  EXPECT_NEAR(lp.sender_value, 0.6, 1e-9);
  EXPECT_NEAR(lp.scheme(kInnocent, kConvict), 3.0 / 7.0, 1e-9);
  EXPECT_NEAR(lp.scheme(kInnocent, kAcquit), 4.0 / 7.0, 1e-9);
  EXPECT_NEAR(lp.scheme(kGuilty, kConvict), 1.0, 1e-9);
  EXPECT_NEAR(lp.scheme(kGuilty, kAcquit), 0.0, 1e-9);
  EXPECT_NEAR(lp.signal_probability(kConvict), 0.6, 1e-9);
  EXPECT_NEAR(lp.posteriors(kInnocent, kConvict), 0.5, 1e-9);
  EXPECT_NEAR(lp.posteriors(kGuilty, kConvict), 0.5, 1e-9);
  EXPECT_NEAR(lp.posteriors(kInnocent, kAcquit), 1.0, 1e-9);
  EXPECT_NEAR(lp.posteriors(kGuilty, kAcquit), 0.0, 1e-9);
}

// With trust theta the convict recommendation stays obedient while
//   (1 - theta)(0.3 + 0.7 t)(-0.4) + theta (0.3 - 0.7 t) >= 0,  t = pi(convict|innocent)
// (pi(convict|guilty) = 1), so t(theta) = (0.42 theta - 0.12) / (0.28 + 0.42 theta)
// for theta >= 2/7 and no conviction is possible below 2/7 (Theorem 1:
// 0.4 / (1 + 0.4) = 2/7).
TEST(TrustAwareLp, ProsecutorAcrossTrustLevels) {
  const Game g = Prosecutor();
  EXPECT_NEAR(MinPersuadableTrust(g).theta_star, 2.0 / 7.0, 1e-15);
  for (int i = 0; i <= 20; ++i) {
    const double theta = i / 20.0;
    const LpResult lp = SolveTrustAwarePersuasion(g, theta);
    ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
    const double t = theta >= 2.0 / 7.0 ? (0.42 * theta - 0.12) / (0.28 + 0.42 * theta) : 0.0;
    const double p_convict = theta >= 2.0 / 7.0 ? 0.3 + 0.7 * t : 0.0;
    EXPECT_NEAR(lp.sender_value, p_convict, 1e-9) << "theta = " << theta;
    EXPECT_NEAR(lp.signal_probability(kConvict), p_convict, 1e-9) << "theta = " << theta;
    if (p_convict > 0.0) {
      EXPECT_NEAR(lp.scheme(kInnocent, kConvict), t, 1e-9) << "theta = " << theta;
      // Obedience is tight: the judge is exactly indifferent after "convict".
      EXPECT_NEAR(lp.posteriors(kGuilty, kConvict), 0.5, 1e-9) << "theta = " << theta;
    } else {
      EXPECT_TRUE(std::isnan(lp.posteriors(kGuilty, kConvict)));
      EXPECT_TRUE(std::isnan(lp.posteriors(kInnocent, kConvict)));
      EXPECT_NEAR(lp.posteriors(kGuilty, kAcquit), 0.3, 1e-12);
    }
  }
  // theta = 0.5 worked by hand: t = 9/49, P(convict) = 3/7.
  EXPECT_NEAR(SolveTrustAwarePersuasion(g, 0.5).sender_value, 3.0 / 7.0, 1e-9);
}

// The LP over all schemes reaches exactly the closed-form TA-EBP design: P(DC) =
// lambda + (1 - lambda) b when theta >= theta*, 0 otherwise; value 2 P(DC) - 1.
TEST(TrustAwareLp, MatchesClosedFormTaebpDesign) {
  const LinearLikelihood linear(2.0);
  int above_p_star = 0, unpersuadable = 0, persuaded = 0;
  for (double lambda : {0.05, 0.1, 0.2, 0.3, 0.35, 0.4, 0.6}) {
    for (double r : {0.5, 1.0, 2.0, 3.0, 5.0}) {
      const AvHvParams params{lambda, r};
      const Game game = AvHvGame(params);
      const double p_star = AvHvPStar(r);
      for (int i = 0; i <= 10; ++i) {
        const double theta = i / 10.0;
        const LpResult lp = SolveTrustAwarePersuasion(game, theta);
        ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
        const TaebpDesign design = DesignTaebp(params, theta, linear);
        const double p_dc = design.persuadable ? design.p_nudge : 0.0;
        const std::string where = "lambda = " + std::to_string(lambda) + ", r = " +
                                  std::to_string(r) + ", theta = " + std::to_string(theta);
        EXPECT_NEAR(lp.signal_probability(kDC), p_dc, 1e-7) << where;
        EXPECT_NEAR(lp.sender_value, 2.0 * p_dc - 1.0, 1e-7) << where;
        EXPECT_NEAR(lp.signal_probability.sum(), 1.0, 1e-9) << where;
        for (int a = 0; a < 2; ++a) {
          if (std::isnan(lp.posteriors(0, a))) {
            EXPECT_LT(lp.signal_probability(a), 1e-12) << where;
            continue;
          }
          EXPECT_NEAR(lp.posteriors.col(a).sum(), 1.0, 1e-9) << where;
          // Obedience: the recommended action is a best response to its posterior.
          EXPECT_EQ(BestResponse(game, lp.posteriors.col(a), 1e-7), a) << where;
        }
        if (lambda >= p_star) {
          ++above_p_star;
          EXPECT_NEAR(lp.signal_probability(kDC), 1.0, 1e-9) << where;
        } else if (!design.persuadable) {
          ++unpersuadable;
        } else if (theta > design.theta_star + 1e-6) {
          ++persuaded;
          // The DC posterior sits exactly on p*, as eq:b makes it.
          EXPECT_NEAR(lp.posteriors(kGo, kDC), p_star, 1e-7) << where;
          EXPECT_NEAR(lp.scheme(kGo, kDC), 1.0, 1e-7) << where;
          EXPECT_NEAR(lp.scheme(kStop, kDC), design.b, 1e-7) << where;
        }
      }
    }
  }
  EXPECT_GT(above_p_star, 0);
  EXPECT_GT(unpersuadable, 0);
  EXPECT_GT(persuaded, 0);
}

TEST(TrustAwareLp, ThreeActionsNeverBeatFullInformationBound) {
  // Sender value with trust theta is nondecreasing in theta (more trust, more
  // obedient schemes) and never above the value of recommending the sender's
  // favourite everywhere.
  Game g;
  g.states = {"w1", "w2", "w3"};
  g.actions = {"a", "b", "c"};
  g.prior = Eigen::Vector3d(0.5, 0.3, 0.2);
  g.receiver_utility.resize(3, 3);
  g.receiver_utility << 1.0, 0.0, 0.2,  //
      0.0, 1.0, 0.2,                    //
      0.0, 0.0, 1.0;
  g.sender_utility.resize(3, 3);
  g.sender_utility << 0.0, 1.0, 2.0,  //
      0.0, 1.0, 2.0,                  //
      0.0, 1.0, 2.0;
  double previous = -1.0;
  for (int i = 0; i <= 10; ++i) {
    const LpResult lp = SolveTrustAwarePersuasion(g, i / 10.0);
    ASSERT_EQ(lp.status, LpResult::Status::kOptimal);
    EXPECT_GE(lp.sender_value, previous - 1e-9);
    EXPECT_LE(lp.sender_value, 2.0 + 1e-9);
    EXPECT_TRUE(((lp.scheme.rowwise().sum().array() - 1.0).abs() < 1e-9).all());
    EXPECT_TRUE((lp.scheme.array() >= 0.0).all());
    previous = lp.sender_value;
  }
  // theta = 0: no information gets through, the receiver plays her default (a).
  EXPECT_NEAR(SolveTrustAwarePersuasion(g, 0.0).sender_value, 0.0, 1e-9);
}

TEST(TrustAwareLp, StatusNamesAndBadInput) {
  EXPECT_STREQ(ToString(LpResult::Status::kOptimal), "optimal");
  EXPECT_STREQ(ToString(LpResult::Status::kInfeasible), "infeasible");
  EXPECT_STREQ(ToString(LpResult::Status::kSolverError), "solver error");
  EXPECT_THAT(InvalidArgumentMessage([] { SolveTrustAwarePersuasion(Prosecutor(), 1.3); }),
              HasSubstr("trust theta = 1.3 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([] {
                SolveTrustAwarePersuasion(Prosecutor(), std::numeric_limits<double>::quiet_NaN());
              }),
              HasSubstr("trust theta = nan is outside [0, 1]"));
  Game bad = Prosecutor();
  bad.prior = Eigen::Vector2d(1.2, -0.2);
  EXPECT_THAT(InvalidArgumentMessage([&] { SolveTrustAwarePersuasion(bad, 0.5); }),
              HasSubstr("prior[1] = -0.2 is negative"));
  bad = Prosecutor();
  bad.sender_utility = Eigen::MatrixXd::Zero(3, 2);
  EXPECT_THAT(InvalidArgumentMessage([&] { SolveTrustAwarePersuasion(bad, 0.5); }),
              HasSubstr("sender_utility has 3 rows but there are 2 states"));
}

}  // namespace
}  // namespace taebp::persuasion
