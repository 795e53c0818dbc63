#include "taebp/encounter/hv_population.h"

#include "trust_inside.h"

#include "taebp/report/sample_spool.h"

#include "taebp/config/model.h"
#include "taebp/encounter/design.h"
#include "taebp/base/number_text.h"
#include "taebp/persuasion/random.h"
#include "streams.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace taebp {
namespace {

namespace per = persuasion;
using per::Policy;

using namespace streams;  // StreamSeed, IdUniform and the salts

bool TaebpFamily(Policy p) {
  return p == Policy::kTaEbp || p == Policy::kPopulationMean || p == Policy::kTaEbpLearned;
}

}  // namespace

HvPopulation::HvPopulation(const ExperimentConfig& config, Policy policy)
    : config_(config),
      policy_(policy),
      model_(MakeLikelihood(config.model.likelihood)),
      noise_rng_(StreamSeed(config.scenario.seed, kSaltNoise)),
      probe_rng_(StreamSeed(config.scenario.seed, kSaltProbe)),
      magnitude_rng_(StreamSeed(config.scenario.seed, kSaltMagnitude)) {
  const ModelConfig& m = config.model;
  params_ = ToModel(m);
  kinds_[Index(GameKind::kStopLines)].params = params_;
  major_ = config.scenario.MajorRoadGame();
  kinds_[Index(GameKind::kMajorRoad)].params =
      major_ ? ToModel(m, config.scenario.major_road).EquivalentPaperParams() : params_;
  beyond_ = config.BeyondPaper();
  dynamic_ = m.trust_dynamics.has_value();
  learned_ = policy == Policy::kTaEbpLearned;
  if (m.experience) {
    experience_ = ToModel(*m.experience);
    experience_->Validate();
    guarded_ = policy == Policy::kTaEbp && m.experience->design == ExperienceDesign::kGuarded;
    if (policy == Policy::kTaEbp && m.experience->design == ExperienceDesign::kRobust)
      robust_margin_ = m.experience->margin;
  }
  next_sample_ = config.scenario.warmup;
  if (m.noise) {
    noise_ = ToModel(*m.noise);
    noise_aware_ = m.noise->design == NoiseDesign::kAware;
    noise_delta_ = m.noise->delta;
  }
  if (dynamic_) {
    rule_ = ToModel(*m.trust_dynamics);
    rule_.Validate();
    // The mean-field and long-run theory (noise-free models of trust_dynamics.h).
    if (!noise_ && !learned_) {
      per::DesignRule r;
      r.policy = policy == Policy::kPopulationMean ? Policy::kTaEbp : policy;
      if (policy == Policy::kPopulationMean) {
        r.assumed_trust = m.trust.Mean();
      } else if (policy == Policy::kTaEbp) {
        const TrustKnowledge k = m.Knowledge();
        if (k == TrustKnowledge::kPopulationMean) r.assumed_trust = m.trust.Mean();
        if (k == TrustKnowledge::kAssumed) r.assumed_trust = m.assumed_trust;
      }
      design_rule_ = r;
    }
  }
  if (learned_) {
    const LearningConfig l = m.learning.value_or(LearningConfig{});
    schedule_ = ToModel(l);
    schedule_.Validate();
    fleet_ = std::make_unique<per::FleetTrustBeliefs>(ToModel(l.prior.value_or(m.trust)));
  }
  SetUpKind(GameKind::kStopLines);
  if (major_) SetUpKind(GameKind::kMajorRoad);
}

void HvPopulation::SetUpKind(GameKind kind) {
  const ModelConfig& m = config_.model;
  Kind& k = kinds_[Index(kind)];
  if (learned_) {
    const per::TrustBelief fresh(std::make_shared<per::TrustPrior>(fleet_->Population()));
    // The design for an HV never met, without a probe.
    const per::LearnedDesign ld =
        per::ChooseLearnedDesign(fresh, k.params, *model_, schedule_, std::nextafter(1.0, 0.0));
    k.population_scheme = ld.mode == per::LearnedDesign::Mode::kDesign
                              ? (noise_aware_ ? SchemeAt(ld.design_trust, kind) : ld.scheme)
                              : ld.scheme;
    return;
  }
  k.population_scheme = SchemeAt(DesignTrustFor(m.trust.Mean()), kind);
  if (dynamic_) return;
  // The a-priori expectation over the trust distribution (and the noise).
  if (noise_) {
    k.theory = ExpectedOver(m.trust, [&](double theta) {
      return Predict(SchemeAt(DesignTrustFor(theta), kind), theta, kind);
    });
  } else {
    ModelConfig game = m;  // the paper's game at this kind's penalty
    game.collision_penalty = k.params.collision_penalty;
    k.theory = ExpectedOutcome(game, policy_);
  }
}

