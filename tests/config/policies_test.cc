// The one table of policies (config/policies.h) against what reads it: the
// config's validation and default, the game enum, the keys a policy reads,
// and the documents generated from it (README's list, docs/policies.md).
#include "taebp/config/config.h"
#include "taebp/config/policies.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "test_support.h"

namespace taebp {
namespace {

using ::testing::HasSubstr;
namespace per = persuasion;

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The text between <!-- MARKER:begin ... --> and <!-- MARKER:end --> of a file.
std::string Block(const std::string& path, const std::string& marker) {
  const std::string text = ReadFile(std::string(TAEBP_SOURCE_DIR) + "/" + path);
  const std::size_t begin = text.find("<!-- " + marker + ":begin");
  const std::size_t end = text.find("<!-- " + marker + ":end -->");
  if (begin == std::string::npos || end == std::string::npos) {
    ADD_FAILURE() << path << " has no " << marker << " block";
    return "";
  }
  const std::size_t first = text.find("-->\n", begin) + 4;
  return text.substr(first, end - first);
}

TEST(Policies, NamesKindsAndGamesAreOneToOne) {
  std::set<std::string> names;
  std::set<int> kinds, games;
  for (const PolicyInfo& p : Policies()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name;
    EXPECT_TRUE(kinds.insert(static_cast<int>(p.kind)).second) << p.name;
    EXPECT_EQ(FindPolicy(p.name), &p);
    EXPECT_EQ(&PolicyOf(p.kind), &p);
    EXPECT_NE(std::string(p.label), "") << p.name;
    if (p.plays_game) {
      EXPECT_TRUE(games.insert(static_cast<int>(p.game)).second) << p.name;
      EXPECT_EQ(&PolicyOf(p.game), &p);
      EXPECT_STREQ(PolicyName(p.game), p.name);
      EXPECT_EQ(ParseGamePolicy(p.name), p.game);
      EXPECT_TRUE(p.needs_avs) << p.name << ": a game needs AVs";
    }
  }
  EXPECT_EQ(names.size(), 9u);
  EXPECT_EQ(GamePolicies().size(), 8u);  // every value of persuasion::Policy
  EXPECT_EQ(FindPolicy("TA_EBP"), nullptr);
  EXPECT_FALSE(SumoNative().plays_game);
  EXPECT_FALSE(PlaysGame(SumoNative().name));
  EXPECT_TRUE(PlaysGame("ta_ebp"));
  EXPECT_FALSE(PlaysGame("bogus"));
  EXPECT_EQ(PolicyLabel("ta_ebp"), "TA-EBP");
  EXPECT_EQ(PolicyLabel("bogus"), "bogus");
}

TEST(Policies, ParseGamePolicyNamesTheValueAndTheChoices) {
  const std::string unknown = test::ErrorOf<ConfigError>([] { ParseGamePolicy("bogus"); });
  EXPECT_THAT(unknown, HasSubstr("policy 'bogus' is unknown"));
  EXPECT_THAT(unknown, HasSubstr("ta_ebp_learned"));
  EXPECT_THAT(test::ErrorOf<ConfigError>([] { ParseGamePolicy(SumoNative().name); }),
              HasSubstr("plays no game"));
}

TEST(Policies, ConfigAcceptsEveryNameAndListsThemAllWhenOneIsWrong) {
  for (const PolicyInfo& p : Policies()) {
    ExperimentConfig c;
    c.policies = {p.name};
    if (p.kind == PolicyKind::kTaEbpLearned) c.model.prior_go = 0.2;
    std::string why;
    EXPECT_TRUE(c.IsValid(&why)) << p.name << ": " << why;
    EXPECT_EQ(c.BeyondPaper(), p.beyond_paper) << p.name;
  }
  ExperimentConfig c;
  c.policies = {"bogus"};
  std::string why;
  EXPECT_FALSE(c.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("'bogus' is not one of " + PolicyChoices()));
  for (const PolicyInfo& p : Policies()) EXPECT_THAT(PolicyChoices(), HasSubstr(p.name));
}

TEST(Policies, DefaultIsThePapersThree) {
  EXPECT_EQ(ExperimentConfig{}.policies, (std::vector<std::string>{"no_ebp", "no_trust", "ta_ebp"}));
}

TEST(Policies, WhatEachPolicyReads) {
  const PolicyInfo& native = SumoNative();
  // Traffic keys: every policy.
  for (const PolicyInfo& p : Policies())
    for (const char* key : {"scenario.demand.flow", "scenario.seed", "scenario.duration",
                            "scenario.av_share", "scenario.avs", "outputs.interval"})
      EXPECT_TRUE(PolicyReads(p, key)) << p.name << " " << key;
  // The model and the game's scenario keys: not sumo_native.
  for (const char* key : {"model", "model.trust", "model.trust.alpha", "model.prior_go",
                          "model.learning.prior", "scenario.encounter_pairs",
                          "scenario.major_road.yield_cost"})
    EXPECT_FALSE(PolicyReads(native, key)) << key;
  EXPECT_TRUE(PolicyReads(PolicyOf(PolicyKind::kTaEbp), "model.trust"));
  // A prefix only counts at a dot: model.trusted would be another key.
  EXPECT_TRUE(PolicyReads(PolicyOf(PolicyKind::kTaEbp), "model.learningx"));
  EXPECT_FALSE(PolicyReads(PolicyOf(PolicyKind::kTaEbp), "model.learning"));
  EXPECT_TRUE(PolicyReads(PolicyOf(PolicyKind::kTaEbp), "model.assumed_trust"));
  EXPECT_FALSE(PolicyReads(PolicyOf(PolicyKind::kNoTrust), "model.assumed_trust"));
  EXPECT_TRUE(PolicyReads(PolicyOf(PolicyKind::kTaEbpLearned), "model.learning.prior"));
  EXPECT_FALSE(PolicyReads(PolicyOf(PolicyKind::kTaEbpLearned), "model.trust_knowledge"));
  // What ta_ebp commits to against a learner: ta_ebp's alone; the learner's
  // own rule (forgetting, k) is every game policy's.
  for (const PolicyInfo& p : Policies()) {
    if (!p.plays_game) continue;
    const bool ta = p.kind == PolicyKind::kTaEbp;
    EXPECT_EQ(PolicyReads(p, "model.experience.design"), ta) << p.name;
    EXPECT_EQ(PolicyReads(p, "model.experience.margin"), ta) << p.name;
    EXPECT_TRUE(PolicyReads(p, "model.experience.forgetting")) << p.name;
  }
}

TEST(Policies, CliPageListIsGeneratedFromTheTable) {
  EXPECT_EQ(Block("docs/cli.md", "policies"), PolicyListMarkdown())
      << "run tools/refresh-docs";
  for (const PolicyInfo& p : Policies())
    EXPECT_THAT(PolicyListMarkdown(), HasSubstr(std::string("`") + p.name + "`"));
}

TEST(Policies, DocsTableIsGeneratedFromTheTable) {
  EXPECT_EQ(Block("docs/policies.md", "policies-table"), PoliciesMarkdown())
      << "run tools/refresh-docs";
}

}  // namespace
}  // namespace taebp
