// Beta trust dynamics (Guo & Yang 2021) meeting TA-EBP: the per-encounter
// update and the long-run trust under each policy.
#include "taebp/persuasion/trust_dynamics.h"

#include "internal.h"

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace taebp::persuasion {


namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

const char* ToString(EncounterOutcome outcome) {
  switch (outcome) {
    case EncounterOutcome::kNudgeGo:
      return "nudge_go";
    case EncounterOutcome::kNudgeStop:
      return "nudge_stop";
    case EncounterOutcome::kStillStop:
      return "still_stop";
    case EncounterOutcome::kStillGo:
      return "still_go";
    case EncounterOutcome::kCollision:
      return "collision";
    case EncounterOutcome::kNearMiss:
      return "near_miss";
  }
  return "unknown";
}

EncounterOutcome ParseEncounterOutcome(const std::string& name) {
  for (EncounterOutcome outcome : kAllEncounterOutcomes) {
    if (name == ToString(outcome)) return outcome;
  }
  throw InvalidArgument("encounter outcome '" + name +
                        "' is unknown (expected nudge_go, nudge_stop, still_stop, still_go, "
                        "collision or near_miss)");
}

EncounterOutcome ClassifyEncounter(bool nudged, bool av_went, bool collision, bool near_miss) {
  if (collision) return EncounterOutcome::kCollision;
  if (near_miss) return EncounterOutcome::kNearMiss;
  if (nudged) return av_went ? EncounterOutcome::kNudgeGo : EncounterOutcome::kNudgeStop;
  return av_went ? EncounterOutcome::kStillGo : EncounterOutcome::kStillStop;
}

// ---------------------------------------------------------------------------
// The q mapping and the update rule.
// ---------------------------------------------------------------------------
double OutcomeQuality::Of(EncounterOutcome outcome) const {
  switch (outcome) {
    case EncounterOutcome::kNudgeGo:
      return nudge_go;
    case EncounterOutcome::kNudgeStop:
      return nudge_stop;
    case EncounterOutcome::kStillStop:
      return still_stop;
    case EncounterOutcome::kStillGo:
      return still_go;
    case EncounterOutcome::kCollision:
      return collision;
    case EncounterOutcome::kNearMiss:
      return near_miss;
  }
  throw InvalidArgument("encounter outcome = " + std::to_string(static_cast<int>(outcome)) +
                        " is unknown");
}

bool OutcomeQuality::IsValid(std::string* why) const {
  for (EncounterOutcome outcome : kAllEncounterOutcomes) {
    const double q = Of(outcome);
    if (!(q >= 0.0 && q <= 1.0)) {
      if (why != nullptr) {
        *why = std::string("quality.") + ToString(outcome) + " = " + NumberText(q) + " is outside [0, 1]";
      }
      return false;
    }
  }
  return true;
}

void OutcomeQuality::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

bool TrustUpdateRule::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(success_weight >= 0.0 && success_weight <= kMaxWeight)) {
    return fail("success_weight w_s = " + NumberText(success_weight) + " is outside [0, " + NumberText(kMaxWeight) +
                "]");
  }
  if (!(failure_weight >= 0.0 && failure_weight <= kMaxWeight)) {
    return fail("failure_weight w_f = " + NumberText(failure_weight) + " is outside [0, " + NumberText(kMaxWeight) +
                "]");
  }
  if (!(forgetting >= 0.0 && forgetting <= 1.0)) {
    return fail("forgetting rho = " + NumberText(forgetting) + " is outside [0, 1]");
  }
  return quality.IsValid(why);
}

void TrustUpdateRule::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

// ---------------------------------------------------------------------------
// BetaTrust
// ---------------------------------------------------------------------------
BetaTrust::BetaTrust(double alpha0, double beta0)
    : alpha0_(alpha0), beta0_(beta0), alpha_(alpha0), beta_(beta0) {
  if (!(alpha0 > 0.0 && std::isfinite(alpha0))) {
    throw InvalidArgument("trust alpha0 = " + NumberText(alpha0) + " must be > 0 and finite");
  }
  if (!(beta0 > 0.0 && std::isfinite(beta0))) {
    throw InvalidArgument("trust beta0 = " + NumberText(beta0) + " must be > 0 and finite");
  }
}

