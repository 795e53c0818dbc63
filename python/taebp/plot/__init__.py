"""Figures of taebp's results: one plotting API for the command line and a
notebook (pure Python and matplotlib; no compiled module needed).

    taebp.plot.sweep(result_or_dir, out=None, x=None, y=None, by=None)
        the figures of a sweep: the shipped studies' presets and the
        standard panels of every other swept key; with x / y / by one view
        (any swept key against any metrics). Returns the PNG paths.
    taebp.plot.run(result_or_dir, out=None)
        the figures of runs: a network run's map, runs beyond the paper's
        time series (learned and dynamic trust, experience).

`tools/plot` is these two on the command line (`tools/plot --help`): the same
calls draw the same files. Modules: tidy (results as long tables; also
SweepResult.tidy()), view (any swept key against any metrics; view_heat,
view_pairs, view_runs: a metric over two keys, a metric against another,
runs' time series), figure (panels of marks at the printed width), presets
(the shipped figures, declared in declare's vocabulary over the data
functions of sweep_data and run_data), style (colours, labels, titles and
units from the program's tables), netmap and figure_map (a network run's
map: its data, its layout)."""

import argparse
import json
import os
import sys
import textwrap

from . import presets, style, tidy, view
from .common import PlotError, Theory, ensure_dir, find_taebp, import_matplotlib, warn
from .netmap import queueing_delay, read_net  # noqa: F401 (tools/plot's API)

__all__ = ["sweep", "run", "main", "PlotError", "tidy", "view", "presets", "style"]


def _sweep_source(result_or_dir):
    return tidy.load(result_or_dir)


def sweep(result_or_dir, out=None, x=None, y=None, by=None, name=None, preset=None,
          taebp=None, theory_binary=True, describe=None):
    """Draws a sweep's figures into `out` (default: the sweep's folder) and
    returns their paths. `result_or_dir`: a taebp.SweepResult, a sweep folder
    or an aggregate.csv. Without x / y / by: the presets whose keys match
    (or only `preset`) and the standard panels against every other swept
    key, and the time-series figures of its tasks. With them: one view,
    `x` a swept key, `y` a metric or a list of them, `by` a swept key whose
    values are panel columns (`name` its file). `taebp`: the program that
    computes dense theory curves (default: found as tools/plot finds it;
    theory_binary=False draws the theory columns). `describe`: a JSON file
    saying what each figure holds. Raises taebp.plot.PlotError (with
    `.code`, tools/plot's exit code) when there is nothing to draw or no
    place to write."""
    s = _sweep_source(result_or_dir)
    if not s.rows:
        raise PlotError("%s: aggregate.csv has no rows" % s.dir)
    plt = import_matplotlib()
    out_dir = ensure_dir(os.fspath(out) if out is not None else s.dir)
    failed = s.failed()
    for point, policy, bad, n in failed[:8]:
        warn("point %d, %s: %d of %d runs failed (marked ✕%s)"
             % (point, policy, bad, n, "; no value" if bad == n else ""))
    if len(failed) > 8:
        warn("... and %d more (point, policy) pairs with failed runs (results.csv: status, "
             "error)" % (len(failed) - 8))
    binary = find_taebp(taebp) if theory_binary else None
    if binary is None and theory_binary:
        warn("no taebp binary found: theory drawn through the theory columns")
    theory = Theory(binary, s)
    written, described = [], []
    if x or y or by:
        x = x or (s.keys[0] if s.keys else None)
        if x is None:
            raise view.cannot(s, "no swept key to draw against")
        ys = [m.strip() for m in (y.split(",") if isinstance(y, str) else y)] if y \
            else view.standard_metrics(s)
        for fig in view.asked(s, x, [m for m in ys if m], by=by, name=name):
            written.append(fig.save(plt, out_dir))
            described.append(fig.description)
    else:
        names = [preset] if preset else presets.applying(s)
        for n in names:
            if n not in presets.PRESETS:
                raise PlotError("preset %r: not a sweep preset (%s)"
                                % (n, ", ".join(presets.PRESETS)), 2)
            paths = presets.draw(n, plt, s, theory, out_dir)
            written += paths
            described += [{"file": os.path.basename(p), "view": "preset " + n} for p in paths]
        rest = [k for k in s.keys if k not in presets.covered(names)] if not preset else []
        for v in (view.default_views(s, rest) if rest else []):
            for fig in v.figures():
                written.append(fig.save(plt, out_dir))
                described.append(fig.description)
        if not preset and os.path.isdir(os.path.join(s.dir, "tasks")):
            runs = tidy.Runs(s.dir)
            if runs:
                written += _draw_runs(plt, runs, out_dir)
    if not written:
        raise view.cannot(s, "no plot for the swept keys %s" % (", ".join(s.keys) or "(none)"))
    if describe:
        _write_description(describe, described, written)
    return written


