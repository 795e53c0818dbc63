// The trust-aware persuasion LP (GLPK) against closed forms: the prosecutor
// example of Section II-B and the TA-EBP design of Section IV-C.
#include "taebp/persuasion/lp.h"

#include "taebp/persuasion/av_hv.h"
#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glpk.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

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

// ------------------------------------------------------------ numerics

// The largest gap by which a recommended action a trails the receiver's best
// action at a's own posterior (0 when every recommendation is obedient).
double WorstObedienceGap(const Game& g, const LpResult& lp) {
  double worst = 0.0;
  for (Eigen::Index a = 0; a < lp.posteriors.cols(); ++a) {
    if (std::isnan(lp.posteriors(0, a))) continue;
    const Eigen::VectorXd u = ExpectedUtilities(g.receiver_utility, lp.posteriors.col(a));
    worst = std::max(worst, u.maxCoeff() - u(a));
  }
  return worst;
}

// Both entries of state w1 at 1e17: recommending x is obedient only if
// dU0(x, y) = 0.5 * 0 + 0.5 * (-1) = -0.5 is weighed in, which a difference of
// the two expected utilities (0.5e17 - (0.5e17 + 0.5), rounded to 0) lost: the
// LP used to report -0.5 with a disobedient x. Right: x is never recommended, -1.
TEST(TrustAwareLp, LargeEqualUtilitiesDoNotHideThePriorGain) {
  Game g;
  g.states = {"w1", "w2"};
  g.actions = {"x", "y"};
  g.prior = Eigen::Vector2d(0.5, 0.5);
  g.receiver_utility.resize(2, 2);
  g.receiver_utility << 1e17, 1e17,  //
      0.0, 1.0;
  g.sender_utility.resize(2, 2);
  g.sender_utility << 0.0, -1.0,  //
      0.0, -1.0;
  const LpResult lp = SolveTrustAwarePersuasion(g, 0.5);
  ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
  EXPECT_NEAR(lp.sender_value, -1.0, 1e-9);
  EXPECT_NEAR(lp.signal_probability(0), 0.0, 1e-9);
  EXPECT_EQ(WorstObedienceGap(g, lp), 0.0);
}

// Adding a constant to one state's utilities changes no decision (obedience
// depends on differences only), so the LP's answer must not move either: with
// utilities in quarters and shifts by powers of two up to 2^50 every input is
// exact, so any change is the LP's own cancellation. Scaling every utility by
// 1e300 or 1e-300 changes nothing either.
TEST(TrustAwareLp, InvariantToShiftingAStateAndScalingTheTables) {
  Game base;
  base.states = {"w1", "w2", "w3"};
  base.actions = {"a", "b", "c"};
  base.prior = Eigen::Vector3d(0.5, 0.3, 0.2);
  base.receiver_utility.resize(3, 3);
  base.receiver_utility << 1.0, 0.0, 0.25,  //
      0.0, 1.0, 0.25,                       //
      0.0, 0.0, 1.0;
  base.sender_utility.resize(3, 3);
  base.sender_utility << 0.0, 1.0, 2.0,  //
      0.0, 1.0, 2.0,                     //
      0.5, 1.0, 0.0;
  int moved = 0;
  for (double theta : {0.0, 0.3, 0.6, 1.0}) {
    const LpResult reference = SolveTrustAwarePersuasion(base, theta);
    ASSERT_EQ(reference.status, LpResult::Status::kOptimal) << reference.message;
    moved += reference.sender_value > 1e-6;
    for (double shift : {0x1p10, 0x1p30, 0x1p50}) {
      for (int w = 0; w < 3; ++w) {
        Game g = base;
        g.receiver_utility.row(w).array() += shift;
        const LpResult lp = SolveTrustAwarePersuasion(g, theta);
        ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
        EXPECT_NEAR(lp.sender_value, reference.sender_value, 1e-9)
            << "theta = " << theta << ", state " << w << " + " << shift;
        EXPECT_LT((lp.scheme - reference.scheme).cwiseAbs().maxCoeff(), 1e-7)
            << "theta = " << theta << ", state " << w << " + " << shift;
      }
    }
    for (double factor : {1e300, 1e-300}) {
      Game g = base;
      g.receiver_utility *= factor;
      g.sender_utility *= factor;
      const LpResult lp = SolveTrustAwarePersuasion(g, theta);
      ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
      EXPECT_NEAR(lp.sender_value / factor, reference.sender_value, 1e-9) << factor;
      EXPECT_LT((lp.scheme - reference.scheme).cwiseAbs().maxCoeff(), 1e-7) << factor;
    }
  }
  EXPECT_GE(moved, 2);  // persuasion happens at some theta: the test is not trivial
}

