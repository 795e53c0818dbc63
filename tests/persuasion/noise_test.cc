// Perception noise: the noise distributions against closed forms, persuasion
// probabilities against a deterministic quadrature of the HV's own decision
// (midpoint rule over the noise's quantile levels) and Boost.Math's
// Gauss-Kronrod, predicted rates against Monte Carlo, and the noise-aware
// design against the paper's (sigma = 0) and against an independent root of
// the rational HV's posterior.
#include "taebp/persuasion/noise.h"

#include "taebp/persuasion/hv_response.h"
#include "taebp/persuasion/random.h"
#include "test_util.h"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

const AvHvParams kPaper{0.2, 3.0};
const double kSStar06 = 64.0 / 39.0;     // Theorem 2 at theta = 0.6
const double kZ99 = 2.3263478740408408;  // Phi^-1(0.99)

PerceptionNoise Gaussian(double sigma, double bias = 0.0) {
  return {PerceptionNoise::Kind::kGaussian, sigma, bias};
}
PerceptionNoise Uniform(double half_width, double bias = 0.0) {
  return {PerceptionNoise::Kind::kUniform, half_width, bias};
}
double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// ------------------------------------------------------------------ the noise

TEST(PerceptionNoise, DistributionsAgainstClosedForms) {
  const PerceptionNoise g = Gaussian(0.2);
  for (double e = -1.0; e <= 1.0; e += 0.05) {
    EXPECT_NEAR(g.Cdf(e), Phi(e / 0.2), 1e-15);
    EXPECT_NEAR(g.Density(e), std::exp(-e * e / 0.08) / (0.2 * std::sqrt(2 * M_PI)), 1e-14);
  }
  for (double p : {1e-6, 0.01, 0.3, 0.5, 0.99}) EXPECT_NEAR(g.Cdf(g.Quantile(p)), p, 1e-14);
  EXPECT_NEAR(g.Quantile(0.99), 0.2 * kZ99, 1e-14);
  const PerceptionNoise u = Uniform(0.3);
  EXPECT_EQ(u.Cdf(-0.3), 0.0);
  EXPECT_NEAR(u.Cdf(0.0), 0.5, 1e-15);
  EXPECT_EQ(u.Cdf(0.4), 1.0);
  EXPECT_NEAR(u.Quantile(0.25), -0.15, 1e-15);
  EXPECT_NEAR(u.Density(0.1), 1.0 / 0.6, 1e-15);
  EXPECT_EQ(u.Density(0.31), 0.0);
  const PerceptionNoise none;
  EXPECT_EQ(none.Cdf(-1e-300), 0.0);
  EXPECT_EQ(none.Cdf(0.0), 1.0);
  EXPECT_EQ(none.Quantile(0.7), 0.0);
}

TEST(PerceptionNoise, NamesAndErrors) {
  for (auto kind : {PerceptionNoise::Kind::kNone, PerceptionNoise::Kind::kGaussian,
                    PerceptionNoise::Kind::kUniform}) {
    EXPECT_EQ(ParseNoiseKind(ToString(kind)), kind);
  }
  EXPECT_THAT(InvalidArgumentMessage([] { ParseNoiseKind("laplace"); }),
              HasSubstr("noise kind 'laplace' is unknown"));
  EXPECT_THAT(InvalidArgumentMessage([] { Gaussian(0.0).Validate(); }),
              HasSubstr("noise.scale = 0 must be > 0 and finite for gaussian noise"));
  EXPECT_THAT(InvalidArgumentMessage([] { Uniform(-1.0).Validate(); }),
              HasSubstr("noise.scale = -1 must be > 0 and finite for uniform noise"));
  EXPECT_THAT(InvalidArgumentMessage([] { Gaussian(0.1, NAN).Validate(); }),
              HasSubstr("noise.bias = nan must be finite"));
  EXPECT_THAT(InvalidArgumentMessage([] { Gaussian(0.1).Quantile(1.0); }),
              HasSubstr("noise quantile level p = 1 is outside (0, 1)"));
  EXPECT_THAT(InvalidArgumentMessage([] { NoisyReading(Gaussian(0.1), 1.0, 2.0, 1.0); }),
              HasSubstr("uniform draw u = 1 is outside [0, 1)"));
  const LinearLikelihood linear(2.0);
  EXPECT_THAT(InvalidArgumentMessage(
                  [&] { PersuasionProbability(Gaussian(0.1), kPaper, 0.6, linear, 2.5); }),
              HasSubstr("displacement s = 2.5 is outside [0, 2]"));
  EXPECT_THAT(
      InvalidArgumentMessage([&] { DesignUnderNoise(kPaper, 0.6, linear, Gaussian(0.1), 0.0); }),
      HasSubstr("delta = 0 is outside (0, 1)"));
}

