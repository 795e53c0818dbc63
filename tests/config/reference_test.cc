// The generated config reference (taebp/config/reference.h) against the
// loader: every key the loader knows (the keys its unknown-key error lists,
// for every section and every trust distribution) is in the reference and
// has one line in the key table, no line names a key the loader does not
// know, and each default is the loader's (a --set of it changes nothing).
#include "taebp/config/config.h"
#include "taebp/config/reference.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <string>

namespace taebp {
namespace {

using ::testing::HasSubstr;

// `a.b.c` -> "a: {b: {c: VALUE}}".
std::string Nested(const std::string& key, const std::string& value) {
  const auto dot = key.find('.');
  if (dot == std::string::npos) return key + ": " + value;
  return key.substr(0, dot) + ": {" + Nested(key.substr(dot + 1), value) + "}";
}

// The names after "known keys here: " (or "known keys: ") of the loader's message.
std::set<std::string> KnownKeys(const std::string& message) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(message, m, std::regex("known keys(?: here)?: ([^)]*)\\)")))
      << message;
  std::set<std::string> out;
  std::string list = m.size() > 1 ? m[1].str() : "";
  std::size_t b = 0;
  while (b < list.size()) {
    const std::size_t e = list.find(", ", b);
    out.insert(list.substr(b, e == std::string::npos ? std::string::npos : e - b));
    if (e == std::string::npos) break;
    b = e + 2;
  }
  return out;
}

