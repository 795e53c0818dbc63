// Finite persuasion core: validation, eq:bayes_update, trust posterior,
// eq:receiver_action tie breaking, Theorem 1 (eq:theta_star), its corollary
// (eq:theta_two_states) and eq:ppp.
#include "taebp/persuasion/persuasion.h"

#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Two states, two actions, a valid starting point for the validation tests.
Game SmallGame() {
  Game g;
  g.states = {"w1", "w2"};
  g.actions = {"a1", "a2"};
  g.prior = Eigen::Vector2d(0.3, 0.7);
  g.receiver_utility = Eigen::MatrixXd::Identity(2, 2);
  g.sender_utility = Eigen::MatrixXd::Zero(2, 2);
  return g;
}

// A three-action game worked by hand in the tests below.
//   prior (0.25, 0.75); u: a0 = (0, 1), a1 = (1, 0), a2 = (0.6, 0.6).
//   U(.|p0) = (0.75, 0.25, 0.6): default a0; dU0(a1) = -0.5, dU0(a2) = -0.15.
Game ThreeActionGame() {
  Game g;
  g.states = {"w1", "w2"};
  g.actions = {"a0", "a1", "a2"};
  g.prior = Eigen::Vector2d(0.25, 0.75);
  g.receiver_utility.resize(2, 3);
  g.receiver_utility << 0.0, 1.0, 0.6,  //
      1.0, 0.0, 0.6;
  g.sender_utility.resize(2, 3);
  g.sender_utility << 0.0, 1.0, 1.0,  //
      0.0, 1.0, 1.0;
  return g;
}

// ---------------------------------------------------------------- validation

TEST(GameValidation, AcceptsAValidGame) {
  std::string why = "untouched";
  EXPECT_TRUE(SmallGame().IsValid(&why));
  EXPECT_EQ(why, "untouched");
  EXPECT_NO_THROW(SmallGame().Validate());
}

TEST(GameValidation, RejectsDuplicateNames) {
  Game g = SmallGame();
  g.states = {"w1", "w1"};
  std::string why;
  EXPECT_FALSE(g.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("states: the name 'w1' appears twice (entries 0 and 1)"));
  g = ThreeActionGame();
  g.actions = {"a0", "a1", "a0"};
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }),
              HasSubstr("actions: the name 'a0' appears twice (entries 0 and 2)"));
}

TEST(GameValidation, RejectsNegativePriorEntry) {
  Game g = SmallGame();
  g.prior = Eigen::Vector2d(1.2, -0.2);
  std::string why;
  EXPECT_FALSE(g.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("prior[1] = -0.2 is negative"));
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }), HasSubstr("prior[1] = -0.2 is negative"));
}

TEST(GameValidation, RejectsZeroPriorEntry) {
  Game g = SmallGame();
  g.prior = Eigen::Vector2d(0.0, 1.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }), HasSubstr("prior[0] = 0 is not in the interior"));
}

TEST(GameValidation, RejectsNaNPriorEntry) {
  Game g = SmallGame();
  g.prior = Eigen::Vector2d(kNaN, 0.5);
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }), HasSubstr("prior[0] = nan is not finite"));
}

TEST(GameValidation, RejectsPriorNotSummingToOne) {
  Game g = SmallGame();
  g.prior = Eigen::Vector2d(0.5, 0.4);
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }), HasSubstr("prior must sum to 1 (sum = 0.9)"));
  g.prior = Eigen::Vector2d(0.5, 0.6);
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }), HasSubstr("prior must sum to 1 (sum = 1.1)"));
}

TEST(GameValidation, AcceptsPriorSumWithinTolerance) {
  Game g = SmallGame();
  g.prior = Eigen::Vector2d(0.3 + 1e-12, 0.7);
  EXPECT_NO_THROW(g.Validate());
}

TEST(GameValidation, RejectsPriorOfWrongSize) {
  Game g = SmallGame();
  g.prior = Eigen::Vector3d(0.2, 0.3, 0.5);
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }),
              HasSubstr("prior has 3 entries but there are 2 states"));
}

TEST(GameValidation, RejectsMismatchedUtilityShapes) {
  Game g = SmallGame();
  g.receiver_utility = Eigen::MatrixXd::Zero(3, 2);
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }),
              HasSubstr("receiver_utility has 3 rows but there are 2 states"));
  g = SmallGame();
  g.sender_utility = Eigen::MatrixXd::Zero(2, 3);
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }),
              HasSubstr("sender_utility has 3 columns but there are 2 actions"));
  g = SmallGame();
  g.receiver_utility(1, 1) = kNaN;
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }), HasSubstr("receiver_utility"));
}

