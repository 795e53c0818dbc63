"""taebp from Python: Trust-Aware Embodied Bayesian Persuasion in SUMO.

The same library as the ``taebp`` program, so the same inputs give the same
numbers and files:

    >>> import taebp
    >>> taebp.theory(prior_go=0.2, collision_penalty=3, trust=0.6)["s_star"]
    1.641025641025641
    >>> grid = taebp.theory(prior_go=np.linspace(0.05, 0.5, 46)[:, None],
    ...                     collision_penalty=np.linspace(0.5, 5, 46))  # a DataFrame
    >>> r = taebp.run("configs/paper.yaml", overrides={"scenario.duration": 600})
    >>> r.summary["policies"]["ta_ebp"]["dc_rate"]
    >>> print(r.table)                       # the Table I printout
    >>> df = r.encounters.to_pandas()        # needs python3-pandas
    >>> s = taebp.sweep({"scenario": {...}, "policies": ["ta_ebp"]}, out="results/mine",
    ...                 grid={"model.trust": [{"dist": "beta", "alpha": 12, "beta": 8}, 0.6]})
    >>> s.aggregate.to_pandas()              # model.trust, model.trust.dist/.mean/.sd, ...

Functions (arguments under the config's names; numbers give a dict, arrays or
lists a DataFrame, one row per point)
    theory(...)   the TA-EBP design and predicted outcomes (``taebp theory --json``)
    design(...)   the TA-EBP design for an assumed trust
    predict(...)  one policy's predicted DC / collision / nudge rates
    solve(problem)  the trust-aware LP for a finite game (``taebp solve --json``;
                  DataFrames in, DataFrames out)
    run(config, overrides=(), out=None, timeout=None)  every policy of a config
                  in SUMO (a path or a dict; overrides a dict or KEY=VALUE strings)
    sweep(config, overrides=(), out=None, jobs=None, quiet=True, shard=None,
          grid=None, replicates=None)  a study with the sweep engine
    load_run(dir), load_sweep(dir)  results already written (taebp.results)
    policies()    every policy a config may list
    stats.wilson(k, n, z)  the Wilson interval the outputs report (taebp.stats;
                  arrays broadcast)
    plot.sweep(...), plot.run(...)  the figures tools/plot draws (taebp.plot)
    dists         swept distributions: their mean, sd and label

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

import hashlib
import json
import os

from . import _taebp
from . import dists, plot, stats
from .results import (RunResult, SweepResult, Table, _flatten, _pandas, load_run, load_sweep,
                      set_metric_types, to_pandas)

__all__ = [
    "theory", "design", "predict", "solve", "run", "sweep", "load_run", "load_sweep",
    "Table", "RunResult", "SweepResult", "to_pandas", "encounter_columns", "metrics", "metric_sections",
    "ConfigError", "InvalidArgument", "OutputError", "SumoError", "BusyError", "StallError",
    "SweepError", "Interrupted", "EXIT_CODES", "stats", "dists", "plot", "policies",
    "policy_table", "shipped_config",
    "__version__",
]

__version__ = _taebp.version()
git_revision = _taebp.git_revision()

ConfigError = _taebp.ConfigError          # bad config, --set or problem (ValueError)
InvalidArgument = _taebp.InvalidArgument  # a parameter out of range (ValueError)
SumoError = _taebp.SumoError              # SUMO failed (RuntimeError)
BusyError = _taebp.SimulationBusy         # a second simulation in this process (RuntimeError)
OutputError = _taebp.OutputError          # an out= folder not usable, a sweep's, in use (OSError)
# A KeyboardInterrupt: Ctrl-C during run() (exit_code 130); SIGTERM or SIGHUP during
# run() or sweep() once Python's own handler for it has returned (143, 129: by
# default that handler ends the process instead). Ctrl-C in sweep() raises a plain
# KeyboardInterrupt.
Interrupted = _taebp.Interrupted
for _e in (ConfigError, InvalidArgument, OutputError, SumoError, BusyError, Interrupted):
    _e.__module__ = __name__
# Every exception's `exit_code`: the code `taebp` exits with for the same error
# (report/exit_codes.h, the README's "Exit codes").
EXIT_CODES = dict(_taebp.exit_codes())


class StallError(RuntimeError):
    """Traffic stalled under scenario.stall_action: error (``taebp run`` exits 4).

    The experiment stopped after the stalled policy; ``result`` is the
    RunResult of the policies that ran, that one included (written to ``out``
    when given), its stall in ``summary["policies"][policy]["stalls"]``."""

    exit_code = EXIT_CODES["StallError"]

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result


class SweepError(RuntimeError):
    """A sweep finished with failed (or, after an interrupt, missing) tasks.

    ``result`` is the SweepResult of the tasks that did finish, ``failed`` a
    list of (point, replicate, error) as recorded in the sweep's journal."""

    exit_code = EXIT_CODES["Error"]  # as `taebp sweep` with a failed task

    def __init__(self, message, result, failed):
        super().__init__(message)
        self.result = result
        self.failed = failed


