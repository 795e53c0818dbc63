// taebp._taebp: the C++ side of `import taebp` (python/taebp/__init__.py is
// the public API). Thin bindings over the same library calls as the taebp
// program: the theory and the LP as JSON (runner/theory.h), one experiment
// (runner/runner.h) and the sweep engine (sweep/engine.h), so Python and the
// command line give the same numbers and files for the same inputs.
#include "taebp/runner/errors.h"
#include "taebp/config/config.h"
#include "taebp/controller/network_controller.h"
#include "taebp/controller/sumo_adapter.h"
#include "taebp/base/number_text.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/persuasion.h"
#include "taebp/report/metrics.h"
#include "taebp/report/report.h"
#include "taebp/runner/runner.h"
#include "taebp/runner/theory.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/sweep/engine.h"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <optional>
#include <thread>

#include <pthread.h>
#include <string>
#include <vector>

namespace py = pybind11;

namespace {

// run(..., timeout=): a thread that, once `seconds` of wall time have passed,
// delivers SIGINT to the thread running the experiment; the InterruptGuard
// notes it, and the run stops at its next simulation step as after Ctrl-C
// (nothing written, the folder as it was). Declared after the guard, so it
// is stopped and joined before the guard gives the signals back to Python.
class Watchdog {
 public:
  explicit Watchdog(std::optional<double> seconds) {
    if (!seconds) return;
    const pthread_t target = pthread_self();
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(*seconds));
    thread_ = std::thread([this, target, deadline] {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!cv_.wait_until(lock, deadline, [this] { return stop_; })) {
        fired_ = true;
        pthread_kill(target, SIGINT);
      }
    });
  }
  ~Watchdog() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;
  bool fired() const { return fired_; }

 private:
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::atomic<bool> fired_{false};
};

taebp::TheoryRequest Request(double prior, double penalty, double trust,
                             std::optional<double> assumed_trust, double s_max,
                             const std::string& likelihood, double steepness, double midpoint) {
  taebp::TheoryRequest r;
  r.prior = prior;
  r.penalty = penalty;
  r.trust = trust;
  r.assumed_trust = assumed_trust;
  r.s_max = s_max;
  r.likelihood = likelihood;
  r.steepness = steepness;
  r.midpoint = midpoint;
  return r;
}

// The theory's defaults under the config's names (model.prior_go, ...): a
// default TheoryRequest's fields, so taebp.theory() retypes none of them.
py::dict TheoryDefaults() {
  const taebp::TheoryRequest r;
  py::dict d;
  d["prior_go"] = r.prior;
  d["collision_penalty"] = r.penalty;
  d["trust"] = r.trust;
  d["s_max"] = r.s_max;
  d["likelihood"] = r.likelihood;
  d["steepness"] = r.steepness;
  d["midpoint"] = r.midpoint;
  return d;
}

// Every policy a config may list, in the table's order (config/policies.h).
std::vector<std::string> PolicyNames() {
  std::vector<std::string> names;
  for (const taebp::PolicyInfo& p : taebp::Policies()) names.emplace_back(p.name);
  return names;
}

// A sweep task in a forked worker: `taebp run CONFIG --set ... --out DIR
// --quiet` as the program's sweep runs it, with the same messages on stderr
// (the engine records a failed task's last stderr line) and exit codes.
int RunTask(const std::string& config, const std::vector<std::string>& overrides,
            const std::string& out) {
  try {
    const taebp::ExperimentResult result = taebp::RunExperiment(config, overrides);
    taebp::WriteExperiment(result, out);
    if (!result.stopped.reason.empty())  // stall_action: error; what ran is written
      throw taebp::StallError(result.stopped.message);
    return taebp::kExitOk;
  } catch (...) {  // the CLI's lines and codes (runner/errors.h)
    const taebp::ErrorReport r = taebp::ReportOf(std::current_exception());
    std::fprintf(stderr, "%s\n", r.line.c_str());
    return r.exit_code;
  }
}

