"""Result folders as data, in pure Python (no compiled module needed): the
tables a run (``taebp run --out``) or a sweep (``taebp sweep``) wrote, typed,
and as pandas DataFrames. ``import taebp`` re-exports these; ``tools/plot``
reads sweeps through them without the built module.

Column types: a column named in the metric table (``taebp metrics``) gets the
table's type in every frame (real -> float64 even when every value is 0,
count -> int64, float64 where a cell is empty, flag -> bool: numpy dtypes, no
pandas extension types; in aggregate.csv a flag pooled by sum, e.g.
``stalled``, counts the runs that had it); ``set_metric_types`` installs the
table (``import taebp`` does). A swept value that is a map (a trust
distribution) keeps its text and gains numeric columns beside it:
``KEY.dist``, ``KEY.mean``, ``KEY.sd`` (taebp.dists).
"""

import csv
import io
import json
import numbers
import os
import re

from . import dists

__all__ = ["Table", "RunResult", "SweepResult", "load_run", "load_sweep", "to_pandas",
           "set_metric_types", "column_types"]

_INT = re.compile(r"^[+-]?\d+$")

# column -> "real" | "count" | "flag", for results/summary columns and for
# aggregate.csv columns (set_metric_types).
_TYPES = {"run": {}, "aggregate": {}}
_FIXED = {"point": "count", "replicate": "count", "seed": "count", "runs_ok": "count",
          "runs_failed": "count"}


def set_metric_types(metrics):
    """Installs the metric table (the list taebp.metrics() returns) as the
    columns' types of every frame."""
    run, agg = {}, {}
    for m in metrics:
        run[m["name"]] = m["type"]
        for c in m.get("columns", []):
            run.setdefault(c, m["type"])
        for c in m.get("aggregate_columns", []):
            t = m["type"]
            if c != m["name"]:
                t = "real"  # _lo, _hi, _sd
            elif t == "flag" and m.get("pool") == "sum":
                t = "count"  # the number of runs with the flag
            elif m.get("pool") in ("mean", "rate", "weighted", "prediction"):
                t = "real"
            agg[c] = t
    _TYPES["run"], _TYPES["aggregate"] = run, agg


def column_types(level="run"):
    """{column: type} of the installed metric table (empty without one)."""
    return dict(_FIXED, **_TYPES[level])


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


def _pandas():
    try:
        import pandas
    except ImportError:
        raise ImportError("pandas is not installed for this Python: install the Debian "
                          "package python3-pandas (tools/setup.sh does)") from None
    return pandas


def typed_frame(df, level="run", keys=()):
    """``df`` with the metric table's dtypes and, for each swept key in
    ``keys`` whose values include a distribution, KEY.dist, KEY.mean and
    KEY.sd inserted after it. Numpy dtypes only, so that numpy takes every
    column as it is (``np.log``, ``np.corrcoef``): real -> float64, count ->
    int64 (float64 with NaN where a cell is empty), flag -> bool."""
    pd = _pandas()
    types = column_types(level)
    columns = {}
    for c in df.columns:
        t = types.get(c)
        col = df[c]
        if t in ("real", "count"):
            col = pd.to_numeric(col, errors="coerce").astype("float64")
            if t == "count" and not col.isna().any():
                col = col.astype("int64")
        elif t == "flag":
            col = col.map(lambda v: bool(v) if v is not None and v == v and v != "" else False)
            col = col.astype(bool)
        columns[c] = col
        if c in keys:
            columns.update(_distribution_columns(pd, c, col))
    # One frame built at once (inserting column by column fragments it, and
    # pandas warns: PerformanceWarning).
    return pd.DataFrame(columns, index=df.index)


def _distribution_columns(pd, key, values):
    """{KEY.dist, KEY.mean, KEY.sd} of a swept key whose values include a
    distribution (taebp.dists), else {}."""
    parsed = []
    for v in values:
        try:
            parsed.append(dists.value(v))
        except ValueError:
            parsed.append(v)
    if not any(dists.is_distribution(p) for p in parsed):
        return {}
    described = [dists.describe(p) for p in parsed]
    return {key + "." + suffix: pd.Series([d[i] for d in described], index=values.index,
                                          dtype=dtype)
            for i, (suffix, dtype) in enumerate((("dist", "object"), ("mean", "float64"),
                                                 ("sd", "float64")))}


