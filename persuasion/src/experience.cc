// HVs who learn what a signal meant: the learning rule, its fixed points, the
// design against the knife edge and the exact mean-field path
// (experience.h; derivations in docs/influence.md).
#include "taebp/persuasion/experience.h"

#include "internal.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace taebp::persuasion {


bool ExperienceRule::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!(strength > 0.0 && std::isfinite(strength)))
    return fail("strength k = " + NumberText(strength) + " must be > 0 and finite");
  if (!(bin_width > 0.0 && std::isfinite(bin_width)))
    return fail("bin_width = " + NumberText(bin_width) + " must be > 0 and finite");
  if (!(forgetting > 0.0 && forgetting <= 1.0))
    return fail("forgetting rho = " + NumberText(forgetting) +
                " is outside (0, 1] (the weight on the past; 1 = forgets nothing)");
  return true;
}

void ExperienceRule::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

SignalExperience::SignalExperience(double bin_width, double forgetting)
    : width_(bin_width), forgetting_(forgetting) {
  ExperienceRule rule;
  rule.bin_width = bin_width;
  rule.forgetting = forgetting;
  rule.Validate();
}

long SignalExperience::Level(double reading) const {
  if (!(reading >= 0.0 && std::isfinite(reading)))
    throw InvalidArgument("reading = " + NumberText(reading) + " must be >= 0 and finite");
  return static_cast<long>(std::floor(reading / width_));
}

SignalCounts SignalExperience::At(double reading) const {
  const auto it = levels_.find(Level(reading));
  return it == levels_.end() ? SignalCounts{} : it->second;
}

void SignalExperience::Record(double reading, bool av_went) {
  const long level = Level(reading);
  if (forgetting_ < 1.0) {
    for (auto& [l, c] : levels_) {
      c.readings *= forgetting_;
      c.went *= forgetting_;
    }
  }
  SignalCounts& c = levels_[level];
  c.readings += 1.0;
  c.went += av_went ? 1.0 : 0.0;
  ++readings_;
}

double ExperiencedPosterior(double intuitive_go, const SignalCounts& c, double strength) {
  if (!(intuitive_go >= 0.0 && intuitive_go <= 1.0))
    throw InvalidArgument("intuitive posterior q = " + NumberText(intuitive_go) + " is outside [0, 1]");
  if (!(strength > 0.0))
    throw InvalidArgument("strength k = " + NumberText(strength) + " must be > 0");
  if (!(c.readings >= 0 && c.went >= 0 && c.went <= c.readings * (1.0 + 1e-12)))
    throw InvalidArgument("experience counts (n = " + NumberText(c.readings) +
                          ", g = " + NumberText(c.went) + ") need 0 <= g <= n");
  if (std::isinf(strength)) return intuitive_go;
  return std::min(1.0, (strength * intuitive_go + c.went) / (strength + c.readings));
}

double ExperiencedBelief(const CommittedScheme& scheme, const AvHvParams& params, double theta,
                         const LikelihoodModel& model, double s, const SignalCounts& counts,
                         double strength) {
  internal::CheckTrust(theta);
  const double q = HvPosteriorGo(scheme, params, 1.0, model, s);
  return (1.0 - theta) * params.prior_go +
         theta * ExperiencedPosterior(q, counts, strength);
}

namespace {

bool Nudges(const CommittedScheme& s) { return s.nudge > 0.0 && s.Signals(); }

void CheckAOneOrNoSignal(const CommittedScheme& s, const char* who) {
  if (s.Signals() && s.nudge > 0.0 && !(s.a == 0.0 || s.a == 1.0))
    throw InvalidArgument(std::string(who) + ": scheme a = " + NumberText(s.a) +
                          " must be 0 or 1 (the still level's learning is not modelled)");
}

}  // namespace