TEST(GameValidation, RejectsTooFewStatesOrActions) {
  Game g = SmallGame();
  g.actions = {"only"};
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }), HasSubstr("at least 2 actions (got 1)"));
  g = SmallGame();
  g.states = {"only"};
  EXPECT_THAT(InvalidArgumentMessage([&] { g.Validate(); }), HasSubstr("at least 2 states (got 1)"));
}

TEST(GameValidation, FunctionsTakingAGameValidateIt) {
  Game g = SmallGame();
  g.prior = Eigen::Vector2d(0.5, 0.4);
  EXPECT_THAT(InvalidArgumentMessage([&] { BestResponse(g, Eigen::Vector2d(0.5, 0.5)); }),
              HasSubstr("prior must sum to 1"));
  EXPECT_THAT(InvalidArgumentMessage([&] { MinPersuadableTrust(g); }), HasSubstr("prior must sum to 1"));
  EXPECT_THAT(InvalidArgumentMessage([&] { MinPersuadableTrust(g, Eigen::Matrix2d::Identity()); }),
              HasSubstr("prior must sum to 1"));
}

// ------------------------------------------------------------ eq:bayes_update

TEST(BayesPosterior, MatchesHandComputation) {
  // Prosecutor, signal g with pi(g|innocent) = 3/7, pi(g|guilty) = 1:
  // joint = (0.7 * 3/7, 0.3) = (0.3, 0.3) -> (0.5, 0.5).
  const Eigen::VectorXd post = BayesPosterior(Eigen::Vector2d(0.7, 0.3), Eigen::Vector2d(3.0 / 7.0, 1.0));
  EXPECT_NEAR(post(0), 0.5, 1e-15);
  EXPECT_NEAR(post(1), 0.5, 1e-15);
}

TEST(BayesPosterior, RejectsBadInput) {
  EXPECT_THAT(InvalidArgumentMessage([] { BayesPosterior(Eigen::Vector2d(0.5, 0.5), Eigen::Vector3d(1, 1, 1)); }),
              HasSubstr("likelihood has 3 entries but prior has 2"));
  EXPECT_THAT(InvalidArgumentMessage([] { BayesPosterior(Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(1, -0.5)); }),
              HasSubstr("likelihood[1] = -0.5 is negative"));
  EXPECT_THAT(InvalidArgumentMessage([] { BayesPosterior(Eigen::Vector2d(1.2, -0.2), Eigen::Vector2d(1, 1)); }),
              HasSubstr("prior[1] = -0.2 is negative"));
  EXPECT_THAT(InvalidArgumentMessage([] { BayesPosterior(Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0, 1)); }),
              HasSubstr("zero probability"));
}

// Bayes plausibility: sum_s P(s) p_FT(.|s) = p0, and since p_theta is a convex
// combination with the prior, also sum_s P(s) p_theta(.|s) = p0.
TEST(BayesPosterior, RandomSchemesAreBayesPlausible) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> unit(0.01, 1.0);
  std::uniform_int_distribution<int> states(2, 5), signals(2, 6);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = states(rng), k = signals(rng);
    Eigen::VectorXd prior(n);
    for (int w = 0; w < n; ++w) prior(w) = unit(rng);
    prior /= prior.sum();
    Eigen::MatrixXd scheme(n, k);  // row w: pi(.|w), a distribution over k signals
    for (int w = 0; w < n; ++w) {
      for (int s = 0; s < k; ++s) scheme(w, s) = unit(rng);
      scheme.row(w) /= scheme.row(w).sum();
    }
    const double theta = unit(rng);
    Eigen::VectorXd mix_ft = Eigen::VectorXd::Zero(n), mix_theta = Eigen::VectorXd::Zero(n);
    double total = 0.0;
    for (int s = 0; s < k; ++s) {
      const Eigen::VectorXd lik = scheme.col(s);
      const double p_s = lik.dot(prior);
      const Eigen::VectorXd ft = BayesPosterior(prior, lik);
      EXPECT_NEAR(ft.sum(), 1.0, 1e-12);
      const Eigen::VectorXd trusted = TrustPosterior(prior, ft, theta);
      EXPECT_NEAR(trusted.sum(), 1.0, 1e-12);
      mix_ft += p_s * ft;
      mix_theta += p_s * trusted;
      total += p_s;
    }
    EXPECT_NEAR(total, 1.0, 1e-12);
    EXPECT_LT((mix_ft - prior).cwiseAbs().maxCoeff(), 1e-12) << "trial " << trial;
    EXPECT_LT((mix_theta - prior).cwiseAbs().maxCoeff(), 1e-12) << "trial " << trial;
  }
}

