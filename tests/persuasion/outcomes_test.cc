// Predicted per-encounter outcomes of the Section V policies (plus full
// revelation), worked by hand for the paper's setting lambda = 0.2, r = 3,
// theta = 0.6, linear likelihood with s_max = 2.
#include "taebp/persuasion/outcomes.h"
#include "taebp/config/policies.h"

#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

const AvHvParams kPaper{0.2, 3.0};

TEST(CommitScheme, PaperSetting) {
  const LinearLikelihood linear(2.0);
  const CommittedScheme none = CommitScheme(Policy::kNoEbp, kPaper, 0.6, linear);
  EXPECT_FALSE(none.av_may_go);  // still AV: p = 0.4 * 0.2 = 0.08 < 0.4
  EXPECT_EQ(none.nudge, 0.0);
  EXPECT_EQ(none.a, 0.0);
  EXPECT_EQ(none.b, 0.0);

  const CommittedScheme agnostic = CommitScheme(Policy::kNoTrust, kPaper, 0.6, linear);
  EXPECT_TRUE(agnostic.av_may_go);
  EXPECT_NEAR(agnostic.nudge, 16.0 / 11.0, 1e-13);
  EXPECT_EQ(agnostic.a, 1.0);
  EXPECT_NEAR(agnostic.b, 0.375, 1e-15);

  const CommittedScheme taebp = CommitScheme(Policy::kTaEbp, kPaper, 0.6, linear);
  EXPECT_TRUE(taebp.av_may_go);
  EXPECT_NEAR(taebp.nudge, 64.0 / 39.0, 1e-13);
  EXPECT_EQ(taebp.a, 1.0);
  EXPECT_NEAR(taebp.b, 7.0 / 32.0, 1e-15);

  const CommittedScheme reveal = CommitScheme(Policy::kFullReveal, kPaper, 0.6, linear);
  EXPECT_TRUE(reveal.av_may_go);
  EXPECT_EQ(reveal.nudge, 2.0);
  EXPECT_EQ(reveal.a, 1.0);
  EXPECT_EQ(reveal.b, 0.0);
}

TEST(PredictOutcome, PaperSetting) {
  const LinearLikelihood linear(2.0);
  // no_ebp: the AV always yields; the HV sees no nudge (p = 0.08) and drives recklessly.
  const PredictedOutcome none = PredictOutcome(Policy::kNoEbp, kPaper, 0.6, linear);
  EXPECT_EQ(none.collision_rate, 0.0);
  EXPECT_EQ(none.dc_rate, 0.0);
  EXPECT_EQ(none.nudge_rate, 0.0);
  EXPECT_EQ(none.av_first_rate, 0.0);
  // no_trust: the 16/11 nudge leaves the HV at 0.32 < 0.4 -> DR, and the AV goes
  // whenever its intent is Go: collisions in a lambda = 0.2 fraction.
  const PredictedOutcome agnostic = PredictOutcome(Policy::kNoTrust, kPaper, 0.6, linear);
  EXPECT_NEAR(agnostic.collision_rate, 0.2, 1e-15);
  EXPECT_EQ(agnostic.dc_rate, 0.0);
  EXPECT_NEAR(agnostic.nudge_rate, 0.5, 1e-15);  // 0.2 + 0.8 * 0.375
  EXPECT_EQ(agnostic.av_first_rate, 0.0);
  // ta_ebp: the 64/39 nudge lands on p* -> DC; no collisions, DC rate 0.375.
  const PredictedOutcome taebp = PredictOutcome(Policy::kTaEbp, kPaper, 0.6, linear);
  EXPECT_EQ(taebp.collision_rate, 0.0);
  EXPECT_NEAR(taebp.dc_rate, 0.375, 1e-15);
  EXPECT_NEAR(taebp.nudge_rate, 0.375, 1e-15);
  EXPECT_NEAR(taebp.av_first_rate, 0.2, 1e-15);
  // full_reveal: s_max gives 0.08 + 0.6 = 0.68 -> DC exactly when Go.
  const PredictedOutcome reveal = PredictOutcome(Policy::kFullReveal, kPaper, 0.6, linear);
  EXPECT_EQ(reveal.collision_rate, 0.0);
  EXPECT_NEAR(reveal.dc_rate, 0.2, 1e-15);
  EXPECT_NEAR(reveal.nudge_rate, 0.2, 1e-15);
  EXPECT_NEAR(reveal.av_first_rate, 0.2, 1e-15);
}

