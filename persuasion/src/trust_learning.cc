// Learned trust: interval-censored posteriors over an HV's trust, the
// delta-safe TA-EBP design, and regret against the exact-theta oracle.
#include "taebp/persuasion/trust_learning.h"

#include "internal.h"

#include <boost/math/special_functions/beta.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace taebp::persuasion {


const double TrustPrior::kAboveOne = std::nextafter(1.0, 2.0);

namespace {

// Boost.Math in double precision (its default promotes to long double, ~5x
// slower here, for digits the posterior does not need).
using DoublePrecision = boost::math::policies::policy<boost::math::policies::promote_double<false>>;

// The smallest x in [lo, hi] where the monotone predicate `reached` holds
// (hi if it holds nowhere before), to adjacent doubles.
template <typename Reached>
double Bisect(double lo, double hi, Reached reached) {
  for (int i = 0; i < 2000 && lo < hi; ++i) {
    const double mid = lo + 0.5 * (hi - lo);
    if (mid <= lo || mid >= hi) break;
    if (reached(mid)) hi = mid; else lo = mid;
  }
  return hi;
}

// Below this width a Beta density is taken as constant across [lo, hi): the
// CDF difference would lose its digits, the constant density loses none that
// matter (relative error ~ width * |f'/f|).
constexpr double kNarrow = 1e-7;

void CheckUnitFraction(double p, const char* name) {
  if (!(p >= 0.0 && p <= 1.0)) {
    throw InvalidArgument(std::string(name) + " = " + NumberText(p) + " is outside [0, 1]");
  }
}

}  // namespace

// ---------------------------------------------------------------------------
// TrustPrior
// ---------------------------------------------------------------------------
TrustPrior TrustPrior::Beta(double a, double b) {
  if (!(a > 0.0 && std::isfinite(a))) {
    throw InvalidArgument("trust prior Beta a = " + NumberText(a) + " must be > 0 and finite");
  }
  if (!(b > 0.0 && std::isfinite(b))) {
    throw InvalidArgument("trust prior Beta b = " + NumberText(b) + " must be > 0 and finite");
  }
  TrustPrior prior;
  prior.kind_ = Kind::kBeta;
  prior.a_ = a;
  prior.b_ = b;
  return prior;
}

TrustPrior TrustPrior::Histogram(std::vector<double> weights) {
  if (weights.empty()) throw InvalidArgument("trust prior histogram has no cells");
  double total = 0.0;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    if (!(weights[k] >= 0.0 && std::isfinite(weights[k]))) {
      throw InvalidArgument("trust prior histogram weight[" + std::to_string(k) +
                            "] = " + NumberText(weights[k]) + " must be finite and >= 0");
    }
    total += weights[k];
  }
  if (!(total > 0.0)) throw InvalidArgument("trust prior histogram weights sum to 0");
  TrustPrior prior;
  prior.kind_ = Kind::kHistogram;
  prior.cells_ = std::move(weights);
  prior.cell_cumulative_.assign(1, 0.0);
  for (double& w : prior.cells_) {
    w /= total;
    prior.cell_cumulative_.push_back(prior.cell_cumulative_.back() + w);
  }
  return prior;
}

TrustPrior TrustPrior::Discrete(std::vector<double> values, std::vector<double> weights) {
  if (values.empty()) throw InvalidArgument("trust prior has no values");
  if (values.size() != weights.size()) {
    throw InvalidArgument("trust prior has " + std::to_string(values.size()) + " values but " +
                          std::to_string(weights.size()) + " weights");
  }
  std::map<double, double> atoms;
  double total = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!(values[i] >= 0.0 && values[i] <= 1.0)) {
      throw InvalidArgument("trust prior value[" + std::to_string(i) + "] = " + NumberText(values[i]) +
                            " is outside [0, 1]");
    }
    if (!(weights[i] >= 0.0 && std::isfinite(weights[i]))) {
      throw InvalidArgument("trust prior weight[" + std::to_string(i) + "] = " + NumberText(weights[i]) +
                            " must be finite and >= 0");
    }
    atoms[values[i]] += weights[i];
    total += weights[i];
  }
  if (!(total > 0.0)) throw InvalidArgument("trust prior weights sum to 0");
  TrustPrior prior;
  prior.kind_ = Kind::kDiscrete;
  prior.atom_cumulative_.assign(1, 0.0);
  for (const auto& [value, weight] : atoms) {
    if (weight == 0.0) continue;
    prior.values_.push_back(value);
    prior.weights_.push_back(weight / total);
    prior.atom_cumulative_.push_back(prior.atom_cumulative_.back() + weight / total);
  }
  return prior;
}