class Table:
    """A CSV output as columns and typed rows (ints, floats, bools, strings;
    None for an empty cell). ``rows`` is a list of tuples in column order;
    iterating gives one dict per row; ``table["column"]`` a column as a
    list, ``table[i]`` the i-th row as a dict and ``table[a:b]`` a Table of
    those rows (as a list slices)."""

    def __init__(self, columns, rows, name="", level="run", keys=()):
        self.columns = list(columns)
        self.rows = rows
        self.name = name
        self.level = level
        self.keys = list(keys)

    @classmethod
    def from_csv(cls, text, name="", level="run", keys=()):
        reader = csv.reader(io.StringIO(text))
        try:
            columns = next(reader)
        except StopIteration:
            return cls([], [], name, level, keys)
        raw = list(reader)
        if not raw:
            return cls(columns, [], name, level, keys)
        converted = [_convert([r[i] if i < len(r) else "" for r in raw])
                     for i in range(len(columns))]
        return cls(columns, list(zip(*converted)), name, level, keys)

    def __len__(self):
        return len(self.rows)

    def __iter__(self):
        for r in self.rows:
            yield dict(zip(self.columns, r))

    def __getitem__(self, what):
        if isinstance(what, slice):
            return Table(self.columns, self.rows[what], self.name, self.level, self.keys)
        if isinstance(what, int) and not isinstance(what, bool):
            return dict(zip(self.columns, self.rows[what]))
        if what not in self.columns:
            raise KeyError("%s: no column %r (columns: %s)"
                           % (self.name or "table", what, ", ".join(self.columns)))
        i = self.columns.index(what)
        return [r[i] for r in self.rows]

    def __repr__(self):
        return "<taebp.Table %s: %d rows x %d columns>" % (self.name or "", len(self.rows),
                                                           len(self.columns))

    def to_pandas(self):
        """A pandas.DataFrame of the table (needs python3-pandas), with the
        metric table's dtypes and swept distributions as numeric columns."""
        pd = _pandas()
        df = pd.DataFrame.from_records(self.rows, columns=self.columns)
        return typed_frame(df, self.level, self.keys)


def to_pandas(obj):
    """pandas DataFrames of a result: a Table -> one DataFrame; a RunResult ->
    {"encounters", "junctions", "collisions", "policies"}; a SweepResult -> {"results",
    "aggregate", "encounters", "junctions"}."""
    if isinstance(obj, (Table, RunResult, SweepResult)):
        return obj.to_pandas()
    raise TypeError("to_pandas: a taebp Table, RunResult or SweepResult, not %s"
                    % type(obj).__name__)


def _flatten(prefix, value, out):
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(prefix + "." + k if prefix else k, v, out)
    else:
        out[prefix] = value
