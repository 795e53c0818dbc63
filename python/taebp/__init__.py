"""taebp from Python: Trust-Aware Embodied Bayesian Persuasion in SUMO.

The same library as the ``taebp`` program, so the same inputs give the same
numbers and files:

    >>> import taebp
    >>> taebp.theory(prior=0.2, penalty=3, trust=0.6)["s_star"]
    1.641025641025641
    >>> r = taebp.run("configs/paper.yaml", overrides=["scenario.duration=600"])
    >>> r.summary["policies"]["ta_ebp"]["dc_rate"]
    >>> print(r.table)                       # the Table I printout
    >>> df = r.encounters.to_pandas()        # needs python3-pandas
    >>> s = taebp.sweep("configs/sweep_trust.yaml", out="results/sweep_trust", jobs=2)
    >>> s.aggregate.to_pandas()

Functions
    theory(...)   the TA-EBP design and predicted outcomes (``taebp theory --json``)
    design(...)   the TA-EBP design for an assumed trust
    predict(...)  one policy's predicted DC / collision / nudge rates
    solve(problem)  the trust-aware LP for a finite game (``taebp solve --json``)
    run(config, overrides=(), out=None)  every policy of a config in SUMO
    sweep(config, overrides=(), out=None, jobs=None)  a study with the sweep engine
    load_run(dir), load_sweep(dir)  results already written
    stats.wilson(k, n, z)  the Wilson interval the outputs report (taebp.stats)

Errors are exceptions with the program's messages: ConfigError and
InvalidArgument (both ValueError), OutputError (OSError: an out= folder that
cannot be used, holds a sweep, or is in use), SumoError, BusyError (RuntimeError),
StallError (RuntimeError: a stall under scenario.stall_action: error, exit
code 4 of the program, with the result of what ran) and SweepError (a sweep
with failed tasks).

One simulation per process: libsumo keeps one simulation per process, and
run() releases the GIL while SUMO runs, so a second run() from another thread
of the same process raises BusyError rather than corrupting the first. Run
experiments in parallel with sweep(..., jobs=N) (forked workers) or with
multiprocessing (each worker process runs its own).
"""

import csv
import io
import json
import os
import re

from . import _taebp

__all__ = [
    "theory", "design", "predict", "solve", "run", "sweep", "load_run", "load_sweep",
    "Table", "RunResult", "SweepResult", "to_pandas", "encounter_columns", "metrics", "metric_sections",
    "ConfigError", "InvalidArgument", "OutputError", "SumoError", "BusyError", "StallError",
    "SweepError",
    "__version__",
]

__version__ = _taebp.version()
git_revision = _taebp.git_revision()

ConfigError = _taebp.ConfigError          # bad config, --set or problem (ValueError)
InvalidArgument = _taebp.InvalidArgument  # a parameter out of range (ValueError)
SumoError = _taebp.SumoError              # SUMO failed (RuntimeError)
BusyError = _taebp.SimulationBusy         # a second simulation in this process (RuntimeError)
OutputError = _taebp.OutputError          # an out= folder not usable, a sweep's, in use (OSError)
for _e in (ConfigError, InvalidArgument, OutputError, SumoError, BusyError):
    _e.__module__ = __name__


class StallError(RuntimeError):
    """Traffic stalled under scenario.stall_action: error (``taebp run`` exits 4).

    The experiment stopped after the stalled policy; ``result`` is the
    RunResult of the policies that ran, that one included (written to ``out``
    when given), its stall in ``summary["policies"][policy]["stalls"]``."""

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result


class SweepError(RuntimeError):
    """A sweep finished with failed (or, after an interrupt, missing) tasks.

    ``result`` is the SweepResult of the tasks that did finish, ``failed`` a
    list of (point, replicate, error) as recorded in the sweep's journal."""

    def __init__(self, message, result, failed):
        super().__init__(message)
        self.result = result
        self.failed = failed


