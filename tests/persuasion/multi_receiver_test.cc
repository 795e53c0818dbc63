// One AV, several HVs, a public nudge (multi_receiver.h, lp_multi.h), checked
// against values derived independently: the paper's single-receiver design,
// the worked example of docs/beyond/multi-receiver.md (by hand), the closed
// form max_k 2 k lambda theta_(k) / (lambda theta_(k) + p* - lambda) - n, the
// general public-signal LP (a second method), and a Monte Carlo of the meeting.
#include "taebp/persuasion/lp_multi.h"
#include "taebp/persuasion/multi_receiver.h"
#include "taebp/persuasion/random.h"

#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

const AvHvParams kPaper{0.2, 3.0};

MultiReceiverDesign Design(const AvHvParams& params, std::vector<double> trusts,
                           const LikelihoodModel& model) {
  MultiReceiverProblem problem;
  problem.params = params;
  problem.design_trusts = std::move(trusts);
  return DesignMultiReceiver(problem, model);
}

void ExpectSameOutcome(const PredictedOutcome& x, const PredictedOutcome& y) {
  EXPECT_EQ(x.dc_rate, y.dc_rate);
  EXPECT_EQ(x.collision_rate, y.collision_rate);
  EXPECT_EQ(x.nudge_rate, y.nudge_rate);
  EXPECT_EQ(x.av_first_rate, y.av_first_rate);
}

void ExpectSameScheme(const CommittedScheme& x, const CommittedScheme& y) {
  EXPECT_EQ(x.av_may_go, y.av_may_go);
  EXPECT_EQ(x.nudge, y.nudge);
  EXPECT_EQ(x.a, y.a);
  EXPECT_EQ(x.b, y.b);
  EXPECT_EQ(x.random_magnitude, y.random_magnitude);
}

// One HV: exactly the paper's TA-EBP (DesignTaebp, CommitScheme, PredictOutcome),
// below theta* (the fallback) included, for the linear and the logistic model.
TEST(MultiReceiver, OneReceiverIsThePapersDesign) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 4.0, 1.0);
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (double theta : {0.1, 0.25, 0.3, 0.6, 0.9, 1.0}) {
      SCOPED_TRACE(model->Name() + " theta " + std::to_string(theta));
      const MultiReceiverDesign d = Design(kPaper, {theta}, *model);
      const TaebpDesign paper = DesignTaebp(kPaper, theta, *model);
      EXPECT_EQ(d.design.persuadable, paper.persuadable);
      EXPECT_EQ(d.design.s_star, paper.s_star);
      EXPECT_EQ(d.design.b, paper.b);
      EXPECT_EQ(d.design.theta_star, paper.theta_star);
      ExpectSameScheme(d.scheme, CommitScheme(Policy::kTaEbp, kPaper, theta, *model));
      ASSERT_EQ(d.predicted.size(), 1u);
      ExpectSameOutcome(d.predicted[0], PredictOutcome(Policy::kTaEbp, kPaper, theta, *model));
      EXPECT_EQ(d.status, paper.persuadable ? MultiReceiverStatus::kAddressesAll
                                            : MultiReceiverStatus::kAddressesNone);
      EXPECT_EQ(d.addressed_count, paper.persuadable ? 1 : 0);
      EXPECT_DOUBLE_EQ(d.sender_value, 2.0 * d.predicted[0].dc_rate - 1.0);
    }
  }
}

// n HVs of one trust: one HV's design, n times its value.
TEST(MultiReceiver, IdenticalReceiversAreOneReceiver) {
  const LinearLikelihood linear(2.0);
  for (double theta : {0.2, 0.3, 0.6, 0.95}) {
    const MultiReceiverDesign one = Design(kPaper, {theta}, linear);
    for (int n : {2, 3, 4}) {
      SCOPED_TRACE("theta " + std::to_string(theta) + " n " + std::to_string(n));
      const MultiReceiverDesign many = Design(kPaper, std::vector<double>(n, theta), linear);
      EXPECT_EQ(many.status, one.status);
      EXPECT_EQ(many.addressed_count, one.addressed_count * n);
      ExpectSameScheme(many.scheme, one.scheme);
      for (const PredictedOutcome& o : many.predicted) ExpectSameOutcome(o, one.predicted[0]);
      EXPECT_NEAR(many.sender_value, n * one.sender_value, 1e-12);
    }
  }
}

