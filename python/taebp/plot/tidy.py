"""Results as long-form (tidy) data: what every figure draws from.

A sweep (Sweep: aggregate.csv, results.csv, sweep.json) gives one row per
point x policy x metric (long_table, to_pandas, SweepResult.tidy()): the
swept keys' values, the metric's value, its interval, its theory, the runs
behind it (finished, failed, stalled) and, from results.csv, each seed's
value. Runs (Runs: a run folder, a sweep's tasks or several run folders)
give per-time-bin rates, cumulative curves and the HVs' trust over time.

Intervals are never re-derived from counts here where the C++ tables hold
them: a rate's interval is aggregate.csv's METRIC_lo / METRIC_hi (as
summary.json's: clustered by HV within each run and by run, docs/metrics.md); a mean over seeds gets the Student t interval of
taebp.stats.mean_interval_of from METRIC_sd and runs_ok. Where only Python
counts (a time bin of encounters.csv), the interval is taebp.stats.encounter_rate's
(clustered by HV and run, as the C++ tables'): one function in one place.
"""

import csv
import json
import math
import os

from .. import dists, stats
from .common import die, number, warn
from . import style

__all__ = ["Sweep", "Key", "load", "long_table", "to_pandas", "metric_names", "value_of",
           "Runs", "binned_rates", "SEEDS_FOR_INTERVAL"]

# With fewer seeds than this a mean's t interval says little (with 2 seeds
# its quantile is 12.7): the seeds' own values are drawn instead.
SEEDS_FOR_INTERVAL = 5


