// Errors of the experiment config loader: each names the key, the value and where
// it came from (file:line or the --set text); and how --set overrides apply.
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

}  // namespace
}  // namespace taebp
