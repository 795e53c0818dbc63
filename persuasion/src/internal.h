// Private helpers shared by the persuasion sources (not installed, not public).
#pragma once

#include "taebp/base/number_text.h"
#include "taebp/persuasion/persuasion.h"

#include <cmath>
#include <functional>
#include <string>

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

}  // namespace taebp::persuasion::internal