ExperienceLongRun LongRunUnderExperience(const CommittedScheme& scheme, const AvHvParams& params,
                                         double theta, const LikelihoodModel& model) {
  params.Validate();
  if (Nudges(scheme)) model.PiGo(scheme.nudge);  // the nudge is a signal of this model
  internal::CheckTrust(theta);
  CheckAOneOrNoSignal(scheme, "LongRunUnderExperience");
  const double lambda = params.prior_go;
  const double go = scheme.av_may_go ? 1.0 : 0.0;
  ExperienceLongRun out;
  const bool nudges = Nudges(scheme);
  const double a = nudges ? scheme.a : 0.0, b = nudges ? scheme.b : 0.0;
  const double p_nudge = lambda * a + (1.0 - lambda) * b;
  const double p_still = 1.0 - p_nudge;
  const double p_star = AvHvPStar(params.collision_penalty);
  double dc_nudge = 0.0, dc_still = 0.0;
  if (p_nudge > 0.0) {
    out.went_after_nudge = lambda * a * go / p_nudge;
    out.belief_after_nudge = (1.0 - theta) * lambda + theta * out.went_after_nudge;
    out.knife_edge = std::abs(out.belief_after_nudge - p_star) <= kTieTolerance;
    dc_nudge = out.knife_edge ? 0.5 : (HvDrivesIfClear(params, out.belief_after_nudge) ? 1.0 : 0.0);
    out.dc_after_nudge = dc_nudge;
  }
  if (p_still > 0.0) {
    out.went_after_still = lambda * (1.0 - a) * go / p_still;
    dc_still =
        HvDrivesIfClear(params, (1.0 - theta) * lambda + theta * out.went_after_still) ? 1.0 : 0.0;
  }
  PredictedOutcome& o = out.outcome;
  o.dc_rate = p_nudge * dc_nudge + p_still * dc_still;
  o.nudge_rate = p_nudge;
  o.collision_rate = lambda * go * (a * (1.0 - dc_nudge) + (1.0 - a) * (1.0 - dc_still));
  o.av_first_rate = lambda * go * (a * dc_nudge + (1.0 - a) * dc_still);
  return out;
}

const char* ToString(ExperiencedDesign::Mode mode) {
  switch (mode) {
    case ExperiencedDesign::Mode::kPaper: return "paper";
    case ExperiencedDesign::Mode::kGuard: return "guard";
    case ExperiencedDesign::Mode::kStronger: return "stronger";
    case ExperiencedDesign::Mode::kYield: return "yield";
  }
  return "unknown";
}

namespace {

// The HV's decision at the nudge level from its intuitive posterior q there
// and its counts: the one rule behind DesignForExperience and the mean field.
bool DcAt(const AvHvParams& params, double theta, double q, const SignalCounts& c, double k) {
  return HvDrivesIfClear(params,
                         (1.0 - theta) * params.prior_go + theta * ExperiencedPosterior(q, c, k));
}
// Would a false alarm now (nudge, then Stop) leave the nudge persuasive?
bool FalseAlarmAffordable(const AvHvParams& params, double theta, double q, const SignalCounts& c,
                          double k) {
  return DcAt(params, theta, q, SignalCounts{c.readings + 1, c.went}, k);
}

}  // namespace

ExperiencedDesign DesignForExperience(const CommittedScheme& paper, const AvHvParams& params,
                                      double theta, const LikelihoodModel& model,
                                      double strength,
                                      const std::function<SignalCounts(double)>& counts_at) {
  internal::CheckTrust(theta);
  ExperiencedDesign out;
  if (!paper.av_may_go || !Nudges(paper)) return out;  // the paper's fallback: yield
  const double s = paper.nudge;
  const SignalCounts c = counts_at(s);
  const double q = HvPosteriorGo(paper, params, 1.0, model, s);
  if (DcAt(params, theta, q, c, strength)) {
    out.scheme = paper;
    out.mode = ExperiencedDesign::Mode::kPaper;
    if (!FalseAlarmAffordable(params, theta, q, c, strength)) {
      out.scheme.b = 0.0;
      out.mode = ExperiencedDesign::Mode::kGuard;
    }
    return out;
  }
  CommittedScheme strong;
  strong.av_may_go = true;
  strong.nudge = model.SMax();
  strong.a = 1.0;
  strong.b = 0.0;
  const double q_max = HvPosteriorGo(strong, params, 1.0, model, strong.nudge);
  if (DcAt(params, theta, q_max, counts_at(strong.nudge), strength)) {
    out.scheme = strong;
    out.mode = ExperiencedDesign::Mode::kStronger;
  }
  return out;
}