# ------------------------------------------------------------------ a sweep
class Sweep:
    """A sweep folder (or an aggregate CSV file itself, e.g. a test fixture):
    aggregate.csv's rows (text cells), results.csv's rows when present (one
    per seed), sweep.json."""

    def __init__(self, where):
        if os.path.isfile(where):
            path, directory = where, os.path.dirname(where) or "."
        else:
            directory, path = where, os.path.join(where, "aggregate.csv")
        self.dir = directory
        if not os.path.isfile(path):
            die("%s: no aggregate.csv (is this the --out folder of `taebp sweep`?)" % directory, 2)
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            self.header = reader.fieldnames or []
            self.rows = list(reader)
        for need in ("point", "policy"):
            if need not in self.header:
                die("%s: column '%s' is missing" % (path, need), 2)
        a, b = self.header.index("point"), self.header.index("policy")
        self.keys = self.header[a + 1:b]
        self.info = {}
        info_path = os.path.join(directory, "sweep.json")
        if os.path.isfile(info_path):
            try:
                with open(info_path, encoding="utf-8") as f:
                    self.info = json.load(f)
            except (OSError, ValueError) as e:
                warn("%s unreadable (%s): plotting without its context" % (info_path, e))
        if not isinstance(self.info, dict):
            self.info = {}
        self.config = self.info.get("config", {}) or {}
        self.policies = []
        for r in self.rows:
            if r["policy"] not in self.policies:
                self.policies.append(r["policy"])
        self._seeds = None

    # -- the config behind it
    def model(self, key, default=None):
        return (self.config.get("model", {}) or {}).get(key, default)

    def scenario(self, key, default=None):
        return (self.config.get("scenario", {}) or {}).get(key, default)

    def setting(self, row, key, default=None):
        """A config key's value at a row's point: swept (the row's cell) or the config's."""
        if key in self.keys:
            v = number(row.get(key))
            return v if v is not None else default
        section, _, rest = key.partition(".")
        value = (self.config.get(section, {}) or {})
        for part in rest.split("."):
            value = value.get(part) if isinstance(value, dict) else None
        return default if value is None else value

    # -- the seeds
    def seed_rows(self):
        """results.csv's rows (one per point, seed and policy); [] without it."""
        if self._seeds is None:
            path = os.path.join(self.dir, "results.csv")
            self._seeds = []
            if os.path.isfile(path):
                with open(path, newline="", encoding="utf-8") as f:
                    self._seeds = list(csv.DictReader(f))
        return self._seeds

    def seeds(self, point, policy, metric):
        """A metric's value in each finished seed of (point, policy)."""
        out = []
        for r in self.seed_rows():
            if r.get("point") == str(point) and r.get("policy") == policy and \
                    r.get("status", "ok") == "ok":
                if metric == "served_share":
                    served, offered = number(r.get("served_flow")), number(r.get("offered_flow"))
                    v = served / offered if served is not None and offered else None
                else:
                    v = number(r.get(metric))
                if v is not None:
                    out.append(v)
        return out

    def measured_seconds(self, row):
        """The simulated time a point's runs measured (after the warm-up):
        results.csv's measured_seconds, else scenario.duration - warmup."""
        got = [number(r.get("measured_seconds")) for r in self.seed_rows()
               if r.get("point") == row.get("point") and r.get("policy") == row.get("policy")]
        got = [g for g in got if g is not None]
        if got:
            return sum(got) / len(got)
        duration = number(str(self.setting(row, "scenario.duration", "")))
        if duration is None:
            return None
        warmup = number(str(self.setting(row, "scenario.warmup", 0))) or 0.0
        return max(0.0, duration - warmup)

    def runs(self, row):
        """(finished, failed) runs of an aggregate row."""
        return int(number(row.get("runs_ok")) or 0), int(number(row.get("runs_failed")) or 0)

    def stalls(self):
        """{(point, policy): (stalled runs, runs)}."""
        out = {}
        for r in self.rows:
            k, n = number(r.get("stalled")), number(r.get("runs_ok"))
            if k is not None and n is not None:
                out[(int(r["point"]), r["policy"])] = (int(k), int(n))
        return out

    def failed(self):
        """[(point, policy, failed, runs)] of every row with a failed run."""
        out = []
        for r in self.rows:
            ok, bad = self.runs(r)
            if bad:
                out.append((int(r["point"]), r["policy"], bad, ok + bad))
        return out

    def context(self, keys=None):
        """One line: the fixed parameters and the sample behind each point
        (the measured time, not the configured one; seeds as finished)."""
        keys = self.keys if keys is None else keys
        parts = []
        lam, r = self.model("prior_go"), self.model("collision_penalty")
        if lam is not None and "model.prior_go" not in keys:
            parts.append("λ = %g" % lam)
        if r is not None and "model.collision_penalty" not in keys:
            parts.append("r = %g" % r)
        if "model.trust" not in keys and isinstance(self.model("trust"), (int, float)):
            parts.append("θ = %g" % self.model("trust"))
        measured = sorted({round(m) for m in (self.measured_seconds(row) for row in self.rows)
                           if m is not None})
        seeds = sorted({sum(self.runs(row)) for row in self.rows})
        sample = []
        if measured:
            hours = measured[0] >= 7200  # long runs in hours
            f = (lambda v: "%g" % (v / 3600.0)) if hours else (lambda v: "%g" % v)
            span = f(measured[0]) if len(measured) == 1 else "%s–%s" % (f(measured[0]),
                                                                      f(measured[-1]))
            sample.append("%s %s measured" % (span, "h" if hours else "s"))
        if seeds and seeds != [0]:
            n = seeds[0] if len(seeds) == 1 else "%d–%d" % (seeds[0], seeds[-1])
            sample.append("%s seed%s per point" % (n, "" if n == 1 else "s"))
        if sample:
            parts.append(" × ".join(sample))
        failed = self.failed()
        if failed:
            points = sorted({f[0] for f in failed})
            parts.append("failed runs at %d point%s (marked ✕)" % (len(points),
                                                                   "" if len(points) == 1 else "s"))
        return ", ".join(parts)


def load(source):
    """A Sweep from a Sweep, a taebp SweepResult, or a folder / aggregate CSV path."""
    if isinstance(source, Sweep):
        return source
    out = getattr(source, "out", None)
    if out is not None and hasattr(source, "aggregate"):
        return Sweep(out)
    if isinstance(source, (str, os.PathLike)):
        where = os.fspath(source)
        if not os.path.exists(where):
            die("%s: no such folder or file" % where, 2)
        return Sweep(where)
    raise TypeError("a sweep folder, an aggregate.csv path, a taebp.SweepResult or a "
                    "taebp.plot Sweep, not %s" % type(source).__name__)


class Key:
    """A swept key: its values in the order they were swept, numeric (an
    axis of numbers) or not (categories, labelled by what they are)."""

    def __init__(self, name, cells, label=None):
        self.name = name
        self.title = label or name
        self.cells = []
        for c in cells:
            if c not in self.cells:
                self.cells.append(c)
        parsed = []
        for c in self.cells:
            try:
                parsed.append(dists.value(c) if isinstance(c, str) else c)
            except ValueError:
                parsed.append(c)
        self.numeric = bool(parsed) and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                            for v in parsed)
        if self.numeric:
            order = sorted(range(len(self.cells)), key=lambda i: parsed[i])
            self.cells = [self.cells[i] for i in order]
            parsed = [parsed[i] for i in order]
        self.values = parsed
        self.labels = [dists.label(c) if isinstance(c, str) else "%g" % c for c in self.cells]

    def position(self, cell):
        """The x of a cell: its number, or its index among the categories."""
        i = self.cells.index(cell)
        return float(self.values[i]) if self.numeric else float(i)

    def label(self, cell):
        return self.labels[self.cells.index(cell)]


