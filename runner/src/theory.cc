#include "taebp/runner/theory.h"

#include "taebp/encounter/design.h"
#include "taebp/persuasion/lp.h"
#include "taebp/persuasion/noise.h"
#include "taebp/base/number_text.h"

#include <cmath>

namespace taebp {

namespace per = persuasion;
using nlohmann::ordered_json;

namespace {
ordered_json Num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return nullptr;
  return v;
}
}  // namespace

void TheoryRequest::Validate() const {
  Params().Validate();
  if (!(trust >= 0 && trust <= 1))
    throw per::InvalidArgument("--trust theta = " + NumberText(trust) + " is outside [0, 1]");
  if (noise != "none" || noise_bias != 0.0) {
    Noise().Validate();
    if (!(noise_delta > 0 && noise_delta < 1))
      throw per::InvalidArgument("--noise-delta = " + NumberText(noise_delta) +
                                 " is outside (0, 1)");
  }
}

per::PerceptionNoise TheoryRequest::Noise() const {
  per::PerceptionNoise n;
  n.kind = per::ParseNoiseKind(noise);
  n.scale = noise_scale;
  n.bias = noise_bias;
  return n;
}

per::AvHvParams TheoryRequest::Params() const { return per::AvHvParams{prior, penalty}; }

LikelihoodConfig TheoryRequest::Likelihood() const {
  LikelihoodConfig c{LikelihoodType::kLinear, s_max, steepness, midpoint};
  if (!ParseEnum(likelihood, &c.type))
    throw per::InvalidArgument("likelihood '" + likelihood + "' is not one of: " +
                               EnumChoices<LikelihoodType>());
  return c;
}

per::TaebpDesign Design(const TheoryRequest& r) {
  r.Validate();
  const auto model = MakeLikelihood(r.Likelihood());
  return per::DesignTaebp(r.Params(), r.assumed_trust.value_or(r.trust), *model);
}

per::PredictedOutcome Predict(per::Policy policy, const TheoryRequest& r) {
  r.Validate();
  const auto model = MakeLikelihood(r.Likelihood());
  return per::PredictOutcome(policy, r.Params(), r.trust, *model,
                             r.assumed_trust.value_or(r.trust));
}

ordered_json TheoryJson(const TheoryRequest& o) {
  o.Validate();
  const per::AvHvParams params = o.Params();
  const auto model = MakeLikelihood(o.Likelihood());
  const double theta_hat = o.assumed_trust.value_or(o.trust);
  const per::TaebpDesign d = per::DesignTaebp(params, theta_hat, *model);
  per::PredictedOutcome predicted;  // the TA-EBP design's outcome (the loop's ta_ebp)
  ordered_json policies;
  for (per::Policy p : {per::Policy::kNoEbp, per::Policy::kNoTrust, per::Policy::kTaEbp,
                        per::Policy::kFullReveal}) {
    const per::PredictedOutcome out = per::PredictOutcome(p, params, o.trust, *model, theta_hat);
    if (p == per::Policy::kTaEbp) predicted = out;
    policies[PolicyName(p)] = {{"dc_rate", out.dc_rate},
                                  {"collision_rate", out.collision_rate},
                                  {"nudge_rate", out.nudge_rate}};
  }
  ordered_json j;
  j["prior_go"] = o.prior;
  j["collision_penalty"] = o.penalty;
  j["trust"] = o.trust;
  j["assumed_trust"] = theta_hat;
  j["likelihood"] = model->Name();
  j["s_max"] = o.s_max;
  j["p_star"] = d.p_star;
  j["theta_star"] = d.theta_star;
  j["persuadable"] = d.persuadable;
  j["s_star"] = d.s_star;
  j["a"] = d.a;
  j["b"] = d.b;
  j["p_nudge"] = d.p_nudge;
  j["dc_rate"] = predicted.dc_rate;
  j["collision_rate"] = predicted.collision_rate;
  j["policies"] = policies;
  if (o.noise != "none" || o.noise_bias != 0.0) {
    const per::PerceptionNoise noise = o.Noise();
    const per::NoiseAwareDesign nd =
        per::DesignUnderNoise(params, theta_hat, *model, noise, o.noise_delta);
    const per::PredictedOutcome aware =
        per::PredictOutcomeUnderNoise(nd.scheme, params, o.trust, *model, noise);
    ordered_json n;
    n["kind"] = o.noise;
    n["scale"] = o.noise_scale;
    n["bias"] = o.noise_bias;
    n["delta"] = o.noise_delta;
    n["collision_bound"] = o.noise_delta * o.prior;
    n["aware"] = {{"status", per::ToString(nd.status)},
                  {"nudge", nd.nudge},
                  {"b", nd.b},
                  {"credible", nd.credible},
                  {"density_ratio", nd.density_ratio},
                  {"persuasion_probability", nd.persuasion_probability},
                  {"dc_rate", aware.dc_rate},
                  {"collision_rate", aware.collision_rate},
                  {"nudge_rate", aware.nudge_rate}};
    ordered_json under;
    for (per::Policy p : {per::Policy::kNoEbp, per::Policy::kNoTrust, per::Policy::kTaEbp,
                          per::Policy::kFullReveal}) {
      const per::PredictedOutcome out = per::PredictOutcomeUnderNoise(
          per::CommitScheme(p, params, theta_hat, *model), params, o.trust, *model, noise);
      under[PolicyName(p)] = {{"dc_rate", out.dc_rate},
                                 {"collision_rate", out.collision_rate},
                                 {"nudge_rate", out.nudge_rate}};
    }
    n["policies"] = under;
    j["noise"] = n;
  }
  return j;
}