RobustDesign DesignRobust(const AvHvParams& params, double theta_hat, const LikelihoodModel& model,
                          double margin) {
  params.Validate();
  internal::CheckTrust(theta_hat, "assumed trust theta_hat");
  if (!(margin >= 0.0 && margin < 1.0))
    throw InvalidArgument("robust margin m = " + NumberText(margin) + " is outside [0, 1)");
  RobustDesign out;
  const double lambda = params.prior_go;
  out.belief_target = AvHvPStar(params.collision_penalty) + margin;
  const double s_max = model.SMax();
  out.intuitive_max = HvPosteriorGo(params, 1.0, model, s_max);
  if (theta_hat <= 0.0) return out;  // the nudge moves no belief: yield
  out.pi_target = (out.belief_target - (1.0 - theta_hat) * lambda) / theta_hat;
  if (out.pi_target > 1.0 || out.intuitive_max < out.pi_target) return out;
  out.persuades = true;
  double b = 1.0;
  if (out.pi_target > lambda)
    b = lambda * (1.0 - out.pi_target) / (out.pi_target * (1.0 - lambda));
  out.scheme.av_may_go = true;
  out.scheme.nudge = s_max;
  out.scheme.a = 1.0;
  out.scheme.b = std::clamp(b, 0.0, 1.0);
  return out;
}

double RobustRiskUnderForgetting(const RobustDesign& design, const AvHvParams& params,
                                 double theta, double strength, double forgetting) {
  internal::CheckTrust(theta);
  ExperienceRule rule;
  rule.strength = strength;
  rule.forgetting = forgetting;
  rule.Validate();
  if (!design.persuades || theta <= 0.0) return 0.0;
  const double lambda = params.prior_go;
  const CommittedScheme& sc = design.scheme;
  const double p_nudge = lambda + (1.0 - lambda) * sc.b;
  const double pi = lambda / p_nudge;
  // The full-trust posterior at which this HV's belief meets p*.
  const double pi_c =
      (AvHvPStar(params.collision_penalty) - (1.0 - theta) * lambda) / theta;
  if (forgetting >= 1.0) return pi > pi_c ? 0.0 : (pi < pi_c ? 1.0 : 0.5);
  const double n = p_nudge / (1.0 - forgetting);
  const double var = p_nudge * pi * (1.0 - pi) / (1.0 - forgetting * forgetting);
  const double t = strength * (design.intuitive_max - pi_c) + n * (pi - pi_c);
  if (var <= 0.0) return t >= 0.0 ? 0.0 : 1.0;
  return 0.5 * std::erfc(t / std::sqrt(2.0 * var));
}

ExperiencePath::ExperiencePath(const CommittedScheme& scheme, const AvHvParams& params,
                               double theta, const LikelihoodModel& model, double strength,
                               bool guarded, double forgetting, double bin_width,
                               double design_strength)
    : scheme_(scheme),
      params_(params),
      theta_(theta),
      strength_(strength),
      forgetting_(forgetting),
      design_strength_(design_strength > 0.0 ? design_strength : strength),
      guarded_(guarded),
      model_(&model) {
  params.Validate();
  internal::CheckTrust(theta);
  CheckAOneOrNoSignal(scheme, "ExperiencePath");
  ExperienceRule rule;
  rule.strength = strength;
  rule.forgetting = forgetting;
  rule.Validate();
  s_max_ = model.SMax();
  if (Nudges(scheme)) q_nudge_ = HvPosteriorGo(scheme, params, 1.0, model, scheme.nudge);
  dc_still_ = HvDrivesIfClear(params, HvPosteriorGo(scheme, params, theta, model, 0.0));
  dist_ = {{1.0}};
  lo_ = {0};
  if (scheme.random_magnitude) {
    if (!(bin_width > 0.0))
      throw InvalidArgument("ExperiencePath: a random magnitude needs the learner's bin_width > 0, got " +
                            NumberText(bin_width));
    if (guarded) throw InvalidArgument("ExperiencePath: a random magnitude has no guarded design");
    const double top = scheme.nudge;
    const auto q = [&](double s) { return HvPosteriorGo(scheme, params, 1.0, model, s); };
    for (double lo = 0.0; lo < top; lo += bin_width) {
      Level l;
      l.lo = lo;
      l.hi = std::min(top, lo + bin_width);
      if (l.hi - l.lo <= 1e-12 * top) break;
      l.weight = (l.hi - l.lo) / top;
      l.q_lo = q(l.lo);
      l.q_hi = q(l.hi);
      double prev = l.q_lo;
      for (int i = 1; i <= 64; ++i) {
        const double now = q(l.lo + (l.hi - l.lo) * i / 64.0);
        if (now < prev - 1e-12)
          throw InvalidArgument("ExperiencePath: the intuitive posterior of " + model.Name() +
                                " decreases in s near s = " + NumberText(l.lo + (l.hi - l.lo) * i / 64.0) +
                                " (a random magnitude needs it non-decreasing)");
        prev = now;
      }
      levels_.push_back(l);
    }
  }
}

