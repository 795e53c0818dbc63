// A measured per-encounter rate's interval as the outputs compute it,
// clustered by HV (report/clustered.h, docs/metrics.md "Intervals"), for
// tests that hold a rate of encounter records against its theory: one run's
// encounters, or several independent runs' (seeds) pooled.
#pragma once

#include "taebp/report/clustered.h"
#include "taebp/report/results.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace taebp::test {

using EncounterHit = std::function<bool(const EncounterRecord&)>;

// HV by HV: the encounters with `hit` and all of them.
inline std::vector<ClusterCount> HvClusters(const std::vector<EncounterRecord>& encounters,
                                            const EncounterHit& hit) {
  std::map<std::string, ClusterCount> by_hv;
  for (const EncounterRecord& e : encounters) {
    ClusterCount& c = by_hv[e.hv];
    c.y += hit(e) ? 1 : 0;
    c.n += 1;
  }
  std::vector<ClusterCount> out;
  for (const auto& [hv, c] : by_hv) out.push_back(c);
  return out;
}

// Whether p lies in a run's 99.9 % interval of rate metric `rate`, as the
// outputs compute it (RunRateInterval: clustered by HV, each HV's
// encounters dependent).
inline bool InsideRun999(const PolicyRun& run, const char* rate, double p) {
  const RateInterval ci = RunRateInterval(run, rate, kZ999);
  return ci.low <= p && p <= ci.high;
}

inline RateInterval EncounterRate(const std::vector<EncounterRecord>& encounters,
                                  const EncounterHit& hit, double z) {
  return ClusteredRate(HvClusters(encounters, hit), z);
}

// Independent runs pooled: clustered by HV within each run and by run.
inline RateInterval PooledEncounterRate(const std::vector<std::vector<EncounterRecord>>& runs,
                                        const EncounterHit& hit, double z) {
  std::vector<RunRate> rates;
  for (const std::vector<EncounterRecord>& run : runs) {
    const RateInterval one = EncounterRate(run, hit, z);
    double y = 0;
    for (const EncounterRecord& e : run) y += hit(e) ? 1 : 0;
    rates.push_back({y, static_cast<double>(run.size()), one.deff, one.clusters});
  }
  return PooledRate(rates, z);
}

inline bool Holds(const RateInterval& ci, double p) { return ci.low <= p && p <= ci.high; }

}  // namespace taebp::test
