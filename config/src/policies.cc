// The one table of policies (policies.h). Every policy name in the C++
// sources is written here and nowhere else (tests/layers/policy_names_test.py).
#include "taebp/config/policies.h"

#include "taebp/config/config.h"

#include <nlohmann/json.hpp>

#include <sstream>
#include <stdexcept>

namespace taebp {

namespace {

using persuasion::Policy;

// What the policies that play no game cannot read: the model (the HVs' trust,
// the prior, the penalty, the likelihood, noise, dynamics, learning) and the
// scenario keys that only shape the game (which pairs meet, the nudge's speed
// and its check, the major-road game). Every other key changes SUMO's traffic
// or the outputs for every policy. scenario.av_share / avs / av_types are read
// by sumo_native too: on a network they leave SUMO's traffic alone (a vehicle
// is an AV by a hash of its id, its SUMO type unchanged) but decide the AV/HV
// split of its results (trips_av, delays by class), and on the figure-8 they
// decide the vehicles' ids and types.
const std::vector<std::string> kGameOnly = {"model", "scenario.encounter_pairs",
                                            "scenario.nudge_check", "scenario.creep_speed",
                                            "scenario.major_road"};
// The design's trust when it is not the HV's own: read by ta_ebp only
// (encounter/design.cc: no_trust designs for 1, population_mean for the mean,
// ta_ebp_learned for its learned bound, no_ebp and full_reveal for none).
const std::vector<std::string> kKnowledge = {"model.trust_knowledge", "model.assumed_trust"};
// ta_ebp_learned's schedule and prior: read by it only (its presence still
// turns on the beyond-the-paper columns of every policy: BeyondPaper).
const std::vector<std::string> kLearning = {"model.learning"};
// What ta_ebp commits to against a learner (model.experience.design and the
// robust design's margin): read by ta_ebp only; every other policy's scheme
// and its HVs' learning are the same under each (encounter/hv_population.cc).
const std::vector<std::string> kExperienceDesign = {"model.experience.design",
                                                    "model.experience.margin"};

std::vector<std::string> Join(std::initializer_list<const std::vector<std::string>*> lists) {
  std::vector<std::string> out;
  for (const auto* l : lists) out.insert(out.end(), l->begin(), l->end());
  return out;
}

const std::vector<PolicyInfo>& Table() {
  static const std::vector<PolicyInfo> table = {
      {PolicyKind::kSumoNative, "sumo_native", "SUMO native", "#000000", false, Policy::kNoEbp, false, false, false,
       kGameOnly,
       "SUMO's own junction logic, no controller: the baseline for flow, delay and SUMO's "
       "collisions"},
      {PolicyKind::kNoEbp, "no_ebp", "No EBP", "#7f7f7f", true, Policy::kNoEbp, true, false, true,
       Join({&kKnowledge, &kLearning, &kExperienceDesign}),
       "the AV never nudges; it goes when the HV, deciding from the prior, drives if clear"},
      {PolicyKind::kNoTrust, "no_trust", "No Trust", "#d62728", true, Policy::kNoTrust, true, false, true,
       Join({&kKnowledge, &kLearning, &kExperienceDesign}),
       "classic Bayesian persuasion: the AV designs its nudge for a fully trusting HV "
       "(theta_hat = 1)"},
      {PolicyKind::kTaEbp, "ta_ebp", "TA-EBP", "#1f77b4", true, Policy::kTaEbp, true, false, true, kLearning,
       "trust-aware persuasion: the AV designs for the HV's trust (model.trust_knowledge)"},
      {PolicyKind::kFullReveal, "full_reveal", "Full reveal", "#2ca02c", true, Policy::kFullReveal, true,
       false, false, Join({&kKnowledge, &kLearning, &kExperienceDesign}),
       "the AV nudges s_max exactly when it means to go"},
      {PolicyKind::kPopulationMean, "population_mean", "Population mean", "#ff7f0e", true,
       Policy::kPopulationMean, true, true, false,
       Join({&kKnowledge, &kLearning, &kExperienceDesign}),
       "TA-EBP with one design for every HV, for the mean of model.trust"},
      {PolicyKind::kTaEbpLearned, "ta_ebp_learned", "TA-EBP learned", "#9467bd", true,
       Policy::kTaEbpLearned, true, true, false, Join({&kKnowledge, &kExperienceDesign}),
       "TA-EBP for a safe lower bound of each HV's trust, learned from its responses "
       "(model.learning)"},
      {PolicyKind::kAlwaysNudge, "always_nudge", "Always nudge", "#17becf", true, Policy::kAlwaysNudge,
       true, true, false, Join({&kLearning, &kExperienceDesign}),
       "nudges TA-EBP's s* in every encounter whatever its intent and goes on its Go intent "
       "(the deterministic strategy of the paper's Section I; docs/influence.md)"},
      {PolicyKind::kRandomNudge, "random_nudge", "Random nudge", "#8c564b", true, Policy::kRandomNudge,
       true, true, false, Join({&kKnowledge, &kLearning, &kExperienceDesign}),
       "nudges in every encounter a magnitude drawn uniformly on (0, s_max] from its own random "
       "stream, independent of its intent, and goes on its Go intent (noise on the action, after "
       "Sagheb et al. 2023; docs/influence.md)"},
  };
  return table;
}

}  // namespace

const std::vector<PolicyInfo>& Policies() { return Table(); }

const PolicyInfo* FindPolicy(const std::string& name) {
  for (const PolicyInfo& p : Table())
    if (name == p.name) return &p;
  return nullptr;
}

const PolicyInfo& PolicyOf(PolicyKind kind) {
  for (const PolicyInfo& p : Table())
    if (p.kind == kind) return p;
  throw std::logic_error("PolicyOf: a kind without a row");
}

const PolicyInfo& PolicyOf(persuasion::Policy game) {
  for (const PolicyInfo& p : Table())
    if (p.plays_game && p.game == game) return p;
  throw std::logic_error("PolicyOf: a game policy without a row");
}

const char* PolicyName(persuasion::Policy game) { return PolicyOf(game).name; }

persuasion::Policy ParseGamePolicy(const std::string& name) {
  const PolicyInfo* p = FindPolicy(name);
  if (p && p->plays_game) return p->game;
  std::string games;
  for (const PolicyInfo& q : Table())
    if (q.plays_game) games += (games.empty() ? "" : ", ") + std::string(q.name);
  throw ConfigError("policy '" + name + "' " +
                    (p ? "plays no game" : "is unknown") + " (expected one of " + games + ")");
}

std::vector<persuasion::Policy> GamePolicies() {
  std::vector<persuasion::Policy> out;
  for (const PolicyInfo& p : Table())
    if (p.plays_game) out.push_back(p.game);
  return out;
}

std::string PolicyChoices() {
  std::string out;
  for (const PolicyInfo& p : Table()) out += (out.empty() ? "" : ", ") + std::string(p.name);
  return out;
}

std::string PolicyLabel(const std::string& name) {
  const PolicyInfo* p = FindPolicy(name);
  return p ? p->label : name;
}

bool PolicyReads(const PolicyInfo& p, const std::string& key) {
  for (const std::string& i : p.ignores)
    if (key == i || (key.size() > i.size() && key.compare(0, i.size(), i) == 0 &&
                     key[i.size()] == '.'))
      return false;
  return true;
}

bool PlaysGame(const std::string& name) {
  const PolicyInfo* p = FindPolicy(name);
  return p && p->plays_game;
}

std::vector<std::string> DefaultPolicies() {
  std::vector<std::string> out;
  for (const PolicyInfo& p : Table())
    if (p.by_default) out.push_back(p.name);
  return out;
}

const PolicyInfo& SumoNative() { return PolicyOf(PolicyKind::kSumoNative); }

namespace {

std::string Ignored(const PolicyInfo& p) {
  std::string out;
  for (const std::string& i : p.ignores)
    out += (out.empty() ? "" : ", ") + ("`" + i + (i.find('.') == std::string::npos ? ".*" : "") + "`");
  return out.empty() ? "none" : out;
}

}  // namespace

std::string PoliciesMarkdown() {
  std::ostringstream out;
  out << "| policy | label | plays the game | needs AVs | beyond the paper | keys it does not "
         "read | what it does |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const PolicyInfo& p : Table())
    out << "| `" << p.name << "` | " << p.label << " | " << (p.plays_game ? "yes" : "no")
        << " | " << (p.needs_avs ? "yes" : "no") << " | " << (p.beyond_paper ? "yes" : "no")
        << " | " << Ignored(p) << " | " << p.summary << " |\n";
  return out.str();
}

std::string PolicyListMarkdown() {
  std::ostringstream out;
  for (const PolicyInfo& p : Table())
    out << "- `" << p.name << "` (" << p.label << "): " << p.summary << "\n";
  return out.str();
}

std::string PoliciesJson() {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const PolicyInfo& p : Table())
    rows.push_back({{"name", p.name},
                    {"label", p.label},
                    {"colour", p.colour},
                    {"plays_game", p.plays_game},
                    {"needs_avs", p.needs_avs},
                    {"beyond_paper", p.beyond_paper},
                    {"by_default", p.by_default},
                    {"ignores", p.ignores},
                    {"summary", p.summary}});
  return rows.dump(2);
}

}  // namespace taebp
