// The 3x3 grid of the network tests (network_test.cc, network_premise_test.cc):
// a short run of kind: network with fringe demand and the paper's model.
#pragma once

#include "taebp/config/config.h"

#include <string>
#include <vector>

namespace taebp {
namespace test {

inline const char* const kModel =
    "model:\n"
    "  prior_go: 0.2\n"
    "  collision_penalty: 3.0\n"
    "  trust: {dist: beta, alpha: 4, beta: 2}\n"
    "  likelihood: {type: linear, s_max: 2.0}\n";

// A 3x3 grid with 50 m fringe edges and fringe demand.
inline ExperimentConfig GridConfig(const std::vector<std::string>& overrides) {
  const std::string yaml = std::string(
                               "scenario:\n"
                               "  kind: network\n"
                               "  grid: {columns: 3, rows: 3, length: 100, attach_length: 50}\n"
                               "  demand: {flow: 600}\n"
                               "  av_share: 0.5\n"
                               "  cruise_speed: 10\n"
                               "  duration: 600\n"
                               "  seed: 11\n") +
                           kModel + "policies: [sumo_native]\n";
  return ParseExperimentConfig(yaml, "network_test grid", overrides);
}

}  // namespace test
}  // namespace taebp
