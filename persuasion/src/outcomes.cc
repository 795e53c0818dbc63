// Per-encounter outcome prediction for the policies of Section V-B (plus full
// revelation), the theory behind the paper's Table "sim_results".
#include "taebp/persuasion/outcomes.h"

#include "internal.h"

#include <string>

namespace taebp::persuasion {

namespace {

// A TA-EBP design as a commitment; the fallback (not persuadable) always yields.
CommittedScheme FromDesign(const TaebpDesign& design) {
  CommittedScheme scheme;
  if (!design.persuadable) return scheme;
  scheme.av_may_go = true;
  scheme.nudge = design.s_star;
  scheme.a = design.a;
  scheme.b = design.b;
  return scheme;
}

}  // namespace

namespace internal {

double ShareWhere(const std::function<bool(double)>& f, double lo, double hi, int cells) {
  if (!(hi >= lo)) throw InvalidArgument("ShareWhere: hi = " + NumberText(hi) + " is below lo = " + NumberText(lo));
  if (hi == lo) return f(lo) ? 1.0 : 0.0;
  const double width = (hi - lo) / cells;
  double held = 0.0;
  bool left = f(lo);
  for (int i = 0; i < cells; ++i) {
    const double x0 = lo + i * width, x1 = (i + 1 == cells) ? hi : lo + (i + 1) * width;
    const bool right = f(x1);
    if (left == right) {
      if (left) held += x1 - x0;
    } else {
      double a = x0, b = x1;  // f(a) == left, f(b) == right
      while (b - a > 1e-12 * (hi - lo)) {
        const double m = 0.5 * (a + b);
        (f(m) == left ? a : b) = m;
      }
      const double cut = 0.5 * (a + b);
      held += left ? cut - x0 : x1 - cut;
    }
    left = right;
  }
  return held / (hi - lo);
}

}  // namespace internal

double NudgeMagnitude(const CommittedScheme& scheme, double u) {
  return scheme.random_magnitude ? (1.0 - u) * scheme.nudge : scheme.nudge;
}

CommittedScheme CommitScheme(Policy policy, const AvHvParams& params, double theta_hat,
                             const LikelihoodModel& model) {
  params.Validate();
  switch (policy) {
    case Policy::kNoEbp: {
      // Never nudges, so a still AV tells the HV nothing: the AV predicts the HV's
      // reaction from the prior (any trust gives the same) and goes iff it is DC.
      CommittedScheme scheme;
      scheme.av_may_go = HvDrivesIfClear(params, HvPosteriorGo(scheme, params, theta_hat, model, 0.0));
      return scheme;
    }
    case Policy::kNoTrust:
      // Classic Bayesian persuasion: assumes a fully trusting HV.
      return FromDesign(DesignTaebp(params, 1.0, model));
    case Policy::kTaEbp:
    case Policy::kPopulationMean:  // theta_hat: the population's mean trust
    case Policy::kTaEbpLearned:    // theta_hat: the learned lower bound
      return FromDesign(DesignTaebp(params, theta_hat, model));
    case Policy::kAlwaysNudge: {
      // The same s* in every encounter: the nudge carries no information.
      CommittedScheme scheme = FromDesign(DesignTaebp(params, theta_hat, model));
      if (scheme.av_may_go) scheme.b = 1.0;
      return scheme;
    }
    case Policy::kRandomNudge: {
      // Every encounter a nudge of a magnitude uniform on (0, s_max], whatever
      // the intent: no information; goes on its Go intent.
      CommittedScheme scheme;
      scheme.av_may_go = true;
      scheme.nudge = model.SMax();
      scheme.a = 1.0;
      scheme.b = 1.0;
      scheme.random_magnitude = true;
      return scheme;
    }
    case Policy::kFullReveal: {
      // Nudge s_max iff Go: pi(s_max|Go) = 1, pi(s_max|Stop) = 0.
      CommittedScheme scheme;
      scheme.av_may_go = true;
      scheme.nudge = model.SMax();
      scheme.a = 1.0;
      scheme.b = 0.0;
      return scheme;
    }
  }
  throw InvalidArgument("policy = " + std::to_string(static_cast<int>(policy)) + " is unknown");
}

double HvPosteriorGo(const CommittedScheme& scheme, const AvHvParams& params, double theta,
                     const LikelihoodModel& model, double s) {
  if (scheme.Signals()) return HvPosteriorGo(params, theta, model, s);
  params.Validate();
  internal::CheckTrust(theta);
  model.PiGo(s);  // validates s like the signalling case
  return params.prior_go;
}

// The HV (true trust theta_true, intuitive model hv_model) sees either the nudge
// s (probability a under Go, b under Stop) or no nudge (s = 0), forms its belief
// by HvPosteriorGo(scheme, ...) (a still AV is s = 0 under a signalling scheme,
// nothing without one) and drives if clear iff that reaches p* (HvDrivesIfClear). The AV goes iff its
// intent is Go and the scheme lets it go; a collision is the AV going while the
// HV drives recklessly.
PredictedOutcome PredictOutcome(const CommittedScheme& scheme, const AvHvParams& params,
                                double theta_true, const LikelihoodModel& hv_model) {
  params.Validate();
  internal::CheckTrust(theta_true, "trust theta_true");
  auto check_probability = [](double x, const char* name) {
    if (!(x >= 0.0 && x <= 1.0)) {
      throw InvalidArgument(std::string(name) + " = " + NumberText(x) + " is outside [0, 1]");
    }
  };
  check_probability(scheme.a, "scheme a (P(nudge | Go))");
  check_probability(scheme.b, "scheme b (P(nudge | Stop))");
  const double lambda = params.prior_go;
  auto dc_after = [&](double s) {
    return HvDrivesIfClear(params, HvPosteriorGo(scheme, params, theta_true, hv_model, s)) ? 1.0
                                                                                          : 0.0;
  };
  const double dc_nudge =
      scheme.random_magnitude
          ? internal::ShareWhere([&](double s) { return dc_after(s) > 0.5; }, 0.0, scheme.nudge)
          : dc_after(scheme.nudge);
  const double dc_still = dc_after(0.0);

  // P(DC | Go) and P(DC | Stop).
  const double dc_go = scheme.a * dc_nudge + (1.0 - scheme.a) * dc_still;
  const double dc_stop = scheme.b * dc_nudge + (1.0 - scheme.b) * dc_still;

  PredictedOutcome outcome;
  outcome.dc_rate = lambda * dc_go + (1.0 - lambda) * dc_stop;
  // A "nudge" of 0 is standing still: it is not counted as nudging.
  outcome.nudge_rate =
      scheme.nudge > 0.0 ? lambda * scheme.a + (1.0 - lambda) * scheme.b : 0.0;
  if (scheme.av_may_go) {
    outcome.collision_rate = lambda * (1.0 - dc_go);  // AV goes, HV drives recklessly
    outcome.av_first_rate = lambda * dc_go;           // AV goes, HV waits for it
  }
  return outcome;
}

PredictedOutcome PredictOutcome(Policy policy, const AvHvParams& params, double theta_true,
                                const LikelihoodModel& model, std::optional<double> theta_hat) {
  internal::CheckTrust(theta_true, "trust theta_true");
  // CommitScheme designs no_trust for theta_hat = 1 whatever is assumed.
  return PredictOutcome(CommitScheme(policy, params, theta_hat.value_or(theta_true), model), params,
                        theta_true, model);
}

}  // namespace taebp::persuasion
