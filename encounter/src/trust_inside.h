// A drawn trust as the mean of a proper Beta state: private to the encounter
// room (hv_population.cc and hv_population_results.cc both start a Beta
// state from a drawn trust).
#pragma once

#include <algorithm>

namespace taebp {

// A drawn trust 0 or 1 (a quantile at the very end of a distribution) as the
// mean of a proper Beta state.
inline double Inside01(double theta) { return std::clamp(theta, 1e-9, 1.0 - 1e-9); }

}  // namespace taebp
