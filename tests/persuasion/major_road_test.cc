// The major-road encounter (docs/beyond/major-road.md): the AV at the minor
// road's stop line, the HV approaching on the major road with the right of way.
// Every expected value is a closed form written out below (independently of the
// library), the paper's worked numbers (Section V, c = 0), or a fraction worked by
// hand from those closed forms in the comment next to it.
#include "taebp/persuasion/major_road.h"
#include "taebp/config/policies.h"

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/outcomes.h"
#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

const std::vector<double> kLambdas = {0.05, 0.1, 0.2, 0.3, 0.45};
const std::vector<double> kPenalties = {0.5, 1.0, 3.0, 5.0, 10.0};
const std::vector<double> kYieldCosts = {0.0, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0};

std::vector<double> Trusts() {
  std::vector<double> thetas;
  for (int i = 0; i <= 20; ++i) thetas.push_back(i / 20.0);
  return thetas;
}

// Every (lambda, r, c) of the grid with c < r.
std::vector<MajorRoadParams> Grid() {
  std::vector<MajorRoadParams> grid;
  for (double lambda : kLambdas) {
    for (double r : kPenalties) {
      for (double c : kYieldCosts) {
        if (c < r) grid.push_back(MajorRoadParams{lambda, r, c});
      }
    }
  }
  return grid;
}

std::string Where(const MajorRoadParams& p, double theta = kNaN) {
  return "lambda = " + std::to_string(p.prior_go) + ", r = " + std::to_string(p.collision_penalty) +
         ", c = " + std::to_string(p.yield_cost) + ", theta = " + std::to_string(theta);
}

// ------------------------------------------------ the closed forms (docs/beyond/major-road.md)

// p* = (2 + c) / (2 + r).
double PStar(const MajorRoadParams& p) {
  return (2.0 + p.yield_cost) / (2.0 + p.collision_penalty);
}
// theta* = (2(1 - lambda) + c - r lambda) / ((1 - lambda)(2 + r)), 0 when lambda >= p*.
double ThetaStar(const MajorRoadParams& p) {
  const double lambda = p.prior_go;
  const double r = p.collision_penalty;
  const double c = p.yield_cost;
  return std::max(0.0, (2.0 * (1.0 - lambda) + c - r * lambda) / ((1.0 - lambda) * (2.0 + r)));
}
// r_eff = 2 (r - c) / (2 + c).
double EffectivePenalty(const MajorRoadParams& p) {
  return 2.0 * (p.collision_penalty - p.yield_cost) / (2.0 + p.yield_cost);
}
// Theorem 2's ratio R = (1 - lambda)(p* - (1 - theta) lambda) / (lambda (theta - p* + (1 - theta) lambda)).
double Ratio(const MajorRoadParams& p, double theta) {
  const double lambda = p.prior_go;
  const double ps = PStar(p);
  return (1.0 - lambda) * (ps - (1.0 - theta) * lambda) /
         (lambda * (theta - ps + (1.0 - theta) * lambda));
}
// Linear likelihood on [0, s_max]: L^{-1}(R) = s_max R / (1 + R).
double LinearNudge(double ratio, double s_max) { return s_max * ratio / (1.0 + ratio); }
// eq:b = 1 / R.
double B(const MajorRoadParams& p, double theta) { return 1.0 / Ratio(p, theta); }
// TA-EBP's DC rate: lambda + (1 - lambda) b = lambda theta / (p* - (1 - theta) lambda).
double TaebpDcRate(const MajorRoadParams& p, double theta) {
  const double lambda = p.prior_go;
  return lambda * theta / (PStar(p) - (1.0 - theta) * lambda);
}

