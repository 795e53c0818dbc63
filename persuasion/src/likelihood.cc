// The HV's intuitive likelihood of a nudge s (paper Section IV-B) and the
// inverse likelihood ratio L^{-1} used by Theorem 2 (eq:s^*).
#include "taebp/persuasion/likelihood.h"

#include "internal.h"
#include "taebp/persuasion/persuasion.h"

#include <boost/math/tools/roots.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace taebp::persuasion {


namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

void CheckRatioArgument(double ratio) {
  if (std::isnan(ratio)) throw InvalidArgument("likelihood ratio = nan is not a number");
}
}  // namespace

// ---------------------------------------------------------------------------
// LikelihoodModel
// ---------------------------------------------------------------------------
LikelihoodModel::LikelihoodModel(double s_max) : s_max_(s_max) {
  if (!(s_max > 0.0) || !std::isfinite(s_max)) {
    throw InvalidArgument("s_max = " + NumberText(s_max) + " must be > 0 and finite");
  }
}

void LikelihoodModel::CheckSignal(double s) const {
  if (!(s >= 0.0 && s <= s_max_)) {
    throw InvalidArgument("signal s = " + NumberText(s) + " is outside [0, " + NumberText(s_max_) + "]");
  }
}

// L(s) = pi(s|Go) / pi(s|Stop) (the argument of eq:pp); +inf where pi(s|Stop) = 0.
double LikelihoodModel::Ratio(double s) const {
  const double go = PiGo(s);      // validates s
  const double stop = PiStop(s);
  if (stop == 0.0) return kInf;
  return go / stop;
}

// ---------------------------------------------------------------------------
// LinearLikelihood (Section V-A): pi(s|Go) = s/s_max, pi(s|Stop) = 1 - s/s_max,
// L(s) = s / (s_max - s). At s = s_max, pi(s|Stop) is exactly 0 (L = +inf), at
// s = 0, pi(s|Go) is exactly 0 (L = 0).
// ---------------------------------------------------------------------------
LinearLikelihood::LinearLikelihood(double s_max) : LikelihoodModel(s_max) {}

double LinearLikelihood::PiGo(double s) const {
  CheckSignal(s);
  return s / s_max_;
}

double LinearLikelihood::PiStop(double s) const {
  CheckSignal(s);
  return (s_max_ - s) / s_max_;
}

// L^{-1}(R) = s_max R / (1 + R): solves s / (s_max - s) = R.
double LinearLikelihood::InverseRatio(double ratio) const {
  CheckRatioArgument(ratio);
  if (ratio <= 0.0) return 0.0;  // L(0) = 0
  if (ratio == kInf) return s_max_;
  const double s = s_max_ * ratio / (1.0 + ratio);
  return s > s_max_ ? s_max_ : s;
}

// ---------------------------------------------------------------------------
// LogisticLikelihood: pi(s|Go) = sigma(k (s - m)), pi(s|Stop) = 1 - pi(s|Go),
// so L(s) = exp(k (s - m)) is finite on [0, s_max]. pi(s|Stop) is evaluated as
// sigma(-k (s - m)), which equals 1 - sigma(k (s - m)) but without cancellation.
// ---------------------------------------------------------------------------
LogisticLikelihood::LogisticLikelihood(double s_max, double steepness, double midpoint)
    : LikelihoodModel(s_max), k_(steepness), m_(midpoint) {
  if (!(steepness > 0.0) || !std::isfinite(steepness)) {
    throw InvalidArgument("logistic steepness k = " + NumberText(steepness) + " must be > 0 and finite");
  }
  if (!(midpoint >= 0.0 && midpoint <= s_max)) {
    throw InvalidArgument("logistic midpoint m = " + NumberText(midpoint) + " is outside [0, " +
                          NumberText(s_max) + "]");
  }
}

double LogisticLikelihood::PiGo(double s) const {
  CheckSignal(s);
  return 1.0 / (1.0 + std::exp(-k_ * (s - m_)));
}

double LogisticLikelihood::PiStop(double s) const {
  CheckSignal(s);
  return 1.0 / (1.0 + std::exp(k_ * (s - m_)));
}

// L^{-1}(R): the root of f(s) = pi(s|Go) - R pi(s|Stop) on [0, s_max]. f is
// strictly increasing (pi(.|Go) increases, pi(.|Stop) decreases), f(0) < 0 once
// R > L(0) and f(s_max) >= 0 once R <= L(s_max), so the root is bracketed. It is
// found with Boost.Math's TOMS 748 (Alefeld, Potra & Shi), stopping when the
// bracket is at most kInverseTolerance wide; we return the bracket's upper end,
// where f >= 0, i.e. L(s) >= R up to round-off. The solver never uses the closed
// form s = m + log(R) / k, so tests can use that as an independent check.
double LogisticLikelihood::InverseRatio(double ratio) const {
  CheckRatioArgument(ratio);
  if (ratio <= Ratio(0.0)) return 0.0;
  const double max_ratio = MaxRatio();
  if (ratio > max_ratio) {
    throw InvalidArgument("likelihood ratio " + NumberText(ratio) + " is unreachable by the " + Name() +
                          " model (L(s_max) = " + NumberText(max_ratio) + ")");
  }
  auto f = [this, ratio](double s) { return PiGo(s) - ratio * PiStop(s); };
  const double f_lo = f(0.0);
  const double f_hi = f(s_max_);
  if (f_hi == 0.0) return s_max_;
  if (!(f_lo < 0.0 && f_hi > 0.0)) {
    // Only reachable through round-off right at the ends of the range.
    return f_lo >= 0.0 ? 0.0 : s_max_;
  }
  auto tolerance = [](double lo, double hi) { return std::abs(hi - lo) <= kInverseTolerance; };
  std::uintmax_t max_iter = 200;
  const auto bracket =
      boost::math::tools::toms748_solve(f, 0.0, s_max_, f_lo, f_hi, tolerance, max_iter);
  if (!(std::abs(bracket.second - bracket.first) <= kInverseTolerance)) {
    throw std::runtime_error("TOMS 748 did not converge for likelihood ratio " + NumberText(ratio));
  }
  return bracket.second;
}

}  // namespace taebp::persuasion
