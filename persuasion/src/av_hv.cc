// The AV-HV two-way-stop game (Table "utility") and TA-EBP (Section IV-C).
#include "taebp/persuasion/av_hv.h"

#include "internal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace taebp::persuasion {

using internal::Num;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

bool AvHvParams::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(prior_go > 0.0 && prior_go < 1.0)) {
    return fail("prior_go (lambda) = " + Num(prior_go) + " is outside (0, 1)");
  }
  if (!(collision_penalty > 0.0)) {
    return fail("collision_penalty r = " + Num(collision_penalty) + " must be > 0");
  }
  if (!std::isfinite(collision_penalty)) {
    return fail("collision_penalty r = " + Num(collision_penalty) + " must be finite");
  }
  return true;
}

void AvHvParams::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

// Table "utility": rows (Go, Stop), columns (DR, DC).
//   u: DR -> (-r, 1), DC -> (0, -1);  v: DR -> (-1, -1), DC -> (1, 1).
Game AvHvGame(const AvHvParams& params) {
  params.Validate();
  Game game;
  game.states = {"Go", "Stop"};
  game.actions = {"DR", "DC"};
  game.prior = Eigen::Vector2d(params.prior_go, 1.0 - params.prior_go);
  game.receiver_utility.resize(2, 2);
  game.receiver_utility << -params.collision_penalty, 0.0,  //
      1.0, -1.0;
  game.sender_utility.resize(2, 2);
  game.sender_utility << -1.0, 1.0,  //
      -1.0, 1.0;
  return game;
}

// eq:ppp: p* = (u(Stop,DC) - u(Stop,DR)) / (u(Go,DR) - u(Go,DC) - u(Stop,DR) + u(Stop,DC))
//            = 2 / (2 + r).
double AvHvPStar(double collision_penalty) {
  AvHvParams params;
  params.collision_penalty = collision_penalty;
  params.Validate();
  return 2.0 / (2.0 + collision_penalty);
}

// eq:tt: theta* = (2(1 - lambda) - r lambda) / ((1 - lambda)(r + 2)), which equals
// (p* - lambda) / (1 - lambda). For lambda >= p* the HV already drives if clear
// at the prior, so no trust is needed (theta* = 0).
double AvHvThetaStar(const AvHvParams& params) {
  params.Validate();
  const double lambda = params.prior_go;
  const double r = params.collision_penalty;
  if (lambda >= AvHvPStar(r)) return 0.0;
  const double theta = (2.0 * (1.0 - lambda) - r * lambda) / ((1.0 - lambda) * (r + 2.0));
  return std::clamp(theta, 0.0, 1.0);
}

// eq:pp, evaluated from pi(s|Go) and pi(s|Stop) directly (not through L(s)) so that
// s = 0 and s = s_max, where L is 0 or +inf, are exact:
//   p_FT(Go|s) = pi(s|Go) lambda / (pi(s|Go) lambda + pi(s|Stop) (1 - lambda)),
//   p_theta(Go|s) = (1 - theta) lambda + theta p_FT(Go|s).
double HvPosteriorGo(const AvHvParams& params, double theta, const LikelihoodModel& model,
                     double s) {
  params.Validate();
  internal::CheckTrust(theta);
  const double lambda = params.prior_go;
  const double go = model.PiGo(s) * lambda;  // validates s
  const double stop = model.PiStop(s) * (1.0 - lambda);
  const double evidence = go + stop;
  if (!(evidence > 0.0)) {
    throw InvalidArgument("signal s = " + Num(s) + " has zero probability under the " +
                          model.Name() + " model");
  }
  return (1.0 - theta) * lambda + theta * (go / evidence);
}

bool HvDrivesIfClear(const AvHvParams& params, double p_go) {
  const double p_star = AvHvPStar(params.collision_penalty);
  params.Validate();
  // Round-off may push a posterior a hair outside [0, 1]; only reject real errors.
  if (!(p_go >= -kTieTolerance && p_go <= 1.0 + kTieTolerance)) {
    throw InvalidArgument("posterior p_go = " + Num(p_go) + " is outside [0, 1]");
  }
  return p_go >= p_star - kTieTolerance;
}

// Argument of L^{-1} in eq:s^*: setting eq:pp equal to p* and solving for L,
//   R = (1 - lambda)(p* - (1 - theta) lambda) / (lambda (theta + (1 - theta) lambda - p*)).
// Numerator <= 0: the prior weight alone reaches p*, any L >= 0 works (R <= 0 is
// returned; 0 when both vanish). Denominator <= 0 with a positive numerator
// (theta <= theta*): no finite ratio suffices, +infinity.
double RequiredRatio(const AvHvParams& params, double theta) {
  params.Validate();
  internal::CheckTrust(theta);
  const double lambda = params.prior_go;
  const double p_star = AvHvPStar(params.collision_penalty);
  const double numerator = (1.0 - lambda) * (p_star - (1.0 - theta) * lambda);
  const double denominator = lambda * (theta + (1.0 - theta) * lambda - p_star);
  if (numerator <= 0.0) return denominator > 0.0 ? numerator / denominator : 0.0;
  if (denominator <= 0.0) return kInf;
  return numerator / denominator;
}

