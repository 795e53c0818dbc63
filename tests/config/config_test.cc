// The experiment and problem config loader: documented values, one schema for
// load and save, and errors that name the key, the value and where they came
// from (file:line or the --set text).
#include "taebp/config/config.h"
#include "taebp/config/model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>

#include <sys/stat.h>

#include "test_support.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace taebp {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

const std::string kPaper = std::string(TAEBP_SOURCE_DIR) + "/configs/paper.yaml";
const std::string kProblems = std::string(TAEBP_SOURCE_DIR) + "/configs/problems";

using test::TempDir;

// The ConfigError message of `f()`, or a recorded failure.
template <typename F>
std::string ConfigErrorOf(F&& f) {
  return test::ErrorOf<ConfigError>(std::forward<F>(f));
}

// Loads `yaml` from a file named `name` in a fresh temporary directory; returns
// the ConfigError message and the file's path.
struct FileError {
  std::string message, path;
};
FileError LoadError(const std::string& yaml, const std::vector<std::string>& overrides = {},
                    const std::string& name = "exp.yaml") {
  TempDir dir;
  const std::string path = dir.Write(name, yaml);
  return {ConfigErrorOf([&] { LoadExperimentConfig(path, overrides); }), path};
}

// ------------------------------------------------------------------ paper.yaml

TEST(ConfigLoad, PaperYamlHasTheDocumentedValues) {
  const ExperimentConfig c = LoadExperimentConfig(kPaper);
  const ScenarioConfig& s = c.scenario;
  EXPECT_EQ(s.avs, 8);
  EXPECT_EQ(s.hvs, 8);
  EXPECT_EQ(s.cruise_speed, 4.0);
  EXPECT_EQ(s.min_gap, 2.0);
  // 3.0 m, not the paper's 1.7: a nudge of up to s_max = 2 m from 1.7 m would put
  // the AV's nose into the crossing path of a 1.8 m wide HV (docs/sumo-facts.md).
  EXPECT_EQ(s.stop_distance, 3.0);
  EXPECT_GE(s.stop_distance, c.model.likelihood.s_max + s.vehicle_width / 2);
  EXPECT_EQ(s.step_length, 0.1);
  EXPECT_EQ(s.duration, 3600.0);
  EXPECT_EQ(s.seed, 1u);
  const ModelConfig& m = c.model;
  EXPECT_EQ(m.prior_go, 0.2);
  EXPECT_EQ(m.collision_penalty, 3.0);
  EXPECT_TRUE(m.trust.IsFixed());
  EXPECT_EQ(m.trust.value, 0.6);
  EXPECT_FALSE(m.assumed_trust.has_value());
  EXPECT_EQ(m.Knowledge(), TrustKnowledge::kExact);
  EXPECT_EQ(m.likelihood.type, LikelihoodType::kLinear);
  EXPECT_EQ(m.likelihood.s_max, 2.0);
  EXPECT_EQ(c.policies, (std::vector<std::string>{"no_ebp", "no_trust", "ta_ebp"}));
  EXPECT_FALSE(c.sweep.has_value());
  // Keys the file does not set keep the struct defaults.
  const ScenarioConfig defaults;
  EXPECT_EQ(s.vehicle_length, defaults.vehicle_length);
  EXPECT_EQ(s.vehicle_width, defaults.vehicle_width);
  EXPECT_EQ(s.meeting_distance, defaults.meeting_distance);
  EXPECT_EQ(s.network, "");
  std::string why;
  EXPECT_TRUE(c.IsValid(&why)) << why;
}

TEST(ConfigLoad, ToYamlRoundTripGivesIdenticalJson) {
  const ExperimentConfig paper = LoadExperimentConfig(kPaper);
  const std::string yaml = ToYaml(paper);
  EXPECT_EQ(ToJson(ParseExperimentConfig(yaml, "roundtrip.yaml")), ToJson(paper));
  // A config that sets every kind of field: optional, distribution, logistic
  // likelihood, awkward doubles, a sweep grid and a non-default policy list.
  const ExperimentConfig rich = ParseExperimentConfig(
      "scenario: {avs: 3, hvs: 5, duration: 123.45, seed: 2147483644,\n"
      "           step_length: 0.05, auto_length: false, network: some/net.xml,\n"
      "           creep_speed: 0.1}\n"
      "model:\n"
      "  prior_go: 0.1\n"
      "  collision_penalty: 3.3333333333333335\n"
      "  trust: {dist: discrete, values: [0.2, 0.7], weights: [1, 2]}\n"
      "  trust_knowledge: assumed\n"
      "  assumed_trust: 0.9\n"
      "  likelihood: {type: logistic, s_max: 1.5, steepness: 6, midpoint: 0.7}\n"
      "policies: [ta_ebp, full_reveal]\n"
      "sweep:\n"
      "  replicates: 3\n"
      "  grid:\n"
      "    model.trust: [0.1, 0.5, {dist: uniform, low: 0.2, high: 0.9}]\n"
      "    scenario.avs: [0, 8]\n",
      "rich.yaml");
  EXPECT_EQ(rich.scenario.seed, 2147483644u);  // the last replicate, +2, is SUMO's largest
  ASSERT_TRUE(rich.sweep.has_value());
  EXPECT_EQ(rich.sweep->grid.size(), 2u);
  const std::string rich_yaml = ToYaml(rich);
  const ExperimentConfig back = ParseExperimentConfig(rich_yaml, "rich-roundtrip.yaml");
  EXPECT_EQ(ToJson(back), ToJson(rich)) << rich_yaml;
  EXPECT_EQ(back.scenario.duration, 123.45);
  EXPECT_EQ(back.model.collision_penalty, 3.3333333333333335);
  ASSERT_TRUE(back.model.assumed_trust.has_value());
  EXPECT_EQ(*back.model.assumed_trust, 0.9);
  // And the YAML we write is itself stable.
  EXPECT_EQ(ToYaml(back), rich_yaml);
}

// Every option with a fixed set of values is an enum (enums.h): each of its
// names loads as that value and is written back as the same name (YAML and
// JSON), and a name outside the set is refused when the file is read, naming
// the key, the value, the file and line, and the choices.
template <typename E>
void ExpectEnumKey(const std::string& key, const std::function<E(const ExperimentConfig&)>& get,
                   const std::string& context = "") {
  SCOPED_TRACE(key);
  int names = 0;
  for (const auto& [value, name] : EnumNames<E>::kNames) {
    ++names;
    E parsed{};
    ASSERT_TRUE(ParseEnum(name, &parsed));
    EXPECT_EQ(parsed, value);
    EXPECT_STREQ(EnumName(value), name);
    if (context == "-") continue;  // not loadable alone (e.g. trust dist fixed)
    const ExperimentConfig c =
        LoadExperimentConfig(kPaper, {context.empty() ? key + "=" + name : context, key + "=" + name});
    EXPECT_EQ(get(c), value) << name;
    EXPECT_THAT(ToYaml(c), HasSubstr(key.substr(key.rfind('.') + 1) + ": " + name)) << name;
    EXPECT_EQ(ToJson(ParseExperimentConfig(ToYaml(c), "again.yaml")), ToJson(c));
  }
  EXPECT_GE(names, 1);
  E untouched = EnumNames<E>::kNames[0].first;
  EXPECT_FALSE(ParseEnum("no_such_value", &untouched));
  EXPECT_EQ(untouched, EnumNames<E>::kNames[0].first);
  // Nested keys as a YAML file: the message has the file and line.
  std::string yaml, indent;
  std::string rest = key;
  for (std::size_t dot; (dot = rest.find('.')) != std::string::npos; rest = rest.substr(dot + 1)) {
    yaml += indent + rest.substr(0, dot) + ":\n";
    indent += "  ";
  }
  yaml += indent + rest + ": no_such_value\n";
  const FileError e = LoadError(yaml);
  // (a trust distribution map offers its map forms only: a fixed trust is a number)
  const std::string choices = std::is_same_v<E, TrustDist> ? "uniform, beta, discrete" : EnumChoices<E>();
  EXPECT_THAT(e.message, HasSubstr(key + " = 'no_such_value' is not one of: " + choices));
  EXPECT_THAT(e.message, HasSubstr(e.path + ":"));
}