BetaTrust BetaTrust::FromMean(double mean, double strength) {
  if (!(mean > 0.0 && mean < 1.0)) {
    throw InvalidArgument("initial trust mean = " + NumberText(mean) + " is outside (0, 1)");
  }
  if (!(strength > 0.0 && std::isfinite(strength))) {
    throw InvalidArgument("trust strength alpha0 + beta0 = " + NumberText(strength) +
                          " must be > 0 and finite");
  }
  return BetaTrust(mean * strength, (1.0 - mean) * strength);
}

void BetaTrust::Update(double q, const TrustUpdateRule& rule) {
  rule.Validate();
  if (!(q >= 0.0 && q <= 1.0)) {
    throw InvalidArgument("encounter quality q = " + NumberText(q) + " is outside [0, 1]");
  }
  const double keep = 1.0 - rule.forgetting;
  // alpha0 + keep * 0 is alpha0 exactly, so an untouched state stays put.
  alpha_ = alpha0_ + keep * (alpha_ - alpha0_) + rule.success_weight * q;
  beta_ = beta0_ + keep * (beta_ - beta0_) + rule.failure_weight * (1.0 - q);
}

void BetaTrust::Update(EncounterOutcome outcome, const TrustUpdateRule& rule) {
  Update(rule.quality.Of(outcome), rule);
}

// ---------------------------------------------------------------------------
// Expected behaviour of one encounter.
// ---------------------------------------------------------------------------
CommittedScheme SchemeFor(const DesignRule& rule, const AvHvParams& params, double theta,
                          const LikelihoodModel& model) {
  internal::CheckTrust(theta);
  if (rule.assumed_trust) internal::CheckTrust(*rule.assumed_trust, "assumed trust theta_hat");
  return CommitScheme(rule.policy, params, rule.assumed_trust.value_or(theta), model);
}

std::array<double, kEncounterOutcomeCount> OutcomeProbabilities(const CommittedScheme& scheme,
                                                                const AvHvParams& params,
                                                                double theta_true,
                                                                const LikelihoodModel& model) {
  params.Validate();
  internal::CheckTrust(theta_true, "trust theta_true");
  auto check_probability = [](double x, const char* name) {
    if (!(x >= 0.0 && x <= 1.0)) {
      throw InvalidArgument(std::string(name) + " = " + NumberText(x) + " is outside [0, 1]");
    }
  };
  check_probability(scheme.a, "scheme a (P(nudge | Go))");
  check_probability(scheme.b, "scheme b (P(nudge | Stop))");
  // As PredictOutcome: the HV reads the nudge exactly; a nudge of 0 is standing
  // still, which tells it nothing when the scheme never signals (it keeps its
  // prior: HvPosteriorGo(scheme, ...)).
  const bool signals = scheme.nudge > 0.0;
  const bool dc_nudge =
      HvDrivesIfClear(params, HvPosteriorGo(scheme, params, theta_true, model, scheme.nudge));
  const bool dc_still =
      HvDrivesIfClear(params, HvPosteriorGo(scheme, params, theta_true, model, 0.0));
  std::array<double, kEncounterOutcomeCount> p{};
  const double lambda = params.prior_go;
  for (const bool go : {true, false}) {
    const double p_intent = go ? lambda : 1.0 - lambda;
    const double p_signal = go ? scheme.a : scheme.b;
    const bool av_went = go && scheme.av_may_go;
    for (const bool signal : {true, false}) {
      const double p_branch = p_intent * (signal ? p_signal : 1.0 - p_signal);
      const bool dc = signal ? dc_nudge : dc_still;
      const EncounterOutcome outcome =
          ClassifyEncounter(signal && signals, av_went, av_went && !dc, false);
      p[static_cast<int>(outcome)] += p_branch;
    }
  }
  return p;
}

double ExpectedQuality(const DesignRule& rule, const AvHvParams& params, double theta,
                       const LikelihoodModel& model, const OutcomeQuality& quality) {
  quality.Validate();
  const auto p = OutcomeProbabilities(SchemeFor(rule, params, theta, model), params, theta, model);
  double q = 0.0;
  for (EncounterOutcome outcome : kAllEncounterOutcomes) {
    q += p[static_cast<int>(outcome)] * quality.Of(outcome);
  }
  return q;
}