def metric_names(sweep):
    """aggregate.csv's metrics (its columns after runs_failed, without the
    _lo, _hi and _sd of another), encounters_per_hour included."""
    header = sweep.header
    start = header.index("runs_failed") + 1 if "runs_failed" in header else header.index("policy") + 1
    cols = header[start:]
    names = []
    for c in cols:
        if not any(c.endswith(s) and c[:-len(s)] in cols for s in ("_lo", "_hi", "_sd")):
            names.append(c)
    if "encounters" in cols and "encounters_per_hour" not in names:
        names.append("encounters_per_hour")  # an older aggregate.csv: derived below
    if "served_flow" in cols and "offered_flow" in cols:
        names.append("served_share")  # style.DERIVED
    return names


def value_of(sweep, row, metric):
    """(value, low, high, theory) of one aggregate row's metric; None where
    the row has none (a rate of a policy that plays no game, a failed point)."""
    if metric == "encounters_per_hour" and "encounters_per_hour" not in row:
        # aggregate.csv before the metric table had it: encounters per run
        # over the measured hours (none for a policy without a game).
        enc, runs = number(row.get("encounters")), number(row.get("runs_ok"))
        seconds = sweep.measured_seconds(row)
        if enc is None or not runs or not seconds or not style.plays_game(row["policy"]):
            return None, None, None, None
        return enc / runs / (seconds / 3600.0), None, None, None
    if metric == "served_share":
        # The seeds' own ratios where results.csv has them (their mean and t
        # interval), else the ratio of the means.
        ratios = sweep.seeds(row["point"], row["policy"], metric)
        if ratios:
            mean, lo, hi = stats.mean_interval(ratios)
            return mean, (lo if len(ratios) > 1 else None), (hi if len(ratios) > 1 else None), None
        served, offered = number(row.get("served_flow")), number(row.get("offered_flow"))
        if served is None or not offered:
            return None, None, None, None
        return served / offered, None, None, None
    y = number(row.get(metric))
    if y is None:
        return None, None, None, None
    lo, hi = number(row.get(metric + "_lo")), number(row.get(metric + "_hi"))
    if lo is None and (metric + "_sd") in row:
        lo, hi = stats.mean_interval_of(y, number(row.get(metric + "_sd")),
                                        number(row.get("runs_ok")))
    theory = number(row.get("theory_" + metric))
    return y, lo, hi, theory


def long_table(source, metrics=None):
    """[{point, KEY: cell..., policy, metric, value, lo, hi, theory, runs,
    failed, stalled}] for every aggregate row and metric with a value."""
    sweep = load(source)
    metrics = metrics or metric_names(sweep)
    out = []
    for r in sweep.rows:
        ok, bad = sweep.runs(r)
        stalled = number(r.get("stalled"))
        for m in metrics:
            y, lo, hi, th = value_of(sweep, r, m)
            if y is None:
                continue
            row = {"point": int(r["point"])}
            for k in sweep.keys:
                row[k] = r.get(k)
            row.update({"policy": r["policy"], "metric": m, "value": y, "lo": lo, "hi": hi,
                        "theory": th, "runs": ok, "failed": bad,
                        "stalled": int(stalled) if stalled else 0})
            out.append(row)
    return out


def to_pandas(source, metrics=None):
    """The long table as a pandas DataFrame (SweepResult.tidy()): swept keys
    as numbers where they are (a distribution as its text with KEY.dist,
    KEY.mean, KEY.sd beside it), value / lo / hi / theory float64, runs /
    failed / stalled int64."""
    import pandas as pd
    sweep = load(source)
    rows = long_table(sweep, metrics)
    columns = ["point"] + sweep.keys + ["policy", "metric", "value", "lo", "hi", "theory",
                                        "runs", "failed", "stalled"]
    frame = pd.DataFrame(rows, columns=columns)
    out = {}
    for c in frame.columns:
        col = frame[c]
        if c in ("value", "lo", "hi", "theory"):
            col = pd.to_numeric(col, errors="coerce").astype("float64")
        elif c in ("point", "runs", "failed", "stalled"):
            col = col.astype("int64")
        elif c in sweep.keys:
            numeric = pd.to_numeric(col, errors="coerce")
            if not numeric.isna().any():
                col = numeric.astype("int64") if (numeric == numeric.round()).all() and \
                    all("." not in str(v) and "e" not in str(v).lower() for v in col) \
                    else numeric.astype("float64")
        out[c] = col
        if c in sweep.keys:
            parsed = []
            for v in frame[c]:
                try:
                    parsed.append(dists.value(v) if isinstance(v, str) else v)
                except ValueError:
                    parsed.append(v)
            if any(dists.is_distribution(p) for p in parsed):
                described = [dists.describe(p) for p in parsed]
                out[c + ".dist"] = pd.Series([d[0] for d in described], index=frame.index,
                                             dtype="object")
                out[c + ".mean"] = pd.Series([d[1] for d in described], index=frame.index,
                                             dtype="float64")
                out[c + ".sd"] = pd.Series([d[2] for d in described], index=frame.index,
                                           dtype="float64")
    return pd.DataFrame(out, index=frame.index)


