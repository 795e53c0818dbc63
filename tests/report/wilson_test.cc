// The one Wilson interval of the C++ code (report.h), against published values
// and closed forms at its edges. python/taebp/stats.py is checked against the
// same values (tests/python/test_stats.py).
#include "taebp/report/report.h"

#include <gtest/gtest.h>

namespace taebp {
namespace {

// Newcombe (1998), "Two-sided confidence intervals for the single proportion:
// comparison of seven methods", Statistics in Medicine 17:857-872, Table II,
// method 3 (Wilson score interval without continuity correction), 95 %, to the
// four decimals printed there.
TEST(Wilson, MatchesNewcombesPublishedExamples) {
  struct Case {
    long k, n;
    double low, high;
  };
  for (const Case& c : {Case{81, 263, 0.2553, 0.3662}, Case{15, 148, 0.0624, 0.1605},
                        Case{0, 20, 0.0, 0.1611}, Case{1, 29, 0.0061, 0.1718}}) {
    const Interval i = Wilson(c.k, c.n);
    EXPECT_NEAR(i.low, c.low, 5e-5) << c.k << "/" << c.n;
    EXPECT_NEAR(i.high, c.high, 5e-5) << c.k << "/" << c.n;
  }
}

// At k = 0 the upper bound is z^2 / (n + z^2) and the lower bound exactly 0;
// k = n mirrors it; n = 1 is the smallest sample.
TEST(Wilson, EdgesAreExactClosedForms) {
  for (double z : {kZ95, kZ999}) {
    for (long n : {1L, 2L, 10L, 1000L}) {
      const double edge = z * z / (n + z * z);
      const Interval none = Wilson(0, n, z), all = Wilson(n, n, z);
      EXPECT_EQ(none.low, 0.0) << n;
      EXPECT_NEAR(none.high, edge, 1e-14) << n;
      EXPECT_NEAR(all.low, 1.0 - edge, 1e-14) << n;
      EXPECT_EQ(all.high, 1.0) << n;
    }
  }
  EXPECT_NEAR(Wilson(0, 1).high, 0.7935, 5e-5);  // 0/1 at 95 %
  EXPECT_NEAR(Wilson(1, 1).low, 0.2065, 5e-5);
  const Interval empty = Wilson(0, 0);
  EXPECT_EQ(empty.low, 0.0);
  EXPECT_EQ(empty.high, 1.0);
}

// Over a grid: inside [0, 1], contains k/n, symmetric under k -> n - k, wider
// at 99.9 % than at 95 %.
TEST(Wilson, InvariantsOverAGrid) {
  for (long n = 1; n <= 60; ++n) {
    for (long k = 0; k <= n; ++k) {
      const Interval a = Wilson(k, n), b = Wilson(n - k, n), wide = Wilson(k, n, kZ999);
      const double p = static_cast<double>(k) / n;
      EXPECT_LE(0.0, a.low);
      EXPECT_LE(a.low, p);
      EXPECT_LE(p, a.high);
      EXPECT_LE(a.high, 1.0);
      EXPECT_NEAR(a.low, 1.0 - b.high, 1e-12) << k << "/" << n;
      EXPECT_LE(wide.low, a.low + 1e-15);
      EXPECT_GE(wide.high, a.high - 1e-15);
    }
  }
}

}  // namespace
}  // namespace taebp
