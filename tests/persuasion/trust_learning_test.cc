// Learned trust: the priors against closed forms, the interval-censored
// posterior against a brute-force grid posterior, the delta-safe design, the
// regret helpers by hand, and a long SUMO-free run: calibration of the
// posterior's failure probabilities (a martingale identity), the failure rate
// against delta, regret growth and convergence to the oracle.
#include "taebp/persuasion/trust_learning.h"

#include "taebp/persuasion/random.h"
#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

const AvHvParams kPaper{0.2, 3.0};  // theta* = 0.25

std::shared_ptr<const TrustPrior> Share(TrustPrior prior) {
  return std::make_shared<const TrustPrior>(std::move(prior));
}

// ------------------------------------------------------------------ priors

TEST(TrustPrior, BetaAgainstClosedForms) {
  // Beta(2, 2): F(x) = 3x^2 - 2x^3, E[theta; theta < x] = 2x^3 - 1.5x^4.
  const TrustPrior p = TrustPrior::Beta(2.0, 2.0);
  for (double x = 0.0; x <= 1.0; x += 0.05) {
    EXPECT_NEAR(p.Mass(0.0, x), 3 * x * x - 2 * x * x * x, 1e-14);
    EXPECT_NEAR(p.FirstMoment(0.0, x), 2 * x * x * x - 1.5 * x * x * x * x, 1e-14);
    for (double y = x; y <= 1.0; y += 0.05) {
      EXPECT_NEAR(p.Mass(x, y), (3 * y * y - 2 * y * y * y) - (3 * x * x - 2 * x * x * x), 1e-14);
    }
  }
  EXPECT_NEAR(p.Mean(), 0.5, 1e-15);
  EXPECT_NEAR(p.Mass(0.0, TrustPrior::kAboveOne), 1.0, 1e-15);
  // Beta(2, 1): F = x^2, quantile sqrt(p); restricted to [0.5, 1): F^-1(0.25 + 0.75 p).
  const TrustPrior q = TrustPrior::Beta(2.0, 1.0);
  for (double u = 0.0; u <= 1.0; u += 0.1) {
    EXPECT_NEAR(q.QuantileWithin(0.0, TrustPrior::kAboveOne, u, false), std::sqrt(u), 1e-13);
    EXPECT_NEAR(q.QuantileWithin(0.5, TrustPrior::kAboveOne, u, true), std::sqrt(0.25 + 0.75 * u),
                1e-13);
    EXPECT_NEAR(q.QuantileWithin(0.2, 0.6, u, false), std::sqrt(0.04 + 0.32 * u), 1e-13);
  }
}

TEST(TrustPrior, BetaQuantilesFarInATailAreFound) {
  // Issue 45 item 10: model.learning.delta = 1e-300 (allowed) failed with Boost's
  // "newton_raphson_iterate: no root to be found". Closed forms: Beta(4, 2) has
  // F = 5x^4 - 4x^5 (evaluated at the quantile found, it gives p back);
  // Beta(2, 1) has F = x^2, Beta(1, 3) has 1 - F = (1 - x)^3.
  const TrustPrior b42 = TrustPrior::Beta(4.0, 2.0);
  const TrustPrior b21 = TrustPrior::Beta(2.0, 1.0);
  const TrustPrior b13 = TrustPrior::Beta(1.0, 3.0);
  for (double p : {1e-300, 1e-200, 1e-100, 1e-30}) {
    for (bool upper : {false, true}) {
      const double x42 = b42.QuantileWithin(0.0, TrustPrior::kAboveOne, p, upper);
      EXPECT_NEAR((5.0 * std::pow(x42, 4) - 4.0 * std::pow(x42, 5)) / p, 1.0, 1e-9) << p;
      const double x21 = b21.QuantileWithin(0.0, TrustPrior::kAboveOne, p, upper);
      EXPECT_NEAR(x21 / std::sqrt(p), 1.0, 1e-9) << p;
      // Beta(1, 3) restricted to [0.5, 1): the upper tail from 0.5 holds 1/8;
      // the quantile q has (1 - 0.5)^3 - (1 - q)^3 = p / 8.
      const double x13 = b13.QuantileWithin(0.5, TrustPrior::kAboveOne, p, upper);
      EXPECT_NEAR(x13, 1.0 - std::cbrt(0.125 - p / 8.0), 1e-15) << p;
    }
  }
}