double TrustPrior::Mass(double lo, double hi) const {
  lo = std::max(lo, 0.0);
  if (!(hi > lo)) return 0.0;
  switch (kind_) {
    case Kind::kBeta: {
      const double top = std::min(hi, 1.0);
      if (!(top > lo)) return 0.0;  // [1, kAboveOne): no atom at 1
      if (top - lo <= kNarrow) {
        const double mid = 0.5 * (lo + top);
        return boost::math::ibeta_derivative(a_, b_, mid, DoublePrecision()) * (top - lo);
      }
      // Differences of the tail nearer to the interval keep their digits.
      if (lo >= a_ / (a_ + b_)) {
        return boost::math::ibetac(a_, b_, lo, DoublePrecision()) -
               (hi >= 1.0 ? 0.0 : boost::math::ibetac(a_, b_, hi, DoublePrecision()));
      }
      return (hi >= 1.0 ? 1.0 : boost::math::ibeta(a_, b_, hi, DoublePrecision())) -
             boost::math::ibeta(a_, b_, lo, DoublePrecision());
    }
    case Kind::kHistogram: {
      const auto k_count = static_cast<double>(cells_.size());
      const double top = std::min(hi, 1.0);
      double mass = 0.0;
      const auto first = static_cast<std::size_t>(std::min(std::floor(lo * k_count), k_count - 1));
      for (std::size_t k = first; k < cells_.size(); ++k) {
        const double cell_lo = static_cast<double>(k) / k_count;
        if (cell_lo >= top) break;
        const double cell_hi = static_cast<double>(k + 1) / k_count;
        const double overlap = std::min(top, cell_hi) - std::max(lo, cell_lo);
        if (overlap > 0.0) mass += cells_[k] * k_count * overlap;
      }
      return mass;
    }
    case Kind::kDiscrete: {
      const auto begin = std::lower_bound(values_.begin(), values_.end(), lo) - values_.begin();
      const auto end = std::lower_bound(values_.begin(), values_.end(), hi) - values_.begin();
      return atom_cumulative_[end] - atom_cumulative_[begin];
    }
  }
  return 0.0;
}

double TrustPrior::FirstMoment(double lo, double hi) const {
  lo = std::max(lo, 0.0);
  if (!(hi > lo)) return 0.0;
  switch (kind_) {
    case Kind::kBeta: {
      const double top = std::min(hi, 1.0);
      if (top - lo <= kNarrow) return 0.5 * (lo + top) * Mass(lo, hi);
      // theta f(theta; a, b) = a / (a + b) f(theta; a + 1, b).
      const double scale = a_ / (a_ + b_);
      if (lo >= scale) {
        return scale *
               (boost::math::ibetac(a_ + 1.0, b_, lo, DoublePrecision()) -
                (hi >= 1.0 ? 0.0 : boost::math::ibetac(a_ + 1.0, b_, hi, DoublePrecision())));
      }
      return scale * ((hi >= 1.0 ? 1.0 : boost::math::ibeta(a_ + 1.0, b_, hi, DoublePrecision())) -
                      boost::math::ibeta(a_ + 1.0, b_, lo, DoublePrecision()));
    }
    case Kind::kHistogram: {
      const auto k_count = static_cast<double>(cells_.size());
      const double top = std::min(hi, 1.0);
      double moment = 0.0;
      for (std::size_t k = 0; k < cells_.size(); ++k) {
        const double x1 = std::max(lo, static_cast<double>(k) / k_count);
        const double x2 = std::min(top, static_cast<double>(k + 1) / k_count);
        if (x2 > x1) moment += cells_[k] * k_count * 0.5 * (x2 * x2 - x1 * x1);
      }
      return moment;
    }
    case Kind::kDiscrete: {
      double moment = 0.0;
      for (std::size_t i = 0; i < values_.size(); ++i) {
        if (values_[i] >= lo && values_[i] < hi) moment += values_[i] * weights_[i];
      }
      return moment;
    }
  }
  return 0.0;
}

