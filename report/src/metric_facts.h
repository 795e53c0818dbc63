// The numbers a metric of metrics.h is read from (internal to report/).
#pragma once

#include "taebp/report/metrics.h"
#include "taebp/report/results.h"

#include <string>
#include <vector>

namespace taebp {

// Encounter statistics of a policy (or of one junction's encounters).
struct EncounterStats {
  long n = 0, collisions = 0, dc = 0, nudges = 0;
  double commanded_sum = 0, observed_sum = 0, max_abs_error = 0;
  double min_excess = 0;  // min over nudges of observed - commanded
  double theory_dc_sum = 0, theory_collision_sum = 0;  // per-encounter predictions
};
// `junction` empty: every encounter of the run.
EncounterStats ComputeEncounterStats(const PolicyRun& r, const std::string& junction = "");

// Encounters from `from` on (the last hour's window).
struct LastHourWindow {
  double from = 0;
  long n = 0, dc = 0, collisions = 0;
  double theory_dc = 0, oracle_dc = 0, theory_collisions = 0;
};
LastHourWindow LastHour(const PolicyRun& r);

// Sums over the encounters of a run beyond the paper.
struct BeyondSums {
  double oracle_dc = 0, oracle_collision = 0, dc_lost = 0, collisions = 0, regret = 0;
  long failures = 0;            // nudged, then the HV drove recklessly
  double expected_failures = 0;
};

struct MetricFacts {
  const PolicyRun* run = nullptr;
  const JunctionRun* junction = nullptr;  // junction level, else nullptr
  EncounterStats s;
  LastHourWindow last_hour;  // policy level
  BeyondSums beyond;         // policy level
};
MetricFacts PolicyFacts(const PolicyRun& r);
MetricFacts JunctionFacts(const PolicyRun& r, const JunctionRun& j);

// Whether metric scope `s` applies to run `r`.
bool InScope(MetricScope s, const PolicyRun& r);

// The rows of RunMetrics() for scenario.outputs.ssm (ssm.cc), in table order.
std::vector<Metric> SsmMetricRows();

double Rate(long k, long n);
// Whether any of the runs is beyond the paper (its extra columns and rows).
bool AnyBeyond(const std::vector<PolicyRun>& runs);
double PerHour(double count, double seconds);

}  // namespace taebp
