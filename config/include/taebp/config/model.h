// The one typed conversion from a config to the model it configures: the
// structs of persuasion/ built from their config sections, field by field here
// and nowhere else. Their ranges are checked once, by the model's own IsValid,
// which ExperimentConfig::IsValid calls with the section's key in front (so a
// message still names the key and the value: "model.trust_dynamics.forgetting
// rho = 1.5 is outside [0, 1]").
#pragma once

#include "taebp/config/config.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/experience.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/major_road.h"
#include "taebp/persuasion/noise.h"
#include "taebp/persuasion/trust_dynamics.h"
#include "taebp/persuasion/trust_learning.h"

#include <memory>

namespace taebp {

// model.prior_go, model.collision_penalty
persuasion::AvHvParams ToModel(const ModelConfig& model);
// scenario.major_road with model.prior_go, model.collision_penalty: the
// major-road game (yield_cost c; persuasion/major_road.h)
persuasion::MajorRoadParams ToModel(const ModelConfig& model, const MajorRoadConfig& major);
// model.noise: kind, scale, bias (delta and design belong to the AV's design)
persuasion::PerceptionNoise ToModel(const NoiseConfig& noise);
// model.trust_dynamics: the weights, the forgetting and the quality mapping
// (strength sets each HV's initial state)
persuasion::TrustUpdateRule ToModel(const TrustDynamicsConfig& dynamics);
// model.learning: delta, decay (infinite with constant_level), probe
persuasion::ExplorationSchedule ToModel(const LearningConfig& learning);
// model.experience: strength, bin_width (design belongs to the AV)
persuasion::ExperienceRule ToModel(const ExperienceConfig& experience);
// A trust distribution as the learner's population prior: Beta as it is;
// fixed and discrete as atoms; uniform on [low, high] as a histogram of 1000
// cells (exact when low and high are multiples of 1/1000).
persuasion::TrustPrior ToModel(const TrustSpec& trust);
// model.likelihood: the HV's likelihood model.
std::unique_ptr<persuasion::LikelihoodModel> MakeLikelihood(const LikelihoodConfig& likelihood);

}  // namespace taebp