ExpectedUpdate ExpectedStep(const BetaTrust& state, const DesignRule& rule,
                            const AvHvParams& params, const LikelihoodModel& model,
                            const TrustUpdateRule& update) {
  update.Validate();
  const double theta = state.Mean();
  const auto p = OutcomeProbabilities(SchemeFor(rule, params, theta, model), params, theta, model);
  ExpectedUpdate result;
  double mean_after = 0.0;
  for (EncounterOutcome outcome : kAllEncounterOutcomes) {
    const double pk = p[static_cast<int>(outcome)];
    if (pk == 0.0) continue;
    BetaTrust next = state;
    next.Update(outcome, update);
    result.quality += pk * update.quality.Of(outcome);
    mean_after += pk * next.Mean();
  }
  const double rho = update.forgetting;
  result.alpha =
      rho * (state.InitialAlpha() - state.Alpha()) + update.success_weight * result.quality;
  result.beta =
      rho * (state.InitialBeta() - state.Beta()) + update.failure_weight * (1.0 - result.quality);
  result.mean = mean_after - theta;
  return result;
}

namespace {

double DriftFromQuality(double theta, double q, const TrustUpdateRule& update, double alpha0,
                        double beta0) {
  const double rho = update.forgetting;
  return rho * (alpha0 * (1.0 - theta) - beta0 * theta) +
         update.success_weight * q * (1.0 - theta) - update.failure_weight * (1.0 - q) * theta;
}

void CheckInitial(double alpha0, double beta0) { BetaTrust check(alpha0, beta0); }

}  // namespace

double MeanDrift(double theta, const DesignRule& rule, const AvHvParams& params,
                 const LikelihoodModel& model, const TrustUpdateRule& update, double alpha0,
                 double beta0) {
  update.Validate();
  CheckInitial(alpha0, beta0);
  const double q = ExpectedQuality(rule, params, theta, model, update.quality);
  return DriftFromQuality(theta, q, update, alpha0, beta0);
}

double ConstantQualityEquilibrium(double quality, const TrustUpdateRule& update, double alpha0,
                                  double beta0) {
  update.Validate();
  CheckInitial(alpha0, beta0);
  if (!(quality >= 0.0 && quality <= 1.0)) {
    throw InvalidArgument("expected quality Q = " + NumberText(quality) + " is outside [0, 1]");
  }
  const double rho = update.forgetting;
  const double numerator = rho * alpha0 + update.success_weight * quality;
  const double denominator = rho * (alpha0 + beta0) + update.success_weight * quality +
                             update.failure_weight * (1.0 - quality);
  if (denominator == 0.0) return kNaN;
  return numerator / denominator;
}

std::vector<double> TaebpEquilibria(const AvHvParams& params, const TrustUpdateRule& update,
                                    double alpha0, double beta0, double lo, double hi) {
  params.Validate();
  update.Validate();
  CheckInitial(alpha0, beta0);
  const double lambda = params.prior_go;
  const double p_star = AvHvPStar(params.collision_penalty);
  if (!(lambda < p_star)) {
    throw InvalidArgument("prior_go (lambda) = " + NumberText(lambda) + " is not below p* = " +
                          NumberText(p_star) + ": the HV drives if clear without persuasion");
  }
  const OutcomeQuality& q = update.quality;
  const double d = p_star - lambda;
  // Q (D + lambda theta) = p0 + p1 theta.
  const double a_const = lambda * q.nudge_go + (1.0 - lambda) * q.still_stop;
  const double b_coef = q.nudge_stop - q.still_stop;
  const double p0 = a_const * d - b_coef * lambda * d;
  const double p1 = a_const * lambda + b_coef * lambda * (1.0 - lambda);
  // G = e0 - e1 theta + Q (w0 + w1 theta).
  const double rho = update.forgetting;
  const double e0 = rho * alpha0;
  const double e1 = rho * (alpha0 + beta0) + update.failure_weight;
  const double w0 = update.success_weight;
  const double w1 = update.failure_weight - update.success_weight;
  // G (D + lambda theta) = c2 theta^2 + c1 theta + c0.
  const double c2 = -e1 * lambda + w1 * p1;
  const double c1 = e0 * lambda - e1 * d + w0 * p1 + w1 * p0;
  const double c0 = e0 * d + w0 * p0;
  std::vector<double> roots;
  const double scale = std::max({std::abs(c2), std::abs(c1), std::abs(c0)});
  if (scale == 0.0) return roots;  // G vanishes identically (static trust)
  if (std::abs(c2) <= 1e-14 * scale) {
    if (c1 != 0.0) roots.push_back(-c0 / c1);
  } else {
    const double disc = c1 * c1 - 4.0 * c2 * c0;
    if (disc >= 0.0) {
      // Stable form: q = -(c1 + sign(c1) sqrt(disc)) / 2, roots q / c2 and c0 / q.
      const double sq = std::sqrt(disc);
      const double qq = -0.5 * (c1 + (c1 >= 0.0 ? sq : -sq));
      if (qq != 0.0) {
        roots.push_back(qq / c2);
        roots.push_back(c0 / qq);
      } else {
        roots.push_back(0.0);  // c1 = c0 = 0
      }
    }
  }
  std::vector<double> inside;
  for (double r : roots) {
    if (r >= lo && r <= hi) inside.push_back(r);
  }
  std::sort(inside.begin(), inside.end());
  inside.erase(std::unique(inside.begin(), inside.end()), inside.end());
  return inside;
}

