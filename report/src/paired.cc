// Paired games (scenario.paired): paired.csv, one row per game and branch
// policy, and summary.json's "paired" section: each policy's rates over the
// paired games with their clustered intervals, and the differences between
// two policies on the same games.
#include "taebp/report/paired.h"

#include "taebp/base/number_text.h"
#include "taebp/report/clustered.h"
#include "taebp/report/report.h"

#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace taebp {
namespace {

using json = nlohmann::ordered_json;

std::string Opt(double v) { return std::isfinite(v) ? NumberText(v) : std::string(); }
json OptJson(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

struct PairedColumn {
  const char* name;
  const char* description;
  std::string (*cell)(const PairedRecord& r);
};

const std::vector<PairedColumn>& Columns() {
  static const std::vector<PairedColumn> cols = {
      {"game", "the game: HOST-K, the K-th paired game of the run of policy HOST (the same in every row of the game)",
       [](const PairedRecord& r) { return r.game; }},
      {"host", "the policy of the run the game formed in", [](const PairedRecord& r) { return r.host; }},
      {"policy", "the policy this branch played the game under", [](const PairedRecord& r) { return r.policy; }},
      {"time", "when the game formed (s)", [](const PairedRecord& r) { return NumberText(r.time); }},
      {"junction", "SUMO junction id", [](const PairedRecord& r) { return r.junction; }},
      {"av", "the AV", [](const PairedRecord& r) { return r.av; }},
      {"hv", "the HV", [](const PairedRecord& r) { return r.hv; }},
      {"status", "ok (the game finished), unfinished (the window or the run ended first) or failed (error)",
       [](const PairedRecord& r) { return r.status; }},
      {"intent", "the AV's intent (go / stop; the same draw under every policy)",
       [](const PairedRecord& r) { return std::string(r.intent_go ? "go" : "stop"); }},
      {"commanded_nudge", "the nudge the branch's scheme commanded (m)",
       [](const PairedRecord& r) { return NumberText(r.nudge); }},
      {"hv_action", "DC or DR", [](const PairedRecord& r) { return std::string(r.hv_dc ? "DC" : "DR"); }},
      {"av_action", "go or wait", [](const PairedRecord& r) { return std::string(r.av_first ? "go" : "wait"); }},
      {"collision", "SUMO reported the AV and the HV colliding (1 / 0)",
       [](const PairedRecord& r) { return std::string(r.collision ? "1" : "0"); }},
      {"decided_at", "when the HV decided (s)", [](const PairedRecord& r) { return Opt(r.decided_at); }},
      {"av_clear", "s from the game's formation until the AV reached the edge after the junction (empty: not in the window)",
       [](const PairedRecord& r) { return Opt(r.av_clear); }},
      {"hv_clear", "the same for the HV", [](const PairedRecord& r) { return Opt(r.hv_clear); }},
      {"third_collisions", "collisions of a game move with a third vehicle in the window",
       [](const PairedRecord& r) { return std::to_string(r.third_collisions); }},
      {"pair_min_ttc", "the pair's least time to collision in the window, both carried on at speed and heading (s; empty: never on a collision course within 10 s)",
       [](const PairedRecord& r) { return Opt(r.pair_min_ttc); }},
      {"pair_min_pet", "the pair's post-encroachment time: the least time between the two occupying the same place (s; 0: a collision; empty: never)",
       [](const PairedRecord& r) { return Opt(r.pair_min_pet); }},
      {"hv_trust", "the HV's trust", [](const PairedRecord& r) { return NumberText(r.hv_trust); }},
      {"theory_dc", "the library's DC rate for this HV under the branch's policy",
       [](const PairedRecord& r) { return NumberText(r.theory_dc); }},
      {"theory_collision", "its collision rate", [](const PairedRecord& r) { return NumberText(r.theory_collision); }},
      {"error", "why a branch failed", [](const PairedRecord& r) { return r.error; }},
  };
  return cols;
}

// A measure of a row (NaN: not available for it).
double Measure(const PairedRecord& r, const std::string& m) {
  if (m == "collision") return r.collision ? 1 : 0;
  if (m == "dc") return r.hv_dc ? 1 : 0;
  if (m == "av_clear") return r.av_clear;
  if (m == "hv_clear") return r.hv_clear;
  if (m == "third_collisions") return static_cast<double>(r.third_collisions);
  if (m == "pair_min_ttc") return r.pair_min_ttc;
  if (m == "pair_min_pet") return r.pair_min_pet;
  return std::nan("");
}

}  // namespace

const std::vector<std::string>& PairedMeasures() {
  static const std::vector<std::string> m = {"collision", "dc", "av_clear", "hv_clear",
                                              "third_collisions", "pair_min_ttc", "pair_min_pet"};
  return m;
}

std::vector<std::string> PairedCsvColumns() {
  std::vector<std::string> out;
  for (const PairedColumn& c : Columns()) out.push_back(c.name);
  return out;
}

std::string PairedColumnsMarkdown() {
  std::ostringstream out;
  out << "| column | meaning |\n|---|---|\n";
  for (const PairedColumn& c : Columns()) out << "| `" << c.name << "` | " << c.description << " |\n";
  return out.str();
}

bool AnyPaired(const std::vector<PolicyRun>& runs) {
  for (const PolicyRun& r : runs)
    if (!r.paired.empty()) return true;
  return false;
}

std::string PairedCsv(const std::vector<PolicyRun>& runs) {
  std::string out;
  const std::vector<PairedColumn>& cols = Columns();
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + std::string(cols[i].name);
  out += '\n';
  for (const PolicyRun& run : runs)
    for (const PairedRecord& r : run.paired) {
      for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + CsvCell(cols[i].cell(r));
      out += '\n';
    }
  return out;
}

namespace {

// The rows by policy, and by game.
struct PairedRows {
  std::vector<std::string> policies;
  std::map<std::string, std::vector<const PairedRecord*>> of_policy;
  std::map<std::string, std::map<std::string, const PairedRecord*>> of_game;  // game -> policy -> row
  long failed = 0;
};

PairedRows GroupRows(const std::vector<PolicyRun>& runs) {
  PairedRows g;
  for (const PolicyRun& run : runs)
    for (const PairedRecord& r : run.paired) {
      if (!g.of_policy.count(r.policy)) g.policies.push_back(r.policy);
      if (r.status != "ok") {  // only finished games have an outcome
        g.failed += r.status == "failed";
        g.of_policy[r.policy];
        continue;
      }
      g.of_policy[r.policy].push_back(&r);
      g.of_game[r.game][r.policy] = &r;
    }
  return g;
}

// A policy's rates over its finished paired games (clustered by HV) with the
// theory's, and its mean clearances.
json PolicyRates(const std::vector<const PairedRecord*>& rows) {
  json q;
  q["games"] = rows.size();
  for (const char* m : {"collision", "dc"}) {
    std::map<std::string, ClusterCount> hvs;
    double theory = 0;
    for (const PairedRecord* r : rows) {
      ClusterCount& c = hvs[r->hv];
      c.y += Measure(*r, m);
      c.n += 1;
      theory += std::string(m) == "dc" ? r->theory_dc : r->theory_collision;
    }
    std::vector<ClusterCount> clusters;
    for (const auto& [hv, c] : hvs) clusters.push_back(c);
    const RateInterval ci = ClusteredRate(clusters);
    const std::string name = std::string(m) + "_rate";
    const bool none = rows.empty();
    q[name] = none ? json(nullptr) : json(ci.rate);
    q[name + "_lo"] = none ? json(nullptr) : json(ci.low);
    q[name + "_hi"] = none ? json(nullptr) : json(ci.high);
    q[name + "_deff"] = none ? json(nullptr) : json(ci.deff);
    q[name + "_clusters"] = ci.clusters;
    q["theory_" + name] = none ? json(nullptr) : json(theory / static_cast<double>(rows.size()));
  }
  for (const char* m : {"av_clear", "hv_clear"}) {
    double sum = 0;
    long n = 0;
    for (const PairedRecord* r : rows)
      if (std::isfinite(Measure(*r, m))) sum += Measure(*r, m), ++n;
    q[std::string(m) + "_mean"] = n ? json(sum / static_cast<double>(n)) : json(nullptr);
  }
  return q;
}

// Every two policies on the games both played: the mean difference a - b
// with its interval clustered by HV.
json Differences(const PairedRows& g) {
  const std::vector<std::string>& policies = g.policies;
  json diffs = json::array();
  for (std::size_t a = 0; a < policies.size(); ++a)
    for (std::size_t b = a + 1; b < policies.size(); ++b)
      for (const std::string& m : PairedMeasures()) {
        std::vector<double> d;
        std::vector<std::string> hv;
        for (const auto& [game, rows] : g.of_game) {
          const auto ra = rows.find(policies[a]), rb = rows.find(policies[b]);
          if (ra == rows.end() || rb == rows.end()) continue;
          const double x = Measure(*ra->second, m) - Measure(*rb->second, m);
          if (!std::isfinite(x)) continue;
          d.push_back(x);
          hv.push_back(ra->second->hv);
        }
        const MeanInterval mi = ClusteredMean(d, hv);
        diffs.push_back({{"a", policies[a]},
                         {"b", policies[b]},
                         {"measure", m},
                         {"games", d.size()},
                         {"mean", d.empty() ? json(nullptr) : json(mi.mean)},
                         {"lo", OptJson(mi.low)},
                         {"hi", OptJson(mi.high)},
                         {"clusters", mi.clusters}});
      }
  return diffs;
}

}  // namespace

nlohmann::ordered_json PairedSummary(const std::vector<PolicyRun>& runs) {
  PairedRows g = GroupRows(runs);
  json j;
  j["games"] = g.of_game.size();  // with at least one finished branch
  j["branches_failed"] = g.failed;
  long unfinished = 0;
  for (const PolicyRun& run : runs)
    for (const PairedRecord& r : run.paired) unfinished += r.status == "unfinished";
  j["branches_unfinished"] = unfinished;
  json by_policy = json::object();
  for (const std::string& p : g.policies) by_policy[p] = PolicyRates(g.of_policy[p]);
  j["policies"] = by_policy;
  j["differences"] = Differences(g);
  return j;
}

}  // namespace taebp