def _draw_runs(plt, runs, out_dir, only=None):
    written = []
    for n in presets.RUN_PRESETS:
        if (only is None or n == only) and presets.run_applies(n, runs):
            written += presets.draw_runs(n, plt, runs, out_dir)
    return written


def run(result_or_dir, out=None, preset=None, table=None, describe=None):
    """Draws the figures of runs into `out` (default: the (first) run's
    folder) and returns their paths: a network run's map (network_map.png)
    and, for runs beyond the paper, their time series (ta_ebp_learned:
    learned_rates.png, learned_regret.png; model.trust_dynamics:
    dynamic_trust.png; model.experience: influence.png), pooling only runs
    of one config (a sweep's point; run folders differing in their seed).
    `result_or_dir`: a taebp.RunResult written with out=, a run folder, a
    sweep folder (its tasks) or a list of run folders. `table`: with the
    influence preset, the markdown table of docs/influence.md written there."""
    sources = result_or_dir if isinstance(result_or_dir, (list, tuple)) else [result_or_dir]
    dirs = []
    for src in sources:
        where = getattr(src, "out", src)
        if where is None:
            raise PlotError("a RunResult without a folder: run it with out=DIR first", 2)
        where = os.fspath(where)
        if not os.path.exists(where):
            raise PlotError("%s: no such folder" % where, 2)
        dirs.append(where)
    plt = import_matplotlib()
    out_dir = ensure_dir(os.fspath(out) if out is not None else dirs[0])
    runs = tidy.Runs(dirs)
    written = []
    if preset is None and len(dirs) == 1 and os.path.isfile(os.path.join(dirs[0], "summary.json")):
        path = presets.draw_map(plt, dirs[0], out_dir)
        if path:
            written.append(path)
    if runs:
        if preset is not None and preset not in presets.RUN_PRESETS:
            raise PlotError("preset %r: not a run preset (%s)"
                            % (preset, ", ".join(presets.RUN_PRESETS)), 2)
        written += _draw_runs(plt, runs, out_dir, preset)
    if table:
        if not runs or not presets.run_applies("influence", runs):
            raise PlotError("--table: only runs with model.experience have the influence table", 2)
        try:
            with open(table, "w", encoding="utf-8") as f:
                f.write(presets.influence_table(runs))
        except OSError as e:
            raise PlotError("--table %s: cannot write it (%s)" % (table, e.strerror or e), 2)
        written.append(table)
    if not written:
        raise PlotError("%s: no figure for these runs: a network run gets its map "
                        "(network_map.png), runs beyond the paper their time series "
                        "(ta_ebp_learned, model.trust_dynamics, model.experience)"
                        % ", ".join(dirs))
    if describe:
        _write_description(describe, [{"file": os.path.basename(p)} for p in written], written)
    return written


def _write_description(path, described, written):
    try:
        with open(path, "w", encoding="utf-8") as f:
            json.dump({"figures": described, "written": [os.path.basename(p) for p in written]},
                      f, indent=1)
    except OSError as e:
        raise PlotError("--describe %s: cannot write it (%s)" % (path, e.strerror or e), 2)


# ------------------------------------------------------------------ command line
def metric_list(binary=None):
    """The metric table's run metrics (tables.json), wrapped for --help."""
    names = [m["name"] for m in style.tables()["metrics"] if "run" in m["levels"]]
    return textwrap.fill(", ".join(names), 79, initial_indent="  ", subsequent_indent="  ") + "\n"