# ------------------------------------------------------------------ theory
# The arguments' defaults: the C++ request's (runner/theory.h TheoryRequest),
# under the config's names (model.prior_go, model.collision_penalty, ...).
_DEFAULTS = dict(_taebp.theory_defaults())
# Old keyword names (taebp < 0.3), accepted with a DeprecationWarning.
_OLD_NAMES = {"prior": "prior_go", "penalty": "collision_penalty"}
# The C++ messages name the program's options; Python names the arguments.
_OPTION_NAMES = [("--trust theta", "trust"), ("--trust", "trust"), ("--prior", "prior_go"),
                 ("--penalty", "collision_penalty"), ("--assumed-trust", "assumed_trust"),
                 ("--s-max", "s_max"), ("prior lambda", "prior_go lambda"),
                 ("penalty r", "collision_penalty r")]
_NUMERIC = ("prior_go", "collision_penalty", "trust", "assumed_trust", "s_max", "steepness",
            "midpoint")


def _arguments(function, given, old):
    for name, value in old.items():
        if name not in _OLD_NAMES:
            raise TypeError("%s() got an unexpected keyword argument %r (arguments: %s)"
                            % (function, name, ", ".join(list(given))))
        import warnings
        warnings.warn("%s(%s=...) is deprecated: use %s=... (the config's name)"
                      % (function, name, _OLD_NAMES[name]), DeprecationWarning, stacklevel=3)
        given[_OLD_NAMES[name]] = value
    return given


def _is_many(v):
    return not isinstance(v, (str, bytes)) and (hasattr(v, "__len__") or hasattr(v, "shape")) \
        and getattr(v, "ndim", 1) != 0


def _points(args):
    """The arguments broadcast (numpy rules) to one dict per point, and
    whether any argument was an array or a list."""
    import numpy as np
    many = {k: v for k, v in args.items() if _is_many(v)}
    if not many:
        return [args], False
    shape = np.broadcast_shapes(*[np.shape(v) for v in many.values()])
    cols = {k: np.broadcast_to(np.asarray(v, dtype=object), shape).ravel()
            for k, v in many.items()}
    n = int(np.prod(shape)) if shape else 1
    return [{k: (cols[k][i] if k in cols else v) for k, v in args.items()} for i in range(n)], True


def _call(function, point, call):
    try:
        return call()
    except InvalidArgument as e:
        message = str(e)
        for option, name in _OPTION_NAMES:
            message = message.replace(option, name)
        shown = ", ".join("%s=%r" % (k, v) for k, v in point.items() if v is not None)
        raise InvalidArgument("%s(%s): %s" % (function, shown, message)) from None


def _number(function, point, name):
    """An argument as a float, or InvalidArgument naming it: a number (numpy's
    included), never a string or a bool (the config loader's rule)."""
    v = point[name]
    bad = isinstance(v, (str, bytes, bool)) or (hasattr(v, "dtype") and v.dtype.kind in "bUSO")
    if not bad:
        try:
            return float(v)
        except (TypeError, ValueError):
            bad = True
    shown = ", ".join("%s=%r" % (k, x) for k, x in point.items() if x is not None)
    raise InvalidArgument("%s(%s): %s must be a number, got %r%s" % (
        function, shown, name, v, " (a string: write the number itself)"
        if isinstance(v, (str, bytes)) else ""))


