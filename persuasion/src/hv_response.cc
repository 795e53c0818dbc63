// The HV's decision thresholds in trust and in the reading (bisection on its
// own decision function, so ties resolve exactly as the HV resolves them).
#include "taebp/persuasion/hv_response.h"

#include "internal.h"

#include <cmath>

namespace taebp::persuasion {

namespace {

// Smallest x in [lo, hi] with dc(x) true, given dc(lo) false, dc(hi) true and
// dc monotone: bisection down to adjacent doubles.
template <typename F>
double Bisect(double lo, double hi, F dc) {
  for (;;) {
    const double mid = lo + 0.5 * (hi - lo);
    if (!(mid > lo && mid < hi)) return hi;
    (dc(mid) ? hi : lo) = mid;
  }
}

}  // namespace

TrustInterval DcTrustInterval(const AvHvParams& params, const LikelihoodModel& model,
                              double reading) {
  params.Validate();
  auto dc = [&](double theta) {
    return HvDrivesIfClear(params, HvPosteriorGo(params, theta, model, reading));
  };
  // p_theta is affine in theta, so the DC set is an interval holding 0 or 1.
  const bool at0 = dc(0.0);  // validates the reading
  const bool at1 = dc(1.0);
  if (at0 && at1) return {0.0, 1.0};
  if (!at0 && !at1) return {};
  if (at1) {
    // Start from the closed form theta_needed = (p* - lambda) / (p_FT - lambda): the
    // tie tolerance moves the switch by less than 1e-9 / (p_FT - lambda), so a
    // bracket a few times that wide halves the bisection (checked, else [0, 1]).
    const double lambda = params.prior_go;
    const double go = model.PiGo(reading) * lambda;
    const double p_ft = go / (go + model.PiStop(reading) * (1.0 - lambda));
    const double guess = (AvHvPStar(params.collision_penalty) - lambda) / (p_ft - lambda);
    const double margin = 4e-9 / (p_ft - lambda) + 1e-15;
    const double lo = guess - margin, hi = guess + margin;
    if (std::isfinite(guess) && lo > 0.0 && hi < 1.0 && !dc(lo) && dc(hi)) {
      return {Bisect(lo, hi, dc), 1.0};
    }
    return {Bisect(0.0, 1.0, dc), 1.0};
  }
  // DC at 0 only: the greatest trust with DC, by bisection on "not DC".
  auto dr = [&](double theta) { return !dc(theta); };
  return {0.0, std::nextafter(Bisect(0.0, 1.0, dr), 0.0)};
}

std::optional<double> MinReadingForDc(const AvHvParams& params, const LikelihoodModel& model,
                                      double theta) {
  params.Validate();
  internal::CheckTrust(theta);
  auto dc = [&](double s) {
    return HvDrivesIfClear(params, HvPosteriorGo(params, theta, model, s));
  };
  if (dc(0.0)) return 0.0;
  if (!dc(model.SMax())) return std::nullopt;
  return Bisect(0.0, model.SMax(), dc);  // eq:pp is increasing in s (Theorem 2)
}

}  // namespace taebp::persuasion