TEST(NoisyReading, ClampsAndFollowsTheNoise) {
  const PerceptionNoise none{PerceptionNoise::Kind::kNone, 0.0, -0.1};
  EXPECT_DOUBLE_EQ(NoisyReading(none, 1.5, 2.0, 0.3), 1.4);
  EXPECT_EQ(NoisyReading(none, 0.05, 2.0, 0.3), 0.0);
  EXPECT_EQ(NoisyReading(Uniform(0.5, 0.2), 1.9, 2.0, 0.9), 2.0);
  // The extreme draws stay finite.
  EXPECT_EQ(NoisyReading(Gaussian(0.1), 1.0, 2.0, 0.0), 1.0 + Gaussian(0.1).Quantile(0x1.0p-54));
  EXPECT_LT(NoisyReading(Gaussian(0.1), 1.0, 2.0, 1.0 - 0x1.0p-53), 2.0);
  // Readings of 1.0 under N(0, 0.2): the fraction below x is Phi((x - 1) / 0.2)
  // within the binomial 4-sigma band.
  std::mt19937_64 rng(11);
  const int n = 100000;
  int below_09 = 0, below_12 = 0;
  for (int i = 0; i < n; ++i) {
    const double r = NoisyReading(Gaussian(0.2), 1.0, 2.0, Uniform01(rng));
    below_09 += r < 0.9;
    below_12 += r < 1.2;
  }
  for (const auto& [count, p] : {std::pair{below_09, Phi(-0.5)}, std::pair{below_12, Phi(1.0)}}) {
    EXPECT_NEAR(static_cast<double>(count) / n, p, 4.0 * std::sqrt(p * (1 - p) / n));
  }
}

// ------------------------------------------------------------------ persuasion probability

// The HV's own decision averaged over the noise by the midpoint rule on the
// quantile levels u_i = (i + 1/2) / n: the decision is monotone in u, so the
// error is at most 1/n. Uses neither the noise CDF nor r*.
double QuantileMidpoint(const PerceptionNoise& noise, double theta, const LikelihoodModel& model,
                        double s, int n) {
  int dc = 0;
  for (int i = 0; i < n; ++i) {
    const double reading = NoisyReading(noise, s, model.SMax(), (i + 0.5) / n);
    dc += HvDrivesIfClear(kPaper, HvPosteriorGo(kPaper, theta, model, reading));
  }
  return static_cast<double>(dc) / n;
}