// A receiver row [1e308, -1e308] made u(w,a) - u(w,a') infinite and GLPK abort
// the process. Now: w1 favours x by 2e308, w2 favours y by a negligible 1, so a
// sender who always wants x gets it in both states (value 1), with any trust.
TEST(TrustAwareLp, ExtremeFiniteUtilitiesSolve) {
  Game g;
  g.states = {"w1", "w2"};
  g.actions = {"x", "y"};
  g.prior = Eigen::Vector2d(0.5, 0.5);
  g.receiver_utility.resize(2, 2);
  g.receiver_utility << 1e308, -1e308,  //
      0.0, 1.0;
  g.sender_utility.resize(2, 2);
  g.sender_utility << 1.0, 0.0,  //
      1.0, 0.0;
  for (double theta : {0.0, 0.5, 1.0}) {
    const LpResult lp = SolveTrustAwarePersuasion(g, theta);
    ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
    EXPECT_NEAR(lp.sender_value, 1.0, 1e-9);
  }
  // Huge sender utilities: the value is reported in their units.
  g.sender_utility << 1e308, -1e308,  //
      1e308, -1e308;
  const LpResult lp = SolveTrustAwarePersuasion(g, 1.0);
  ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
  EXPECT_EQ(lp.sender_value, 1e308);
}

// The prosecutor with utilities of +-1e308: u(w,a) - u(w,a') = +-2e308 would be
// infinite, yet the game is the prosecutor's (an affine transform of the judge's
// utility), so the answer must be too, at every trust level.
TEST(TrustAwareLp, ProsecutorAtTheEdgeOfTheDoubleRange) {
  Game huge = Prosecutor();
  huge.receiver_utility << -1e308, 1e308,  //
      1e308, -1e308;
  for (int i = 0; i <= 10; ++i) {
    const double theta = i / 10.0;
    const LpResult reference = SolveTrustAwarePersuasion(Prosecutor(), theta);
    const LpResult lp = SolveTrustAwarePersuasion(huge, theta);
    ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
    EXPECT_NEAR(lp.sender_value, reference.sender_value, 1e-9) << "theta = " << theta;
    EXPECT_LT((lp.scheme - reference.scheme).cwiseAbs().maxCoeff(), 1e-7) << "theta = " << theta;
  }
}

// GLPK reports a fatal error through glp_error, which calls abort() unless an
// error hook is installed. Under RunGlpkGuarded it comes back as false with
// GLPK's own message, and GLPK is usable again afterwards.
void AddZeroColumns(void*) {
  glp_prob* lp = glp_create_prob();
  glp_add_cols(lp, 0);  // "invalid number of columns": a fatal GLPK error
  glp_delete_prob(lp);
}

void SolveNothing(void* arg) {
  glp_prob* lp = glp_create_prob();
  *static_cast<int*>(arg) = glp_get_num_cols(lp);
  glp_delete_prob(lp);
}

TEST(TrustAwareLp, GlpkErrorsComeBackInsteadOfAborting) {
  for (int i = 0; i < 3; ++i) {
    std::string error;
    EXPECT_FALSE(RunGlpkGuarded(AddZeroColumns, nullptr, &error));
    EXPECT_THAT(error, HasSubstr("glp_add_cols"));
    EXPECT_THAT(error, HasSubstr("invalid number of columns"));
    // GLPK works again: a guarded call that succeeds, then a whole LP.
    int columns = -1;
    EXPECT_TRUE(RunGlpkGuarded(SolveNothing, &columns, &error));
    EXPECT_EQ(columns, 0);
    EXPECT_EQ(error, "");
    const LpResult lp = SolveTrustAwarePersuasion(Prosecutor(), 1.0);
    ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
    EXPECT_NEAR(lp.sender_value, 0.6, 1e-9);
  }
}