def _request(p, function="theory"):
    num = lambda name: _number(function, p, name)  # noqa: E731
    likelihood = p["likelihood"]
    if not isinstance(likelihood, str):
        raise InvalidArgument("%s(likelihood=%r): likelihood must be the name of a "
                              "likelihood (e.g. 'linear')" % (function, likelihood))
    assumed = p["assumed_trust"]
    if assumed is None or (isinstance(assumed, float) and assumed != assumed):
        assumed = None
    else:
        assumed = num("assumed_trust")
        assumed = None if assumed != assumed else assumed
    return (num("prior_go"), num("collision_penalty"), num("trust"), assumed, num("s_max"),
            likelihood, num("steepness"), num("midpoint"))


def _frame(points, rows):
    pd = _pandas()
    out = []
    for p, r in zip(points, rows):
        flat = {}
        _flatten("", r, flat)
        out.append(dict(p, **{k: v for k, v in flat.items() if k not in p}))
    return pd.DataFrame(out)


def theory(prior_go=_DEFAULTS["prior_go"], collision_penalty=_DEFAULTS["collision_penalty"],
           trust=_DEFAULTS["trust"], assumed_trust=None, s_max=_DEFAULTS["s_max"],
           likelihood=_DEFAULTS["likelihood"], steepness=_DEFAULTS["steepness"],
           midpoint=_DEFAULTS["midpoint"], **old):
    """The TA-EBP design and predicted outcomes: the object ``taebp theory --json`` prints.

    Arguments have the config's names (model.prior_go, model.collision_penalty,
    model.trust, model.assumed_trust, model.likelihood.{type, s_max,
    steepness, midpoint}); their defaults are the C++ request's
    (runner/theory.h). Numbers give a dict with keys prior_go,
    collision_penalty, trust, assumed_trust, likelihood, s_max, p_star,
    theta_star, persuadable, s_star, a, b, p_nudge, dc_rate, collision_rate
    (the TA-EBP design's), and policies.<no_ebp | no_trust | ta_ebp |
    full_reveal>.{dc_rate, collision_rate, nudge_rate}. Arrays or lists
    broadcast (numpy rules) and give a pandas DataFrame, one row per point,
    the inputs then those keys flattened (``policies.ta_ebp.dc_rate``):

        >>> taebp.theory(prior_go=np.linspace(0.05, 0.5, 46)[:, None],
        ...              collision_penalty=np.linspace(0.5, 5, 46)[None, :])

    ``assumed_trust`` is the trust the AV designs for (default: ``trust``).
    ``prior=`` and ``penalty=`` (the old names) still work, with a
    DeprecationWarning."""
    args = _arguments("theory", dict(prior_go=prior_go, collision_penalty=collision_penalty,
                                     trust=trust, assumed_trust=assumed_trust, s_max=s_max,
                                     likelihood=likelihood, steepness=steepness,
                                     midpoint=midpoint), old)
    points, many = _points(args)
    rows = [_call("theory", p, lambda r=_request(p): json.loads(_taebp.theory_json(*r)))
            for p in points]
    return _frame(points, rows) if many else rows[0]


def design(prior_go=_DEFAULTS["prior_go"], collision_penalty=_DEFAULTS["collision_penalty"],
           trust=_DEFAULTS["trust"], s_max=_DEFAULTS["s_max"], likelihood=_DEFAULTS["likelihood"],
           steepness=_DEFAULTS["steepness"], midpoint=_DEFAULTS["midpoint"], **old):
    """The TA-EBP design for an AV that assumes trust ``trust`` (paper Sec. IV-C).

    Returns persuadable, theta_star, p_star, s_star, a, b, p_nudge (a dict;
    a DataFrame, one row per point, when an argument is an array or list).
    Arguments as theory()."""
    args = _arguments("design", dict(prior_go=prior_go, collision_penalty=collision_penalty,
                                     trust=trust, assumed_trust=None, s_max=s_max,
                                     likelihood=likelihood, steepness=steepness,
                                     midpoint=midpoint), old)
    points, many = _points(args)
    rows = []
    for p in points:
        r = _request(p, "design")
        rows.append(_call("design", p, lambda r=r: dict(_taebp.design(*(r[:3] + r[4:])))))
    for p in points:
        p.pop("assumed_trust")
    return _frame(points, rows) if many else rows[0]


