#include "taebp/report/report.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

#if __has_include("taebp_git.h")
#include "taebp_git.h"
#endif
#ifndef TAEBP_GIT_REVISION
#define TAEBP_GIT_REVISION "unknown"
#endif
#ifndef TAEBP_VERSION
#define TAEBP_VERSION "0.1.0"
#endif

namespace taebp {
namespace {

using json = nlohmann::ordered_json;

// 97.5% standard normal quantile.
constexpr double kZ95 = 1.959963984540054;

std::string PolicyLabel(const std::string& p) {
  if (p == "no_ebp") return "No EBP";
  if (p == "no_trust") return "No Trust";
  if (p == "ta_ebp") return "TA-EBP";
  if (p == "full_reveal") return "Full reveal";
  return p;
}

struct Stats {
  long n = 0, collisions = 0, dc = 0, nudges = 0;
  double commanded_sum = 0, observed_sum = 0, max_abs_error = 0;
  double min_excess = 0;  // min over nudges of observed - commanded
  double theory_dc_sum = 0, theory_collision_sum = 0;  // per-encounter predictions
};

Stats Compute(const PolicyRun& r) {
  Stats s;
  s.n = static_cast<long>(r.encounters.size());
  bool first = true;
  for (const EncounterRecord& e : r.encounters) {
    s.collisions += e.collision;
    s.dc += e.hv_dc;
    s.theory_dc_sum += e.theory_dc;
    s.theory_collision_sum += e.theory_collision;
    if (e.commanded > 0) {
      ++s.nudges;
      s.commanded_sum += e.commanded;
      s.observed_sum += e.observed;
      const double excess = e.observed - e.commanded;
      s.max_abs_error = std::max(s.max_abs_error, std::abs(excess));
      s.min_excess = first ? excess : std::min(s.min_excess, excess);
      first = false;
    }
  }
  return s;
}

double Rate(long k, long n) { return n > 0 ? static_cast<double>(k) / n : 0.0; }

}  // namespace

std::string FormatDouble(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

Interval Wilson95(long k, long n) {
  if (n <= 0) return {0.0, 1.0};
  const double p = static_cast<double>(k) / n;
  const double z2 = kZ95 * kZ95;
  const double denom = 1 + z2 / n;
  const double centre = (p + z2 / (2.0 * n)) / denom;
  const double half = kZ95 * std::sqrt(p * (1 - p) / n + z2 / (4.0 * n * n)) / denom;
  // At k = 0 (k = n) the bound is exactly 0 (1); avoid round-off residue.
  return {k == 0 ? 0.0 : std::max(0.0, centre - half), k == n ? 1.0 : std::min(1.0, centre + half)};
}

std::string BuildGitRevision() { return TAEBP_GIT_REVISION; }
std::string TaebpVersion() { return TAEBP_VERSION; }

std::string SummaryJson(const std::vector<PolicyRun>& runs, const Provenance& prov) {
  json root;
  json& p = root["provenance"];
  p["tool"] = "taebp " + prov.taebp_version;
  p["git_revision"] = prov.git_revision;
  p["sumo_version"] = prov.sumo_version;
  p["seed"] = prov.seed;
  p["config_path"] = prov.config_path;
  p["config"] = json::parse(prov.config_json);
  p["warnings"] = prov.warnings;
  json& pol = root["policies"];
  pol = json::object();
  for (const PolicyRun& r : runs) {
    const Stats s = Compute(r);
    const Interval ci_c = Wilson95(s.collisions, s.n);
    const Interval ci_d = Wilson95(s.dc, s.n);
    const double hours = r.simulated_seconds / 3600.0;
    json j;
    j["encounters"] = s.n;
    j["collisions"] = s.collisions;
    j["collision_rate"] = Rate(s.collisions, s.n);
    j["collision_rate_ci95"] = {ci_c.low, ci_c.high};
    j["dc"] = s.dc;
    j["dc_rate"] = Rate(s.dc, s.n);
    j["dc_rate_ci95"] = {ci_d.low, ci_d.high};
    j["theory"] = {{"collision_rate", r.theory.collision_rate},
                   {"dc_rate", r.theory.dc_rate},
                   {"nudge_rate", r.theory.nudge_rate},
                   {"av_first_rate", r.theory.av_first_rate}};
    // Mean of the per-encounter predictions for the HVs actually met (equals
    // `theory` for a fixed trust; the fair comparison for a drawn population).
    j["theory_given_hvs"] = {{"collision_rate", s.n ? s.theory_collision_sum / s.n : 0.0},
                             {"dc_rate", s.n ? s.theory_dc_sum / s.n : 0.0}};
    j["hv_trust"] = r.hv_trust;
    j["scheme"] = {{"av_may_go", r.scheme.av_may_go},
                   {"nudge", r.scheme.nudge},
                   {"p_nudge_given_go", r.scheme.a},
                   {"p_nudge_given_stop", r.scheme.b}};
    const long all = r.crossings_av + r.crossings_hv;
    j["throughput_per_hour"] = {{"av", hours > 0 ? r.crossings_av / hours : 0.0},
                                {"hv", hours > 0 ? r.crossings_hv / hours : 0.0},
                                {"all", hours > 0 ? all / hours : 0.0}};
    j["crossings"] = {{"av", r.crossings_av}, {"hv", r.crossings_hv}, {"all", all}};
    j["wait_at_stop_line"] = {{"mean", all > 0 ? r.wait_sum / all : 0.0}, {"max", r.wait_max}};
    j["nudges"] = {{"count", s.nudges},
                   {"mean_commanded", s.nudges ? s.commanded_sum / s.nudges : 0.0},
                   {"mean_observed", s.nudges ? s.observed_sum / s.nudges : 0.0},
                   {"max_abs_error", s.max_abs_error},
                   {"min_observed_minus_commanded", s.min_excess},
                   {"tolerance", kNudgeTolerance}};
    j["other_collisions"] = r.other_collisions;
    j["teleports"] = r.teleports;
    j["longest_gap_without_crossing"] = r.longest_gap_without_crossing;
    j["simulated_seconds"] = r.simulated_seconds;
    pol[r.policy] = j;
  }
  return root.dump(2) + "\n";
}

std::string EncountersCsv(const std::vector<PolicyRun>& runs, const Provenance& prov) {
  std::ostringstream out;
  out << "# taebp " << prov.taebp_version << " git " << prov.git_revision << " | "
      << prov.sumo_version << " | seed " << prov.seed << " | config " << prov.config_path
      << "\n# config " << prov.config_json << "\n";
  out << "policy,time,av,hv,intent,commanded_nudge,observed_displacement,hv_trust,"
         "hv_posterior,hv_action,av_action,collision\n";
  for (const PolicyRun& r : runs) {
    for (const EncounterRecord& e : r.encounters) {
      out << r.policy << ',' << FormatDouble(e.time) << ',' << e.av << ',' << e.hv << ','
          << (e.intent_go ? "go" : "stop") << ',' << FormatDouble(e.commanded) << ','
          << FormatDouble(e.observed) << ',' << FormatDouble(e.hv_trust) << ',' << FormatDouble(e.posterior) << ','
          << (e.hv_dc ? "DC" : "DR") << ',' << (e.av_first ? "go" : "wait") << ','
          << (e.collision ? 1 : 0) << '\n';
    }
  }
  return out.str();
}

void PrintTable(std::ostream& out, const std::vector<PolicyRun>& runs) {
  const int w0 = 22, w = 34;
  out << std::left << std::setw(w0) << "Metric";
  for (const PolicyRun& r : runs) out << std::setw(w) << PolicyLabel(r.policy);
  out << "\n";
  auto cell = [&](long k, long n, double theory) {
    const Interval ci = Wilson95(k, n);
    char buf[96];
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "n/a (no AV-HV encounter) th %.3f", theory);
      return std::string(buf);
    }
    std::snprintf(buf, sizeof buf, "%.3f [%.3f,%.3f] th %.3f", Rate(k, n), ci.low, ci.high,
                  theory);
    return std::string(buf);
  };
  std::vector<Stats> stats;
  for (const PolicyRun& r : runs) stats.push_back(Compute(r));
  out << std::setw(w0) << "Collision Rate";
  for (std::size_t i = 0; i < runs.size(); ++i)
    out << std::setw(w) << cell(stats[i].collisions, stats[i].n, runs[i].theory.collision_rate);
  out << "\n" << std::setw(w0) << "DC Rate";
  for (std::size_t i = 0; i < runs.size(); ++i)
    out << std::setw(w) << cell(stats[i].dc, stats[i].n, runs[i].theory.dc_rate);
  out << "\n" << std::setw(w0) << "AV-HV encounters";
  for (std::size_t i = 0; i < runs.size(); ++i) out << std::setw(w) << stats[i].n;
  out << "\n" << std::setw(w0) << "Crossings / hour";
  for (const PolicyRun& r : runs) {
    const double h = r.simulated_seconds / 3600.0;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f (AV %.0f, HV %.0f)",
                  h > 0 ? (r.crossings_av + r.crossings_hv) / h : 0.0,
                  h > 0 ? r.crossings_av / h : 0.0, h > 0 ? r.crossings_hv / h : 0.0);
    out << std::setw(w) << buf;
  }
  out << "\n" << std::setw(w0) << "Mean / max wait (s)";
  for (const PolicyRun& r : runs) {
    const long all = r.crossings_av + r.crossings_hv;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f / %.1f", all ? r.wait_sum / all : 0.0, r.wait_max);
    out << std::setw(w) << buf;
  }
  out << "\n";
  out << "(rate [95% Wilson interval] th = library theory for the same parameters)\n";
}