double TrustPrior::QuantileWithin(double lo, double hi, double p, bool upper) const {
  CheckUnitFraction(p, "quantile level p");
  lo = std::max(lo, 0.0);
  const double total = Mass(lo, hi);
  if (!(total > 0.0)) {
    throw InvalidArgument("the trust interval [" + NumberText(lo) + ", " + NumberText(hi) +
                          ") has no prior mass");
  }
  const double top = std::min(hi, 1.0);
  auto clamp = [lo, top](double x) { return std::clamp(x, lo, top); };
  const double target = p * total;
  switch (kind_) {
    case Kind::kBeta: {
      // A positive density: the lower and the upper quantile coincide.
      if (top - lo <= kNarrow) return clamp(lo + p * (top - lo));
      // Boost's Newton iteration gives up on levels far in a tail (a learning
      // delta of 1e-300: "no root to be found"); bisection on the monotone
      // distribution function then finds the quantile to the last double.
      if (lo >= a_ / (a_ + b_)) {
        const double tail = boost::math::ibetac(a_, b_, lo, DoublePrecision()) - target;
        if (tail <= 0.0) return top;
        try {
          return clamp(boost::math::ibetac_inv(a_, b_, tail, DoublePrecision()));
        } catch (const boost::math::evaluation_error&) {
          return Bisect(lo, top, [&](double x) {
            return boost::math::ibetac(a_, b_, x, DoublePrecision()) <= tail;
          });
        }
      }
      const double cdf = boost::math::ibeta(a_, b_, lo, DoublePrecision()) + target;
      if (cdf >= 1.0) return top;
      try {
        return clamp(boost::math::ibeta_inv(a_, b_, cdf, DoublePrecision()));
      } catch (const boost::math::evaluation_error&) {
        return Bisect(lo, top, [&](double x) {
          return boost::math::ibeta(a_, b_, x, DoublePrecision()) >= cdf;
        });
      }
    }
    case Kind::kHistogram: {
      const auto k_count = static_cast<double>(cells_.size());
      double acc = 0.0;
      double last_positive_end = lo;
      for (std::size_t k = 0; k < cells_.size(); ++k) {
        const double x1 = std::max(lo, static_cast<double>(k) / k_count);
        const double x2 = std::min(top, static_cast<double>(k + 1) / k_count);
        if (!(x2 > x1) || cells_[k] == 0.0) continue;
        const double density = cells_[k] * k_count;
        const double seg = density * (x2 - x1);
        const bool reached = upper ? acc + seg > target : acc + seg >= target;
        if (reached) return clamp(x1 + (target - acc) / density);
        acc += seg;
        last_positive_end = x2;
      }
      // Round-off left the target unreached: the end of the support (lower) or
      // of the interval (upper: no mass above the target).
      return upper ? top : last_positive_end;
    }
    case Kind::kDiscrete: {
      const auto begin = std::lower_bound(values_.begin(), values_.end(), lo) - values_.begin();
      const auto end = std::lower_bound(values_.begin(), values_.end(), hi) - values_.begin();
      double acc = 0.0;
      for (auto i = begin; i < end; ++i) {
        acc += weights_[i];
        const bool reached = upper ? acc > target : acc >= target;
        if (reached) return values_[i];
      }
      return upper ? top : values_[end - 1];
    }
  }
  return lo;
}

double TrustPrior::Draw(double u01) const {
  if (!(u01 >= 0.0 && u01 < 1.0)) {
    throw InvalidArgument("uniform draw u = " + NumberText(u01) + " is outside [0, 1)");
  }
  return QuantileWithin(0.0, kAboveOne, u01, false);
}

// ---------------------------------------------------------------------------
// TrustBelief
// ---------------------------------------------------------------------------
const char* ToString(ObservationEffect effect) {
  switch (effect) {
    case ObservationEffect::kNarrowed:
      return "narrowed";
    case ObservationEffect::kConsistent:
      return "consistent";
    case ObservationEffect::kUninformative:
      return "uninformative";
    case ObservationEffect::kContradiction:
      return "contradiction";
  }
  return "unknown";
}

TrustBelief::TrustBelief(std::shared_ptr<const TrustPrior> prior)
    : prior_(std::move(prior)), upper_(TrustPrior::kAboveOne) {
  if (prior_ == nullptr) throw InvalidArgument("trust belief needs a prior (got none)");
}