TEST(TrustPrior, BetaNarrowIntervalsStayAccurate) {
  // Below 1e-7 the density is taken as constant: compare with the exact mass
  // of Beta(3, 2) (F = 4x^3 - 3x^4) differentiated: f = 12 x^2 (1 - x).
  const TrustPrior p = TrustPrior::Beta(3.0, 2.0);
  for (double x : {0.1, 0.5, 0.77, 0.95}) {
    for (double nominal : {1e-6, 1e-8, 1e-12}) {
      const double top = x + nominal;
      const double width = top - x;  // as represented
      const double mid = x + 0.5 * width;
      EXPECT_NEAR(p.Mass(x, top) / width, 12 * mid * mid * (1 - mid), 1e-6) << x << " " << width;
      const double q = p.QuantileWithin(x, top, 0.3, true);
      EXPECT_NEAR((q - x) / width, 0.3, 1e-4) << x << " " << width;
      EXPECT_GE(q, x);
      EXPECT_LE(q, top);
    }
  }
}

TEST(TrustPrior, HistogramByHand) {
  // Cells [0, .25), [.25, .5), [.5, .75), [.75, 1) with masses 0.5, 0, 0.25, 0.25.
  const TrustPrior p = TrustPrior::Histogram({2.0, 0.0, 1.0, 1.0});
  EXPECT_NEAR(p.Mass(0.0, 0.125), 0.25, 1e-15);
  EXPECT_NEAR(p.Mass(0.125, 0.6), 0.25 + 0.1, 1e-15);
  EXPECT_NEAR(p.Mass(0.0, TrustPrior::kAboveOne), 1.0, 1e-15);
  EXPECT_NEAR(p.Mean(), 0.5 * 0.125 + 0.25 * 0.625 + 0.25 * 0.875, 1e-15);
  // Mass 0.5 ends at 0.25 and the next mass starts at 0.5: the lower quantile
  // at 1/2 is 0.25, the upper one (the largest x with P(theta < x) <= 1/2) is 0.5.
  EXPECT_NEAR(p.QuantileWithin(0.0, TrustPrior::kAboveOne, 0.5, false), 0.25, 1e-15);
  EXPECT_NEAR(p.QuantileWithin(0.0, TrustPrior::kAboveOne, 0.5, true), 0.5, 1e-15);
  EXPECT_NEAR(p.QuantileWithin(0.0, TrustPrior::kAboveOne, 0.1, true), 0.05, 1e-15);
  EXPECT_NEAR(p.QuantileWithin(0.6, 0.9, 0.5, false), 0.6 + 0.5 * 0.3, 1e-15);
}

TEST(TrustPrior, DiscreteAtoms) {
  // theta in {0.3, 0.6, 0.9} with weights 1 : 2 : 1 (0.6 given twice is merged).
  const TrustPrior p = TrustPrior::Discrete({0.9, 0.6, 0.3, 0.6}, {1.0, 1.0, 1.0, 1.0});
  EXPECT_NEAR(p.Mass(0.0, 0.6), 0.25, 1e-15);  // theta < 0.6
  EXPECT_NEAR(p.Mass(0.6, TrustPrior::kAboveOne), 0.75, 1e-15);
  EXPECT_NEAR(p.Mean(), 0.25 * 0.3 + 0.5 * 0.6 + 0.25 * 0.9, 1e-15);
  EXPECT_EQ(p.QuantileWithin(0.0, TrustPrior::kAboveOne, 0.25, false), 0.3);
  EXPECT_EQ(p.QuantileWithin(0.0, TrustPrior::kAboveOne, 0.25, true),
            0.6);  // P(theta < 0.6) = 0.25
  EXPECT_EQ(p.QuantileWithin(0.0, TrustPrior::kAboveOne, 0.2, true), 0.3);
  EXPECT_EQ(p.QuantileWithin(0.0, TrustPrior::kAboveOne, 0.8, false), 0.9);
  EXPECT_EQ(p.Draw(0.0), 0.3);
  EXPECT_EQ(p.Draw(0.5), 0.6);
  EXPECT_EQ(p.Draw(0.99), 0.9);
}