TEST(PredictOutcome, ThetaHatOverridesAndNoTrustIgnoresIt) {
  const LinearLikelihood linear(2.0);
  // A TA-EBP AV that wrongly assumes full trust behaves like no_trust.
  const PredictedOutcome wrong = PredictOutcome(Policy::kTaEbp, kPaper, 0.6, linear, 1.0);
  EXPECT_NEAR(wrong.collision_rate, 0.2, 1e-15);
  EXPECT_EQ(wrong.dc_rate, 0.0);
  // no_trust forces theta_hat = 1 whatever is passed.
  const PredictedOutcome forced = PredictOutcome(Policy::kNoTrust, kPaper, 0.6, linear, 0.6);
  EXPECT_NEAR(forced.collision_rate, 0.2, 1e-15);
  // Underestimating trust is safe: a bigger nudge, still DC, a smaller DC rate.
  const PredictedOutcome cautious = PredictOutcome(Policy::kTaEbp, kPaper, 0.6, linear, 0.4);
  EXPECT_EQ(cautious.collision_rate, 0.0);
  EXPECT_GT(cautious.dc_rate, 0.2);
  EXPECT_LT(cautious.dc_rate, 0.375);
}

TEST(PredictOutcome, FallbackBelowThresholdAlwaysYields) {
  const LinearLikelihood linear(2.0);
  const CommittedScheme scheme = CommitScheme(Policy::kTaEbp, kPaper, 0.2, linear);
  EXPECT_FALSE(scheme.av_may_go);
  EXPECT_EQ(scheme.nudge, 0.0);
  EXPECT_EQ(scheme.a, 0.0);
  EXPECT_EQ(scheme.b, 0.0);
  const PredictedOutcome o = PredictOutcome(Policy::kTaEbp, kPaper, 0.2, linear);
  EXPECT_EQ(o.collision_rate, 0.0);
  EXPECT_EQ(o.dc_rate, 0.0);
  EXPECT_EQ(o.nudge_rate, 0.0);
}

// No EBP is "no information" (the paper, Section V-B: the AV "never sends a
// signal", the HV decides "from the prior"): whatever the HV's trust, it drives
// if clear iff lambda >= p*, and the AV, predicting the same, goes on Go intent
// exactly then. At lambda = 0.5 > p* = 0.4 that is a DC rate of 1 (a still AV
// used to be read as the signal s = 0, giving 0 for any theta > 0.2).
TEST(PredictOutcome, NoEbpDecidesFromThePriorOnBothSidesOfPStar) {
  const LinearLikelihood linear(2.0);
  const PredictedOutcome eager = PredictOutcome(Policy::kNoEbp, AvHvParams{0.5, 3.0}, 0.6, linear);
  EXPECT_EQ(eager.dc_rate, 1.0);
  EXPECT_EQ(eager.collision_rate, 0.0);
  EXPECT_EQ(eager.av_first_rate, 0.5);
  EXPECT_EQ(eager.nudge_rate, 0.0);
  int above = 0, below = 0;
  for (double lambda : {0.01, 0.1, 0.2, 0.3, 0.39, 0.4, 0.41, 0.5, 0.7, 0.9, 0.99}) {
    for (double r : {0.5, 1.0, 3.0, 5.0, 20.0}) {
      const AvHvParams params{lambda, r};
      const bool prior_dc = lambda >= AvHvPStar(r) - 1e-12;
      (prior_dc ? above : below) += 1;
      for (double theta : {0.0, 0.3, 0.6, 1.0}) {
        for (double theta_hat : {0.0, 0.5, 1.0}) {
          const PredictedOutcome o = PredictOutcome(Policy::kNoEbp, params, theta, linear, theta_hat);
          EXPECT_EQ(CommitScheme(Policy::kNoEbp, params, theta_hat, linear).av_may_go, prior_dc);
          EXPECT_EQ(o.dc_rate, prior_dc ? 1.0 : 0.0) << lambda << " " << r << " " << theta;
          EXPECT_EQ(o.av_first_rate, prior_dc ? lambda : 0.0) << lambda << " " << r << " " << theta;
          // The AV's and the HV's readings are the same prior: no mismatch can collide.
          EXPECT_EQ(o.collision_rate, 0.0) << lambda << " " << r << " " << theta;
          EXPECT_EQ(o.nudge_rate, 0.0);
        }
      }
    }
  }
  EXPECT_GT(above, 10);
  EXPECT_GT(below, 10);
}

// Under a committed scheme a still AV is the signal s = 0, read through the HV's
// likelihood (eq:pp): for full revelation above p*, a still AV means Stop, so a
// trusting HV drives recklessly when the AV stays and the DC rate is lambda; an
// HV with little trust keeps enough of its prior to drive if clear anyway.
TEST(PredictOutcome, UnderASchemeAStillAvIsTheSignalZero) {
  const LinearLikelihood linear(2.0);
  const AvHvParams eager{0.5, 3.0};
  // theta = 0.6: still -> 0.4 * 0.5 = 0.2 < 0.4 (DR); s_max -> 0.2 + 0.6 = 0.8 (DC).
  const PredictedOutcome trusting = PredictOutcome(Policy::kFullReveal, eager, 0.6, linear);
  EXPECT_EQ(trusting.dc_rate, 0.5);
  EXPECT_EQ(trusting.collision_rate, 0.0);
  // theta = 0.1: still -> 0.9 * 0.5 = 0.45 >= 0.4 (DC).
  EXPECT_EQ(PredictOutcome(Policy::kFullReveal, eager, 0.1, linear).dc_rate, 1.0);
  // TA-EBP above p* nudges always (b = 1) and the nudge lands on p*; at theta = 0.1
  // no nudge is needed (s* = 0) and the still AV, read as s = 0, persuades.
  for (double theta : {0.1, 0.5, 1.0}) {
    const PredictedOutcome o = PredictOutcome(Policy::kTaEbp, eager, theta, linear);
    EXPECT_EQ(o.dc_rate, 1.0) << theta;
    EXPECT_EQ(o.collision_rate, 0.0) << theta;
  }
  EXPECT_EQ(CommitScheme(Policy::kTaEbp, eager, 0.1, linear).nudge, 0.0);
}