void WriteFilesAtomically(const std::string& dir,
                          const std::vector<std::pair<std::string, std::string>>& files) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const std::string suffix = ".tmp." + std::to_string(::getpid());
  std::vector<fs::path> temps;
  auto fail = [](const fs::path& p, const char* what) {
    return std::runtime_error("cannot write " + p.string() + ": " + what + ": " +
                              std::strerror(errno));
  };
  try {
    // Each file in full, on disk (fsync), under a temporary name ...
    for (const auto& [name, content] : files) {
      const fs::path tmp = fs::path(dir) / (name + suffix);
      const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (fd < 0) throw fail(tmp, "open");
      temps.push_back(tmp);
      std::size_t done = 0;
      while (done < content.size()) {
        const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
          const std::runtime_error e = fail(tmp, "write");
          ::close(fd);
          throw e;
        }
        done += static_cast<std::size_t>(n);
      }
      if (::fsync(fd) != 0) {
        const std::runtime_error e = fail(tmp, "fsync");
        ::close(fd);
        throw e;
      }
      if (::close(fd) != 0) throw fail(tmp, "close");
    }
  } catch (...) {
    std::error_code ec;
    for (const fs::path& t : temps) fs::remove(t, ec);
    throw;
  }
  // ... then renamed into place, and the folder's entries synced.
  for (std::size_t i = 0; i < files.size(); ++i)
    fs::rename(temps[i], fs::path(dir) / files[i].first);
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace taebp
