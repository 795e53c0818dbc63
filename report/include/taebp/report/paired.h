// Paired games (scenario.paired, docs/paired.md) as files: paired.csv (one
// row per game and branch policy, results.h PairedRecord) and summary.json's
// "paired" section: each policy's collision and DC rates over its branches
// with intervals clustered by HV, the theory beside them, the mean clearing
// times, and for every two policies the mean difference of each measure
// (PairedMeasures) on the games both played, with its interval clustered by
// HV (clustered.h ClusteredMean).
#pragma once

#include "taebp/report/results.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace taebp {

// The measures compared between two policies on the same games: collision,
// dc (0 / 1), av_clear, hv_clear (s), third_collisions.
const std::vector<std::string>& PairedMeasures();
std::vector<std::string> PairedCsvColumns();
std::string PairedColumnsMarkdown();  // docs/paired.md's column table
bool AnyPaired(const std::vector<PolicyRun>& runs);
std::string PairedCsv(const std::vector<PolicyRun>& runs);
nlohmann::ordered_json PairedSummary(const std::vector<PolicyRun>& runs);

}  // namespace taebp
