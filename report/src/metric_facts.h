// The numbers a metric of metrics.h is read from (internal to report/).
#pragma once

#include "taebp/report/clustered.h"
#include "taebp/report/metrics.h"
#include "taebp/report/results.h"

#include <array>
#include <string>
#include <vector>

namespace taebp {

// Encounter statistics of a policy (or of one junction's encounters).
struct EncounterStats {
  long n = 0, collisions = 0, dc = 0, nudges = 0;
  double commanded_sum = 0, observed_sum = 0, max_abs_error = 0;
  double min_excess = 0;  // min over nudges of observed - commanded
  bool any_nudge = false;
  double theory_dc_sum = 0, theory_collision_sum = 0;  // per-encounter predictions
  // scenario.outputs.ssm: games without a collision whose pair measures
  // (EncounterRecord::ssm) pass a threshold: any measure, and by measure.
  long near_misses = 0;
  std::array<long, kSsmMeasures> near_misses_by{};
};
// Adds encounter `e` of run `r` (its SSM rules) to `s`.
void AddEncounter(const PolicyRun& r, const EncounterRecord& e, EncounterStats* s);
// `junction` empty: every encounter of the run.
EncounterStats ComputeEncounterStats(const PolicyRun& r, const std::string& junction = "");

// Encounters from `from` on (the last hour's window).
struct LastHourWindow {
  double from = 0;
  long n = 0, dc = 0, collisions = 0;
  double theory_dc = 0, oracle_dc = 0, theory_collisions = 0;
};
// The window's start for run `r`, and encounter `e` added to it when in it.
double LastHourFrom(const PolicyRun& r);
void AddLastHour(const EncounterRecord& e, LastHourWindow* w);
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
// The facts of each HV's encounters among those of `f` (its junction's at
// the junction level), in HV order: the clusters of a rate's interval
// (encounter statistics and the last hour only).
std::vector<MetricFacts> HvFacts(const MetricFacts& f);
// The interval of rate metric `m` (Pool::kRate) over the clusters `hvs`
// (HvFacts), at normal quantile z.
RateInterval MetricInterval(const Metric& m, const std::vector<MetricFacts>& hvs, double z);

// Whether metric scope `s` applies to run `r`.
bool InScope(MetricScope s, const PolicyRun& r);

// The rows of RunMetrics() for scenario.outputs.ssm (ssm.cc), in table order.
std::vector<Metric> SsmMetricRows();

double Rate(long k, long n);
// Whether any of the runs is beyond the paper (its extra columns and rows).
bool AnyBeyond(const std::vector<PolicyRun>& runs);
double PerHour(double count, double seconds);

}  // namespace taebp