def predict(policy, prior_go=_DEFAULTS["prior_go"],
            collision_penalty=_DEFAULTS["collision_penalty"], trust=_DEFAULTS["trust"],
            assumed_trust=None, s_max=_DEFAULTS["s_max"], likelihood=_DEFAULTS["likelihood"],
            steepness=_DEFAULTS["steepness"], midpoint=_DEFAULTS["midpoint"], **old):
    """Predicted rates per AV-HV encounter of ``policy`` ({game_policies}:
    the game's policies; {no_game} plays none) for an HV of trust ``trust`` when the
    AV designs for ``assumed_trust`` (default ``trust``; no_trust designs
    for 1).

    Returns dc_rate, collision_rate, nudge_rate, av_first_rate (a dict; a
    DataFrame, one row per point, when an argument, ``policy`` included, is
    an array or list). Arguments as theory()."""
    args = _arguments("predict", dict(policy=policy, prior_go=prior_go,
                                      collision_penalty=collision_penalty, trust=trust,
                                      assumed_trust=assumed_trust, s_max=s_max,
                                      likelihood=likelihood, steepness=steepness,
                                      midpoint=midpoint), old)
    points, many = _points(args)
    rows = [_call("predict", p, lambda p=p, r=_request(p, "predict"):
                  dict(_taebp.predict(str(p["policy"]), *r)))
            for p in points]
    return _frame(points, rows) if many else rows[0]


def _plain(value):
    """Numpy arrays and scalars -> lists and numbers (for JSON)."""
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def _from_frames(problem):
    """A problem whose utilities are pandas DataFrames (index = states,
    columns = actions) and whose prior is a Series (or list) -> the plain
    dict the LP reads; True when a frame was given."""
    framed = False
    out = dict(problem)
    for key in ("receiver_utility", "sender_utility"):
        v = out.get(key)
        if hasattr(v, "iloc") and hasattr(v, "columns"):
            framed = True
            out.setdefault("states", [str(s) for s in v.index])
            out.setdefault("actions", [str(a) for a in v.columns])
            out[key] = v.to_numpy().tolist()
    p = out.get("prior")
    if hasattr(p, "iloc") and not hasattr(p, "columns"):
        framed = True
        out.setdefault("states", [str(s) for s in p.index])
        out["prior"] = p.to_numpy().tolist()
    return out, framed


def _to_frames(result):
    pd = _pandas()
    states, actions = result.get("states", []), result.get("actions", [])
    if result.get("scheme") is not None:
        result["scheme"] = pd.DataFrame(result["scheme"], index=pd.Index(states, name="state"),
                                        columns=pd.Index(actions, name="recommended"))
    if result.get("posteriors") is not None:
        rows = [r if r is not None else [float("nan")] * len(states) for r in result["posteriors"]]
        result["posteriors"] = pd.DataFrame(rows, index=pd.Index(actions, name="recommended"),
                                            columns=pd.Index(states, name="state"))
    if result.get("signal_probability") is not None:
        result["signal_probability"] = pd.Series(result["signal_probability"],
                                                 index=pd.Index(actions, name="recommended"))
    return result


def solve(problem, frames=None):
    """The optimal trust-aware scheme of a finite game: the object ``taebp solve --json`` prints.

    ``problem`` is a dict with states, actions, prior, receiver_utility,
    sender_utility (rows = states; lists, numpy arrays, or pandas DataFrames
    with the states as index and the actions as columns, which then also
    name states and actions; prior a list or a Series) and trust, or the
    path of a problem YAML file. Returns status, sender_value, states,
    actions, trust, scheme (rows = states), signal_probability, posteriors
    (one row per recommended action; None where an action is never
    recommended) and, when the LP is not optimal, message. With DataFrames
    in (or ``frames=True``) scheme is a DataFrame (states x recommended
    actions), posteriors one (recommended actions x states; NaN for an
    action never recommended) and signal_probability a Series. Raises
    ConfigError for a malformed problem."""
    framed = False
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
        plain, framed = _from_frames(problem)
        text = json.dumps(_plain(plain))
        origin = "problem"
    else:
        raise TypeError("solve(problem): a dict or the path of a problem YAML file, not %s"
                        % type(problem).__name__)
    out, _optimal = _taebp.solve_json(text, origin)
    result = json.loads(out)
    return _to_frames(result) if (frames if frames is not None else framed) else result


def encounter_columns(beyond=False, network=False, ssm=False):
    """The columns of encounters.csv, in order; ``network=True``: those of a
    network scenario (adds ``both_proceed_collides``, ``premise``,
    ``collision_after_handback``, ``encounter_kind``); ``beyond=True``: those
    of a run beyond the paper (dynamic / learned trust, noise,
    population_mean), which add columns after those; ``ssm=True``: those of a
    run with SUMO's SSM device (``ssm_min_ttc``, ``ssm_max_drac``,
    ``ssm_min_pet``: the game's pair measures), last."""
    return list(_taebp.encounter_columns(bool(beyond), bool(network), bool(ssm)))


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


