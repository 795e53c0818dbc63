"""Simulations from Python: run() (``taebp run``) and sweep() (``taebp
sweep``), a config given as a path or a dict, overrides as a dict or
KEY=VALUE strings."""

import hashlib
import json
import os

from . import _taebp
from .errors import ConfigError, InvalidArgument, StallError, SweepError
from .lp import _plain
from .results import RunResult, SweepResult


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