struct Rates {
  double dc, collision, nudge, av_first;
};
// The four policies for the linear likelihood, lambda < p* (docs/beyond/major-road.md, "Rates").
Rates ClosedFormRates(Policy policy, const MajorRoadParams& p, double theta) {
  const double lambda = p.prior_go;
  const double ts = ThetaStar(p);
  switch (policy) {
    case Policy::kNoEbp:
      return {0.0, 0.0, 0.0, 0.0};
    case Policy::kNoTrust:  // theta < 1: the design for 1 lands on p* only for theta = 1
      return {0.0, lambda, lambda / PStar(p), 0.0};
    case Policy::kTaEbp:
      if (theta < ts) return {0.0, 0.0, 0.0, 0.0};
      return {TaebpDcRate(p, theta), 0.0, TaebpDcRate(p, theta), lambda};
    case Policy::kFullReveal:
      if (theta < ts) return {0.0, lambda, lambda, 0.0};
      return {lambda, 0.0, lambda, lambda};
    default:
      break;
  }
  ADD_FAILURE() << "no closed form for " << taebp::PolicyName(policy);
  return {kNaN, kNaN, kNaN, kNaN};
}

// ------------------------------------------------------------------ validation

TEST(MajorRoadParams, DefaultsAreValidAndThePaperGame) {
  const MajorRoadParams defaults;
  std::string why;
  EXPECT_TRUE(defaults.IsValid(&why)) << why;
  EXPECT_EQ(defaults.prior_go, 0.2);
  EXPECT_EQ(defaults.collision_penalty, 3.0);
  EXPECT_EQ(defaults.yield_cost, 0.0);
}

TEST(MajorRoadParams, IsValidRejectsOutOfRangeNamingTheField) {
  struct Case {
    MajorRoadParams params;
    const char* field;
  };
  const std::vector<Case> cases = {
      {{0.0, 3.0, 0.0}, "prior_go (lambda) = 0 is outside (0, 1)"},
      {{1.0, 3.0, 0.0}, "prior_go (lambda) = 1 is outside (0, 1)"},
      {{kNaN, 3.0, 0.0}, "prior_go"},
      {{0.2, 0.0, 0.0}, "collision_penalty r = 0 must be > 0"},
      {{0.2, -1.0, 0.0}, "collision_penalty"},
      {{0.2, kInf, 0.0}, "collision_penalty r = inf"},
      {{0.2, 3.0, -0.1}, "yield_cost c = -0.1 must be >= 0"},
      {{0.2, 3.0, kNaN}, "yield_cost"},
      {{0.2, 3.0, 3.0}, "yield_cost c = 3 must be < collision_penalty r = 3"},
      {{0.2, 3.0, 5.0}, "yield_cost c = 5 must be < collision_penalty"},
  };
  for (const Case& c : cases) {
    std::string why;
    EXPECT_FALSE(c.params.IsValid(&why)) << c.field;
    EXPECT_THAT(why, HasSubstr(c.field));
    EXPECT_THAT(InvalidArgumentMessage([&] { c.params.Validate(); }), HasSubstr(c.field));
    EXPECT_THAT(InvalidArgumentMessage([&] { MajorRoadPStar(c.params); }), HasSubstr(c.field));
    EXPECT_THAT(InvalidArgumentMessage([&] {
                  PredictMajorRoadOutcome(Policy::kTaEbp, c.params, 0.6, LinearLikelihood(2.0));
                }),
                HasSubstr(c.field));
  }
  EXPECT_FALSE(MajorRoadParams({0.2, 3.0, 3.0}).IsValid(nullptr));  // nullptr allowed
}

// ------------------------------------------------------------------ the game

TEST(MajorRoadGame, UtilityTable) {
  const Game g = MajorRoadGame(MajorRoadParams{0.3, 4.0, 1.5});
  EXPECT_EQ(g.states, (std::vector<std::string>{"Go", "Stop"}));
  EXPECT_EQ(g.actions, (std::vector<std::string>{"DR", "DC"}));
  EXPECT_EQ(g.prior(kGo), 0.3);
  EXPECT_EQ(g.prior(kStop), 0.7);
  EXPECT_EQ(g.receiver_utility(kGo, kDR), -4.0);   // -r: the collision
  EXPECT_EQ(g.receiver_utility(kStop, kDR), 1.0);  // keeps its way, nobody in it
  EXPECT_EQ(g.receiver_utility(kGo, kDC), -1.5);   // -c: slowed down, the AV went
  EXPECT_EQ(g.receiver_utility(kStop, kDC), -2.5); // -1 - c: slowed down for nothing
  for (int w : {kGo, kStop}) {
    EXPECT_EQ(g.sender_utility(w, kDR), -1.0);
    EXPECT_EQ(g.sender_utility(w, kDC), 1.0);
  }
}