per::PredictedOutcome HvPopulation::Theory() const {
  if (encounter_theory_) return EncounterTheory();
  const long stop = totals_.of_kind[0], major = totals_.of_kind[1];
  if (major == 0) return kinds_[0].theory;
  if (stop == 0) return kinds_[1].theory;
  const double w = static_cast<double>(major) / static_cast<double>(stop + major);
  const per::PredictedOutcome& a = kinds_[0].theory;
  const per::PredictedOutcome& b = kinds_[1].theory;
  per::PredictedOutcome o;
  o.dc_rate = (1 - w) * a.dc_rate + w * b.dc_rate;
  o.collision_rate = (1 - w) * a.collision_rate + w * b.collision_rate;
  o.nudge_rate = (1 - w) * a.nudge_rate + w * b.nudge_rate;
  o.av_first_rate = (1 - w) * a.av_first_rate + w * b.av_first_rate;
  return o;
}

HvPopulation::~HvPopulation() = default;

double HvPopulation::DesignTrustFor(double theta) const {
  return DesignTrust(config_.model, policy_, theta);
}

per::CommittedScheme HvPopulation::SchemeAt(double theta_hat, GameKind kind) const {
  const per::AvHvParams& params = Params(kind);
  if (robust_margin_) return per::DesignRobust(params, theta_hat, *model_, *robust_margin_).scheme;
  if (noise_ && noise_aware_ && TaebpFamily(policy_))
    return per::DesignUnderNoise(params, theta_hat, *model_, *noise_, noise_delta_).scheme;
  return per::CommitScheme(policy_, params, theta_hat, *model_);
}

per::CommittedScheme HvPopulation::OracleScheme(double theta, GameKind kind) const {
  const per::AvHvParams& params = Params(kind);
  if (noise_ && noise_aware_)
    return per::DesignUnderNoise(params, theta, *model_, *noise_, noise_delta_).scheme;
  return per::CommitScheme(Policy::kTaEbp, params, theta, *model_);
}

per::PredictedOutcome HvPopulation::Predict(const per::CommittedScheme& scheme, double theta,
                                            GameKind kind) const {
  if (noise_) return per::PredictOutcomeUnderNoise(scheme, Params(kind), theta, *model_, *noise_);
  return per::PredictOutcome(scheme, Params(kind), theta, *model_);
}

HvPopulation::KindDesign HvPopulation::DesignFor(double trust, GameKind kind) const {
  KindDesign d;
  d.design_trust = DesignTrustFor(trust);
  d.scheme = SchemeAt(d.design_trust, kind);
  d.theory = Predict(d.scheme, trust, kind);
  if (beyond_) d.oracle = Predict(OracleScheme(trust, kind), trust, kind);
  return d;
}

per::ExperiencePath& HvPopulation::PathFor(double theta_hat, double theta, double strength,
                                           GameKind kind) {
  auto& slot = paths_[{theta_hat, theta, strength, Index(kind)}];
  if (!slot)
    slot = std::make_unique<per::ExperiencePath>(
        SchemeAt(theta_hat, kind), Params(kind), theta, *model_, strength, guarded_,
        experience_->forgetting, experience_->bin_width, experience_->strength);
  return *slot;
}

void HvPopulation::Add(const std::string& hv, double trust) {
  Hv h;
  h.trust0 = trust;
  if (experience_) {
    h.strength = StrengthOf(hv);
    h.experience.emplace(experience_->bin_width, experience_->forgetting);
    // What the AVs know of it: the public history, counted exactly (the
    // guarded design assumes the rule of issue 29; the HV may forget).
    if (guarded_ && (experience_->forgetting < 1.0 || noise_))
      h.history.emplace(experience_->bin_width, 1.0);
  }
  if (dynamic_) {
    const double strength = config_.model.trust_dynamics->strength;
    h.state = per::BetaTrust::FromMean(Inside01(trust), strength);
    h.mean_field = h.state;
  } else if (!learned_) {
    // Static trust: one design per HV and kind, as the paper's controller had it.
    h.cached = true;
    h.design[Index(GameKind::kStopLines)] = DesignFor(trust, GameKind::kStopLines);
    if (major_) h.design[Index(GameKind::kMajorRoad)] = DesignFor(trust, GameKind::kMajorRoad);
  }
  if (learned_) met_trust_[hv] = trust;
  hvs_[hv] = std::move(h);
  ++hvs_added_;
  trust_sum_ += trust;
}

