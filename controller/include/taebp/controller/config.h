// Experiment configuration: plain structs with defaults at the field, one schema
// (Serialize) used for loading, saving and provenance, and IsValid() checks.
// All YAML parsing lives in config_yaml.cc (the one loader); this header has no
// yaml-cpp include.
#pragma once

#include <cstdint>
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
  double stop_distance = 1.7;   // m from the vehicle's front to the centre when held
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

struct ModelConfig {
  double prior_go = 0.2;           // lambda
  double collision_penalty = 3.0;  // r
  double trust = 0.6;              // theta, every HV
  std::optional<double> assumed_trust;  // theta_hat used by ta_ebp (default: trust)
  LikelihoodConfig likelihood;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("prior_go", &prior_go);
    a->Visit("collision_penalty", &collision_penalty);
    a->Visit("trust", &trust);
    a->Visit("assumed_trust", &assumed_trust);
    a->Visit("likelihood", &likelihood);
  }
};

struct ExperimentConfig {
  ScenarioConfig scenario;
  ModelConfig model;
  std::vector<std::string> policies = {"no_ebp", "no_trust", "ta_ebp"};

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("scenario", &scenario);
    a->Visit("model", &model);
    a->Visit("policies", &policies);
  }

  // Range checks; on failure returns false and a message naming the key and value.
  bool IsValid(std::string* why) const;
};

// Loads a YAML experiment file, applies `overrides` ("key.path=VALUE", VALUE
// parsed as YAML) and validates. Unknown keys, wrong types and out-of-range
// values throw ConfigError naming the file (or the --set), the key and value.
ExperimentConfig LoadExperimentConfig(const std::string& path,
                                      const std::vector<std::string>& overrides = {});
// Same, from YAML text (`origin` names it in messages).
ExperimentConfig ParseExperimentConfig(const std::string& yaml_text, const std::string& origin,
                                       const std::vector<std::string>& overrides = {});
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