TEST(MajorRoadGame, ZeroYieldCostIsThePaperTable) {
  for (double lambda : kLambdas) {
    for (double r : kPenalties) {
      const Game major = MajorRoadGame(MajorRoadParams{lambda, r, 0.0});
      const Game paper = AvHvGame(AvHvParams{lambda, r});
      EXPECT_EQ(major.receiver_utility, paper.receiver_utility);
      EXPECT_EQ(major.sender_utility, paper.sender_utility);
      EXPECT_EQ(major.prior, paper.prior);
      EXPECT_EQ(MajorRoadEffectivePenalty(MajorRoadParams{lambda, r, 0.0}), r);
    }
  }
}

// u_major(w, a) = k u_paper(w, a; r_eff) + h(w), k = (2 + c)/2, h = (-c, -c/2): a
// positive rescaling plus a per-state shift, which changes no best response.
TEST(MajorRoadGame, IsThePaperGameAtTheEffectivePenalty) {
  for (const MajorRoadParams& p : Grid()) {
    const double c = p.yield_cost;
    const double k = (2.0 + c) / 2.0;
    const double h[2] = {-c, -c / 2.0};
    EXPECT_NEAR(MajorRoadEffectivePenalty(p), EffectivePenalty(p), 1e-15 * p.collision_penalty);
    const AvHvParams paper = p.EquivalentPaperParams();
    EXPECT_EQ(paper.prior_go, p.prior_go);
    EXPECT_EQ(paper.collision_penalty, MajorRoadEffectivePenalty(p));
    EXPECT_LE(paper.collision_penalty, p.collision_penalty);
    const Game major = MajorRoadGame(p);
    const Game equivalent = AvHvGame(paper);
    for (int w : {kGo, kStop}) {
      for (int a : {kDR, kDC}) {
        EXPECT_NEAR(major.receiver_utility(w, a), k * equivalent.receiver_utility(w, a) + h[w],
                    1e-14 * (1.0 + p.collision_penalty))
            << Where(p) << " w = " << w << " a = " << a;
      }
    }
  }
}

// eq:ppp: the general 2x2 indifference point of the major table, the closed form
// (2 + c)/(2 + r) and the paper's 2/(2 + r_eff) agree; c = 0 gives 2/(2 + r).
TEST(MajorRoadTheory, ThresholdPosterior) {
  for (const MajorRoadParams& p : Grid()) {
    const Eigen::Matrix2d u = MajorRoadGame(p).receiver_utility;
    // Rows (Go, Stop), columns reordered to (DC, DR): the indifference posterior of Go.
    Eigen::Matrix2d dc_first;
    dc_first << u(kGo, kDC), u(kGo, kDR), u(kStop, kDC), u(kStop, kDR);
    EXPECT_NEAR(IndifferencePosterior(dc_first), PStar(p), 1e-15) << Where(p);
    EXPECT_NEAR(MajorRoadPStar(p), PStar(p), 1e-15) << Where(p);
    if (p.yield_cost == 0.0) {
      EXPECT_EQ(MajorRoadPStar(p), AvHvPStar(p.collision_penalty));
      EXPECT_NEAR(MajorRoadPStar(p), 2.0 / (2.0 + p.collision_penalty), 1e-15);
    }
  }
}

// The HV yields iff p >= p*: the library's decision, the general best response on
// the major table and the closed form agree (away from the tie band at p*).
TEST(MajorRoadTheory, HvYieldsExactlyAbovePStar) {
  for (const MajorRoadParams& p : Grid()) {
    const Game game = MajorRoadGame(p);
    for (int i = 0; i <= 200; ++i) {
      const double belief = i / 200.0;
      if (std::abs(belief - PStar(p)) < 1e-6) continue;
      const bool closed_form = belief >= PStar(p);
      EXPECT_EQ(MajorRoadHvYields(p, belief), closed_form) << Where(p) << " p = " << belief;
      EXPECT_EQ(BestResponse(game, Eigen::Vector2d(belief, 1.0 - belief)) == kDC, closed_form)
          << Where(p) << " p = " << belief;
    }
    EXPECT_TRUE(MajorRoadHvYields(p, MajorRoadPStar(p)));  // ties toward the AV
  }
}