def policy_table():
    """The policies, declared once in C++ (config/policies.h; ``taebp
    policies``): a list of dicts with name, label (as tables and plots print
    it), plays_game (False: SUMO's own logic), needs_avs, beyond_paper,
    by_default (listed when a config gives no ``policies``), ignores (the
    config keys, or sections, that cannot change the policy's run) and
    summary. The names are those a config's ``policies`` and results use:
    {all_policies}."""
    return json.loads(_taebp.policies_json())


def _policy_docstrings():
    """Fills the policy lists of the docstrings from the table."""
    rows = policy_table()
    names = {
        "{all_policies}": ", ".join(r["name"] for r in rows),
        "{game_policies}": ", ".join(r["name"] for r in rows if r["plays_game"]),
        "{no_game}": ", ".join(r["name"] for r in rows if not r["plays_game"]),
    }
    for f in (predict, policy_table):
        for key, text in names.items():
            f.__doc__ = f.__doc__.replace(key, text)


def metric_sections():
    """The structured parts of summary.json that are not metrics (scheme,
    hv_trust, stalls, junctions, ...): dicts with name, level (run, junction),
    scope, was and description."""
    return json.loads(_taebp.metrics_json())["sections"]


def _override_list(overrides):
    """Overrides as --set strings: a dict {key: value} (values as YAML: JSON
    of the Python value) or a list of 'KEY=VALUE' strings."""
    if isinstance(overrides, str):
        raise TypeError("overrides: a dict {'scenario.duration': 600} or a list of 'KEY=VALUE' "
                        "strings, e.g. ['scenario.duration=600'], not one string")
    if isinstance(overrides, dict):
        return ["%s=%s" % (k, json.dumps(_plain(v))) for k, v in overrides.items()]
    return [str(o) for o in overrides]


class _ConfigFile:
    """A config given as a dict, as a file while it is used: JSON (which is
    YAML) in the working directory, so that relative paths in it (networks,
    routes) are relative to the working directory; named by its content, so
    the same dict gives the same provenance; removed afterwards. The errors
    of the program name the file; for a dict they name "config dict" (the
    file is gone after the call), the key and the value."""

    def __init__(self, config):
        self.config = config
        self.path = None

    def __enter__(self):
        if isinstance(self.config, dict):
            text = json.dumps(_plain(self.config), indent=1, sort_keys=False) + "\n"
            name = ".taebp-config-%s.yaml" % hashlib.sha1(text.encode()).hexdigest()[:12]
            self.path = os.path.join(os.getcwd(), name)
            with open(self.path, "w", encoding="utf-8") as f:
                f.write(text)
            return self.path, "config"
        if isinstance(self.config, (str, os.PathLike)):
            path = os.fspath(self.config)
            return path, os.path.splitext(os.path.basename(path))[0]
        raise TypeError("config: a dict or the path of a config YAML file, not %s"
                        % type(self.config).__name__)

    def __exit__(self, kind, error, tb):
        if self.path:
            try:
                os.remove(self.path)
            except OSError:
                pass
            if error is not None and isinstance(error, (ConfigError, InvalidArgument)):
                message = _dict_message(str(error), self.path)
                if message != str(error):
                    raise type(error)(message).with_traceback(tb) from None
        return False


def _dict_message(message, path):
    """A message naming the temporary file of a dict config, naming the dict
    instead: "PATH:LINE:COL: scenario.avs ..." -> "config dict: scenario.avs ..."."""
    import re
    for shown in (path, os.path.basename(path)):
        message = re.sub(re.escape(shown) + r"(:\d+)*", "config dict", message)
    return message