// predict()'s `policy`: a game policy of the table; another name is an
// InvalidArgument (a function argument, not a config), with the table's message.
taebp::persuasion::Policy GamePolicyArgument(const std::string& name) {
  try {
    return taebp::ParseGamePolicy(name);
  } catch (const taebp::ConfigError& e) {
    throw taebp::persuasion::InvalidArgument(e.what());
  }
}

// A run or sweep stopped by `signal` (its guard gone, Python's handlers
// back): the signal goes on to Python's handler (SIGTERM's default ends the
// process as it would have without taebp; a handler of the user's runs);
// Ctrl-C raises taebp.Interrupted (a KeyboardInterrupt) with `message`.
[[noreturn]] void RaiseInterrupted(int signal, const std::string& message) {
  if (signal != SIGINT) {
    ::raise(signal);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  // taebp.Interrupted, a KeyboardInterrupt carrying the CLI's exit code.
  const py::object type = py::module_::import("taebp._taebp").attr("Interrupted");
  py::object error = type(message);
  error.attr("exit_code") = taebp::kExitSignalBase + signal;
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

}  // namespace

namespace {

// The run's result for Python: the result files (name -> text, the time
// series read from disk), the printed table, the warnings, a stall's stop
// and what the run replaced in its folder.
py::dict RunResultDict(const taebp::ExperimentResult& result, const std::string& replaced) {
  py::dict files;
  for (const auto& [name, text] : result.Files()) files[py::str(name)] = py::str(text);
  for (const auto& [name, path] : result.sample_files) {  // the time series, on disk
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in.good() && !in.eof())
      throw std::runtime_error("cannot read " + path + " (" + name + ")");
    files[py::str(name)] = py::str(text.str());
  }
  py::dict r;
  r["files"] = files;
  r["table"] = result.Table();
  r["warnings"] = result.warnings;
  // A stall under stall_action: error: the files hold what ran;
  // taebp.run raises StallError with them (the program exits 4).
  r["stopped"] = result.stopped.reason;
  r["error"] = result.stopped.message;
  r["replaced"] = replaced;
  return r;
}

// taebp.run (BindRun): the GIL released while SUMO runs.
py::dict RunForPython(const std::string& config, const std::vector<std::string>& overrides,
                      std::optional<std::string> out, bool progress, std::optional<double> timeout) {
  taebp::ExperimentResult result;
  // Checked, not a sweep's, locked before the run (as `taebp run --out`).
  std::optional<taebp::RunFolder> folder;
  if (out) folder.emplace(*out, "out=");
  std::string replaced;
  int interrupted = 0;
  bool timed_out = false;
  std::string interrupted_message;
  try {
    py::gil_scoped_release release;
    // Ctrl-C, SIGTERM, SIGHUP: noted, the run stops at its next step
    // with the folder as it was; Python's handlers back afterwards.
    const taebp::InterruptGuard interrupts;
    std::optional<Watchdog> watchdog;
    watchdog.emplace(timeout);
    taebp::ExperimentObserver observer;
    if (progress) {
      observer.policy_done = [](const taebp::PolicyRun& run, double wall) {
        std::fprintf(stderr, "taebp: %-12s %.0f simulated s in %.2f s wall, %zu encounters\n",
                     run.policy.c_str(), run.simulated_seconds, wall,
                     run.encounters.size());
      };
    }
    try {
      result = taebp::RunExperiment(config, overrides, {}, observer);
      if (folder) replaced = taebp::WriteExperiment(result, *folder);
    } catch (const taebp::Interrupted&) {
      timed_out = watchdog->fired();
      throw;
    }
  } catch (const taebp::Interrupted& e) {
    interrupted = e.signal();
    interrupted_message = e.what();
  }
  if (timed_out) {
    folder.reset();  // unlocked, as it was
    PyErr_SetString(PyExc_TimeoutError,
                    ("taebp.run(timeout=" + taebp::NumberText(*timeout, 6) +
                     "): stopped after " + taebp::NumberText(*timeout, 6) +
                     " s of wall time at its next simulation step; nothing written" +
                     (out ? ", " + *out + " as it was" : std::string()))
                        .c_str());
    throw py::error_already_set();
  }
  if (interrupted) {
    folder.reset();  // unlocked, as it was
    RaiseInterrupted(interrupted, "taebp.run " + interrupted_message);
  }
  return RunResultDict(result, replaced);
}

// The library's errors as Python exceptions, and the exit codes by kind.
void BindErrors(py::module_& m) {
  // Python exceptions for the library's errors (same messages), each with the
  // CLI's exit code as `exit_code` (base/exit_codes.h; runner/errors.h).
  using taebp::ErrorKind;
  auto code = [](ErrorKind k) { return taebp::ErrorKindOf(k).exit_code; };
  auto name = [](ErrorKind k) { return taebp::ErrorKindOf(k).python_name; };
  static py::exception<taebp::ConfigError> config_error(m, name(ErrorKind::kConfig),
                                                        PyExc_ValueError);
  static py::exception<taebp::persuasion::InvalidArgument> invalid(
      m, name(ErrorKind::kInvalidArgument), PyExc_ValueError);
  static py::exception<taebp::SumoError> sumo_error(m, name(ErrorKind::kSumo), PyExc_RuntimeError);
  static py::exception<taebp::SimulationBusy> busy(m, name(ErrorKind::kBusy), PyExc_RuntimeError);
  static py::exception<taebp::OutputError> output_error(m, name(ErrorKind::kOutput), PyExc_OSError);
  // Ctrl-C during a run: a KeyboardInterrupt, exit_code 128 + the signal.
  static py::exception<taebp::Interrupted> interrupted(m, name(ErrorKind::kInterrupted),
                                                       PyExc_KeyboardInterrupt);
  config_error.attr("exit_code") = code(ErrorKind::kConfig);
  invalid.attr("exit_code") = code(ErrorKind::kInvalidArgument);
  sumo_error.attr("exit_code") = code(ErrorKind::kSumo);
  busy.attr("exit_code") = code(ErrorKind::kBusy);
  output_error.attr("exit_code") = code(ErrorKind::kOutput);
  interrupted.attr("exit_code") = code(ErrorKind::kInterrupted);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const taebp::ConfigError& e) {
      config_error(e.what());
    } catch (const taebp::persuasion::InvalidArgument& e) {
      invalid(e.what());
    } catch (const taebp::SumoError& e) {
      sumo_error(e.what());
    } catch (const taebp::SimulationBusy& e) {
      busy(e.what());
    } catch (const taebp::OutputError& e) {
      output_error(e.what());
    } catch (const taebp::Interrupted& e) {
      py::object error = py::reinterpret_borrow<py::object>(interrupted.ptr())(e.what());
      error.attr("exit_code") = e.exit_code();
      PyErr_SetObject(interrupted.ptr(), error.ptr());
    }
  });
  // The exit codes by kind, for the exceptions defined in Python (StallError,
  // SweepError): {python_name: exit_code}.
  m.def("exit_codes", [] {
    py::dict d;
    for (const taebp::ErrorKindInfo& k : taebp::ErrorKinds()) d[k.python_name] = k.exit_code;
    return d;
  });
}

