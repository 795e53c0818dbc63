#include "taebp/encounter/design.h"

#include <utility>
#include <vector>

namespace taebp {

using persuasion::Policy;

double DesignTrust(const ModelConfig& model, Policy policy, double theta) {
  if (policy == Policy::kNoTrust) return 1.0;
  if (policy == Policy::kPopulationMean) return model.trust.Mean();
  if (policy == Policy::kTaEbpLearned) return theta;
  const TrustKnowledge k = model.Knowledge();
  if (k == TrustKnowledge::kAssumed) return model.assumed_trust.value_or(theta);
  if (k == TrustKnowledge::kPopulationMean) return model.trust.Mean();
  return theta;
}

std::vector<std::pair<double, double>> TrustNodes(const TrustSpec& t, int points) {
  std::vector<std::pair<double, double>> nodes;  // (theta, weight)
  if (t.IsFixed()) {
    nodes.emplace_back(t.value, 1.0);
  } else if (t.dist == TrustDist::kDiscrete) {
    const double total = t.TotalWeight();
    for (std::size_t i = 0; i < t.values.size(); ++i)
      nodes.emplace_back(t.values[i], t.Weight(i) / total);
  } else {
    for (int j = 0; j < points; ++j) nodes.emplace_back(t.Quantile((j + 0.5) / points), 1.0 / points);
  }
  return nodes;
}

persuasion::PredictedOutcome ExpectedOver(
    const TrustSpec& trust, const std::function<persuasion::PredictedOutcome(double)>& at,
    int points) {
  if (trust.IsFixed()) return at(trust.value);
  persuasion::PredictedOutcome e;
  for (const auto& [theta, w] : TrustNodes(trust, points)) {
    const auto o = at(theta);
    e.dc_rate += w * o.dc_rate;
    e.collision_rate += w * o.collision_rate;
    e.nudge_rate += w * o.nudge_rate;
    e.av_first_rate += w * o.av_first_rate;
  }
  return e;
}

persuasion::PredictedOutcome ExpectedOutcome(const ModelConfig& model, Policy policy, int points) {
  const persuasion::AvHvParams params = ToModel(model);
  const auto lik = MakeLikelihood(model.likelihood);
  auto at = [&](double theta) {
    const auto scheme =
        persuasion::CommitScheme(policy, params, DesignTrust(model, policy, theta), *lik);
    return persuasion::PredictOutcome(scheme, params, theta, *lik);
  };
  return ExpectedOver(model.trust, at, points);
}

}  // namespace taebp
