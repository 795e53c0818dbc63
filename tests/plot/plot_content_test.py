#!/usr/bin/python3
"""ctest for what tools/plot draws (not only that it writes a PNG): the figures
are captured before saving and their texts, legends and artists inspected.
  mismatch heat maps (collisions and DC): theta-hat named on the axis and in
    the legend, the theta* line in the legend, every cell its rate and
    interval with a halo, white on dark cells;
  penetration: collisions beside throughput, intervals on the waits, the
    seed count, the loop length and the track caveat;
  noise: sigma = 0 (the paper's rates) a point of its own, the theory curves
    for sigma > 0 only (they do not meet sigma = 0 at the noisy values);
  network: stalled points ringed on every panel, encounters per hour without
    SUMO's own logic, served = offered, the title inside the figure;
  map: one panel per controller policy, junction markers coloured by delay.
Usage: plot_content_test.py SOURCE_DIR TAEBP_BINARY WORK_DIR."""
import importlib.machinery
import importlib.util
import json
import os
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.figure  # noqa: E402

source, taebp, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
loader = importlib.machinery.SourceFileLoader("taebp_plot", os.path.join(source, "tools", "plot"))
spec = importlib.util.spec_from_loader("taebp_plot", loader)
plot = importlib.util.module_from_spec(spec)
loader.exec_module(plot)

figures = []
original_savefig = matplotlib.figure.Figure.savefig


def capture(self, *args, **kwargs):
    figures.append(self)
    return original_savefig(self, *args, **kwargs)


matplotlib.figure.Figure.savefig = capture
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def sweep_dir(name, fixture, info):
    d = os.path.join(work, name)
    os.makedirs(d)
    shutil.copy(os.path.join(source, "tests", "data", fixture), os.path.join(d, "aggregate.csv"))
    with open(os.path.join(d, "sweep.json"), "w") as f:
        json.dump(info, f)
    return d


# aggregate.csv's metric columns, from the one metric table (taebp metrics):
# the fixtures below give values by name; every other column is empty.
import subprocess  # noqa: E402
METRICS = json.loads(subprocess.run([taebp, "metrics", "--print", "json"], check=True,
                                    capture_output=True, text=True).stdout)["metrics"]
AGGREGATE = [c for m in METRICS if "run" in m["levels"] for c in m["aggregate_columns"]]


def write_aggregate(path, axes, rows):
    """aggregate.csv with this version's header: point, the swept `axes`,
    policy, runs_ok, runs_failed, then every metric; `rows` are dicts."""
    import csv
    header = ["point"] + list(axes) + ["policy", "runs_ok", "runs_failed"] + AGGREGATE
    for r in rows:
        unknown = set(r) - set(header)
        assert not unknown, "fixture columns not in the metric table: %s" % sorted(unknown)
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        for r in rows:
            w.writerow(["" if r.get(c) is None else r.get(c) for c in header])


def read_rows(path):
    import csv
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def texts(fig):
    out = [t.get_text() for t in fig.texts]
    if fig._suptitle is not None:
        out.append(fig._suptitle.get_text())
    for ax in fig.axes:
        out += [ax.get_title(), ax.get_xlabel(), ax.get_ylabel()]
        leg = ax.get_legend()
        if leg:
            out += [t.get_text() for t in leg.get_texts()]
    for leg in fig.legends:
        out += [t.get_text() for t in leg.get_texts()]
    return out


# ---- mismatch heat map
d = sweep_dir("mismatch", "aggregate_mismatch.csv",
              {"config": {"model": {"prior_go": 0.2, "collision_penalty": 3.0,
                                    "likelihood": {"type": "linear", "s_max": 2.0}}},
               "replicates": 2})
