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
NARROW, WIDE = "{dist: beta, alpha: 12, beta: 8}", "{dist: beta, alpha: 1.2, beta: 0.8}"
POLICIES = [p["name"] for p in style.tables()["policies"]]


def grid_study(folder, seeds=3, shares=(0.25, 0.5, 0.75), failed=()):
    """A two-way grid's study by hand: AV share x two trust distributions x
    every policy x `seeds` seeds; `failed`: (share, policy, failed runs)."""
    rows, runs, point = [], [], 0
    for share in shares:
        for trust in (NARROW, WIDE):
            for i, policy in enumerate(POLICIES):
                game = style.plays_game(policy)
                bad = sum(f for s, p, f in failed if s == share and p == policy)
                ok = seeds - bad
                flow = 1500 + 40 * share - 3 * i
                row = {"point": point, "scenario.av_share": share, "model.trust": trust,
                       "policy": policy, "runs_ok": ok, "runs_failed": bad}
                if ok:
                    row.update({"served_flow": flow, "served_flow_sd": 12.0,
                                "offered_flow": 1600, "time_loss_mean_av": 30 + 2 * i,
                                "time_loss_mean_av_sd": 1.5, "time_loss_mean_hv": 28 + i,
                                "time_loss_mean_hv_sd": 1.0, "stalled": 0})
                    if game:
                        n = 120 * seeds
                        k = int(0.1 * (i % 3) * n)
                        row.update({"encounters": n, "collisions": k,
                                    "collision_rate": k / n, "collision_rate_lo": k / n * 0.7,
                                    "collision_rate_hi": k / n * 1.3 + 0.01,
                                    "dc": n // 3, "dc_rate": (n // 3) / n,
                                    "dc_rate_lo": 0.28, "dc_rate_hi": 0.38,
                                    "theory_collision_rate": 0.1 * (i % 3),
                                    "theory_dc_rate": 1 / 3,
                                    "encounters_per_hour": 120 / (1680 / 3600),
                                    "encounters_per_hour_sd": 9.0})
                    else:
                        row.update({"encounters": 0})
                rows.append(row)
                for rep in range(ok):
                    runs.append({"point": point, "replicate": rep, "scenario.av_share": share,
                                 "model.trust": trust, "policy": policy,
                                 "served_flow": flow + 10 * (rep - 1),
                                 "time_loss_mean_av": 30 + 2 * i + rep,
                                 "time_loss_mean_hv": 28 + i - rep,
                                 "encounters_per_hour": 257 + rep if game else None,
                                 "measured_seconds": 1680})
                for rep in range(ok, seeds):
                    runs.append({"point": point, "replicate": rep, "policy": policy,
                                 "status": "failed", "error": "SUMO aborted"})
            point += 1
    return write_sweep(str(folder), ["scenario.av_share", "model.trust"], rows, runs,
                       config={"scenario": {"kind": "network", "duration": 1800, "warmup": 120},
                               "model": {"prior_go": 0.2, "collision_penalty": 3.0}},
                       replicates=seeds)


def mismatch_study(folder, zipped=False):
    rows, point = [], 0
    for theta in (0.2, 0.6, 1.0):
        for hat in (0.2, 0.6, 1.0):
            n = 200
            k = 40 if hat > theta and hat >= 0.25 else 0
            rows.append({"point": point, "model.trust": theta, "model.assumed_trust": hat,
                         "policy": "ta_ebp", "runs_ok": 2, "runs_failed": 0, "encounters": n,
                         "collisions": k, "collision_rate": k / n,
                         "collision_rate_lo": max(0, k / n - 0.05), "collision_rate_hi": k / n + 0.05,
                         "dc_rate": 0.3, "dc_rate_lo": 0.24, "dc_rate_hi": 0.37,
                         "theory_collision_rate": 0.2 if k else 0.0, "theory_dc_rate": 0.3})
            point += 1
    return write_sweep(str(folder), ["model.trust", "model.assumed_trust"], rows,
                       config={"model": {"prior_go": 0.2, "collision_penalty": 3.0,
                                         "likelihood": {"type": "linear", "s_max": 2.0}},
                               "scenario": {"duration": 600}}, replicates=2)


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