// Theorem 1 (eq:tt analogue): the closed form, the general theorem on the major
// table (unrestricted signals), the linear model's threshold in the design, and
// the Remark's identity p* = (1 - theta*) lambda + theta* * 1.
TEST(MajorRoadTheory, MinimumPersuadableTrust) {
  const LinearLikelihood linear(2.0);
  int persuasion_cases = 0;
  for (const MajorRoadParams& p : Grid()) {
    const double ts = ThetaStar(p);
    EXPECT_NEAR(MajorRoadThetaStar(p), ts, 1e-14) << Where(p);
    EXPECT_NEAR(DesignMajorRoad(p, 1.0, linear).theta_star, ts, 1e-14) << Where(p);
    if (p.prior_go < PStar(p)) {
      ++persuasion_cases;
      const TrustThreshold general = MinPersuadableTrust(MajorRoadGame(p));
      EXPECT_TRUE(general.persuadable);
      EXPECT_EQ(general.default_action, kDR);
      EXPECT_EQ(general.target_action, kDC);
      EXPECT_NEAR(general.theta_star, ts, 1e-14) << Where(p);
      EXPECT_NEAR((1.0 - ts) * p.prior_go + ts, PStar(p), 1e-14) << Where(p);
    } else {
      EXPECT_EQ(MajorRoadThetaStar(p), 0.0) << Where(p);  // yields at the prior already
    }
    if (p.yield_cost == 0.0) {
      EXPECT_EQ(MajorRoadThetaStar(p), AvHvThetaStar(AvHvParams{p.prior_go, p.collision_penalty}));
    }
  }
  EXPECT_GT(persuasion_cases, 50);
}

// Theorem 2 and eq:b for the linear model: s* = s_max R/(1 + R), b = 1/R, and the
// nudge lands the HV exactly on p* (eq:pp), the committed scheme's posterior too.
TEST(MajorRoadTheory, MinimalNudgeAndStopNudgeProbability) {
  int checked = 0;
  for (double s_max : {2.0, 1.0}) {
    const LinearLikelihood linear(s_max);
    for (const MajorRoadParams& p : Grid()) {
      if (!(p.prior_go < PStar(p) - 1e-3)) continue;
      for (double theta : Trusts()) {
        const TaebpDesign d = DesignMajorRoad(p, theta, linear);
        if (theta < ThetaStar(p) - 1e-3) {
          EXPECT_FALSE(d.persuadable) << Where(p, theta);
          continue;
        }
        if (!(theta > ThetaStar(p) + 1e-3)) continue;
        ++checked;
        ASSERT_TRUE(d.persuadable) << Where(p, theta);
        EXPECT_NEAR(d.p_star, PStar(p), 1e-15);
        EXPECT_NEAR(d.s_star, LinearNudge(Ratio(p, theta), s_max), 1e-12) << Where(p, theta);
        EXPECT_EQ(d.a, 1.0);
        EXPECT_NEAR(d.b, B(p, theta), 1e-12) << Where(p, theta);
        EXPECT_NEAR(d.p_nudge, TaebpDcRate(p, theta), 1e-12) << Where(p, theta);
        // eq:pp at s*: (1 - theta) lambda + theta (s*/s_max) lambda / ((s*/s_max) lambda + (1 - s*/s_max)(1 - lambda)).
        const double x = d.s_star / s_max;
        const double lambda = p.prior_go;
        const double p_ft = x * lambda / (x * lambda + (1.0 - x) * (1.0 - lambda));
        EXPECT_NEAR((1.0 - theta) * lambda + theta * p_ft, PStar(p), 1e-12) << Where(p, theta);
        // The scheme's own posterior (pi(s*|Go) = 1, pi(s*|Stop) = b) is p* as well.
        EXPECT_NEAR((1.0 - theta) * lambda + theta * lambda / (lambda + d.b * (1.0 - lambda)),
                    PStar(p), 1e-12)
            << Where(p, theta);
        EXPECT_TRUE(MajorRoadHvYields(p, HvPosteriorGo(p.EquivalentPaperParams(), theta, linear,
                                                       d.s_star)));
      }
    }
  }
  EXPECT_GT(checked, 500);
}