// The lazily generated obedience rows give the optimum of the full LP (all
// m (m - 1) rows at once), on random games of several shapes and trust levels,
// and every recommendation is obedient at its own posterior.
TEST(TrustAwareLp, LazyRowsReachTheFullLpOptimum) {
  std::mt19937_64 rng(20240607);
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  int nontrivial = 0;
  for (int n : {2, 3, 5, 8}) {
    for (int m : {2, 3, 6, 12}) {
      for (int rep = 0; rep < 3; ++rep) {
        Game g;
        for (int i = 0; i < n; ++i) g.states.push_back("w" + std::to_string(i));
        for (int a = 0; a < m; ++a) g.actions.push_back("a" + std::to_string(a));
        g.prior.resize(n);
        for (int i = 0; i < n; ++i) g.prior(i) = 0.05 + unit(rng);
        g.prior /= g.prior.sum();
        g.receiver_utility.resize(n, m);
        g.sender_utility.resize(n, m);
        for (int i = 0; i < n; ++i) {
          for (int a = 0; a < m; ++a) {
            g.receiver_utility(i, a) = sym(rng);
            g.sender_utility(i, a) = sym(rng);
          }
        }
        const double no_information = g.sender_utility.col(DefaultAction(g)).dot(g.prior);
        for (double theta : {0.0, 0.4, 0.8, 1.0}) {
          LpOptions full_rows;
          full_rows.lazy_obedience = false;
          const LpResult full = SolveTrustAwarePersuasion(g, theta, full_rows);
          const LpResult lazy = SolveTrustAwarePersuasion(g, theta);
          ASSERT_EQ(full.status, LpResult::Status::kOptimal) << full.message;
          ASSERT_EQ(lazy.status, LpResult::Status::kOptimal) << lazy.message;
          const std::string where = std::to_string(n) + "x" + std::to_string(m) + " #" +
                                    std::to_string(rep) + " theta = " + std::to_string(theta);
          EXPECT_NEAR(lazy.sender_value, full.sender_value, 1e-8) << where;
          EXPECT_EQ(full.obedience_rows, m * (m - 1)) << where;
          EXPECT_LE(lazy.obedience_rows, m * (m - 1)) << where;
          // Never below the no-information value, nor above the sender's first best.
          EXPECT_GE(lazy.sender_value, no_information - 1e-9) << where;
          EXPECT_LE(lazy.sender_value, g.sender_utility.rowwise().maxCoeff().dot(g.prior) + 1e-9)
              << where;
          for (const LpResult* r : {&lazy, &full}) {
            EXPECT_TRUE(WeaklyPrefers(-WorstObedienceGap(g, *r), UtilityScale(g.receiver_utility),
                                      kObedienceTolerance))
                << where;
          }
          if (lazy.sender_value > no_information + 1e-6) ++nontrivial;
        }
      }
    }
  }
  EXPECT_GT(nontrivial, 50);
}

// Larger random games (the bench's distribution): GLPK's round-off, divided by a
// tiny P(a), can leave a rare recommendation visibly disobedient at its own
// posterior; such recommendations are merged into the receiver's best response,
// so every reported recommendation is obedient, and the value stays the full
// LP's (it moves by at most the merged recommendations' tiny probability).
TEST(TrustAwareLp, EveryRecommendationIsObedientOnLargerRandomGames) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  int merged = 0;
  for (int n : {30, 40, 50}) {
    Game g;
    for (int i = 0; i < n; ++i) {
      g.states.push_back("w" + std::to_string(i));
      g.actions.push_back("a" + std::to_string(i));
    }
    g.prior.resize(n);
    for (int i = 0; i < n; ++i) g.prior(i) = 0.1 + unit(rng);
    g.prior /= g.prior.sum();
    g.receiver_utility.resize(n, n);
    g.sender_utility.resize(n, n);
    for (int i = 0; i < n; ++i) {
      for (int a = 0; a < n; ++a) {
        g.receiver_utility(i, a) = sym(rng);
        g.sender_utility(i, a) = sym(rng);
      }
    }
    for (double theta : {0.7, 1.0}) {
      const LpResult lp = SolveTrustAwarePersuasion(g, theta);
      ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
      const std::string where = std::to_string(n) + "x" + std::to_string(n) + " theta = " +
                                std::to_string(theta);
      EXPECT_TRUE(WeaklyPrefers(-WorstObedienceGap(g, lp), UtilityScale(g.receiver_utility),
                                kObedienceTolerance))
          << where << ": gap " << WorstObedienceGap(g, lp);
      merged += lp.merged_recommendations;
      if (n <= 40) {
        LpOptions full_rows;
        full_rows.lazy_obedience = false;
        const LpResult full = SolveTrustAwarePersuasion(g, theta, full_rows);
        ASSERT_EQ(full.status, LpResult::Status::kOptimal) << full.message;
        EXPECT_NEAR(lp.sender_value, full.sender_value, 1e-5) << where;
      }
    }
  }
  // The games are big enough to exercise the merge (GLPK 5.0 on these seeds).
  EXPECT_GT(merged, 0);
}

// Above the documented limits the LP is refused up front, naming the size.
TEST(TrustAwareLp, RefusesGamesAboveTheLimits) {
  auto game = [](int n, int m) {
    Game g;
    for (int i = 0; i < n; ++i) g.states.push_back("w" + std::to_string(i));
    for (int a = 0; a < m; ++a) g.actions.push_back("a" + std::to_string(a));
    g.prior = Eigen::VectorXd::Constant(n, 1.0 / n);
    g.receiver_utility = Eigen::MatrixXd::Zero(n, m);
    g.sender_utility = Eigen::MatrixXd::Zero(n, m);
    return g;
  };
  EXPECT_THAT(InvalidArgumentMessage([&] { SolveTrustAwarePersuasion(game(201, 200), 0.5); }),
              HasSubstr("201 states and 200 actions: 40200 scheme entries"));
  EXPECT_THAT(InvalidArgumentMessage([&] { SolveTrustAwarePersuasion(game(2, 4001), 0.5); }),
              HasSubstr("32008000 obedience coefficients, above the LP's limits of 40000 and 16000000"));
  // At the limits it still solves (all-zero utilities: everything ties).
  EXPECT_EQ(SolveTrustAwarePersuasion(game(2, 2000), 0.5).status, LpResult::Status::kOptimal);
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
