// The totals of a run's HV population (HvPopulation::Results): trust, the
// oracle, and per model beyond the paper its long run (experience, dynamic
// trust), what the fleet learned, the design under noise.
#include "taebp/encounter/hv_population.h"

#include "trust_inside.h"

#include "taebp/config/model.h"
#include "taebp/encounter/design.h"
#include "taebp/base/number_text.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace taebp {
namespace {

namespace per = persuasion;
using per::Policy;

}  // namespace

BeyondRun HvPopulation::Results(double end) {
  BeyondRun out;
  out.on = beyond_;
  if (!beyond_) return out;
  if (end >= config_.scenario.warmup && last_sample_ < end - 1e-9) {
    next_sample_ = end;
    Sample(end);
  }
  out.samples = spool_;
  out.hvs = hvs_added_;
  out.trust_moves = dynamic_ || experience_.has_value();
  const ModelConfig& m = config_.model;
  out.initial_mean_trust = hvs_added_ ? trust_sum_ / static_cast<double>(hvs_added_) : kNoValue;
  double sum = 0;
  for (const auto& [id, h] : hvs_) sum += h.state ? h.state->Mean() : h.trust0;
  out.final_mean_trust = hvs_.empty() ? kNoValue : sum / static_cast<double>(hvs_.size());
  out.oracle = ExpectedOver(m.trust, [&](double theta) {
    return Predict(OracleScheme(theta, PlayedKind()), theta, PlayedKind());
  });
  encounter_theory_ = dynamic_ || learned_ || experience_.has_value();
  if (experience_) ExperienceLongRun(&out);
  if (design_rule_) DynamicsLongRun(&out);
  if (learned_) LearningResults(&out);
  if (noise_) NoiseResults(&out);
  return out;
}

void HvPopulation::ExperienceLongRun(BeyondRun* result) const {
  BeyondRun& out = *result;
  const ModelConfig& m = config_.model;
  // The long run of the learned beliefs (LongRunUnderExperience): guarded
  // ta_ebp recovers the paper's rates (the guard binds on a vanishing share).
  // A learner that forgets never settles: its stationary normal
  // approximation (ExperiencePath, rho < 1). Of the one kind of game the run
  // played: a run of both kinds mixes two schemes in each HV's experience,
  // which these long runs do not model (the cells stay empty).
  out.experience = true;
  const GameKind kind = PlayedKind();
  const per::AvHvParams& params = Params(kind);
  double dc = 0, coll = 0;
  const bool forgets = experience_->forgetting < 1.0;
  // Each HV's k, equally likely (only a forgetting learner's long run needs it).
  const std::vector<double> ks = m.experience->strengths.empty()
                                     ? std::vector<double>{experience_->strength}
                                     : m.experience->strengths;
  if (NoTheory() || MixedKinds()) dc = coll = kNoValue;
  else for (const auto& [theta, w] : TrustNodes(m.trust, 64)) {
    const per::CommittedScheme sc = SchemeAt(DesignTrustFor(theta), kind);
    per::PredictedOutcome o;
    if (forgets) {
      for (const double k : ks) {
        const per::PredictedOutcome at_k =
            per::ExperiencePath(sc, params, theta, *model_, k, false, experience_->forgetting,
                                experience_->bin_width)
                .At(1000000);
        o.dc_rate += at_k.dc_rate / static_cast<double>(ks.size());
        o.collision_rate += at_k.collision_rate / static_cast<double>(ks.size());
      }
    } else {
      o = guarded_ ? per::PredictOutcome(sc, params, theta, *model_)
                   : per::LongRunUnderExperience(sc, params, theta, *model_).outcome;
    }
    dc += w * o.dc_rate;
    coll += w * o.collision_rate;
  }
  out.long_run_dc = dc;
  out.long_run_collision = coll;
}