figures.clear()
assert plot.main([d, "--taebp", taebp]) == 0
check(len(figures) == 2, "mismatch: a heat map of collisions and one of DC")
for fig in figures:
    ax = fig.axes[0]
    all_text = texts(fig)
    check(r"\hat{\theta}" in ax.get_ylabel(), "mismatch: the y axis names theta-hat in mathtext")
    legend = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    check(any(r"\theta^*" in t and "0.25" in t for t in legend), "mismatch: the theta* line is in the legend")
    check(any(r"\hat{\theta} = \theta$" in t for t in legend), "mismatch: the diagonal is in the legend")
    notes = [t for t in ax.texts if t.get_text() == "n/a" or t.get_text()[:1].isdigit()]
    check(len(notes) >= 9, "mismatch: every cell annotated (%d notes)" % len(notes))
    check(all("n/a" == t.get_text() or "–" in t.get_text() for t in notes),
          "mismatch: every cell with a value shows its interval")
    check(all(t.get_path_effects() for t in notes), "mismatch: every cell note has a halo")
    mesh = ax.collections[0]
    def luminance(t):
        r, g, b, _ = mesh.cmap(mesh.norm(float(t.get_text().split("\n")[0])))
        return 0.2126 * r + 0.7152 * g + 0.0722 * b
    valued = [t for t in notes if t.get_text() != "n/a"]
    check(all(t.get_color() == ("white" if luminance(t) < 0.45 else "black") for t in valued),
          "mismatch: white notes on dark cells, black on light ones")
    check(not any(t.get_text().startswith("θ̂") for t in ax.texts), "mismatch: no annotation over the cells")

# ---- penetration
d = sweep_dir("penetration", "aggregate_penetration.csv",
              {"config": {"model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6},
                          "scenario": {"avs": 8, "hvs": 8, "duration": 1800, "loop_length": 80}},
               "replicates": 3})
pen_rows = read_rows(os.path.join(d, "aggregate.csv"))
for r in pen_rows:
    # 3 seeds, as sweep.json says, and the encounters per hour of the game's policies.
    r["runs_ok"] = 3
    if (float(r["encounters"] or 0)) > 0:
        r["encounters_per_hour"] = float(r["encounters"]) * 2
    r["wait_mean_sd"] = 0.25
write_aggregate(os.path.join(d, "aggregate.csv"), ["scenario.avs", "scenario.hvs"], pen_rows)
figures.clear()
assert plot.main([d, "--no-theory-binary"]) == 0
fig = figures[-1]
all_text = texts(fig)
titles = [a.get_title() for a in fig.axes if a.get_visible()]
check(len(titles) == 6, "penetration: six panels (crossings all, AV, HV; collisions; wait; encounters)")
check(any(t.startswith("Collisions per encounter") for t in titles), "penetration: collisions beside throughput")
coll_ax = [a for a in fig.axes if a.get_title().startswith("Collisions")][0]  # noqa: E501
check(coll_ax.containers, "penetration: collision rates with intervals")
check("3 seeds" in fig._suptitle.get_text(), "penetration: the seed count in the title")
wait_ax = [a for a in fig.axes if "wait" in a.get_title()][0]
check(wait_ax.containers and all(c.has_yerr for c in wait_ax.containers),
      "penetration: intervals on the waits (no seeds' values in the fixture)")
check(any("80 m loops" in t for t in all_text), "penetration: the loop length in the title")
check(any("Caveat" in t and "track" in t for t in all_text), "penetration: the track caveat")
check(not any("stalled" in t for t in all_text), "penetration: no stall mark without stalled runs")
# The same with one run of the second row stalled: ringed on the throughput panel.
for i, r in enumerate(pen_rows):
    r["stalled"] = 1 if i == 1 else 0
write_aggregate(os.path.join(d, "aggregate.csv"), ["scenario.avs", "scenario.hvs"], pen_rows)
figures.clear()
assert plot.main([d, "--no-theory-binary"]) == 0
fig = figures[-1]
rings = [l for l in fig.axes[0].get_lines()
         if l.get_markerfacecolor() == "none" and l.get_markeredgecolor() == "red"]
check(len(rings) == 1 and len(rings[0].get_xdata()) == 1 and
      any("stalled" in t.get_text() for t in fig.axes[0].texts),
      "penetration: a stalled run ringed and counted on the throughput panel")
check(any("a seed stalled" in t for t in texts(fig)), "penetration: the legend explains the ring")

# ---- noise: the sigma = 0 limit is the paper's result, not the curves' end
d = os.path.join(work, "noise")
os.makedirs(d)
NOISE = ("point", "model.noise.scale", "model.noise.design", "policy", "encounters",
         "collision_rate", "collision_rate_lo", "collision_rate_hi", "dc_rate", "dc_rate_lo",
         "dc_rate_hi", "theory_collision_rate", "theory_dc_rate")