TEST(TrustPrior, ErrorsNameTheInput) {
  EXPECT_THAT(InvalidArgumentMessage([] { TrustPrior::Beta(0.0, 1.0); }),
              HasSubstr("trust prior Beta a = 0 must be > 0 and finite"));
  EXPECT_THAT(InvalidArgumentMessage([] { TrustPrior::Beta(1.0, INFINITY); }),
              HasSubstr("trust prior Beta b = inf must be > 0 and finite"));
  EXPECT_THAT(InvalidArgumentMessage([] { TrustPrior::Histogram({}); }),
              HasSubstr("trust prior histogram has no cells"));
  EXPECT_THAT(InvalidArgumentMessage([] {
                TrustPrior::Histogram({1.0, -2.0});
              }),
              HasSubstr("trust prior histogram weight[1] = -2 must be finite and >= 0"));
  EXPECT_THAT(InvalidArgumentMessage([] {
                TrustPrior::Histogram({0.0, 0.0});
              }),
              HasSubstr("trust prior histogram weights sum to 0"));
  EXPECT_THAT(InvalidArgumentMessage([] {
                TrustPrior::Discrete({0.5, 1.2}, {1.0, 1.0});
              }),
              HasSubstr("trust prior value[1] = 1.2 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([] {
                TrustPrior::Discrete({0.5}, {1.0, 1.0});
              }),
              HasSubstr("trust prior has 1 values but 2 weights"));
  const TrustPrior p = TrustPrior::Histogram({1.0, 0.0});
  EXPECT_THAT(InvalidArgumentMessage([&] { p.QuantileWithin(0.6, 0.9, 0.5, false); }),
              HasSubstr("the trust interval [0.6, 0.9) has no prior mass"));
  EXPECT_THAT(InvalidArgumentMessage([&] { p.QuantileWithin(0.0, 0.4, 1.5, false); }),
              HasSubstr("quantile level p = 1.5 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { p.Draw(1.0); }),
              HasSubstr("uniform draw u = 1 is outside [0, 1)"));
}

// ------------------------------------------------------------------ the posterior

// An independent posterior: the Beta density times the 0/1 likelihood of every
// response, integrated with the midpoint rule on a million cells.
struct GridPosterior {
  std::vector<double> theta, weight;
  GridPosterior(double a, double b, const std::function<bool(double)>& consistent) {
    const int n = 1000000;
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) / n;
      theta.push_back(x);
      weight.push_back(consistent(x) ? std::pow(x, a - 1) * std::pow(1 - x, b - 1) : 0.0);
    }
  }
  double Mean() const {
    double s = 0, m = 0;
    for (std::size_t i = 0; i < theta.size(); ++i) {
      s += weight[i];
      m += weight[i] * theta[i];
    }
    return m / s;
  }
  double Below(double x) const {
    double s = 0, below = 0;
    for (std::size_t i = 0; i < theta.size(); ++i) {
      s += weight[i];
      if (theta[i] < x) below += weight[i];
    }
    return below / s;
  }
};

