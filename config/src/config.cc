#include "taebp/config/config.h"
#include "taebp/config/model.h"

#include "taebp/base/number_text.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/random.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace taebp {
namespace {

// "population_mean, ta_ebp_learned": the policies defined beyond the paper.
std::string BeyondPaperPolicies() {
  std::string out;
  for (const PolicyInfo& p : Policies())
    if (p.beyond_paper) out += (out.empty() ? "" : ", ") + std::string(p.name);
  return out;
}


// Collects the first failure; keeps IsValid readable.
class Checker {
 public:
  explicit Checker(std::string* why) : why_(why) {}
  bool ok() const { return ok_; }
  void Fail(const std::string& msg) {
    if (!ok_) return;
    ok_ = false;
    if (why_) *why_ = msg;
  }
  // A model struct's own check (its IsValid), its message after the config
  // section's key: "model.trust_dynamics." + "forgetting rho = 1.5 is ...".
  template <typename M>
  void Model(const std::string& section, const M& model) {
    std::string why;
    if (!model.IsValid(&why)) Fail(section + why);
  }
  void Positive(const char* key, double v) {
    if (!(std::isfinite(v) && v > 0)) Fail(std::string(key) + " = " + NumberText(v, 10) + " must be > 0");
  }
  void NonNegative(const char* key, double v) {
    if (!(std::isfinite(v) && v >= 0)) Fail(std::string(key) + " = " + NumberText(v, 10) + " must be >= 0");
  }
  void Closed01(const char* key, double v) {
    if (!(v >= 0.0 && v <= 1.0)) Fail(std::string(key) + " = " + NumberText(v, 10) + " is outside [0, 1]");
  }
  void Open01(const char* key, double v) {
    if (!(v > 0.0 && v < 1.0)) Fail(std::string(key) + " = " + NumberText(v, 10) + " is outside (0, 1)");
  }

 private:
  std::string* why_;
  bool ok_ = true;
};

}  // namespace

double TrustSpec::Mean() const {
  if (dist == TrustDist::kUniform) return 0.5 * (low + high);
  if (dist == TrustDist::kBeta) return alpha / (alpha + beta);
  if (dist == TrustDist::kDiscrete) {
    double m = 0;
    for (std::size_t i = 0; i < values.size(); ++i) m += Weight(i) * values[i];
    const double w = TotalWeight();
    return w > 0 ? m / w : 0.0;
  }
  return value;
}

double TrustSpec::TotalWeight() const {
  double total = 0;
  for (std::size_t i = 0; i < values.size(); ++i) total += Weight(i);
  return total;
}

double TrustSpec::Quantile(double q) const {
  q = std::clamp(q, 0.0, 1.0);
  if (dist == TrustDist::kUniform) return low + q * (high - low);
  if (dist == TrustDist::kBeta) {
    if (q <= 0) return 0.0;
    if (q >= 1) return 1.0;
    return persuasion::BetaQuantile(alpha, beta, q);
  }
  if (dist == TrustDist::kDiscrete) {
    const double total = TotalWeight();
    double acc = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
      acc += Weight(i) / total;
      if (q < acc) return values[i];
    }
    return values.empty() ? 0.0 : values.back();
  }
  return value;
}

std::vector<std::string> TrustDistKeys(TrustDist dist) {
  switch (dist) {
    case TrustDist::kUniform: return {"low", "high"};
    case TrustDist::kBeta: return {"alpha", "beta"};
    case TrustDist::kDiscrete: return {"values", "weights"};
    case TrustDist::kFixed: break;
  }
  return {};
}