void HvPopulation::Remove(const std::string& hv) { hvs_.erase(hv); }

double HvPopulation::GoSignal(const std::string& hv, GameKind kind) const {
  const auto go = [](const per::CommittedScheme& sc) { return sc.a > 0 ? sc.nudge : 0.0; };
  const auto it = hvs_.find(hv);
  if (it == hvs_.end() || learned_) return go(PopulationScheme(kind));
  const Hv& h = it->second;
  if (h.cached) return go(h.design[Index(kind)].scheme);
  return go(SchemeAt(DesignTrustFor(h.state ? h.state->Mean() : h.trust0), kind));
}

double HvPopulation::Trust(const std::string& hv) const {
  const auto it = hvs_.find(hv);
  if (it == hvs_.end()) throw std::logic_error("HvPopulation: HV '" + hv + "' is not in the network");
  return it->second.state ? it->second.state->Mean() : it->second.trust0;
}

const per::CommittedScheme& HvPopulation::Commit(const std::string& av, const std::string& hv,
                                                 GameKind kind) {
  const auto it = hvs_.find(hv);
  if (it == hvs_.end()) throw std::logic_error("HvPopulation: HV '" + hv + "' is not in the network");
  if (kind == GameKind::kMajorRoad && !major_)
    throw std::logic_error("HvPopulation: a major-road game without scenario.major_road");
  Hv& h = it->second;
  const per::AvHvParams& params = Params(kind);
  Pending p;
  p.kind = kind;
  p.trust = h.state ? h.state->Mean() : h.trust0;
  if (learned_) {
    const double u = per::Uniform01(probe_rng_);  // one per encounter, whatever the mode
    const per::TrustBelief& belief = fleet_->For(hv);
    p.belief_lower = belief.Lower();
    p.belief_upper = belief.Upper();
    const per::LearnedDesign ld = per::ChooseLearnedDesign(belief, params, *model_, schedule_, u);
    p.scheme = ld.scheme;
    p.design_trust = ld.design_trust;
    if (noise_ && noise_aware_ && ld.mode != per::LearnedDesign::Mode::kFallback)
      p.scheme = SchemeAt(ld.design_trust, kind);
    if (ld.mode == per::LearnedDesign::Mode::kProbe) ++probes_;
    p.learned = ld;
  } else if (h.cached) {
    const KindDesign& d = h.design[Index(kind)];
    p.scheme = d.scheme;
    p.design_trust = d.design_trust;
    p.theory = d.theory;
    p.oracle = d.oracle;
    if (experience_) {
      // The expected outcome of this HV's encounter number h.encounters over
      // its learning path; ta_ebp guarded: the design for what it learned.
      // Where it is not modelled (NoTheory, or an HV that has met both kinds
      // of game: its path mixes two schemes) the theory cells stay empty.
      const bool other_kind = (h.kinds_met & ~(1 << Index(kind))) != 0;
      p.theory = NoTheory() || other_kind
                     ? Unmodelled()
                     : PathFor(d.design_trust, h.trust0, h.strength, kind).At(h.encounters);
      if (guarded_) {
        const per::SignalExperience& e = h.history ? *h.history : *h.experience;
        p.scheme = per::DesignForExperience(d.scheme, params, d.design_trust, *model_,
                                            experience_->strength,
                                            [&](double s) { return e.At(s); })
                       .scheme;
      }
    }
  } else {
    p.design_trust = DesignTrustFor(p.trust);
    p.scheme = SchemeAt(p.design_trust, kind);
  }
  if (!h.cached) {
    p.theory = Predict(p.scheme, p.trust, kind);
    if (beyond_) p.oracle = Predict(OracleScheme(p.trust, kind), p.trust, kind);
  }
  if (policy_ == Policy::kNoEbp || policy_ == Policy::kFullReveal ||
      policy_ == Policy::kRandomNudge)
    p.design_trust = kNoValue;
  Pending& slot = pending_[{av, hv}];
  slot = std::move(p);
  return slot.scheme;
}

bool HvPopulation::NoTheory() const {
  return experience_ && ((guarded_ && experience_->forgetting < 1.0) || noise_);
}

per::PredictedOutcome HvPopulation::Unmodelled() {
  per::PredictedOutcome o;
  o.dc_rate = o.collision_rate = o.nudge_rate = o.av_first_rate = kNoValue;
  return o;
}