# ------------------------------------------------------------------ runs
class Runs:
    """Run folders with time series (runs beyond the paper): a run folder
    (`taebp run --out`), the tasks of a sweep folder, or several run folders.
    `groups()` pools only runs of the same config but their seed: a sweep's
    tasks by point, run folders by their config but scenario.seed."""

    def __init__(self, where):
        wheres = [where] if isinstance(where, (str, os.PathLike)) else list(where)
        self.dirs, self.points = [], []
        self.point_text = {}  # point -> "KEY = value, ..." of a sweep's point
        for w in wheres:
            w = os.fspath(w)
            if os.path.isfile(os.path.join(w, "summary.json")):
                self.dirs.append(w)
                self.points.append(None)
            elif os.path.isdir(os.path.join(w, "tasks")):
                tasks = os.path.join(w, "tasks")

                def order(name):
                    try:
                        return tuple(int(x) for x in name.split("-"))
                    except ValueError:
                        return (1 << 30, 0)
                for d in sorted(os.listdir(tasks), key=order):
                    full = os.path.join(tasks, d)
                    if d.startswith(".") or not os.path.isfile(os.path.join(full, "timeseries.csv")):
                        continue  # a staging folder, or a task without time series
                    self.dirs.append(full)
                    self.points.append(order(d)[0])
                self._point_values(w)
        self.summaries = []
        for d in self.dirs:
            with open(os.path.join(d, "summary.json"), encoding="utf-8") as f:
                self.summaries.append(json.load(f))
        self.policies = []
        for s in self.summaries:
            for p in s.get("policies", {}):
                if p not in self.policies:
                    self.policies.append(p)
        self._csv = {}

    def _point_values(self, sweep_dir):
        """The swept values of each point of a sweep (results.csv), as text."""
        path = os.path.join(sweep_dir, "results.csv")
        info = os.path.join(sweep_dir, "sweep.json")
        if not (os.path.isfile(path) and os.path.isfile(info)):
            return
        with open(info, encoding="utf-8") as f:
            keys = (json.load(f) or {}).get("columns", [])
        with open(path, newline="", encoding="utf-8") as f:
            for r in csv.DictReader(f):
                p = int(r["point"])
                if p not in self.point_text and keys:
                    self.point_text[p] = ", ".join(
                        "%s = %s" % (k, dists.label(r.get(k, ""))) for k in keys)

    def __bool__(self):
        return bool(self.dirs)

    def config(self, i=0):
        return self.summaries[i].get("provenance", {}).get("config", {}) if self.summaries else {}

    def groups(self):
        """[(name, [run indices])]: runs that may be pooled (the same config
        but the seed). A sweep's points are named "point P"; one group: ""."""
        keyed = {}
        for i, p in enumerate(self.points):
            if p is not None:
                key = ("point %d" % p,) if p not in self.point_text else \
                    ("point %d" % p, self.point_text[p])
            else:
                c = json.loads(json.dumps(self.config(i)))
                (c.get("scenario") or {}).pop("seed", None)
                c.pop("sweep", None)
                key = (json.dumps(c, sort_keys=True),)
            keyed.setdefault(key, []).append(i)
        groups = list(keyed.items())
        if len(groups) == 1:
            return [("", groups[0][1])]
        named = []
        for n, (key, idx) in enumerate(groups):
            named.append((key[0] if key[0].startswith("point") else "config %d" % (n + 1), idx))
        return named

    def group_title(self, name):
        """A group's name for a title: "point 3: KEY = value, ..." for a sweep's point."""
        if name.startswith("point "):
            p = int(name.split()[1])
            if p in self.point_text:
                return "%s: %s" % (name, self.point_text[p])
        return name

    def csv(self, i, name):
        """Rows of one run's CSV ([] when it has none)."""
        if (i, name) not in self._csv:
            path = os.path.join(self.dirs[i], name)
            rows = []
            if os.path.isfile(path):
                with open(path, newline="", encoding="utf-8") as f:
                    rows = list(csv.DictReader(f))
            self._csv[(i, name)] = rows
        return self._csv[(i, name)]

    def measured(self, i):
        """(warm-up end, run end) of run i in s."""
        sc = self.config(i).get("scenario", {}) or {}
        return float(sc.get("warmup", 0) or 0), float(sc.get("duration", 0) or 0)

    def context(self, idx):
        """One line naming a group's config: λ, r, the HVs' trust as that
        config has it, the fleet, the measured time and the seeds pooled."""
        c = self.config(idx[0])
        m, sc = c.get("model", {}) or {}, c.get("scenario", {}) or {}
        parts = []
        if m.get("prior_go") is not None:
            parts.append("λ = %g" % m["prior_go"])
        if m.get("collision_penalty") is not None:
            parts.append("r = %g" % m["collision_penalty"])
        t = m.get("trust")
        if isinstance(t, (int, float)):
            parts.append("θ = %g" % t)
        elif isinstance(t, dict) and t.get("dist") == "beta":
            parts.append("θ ~ Beta(%g, %g)" % (t.get("alpha"), t.get("beta")))
        elif t is not None:
            parts.append("θ: %s" % dists.label(t))
        if sc.get("avs") is not None and sc.get("kind", "figure8") == "figure8":
            parts.append("%d AVs + %d HVs" % (sc.get("avs"), sc.get("hvs")))
        warm, end = self.measured(idx[0])
        if end:
            span = end - warm
            parts.append(("%g h measured" % (span / 3600.0)) if span >= 3600 else
                         "%g s measured" % span)
        parts.append("%d seed%s" % (len(idx), "" if len(idx) == 1 else "s"))
        return ", ".join(parts)