write_aggregate(os.path.join(d, "aggregate.csv"), ["model.noise.scale", "model.noise.design"],
                [dict(zip(NOISE, row.split(","))) for row in (
                    "0,0.05,aware,ta_ebp,4118,0.0015,0.0007,0.0032,0.357,0.342,0.371,0.002,0.37125",
                    "1,0.05,paper,ta_ebp,4307,0.0947,0.0863,0.1038,0.185,0.174,0.197,0.1,0.1875",
                    "2,0.1,aware,ta_ebp,4114,0.0015,0.0007,0.0032,0.356,0.342,0.371,0.002,0.37125",
                    "3,0.1,paper,ta_ebp,4307,0.0947,0.0863,0.1038,0.185,0.174,0.197,0.1,0.1875")])
with open(os.path.join(d, "sweep.json"), "w") as f:
    json.dump({"config": {"model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6,
                                    "likelihood": {"type": "linear", "s_max": 2.0},
                                    "noise": {"kind": "gaussian", "delta": 0.01}}},
               "replicates": 2}, f)
figures.clear()
assert plot.main([d, "--taebp", taebp]) == 0
fig = figures[-1]
dc_ax, coll_ax = fig.axes[0], fig.axes[1]
check(any("σ = 0" in t and "paper" in t for t in texts(fig)), "noise: the sigma = 0 point is in the legend")
for ax, metric, paper in ((dc_ax, "DC", 0.375), (coll_ax, "collision", 0.0)):
    zero = [l for l in ax.get_lines() if list(l.get_xdata()) == [0]]
    check(len(zero) == 1 and abs(zero[0].get_ydata()[0] - paper) < 1e-9,
          "noise: %s rate at sigma = 0 is the paper's %g" % (metric, paper))
    curves = [l for l in ax.get_lines() if len(l.get_xdata()) > 10]
    check(curves and all(min(l.get_xdata()) > 0 for l in curves),
          "noise: %s theory curves start at sigma > 0" % metric)
    styles = {(l.get_linestyle(), l.get_marker()) for l in ax.get_lines() if l.get_gid() == "simulated"}
    check(len(styles) == 2, "noise: the two designs told apart by line style (%s)" % styles)

# ---- learners (issue 42): one column per design against forgetting, and the
# frontier, DC against collisions, one panel per learner with the safe bound;
# the policies that read no design key drawn once per learner
d = os.path.join(work, "learners")
os.makedirs(d)
LEARN = ("point", "model.experience.forgetting", "model.experience.design", "policy", "encounters",
         "collision_rate", "collision_rate_lo", "collision_rate_hi", "dc_rate", "dc_rate_lo",
         "dc_rate_hi", "theory_collision_rate", "theory_dc_rate")
rows, point = [], 0
for rho in ("1", "0.95"):
    for design, (coll, dc) in (("robust", (0.0, 0.28)), ("guarded", (0.0, 0.35)), ("paper", (0.1, 0.19))):
        for policy, c, v in (("ta_ebp", coll, dc), ("full_reveal", 0.0, 0.2), ("random_nudge", 0.16, 0.17)):
            rows.append(dict(zip(LEARN, (point, rho, design, policy, 3000, c, max(0, c - 0.01), c + 0.01,
                                         v, v - 0.01, v + 0.01, c, v))))
        point += 1