// ------------------------------------------------------------ trust posterior

TEST(TrustPosterior, InterpolatesBetweenPriorAndFullTrust) {
  const Eigen::Vector2d prior(0.2, 0.8), ft(1.0, 0.0);
  EXPECT_TRUE(TrustPosterior(prior, ft, 0.0).isApprox(prior));
  EXPECT_TRUE(TrustPosterior(prior, ft, 1.0).isApprox(ft));
  const Eigen::VectorXd mid = TrustPosterior(prior, ft, 0.6);  // 0.4*0.2 + 0.6*1 = 0.68
  EXPECT_NEAR(mid(0), 0.68, 1e-15);
  EXPECT_NEAR(mid(1), 0.32, 1e-15);
}

TEST(TrustPosterior, RejectsTrustOutsideUnitInterval) {
  const Eigen::Vector2d prior(0.2, 0.8), ft(1.0, 0.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { TrustPosterior(prior, ft, 1.3); }),
              HasSubstr("trust theta = 1.3 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { TrustPosterior(prior, ft, -0.1); }),
              HasSubstr("trust theta = -0.1 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { TrustPosterior(prior, ft, kNaN); }),
              HasSubstr("trust theta = nan is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { TrustPosterior(prior, Eigen::Vector3d(1, 0, 0), 0.5); }),
              HasSubstr("full_trust_posterior has 3 entries but prior has 2"));
}

// -------------------------------------------------------- eq:receiver_action

TEST(ExpectedUtilities, IsUtilityTransposeTimesBelief) {
  const Game g = ThreeActionGame();
  const Eigen::VectorXd u = ExpectedUtilities(g.receiver_utility, g.prior);
  EXPECT_NEAR(u(0), 0.75, 1e-15);
  EXPECT_NEAR(u(1), 0.25, 1e-15);
  EXPECT_NEAR(u(2), 0.6, 1e-15);
  EXPECT_THAT(InvalidArgumentMessage([&] { ExpectedUtilities(g.receiver_utility, Eigen::Vector3d(1, 0, 0)); }),
              HasSubstr("utility has 2 rows but belief has 3 entries"));
}

TEST(BestResponse, PicksTheReceiverOptimum) {
  const Game g = ThreeActionGame();
  EXPECT_EQ(DefaultAction(g), 0);
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(1.0, 0.0)), 1);  // U = (0, 1, 0.6)
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(0.5, 0.5)), 2);  // U = (0.5, 0.5, 0.6)
}

TEST(BestResponse, TiesBreakTowardTheSenderThenLowestIndex) {
  Game g = SmallGame();
  g.prior = Eigen::Vector2d(0.5, 0.5);
  // Receiver indifferent at (0.5, 0.5); the sender prefers a2.
  g.sender_utility << 0.0, 1.0,  //
      0.0, 1.0;
  EXPECT_EQ(BestResponse(g, g.prior), 1);
  // Sender indifferent too: the lowest index wins.
  g.sender_utility.setZero();
  EXPECT_EQ(BestResponse(g, g.prior), 0);
  // A near-tie within the tolerance still goes to the sender, a clear gap does not.
  g.sender_utility << 0.0, 1.0,  //
      0.0, 1.0;
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(0.5 + 1e-11, 0.5 - 1e-11)), 1);
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(0.5 + 1e-6, 0.5 - 1e-6)), 0);
  // ... unless the caller widens the tolerance.
  EXPECT_EQ(BestResponse(g, Eigen::Vector2d(0.5 + 1e-6, 0.5 - 1e-6), 1e-5), 1);
}

// ------------------------------------------------------ Theorem 1, unrestricted

TEST(MinPersuadableTrust, UnrestrictedThreeActionGameByHand) {
  // theta*(a') = -dU0 / (max_w du(w) - dU0):
  //   a1: max du = max(1 - 0, 0 - 1) = 1     -> 0.5 / 1.5 = 1/3
  //   a2: max du = max(0.6, -0.4) = 0.6       -> 0.15 / 0.75 = 0.2
  const TrustThreshold t = MinPersuadableTrust(ThreeActionGame());
  EXPECT_TRUE(t.persuadable);
  EXPECT_EQ(t.default_action, 0);
  EXPECT_EQ(t.target_action, 2);
  EXPECT_NEAR(t.theta_star, 0.2, 1e-15);
}

