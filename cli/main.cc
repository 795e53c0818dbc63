// taebp: the command-line program. Subcommands: theory, solve, run, sweep, merge, snapshot,
// metrics, policies.
#include "taebp/config/config.h"
#include "taebp/controller/policy_run.h"
#include "taebp/controller/network_controller.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/report/metrics.h"
#include "taebp/report/paired.h"
#include "taebp/report/report.h"
#include "taebp/runner/errors.h"
#include "taebp/runner/runner.h"
#include "taebp/runner/theory.h"
#include "taebp/encounter/design.h"
#include "taebp/controller/sumo_adapter.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/lp.h"
#include "taebp/base/number_text.h"
#include "taebp/persuasion/outcomes.h"
#include "config_cmd.h"
#include "gui_cmd.h"
#include "sweep_cmd.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include <unistd.h>

namespace {

using nlohmann::ordered_json;
namespace per = taebp::persuasion;
namespace fs = std::filesystem;

using taebp::kExitConfig;  // base/exit_codes.h: the one list of exit codes
using taebp::kExitFailed;

// ------------------------------------------------------------------ theory
struct TheoryOptions : taebp::TheoryRequest {
  bool json = false;
};

int Theory(const TheoryOptions& o) {
  const ordered_json j = taebp::TheoryJson(o);  // the same object as Python's taebp.theory()
  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  auto t = [](double v) { return taebp::NumberText(v, 10); };
  auto num = [&](const char* key) { return t(j[key].get<double>()); };
  std::cout << "TA-EBP theory (" << j["likelihood"].get<std::string>()
            << " likelihood, s in [0, " << t(o.s_max) << "] m)\n"
            << "  prior lambda = p0(Go)            " << t(o.prior) << "\n"
            << "  collision penalty r              " << t(o.penalty) << "\n"
            << "  HV trust theta                   " << t(o.trust) << "\n"
            << "  AV's assumed trust theta_hat     " << num("assumed_trust") << "\n"
            << "  indifference posterior p*        " << num("p_star") << "   (eq:ppp)\n"
            << "  minimum persuadable trust theta* " << num("theta_star") << "   (eq:tt / eq:theta_star)\n"
            << "  persuadable (theta_hat >= theta*) "
            << (j["persuadable"].get<bool>() ? "yes" : "no: always yield") << "\n"
            << "  minimal nudge s*                 " << num("s_star") << " m   (eq:s^*)\n"
            << "  pi(s*|Go) = a                    " << num("a") << "\n"
            << "  pi(s*|Stop) = b                  " << num("b") << "   (eq:b)\n"
            << "  P(nudge) = lambda + (1-lambda) b " << num("p_nudge") << "\n\n"
            << "Predicted per AV-HV encounter, HV of true trust " << t(o.trust) << ":\n"
            << "  policy        DC rate       collision rate\n";
  const ordered_json& policies = j["policies"];
  for (auto it = policies.begin(); it != policies.end(); ++it) {
    std::cout << "  " << std::left << std::setw(14) << it.key() << std::setw(14)
              << t(it.value()["dc_rate"].get<double>()) << t(it.value()["collision_rate"].get<double>())
              << "\n";
  }
  if (j.contains("noise")) {
    const ordered_json& n = j["noise"];
    const ordered_json& a = n["aware"];
    std::cout << "\nWith perception noise (" << o.noise << ", scale " << t(o.noise_scale)
              << " m, bias " << t(o.noise_bias) << " m) on the HV's reading:\n"
              << "  noise-aware nudge s_delta        " << t(a["nudge"].get<double>()) << " m   ("
              << a["status"].get<std::string>() << ", P(DC | nudge) "
              << t(a["persuasion_probability"].get<double>()) << " >= 1 - delta = "
              << t(1.0 - o.noise_delta) << ")\n"
              << "  its b                            " << t(a["b"].get<double>()) << "\n"
              << "  policy        DC rate       collision rate\n"
              << "  " << std::left << std::setw(14) << "ta_ebp_aware" << std::setw(14)
              << t(a["dc_rate"].get<double>()) << t(a["collision_rate"].get<double>())
              << "   (bound delta * lambda = " << t(n["collision_bound"].get<double>()) << ")\n";
    const ordered_json& under = n["policies"];
    for (auto it = under.begin(); it != under.end(); ++it) {
      std::cout << "  " << std::left << std::setw(14) << it.key() << std::setw(14)
                << t(it.value()["dc_rate"].get<double>())
                << t(it.value()["collision_rate"].get<double>()) << "\n";
    }
  }
  return 0;
}

// ------------------------------------------------------------------ solve
int Solve(const std::string& path, bool json) {
  const taebp::ProblemConfig pc = taebp::LoadProblemConfig(path);
  const per::Game g = taebp::ProblemGame(pc, path);
  const auto n = static_cast<Eigen::Index>(g.states.size());
  const auto m = static_cast<Eigen::Index>(g.actions.size());
  per::LpResult r;
  try {
    r = per::SolveTrustAwarePersuasion(g, pc.trust);
  } catch (const per::InvalidArgument& e) {  // e.g. a game above the LP's size limits
    throw taebp::ConfigError(path + ": " + e.what());
  }
  if (json) {
    const ordered_json j = taebp::SolveResultJson(g, pc.trust, r);
    std::cout << j.dump(2) << "\n";
    return r.status == per::LpResult::Status::kOptimal ? 0 : kExitFailed;
  }
  auto t8 = [](double v) { return taebp::NumberText(v, 8); };
  std::cout << "status: " << per::ToString(r.status) << "\n";
  if (r.status != per::LpResult::Status::kOptimal) {
    std::cout << r.message << "\n";
    return kExitFailed;
  }
  std::cout << "trust theta: " << t8(pc.trust) << "\nsender value: " << t8(r.sender_value)
            << "\n\nscheme pi(recommend action | state):\n" << std::left << std::setw(16) << "";
  for (const auto& a : g.actions) std::cout << std::setw(14) << a;
  std::cout << "\n";
  for (Eigen::Index i = 0; i < n; ++i) {
    std::cout << std::setw(16) << g.states[i];
    for (Eigen::Index a = 0; a < m; ++a) std::cout << std::setw(14) << t8(r.scheme(i, a));
    std::cout << "\n";
  }
  std::cout << "\ntrust-weighted posterior after each recommendation:\n" << std::setw(16) << "";
  for (const auto& s : g.states) std::cout << std::setw(14) << s;
  std::cout << std::setw(14) << "P(signal)" << "\n";
  for (Eigen::Index a = 0; a < m; ++a) {
    std::cout << std::setw(16) << g.actions[a];
    for (Eigen::Index i = 0; i < n; ++i) {
      const double v = r.posteriors(i, a);
      if (std::isnan(v)) std::cout << std::setw(14) << "-";
      else std::cout << std::setw(14) << t8(v);
    }
    std::cout << std::setw(14) << t8(r.signal_probability(a)) << "\n";
  }
  return 0;
}

// ------------------------------------------------------------------ run
int RunExperimentCommand(const std::string& config_path, const std::vector<std::string>& overrides,
                         std::string out_dir, bool quiet, const taebp::RunOptions& run_options = {}) {
  if (out_dir.empty()) out_dir = taebp::DefaultOutDir(config_path);
  // Checked, not a sweep's, locked: before the first simulation step.
  taebp::RunFolder folder(out_dir);
  const taebp::InterruptGuard interrupts;
  // A progress line per policy on a terminal (not with --quiet, not when
  // stderr is a file or a pipe), rewritten in place, at most 5 times a second.
  // The terminal itself (a copy of stderr's descriptor): while SUMO runs,
  // stderr is collected (SUMO's warnings), the progress line is not.
  const bool live = !quiet && ::isatty(STDERR_FILENO) == 1;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> tty(
      live ? ::fdopen(::dup(STDERR_FILENO), "w") : nullptr, &std::fclose);
  bool line_open = false;
  auto clear_line = [&] {
    if (line_open && tty) {
      std::fputs("\r\033[K", tty.get());
      std::fflush(tty.get());
    }
    line_open = false;
  };
  taebp::RunOptions options = run_options;
  using Clock = std::chrono::steady_clock;
  Clock::time_point policy_start = Clock::now(), last_print{};
  std::string current;
  if (tty) {
    options.progress = [&](const taebp::RunOptions::Progress& p) {
      const Clock::time_point now = Clock::now();
      if (p.policy != current) current = p.policy, policy_start = now;
      if (now - last_print < std::chrono::milliseconds(200) && p.simulated < p.duration) return;
      last_print = now;
      const double wall = std::chrono::duration<double>(now - policy_start).count();
      const double eta = p.simulated > 0 ? wall * (p.duration - p.simulated) / p.simulated : 0;
      std::fprintf(tty.get(),
                   "\rtaebp: %-12s %.0f/%.0f s simulated, %ld vehicles, %ld encounters, "
                   "%.0f s to go\033[K",
                   p.policy.c_str(), p.simulated, p.duration, p.vehicles, p.encounters, eta);
      std::fflush(tty.get());
      line_open = true;
    };
  }
  taebp::ExperimentObserver observer;
  observer.warning = [&](const std::string& w) {
    clear_line();
    std::fprintf(stderr, "taebp: warning: %s\n", w.c_str());
  };
  observer.policy_done = [&](const taebp::PolicyRun& run, double wall) {
    clear_line();
    if (!quiet)
      std::fprintf(stderr, "taebp: %-12s %.0f simulated s in %.2f s wall, %zu encounters\n",
                   run.policy.c_str(), run.simulated_seconds, wall, run.encounters.size());
  };
  struct ClearOnExit {  // an error mid-run starts on a line of its own
    std::function<void()> f;
    ~ClearOnExit() { f(); }
  } clear_on_exit{clear_line};
  const taebp::ExperimentResult result =
      taebp::RunExperiment(config_path, overrides, options, observer);
  const std::string replaced = taebp::WriteExperiment(result, folder);
  std::cout << result.Table();
  if (!quiet && !replaced.empty()) std::fprintf(stderr, "taebp: %s\n", replaced.c_str());
  if (!quiet) std::fprintf(stderr, "taebp: results in %s\n", out_dir.c_str());
  // The files hold every policy up to and including the stalled one; the
  // stall's message is the last line on stderr (a sweep records it).
  if (!result.stopped.reason.empty()) {
    std::string not_run;
    for (const std::string& p : result.stopped.not_run) not_run += (not_run.empty() ? "" : ", ") + p;
    std::fprintf(stderr, "taebp: the run stopped at the stall%s%s; results so far in %s\n",
                 not_run.empty() ? "" : ", not run: ", not_run.c_str(), out_dir.c_str());
    throw taebp::StallError(result.stopped.message);
  }
  return 0;
}

// Runs `body`, turning an error into its message on stderr and the exit code
// the README documents (base/exit_codes.h; runner/errors.h classifies).
template <typename F>
int ReportErrors(F&& body) {
  try {
    return body();
  } catch (...) {
    const taebp::ErrorReport r = taebp::ReportOf(std::current_exception());
    std::cerr << r.line << "\n";
    return r.exit_code;
  }
}

// Parses the command line. Exit codes as the README documents: --help and
// --version 0, any argument error 2 (CLI11's own codes are 100+), with the
// name of an unknown subcommand (CLI11 only says one is required).
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv) {
  if (argc > 1 && argv[1][0] != '-') {
    const std::string name = argv[1];
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands({})) {
      known += (known.empty() ? "" : ", ") + sub->get_name();
      found = found || sub->check_name(name);
    }
    if (!found) {
      std::cerr << "taebp: unknown subcommand '" << name << "' (one of: " << known
                << ")\nRun with --help for more information.\n";
      return kExitConfig;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints --help, --version or the error
    return code == 0 ? 0 : kExitConfig;
  }
  return std::nullopt;
}