// ---------------------------------------------------------- the paper, c = 0

// c = 0 is the paper's game: every prediction equals the paper's function exactly.
TEST(MajorRoadPaper, ZeroYieldCostEqualsThePaperGameEverywhere) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 3.0, 1.0);
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (double lambda : kLambdas) {
      for (double r : kPenalties) {
        const MajorRoadParams major{lambda, r, 0.0};
        const AvHvParams paper{lambda, r};
        for (double theta : Trusts()) {
          for (Policy policy : {Policy::kNoEbp, Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
            const PredictedOutcome m = PredictMajorRoadOutcome(policy, major, theta, *model);
            const PredictedOutcome q = PredictOutcome(policy, paper, theta, *model);
            EXPECT_EQ(m.dc_rate, q.dc_rate) << Where(major, theta) << " " << taebp::PolicyName(policy);
            EXPECT_EQ(m.collision_rate, q.collision_rate);
            EXPECT_EQ(m.nudge_rate, q.nudge_rate);
            EXPECT_EQ(m.av_first_rate, q.av_first_rate);
            const CommittedScheme ms = CommitMajorRoadScheme(policy, major, theta, *model);
            const CommittedScheme qs = CommitScheme(policy, paper, theta, *model);
            EXPECT_EQ(ms.av_may_go, qs.av_may_go);
            EXPECT_EQ(ms.nudge, qs.nudge);
            EXPECT_EQ(ms.a, qs.a);
            EXPECT_EQ(ms.b, qs.b);
          }
        }
      }
    }
  }
}

// The paper's Section V numbers (lambda = 0.2, r = 3, theta = 0.6, linear on [0, 2]):
// p* = 0.4, theta* = 0.25, s* = 64/39 = 1.64, No Trust's nudge 16/11 = 1.45,
// Table I theory: No EBP 0 / 0, No Trust collision 0.2 / DC 0, TA-EBP 0 / 0.375,
// full revelation 0 / 0.2.
TEST(MajorRoadPaper, TableOneTheory) {
  const LinearLikelihood linear(2.0);
  const MajorRoadParams paper{0.2, 3.0, 0.0};
  EXPECT_DOUBLE_EQ(MajorRoadPStar(paper), 0.4);
  EXPECT_DOUBLE_EQ(MajorRoadThetaStar(paper), 0.25);
  EXPECT_NEAR(DesignMajorRoad(paper, 0.6, linear).s_star, 64.0 / 39.0, 1e-13);
  EXPECT_NEAR(DesignMajorRoad(paper, 0.6, linear).b, 7.0 / 32.0, 1e-15);
  EXPECT_NEAR(CommitMajorRoadScheme(Policy::kNoTrust, paper, 0.6, linear).nudge, 16.0 / 11.0, 1e-13);
  const PredictedOutcome none = PredictMajorRoadOutcome(Policy::kNoEbp, paper, 0.6, linear);
  EXPECT_EQ(none.collision_rate, 0.0);
  EXPECT_EQ(none.dc_rate, 0.0);
  const PredictedOutcome agnostic = PredictMajorRoadOutcome(Policy::kNoTrust, paper, 0.6, linear);
  EXPECT_NEAR(agnostic.collision_rate, 0.2, 1e-15);
  EXPECT_EQ(agnostic.dc_rate, 0.0);
  EXPECT_NEAR(agnostic.nudge_rate, 0.5, 1e-15);  // lambda / p* = 0.2 / 0.4
  const PredictedOutcome taebp = PredictMajorRoadOutcome(Policy::kTaEbp, paper, 0.6, linear);
  EXPECT_EQ(taebp.collision_rate, 0.0);
  EXPECT_NEAR(taebp.dc_rate, 0.375, 1e-15);  // 0.2 * 0.6 / (0.4 - 0.08)
  const PredictedOutcome reveal = PredictMajorRoadOutcome(Policy::kFullReveal, paper, 0.6, linear);
  EXPECT_EQ(reveal.collision_rate, 0.0);
  EXPECT_NEAR(reveal.dc_rate, 0.2, 1e-15);
}

// ------------------------------------------------------------- worked example

