// Where the HV's decision switches: the least trust, and the least reading of
// the nudge, for which it drives if clear (DC).
//
// The HV's posterior (eq:pp) is p_theta(Go|s) = lambda + theta (p_FT(Go|s) - lambda),
// increasing in s (Theorem 2) and affine in theta. So after a reading s the
// trusts that drive if clear form an interval touching 0 or 1:
//   p_FT(Go|s) > lambda: DC <=> theta >= theta_needed(s) = (p* - lambda) / (p_FT(Go|s) - lambda)
//   (the nudge raises the belief in Go; with lambda < p* this is every nudge that
//   can persuade), and p_FT(Go|s) < lambda: DC <=> theta <= that value (a reading
//   below the prior's belief in Go lowers it, so only low trust stays at DC,
//   which needs lambda >= p*). At trust theta, DC <=> s >= s*(theta) (Theorem 2).
// Both thresholds are found by bisection on the HV's own decision (HvDrivesIfClear
// of HvPosteriorGo), so they agree with whatever tie tolerance that decision
// uses; the closed forms agree up to that tolerance.
#pragma once

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"

#include <optional>

namespace taebp::persuasion {

// A closed interval of trust [lo, hi] within [0, 1]; empty when hi < lo.
struct TrustInterval {
  double lo = 0.0;
  double hi = -1.0;
  bool Empty() const { return hi < lo; }
  bool Contains(double theta) const { return theta >= lo && theta <= hi; }
};

// The trusts with which the HV drives if clear after reading s (s in [0, s_max]):
// [theta_needed(s), 1], [0, 1] (every trust), [0, u] (lambda >= p* and a
// reading below the prior), or empty (e.g. s = 0 under the linear model with
// lambda < p*). The finite end is exact to adjacent doubles: the HV drives if
// clear at it and not one double beyond.
TrustInterval DcTrustInterval(const AvHvParams& params, const LikelihoodModel& model,
                              double reading);

// The least reading r in [0, s_max] with which an HV of trust theta drives if
// clear: 0 when even standing still persuades, nullopt when not even s_max does
// (theta below the model's theta*). DC <=> reading >= result.
std::optional<double> MinReadingForDc(const AvHvParams& params, const LikelihoodModel& model,
                                      double theta);

}  // namespace taebp::persuasion