ObservationEffect TrustBelief::Observe(const AvHvParams& params, const LikelihoodModel& model,
                                       double reading, bool drove_if_clear) {
  return Observe(DcTrustInterval(params, model, reading), drove_if_clear);
}

ObservationEffect TrustBelief::Observe(const TrustInterval& dc_set, bool drove_if_clear) {
  // The DC set touches 0 or 1; what is left of [0, 1] is the other half-line.
  if (!dc_set.Empty() && dc_set.lo > 0.0 && dc_set.hi < 1.0) {
    throw InvalidArgument("DC trust set [" + NumberText(dc_set.lo) + ", " + NumberText(dc_set.hi) +
                          "] touches neither 0 nor 1 (eq:pp is affine in theta)");
  }
  if (dc_set.Empty() || (dc_set.lo <= 0.0 && dc_set.hi >= 1.0)) {
    // Every trust (or none) responds alike: only the other response would be news.
    const bool expected = !dc_set.Empty();
    if (drove_if_clear == expected) return ObservationEffect::kUninformative;
    ++contradictions_;
    return ObservationEffect::kContradiction;
  }
  // The constraint as theta in [lo, hi): DC set [t, 1] -> DC: [t, up), DR: [0, t);
  // DC set [0, u] -> DC: [0, u'), DR: [u', up) with u' the double above u.
  double lo = 0.0, hi = TrustPrior::kAboveOne;
  if (dc_set.lo > 0.0) {
    (drove_if_clear ? lo : hi) = dc_set.lo;
  } else {
    (drove_if_clear ? hi : lo) = std::nextafter(dc_set.hi, 2.0);
  }
  ++observations_;
  const double new_lower = std::max(lower_, lo);
  const double new_upper = std::min(upper_, hi);
  if (!(prior_->Mass(new_lower, new_upper) > 0.0)) {
    ++contradictions_;
    return ObservationEffect::kContradiction;
  }
  if (new_lower == lower_ && new_upper == upper_) return ObservationEffect::kConsistent;
  lower_ = new_lower;
  upper_ = new_upper;
  return ObservationEffect::kNarrowed;
}

double TrustBelief::Evidence() const { return prior_->Mass(lower_, upper_); }

double TrustBelief::Mean() const {
  const double mean = prior_->FirstMoment(lower_, upper_) / Evidence();
  return std::clamp(mean, lower_, Upper());
}

double TrustBelief::Quantile(double p) const {
  return prior_->QuantileWithin(lower_, upper_, p, false);
}

double TrustBelief::ProbabilityBelow(double x) const {
  if (std::isnan(x)) throw InvalidArgument("trust x = nan is not a number");
  if (x <= lower_) return 0.0;
  if (x >= upper_) return 1.0;
  return std::clamp(prior_->Mass(lower_, x) / Evidence(), 0.0, 1.0);
}

double TrustBelief::LowerBound(double delta) const {
  CheckUnitFraction(delta, "credible level delta");
  return prior_->QuantileWithin(lower_, upper_, delta, true);
}

FleetTrustBeliefs::FleetTrustBeliefs(TrustPrior population)
    : population_(std::make_shared<const TrustPrior>(std::move(population))) {}

TrustBelief& FleetTrustBeliefs::For(const std::string& hv_id) {
  auto it = beliefs_.find(hv_id);
  if (it == beliefs_.end()) it = beliefs_.emplace(hv_id, TrustBelief(population_)).first;
  return it->second;
}

const TrustBelief* FleetTrustBeliefs::Find(const std::string& hv_id) const {
  const auto it = beliefs_.find(hv_id);
  return it == beliefs_.end() ? nullptr : &it->second;
}

// ---------------------------------------------------------------------------
// The delta-safe design.
// ---------------------------------------------------------------------------
double ExplorationSchedule::Level(int observations) const {
  Validate();
  if (observations < 0) {
    throw InvalidArgument("observations = " + std::to_string(observations) + " must be >= 0");
  }
  return std::min(delta, decay / (static_cast<double>(observations) + 1.0));
}

bool ExplorationSchedule::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(delta > 0.0 && delta < 1.0)) return fail("delta = " + NumberText(delta) + " is outside (0, 1)");
  if (!(decay > 0.0)) return fail("decay = " + NumberText(decay) + " must be > 0");
  return true;
}