per::Game ProblemGame(const ProblemConfig& pc, const std::string& path) {
  per::Game g;
  g.states = pc.states;
  g.actions = pc.actions;
  const auto n = static_cast<Eigen::Index>(pc.states.size());
  const auto m = static_cast<Eigen::Index>(pc.actions.size());
  auto matrix = [&](const std::vector<std::vector<double>>& rows, const char* key) {
    if (static_cast<Eigen::Index>(rows.size()) != n)
      throw ConfigError(path + ": key '" + key + "' has " + std::to_string(rows.size()) +
                        " rows but there are " + std::to_string(n) + " states");
    Eigen::MatrixXd mat(n, m);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (static_cast<Eigen::Index>(rows[i].size()) != m)
        throw ConfigError(path + ": key '" + key + "' row " + std::to_string(i) + " has " +
                          std::to_string(rows[i].size()) + " entries but there are " +
                          std::to_string(m) + " actions");
      for (Eigen::Index a = 0; a < m; ++a) mat(i, a) = rows[i][a];
    }
    return mat;
  };
  if (static_cast<Eigen::Index>(pc.prior.size()) != n)
    throw ConfigError(path + ": key 'prior' has " + std::to_string(pc.prior.size()) +
                      " entries but there are " + std::to_string(n) + " states");
  g.prior = Eigen::Map<const Eigen::VectorXd>(pc.prior.data(), n);
  g.receiver_utility = matrix(pc.receiver_utility, "receiver_utility");
  g.sender_utility = matrix(pc.sender_utility, "sender_utility");
  std::string why;
  if (!g.IsValid(&why)) throw ConfigError(path + ": " + why);
  if (!(pc.trust >= 0 && pc.trust <= 1))
    throw ConfigError(path + ": key 'trust' = " + NumberText(pc.trust) +
                      " is outside [0, 1]");
  return g;
}

ordered_json SolveResultJson(const per::Game& g, double trust, const per::LpResult& r) {
  ordered_json j;
  j["status"] = per::ToString(r.status);
  j["sender_value"] = r.sender_value;
  j["states"] = g.states;
  j["actions"] = g.actions;
  j["trust"] = trust;
  ordered_json scheme = ordered_json::array(), post = ordered_json::array();
  for (Eigen::Index i = 0; i < r.scheme.rows(); ++i) {
    ordered_json row = ordered_json::array();
    for (Eigen::Index a = 0; a < r.scheme.cols(); ++a) row.push_back(r.scheme(i, a));
    scheme.push_back(row);
  }
  // posteriors: one row per recommended action, one entry per state.
  for (Eigen::Index a = 0; a < r.posteriors.cols(); ++a) {
    ordered_json row = ordered_json::array();
    for (Eigen::Index i = 0; i < r.posteriors.rows(); ++i) row.push_back(Num(r.posteriors(i, a)));
    post.push_back(row);
  }
  j["scheme"] = scheme;
  j["signal_probability"] = std::vector<double>(
      r.signal_probability.data(), r.signal_probability.data() + r.signal_probability.size());
  j["posteriors"] = post;
  if (!r.message.empty()) j["message"] = r.message;
  return j;
}

SolveOutput SolveJson(const ProblemConfig& pc, const std::string& path) {
  const per::Game g = ProblemGame(pc, path);
  const per::LpResult r = per::SolveTrustAwarePersuasion(g, pc.trust);
  return {SolveResultJson(g, pc.trust, r), r.status == per::LpResult::Status::kOptimal};
}

}  // namespace taebp
