// Controller overhead against a baseline: the same network, vehicles and step,
// timed interleaved (baseline, policy 1, policy 2, ..., baseline, ...) so
// machine noise hits all alike. The baseline is bare SUMO (only
// Simulation::step; the default) or, with --baseline sumo_native, SUMO's own
// junction logic under the controller's observation (the policy every
// network throughput figure is compared with). Prints the median CPU time
// (user + system) of each and the ratio median(policy) / median(baseline),
// then the same for wall time, and on a network the most vehicles in it at
// once. The CPU ratio is the target's: on a shared machine wall time also
// counts the time a run waited for a core. A benchmark, not a test: run it on demand
// (tools/bench), not in ctest.
#include "taebp/config/config.h"
#include "taebp/controller/policy_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <sys/resource.h>

namespace {
double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
// The process's CPU time (user + system), s: what a run costs, whatever else
// the machine does meanwhile (wall time also counts the time this process
// waited for a core).
double CpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
struct Cost {
  double wall = 0, cpu = 0;
};
template <typename F>
Cost Time(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = CpuSeconds();
  f();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
          CpuSeconds() - c0};
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: sumo_overhead CONFIG [ROUNDS] [--baseline bare|%s] [--set K=V]...\n",
                 taebp::SumoNative().name);
    return 2;
  }
  const std::string path = argv[1];
  int rounds = 5;
  std::string baseline = "bare";
  std::vector<std::string> overrides;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--set" && i + 1 < argc) overrides.push_back(argv[++i]);
    else if (a == "--baseline" && i + 1 < argc) baseline = argv[++i];
    else rounds = std::max(1, std::atoi(a.c_str()));
  }
  try {
    const taebp::ExperimentConfig config = taebp::LoadExperimentConfig(path, overrides);
    const taebp::Scenario files = taebp::BuildScenario(config, "");
    std::vector<Cost> bare;
    std::map<std::string, std::vector<Cost>> policy;
    long vehicles_max = 0;
    std::size_t junctions = files.junctions.size();
    for (int r = 0; r < rounds; ++r) {
      if (baseline == "bare") {
        bare.push_back(Time([&] { taebp::RunBareSumo(config, files); }));
      } else {
        bare.push_back(Time([&] {
          const taebp::PolicyRun run = taebp::RunPolicy(config, taebp::SumoNative().name, files);
          vehicles_max = std::max(vehicles_max, run.network.vehicles_max);
        }));
      }
      for (const std::string& p : config.policies) {
        if (p == taebp::SumoNative().name) continue;
        policy[p].push_back(Time([&] {
          const taebp::PolicyRun run = taebp::RunPolicy(config, p, files);
          vehicles_max = std::max(vehicles_max, run.network.vehicles_max);
        }));
      }
    }
    auto median = [](const std::vector<Cost>& v, double Cost::*field) {
      std::vector<double> x;
      for (const Cost& c : v) x.push_back(c.*field);
      return Median(x);
    };
    const double b = median(bare, &Cost::cpu), bw = median(bare, &Cost::wall);
    if (config.scenario.IsNetwork())
      std::printf("%.0f simulated s, %zu controlled junctions, up to %ld vehicles at once, step "
                  "%.2f s, %d interleaved rounds\n",
                  config.scenario.duration, junctions, vehicles_max, config.scenario.step_length,
                  rounds);
    else
      std::printf("%.0f simulated s, %d vehicles, step %.2f s, %d interleaved rounds\n",
                  config.scenario.duration, config.scenario.avs + config.scenario.hvs,
                  config.scenario.step_length, rounds);
    std::printf("%-12s %10s %8s %10s %8s\n", "run", "median cpu", "ratio", "wall s", "ratio");
    std::printf("%-12s %10.3f %8.3f %10.3f %8.3f\n",
                baseline == "bare" ? "bare SUMO" : taebp::SumoNative().name, b, 1.0, bw, 1.0);
    for (const std::string& p : config.policies) {
      if (p == taebp::SumoNative().name) continue;
      const double m = median(policy[p], &Cost::cpu), mw = median(policy[p], &Cost::wall);
      std::printf("%-12s %10.3f %8.3f %10.3f %8.3f\n", p.c_str(), m, m / b, mw, mw / bw);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sumo_overhead: %s\n", e.what());
    return 1;
  }
  return 0;
}
