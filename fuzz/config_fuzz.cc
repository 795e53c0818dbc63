// Fuzz target: the experiment-config loader with --set overrides.
// Input: YAML config text, optionally followed by a line "%%" and one
// "KEY=VALUE" override per line. Errors must be ConfigError; a config that
// loads must save (ToYaml) and load back to the same config, and loading
// through ExperimentTemplate (a sweep's grid points) must agree.
#include "fuzz_support.h"
#include "taebp/config/config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace taebp;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const auto [yaml, set_text] = fuzz::SplitAt(input, "%%");
  const std::vector<std::string> overrides = fuzz::Lines(set_text);

  std::string error, json;
  try {
    json = ToJson(ParseExperimentConfig(yaml, "fuzz.yaml", overrides));
  } catch (const ConfigError& e) {
    error = e.what();
  }
  // The template drops the sweep: section (the same for each grid point).
  std::vector<std::string> unswept = {"sweep=~"};
  unswept.insert(unswept.end(), overrides.begin(), overrides.end());
  std::string unswept_error, unswept_json;
  try {
    unswept_json = ToJson(ParseExperimentConfig(yaml, "fuzz.yaml", unswept));
  } catch (const ConfigError& e) {
    unswept_error = e.what();
  }
  std::string template_error, template_json;
  try {
    template_json = ToJson(ExperimentTemplate(yaml, "fuzz.yaml").Load(overrides));
  } catch (const ConfigError& e) {
    template_error = e.what();
  }
  if (unswept_error != template_error || unswept_json != template_json)
    fuzz::Finding("ExperimentTemplate disagrees with ParseExperimentConfig: '" + unswept_error +
                  "' vs '" + template_error + "'");
  if (!error.empty()) return 0;

  const ExperimentConfig config = ParseExperimentConfig(yaml, "fuzz.yaml", overrides);
  const std::string saved = ToYaml(config);
  std::string reloaded;
  try {
    reloaded = ToJson(ParseExperimentConfig(saved, "saved.yaml"));
  } catch (const ConfigError& e) {
    fuzz::Finding(std::string("the saved config does not load: ") + e.what() + "\n" + saved);
  }
  if (reloaded != json)
    fuzz::Finding("the saved config loads differently:\n" + saved + "\nloaded:   " + json +
                  "\nreloaded: " + reloaded);
  return 0;
}