write_aggregate(os.path.join(d, "aggregate.csv"), ["model.experience.forgetting", "model.experience.design"], rows)
with open(os.path.join(d, "sweep.json"), "w") as f:
    json.dump({"config": {"model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6}},
               "replicates": 2}, f)
figures.clear()
assert plot.main([d, "--no-theory-binary"]) == 0
frontier = figures[-1]
check(len(figures) >= 2, "learners: the study figure and the frontier (%d figures)" % len(figures))
panels = [ax for ax in frontier.axes if ax.get_title().startswith("ρ")]
check(len(panels) == 2, "learners frontier: one panel per learner (%s)" % [a.get_title() for a in panels])
for ax in panels:
    check(ax.get_xlabel() == "collisions per encounter" and ax.get_ylabel() == "DC per encounter",
          "learners frontier: axes named (%s / %s)" % (ax.get_xlabel(), ax.get_ylabel()))
    pts = [l for l in ax.get_lines() if l.get_gid() == "simulated"]
    check(len(pts) == 5, "learners frontier %s: ta_ebp per design + 2 policies drawn once (%d)"
          % (ax.get_title(), len(pts)))
    bound = [l for l in ax.get_lines() if list(l.get_xdata()) == [0.01, 0.01]]
    check(len(bound) == 1, "learners frontier %s: the safe bound at 0.01" % ax.get_title())
check(any("safe" in t for t in texts(frontier)), "learners frontier: the bound in the legend")
check(any("Random nudge" in t for t in texts(frontier)), "learners frontier: random_nudge labelled")

# ---- network throughput against demand: stalled runs marked, encounters per point,
# served = offered, the title inside the figure
d = os.path.join(work, "network_sweep")
os.makedirs(d)
rows = []
for point, flow in enumerate((100, 200, 300)):
    for policy, enc in (("sumo_native", 0), ("no_ebp", 40 * (point + 1)), ("ta_ebp", 37 * (point + 1))):
        stalled = 2 if (policy == "ta_ebp" and flow == 300) else 0
        rows.append({"point": point, "scenario.demand.flow": flow, "scenario.av_share": 0.5,
                     "policy": policy, "runs_ok": 3, "runs_failed": 0, "encounters": enc,
                     "encounters_per_hour": "" if policy == "sumo_native" else enc / 3 / (1200 / 3600.0),
                     "served_flow": "%d" % (16 * flow * (0.7 if stalled else 1)), "served_flow_sd": 5,
                     "time_loss_mean": "%g" % (20 + flow / 10), "time_loss_mean_sd": 1,
                     "waiting_to_depart_end": 0, "offered_flow": 16 * flow, "stalled": stalled})
write_aggregate(os.path.join(d, "aggregate.csv"), ["scenario.demand.flow", "scenario.av_share"], rows)
with open(os.path.join(d, "sweep.json"), "w") as f:
    json.dump({"config": {"scenario": {"kind": "network", "duration": 1200,
                                       "grid": {"columns": 4, "rows": 4, "attach_length": 100,
                                                "junction_type": "allway_stop"}}},
               "replicates": 3}, f)
figures.clear()
assert plot.main([d, "--no-theory-binary"]) == 0
fig = figures[-1]
flow_ax = fig.axes[0]
rings = [l for ax in fig.axes for l in ax.get_lines()
         if l.get_markerfacecolor() == "none" and l.get_markeredgecolor() == "red"]
check(len(rings) == 3 and all(list(l.get_xdata()) == [300] or abs(l.get_xdata()[0] - 300) < 40
                              for l in rings),
      "network: the stalled point (TA-EBP at 300 veh/h) ringed on each of the 3 panels")
notes = [t.get_text() for t in flow_ax.texts]
check("2/3 stalled" in notes, "network: the stalled point says 2 of its 3 seeds stalled")
per_hour = [ax for ax in fig.axes if ax.get_ylabel().startswith("encounters_per_hour")]
check(len(per_hour) == 1, "network: an encounters-per-hour panel")
check(any("encounters_per_hour: AV-HV encounters per measured hour" in " ".join(t.split())
          for t in texts(fig)), "network: the caption says what encounters_per_hour is")
from matplotlib.colors import to_hex  # noqa: E402
check(per_hour and plot._plot.style.policy_colour("sumo_native") not in {
    to_hex(l.get_color()) for l in per_hour[0].get_lines()
                                     if l.get_gid() == "simulated"},
      "network: no encounters-per-hour line for SUMO's own logic")
check(any("served = offered" in t for t in texts(fig)), "network: served = offered drawn and named")
check(any("a seed stalled" in t for t in texts(fig)), "network: the legend explains the rings")
check(flow_ax.get_ylim()[0] > 0, "network: served flow not from 0 (its differences visible)")
fig.canvas.draw()
title = fig._suptitle.get_window_extent(fig.canvas.get_renderer())
check(title.x0 >= 0 and title.x1 <= fig.bbox.width + 1 and title.y1 <= fig.bbox.height + 1,
      "network: the title fits inside the figure")

# ---- the map of a network run: a real run of a small grid
import subprocess  # noqa: E402

run = os.path.join(work, "grid_run")
r = subprocess.run([taebp, "run", os.path.join(source, "configs", "grid_throughput.yaml"), "--quiet",
                    "--out", run, "--set", "scenario.grid={columns: 3, rows: 3}",
                    "--set", "scenario.duration=600", "--set", "scenario.warmup=60",
                    "--set", "scenario.demand.flow=300", "--set", "policies=[sumo_native, no_ebp, ta_ebp]"],
                   capture_output=True, text=True)
check(r.returncode == 0, "map: the grid run finished (%s)" % r.stderr.strip()[-300:])
with open(os.path.join(run, "summary.json")) as f:
    summary = json.load(f)
figures.clear()
assert plot.main([run]) == 0
check(os.path.isfile(os.path.join(run, "network_map.png")), "map: network_map.png written")
fig = figures[-1]
panels = [ax for ax in fig.axes if ax.get_title()]
all_texts = texts(fig)
check(len(panels) == 2, "map: one panel per controller policy (no_ebp, ta_ebp)")
for ax, policy in zip(panels, ("no_ebp", "ta_ebp")):
    total = summary["policies"][policy]["encounters"]
    check(ax.get_title().startswith(("No EBP" if policy == "no_ebp" else "TA-EBP") + ": %d AV-HV encounter" % total),
          "map: %s's panel names its %d encounters" % (policy, total))
    # Every controlled junction is one marker, at its place in the net.
    offsets = [o for c in ax.collections if hasattr(c, "get_offsets") and
               c.__class__.__name__ == "PathCollection" for o in c.get_offsets()]
    check(len(offsets) == 9, "map: %s: 9 junction markers (got %d)" % (policy, len(offsets)))
    # The marker colour follows the sign of the queueing-delay change.
    base = {j["junction"]: plot.queueing_delay(j) for j in summary["policies"]["sumo_native"]["junctions"]}
    lanes, nodes = plot.read_net(os.path.join(run, "network.net.xml"))
    signs_ok = True
    compared = []
    ramp = matplotlib.colormaps["RdBu_r"]
    for c in ax.collections:
        if c.__class__.__name__ != "PathCollection":
            continue
        for (x, y), colour in zip(c.get_offsets(), c.get_facecolors()):
            jid = min(nodes, key=lambda k: (nodes[k][0] - x) ** 2 + (nodes[k][1] - y) ** 2)
            j = [q for q in summary["policies"][policy]["junctions"] if q["junction"] == jid][0]
            d, b = plot.queueing_delay(j), base.get(jid)
            if d is None or b is None or abs(d - b) < 1e-3:
                continue
            red, blue = colour[0], colour[2]
            signs_ok = signs_ok and ((red > blue) == (d > b))
            # the colour's place on the colour map (0: bluest, 1: reddest)
            place = min(range(256), key=lambda i: sum((a - q) ** 2 for a, q in
                                                      zip(ramp(i / 255.0)[:3], colour[:3])))
            compared.append((d - b, place))
    check(signs_ok and len(compared) >= 3,
          "map: %s: red where the delay grew, blue where it fell (%d junctions)" % (policy, len(compared)))
    check(all(rb1 <= rb2 + 1e-9 for c1, rb1 in compared for c2, rb2 in compared if c1 < c2),
          "map: %s: the colour runs with the delay change (more red, more delay)" % policy)
    check(any(t.get_text() == "N" for t in ax.texts), "map: %s: a north arrow" % policy)
    check(any(t.get_text().endswith(" m") for t in ax.texts), "map: %s: a scale bar in metres" % policy)
    check(ax.get_aspect() == 1.0, "map: %s: equal aspect (metres both ways)" % policy)
check(any("against SUMO native" in t for t in [a.get_ylabel() for a in fig.axes]),
      "map: the colour bar says what the colour is against")
check(any(t == "no encounter" for t in all_texts), "map: the legend explains the small markers")
check(fig._suptitle is not None and "Little's law" in fig._suptitle.get_text(),
      "map: the title says how the delay is measured")
top = fig._suptitle.get_window_extent(fig.canvas.get_renderer())
check(top.x0 >= 0 and top.x1 <= fig.bbox.width + 1, "map: the title fits inside the figure")

print("%d checks failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
