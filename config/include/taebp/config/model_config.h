// The model section of an experiment config (model:): the game, the HV's
// reading (likelihood), trust (fixed, a distribution, dynamic, learned),
// noise and experience. Plain structs with defaults at the field and one schema
// (Serialize); checked by ExperimentConfig::IsValid (config.h).
#pragma once

#include "taebp/config/enums.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace taebp {

struct LikelihoodConfig {
  LikelihoodType type = LikelihoodType::kLinear;
  double s_max = 2.0;           // m
  double steepness = 4.0;       // logistic only
  double midpoint = 1.0;        // logistic only

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("type", &type);
    a->Visit("s_max", &s_max);
    a->Visit("steepness", &steepness);
    a->Visit("midpoint", &midpoint);
  }
};

// The HVs' trust: one number for every HV, or a distribution from which each
// HV draws its own theta at the start of a run (with the run's seed).
// YAML: `trust: 0.6`, `trust: {dist: uniform, low: 0.2, high: 0.9}`,
// `trust: {dist: beta, alpha: 2, beta: 5}`,
// `trust: {dist: discrete, values: [0.2, 0.8], weights: [1, 3]}`.
struct TrustSpec {
  TrustDist dist = TrustDist::kFixed;
  double value = 0.6;          // fixed
  double low = 0.0, high = 1.0;         // uniform
  double alpha = 1.0, beta = 1.0;       // beta
  std::vector<double> values, weights;  // discrete (weights default to equal)

  static TrustSpec Fixed(double v) {
    TrustSpec t;
    t.value = v;
    return t;
  }
  bool IsFixed() const { return dist == TrustDist::kFixed; }
  double Mean() const;
  // dist discrete: the weight of values[i] (1 when no weights are given) and
  // the sum of all weights.
  double Weight(std::size_t i) const { return weights.empty() ? 1.0 : weights[i]; }
  double TotalWeight() const;
  // theta with cumulative probability q in (0, 1) (the quantile function).
  double Quantile(double q) const;
  // One draw from a uniform u in [0, 1) (inverse-CDF sampling).
  double Draw(double u) const { return Quantile(u); }
  // Checks ranges; `key` names the config key in the message.
  bool IsValid(const std::string& key, std::string* why) const;
  std::string ToString() const;  // compact, for tables and file names
};
// The keys of a `model.trust` distribution map besides `dist` (the loader
// accepts these and no others; the generated reference lists them).
std::vector<std::string> TrustDistKeys(TrustDist dist);

// model.trust_dynamics: each HV's trust is a Beta(alpha, beta) state whose
// mean it uses, updated after every AV-HV encounter it is in (Guo & Yang;
// persuasion/trust_dynamics.h). alpha0 + beta0 = strength with the mean the
// HV's drawn model.trust. q per outcome (what the HV saw: did the AV nudge,
// did it then go, did they collide) is the quality mapping; SUMO's collision
// flag decides `collision`. No near misses are defined (the HV cannot tell a
// close call in SUMO from a clean encounter).
struct TrustQualityConfig {
  double nudge_go = 1.0;    // nudged, then went: the nudge meant Go
  double nudge_stop = 0.0;  // nudged, then yielded: a false alarm
  double still_stop = 1.0;  // stood still, then yielded
  double still_go = 0.0;    // stood still, then went: an unannounced Go
  double collision = 0.0;   // SUMO reported a collision between the two

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("nudge_go", &nudge_go);
    a->Visit("nudge_stop", &nudge_stop);
    a->Visit("still_stop", &still_stop);
    a->Visit("still_go", &still_go);
    a->Visit("collision", &collision);
  }
};
struct TrustDynamicsConfig {
  double strength = 10.0;       // alpha0 + beta0: encounters' worth of initial evidence
  double success_weight = 1.0;  // w_s: alpha += w_s q
  double failure_weight = 1.0;  // w_f: beta += w_f (1 - q)
  double forgetting = 0.0;      // rho in [0, 1]: decay toward (alpha0, beta0) per encounter
  TrustQualityConfig quality;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("strength", &strength);
    a->Visit("success_weight", &success_weight);
    a->Visit("failure_weight", &failure_weight);
    a->Visit("forgetting", &forgetting);
    a->Visit("quality", &quality);
  }
};

// model.noise: the HV reads SUMO's displacement plus noise and a bias
// (persuasion/noise.h). The nudge SUMO realises is unchanged (and still
// checked against its tolerance). design: aware = the AV's TA-EBP designs
// (ta_ebp, population_mean, ta_ebp_learned) nudge s* - bias - F^-1(delta) so
// that the noisy reading still persuades with probability >= 1 - delta;
// paper = they keep the paper's s* (to measure what noise does to it).
struct NoiseConfig {
  NoiseKind kind = NoiseKind::kGaussian;
  double scale = 0.05;            // m: Gaussian sigma, or the uniform half-width
  double bias = 0.0;              // m, added to every reading
  double delta = 0.01;            // the noise-aware design's failure budget, in (0, 1)
  NoiseDesign design = NoiseDesign::kAware;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("kind", &kind);
    a->Visit("scale", &scale);
    a->Visit("bias", &bias);
    a->Visit("delta", &delta);
    a->Visit("design", &design);
  }
};

