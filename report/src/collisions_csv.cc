// collisions.csv (report.h CollisionsCsv): one row per collision SUMO
// reported after the warm-up, and the count each is in.
#include "taebp/report/report.h"

#include "taebp/base/number_text.h"

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace taebp {
namespace {

// The junction of a lane inside one (SUMO's internal lanes are
// ":JUNCTION_LINK_LANE"); "" for a lane of an edge.
std::string JunctionOfLane(const std::string& lane) {
  if (lane.empty() || lane[0] != ':') return "";
  const std::size_t last = lane.rfind('_');
  if (last == std::string::npos || last < 2) return "";
  const std::size_t link = lane.rfind('_', last - 1);
  if (link == std::string::npos || link < 1) return "";
  return lane.substr(1, link - 1);
}

// Which count of summary.json each collision is in: an encounter's AV-HV
// collision (collisions, in collision_rate and collisions_total) or one after
// its pair went back to SUMO (collisions_after_handback); a move of the game
// hitting a third vehicle (other_collisions_game_move, in collisions_total);
// any other (other_collisions). An encounter's pair without its encounter on
// record (drawn in the warm-up, or the pair colliding again): none.
std::vector<std::string> CountedIn(const PolicyRun& r) {
  std::vector<std::string> out;
  std::vector<bool> used(r.encounters.size(), false);
  for (const CollisionRecord& c : r.collisions) {
    if (!c.encounter_pair) {
      out.push_back(c.game_move ? "other_collisions_game_move" : "other_collisions");
      continue;
    }
    const std::set<std::string> pair = {c.collider, c.victim};
    std::string counted = "none";
    for (std::size_t i = 0; i < r.encounters.size(); ++i) {
      const EncounterRecord& e = r.encounters[i];
      if (used[i] || !(e.collision || e.collision_after_handback) ||
          std::set<std::string>{e.av, e.hv} != pair)
        continue;
      used[i] = true;
      counted = e.collision ? "collisions" : "collisions_after_handback";
      break;
    }
    out.push_back(counted);
  }
  return out;
}

}  // namespace

std::vector<std::string> CollisionCsvColumns() {
  return {"policy",      "time",     "junction",        "lane",         "pos",
          "type",        "collider", "collider_kind",   "collider_in_game",
          "victim",      "victim_kind", "victim_in_game", "encounter_pair", "game_move",
          "counted_in"};
}

std::string CollisionsCsv(const std::vector<PolicyRun>& runs) {
  std::string out;
  for (const std::string& c : CollisionCsvColumns()) out += (out.empty() ? "" : ",") + c;
  out += "\n";
  auto flag = [](bool b) { return std::string(b ? "1" : "0"); };
  auto kind = [](bool av) { return std::string(av ? "av" : "hv"); };
  for (const PolicyRun& r : runs) {
    const std::vector<std::string> counted = CountedIn(r);
    for (std::size_t i = 0; i < r.collisions.size(); ++i) {
      const CollisionRecord& c = r.collisions[i];
      const std::vector<std::string> cells = {
          CsvCell(r.policy),       NumberText(c.time),     CsvCell(JunctionOfLane(c.lane)),
          CsvCell(c.lane),         NumberText(c.pos),      CsvCell(c.type),
          CsvCell(c.collider),     kind(c.collider_av),    flag(c.collider_in_game),
          CsvCell(c.victim),       kind(c.victim_av),      flag(c.victim_in_game),
          flag(c.encounter_pair),  flag(c.game_move),      counted[i]};
      std::string line;
      for (const std::string& cell : cells) line += (line.empty() ? "" : ",") + cell;
      out += line + "\n";
    }
  }
  return out;
}

}  // namespace taebp
