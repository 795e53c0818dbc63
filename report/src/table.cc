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

constexpr int kW0 = 22, kW = 34;  // the label column's width, a policy column's

// Prints the table's rows and footnotes, noting on the way whether a theory
// value was flagged and whether too few HVs were met for an interval.
class TablePrinter {
 public:
  TablePrinter(std::ostream& out, const std::vector<PolicyRun>& runs) : out_(out), runs_(runs) {}

  void Header();
  void PaperRows();
  void NetworkRows();
  void BeyondRows();
  void StalledRow();
  void Footnotes(const std::vector<std::string>& warnings);

  bool Network() const { return !runs_.empty() && runs_.front().scenario_kind == "network"; }

 private:
  std::string Interval(const RateInterval& ci);
  std::string Cell(const PolicyRun& r, const char* metric, double theory);
  void RateRows(const std::vector<EncounterStats>& stats);
  void TrafficRows(const std::vector<EncounterStats>& stats);
  template <typename F>
  void Row(const char* label, F cell) {
    out_ << std::setw(kW0) << label;
    for (const PolicyRun& r : runs_) out_ << std::setw(kW) << cell(r);
    out_ << "\n";
  }

  std::ostream& out_;
  const std::vector<PolicyRun>& runs_;
  bool flagged_ = false, few_ = false;
};

void TablePrinter::Header() {
  out_ << std::left << std::setw(kW0) << "Metric";
  for (const PolicyRun& r : runs_) out_ << std::setw(kW) << PolicyLabel(r.policy);
  out_ << "\n";
}

// A rate with its 95 % interval clustered by HV (clustered.h); "~" where
// too few HVs were met for any interval to account for their dependence.
std::string TablePrinter::Interval(const RateInterval& ci) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f [%.3f,%.3f]%s", ci.rate, ci.low, ci.high,
                ci.few_clusters ? "~" : "");
  few_ = few_ || ci.few_clusters;
  return std::string(buf);
}

std::string TablePrinter::Cell(const PolicyRun& r, const char* metric, double theory) {
  char buf[96];
  if (r.encounters.empty() && theory < 0) return std::string("- (SUMO's own logic)");
  if (r.encounters.empty()) {
    std::snprintf(buf, sizeof buf, "n/a (no AV-HV encounter) th %.3f", theory);
    return std::string(buf);
  }
  const RateInterval ci = RunRateInterval(r, metric);
  if (std::isnan(theory)) return Interval(ci) + " th n/a";  // not modelled
  // The theory outside the measured rate's 95% interval: worth a look.
  const bool outside = theory < ci.low || theory > ci.high;
  flagged_ = flagged_ || outside;
  std::snprintf(buf, sizeof buf, " th %.3f%s", theory, outside ? " !" : "");
  return Interval(ci) + buf;
}

// The paper's rows: the two rates against the theory, the collisions, then
// the design effects and the traffic.
void TablePrinter::PaperRows() {
  std::vector<EncounterStats> stats;
  for (const PolicyRun& r : runs_) stats.push_back(ComputeEncounterStats(r));
  RateRows(stats);
  TrafficRows(stats);
}

void TablePrinter::RateRows(const std::vector<EncounterStats>& stats) {
  const std::vector<PolicyRun>& runs = runs_;
  out_ << std::setw(kW0) << "Collision Rate";
  for (std::size_t i = 0; i < runs.size(); ++i)
    out_ << std::setw(kW)
         << Cell(runs[i], "collision_rate",
                 !PlaysGame(runs[i].policy) ? -1.0 : runs[i].theory.collision_rate);
  // The headline's count: every collision a move of the game took part in
  // (metric collisions_total), a third vehicle hit by one included.
  out_ << "\n" << std::setw(kW0) << "Collisions, all";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    char buf[96];
    if (!PlaysGame(runs[i].policy))
      std::snprintf(buf, sizeof buf, "- (SUMO's own logic: %ld)", runs[i].other_collisions);
    else
      std::snprintf(buf, sizeof buf, "%ld (AV-HV %ld, third vehicles %ld)",
                    stats[i].collisions + runs[i].other_collisions_game_move, stats[i].collisions,
                    runs[i].other_collisions_game_move);
    out_ << std::setw(kW) << buf;
  }
  out_ << "\n" << std::setw(kW0) << "DC Rate";
  for (std::size_t i = 0; i < runs.size(); ++i)
    out_ << std::setw(kW)
         << Cell(runs[i], "dc_rate", !PlaysGame(runs[i].policy) ? -1.0 : runs[i].theory.dc_rate);
}

