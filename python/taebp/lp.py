"""The trust-aware LP of a finite game from Python: solve() (``taebp solve
--json``), problems and results as plain dicts or pandas DataFrames."""

import json
import os

from . import _taebp
from .errors import ConfigError
from .results import _pandas


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