// ---------------------------------------------------------------------------
// FindLongRunTrust: pieces of continuity of Q, sign changes of G.
// ---------------------------------------------------------------------------
const char* ToString(TrustEquilibrium::Kind kind) {
  switch (kind) {
    case TrustEquilibrium::Kind::kRoot:
      return "root";
    case TrustEquilibrium::Kind::kJump:
      return "jump";
    case TrustEquilibrium::Kind::kBoundary:
      return "boundary";
  }
  return "unknown";
}

std::vector<double> LongRunTrust::Attractors() const {
  std::vector<double> out;
  for (const TrustEquilibrium& e : equilibria) {
    if (e.stable) out.push_back(e.theta);
  }
  return out;
}

namespace {

// The discrete shape of the encounter at trust theta: Q is continuous in theta
// wherever this does not change.
struct Shape {
  bool av_may_go, signals, dc_nudge, dc_still;
  bool operator==(const Shape& o) const {
    return av_may_go == o.av_may_go && signals == o.signals && dc_nudge == o.dc_nudge &&
           dc_still == o.dc_still;
  }
  bool operator!=(const Shape& o) const { return !(*this == o); }
};

class DriftEvaluator {
 public:
  DriftEvaluator(const DesignRule& rule, const AvHvParams& params, const LikelihoodModel& model,
                 const TrustUpdateRule& update, double alpha0, double beta0)
      : rule_(rule), params_(params), model_(model), update_(update), a0_(alpha0), b0_(beta0) {}

  Shape ShapeAt(double theta) const {
    const CommittedScheme s = SchemeFor(rule_, params_, theta, model_);
    return {s.av_may_go, s.nudge > 0.0,
            HvDrivesIfClear(params_, HvPosteriorGo(s, params_, theta, model_, s.nudge)),
            HvDrivesIfClear(params_, HvPosteriorGo(s, params_, theta, model_, 0.0))};
  }
  double G(double theta) const {
    const double q = ExpectedQuality(rule_, params_, theta, model_, update_.quality);
    return DriftFromQuality(theta, q, update_, a0_, b0_);
  }

 private:
  const DesignRule& rule_;
  const AvHvParams& params_;
  const LikelihoodModel& model_;
  const TrustUpdateRule& update_;
  double a0_, b0_;
};

int Sign(double x) { return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0); }

// A piece [start, end] of [0, 1] on which the drift's shape is constant.
struct Piece {
  double start, end;
};

