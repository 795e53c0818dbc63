// Predicted per-encounter outcomes of the Section V policies (plus full
// revelation), worked by hand for the paper's setting lambda = 0.2, r = 3,
// theta = 0.6, linear likelihood with s_max = 2.
#include "taebp/persuasion/outcomes.h"

#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

const AvHvParams kPaper{0.2, 3.0};

TEST(Policy, NamesRoundTrip) {
  for (Policy p : {Policy::kNoEbp, Policy::kNoTrust, Policy::kTaEbp, Policy::kFullReveal}) {
    EXPECT_EQ(ParsePolicy(ToString(p)), p);
  }
  EXPECT_STREQ(ToString(Policy::kTaEbp), "ta_ebp");
  EXPECT_EQ(ParsePolicy("full_reveal"), Policy::kFullReveal);
  EXPECT_THAT(InvalidArgumentMessage([] { ParsePolicy("bogus"); }), HasSubstr("policy 'bogus' is unknown"));
  EXPECT_THAT(InvalidArgumentMessage([] { ParsePolicy("TA_EBP"); }), HasSubstr("policy 'TA_EBP' is unknown"));
}

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

TEST(PredictOutcome, NoEbpGoesOnlyWhenTheStillAvPersuades) {
  const LinearLikelihood linear(2.0);
  const AvHvParams eager{0.5, 3.0};  // lambda = 0.5 > p* = 0.4
  // theta = 0: the HV keeps its prior 0.5 >= 0.4 -> DC; the AV may go.
  EXPECT_TRUE(CommitScheme(Policy::kNoEbp, eager, 0.0, linear).av_may_go);
  const PredictedOutcome calm = PredictOutcome(Policy::kNoEbp, eager, 0.0, linear);
  EXPECT_EQ(calm.dc_rate, 1.0);
  EXPECT_EQ(calm.collision_rate, 0.0);
  EXPECT_EQ(calm.av_first_rate, 0.5);
  // theta = 0.5: a still AV reads as Stop (p = 0.25 < 0.4); the AV predicts DR and yields.
  EXPECT_FALSE(CommitScheme(Policy::kNoEbp, eager, 0.5, linear).av_may_go);
  EXPECT_EQ(PredictOutcome(Policy::kNoEbp, eager, 0.5, linear).collision_rate, 0.0);
  // If the AV wrongly assumes theta = 0 while the HV has 0.5: it goes on Go intent
  // and meets a reckless HV.
  const PredictedOutcome wrong = PredictOutcome(Policy::kNoEbp, eager, 0.5, linear, 0.0);
  EXPECT_EQ(wrong.collision_rate, 0.5);
  EXPECT_EQ(wrong.dc_rate, 0.0);
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
