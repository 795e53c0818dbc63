// Planning a sweep is linear in its points (issue 32, item 8: `taebp sweep
// --list` with one axis of N values took 1.0 / 3.2 / 11.7 / 42.8 s for N =
// 1,250 / 2,500 / 5,000 / 10,000, because each point's config copied the
// whole grid). Asserted on the cause (a point's config does not carry the
// grid) and on the growth (8 times the points cost well under 64 times the
// CPU time), not on a wall time.
// The cause's test also runs under the sanitizers; the growth's test only in the
// plain half (11 s there, 197 s under the sanitizers' -O0 at 6e7246f).
#include "taebp/config/config.h"
#include "taebp/sweep/plan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <ctime>
#include <string>

namespace taebp::sweep {
namespace {

const char* kBase = "scenario: {avs: 8, hvs: 8, seed: 10, duration: 60}\npolicies: [ta_ebp]\n";

// --set 'sweep.grid={model.trust: [v1, ..., vN]}' (as the reproduction).
std::string GridOverride(int n) {
  std::string values;
  for (int i = 0; i < n; ++i)
    values += (i ? ", " : "") + std::to_string(0.05 + 0.9 * i / n).substr(0, 8);
  return "sweep.grid={model.trust: [" + values + "]}";
}

// CPU seconds (not wall time: a loaded machine would blur the growth).
double SecondsToPlan(int n) {
  const std::clock_t start = std::clock();
  const Plan plan = ExpandSweep(std::string(kBase) + "sweep: {replicates: 1}\n", "scale.yaml",
                                {GridOverride(n)});
  const double s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  EXPECT_EQ(plan.points.size(), static_cast<std::size_t>(n));
  return s;
}

// taebp-test: sanitize (also run under the sanitizers; tests/CMakeLists.txt)
TEST(SweepPlan, APointsConfigDoesNotCarryTheGrid) {
  const ExperimentTemplate t(std::string(kBase) + "sweep: {replicates: 1}\n", "scale.yaml",
                             {GridOverride(100)});
  const ExperimentConfig c = t.Load({"model.trust=0.4"});
  EXPECT_FALSE(c.sweep.has_value()) << "each point's config holds the sweep's grid";
  EXPECT_DOUBLE_EQ(c.model.trust.value, 0.4);
  EXPECT_EQ(c.scenario.avs, 8);
}

TEST(SweepPlan, ATwentyThousandValueAxisIsPlannedInLinearTime) {
  const double small = SecondsToPlan(2500);
  const double large = SecondsToPlan(20000);
  // Linear: about 8x; quadratic (the bug): about 64x (20,000 never finished in 300 s).
  EXPECT_LT(large, 24 * small + 0.5) << "2,500 points in " << small << " s, 20,000 in " << large
                                     << " s";
}

}  // namespace
}  // namespace taebp::sweep