TEST(ConfigEnums, EveryNameLoadsSavesAndAnUnknownOneIsRefusedWithTheChoices) {
  ExpectEnumKey<ScenarioKind>("scenario.kind", [](const ExperimentConfig& c) { return c.scenario.kind; },
                              "scenario={grid: {}, demand: {flow: 10}}");
  ExpectEnumKey<NudgeCheck>("scenario.nudge_check",
                            [](const ExperimentConfig& c) { return c.scenario.nudge_check; });
  ExpectEnumKey<StallAction>("scenario.stall_action",
                             [](const ExperimentConfig& c) { return c.scenario.stall_action; });
  ExpectEnumKey<EncounterPairs>(
      "scenario.encounter_pairs", [](const ExperimentConfig& c) { return c.scenario.encounter_pairs; },
      "scenario={kind: network, grid: {}, demand: {flow: 10}}");
  ExpectEnumKey<StopRule>("scenario.junctions.priority",
                          [](const ExperimentConfig& c) { return c.scenario.junctions.priority; });
  ExpectEnumKey<StopRule>("scenario.junctions.right_before_left", [](const ExperimentConfig& c) {
    return c.scenario.junctions.right_before_left;
  });
  ExpectEnumKey<StopRule>("scenario.junctions.unregulated",
                          [](const ExperimentConfig& c) { return c.scenario.junctions.unregulated; });
  ExpectEnumKey<GridJunctionType>(
      "scenario.grid.junction_type",
      [](const ExperimentConfig& c) { return c.scenario.grid->junction_type; },
      "scenario={kind: network, grid: {}, demand: {flow: 10}}");
  ExpectEnumKey<Routing>("scenario.demand.routing",
                         [](const ExperimentConfig& c) { return c.scenario.demand->routing; },
                         "scenario={kind: network, grid: {}, demand: {flow: 10}}");
  ExpectEnumKey<LikelihoodType>("model.likelihood.type",
                                [](const ExperimentConfig& c) { return c.model.likelihood.type; });
  ExpectEnumKey<TrustKnowledge>(
      "model.trust_knowledge", [](const ExperimentConfig& c) { return c.model.Knowledge(); },
      "model.assumed_trust=0.5");
  ExpectEnumKey<NoiseKind>("model.noise.kind",
                           [](const ExperimentConfig& c) { return c.model.noise->kind; });
  ExpectEnumKey<NoiseDesign>("model.noise.design",
                             [](const ExperimentConfig& c) { return c.model.noise->design; });
  ExpectEnumKey<TrustDist>("model.trust.dist",
                           [](const ExperimentConfig& c) { return c.model.trust.dist; }, "-");
}

// A distribution map cannot be dist: fixed (a fixed trust is a number).
TEST(ConfigEnums, TrustDistributionsAreMapsAndAFixedTrustIsANumber) {
  EXPECT_THAT(LoadError("model: {trust: {dist: fixed, value: 0.3}}\n").message,
              HasSubstr("model.trust.dist = 'fixed' is not one of: uniform, beta, discrete"));
  EXPECT_THAT(LoadError("model: {trust: {dist: gamma}}\n").message,
              HasSubstr("model.trust.dist = 'gamma' is not one of: uniform, beta, discrete"));
}

// config/model.h: the one conversion from the config to the model carries
// every field (distinct values in, the same values out), and a config is valid
// exactly when the model's own check passes (one check per field).
TEST(ConfigModel, ToModelCarriesEveryFieldAndTheModelChecksItsRanges) {
  const ExperimentConfig c = LoadExperimentConfig(
      kPaper, {"model.prior_go=0.15", "model.collision_penalty=2.5",
               "model.noise={kind: uniform, scale: 0.07, bias: -0.01}",
               "model.trust_dynamics={success_weight: 0.7, failure_weight: 1.3, forgetting: 0.05, "
               "quality: {nudge_go: 0.9, nudge_stop: 0.1, still_stop: 0.8, still_go: 0.2, "
               "collision: 0.05}}",
               "model.learning={delta: 0.02, decay: 2.5, probe: false}"});
  const persuasion::AvHvParams p = ToModel(c.model);
  EXPECT_EQ(p.prior_go, 0.15);
  EXPECT_EQ(p.collision_penalty, 2.5);
  const persuasion::PerceptionNoise n = ToModel(*c.model.noise);
  EXPECT_EQ(n.kind, persuasion::PerceptionNoise::Kind::kUniform);
  EXPECT_EQ(n.scale, 0.07);
  EXPECT_EQ(n.bias, -0.01);
  const persuasion::TrustUpdateRule r = ToModel(*c.model.trust_dynamics);
  EXPECT_EQ(r.success_weight, 0.7);
  EXPECT_EQ(r.failure_weight, 1.3);
  EXPECT_EQ(r.forgetting, 0.05);
  EXPECT_EQ(r.quality.nudge_go, 0.9);
  EXPECT_EQ(r.quality.nudge_stop, 0.1);
  EXPECT_EQ(r.quality.still_stop, 0.8);
  EXPECT_EQ(r.quality.still_go, 0.2);
  EXPECT_EQ(r.quality.collision, 0.05);
  const persuasion::ExplorationSchedule e = ToModel(*c.model.learning);
  EXPECT_EQ(e.delta, 0.02);
  EXPECT_EQ(e.decay, 2.5);
  EXPECT_FALSE(e.probe);
  LearningConfig constant;
  constant.constant_level = true;
  EXPECT_TRUE(std::isinf(ToModel(constant).decay));
  EXPECT_EQ(ToModel(TrustSpec::Fixed(0.3)).Mean(), 0.3);

  for (double v : {-0.5, 0.0, 0.5, 1.0, 1.5}) {
    const std::string set = "model.trust_dynamics={forgetting: " + std::to_string(v) + "}";
    std::string why;
    persuasion::TrustUpdateRule rule;
    rule.forgetting = v;
    const bool model_ok = rule.IsValid(&why);
    std::string err;
    try {
      LoadExperimentConfig(kPaper, {set});
    } catch (const ConfigError& e) {
      err = e.what();
    }
    EXPECT_EQ(err.empty(), model_ok) << v << ": " << err;
    if (!model_ok) {
      EXPECT_THAT(err, HasSubstr("model.trust_dynamics." + why)) << v;
    }
  }
}