TEST(TrustBelief, CensoredResponsesAgainstAGridPosterior) {
  const LinearLikelihood linear(2.0);
  TrustBelief belief(Share(TrustPrior::Beta(3.0, 2.0)));
  EXPECT_NEAR(belief.Mean(), 0.6, 1e-15);
  // DC after the nudge designed for 0.4, DR after the one designed for 0.8,
  // DC after the one for 0.5 (narrows), DC after the one for 0.45 (implied).
  auto nudge = [&](double theta) { return MinimalNudge(kPaper, theta, linear); };
  EXPECT_EQ(belief.Observe(kPaper, linear, nudge(0.4), true), ObservationEffect::kNarrowed);
  EXPECT_EQ(belief.Observe(kPaper, linear, nudge(0.8), false), ObservationEffect::kNarrowed);
  EXPECT_EQ(belief.Observe(kPaper, linear, nudge(0.5), true), ObservationEffect::kNarrowed);
  EXPECT_EQ(belief.Observe(kPaper, linear, nudge(0.45), true), ObservationEffect::kConsistent);
  EXPECT_EQ(belief.Observe(kPaper, linear, 0.0, false), ObservationEffect::kUninformative);
  EXPECT_EQ(belief.Observations(), 4);
  EXPECT_NEAR(belief.Lower(), 0.5, 1e-8);
  EXPECT_NEAR(belief.Upper(), 0.8, 1e-8);
  const GridPosterior grid(3.0, 2.0,
                           [&](double x) { return x >= belief.Lower() && x < belief.Upper(); });
  // The midpoint rule is off by at most the posterior mass of the two cells cut
  // by L and U: 2 cells of 1e-6 at the posterior's largest density, the prior's
  // 16/9 (at 2/3) over the evidence.
  const double tolerance = 2e-6 * (16.0 / 9.0) / belief.Evidence();
  EXPECT_NEAR(belief.Mean(), grid.Mean(), tolerance);
  for (double x : {0.55, 0.6, 0.7, 0.79}) {
    EXPECT_NEAR(belief.ProbabilityBelow(x), grid.Below(x), tolerance);
  }
  EXPECT_EQ(belief.ProbabilityBelow(0.3), 0.0);
  EXPECT_EQ(belief.ProbabilityBelow(0.9), 1.0);
  // The lower credible bound has exactly delta of the posterior below it.
  for (double delta : {0.001, 0.01, 0.1, 0.5}) {
    const double bound = belief.LowerBound(delta);
    EXPECT_NEAR(belief.ProbabilityBelow(bound), delta, 1e-12);
    EXPECT_NEAR(belief.Quantile(delta), bound, 1e-12);
  }
}

TEST(TrustBelief, ContradictionsAreCountedAndIgnored) {
  const LinearLikelihood linear(2.0);
  TrustBelief belief(Share(TrustPrior::Beta(2.0, 2.0)));
  belief.Observe(kPaper, linear, MinimalNudge(kPaper, 0.6, linear), true);  // theta >= 0.6
  const double lower = belief.Lower(), upper = belief.Upper();
  // A DR after the nudge for 0.5 says theta < 0.5: impossible now.
  EXPECT_EQ(belief.Observe(kPaper, linear, MinimalNudge(kPaper, 0.5, linear), false),
            ObservationEffect::kContradiction);
  // A DC after standing still (no trust drives if clear then) is impossible too.
  EXPECT_EQ(belief.Observe(kPaper, linear, 0.0, true), ObservationEffect::kContradiction);
  EXPECT_EQ(belief.Contradictions(), 2);
  EXPECT_THAT(InvalidArgumentMessage([&] { belief.Observe(TrustInterval{0.3, 0.7}, true); }),
              HasSubstr("DC trust set [0.3, 0.7] touches neither 0 nor 1"));
  EXPECT_EQ(belief.Lower(), lower);
  EXPECT_EQ(belief.Upper(), upper);
}

TEST(TrustBelief, ReadingsThatOnlyLowTrustFollow) {
  // lambda = 0.5 >= p* = 0.4: after standing still only theta <= 0.2 drives if
  // clear, so a DC says theta <= 0.2 and a DR says theta > 0.2.
  const LinearLikelihood linear(2.0);
  const AvHvParams easy{0.5, 3.0};
  TrustBelief dc(Share(TrustPrior::Beta(1.0, 1.0)));
  EXPECT_EQ(dc.Observe(easy, linear, 0.0, true), ObservationEffect::kNarrowed);
  EXPECT_EQ(dc.Lower(), 0.0);
  EXPECT_NEAR(dc.Upper(), 0.2, 1e-8);
  EXPECT_NEAR(dc.Mean(), 0.1, 1e-8);
  TrustBelief dr(Share(TrustPrior::Beta(1.0, 1.0)));
  EXPECT_EQ(dr.Observe(easy, linear, 0.0, false), ObservationEffect::kNarrowed);
  EXPECT_NEAR(dr.Lower(), 0.2, 1e-8);
  EXPECT_EQ(dr.Upper(), 1.0);
  // The two responses split [0, 1] exactly: no trust is in both or neither.
  const TrustInterval set = DcTrustInterval(easy, linear, 0.0);
  EXPECT_EQ(std::nextafter(set.hi, 2.0), dr.Lower());
}