namespace {

// log of the Binomial(n, p) probability of k (p may be 0 or 1).
double LogBinomial(long k, long n, double p) {
  if (p <= 0.0) return k == 0 ? 0.0 : -std::numeric_limits<double>::infinity();
  if (p >= 1.0) return k == n ? 0.0 : -std::numeric_limits<double>::infinity();
  return std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) +
         k * std::log(p) + (n - k) * std::log1p(-p);
}

}  // namespace

// One level's expected DC share at encounter t (see the class comment).
double ExperiencePath::RandomLevelDc(const Level& level, long t) const {
  const double lambda = params_.prior_go;
  const auto q = [&](double s) { return HvPosteriorGo(scheme_, params_, 1.0, *model_, s); };
  // The share of the level's magnitudes read as DC with counts c (DcAt is
  // non-decreasing in q, q in s).
  const auto share = [&](const SignalCounts& c) {
    if (DcAt(params_, theta_, level.q_lo, c, strength_)) return 1.0;
    if (!DcAt(params_, theta_, level.q_hi, c, strength_)) return 0.0;
    return internal::ShareWhere([&](double s) { return DcAt(params_, theta_, q(s), c, strength_); },
                                level.lo, level.hi, 1);
  };
  if (forgetting_ < 1.0) {
    if (t == 0) return share(SignalCounts{0.0, 0.0});
    if (theta_ <= 0.0) return HvDrivesIfClear(params_, lambda) ? 1.0 : 0.0;
    const double pi_c = (AvHvPStar(params_.collision_penalty) - (1.0 - theta_) * lambda) / theta_;
    const double rt = std::pow(forgetting_, static_cast<double>(t));
    const double mean_n = level.weight * (1.0 - rt) / (1.0 - forgetting_);
    const double var = level.weight * lambda * (1.0 - lambda) * (1.0 - rt * rt) /
                       (1.0 - forgetting_ * forgetting_);
    constexpr int kPoints = 64;
    double sum = 0.0;
    for (int j = 0; j < kPoints; ++j) {
      const double s = level.lo + (level.hi - level.lo) * (j + 0.5) / kPoints;
      const double margin = strength_ * (q(s) - pi_c) + mean_n * (lambda - pi_c);
      sum += var <= 0.0 ? (margin >= -kTieTolerance ? 1.0 : 0.0)
                        : 0.5 * std::erfc(-margin / std::sqrt(2.0 * var));
    }
    return sum / kPoints;
  }
  // Binomial(t, w) and Binomial(n, lambda) within 10 standard deviations of
  // their means (the mass outside is below 1e-20).
  const auto window = [](long n, double p) {
    const double mean = n * p, sd = std::sqrt(n * p * (1.0 - p));
    return std::pair<long, long>{std::max(0L, static_cast<long>(std::floor(mean - 10.0 * sd)) - 1),
                                 std::min(n, static_cast<long>(std::ceil(mean + 10.0 * sd)) + 1)};
  };
  double dc = 0.0;
  const auto [n_lo, n_hi] = window(t, level.weight);
  for (long n = n_lo; n <= n_hi; ++n) {
    const double pn = std::exp(LogBinomial(n, t, level.weight));
    const auto [g_lo, g_hi] = window(n, lambda);
    double below = 0.0;  // P(g' < g | n)
    for (long g = g_lo; g <= g_hi; ++g) {
      const double pg = std::exp(LogBinomial(g, n, lambda));
      const double sh = share(SignalCounts{static_cast<double>(n), static_cast<double>(g)});
      if (sh >= 1.0) {
        dc += pn * std::max(0.0, 1.0 - below);  // DC is non-decreasing in g
        break;
      }
      dc += pn * pg * sh;
      below += pg;
    }
  }
  return dc;
}

