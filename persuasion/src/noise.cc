// Perception noise on the HV's reading of the nudge, exact persuasion
// probabilities, and the noise-aware TA-EBP design.
#include "taebp/persuasion/noise.h"

#include "internal.h"
#include "taebp/persuasion/hv_response.h"

#include <boost/math/distributions/normal.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace taebp::persuasion {


namespace {

using DoublePrecision = boost::math::policies::policy<boost::math::policies::promote_double<false>>;

boost::math::normal_distribution<double, DoublePrecision> Normal(double sigma) {
  return boost::math::normal_distribution<double, DoublePrecision>(0.0, sigma);
}

}  // namespace

const char* ToString(PerceptionNoise::Kind kind) {
  switch (kind) {
    case PerceptionNoise::Kind::kNone:
      return "none";
    case PerceptionNoise::Kind::kGaussian:
      return "gaussian";
    case PerceptionNoise::Kind::kUniform:
      return "uniform";
  }
  return "unknown";
}

PerceptionNoise::Kind ParseNoiseKind(const std::string& name) {
  for (PerceptionNoise::Kind kind : {PerceptionNoise::Kind::kNone, PerceptionNoise::Kind::kGaussian,
                                     PerceptionNoise::Kind::kUniform}) {
    if (name == ToString(kind)) return kind;
  }
  throw InvalidArgument("noise kind '" + name +
                        "' is unknown (expected none, gaussian or uniform)");
}

bool PerceptionNoise::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!std::isfinite(bias)) return fail("noise.bias = " + NumberText(bias) + " must be finite");
  if (kind != Kind::kNone && !(scale > 0.0 && std::isfinite(scale))) {
    return fail(std::string("noise.scale = ") + NumberText(scale) + " must be > 0 and finite for " +
                ToString(kind) + " noise");
  }
  return true;
}

void PerceptionNoise::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

double PerceptionNoise::Cdf(double e) const {
  switch (kind) {
    case Kind::kNone:
      return e >= 0.0 ? 1.0 : 0.0;
    case Kind::kGaussian:
      if (std::isinf(e)) return e > 0 ? 1.0 : 0.0;
      return boost::math::cdf(Normal(scale), e);
    case Kind::kUniform:
      return std::clamp((e + scale) / (2.0 * scale), 0.0, 1.0);
  }
  return 0.0;
}

double PerceptionNoise::Quantile(double p) const {
  if (!(p > 0.0 && p < 1.0)) {
    throw InvalidArgument("noise quantile level p = " + NumberText(p) + " is outside (0, 1)");
  }
  switch (kind) {
    case Kind::kNone:
      return 0.0;
    case Kind::kGaussian:
      return boost::math::quantile(Normal(scale), p);
    case Kind::kUniform:
      return scale * (2.0 * p - 1.0);
  }
  return 0.0;
}

double PerceptionNoise::Density(double e) const {
  switch (kind) {
    case Kind::kNone:
      return 0.0;
    case Kind::kGaussian:
      return boost::math::pdf(Normal(scale), e);
    case Kind::kUniform:
      return std::abs(e) <= scale ? 0.5 / scale : 0.0;
  }
  return 0.0;
}

double NoisyReading(const PerceptionNoise& noise, double observed, double s_max, double u01) {
  noise.Validate();
  if (!(u01 >= 0.0 && u01 < 1.0)) {
    throw InvalidArgument("uniform draw u = " + NumberText(u01) + " is outside [0, 1)");
  }
  if (!std::isfinite(observed)) {
    throw InvalidArgument("observed displacement = " + NumberText(observed) + " is not finite");
  }
  // u + 2^-54 keeps the level off 0; above 1/2 it may round up to 1, so cap it.
  const double eps = noise.Quantile(std::min(u01 + 0x1.0p-54, std::nextafter(1.0, 0.0)));
  return std::clamp(observed + noise.bias + eps, 0.0, s_max);
}

double PersuasionProbability(const PerceptionNoise& noise, const AvHvParams& params, double theta,
                             const LikelihoodModel& model, double s) {
  noise.Validate();
  params.Validate();
  internal::CheckTrust(theta);
  if (!(s >= 0.0 && s <= model.SMax())) {
    throw InvalidArgument("displacement s = " + NumberText(s) + " is outside [0, " + NumberText(model.SMax()) +
                          "]");
  }
  if (noise.kind == PerceptionNoise::Kind::kNone) {
    const double reading = std::clamp(s + noise.bias, 0.0, model.SMax());
    return HvDrivesIfClear(params, HvPosteriorGo(params, theta, model, reading)) ? 1.0 : 0.0;
  }
  const std::optional<double> threshold = MinReadingForDc(params, model, theta);
  if (!threshold) return 0.0;         // not even s_max persuades
  if (*threshold <= 0.0) return 1.0;  // every reading does
  // P(s + bias + eps >= r*) = 1 - F(r* - s - bias); the clamp changes no decision.
  return 1.0 - noise.Cdf(*threshold - s - noise.bias);
}