TEST(TrustBelief, DiscretePriorLearnsTheAtom) {
  const LinearLikelihood linear(2.0);
  TrustBelief belief(Share(TrustPrior::Discrete({0.3, 0.6, 0.9}, {1.0, 2.0, 1.0})));
  // The nudge designed for exactly 0.6 persuades theta = 0.6.
  EXPECT_EQ(belief.Observe(kPaper, linear, MinimalNudge(kPaper, 0.6, linear), true),
            ObservationEffect::kNarrowed);
  EXPECT_NEAR(belief.Mean(), (2 * 0.6 + 0.9) / 3.0, 1e-15);
  EXPECT_EQ(belief.LowerBound(0.01), 0.6);
  EXPECT_EQ(belief.Observe(kPaper, linear, MinimalNudge(kPaper, 0.9, linear), false),
            ObservationEffect::kNarrowed);
  EXPECT_EQ(belief.Mean(), 0.6);
  EXPECT_EQ(belief.LowerBound(0.5), 0.6);
}

TEST(FleetTrustBeliefs, OneBeliefPerHvFromThePopulationPrior) {
  const LinearLikelihood linear(2.0);
  FleetTrustBeliefs fleet(TrustPrior::Beta(3.0, 2.0));
  EXPECT_EQ(fleet.Find("hv0"), nullptr);
  fleet.For("hv0").Observe(kPaper, linear, MinimalNudge(kPaper, 0.5, linear), true);
  TrustBelief& other = fleet.For("hv1");
  EXPECT_EQ(other.Lower(), 0.0);
  EXPECT_NEAR(other.Mean(), fleet.Population().Mean(), 1e-15);
  ASSERT_NE(fleet.Find("hv0"), nullptr);
  EXPECT_NEAR(fleet.Find("hv0")->Lower(), 0.5, 1e-8);
  EXPECT_EQ(&fleet.For("hv0"), fleet.Find("hv0"));  // the same object for every AV
  EXPECT_EQ(fleet.All().size(), 2u);
}

// ------------------------------------------------------------------ the safe design