PredictedOutcome ExperiencePath::RandomAt(long t) const {
  double dc = 0.0;
  for (const Level& l : levels_) dc += l.weight * RandomLevelDc(l, t);
  const double lambda = params_.prior_go, go = scheme_.av_may_go ? 1.0 : 0.0;
  PredictedOutcome o;
  o.dc_rate = dc;
  o.nudge_rate = 1.0;
  o.collision_rate = lambda * go * (1.0 - dc);
  o.av_first_rate = lambda * go * dc;
  return o;
}

PredictedOutcome ExperiencePath::At(long t) {
  if (t < 0) throw InvalidArgument("encounter index t = " + std::to_string(t) + " must be >= 0");
  if (scheme_.random_magnitude) {
    auto it = random_.find(t);
    if (it == random_.end()) it = random_.emplace(t, RandomAt(t)).first;
    return it->second;
  }
  if (forgetting_ < 1.0) return Forgetting(t);
  while (static_cast<long>(path_.size()) <= t) Step();
  return path_[static_cast<std::size_t>(t)];
}

PredictedOutcome ExperiencePath::Forgetting(long t) const {
  const double lambda = params_.prior_go;
  const bool nudges = Nudges(scheme_);
  const double go = scheme_.av_may_go ? 1.0 : 0.0;
  const double a = nudges ? scheme_.a : 0.0, b = nudges ? scheme_.b : 0.0;
  const double p_nudge = lambda * a + (1.0 - lambda) * b;
  const double dc_still = dc_still_ ? 1.0 : 0.0;
  double dc_nudge = 0.0;
  if (p_nudge > 0.0) {
    if (theta_ <= 0.0) {
      dc_nudge = HvDrivesIfClear(params_, lambda) ? 1.0 : 0.0;
    } else {
      const double pi = lambda * a * go / p_nudge;
      const double pi_c = (AvHvPStar(params_.collision_penalty) - (1.0 - theta_) * lambda) / theta_;
      const double rt = std::pow(forgetting_, static_cast<double>(t));
      const double mean_n = p_nudge * (1.0 - rt) / (1.0 - forgetting_);
      const double var =
          p_nudge * pi * (1.0 - pi) * (1.0 - rt * rt) / (1.0 - forgetting_ * forgetting_);
      const double margin = strength_ * (q_nudge_ - pi_c) + mean_n * (pi - pi_c);
      if (var <= 0.0)
        dc_nudge = margin >= -kTieTolerance ? 1.0 : 0.0;
      else
        dc_nudge = 0.5 * std::erfc(-margin / std::sqrt(2.0 * var));
    }
  }
  PredictedOutcome o;
  o.dc_rate = p_nudge * dc_nudge + (1.0 - p_nudge) * dc_still;
  o.nudge_rate = p_nudge;
  o.collision_rate = lambda * go * (a * (1.0 - dc_nudge) + (1.0 - a) * (1.0 - dc_still));
  o.av_first_rate = lambda * go * (a * dc_nudge + (1.0 - a) * dc_still);
  return o;
}

namespace {

// The range of g each new row can hold: its own (no reading) and the row
// below's shifted by 0 or 1 (a nudge reading, Stop or Go): rows of zeros.
void RowRanges(const std::vector<std::vector<double>>& dist, const std::vector<long>& lo_of,
               std::vector<std::vector<double>>* next, std::vector<long>* next_lo) {
  const std::size_t rows = dist.size();
  for (std::size_t n = 0; n <= rows; ++n) {
    long lo = 0, hi = -1;
    bool any = false;
    auto take = [&](long l, long h) {
      if (h < l) return;
      lo = any ? std::min(lo, l) : l;
      hi = any ? std::max(hi, h) : h;
      any = true;
    };
    if (n < rows && !dist[n].empty())
      take(lo_of[n], lo_of[n] + static_cast<long>(dist[n].size()) - 1);
    if (n > 0 && !dist[n - 1].empty())
      take(lo_of[n - 1], lo_of[n - 1] + static_cast<long>(dist[n - 1].size()));
    if (any) {
      (*next_lo)[n] = lo;
      (*next)[n].assign(static_cast<std::size_t>(hi - lo + 1), 0.0);
    }
  }
}

// Drops the negligible tails of each row (and empty rows at the end).
void DropTails(std::vector<std::vector<double>>* rows, std::vector<long>* rows_lo) {
  std::vector<std::vector<double>>& next = *rows;
  std::vector<long>& next_lo = *rows_lo;
  constexpr double kDrop = 1e-15;
  for (std::size_t n = 0; n < next.size(); ++n) {
    std::vector<double>& row = next[n];
    std::size_t first = 0, last = row.size();
    while (first < last && row[first] < kDrop) ++first;
    while (last > first && row[last - 1] < kDrop) --last;
    if (first == last) {
      row.clear();
      continue;
    }
    next_lo[n] += static_cast<long>(first);
    row = std::vector<double>(row.begin() + static_cast<long>(first),
                              row.begin() + static_cast<long>(last));
  }
  while (!next.empty() && next.back().empty()) {
    next.pop_back();
    next_lo.pop_back();
  }
}

}  // namespace