// docs/beyond/multi-receiver.md, section 4: lambda = 0.2, r = 3 (p* = 0.4,
// theta* = 0.25), trusts {0.9, 0.6, 0.3}. P(theta) = lambda theta / (lambda
// theta + p* - lambda): 9/19, 3/8, 3/13; k P = 9/19, 3/4, 9/13; values
// 2 k P - 3 = -39/19, -3/2, -21/13. Best: address {0.9, 0.6} (tau = 0.6,
// b = 7/32, s* = 64/39), give up 0.3; the AV then yields.
TEST(MultiReceiver, WorkedExampleGivesUpTheLowestTrust) {
  const LinearLikelihood linear(2.0);
  const MultiReceiverDesign d = Design(kPaper, {0.3, 0.9, 0.6}, linear);
  ASSERT_EQ(d.candidates.size(), 3u);
  EXPECT_EQ(d.candidates[0], 0.9);
  EXPECT_EQ(d.candidates[2], 0.3);
  EXPECT_NEAR(d.candidate_values[0], -39.0 / 19.0, 1e-12);
  EXPECT_NEAR(d.candidate_values[1], -1.5, 1e-12);
  EXPECT_NEAR(d.candidate_values[2], -21.0 / 13.0, 1e-12);
  EXPECT_EQ(d.status, MultiReceiverStatus::kAddressesSome);
  EXPECT_EQ(d.designed_for, 0.6);
  EXPECT_EQ(d.addressed, (std::vector<bool>{false, true, true}));
  EXPECT_EQ(d.addressed_count, 2);
  EXPECT_NEAR(d.design.b, 7.0 / 32.0, 1e-15);
  EXPECT_NEAR(d.scheme.nudge, 64.0 / 39.0, 1e-13);
  EXPECT_EQ(d.scheme.a, 1.0);
  EXPECT_FALSE(d.scheme.av_may_go);  // the 0.3 HV drives recklessly: the AV yields
  EXPECT_NEAR(d.sender_value, -1.5, 1e-12);
  EXPECT_EQ(d.predicted[0].dc_rate, 0.0);
  EXPECT_NEAR(d.predicted[1].dc_rate, 0.375, 1e-15);
  EXPECT_NEAR(d.predicted[2].dc_rate, 0.375, 1e-15);
  for (const PredictedOutcome& o : d.predicted) EXPECT_EQ(o.collision_rate, 0.0);
  EXPECT_THAT(d.why, HasSubstr("gives up 1 persuadable HV"));
}

// The other side of the trade and theta*: {0.9, 0.6, 0.5} addresses all
// (3 P(0.5) = 1 > 2 P(0.6) = 3/4); {0.9, 0.2}: 0.2 < theta* = 0.25 cannot be
// persuaded, 0.9 is addressed alone (b = 13/38) and the AV yields.
TEST(MultiReceiver, AddressesAllWhenTheLowestTrustPaysAndNeverBelowThetaStar) {
  const LinearLikelihood linear(2.0);
  const MultiReceiverDesign all = Design(kPaper, {0.9, 0.6, 0.5}, linear);
  EXPECT_EQ(all.status, MultiReceiverStatus::kAddressesAll);
  EXPECT_EQ(all.designed_for, 0.5);
  EXPECT_NEAR(all.design.b, 1.0 / 6.0, 1e-15);  // P = 1/3 = 0.2 + 0.8 b
  EXPECT_TRUE(all.scheme.av_may_go);
  EXPECT_NEAR(all.sender_value, 3.0 * (2.0 / 3.0 - 1.0), 1e-12);
  for (const PredictedOutcome& o : all.predicted) EXPECT_EQ(o.collision_rate, 0.0);

  const MultiReceiverDesign low = Design(kPaper, {0.9, 0.2}, linear);
  EXPECT_EQ(low.status, MultiReceiverStatus::kAddressesSome);
  EXPECT_EQ(low.candidates, std::vector<double>{0.9});
  EXPECT_NEAR(low.design.b, 13.0 / 38.0, 1e-15);
  EXPECT_EQ(low.predicted[1].dc_rate, 0.0);
  EXPECT_THAT(low.why, HasSubstr("1 HV(s) below theta*"));

  const MultiReceiverDesign none = Design(kPaper, {0.1, 0.2}, linear);
  EXPECT_EQ(none.status, MultiReceiverStatus::kAddressesNone);
  ExpectSameScheme(none.scheme, CommittedScheme{});
  EXPECT_EQ(none.sender_value, -2.0);
}