class RunResult:
    """What ``taebp run`` writes, as data.

    summary     summary.json as a dict (policies.<name>.{...}, provenance)
    encounters  encounters.csv as a Table (one row per AV-HV encounter)
    junctions   junctions.csv as a Table (one row per controlled junction and
                policy: crossings, waits, queues, encounters, rates)
    collisions  collisions.csv as a Table (one row per collision SUMO reported
                after the warm-up: when, where, the two vehicles, the count it
                is in)
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
        self.collisions = Table.from_csv(self.files.get("collisions.csv", ""), "collisions.csv")
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
        junction and policy, "collisions": one row per collision SUMO reported,
        "policies": one row per policy with summary.json's
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
               "collisions": self.collisions.to_pandas(),
               "policies": typed_frame(pd.DataFrame(rows))}
        for name in ("timeseries", "hv_trust"):
            if getattr(self, name) is not None:
                out[name] = getattr(self, name).to_pandas()
        return out

    def __repr__(self):
        return "<taebp.RunResult %s: %d encounters>" % (", ".join(self.policies),
                                                       len(self.encounters))


def load_run(out_dir):
    """The RunResult of a directory that ``taebp run --out`` (or run(out=...)) wrote."""
    files = {}
    for name in ("summary.json", "encounters.csv", "junctions.csv", "collisions.csv",
                 "config.yaml", "timing.json", "timeseries.csv", "hv_trust.csv"):
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
                level = "aggregate" if name == "aggregate.csv" else "run"
                self._tables[name] = Table.from_csv(f.read(), name, level, self.keys)
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
                files, _ = self._task_files(point, replicate)  # reused runs' rows put in
                if files is not None:
                    if "junctions.csv" not in files:
                        continue
                    t = Table.from_csv(files["junctions.csv"], "junctions.csv")
                else:
                    path = os.path.join(self.out, "tasks", "%d-%d" % (point, replicate),
                                        "junctions.csv")
                    if not os.path.isfile(path):
                        continue
                    with open(path, encoding="utf-8", newline="") as f:
                        t = Table.from_csv(f.read(), "junctions.csv")
                columns = columns or front + t.columns
                rows.extend(tuple(values) + row for row in t.rows)
            self._tables["junctions.csv"] = Table(columns or front, rows, "junctions",
                                                  keys=self.keys)
        return self._tables["junctions.csv"]

    def run(self, point, replicate=0):
        """One task's RunResult (tasks/POINT-REPLICATE)."""
        for what, v in (("point", point), ("replicate", replicate)):
            if isinstance(v, bool) or not isinstance(v, numbers.Integral):
                raise TypeError("SweepResult.run: %s must be %s number (an int, as in "
                                "results.csv), got %r"
                                % (what, "a grid point's" if what == "point" else "a", v))
        files, reused = self._task_files(point, replicate)
        if files is None:
            return load_run(os.path.join(self.out, "tasks", "%d-%d" % (point, replicate)))
        here = os.path.join(self.out, "tasks", "%d-%d" % (point, replicate))
        return RunResult(files, out=here if os.path.isdir(here) else None)  # None: all reused

    def _task_files(self, point, replicate):
        """A task's result files with the runs it reused put in (results.csv's
        reused_from: a policy whose run at this task could not differ from an
        earlier task's): each CSV's rows policy by policy in the point's order,
        summary.json's policies likewise, and summary["reused_from"] {policy:
        "P-R"}; (None, {}) for a task that reused nothing."""
        if "_tasks" not in self._tables:  # (point, replicate) -> ([policies], {reused})
            tasks = {}
            for r in self.results:
                order, reused = tasks.setdefault((r["point"], r["replicate"]), ([], {}))
                order.append(r["policy"])
                if r.get("reused_from"):
                    reused[r["policy"]] = r["reused_from"]
            self._tables["_tasks"] = tasks
        order, reused = self._tables["_tasks"].get((point, replicate), ([], {}))
        if not reused:
            return None, {}
        here = os.path.join(self.out, "tasks", "%d-%d" % (point, replicate))
        folders = {}

        def files_of(task):
            if task not in folders:
                folder = os.path.join(self.out, "tasks", task)
                got = {}
                for name in ("summary.json", "encounters.csv", "junctions.csv", "collisions.csv",
                             "config.yaml", "timeseries.csv", "hv_trust.csv"):
                    path = os.path.join(folder, name)
                    if os.path.isfile(path):
                        with open(path, encoding="utf-8", newline="") as f:
                            got[name] = f.read()
                folders[task] = got
            return folders[task]

        own_task = "%d-%d" % (point, replicate)
        sources = {p: reused.get(p, own_task) for p in order}
        missing = sorted({t for t in sources.values() if "summary.json" not in files_of(t)})
        if missing:
            raise FileNotFoundError("%s: the run(s) of task %s are in tasks/%s, which has no "
                                    "summary.json (not finished?)" % (here, own_task,
                                                                       ", tasks/".join(missing)))
        base = files_of(own_task) if "summary.json" in files_of(own_task) else \
            files_of(sources[order[0]])
        summary = json.loads(base["summary.json"])
        summary["policies"] = {p: json.loads(files_of(sources[p])["summary.json"])["policies"][p]
                               for p in order}
        summary["reused_from"] = dict(reused)
        files = {"summary.json": json.dumps(summary, indent=2) + "\n"}
        for name in ("encounters.csv", "junctions.csv", "collisions.csv", "timeseries.csv",
                     "hv_trust.csv"):
            header, rows = None, []
            for p in order:
                text = files_of(sources[p]).get(name)
                if text is None:
                    continue
                lines = list(csv.reader(io.StringIO(text)))
                if not lines:
                    continue
                header = header or lines[0]
                at = lines[0].index("policy") if "policy" in lines[0] else None
                rows.extend(r for r in lines[1:] if at is not None and at < len(r) and r[at] == p)
            if header is not None:
                out = io.StringIO()
                csv.writer(out, lineterminator="\n").writerows([header] + rows)
                files[name] = out.getvalue()
        if "config.yaml" in files_of(own_task):
            files["config.yaml"] = files_of(own_task)["config.yaml"]
        return files, reused

    def tidy(self, metrics=None):
        """The sweep as one long pandas DataFrame, the table every figure is
        drawn from (taebp.plot.tidy): one row per point x policy x metric
        with a value, the swept keys as numbers where they are (a
        distribution with KEY.dist, KEY.mean, KEY.sd), value / lo / hi /
        theory as float64 (lo, hi: a rate's interval as aggregate.csv has it,
        a mean's t interval over the seeds), runs / failed / stalled as int64.
        ``metrics``: a list of metric names (default: every one)."""
        from .plot import tidy
        return tidy.to_pandas(self, metrics)

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