// The pieces on which the shape is constant: scanned on `grid` points, each
// switch bisected to adjacent doubles lo < hi (hi appended to `breakpoints`).
std::vector<Piece> ShapePieces(const DriftEvaluator& eval, int grid,
                               std::vector<double>* breakpoints) {
  std::vector<Piece> pieces;
  double start = 0.0;
  double known = 0.0;  // the last theta known to have `shape`
  Shape shape = eval.ShapeAt(0.0);
  for (int i = 1; i <= grid;) {
    const double x = static_cast<double>(i) / grid;
    if (eval.ShapeAt(x) == shape) {
      known = x;
      ++i;
      continue;
    }
    // The first switch after `known`: bisect to adjacent doubles lo < hi.
    double lo = known, hi = x;
    for (;;) {
      const double mid = lo + 0.5 * (hi - lo);
      if (!(mid > lo && mid < hi)) break;
      (eval.ShapeAt(mid) == shape ? lo : hi) = mid;
    }
    pieces.push_back({start, lo});
    breakpoints->push_back(hi);
    start = known = hi;
    shape = eval.ShapeAt(hi);  // x is tested again against the new shape
  }
  pieces.push_back({start, 1.0});
  return pieces;
}

}  // namespace

LongRunTrust FindLongRunTrust(const DesignRule& rule, const AvHvParams& params,
                              const LikelihoodModel& model, const TrustUpdateRule& update,
                              double alpha0, double beta0, int grid) {
  params.Validate();
  update.Validate();
  CheckInitial(alpha0, beta0);
  if (grid < 2) throw InvalidArgument("grid = " + std::to_string(grid) + " must be >= 2");
  LongRunTrust result;
  if (update.IsStatic()) return result;  // G = 0 everywhere: trust never moves
  const DriftEvaluator eval(rule, params, model, update, alpha0, beta0);

  // 1. Pieces [start, end] on which the shape is constant.
  const std::vector<Piece> pieces = ShapePieces(eval, grid, &result.breakpoints);

  // 2. Sign changes of G inside each piece (G is continuous there).
  auto add = [&result](double theta, TrustEquilibrium::Kind kind, bool stable) {
    result.equilibria.push_back({theta, kind, stable});
  };
  auto tolerance = [](double a, double b) { return std::abs(b - a) <= 1e-14; };
  std::vector<std::pair<double, double>> piece_ends;  // G just inside each end
  for (const Piece& piece : pieces) {
    std::vector<double> xs{piece.start};
    const int first = static_cast<int>(std::floor(piece.start * grid)) + 1;
    for (int i = first; static_cast<double>(i) / grid < piece.end; ++i) {
      xs.push_back(static_cast<double>(i) / grid);
    }
    if (piece.end > piece.start) xs.push_back(piece.end);
    std::vector<double> gs;
    gs.reserve(xs.size());
    for (double x : xs) gs.push_back(eval.G(x));
    piece_ends.push_back({gs.front(), gs.back()});
    for (std::size_t k = 0; k < xs.size(); ++k) {
      const int s = Sign(gs[k]);
      if (s == 0) {
        // An exact zero at a sample: its kind and stability from the neighbours.
        const bool interior = xs[k] > 0.0 && xs[k] < 1.0;
        const int left = k > 0 ? Sign(gs[k - 1]) : 0;
        const int right = k + 1 < xs.size() ? Sign(gs[k + 1]) : 0;
        const bool stable =
            (k == 0 || left > 0) && (k + 1 == xs.size() || right < 0) && (left != 0 || right != 0);
        add(xs[k], interior ? TrustEquilibrium::Kind::kRoot : TrustEquilibrium::Kind::kBoundary,
            stable);
        continue;
      }
      if (k + 1 < xs.size() && s * Sign(gs[k + 1]) < 0) {
        auto f = [&eval](double x) { return eval.G(x); };
        std::uintmax_t max_iter = 200;
        const auto bracket = boost::math::tools::toms748_solve(f, xs[k], xs[k + 1], gs[k],
                                                               gs[k + 1], tolerance, max_iter);
        add(0.5 * (bracket.first + bracket.second), TrustEquilibrium::Kind::kRoot, s > 0);
      }
    }
  }

  // 3. Sign changes across the jumps of Q.
  for (std::size_t j = 0; j + 1 < pieces.size(); ++j) {
    const int left = Sign(piece_ends[j].second);
    const int right = Sign(piece_ends[j + 1].first);
    if (left * right < 0) {
      add(result.breakpoints[j], TrustEquilibrium::Kind::kJump, left > 0);
    }
  }
  std::sort(result.equilibria.begin(), result.equilibria.end(),
            [](const TrustEquilibrium& a, const TrustEquilibrium& b) { return a.theta < b.theta; });
  return result;
}

}  // namespace taebp::persuasion