// The version, the git revision, and config.h's file check.
void BindVersion(py::module_& m) {
  m.def("version", [] { return taebp::TaebpVersion(); });
  m.def("git_revision", [] { return taebp::BuildGitRevision(); });
  // Why a path is not a regular file ("" when it is): config.h's NotAFile.
  m.def("not_a_file", [](const std::string& path) { return taebp::NotAFile(path); });
}

// The theory: the design, its predictions and the LP solver.
void BindTheory(py::module_& m) {
  m.def("theory_json",
        [](double prior, double penalty, double trust, std::optional<double> assumed_trust,
           double s_max, const std::string& likelihood, double steepness, double midpoint) {
          return taebp::TheoryJson(Request(prior, penalty, trust, assumed_trust, s_max,
                                           likelihood, steepness, midpoint))
              .dump();
        });

  m.def("design", [](double prior, double penalty, double trust, double s_max,
                     const std::string& likelihood, double steepness, double midpoint) {
    const taebp::persuasion::TaebpDesign d = taebp::Design(
        Request(prior, penalty, trust, std::nullopt, s_max, likelihood, steepness, midpoint));
    py::dict out;
    out["persuadable"] = d.persuadable;
    out["theta_star"] = d.theta_star;
    out["p_star"] = d.p_star;
    out["s_star"] = d.s_star;
    out["a"] = d.a;
    out["b"] = d.b;
    out["p_nudge"] = d.p_nudge;
    return out;
  });

  m.def("predict", [](const std::string& policy, double prior, double penalty, double trust,
                      std::optional<double> assumed_trust, double s_max,
                      const std::string& likelihood, double steepness, double midpoint) {
    const taebp::persuasion::PredictedOutcome o =
        taebp::Predict(GamePolicyArgument(policy),
                       Request(prior, penalty, trust, assumed_trust, s_max, likelihood,
                               steepness, midpoint));
    py::dict out;
    out["dc_rate"] = o.dc_rate;
    out["collision_rate"] = o.collision_rate;
    out["nudge_rate"] = o.nudge_rate;
    out["av_first_rate"] = o.av_first_rate;
    return out;
  });

  m.def("solve_json", [](const std::string& problem_text, const std::string& origin) {
    const taebp::SolveOutput out =
        taebp::SolveJson(taebp::ParseProblemConfig(problem_text, origin), origin);
    return py::make_tuple(out.json.dump(), out.optimal);
  });
}