TEST(PersuasionProbability, AgainstTheQuantileMidpointRuleAndGaussKronrod) {
  const LinearLikelihood linear(2.0);
  const int n = 20000;
  for (const PerceptionNoise& noise :
       {Gaussian(0.1), Gaussian(0.3, -0.05), Uniform(0.2), Uniform(0.4, 0.1)}) {
    for (double theta : {0.3, 0.6, 0.9}) {
      for (double s : {0.0, 0.8, 1.2, kSStar06, 1.8, 2.0}) {
        const double p = PersuasionProbability(noise, kPaper, theta, linear, s);
        EXPECT_NEAR(p, QuantileMidpoint(noise, theta, linear, s, n), 1.0 / n + 1e-12)
            << ToString(noise.kind) << " theta " << theta << " s " << s;
        if (noise.kind == PerceptionNoise::Kind::kGaussian) {
          // Gauss-Kronrod over the noise density on the DC side of r*.
          const double r_star = *MinReadingForDc(kPaper, linear, theta);
          const double from = r_star - s - noise.bias;
          auto density = [&](double e) { return noise.Density(e); };
          const double quad = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
              density, from, std::max(from, 0.0) + 12.0 * noise.scale, 10, 1e-14);
          EXPECT_NEAR(p, quad, 1e-12);
        }
      }
    }
  }
}

TEST(PersuasionProbability, NoNoiseIsTheHvsDecision) {
  const LinearLikelihood linear(2.0);
  const PerceptionNoise none;
  for (double theta = 0.0; theta <= 1.0; theta += 0.05) {
    for (double s = 0.0; s <= 2.0; s += 0.05) {
      const bool dc = HvDrivesIfClear(kPaper, HvPosteriorGo(kPaper, theta, linear, s));
      EXPECT_EQ(PersuasionProbability(none, kPaper, theta, linear, s), dc ? 1.0 : 0.0);
    }
  }
  // At Theorem 2's nudge exactly: persuaded without noise, a coin flip with
  // symmetric noise of any size.
  EXPECT_EQ(PersuasionProbability(none, kPaper, 0.6, linear, kSStar06), 1.0);
  for (double sigma : {1e-6, 0.01, 0.3}) {
    EXPECT_NEAR(PersuasionProbability(Gaussian(sigma), kPaper, 0.6, linear, kSStar06), 0.5,
                1e-8 / sigma);
  }
}

// ------------------------------------------------------------------ predicted rates

TEST(PredictOutcomeUnderNoise, NoNoiseIsPredictOutcomeExactly) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 4.0, 1.0);
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (Policy policy : {Policy::kNoEbp, Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
      for (double theta_hat : {0.2, 0.6, 0.9}) {
        const CommittedScheme scheme = CommitScheme(policy, kPaper, theta_hat, *model);
        for (double theta = 0.0; theta <= 1.0; theta += 0.05) {
          const PredictedOutcome a = PredictOutcome(scheme, kPaper, theta, *model);
          const PredictedOutcome b =
              PredictOutcomeUnderNoise(scheme, kPaper, theta, *model, PerceptionNoise{});
          EXPECT_EQ(a.dc_rate, b.dc_rate);
          EXPECT_EQ(a.collision_rate, b.collision_rate);
          EXPECT_EQ(a.nudge_rate, b.nudge_rate);
          EXPECT_EQ(a.av_first_rate, b.av_first_rate);
        }
      }
    }
  }
}

// Encounters drawn as the controller would: intent, signal, the HV's noisy
// reading of the displacement and its decision through eq:pp.
struct Rates {
  double dc = 0.0, collision = 0.0;
};
Rates SimulateNoisy(const CommittedScheme& scheme, double theta, const PerceptionNoise& noise,
                    int n, std::uint64_t seed) {
  const LinearLikelihood linear(2.0);
  std::mt19937_64 rng(seed);
  int dc = 0, collisions = 0;
  for (int i = 0; i < n; ++i) {
    const bool go = Uniform01(rng) < kPaper.prior_go;
    const bool signal = Uniform01(rng) < (go ? scheme.a : scheme.b);
    const double displacement = signal ? scheme.nudge : 0.0;
    const double reading = NoisyReading(noise, displacement, linear.SMax(), Uniform01(rng));
    const bool hv_dc = HvDrivesIfClear(kPaper, HvPosteriorGo(kPaper, theta, linear, reading));
    dc += hv_dc;
    collisions += go && scheme.av_may_go && !hv_dc;
  }
  return {static_cast<double>(dc) / n, static_cast<double>(collisions) / n};
}

