// Controller overhead against bare SUMO: the same network, vehicles and step,
// timed interleaved (bare, policy 1, policy 2, ..., bare, ...) so machine noise
// hits all alike. Prints the median wall time of each and the ratio
// median(policy) / median(bare). A benchmark, not a test: run it on demand
// (tools/bench), not in ctest.
#include "taebp/config/config.h"
#include "taebp/controller/experiment.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace {
double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
template <typename F>
double Time(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: sumo_overhead CONFIG [ROUNDS] [--set K=V]...\n");
    return 2;
  }
  const std::string path = argv[1];
  int rounds = 5;
  std::vector<std::string> overrides;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--set" && i + 1 < argc) overrides.push_back(argv[++i]);
    else rounds = std::max(1, std::atoi(a.c_str()));
  }
  try {
    const taebp::ExperimentConfig config = taebp::LoadExperimentConfig(path, overrides);
    const taebp::Scenario files = taebp::BuildScenario(config, "");
    std::vector<double> bare;
    std::map<std::string, std::vector<double>> policy;
    for (int r = 0; r < rounds; ++r) {
      bare.push_back(Time([&] { taebp::RunBareSumo(config, files); }));
      for (const std::string& p : config.policies)
        policy[p].push_back(
            Time([&] { taebp::RunPolicy(config, p, files); }));
    }
    const double b = Median(bare);
    std::printf("%.0f simulated s, %d vehicles, step %.2f s, %d interleaved rounds\n",
                config.scenario.duration, config.scenario.avs + config.scenario.hvs,
                config.scenario.step_length, rounds);
    std::printf("%-12s %10s %8s\n", "run", "median s", "ratio");
    std::printf("%-12s %10.3f %8.3f\n", "bare SUMO", b, 1.0);
    for (const std::string& p : config.policies) {
      const double m = Median(policy[p]);
      std::printf("%-12s %10.3f %8.3f\n", p.c_str(), m, m / b);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sumo_overhead: %s\n", e.what());
    return 1;
  }
  return 0;
}