TEST(MinPersuadableTrust, MinimumDoesNotDependOnActionOrder) {
  // Same game with the last two actions swapped: the cheapest target is now index 1.
  Game g = ThreeActionGame();
  g.actions = {"a0", "a2", "a1"};
  g.receiver_utility.col(1).swap(g.receiver_utility.col(2));
  g.sender_utility.col(1).swap(g.sender_utility.col(2));
  const TrustThreshold t = MinPersuadableTrust(g);
  EXPECT_EQ(t.target_action, 1);
  EXPECT_NEAR(t.theta_star, 0.2, 1e-15);
  Eigen::Matrix2d signals;
  signals << 0.8, 0.2,  //
      0.2, 0.8;
  EXPECT_EQ(MinPersuadableTrust(g, signals).target_action, 1);
  EXPECT_NEAR(MinPersuadableTrust(g, signals).theta_star, 7.0 / 15.0, 1e-14);
}

TEST(MinPersuadableTrust, ThresholdSeparatesPersuadableFromNot) {
  // With a fully revealing w1 signal, the receiver leaves a0 exactly from theta* on.
  const Game g = ThreeActionGame();
  const double theta_star = MinPersuadableTrust(g).theta_star;
  const Eigen::Vector2d reveal_w1(1.0, 0.0);
  EXPECT_EQ(BestResponse(g, TrustPosterior(g.prior, reveal_w1, theta_star - 1e-6)), 0);
  EXPECT_EQ(BestResponse(g, TrustPosterior(g.prior, reveal_w1, theta_star)), 2);
  EXPECT_EQ(BestResponse(g, TrustPosterior(g.prior, reveal_w1, theta_star + 1e-6)), 2);
}

TEST(MinPersuadableTrust, ZeroWhenAnotherActionIsAlreadyTiedAtThePrior) {
  Game g = SmallGame();
  g.prior = Eigen::Vector2d(0.5, 0.5);
  g.sender_utility << 1.0, 0.0,  //
      1.0, 0.0;  // sender likes a1, so the tie at the prior resolves to a1
  const TrustThreshold t = MinPersuadableTrust(g);
  EXPECT_EQ(t.default_action, 0);
  EXPECT_EQ(t.target_action, 1);
  EXPECT_TRUE(t.persuadable);
  EXPECT_EQ(t.theta_star, 0.0);
  // A round-off-sized gap (2e-12 < kTieTolerance) still counts as a tie: theta* = 0,
  // not 2e-12.
  g.prior = Eigen::Vector2d(0.5 + 1e-12, 0.5 - 1e-12);
  EXPECT_EQ(MinPersuadableTrust(g).theta_star, 0.0);
  EXPECT_EQ(MinPersuadableTrust(g).target_action, 1);
}

TEST(MinPersuadableTrust, DominatedActionIsNeverPersuadable) {
  Game g = SmallGame();
  g.receiver_utility << 1.0, 0.0,  //
      1.0, 0.0;  // a1 strictly dominates a2
  const TrustThreshold t = MinPersuadableTrust(g);
  EXPECT_FALSE(t.persuadable);
  EXPECT_EQ(t.theta_star, 1.0);
  EXPECT_EQ(t.target_action, -1);
  EXPECT_EQ(t.default_action, 0);
}

// ------------------------------------------------------ Theorem 1, finite set

TEST(MinPersuadableTrust, FiniteSignalSetByHand) {
  // Columns pi(.|s1) = (0.8, 0.2), pi(.|s2) = (0.2, 0.8).
  // p_FT(w1|s1) = 0.2 / 0.35 = 4/7; dU_FT(a2; s1) = (4*0.6 - 3*0.4)/7 = 1.2/7,
  // dU_FT(a1; s1) = (4 - 3)/7 = 1/7; s2 favours w2 and helps neither.
  //   theta*(a2) = 0.15 / (1.2/7 + 0.15) = 7/15,  theta*(a1) = 0.5 / (1/7 + 0.5) = 7/9.
  Eigen::Matrix2d signals;
  signals << 0.8, 0.2,  //
      0.2, 0.8;
  const TrustThreshold t = MinPersuadableTrust(ThreeActionGame(), signals);
  EXPECT_TRUE(t.persuadable);
  EXPECT_EQ(t.target_action, 2);
  EXPECT_NEAR(t.theta_star, 7.0 / 15.0, 1e-14);
  // A coarser signal set can only need more trust than the unrestricted one.
  EXPECT_GT(t.theta_star, MinPersuadableTrust(ThreeActionGame()).theta_star);
}

TEST(MinPersuadableTrust, UninformativeSignalsCannotPersuade) {
  const Eigen::MatrixXd signals = Eigen::MatrixXd::Ones(2, 3);
  const TrustThreshold t = MinPersuadableTrust(ThreeActionGame(), signals);
  EXPECT_FALSE(t.persuadable);
  EXPECT_EQ(t.theta_star, 1.0);
  EXPECT_EQ(t.target_action, -1);
}

