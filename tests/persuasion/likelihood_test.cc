// The HV's intuitive likelihood models (Section IV-B, Section V-A) and L^{-1}.
#include "taebp/persuasion/likelihood.h"

#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace taebp::persuasion {
namespace {

using ::testing::HasSubstr;
using testing::InvalidArgumentMessage;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ------------------------------------------------------------------- linear

TEST(LinearLikelihood, PaperModel) {
  const LinearLikelihood model;  // s_max = 2: pi(s|Go) = s/2, pi(s|Stop) = 1 - s/2
  EXPECT_EQ(model.Name(), "linear");
  EXPECT_EQ(model.SMax(), 2.0);
  EXPECT_DOUBLE_EQ(model.PiGo(0.5), 0.25);
  EXPECT_DOUBLE_EQ(model.PiStop(0.5), 0.75);
  EXPECT_DOUBLE_EQ(model.Ratio(0.5), 1.0 / 3.0);  // L(s) = s / (2 - s)
  EXPECT_DOUBLE_EQ(model.Ratio(1.5), 3.0);
  EXPECT_EQ(model.Ratio(1.0), 1.0);
  EXPECT_EQ(model.Ratio(0.0), 0.0);
  EXPECT_EQ(model.PiStop(2.0), 0.0);  // exact, so L(s_max) is +inf, not huge
  EXPECT_EQ(model.Ratio(2.0), kInf);
  EXPECT_EQ(model.MaxRatio(), kInf);
}

TEST(LinearLikelihood, InverseRatioClosedForm) {
  const LinearLikelihood model(2.0);
  // L^{-1}(R) = 2R / (1 + R): 32/7 -> 64/39 and 8/3 -> 16/11 (the paper's nudges).
  EXPECT_NEAR(model.InverseRatio(32.0 / 7.0), 64.0 / 39.0, 1e-15);
  EXPECT_NEAR(model.InverseRatio(8.0 / 3.0), 16.0 / 11.0, 1e-15);
  EXPECT_EQ(model.InverseRatio(1.0), 1.0);
  EXPECT_EQ(model.InverseRatio(0.0), 0.0);
  EXPECT_EQ(model.InverseRatio(-3.0), 0.0);
  EXPECT_EQ(model.InverseRatio(kInf), 2.0);
  for (int i = 1; i < 40; ++i) {
    const double s = 0.05 * i;
    EXPECT_NEAR(model.InverseRatio(model.Ratio(s)), s, 1e-13) << "s = " << s;
  }
}

TEST(LinearLikelihood, OtherSMax) {
  const LinearLikelihood model(0.8);
  EXPECT_DOUBLE_EQ(model.PiGo(0.2), 0.25);
  EXPECT_NEAR(model.InverseRatio(1.0), 0.4, 1e-15);
  EXPECT_THAT(InvalidArgumentMessage([&] { model.PiGo(1.0); }), HasSubstr("signal s = 1 is outside [0, 0.8]"));
}

TEST(LinearLikelihood, RejectsSignalsOutsideRange) {
  const LinearLikelihood model(2.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { model.PiGo(2.5); }), HasSubstr("signal s = 2.5 is outside [0, 2]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { model.PiStop(-0.1); }),
              HasSubstr("signal s = -0.1 is outside [0, 2]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { model.Ratio(kNaN); }), HasSubstr("signal s = nan is outside [0, 2]"));
  EXPECT_THAT(InvalidArgumentMessage([&] { model.InverseRatio(kNaN); }), HasSubstr("likelihood ratio = nan"));
}

TEST(LinearLikelihood, RejectsBadSMax) {
  EXPECT_THAT(InvalidArgumentMessage([] { LinearLikelihood m(0.0); }), HasSubstr("s_max = 0 must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { LinearLikelihood m(-1.0); }), HasSubstr("s_max = -1 must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { LinearLikelihood m(kNaN); }), HasSubstr("s_max = nan must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { LinearLikelihood m(kInf); }),
              HasSubstr("s_max = inf must be > 0 and finite"));
}

// ----------------------------------------------------------------- logistic

TEST(LogisticLikelihood, ValuesAndRatio) {
  const LogisticLikelihood model(2.0, 3.0, 1.0);
  EXPECT_EQ(model.Name(), "logistic");
  EXPECT_EQ(model.Steepness(), 3.0);
  EXPECT_EQ(model.Midpoint(), 1.0);
  EXPECT_DOUBLE_EQ(model.PiGo(1.0), 0.5);
  for (double s = 0.0; s <= 2.0; s += 0.125) {
    EXPECT_NEAR(model.PiGo(s) + model.PiStop(s), 1.0, 1e-15);
    EXPECT_NEAR(model.PiGo(s), 1.0 / (1.0 + std::exp(-3.0 * (s - 1.0))), 1e-15);
    // L(s) = sigma(x) / sigma(-x) = exp(x), x = k (s - m).
    EXPECT_NEAR(model.Ratio(s), std::exp(3.0 * (s - 1.0)), 1e-13 * std::exp(3.0 * (s - 1.0)));
  }
  EXPECT_NEAR(model.MaxRatio(), std::exp(3.0), 1e-12);
  EXPECT_TRUE(std::isfinite(model.MaxRatio()));
}

// The TOMS 748 inverse against the closed form s = m + log(R) / k, which the
// implementation never uses.
TEST(LogisticLikelihood, InverseMatchesClosedForm) {
  for (const auto& [k, m] : {std::pair{3.0, 1.0}, std::pair{1.5, 0.4}, std::pair{8.0, 1.7}}) {
    const LogisticLikelihood model(2.0, k, m);
    const double lo = std::log(model.Ratio(0.0)), hi = std::log(model.MaxRatio());
    for (int i = 1; i < 100; ++i) {
      const double ratio = std::exp(lo + (hi - lo) * i / 100.0);
      const double closed_form = m + std::log(ratio) / k;
      EXPECT_NEAR(model.InverseRatio(ratio), closed_form, 2e-12)
          << "k = " << k << ", m = " << m << ", R = " << ratio;
    }
  }
}

TEST(LogisticLikelihood, InverseEdgeCases) {
  const LogisticLikelihood model(2.0, 3.0, 1.0);
  EXPECT_EQ(model.InverseRatio(0.0), 0.0);
  EXPECT_EQ(model.InverseRatio(-1.0), 0.0);
  EXPECT_EQ(model.InverseRatio(model.Ratio(0.0)), 0.0);       // L(0) needs no nudge
  EXPECT_EQ(model.InverseRatio(0.5 * model.Ratio(0.0)), 0.0);
  EXPECT_NEAR(model.InverseRatio(model.MaxRatio()), 2.0, 1e-12);
  EXPECT_NEAR(model.InverseRatio(1.0), 1.0, 1e-12);
}

TEST(LogisticLikelihood, UnreachableRatioThrows) {
  const LogisticLikelihood model(2.0, 3.0, 1.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { model.InverseRatio(1.01 * std::exp(3.0)); }),
              HasSubstr("is unreachable by the logistic model"));
  EXPECT_THAT(InvalidArgumentMessage([&] { model.InverseRatio(kInf); }),
              HasSubstr("likelihood ratio inf is unreachable"));
}

TEST(LogisticLikelihood, RejectsBadParameters) {
  EXPECT_THAT(InvalidArgumentMessage([] { LogisticLikelihood m(2.0, 0.0, 1.0); }),
              HasSubstr("logistic steepness k = 0 must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { LogisticLikelihood m(2.0, -2.0, 1.0); }),
              HasSubstr("logistic steepness k = -2 must be > 0"));
  EXPECT_THAT(InvalidArgumentMessage([] { LogisticLikelihood m(2.0, 3.0, 2.5); }),
              HasSubstr("logistic midpoint m = 2.5 is outside [0, 2]"));
  EXPECT_THAT(InvalidArgumentMessage([] { LogisticLikelihood m(2.0, 3.0, -0.5); }),
              HasSubstr("logistic midpoint m = -0.5 is outside [0, 2]"));
  EXPECT_THAT(InvalidArgumentMessage([] { LogisticLikelihood m(0.0, 3.0, 0.0); }),
              HasSubstr("s_max = 0 must be > 0"));
  const LogisticLikelihood model(2.0, 3.0, 1.0);
  EXPECT_THAT(InvalidArgumentMessage([&] { model.PiStop(2.5); }), HasSubstr("signal s = 2.5 is outside [0, 2]"));
}

}  // namespace
}  // namespace taebp::persuasion