// The tables notebooks read (metrics, policies, theory defaults, columns).
void BindTables(py::module_& m) {
  m.def("metrics_json", [] { return taebp::MetricsJson(); });
  m.def("policies_json", [] { return taebp::PoliciesJson(); });

  // Notebook-facing tables (taebp.theory's defaults, the policy list):
  // read here, never retyped in Python.
  m.def("theory_defaults", &TheoryDefaults);
  m.def("policy_names", &PolicyNames);

  m.def("source_dir", [] { return std::string(TAEBP_SOURCE_DIR); });
  m.def("encounter_columns",
        [](bool beyond, bool network, bool ssm) {
          return taebp::EncounterCsvColumns(beyond, network, ssm);
        },
        py::arg("beyond") = false, py::arg("network") = false, py::arg("ssm") = false);
}

// taebp.run.
void BindRun(py::module_& m) {
  // One experiment; the GIL is released while SUMO runs. Returns the result
  // files (name -> text), the printed table and the warnings.
  m.def("run", &RunForPython,
        py::arg("config"), py::arg("overrides"), py::arg("out"), py::arg("progress"),
        py::arg("timeout") = std::nullopt);
}

// taebp.sweep.
void BindSweep(py::module_& m) {
  // The sweep engine, tasks in forked workers; returns its exit code (0 ok,
  // 1 a task failed, 130 Ctrl-C). The GIL is released throughout and
  // this process's simulation slot held, so no run() starts meanwhile.
  m.def(
      "sweep",
      [](const std::string& config, const std::vector<std::string>& overrides,
         const std::string& out, int jobs, bool quiet, const std::string& shard) {
        taebp::sweep::SweepOptions o;
        o.config = config;
        o.overrides = overrides;
        o.out = out;
        o.jobs = jobs;
        o.quiet = quiet;
        o.shard = shard;
        int code = 0;
        {
          py::gil_scoped_release release;
          const taebp::SimulationSlot slot("sweep " + config);
          std::fflush(nullptr);
          code = taebp::sweep::RunSweep(o, RunTask);  // its InterruptGuard restores Python's
        }
        // SIGTERM, SIGHUP: on to Python's handler (as without taebp); Ctrl-C
        // is taebp.sweep's KeyboardInterrupt (code 130).
        if (code == 128 + SIGTERM || code == 128 + SIGHUP)
          RaiseInterrupted(code - 128, "taebp.sweep interrupted; the same call resumes it");
        return code;
      },
      py::arg("config"), py::arg("overrides"), py::arg("out"), py::arg("jobs"),
      py::arg("quiet"), py::arg("shard"));
}

}  // namespace

PYBIND11_MODULE(_taebp, m) {
  m.doc() = "taebp's C++ library; use the `taebp` package, not this module";
  BindErrors(m);
  BindVersion(m);
  BindTheory(m);
  BindTables(m);
  BindRun(m);
  BindSweep(m);
}
