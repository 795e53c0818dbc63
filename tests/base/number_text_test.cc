// taebp::NumberText, the one number formatter: checked against values written
// out by hand and against a second method (strtod reads the shortest text back
// as the same double; a stream's precision, which the project's messages used
// before, for the digits form).
#include "taebp/base/number_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>

namespace {

using taebp::NumberText;

TEST(NumberText, ShortestTextAsWrittenByHand) {
  EXPECT_EQ(NumberText(0.9), "0.9");
  EXPECT_EQ(NumberText(-0.2), "-0.2");
  EXPECT_EQ(NumberText(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(NumberText(3.0), "3");
  EXPECT_EQ(NumberText(1e-7), "1e-07");
  EXPECT_EQ(NumberText(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(NumberText(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(NumberText, ShortestTextReadsBackAsTheSameDouble) {
  std::mt19937_64 rng(27);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  for (int i = 0; i < 20000; ++i) {
    const double v = std::ldexp(mantissa(rng), exponent(rng));
    const std::string text = NumberText(v);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
  }
}

TEST(NumberText, SignificantDigitsAsWrittenByHand) {
  EXPECT_EQ(NumberText(160.53981633974483, 6), "160.54");
  EXPECT_EQ(NumberText(2.0 / 3.0, 6), "0.666667");
  EXPECT_EQ(NumberText(1e6, 6), "1e+06");
  EXPECT_EQ(NumberText(1e6, 10), "1000000");
  EXPECT_EQ(NumberText(0.1, 17), "0.10000000000000001");
  EXPECT_EQ(NumberText(4.5, 3), "4.5");
  EXPECT_EQ(NumberText(std::numeric_limits<double>::quiet_NaN(), 6), "nan");
}

TEST(NumberText, SignificantDigitsAgreeWithAStreamsPrecision) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  for (int digits : {1, 3, 6, 8, 10, 17}) {
    for (int i = 0; i < 2000; ++i) {
      const double v = std::ldexp(mantissa(rng), exponent(rng));
      std::ostringstream expected;
      expected.precision(digits);
      expected << v;
      EXPECT_EQ(NumberText(v, digits), expected.str()) << v << " to " << digits << " digits";
    }
  }
}

}  // namespace
