// scenario.outputs.ssm: off by default, SUMO's defaults with `ssm: {}`, and
// errors that name the key, the value and the file.
#include "taebp/config/config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"

#include <string>

namespace taebp {
namespace {

using ::testing::HasSubstr;

std::string LoadError(const std::string& yaml, std::string* path) {
  test::TempDir dir;
  *path = dir.Write("ssm.yaml", yaml);
  return test::ErrorOf<ConfigError>([&] { LoadExperimentConfig(*path); });
}

TEST(SsmConfig, OffByDefaultAndSumosDefaultsWhenGivenEmpty) {
  EXPECT_FALSE(ParseExperimentConfig("{}", "t.yaml").scenario.outputs.ssm.has_value());
  const ExperimentConfig c = ParseExperimentConfig("scenario: {outputs: {ssm: {}}}", "t.yaml");
  ASSERT_TRUE(c.scenario.outputs.ssm.has_value());
  const SsmConfig& s = *c.scenario.outputs.ssm;
  EXPECT_EQ(s.measures, (std::vector<std::string>{"TTC", "DRAC", "PET"}));
  // SUMO 1.15's MSDevice_SSM defaults: TTC 3 s, DRAC 3 m/s^2, PET 2 s.
  EXPECT_EQ(s.thresholds.ttc, 3.0);
  EXPECT_EQ(s.thresholds.drac, 3.0);
  EXPECT_EQ(s.thresholds.pet, 2.0);
  // The SSM outputs are metrics too: a sweep may keep them (Any() is the
  // file-only outputs a sweep refuses).
  EXPECT_FALSE(c.scenario.outputs.Any());
  const ExperimentConfig own = ParseExperimentConfig(
      "scenario: {outputs: {ssm: {measures: [PET], thresholds: {PET: 1.5}}}}", "t.yaml");
  EXPECT_EQ(own.scenario.outputs.ssm->measures, (std::vector<std::string>{"PET"}));
  EXPECT_EQ(own.scenario.outputs.ssm->thresholds.pet, 1.5);
}

TEST(SsmConfig, BadMeasuresAndThresholdsNameKeyValueAndFile) {
  struct Case {
    std::string yaml, expected;
  };
  const Case cases[] = {
      {"scenario: {outputs: {ssm: {measures: [TTC, TTX]}}}\n",
       "scenario.outputs.ssm.measures: 'TTX' is not a conflict measure of SUMO 1.15's SSM "
       "device (known: TTC, DRAC, PET)"},
      {"scenario: {outputs: {ssm: {measures: [ttc]}}}\n", "'ttc' is not a conflict measure"},
      {"scenario: {outputs: {ssm: {measures: [PET, PET]}}}\n", "'PET' is listed twice"},
      {"scenario: {outputs: {ssm: {measures: []}}}\n", "scenario.outputs.ssm.measures is empty"},
      {"scenario: {outputs: {ssm: {thresholds: {TTC: 0}}}}\n",
       "scenario.outputs.ssm.thresholds.TTC = 0 must be > 0"},
      {"scenario: {outputs: {ssm: {thresholds: {DRAC: -1}}}}\n",
       "scenario.outputs.ssm.thresholds.DRAC = -1 must be > 0"},
      {"scenario: {outputs: {ssm: {thresholds: {BR: 1}}}}\n",
       "unknown key 'scenario.outputs.ssm.thresholds.BR'"},
      {"scenario: {outputs: {ssm: {junction_radius: -2}}}\n",
       "scenario.outputs.ssm.junction_radius = -2 must be >= 0"},
      // A threshold for a measure not measured would be silently ignored.
      {"scenario: {outputs: {ssm: {measures: [PET], thresholds: {TTC: 1.5}}}}\n",
       "scenario.outputs.ssm.thresholds.TTC is set but TTC is not among "
       "scenario.outputs.ssm.measures [PET]: add it there or drop the threshold"},
  };
  for (const Case& c : cases) {
    std::string path;
    const std::string message = LoadError(c.yaml, &path);
    EXPECT_THAT(message, HasSubstr(c.expected)) << c.yaml;
    EXPECT_THAT(message, HasSubstr(path)) << c.yaml;
  }
}

}  // namespace
}  // namespace taebp