def binned_rates(runs, idx, width, policy_key=lambda i, p: p):
    """Per series and time bin of `width` s (from the warm-up's end) over
    the runs `idx`, pooled: {series: [(bin start, bin end, n, dc, collisions,
    oracle_dc_sum, clusters)]} from encounters.csv; series = policy_key(run,
    policy); clusters = {(run, hv): [n, dc, collisions]}, who was sampled
    (rate_interval)."""
    acc = {}
    for i in idx:
        warm, _ = runs.measured(i)
        for r in runs.csv(i, "encounters.csv"):
            t = number(r.get("time"))
            if t is None:
                continue
            b = int(math.floor((t - warm) / width))
            a = acc.setdefault(policy_key(i, r["policy"]), {}).setdefault(b, [0, 0, 0, 0.0, {}])
            dc, coll = r.get("hv_action") == "DC", r.get("collision") == "1"
            a[0] += 1
            a[1] += dc
            a[2] += coll
            a[3] += number(r.get("oracle_dc")) or 0.0
            c = a[4].setdefault((i, r.get("hv")), [0, 0, 0])
            c[0] += 1
            c[1] += dc
            c[2] += coll
    out = {}
    for series, bins in acc.items():
        warm = runs.measured(idx[0])[0]
        out[series] = [(warm + b * width, warm + (b + 1) * width, *bins[b]) for b in sorted(bins)]
    return out


def rate_interval(clusters, k, z=stats.Z95):
    """A pooled rate's interval computed in Python (a time bin) as the
    outputs' are (docs/metrics.md): clustered by HV within each run and by
    run over several runs. `clusters` = {(run, hv): [n, k0, k1, ...]}; the
    rate is the k-th count (1: DC, 2: collisions) over n. (low, high)."""
    r = clustered_counts(clusters, k, z)
    return r["low"], r["high"]


def clustered_counts(clusters, k, z=stats.Z95):
    """rate_interval's whole answer: the dict of taebp.stats.pooled_rate
    (rate, low, high, deff, clusters, few_clusters)."""
    by_run = {}
    for (run, _hv), c in clusters.items():
        by_run.setdefault(run, []).append((c[k], c[0]))
    ys, ns, deffs, gs = [], [], [], []
    for members in by_run.values():
        one = stats.clustered_rate([a for a, _ in members], [b for _, b in members], z)
        ys.append(sum(a for a, _ in members))
        ns.append(sum(b for _, b in members))
        deffs.append(one["deff"])
        gs.append(one["clusters"])
    return stats.pooled_rate(ys, ns, deffs, gs, z)
