"""Reading the results the commands wrote: summary.json's policies, a
sweep's runs per seed, means with their t interval, paired differences,
an aggregate row's interval against its theory. `stats` is python/taebp's
(the one Wilson and clustered interval of the Python code)."""

import os
import sys

from .context import ROOT


def load_package():
    """python/taebp as the package `taebp` without its __init__ (which needs
    the compiled module): its pure-Python modules (stats: the one Wilson and clustered
    interval of the Python code; results, plot), as tools/plot loads them."""
    import types
    if "taebp" not in sys.modules or not hasattr(sys.modules["taebp"], "__path__"):
        pkg = types.ModuleType("taebp")
        pkg.__path__ = [os.path.join(ROOT, "python", "taebp")]
        sys.modules["taebp"] = pkg


load_package()
from taebp import stats  # noqa: E402


def summary(ctx, *rel):
    return ctx.json(*rel, "summary.json")["policies"]


# The policies of the efficiency and city tables, in order, and their names there.
EFF_POLICIES = ("sumo_native", "no_ebp", "no_trust", "ta_ebp", "full_reveal")
EFF_NAMES = {"sumo_native": "sumo_native", "no_ebp": "No EBP", "no_trust": "No Trust",
             "ta_ebp": "TA-EBP", "full_reveal": "Full reveal"}


def per_seed(ctx, folder, point_key):
    """{(point, policy): {replicate: results.csv row}} of a sweep's finished runs;
    point_key(row) names the point."""
    out = {}
    for r in ctx.csv("results", folder, "results.csv"):
        if r["status"] == "ok":
            out.setdefault((point_key(r), r["policy"]), {})[int(r["replicate"])] = r
    return out


def mean_ci(values, d):
    """'mean [lo, hi]': the mean over seeds and its 95 % Student t interval (stats.mean_interval)."""
    xs = [float(v) for v in values if v not in ("", None)]
    if not xs:
        return "–"
    m, lo, hi = stats.mean_interval(xs)
    def f(x):
        text = "%.*f" % (d, x)
        return text[1:] if text.startswith("-") and float(text) == 0 else text  # no "-0"
    return "%s [%s, %s]" % (f(m), f(lo), f(hi))


def paired(runs, a, b, col):
    """Per-seed differences a - b of one column, over the seeds both finished."""
    return [float(runs[a][k][col]) - float(runs[b][k][col]) for k in sorted(set(runs[a]) & set(runs[b]))
            if runs[a][k][col] != "" and runs[b][k][col] != ""]


def num(r, k):
    return float(r[k]) if r.get(k, "") != "" else None


def inside(r, metric):
    lo, hi, th = num(r, metric + "_lo"), num(r, metric + "_hi"), num(r, "theory_" + metric)
    return lo is not None and lo - 1e-12 <= th <= hi + 1e-12