// `taebp metrics`: the metric table of report/metrics.h, as the README's
// generated table, CHANGELOG.md's renames or JSON (python's taebp.metrics()).
int PrintMetrics(const std::string& what) {
  if (what == "markdown") std::cout << taebp::MetricsMarkdown() << "\n" << taebp::SampleColumnsMarkdown();
  else if (what == "renames") std::cout << taebp::RenamesMarkdown();
  else if (what == "paired") std::cout << taebp::PairedColumnsMarkdown();
  else std::cout << taebp::MetricsJson() << "\n";
  return 0;
}

// `taebp policies`: the policy table of config/policies.h, as docs/policies.md's
// table, the README's list or JSON (python's taebp.policies(), tools/plot).
int PrintPolicies(const std::string& what) {
  if (what == "markdown") std::cout << taebp::PoliciesMarkdown();
  else if (what == "list") std::cout << taebp::PolicyListMarkdown();
  else std::cout << taebp::PoliciesJson() << "\n";
  return 0;
}

// `taebp theory`: its options into `th`.
CLI::App* AddTheory(CLI::App& app, TheoryOptions& th) {
  CLI::App* theory = app.add_subcommand(
      "theory", "The TA-EBP design and predicted outcomes for the AV-HV game (paper Sec. IV)");
  theory->add_option("--prior", th.prior, "prior probability lambda = p0(Go) that the AV goes, in (0, 1)")
      ->capture_default_str();
  theory->add_option("--penalty", th.penalty, "collision penalty r > 0 (HV utility -r for DR when the AV goes)")
      ->capture_default_str();
  theory->add_option("--trust", th.trust, "the HV's true trust theta in [0, 1]")->capture_default_str();
  theory->add_option("--assumed-trust", th.assumed_trust,
                     "the trust theta_hat the AV designs for (default: --trust; " +
                         std::string(taebp::PolicyOf(taebp::PolicyKind::kNoTrust).name) +
                         " uses 1)");
  theory->add_option("--s-max", th.s_max, "largest nudge s_max (m) of the likelihood model")
      ->capture_default_str();
  theory->add_option("--likelihood", th.likelihood, "HV likelihood model: linear or logistic")
      ->capture_default_str();
  theory->add_option("--steepness", th.steepness, "logistic model: steepness k > 0")->capture_default_str();
  theory->add_option("--midpoint", th.midpoint, "logistic model: midpoint m in [0, s_max]")->capture_default_str();
  theory->add_option("--noise", th.noise,
                     "perception noise on the HV's reading: none, gaussian or uniform")
      ->capture_default_str();
  theory->add_option("--noise-scale", th.noise_scale,
                     "noise scale (m): Gaussian sigma or uniform half-width")
      ->capture_default_str();
  theory->add_option("--noise-bias", th.noise_bias, "bias added to every reading (m)")
      ->capture_default_str();
  theory->add_option("--noise-delta", th.noise_delta,
                     "the noise-aware design's failure budget delta in (0, 1)")
      ->capture_default_str();
  theory->add_flag("--json", th.json, "print one JSON object instead of a table");
  return theory;
}

