// A network that gridlocks fast and for sure: a 2 x 2 all-way-stop grid
// (scenario.grid, 100 m blocks and fringe edges) whose every vehicle heads for
// the east exit of junction B0 (B0right0), where the first vehicle stops for
// good near the end. The exit fills within a minute, the queue backs up
// through B0 and A0, and after the stall limit (300 s on a network) nothing
// has passed B0 while vehicles wait at its stop lines: a stall, under every
// policy (sumo_native included). Shared by the CLI and controller suites.
// Sorted by departure time (SUMO drops what comes out of order: it used to
// drop sb and nb here unnoticed, until SUMO's warnings were read).
#pragma once

#include <string>

namespace taebp::test {

inline std::string BlockedGridRoutes() {
  return R"(<routes>
    <route id="west" edges="left0A0 A0B0 B0right0"/>
    <route id="south_a" edges="bottom0A0 A0B0 B0right0"/>
    <route id="south_b" edges="bottom1B0 B0right0"/>
    <route id="north_b" edges="top1B1 B1B0 B0right0"/>
    <vehicle id="blocker" depart="0" route="west">
        <stop lane="B0right0_0" endPos="85" duration="100000"/>
    </vehicle>
    <flow id="sb" route="south_b" begin="1" end="900" period="4"/>
    <flow id="w" route="west" begin="2" end="900" period="4"/>
    <flow id="nb" route="north_b" begin="2.5" end="900" period="4"/>
    <flow id="sa" route="south_a" begin="3" end="900" period="4"/>
</routes>
)";
}

// The scenario's YAML (routes: the file holding BlockedGridRoutes()).
inline std::string BlockedGridConfig(const std::string& routes_file) {
  return "scenario:\n"
         "  kind: network\n"
         "  grid: {columns: 2, rows: 2, length: 100, attach_length: 100}\n"
         "  routes: [" + routes_file + "]\n"
         "  av_share: 0.5\n"
         "  cruise_speed: 10\n"
         "  duration: 900\n"
         "  seed: 5\n"
         "model:\n"
         "  prior_go: 0.2\n"
         "  collision_penalty: 3.0\n"
         "  trust: 0.6\n"
         "  likelihood: {type: linear, s_max: 2.0}\n";
}

}  // namespace taebp::test