// lambda = 0.2, r = 3, theta = 0.6, linear on [0, 2], with a yielding cost, from
// p* = (2 + c)/5, theta* = (p* - 0.2)/0.8, R = 0.8 (p* - 0.08)/(0.2 (0.68 - p*)),
// s* = 2R/(1 + R), b = 1/R, DC = 0.12/(p* - 0.08); No Trust: R1 = 0.8 p*/(0.2 (1 - p*)),
// nudge rate 0.2/p*.
TEST(MajorRoadExample, YieldCostHalf) {
  // c = 0.5: p* = 0.5, theta* = 0.375, R = 0.336/0.036 = 28/3, s* = 56/31, b = 3/28,
  // DC = 0.12/0.42 = 2/7; No Trust: R1 = 4, s1 = 8/5, nudge 0.4.
  const LinearLikelihood linear(2.0);
  const MajorRoadParams p{0.2, 3.0, 0.5};
  EXPECT_DOUBLE_EQ(MajorRoadEffectivePenalty(p), 2.0);
  EXPECT_DOUBLE_EQ(MajorRoadPStar(p), 0.5);
  EXPECT_DOUBLE_EQ(MajorRoadThetaStar(p), 0.375);
  const TaebpDesign d = DesignMajorRoad(p, 0.6, linear);
  EXPECT_NEAR(d.s_star, 56.0 / 31.0, 1e-13);
  EXPECT_NEAR(d.b, 3.0 / 28.0, 1e-14);
  const PredictedOutcome taebp = PredictMajorRoadOutcome(Policy::kTaEbp, p, 0.6, linear);
  EXPECT_NEAR(taebp.dc_rate, 2.0 / 7.0, 1e-14);
  EXPECT_EQ(taebp.collision_rate, 0.0);
  EXPECT_NEAR(CommitMajorRoadScheme(Policy::kNoTrust, p, 0.6, linear).nudge, 8.0 / 5.0, 1e-13);
  const PredictedOutcome agnostic = PredictMajorRoadOutcome(Policy::kNoTrust, p, 0.6, linear);
  EXPECT_NEAR(agnostic.collision_rate, 0.2, 1e-15);
  EXPECT_EQ(agnostic.dc_rate, 0.0);
  EXPECT_NEAR(agnostic.nudge_rate, 0.4, 1e-14);
  const PredictedOutcome reveal = PredictMajorRoadOutcome(Policy::kFullReveal, p, 0.6, linear);
  EXPECT_NEAR(reveal.dc_rate, 0.2, 1e-15);
  EXPECT_EQ(reveal.collision_rate, 0.0);
}

TEST(MajorRoadExample, YieldCostOne) {
  // c = 1: p* = 0.6, theta* = 0.5, R = 0.416/0.016 = 26, s* = 52/27, b = 1/26,
  // DC = 0.12/0.52 = 3/13; No Trust: R1 = 6, s1 = 12/7, nudge 1/3.
  const LinearLikelihood linear(2.0);
  const MajorRoadParams p{0.2, 3.0, 1.0};
  EXPECT_DOUBLE_EQ(MajorRoadEffectivePenalty(p), 4.0 / 3.0);
  EXPECT_DOUBLE_EQ(MajorRoadPStar(p), 0.6);
  EXPECT_DOUBLE_EQ(MajorRoadThetaStar(p), 0.5);
  const TaebpDesign d = DesignMajorRoad(p, 0.6, linear);
  EXPECT_NEAR(d.s_star, 52.0 / 27.0, 1e-13);
  EXPECT_NEAR(d.b, 1.0 / 26.0, 1e-14);
  EXPECT_NEAR(PredictMajorRoadOutcome(Policy::kTaEbp, p, 0.6, linear).dc_rate, 3.0 / 13.0, 1e-14);
  EXPECT_NEAR(CommitMajorRoadScheme(Policy::kNoTrust, p, 0.6, linear).nudge, 12.0 / 7.0, 1e-13);
  const PredictedOutcome agnostic = PredictMajorRoadOutcome(Policy::kNoTrust, p, 0.6, linear);
  EXPECT_NEAR(agnostic.collision_rate, 0.2, 1e-15);
  EXPECT_NEAR(agnostic.nudge_rate, 1.0 / 3.0, 1e-14);
}