void HvPopulation::DynamicsLongRun(BeyondRun* result) const {
  BeyondRun& out = *result;
  const ModelConfig& m = config_.model;
  // The long run: where the mean-field drift G of each HV's trust changes
  // sign (FindLongRunTrust), for the population's mean initial state, and
  // each HV's attractor from its own initial trust, averaged over the
  // trust distribution. Of the one kind of game the run played (a run of both
  // kinds drifts by their mix, which this does not model: the cells stay
  // empty; the mean-field twin follows the kinds as played).
  out.long_run = true;
  const per::DesignRule& rule = *design_rule_;
  const per::AvHvParams& params = Params(PlayedKind());
  double mf = 0;
  for (const auto& [id, h] : hvs_) mf += h.mean_field->Mean();
  out.final_mean_field = hvs_.empty() ? kNoValue : mf / static_cast<double>(hvs_.size());
  const double strength = m.trust_dynamics->strength;
  out.design_rule = PolicyName(rule.policy);
  if (rule.policy == Policy::kTaEbp)
    out.design_rule += rule.assumed_trust ? " for theta_hat = " + NumberText(*rule.assumed_trust, 6)
                                          : " tracking the HV's trust";
  if (MixedKinds()) {
    out.expected_long_run_mean = out.long_run_dc = out.long_run_collision = kNoValue;
    return;
  }
  auto initial = [&](double theta) {
    const double mean = Inside01(theta);
    return std::pair<double, double>(mean * strength, (1.0 - mean) * strength);
  };
  const auto [a_bar, b_bar] = initial(m.trust.Mean());
  const per::LongRunTrust lr =
      per::FindLongRunTrust(rule, params, *model_, rule_, a_bar, b_bar);
  for (const per::TrustEquilibrium& e : lr.equilibria)
    out.equilibria.push_back({e.theta, per::ToString(e.kind), e.stable});
  // Without forgetting G does not depend on (alpha0, beta0): one scan serves
  // every HV. With forgetting each initial state has its own.
  std::map<double, double> attractor_of;
  auto attractor = [&](double theta0) {
    const auto cached = attractor_of.find(theta0);
    if (cached != attractor_of.end()) return cached->second;
    const auto [a0, b0] = initial(theta0);
    const per::LongRunTrust own =
        rule_.forgetting > 0 ? per::FindLongRunTrust(rule, params, *model_, rule_, a0, b0) : lr;
    const double x = Inside01(theta0);
    const double g = per::MeanDrift(x, rule, params, *model_, rule_, a0, b0);
    double to = x;
    if (g > 0) {
      to = 1.0;
      for (const per::TrustEquilibrium& e : own.equilibria)
        if (e.stable && e.theta >= x) {
          to = e.theta;
          break;
        }
    } else if (g < 0) {
      to = 0.0;
      for (auto e = own.equilibria.rbegin(); e != own.equilibria.rend(); ++e)
        if (e->stable && e->theta <= x) {
          to = e->theta;
          break;
        }
    }
    attractor_of.emplace(theta0, to);
    return to;
  };
  double mean = 0, dc = 0, coll = 0;
  for (const auto& [theta0, w] : TrustNodes(m.trust, 64)) {
    const double to = attractor(theta0);
    mean += w * to;
    const per::PredictedOutcome o =
        per::PredictOutcome(per::SchemeFor(rule, params, to, *model_), params, to, *model_);
    dc += w * o.dc_rate;
    coll += w * o.collision_rate;
  }
  out.expected_long_run_mean = mean;
  out.long_run_dc = dc;
  out.long_run_collision = coll;
}

void HvPopulation::LearningResults(BeyondRun* result) const {
  BeyondRun& out = *result;
  out.learning = true;
  double err = 0;
  long met = 0;
  for (const auto& [id, belief] : fleet_->All()) {
    ++out.hvs_met;
    out.observations += belief.Observations();
    out.contradictions += belief.Contradictions();
    const auto t = met_trust_.find(id);
    if (t != met_trust_.end()) {
      err += std::abs(belief.Mean() - t->second);
      ++met;
    }
  }
  out.probes = probes_;
  out.final_mean_abs_error = met ? err / static_cast<double>(met) : kNoValue;
}

void HvPopulation::NoiseResults(BeyondRun* result) const {
  BeyondRun& out = *result;
  const ModelConfig& m = config_.model;
  out.noise = true;
  const NoiseConfig& n = *m.noise;
  out.noise_kind = EnumName(n.kind);
  out.noise_design = EnumName(n.design);
  out.noise_scale = n.scale;
  out.noise_bias = n.bias;
  out.noise_delta = n.delta;
  // The population's design (TA-EBP for the mean trust) under this noise.
  const per::NoiseAwareDesign nd =
      per::DesignUnderNoise(Params(PlayedKind()), m.trust.Mean(), *model_, *noise_, n.delta);
  out.noise_status = per::ToString(nd.status);
  out.noise_nudge = nd.nudge;
  out.noise_b = nd.b;
  out.noise_persuasion = nd.persuasion_probability;
  out.noise_density_ratio = nd.density_ratio;
  out.noise_credible = nd.credible;
}

}  // namespace taebp
