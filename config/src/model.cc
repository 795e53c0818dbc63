#include "taebp/config/model.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace taebp {

namespace per = persuasion;

per::AvHvParams ToModel(const ModelConfig& m) { return per::AvHvParams{m.prior_go, m.collision_penalty}; }

per::MajorRoadParams ToModel(const ModelConfig& m, const MajorRoadConfig& major) {
  per::MajorRoadParams p;
  p.prior_go = m.prior_go;
  p.collision_penalty = m.collision_penalty;
  p.yield_cost = major.yield_cost;
  return p;
}

per::PerceptionNoise ToModel(const NoiseConfig& n) {
  per::PerceptionNoise out;
  switch (n.kind) {
    case NoiseKind::kNone: out.kind = per::PerceptionNoise::Kind::kNone; break;
    case NoiseKind::kGaussian: out.kind = per::PerceptionNoise::Kind::kGaussian; break;
    case NoiseKind::kUniform: out.kind = per::PerceptionNoise::Kind::kUniform; break;
  }
  out.scale = n.scale;
  out.bias = n.bias;
  return out;
}

per::TrustUpdateRule ToModel(const TrustDynamicsConfig& d) {
  per::TrustUpdateRule r;
  r.success_weight = d.success_weight;
  r.failure_weight = d.failure_weight;
  r.forgetting = d.forgetting;
  r.quality.nudge_go = d.quality.nudge_go;
  r.quality.nudge_stop = d.quality.nudge_stop;
  r.quality.still_stop = d.quality.still_stop;
  r.quality.still_go = d.quality.still_go;
  r.quality.collision = d.quality.collision;
  return r;
}

per::ExplorationSchedule ToModel(const LearningConfig& l) {
  per::ExplorationSchedule s;
  s.delta = l.delta;
  s.decay = l.constant_level ? std::numeric_limits<double>::infinity() : l.decay;
  s.probe = l.probe;
  return s;
}

per::TrustPrior ToModel(const TrustSpec& t) {
  switch (t.dist) {
    case TrustDist::kBeta:
      return per::TrustPrior::Beta(t.alpha, t.beta);
    case TrustDist::kDiscrete: {
      std::vector<double> w;
      for (std::size_t i = 0; i < t.values.size(); ++i) w.push_back(t.Weight(i));
      return per::TrustPrior::Discrete(t.values, w);
    }
    case TrustDist::kUniform: {
      if (t.low == t.high) return per::TrustPrior::Discrete({t.low}, {1.0});
      if (t.low == 0.0 && t.high == 1.0) return per::TrustPrior::Beta(1.0, 1.0);
      constexpr int kCells = 1000;
      std::vector<double> w(kCells, 0.0);
      for (int k = 0; k < kCells; ++k) {
        const double a = static_cast<double>(k) / kCells, b = static_cast<double>(k + 1) / kCells;
        w[k] = std::max(0.0, std::min(b, t.high) - std::max(a, t.low));
      }
      return per::TrustPrior::Histogram(w);
    }
    case TrustDist::kFixed: break;
  }
  return per::TrustPrior::Discrete({t.value}, {1.0});
}

std::unique_ptr<per::LikelihoodModel> MakeLikelihood(const LikelihoodConfig& c) {
  switch (c.type) {
    case LikelihoodType::kLogistic:
      return std::make_unique<per::LogisticLikelihood>(c.s_max, c.steepness, c.midpoint);
    case LikelihoodType::kLinear: break;
  }
  return std::make_unique<per::LinearLikelihood>(c.s_max);
}

per::ExperienceRule ToModel(const ExperienceConfig& e) {
  per::ExperienceRule r;
  r.strength = e.strength;
  r.bin_width = e.bin_width;
  r.forgetting = e.forgetting;
  return r;
}

}  // namespace taebp