double HvPopulation::StrengthOf(const std::string& hv) const {
  const std::vector<double>& ks = config_.model.experience->strengths;
  if (ks.empty()) return experience_->strength;
  const double u = IdUniform(config_.scenario.seed, hv, kSaltStrength);
  return ks[std::min(ks.size() - 1, static_cast<std::size_t>(u * static_cast<double>(ks.size())))];
}

double HvPopulation::Strength(const std::string& hv) const {
  const auto it = hvs_.find(hv);
  if (it == hvs_.end()) throw std::logic_error("HvPopulation: HV '" + hv + "' is not in the network");
  return it->second.strength;
}

double HvPopulation::Magnitude(const per::CommittedScheme& scheme) {
  return scheme.random_magnitude ? per::NudgeMagnitude(scheme, per::Uniform01(magnitude_rng_))
                                 : scheme.nudge;
}

HvReading HvPopulation::Read(const std::string& av, const std::string& hv, double observed) {
  const auto it = pending_.find({av, hv});
  if (it == pending_.end())
    throw std::logic_error("HvPopulation: no encounter of " + av + " and " + hv + " to read");
  Pending& p = it->second;
  const per::AvHvParams& params = Params(p.kind);
  if (experience_) {
    // What this HV learned of the level it read (SUMO's displacement).
    const auto h = hvs_.find(hv);
    if (h == hvs_.end() || !h->second.experience)
      throw std::logic_error("HvPopulation: HV '" + hv + "' has no experience to read with");
    HvReading r;
    r.observed = observed;
    // model.noise: what it perceived (one draw of the noise stream).
    p.reading = noise_ ? per::NoisyReading(*noise_, observed, model_->SMax(), per::Uniform01(noise_rng_))
                       : std::clamp(observed, 0.0, model_->SMax());
    r.posterior = per::ExperiencedBelief(p.scheme, params, p.trust, *model_, p.reading,
                                         h->second.experience->At(p.reading), h->second.strength);
    r.drives_if_clear = per::HvDrivesIfClear(params, r.posterior);
    return r;
  }
  if (!noise_) {
    const HvReading r = ReadNudge(p.scheme, params, p.trust, *model_, observed);
    p.reading = std::clamp(observed, 0.0, model_->SMax());
    return r;
  }
  // The noise is added to what SUMO realised, never to the command.
  const double u = per::Uniform01(noise_rng_);
  p.reading = per::NoisyReading(*noise_, observed, model_->SMax(), u);
  HvReading r;
  r.observed = observed;
  r.posterior = per::HvPosteriorGo(p.scheme, params, p.trust, *model_, p.reading);
  r.drives_if_clear = per::HvDrivesIfClear(params, r.posterior);
  return r;
}

void HvPopulation::Finish(const std::string& av, const std::string& hv, const AvDraw& draw,
                          const HvReading& reading, bool collision, bool counted,
                          EncounterRecord* record) {
  const auto it = pending_.find({av, hv});
  if (it == pending_.end())
    throw std::logic_error("HvPopulation: no encounter of " + av + " and " + hv + " to finish");
  const Pending p = std::move(it->second);
  pending_.erase(it);
  record->hv_trust = p.trust;
  record->theory_dc = p.theory.dc_rate;
  record->theory_collision = p.theory.collision_rate;

  const bool nudged = draw.nudge_distance > 0.0;
  const per::EncounterOutcome outcome =
      per::ClassifyEncounter(nudged, draw.goes_first, collision, /*near_miss=*/false);
  BeyondEncounter& b = record->beyond;
  b.design_trust = p.design_trust;
  b.scheme_b = p.scheme.b;
  b.reading = p.reading;
  b.trust_after = p.trust;
  b.outcome = per::ToString(outcome);
  b.oracle_dc = p.oracle.dc_rate;
  b.oracle_collision = p.oracle.collision_rate;
  b.regret = (p.oracle.dc_rate - p.theory.dc_rate) +
             params_.collision_penalty * (p.theory.collision_rate - p.oracle.collision_rate);
  if (p.learned) {
    const per::LearnedDesign& ld = *p.learned;
    b.mode = per::ToString(ld.mode);
    b.risk_level = ld.risk_level;
    b.failure_probability = ld.failure_probability;
    b.belief_lower = p.belief_lower;
    b.belief_upper = p.belief_upper;
    // The AV knows the displacement it realised, not the HV's (noisy) reading.
    // Without a signalling scheme the HV reads the prior: nothing to learn.
    per::ObservationEffect effect = per::ObservationEffect::kUninformative;
    if (p.scheme.Signals())
      effect = fleet_->For(hv).Observe(Params(p.kind), *model_,
                                       std::clamp(reading.observed, 0.0, model_->SMax()),
                                       reading.drives_if_clear);
    b.observation = per::ToString(effect);
  }
  const auto hit = hvs_.find(hv);
  if (hit != hvs_.end()) {
    Hv& h = hit->second;
    ++h.encounters;
    h.kinds_met |= 1 << Index(p.kind);
    // It saw what SUMO showed it: the displacement it read, then whether the
    // AV took the right of way.
    // The HV files it under the level it perceived (p.reading: SUMO's
    // displacement, plus its noise under model.noise); the AVs' public
    // history under the displacement SUMO realised.
    if (h.experience) h.experience->Record(p.reading, draw.goes_first);
    if (h.history) h.history->Record(std::clamp(reading.observed, 0.0, model_->SMax()), draw.goes_first);
    if (h.state) {
      b.quality = rule_.quality.Of(outcome);
      h.state->Update(outcome, rule_);
      b.trust_after = h.state->Mean();
      if (design_rule_)
        h.mean_field->Update(per::ExpectedQuality(*design_rule_, Params(p.kind), h.mean_field->Mean(),
                                                  *model_, rule_.quality),
                             rule_);
    }
  }
  if (!counted) return;
  Totals& t = totals_;
  ++t.encounters;
  ++t.of_kind[Index(p.kind)];
  t.dc += reading.drives_if_clear;
  t.collisions += collision;
  t.nudges += nudged;
  t.failures += nudged && !reading.drives_if_clear;
  t.theory_dc += p.theory.dc_rate;
  t.theory_collisions += p.theory.collision_rate;
  t.oracle_dc += p.oracle.dc_rate;
  t.oracle_collisions += p.oracle.collision_rate;
  t.regret += b.regret;
  if (p.learned && nudged) t.expected_failures += p.learned->failure_probability;
}