TEST(PredictOutcomeUnderNoise, AgreesWithMonteCarlo) {
  const LinearLikelihood linear(2.0);
  const int n = 200000;
  std::uint64_t seed = 21;
  for (const PerceptionNoise& noise : {Gaussian(0.15), Gaussian(0.12, 0.1), Uniform(0.25)}) {
    const NoiseAwareDesign aware = DesignUnderNoise(kPaper, 0.6, linear, noise, 0.01);
    ASSERT_EQ(aware.status, NoiseAwareDesign::Status::kOk);
    for (const CommittedScheme& scheme :
         {aware.scheme, CommitScheme(Policy::kTaEbp, kPaper, 0.6, linear),
          CommitScheme(Policy::kFullReveal, kPaper, 0.6, linear)}) {
      const PredictedOutcome predicted =
          PredictOutcomeUnderNoise(scheme, kPaper, 0.6, linear, noise);
      const Rates simulated = SimulateNoisy(scheme, 0.6, noise, n, seed++);
      for (const auto& [sim, p] : {std::pair{simulated.dc, predicted.dc_rate},
                                   std::pair{simulated.collision, predicted.collision_rate}}) {
        EXPECT_NEAR(sim, p, 4.0 * std::sqrt(p * (1 - p) / n) + 1e-12)
            << ToString(noise.kind) << " sigma " << noise.scale << " nudge " << scheme.nudge;
      }
    }
  }
}

// ------------------------------------------------------------------ the noise-aware design

TEST(DesignUnderNoise, WithoutNoiseItIsThePapersDesign) {
  const LinearLikelihood linear(2.0);
  for (double theta = 0.0; theta <= 1.0; theta += 0.02) {
    const NoiseAwareDesign d = DesignUnderNoise(kPaper, theta, linear, PerceptionNoise{}, 0.01);
    const TaebpDesign paper = DesignTaebp(kPaper, theta, linear);
    const CommittedScheme scheme = CommitScheme(Policy::kTaEbp, kPaper, theta, linear);
    EXPECT_EQ(d.status == NoiseAwareDesign::Status::kOk, paper.persuadable);
    EXPECT_EQ(d.nudge, paper.s_star);
    EXPECT_EQ(d.b, paper.b);
    EXPECT_EQ(d.scheme.av_may_go, scheme.av_may_go);
    EXPECT_EQ(d.scheme.nudge, scheme.nudge);
    EXPECT_EQ(d.scheme.a, scheme.a);
    EXPECT_EQ(d.scheme.b, scheme.b);
    if (paper.persuadable) {
      EXPECT_EQ(d.persuasion_probability, 1.0);
    }
  }
  // Table I's TA-EBP: s* = 64/39, b = 7/32, DC rate 0.375, no collisions.
  const NoiseAwareDesign d = DesignUnderNoise(kPaper, 0.6, linear, PerceptionNoise{}, 0.01);
  EXPECT_NEAR(d.nudge, kSStar06, 1e-13);
  EXPECT_NEAR(d.b, 7.0 / 32.0, 1e-15);
  const PredictedOutcome o =
      PredictOutcomeUnderNoise(d.scheme, kPaper, 0.6, linear, PerceptionNoise{});
  EXPECT_NEAR(o.dc_rate, 0.375, 1e-15);
  EXPECT_EQ(o.collision_rate, 0.0);
}