# ------------------------------------------------------------------ theory
def theory(prior=0.2, penalty=3.0, trust=0.6, assumed_trust=None, s_max=2.0,
           likelihood="linear", steepness=4.0, midpoint=1.0):
    """The TA-EBP design and predicted outcomes: the object ``taebp theory --json`` prints.

    Keys: prior_go, collision_penalty, trust, assumed_trust, likelihood, s_max,
    p_star, theta_star, persuadable, s_star, a, b, p_nudge, dc_rate,
    collision_rate (the TA-EBP design's), and policies.<no_ebp | no_trust |
    ta_ebp | full_reveal>.{dc_rate, collision_rate, nudge_rate}.
    ``assumed_trust`` is the trust the AV designs for (default: ``trust``)."""
    return json.loads(_taebp.theory_json(
        float(prior), float(penalty), float(trust),
        None if assumed_trust is None else float(assumed_trust), float(s_max),
        str(likelihood), float(steepness), float(midpoint)))


def design(prior=0.2, penalty=3.0, trust=0.6, s_max=2.0, likelihood="linear",
           steepness=4.0, midpoint=1.0):
    """The TA-EBP design for an AV that assumes trust ``trust`` (paper Sec. IV-C).

    Returns persuadable, theta_star, p_star, s_star, a, b, p_nudge."""
    return _taebp.design(float(prior), float(penalty), float(trust), float(s_max),
                         str(likelihood), float(steepness), float(midpoint))


def predict(policy, prior=0.2, penalty=3.0, trust=0.6, assumed_trust=None, s_max=2.0,
            likelihood="linear", steepness=4.0, midpoint=1.0):
    """Predicted rates per AV-HV encounter of ``policy`` (no_ebp, no_trust, ta_ebp,
    full_reveal) for an HV of trust ``trust`` when the AV designs for
    ``assumed_trust`` (default ``trust``; no_trust designs for 1).

    Returns dc_rate, collision_rate, nudge_rate, av_first_rate."""
    return _taebp.predict(str(policy), float(prior), float(penalty), float(trust),
                          None if assumed_trust is None else float(assumed_trust),
                          float(s_max), str(likelihood), float(steepness), float(midpoint))


def _plain(value):
    """Numpy arrays and scalars -> lists and numbers (for JSON)."""
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def solve(problem):
    """The optimal trust-aware scheme of a finite game: the object ``taebp solve --json`` prints.

    ``problem`` is a dict with states, actions, prior, receiver_utility,
    sender_utility (rows = states; lists or numpy arrays) and trust, or the
    path of a problem YAML file. Returns status, sender_value, states, actions,
    trust, scheme (rows = states), signal_probability, posteriors (one row per
    recommended action; None where an action is never recommended) and, when
    the LP is not optimal, message. Raises ConfigError for a malformed problem."""
    if isinstance(problem, (str, os.PathLike)):
        path = os.fspath(problem)
        why = _taebp.not_a_file(path)  # a FIFO would block the read for good
        if why:
            raise ConfigError(path + ": " + why + " (a config file is expected)")
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except OSError:
            raise ConfigError(path + ": cannot open the file (does it exist?)") from None
        origin = path
    elif isinstance(problem, dict):
        text = json.dumps(_plain(problem))
        origin = "problem"
    else:
        raise TypeError("solve(problem): a dict or the path of a problem YAML file, not %s"
                        % type(problem).__name__)
    out, _optimal = _taebp.solve_json(text, origin)
    return json.loads(out)


# ------------------------------------------------------------------ tables
_INT = re.compile(r"^[+-]?\d+$")


def _convert(cells):
    """A column's cells with one type: int, float, bool, else str; '' -> None."""
    present = [c for c in cells if c != ""]
    if present and all(_INT.match(c) for c in present):
        return [int(c) if c != "" else None for c in cells]
    try:
        values = [float(c) if c != "" else None for c in cells]
        return values
    except ValueError:
        pass
    if present and all(c in ("true", "false") for c in present):
        return [(c == "true") if c != "" else None for c in cells]
    return [c if c != "" else None for c in cells]