// Found by replaying configs/sweep_trust.yaml through the fuzz target: the
// saved config wrote the double 1.0 as "1", so a grid [..., 0.9, 1.0] came
// back as [..., 0.9, 1], another grid (another config hash). Doubles are
// written with the shortest digits that read back exactly, and a fraction.
TEST(ConfigLoad, SavedConfigKeepsNumbersAsTheyRead) {
  const ExperimentConfig c = ParseExperimentConfig(
      "scenario: {duration: 60.0, step_length: 0.1}\n"
      "sweep: {replicates: 1, grid: {model.trust: [0.9, 1.0], scenario.seed: [1, 2]}}\n",
      "numbers.yaml");
  const std::string saved = ToYaml(c);
  EXPECT_THAT(saved, HasSubstr("model.trust: [0.9, 1.0]"));
  EXPECT_THAT(saved, HasSubstr("scenario.seed: [1, 2]"));
  EXPECT_THAT(saved, HasSubstr("duration: 60.0\n"));
  EXPECT_THAT(saved, HasSubstr("step_length: 0.1\n"));
  EXPECT_EQ(ToJson(ParseExperimentConfig(saved, "saved.yaml")), ToJson(c)) << saved;
  // An infinite value (even of a key the linear likelihood ignores) was
  // accepted and saved as null, which does not load: refused.
  for (const char* inf : {".inf", "-.inf", ".nan"}) {
    EXPECT_THAT(ConfigErrorOf([&] {
                  ParseExperimentConfig(std::string("model: {likelihood: {midpoint: ") + inf + "}}",
                                        "inf.yaml");
                }),
                HasSubstr("key 'model.likelihood.midpoint' expects a finite number"))
        << inf;
  }
  EXPECT_THAT(ConfigErrorOf([&] { ParseExperimentConfig("scenario: {duration: 1e999}", "big.yaml"); }),
              HasSubstr("key 'scenario.duration' expects a number, got '1e999'"));
}

// The built-in default is the safe geometry (README "Geometry"): a nudge of up
// to s_max from the stop line keeps the AV's nose out of a crossing HV's path.
TEST(ConfigLoad, DefaultGeometryIsTheSafeOne) {
  const ExperimentConfig d;
  EXPECT_EQ(d.scenario.stop_distance, 3.0);
  EXPECT_GE(d.scenario.stop_distance, d.model.likelihood.s_max + d.scenario.vehicle_width / 2);
  EXPECT_EQ(ParseExperimentConfig("scenario: {avs: 2}", "t.yaml").scenario.stop_distance, 3.0);
}

TEST(ConfigLoad, EmptyTextGivesTheDefaults) {
  EXPECT_EQ(ToJson(ParseExperimentConfig("", "empty.yaml")), ToJson(ExperimentConfig{}));
  EXPECT_EQ(ToJson(ParseExperimentConfig("{}", "empty.yaml")), ToJson(ExperimentConfig{}));
}

// ------------------------------------------------------------------ unknown keys

TEST(ConfigErrors, UnknownTopLevelKeyNamesKeyFileAndLine) {
  const FileError e = LoadError(
      "# an experiment\n"
      "scenario:\n"
      "  avs: 8\n"
      "scenaro:\n"
      "  hvs: 8\n");
  EXPECT_THAT(e.message, HasSubstr("scenaro"));
  EXPECT_THAT(e.message, HasSubstr(e.path + ":4"));
  EXPECT_THAT(e.message, HasSubstr("unknown key"));
}

TEST(ConfigErrors, UnknownNestedKeyNamesFullKeyFileAndLine) {
  const FileError e = LoadError(
      "scenario:\n"
      "  avs: 8\n"
      "  hvs: 8\n"
      "  avss: 3\n"
      "model:\n"
      "  prior_go: 0.2\n");
  EXPECT_THAT(e.message, HasSubstr("scenario.avss"));
  EXPECT_THAT(e.message, HasSubstr(e.path + ":4"));
  const FileError deep = LoadError(
      "model:\n"
      "  likelihood:\n"
      "    type: linear\n"
      "    smax: 2\n");
  EXPECT_THAT(deep.message, HasSubstr("model.likelihood.smax"));
  EXPECT_THAT(deep.message, HasSubstr(deep.path + ":4"));
}

TEST(ConfigErrors, DuplicateKeysAreErrorsNotSilentlyFirstWins) {
  const FileError nested = LoadError(
      "scenario:\n"
      "  duration: 60\n"
      "  avs: 8\n"
      "  duration: 3600\n");
  EXPECT_THAT(nested.message, HasSubstr("scenario.duration"));
  EXPECT_THAT(nested.message, HasSubstr("twice"));
  EXPECT_THAT(nested.message, HasSubstr(nested.path + ":4"));
  const FileError top = LoadError("policies: [ta_ebp]\nmodel: {}\npolicies: [no_ebp]\n");
  EXPECT_THAT(top.message, HasSubstr("policies"));
  EXPECT_THAT(top.message, HasSubstr(top.path + ":3"));
  const FileError trust = LoadError("model: {trust: {dist: beta, alpha: 2, beta: 3, alpha: 4}}\n");
  EXPECT_THAT(trust.message, HasSubstr("model.trust.alpha"));
  EXPECT_THAT(trust.message, HasSubstr("twice"));
}