def parser():
    epilog = (
        "Default: the shipped figures where a study's keys match one (presets: "
        + ", ".join(presets.PRESETS) + "), and for every other swept key KEY the standard "
        "panels in sweep_KEY.png: " + ", ".join(view.STANDARD) + " (those with data), one "
        "line per policy, the other swept keys that vary at one x as line styles, a rate's "
        "95 % interval, a mean's t interval from 5 seeds (each seed's value below that), "
        "theory a bar at the point, stalled runs ringed, failed runs marked. --x/--y/--by draw "
        "one view instead. Figures are drawn at a journal page's width (7 in), text 8 pt or "
        "more.")
    epilog = textwrap.fill(epilog, 79) + (
        "\n\nMetrics (--y; aggregate.csv's columns, `taebp metrics`):\n" + metric_list() +
        "\nRun presets (a run folder, a sweep's tasks, or several run folders): " +
        ", ".join(presets.RUN_PRESETS) +
        "\n\nExamples: build/taebp sweep configs/sweep_trust.yaml && tools/plot results/sweep_trust"
        "\n          tools/plot results/influence/seed* --preset influence --out docs/img")
    ap = argparse.ArgumentParser(
        prog="tools/plot", formatter_class=argparse.RawDescriptionHelpFormatter,
        description="PNG figures of a `taebp sweep` folder (aggregate.csv, sweep.json): any "
                    "swept key against any metric; the shipped studies' figures as presets. "
                    "Of `taebp run` folders: a network run's map, runs beyond the paper's "
                    "time series. The same as taebp.plot.sweep() and taebp.plot.run().",
        epilog=epilog)
    ap.add_argument("sources", metavar="DIR", nargs="+",
                    help="the --out folder of `taebp sweep` (or an aggregate CSV file), or of "
                         "`taebp run` (several: runs pooled by config)")
    ap.add_argument("--out", metavar="DIR",
                    help="where to write the PNGs (default: the first DIR, or the CSV's folder)")
    ap.add_argument("--x", metavar="KEY", help="the swept key on the x axis (a generic view)")
    ap.add_argument("--y", metavar="METRIC[,METRIC]",
                    help="the metrics, one panel each (default: the standard panels)")
    ap.add_argument("--by", metavar="KEY", help="a swept key whose values are panel columns")
    ap.add_argument("--name", metavar="FILE.png", help="the generic view's file name "
                    "(default: sweep_KEY.png)")
    ap.add_argument("--preset", metavar="NAME",
                    choices=sorted(presets.PRESETS) + sorted(presets.RUN_PRESETS),
                    help="draw only this preset (%s)" % ", ".join(
                        list(presets.PRESETS) + list(presets.RUN_PRESETS)))
    ap.add_argument("--table", metavar="FILE.md",
                    help="with the influence preset: also its markdown table (docs/influence.md)")
    ap.add_argument("--describe", metavar="FILE.json",
                    help="also write what each figure holds (file, axes, lines and their "
                         "points) as JSON")
    ap.add_argument("--taebp", metavar="PATH",
                    help="the taebp binary for dense theory curves (default: $TAEBP_BUILD_DIR/"
                         "taebp, the build tree's, then PATH; without one, the theory columns)")
    ap.add_argument("--no-theory-binary", action="store_true",
                    help="draw theory from aggregate.csv's theory columns, never call taebp")
    return ap


def _is_run(d):
    return os.path.isdir(d) and not os.path.isfile(os.path.join(d, "aggregate.csv")) and \
        os.path.isfile(os.path.join(d, "summary.json"))


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    args = parser().parse_args(argv)
    try:
        for d in args.sources:
            if not os.path.exists(d):
                raise PlotError("%s: no such folder or file" % d, 2)
        if len(args.sources) > 1 or _is_run(args.sources[0]) or \
                args.preset in presets.RUN_PRESETS:
            written = run(args.sources, out=args.out, preset=args.preset, table=args.table,
                          describe=args.describe)
        else:
            if args.table:
                raise PlotError("--table: only with run folders of the influence study", 2)
            written = sweep(args.sources[0], out=args.out, x=args.x, y=args.y, by=args.by,
                            name=args.name, preset=args.preset, taebp=args.taebp,
                            theory_binary=not args.no_theory_binary, describe=args.describe)
    except PlotError as e:
        print("tools/plot: %s" % e, file=sys.stderr)
        return e.code
    for p in written:
        print(p)
    return 0
