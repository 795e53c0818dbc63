// The result metrics, declared once.
//
// Every number a run reports per policy (summary.json's policies.POLICY) or
// per controlled junction (summary.json's junctions[], junctions.csv) is one
// row of RunMetrics(): its one name, type, unit, meaning, the levels it is
// reported at and how a sweep pools it over seeds. summary.json, junctions.csv,
// a sweep's results.csv / results.jsonl / aggregate.csv, the Python module
// (taebp.metrics()) and the README's metric table (`taebp metrics --markdown`)
// are all made from this table, so a metric has the same name everywhere.
//
// Structured details that are not one number (the scheme, each HV's trust, the
// stalls, the trust dynamics' equilibria, ...) are the sections of
// RunSections(); summary.json holds nothing else per policy.
#pragma once

#include <string>
#include <vector>

namespace taebp {

enum class MetricType {
  kCount,  // a whole number (summary.json: an integer)
  kReal,   // a real number; null (an empty cell) where it is undefined
  kFlag,   // yes / no (summary.json: true / false; CSV: 1 / 0)
};

// How aggregate.csv pools one (point, policy)'s runs over seeds.
enum class Pool {
  kSum,         // summed: NAME
  kRate,        // pooled rate sum(count) / sum(per) with its 95 % Wilson
                // interval: NAME, NAME_lo, NAME_hi (runs and summary.json too)
  kWeighted,    // mean weighted by `per` (a per-encounter mean): NAME
  kPrediction,  // as kWeighted, but the plain mean over runs when sum(per) = 0
                // (a prediction exists without encounters): NAME
  kMean,        // mean over runs where defined, and its sample SD: NAME, NAME_sd
  kMax,         // the largest over runs: NAME
  kNone,        // not pooled (the same for every run, e.g. the simulated time)
};

// Where a metric is reported.
enum MetricLevel : unsigned {
  kPolicyLevel = 1,    // summary.json policies.POLICY, results.csv, aggregate.csv
  kJunctionLevel = 2,  // summary.json policies.POLICY.junctions[], junctions.csv
};

// Which runs have it (absent from summary.json otherwise; empty in the CSVs).
enum class MetricScope {
  kAll,
  kNetwork,  // scenario.kind: network
  kBeyond,   // a run beyond the paper (dynamic or learned trust, noise), not sumo_native
  kSsm,      // scenario.outputs.ssm: SUMO's surrogate safety measures (every policy)
};

struct MetricFacts;  // the numbers of one policy or junction (report/src)

struct Metric {
  const char* name;         // the one name, everywhere
  MetricType type;
  const char* unit;         // "" for a count or a fraction
  unsigned levels;          // MetricLevel bits
  MetricScope scope;
  Pool pool;
  const char* count;        // kRate: the metric counted (successes), else nullptr
  const char* per;          // kRate / kWeighted / kPrediction: the trials or weight;
                            // where it is 0 the value is undefined (null in results)
                            // except for kPrediction; kMean: likewise, or nullptr
  const char* was;          // its name before taebp 0.2 (CHANGELOG.md), or nullptr
  const char* description;  // one sentence for the README
  // The value (NaN: undefined, written as null / an empty cell).
  double (*value)(const MetricFacts& facts);
};

// The table, in output order.
const std::vector<Metric>& RunMetrics();

// Whether a policy plays the paper's game (every policy but sumo_native,
// SUMO's own junction logic). Only these have a theory (kPrediction).
bool PlaysGame(const std::string& policy);
// Whether metric `m` is undefined (null, an empty cell) for a run of `policy`
// in which what it is per (`m.per`) counted `per`: a rate or mean over no
// encounter (no nudge, no held vehicle, ...), or a prediction of a policy that
// plays no game. summary.json, junctions.csv and a sweep's tables all ask here.
bool MetricUndefined(const Metric& m, const std::string& policy, double per);
// The metric named `name`, or nullptr.
const Metric* FindMetric(const std::string& name);

// A structured, non-numeric part of summary.json's policies.POLICY (or of a
// junction's object: `junction` true).
struct MetricSection {
  const char* name;
  bool junction;
  MetricScope scope;
  const char* was;
  const char* description;
};
const std::vector<MetricSection>& RunSections();

// The columns one metric gives a table: NAME, plus NAME_lo/NAME_hi for a rate,
// in runs (`aggregate` false: results.csv, junctions.csv, summary.json) or
// pooled over seeds (`aggregate` true: plus NAME_sd for kMean; none for kNone).
std::vector<std::string> MetricColumns(const Metric& m, bool aggregate);
// Every metric column of a level, in table order.
std::vector<std::string> MetricColumns(MetricLevel level, bool aggregate);

// The README's metric table (Markdown), and CHANGELOG.md's list of renamed
// result names, both generated from the table (`taebp metrics`).
std::string MetricsMarkdown();
std::string RenamesMarkdown();
// The table as JSON (`taebp metrics --print json`, Python's taebp.metrics()):
// {"metrics": [{name, type, unit, levels, scope, pool, count, per, was,
// description, columns, aggregate_columns}], "sections": [...]}.
std::string MetricsJson();
// timeseries.csv's and hv_trust.csv's columns with their meaning (report.cc,
// where their cells are declared).
std::string SampleColumnsMarkdown();

const char* ToString(Pool p);
const char* ToString(MetricType t);
const char* ToString(MetricScope s);

}  // namespace taebp