TEST(MajorRoadExample, YieldCostOneAndAHalfMakesTheHvUnpersuadable) {
  // c = 1.5: p* = 0.7, theta* = 0.625 > 0.6: TA-EBP falls back to yielding (0 / 0),
  // full revelation's s_max leaves 0.08 + 0.6 = 0.68 < 0.7 (collision 0.2, DC 0),
  // No Trust: R1 = 0.56/0.06 = 28/3, s1 = 56/31, nudge 2/7, collision 0.2.
  const LinearLikelihood linear(2.0);
  const MajorRoadParams p{0.2, 3.0, 1.5};
  EXPECT_DOUBLE_EQ(MajorRoadPStar(p), 0.7);
  EXPECT_DOUBLE_EQ(MajorRoadThetaStar(p), 0.625);
  EXPECT_FALSE(DesignMajorRoad(p, 0.6, linear).persuadable);
  const PredictedOutcome taebp = PredictMajorRoadOutcome(Policy::kTaEbp, p, 0.6, linear);
  EXPECT_EQ(taebp.dc_rate, 0.0);
  EXPECT_EQ(taebp.collision_rate, 0.0);
  EXPECT_EQ(taebp.nudge_rate, 0.0);
  const PredictedOutcome reveal = PredictMajorRoadOutcome(Policy::kFullReveal, p, 0.6, linear);
  EXPECT_EQ(reveal.dc_rate, 0.0);
  EXPECT_NEAR(reveal.collision_rate, 0.2, 1e-15);
  EXPECT_NEAR(CommitMajorRoadScheme(Policy::kNoTrust, p, 0.6, linear).nudge, 56.0 / 31.0, 1e-13);
  const PredictedOutcome agnostic = PredictMajorRoadOutcome(Policy::kNoTrust, p, 0.6, linear);
  EXPECT_NEAR(agnostic.collision_rate, 0.2, 1e-15);
  EXPECT_NEAR(agnostic.nudge_rate, 2.0 / 7.0, 1e-14);
}

// ------------------------------------------------------------ rates, closed form

TEST(MajorRoadOutcomes, FourPoliciesMatchTheClosedForms) {
  const LinearLikelihood linear(2.0);
  int checked = 0;
  for (const MajorRoadParams& p : Grid()) {
    if (!(p.prior_go < PStar(p) - 1e-3)) continue;
    for (double theta : Trusts()) {
      if (std::abs(theta - ThetaStar(p)) < 1e-3) continue;
      for (Policy policy : {Policy::kNoEbp, Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
        if (policy == Policy::kNoTrust && theta > 1.0 - 1e-3) continue;  // theta = 1: see below
        ++checked;
        const Rates want = ClosedFormRates(policy, p, theta);
        const PredictedOutcome got = PredictMajorRoadOutcome(policy, p, theta, linear);
        const std::string where = Where(p, theta) + " " + taebp::PolicyName(policy);
        EXPECT_NEAR(got.dc_rate, want.dc, 1e-12) << where;
        EXPECT_NEAR(got.collision_rate, want.collision, 1e-12) << where;
        EXPECT_NEAR(got.nudge_rate, want.nudge, 1e-12) << where;
        EXPECT_NEAR(got.av_first_rate, want.av_first, 1e-12) << where;
      }
    }
    // A fully trusting HV is what No Trust designs for: its nudge lands on p*,
    // DC = lambda / p*, no collision.
    const PredictedOutcome full = PredictMajorRoadOutcome(Policy::kNoTrust, p, 1.0, linear);
    EXPECT_NEAR(full.dc_rate, p.prior_go / PStar(p), 1e-12) << Where(p, 1.0);
    EXPECT_EQ(full.collision_rate, 0.0) << Where(p, 1.0);
  }
  EXPECT_GT(checked, 3000);
}

// lambda >= p*: the HV yields from the prior; without signals (No EBP) every HV
// yields and the AV goes on Go intent, no collision.
TEST(MajorRoadOutcomes, AbovePStarNoEbpYieldsFromThePrior) {
  const LinearLikelihood linear(2.0);
  int checked = 0;
  for (const MajorRoadParams& p : Grid()) {
    if (!(p.prior_go > PStar(p) + 1e-3)) continue;
    ++checked;
    EXPECT_EQ(MajorRoadThetaStar(p), 0.0);
    for (double theta : Trusts()) {
      const PredictedOutcome none = PredictMajorRoadOutcome(Policy::kNoEbp, p, theta, linear);
      EXPECT_EQ(none.dc_rate, 1.0) << Where(p, theta);
      EXPECT_EQ(none.collision_rate, 0.0);
      EXPECT_EQ(none.av_first_rate, p.prior_go);
    }
  }
  EXPECT_GT(checked, 5);
}

// ------------------------------------------------------------------ invariants
// Each one is proved in docs/beyond/major-road.md ("Comparative statics").

TEST(MajorRoadInvariants, TaebpNeverCollides) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 3.0, 1.0);
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (const MajorRoadParams& p : Grid()) {
      for (double theta : Trusts()) {
        const PredictedOutcome o = PredictMajorRoadOutcome(Policy::kTaEbp, p, theta, *model);
        EXPECT_EQ(o.collision_rate, 0.0) << Where(p, theta) << " " << model->Name();
        if (theta >= ThetaStar(p) + 1e-9 && model == &linear) {
          EXPECT_GE(o.dc_rate, p.prior_go - 1e-12) << Where(p, theta);  // at least full revelation
        }
      }
    }
  }
}