def run(config, overrides=(), out=None, progress=False, timeout=None):
    """Runs every listed policy of the experiment config in SUMO (``taebp run``).

    ``config`` is the path of a config YAML file or the config as a dict
    ({"scenario": {...}, "model": {...}, "policies": [...]}; relative paths in
    it are relative to the working directory). The policies: {policies}.
    ``overrides`` are ``taebp run --set`` values, a dict
    {"scenario.duration": 600, "policies": ["ta_ebp"]} or a list of strings
    ["scenario.duration=600", "policies=[ta_ebp]"]. With ``out`` the result files are written there (as
    ``--out``; atomically); without, nothing is written. ``progress`` prints
    each policy's wall time on stderr. ``timeout``: seconds of wall time
    after which the run stops at its next simulation step and raises
    TimeoutError (nothing written, ``out`` as it was; None: no limit). The
    GIL is released while SUMO runs.
    Raises ConfigError, InvalidArgument, OutputError, SumoError or BusyError;
    StallError (with the result so far, written to ``out``) when a run stalled
    under scenario.stall_action: error; Interrupted on Ctrl-C. Each carries
    ``exit_code``, the code ``taebp run`` exits with for the same error."""
    overrides = _override_list(overrides)
    out = None if out is None else os.fspath(out)
    if timeout is not None:
        if isinstance(timeout, (bool, str)) or not float(timeout) > 0:
            raise ValueError("run(timeout=%r): seconds of wall time, a number > 0 (or None)"
                             % (timeout,))
        timeout = float(timeout)
    with _ConfigFile(config) as (path, _name):
        r = _taebp.run(path, overrides, out, bool(progress), timeout)
    result = RunResult(r["files"], table=r["table"], warnings=r["warnings"], out=out)
    if r["stopped"]:
        raise StallError(r["error"], result)
    return result


def sweep(config, overrides=(), out=None, jobs=None, quiet=True, shard=None, grid=None,
          replicates=None):
    """Runs a config's sweep with the sweep engine (``taebp sweep``).

    ``config`` and ``overrides`` as run() (a path or a dict; a dict or a
    list of 'KEY=VALUE'); ``grid`` the sweep's grid as a dict {key: [values]}
    (values may be maps, e.g. {"model.trust": [{"dist": "beta", "alpha": 12,
    "beta": 8}, 0.6]}; it replaces the config's sweep.grid) and
    ``replicates`` its seeds per point. ``quiet`` (default True) prints no
    progress line per task (``--quiet``); ``shard`` runs one part of the
    tasks, "I/N" (``--shard I/N``); ``jobs`` worker processes.

    Each task (grid point x seed replicate) runs in a forked worker process,
    up to ``jobs`` at once (default: the number of cores); finished tasks are
    journaled, so the same call resumes an interrupted sweep. ``out`` defaults
    to results/<config name> (relative to the working directory), ``shard``
    is ``--shard I/N``. Returns a SweepResult; raises SweepError (with the
    partial result) when a task failed, ConfigError for a bad config and
    KeyboardInterrupt after Ctrl-C."""
    overrides = _override_list(overrides)
    if grid is not None:
        overrides.append("sweep.grid=" + json.dumps(_plain(dict(grid))))
    if replicates is not None:
        overrides.append("sweep.replicates=%d" % int(replicates))
    if jobs is not None and (isinstance(jobs, bool) or not float(jobs).is_integer() or int(jobs) < 1):
        raise ValueError("sweep: jobs = %r: give a whole number >= 1 (None: the number of cores)"
                         % (jobs,))
    with _ConfigFile(config) as (path, name):
        if out is None:
            out = os.path.join("results", name)
        out = os.fspath(out)
        code = _taebp.sweep(path, overrides, out, 0 if jobs is None else int(jobs), bool(quiet),
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


def shipped_config(name):
    """The path of a config shipped with taebp (configs/NAME of the source
    tree this module was built from), so that a script runs from any folder:
    ``taebp.run(taebp.shipped_config("paper.yaml"))``. FileNotFoundError
    naming the configs there when there is none of that name."""
    folder = os.path.join(_taebp.source_dir(), "configs")
    path = os.path.join(folder, name)
    if not os.path.isfile(path):
        shipped = sorted(f for f in os.listdir(folder) if f.endswith(".yaml")) \
            if os.path.isdir(folder) else []
        raise FileNotFoundError("%s: no shipped config %r (in %s: %s)"
                                % (path, name, folder, ", ".join(shipped) or "none"))
    return path


def policies():
    """Every policy a config may list, in the program's order."""
    return list(_taebp.policy_names())


# The policy lists of the docstrings, from the one list.
run.__doc__ = run.__doc__.replace("{policies}", ", ".join(policies()))
set_metric_types(metrics())
_policy_docstrings()
