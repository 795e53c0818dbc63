// The policies: the one table. Each policy's name, label, whether it plays the
// game, whether it needs AVs and which config keys it ignores are written
// once, in policies.cc; config validation, the report's labels, the result
// folder's recognition, the CLI's help, the sweep's reuse of results, the
// Python module and docs/policies.md read them from here (tests fail on drift:
// tests/config/policies_test.cc, tests/layers/policy_names_test.py).
#pragma once

#include "taebp/persuasion/outcomes.h"

#include <string>
#include <vector>

namespace taebp {

enum class PolicyKind {
  kSumoNative, kNoEbp, kNoTrust, kTaEbp, kFullReveal, kPopulationMean, kTaEbpLearned, kAlwaysNudge,
  kRandomNudge
};

struct PolicyInfo {
  PolicyKind kind;
  const char* name;   // as the config and the result folders write it
  const char* label;  // as tables and figures print it
  const char* colour; // as figures draw it (python/taebp/plot reads it: tables.json)
  // Plays the AV-HV game (an AV designs a signal); false: SUMO's own logic.
  bool plays_game;
  persuasion::Policy game;  // the game's policy (meaningful when plays_game)
  // Needs AVs among the vehicles (a game without AVs says nothing).
  bool needs_avs;
  // Only defined beyond the paper: its runs write the extra columns
  // (ExperimentConfig::BeyondPaper).
  bool beyond_paper;
  // Listed when a config gives no `policies` (the paper's three).
  bool by_default;
  // The config keys (a key or a whole section, e.g. "model") whose value
  // cannot change this policy's run: every other key may (PolicyReads).
  std::vector<std::string> ignores;
  const char* summary;  // one line for help and docs
};

// Every policy, in the order help, docs and messages list them.
const std::vector<PolicyInfo>& Policies();
// The row of `name`; nullptr when no policy is called that.
const PolicyInfo* FindPolicy(const std::string& name);
// The row of a kind / of a game policy.
const PolicyInfo& PolicyOf(PolicyKind kind);
const PolicyInfo& PolicyOf(persuasion::Policy game);
// The name of a game policy ("ta_ebp").
const char* PolicyName(persuasion::Policy game);
// The game policy called `name`; throws ConfigError naming the value and the
// choices for a name that is not one (sumo_native included: it plays none).
persuasion::Policy ParseGamePolicy(const std::string& name);
// The game policies, in table order.
std::vector<persuasion::Policy> GamePolicies();
// "sumo_native, no_ebp, ...": every name, for messages and help.
std::string PolicyChoices();
// The label of `name` ("TA-EBP"); `name` itself for a name not in the table.
std::string PolicyLabel(const std::string& name);
// Whether policy `p` reads the config key `key` ("scenario.av_share",
// "model.trust.alpha"): false when `key` is one of p.ignores or inside one.
bool PolicyReads(const PolicyInfo& p, const std::string& key);
// Whether `name` plays the game (false for sumo_native and unknown names).
bool PlaysGame(const std::string& name);

// The names of the policies with by_default: ExperimentConfig::policies' default.
std::vector<std::string> DefaultPolicies();

// The policy of SUMO's own junction logic (no controller).
const PolicyInfo& SumoNative();

// docs/policies.md's table and the README's policy list, generated from the
// table (tools/refresh-docs writes them; tests compare).
std::string PoliciesMarkdown();
std::string PolicyListMarkdown();
// The table as a JSON array of rows (`taebp policies --print json`, Python's
// taebp.policies()): name, label, plays_game, needs_avs, beyond_paper,
// by_default, ignores, summary.
std::string PoliciesJson();

}  // namespace taebp
