// The Table I printout of a run (report.h's PrintTable): a column per
// policy, the paper's rows (collision and DC rates with clustered intervals
// against the theory) and, where they apply, the network's, beyond-the-paper
// and stalled-junction rows, then the footnotes.
#include "taebp/report/report.h"

#include "metric_facts.h"
#include "taebp/report/clustered.h"
#include "taebp/config/policies.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <ostream>
#include <string>
#include <vector>

namespace taebp {
namespace {

// Whether a run measured more than an hour: only then is its last hour not
// the whole run.
bool LongerThanAnHour(const std::vector<PolicyRun>& runs) {
  return std::any_of(runs.begin(), runs.end(),
                     [](const PolicyRun& r) { return r.measured_seconds > 3600.0 + 1e-9; });
}

}  // namespace

void PrintTable(std::ostream& out, const std::vector<PolicyRun>& runs,
                const std::vector<std::string>& warnings) {
  const int w0 = 22, w = 34;
  out << std::left << std::setw(w0) << "Metric";
  for (const PolicyRun& r : runs) out << std::setw(w) << PolicyLabel(r.policy);
  out << "\n";
  bool flagged = false, few = false;
  // A rate with its 95 % interval clustered by HV (clustered.h); "~" where
  // too few HVs were met for any interval to account for their dependence.
  auto interval = [&](const RateInterval& ci) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f [%.3f,%.3f]%s", ci.rate, ci.low, ci.high,
                  ci.few_clusters ? "~" : "");
    few = few || ci.few_clusters;
    return std::string(buf);
  };
  auto cell = [&](const PolicyRun& r, const char* metric, double theory) {
    char buf[96];
    if (r.encounters.empty() && theory < 0) return std::string("- (SUMO's own logic)");
    if (r.encounters.empty()) {
      std::snprintf(buf, sizeof buf, "n/a (no AV-HV encounter) th %.3f", theory);
      return std::string(buf);
    }
    const RateInterval ci = RunRateInterval(r, metric);
    if (std::isnan(theory)) return interval(ci) + " th n/a";  // not modelled
    // The theory outside the measured rate's 95% interval: worth a look.
    const bool outside = theory < ci.low || theory > ci.high;
    flagged = flagged || outside;
    std::snprintf(buf, sizeof buf, " th %.3f%s", theory, outside ? " !" : "");
    return interval(ci) + buf;
  };
  std::vector<EncounterStats> stats;
  for (const PolicyRun& r : runs) stats.push_back(ComputeEncounterStats(r));
  out << std::setw(w0) << "Collision Rate";
  for (std::size_t i = 0; i < runs.size(); ++i)
    out << std::setw(w)
        << cell(runs[i], "collision_rate",
                !PlaysGame(runs[i].policy) ? -1.0 : runs[i].theory.collision_rate);
  // The headline's count: every collision a move of the game took part in
  // (metric collisions_total), a third vehicle hit by one included.
  out << "\n" << std::setw(w0) << "Collisions, all";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    char buf[96];
    if (!PlaysGame(runs[i].policy))
      std::snprintf(buf, sizeof buf, "- (SUMO's own logic: %ld)", runs[i].other_collisions);
    else
      std::snprintf(buf, sizeof buf, "%ld (AV-HV %ld, third vehicles %ld)",
                    stats[i].collisions + runs[i].other_collisions_game_move, stats[i].collisions,
                    runs[i].other_collisions_game_move);
    out << std::setw(w) << buf;
  }
  out << "\n" << std::setw(w0) << "DC Rate";
  for (std::size_t i = 0; i < runs.size(); ++i)
    out << std::setw(w)
        << cell(runs[i], "dc_rate", !PlaysGame(runs[i].policy) ? -1.0 : runs[i].theory.dc_rate);
  // The design effects of the two rates' intervals, and the HVs they rest on.
  out << "\n" << std::setw(w0) << "Design effect (HVs)";
  for (const PolicyRun& r : runs) {
    char buf[96];
    if (r.encounters.empty()) {
      std::snprintf(buf, sizeof buf, "-");
    } else {
      const RateInterval c = RunRateInterval(r, "collision_rate");
      const RateInterval d = RunRateInterval(r, "dc_rate");
      std::snprintf(buf, sizeof buf, "%.2f / %.2f (%ld HVs)", c.deff, d.deff, d.clusters);
    }
    out << std::setw(w) << buf;
  }
  out << "\n" << std::setw(w0) << "AV-HV encounters";
  for (std::size_t i = 0; i < runs.size(); ++i) out << std::setw(w) << stats[i].n;
  const bool network = !runs.empty() && runs.front().scenario_kind == "network";
  out << "\n" << std::setw(w0) << (network ? "Junction crossings/h" : "Crossings / hour");
  for (const PolicyRun& r : runs) {
    const double h = r.measured_seconds / 3600.0;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f (AV %.0f, HV %.0f)",
                  h > 0 ? (r.crossings_av + r.crossings_hv) / h : 0.0,
                  h > 0 ? r.crossings_av / h : 0.0, h > 0 ? r.crossings_hv / h : 0.0);
    out << std::setw(w) << buf;
  }
  out << "\n" << std::setw(w0) << "Mean / max wait (s)";
  for (const PolicyRun& r : runs) {
    char buf[64];
    if (r.held == 0)
      std::snprintf(buf, sizeof buf, "%s",
                    !PlaysGame(r.policy) ? "n/a (SUMO's own logic)" : "no vehicle held");
    else
      std::snprintf(buf, sizeof buf, "%.1f / %.1f", r.wait_sum / r.held, r.wait_max);
    out << std::setw(w) << buf;
  }
  out << "\n";
  if (network) {
    auto row = [&](const char* label, auto cell) {
      out << std::setw(w0) << label;
      for (const PolicyRun& r : runs) out << std::setw(w) << cell(r);
      out << "\n";
    };
    // A stalled run's flow and delay are those of a gridlock (see the
    // footnote), not of the junction logic: marked.
    auto mark = [](const PolicyRun& r) { return r.stalls.empty() ? "" : " stalled"; };
    row("Served flow (veh/h)", [&](const PolicyRun& r) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.0f (%ld in, %ld out)%s",
                    PerHour(static_cast<double>(r.network.arrived), r.measured_seconds),
                    r.network.departed, r.network.arrived, mark(r));
      return std::string(buf);
    });
    row("Mean delay (s)", [&](const PolicyRun& r) {
      char buf[96];
      const NetworkRun& n = r.network;
      std::snprintf(buf, sizeof buf, "%.1f loss, %.1f waiting%s",
                    n.trips ? n.time_loss_sum / n.trips : 0.0,
                    n.trips ? n.waiting_time_sum / n.trips : 0.0, mark(r));
      return std::string(buf);
    });
    row("Trips (unfinished)", [](const PolicyRun& r) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%ld (%ld unfinished)", r.network.trips,
                    r.network.trips_unfinished);
      return std::string(buf);
    });
    row("Waiting to depart", [](const PolicyRun& r) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%ld at end (max %ld)", r.network.pending_end,
                    r.network.pending_max);
      return std::string(buf);
    });
  }
  if (AnyBeyond(runs)) {
    auto row = [&](const char* label, auto cell) {
      out << std::setw(w0) << label;
      for (const PolicyRun& r : runs) out << std::setw(w) << cell(r);
      out << "\n";
    };
    // The last hour apart from the whole run only where the run measured
    // more than an hour (a shorter run's last hour is the run).
    if (LongerThanAnHour(runs))
      row("Last hour DC rate", [&](const PolicyRun& r) {
        if (!PlaysGame(r.policy)) return std::string("-");
        const LastHourWindow win = LastHour(r);
        char buf[96];
        std::snprintf(buf, sizeof buf, " or %.3f", win.n ? win.oracle_dc / win.n : 0.0);
        return interval(RunRateInterval(r, "last_hour_dc_rate")) + buf;
      });
    row("Regret / encounter", [](const PolicyRun& r) {
      if (!PlaysGame(r.policy) || r.encounters.empty()) return std::string("-");
      double regret = 0;
      for (const EncounterRecord& e : r.encounters) regret += e.beyond.regret;
      if (std::isnan(regret)) return std::string("n/a (no theory)");
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.4f (total %.1f)", regret / r.encounters.size(), regret);
      return std::string(buf);
    });
    // Mean trust at the start and the end only where trust moves (dynamic
    // trust, experience); otherwise the two are the same draw.
    const bool moves = std::any_of(runs.begin(), runs.end(),
                                   [](const PolicyRun& r) { return r.beyond.trust_moves; });
    if (moves)
      row("Mean trust start/end", [](const PolicyRun& r) {
        if (!PlaysGame(r.policy)) return std::string("-");
        char buf[96];
        if (r.beyond.long_run)
          std::snprintf(buf, sizeof buf, "%.3f / %.3f (long run %.3f)", r.beyond.initial_mean_trust,
                        r.beyond.final_mean_trust, r.beyond.expected_long_run_mean);
        else
          std::snprintf(buf, sizeof buf, "%.3f / %.3f", r.beyond.initial_mean_trust,
                        r.beyond.final_mean_trust);
        return std::string(buf);
      });
  }
  const bool stalled = std::any_of(runs.begin(), runs.end(),
                                   [](const PolicyRun& r) { return !r.stalls.empty(); });
  if (stalled) {
    out << std::setw(w0) << "Stalled junctions";
    for (const PolicyRun& r : runs)
      out << std::setw(w)
          << (r.stalls.empty() ? std::string("none")
                               : std::to_string(r.stalls.size()) +
                                     (r.stall_error.empty() ? " (recorded)" : " (run stopped)"));
    out << "\n";
  }
  out << "(rate [95% interval clustered by HV: Wilson's where the design effect <= 1] th = "
         "library theory for the same parameters)\n"
         "(design effect: of the collision rate / of the DC rate, over the HVs met)\n";
  if (network)
    out << "(delay: SUMO's tripinfo of every trip departed after the warm-up, finished or "
           "still in the network at the end)\n";
  for (const PolicyRun& r : runs) {
    if (r.stalls.empty()) continue;
    out << "stalled: " << PolicyLabel(r.policy) << " at";
    for (std::size_t k = 0; k < r.stalls.size(); ++k) {
      char buf[64];
      std::snprintf(buf, sizeof buf, " since t = %.1f s", r.stalls[k].since);
      out << (k ? ", " : " ") << r.stalls[k].junction << buf;
    }
    out << (r.stall_error.empty()
                ? "; its figures are from a stalled run"
                : "; the run stopped there (scenario.stall_action: error): its figures are up to "
                  "the stall")
        << "\n";
  }
  if (AnyBeyond(runs))
    out << (LongerThanAnHour(runs) ? "(or = the oracle, TA-EBP for each HV's exact trust, on the "
                                     "same encounters; regret = DC lost + r x collisions against "
                                     "it)\n"
                                   : "(regret = DC lost + r x collisions against the oracle, "
                                     "TA-EBP for each HV's exact trust, on the same "
                                     "encounters)\n");
  if (flagged) out << "! the theory lies outside the measured rate's 95% interval\n";
  if (few)
    out << "~ fewer than " << kMinClusters
        << " HVs met: no interval can account for their encounters being dependent\n";
  for (const std::string& warning : warnings) out << "warning: " << warning << "\n";
}

}  // namespace taebp
