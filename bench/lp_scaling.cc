// How SolveTrustAwarePersuasion scales: random n x n games (n states, n
// actions, prior and utilities drawn from a fixed seed, theta = 0.7), solved
// with the lazy obedience rows (the default) and, up to --full-up-to, with the
// full LP too, whose optimum must be the same. Every lazy solution is checked
// for obedience. Prints one line per n and, for the largest n given, checks the
// target (default: n = 100 within 10 s); exits 1 if a check or the target fails.
// A benchmark, not a test: run it on demand (tools/bench), never in ctest.
//
// usage: lp_scaling [N | NxM ...] [--full-up-to N] [--target-seconds S] [--seed S]
#include "taebp/persuasion/lp.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <utility>
#include <string>
#include <vector>

namespace per = taebp::persuasion;

namespace {

per::Game RandomGame(int n, int m, std::uint64_t seed) {
  std::mt19937_64 rng(seed + static_cast<std::uint64_t>(n) * 100003u + static_cast<std::uint64_t>(m));
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  per::Game g;
  for (int i = 0; i < n; ++i) g.states.push_back("s" + std::to_string(i));
  for (int a = 0; a < m; ++a) g.actions.push_back("a" + std::to_string(a));
  g.prior.resize(n);
  for (int i = 0; i < n; ++i) g.prior(i) = 0.1 + unit(rng);
  g.prior /= g.prior.sum();
  g.receiver_utility.resize(n, m);
  g.sender_utility.resize(n, m);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < m; ++a) {
      g.receiver_utility(i, a) = sym(rng);
      g.sender_utility(i, a) = sym(rng);
    }
  }
  return g;
}

double Seconds(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Largest violation of obedience, as a utility gain at the posterior: for every
// recommended a and every a', sum_w p_theta(w|a) (u(w,a') - u(w,a)) <= this.
double WorstObedienceGap(const per::Game& g, const per::LpResult& r) {
  double worst = 0.0;
  for (Eigen::Index a = 0; a < r.posteriors.cols(); ++a) {
    if (r.signal_probability(a) < per::kMinSignalProbability) continue;
    const Eigen::VectorXd utilities = g.receiver_utility.transpose() * r.posteriors.col(a);
    worst = std::max(worst, utilities.maxCoeff() - utilities(a));
  }
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::pair<int, int>> sizes;
  int full_up_to = 50;
  double target_seconds = 10.0;
  std::uint64_t seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--full-up-to" && i + 1 < argc) {
      full_up_to = std::atoi(argv[++i]);
    } else if (a == "--target-seconds" && i + 1 < argc) {
      target_seconds = std::atof(argv[++i]);
    } else if (a == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (!a.empty() && a[0] != '-') {
      // N (N states x N actions) or NxM (N states x M actions).
      const auto x = a.find('x');
      const int n = std::atoi(a.c_str());
      sizes.emplace_back(n, x == std::string::npos ? n : std::atoi(a.c_str() + x + 1));
    } else {
      std::fprintf(stderr,
                   "usage: lp_scaling [N | NxM ...] [--full-up-to N] [--target-seconds S] [--seed S]\n");
      return 2;
    }
  }
  if (sizes.empty()) sizes = {{10, 10}, {20, 20}, {30, 30}, {50, 50}, {70, 70}, {100, 100}};
  const double theta = 0.7;
  bool ok = true;
  std::printf("%11s %8s %15s %6s %6s %9s %9s %14s %10s\n", "n x m", "n*m", "rows used", "rounds",
              "merged", "lazy s", "full s", "sender value", "obedience");
  double last_lazy = 0.0;
  for (const auto& [n, m] : sizes) {
    char shape[32];
    std::snprintf(shape, sizeof shape, "%dx%d", n, m);
    const per::Game g = RandomGame(n, m, seed);
    auto t0 = std::chrono::steady_clock::now();
    const per::LpResult lazy = per::SolveTrustAwarePersuasion(g, theta);
    last_lazy = Seconds(t0);
    if (lazy.status != per::LpResult::Status::kOptimal) {
      std::printf("%11s lazy LP: %s %s\n", shape, per::ToString(lazy.status), lazy.message.c_str());
      ok = false;
      continue;
    }
    const double gap = WorstObedienceGap(g, lazy);
    const bool obedient =
        per::WeaklyPrefers(-gap, per::UtilityScale(g.receiver_utility), per::kObedienceTolerance);
    ok = ok && obedient;
    std::string full_text = "-";
    if (std::max(n, m) <= full_up_to) {
      per::LpOptions options;
      options.lazy_obedience = false;
      t0 = std::chrono::steady_clock::now();
      const per::LpResult full = per::SolveTrustAwarePersuasion(g, theta, options);
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.3f", Seconds(t0));
      full_text = buffer;
      if (full.status != per::LpResult::Status::kOptimal ||
          std::abs(full.sender_value - lazy.sender_value) > 1e-7) {
        std::printf("%11s full LP disagrees: %s value %.12g vs lazy %.12g\n", shape,
                    per::ToString(full.status), full.sender_value, lazy.sender_value);
        ok = false;
      }
    }
    char rows[32];
    std::snprintf(rows, sizeof rows, "%d/%d", lazy.obedience_rows, m * (m - 1));
    std::printf("%11s %8d %15s %6d %6d %9.3f %9s %14.10f %10s\n", shape, n * m, rows,
                lazy.simplex_rounds, lazy.merged_recommendations, last_lazy, full_text.c_str(), lazy.sender_value,
                obedient ? "ok" : ("gap " + std::to_string(gap)).c_str());
    std::fflush(stdout);
  }
  const bool fast = last_lazy <= target_seconds;
  std::printf("target: %dx%d within %.1f s: %.3f s, %s\n", sizes.back().first, sizes.back().second,
              target_seconds, last_lazy,
              fast ? "ok" : "MISSED");
  return ok && fast ? 0 : 1;
}