TEST(ExplorationSchedule, LevelsAndValidation) {
  ExplorationSchedule s;
  EXPECT_EQ(s.Level(0), 0.01);
  EXPECT_EQ(s.Level(99), 0.01);
  EXPECT_EQ(s.Level(199), 1.0 / 200.0);
  s.decay = INFINITY;
  EXPECT_EQ(s.Level(100000), 0.01);
  s.delta = 1.0;
  EXPECT_THAT(InvalidArgumentMessage([&] { s.Validate(); }),
              HasSubstr("delta = 1 is outside (0, 1)"));
  s = ExplorationSchedule{};
  s.decay = 0.0;
  EXPECT_THAT(InvalidArgumentMessage([&] { s.Validate(); }),
              HasSubstr("decay = 0 must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { ExplorationSchedule{}.Level(-1); }),
              HasSubstr("observations = -1 must be >= 0"));
}

TEST(ChooseLearnedDesign, DesignsForTheLowerCredibleBound) {
  const LinearLikelihood linear(2.0);
  const TrustBelief belief(Share(TrustPrior::Beta(8.0, 4.0)));
  const LearnedDesign d = ChooseLearnedDesign(belief, kPaper, linear, ExplorationSchedule{}, 0.5);
  EXPECT_EQ(d.mode, LearnedDesign::Mode::kDesign);
  EXPECT_EQ(d.risk_level, 0.01);
  EXPECT_NEAR(d.design_trust, belief.Quantile(0.01), 1e-15);
  EXPECT_GT(d.design_trust, 0.25);
  const CommittedScheme oracle_like = CommitScheme(Policy::kTaEbp, kPaper, d.design_trust, linear);
  EXPECT_EQ(d.scheme.av_may_go, oracle_like.av_may_go);
  EXPECT_EQ(d.scheme.nudge, oracle_like.nudge);
  EXPECT_EQ(d.scheme.a, oracle_like.a);
  EXPECT_EQ(d.scheme.b, oracle_like.b);
  EXPECT_EQ(d.probe_probability, 1.0);
  // The HV's tie tolerance lowers the nudge's threshold a hair below theta_L.
  EXPECT_LE(d.failure_probability, 0.01);
  EXPECT_NEAR(d.failure_probability, 0.01, 1e-6);
  EXPECT_EQ(d.encounter_risk, d.failure_probability);
}

TEST(ChooseLearnedDesign, ProbesBelowThetaStarWithinTheRiskBudget) {
  const LinearLikelihood linear(2.0);
  const TrustBelief belief(Share(TrustPrior::Beta(2.0, 2.0)));
  const double below = belief.ProbabilityBelow(0.25);  // 0.15625 > delta
  EXPECT_NEAR(below, 3 * 0.0625 - 2 * 0.015625, 1e-15);
  const ExplorationSchedule schedule;
  const double kappa = 0.01 / below;
  const LearnedDesign drawn = ChooseLearnedDesign(belief, kPaper, linear, schedule, 0.5 * kappa);
  EXPECT_EQ(drawn.mode, LearnedDesign::Mode::kProbe);
  EXPECT_NEAR(drawn.probe_probability, kappa, 1e-6);
  EXPECT_NEAR(drawn.design_trust, 0.25, 1e-12);
  EXPECT_EQ(drawn.scheme.nudge, 2.0);  // theta*: the strongest nudge, b = 0
  EXPECT_EQ(drawn.scheme.b, 0.0);
  EXPECT_NEAR(drawn.failure_probability, below, 1e-8);
  EXPECT_NEAR(drawn.encounter_risk, 0.01, 1e-15);
  const LearnedDesign skipped = ChooseLearnedDesign(belief, kPaper, linear, schedule, 2 * kappa);
  EXPECT_EQ(skipped.mode, LearnedDesign::Mode::kFallback);
  EXPECT_FALSE(skipped.scheme.av_may_go);
  EXPECT_EQ(skipped.scheme.nudge, 0.0);
  EXPECT_EQ(skipped.failure_probability, 0.0);
  EXPECT_NEAR(skipped.encounter_risk, 0.01, 1e-15);
  // Without probing the HV is never nudged.
  ExplorationSchedule strict;
  strict.probe = false;
  const LearnedDesign none = ChooseLearnedDesign(belief, kPaper, linear, strict, 0.0);
  EXPECT_EQ(none.mode, LearnedDesign::Mode::kFallback);
  EXPECT_EQ(none.probe_probability, 0.0);
  // Once a DR after s_max is seen the HV is known to be unpersuadable.
  TrustBelief low = belief;
  low.Observe(kPaper, linear, 2.0, false);
  const LearnedDesign known = ChooseLearnedDesign(low, kPaper, linear, schedule, 0.0);
  EXPECT_EQ(known.mode, LearnedDesign::Mode::kFallback);
  EXPECT_EQ(known.probe_probability, 0.0);
  EXPECT_EQ(known.encounter_risk, 0.0);
}

TEST(ChooseLearnedDesign, ErrorsNameTheInput) {
  const LinearLikelihood linear(2.0);
  const TrustBelief belief(Share(TrustPrior::Beta(2.0, 2.0)));
  EXPECT_THAT(
      InvalidArgumentMessage([&] {
        ChooseLearnedDesign(belief, AvHvParams{0.5, 3.0}, linear, ExplorationSchedule{}, 0.0);
      }),
      HasSubstr("learned trust needs prior_go (lambda) = 0.5 below p* = 0.4"));
  EXPECT_THAT(InvalidArgumentMessage(
                  [&] { ChooseLearnedDesign(belief, kPaper, linear, ExplorationSchedule{}, 1.0); }),
              HasSubstr("uniform draw u = 1 is outside [0, 1)"));
}

// ------------------------------------------------------------------ regret

TEST(ExpectedRegret, ByHandAtThePaperSetting) {
  const LinearLikelihood linear(2.0);
  const double theta = 0.6;  // oracle: DC rate 0.2 + 0.8 * 7/32 = 0.375, no collisions
  const EncounterRegret oracle =
      ExpectedRegret(CommitScheme(Policy::kTaEbp, kPaper, theta, linear), kPaper, theta, linear);
  EXPECT_EQ(oracle.regret, 0.0);
  // Always yielding loses every DC.
  const EncounterRegret yield = ExpectedRegret(CommittedScheme{}, kPaper, theta, linear);
  EXPECT_NEAR(yield.dc_lost, 0.375, 1e-15);
  EXPECT_EQ(yield.collisions, 0.0);
  // Designing for 0.4 (b = 0.2 (0.8*0.4 - 0.2) / (0.8 * 0.28) = 3/28): DC rate 0.2 + 0.8 * 3/28.
  const EncounterRegret cautious =
      ExpectedRegret(CommitScheme(Policy::kTaEbp, kPaper, 0.4, linear), kPaper, theta, linear);
  EXPECT_NEAR(cautious.dc_lost, 0.8 * (7.0 / 32.0 - 3.0 / 28.0), 1e-15);
  EXPECT_EQ(cautious.collisions, 0.0);
  // No Trust (designed for 1): every Go intent collides, regret 0.375 + 3 * 0.2.
  const EncounterRegret reckless =
      ExpectedRegret(CommitScheme(Policy::kNoTrust, kPaper, theta, linear), kPaper, theta, linear);
  EXPECT_NEAR(reckless.dc_lost, 0.375, 1e-15);
  EXPECT_NEAR(reckless.collisions, 0.2, 1e-15);
  EXPECT_NEAR(reckless.regret, 0.375 + 0.6, 1e-15);
  RegretTally tally;
  tally.Add(yield);
  tally.Add(reckless);
  EXPECT_EQ(tally.encounters, 2);
  EXPECT_NEAR(tally.regret, 0.375 + 0.975, 1e-15);
}

// ------------------------------------------------------------------ a long run

struct LearningRun {
  std::vector<double> regret_at;  // mean cumulative regret per HV at checkpoints
  double failures = 0, nudges = 0, predicted_failures = 0, collisions = 0;
  std::vector<double> calibration;  // per HV: failures - sum of failure probabilities
  int persuadable = 0, converged = 0, unpersuadable = 0, recognised = 0;
};

// H HVs with trust drawn from the prior, T encounters each; every encounter
// draws the probe, the AV's intent and signal with Uniform01 and the HV decides
// through eq:pp and HvDrivesIfClear; the AV then observes the response.
LearningRun RunLearning(const TrustPrior& prior_value, const ExplorationSchedule& schedule, int hvs,
                        int encounters, const std::vector<int>& checkpoints, std::uint64_t seed) {
  const LinearLikelihood linear(2.0);
  const auto prior = Share(prior_value);
  LearningRun run;
  run.regret_at.assign(checkpoints.size(), 0.0);
  for (int h = 0; h < hvs; ++h) {
    std::mt19937_64 rng(seed + h);
    const double theta = prior->Draw(Uniform01(rng));
    const PredictedOutcome oracle = PredictOutcome(Policy::kTaEbp, kPaper, theta, linear);
    TrustBelief belief(prior);
    double cumulative = 0.0, calibration = 0.0, last_dc = 0.0, last_oracle = 0.0;
    LearnedDesign design;
    std::size_t next = 0;
    for (int n = 1; n <= encounters; ++n) {
      design = ChooseLearnedDesign(belief, kPaper, linear, schedule, Uniform01(rng));
      EXPECT_LE(design.encounter_risk, design.risk_level * (1 + 1e-12));
      EXPECT_LE(design.risk_level, schedule.delta);
      const bool go = Uniform01(rng) < kPaper.prior_go;
      const bool signal = Uniform01(rng) < (go ? design.scheme.a : design.scheme.b);
      const double reading = signal ? design.scheme.nudge : 0.0;
      const bool dc = HvDrivesIfClear(kPaper, HvPosteriorGo(kPaper, theta, linear, reading));
      if (reading > 0.0) {
        run.nudges += 1;
        run.predicted_failures += design.failure_probability;
        calibration += (dc ? 0.0 : 1.0) - design.failure_probability;
        if (!dc) run.failures += 1;
        if (!dc && go && design.scheme.av_may_go) run.collisions += 1;
      }
      EXPECT_NE(belief.Observe(kPaper, linear, reading, dc), ObservationEffect::kContradiction);
      cumulative += ExpectedRegret(design.scheme, oracle, kPaper, theta, linear).regret;
      if (next < checkpoints.size() && n == checkpoints[next]) run.regret_at[next++] += cumulative;
      if (n > encounters - 1000) {
        last_dc += PredictOutcome(design.scheme, kPaper, theta, linear).dc_rate;
        last_oracle += oracle.dc_rate;
      }
    }
    run.calibration.push_back(calibration);
    if (AvHvPersuadable(kPaper, theta, linear)) {
      ++run.persuadable;
      if (design.mode == LearnedDesign::Mode::kDesign && theta - design.design_trust < 1e-3 &&
          last_dc >= 0.99 * last_oracle) {
        ++run.converged;
      }
    } else {
      ++run.unpersuadable;
      if (design.mode == LearnedDesign::Mode::kFallback && design.probe_probability == 0.0) {
        ++run.recognised;
      }
    }
  }
  for (double& r : run.regret_at) r /= hvs;
  return run;
}

// The posterior is exact, so under the prior P(the nudge fails | history) is
// the reported failure probability: failures - sum of failure probabilities is
// a martingale with mean 0 per HV (independent across HVs).
void ExpectCalibrated(const LearningRun& run) {
  double mean = 0.0, var = 0.0;
  for (double c : run.calibration) mean += c;
  mean /= run.calibration.size();
  for (double c : run.calibration) var += (c - mean) * (c - mean);
  const double se = std::sqrt(var / (run.calibration.size() - 1) / run.calibration.size());
  EXPECT_NEAR(mean, 0.0, 4.0 * se)
      << "failures " << run.failures << " predicted " << run.predicted_failures;
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(LearnedTrustRun, DecayingRiskRegretGrowsLikeLogT) {
  // Beta(2, 2) puts 16 % of the HVs below theta* (probed, then left alone).
  ExplorationSchedule schedule;  // delta = 0.01, decay = 1
  const int hvs = 40;
  const LearningRun run =
      RunLearning(TrustPrior::Beta(2.0, 2.0), schedule, hvs, 10000, {100, 1000, 10000}, 500);
  ExpectCalibrated(run);
  // Failures per nudge at most delta (binomial 4-sigma band); collisions come
  // only from failures on Go intents.
  EXPECT_LE(run.failures / run.nudges, 0.01 + 4.0 * std::sqrt(0.01 * 0.99 / run.nudges));
  EXPECT_LE(run.collisions, run.failures);
  // Regret grows like log T: far below the linear extrapolation (x100) from
  // T = 100, and each decade adds no more than the one before.
  const double r2 = run.regret_at[0], r3 = run.regret_at[1], r4 = run.regret_at[2];
  EXPECT_LT(r4, 10.0 * r2) << r2 << " " << r3 << " " << r4;
  EXPECT_LE(r4 - r3, r3 - r2);
  // Every persuadable HV's design converged to the oracle's; every
  // unpersuadable one is recognised (a DR after the strongest nudge).
  EXPECT_EQ(run.converged, run.persuadable);
  EXPECT_EQ(run.recognised, run.unpersuadable);
  EXPECT_GT(run.unpersuadable, 0);
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(LearnedTrustRun, ConstantRiskLevelIsCalibratedAndWithinDelta) {
  ExplorationSchedule schedule;
  schedule.decay = INFINITY;  // eps = delta for ever
  const LearningRun run = RunLearning(TrustPrior::Beta(8.0, 4.0), schedule, 40, 2000, {2000}, 900);
  ExpectCalibrated(run);
  EXPECT_LE(run.failures / run.nudges, 0.01 + 4.0 * std::sqrt(0.01 * 0.99 / run.nudges));
}

}  // namespace
}  // namespace taebp::persuasion
