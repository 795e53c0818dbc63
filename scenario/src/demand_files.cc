#include "demand_files.h"

#include <pugixml.hpp>

#include <string>

namespace taebp {

void CheckDemandFiles(const ScenarioConfig& sc, const Scenario& s) {
  const char* const kVehicles = "//vehicle | //trip | //flow | //person | //personFlow | "
                                "//container | //containerFlow";
  auto origin = [&](const std::string& f) {
    return sc.sumocfg.empty() ? "scenario.routes: '" + f + "'"
                              : "scenario.sumocfg = '" + sc.sumocfg + "': its route file '" + f +
                                    "'";
  };
  bool vehicles = false, parsed = true;
  for (const std::string& f : s.route_files) {
    pugi::xml_document doc;
    if (!doc.load_file(f.c_str())) {
      parsed = false;  // SUMO's own message names the error
      continue;
    }
    const std::string root = doc.document_element().name();
    if (root == "net")
      throw ConfigError(origin(f) + " holds a SUMO network (<net>), not a demand (<routes> with "
                        "vehicles, trips or flows): give a network as scenario.network and its "
                        "demand as scenario.routes (e.g. made with SUMO's randomTrips.py) or "
                        "scenario.demand");
    vehicles = vehicles || doc.select_node(kVehicles);
  }
  if (sc.demand || vehicles || !parsed) return;
  for (const std::string& f : s.additional_files) {
    pugi::xml_document doc;
    if (!doc.load_file(f.c_str())) return;
    if (doc.select_node(kVehicles)) return;
  }
  std::string files;
  for (const std::string& f : s.route_files) files += (files.empty() ? "'" : ", '") + f + "'";
  throw ConfigError(
      (sc.sumocfg.empty() ? "scenario.routes" : "scenario.sumocfg = '" + sc.sumocfg + "'") +
      std::string(": no vehicle, trip, flow or person in ") +
      (files.empty() ? std::string("any route file") : files) +
      (s.additional_files.empty() ? "" : " nor in scenario.additional") +
      ": SUMO would run an empty network. Give route files with the demand (e.g. SUMO's "
      "randomTrips.py) or scenario.demand");
}

}  // namespace taebp