TEST(DesignUnderNoise, GaussianNudgeRateAndTheSigmaToZeroLimit) {
  const LinearLikelihood linear(2.0);
  const double delta = 0.01;
  for (double sigma : {0.15, 0.1, 0.01, 1e-3, 1e-6}) {
    for (double bias : {0.0, -0.05, 0.05}) {
      if (sigma == 0.15 && bias < 0.0) continue;  // s* + 0.05 + 2.33 * 0.15 > s_max
      const NoiseAwareDesign d =
          DesignUnderNoise(kPaper, 0.6, linear, Gaussian(sigma, bias), delta);
      ASSERT_EQ(d.status, NoiseAwareDesign::Status::kOk);
      EXPECT_NEAR(d.nudge, kSStar06 - bias + kZ99 * sigma, 1e-12);
      // The tie tolerance only helps the HV: P(DC) >= 1 - delta, within round-off of it.
      EXPECT_GE(d.persuasion_probability, 1.0 - delta - 1e-12);
      EXPECT_NEAR(d.persuasion_probability, 1.0 - delta, 1e-7 / sigma);
      const PredictedOutcome o =
          PredictOutcomeUnderNoise(d.scheme, kPaper, 0.6, linear, Gaussian(sigma, bias));
      EXPECT_LE(o.collision_rate, kPaper.prior_go * delta + 1e-12);
      // rho = phi((s* - bias) / sigma) / phi(-z sigma / sigma) vanishes as sigma -> 0.
      const double rho = std::exp(-0.5 * (std::pow((kSStar06 - bias) / sigma, 2) - kZ99 * kZ99));
      EXPECT_NEAR(d.density_ratio, rho, 1e-12 + 1e-9 * rho);
      EXPECT_TRUE(d.credible);
    }
  }
  // sigma -> 0: the nudge tends to s* and b to eq:b (exactly, once rho underflows).
  const NoiseAwareDesign tiny = DesignUnderNoise(kPaper, 0.6, linear, Gaussian(1e-6), delta);
  EXPECT_NEAR(tiny.nudge, kSStar06, 3e-6);
  EXPECT_EQ(tiny.b, tiny.b_nominal);
  EXPECT_NEAR(tiny.b, 7.0 / 32.0, 1e-15);
}

// The rational HV of trust theta who knows the scheme (a = 1, b) and the noise
// reads s*: its posterior of Go, from BayesPosterior and TrustPosterior.
double RationalPosteriorAt(double reading, double b, double s, const PerceptionNoise& noise,
                           double theta) {
  const Eigen::Vector2d prior(kPaper.prior_go, 1.0 - kPaper.prior_go);
  const double f_nudge = noise.Density(reading - s - noise.bias);
  const double f_still = noise.Density(reading - noise.bias);
  const Eigen::Vector2d likelihood(f_nudge, b * f_nudge + (1.0 - b) * f_still);
  return TrustPosterior(prior, BayesPosterior(prior, likelihood), theta)(0);
}

TEST(DesignUnderNoise, BIsCredibleForARationalHvThatKnowsTheNoise) {
  const LinearLikelihood linear(2.0);
  // Full trust (s* = 16/11, b0 = 3/8) and delta = 0.2 leave room under s_max for
  // noise wide enough that a still AV is sometimes read near s*.
  for (double sigma : {0.4, 0.5, 0.6}) {
    const PerceptionNoise noise = Gaussian(sigma);
    const double theta = 1.0;
    const NoiseAwareDesign d = DesignUnderNoise(kPaper, theta, linear, noise, 0.2);
    ASSERT_EQ(d.status, NoiseAwareDesign::Status::kOk) << sigma;
    ASSERT_TRUE(d.credible);
    ASSERT_GT(d.density_ratio, 1e-6);  // the noise does change b here
    EXPECT_LT(d.b, d.b_nominal);
    // An independent root: the b that puts the rational posterior at reading s* on p*.
    const double s_star = d.nominal.s_star;
    auto gap = [&](double b) {
      return RationalPosteriorAt(s_star, b, d.nudge, noise, theta) - AvHvPStar(3.0);
    };
    std::uintmax_t iterations = 100;
    const auto root = boost::math::tools::toms748_solve(
        gap, 0.0, d.b_nominal, [](double a, double b) { return std::abs(b - a) < 1e-14; },
        iterations);
    EXPECT_NEAR(d.b, 0.5 * (root.first + root.second), 1e-12) << sigma;
    // Monotone likelihood ratio: readings above s* say Go more, below less.
    EXPECT_GT(RationalPosteriorAt(s_star + 0.1, d.b, d.nudge, noise, theta), AvHvPStar(3.0));
    EXPECT_LT(RationalPosteriorAt(s_star - 0.1, d.b, d.nudge, noise, theta), AvHvPStar(3.0));
  }
  // Uniform noise with which a still AV can be read at s* (an HV that
  // over-reads by 1 m, +-0.6 m): rho = 1, no b is credible; one with which it
  // cannot: rho = 0, b = eq:b.
  const NoiseAwareDesign wide = DesignUnderNoise(kPaper, 1.0, linear, Uniform(0.6, 1.0), 0.01);
  ASSERT_EQ(wide.status, NoiseAwareDesign::Status::kOk);
  EXPECT_EQ(wide.density_ratio, 1.0);
  EXPECT_FALSE(wide.credible);
  EXPECT_EQ(wide.b, 0.0);
  const NoiseAwareDesign mid = DesignUnderNoise(kPaper, 0.9, linear, Uniform(0.4), 0.01);
  ASSERT_EQ(mid.status, NoiseAwareDesign::Status::kOk);
  EXPECT_EQ(mid.density_ratio, 0.0);
  EXPECT_EQ(mid.b, mid.b_nominal);
}

