// Runs built by hand for the metric table's tests (tests/report/metric_table_test.cc,
// tests/sweep/metric_pooling_test.cc): a network run and a figure-8 run that
// fill every metric, their summary.json, and CSV text split into lines and cells.
#pragma once

#include "taebp/report/report.h"
#include "taebp/report/results.h"

#include "csv_text.h"

#include <nlohmann/json.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace taebp::test {

inline EncounterRecord Encounter(const std::string& junction, double time, bool collision, bool dc,
                                 double commanded) {
  EncounterRecord e;
  e.junction = junction;
  e.time = time;
  e.collision = collision;
  e.hv_dc = dc;
  e.commanded = commanded;
  e.observed = commanded + 1e-6;
  e.theory_dc = 0.375;
  e.theory_collision = 0.0;
  e.beyond.oracle_dc = 0.4;
  e.beyond.regret = 0.025;
  e.beyond.failure_probability = 0.1;
  return e;
}

// A network run beyond the paper (dynamics, learning and noise on), with
// encounters at one of its two junctions.
inline PolicyRun NetworkRun() {
  PolicyRun r;
  r.policy = "ta_ebp";
  r.scenario_kind = "network";
  r.simulated_seconds = 700;
  r.measured_seconds = 600;
  r.crossings_av = 30;
  r.crossings_hv = 50;
  r.held = 4;
  r.wait_sum = 10;
  r.wait_max = 4;
  r.encounters = {Encounter("J1", 150, true, false, 1.6), Encounter("J1", 300, false, true, 1.6),
                  Encounter("J1", 500, false, false, 0)};
  r.encounters_formed = 4;
  r.encounters_unfinished = 1;
  JunctionRun j1;
  j1.id = "J1";
  j1.type = "allway_stop";
  j1.original_type = "priority";
  j1.rule = "all_way_stop";
  j1.crossings_av = 20;
  j1.crossings_hv = 30;
  j1.held = 4;
  j1.wait_sum = 10;
  j1.wait_max = 4;
  j1.approaches = {{"a_0", 3, 60, 600}, {"b_0", 5, 120, 600}};
  JunctionRun j2 = j1;
  j2.id = "J2";
  j2.crossings_av = 10;
  j2.crossings_hv = 20;
  j2.held = 0;
  j2.wait_sum = 0;
  j2.wait_max = 0;
  r.junctions = {j1, j2};
  r.network.departed = 90;
  r.network.arrived = 84;
  r.network.pending_end = 2;
  r.network.trips = 90;
  r.network.trips_unfinished = 6;
  r.network.time_loss_sum = 900;
  r.network.duration_sum = 4500;
  r.network.waiting_time_sum = 180;
  r.stalls = {{"J2", 100, 400}};
  // SSM on, PET not measured: 7 conflicts in the network, 4 at J1, none at J2.
  r.ssm.on = true;
  r.ssm.rules.on = {true, true, false};
  r.ssm.network.conflicts = 7;
  r.ssm.network.by_measure = {5, 3, 0};
  r.ssm.network.ttc_min = 0.8;
  r.ssm.at_junctions.conflicts = 4;
  r.ssm.at_junctions.by_measure = {2, 2, 0};
  r.ssm.junction["J1"] = r.ssm.at_junctions;
  r.ssm.junction["J2"] = {};
  r.beyond.on = true;
  r.beyond.long_run = true;
  r.beyond.learning = true;
  r.beyond.noise = true;
  r.beyond.final_mean_trust = 0.55;
  r.beyond.expected_long_run_mean = 0.5;
  return r;
}

inline PolicyRun Figure8Run() {
  PolicyRun r;
  r.policy = "no_ebp";
  r.simulated_seconds = 300;
  r.measured_seconds = 300;
  r.theory.dc_rate = 0;
  r.junctions = {JunctionRun{}};
  r.junctions[0].id = "C";
  return r;
}

inline nlohmann::ordered_json Summary(const std::vector<PolicyRun>& runs) {
  Provenance prov;
  prov.config_json = "{}";
  return nlohmann::ordered_json::parse(SummaryJson(runs, prov));
}

inline std::vector<std::string> Keys(const nlohmann::ordered_json& j) {
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  return keys;
}

}  // namespace taebp::test
