"""A sweep as a long-form (tidy) table: one row per point x policy x metric,
with the swept keys' values (typed: numbers, or a distribution's label), the
metric's value, its interval, its theory and the stalled runs. Every plot
of the generic view (view.py) draws from it.

Intervals: a rate pooled over the seeds (aggregate.csv's METRIC_lo /
METRIC_hi: the interval of the pooled counts, clustered by HV and run (taebp.stats.pooled_rate's)
C++ twin); a mean over the seeds (METRIC_sd with runs_ok): the Student t
95 % interval of the mean (taebp.stats.student_t_quantile).
Derived here (not in the metric table): encounters_per_hour, the AV-HV
encounters of a point's runs over their measured hours (scenario.duration -
scenario.warmup, per run).
"""

import math

from .. import dists, stats
from .common import number

DERIVED = {"encounters_per_hour": "AV-HV encounters per measured hour (encounters / runs / "
                                  "(duration - warmup))"}


class Key:
    """A swept key: its values in the order they were swept, numeric (an
    axis of numbers) or not (categories, labelled by what they are)."""

    def __init__(self, name, cells):
        self.name = name
        self.cells = []
        for c in cells:
            if c not in self.cells:
                self.cells.append(c)
        parsed = []
        for c in self.cells:
            try:
                parsed.append(dists.value(c))
            except ValueError:
                parsed.append(c)
        self.numeric = bool(parsed) and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                            for v in parsed)
        if self.numeric:
            order = sorted(range(len(self.cells)), key=lambda i: parsed[i])
            self.cells = [self.cells[i] for i in order]
            parsed = [parsed[i] for i in order]
        self.values = parsed
        self.labels = [dists.label(c) for c in self.cells]

    def position(self, cell):
        """The x of a cell: its number, or its index among the categories."""
        i = self.cells.index(cell)
        return float(self.values[i]) if self.numeric else float(i)

    def label(self, cell):
        return self.labels[self.cells.index(cell)]


def metric_names(sweep):
    """aggregate.csv's metric columns (after runs_failed), without the
    interval and sd columns of another metric, plus the derived ones."""
    header = sweep.header
    start = header.index("runs_failed") + 1 if "runs_failed" in header else header.index("policy") + 1
    cols = header[start:]
    names = []
    for c in cols:
        base = None
        for suffix in ("_lo", "_hi", "_sd"):
            if c.endswith(suffix) and c[:-len(suffix)] in cols:
                base = c[:-len(suffix)]
        if base is None:
            names.append(c)
    if "encounters" in cols:
        names.append("encounters_per_hour")
    return names


def _measured_hours(sweep, row):
    def setting(key, default):
        if key in sweep.keys:
            v = number(row.get(key))
            return v if v is not None else default
        return sweep.scenario(key.split(".", 1)[1], default)
    duration = setting("scenario.duration", None)
    warmup = setting("scenario.warmup", 0.0) or 0.0
    if duration is None:
        return None
    return max(0.0, float(duration) - float(warmup)) / 3600.0


def value_of(sweep, row, metric):
    """(value, low, high, theory) of one aggregate row's metric; None where
    the row has none (an empty rate: no game, e.g. sumo_native)."""
    if metric == "encounters_per_hour":
        enc, runs = number(row.get("encounters")), number(row.get("runs_ok"))
        hours = _measured_hours(sweep, row)
        if enc is None or not runs or not hours:
            return None, None, None, None
        return enc / runs / hours, None, None, None
    y = number(row.get(metric))
    lo, hi = number(row.get(metric + "_lo")), number(row.get(metric + "_hi"))
    if y is not None and lo is None and (metric + "_sd") in row:
        sd, n = number(row.get(metric + "_sd")), number(row.get("runs_ok"))
        if sd is not None and n and n > 1:
            half = stats.student_t_quantile(int(n) - 1) * sd / math.sqrt(n)
            lo, hi = y - half, y + half
    theory = number(row.get("theory_" + metric)) if y is not None else None
    return y, lo, hi, theory


def long_table(sweep, metrics=None):
    """[{point, policy, KEY: cell..., metric, value, low, high, theory,
    stalled, runs}] for every aggregate row and metric with a value."""
    metrics = metrics or metric_names(sweep)
    out = []
    for r in sweep.rows:
        stalled, runs = number(r.get("stalled")), number(r.get("runs_ok"))
        for m in metrics:
            y, lo, hi, th = value_of(sweep, r, m)
            if y is None:
                continue
            row = {"point": int(r["point"]), "policy": r["policy"], "metric": m, "value": y,
                   "low": lo, "high": hi, "theory": th,
                   "stalled": int(stalled) if stalled else 0, "runs": int(runs) if runs else 0}
            for k in sweep.keys:
                row[k] = r.get(k)
            out.append(row)
    return out


def to_pandas(sweep, metrics=None):
    """The long table as a pandas DataFrame."""
    import pandas as pd
    return pd.DataFrame(long_table(sweep, metrics))
