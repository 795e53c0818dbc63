// The theory and the LP as data: what `taebp theory --json` and
// `taebp solve --json` print, shared by the CLI and the Python module so both
// give the same fields and numbers for the same inputs. SUMO-free.
#pragma once

#include "taebp/config/config.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/lp.h"
#include "taebp/persuasion/noise.h"
#include "taebp/persuasion/outcomes.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace taebp {

// The AV-HV game's parameters as `taebp theory` takes them.
struct TheoryRequest {
  double prior = 0.2, penalty = 3.0, trust = 0.6, s_max = 2.0;
  std::optional<double> assumed_trust;  // theta_hat the AV designs for (default: trust)
  std::string likelihood = "linear";    // linear | logistic
  double steepness = 4.0, midpoint = 1.0;
  // Perception noise on the HV's reading (model.noise): none | gaussian |
  // uniform, its scale (sigma or half-width, m), bias (m) and the
  // noise-aware design's delta. With noise (or a bias) the JSON gains `noise`.
  std::string noise = "none";
  double noise_scale = 0.05, noise_bias = 0.0, noise_delta = 0.01;

  // Throws persuasion::InvalidArgument naming the parameter and value.
  void Validate() const;
  persuasion::AvHvParams Params() const;
  LikelihoodConfig Likelihood() const;
  persuasion::PerceptionNoise Noise() const;  // throws for an unknown kind
};

// `taebp theory --json`: prior_go, collision_penalty, trust, assumed_trust,
// likelihood, s_max, p_star, theta_star, persuadable, s_star, a, b, p_nudge,
// dc_rate, collision_rate (the TA-EBP design's) and policies.NAME.{dc_rate,
// collision_rate, nudge_rate}; with noise also noise.{kind, scale, bias,
// delta, aware: the noise-aware design for theta_hat (status, nudge, b,
// credible, density_ratio, persuasion_probability, dc_rate, collision_rate),
// policies.NAME: every policy's rates under the noise (ta_ebp: the paper's
// s*, unaware of the noise), collision_bound = delta * lambda}. Throws
// persuasion::InvalidArgument.
nlohmann::ordered_json TheoryJson(const TheoryRequest& request);

// The TA-EBP design for theta_hat = request.assumed_trust (default trust).
persuasion::TaebpDesign Design(const TheoryRequest& request);
// One policy's predicted outcome for an HV of trust request.trust when the AV
// designs for request.assumed_trust (default: trust; no_trust forces 1).
persuasion::PredictedOutcome Predict(persuasion::Policy policy, const TheoryRequest& request);

// The game of a problem config (rows = states), checked: ConfigError naming
// `origin`, the key and the sizes for a malformed problem or a trust outside [0, 1].
persuasion::Game ProblemGame(const ProblemConfig& problem, const std::string& origin);

// The LP's result as `taebp solve --json` prints it.
nlohmann::ordered_json SolveResultJson(const persuasion::Game& game, double trust,
                                       const persuasion::LpResult& result);

// `taebp solve --json` for a problem (rows = states). Throws ConfigError
// naming `origin`, the key and the sizes for a malformed problem. `optimal`
// is false when the LP was not solved to optimality (the CLI's exit code 1).
struct SolveOutput {
  nlohmann::ordered_json json;
  bool optimal = false;
};
SolveOutput SolveJson(const ProblemConfig& problem, const std::string& origin);

}  // namespace taebp