TEST(MajorRoadInvariants, TaebpDcRateIncreasesWithTrustUpToLambdaOverPStar) {
  const LinearLikelihood linear(2.0);
  for (const MajorRoadParams& p : Grid()) {
    if (!(p.prior_go < PStar(p) - 1e-3)) continue;
    double previous = -1.0;
    bool previous_persuaded = false;
    for (double theta : Trusts()) {
      const double dc = PredictMajorRoadOutcome(Policy::kTaEbp, p, theta, linear).dc_rate;
      const bool persuaded = DesignMajorRoad(p, theta, linear).persuadable;
      if (persuaded && previous_persuaded) {
        EXPECT_GT(dc, previous) << Where(p, theta);  // strictly, on [theta*, 1]
      } else {
        EXPECT_GE(dc, previous) << Where(p, theta);
      }
      EXPECT_LE(dc, p.prior_go / PStar(p) + 1e-12) << Where(p, theta);
      previous = dc;
      previous_persuaded = persuaded;
    }
  }
}

// Raising c at fixed (lambda, r, theta): p* and theta* rise, s* rises, b and the
// TA-EBP DC rate fall.
TEST(MajorRoadInvariants, YieldCostRaisesThresholdsAndLowersDc) {
  const LinearLikelihood linear(2.0);
  for (double lambda : kLambdas) {
    for (double r : kPenalties) {
      for (double theta : Trusts()) {
        MajorRoadParams prev{lambda, r, 0.0};
        for (double c : kYieldCosts) {
          if (c == 0.0 || !(c < r)) continue;
          const MajorRoadParams next{lambda, r, c};
          const std::string where = Where(next, theta);
          EXPECT_GT(MajorRoadPStar(next), MajorRoadPStar(prev)) << where;
          EXPECT_GE(MajorRoadThetaStar(next), MajorRoadThetaStar(prev)) << where;
          EXPECT_LT(MajorRoadEffectivePenalty(next), MajorRoadEffectivePenalty(prev)) << where;
          const TaebpDesign d0 = DesignMajorRoad(prev, theta, linear);
          const TaebpDesign d1 = DesignMajorRoad(next, theta, linear);
          EXPECT_LE(PredictMajorRoadOutcome(Policy::kTaEbp, next, theta, linear).dc_rate,
                    PredictMajorRoadOutcome(Policy::kTaEbp, prev, theta, linear).dc_rate)
              << where;
          if (d1.persuadable) {
            EXPECT_TRUE(d0.persuadable) << where;
            if (lambda < PStar(prev)) {
              EXPECT_GE(d1.s_star, d0.s_star) << where;
              EXPECT_LE(d1.b, d0.b) << where;
            }
          }
          prev = next;
        }
      }
    }
  }
}

}  // namespace
}  // namespace taebp::persuasion