void ExplorationSchedule::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

const char* ToString(LearnedDesign::Mode mode) {
  switch (mode) {
    case LearnedDesign::Mode::kDesign:
      return "design";
    case LearnedDesign::Mode::kProbe:
      return "probe";
    case LearnedDesign::Mode::kFallback:
      return "fallback";
  }
  return "unknown";
}

namespace {

// Posterior P(the HV does not drive if clear after reading the scheme's nudge).
double FailureProbability(const TrustBelief& belief, const AvHvParams& params,
                          const LikelihoodModel& model, const CommittedScheme& scheme) {
  if (!(scheme.nudge > 0.0)) return 0.0;
  const TrustInterval dc = DcTrustInterval(params, model, scheme.nudge);
  if (dc.Empty()) return 1.0;
  // lambda < p*: the DC set is [t, 1].
  return belief.ProbabilityBelow(dc.lo);
}

}  // namespace

LearnedDesign ChooseLearnedDesign(const TrustBelief& belief, const AvHvParams& params,
                                  const LikelihoodModel& model, const ExplorationSchedule& schedule,
                                  double u01) {
  params.Validate();
  schedule.Validate();
  if (!(u01 >= 0.0 && u01 < 1.0)) {
    throw InvalidArgument("uniform draw u = " + NumberText(u01) + " is outside [0, 1)");
  }
  const double p_star = AvHvPStar(params.collision_penalty);
  if (!(params.prior_go < p_star)) {
    throw InvalidArgument("learned trust needs prior_go (lambda) = " + NumberText(params.prior_go) +
                          " below p* = " + NumberText(p_star) +
                          ": otherwise the HV drives if clear without persuasion");
  }
  LearnedDesign out;
  out.risk_level = schedule.Level(belief.Observations());
  out.scheme = CommittedScheme{};  // the fallback: always yield, never nudge
  const double theta_l = belief.LowerBound(out.risk_level);
  const TaebpDesign design = DesignTaebp(params, theta_l, model);
  if (design.persuadable) {
    out.mode = LearnedDesign::Mode::kDesign;
    out.design_trust = theta_l;
    out.probe_probability = 1.0;
    // CommitScheme(kTaEbp, theta_l) without designing twice.
    out.scheme.av_may_go = true;
    out.scheme.nudge = design.s_star;
    out.scheme.a = design.a;
    out.scheme.b = design.b;
    out.failure_probability = FailureProbability(belief, params, model, out.scheme);
    out.encounter_risk = out.failure_probability;
    return out;
  }
  // theta_L is below theta*: only the design for theta* can be tested.
  const double theta_star = design.theta_star;
  const CommittedScheme probe = CommitScheme(Policy::kTaEbp, params, theta_star, model);
  const double fail = FailureProbability(belief, params, model, probe);
  out.design_trust = theta_star;
  if (!schedule.probe || !probe.av_may_go || fail >= 1.0) return out;  // known unpersuadable
  out.probe_probability = std::min(1.0, out.risk_level / fail);
  out.encounter_risk = out.probe_probability * fail;
  if (u01 < out.probe_probability) {
    out.mode = LearnedDesign::Mode::kProbe;
    out.scheme = probe;
    out.failure_probability = fail;
  }
  return out;
}

// ---------------------------------------------------------------------------
// Regret.
// ---------------------------------------------------------------------------
EncounterRegret ExpectedRegret(const CommittedScheme& used, const AvHvParams& params,
                               double theta_true, const LikelihoodModel& model) {
  return ExpectedRegret(used, PredictOutcome(Policy::kTaEbp, params, theta_true, model), params,
                        theta_true, model);
}

EncounterRegret ExpectedRegret(const CommittedScheme& used, const PredictedOutcome& oracle,
                               const AvHvParams& params, double theta_true,
                               const LikelihoodModel& model) {
  const PredictedOutcome mine = PredictOutcome(used, params, theta_true, model);
  EncounterRegret r;
  r.dc_lost = oracle.dc_rate - mine.dc_rate;
  r.collisions = mine.collision_rate - oracle.collision_rate;
  r.regret = r.dc_lost + params.collision_penalty * r.collisions;
  return r;
}

}  // namespace taebp::persuasion