class Table:
    """A CSV output as columns and typed rows (ints, floats, bools, strings;
    None for an empty cell). ``rows`` is a list of tuples in column order;
    iterating gives one dict per row; ``table[name]`` a column as a list."""

    def __init__(self, columns, rows, name=""):
        self.columns = list(columns)
        self.rows = rows
        self.name = name

    @classmethod
    def from_csv(cls, text, name=""):
        reader = csv.reader(io.StringIO(text))
        try:
            columns = next(reader)
        except StopIteration:
            return cls([], [], name)
        raw = list(reader)
        if not raw:
            return cls(columns, [], name)
        converted = [_convert([r[i] if i < len(r) else "" for r in raw])
                     for i in range(len(columns))]
        return cls(columns, list(zip(*converted)), name)

    def __len__(self):
        return len(self.rows)

    def __iter__(self):
        for r in self.rows:
            yield dict(zip(self.columns, r))

    def __getitem__(self, column):
        i = self.columns.index(column)
        return [r[i] for r in self.rows]

    def __repr__(self):
        return "<taebp.Table %s: %d rows x %d columns>" % (self.name or "", len(self.rows),
                                                           len(self.columns))

    def to_pandas(self):
        """A pandas.DataFrame of the table (needs python3-pandas)."""
        pd = _pandas()
        return _real_columns_float(pd.DataFrame.from_records(self.rows, columns=self.columns))


def _real_columns_float(frame):
    """The frame with every real metric's column (rates, their intervals,
    means) as float: an empty cell (an undefined value, e.g. sumo_native's
    collision_rate) is NaN even where no row has a value."""
    real = set()
    for m in metrics():
        if m["type"] == "real":
            real.update(m["columns"])
            real.update(m["aggregate_columns"])
    for c in frame.columns:
        if c in real:
            frame[c] = frame[c].astype(float)
    return frame


def _pandas():
    try:
        import pandas
    except ImportError:
        raise ImportError("pandas is not installed for this Python: install the Debian "
                          "package python3-pandas (tools/setup.sh does)") from None
    return pandas


def to_pandas(obj):
    """pandas DataFrames of a result: a Table -> one DataFrame; a RunResult ->
    {"encounters", "policies"}; a SweepResult -> {"results", "aggregate",
    "encounters"}."""
    if isinstance(obj, Table):
        return obj.to_pandas()
    if isinstance(obj, (RunResult, SweepResult)):
        return obj.to_pandas()
    raise TypeError("to_pandas: a taebp Table, RunResult or SweepResult, not %s"
                    % type(obj).__name__)


def encounter_columns(beyond=False, network=False):
    """The columns of encounters.csv, in order; ``network=True``: those of a
    network scenario (adds ``both_proceed_collides``, ``premise``,
    ``collision_after_handback``, ``encounter_kind``); ``beyond=True``: those
    of a run beyond the paper (dynamic / learned trust, noise,
    population_mean), which add columns after those."""
    return list(_taebp.encounter_columns(bool(beyond), bool(network)))


def metrics():
    """The result metrics, declared once in C++ (report/metrics.h; ``taebp
    metrics``): a list of dicts with name, type (count, real, flag), unit,
    levels (run, junction), scope (all, network, beyond), pool (how a sweep's
    aggregate.csv pools the seeds: sum, rate, weighted, prediction, mean, max,
    none), count / per (a rate's numerator / what it is per), was (its name
    before taebp 0.2), description, columns (in summary.json, results.csv and
    junctions.csv) and aggregate_columns (in aggregate.csv). A metric has the
    same name in summary.json's policies.<p>, RunResult.to_pandas()["policies"],
    SweepResult.results and SweepResult.aggregate."""
    return json.loads(_taebp.metrics_json())["metrics"]


def metric_sections():
    """The structured parts of summary.json that are not metrics (scheme,
    hv_trust, stalls, junctions, ...): dicts with name, level (run, junction),
    scope, was and description."""
    return json.loads(_taebp.metrics_json())["sections"]


def _flatten(prefix, value, out):
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(prefix + "." + k if prefix else k, v, out)
    else:
        out[prefix] = value