// The closed form of the doc (section 3), written from scratch: n for lambda >= p*, else
// max(-n, max over trusts theta_(k) >= theta* of 2 k lambda theta_(k) /
// (lambda theta_(k) + p* - lambda) - n), k = #{i: theta_i >= theta_(k)}.
double ClosedFormValue(double lambda, double r, const std::vector<double>& trusts) {
  const double p_star = 2.0 / (2.0 + r), theta_star = (p_star - lambda) / (1.0 - lambda);
  const double n = static_cast<double>(trusts.size());
  if (lambda >= p_star) return n;  // every HV drives if clear (section 5)
  double best = -n;
  for (double t : trusts) {
    if (t < theta_star) continue;
    const double k = static_cast<double>(std::count_if(trusts.begin(), trusts.end(),
                                                       [t](double x) { return x >= t; }));
    best = std::max(best, 2.0 * k * lambda * t / (lambda * t + p_star - lambda) - n);
  }
  return best;
}

// Random meetings (1-4 HVs, lambda on both sides of p*): the design's value equals the closed
// form and the optimum of the general public-signal LP on the AV-HV game; each
// HV's DC rate equals the LP's P(DC_i) when the best threshold is unique.
TEST(MultiReceiver, DesignEqualsClosedFormAndThePublicLp) {
  const LinearLikelihood linear(2.0);
  std::mt19937_64 rng(43);
  int compared = 0;
  while (compared < 60) {
    AvHvParams params;
    params.collision_penalty = 0.3 + 6.0 * Uniform01(rng);
    params.prior_go = 0.02 + 0.9 * Uniform01(rng);
    if (std::abs(params.prior_go - AvHvPStar(params.collision_penalty)) < 1e-3) continue;
    const int n = 1 + static_cast<int>(4 * Uniform01(rng));
    std::vector<double> trusts(n);
    for (double& t : trusts) t = Uniform01(rng);
    SCOPED_TRACE("case " + std::to_string(compared));
    const MultiReceiverDesign d = Design(params, trusts, linear);
    EXPECT_NEAR(d.sender_value, ClosedFormValue(params.prior_go, params.collision_penalty, trusts), 1e-9);
    const PublicLpResult lp =
        SolvePublicPersuasion(std::vector<Game>(n, AvHvGame(params)), trusts);
    ASSERT_EQ(lp.status, LpResult::Status::kOptimal) << lp.message;
    EXPECT_NEAR(d.sender_value, lp.sender_value, 1e-7);
    std::vector<double> values = d.candidate_values;
    std::sort(values.rbegin(), values.rend());
    if (values.size() < 2 || values[0] - values[1] > 1e-6) {
      for (int i = 0; i < n; ++i) EXPECT_NEAR(d.predicted[i].dc_rate, lp.action_probability(i, kDC), 1e-7);
    }
    ++compared;
  }
}

// The AV-HV game with lambda >= p*: every HV drives if clear at the prior, the
// LP's value is n, and so is the design's: always nudge (b = 1) the magnitude
// the HIGHEST trust needs (its intuitive reading of a small nudge is "Stop").
TEST(MultiReceiver, PublicLpNeedsNoPersuasionAbovePStar) {
  const AvHvParams params{0.5, 3.0};
  const PublicLpResult lp = SolvePublicPersuasion(std::vector<Game>(3, AvHvGame(params)), {0.1, 0.5, 0.9});
  ASSERT_EQ(lp.status, LpResult::Status::kOptimal);
  EXPECT_NEAR(lp.sender_value, 3.0, 1e-9);
  const MultiReceiverDesign d = Design(params, {0.1, 0.5, 0.9}, LinearLikelihood(2.0));
  EXPECT_EQ(d.status, MultiReceiverStatus::kAddressesAll);
  EXPECT_NEAR(d.sender_value, 3.0, 1e-9);
  // Designed for the highest trust: p_FT(Go|s) = s/2 must reach 0.5 - 0.1/0.9, s = 7/9.
  EXPECT_EQ(d.designed_for, 0.9);
  EXPECT_NEAR(d.scheme.nudge, 7.0 / 9.0, 1e-12);
  EXPECT_EQ(d.scheme.b, 1.0);
}

