// The AV-HV two-way-stop game (Table "utility") and TA-EBP (Section IV-C).
#include "taebp/persuasion/av_hv.h"

#include "internal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace taebp::persuasion {


namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

bool AvHvParams::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(prior_go > 0.0 && prior_go < 1.0)) {
    return fail("prior_go (lambda) = " + NumberText(prior_go) + " is outside (0, 1)");
  }
  if (!(collision_penalty > 0.0)) {
    return fail("collision_penalty r = " + NumberText(collision_penalty) + " must be > 0");
  }
  if (!std::isfinite(collision_penalty)) {
    return fail("collision_penalty r = " + NumberText(collision_penalty) + " must be finite");
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
// (p* - lambda) / (1 - lambda). When the HV already drives if clear at the prior
// (lambda >= p*, decided by the tolerance policy like every other comparison) no
// trust is needed (theta* = 0).
double AvHvThetaStar(const AvHvParams& params) {
  params.Validate();
  const double lambda = params.prior_go;
  const double r = params.collision_penalty;
  if (HvDrivesIfClear(params, lambda)) return 0.0;
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
    throw InvalidArgument("signal s = " + NumberText(s) + " has zero probability under the " +
                          model.Name() + " model");
  }
  return (1.0 - theta) * lambda + theta * (go / evidence);
}

// eq:ppp as a decision: DC is a best response at p_go (ties toward the AV, who
// prefers DC). The gain of DC over DR and the table's UtilityScale are those of
// AvHvGame, spelled out so that no Game is built per encounter:
//   U(DR|p) = -r p + (1 - p),  U(DC|p) = -(1 - p),  gain = (2 + r)(p - p*),
//   scale = max u - min u = 1 - min(-r, -1) = 1 + max(r, 1).
// The expected utilities are computed term for term as ExpectedUtilities does,
// so this is BestResponse(AvHvGame(params), (p_go, 1 - p_go)) == DC exactly.
bool HvDrivesIfClear(const AvHvParams& params, double p_go) {
  params.Validate();
  // Round-off may push a posterior a hair outside [0, 1]; only reject real errors.
  if (!(p_go >= -kProbabilityTolerance && p_go <= 1.0 + kProbabilityTolerance)) {
    throw InvalidArgument("posterior p_go = " + NumberText(p_go) + " is outside [0, 1]");
  }
  const double r = params.collision_penalty;
  const double p_stop = 1.0 - p_go;
  const double u_dr = -r * p_go + 1.0 * p_stop;
  const double u_dc = 0.0 * p_go + -1.0 * p_stop;
  return WeaklyPrefers(u_dc - u_dr, 1.0 + std::max(r, 1.0));
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
  if (HvDrivesIfClear(params, lambda)) {
    // Already DC at the prior (lambda >= p*, ties included). (The general theorem would call DC the default
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

// Theorem 2 (eq:s^*): s*(theta) = L^{-1}(R(theta)). Both decisions -- can any
// nudge persuade (the strongest, s_max) and is none needed (s = 0) -- are the
// HV's best response there (tolerance policy); L^{-1} is used only in between.
double MinimalNudge(const AvHvParams& params, double theta, const LikelihoodModel& model) {
  params.Validate();
  internal::CheckTrust(theta);
  if (!AvHvPersuadable(params, theta, model)) {
    const TrustThreshold threshold = AvHvModelTrustThreshold(params, model);
    throw InvalidArgument(
        "trust theta = " + NumberText(theta) +
        " is below the minimum persuadable trust theta* = " + NumberText(threshold.theta_star) +
        " of the " + model.Name() + " likelihood model: no nudge in [0, " + NumberText(model.SMax()) +
        "] makes the HV drive if clear");
  }
  if (HvDrivesIfClear(params, HvPosteriorGo(params, theta, model, 0.0))) return 0.0;
  const double ratio = RequiredRatio(params, theta);
  // theta is (within tolerance) at the model's threshold: only the strongest nudge works.
  if (ratio >= model.MaxRatio()) return model.SMax();
  return model.InverseRatio(ratio);
}

// eq:b: setting the scheme posterior (pi(s*|Go) = 1, pi(s*|Stop) = b) to p*,
//   b = lambda (theta - p* + (1 - theta) lambda) / ((1 - lambda)(p* - (1 - theta) lambda)),
// i.e. b = 1 / R(theta). For lambda >= p*, b >= 1 (or the denominator is <= 0):
// the AV may always nudge, b = 1. Both decisions follow the tolerance policy:
// "lambda >= p*" is the HV's best response at the prior, "theta >= theta*" its
// best response to the most informative signal (b = 0, p_FT(Go) = 1), the same
// expression as HvPosteriorGo at s_max of the linear model.
double StopNudgeProbability(const AvHvParams& params, double theta) {
  params.Validate();
  internal::CheckTrust(theta);
  const double lambda = params.prior_go;
  const double p_star = AvHvPStar(params.collision_penalty);
  if (HvDrivesIfClear(params, lambda)) return 1.0;
  if (!HvDrivesIfClear(params, (1.0 - theta) * lambda + theta * 1.0)) {
    throw InvalidArgument("trust theta = " + NumberText(theta) +
                          " is below the minimum persuadable trust theta* = " +
                          NumberText(AvHvThetaStar(params)));
  }
  const double numerator = lambda * (theta - p_star + (1.0 - theta) * lambda);
  // > 0 here: (1 - theta) lambda <= lambda < p* since the prior alone does not persuade.
  const double denominator = (1.0 - lambda) * (p_star - (1.0 - theta) * lambda);
  return std::clamp(numerator / denominator, 0.0, 1.0);
}

// Section IV-C, Steps 1-3.
TaebpDesign DesignTaebp(const AvHvParams& params, double theta_hat, const LikelihoodModel& model) {
  params.Validate();
  internal::CheckTrust(theta_hat, "trust theta_hat");
  TaebpDesign design;
  design.p_star = AvHvPStar(params.collision_penalty);
  design.theta_star = AvHvModelTrustThreshold(params, model).theta_star;
  // Step 1: persuadable iff theta_hat >= theta*, decided as "the strongest nudge
  // makes DC a best response" (the tolerance policy, persuasion.h); MinimalNudge
  // and StopNudgeProbability decide the same way, so they cannot disagree here.
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
