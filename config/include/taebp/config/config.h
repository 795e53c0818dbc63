// Experiment configuration: plain structs with defaults at the field, one schema
// (Serialize) used for loading, saving and provenance, and IsValid() checks.
// The scenario: and model: sections are in scenario_config.h and model_config.h.
// All YAML parsing lives in config_yaml.cc (the one loader); this header has no
// yaml-cpp include.
#pragma once

#include "taebp/base/errors.h"
#include "taebp/config/enums.h"
#include "taebp/config/model_config.h"
#include "taebp/config/policies.h"
#include "taebp/config/scenario_config.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace taebp {

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

// Bounds that keep a run's allocations and SUMO's physics sane.
inline constexpr double kMaxCruiseSpeed = 70.0;  // m/s (252 km/h)
inline constexpr double kMaxDuration = 1e7;      // s (~116 simulated days)
// scenario.avs and scenario.hvs each: SUMO inserts them all in its first
// step, which a signal cannot interrupt (a million took over 10 minutes).
inline constexpr int kMaxVehicles = 10000;
inline constexpr double kMaxSteps = 1e9;
// A config's YAML values with its aliases expanded (a sweep grid of a
// thousand points of a few values each is some ten thousand).
inline constexpr std::size_t kMaxConfigNodes = 1000000;
// scenario.seed (and a sweep's last replicate, seed + replicates - 1): SUMO
// takes its --seed modulo 2^31 - 1, so seeds 1 and 2147483648 would run alike.
inline constexpr std::uint64_t kMaxSeed = 2147483646;


// outputs: the time series written by runs beyond the paper (timeseries.csv,
// hv_trust.csv), sampled every `interval` simulated seconds (>= 1: the
// controller samples once a simulated second).
struct OutputConfig {
  double interval = 60.0;  // s
  bool per_hv = true;      // hv_trust.csv: a row per HV in the network per sample

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("interval", &interval);
    a->Visit("per_hv", &per_hv);
  }
};

struct ExperimentConfig {
  ScenarioConfig scenario;
  ModelConfig model;
  std::vector<std::string> policies = DefaultPolicies();  // config/policies.h
  std::optional<SweepConfig> sweep;  // only `taebp sweep` uses it
  OutputConfig outputs;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("scenario", &scenario);
    a->Visit("model", &model);
    a->Visit("policies", &policies);
    a->Visit("sweep", &sweep);
    a->Visit("outputs", &outputs);
  }

  // Range checks; on failure returns false and a message naming the key and value.
  bool IsValid(std::string* why) const;
  // True when the run goes beyond the paper's setting: dynamic trust, noise,
  // learning, or a policy only defined here (population_mean,
  // ta_ebp_learned). Such runs write the extra encounter columns, summary
  // sections and time series; the paper's runs write exactly what they did.
  bool BeyondPaper() const;
};

// The text of a config file. Throws ConfigError naming the path when it is
// not a regular file (NotAFile), or unreadable.
std::string ReadConfigFile(const std::string& path);

// Why `path` cannot be read as a file, or "" when it is a regular file (a
// symbolic link to one counts): "no such file", "a folder, not a file", "a
// FIFO (named pipe), not a file" (reading one would wait for a writer
// forever), "a socket, not a file", "a device, not a file", "a dangling
// symbolic link", or the system's reason it cannot be looked at.
std::string NotAFile(const std::string& path);

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
// ParseExperimentConfig(yaml_text, origin, base + {"sweep=~"} + o), without
// re-parsing the text or copying the sweep's grid (linear in the points).
class ExperimentTemplate {
 public:
  // `base`: overrides applied once, before each Load's own; the config's
  // sweep: section is dropped (each Load is a point's config without it).
  ExperimentTemplate(const std::string& yaml_text, const std::string& origin,
                     const std::vector<std::string>& base = {});
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
// Same, from YAML (or JSON) text; `origin` names it in messages.
ProblemConfig ParseProblemConfig(const std::string& yaml_text, const std::string& origin);

// A YAML value (e.g. a --set or sweep grid value) as JSON text with its YAML
// type: 0.5 -> 0.5, true -> true, ta_ebp -> "ta_ebp", '1' -> "1",
// [8, 8] -> [8,8], {dist: beta, alpha: 2} -> {"dist":"beta","alpha":2}.
// Throws ConfigError for malformed YAML.
std::string YamlValueAsJson(const std::string& yaml_text);

}  // namespace taebp