// `taebp solve PROBLEM [--json]`.
struct SolveArgs {
  std::string problem;
  bool json = false;
};

CLI::App* AddSolve(CLI::App& app, SolveArgs& a) {
  CLI::App* solve = app.add_subcommand(
      "solve", "Optimal trust-aware signaling scheme for a finite game (linear program, GLPK)");
  solve->add_option("PROBLEM", a.problem,
                    "YAML file with states, actions, prior, receiver_utility, sender_utility, trust")
      ->required();
  solve->add_flag("--json", a.json, "print one JSON object (status, sender_value, scheme, posteriors)");
  return solve;
}

// `taebp run CONFIG`'s arguments.
struct RunArgs {
  std::string config_path, out_dir;
  std::vector<std::string> overrides;
  bool quiet = false;
  bool paired = false;
  std::string rss_log;
};

CLI::App* AddRun(CLI::App& app, RunArgs& a) {
  CLI::App* run = app.add_subcommand(
      "run", "Run every listed policy of an experiment config in SUMO and write the results "
             "(policies: " + taebp::PolicyChoices() + "; `taebp policies` says what each does)");
  run->add_option("CONFIG", a.config_path, "experiment YAML (e.g. configs/paper.yaml)")->required();
  run->add_option("--set", a.overrides,
                  "override a config key, KEY=VALUE with VALUE read as YAML (repeatable), "
                  "e.g. --set scenario.duration=600 --set policies=[" +
                      std::string(taebp::PolicyOf(taebp::PolicyKind::kTaEbp).name) + "]");
  run->add_option("--out", a.out_dir, "output directory (default: results/<config name>)");
  run->add_flag("--quiet", a.quiet, "no progress on stderr");
  run->add_flag("--paired", a.paired,
                "paired games: play each game from the state it formed in under every game policy "
                "of the config (scenario.paired; paired.csv, docs/paired.md)");
  run->add_option("--rss-log", a.rss_log,
                  "append 'policy,simulated_seconds,rss_kb' every simulated minute (tools/soak)")
      ->group("");  // hidden: for tools/soak and benchmarks
  return run;
}

