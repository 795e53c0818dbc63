#!/usr/bin/python3
"""ctest for what tools/plot draws (not only that it writes a PNG): the figures
are captured before saving and their texts, legends and artists inspected.
  mismatch heat map: theta-hat named on the axis and in the legend, the theta*
    line in the legend, every cell note with a halo, white on dark cells;
  penetration: collisions beside throughput, error bars on the waits, the
    seed count, the loop length and the track caveat;
  noise: sigma = 0 (the paper's rates) a point of its own, the theory curves
    for sigma > 0 only (they do not meet sigma = 0 at the noisy values).
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
fig = figures[-1]
ax = fig.axes[0]
all_text = texts(fig)
check(r"\hat{\theta}" in ax.get_ylabel(), "mismatch: the y axis names theta-hat in mathtext")
legend = [t.get_text() for t in ax.get_legend().get_texts()]
check(any(r"\theta^*" in t and "0.25" in t for t in legend), "mismatch: the theta* line is in the legend")
check(any(r"\hat{\theta} = \theta$" in t for t in legend), "mismatch: the diagonal is in the legend")
notes = [t for t in ax.texts if t.get_text() in ("n/a",) or t.get_text().replace(".", "").isdigit()]
check(len(notes) >= 9, "mismatch: every cell annotated (%d notes)" % len(notes))
check(all(t.get_path_effects() for t in notes), "mismatch: every cell note has a halo")
mesh = ax.collections[0]
dark = [t for t in notes if t.get_text() != "n/a" and mesh.norm(float(t.get_text())) > 0.45]
check(dark and all(t.get_color() == "white" for t in dark), "mismatch: white notes on dark cells")
check(not any(t.get_text().startswith("θ̂") for t in ax.texts), "mismatch: no annotation over the cells")

# ---- penetration
d = sweep_dir("penetration", "aggregate_penetration.csv",
              {"config": {"model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6},
                          "scenario": {"avs": 8, "hvs": 8, "duration": 1800, "loop_length": 80}},
               "replicates": 3})
with open(os.path.join(d, "aggregate.csv")) as f:
    lines = f.read().splitlines()
# A sweep of this version has wait_mean_sd; add it to the older fixture.
lines = [lines[0] + ",wait_mean_sd"] + [l + ",0.25" for l in lines[1:]]
with open(os.path.join(d, "aggregate.csv"), "w") as f:
    f.write("\n".join(lines) + "\n")
figures.clear()
assert plot.main([d, "--no-theory-binary"]) == 0
fig = figures[-1]
all_text = texts(fig)
titles = [a.get_title() for a in fig.axes]
check(len(fig.axes) == 4, "penetration: four panels")
check(any("collisions per AV-HV encounter" in t for t in titles), "penetration: collisions beside throughput")
check(fig.axes[2].containers, "penetration: collision rates with intervals")
check(any("3 seeds" in t for t in titles), "penetration: the seed count in the titles")
wait_ax = [a for a in fig.axes if "wait" in a.get_title()][0]
check(wait_ax.containers and all(c.has_yerr for c in wait_ax.containers),
      "penetration: error bars on the waits")
check(any("80 m loops" in t for t in all_text), "penetration: the loop length in the title")
check(any("Caveat" in t and "track" in t for t in all_text), "penetration: the track caveat")

# ---- noise: the sigma = 0 limit is the paper's result, not the curves' end
d = os.path.join(work, "noise")
os.makedirs(d)
cols = ("point,model.noise.scale,model.noise.design,policy,encounters,collision_rate,collision_rate_lo,"
        "collision_rate_hi,dc_rate,dc_rate_lo,dc_rate_hi,theory_collision_rate,theory_dc_rate")
rows = ["0,0.05,aware,ta_ebp,4118,0.0015,0.0007,0.0032,0.357,0.342,0.371,0.002,0.37125",
        "1,0.05,paper,ta_ebp,4307,0.0947,0.0863,0.1038,0.185,0.174,0.197,0.1,0.1875",
        "2,0.1,aware,ta_ebp,4114,0.0015,0.0007,0.0032,0.356,0.342,0.371,0.002,0.37125",
        "3,0.1,paper,ta_ebp,4307,0.0947,0.0863,0.1038,0.185,0.174,0.197,0.1,0.1875"]
with open(os.path.join(d, "aggregate.csv"), "w") as f:
    f.write("\n".join([cols] + rows) + "\n")
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

print("%d checks failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