void ExperiencePath::Step() {
  const double lambda = params_.prior_go;
  const bool nudges = Nudges(scheme_);
  const std::size_t rows = dist_.size();
  std::vector<std::vector<double>> next(rows + 1);
  std::vector<long> next_lo(rows + 1, 0);
  RowRanges(dist_, lo_, &next, &next_lo);
  auto add = [&](std::size_t n, long g, double p) {
    next[n][static_cast<std::size_t>(g - next_lo[n])] += p;
  };
  PredictedOutcome o;
  const double dc_still = dc_still_ ? 1.0 : 0.0;
  for (std::size_t n = 0; n < rows; ++n) {
    for (std::size_t i = 0; i < dist_[n].size(); ++i) {
      const double p = dist_[n][i];
      if (p == 0.0) continue;
      const long g = lo_[n] + static_cast<long>(i);
      const SignalCounts c{static_cast<double>(n), static_cast<double>(g)};
      CommittedScheme sc = scheme_;
      const bool dc_now = nudges && DcAt(params_, theta_, q_nudge_, c, strength_);
      // What the guard predicts, with the k it assumes.
      const bool dc_designed = nudges && DcAt(params_, theta_, q_nudge_, c, design_strength_);
      bool yield = false;
      if (guarded_ && nudges && sc.av_may_go) {
        // DesignForExperience with these counts at s* and none elsewhere:
        // not persuaded now -> s_max or yield (s_max's level is not tracked;
        // the invariant keeps both unused from n = 0, tested; counted as a
        // yield if they ever happen); else b unless a false alarm breaks it.
        if (!dc_designed) {
          yield = true;
        } else if (!FalseAlarmAffordable(params_, theta_, q_nudge_, c, design_strength_)) {
          sc.b = 0.0;
        }
      }
      if (yield || !nudges) {
        // No nudge: the still response; the AV goes on Go iff it may.
        const double go = (!yield && sc.av_may_go) ? lambda : 0.0;
        o.dc_rate += p * dc_still;
        o.collision_rate += p * go * (1.0 - dc_still);
        o.av_first_rate += p * go * dc_still;
        add(n, g, p);
        continue;
      }
      const double dc_nudge = dc_now ? 1.0 : 0.0;
      const double may_go = sc.av_may_go ? 1.0 : 0.0;
      const double go_nudge = lambda * sc.a, go_still = lambda * (1.0 - sc.a);
      const double stop_nudge = (1.0 - lambda) * sc.b, stop_still = (1.0 - lambda) * (1.0 - sc.b);
      o.dc_rate += p * ((go_nudge + stop_nudge) * dc_nudge + (go_still + stop_still) * dc_still);
      o.nudge_rate += p * (go_nudge + stop_nudge);
      o.collision_rate +=
          p * may_go * (go_nudge * (1.0 - dc_nudge) + go_still * (1.0 - dc_still));
      o.av_first_rate += p * may_go * (go_nudge * dc_nudge + go_still * dc_still);
      add(n + 1, g + (sc.av_may_go ? 1 : 0), p * go_nudge);
      add(n + 1, g, p * stop_nudge);
      add(n, g, p * (go_still + stop_still));
    }
  }
  DropTails(&next, &next_lo);
  dist_ = std::move(next);
  lo_ = std::move(next_lo);
  path_.push_back(o);
}

}  // namespace taebp::persuasion