void TablePrinter::TrafficRows(const std::vector<EncounterStats>& stats) {
  const std::vector<PolicyRun>& runs = runs_;
  // The design effects of the two rates' intervals, and the HVs they rest on.
  out_ << "\n" << std::setw(kW0) << "Design effect (HVs)";
  for (const PolicyRun& r : runs) {
    char buf[96];
    if (r.encounters.empty()) {
      std::snprintf(buf, sizeof buf, "-");
    } else {
      const RateInterval c = RunRateInterval(r, "collision_rate");
      const RateInterval d = RunRateInterval(r, "dc_rate");
      std::snprintf(buf, sizeof buf, "%.2f / %.2f (%ld HVs)", c.deff, d.deff, d.clusters);
    }
    out_ << std::setw(kW) << buf;
  }
  out_ << "\n" << std::setw(kW0) << "AV-HV encounters";
  for (std::size_t i = 0; i < runs.size(); ++i) out_ << std::setw(kW) << stats[i].n;
  out_ << "\n" << std::setw(kW0) << (Network() ? "Junction crossings/h" : "Crossings / hour");
  for (const PolicyRun& r : runs) {
    const double h = r.measured_seconds / 3600.0;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f (AV %.0f, HV %.0f)",
                  h > 0 ? (r.crossings_av + r.crossings_hv) / h : 0.0,
                  h > 0 ? r.crossings_av / h : 0.0, h > 0 ? r.crossings_hv / h : 0.0);
    out_ << std::setw(kW) << buf;
  }
  out_ << "\n" << std::setw(kW0) << "Mean / max wait (s)";
  for (const PolicyRun& r : runs) {
    char buf[64];
    if (r.held == 0)
      std::snprintf(buf, sizeof buf, "%s",
                    !PlaysGame(r.policy) ? "n/a (SUMO's own logic)" : "no vehicle held");
    else
      std::snprintf(buf, sizeof buf, "%.1f / %.1f", r.wait_sum / r.held, r.wait_max);
    out_ << std::setw(kW) << buf;
  }
  out_ << "\n";
}

// A network's rows: served flow, delay, trips, vehicles waiting to depart.
void TablePrinter::NetworkRows() {
  // A stalled run's flow and delay are those of a gridlock (see the
  // footnote), not of the junction logic: marked.
  auto mark = [](const PolicyRun& r) { return r.stalls.empty() ? "" : " stalled"; };
  Row("Served flow (veh/h)", [&](const PolicyRun& r) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.0f (%ld in, %ld out)%s",
                  PerHour(static_cast<double>(r.network.arrived), r.measured_seconds),
                  r.network.departed, r.network.arrived, mark(r));
    return std::string(buf);
  });
  Row("Mean delay (s)", [&](const PolicyRun& r) {
    char buf[96];
    const NetworkRun& n = r.network;
    std::snprintf(buf, sizeof buf, "%.1f loss, %.1f waiting%s",
                  n.trips ? n.time_loss_sum / n.trips : 0.0,
                  n.trips ? n.waiting_time_sum / n.trips : 0.0, mark(r));
    return std::string(buf);
  });
  Row("Trips (unfinished)", [](const PolicyRun& r) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%ld (%ld unfinished)", r.network.trips,
                  r.network.trips_unfinished);
    return std::string(buf);
  });
  Row("Waiting to depart", [](const PolicyRun& r) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%ld at end (max %ld)", r.network.pending_end,
                  r.network.pending_max);
    return std::string(buf);
  });
}

