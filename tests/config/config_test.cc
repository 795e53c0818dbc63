// The experiment and problem config loader: documented values, one schema for
// load and save, and errors that name the key, the value and where they came
// from (file:line or the --set text).
#include "taebp/config/config.h"
#include "taebp/config/model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>

#include <sys/stat.h>

#include "config_support.h"
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

using test::ConfigErrorOf;
using test::FileError;
using test::kPaper;
using test::kProblems;
using test::LoadError;
using test::TempDir;

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