TEST(MinPersuadableTrust, IgnoresZeroProbabilitySignalsAndRejectsBadSets) {
  Eigen::MatrixXd signals(2, 2);
  signals << 0.8, 0.0,  //
      0.2, 0.0;
  EXPECT_NEAR(MinPersuadableTrust(ThreeActionGame(), signals).theta_star, 7.0 / 15.0, 1e-14);
  EXPECT_THAT(InvalidArgumentMessage([] { MinPersuadableTrust(ThreeActionGame(), Eigen::MatrixXd::Zero(2, 2)); }),
              HasSubstr("zero probability"));
  EXPECT_THAT(InvalidArgumentMessage([] { MinPersuadableTrust(ThreeActionGame(), Eigen::MatrixXd::Ones(3, 2)); }),
              HasSubstr("signals has 3 rows but there are 2 states"));
  signals(1, 1) = -0.1;
  EXPECT_THAT(InvalidArgumentMessage([&] { MinPersuadableTrust(ThreeActionGame(), signals); }),
              HasSubstr("signals(1, 1) = -0.1"));
}

// ------------------------------------------------- corollary and eq:ppp

TEST(TwoStateTrustThreshold, MatchesTheoremOneOnRandomTwoByTwoGames) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> utility(-5.0, 5.0), prob(0.05, 0.95);
  int checked = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Game g = SmallGame();
    const double p1 = prob(rng);
    g.prior = Eigen::Vector2d(p1, 1.0 - p1);
    for (int w = 0; w < 2; ++w)
      for (int a = 0; a < 2; ++a) g.receiver_utility(w, a) = utility(rng);
    const TrustThreshold t = MinPersuadableTrust(g);
    if (!t.persuadable || t.theta_star <= 0.0) continue;
    // Relabel so that w1 is the state favouring the target a1 and a2 is the default.
    const int a1 = t.target_action, a2 = t.default_action;
    const double du_w0 = g.receiver_utility(0, a1) - g.receiver_utility(0, a2);
    const double du_w1 = g.receiver_utility(1, a1) - g.receiver_utility(1, a2);
    const bool w0_first = du_w0 > du_w1;
    const double formula = w0_first ? TwoStateTrustThreshold(p1, du_w0, du_w1)
                                    : TwoStateTrustThreshold(1.0 - p1, du_w1, du_w0);
    EXPECT_NEAR(t.theta_star, formula, 1e-12) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(TwoStateTrustThreshold, RejectsBadInput) {
  EXPECT_THAT(InvalidArgumentMessage([] { TwoStateTrustThreshold(0.0, 3.0, -2.0); }),
              HasSubstr("prior_w1 = 0 is outside (0, 1)"));
  EXPECT_THAT(InvalidArgumentMessage([] { TwoStateTrustThreshold(1.0, 3.0, -2.0); }),
              HasSubstr("prior_w1 = 1 is outside (0, 1)"));
  EXPECT_THAT(InvalidArgumentMessage([] { TwoStateTrustThreshold(0.5, 2.0, 2.0); }),
              HasSubstr("delta_u1 = delta_u2 = 2"));
}

TEST(IndifferencePosterior, SolvesTheIndifferenceEquation) {
  // u(w1,.) = (3, -1), u(w2,.) = (0, 2): U(a1) = 3p, U(a2) = -p + 2(1-p) = 2 - 3p,
  // equal at p* = 1/3.
  Eigen::Matrix2d u;
  u << 3.0, -1.0,  //
      0.0, 2.0;
  const double p = IndifferencePosterior(u);
  EXPECT_NEAR(p, 1.0 / 3.0, 1e-15);
  const Eigen::Vector2d belief(p, 1.0 - p);
  const Eigen::Vector2d eu = u.transpose() * belief;
  EXPECT_NEAR(eu(0), eu(1), 1e-15);
}

TEST(IndifferencePosterior, ThrowsWithoutInteriorPoint) {
  Eigen::Matrix2d dominant;
  dominant << 1.0, 0.0,  //
      2.0, 0.0;
  EXPECT_THAT(InvalidArgumentMessage([&] { IndifferencePosterior(dominant); }),
              HasSubstr("no interior indifference point"));
  EXPECT_THAT(InvalidArgumentMessage([] { IndifferencePosterior(Eigen::Matrix2d::Zero()); }),
              HasSubstr("no interior indifference point"));
}

}  // namespace
}  // namespace taebp::persuasion
