#include "junction_selection.h"

#include "taebp/base/number_text.h"

#include "process.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace taebp::scenario_internal {

namespace {

// scenario.junctions.ids and .exclude name junctions the net has (not
// internal ones), of a type the rules cover; an id is not both.
void CheckListed(const JunctionSelection& sel, const net::NetFile& net, const std::string& where) {
  for (const std::string& id : sel.ids) {
    const net::Junction* j = net.FindJunction(id);
    if (!j || j->type == "internal")
      throw ConfigError("scenario.junctions.ids: junction '" + id + "' is not" + where);
    if (StopType(j->type, sel).empty())
      throw ConfigError("scenario.junctions.ids: junction '" + id + "' is a " + j->type +
                        " junction" + where +
                        "; the rules cover allway_stop, priority_stop, priority, "
                        "right_before_left and unregulated junctions");
  }
  for (const std::string& id : sel.exclude) {
    const net::Junction* j = net.FindJunction(id);
    if (!j || j->type == "internal")
      throw ConfigError("scenario.junctions.exclude: junction '" + id + "' is not" + where);
    if (std::find(sel.ids.begin(), sel.ids.end(), id) != sel.ids.end())
      throw ConfigError("scenario.junctions.exclude: junction '" + id +
                        "' is also in scenario.junctions.ids");
  }
}

// No approach faster than scenario.junctions.max_speed (0: any speed).
bool SlowEnough(const JunctionSelection& sel, const net::NetFile& net, const net::Junction& j) {
  if (sel.max_speed <= 0) return true;
  for (const std::string& lane : j.inc_lanes) {
    const net::Lane* l = net.FindLane(lane);
    if (l && l->speed > sel.max_speed + 1e-9) return false;
  }
  return true;
}

// Selected by type, a junction must be an intersection: two or more incoming
// roads with movements that conflict between them (an OSM import has many
// nodes where a road only changes its lanes, and a stop there would make
// SUMO's own all-way logic deadlock between the lanes).
bool IsIntersection(const net::NetFile& net, const net::Junction& j) {
  std::set<std::string> roads;
  for (const std::string& lane : j.inc_lanes)
    if (const net::Lane* l = net.FindLane(lane)) roads.insert(l->edge);
  if (roads.size() < 2) return false;
  for (std::size_t a = 0; a < j.links.size(); ++a)
    for (std::size_t b = 0; b < j.links.size(); ++b) {
      if (j.links[a] < 0 || j.links[b] < 0 || !j.foes[a][b]) continue;
      const net::Lane* la = net.FindLane(net.links()[j.links[a]].from_lane);
      const net::Lane* lb = net.FindLane(net.links()[j.links[b]].from_lane);
      if (la && lb && la->edge != lb->edge) return true;
    }
  return false;
}

// Why junctions of a selected type were passed over, for the message when
// nothing is selected.
struct PassedOver {
  std::map<std::string, int> all_types;  // every junction of the net by type
  int of_type = 0, excluded = 0, too_fast = 0, no_internal = 0, not_intersection = 0,
      few_arms = 0;
};

// Whether a junction of a selected type (not listed by id) passes the filters
// of scenario.junctions; counts the reason in `p` when not.
bool PassesFilters(const JunctionSelection& sel, const net::NetFile& net, const std::string& id,
                   const net::Junction& j,
                   const std::map<std::string, std::set<std::string>>& arms, PassedOver* p) {
  ++p->of_type;
  if (std::find(sel.exclude.begin(), sel.exclude.end(), id) != sel.exclude.end()) {
    ++p->excluded;
    return false;
  }
  if (!SlowEnough(sel, net, j)) {
    ++p->too_fast;
    return false;
  }
  // Arms (scenario.junctions.min_arms): the distinct junctions a junction's
  // normal car edges lead to or come from.
  if (sel.min_arms > 0) {
    const auto it = arms.find(id);
    if (it == arms.end() || static_cast<int>(it->second.size()) < sel.min_arms) {
      ++p->few_arms;
      return false;
    }
  }
  if (!IsIntersection(net, j)) {
    j.int_lanes.empty() ? ++p->no_internal : ++p->not_intersection;
    return false;
  }
  return true;
}

ConfigError NothingSelected(const JunctionSelection& sel, const PassedOver& p,
                            const std::string& where) {
  std::string list;
  for (const std::string& t : sel.types) list += (list.empty() ? "" : ", ") + t;
  std::string have;
  for (const auto& [type, n] : p.all_types)
    have += (have.empty() ? "" : ", ") + std::to_string(n) + " " + type;
  std::string why;
  auto add = [&](int n, const std::string& what) {
    if (n > 0) why += (why.empty() ? "" : "; ") + std::to_string(n) + " " + what;
  };
  add(p.excluded, "in scenario.junctions.exclude");
  add(p.too_fast, "with an approach faster than scenario.junctions.max_speed = " +
                      NumberText(sel.max_speed, 6) + " m/s");
  add(p.few_arms, "where fewer than scenario.junctions.min_arms = " +
                      std::to_string(sel.min_arms) + " roads open to cars meet");
  add(p.no_internal,
      "without internal lanes (the network was built with --no-internal-links: SUMO reports "
      "no collision inside such a junction and has no conflicts for it; rebuild it with "
      "internal links, netconvert's default)");
  add(p.not_intersection,
      "not intersections (fewer than two incoming roads with conflicting movements)");
  return ConfigError(
      "scenario.junctions selects no junction" + where + " (ids: " +
      std::to_string(sel.ids.size()) + " given, types: [" + list + "]). The network has " +
      (have.empty() ? std::string("no junctions") : have) + "; of the selected types " +
      std::to_string(p.of_type) + (p.of_type == 1 ? " junction" : " junctions") +
      (why.empty() ? std::string() : ", passed over: " + why) +
      ". Select by scenario.junctions.types (a type the network has) or .ids");
}

}  // namespace