// `taebp metrics --print WHAT`.
CLI::App* AddMetrics(CLI::App& app, std::string& metrics_what) {
  CLI::App* metrics = app.add_subcommand(
      "metrics", "The result metrics: names, units, meaning and how sweeps pool them");
  metrics->add_option("--print", metrics_what,
                      "markdown: the manual's table (docs/metrics.md); renames: CHANGELOG.md's list; json: the "
                      "table as data; paired: paired.csv's columns (docs/paired.md)")
      ->check(CLI::IsMember({"markdown", "renames", "json", "paired"}))
      ->capture_default_str();
  return metrics;
}

// `taebp policies --print WHAT`.
CLI::App* AddPolicies(CLI::App& app, std::string& policies_what) {
  CLI::App* policies = app.add_subcommand(
      "policies", "The policies: names, labels, whether they play the game and the config keys "
                  "they do not read");
  policies->add_option("--print", policies_what,
                       "list: one line each (the README's list); markdown: docs/policies.md's "
                       "table; json: the table as data")
      ->check(CLI::IsMember({"list", "markdown", "json"}))
      ->capture_default_str();
  return policies;
}

// `taebp run`: the experiment, with --gui, --rss-log and --paired applied.
int RunCommand(RunArgs& a, taebp::gui::RunGui& run_gui) {
  taebp::RunOptions options = run_gui.Prepare();
  if (!a.rss_log.empty()) {
    const std::string& rss_log = a.rss_log;
    std::ofstream(rss_log, std::ios::trunc) << "policy,simulated_seconds,rss_kb\n";
    options.every_minute = [&rss_log](const std::string& policy, double t) {
      std::ifstream status("/proc/self/status");
      long kb = -1;
      for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) kb = std::atol(line.c_str() + 6);
      std::ofstream(rss_log, std::ios::app) << policy << ',' << t << ',' << kb << '\n';
    };
  }
  if (a.paired) a.overrides.push_back("scenario.paired=true");
  return RunExperimentCommand(a.config_path, a.overrides, a.out_dir, a.quiet, options);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"taebp: Trust-Aware Embodied Bayesian Persuasion in SUMO"};
  app.require_subcommand(1);
  app.set_version_flag("--version", taebp::TaebpVersion() + " (git " + taebp::BuildGitRevision() + ")");

  TheoryOptions th;
  CLI::App* theory = AddTheory(app, th);
  SolveArgs solve_args;
  CLI::App* solve = AddSolve(app, solve_args);
  RunArgs run_args;
  CLI::App* run = AddRun(app, run_args);
  taebp::gui::RunGui run_gui(run);           // run --gui [--delay MS]
  taebp::sweep::Commands sweep_commands(  // sweep, merge; a task = `run` in a forked worker
      app, [](const std::string& c, const std::vector<std::string>& o, const std::string& out) {
        return ReportErrors([&] { return RunExperimentCommand(c, o, out, true); });
      });
  taebp::gui::Snapshot snapshot(app);
  std::string metrics_what = "markdown";
  CLI::App* metrics = AddMetrics(app, metrics_what);
  std::string policies_what = "list";
  CLI::App* policies = AddPolicies(app, policies_what);

  taebp::cli::ConfigCommand config_command(app);  // config --reference

  if (const std::optional<int> code = ParseCommandLine(app, argc, argv)) return *code;
  const int code = ReportErrors([&] {
    if (*theory) return Theory(th);
    if (*solve) return Solve(solve_args.problem, solve_args.json);
    if (*run) return RunCommand(run_args, run_gui);
    if (*metrics) return PrintMetrics(metrics_what);
    if (*policies) return PrintPolicies(policies_what);
    if (config_command.Parsed()) return config_command.Run();
    if (snapshot.Parsed()) return snapshot.Run(argc, argv);
    if (sweep_commands.Parsed()) return sweep_commands.Run();
    return 0;
  });
  if (snapshot.Parsed()) taebp::gui::Snapshot::HandBack(code);
  return code;
}
