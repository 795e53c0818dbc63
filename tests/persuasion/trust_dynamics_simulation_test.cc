// The long-run trust of the Beta recursion simulated directly (encounters drawn
// with the portable uniform, the HV deciding through HvDrivesIfClear, not through
// OutcomeProbabilities) against the fixed points derived in trust_dynamics_test.cc.
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

// ------------------------------------------------------------------ long run: simulation

// Direct simulation of the Beta recursion: each encounter draws the AV's intent
// and signal from the scheme the policy commits at the HV's current mean, the
// HV decides through eq:pp and HvDrivesIfClear, and the HV's state is updated
// with the outcome it saw. Returns the mean after `steps` encounters.
double SimulateMean(const DesignRule& rule, const TrustUpdateRule& update, double a0, double b0,
                    int steps, std::uint64_t seed, double* alpha = nullptr,
                    double* beta = nullptr) {
  const LinearLikelihood linear(2.0);
  std::mt19937_64 rng(seed);
  BetaTrust trust(a0, b0);
  for (int i = 0; i < steps; ++i) {
    const double theta = trust.Mean();
    const CommittedScheme scheme = SchemeFor(rule, kPaper, theta, linear);
    const bool go = Uniform01(rng) < kPaper.prior_go;
    const bool signal = Uniform01(rng) < (go ? scheme.a : scheme.b);
    const double reading = signal ? scheme.nudge : 0.0;
    const bool dc = HvDrivesIfClear(kPaper, HvPosteriorGo(kPaper, theta, linear, reading));
    const bool av_went = go && scheme.av_may_go;
    trust.Update(ClassifyEncounter(reading > 0.0, av_went, av_went && !dc, false), update);
  }
  if (alpha != nullptr) *alpha = trust.Alpha();
  if (beta != nullptr) *beta = trust.Beta();
  return trust.Mean();
}

struct Sample {
  double mean = 0.0, sd = 0.0;
  double StandardError(int n) const { return sd / std::sqrt(static_cast<double>(n)); }
};
Sample Summarise(const std::vector<double>& xs) {
  Sample s;
  for (double x : xs) s.mean += x;
  s.mean /= static_cast<double>(xs.size());
  for (double x : xs) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(s.sd / static_cast<double>(xs.size() - 1));
  return s;
}