std::string StopType(const std::string& type, const JunctionSelection& sel) {
  auto as = [](StopRule rule) {
    return rule == StopRule::kTwoWay ? "priority_stop" : "allway_stop";
  };
  if (type == "allway_stop" || type == "priority_stop") return type;
  if (type == "priority") return as(sel.priority);
  if (type == "right_before_left") return as(sel.right_before_left);
  if (type == "unregulated") return as(sel.unregulated);
  return "";
}

void SelectJunctions(const ScenarioConfig& sc, const net::NetFile& net, Scenario* s) {
  const JunctionSelection& sel = sc.junctions;
  const std::string where = " in " + s->net;
  CheckListed(sel, net, where);
  const std::set<std::string> ids(sel.ids.begin(), sel.ids.end());
  const std::set<std::string> types(sel.types.begin(), sel.types.end());
  std::map<std::string, std::set<std::string>> arms;
  if (sel.min_arms > 0) arms = net.CarNeighbours();
  PassedOver passed;
  for (const auto& [id, j] : net.junctions()) {
    if (j.type != "internal") ++passed.all_types[j.type];
    if (!ids.count(id)) {
      if (!types.count(j.type)) continue;
      if (!PassesFilters(sel, net, id, j, arms, &passed)) continue;
    }
    if (j.int_lanes.empty())
      throw ConfigError("scenario.junctions: junction '" + id + "'" + where +
                        " has no internal lanes (built with --no-internal-links?): SUMO cannot "
                        "report collisions inside it");
    bool stop_links = false;
    for (int l : j.links) stop_links |= l >= 0;
    if (!stop_links) continue;  // e.g. a junction without any movement
    s->junctions.push_back({id, StopType(j.type, sel), j.type});
  }
  if (s->junctions.empty()) throw NothingSelected(sel, passed, where);
}

// Turns the selected junctions of other types into stop-controlled ones with
// netconvert (a node patch: geometry unchanged).
bool PatchJunctionTypes(Scenario* s) {
  std::vector<const ControlledJunction*> changed;
  for (const ControlledJunction& j : s->junctions)
    if (j.type != j.original_type) changed.push_back(&j);
  if (changed.empty()) return false;
  const std::filesystem::path dir = s->scratch->path();
  const std::filesystem::path patch = dir / "junction_types.nod.xml";
  {
    std::ofstream out(patch);
    out << "<nodes>\n";
    for (const ControlledJunction* j : changed)
      out << "    <node id=\"" << j->id << "\" type=\"" << j->type << "\"/>\n";
    out << "</nodes>\n";
  }
  const std::filesystem::path patched = dir / "network.net.xml";
  const std::string log = (dir / "netconvert.log").string();
  if (RunProgram({"netconvert", "--sumo-net-file", s->net, "--node-files", patch.string(),
                  "--precision", "4", "--xml-validation", "never", "--output-file",
                  patched.string()},
                 log) != 0)
    throw ConfigError("scenario.junctions: netconvert could not turn " +
                      std::to_string(changed.size()) + " junctions of " + s->net +
                      " into stop-controlled ones (" + LogTail(log) + ")");
  std::map<std::string, int> kinds;
  for (const ControlledJunction* j : changed) ++kinds[j->original_type + " -> " + j->type];
  std::string list;
  for (const auto& [k, n] : kinds) list += (list.empty() ? "" : ", ") + std::to_string(n) + " " + k;
  s->notes.push_back(std::to_string(changed.size()) + " junctions of " + s->net +
                     " run as stop-controlled (" + list + "; see summary.json junctions)");
  s->net = patched.string();
  return true;
}

}  // namespace taebp::scenario_internal