// The rows of a run beyond the paper: the last hour, the regret, the trust.
void TablePrinter::BeyondRows() {
  const std::vector<PolicyRun>& runs = runs_;
  // The last hour apart from the whole run only where the run measured
  // more than an hour (a shorter run's last hour is the run).
  if (LongerThanAnHour(runs))
    Row("Last hour DC rate", [&](const PolicyRun& r) {
      if (!PlaysGame(r.policy)) return std::string("-");
      const LastHourWindow win = LastHour(r);
      char buf[96];
      std::snprintf(buf, sizeof buf, " or %.3f", win.n ? win.oracle_dc / win.n : 0.0);
      return Interval(RunRateInterval(r, "last_hour_dc_rate")) + buf;
    });
  Row("Regret / encounter", [](const PolicyRun& r) {
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
    Row("Mean trust start/end", [](const PolicyRun& r) {
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

void TablePrinter::StalledRow() {
  const std::vector<PolicyRun>& runs = runs_;
  const bool stalled = std::any_of(runs.begin(), runs.end(),
                                   [](const PolicyRun& r) { return !r.stalls.empty(); });
  if (stalled) {
    out_ << std::setw(kW0) << "Stalled junctions";
    for (const PolicyRun& r : runs)
      out_ << std::setw(kW)
           << (r.stalls.empty() ? std::string("none")
                                : std::to_string(r.stalls.size()) +
                                      (r.stall_error.empty() ? " (recorded)" : " (run stopped)"));
    out_ << "\n";
  }
}

void TablePrinter::Footnotes(const std::vector<std::string>& warnings) {
  const std::vector<PolicyRun>& runs = runs_;
  out_ << "(rate [95% interval clustered by HV: Wilson's where the design effect <= 1] th = "
          "library theory for the same parameters)\n"
          "(design effect: of the collision rate / of the DC rate, over the HVs met)\n";
  if (Network())
    out_ << "(delay: SUMO's tripinfo of every trip departed after the warm-up, finished or "
            "still in the network at the end)\n";
  for (const PolicyRun& r : runs) {
    if (r.stalls.empty()) continue;
    out_ << "stalled: " << PolicyLabel(r.policy) << " at";
    for (std::size_t k = 0; k < r.stalls.size(); ++k) {
      char buf[64];
      std::snprintf(buf, sizeof buf, " since t = %.1f s", r.stalls[k].since);
      out_ << (k ? ", " : " ") << r.stalls[k].junction << buf;
    }
    out_ << (r.stall_error.empty()
                 ? "; its figures are from a stalled run"
                 : "; the run stopped there (scenario.stall_action: error): its figures are up to "
                   "the stall")
         << "\n";
  }
  if (AnyBeyond(runs))
    out_ << (LongerThanAnHour(runs) ? "(or = the oracle, TA-EBP for each HV's exact trust, on the "
                                      "same encounters; regret = DC lost + r x collisions against "
                                      "it)\n"
                                    : "(regret = DC lost + r x collisions against the oracle, "
                                      "TA-EBP for each HV's exact trust, on the same "
                                      "encounters)\n");
  if (flagged_) out_ << "! the theory lies outside the measured rate's 95% interval\n";
  if (few_)
    out_ << "~ fewer than " << kMinClusters
         << " HVs met: no interval can account for their encounters being dependent\n";
  for (const std::string& warning : warnings) out_ << "warning: " << warning << "\n";
}

}  // namespace

void PrintTable(std::ostream& out, const std::vector<PolicyRun>& runs,
                const std::vector<std::string>& warnings) {
  TablePrinter table(out, runs);
  table.Header();
  table.PaperRows();
  if (table.Network()) table.NetworkRows();
  if (AnyBeyond(runs)) table.BeyondRows();
  table.StalledRow();
  table.Footnotes(warnings);
}

}  // namespace taebp
