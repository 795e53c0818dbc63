// Private helpers shared by the persuasion sources (not installed, not public).
#pragma once

#include "taebp/base/number_text.h"
#include "taebp/persuasion/persuasion.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace taebp::persuasion::internal {

// theta in [0, 1] (NaN rejected).
inline void CheckTrust(double theta, const char* name = "trust theta") {
  if (!(theta >= 0.0 && theta <= 1.0)) {
    throw InvalidArgument(std::string(name) + " = " + NumberText(theta) + " is outside [0, 1]");
  }
}

// The share of [lo, hi] where `f` holds, for an f whose value changes at most
// once inside each of `cells` equal cells (each change located by bisection
// to 1e-12 of the range). lo == hi: f(lo) as 0 or 1.
double ShareWhere(const std::function<bool(double)>& f, double lo, double hi, int cells = 1024);

// The LP's numerics (lp.cc), shared by the single- and the multi-receiver LP
// (lp_multi.cc). PowerOfTwoScale: 2^(k-1) with max |entry| in [2^(k-1), 2^k)
// (1 for an all-zero table), an exact divisor leaving every entry below 2.
double PowerOfTwoScale(const Eigen::MatrixXd& table);
// Obedience coefficients of one receiver (trust theta, scaled utility u):
// obedience[(a m + a') n + w] = p0(w) [(1 - theta) dU0(a, a') + theta D(w; a, a')]
// divided by the row's largest |entry|; the row (a, a') multiplies pi(a | w)
// (or, for several receivers, pi(profile | w) of every profile recommending a).
// Returns "" or what is wrong with a row.
std::string ObedienceRows(const Game& game, const Eigen::MatrixXd& u, double theta,
                          std::vector<double>* obedience);

}  // namespace taebp::persuasion::internal