TEST(DesignUnderNoise, FallsBackWhenNoNudgeIsSafeEnough) {
  const LinearLikelihood linear(2.0);
  // sigma = 0.5: s* + 2.33 * 0.5 > s_max = 2.
  const NoiseAwareDesign d = DesignUnderNoise(kPaper, 0.6, linear, Gaussian(0.5), 0.01);
  EXPECT_EQ(d.status, NoiseAwareDesign::Status::kUnachievable);
  EXPECT_FALSE(d.scheme.av_may_go);
  EXPECT_EQ(d.scheme.nudge, 0.0);
  EXPECT_NEAR(d.max_persuasion_probability, 1.0 - Phi((kSStar06 - 2.0) / 0.5), 1e-8);
  const NoiseAwareDesign low = DesignUnderNoise(kPaper, 0.1, linear, Gaussian(0.1), 0.01);
  EXPECT_EQ(low.status, NoiseAwareDesign::Status::kNotPersuadable);
  EXPECT_FALSE(low.scheme.av_may_go);
  EXPECT_EQ(low.max_persuasion_probability, 0.0);
}

TEST(DesignUnderNoise, SigmaSweepNoiseAwareStaysSafeWhileThePapersSStarDegrades) {
  // configs/noise.yaml's question in theory: collisions per encounter of the
  // noise-aware design stay at or below delta * lambda, the paper's s* read
  // with symmetric noise persuades half the time (collisions lambda / 2).
  const LinearLikelihood linear(2.0);
  const double delta = 0.01;
  const CommittedScheme paper = CommitScheme(Policy::kTaEbp, kPaper, 0.6, linear);
  for (double sigma : {0.01, 0.05, 0.1, 0.15}) {
    const PerceptionNoise noise = Gaussian(sigma);
    const NoiseAwareDesign d = DesignUnderNoise(kPaper, 0.6, linear, noise, delta);
    ASSERT_EQ(d.status, NoiseAwareDesign::Status::kOk) << sigma;
    const PredictedOutcome aware = PredictOutcomeUnderNoise(d.scheme, kPaper, 0.6, linear, noise);
    const PredictedOutcome naive = PredictOutcomeUnderNoise(paper, kPaper, 0.6, linear, noise);
    EXPECT_LE(aware.collision_rate, delta * kPaper.prior_go + 1e-12);
    EXPECT_NEAR(naive.collision_rate, 0.5 * kPaper.prior_go, 1e-6);
  }
}

}  // namespace
}  // namespace taebp::persuasion
