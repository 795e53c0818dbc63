// encounters.csv (report.h EncountersCsv): its columns, one line each, in
// groups (the paper's, a network's, a run beyond the paper's, the SSM
// device's), and the CSV cells they print.
#include "taebp/report/report.h"

#include "metric_facts.h"
#include "taebp/base/number_text.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace taebp {

namespace {

// The encounters.csv columns: name and how a record prints. A new column is
// one line here (and one in the README's Outputs).
struct EncounterColumn {
  const char* name;
  std::string (*cell)(const PolicyRun& run, const EncounterRecord& e);
};
const std::vector<EncounterColumn>& EncounterColumns() {
  static const std::vector<EncounterColumn> cols = {
      {"policy", [](const PolicyRun& r, const EncounterRecord&) { return r.policy; }},
      {"time", [](const PolicyRun&, const EncounterRecord& e) { return NumberText(e.time); }},
      {"junction", [](const PolicyRun&, const EncounterRecord& e) { return e.junction; }},
      {"av", [](const PolicyRun&, const EncounterRecord& e) { return e.av; }},
      {"hv", [](const PolicyRun&, const EncounterRecord& e) { return e.hv; }},
      {"av_movement", [](const PolicyRun&, const EncounterRecord& e) { return e.av_movement; }},
      {"hv_movement", [](const PolicyRun&, const EncounterRecord& e) { return e.hv_movement; }},
      {"av_dir", [](const PolicyRun&, const EncounterRecord& e) { return std::string(1, e.av_dir); }},
      {"hv_dir", [](const PolicyRun&, const EncounterRecord& e) { return std::string(1, e.hv_dir); }},
      {"intent", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.intent_go ? "go" : "stop"); }},
      {"commanded_nudge", [](const PolicyRun&, const EncounterRecord& e) {
         return NumberText(e.commanded); }},
      {"observed_displacement", [](const PolicyRun&, const EncounterRecord& e) {
         return NumberText(e.observed); }},
      {"hv_trust", [](const PolicyRun&, const EncounterRecord& e) { return NumberText(e.hv_trust); }},
      {"hv_posterior", [](const PolicyRun&, const EncounterRecord& e) {
         return NumberText(e.posterior); }},
      {"hv_action", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.hv_dc ? "DC" : "DR"); }},
      {"av_action", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.av_first ? "go" : "wait"); }},
      {"collision", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.collision ? "1" : "0"); }},
  };
  return cols;
}

std::string Opt(double v) { return std::isfinite(v) ? NumberText(v) : std::string(); }

// The columns a run beyond the paper adds after those (README "Outputs").
const std::vector<EncounterColumn>& BeyondColumns() {
  static const std::vector<EncounterColumn> cols = {
      {"design_trust", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.design_trust); }},
      {"scheme_b", [](const PolicyRun&, const EncounterRecord& e) {
         return NumberText(e.beyond.scheme_b); }},
      {"hv_reading", [](const PolicyRun&, const EncounterRecord& e) {
         return NumberText(e.beyond.reading); }},
      {"hv_trust_after", [](const PolicyRun&, const EncounterRecord& e) {
         return NumberText(e.beyond.trust_after); }},
      {"outcome", [](const PolicyRun&, const EncounterRecord& e) { return e.beyond.outcome; }},
      {"quality", [](const PolicyRun&, const EncounterRecord& e) { return Opt(e.beyond.quality); }},
      {"theory_dc", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.theory_dc); }},
      {"theory_collision", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.theory_collision); }},
      {"oracle_dc", [](const PolicyRun&, const EncounterRecord& e) {
         return NumberText(e.beyond.oracle_dc); }},
      {"oracle_collision", [](const PolicyRun&, const EncounterRecord& e) {
         return NumberText(e.beyond.oracle_collision); }},
      {"regret", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.regret); }},
      {"learn_mode", [](const PolicyRun&, const EncounterRecord& e) { return e.beyond.mode; }},
      {"risk_level", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.risk_level); }},
      {"failure_probability", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.failure_probability); }},
      {"belief_lower", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.belief_lower); }},
      {"belief_upper", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.beyond.belief_upper); }},
      {"observation", [](const PolicyRun&, const EncounterRecord& e) {
         return e.beyond.observation; }},
  };
  return cols;
}