PredictedOutcome PredictOutcomeUnderNoise(const CommittedScheme& scheme, const AvHvParams& params,
                                          double theta_true, const LikelihoodModel& model,
                                          const PerceptionNoise& noise) {
  // The structure of PredictOutcome (outcomes.cc) with the 0/1 responses
  // replaced by their probabilities over the noise.
  params.Validate();
  internal::CheckTrust(theta_true, "trust theta_true");
  for (const auto& [x, name] : {std::pair{scheme.a, "scheme a (P(nudge | Go))"},
                                std::pair{scheme.b, "scheme b (P(nudge | Stop))"}}) {
    if (!(x >= 0.0 && x <= 1.0)) {
      throw InvalidArgument(std::string(name) + " = " + NumberText(x) + " is outside [0, 1]");
    }
  }
  const double lambda = params.prior_go;
  double dc_nudge = 0.0;
  if (scheme.random_magnitude) {
    // The mean over the magnitude, uniform on (0, nudge] (midpoint rule).
    constexpr int kPoints = 512;
    for (int j = 0; j < kPoints; ++j)
      dc_nudge += PersuasionProbability(noise, params, theta_true, model,
                                        scheme.nudge * (j + 0.5) / kPoints) / kPoints;
  } else {
    dc_nudge = PersuasionProbability(noise, params, theta_true, model, scheme.nudge);
  }
  const double dc_still = PersuasionProbability(noise, params, theta_true, model, 0.0);
  const double dc_go = scheme.a * dc_nudge + (1.0 - scheme.a) * dc_still;
  const double dc_stop = scheme.b * dc_nudge + (1.0 - scheme.b) * dc_still;
  PredictedOutcome outcome;
  outcome.dc_rate = lambda * dc_go + (1.0 - lambda) * dc_stop;
  outcome.nudge_rate = scheme.nudge > 0.0 ? lambda * scheme.a + (1.0 - lambda) * scheme.b : 0.0;
  if (scheme.av_may_go) {
    outcome.collision_rate = lambda * (1.0 - dc_go);
    outcome.av_first_rate = lambda * dc_go;
  }
  return outcome;
}

const char* ToString(NoiseAwareDesign::Status status) {
  switch (status) {
    case NoiseAwareDesign::Status::kOk:
      return "ok";
    case NoiseAwareDesign::Status::kNotPersuadable:
      return "not_persuadable";
    case NoiseAwareDesign::Status::kUnachievable:
      return "unachievable";
  }
  return "unknown";
}

NoiseAwareDesign DesignUnderNoise(const AvHvParams& params, double theta_hat,
                                  const LikelihoodModel& model, const PerceptionNoise& noise,
                                  double delta) {
  params.Validate();
  noise.Validate();
  internal::CheckTrust(theta_hat, "trust theta_hat");
  if (!(delta > 0.0 && delta < 1.0)) {
    throw InvalidArgument("delta = " + NumberText(delta) + " is outside (0, 1)");
  }
  NoiseAwareDesign out;
  out.nominal = DesignTaebp(params, theta_hat, model);
  out.b_nominal = out.nominal.b;
  out.max_persuasion_probability =
      PersuasionProbability(noise, params, theta_hat, model, model.SMax());
  if (!out.nominal.persuadable) return out;  // kNotPersuadable: the paper's fallback
  const double s_star = out.nominal.s_star;
  const bool exact = noise.kind == PerceptionNoise::Kind::kNone;
  // Without noise and bias this is the paper's s* itself.
  double s = exact ? (noise.bias == 0.0 ? s_star : s_star - noise.bias)
                   : s_star - noise.bias - noise.Quantile(delta);
  s = std::max(s, 0.0);
  if (s > model.SMax()) {
    out.status = NoiseAwareDesign::Status::kUnachievable;
    return out;
  }
  out.status = NoiseAwareDesign::Status::kOk;
  out.nudge = s;
  out.persuasion_probability = PersuasionProbability(noise, params, theta_hat, model, s);
  const double b0 = out.b_nominal;
  if (exact) {
    out.b = b0;
  } else {
    const double at_still = noise.Density(s_star - noise.bias);
    const double at_nudge = noise.Density(s_star - s - noise.bias);
    out.density_ratio = at_nudge > 0.0 ? at_still / at_nudge : 1.0;
    const double rho = out.density_ratio;
    if (b0 >= 1.0) {
      out.b = 1.0;
    } else if (rho <= b0) {
      out.b = (b0 - rho) / (1.0 - rho);
    } else {
      out.b = 0.0;
      out.credible = false;
    }
  }
  out.scheme.av_may_go = true;
  out.scheme.nudge = s;
  out.scheme.a = 1.0;
  out.scheme.b = out.b;
  return out;
}

}  // namespace taebp::persuasion