// A Monte Carlo of meetings: draw the intent and the nudge, every HV reads the
// public nudge with its TRUE trust. DC and collision rates per HV and the
// any-HV collision rate match PredictMultiReceiver within 5 standard errors.
void ExpectMonteCarloAgrees(const CommittedScheme& scheme, const std::vector<double>& true_trusts) {
  const LinearLikelihood linear(2.0);
  const MultiReceiverOutcome predicted = PredictMultiReceiver(scheme, kPaper, true_trusts, linear);
  const int n = static_cast<int>(true_trusts.size()), draws = 200000;
  std::vector<int> dc(n, 0), crash(n, 0);
  int any_crash = 0;
  std::mt19937_64 rng(7);
  for (int t = 0; t < draws; ++t) {
    const bool go = Uniform01(rng) < kPaper.prior_go;
    const bool nudged = Uniform01(rng) < (go ? scheme.a : scheme.b);
    const double s = nudged ? scheme.nudge : 0.0;
    bool crashed = false;
    for (int i = 0; i < n; ++i) {
      const bool drives_if_clear =
          HvDrivesIfClear(kPaper, HvPosteriorGo(scheme, kPaper, true_trusts[i], linear, s));
      dc[i] += drives_if_clear ? 1 : 0;
      const bool hit = go && scheme.av_may_go && !drives_if_clear;
      crash[i] += hit ? 1 : 0;
      crashed = crashed || hit;
    }
    any_crash += crashed ? 1 : 0;
  }
  auto near = [&](int count, double p, const char* what) {
    const double error = 5.0 * std::sqrt(std::max(p * (1.0 - p), 1e-6) / draws);
    EXPECT_NEAR(static_cast<double>(count) / draws, p, error) << what;
  };
  for (int i = 0; i < n; ++i) {
    near(dc[i], predicted.per_receiver[i].dc_rate, "dc rate");
    near(crash[i], predicted.per_receiver[i].collision_rate, "collision rate");
  }
  near(any_crash, predicted.any_collision_rate, "any collision");
}

TEST(MultiReceiver, MonteCarloOfTheMeetingAgreesWithThePrediction) {
  const LinearLikelihood linear(2.0);
  // The worked example read by HVs whose true trusts differ from the design's:
  // 0.55 < tau = 0.6 is not persuaded after all.
  const MultiReceiverDesign some = Design(kPaper, {0.9, 0.6, 0.3}, linear);
  const MultiReceiverOutcome truth = PredictMultiReceiver(some.scheme, kPaper, {0.8, 0.55, 0.3}, linear);
  EXPECT_NEAR(truth.per_receiver[0].dc_rate, 0.375, 1e-15);
  EXPECT_EQ(truth.per_receiver[1].dc_rate, 0.0);
  EXPECT_EQ(truth.any_collision_rate, 0.0);  // the AV yields
  ExpectMonteCarloAgrees(some.scheme, {0.8, 0.55, 0.3});
  // All addressed (the AV goes on Go), one HV over-estimated: it collides in a
  // lambda share, and so does the meeting.
  const MultiReceiverDesign all = Design(kPaper, {0.9, 0.6}, linear);
  ASSERT_TRUE(all.scheme.av_may_go);
  const MultiReceiverOutcome over = PredictMultiReceiver(all.scheme, kPaper, {0.9, 0.5}, linear);
  EXPECT_NEAR(over.per_receiver[1].collision_rate, 0.2, 1e-15);
  EXPECT_NEAR(over.any_collision_rate, 0.2, 1e-15);
  ExpectMonteCarloAgrees(all.scheme, {0.9, 0.5});
}

// The general LP with one receiver is the single-receiver LP (random 3 x 3 games).
TEST(PublicLp, OneReceiverIsTheSingleReceiverLp) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    Game game;
    game.states = {"w0", "w1", "w2"};
    game.actions = {"a0", "a1", "a2"};
    game.prior = Eigen::Vector3d(0.2 + Uniform01(rng), 0.2 + Uniform01(rng), 0.2 + Uniform01(rng));
    game.prior /= game.prior.sum();
    game.receiver_utility = Eigen::MatrixXd::NullaryExpr(3, 3, [&] { return 2.0 * Uniform01(rng) - 1.0; });
    game.sender_utility = Eigen::MatrixXd::NullaryExpr(3, 3, [&] { return 2.0 * Uniform01(rng) - 1.0; });
    const double theta = Uniform01(rng);
    const PublicLpResult multi = SolvePublicPersuasion({game}, {theta});
    const LpResult single = SolveTrustAwarePersuasion(game, theta);
    ASSERT_EQ(multi.status, LpResult::Status::kOptimal);
    EXPECT_NEAR(multi.sender_value, single.sender_value, 1e-7) << "trial " << trial;
    EXPECT_NEAR(multi.signal_probability.sum(), 1.0, 1e-9);
  }
}

