"""What a reader needs of every figure, checked on the matplotlib figures
taebp.plot saves (captured at savefig): no empty panel, no policy line
without values, points that share an x told apart, the legend inside the
canvas, text of 8 pt or more at the printed width. And small sweep folders
written by hand (the metric table's columns) for the tests that need no
simulation."""
import contextlib
import csv
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.figure  # noqa: E402
import matplotlib.text  # noqa: E402

from taebp.plot import style  # noqa: E402
from taebp.plot.common import SIMULATED  # noqa: E402


@contextlib.contextmanager
def captured():
    """The figures saved inside the block: [(path, figure)]."""
    saved = []
    original = matplotlib.figure.Figure.savefig

    def capture(self, path, *args, **kwargs):
        saved.append((str(path), self))
        return original(self, path, *args, **kwargs)

    matplotlib.figure.Figure.savefig = capture
    try:
        yield saved
    finally:
        matplotlib.figure.Figure.savefig = original


def _finite(line):
    xs, ys = line.get_xdata(), line.get_ydata()
    try:
        return [(float(x), float(y)) for x, y in zip(xs, ys)
                if math.isfinite(float(x)) and math.isfinite(float(y))]
    except (TypeError, ValueError):
        return list(zip(xs, ys))


def problems(fig, name=""):
    """What a reader would object to in a figure: [] when nothing."""
    out = []
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    width = fig.get_figwidth()
    if width > style.PRINT_WIDTH + 1e-6:
        out.append("%s: %.2f in wide, more than the printed width %.1f in"
                   % (name, width, style.PRINT_WIDTH))
    scale = min(1.0, style.PRINT_WIDTH / width)
    for t in fig.findobj(matplotlib.text.Text):
        if not t.get_visible() or not t.get_text().strip():
            continue
        if t.axes is not None and not t.axes.get_visible():
            continue
        size = t.get_fontsize() * scale
        if size < style.MIN_FONT - 1e-9:
            out.append("%s: text %r at %.1f pt printed (< %g)" % (name, t.get_text()[:30], size,
                                                                  style.MIN_FONT))
    box = fig.bbox
    for leg in fig.legends + [ax.get_legend() for ax in fig.axes if ax.get_legend()]:
        e = leg.get_window_extent(renderer)
        if e.x0 < box.x0 - 1 or e.x1 > box.x1 + 1 or e.y0 < box.y0 - 1 or e.y1 > box.y1 + 1:
            out.append("%s: legend outside the canvas (%s in %s)" % (name, e.bounds, box.bounds))
    for ax in fig.axes:
        if not ax.get_visible() or ax.get_label() == "<colorbar>":
            continue
        sim_lines = [l for l in ax.get_lines() if l.get_gid() == SIMULATED]
        sim_meshes = [c for c in ax.collections if c.get_gid() == SIMULATED]
        title = ax.get_title().split("\n")[0]
        if not sim_lines and not sim_meshes:
            out.append("%s: panel %r draws no simulated value" % (name, title))
        for l in sim_lines:
            if not _finite(l):
                out.append("%s: panel %r: a line without values (%s)"
                           % (name, title, l.get_color()))
        # Points sharing an x: two lines of one colour (one policy) must
        # differ in line style or marker.
        seen = {}
        for l in sim_lines:
            if l.get_marker() in (None, "", "None", " ") or l.get_markerfacecolor() == "none":
                continue  # a curve (over time, over encounters), or each seed's value

            key = matplotlib.colors.to_hex(l.get_color())
            look = (l.get_linestyle(), l.get_marker())
            if look in seen.setdefault(key, set()):
                xs = {round(x, 6) for x, _ in _finite(l)}
                out.append("%s: panel %r: two lines of colour %s look alike (%s)"
                           % (name, title, key, sorted(xs)[:4]))
            seen[key].add(look)
    return out


# ------------------------------------------------------------------ sweeps by hand
def metric_columns(metrics, level="run", aggregate=True):
    key = "aggregate_columns" if aggregate else "columns"
    return [c for m in metrics if level in m["levels"] for c in m[key]]


def write_sweep(folder, keys, rows, seeds=None, config=None, replicates=None, metrics=None):
    """A sweep folder written by hand: aggregate.csv (this version's
    columns, `rows` dicts giving values by name), results.csv (`seeds`:
    dicts with point, replicate, policy and values), sweep.json."""
    import taebp
    metrics = metrics or taebp.metrics()
    os.makedirs(folder, exist_ok=True)
    header = ["point"] + list(keys) + ["policy", "runs_ok", "runs_failed"] + \
        metric_columns(metrics)
    for r in rows:
        unknown = set(r) - set(header)
        assert not unknown, "columns not in the metric table: %s" % sorted(unknown)
    with open(os.path.join(folder, "aggregate.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        for r in rows:
            w.writerow(["" if r.get(c) is None else r.get(c) for c in header])
    if seeds is not None:
        run_header = ["point", "replicate", "seed"] + list(keys) + ["policy", "status", "error"] + \
            metric_columns(metrics, aggregate=False)
        with open(os.path.join(folder, "results.csv"), "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(run_header)
            for r in seeds:
                r = dict({"status": "ok", "seed": 1 + r.get("replicate", 0)}, **r)
                w.writerow(["" if r.get(c) is None else r.get(c) for c in run_header])
    with open(os.path.join(folder, "sweep.json"), "w") as f:
        json.dump({"columns": list(keys), "replicates": replicates,
                   "config": config or {}}, f)
    return folder
