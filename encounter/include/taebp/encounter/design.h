// What the AV commits to for a configured HV population: the likelihood model
// named by the config, the trust each policy designs for, and the theory's
// expected outcome over the trust distribution. SUMO-free.
#pragma once

#include "taebp/config/config.h"
#include "taebp/config/model.h"  // MakeLikelihood
#include "taebp/persuasion/outcomes.h"

#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace taebp {

// The AV's design trust theta_hat for an HV of true trust `theta` under
// `policy` and the config's trust_knowledge (no_trust: 1; population_mean:
// the mean of model.trust whatever the knowledge; ta_ebp_learned: theta, the
// oracle's, as the learned bound is not a function of theta).
double DesignTrust(const ModelConfig& model, persuasion::Policy policy, double theta);

// The nodes (theta, weight) of an expectation over the trust distribution:
// the value itself (fixed), the atoms (discrete), else the quantile midpoint
// rule with `points` nodes. Weights sum to 1.
std::vector<std::pair<double, double>> TrustNodes(const TrustSpec& trust, int points);

// E[at(theta)] over the trust distribution (TrustNodes).
persuasion::PredictedOutcome ExpectedOver(
    const TrustSpec& trust, const std::function<persuasion::PredictedOutcome(double)>& at,
    int points = 4000);

// Expected outcome over the trust distribution (quantile midpoint rule with
// `points` nodes; exact for fixed and discrete trust).
persuasion::PredictedOutcome ExpectedOutcome(const ModelConfig& model, persuasion::Policy policy,
                                             int points = 4000);


}  // namespace taebp