bool AvHvPersuadable(const AvHvParams& params, double theta, const LikelihoodModel& model) {
  return HvDrivesIfClear(params, HvPosteriorGo(params, theta, model, model.SMax()));
}

// Theorem 1 restricted to the nudges the model can produce. Since the two-state
// posterior eq:pp is monotone in s, max_{s in [0, s_max]} dU_FT(DC, DR; s) is
// attained at an end of the range, so the finite signal set {pi(.|0), pi(.|s_max)}
// gives the same threshold. For an unbounded L (p_FT(Go|s_max) = 1) this is eq:tt;
// for a bounded one it is (p* - lambda) / (p_FT(Go|s_max) - lambda).
TrustThreshold AvHvModelTrustThreshold(const AvHvParams& params, const LikelihoodModel& model) {
  params.Validate();
  const double lambda = params.prior_go;
  if (lambda >= AvHvPStar(params.collision_penalty)) {
    // Already DC at the prior. (The general theorem would call DC the default
    // action here and report the trust needed to persuade towards DR instead.)
    TrustThreshold result;
    result.theta_star = 0.0;
    result.persuadable = true;
    result.default_action = kDC;
    result.target_action = kDC;
    return result;
  }
  Eigen::Matrix2d signals;
  signals << model.PiGo(0.0), model.PiGo(model.SMax()),  //
      model.PiStop(0.0), model.PiStop(model.SMax());
  return MinPersuadableTrust(AvHvGame(params), signals);
}

// Theorem 2 (eq:s^*): s*(theta) = L^{-1}(R(theta)), checked against the model's
// persuadability threshold (p_theta(Go|s_max) >= p* - kTieTolerance).
double MinimalNudge(const AvHvParams& params, double theta, const LikelihoodModel& model) {
  params.Validate();
  internal::CheckTrust(theta);
  if (!AvHvPersuadable(params, theta, model)) {
    const TrustThreshold threshold = AvHvModelTrustThreshold(params, model);
    throw InvalidArgument(
        "trust theta = " + Num(theta) +
        " is below the minimum persuadable trust theta* = " + Num(threshold.theta_star) +
        " of the " + model.Name() + " likelihood model: no nudge in [0, " + Num(model.SMax()) +
        "] makes the HV drive if clear");
  }
  const double ratio = RequiredRatio(params, theta);
  if (ratio <= model.Ratio(0.0)) return 0.0;
  // theta is (within tolerance) at the model's threshold: only the strongest nudge works.
  if (ratio >= model.MaxRatio()) return model.SMax();
  return model.InverseRatio(ratio);
}

// eq:b: setting the scheme posterior (pi(s*|Go) = 1, pi(s*|Stop) = b) to p*,
//   b = lambda (theta - p* + (1 - theta) lambda) / ((1 - lambda)(p* - (1 - theta) lambda)),
// i.e. b = 1 / R(theta). For lambda >= p*, b >= 1 (or the denominator is <= 0):
// the AV may always nudge, b = 1.
double StopNudgeProbability(const AvHvParams& params, double theta) {
  params.Validate();
  internal::CheckTrust(theta);
  const double lambda = params.prior_go;
  const double p_star = AvHvPStar(params.collision_penalty);
  if (lambda >= p_star) return 1.0;
  const double theta_star = AvHvThetaStar(params);
  // DesignTaebp calls this for every theta that AvHvPersuadable accepts, i.e. down
  // to p = (1 - theta) lambda + theta = p* - kTieTolerance, theta* - kTieTolerance
  // / (1 - lambda); the factor 2 keeps round-off in the two tests from disagreeing.
  if (theta < theta_star - 2.0 * kTieTolerance / (1.0 - lambda)) {
    throw InvalidArgument("trust theta = " + Num(theta) +
                          " is below the minimum persuadable trust theta* = " + Num(theta_star));
  }
  const double numerator = lambda * (theta - p_star + (1.0 - theta) * lambda);
  const double denominator = (1.0 - lambda) * (p_star - (1.0 - theta) * lambda);  // > 0 here
  return std::clamp(numerator / denominator, 0.0, 1.0);
}

// Section IV-C, Steps 1-3.
TaebpDesign DesignTaebp(const AvHvParams& params, double theta_hat, const LikelihoodModel& model) {
  params.Validate();
  internal::CheckTrust(theta_hat, "trust theta_hat");
  TaebpDesign design;
  design.p_star = AvHvPStar(params.collision_penalty);
  design.theta_star = AvHvModelTrustThreshold(params, model).theta_star;
  // Step 1: persuadable iff theta_hat >= theta*, tested as "the strongest nudge
  // lifts the posterior to p*" so that the tie tolerance is the one of eq:ppp.
  if (!AvHvPersuadable(params, theta_hat, model)) return design;  // fallback: always yield
  // Step 2: s* from Theorem 2, a = 1, b from eq:b.
  design.persuadable = true;
  design.s_star = MinimalNudge(params, theta_hat, model);
  design.a = 1.0;
  design.b = StopNudgeProbability(params, theta_hat);
  design.p_nudge = params.prior_go * design.a + (1.0 - params.prior_go) * design.b;
  return design;
}

}  // namespace taebp::persuasion
