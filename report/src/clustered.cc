#include "taebp/report/clustered.h"

#include <boost/math/distributions/students_t.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace taebp {
namespace {

// A level's design effect, its clusters and the degrees of freedom its
// variance was estimated with (df < 1: not estimated).
struct Level {
  double deff = 1;
  long clusters = 0;
  double df = 0;
};

// The design effect the interval uses: the estimated excess over 1 scaled by
// (t_df / z)^2 (clustered.h).
double Adjusted(const Level& l, double z) {
  if (l.df < 1 || !(l.deff > 1)) return 1.0;
  const double t = StudentTQuantile(l.df, NormalLevel(z));
  return 1.0 + (l.deff - 1.0) * (t / z) * (t / z);
}

RateInterval Finish(double y, double n, const std::vector<Level>& levels, double z) {
  RateInterval r;
  if (!(n > 0)) return r;  // no trial: [0, 1], few clusters
  r.rate = y / n;
  // The level with the larger adjusted design effect (the first on a tie:
  // the HVs).
  const Level* used = &levels.front();
  double adj = Adjusted(*used, z);
  for (const Level& l : levels) {
    const double a = Adjusted(l, z);
    if (a > adj) used = &l, adj = a;
  }
  r.deff = used->deff;
  r.clusters = used->clusters;
  r.few_clusters = used->clusters < kMinClusters;
  const Interval ci = WilsonAt(r.rate, n / adj, z);
  r.low = ci.low;
  r.high = ci.high;
  return r;
}

}  // namespace

double NormalLevel(double z) { return std::erf(z / std::sqrt(2.0)); }

double StudentTQuantile(double df, double level) {
  const boost::math::students_t dist(df);
  return boost::math::quantile(boost::math::complement(dist, (1.0 - level) / 2.0));
}

Interval WilsonAt(double p, double n, double z) {
  if (!(n > 0)) return {0.0, 1.0};
  const double z2 = z * z;
  const double denom = 1 + z2 / n;
  const double centre = (p + z2 / (2.0 * n)) / denom;
  const double half = z * std::sqrt(p * (1 - p) / n + z2 / (4.0 * n * n)) / denom;
  // At p = 0 (p = 1) the bound is exactly 0 (1); avoid round-off residue.
  return {p <= 0 ? 0.0 : std::max(0.0, centre - half), p >= 1 ? 1.0 : std::min(1.0, centre + half)};
}

RateInterval ClusteredRate(const std::vector<ClusterCount>& clusters, double z) {
  double y = 0, n = 0;
  long g = 0;
  for (const ClusterCount& c : clusters) {
    if (!(c.n > 0)) continue;
    y += c.y;
    n += c.n;
    ++g;
  }
  Level hv;
  hv.clusters = g;
  hv.df = static_cast<double>(g - 1);
  const double p = n > 0 ? y / n : 0.0;
  const double binomial = n > 0 ? p * (1 - p) / n : 0.0;
  if (g >= 2 && binomial > 0) {
    double ss = 0;
    for (const ClusterCount& c : clusters) {
      if (!(c.n > 0)) continue;
      const double e = c.y - p * c.n;
      ss += e * e;
    }
    const double v = static_cast<double>(g) / static_cast<double>(g - 1) * ss / (n * n);
    hv.deff = v / binomial;
  }
  return Finish(y, n, {hv}, z);
}

RateInterval PooledRate(const std::vector<RunRate>& runs, double z) {
  double y = 0, n = 0;
  long r = 0;
  Level hv, run;
  for (const RunRate& x : runs) {
    if (!(x.n > 0)) continue;
    y += x.y;
    n += x.n;
    ++r;
    hv.clusters += x.clusters;
    hv.df += static_cast<double>(std::max(x.clusters - 1, 0L));
  }
  run.clusters = r;
  run.df = static_cast<double>(r - 1);
  const double p = n > 0 ? y / n : 0.0;
  const double binomial = n > 0 ? p * (1 - p) / n : 0.0;
  if (binomial > 0) {
    // The HVs: each run's clustered variance of its own rate (stratified by run).
    double v_hv = 0;
    for (const RunRate& x : runs) {
      if (!(x.n > 0)) continue;
      const double pr = x.y / x.n;
      v_hv += (std::isfinite(x.deff) ? x.deff : 1.0) * pr * (1 - pr) * x.n;
    }
    hv.deff = v_hv / (n * n) / binomial;
    // The runs: CR1 over their totals.
    if (r >= 2) {
      double ss = 0;
      for (const RunRate& x : runs) {
        if (!(x.n > 0)) continue;
        const double e = x.y - p * x.n;
        ss += e * e;
      }
      run.deff = static_cast<double>(r) / static_cast<double>(r - 1) * ss / (n * n) / binomial;
    }
  }
  return Finish(y, n, {hv, run}, z);
}

MeanInterval ClusteredMean(const std::vector<double>& x, const std::vector<std::string>& cluster,
                           double level) {
  MeanInterval m;
  if (x.empty()) return m;
  double sum = 0;
  for (double v : x) sum += v;
  const double n = static_cast<double>(x.size());
  m.mean = sum / n;
  std::map<std::string, double> residual;  // sum of (x - mean) per cluster
  for (std::size_t i = 0; i < x.size(); ++i) residual[cluster[i]] += x[i] - m.mean;
  const long g = static_cast<long>(residual.size());
  m.clusters = g;
  if (g < 2) return m;
  double ss = 0;
  for (const auto& [c, r] : residual) ss += r * r;
  const double se = std::sqrt(static_cast<double>(g) / static_cast<double>(g - 1) * ss) / n;
  const double t = StudentTQuantile(static_cast<double>(g - 1), level);
  m.low = m.mean - t * se;
  m.high = m.mean + t * se;
  return m;
}

}  // namespace taebp
