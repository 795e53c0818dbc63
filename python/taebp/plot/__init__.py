"""tools/plot as a package: plots of any sweep (and of runs), pure Python with
matplotlib (Debian's python3-matplotlib; no compiled module needed).

  common    reading aggregate.csv (Sweep), styles, the theory binary, save()
  tidy      a sweep as a long-form table (point x policy x metric)
  view      the generic view: any swept key against any metrics
  presets   the shipped figures as named choices (figure8, network, noise)
  netmap    a network run's map; runs: time series of runs beyond the paper

main(argv) is the command line (tools/plot is a thin script around it)."""

import argparse
import json
import os
import subprocess
import sys
import textwrap

from . import presets, tidy, view
from .common import (PlotError, Sweep, Theory, find_taebp, import_matplotlib, load_policy_labels,
                     warn)
from .netmap import plot_map, queueing_delay, read_net  # noqa: F401 (tools/plot's API)
from .runs import Runs, plot_runs

__all__ = ["main", "PlotError", "Sweep", "tidy", "view", "presets"]


def metric_list(binary):
    """The metric table's names (taebp metrics), wrapped for --help."""
    names = None
    if binary:
        try:
            out = subprocess.run([binary, "metrics", "--print", "json"], capture_output=True,
                                 text=True, timeout=20)
            if out.returncode == 0:
                names = [m["name"] for m in json.loads(out.stdout)["metrics"]
                         if "run" in m["levels"]]
        except (OSError, ValueError, KeyError, subprocess.TimeoutExpired):
            names = None
    if names is None:
        return ("  (the metric table needs the taebp binary: `taebp metrics`; none found)\n")
    names += sorted(tidy.DERIVED)
    return textwrap.fill(", ".join(names), 79, initial_indent="  ", subsequent_indent="  ") + "\n"


def parser(binary):
    epilog = (
        "Default: the shipped figures where a study's keys match one (presets: "
        + ", ".join(presets.PRESETS) + "), and for every other swept key KEY the standard "
        "panels in sweep_KEY.png: " + ", ".join(view.STANDARD) + " (those with data), one "
        "line per policy, the other swept keys as line styles or panel columns, 95 % "
        "intervals over the seeds, theory a bar at the point, stalled runs ringed. --x/--y/--by draw one "
        "view instead.")
    epilog = textwrap.fill(epilog, 79) + (
        "\n\nMetrics (--y; aggregate.csv's columns, `taebp metrics`):\n" + metric_list(binary) +
        "\nExample: build/taebp sweep configs/sweep_trust.yaml && tools/plot results/sweep_trust")
    ap = argparse.ArgumentParser(
        prog="tools/plot", formatter_class=argparse.RawDescriptionHelpFormatter,
        description="PNG plots of a `taebp sweep` directory (aggregate.csv, sweep.json): any "
                    "swept key against any metric; the shipped studies' figures as presets. "
                    "Of a `taebp run` directory: a network run's map, runs beyond the paper's "
                    "time series (ta_ebp_learned -> learned_rates.png, learned_regret.png; "
                    "model.trust_dynamics -> dynamic_trust.png).",
        epilog=epilog)
    ap.add_argument("sweep_dir", metavar="SWEEP_DIR",
                    help="the --out directory of `taebp sweep` (or an aggregate CSV file itself), "
                         "or of `taebp run` (a sweep's tasks/P-R included)")
    ap.add_argument("--out", metavar="DIR",
                    help="where to write the PNGs (default: SWEEP_DIR, or the CSV file's directory)")
    ap.add_argument("--x", metavar="KEY", help="the swept key on the x axis (a generic view)")
    ap.add_argument("--y", metavar="METRIC[,METRIC]",
                    help="the metrics, one panel each (default: the standard panels)")
    ap.add_argument("--by", metavar="KEY", help="a swept key whose values are panel columns")
    ap.add_argument("--name", metavar="FILE.png", help="the generic view's file name "
                    "(default: sweep_KEY.png)")
    ap.add_argument("--preset", metavar="NAME", choices=sorted(presets.PRESETS),
                    help="draw only this preset (%s)" % ", ".join(presets.PRESETS))
    ap.add_argument("--describe", metavar="FILE.json",
                    help="also write what each figure holds (file, axes, lines and their "
                         "points) as JSON")
    ap.add_argument("--taebp", metavar="PATH",
                    help="the taebp binary for the dense theory curves (default: $TAEBP_BUILD_DIR/taebp, "
                         "build/taebp, then PATH; without one, the theory columns are drawn)")
    ap.add_argument("--no-theory-binary", action="store_true",
                    help="draw theory from aggregate.csv's theory columns, never call taebp")
    return ap