// model.learning: the policy ta_ebp_learned (persuasion/trust_learning.h).
// The AVs share a posterior over each HV's trust (by HV id), start from
// `prior` (default: model.trust, the population's distribution) and design
// TA-EBP for the lower credible bound at risk level
// eps_m = min(delta, decay / (m + 1)) after m observed responses of that HV
// (constant_level: eps = delta for ever).
struct LearningConfig {
  double delta = 0.01;  // in (0, 1): P(a nudge fails to persuade) per encounter
  double decay = 1.0;   // c > 0 (regret O(log T) needs c > 1/2)
  bool constant_level = false;  // eps = delta for ever (regret linear in T)
  bool probe = true;    // test the strongest nudge with probability eps / P(theta < theta*)
  std::optional<TrustSpec> prior;  // the population prior; unset: model.trust

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("delta", &delta);
    a->Visit("decay", &decay);
    a->Visit("constant_level", &constant_level);
    a->Visit("probe", &probe);
    a->Visit("prior", &prior);
  }
};

// model.experience (issue 29; docs/influence.md, persuasion/experience.h):
// each HV remembers, per signal level (the displacement SUMO reported, in bins
// of bin_width m), how often the AV then went, and reads a nudge with
// p_E = (k q + g) / (k + n) in place of the intuitive posterior q (trust weighs
// it as in eq:pp). Each HV learns from its own encounters only. design: what
// ta_ebp commits to: guarded = TA-EBP for each HV's experienced belief (b = 0
// when a false alarm would leave s* unpersuasive; DesignForExperience), paper
// = the paper's scheme whatever the HV learned (to measure the knife edge),
// robust = s_max with the largest b that keeps a margin above p* without
// knowing the learner's rule (DesignRobust; issue 42). forgetting: the
// learner's weight on its past per encounter (1 = exact counts).
// Unset: the paper's HV, who never learns.
struct ExperienceConfig {
  double strength = 20.0;   // k > 0: readings' worth of trust in the intuitive model
  double bin_width = 0.1;   // m > 0: one signal level
  double forgetting = 1.0;  // rho in (0, 1]: the learner's weight on its past
  ExperienceDesign design = ExperienceDesign::kGuarded;
  double margin = 0.1;      // robust: the belief's margin above p*, in [0, 1)
  // HVs of different k: each HV draws one of these, equally likely, by a hash
  // of its id (the designs keep assuming `strength`); empty: every HV has
  // `strength`.
  std::vector<double> strengths;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("strength", &strength);
    a->Visit("strengths", &strengths);
    a->Visit("bin_width", &bin_width);
    a->Visit("forgetting", &forgetting);
    a->Visit("design", &design);
    a->Visit("margin", &margin);
  }
};

struct ModelConfig {
  double prior_go = 0.2;           // lambda
  double collision_penalty = 3.0;  // r
  TrustSpec trust = TrustSpec::Fixed(0.6);  // theta of the HVs
  // What the AV knows of each HV's trust when it designs its scheme (ta_ebp):
  // exact (that HV's own theta), population_mean (one design for the mean),
  // assumed (one design for assumed_trust). Unset: assumed if assumed_trust is
  // set, else exact.
  std::optional<TrustKnowledge> trust_knowledge;
  std::optional<double> assumed_trust;  // theta_hat for trust_knowledge = assumed
  LikelihoodConfig likelihood;
  // Beyond the paper (unset: the paper's static, exactly seen, known trust).
  std::optional<TrustDynamicsConfig> trust_dynamics;
  std::optional<NoiseConfig> noise;
  std::optional<LearningConfig> learning;
  std::optional<ExperienceConfig> experience;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("prior_go", &prior_go);
    a->Visit("collision_penalty", &collision_penalty);
    a->Visit("trust", &trust);
    a->Visit("trust_knowledge", &trust_knowledge);
    a->Visit("assumed_trust", &assumed_trust);
    a->Visit("likelihood", &likelihood);
    a->Visit("trust_dynamics", &trust_dynamics);
    a->Visit("noise", &noise);
    a->Visit("learning", &learning);
    a->Visit("experience", &experience);
  }
  // trust_knowledge with the default resolved.
  TrustKnowledge Knowledge() const {
    if (trust_knowledge) return *trust_knowledge;
    return assumed_trust ? TrustKnowledge::kAssumed : TrustKnowledge::kExact;
  }
};

}  // namespace taebp