bool TrustSpec::IsValid(const std::string& key, std::string* why) const {
  Checker c(why);
  if (dist == TrustDist::kFixed) {
    c.Closed01(key.c_str(), value);
  } else if (dist == TrustDist::kUniform) {
    c.Closed01((key + ".low").c_str(), low);
    c.Closed01((key + ".high").c_str(), high);
    if (c.ok() && low > high)
      c.Fail(key + ".low = " + NumberText(low, 10) + " is above " + key + ".high = " + NumberText(high, 10));
  } else if (dist == TrustDist::kBeta) {
    c.Positive((key + ".alpha").c_str(), alpha);
    c.Positive((key + ".beta").c_str(), beta);
  } else {  // discrete
    if (values.empty()) c.Fail(key + ".values is empty");
    for (double v : values) c.Closed01((key + ".values").c_str(), v);
    if (!weights.empty() && weights.size() != values.size())
      c.Fail(key + ".weights has " + std::to_string(weights.size()) + " entries but " + key +
             ".values has " + std::to_string(values.size()));
    double total = 0;
    for (double w : weights) {
      c.NonNegative((key + ".weights").c_str(), w);
      total += w;
    }
    if (c.ok() && !weights.empty() && total <= 0) c.Fail(key + ".weights sum to 0");
  }
  return c.ok();
}

std::string TrustSpec::ToString() const {
  if (dist == TrustDist::kUniform) return "uniform(" + NumberText(low, 10) + "," + NumberText(high, 10) + ")";
  if (dist == TrustDist::kBeta) return "beta(" + NumberText(alpha, 10) + "," + NumberText(beta, 10) + ")";
  if (dist == TrustDist::kDiscrete) {
    std::string s = "discrete(";
    for (std::size_t i = 0; i < values.size(); ++i) {
      s += (i ? "," : "") + NumberText(values[i], 10);
      if (!weights.empty()) s += ":" + NumberText(weights[i], 10);
    }
    return s + ")";
  }
  return NumberText(value, 10);
}