// Without forgetting the mean is a stochastic approximation with step ~1/n
// toward the zeros of G; replicas of n encounters scatter about the attractor
// with sd ~ sqrt(theta (1 - theta) / ((2|G'| - 1) n)) and a bias O(1/n) (start
// and curvature of Q), far below the 4-sigma band of the replica average here.
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(LongRunTrustSimulation, TaebpAndNoTrustConvergeToTheDerivedFixedPoint) {
  const TrustUpdateRule equal = Weights(1.0, 1.0);
  const int replicas = 60, steps = 20000;
  struct Case {
    DesignRule rule;
    double expected;
  };
  const LinearLikelihood linear(2.0);
  for (const Case& c : {Case{{Policy::kTaEbp, {}}, (-0.8 + std::sqrt(5.44)) / 2.0},
                        Case{{Policy::kNoTrust, {}}, 0.5}}) {
    const auto attractors = FindLongRunTrust(c.rule, kPaper, linear, equal, 6.0, 4.0).Attractors();
    ASSERT_EQ(attractors.size(), 1u);
    EXPECT_NEAR(attractors[0], c.expected, 1e-12);
    std::vector<double> means;
    for (int r = 0; r < replicas; ++r) {
      means.push_back(SimulateMean(c.rule, equal, 6.0, 4.0, steps, 1000 + r));
    }
    const Sample s = Summarise(means);
    EXPECT_NEAR(s.mean, attractors[0], 4.0 * s.StandardError(replicas))
        << taebp::PolicyName(c.rule.policy) << " sd " << s.sd;
    EXPECT_LT(s.sd, 0.01);  // the replicas themselves have converged
  }
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(LongRunTrustSimulation, FixedDesignFallsBelowThetaStarAndAStableJumpAttracts) {
  const int replicas = 60, steps = 20000;
  {
    // AFixedHonestDesignCanPushTrustBelowThetaStar, simulated from theta = 0.6.
    std::vector<double> means;
    for (int r = 0; r < replicas; ++r) {
      means.push_back(
          SimulateMean({Policy::kTaEbp, 0.6}, Weights(1.0, 6.0), 6.0, 4.0, steps, 2000 + r));
    }
    const Sample s = Summarise(means);
    EXPECT_NEAR(s.mean, 0.625 / (0.625 + 6.0 * 0.375), 4.0 * s.StandardError(replicas));
    EXPECT_LT(s.mean + 4.0 * s.StandardError(replicas), 0.25);
  }
  {
    // StableJump: the mean chatters about the switch at 0.6 with steps ~1/n.
    TrustUpdateRule rule = Weights(1.0, 2.0);
    rule.quality.collision = 1.0;
    rule.quality.nudge_go = 0.0;
    std::vector<double> means;
    for (int r = 0; r < replicas; ++r) {
      means.push_back(SimulateMean({Policy::kTaEbp, 0.6}, rule, 6.0, 4.0, steps, 3000 + r));
    }
    const Sample s = Summarise(means);
    EXPECT_NEAR(s.mean, 0.6, 4.0 * s.StandardError(replicas)) << "sd " << s.sd;
  }
}

TEST(LongRunTrustSimulation, FullRevealGrowsToOneDeterministically) {
  // From theta >= theta* full revelation always persuades: every encounter is
  // nudge_go or still_stop (q = 1), so alpha grows by w_s each time and beta stays.
  double alpha = 0.0, beta = 0.0;
  const double mean =
      SimulateMean({Policy::kFullReveal, {}}, Weights(1.0, 20.0), 6.0, 4.0, 1000, 5, &alpha, &beta);
  EXPECT_EQ(alpha, 1006.0);
  EXPECT_EQ(beta, 4.0);
  EXPECT_EQ(mean, 1006.0 / 1010.0);
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(LongRunTrustSimulation, ForgettingStationaryPointWhereQIsConstant) {
  // No Trust below theta = 1: Q = 0.5 whatever the trust, so E[alpha_n] and
  // E[beta_n] follow linear recursions with fixed points alpha0 + w_s Q / rho and
  // beta0 + w_f (1 - Q) / rho; after 3000 steps with rho = 0.01 the start is
  // forgotten to (0.99)^3000 < 1e-13.
  const double rho = 0.01, a0 = 6.0, b0 = 4.0;
  const TrustUpdateRule rule = Weights(1.0, 2.0, rho);
  const LinearLikelihood linear(2.0);
  const double q = ExpectedQuality({Policy::kNoTrust, {}}, kPaper, 0.5, linear, rule.quality);
  EXPECT_NEAR(q, 0.5, 1e-15);
  const double alpha_inf = a0 + 1.0 * q / rho, beta_inf = b0 + 2.0 * (1.0 - q) / rho;
  const int replicas = 400;
  std::vector<double> alphas, betas;
  for (int r = 0; r < replicas; ++r) {
    double alpha = 0.0, beta = 0.0;
    SimulateMean({Policy::kNoTrust, {}}, rule, a0, b0, 3000, 4000 + r, &alpha, &beta);
    alphas.push_back(alpha);
    betas.push_back(beta);
  }
  const Sample sa = Summarise(alphas), sb = Summarise(betas);
  EXPECT_NEAR(sa.mean, alpha_inf, 4.0 * sa.StandardError(replicas));
  EXPECT_NEAR(sb.mean, beta_inf, 4.0 * sb.StandardError(replicas));
  // Stationary sd of the AR(1) alpha_n: w_s sqrt(Q (1 - Q) / (1 - (1 - rho)^2));
  // a sample sd of n near-Gaussian values has relative sd 1 / sqrt(2 (n - 1)).
  EXPECT_NEAR(sa.sd, std::sqrt(0.25 / (1.0 - 0.99 * 0.99)),
              4.0 * sa.sd / std::sqrt(2.0 * (replicas - 1)));
  // The scan's stationary point is the mean-field one.
  const auto attractors =
      FindLongRunTrust({Policy::kNoTrust, {}}, kPaper, linear, rule, a0, b0).Attractors();
  ASSERT_EQ(attractors.size(), 1u);
  EXPECT_NEAR(attractors[0], alpha_inf / (alpha_inf + beta_inf), 1e-12);
  EXPECT_NEAR(attractors[0], ConstantQualityEquilibrium(q, rule, a0, b0), 1e-12);
}

}  // namespace
}  // namespace taebp::persuasion
