// Experiment configuration: plain structs with defaults at the field, one schema
// (Serialize) used for loading, saving and provenance, and IsValid() checks.
// All YAML parsing lives in config_yaml.cc (the one loader); this header has no
// yaml-cpp include.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace taebp {

// A configuration error. The message names the file (or --set), the key and
// the offending value.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ScenarioConfig {
  int avs = 8;                  // number of autonomous vehicles (blue)
  int hvs = 8;                  // number of human-driven vehicles (red)
  double cruise_speed = 4.0;    // m/s
  double min_gap = 2.0;         // m, SUMO minGap
  double stop_distance = 3.0;   // m from the front to the centre when held (>= s_max + width/2: README "Geometry")
  double step_length = 0.1;     // s
  double duration = 3600.0;     // simulated seconds per policy
  std::uint64_t seed = 1;       // run seed (SUMO --seed and the controller's RNG)
  double vehicle_length = 5.0;  // m
  double vehicle_width = 1.8;   // m
  double accel = 2.6;           // m/s^2
  double decel = 4.5;           // m/s^2
  double arrival_window = 1.0;  // s: heads ready within this window form an encounter
  double confirm_delay = 1.0;   // s: a DC HV facing a waiting AV waits this long
  double creep_speed = 1.0;     // m/s: top speed of a nudge
  double loop_length = 80.0;    // m per loop of the figure-8 (network generation)
  bool auto_length = true;      // grow the loops when the vehicles do not fit
  std::string network;          // path to a .net.xml; empty: the built-in figure-8

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("avs", &avs);
    a->Visit("hvs", &hvs);
    a->Visit("cruise_speed", &cruise_speed);
    a->Visit("min_gap", &min_gap);
    a->Visit("stop_distance", &stop_distance);
    a->Visit("step_length", &step_length);
    a->Visit("duration", &duration);
    a->Visit("seed", &seed);
    a->Visit("vehicle_length", &vehicle_length);
    a->Visit("vehicle_width", &vehicle_width);
    a->Visit("accel", &accel);
    a->Visit("decel", &decel);
    a->Visit("arrival_window", &arrival_window);
    a->Visit("confirm_delay", &confirm_delay);
    a->Visit("creep_speed", &creep_speed);
    a->Visit("loop_length", &loop_length);
    a->Visit("auto_length", &auto_length);
    a->Visit("network", &network);
  }
};

struct LikelihoodConfig {
  std::string type = "linear";  // linear | logistic
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
  std::string dist = "fixed";  // fixed | uniform | beta | discrete
  double value = 0.6;          // fixed
  double low = 0.0, high = 1.0;         // uniform
  double alpha = 1.0, beta = 1.0;       // beta
  std::vector<double> values, weights;  // discrete (weights default to equal)

  static TrustSpec Fixed(double v) {
    TrustSpec t;
    t.value = v;
    return t;
  }
  bool IsFixed() const { return dist == "fixed"; }
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

struct ModelConfig {
  double prior_go = 0.2;           // lambda
  double collision_penalty = 3.0;  // r
  TrustSpec trust = TrustSpec::Fixed(0.6);  // theta of the HVs
  // What the AV knows of each HV's trust when it designs its scheme (ta_ebp):
  // exact (that HV's own theta), population_mean (one design for the mean),
  // assumed (one design for assumed_trust). Empty: assumed if assumed_trust is
  // set, else exact.
  std::string trust_knowledge;
  std::optional<double> assumed_trust;  // theta_hat for trust_knowledge = assumed
  LikelihoodConfig likelihood;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("prior_go", &prior_go);
    a->Visit("collision_penalty", &collision_penalty);
    a->Visit("trust", &trust);
    a->Visit("trust_knowledge", &trust_knowledge);
    a->Visit("assumed_trust", &assumed_trust);
    a->Visit("likelihood", &likelihood);
  }
  // trust_knowledge with the default resolved.
  std::string Knowledge() const {
    if (!trust_knowledge.empty()) return trust_knowledge;
    return assumed_trust ? "assumed" : "exact";
  }
};

// A sweep: a grid over config keys (each point is one `run` of every listed
// policy) times seed replicates. YAML:
//   sweep:
//     replicates: 5            # seeds scenario.seed, +1, ..., +4
//     grid:                    # axes in order; the last varies fastest
//       model.trust: [0.1, 0.2, 0.5]
//       scenario.avs: [0, 8, 16]
// Values are YAML (numbers, lists, maps such as trust distributions).
struct SweepConfig {
  int replicates = 1;
  // (key, values as YAML flow text), in file order.
  std::vector<std::pair<std::string, std::vector<std::string>>> grid;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("replicates", &replicates);
    a->Visit("grid", &grid);
  }
};

struct ExperimentConfig {
  ScenarioConfig scenario;
  ModelConfig model;
  std::vector<std::string> policies = {"no_ebp", "no_trust", "ta_ebp"};
  std::optional<SweepConfig> sweep;  // only `taebp sweep` uses it

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("scenario", &scenario);
    a->Visit("model", &model);
    a->Visit("policies", &policies);
    a->Visit("sweep", &sweep);
  }

  // Range checks; on failure returns false and a message naming the key and value.
  bool IsValid(std::string* why) const;
};

// The text of a config file. Throws ConfigError naming the path when it is a
// directory, missing or unreadable.
std::string ReadConfigFile(const std::string& path);

// Loads a YAML experiment file, applies `overrides` ("key.path=VALUE", VALUE
// parsed as YAML) and validates. Unknown keys, wrong types and out-of-range
// values throw ConfigError naming the file (or the --set), the key and value.
ExperimentConfig LoadExperimentConfig(const std::string& path,
                                      const std::vector<std::string>& overrides = {});
// Same, from YAML text (`origin` names it in messages).
ExperimentConfig ParseExperimentConfig(const std::string& yaml_text, const std::string& origin,
                                       const std::vector<std::string>& overrides = {});
// A config text parsed once, to be loaded many times with different
// overrides (a sweep's grid points): Load(o) equals
// ParseExperimentConfig(yaml_text, origin, o), without re-parsing the text.
class ExperimentTemplate {
 public:
  ExperimentTemplate(const std::string& yaml_text, const std::string& origin);
  ~ExperimentTemplate();
  ExperimentConfig Load(const std::vector<std::string>& overrides) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

// The resolved config as YAML text and as a JSON string (same schema).
std::string ToYaml(const ExperimentConfig& config);
std::string ToJson(const ExperimentConfig& config);

// `taebp solve` problem files: a finite persuasion game and a trust level.
struct ProblemConfig {
  std::vector<std::string> states;
  std::vector<std::string> actions;
  std::vector<double> prior;
  std::vector<std::vector<double>> receiver_utility;  // rows = states
  std::vector<std::vector<double>> sender_utility;    // rows = states
  double trust = 1.0;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("states", &states);
    a->Visit("actions", &actions);
    a->Visit("prior", &prior);
    a->Visit("receiver_utility", &receiver_utility);
    a->Visit("sender_utility", &sender_utility);
    a->Visit("trust", &trust);
  }
};
// Throws ConfigError (file, key, line) on unknown keys, missing keys, bad types.
ProblemConfig LoadProblemConfig(const std::string& path);

}  // namespace taebp