namespace {

// The vehicles, speeds, the step and the duration of a run.
void CheckVehiclesAndTime(const ExperimentConfig& e, Checker& c) {
  const ScenarioConfig& s = e.scenario;
  if (s.avs < 0) c.Fail("scenario.avs = " + std::to_string(s.avs) + " must be >= 0");
  if (s.hvs < 0) c.Fail("scenario.hvs = " + std::to_string(s.hvs) + " must be >= 0");
  for (const auto& [key, n] : {std::pair<const char*, int>{"scenario.avs", s.avs}, {"scenario.hvs", s.hvs}})
    if (c.ok() && n > kMaxVehicles)
      c.Fail(std::string(key) + " = " + std::to_string(n) + " is above " +
             std::to_string(kMaxVehicles) +
             " (SUMO inserts them all in its first step, which cannot be interrupted)");
  if (s.avs >= 0 && s.hvs >= 0 && s.avs + s.hvs == 0)
    c.Fail("scenario.avs + scenario.hvs = 0: the scenario needs at least one vehicle");
  c.Positive("scenario.cruise_speed", s.cruise_speed);
  // A road vehicle: SUMO's physics (and the controller's braking and creep
  // profiles) mean nothing far beyond motorway speeds.
  if (c.ok() && s.cruise_speed > kMaxCruiseSpeed)
    c.Fail("scenario.cruise_speed = " + NumberText(s.cruise_speed, 10) + " m/s is above " +
           NumberText(kMaxCruiseSpeed, 10) + " m/s (" + NumberText(kMaxCruiseSpeed * 3.6, 10) + " km/h)");
  c.NonNegative("scenario.min_gap", s.min_gap);
  c.Positive("scenario.stop_distance", s.stop_distance);
  c.Positive("scenario.step_length", s.step_length);
  if (c.ok() && s.step_length > 1.0)
    c.Fail("scenario.step_length = " + NumberText(s.step_length, 10) + " must be <= 1 s");
  // SUMO counts time in whole milliseconds: it refuses a step below 1 ms and
  // silently rounds any other step to a whole millisecond.
  if (c.ok()) {
    const double ms = s.step_length * 1000.0;
    if (ms < 1.0 - 1e-9)
      c.Fail("scenario.step_length = " + NumberText(s.step_length, 10) +
             " is below SUMO's smallest step, one millisecond (0.001 s)");
    else if (std::abs(ms - std::round(ms)) > 1e-6 * ms)
      c.Fail("scenario.step_length = " + NumberText(s.step_length, 10) +
             " is not a whole number of milliseconds (SUMO would run " +
             NumberText(std::round(ms) / 1000.0, 10) + " s steps)");
  }
  c.Positive("scenario.duration", s.duration);
  if (c.ok() && s.duration < s.step_length)
    c.Fail("scenario.duration = " + NumberText(s.duration, 10) + " is shorter than one step");
  // The run is a whole number of steps: a duration between two would be
  // rounded without a word.
  if (c.ok()) {
    const double steps = s.duration / s.step_length;
    if (std::abs(steps - std::round(steps)) > 1e-6 * std::max(1.0, steps))
      c.Fail("scenario.duration = " + NumberText(s.duration, 10) + " s is not a whole number of steps (" +
             NumberText(steps, 10) + " steps of scenario.step_length = " + NumberText(s.step_length, 10) +
             " s): give " + NumberText(std::floor(steps) * s.step_length, 10) + " or " +
             NumberText(std::ceil(steps) * s.step_length, 10));
  }
  // What the run allocates grows with the simulated time (one record per
  // encounter, about 300 bytes, ~500 an hour on the figure-8, more on a
  // network): bound it, and the number of steps, before anything starts.
  if (c.ok() && s.duration > kMaxDuration)
    c.Fail("scenario.duration = " + NumberText(s.duration, 10) + " s is above " + NumberText(kMaxDuration, 10) +
           " s (" + NumberText(kMaxDuration / 86400.0, 10) +
           " simulated days; split a longer study into seeds or a sweep)");
  if (c.ok() && s.duration / s.step_length > kMaxSteps)
    c.Fail("scenario.duration / scenario.step_length = " + NumberText(s.duration / s.step_length, 10) +
           " steps is above " + NumberText(kMaxSteps, 10));
  if (s.seed > kMaxSeed)
    c.Fail("scenario.seed = " + std::to_string(s.seed) + " is above " + std::to_string(kMaxSeed) +
           " (SUMO takes its seed modulo 2147483647: a larger one would repeat a smaller one's run)");
  c.Positive("scenario.vehicle_length", s.vehicle_length);
  c.Positive("scenario.vehicle_width", s.vehicle_width);
  c.Positive("scenario.accel", s.accel);
  c.Positive("scenario.decel", s.decel);
  c.NonNegative("scenario.meeting_distance", s.meeting_distance);
  c.NonNegative("scenario.confirm_delay", s.confirm_delay);
  c.Positive("scenario.creep_speed", s.creep_speed);
  c.Positive("scenario.loop_length", s.loop_length);
  if (!s.IsNetwork() && c.ok() && s.stop_distance < 1.7 - 1e-9)
    c.Fail("scenario.stop_distance = " + NumberText(s.stop_distance, 10) +
           " is inside the junction: on the figure-8 the stop line is 1.6 m from the centre and "
           "SUMO holds vehicles 0.1 m before it, so it must be >= 1.7");
}

// A network run: its sources, the routes' scale and a generated grid.
void CheckNetwork(const ExperimentConfig& e, Checker& c) {
  const ScenarioConfig& s = e.scenario;
  if (s.IsNetwork()) {
    const int sources = !s.network.empty() + !s.sumocfg.empty() + s.grid.has_value();
    if (sources == 0)
      c.Fail("scenario.kind = 'network' needs one of scenario.network, scenario.sumocfg or "
             "scenario.grid");
    else if (sources > 1)
      c.Fail("scenario.network, scenario.sumocfg and scenario.grid are alternatives: give one");
    if (s.sumocfg.empty() && s.routes.empty() && !s.demand)
      c.Fail("scenario.kind = 'network' has no vehicles: give scenario.routes, scenario.demand "
             "or a scenario.sumocfg with route files");
  }
  if (!(std::isfinite(s.routes_scale) && s.routes_scale > 0.0 && s.routes_scale <= 100.0))
    c.Fail("scenario.routes_scale = " + NumberText(s.routes_scale, 10) + " must be in (0, 100] (SUMO's --scale)");
  if (s.routes_scale != 1.0 && !s.IsNetwork())
    c.Fail("scenario.routes_scale = " + NumberText(s.routes_scale, 10) +
           " applies to scenario.kind = 'network' only (the figure-8 has exact vehicle counts)");
  if (s.grid) {
    const GridConfig& g = *s.grid;
    if (g.columns < 2 || g.rows < 2)
      c.Fail("scenario.grid = " + std::to_string(g.columns) + " x " + std::to_string(g.rows) +
             " junctions: netgenerate needs at least 2 x 2 (scenario.grid.columns, .rows)");
    if (g.columns > 100 || g.rows > 100)
      c.Fail("scenario.grid.columns/rows must be <= 100");
    if (!(g.length >= 20.0 && g.length <= 10000.0))
      c.Fail("scenario.grid.length = " + NumberText(g.length, 10) + " must be in [20, 10000] m");
    if (!(g.attach_length == 0.0 || (g.attach_length >= 20.0 && g.attach_length <= 10000.0)))
      c.Fail("scenario.grid.attach_length = " + NumberText(g.attach_length, 10) +
             " must be 0 or in [20, 10000] m");
    if (g.lanes < 1 || g.lanes > 4)
      c.Fail("scenario.grid.lanes = " + std::to_string(g.lanes) + " must be in 1..4");
    c.Positive("scenario.grid.speed", g.speed);
  }
}

// SUMO's safety measures (scenario.outputs.ssm), the demand, the junctions, the
// AV share, the warm-up and which meetings are games.
void CheckOutputsDemandJunctions(const ExperimentConfig& e, Checker& c) {
  const ScenarioConfig& s = e.scenario;
  if (s.outputs.ssm) {
    const SsmConfig& ssm = *s.outputs.ssm;
    std::string known;
    for (const std::string& m : SsmMeasures()) known += (known.empty() ? "" : ", ") + m;
    if (ssm.measures.empty())
      c.Fail("scenario.outputs.ssm.measures is empty: list at least one of " + known);
    std::set<std::string> seen;
    for (const std::string& m : ssm.measures) {
      if (std::find(SsmMeasures().begin(), SsmMeasures().end(), m) == SsmMeasures().end())
        c.Fail("scenario.outputs.ssm.measures: '" + m +
               "' is not a conflict measure of SUMO 1.15's SSM device (known: " + known + ")");
      if (!seen.insert(m).second)
        c.Fail("scenario.outputs.ssm.measures: '" + m + "' is listed twice");
    }
    c.Positive("scenario.outputs.ssm.thresholds.TTC", ssm.thresholds.ttc);
    c.Positive("scenario.outputs.ssm.thresholds.DRAC", ssm.thresholds.drac);
    c.Positive("scenario.outputs.ssm.thresholds.PET", ssm.thresholds.pet);
    c.NonNegative("scenario.outputs.ssm.junction_radius", ssm.junction_radius);
    // A threshold given for a measure not measured would be silently ignored.
    const SsmThresholds defaults;
    const std::pair<const char*, double> given[] = {
        {"TTC", ssm.thresholds.ttc - defaults.ttc},
        {"DRAC", ssm.thresholds.drac - defaults.drac},
        {"PET", ssm.thresholds.pet - defaults.pet}};
    std::string listed;
    for (const std::string& m : ssm.measures) listed += (listed.empty() ? "" : ", ") + m;
    for (const auto& [m, change] : given)
      if (change != 0 && !ssm.Measures(m))
        c.Fail(std::string("scenario.outputs.ssm.thresholds.") + m + " is set but " + m +
               " is not among scenario.outputs.ssm.measures [" + listed +
               "]: add it there or drop the threshold");
  }
  if (s.demand) {
    const DemandConfig& d = *s.demand;
    if (!(std::isfinite(d.flow) && d.flow > 0 && d.flow <= 3600.0 / s.step_length))
      c.Fail("scenario.demand.flow = " + NumberText(d.flow, 10) +
             " veh/h must be > 0 and at most one vehicle per step and edge");
    if (!(std::isfinite(d.major_flow) && d.major_flow >= 0 &&
          d.major_flow <= 3600.0 / s.step_length))
      c.Fail("scenario.demand.major_flow = " + NumberText(d.major_flow, 10) +
             " veh/h must be >= 0 and at most one vehicle per step and edge");
    if (!(std::isfinite(d.end)))
      c.Fail("scenario.demand.end = " + NumberText(d.end, 10) + " must be a number of seconds");
  }
  {
    const JunctionSelection& j = s.junctions;
    static const std::set<std::string> kTypes = {"allway_stop", "priority_stop", "priority",
                                                 "right_before_left", "unregulated"};
    for (const std::string& t : j.types)
      if (!kTypes.count(t))
        c.Fail("scenario.junctions.types: '" + t +
               "' is not a junction type the rules cover (allway_stop, priority_stop, priority, "
               "right_before_left, unregulated)");
  }
  c.NonNegative("scenario.junctions.max_speed", s.junctions.max_speed);
  if (s.junctions.min_arms < 0 || s.junctions.min_arms > 64)
    c.Fail("scenario.junctions.min_arms = " + std::to_string(s.junctions.min_arms) +
           " must be in [0, 64] (roads meeting at a junction)");
  if (s.av_share) c.Closed01("scenario.av_share", *s.av_share);
  c.NonNegative("scenario.warmup", s.warmup);
  if (c.ok() && s.warmup >= s.duration)
    c.Fail("scenario.warmup = " + NumberText(s.warmup, 10) + " leaves nothing of scenario.duration = " +
           NumberText(s.duration, 10));
  c.Positive("scenario.critical_gap", s.critical_gap);
  if (!s.IsNetwork() && s.encounter_pairs == EncounterPairs::kAll)
    c.Fail("scenario.encounter_pairs = 'all' applies to scenario.kind = 'network' only (the "
           "figure-8's crossing is always the game)");
}

// The major-road game (scenario.major_road).
void CheckMajorRoad(const ExperimentConfig& e, Checker& c) {
  const ScenarioConfig& s = e.scenario;
  const MajorRoadConfig& mr = s.major_road;
  // The figure-8's crossing has no major road: its section is inert there,
  // but a value set in it is a mistake worth naming.
  if (!s.IsNetwork()) {
    const MajorRoadConfig d;
    const std::pair<const char*, bool> set[] = {
        {"yield_cost", mr.yield_cost != d.yield_cost},
        {"comfortable_decel", mr.comfortable_decel != d.comfortable_decel},
        {"reaction_time", mr.reaction_time != d.reaction_time}};
    for (const auto& [key, differs] : set)
      if (differs)
        c.Fail(std::string("scenario.major_road.") + key + " applies to scenario.kind = 'network' "
               "only (the figure-8's crossing has no major road)");
    return;
  }
  {
    c.NonNegative("scenario.major_road.yield_cost", mr.yield_cost);
    if (c.ok() && !(mr.yield_cost < e.model.collision_penalty))
      c.Fail("scenario.major_road.yield_cost = " + NumberText(mr.yield_cost, 10) +
             " must be below model.collision_penalty = " + NumberText(e.model.collision_penalty, 10) +
             " (else keeping its way is dominant for the HV: no signal can make it yield)");
    if (c.ok()) c.Model("scenario.major_road: ", ToModel(e.model, mr));
    c.Positive("scenario.major_road.comfortable_decel", mr.comfortable_decel);
    if (c.ok() && mr.comfortable_decel > s.decel)
      c.Fail("scenario.major_road.comfortable_decel = " + NumberText(mr.comfortable_decel, 10) +
             " m/s^2 is above scenario.decel = " + NumberText(s.decel, 10) +
             " (a yielding HV brakes comfortably, within its type's deceleration)");
    c.NonNegative("scenario.major_road.reaction_time", mr.reaction_time);
    if (c.ok() && !(mr.reaction_time <= 10.0))
      c.Fail("scenario.major_road.reaction_time = " + NumberText(mr.reaction_time, 10) +
             " s is not a reaction (at most 10 s)");
  }
}

// The model: the game's numbers, trust and the HV's reading.
void CheckModel(const ExperimentConfig& e, Checker& c) {
  const ScenarioConfig& s = e.scenario;
  const ModelConfig& m = e.model;
  // The model's sections are checked by the model itself (config/model.h).
  c.Model("model.", ToModel(m));
  {
    std::string why_trust;
    if (!m.trust.IsValid("model.trust", &why_trust)) c.Fail(why_trust);
  }
  if (m.assumed_trust) c.Closed01("model.assumed_trust", *m.assumed_trust);
  if (m.Knowledge() == TrustKnowledge::kAssumed && !m.assumed_trust)
    c.Fail("model.trust_knowledge = 'assumed' needs model.assumed_trust");
  const LikelihoodConfig& l = m.likelihood;
  c.Positive("model.likelihood.s_max", l.s_max);
  if (l.type == LikelihoodType::kLogistic) {
    c.Positive("model.likelihood.steepness", l.steepness);
    if (!(l.midpoint >= 0 && l.midpoint <= l.s_max))
      c.Fail("model.likelihood.midpoint = " + NumberText(l.midpoint, 10) + " is outside [0, s_max]");
  }
  if (c.ok() && l.s_max >= s.stop_distance + 50.0)
    c.Fail("model.likelihood.s_max = " + NumberText(l.s_max, 10) + " is not a nudge (> 50 m past the stop)");
}

// Beyond the paper: dynamic trust, perception noise, learned trust, experience.
void CheckBeyondThePaper(const ExperimentConfig& e, Checker& c) {
  const ModelConfig& m = e.model;
  // Beyond the paper: dynamic trust, perception noise, learned trust.
  if (m.trust_dynamics) {
    const TrustDynamicsConfig& d = *m.trust_dynamics;
    c.Positive("model.trust_dynamics.strength", d.strength);
    c.Model("model.trust_dynamics.", ToModel(d));
    // Each HV's initial state is Beta(mean * strength, (1 - mean) * strength):
    // its drawn trust must lie strictly inside (0, 1).
    const TrustSpec& t = m.trust;
    auto inside = [&](const std::string& key, double v) {
      if (c.ok() && !(v > 0.0 && v < 1.0))
        c.Fail(key + " = " + NumberText(v, 10) +
               " must lie strictly inside (0, 1) with model.trust_dynamics (the HV's trust is the "
               "mean of a Beta distribution)");
    };
    if (t.dist == TrustDist::kFixed) inside("model.trust", t.value);
    if (t.dist == TrustDist::kDiscrete)
      for (double v : t.values) inside("model.trust.values", v);
    if (t.dist == TrustDist::kUniform) {
      inside("model.trust.low", t.low);
      inside("model.trust.high", t.high);
    }
  }
  if (m.noise) {
    const NoiseConfig& n = *m.noise;
    c.Model("model.", ToModel(n));
    c.Open01("model.noise.delta", n.delta);
  }
  const bool learned = std::find(e.policies.begin(), e.policies.end(),
                                 PolicyOf(PolicyKind::kTaEbpLearned).name) != e.policies.end();
  if (m.learning) {
    const LearningConfig& l = *m.learning;
    c.Model("model.learning.", ToModel(l));
    if (l.prior) {
      std::string why_prior;
      if (!l.prior->IsValid("model.learning.prior", &why_prior)) c.Fail(why_prior);
    }
  }
  if (learned && c.ok() && !(m.prior_go < 2.0 / (2.0 + m.collision_penalty)))
    c.Fail("model.prior_go = " + NumberText(m.prior_go, 10) +
           " is at or above p* = 2/(2 + model.collision_penalty) = " +
           NumberText(2.0 / (2.0 + m.collision_penalty), 10) +
           ": every HV drives if clear without persuasion, so " +
           PolicyOf(PolicyKind::kTaEbpLearned).name + " has nothing to learn");
  if (m.experience) {
    c.Model("model.experience.", ToModel(*m.experience));
    for (std::size_t i = 0; i < m.experience->strengths.size(); ++i) {
      const double k = m.experience->strengths[i];
      if (!(std::isfinite(k) && k > 0))
        c.Fail("model.experience.strengths[" + std::to_string(i) + "] = " + NumberText(k, 10) +
               " must be > 0 and finite (an HV's prior strength k)");
    }
    if (!(m.experience->margin >= 0.0 && m.experience->margin < 1.0))
      c.Fail("model.experience.margin = " + NumberText(m.experience->margin, 10) +
             " is outside [0, 1) (robust: the belief's margin above p*)");
    if (m.trust_dynamics || m.learning)
      c.Fail("model.experience is not modelled with model.trust_dynamics or model.learning "
             "(their theories assume an HV whose reading of a nudge never changes); with "
             "model.noise it runs without a theory");
    for (const std::string& p : e.policies) {
      const PolicyInfo* info = FindPolicy(p);
      if (info && info->plays_game &&
          (info->game == persuasion::Policy::kPopulationMean ||
           info->game == persuasion::Policy::kTaEbpLearned))
        c.Fail("policies: '" + p + "' is not modelled with model.experience (use " +
               PolicyOf(PolicyKind::kTaEbp).name + ")");
    }
  }
}

// Outputs, policies, pairing and the sweep.
void CheckPoliciesAndSweep(const ExperimentConfig& e, Checker& c) {
  const ScenarioConfig& s = e.scenario;
  if (!(std::isfinite(e.outputs.interval) && e.outputs.interval >= 1.0))
    c.Fail("outputs.interval = " + NumberText(e.outputs.interval, 10) +
           " must be >= 1 s (the time series are sampled once a simulated second)");

  if (e.policies.empty())
    c.Fail("policies is empty: list at least one of " + PolicyChoices());
  std::set<std::string> seen;
  for (const std::string& p : e.policies) {
    if (!FindPolicy(p)) c.Fail("policies: '" + p + "' is not one of " + PolicyChoices());
    if (!seen.insert(p).second) c.Fail("policies: '" + p + "' is listed twice");
  }
  if (s.paired) {
    const bool game = std::any_of(e.policies.begin(), e.policies.end(), [](const std::string& p) {
      const PolicyInfo* info = FindPolicy(p);
      return info && info->plays_game;
    });
    if (!e.policies.empty() && !game)
      c.Fail("scenario.paired needs a policy that plays the game in policies (" +
             std::string(SumoNative().name) +
             " plays none, so there is no game to pair): add one of " + PolicyChoices() +
             " or set scenario.paired: false");
    if (e.BeyondPaper())
      c.Fail("scenario.paired is modelled in the paper's setting only: not with "
             "model.trust_dynamics, model.noise, model.learning, model.experience or the "
             "policies beyond it (" + BeyondPaperPolicies() + "): an HV's state there comes from "
             "its earlier games under one policy, so a game's branches would not start from the "
             "same state; remove them or set scenario.paired: false");
  }
  if (e.sweep) {
    if (e.sweep->replicates < 1)
      c.Fail("sweep.replicates = " + std::to_string(e.sweep->replicates) + " must be >= 1");
    else if (s.seed <= kMaxSeed &&
             static_cast<std::uint64_t>(e.sweep->replicates) - 1 > kMaxSeed - s.seed)
      c.Fail("sweep.replicates = " + std::to_string(e.sweep->replicates) + " from scenario.seed = " +
             std::to_string(s.seed) + " would reach seed " +
             std::to_string(s.seed + static_cast<std::uint64_t>(e.sweep->replicates) - 1) +
             ", above " + std::to_string(kMaxSeed) + " (SUMO takes its seed modulo 2147483647)");
    for (const auto& [key, values] : e.sweep->grid) {
      if (key.empty()) c.Fail("sweep.grid has an empty key");
      if (key == "sweep" || key.rfind("sweep.", 0) == 0)
        c.Fail("sweep.grid key '" + key + "' cannot sweep the sweep section");
      if (values.empty()) c.Fail("sweep.grid." + key + " has no values");
    }
  }
}

}  // namespace

bool ExperimentConfig::IsValid(std::string* why) const {
  Checker c(why);
  CheckVehiclesAndTime(*this, c);
  CheckNetwork(*this, c);
  CheckOutputsDemandJunctions(*this, c);
  CheckMajorRoad(*this, c);
  CheckModel(*this, c);
  CheckBeyondThePaper(*this, c);
  CheckPoliciesAndSweep(*this, c);
  return c.ok();
}

bool ExperimentConfig::BeyondPaper() const {
  if (model.trust_dynamics || model.noise || model.learning || model.experience) return true;
  for (const std::string& p : policies) {
    const PolicyInfo* info = FindPolicy(p);
    if (info && info->beyond_paper) return true;
  }
  return false;
}

}  // namespace taebp
