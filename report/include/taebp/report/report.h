// Results of an experiment: statistics, summary.json, encounters.csv and the
// Table I printout. Outputs are deterministic (no timing inside them).
#pragma once

#include "taebp/report/results.h"

#include <ostream>
#include <string>
#include <vector>

namespace taebp {

struct Interval {
  double low = 0, high = 0;
};
// Two-sided standard normal quantiles of the intervals taebp uses: 95 % (what
// every output reports) and 99.9 % (tests and readme-check comparing a measured
// rate with its theory, where a false alarm should be rare).
inline constexpr double kZ95 = 1.959963984540054;
inline constexpr double kZ999 = 3.2905267314919255;
// The Wilson score interval for k successes out of n at normal quantile z
// (Wilson 1927; Newcombe 1998, method 3, without continuity correction): the
// one interval taebp computes in C++ (python/taebp/stats.py is Python's).
// Edges: n = 0 -> [0, 1]; k = 0 -> low exactly 0; k = n -> high exactly 1;
// always inside [0, 1]. Needs 0 <= k <= n.
Interval Wilson(long k, long n, double z = kZ95);

struct Provenance {
  std::string config_path;
  std::string config_json;  // the resolved config (ToJson)
  std::uint64_t seed = 0;
  std::string git_revision;
  std::string sumo_version;
  std::string taebp_version;
  std::vector<std::string> warnings;  // ScenarioWarnings
  // What this process changed in SUMO's library for the run (sumo_adapter.h
  // SsmReleaseBehaviour): empty for most runs.
  std::vector<std::string> sumo_patches;
};
// The git revision the binary was built from ("unknown" outside a checkout).
std::string BuildGitRevision();
std::string TaebpVersion();

// Why an experiment ended before its last policy: a stall under
// scenario.stall_action: error (reason "stall") in `policy`, with the stall's
// message; `not_run` the config's policies after it. Empty reason: every
// policy ran.
struct Stopped {
  std::string reason, policy, message;
  std::vector<std::string> not_run;
};

// summary.json text (pretty, stable key order). A stopped experiment adds the
// top-level keys "stopped" (the reason), "stopped_policy", "error" (the
// message) and "policies_not_run" after "provenance".
std::string SummaryJson(const std::vector<PolicyRun>& runs, const Provenance& provenance,
                        const Stopped& stopped = {});
// encounters.csv text: the header (EncounterCsvColumns) on the first line, then
// one row per AV-HV encounter, policy first. No comment lines: provenance is in
// summary.json.
// Network scenarios add both_proceed_collides after the paper's columns;
// runs beyond the paper (PolicyRun::beyond.on) then add the columns of
// EncounterCsvColumns(true, ...); runs with SUMO's SSM device
// (scenario.outputs.ssm) then the game's pair measures.
std::string EncountersCsv(const std::vector<PolicyRun>& runs);
std::vector<std::string> EncounterCsvColumns(bool beyond = false, bool network = false,
                                             bool ssm = false);
// One group of those columns: "paper", "network", "beyond" or "ssm".
std::vector<std::string> EncounterCsvColumnGroup(const std::string& group);
// The cells of one CSV line as written (RFC 4180 records on one line; a
// quoted cell keeps its quotes), for copying cells between files.
std::vector<std::string> SplitCsvRow(const std::string& line);
// Whether any run is beyond the paper (then the files below are written too).
bool BeyondPaper(const std::vector<PolicyRun>& runs);
// timeseries.csv: one row per (policy, sample time): the HVs in the network,
// their mean trust (and its mean-field prediction), cumulative counts, theory,
// oracle and regret. hv_trust.csv: one row per (policy, sample, HV): its
// trust and the fleet's belief about it. Header first, no comment lines.
// Written to `path` from the runs' spools (PolicyRun::beyond.samples,
// report/sample_spool.h), streamed: the rows are never all in memory.
// Throws std::runtime_error naming the file it cannot write.
void WriteTimeseriesCsv(const std::vector<PolicyRun>& runs, const std::string& path);
std::vector<std::string> TimeseriesCsvColumns();
void WriteHvTrustCsv(const std::vector<PolicyRun>& runs, const std::string& path);
std::vector<std::string> HvTrustCsvColumns();
// One row of each (its line, newline included), as a spool writes it.
std::string TimeseriesCsvRow(const std::string& policy, const TimeSample& s);
std::string HvTrustCsvRow(const std::string& policy, const HvSample& s);
// junctions.csv text: one row per (policy, controlled junction): crossings,
// throughput, waits, queues, encounters and rates with the theory.
std::string JunctionsCsv(const std::vector<PolicyRun>& runs);
// collisions.csv text: one row per collision SUMO reported after the warm-up
// (PolicyRun::collisions), policy first: when, where (junction, lane, pos),
// SUMO's type, the two vehicles (AV or HV, in a game or not), whether they
// were an encounter's pair or a move of the game hit a third vehicle, and
// the count of summary.json it is in (counted_in: collisions,
// collisions_after_handback, other_collisions_game_move, other_collisions,
// or none). collisions_total = the rows counted in collisions and in
// other_collisions_game_move.
std::string CollisionsCsv(const std::vector<PolicyRun>& runs);
std::vector<std::string> CollisionCsvColumns();
// A CSV cell (RFC 4180): quoted when it holds a comma, quote or line break.
std::string CsvCell(const std::string& s);

// Paper-style table: one row per metric, one column per policy, theory beside
// simulation. A rate whose theory value lies outside its 95% interval is
// flagged with '!'; `warnings` (e.g. the geometry warning) are repeated below.
// A policy whose run stalled has its flow and delay cells marked "stalled",
// and a footnote names every stalled junction (id, since when) per policy.
void PrintTable(std::ostream& out, const std::vector<PolicyRun>& runs,
                const std::vector<std::string>& warnings = {});

}  // namespace taebp