def _run_dir(plt, args):
    runs = Runs(args.sweep_dir)
    out_dir = args.out or args.sweep_dir
    os.makedirs(out_dir, exist_ok=True)
    written = plot_runs(plt, runs, out_dir)
    network_map = plot_map(plt, args.sweep_dir, out_dir)
    if network_map:
        written.append(network_map)
    if not written:
        raise PlotError("%s: a run directory; plots are drawn for network runs (network_map.png) "
                        "and runs beyond the paper (ta_ebp_learned, model.trust_dynamics)"
                        % args.sweep_dir)
    return written, []


def _sweep(plt, args):
    sweep = Sweep(args.sweep_dir)
    if not sweep.rows:
        raise PlotError("%s: aggregate.csv has no rows" % args.sweep_dir)
    out_dir = args.out or sweep.dir
    os.makedirs(out_dir, exist_ok=True)
    binary = None if args.no_theory_binary else find_taebp(args.taebp)
    if binary is None and not args.no_theory_binary:
        warn("no taebp binary found: theory drawn through the theory columns")
    theory = Theory(binary, sweep)
    written, described = [], []
    if args.x or args.y or args.by:
        x = args.x or (sweep.keys[0] if sweep.keys else None)
        if x is None:
            raise view.cannot(sweep, "no swept key to draw against")
        ys = [y.strip() for y in args.y.split(",") if y.strip()] if args.y else \
            view.standard_metrics(sweep)
        v = view.View(sweep, x, ys, args.by)
        written.append(v.draw(plt, out_dir, args.name))
        described.append(v.description)
        return written, described
    names = [args.preset] if args.preset else presets.applying(sweep)
    for name in names:
        paths = presets.draw(name, plt, sweep, theory, out_dir)
        written += paths
        described += [{"file": os.path.basename(p), "view": "preset " + name} for p in paths]
    rest = [k for k in sweep.keys if k not in presets.covered(names)] if not args.preset else []
    if rest:
        for v in view.default_views(sweep, rest):
            written.append(v.draw(plt, out_dir))
            described.append(v.description)
    if os.path.isdir(sweep.dir):
        runs = Runs(sweep.dir)
        if runs:
            written += plot_runs(plt, runs, out_dir)
    if not written:
        raise view.cannot(sweep, "no plot for the swept keys %s" % (", ".join(sweep.keys) or "(none)"))
    return written, described


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    binary = None
    if any(a in ("-h", "--help") for a in argv):
        explicit = argv[argv.index("--taebp") + 1] if "--taebp" in argv[:-1] else None
        try:
            binary = find_taebp(explicit)
        except PlotError:
            binary = None
    args = parser(binary).parse_args(argv)
    try:
        if not os.path.exists(args.sweep_dir):
            raise PlotError("%s: no such directory or file" % args.sweep_dir, 2)
        plt = import_matplotlib()
        load_policy_labels(find_taebp(args.taebp))  # the labels of the one policy table
        if os.path.isdir(args.sweep_dir) and \
                not os.path.isfile(os.path.join(args.sweep_dir, "aggregate.csv")) and \
                os.path.isfile(os.path.join(args.sweep_dir, "summary.json")):
            written, described = _run_dir(plt, args)
        else:
            written, described = _sweep(plt, args)
    except PlotError as e:
        print("tools/plot: %s" % e, file=sys.stderr)
        return e.code
    if args.describe:
        with open(args.describe, "w", encoding="utf-8") as f:
            json.dump({"figures": described, "written": [os.path.basename(p) for p in written]},
                      f, indent=1)
    for p in written:
        print(p)
    return 0