# ------------------------------------------------------------------ experiments
class RunResult:
    """What ``taebp run`` writes, as data.

    summary     summary.json as a dict (policies.<name>.{...}, provenance)
    encounters  encounters.csv as a Table (one row per AV-HV encounter)
    junctions   junctions.csv as a Table (one row per controlled junction and
                policy: crossings, waits, queues, encounters, rates)
    config      config.yaml: the resolved configuration (YAML text)
    table       the Table I printout of ``taebp run``
    warnings    the run's warnings (also in summary.json's provenance)
    files       every result file's exact text (name -> text)
    out         the directory written, or None
    timeseries  timeseries.csv as a Table (runs beyond the paper), else None
    hv_trust    hv_trust.csv as a Table (runs beyond the paper), else None"""

    def __init__(self, files, table=None, warnings=None, out=None):
        self.files = dict(files)
        self.summary = json.loads(self.files["summary.json"])
        self.encounters = Table.from_csv(self.files["encounters.csv"], "encounters.csv")
        self.junctions = Table.from_csv(self.files.get("junctions.csv", ""), "junctions.csv")
        self.timeseries = (Table.from_csv(self.files["timeseries.csv"], "timeseries.csv")
                           if "timeseries.csv" in self.files else None)
        self.hv_trust = (Table.from_csv(self.files["hv_trust.csv"], "hv_trust.csv")
                         if "hv_trust.csv" in self.files else None)
        self.config = self.files.get("config.yaml", "")
        self.warnings = list(warnings if warnings is not None
                             else self.summary.get("provenance", {}).get("warnings", []))
        self.table = table
        self.out = out

    @property
    def policies(self):
        return list(self.summary.get("policies", {}))

    def to_pandas(self):
        """{"encounters": one row per encounter, "junctions": one row per
        junction and policy, "policies": one row per policy with summary.json's
        metrics (the names of the metric table, e.g. theory_dc_rate;
        sections such as scheme flattened: scheme.nudge)}, plus "timeseries" and
        "hv_trust" for runs beyond the paper."""
        pd = _pandas()
        rows = []
        for name, metrics in self.summary.get("policies", {}).items():
            flat = {"policy": name}
            _flatten("", metrics, flat)
            rows.append(flat)
        out = {"encounters": self.encounters.to_pandas(),
               "junctions": self.junctions.to_pandas(),
               "policies": _real_columns_float(pd.DataFrame(rows))}
        for name in ("timeseries", "hv_trust"):
            if getattr(self, name) is not None:
                out[name] = getattr(self, name).to_pandas()
        return out

    def __repr__(self):
        return "<taebp.RunResult %s: %d encounters>" % (", ".join(self.policies),
                                                       len(self.encounters))


def _paths(config, overrides):
    if isinstance(overrides, str):
        raise TypeError("overrides: a list of 'KEY=VALUE' strings, e.g. "
                        "['scenario.duration=600'], not one string")
    return os.fspath(config), [str(o) for o in overrides]


def run(config, overrides=(), out=None, progress=False):
    """Runs every listed policy of the experiment config in SUMO (``taebp run``).

    ``overrides`` are ``taebp run --set`` values, e.g. ["scenario.duration=600",
    "policies=[ta_ebp]"]. With ``out`` the result files are written there (as
    ``--out``; atomically); without, nothing is written. ``progress`` prints
    each policy's wall time on stderr. The GIL is released while SUMO runs.
    Raises ConfigError, InvalidArgument, SumoError or BusyError; StallError
    (with the result so far, written to ``out``) when a run stalled under
    scenario.stall_action: error."""
    config, overrides = _paths(config, overrides)
    out = None if out is None else os.fspath(out)
    r = _taebp.run(config, overrides, out, bool(progress))
    result = RunResult(r["files"], table=r["table"], warnings=r["warnings"], out=out)
    if r["stopped"]:
        raise StallError(r["error"], result)
    return result


def load_run(out_dir):
    """The RunResult of a directory that ``taebp run --out`` (or run(out=...)) wrote."""
    files = {}
    for name in ("summary.json", "encounters.csv", "junctions.csv", "config.yaml",
                 "timing.json", "timeseries.csv", "hv_trust.csv"):
        path = os.path.join(out_dir, name)
        if os.path.isfile(path):
            with open(path, encoding="utf-8") as f:
                files[name] = f.read()
    if "summary.json" not in files or "encounters.csv" not in files:
        raise FileNotFoundError("%s: no summary.json / encounters.csv (is it the --out of "
                                "taebp run?)" % out_dir)
    return RunResult(files, out=out_dir)