// The LP on the worked example: the profile numbering (receiver 0 fastest),
// the doc's value -3/2 and who drives if clear (0.9 and 0.6 with 3/8, 0.3 never).
TEST(PublicLp, ProfilesAndActionProbabilitiesAreConsistent) {
  const PublicLpResult lp = SolvePublicPersuasion(std::vector<Game>(3, AvHvGame(kPaper)), {0.9, 0.6, 0.3});
  ASSERT_EQ(lp.status, LpResult::Status::kOptimal);
  ASSERT_EQ(lp.profiles.size(), 8u);
  EXPECT_EQ(lp.profiles[1], (std::vector<int>{1, 0, 0}));  // receiver 0 fastest
  EXPECT_EQ(lp.profiles[6], (std::vector<int>{0, 1, 1}));
  EXPECT_NEAR(lp.sender_value, -1.5, 1e-9);               // the worked example
  EXPECT_NEAR(lp.action_probability(0, kDC), 0.375, 1e-9);
  EXPECT_NEAR(lp.action_probability(1, kDC), 0.375, 1e-9);
  EXPECT_NEAR(lp.action_probability(2, kDC), 0.0, 1e-9);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(lp.action_probability.row(i).sum(), 1.0, 1e-9);
}

TEST(MultiReceiver, InvalidInputIsNamed) {
  const LinearLikelihood linear(2.0);
  MultiReceiverProblem problem;
  problem.design_trusts = {0.5, 1.3};
  std::string why;
  EXPECT_FALSE(problem.IsValid(&why));
  EXPECT_EQ(why, "design_trusts[1] = 1.3 is outside [0, 1]");
  EXPECT_EQ(InvalidArgumentMessage([&] { DesignMultiReceiver(problem, linear); }), why);
  problem.design_trusts = {};
  EXPECT_FALSE(problem.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("design_trusts is empty"));
  problem.design_trusts = {std::nan("")};
  EXPECT_FALSE(problem.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("design_trusts[0] = nan"));
  problem.design_trusts = {0.5};
  problem.params.prior_go = 1.5;
  EXPECT_FALSE(problem.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("params: prior_go (lambda) = 1.5"));
  problem.params = kPaper;
  EXPECT_TRUE(problem.IsValid(&why));
  EXPECT_THAT(InvalidArgumentMessage([&] { PredictMultiReceiver({}, kPaper, {0.5, -0.1}, linear); }),
              HasSubstr("true_trusts[1] = -0.1 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { PredictMultiReceiver({}, kPaper, {}, linear); }),
              HasSubstr("true_trusts is empty"));
}

TEST(PublicLp, InvalidInputIsNamed) {
  const Game game = AvHvGame(kPaper);
  EXPECT_THAT(InvalidArgumentMessage([&] { SolvePublicPersuasion({game, game}, {0.5}); }),
              HasSubstr("trusts has 1 entries for 2 receivers"));
  EXPECT_THAT(InvalidArgumentMessage([&] { SolvePublicPersuasion({game, game}, {0.5, 2.0}); }),
              HasSubstr("trusts[1] = 2 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { SolvePublicPersuasion({game, AvHvGame({0.3, 3.0})}, {0.5, 0.5}); }),
              HasSubstr("receivers[1]'s prior differs"));
  Game renamed = game;
  renamed.states = {"Go", "Wait"};
  EXPECT_THAT(InvalidArgumentMessage([&] { SolvePublicPersuasion({game, renamed}, {0.5, 0.5}); }),
              HasSubstr("receivers[1] has other states"));
  EXPECT_THAT(InvalidArgumentMessage([&] { SolvePublicPersuasion({}, {}); }), HasSubstr("receivers is empty"));
  EXPECT_THAT(InvalidArgumentMessage(
                  [&] { SolvePublicPersuasion(std::vector<Game>(16, game), std::vector<double>(16, 0.5)); }),
              HasSubstr("above the limits"));
}

}  // namespace
}  // namespace taebp::persuasion