// The belief function the runner's HV uses: eq:pp under a signalling scheme,
// the prior without one, for every s in range (and the same range check).
TEST(HvPosteriorGoUnderScheme, SignallingReadsTheLikelihoodOtherwiseThePrior) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 4.0, 1.0);
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (const AvHvParams& params : {kPaper, AvHvParams{0.5, 3.0}}) {
      for (Policy policy : {Policy::kNoEbp, Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
        for (double theta : {0.0, 0.1, 0.6, 1.0}) {
          const CommittedScheme scheme = CommitScheme(policy, params, theta, *model);
          const bool signals = policy != Policy::kNoEbp && !(policy == Policy::kTaEbp && !scheme.av_may_go);
          EXPECT_EQ(scheme.Signals(), signals) << taebp::PolicyName(policy) << " " << theta;
          for (double s : {0.0, 0.7, 2.0}) {
            const double p = HvPosteriorGo(scheme, params, theta, *model, s);
            EXPECT_EQ(p, signals ? HvPosteriorGo(params, theta, *model, s) : params.prior_go);
          }
          EXPECT_THAT(InvalidArgumentMessage([&] { HvPosteriorGo(scheme, params, theta, *model, 2.5); }),
                      HasSubstr("signal s = 2.5 is outside [0, 2]"));
        }
      }
    }
  }
  // TA-EBP's fallback (theta = 0.2 < theta* = 0.25) never nudges: no signal either.
  EXPECT_FALSE(CommitScheme(Policy::kTaEbp, kPaper, 0.2, linear).Signals());
  EXPECT_EQ(HvPosteriorGo(CommitScheme(Policy::kTaEbp, kPaper, 0.2, linear), kPaper, 0.2, linear, 0.0), 0.2);
}

// With theta_hat = theta_true, TA-EBP never collides and its DC rate is the
// design's P(nudge) (or 0 for the fallback), over a grid including lambda >= p*.
TEST(PredictOutcome, TaEbpWithCorrectTrustIsSafeEverywhere) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 3.0, 1.0);
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (double lambda : {0.05, 0.2, 0.35, 0.4, 0.6}) {
      for (double r : {0.5, 1.0, 3.0, 5.0}) {
        const AvHvParams params{lambda, r};
        for (int i = 0; i <= 10; ++i) {
          const double theta = i / 10.0;
          const PredictedOutcome o = PredictOutcome(Policy::kTaEbp, params, theta, *model);
          const TaebpDesign d = DesignTaebp(params, theta, *model);
          EXPECT_EQ(o.collision_rate, 0.0) << model->Name() << " " << lambda << " " << r << " " << theta;
          EXPECT_NEAR(o.dc_rate, d.persuadable ? d.p_nudge : 0.0, 1e-12)
              << model->Name() << " " << lambda << " " << r << " " << theta;
          // The AV crosses first exactly when it intends to go (the HV then waits).
          EXPECT_NEAR(o.av_first_rate, d.persuadable ? lambda : 0.0, 1e-15);
        }
      }
    }
  }
}

TEST(PredictOutcome, RejectsBadInput) {
  const LinearLikelihood linear(2.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { PredictOutcome(Policy::kTaEbp, kPaper, 1.3, linear); }),
              HasSubstr("theta_true = 1.3 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { PredictOutcome(Policy::kTaEbp, kPaper, 0.6, linear, -0.1); }),
              HasSubstr("theta_hat = -0.1 is outside [0, 1]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { PredictOutcome(Policy::kTaEbp, AvHvParams{0.0, 3.0}, 0.6, linear); }),
              HasSubstr("prior_go (lambda) = 0 is outside (0, 1)"));
  CommittedScheme scheme;
  scheme.nudge = 2.5;
  EXPECT_THAT(InvalidArgumentMessage([&] { PredictOutcome(scheme, kPaper, 0.6, linear); }),
              HasSubstr("signal s = 2.5 is outside [0, 2]"));
  scheme.nudge = 1.0;
  scheme.b = 1.5;
  EXPECT_THAT(InvalidArgumentMessage([&] { PredictOutcome(scheme, kPaper, 0.6, linear); }),
              HasSubstr("scheme b (P(nudge | Stop)) = 1.5 is outside [0, 1]"));
}

}  // namespace
}  // namespace taebp::persuasion
