// The HV's decision thresholds against their closed forms:
// theta_needed(s) = (p* - lambda) / (p_FT(Go|s) - lambda) and s*(theta) of Theorem 2.
#include "taebp/persuasion/hv_response.h"

#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

const AvHvParams kPaper{0.2, 3.0};

double FullTrustPosterior(const AvHvParams& params, const LikelihoodModel& model, double s) {
  const double go = model.PiGo(s) * params.prior_go;
  return go / (go + model.PiStop(s) * (1.0 - params.prior_go));
}

TEST(DcTrustInterval, PaperValues) {
  const LinearLikelihood linear(2.0);
  // s* = 64/39 is Theorem 2's nudge for theta = 0.6; No Trust's 16/11 needs theta = 1.
  const TrustInterval t06 = DcTrustInterval(kPaper, linear, 64.0 / 39.0);
  EXPECT_NEAR(t06.lo, 0.6, 1e-8);
  EXPECT_EQ(t06.hi, 1.0);
  EXPECT_NEAR(DcTrustInterval(kPaper, linear, 16.0 / 11.0).lo, 1.0, 1e-8);
  EXPECT_NEAR(DcTrustInterval(kPaper, linear, 2.0).lo, 0.25, 1e-8);  // s_max: theta*
  EXPECT_TRUE(DcTrustInterval(kPaper, linear, 0.0).Empty());  // standing still never persuades
  EXPECT_TRUE(DcTrustInterval(kPaper, linear, 1.0).Empty());  // p_FT = 0.2 = lambda
  // lambda = 0.5 >= p* = 0.4: standing still (p_FT = 0) keeps the HV at DC only
  // while (1 - theta) 0.5 >= 0.4, theta <= 0.2; s_max persuades everyone.
  const TrustInterval low = DcTrustInterval(AvHvParams{0.5, 3.0}, linear, 0.0);
  EXPECT_EQ(low.lo, 0.0);
  EXPECT_NEAR(low.hi, 0.2, 1e-8);
  const TrustInterval all = DcTrustInterval(AvHvParams{0.5, 3.0}, linear, 2.0);
  EXPECT_EQ(all.lo, 0.0);
  EXPECT_EQ(all.hi, 1.0);
}

TEST(DcTrustInterval, ClosedFormAndTheDecisionOverAGrid) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 4.0, 1.0);
  int bounded = 0;
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (double lambda : {0.1, 0.2, 0.3, 0.5}) {
      for (double r : {2.0, 3.0, 6.0}) {
        const AvHvParams params{lambda, r};
        const double p_star = AvHvPStar(r);
        for (double s = 0.0; s <= 2.0; s += 0.01) {
          const TrustInterval t = DcTrustInterval(params, *model, s);
          const double p_ft = FullTrustPosterior(params, *model, s);
          // The HV's own decision agrees on a grid of trust and at the ends.
          for (double theta = 0.0; theta <= 1.0; theta += 0.01) {
            if (std::abs(theta - t.lo) < 1e-6 || std::abs(theta - t.hi) < 1e-6) continue;
            EXPECT_EQ(t.Contains(theta),
                      HvDrivesIfClear(params, HvPosteriorGo(params, theta, *model, s)))
                << model->Name() << " s " << s << " theta " << theta;
          }
          if (t.Empty()) continue;
          const double closed = (p_star - lambda) / (p_ft - lambda);
          // The HV's tie tolerance (a gain of -kTieTolerance counts as a tie, at most
          // kTieTolerance in p) moves the switch by at most that over |dp/dtheta|.
          const double slack = 2.0 * kTieTolerance / std::abs(p_ft - lambda) + 1e-14;
          for (const double end : {t.lo, t.hi}) {
            if (end == 0.0 || end == 1.0) continue;
            ++bounded;
            EXPECT_NEAR(end, closed, slack) << model->Name() << " s " << s;
            EXPECT_TRUE(HvDrivesIfClear(params, HvPosteriorGo(params, end, *model, s)));
            const double beyond = std::nextafter(end, end == t.lo ? 0.0 : 1.0);
            EXPECT_FALSE(HvDrivesIfClear(params, HvPosteriorGo(params, beyond, *model, s)));
          }
        }
      }
    }
  }
  EXPECT_GT(bounded, 500);
}

TEST(MinReadingForDc, MatchesTheoremTwoOverAGrid) {
  const LinearLikelihood linear(2.0);
  const LogisticLikelihood logistic(2.0, 4.0, 1.0);
  for (const LikelihoodModel* model : {static_cast<const LikelihoodModel*>(&linear),
                                       static_cast<const LikelihoodModel*>(&logistic)}) {
    for (double lambda : {0.1, 0.2, 0.3}) {
      for (double r : {2.0, 3.0, 6.0}) {
        const AvHvParams params{lambda, r};
        for (double theta = 0.0; theta <= 1.0; theta += 0.01) {
          const std::optional<double> s = MinReadingForDc(params, *model, theta);
          if (!AvHvPersuadable(params, theta, *model)) {
            EXPECT_FALSE(s.has_value());
            continue;
          }
          ASSERT_TRUE(s.has_value());
          // As above, the tie tolerance over dp/ds (>= 0.02 on this grid).
          EXPECT_NEAR(*s, MinimalNudge(params, theta, *model), 1e-7)
              << model->Name() << " theta " << theta;
          EXPECT_TRUE(HvDrivesIfClear(params, HvPosteriorGo(params, theta, *model, *s)));
          if (*s > 0.0) {
            EXPECT_FALSE(HvDrivesIfClear(
                params, HvPosteriorGo(params, theta, *model, std::nextafter(*s, 0.0))));
          }
        }
      }
    }
  }
  EXPECT_NEAR(*MinReadingForDc(kPaper, linear, 0.6), 64.0 / 39.0, 1e-8);
}

TEST(HvResponse, ErrorsNameTheInput) {
  const LinearLikelihood linear(2.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { DcTrustInterval(kPaper, linear, 2.5); }),
              HasSubstr("signal s = 2.5 is outside [0, 2]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { MinReadingForDc(kPaper, linear, 1.5); }),
              HasSubstr("trust theta = 1.5 is outside [0, 1]"));
}

}  // namespace
}  // namespace taebp::persuasion