std::string LoaderError(const std::string& yaml) {
  try {
    ParseExperimentConfig(yaml, "reference_test.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(loaded without an error)";
}

// Direct children of `section` ("" for the top level) in the reference.
std::set<std::string> Children(const std::vector<ConfigKey>& keys, const std::string& section) {
  std::set<std::string> out;
  const std::string prefix = section.empty() ? "" : section + ".";
  for (const ConfigKey& k : keys) {
    if (k.key.rfind(prefix, 0) != 0) continue;
    const std::string rest = k.key.substr(prefix.size());
    if (!rest.empty() && rest.find('.') == std::string::npos) out.insert(rest);
  }
  return out;
}

TEST(ConfigReference, EveryKeyHasOneLineAndEveryLineNamesAKey) {
  std::vector<ConfigKey> keys;
  ASSERT_NO_THROW(keys = ExperimentConfigReference());
  std::set<std::string> schema, table;
  for (const ConfigKey& k : keys) EXPECT_TRUE(schema.insert(k.key).second) << "twice: " << k.key;
  for (const KeyDoc& d : ConfigKeyDocs()) {
    EXPECT_TRUE(table.insert(d.key).second) << "two lines for " << d.key;
    EXPECT_FALSE(std::string(d.meaning).empty()) << d.key;
    EXPECT_EQ(std::string(d.meaning).find('\n'), std::string::npos) << d.key;
  }
  for (const std::string& k : table) EXPECT_TRUE(schema.count(k)) << "a line for an unknown key: " << k;
  for (const std::string& k : schema) EXPECT_TRUE(table.count(k)) << "no line for " << k;
  EXPECT_GT(keys.size(), 100u);
}

TEST(ConfigReference, HasEveryKeyTheLoaderKnowsInEverySection) {
  const std::vector<ConfigKey> keys = ExperimentConfigReference();
  // The top level.
  EXPECT_EQ(Children(keys, ""), KnownKeys(LoaderError("zz_not_a_key: 1")));
  int sections = 0, dists = 0;
  for (const ConfigKey& k : keys) {
    if (!k.section) continue;
    if (k.type == "number or distribution") {
      // A trust map: per distribution, the keys the loader takes besides dist.
      std::set<std::string> known;
      const ConfigKey* dist = nullptr;
      for (const ConfigKey& d : keys)
        if (d.key == k.key + ".dist") dist = &d;
      ASSERT_NE(dist, nullptr) << k.key;
      for (const std::string& d : dist->choices) {
        const std::set<std::string> here =
            KnownKeys(LoaderError(Nested(k.key, "{dist: " + d + ", zz_not_a_key: 1}")));
        known.insert(here.begin(), here.end());
        ++dists;
      }
      EXPECT_EQ(Children(keys, k.key), known) << k.key;
      continue;
    }
    ++sections;
    EXPECT_EQ(Children(keys, k.key), KnownKeys(LoaderError(Nested(k.key, "{zz_not_a_key: 1}"))))
        << k.key;
  }
  EXPECT_GE(sections, 14);  // scenario, its 6 sections, model and its 5, sweep, outputs
  EXPECT_EQ(dists, 6);      // model.trust and model.learning.prior, 3 distributions each
}

TEST(ConfigReference, DefaultsAreTheLoadersDefaults) {
  const std::vector<ConfigKey> keys = ExperimentConfigReference();
  const std::string defaults = ToYaml(ParseExperimentConfig("{}", "defaults"));
  std::set<std::string> optional;  // keys under an optional section or value
  int checked = 0;
  for (const ConfigKey& k : keys) {
    bool under_optional = false;
    for (const std::string& o : optional) under_optional = under_optional || k.key.rfind(o + ".", 0) == 0;
    if (k.optional || under_optional) {
      optional.insert(k.key);
      EXPECT_TRUE(k.optional || under_optional) << k.key;
      if (k.optional) {
        EXPECT_EQ(k.default_value, "unset") << k.key;
      }
      continue;
    }
    if (k.section || k.default_value.empty() || k.key.find(".trust.") != std::string::npos) continue;
    SCOPED_TRACE(k.key + "=" + k.default_value);
    EXPECT_EQ(ToYaml(ParseExperimentConfig("{}", "defaults", {k.key + "=" + k.default_value})), defaults);
    ++checked;
  }
  EXPECT_GT(checked, 50);
  // A few by value, as config.h writes them.
  std::map<std::string, std::string> by_key;
  for (const ConfigKey& k : keys) by_key[k.key] = k.default_value;
  EXPECT_EQ(by_key["scenario.duration"], "3600");
  EXPECT_EQ(by_key["scenario.grid.speed"], "13.89");
  EXPECT_EQ(by_key["scenario.junctions.types"], "[allway_stop, priority_stop]");
  EXPECT_EQ(by_key["model.trust"], "0.6");
  EXPECT_EQ(by_key["scenario.major_road.enabled"], "true");
  EXPECT_EQ(by_key["scenario.major_road.comfortable_decel"], "3");
  EXPECT_EQ(by_key["policies"], "[no_ebp, no_trust, ta_ebp]");
}

TEST(ConfigReference, ChoicesAreTheOptionsNames) {
  for (const ConfigKey& k : ExperimentConfigReference()) {
    if (k.key == "scenario.stall_action") {
      EXPECT_THAT(k.choices, ::testing::ElementsAre("error", "record"));
    }
    if (k.key == "model.trust.dist") {
      EXPECT_THAT(k.choices, ::testing::ElementsAre("uniform", "beta", "discrete"));
    }
    if (k.type == "one of") {
      EXPECT_FALSE(k.choices.empty()) << k.key;
      // Every choice is accepted by the loader (trust maps need their keys).
      if (k.key.find(".dist") != std::string::npos) continue;
      for (const std::string& c : k.choices)
        EXPECT_THAT(LoaderError(Nested(k.key, c) + "\nzz_not_a_key: 1"), HasSubstr("unknown key 'zz_not_a_key'"))
            << k.key << " = " << c;
    }
  }
}

TEST(ConfigReference, MarkdownAndJsonHaveEveryKeyWithItsMeaning) {
  const std::string md = ConfigReferenceMarkdown();
  const std::string json = ConfigReferenceJson();
  for (const ConfigKey& k : ExperimentConfigReference()) {
    const bool heading = (k.section && k.type == "section") || k.key.find('.') == std::string::npos;
    EXPECT_THAT(md, HasSubstr(heading ? " `" + k.key + "`\n\n" + k.meaning
                                      : "\n`" + k.key + "`\n:   " + k.meaning))
        << k.key;
    EXPECT_THAT(json, HasSubstr("\"key\": \"" + k.key + "\"")) << k.key;
  }
}

}  // namespace
}  // namespace taebp