// The column a network scenario adds after those (README "Outputs").
const std::vector<EncounterColumn>& NetworkColumns() {
  static const std::vector<EncounterColumn> cols = {
      {"both_proceed_collides", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.both_proceed_collides ? "1" : "0"); }},
      {"premise", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(ToString(e.premise)); }},
      {"collision_after_handback", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.collision_after_handback ? "1" : "0"); }},
      {"encounter_kind", [](const PolicyRun&, const EncounterRecord& e) {
         return std::string(e.major_road ? "major_road" : "stop_lines"); }},
  };
  return cols;
}

// The columns the SSM device adds (scenario.outputs.ssm): the game's pair
// measures (EncounterRecord::ssm), empty where the device logged none.
const std::vector<EncounterColumn>& SsmColumns() {
  static const std::vector<EncounterColumn> cols = {
      {"ssm_min_ttc", [](const PolicyRun&, const EncounterRecord& e) { return Opt(e.ssm.min_ttc); }},
      {"ssm_max_drac", [](const PolicyRun&, const EncounterRecord& e) {
         return Opt(e.ssm.max_drac); }},
      {"ssm_min_pet", [](const PolicyRun&, const EncounterRecord& e) { return Opt(e.ssm.min_pet); }},
  };
  return cols;
}

bool AnySsm(const std::vector<PolicyRun>& runs) {
  return std::any_of(runs.begin(), runs.end(), [](const PolicyRun& r) { return r.ssm.on; });
}

bool AnyNetwork(const std::vector<PolicyRun>& runs) {
  return std::any_of(runs.begin(), runs.end(),
                     [](const PolicyRun& r) { return r.scenario_kind == "network"; });
}

}  // namespace

bool AnyBeyond(const std::vector<PolicyRun>& runs) {
  return std::any_of(runs.begin(), runs.end(), [](const PolicyRun& r) { return r.beyond.on; });
}

const char* ToString(Premise p) {
  switch (p) {
    case Premise::kHolds: return "holds";
    case Premise::kNoCollision: return "no_collision";
    case Premise::kUncertainMerge: return "uncertain_merge";
    case Premise::kNudgeInHvWay: return "nudge_in_hv_way";
    case Premise::kGrazing: return "grazing";
  }
  return "?";
}

std::string CsvCell(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::vector<std::string> EncounterCsvColumns(bool beyond, bool network, bool ssm) {
  std::vector<std::string> names;
  for (const EncounterColumn& c : EncounterColumns()) names.emplace_back(c.name);
  if (network)
    for (const EncounterColumn& c : NetworkColumns()) names.emplace_back(c.name);
  if (beyond)
    for (const EncounterColumn& c : BeyondColumns()) names.emplace_back(c.name);
  if (ssm)
    for (const EncounterColumn& c : SsmColumns()) names.emplace_back(c.name);
  return names;
}

std::vector<std::string> EncounterCsvColumnGroup(const std::string& group) {
  const std::vector<EncounterColumn>* cols = group == "paper"     ? &EncounterColumns()
                                             : group == "network" ? &NetworkColumns()
                                             : group == "beyond"  ? &BeyondColumns()
                                             : group == "ssm"     ? &SsmColumns()
                                                                  : nullptr;
  if (!cols) throw std::invalid_argument("no encounters.csv column group '" + group + "'");
  std::vector<std::string> names;
  for (const EncounterColumn& c : *cols) names.emplace_back(c.name);
  return names;
}

std::vector<std::string> SplitCsvRow(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) {
      cells.emplace_back();
      continue;
    }
    cells.back() += c;
  }
  return cells;
}

bool BeyondPaper(const std::vector<PolicyRun>& runs) { return AnyBeyond(runs); }

std::string EncountersCsv(const std::vector<PolicyRun>& runs) {
  std::vector<EncounterColumn> cols = EncounterColumns();
  if (AnyNetwork(runs))
    cols.insert(cols.end(), NetworkColumns().begin(), NetworkColumns().end());
  if (AnyBeyond(runs))
    cols.insert(cols.end(), BeyondColumns().begin(), BeyondColumns().end());
  if (AnySsm(runs)) cols.insert(cols.end(), SsmColumns().begin(), SsmColumns().end());
  std::string out;
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + std::string(cols[i].name);
  out += '\n';
  for (const PolicyRun& r : runs) {
    for (const EncounterRecord& e : r.encounters) {
      for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + CsvCell(cols[i].cell(r, e));
      out += '\n';
    }
  }
  return out;
}

}  // namespace taebp