class SweepResult:
    """A sweep's output directory, as data (tables read when first used).

    info        sweep.json (config, grid with typed values, provenance)
    results     results.csv: one row per (point, seed, policy)
    aggregate   aggregate.csv: one row per (point, policy), pooled over seeds
    encounters  encounters.csv: every encounter, with point, replicate, seed
                and the swept keys in front
    junctions   every finished task's junctions.csv (one row per junction and
                policy), with point, replicate, seed and the swept keys in front
    keys        the swept config keys (columns between point/seed and policy)
    out         the directory"""

    def __init__(self, out):
        self.out = out
        with open(os.path.join(out, "sweep.json"), encoding="utf-8") as f:
            self.info = json.load(f)
        self.keys = list(self.info.get("columns", []))
        self._tables = {}

    def _table(self, name):
        if name not in self._tables:
            with open(os.path.join(self.out, name), encoding="utf-8", newline="") as f:
                self._tables[name] = Table.from_csv(f.read(), name)
        return self._tables[name]

    @property
    def results(self):
        return self._table("results.csv")

    @property
    def aggregate(self):
        return self._table("aggregate.csv")

    @property
    def encounters(self):
        return self._table("encounters.csv")

    @property
    def junctions(self):
        if "junctions.csv" not in self._tables:
            front = ["point", "replicate", "seed"] + self.keys
            columns, rows, tasks = None, [], {}
            for r in self.results:  # the finished tasks, in task order
                if r.get("status") == "ok":
                    tasks.setdefault((r["point"], r["replicate"]), [r[c] for c in front])
            for (point, replicate), values in tasks.items():
                path = os.path.join(self.out, "tasks", "%d-%d" % (point, replicate),
                                    "junctions.csv")
                if not os.path.isfile(path):
                    continue
                with open(path, encoding="utf-8", newline="") as f:
                    t = Table.from_csv(f.read(), "junctions.csv")
                columns = columns or front + t.columns
                rows.extend(tuple(values) + row for row in t.rows)
            self._tables["junctions.csv"] = Table(columns or front, rows, "junctions")
        return self._tables["junctions.csv"]

    def run(self, point, replicate=0):
        """One task's RunResult (tasks/POINT-REPLICATE)."""
        return load_run(os.path.join(self.out, "tasks", "%d-%d" % (point, replicate)))

    def to_pandas(self):
        """{"results", "aggregate", "encounters", "junctions"} as pandas DataFrames."""
        return {name: getattr(self, name).to_pandas()
                for name in ("results", "aggregate", "encounters", "junctions")}

    def __repr__(self):
        return "<taebp.SweepResult %s: %s points x %s replicates>" % (
            self.out, self.info.get("points"), self.info.get("replicates"))


def load_sweep(out_dir):
    """The SweepResult of a directory a sweep wrote."""
    if not os.path.isfile(os.path.join(out_dir, "sweep.json")):
        raise FileNotFoundError("%s: no sweep.json (is it the --out of taebp sweep?)" % out_dir)
    return SweepResult(out_dir)


def sweep(config, overrides=(), out=None, jobs=None, quiet=True, shard=None):
    """Runs a config's sweep with the sweep engine (``taebp sweep``).

    Each task (grid point x seed replicate) runs in a forked worker process,
    up to ``jobs`` at once (default: the number of cores); finished tasks are
    journaled, so the same call resumes an interrupted sweep. ``out`` defaults
    to results/<config name> (relative to the working directory), ``shard``
    is ``--shard I/N``. Returns a SweepResult; raises SweepError (with the
    partial result) when a task failed, ConfigError for a bad config and
    KeyboardInterrupt after Ctrl-C."""
    config, overrides = _paths(config, overrides)
    if out is None:
        out = os.path.join("results", os.path.splitext(os.path.basename(config))[0])
    out = os.fspath(out)
    code = _taebp.sweep(config, overrides, out, 0 if jobs is None else int(jobs), bool(quiet),
                        "" if shard is None else str(shard))
    if code == 130:
        raise KeyboardInterrupt("taebp sweep interrupted; the same call resumes it")
    result = SweepResult(out)
    if code != 0:
        failed = []
        with open(os.path.join(out, "journal.jsonl"), encoding="utf-8") as f:
            latest = {}
            for line in f:
                try:
                    e = json.loads(line)
                except ValueError:
                    continue
                key = (e.get("point"), e.get("replicate"))
                if e.get("status") == "ok" or latest.get(key, {}).get("status") != "ok":
                    latest[key] = e
        for (p, r), e in sorted(latest.items()):
            if e.get("status") != "ok":
                failed.append((p, r, e.get("error", "")))
        detail = "; ".join("task %s-%s: %s" % f for f in failed[:3])
        raise SweepError("taebp sweep %s: %d task(s) failed%s (results of the others in %s)"
                         % (config, len(failed), (": " + detail) if detail else "", out),
                         result, failed)
    return result