TEST(ConfigErrors, ASweepSectionGivenTwiceIsTheFilesErrorInEveryPath) {
  // tools/fuzz config: with `sweep:` twice the run's path blamed the sweep
  // template's own "--set sweep=~" for it, and the template (which drops the
  // section) took the config.
  const std::string text = "sweep: {replicates: 2}\nmodel: {}\nsweep: {replicates: 3}\n";
  const std::string want = "x.yaml:3: key 'sweep' is given twice (first on line 1)";
  auto message = [](auto load) {
    try {
      load();
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([&] { ParseExperimentConfig(text, "x.yaml"); }), want);
  EXPECT_EQ(message([&] { ParseExperimentConfig(text, "x.yaml", {"sweep=~"}); }), want);
  EXPECT_EQ(message([&] { ExperimentTemplate(text, "x.yaml").Load({}); }), want);
  // In a --set value too, named by it.
  EXPECT_THAT(message([&] { ParseExperimentConfig("{}", "x.yaml", {"model={prior_go: 0.1, prior_go: 0.2}"}); }),
              HasSubstr("key 'prior_go' is given twice"));
}

// ------------------------------------------------------------------ wrong types

TEST(ConfigErrors, WrongTypesNameKeyValueAndLine) {
  {
    const FileError e = LoadError("scenario:\n  avs: abc\n");
    EXPECT_THAT(e.message, HasSubstr("scenario.avs"));
    EXPECT_THAT(e.message, HasSubstr("abc"));
    EXPECT_THAT(e.message, HasSubstr(e.path + ":2"));
  }
  {
    const FileError e = LoadError("scenario:\n  avs: 8\n  duration: [1]\n");
    EXPECT_THAT(e.message, HasSubstr("scenario.duration"));
    EXPECT_THAT(e.message, HasSubstr("[1]"));
    EXPECT_THAT(e.message, HasSubstr(e.path + ":3"));
  }
  {
    const FileError e = LoadError("model: {prior_go: 0.2}\npolicies: ta_ebp\n");
    EXPECT_THAT(e.message, HasSubstr("policies"));
    EXPECT_THAT(e.message, HasSubstr("list"));
    EXPECT_THAT(e.message, HasSubstr("ta_ebp"));
    EXPECT_THAT(e.message, HasSubstr(e.path + ":2"));
  }
  {
    // A fraction for an integer, a word for a bool, a map where a number goes.
    EXPECT_THAT(LoadError("scenario: {hvs: 2.5}\n").message, HasSubstr("scenario.hvs"));
    EXPECT_THAT(LoadError("scenario: {auto_length: maybe}\n").message,
                HasSubstr("scenario.auto_length"));
    EXPECT_THAT(LoadError("model: {collision_penalty: {a: 1}}\n").message,
                HasSubstr("model.collision_penalty"));
    EXPECT_THAT(LoadError("model: {prior_go: yes}\n").message, HasSubstr("model.prior_go"));
    EXPECT_THAT(LoadError("scenario: {seed: -1}\n").message, HasSubstr("scenario.seed"));
    EXPECT_THAT(LoadError("scenario: 5\n").message, HasSubstr("scenario"));
  }
  {
    // A control character in a value is shown (\xNN), not printed raw: an
    // escape or a NUL would hide the value or cut the message.
    const FileError e = LoadError("scenario: {avs: \"1\\x01\\x1b\"}\n");
    EXPECT_THAT(e.message, HasSubstr("'1\\x01\\x1b'")) << e.message;
    const std::string nul = ConfigErrorOf(
        [] { ParseExperimentConfig("scenario: {avs: 1}\n", "nul.yaml",
                                   {std::string("scenario.avs=\"2\\0x\"")}); });
    EXPECT_THAT(nul, HasSubstr("\\x00x")) << nul;
    EXPECT_THAT(nul, HasSubstr("scenario.avs")) << nul;
  }
}

// ------------------------------------------------------------------ ranges

TEST(ConfigErrors, OutOfRangeValuesNameKeyAndValue) {
  struct Case {
    std::string yaml, expected;
  };
  const std::vector<Case> cases = {
      {"model: {trust: 1.3}\n", "model.trust = 1.3"},
      {"model: {prior_go: 0}\n", "model.prior_go (lambda) = 0 is outside (0, 1)"},
      {"model: {prior_go: 1}\n", "model.prior_go (lambda) = 1 is outside (0, 1)"},
      {"model: {collision_penalty: -2}\n", "model.collision_penalty r = -2 must be > 0"},
      {"model: {assumed_trust: -0.1}\n", "model.assumed_trust = -0.1"},
      {"model: {likelihood: {s_max: 0}}\n", "model.likelihood.s_max = 0"},
      {"model: {likelihood: {type: cubic}}\n", "model.likelihood.type = 'cubic'"},
      {"scenario: {duration: -5}\n", "scenario.duration = -5"},
      {"scenario: {avs: -1}\n", "scenario.avs = -1"},
      {"scenario: {hvs: -3}\n", "scenario.hvs = -3"},
      {"scenario: {avs: 0, hvs: 0}\n", "scenario.avs + scenario.hvs = 0"},
      {"scenario: {step_length: 0}\n", "scenario.step_length = 0"},
      {"scenario: {cruise_speed: -4}\n", "scenario.cruise_speed = -4"},
      {"policies: [ta_ebp, yolo]\n", "'yolo'"},
      {"policies: [ta_ebp, no_ebp, ta_ebp]\n", "'ta_ebp' is listed twice"},
      {"policies: []\n", "policies is empty"},
      // What a run would allocate or simulate is bounded before it starts
      // (1e6 m/s used to grow routes to 18 GB; 1e9 s ended in bad_alloc).
      {"scenario: {cruise_speed: 1e6}\n", "scenario.cruise_speed = 1000000 m/s is above 70"},
      {"scenario: {duration: 1e9}\n", "scenario.duration = 1000000000 s is above"},
      {"scenario: {duration: 1e12}\n", "scenario.duration = 1e+12 s is above"},
      {"scenario: {duration: 5e6, step_length: 0.001}\n", "steps is above"},
      {"scenario: {kind: grid}\n", "scenario.kind = 'grid'"},
      {"scenario: {kind: network}\n", "scenario.kind = 'network' needs one of"},
      {"scenario: {kind: network, network: a.net.xml}\n", "has no vehicles"},
      {"scenario: {kind: network, network: a.net.xml, routes: [r.xml], av_share: 1.5}\n",
       "scenario.av_share = 1.5"},
      {"scenario: {junctions: {types: [traffic_light]}}\n", "'traffic_light' is not a junction type"},
      {"scenario: {junctions: {priority: three_way}}\n", "scenario.junctions.priority = 'three_way'"},
      {"scenario: {junctions: {min_arms: -1}}\n", "scenario.junctions.min_arms = -1 must be in [0, 64]"},
      {"scenario: {grid: {columns: 1, rows: 4}, kind: network, demand: {flow: 10}}\n",
       "scenario.grid = 1 x 4"},
      {"scenario: {kind: network, grid: {}, demand: {flow: -3}}\n", "scenario.demand.flow = -3"},
      {"scenario: {kind: network, grid: {}, demand: {flow: 3, major_flow: -1}}\n",
       "scenario.demand.major_flow = -1 veh/h must be >= 0"},
      {"scenario: {kind: network, grid: {}, demand: {flow: 3, major_flow: .nan}}\n",
       "key 'scenario.demand.major_flow' expects a finite number"},
      {"scenario: {kind: network, grid: {}, demand: {flow: 10}, warmup: 4000}\n",
       "scenario.warmup = 4000 leaves nothing"},
      {"scenario: {stall_action: ignore}\n", "scenario.stall_action = 'ignore'"},
      {"scenario: {nudge_check: maybe}\n", "scenario.nudge_check = 'maybe'"},
      {"scenario: {kind: network, grid: {}, demand: {flow: 10}, encounter_pairs: crossing}\n",
       "scenario.encounter_pairs = 'crossing' is not one of: colliding, all"},
      {"scenario: {encounter_pairs: all}\n",
       "scenario.encounter_pairs = 'all' applies to scenario.kind = 'network' only"},
      {"policies: [sumo_native, yolo]\n", "'yolo' is not one of sumo_native"},
      {"scenario: {kind: network, grid: {}, demand: {flow: 10}, routes_scale: 0}\n",
       "scenario.routes_scale = 0 must be in (0, 100]"},
      {"scenario: {kind: network, grid: {}, demand: {flow: 10}, routes_scale: 1e3}\n",
       "scenario.routes_scale = 1000 must be in (0, 100]"},
      {"scenario: {routes_scale: 2}\n", "applies to scenario.kind = 'network' only"},
  };
  for (const Case& c : cases) {
    const FileError e = LoadError(c.yaml);
    EXPECT_THAT(e.message, HasSubstr(c.expected)) << c.yaml;
    EXPECT_THAT(e.message, HasSubstr(e.path)) << c.yaml;
  }
}

// ------------------------------------------------------------------ files

TEST(ConfigErrors, MalformedYamlNamesFileAndLine) {
  const FileError e = LoadError(
      "scenario:\n"
      "  avs: 8\n"
      "  hvs: [8, 9\n"
      "model:\n"
      "  prior_go: 0.2\n");
  EXPECT_THAT(e.message, HasSubstr("malformed YAML"));
  // The parser reports the unterminated list somewhere from its start on.
  EXPECT_THAT(e.message, ::testing::ContainsRegex(e.path + ":[3-6]:"));
  // A tab used for indentation on line 4.
  const FileError tab = LoadError("scenario:\n  avs: 8\n  hvs: 8\n\tseed: 1\n");
  EXPECT_THAT(tab.message, HasSubstr("malformed YAML"));
  EXPECT_THAT(tab.message, HasSubstr(tab.path + ":4:"));
  // A stray closing brace on line 3.
  const FileError brace = LoadError("scenario:\n  avs: 8\nmodel: {prior_go: 0.2}}\n");
  EXPECT_THAT(brace.message, HasSubstr("malformed YAML"));
  EXPECT_THAT(brace.message, HasSubstr(brace.path + ":3:"));
  // A lone ',' (yaml-cpp 0.7's parser stops advancing there: LoadAll made
  // empty documents until the memory was gone, found by tools/fuzz problem).
  for (const std::string& text : {std::string(","), std::string(",\x18"),
                                   std::string("scenario: {avs: 8}\n,\n")}) {
    const FileError stray = LoadError(text);
    EXPECT_THAT(stray.message, HasSubstr(stray.path)) << text;
    EXPECT_THAT(stray.message, ::testing::AnyOf(HasSubstr("parser stops advancing"),
                                                HasSubstr("malformed YAML")))
        << text;
  }
}

TEST(ConfigErrors, MissingFileNamesThePath) {
  TempDir dir;
  const std::string path = (dir.path() / "nope.yaml").string();
  const std::string msg = ConfigErrorOf([&] { LoadExperimentConfig(path); });
  EXPECT_THAT(msg, HasSubstr(path));
  const std::string pmsg = ConfigErrorOf([&] { LoadProblemConfig(path); });
  EXPECT_THAT(pmsg, HasSubstr(path));
}

// Found by fuzzing (tools/fuzz, fuzz/regressions/config): bytes that are not
// UTF-8 (a Latin-1 comment or path) used to load and then make every JSON
// output throw nlohmann's type_error 316 after the simulation. YAML is UTF-8:
// refused at load, naming the file and line (or the --set).
TEST(ConfigErrors, TextThatIsNotUtf8IsRefusedNamingFileAndLine) {
  const FileError latin1 = LoadError("# M\xfcller's experiment\nscenario: {avs: 2}\n");
  EXPECT_THAT(latin1.message, HasSubstr(latin1.path + ":1: not UTF-8 text (byte 0xFC)"));
  const FileError path = LoadError("scenario:\n  network: \"caf\xe9.net.xml\"\n");
  EXPECT_THAT(path.message, HasSubstr(path.path + ":2: not UTF-8"));
  for (const char* bad : {"\xc0\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xe2\x82"}) {
    EXPECT_THAT(LoadError(std::string("policies: [") + bad + "]\n").message, HasSubstr("not UTF-8"))
        << "overlong, surrogate, beyond U+10FFFF or truncated";
  }
  EXPECT_THAT(ConfigErrorOf([&] { LoadExperimentConfig(kPaper, {"scenario.network=\xff"}); }),
              HasSubstr("not UTF-8"));
  // Valid UTF-8 of every length is fine.
  const ExperimentConfig c =
      ParseExperimentConfig("# caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\x97\nscenario: {network: \"\xc3\xa9.net.xml\"}\n",
                            "utf8.yaml");
  EXPECT_EQ(c.scenario.network, "\xc3\xa9.net.xml");
  EXPECT_NO_THROW(ToJson(c));
}

// yaml-cpp stops at 2000 levels of nesting; the message says so (it used to
// say "bad file").
TEST(ConfigErrors, DeepNestingIsAClearError) {
  const std::string deep = "policies: " + std::string(3000, '[') + std::string(3000, ']') + "\n";
  const FileError e = LoadError(deep);
  EXPECT_THAT(e.message, HasSubstr(e.path + ":1: malformed YAML: nested more than"));
  EXPECT_THAT(e.message, HasSubstr("levels deep"));
  EXPECT_THAT(ConfigErrorOf([&] {
                LoadExperimentConfig(kPaper, {"policies=" + std::string(3000, '[')});
              }),
              HasSubstr("levels deep"));
}

TEST(ConfigErrors, NonMapTopLevelIsRejected) {
  EXPECT_THAT(LoadError("- a\n- b\n").message, HasSubstr("top level"));
}

// Found by fuzzing (fuzz/regressions/config/set_on_a_list.txt): --set on a
// config whose top level is not a map read parts[-1] (undefined behaviour,
// flagged by UBSan) to name the parent key.
TEST(ConfigErrors, SetOnAConfigThatIsNotAMapIsAnError) {
  for (const std::string& text : {std::string("- a\n- b\n"), std::string("just text\n"),
                                  std::string("3\n")}) {
    EXPECT_THAT(ConfigErrorOf([&] { ParseExperimentConfig(text, "top.yaml", {"scenario.avs=1"}); }),
                HasSubstr("--set scenario.avs=1: the config is not a map of keys"))
        << text;
  }
}

// Found by fuzzing (fuzz/regressions/problem/complex_key.yaml): a key that is
// not a name (`? [1, 0]` or `? ` with no key) threw yaml-cpp's
// TypedBadConversion ("bad conversion", exit 1) instead of a config error.
TEST(ConfigErrors, KeysMustBeNames) {
  for (const std::string& text :
       {std::string("? [a, b]\n: 1\n"), std::string("scenario: {? [x]: 1}\n"),
        std::string("model: {trust: {dist: uniform, ? {a: 1}: 2}}\n"),
        std::string("? \n: 1\n"),
        std::string("sweep: {replicates: 1, grid: {? [model.trust]: [0.5]}}\n")}) {
    const FileError e = LoadError(text);
    EXPECT_THAT(e.message, HasSubstr("must be a name")) << text;
    EXPECT_THAT(e.message, HasSubstr(e.path + ":")) << text;
  }
  TempDir dir;
  const std::string problem =
      dir.Write("p.yaml",
                "states: [a, b]\nactions: [x, y]\nprior: [0.5, 0.5]\n"
                "receiver_utility: [[1, 0], [0, 1]]\nsender_utility: [[1, 0], [1, 0]]\n"
                "trust: 1\n? [1, 0]\n: 2\n");
  EXPECT_THAT(ConfigErrorOf([&] { LoadProblemConfig(problem); }), HasSubstr("must be a name"));
  // Inside a grid value a complex key is only data: ToJson (the sweep's
  // config hash) does not throw on it.
  const ExperimentConfig c = ParseExperimentConfig(
      "sweep: {replicates: 1, grid: {model.trust: [{? [a]: 1}]}}\n", "grid.yaml");
  EXPECT_NO_THROW(ToJson(c));
}

// A directory, an empty file or a file of comments only is not a config: an
// error naming the path (it used to run with the built-in defaults), for the
// experiment loader and the problem loader alike.
TEST(ConfigErrors, DirectoryOrEmptyFileIsAnErrorNamingThePath) {
  TempDir dir;
  const std::string folder = (dir.path() / "configs").string();
  fs::create_directories(folder);
  const std::string dmsg = ConfigErrorOf([&] { LoadExperimentConfig(folder); });
  EXPECT_THAT(dmsg, HasSubstr(folder));
  EXPECT_THAT(dmsg, HasSubstr("a folder, not a file"));
  EXPECT_THAT(ConfigErrorOf([&] { LoadProblemConfig(folder); }), HasSubstr("a folder, not a file"));
  // A FIFO is refused at once (reading it would wait for a writer forever).
  const std::string fifo = (dir.path() / "config.fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const std::string fmsg = ConfigErrorOf([&] { LoadExperimentConfig(fifo); });
  EXPECT_THAT(fmsg, HasSubstr(fifo));
  EXPECT_THAT(fmsg, HasSubstr("a FIFO (named pipe), not a file"));
  for (const std::string& text : {std::string(""), std::string("# only a comment\n\n"),
                                  std::string("---\n"), std::string("~\n")}) {
    SCOPED_TRACE("text '" + text + "'");
    const std::string path = dir.Write("empty.yaml", text);
    const std::string msg = ConfigErrorOf([&] { LoadExperimentConfig(path); });
    EXPECT_THAT(msg, HasSubstr(path));
    EXPECT_THAT(msg, HasSubstr("empty"));
    // --set overrides do not turn an empty file into a config either.
    EXPECT_THAT(ConfigErrorOf([&] { LoadExperimentConfig(path, {"scenario.avs=2"}); }),
                HasSubstr(path + ": the file is empty"));
    EXPECT_THAT(ConfigErrorOf([&] { LoadProblemConfig(path); }),
                HasSubstr(path + ": the file is empty"));
  }
  // An explicit empty map is a deliberate "all defaults".
  const std::string braces = dir.Write("braces.yaml", "{}\n");
  EXPECT_EQ(ToJson(LoadExperimentConfig(braces)), ToJson(ExperimentConfig{}));
}

// SUMO counts time in whole milliseconds: it refuses a step below 0.001 s
// ("the minimum step-length is 0.001") and rounds any other step to a whole
// millisecond (0.0015 runs as 0.002 s), which would desynchronise the
// controller's clock. Both are config errors naming the key and the value.
TEST(ConfigErrors, StepLengthIsAWholeNumberOfMillisecondsOfAtLeastOne) {
  for (const char* bad : {"1e-9", "0.0005", "0.0009999", "0.0015", "0.1234"}) {
    SCOPED_TRACE(bad);
    const std::string msg = ConfigErrorOf(
        [&] { LoadExperimentConfig(kPaper, {std::string("scenario.step_length=") + bad}); });
    EXPECT_THAT(msg, HasSubstr("scenario.step_length = "));
    EXPECT_THAT(msg, HasSubstr("millisecond"));
  }
  EXPECT_THAT(ConfigErrorOf([&] { LoadExperimentConfig(kPaper, {"scenario.step_length=1e-9"}); }),
              HasSubstr("scenario.step_length = 1e-09"));
  for (const char* good : {"0.001", "0.002", "0.05", "0.1", "0.25", "1"}) {
    SCOPED_TRACE(good);
    EXPECT_NO_THROW(LoadExperimentConfig(kPaper, {std::string("scenario.step_length=") + good}));
  }
}

// The run is a whole number of steps: a duration between two is an error
// naming both neighbours (it used to be rounded without a word).
TEST(ConfigErrors, DurationIsAWholeNumberOfSteps) {
  const std::string msg = ConfigErrorOf([&] {
    LoadExperimentConfig(kPaper, {"scenario.duration=100.05", "scenario.step_length=0.1"});
  });
  EXPECT_THAT(msg, HasSubstr("scenario.duration = 100.05 s is not a whole number of steps"));
  EXPECT_THAT(msg, HasSubstr("scenario.step_length = 0.1"));
  EXPECT_THAT(msg, HasSubstr("give 100 or 100.1"));
  EXPECT_THAT(ConfigErrorOf([&] {
                LoadExperimentConfig(kPaper, {"scenario.duration=10", "scenario.step_length=0.3"});
              }),
              HasSubstr("give 9.9 or 10.2"));
  for (const auto& [duration, step] : std::vector<std::pair<const char*, const char*>>{
           {"3600", "0.1"}, {"0.3", "0.1"}, {"7200", "0.002"}, {"30", "0.25"}, {"59.9", "0.1"}}) {
    SCOPED_TRACE(std::string(duration) + " / " + step);
    EXPECT_NO_THROW(LoadExperimentConfig(kPaper, {std::string("scenario.duration=") + duration,
                                                  std::string("scenario.step_length=") + step}));
  }
}

// ------------------------------------------------------------------ --set

TEST(ConfigOverrides, OverridesApply) {
  const ExperimentConfig c = LoadExperimentConfig(
      kPaper, {"scenario.duration=60", "policies=[ta_ebp]", "model.likelihood.s_max=1.5"});
  EXPECT_EQ(c.scenario.duration, 60.0);
  EXPECT_EQ(c.policies, std::vector<std::string>{"ta_ebp"});
  EXPECT_EQ(c.model.likelihood.s_max, 1.5);
  // Everything else as in the file.
  ExperimentConfig expected = LoadExperimentConfig(kPaper);
  expected.scenario.duration = 60;
  expected.policies = {"ta_ebp"};
  expected.model.likelihood.s_max = 1.5;
  EXPECT_EQ(ToJson(c), ToJson(expected));
}

TEST(ConfigOverrides, LaterOverridesWinAndCreateMissingSections) {
  const ExperimentConfig c =
      ParseExperimentConfig("", "empty.yaml",
                            {"scenario.avs=2", "scenario.avs=5", "model.assumed_trust=0.9",
                             "model.likelihood={type: logistic, s_max: 2, steepness: 3}"});
  EXPECT_EQ(c.scenario.avs, 5);
  ASSERT_TRUE(c.model.assumed_trust.has_value());
  EXPECT_EQ(*c.model.assumed_trust, 0.9);
  EXPECT_EQ(c.model.Knowledge(), TrustKnowledge::kAssumed);
  EXPECT_EQ(c.model.likelihood.type, LikelihoodType::kLogistic);
  EXPECT_EQ(c.model.likelihood.steepness, 3.0);
}

TEST(ConfigOverrides, ErrorsNameTheSetNotTheFile) {
  struct Case {
    std::string set, expected;
  };
  const std::vector<Case> cases = {
      {"scenario.avss=3", "scenario.avss"},
      {"model.trust=2", "model.trust = 2"},
      {"novalue", "KEY=VALUE"},
      {"scenario.duration=abc", "scenario.duration"},
      {"scenario.avs=-1", "scenario.avs = -1"},
      {"policies=[ta_ebp, ta_ebp]", "listed twice"},
      {"scenario..avs=3", "empty component"},
      {"scenario.avs=[1, 2", "not valid YAML"},
  };
  for (const Case& c : cases) {
    const std::string msg =
        ConfigErrorOf([&] { LoadExperimentConfig(kPaper, {"scenario.duration=60", c.set}); });
    EXPECT_THAT(msg, HasSubstr("--set " + c.set)) << c.set;
    EXPECT_THAT(msg, HasSubstr(c.expected)) << c.set;
    EXPECT_THAT(msg, Not(HasSubstr("paper.yaml"))) << c.set;
    // The error is about this --set, not the valid one before it.
    EXPECT_THAT(msg, Not(HasSubstr("scenario.duration=60"))) << c.set;
  }
}

// A map value for a section (scenario, model, model.likelihood, sweep) is
// merged into it key by key: `--set 'scenario={avs: 1}'` changes avs and keeps
// every other scenario key of the file (it used to replace the section, so the
// omitted keys fell back to the built-in defaults). Values that are maps
// themselves (a trust distribution, sweep.grid) still replace.
TEST(ConfigOverrides, MapValueMergesIntoASection) {
  const ExperimentConfig file = LoadExperimentConfig(kPaper);
  const ExperimentConfig c = LoadExperimentConfig(
      kPaper, {"scenario={avs: 1, duration: 60}", "model={likelihood: {s_max: 1.5}}"});
  ExperimentConfig expected = file;
  expected.scenario.avs = 1;
  expected.scenario.duration = 60;
  expected.model.likelihood.s_max = 1.5;
  EXPECT_EQ(ToJson(c), ToJson(expected));

  TempDir dir;
  const std::string path = dir.Write(
      "exp.yaml",
      "scenario: {hvs: 3, stop_distance: 3.5}\n"
      "model: {trust: {dist: uniform, low: 0.2, high: 0.4}, likelihood: {type: logistic}}\n"
      "sweep: {replicates: 3, grid: {model.prior_go: [0.1, 0.2], scenario.avs: [1, 2]}}\n");
  const ExperimentConfig m = LoadExperimentConfig(
      path, {"model={trust: {dist: beta, alpha: 2, beta: 5}}", "sweep={grid: {model.trust: [0.5]}}"});
  EXPECT_EQ(m.model.trust.dist, TrustDist::kBeta);  // a distribution replaces the old one
  EXPECT_EQ(m.model.trust.alpha, 2.0);
  EXPECT_EQ(m.model.likelihood.type, LikelihoodType::kLogistic);  // kept from the file
  ASSERT_TRUE(m.sweep.has_value());
  EXPECT_EQ(m.sweep->replicates, 3);  // kept from the file
  ASSERT_EQ(m.sweep->grid.size(), 1u);  // the grid is one value: replaced
  EXPECT_EQ(m.sweep->grid[0].first, "model.trust");

  // A bad key inside the merged map names the --set; a bad file key the file.
  const std::string set_error =
      ConfigErrorOf([&] { LoadExperimentConfig(path, {"scenario={avs: 1, avss: 2}"}); });
  EXPECT_THAT(set_error, HasSubstr("--set scenario={avs: 1, avss: 2}"));
  EXPECT_THAT(set_error, HasSubstr("scenario.avss"));
  const std::string bad_file = dir.Write("bad.yaml", "scenario:\n  hvs: 3\n  min_gap: -1\n");
  const std::string file_error =
      ConfigErrorOf([&] { LoadExperimentConfig(bad_file, {"scenario={avs: 1}"}); });
  EXPECT_THAT(file_error, HasSubstr(bad_file));
  EXPECT_THAT(file_error, HasSubstr("scenario.min_gap = -1"));
  EXPECT_THAT(file_error, Not(HasSubstr("--set")));
}

TEST(ConfigOverrides, FileErrorsStillNameTheFileWhenOverridesAreGiven) {
  const FileError e = LoadError("scenario:\n  avs: 8\n  avss: 3\n", {"scenario.duration=60"});
  EXPECT_THAT(e.message, HasSubstr(e.path + ":3"));
  EXPECT_THAT(e.message, Not(HasSubstr("--set")));
}

// ------------------------------------------------------------------ problems

constexpr const char* kGoodProblem =
    "states: [a, b]\n"
    "actions: [x, y]\n"
    "prior: [0.4, 0.6]\n"
    "receiver_utility:\n"
    "  - [1, 0]\n"
    "  - [0, 1]\n"
    "sender_utility:\n"
    "  - [1, 0]\n"
    "  - [1, 0]\n"
    "trust: 0.5\n";

TEST(ProblemConfig, LoadsAGoodFile) {
  TempDir dir;
  const ProblemConfig p = LoadProblemConfig(dir.Write("p.yaml", kGoodProblem));
  EXPECT_EQ(p.states, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(p.actions, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(p.prior, (std::vector<double>{0.4, 0.6}));
  ASSERT_EQ(p.receiver_utility.size(), 2u);
  EXPECT_EQ(p.receiver_utility[1], (std::vector<double>{0, 1}));
  EXPECT_EQ(p.sender_utility[1], (std::vector<double>{1, 0}));
  EXPECT_EQ(p.trust, 0.5);
}

TEST(ProblemConfig, MissingUnknownAndBadlyTypedKeysAreErrors) {
  TempDir dir;
  std::string text = kGoodProblem;
  {
    std::string missing = text;
    missing.erase(missing.find("prior:"), std::string("prior: [0.4, 0.6]\n").size());
    const std::string path = dir.Write("missing.yaml", missing);
    const std::string msg = ConfigErrorOf([&] { LoadProblemConfig(path); });
    EXPECT_THAT(msg, HasSubstr("missing"));
    EXPECT_THAT(msg, HasSubstr("'prior'"));
    EXPECT_THAT(msg, HasSubstr(path));
  }
  {
    const std::string path = dir.Write("unknown.yaml", text + "trsut: 0.5\n");
    const std::string msg = ConfigErrorOf([&] { LoadProblemConfig(path); });
    EXPECT_THAT(msg, HasSubstr("trsut"));
    EXPECT_THAT(msg, HasSubstr(path + ":11"));
  }
  {
    std::string bad = text;
    bad.replace(bad.find("trust: 0.5"), std::string("trust: 0.5").size(), "trust: high");
    const std::string path = dir.Write("badtype.yaml", bad);
    const std::string msg = ConfigErrorOf([&] { LoadProblemConfig(path); });
    EXPECT_THAT(msg, HasSubstr("trust"));
    EXPECT_THAT(msg, HasSubstr("high"));
    EXPECT_THAT(msg, HasSubstr(path + ":10"));
  }
  {
    std::string bad = text;
    bad.replace(bad.find("  - [0, 1]"), std::string("  - [0, 1]").size(), "  - [0, one]");
    const std::string path = dir.Write("badcell.yaml", bad);
    const std::string msg = ConfigErrorOf([&] { LoadProblemConfig(path); });
    EXPECT_THAT(msg, HasSubstr("receiver_utility"));
    EXPECT_THAT(msg, HasSubstr("one"));
    EXPECT_THAT(msg, HasSubstr(path + ":6"));
  }
  {
    const std::string path = dir.Write("duplicate.yaml", text + "prior: [0.5, 0.5]\n");
    const std::string msg = ConfigErrorOf([&] { LoadProblemConfig(path); });
    EXPECT_THAT(msg, HasSubstr("'prior'"));
    EXPECT_THAT(msg, HasSubstr("twice"));
    EXPECT_THAT(msg, HasSubstr(path + ":11"));
  }
  {
    const std::string path = dir.Write("empty.yaml", "");
    EXPECT_THAT(ConfigErrorOf([&] { LoadProblemConfig(path); }), HasSubstr(path));
  }
}

TEST(ProblemConfig, ShippedProblemsLoad) {
  if (!fs::is_directory(kProblems)) GTEST_FAIL() << kProblems << " is missing";
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(kProblems)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const ProblemConfig p = LoadProblemConfig(entry.path().string());
    EXPECT_GE(p.states.size(), 2u);
    EXPECT_GE(p.actions.size(), 2u);
    EXPECT_EQ(p.prior.size(), p.states.size());
    EXPECT_EQ(p.receiver_utility.size(), p.states.size());
    EXPECT_EQ(p.sender_utility.size(), p.states.size());
    for (const auto& row : p.receiver_utility) EXPECT_EQ(row.size(), p.actions.size());
    for (const auto& row : p.sender_utility) EXPECT_EQ(row.size(), p.actions.size());
    EXPECT_GE(p.trust, 0.0);
    EXPECT_LE(p.trust, 1.0);
    ++loaded;
  }
  if (loaded == 0) GTEST_FAIL() << "no problem files in " << kProblems;
}

// ------------------------------------------------------------------ beyond the paper

TEST(ConfigBeyond, ShippedStudiesLoadAndThePaperIsNotBeyond) {
  EXPECT_FALSE(LoadExperimentConfig(kPaper).BeyondPaper());
  for (const char* name : {"learned_trust", "dynamic_trust", "noise"}) {
    SCOPED_TRACE(name);
    const ExperimentConfig c =
        LoadExperimentConfig(std::string(TAEBP_SOURCE_DIR) + "/configs/" + name + ".yaml");
    EXPECT_TRUE(c.BeyondPaper());
  }
  EXPECT_TRUE(ParseExperimentConfig("policies: [population_mean]", "t.yaml").BeyondPaper());
  EXPECT_TRUE(ParseExperimentConfig("model: {noise: {kind: none}}", "t.yaml").BeyondPaper());
}

// Every config the project ships (configs/*.yaml: the paper, the studies, the
// benchmarks, the Bologna scenarios) loads under the one schema: a key renamed
// or a range tightened without the shipped files following fails here, naming
// the file.
TEST(ConfigShipped, EveryShippedConfigLoads) {
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(std::string(TAEBP_SOURCE_DIR) + "/configs")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(LoadExperimentConfig(entry.path().string()));
    ++loaded;
  }
  EXPECT_GE(loaded, 15) << "the shipped configs moved?";
}

TEST(ConfigBeyond, DefaultsOfEachSection) {
  const ExperimentConfig c = ParseExperimentConfig(
      "model: {trust_dynamics: {}, noise: {}, learning: {}}\npolicies: [ta_ebp_learned]\n", "t.yaml");
  ASSERT_TRUE(c.model.trust_dynamics && c.model.noise && c.model.learning);
  EXPECT_EQ(c.model.trust_dynamics->strength, 10.0);
  EXPECT_EQ(c.model.trust_dynamics->quality.nudge_stop, 0.0);
  EXPECT_EQ(c.model.trust_dynamics->quality.still_stop, 1.0);
  EXPECT_EQ(c.model.noise->kind, NoiseKind::kGaussian);
  EXPECT_EQ(c.model.noise->design, NoiseDesign::kAware);
  EXPECT_EQ(c.model.noise->delta, 0.01);
  EXPECT_EQ(c.model.learning->delta, 0.01);
  EXPECT_FALSE(c.model.learning->prior.has_value());
  EXPECT_EQ(c.outputs.interval, 60.0);
  // Round trip through the one schema, the learning prior included.
  const ExperimentConfig rich = ParseExperimentConfig(
      "model:\n  trust_dynamics: {strength: 4, failure_weight: 6, forgetting: 0.01,\n"
      "                   quality: {nudge_stop: 0.25}}\n"
      "  noise: {kind: uniform, scale: 0.3, bias: -0.05, delta: 0.02, design: paper}\n"
      "  learning: {delta: 0.05, decay: 0.75, constant_level: true, probe: false,\n"
      "             prior: {dist: discrete, values: [0.3, 0.8], weights: [1, 2]}}\n"
      "outputs: {interval: 120, per_hv: false}\n",
      "rich.yaml");
  EXPECT_EQ(ToJson(ParseExperimentConfig(ToYaml(rich), "back.yaml")), ToJson(rich));
  EXPECT_EQ(rich.model.learning->prior->values, (std::vector<double>{0.3, 0.8}));
}

TEST(ConfigBeyond, BadValuesNameTheKeyAndTheValue) {
  struct Case {
    const char* yaml;
    std::vector<const char*> expect;
  };
  const std::vector<Case> cases = {
      {"model: {trust_dynamics: {strength: 0}}", {"model.trust_dynamics.strength", "0", "> 0"}},
      {"model: {trust_dynamics: {failure_weight: -1}}",
       {"model.trust_dynamics.failure_weight", "-1"}},
      {"model: {trust_dynamics: {forgetting: 1.5}}", {"model.trust_dynamics.forgetting", "1.5"}},
      {"model: {trust_dynamics: {quality: {nudge_stop: 2}}}",
       {"model.trust_dynamics.quality.nudge_stop", "2"}},
      {"model: {trust: 1, trust_dynamics: {}}", {"model.trust", "1", "strictly inside (0, 1)"}},
      {"model: {trust: {dist: uniform, low: 0, high: 0.5}, trust_dynamics: {}}",
       {"model.trust.low", "0"}},
      {"model: {noise: {kind: laplace}}", {"model.noise.kind", "laplace", "gaussian"}},
      {"model: {noise: {scale: -0.1}}", {"model.noise.scale", "-0.1"}},
      {"model: {noise: {delta: 1}}", {"model.noise.delta", "1"}},
      {"model: {noise: {design: smart}}", {"model.noise.design", "smart", "aware, paper"}},
      {"model: {learning: {delta: 0}}", {"model.learning.delta", "0"}},
      {"model: {learning: {decay: -2}}", {"model.learning.decay", "-2"}},
      {"model: {learning: {prior: {dist: beta, alpha: 0, beta: 1}}}",
       {"model.learning.prior.alpha", "0"}},
      {"model: {prior_go: 0.5}\npolicies: [ta_ebp_learned]", {"model.prior_go", "0.5", "p*"}},
      {"outputs: {interval: 0.5}", {"outputs.interval", "0.5"}},
      // Issue 42: the learner's forgetting, the robust design's margin.
      {"model: {experience: {forgetting: 0}}", {"model.experience.forgetting", "0", "(0, 1]"}},
      {"model: {experience: {forgetting: 1.05}}", {"model.experience.forgetting", "1.05"}},
      {"model: {experience: {forgetting: .nan}}", {"model.experience.forgetting", "nan"}},
      {"model: {experience: {design: robust, margin: -0.1}}",
       {"model.experience.margin", "-0.1", "[0, 1)"}},
      {"model: {experience: {design: sturdy}}",
       {"model.experience.design", "sturdy", "guarded, paper, robust"}},
      {"policies: [ta_ebp_learnt]", {"ta_ebp_learnt", "ta_ebp_learned", "population_mean"}},
      // The robust design without model.experience: the key, one level too
      // high, and where it lives.
      {"model: {design: robust}",
       {"unknown key 'model.design'", "did you mean ", "model.experience.design?"}},
      {"model: {margin: 0.1}", {"unknown key 'model.margin'", "did you mean model.experience.margin?"}},
      {"policies: [random_nudges]", {"random_nudges", "random_nudge"}},
      {"model: {experience: {strengths: [5, -1]}}", {"model.experience.strengths[1]", "-1", "> 0"}},
      {"model: {experience: {strengths: [5, .inf]}}", {"model.experience.strengths[1]", "inf"}},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.yaml);
    const FileError e = LoadError(k.yaml);
    EXPECT_THAT(e.message, HasSubstr(e.path));
    for (const char* part : k.expect) EXPECT_THAT(e.message, HasSubstr(part));
  }
  // Unknown keys inside the new sections, with the line.
  const FileError unknown = LoadError("model:\n  noise:\n    kind: gaussian\n    sigma: 0.1\n");
  EXPECT_THAT(unknown.message, HasSubstr("model.noise.sigma"));
  EXPECT_THAT(unknown.message, HasSubstr(unknown.path + ":4"));
  EXPECT_THAT(LoadError("model: {trust_dynamics: {quality: {near_miss: 0}}}").message,
              HasSubstr("model.trust_dynamics.quality.near_miss"));
  // And from --set.
  EXPECT_THAT(LoadError("model: {}", {"model.noise.scale=-3"}).message,
              HasSubstr("--set model.noise.scale=-3"));
}

}  // namespace
}  // namespace taebp