void HvPopulation::Sample(double now) {
  if (!beyond_ || now + 1e-9 < next_sample_) return;
  const double interval = config_.outputs.interval;
  while (next_sample_ <= now + 1e-9) next_sample_ += interval;
  last_sample_ = now;
  TimeSample s;
  s.time = now;
  s.hvs = static_cast<long>(hvs_.size());
  double sum = 0, mf = 0;
  for (const auto& [id, h] : hvs_) {
    sum += h.state ? h.state->Mean() : h.trust0;
    if (h.mean_field) mf += h.mean_field->Mean();
  }
  s.mean_trust = s.hvs ? sum / s.hvs : kNoValue;
  if (design_rule_) s.mean_field_trust = s.hvs ? mf / s.hvs : kNoValue;
  const Totals& t = totals_;
  s.encounters = t.encounters;
  s.dc = t.dc;
  s.collisions = t.collisions;
  s.nudges = t.nudges;
  s.failures = t.failures;
  s.theory_dc = t.theory_dc;
  s.theory_collisions = t.theory_collisions;
  s.oracle_dc = t.oracle_dc;
  s.oracle_collisions = t.oracle_collisions;
  s.regret = t.regret;
  s.expected_failures = t.expected_failures;
  if (!spool_) spool_ = std::make_shared<SampleSpool>("", "");  // unnamed files
  spool_->Add(s);
  if (!config_.outputs.per_hv) return;
  std::optional<per::TrustBelief> fresh;
  for (const auto& [id, h] : hvs_) {
    HvSample hs;
    hs.time = now;
    hs.hv = id;
    hs.trust = h.state ? h.state->Mean() : h.trust0;
    hs.encounters = h.encounters;
    if (learned_) {
      const per::TrustBelief* belief = fleet_->Find(id);
      if (!belief) {
        if (!fresh) fresh.emplace(std::make_shared<per::TrustPrior>(fleet_->Population()));
        belief = &*fresh;
      }
      hs.belief_lower = belief->Lower();
      hs.belief_upper = belief->Upper();
      hs.belief_mean = belief->Mean();
      hs.design_trust = belief->LowerBound(schedule_.Level(belief->Observations()));
      hs.observations = belief->Observations();
      hs.contradictions = belief->Contradictions();
    }
    spool_->Add(hs);
  }
}

per::PredictedOutcome HvPopulation::EncounterTheory() const {
  per::PredictedOutcome o;
  if (totals_.encounters == 0) return o;
  const double n = static_cast<double>(totals_.encounters);
  o.dc_rate = totals_.theory_dc / n;
  o.collision_rate = totals_.theory_collisions / n;
  return o;
}

}  // namespace taebp
