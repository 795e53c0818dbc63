// The interval of a per-encounter rate when encounters are not independent:
// clustered by who was sampled (docs/metrics.md, "Intervals").
//
// Encounters of one HV share its trust and, beyond the paper, its learning
// or dynamics; encounters of one run share its traffic. A rate's interval
// counts the HVs (within a run) and the runs (pooled over seeds) as the
// units sampled, not the encounters:
//
// - Within a run, the clusters are the HVs met (y_i successes in n_i
//   encounters of HV i; n = sum n_i, p = sum y_i / n). The cluster-robust
//   variance of p with the small-sample factor G / (G - 1) (CR1; Cameron and
//   Miller 2015) is V = G / (G - 1) * sum (y_i - p n_i)^2 / n^2, and the
//   design effect deff = V / (p (1 - p) / n).
// - Pooled over runs, two levels: the HVs of every run, each run's variance
//   as above (V_hv = sum over runs of deff_r p_r (1 - p_r) n_r / n^2), and
//   the runs themselves (V_run: CR1 over the runs' totals). The larger of the
//   two adjusted design effects below is used, and its level reported.
// - The design effect is estimated from G clusters, so its excess over 1 is
//   scaled by (t_{G-1} / z)^2, Student's quantile over the normal one at the
//   same level (the small-sample correction of Korn and Graubard 1998 applied
//   to the part of the variance that is estimated): deff_adj = 1 + max(0,
//   deff - 1) (t_{G-1} / z)^2. Where deff <= 1 the interval is Wilson's.
// - The interval is Wilson's at the effective sample size n / deff_adj
//   (Kish), so it stays inside [0, 1] and is exactly 0 at p = 0 (1 at p = 1).
//
// With fewer than kMinClusters clusters no interval accounts for their
// dependence: `few_clusters` says so (tables mark it).
#pragma once

#include "taebp/report/report.h"

#include <limits>
#include <string>
#include <vector>

namespace taebp {

// Below this many clusters (HVs met, or runs) an interval is not to be
// trusted: the clusters' spread cannot be estimated (docs/metrics.md).
inline constexpr long kMinClusters = 5;

// One cluster: y successes in n trials (n > 0).
struct ClusterCount {
  double y = 0, n = 0;
};

// One run's rate as its summary reports it: y successes in n trials, its
// design effect and clusters (for pooling over runs).
struct RunRate {
  double y = 0, n = 0;
  double deff = 1;
  long clusters = 0;
};

struct RateInterval {
  double rate = 0;           // y / n (0 without trials)
  double low = 0, high = 1;  // the interval at the requested z
  double deff = 1;           // the estimated design effect of the level used (1: none estimated)
  long clusters = 0;         // clusters of that level (HVs, or runs)
  bool few_clusters = true;  // clusters < kMinClusters
};

// The clustered interval of sum y / sum n over `clusters` (empty clusters
// are skipped) at normal quantile z (kZ95, kZ999).
RateInterval ClusteredRate(const std::vector<ClusterCount>& clusters, double z = kZ95);
// The same pooled over independent runs (a sweep's seeds).
RateInterval PooledRate(const std::vector<RunRate>& runs, double z = kZ95);

// The mean of values x (e.g. one paired difference per game) whose values
// come in clusters (`cluster[i]`, e.g. the game's HV): the CR1 standard error
// with Student's t at G - 1 degrees of freedom (G clusters); no interval
// (NaN) with fewer than 2 clusters.
struct MeanInterval {
  double mean = 0;
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
  long clusters = 0;
};
MeanInterval ClusteredMean(const std::vector<double>& x, const std::vector<std::string>& cluster,
                           double level = 0.95);

// The interval of rate metric `name` (a Pool::kRate row of metrics.h, e.g.
// "dc_rate") of run `r`, clustered by HV, at normal quantile z: what
// summary.json reports at kZ95 (tests compare theory at kZ999). Throws
// std::invalid_argument for a name that is not a rate.
RateInterval RunRateInterval(const PolicyRun& r, const std::string& name, double z = kZ95);

// Wilson's interval for a proportion p from an effective sample size n > 0
// (real-valued; Wilson(k, n) at p = k / n and n trials).
Interval WilsonAt(double p, double n, double z = kZ95);
// Student's two-sided quantile: P(|T| < t) = level for df >= 1 degrees of
// freedom.
double StudentTQuantile(double df, double level);
// The two-sided level of a normal quantile z (0.95 for kZ95).
double NormalLevel(double z);

}  // namespace taebp
