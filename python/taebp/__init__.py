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

import json
import os

from . import _taebp
from . import dists, plot, stats
from .analytic import design, predict, theory
from .errors import (EXIT_CODES, BusyError, ConfigError, Interrupted, InvalidArgument, OutputError,
                     StallError, SumoError, SweepError)
from .lp import solve
from .results import (RunResult, SweepResult, Table, load_run, load_sweep, set_metric_types,
                      to_pandas)
from .simulate import run, sweep

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

# The API's classes and functions, defined in the modules next to this one
# (errors, analytic, lp, simulate), are named taebp.X (help(), tracebacks).
for _e in (ConfigError, InvalidArgument, OutputError, SumoError, BusyError, Interrupted,
           StallError, SweepError, theory, design, predict, solve, run, sweep):
    _e.__module__ = __name__


# ------------------------------------------------------------------ the program's tables
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
