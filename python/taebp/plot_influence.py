#!/usr/bin/python3
"""The influence study's figure and table (issue 29, docs/influence.md).

usage: /usr/bin/python3 python/taebp/plot_influence.py OUT.png RUN_DIR... [--table OUT.md]

Each RUN_DIR is a `taebp run --out` folder of configs/influence.yaml (one
seed; runs of the same policy are pooled). Reads timeseries.csv (cumulative
counts every outputs.interval: the SUMO rates per interval and the mean-field
theory, the sum of the encounters' theory_dc / theory_collision),
encounters.csv (each HV's encounter number, for the first encounters) and
summary.json (long_run_theory_dc_rate / _collision_rate: the learned beliefs'
fixed point, persuasion/experience.h).

Figure: (a) DC rate and (b) collision rate per interval against simulated
time, SUMO pooled over the runs as points with 95 % Wilson intervals, the
mean field as a line, the long run dashed; (c) the DC rate by each HV's own
encounter number (1..40), SUMO pooled against the mean field: where the
"high start" of always_nudge is. Table (markdown): first hour, last hour
(SUMO pooled, 95 % interval), the last hour's mean field, the long run, and
whether the long run lies in the last hour's 99.9 % interval.
Runs with Debian's /usr/bin/python3 and python3-matplotlib.
"""

import csv
import json
import os
import sys
from collections import defaultdict


def _stats():
    """stats.py by its path (the one Wilson interval; runs without the built module)."""
    import importlib.util
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "stats.py")
    spec = importlib.util.spec_from_file_location("taebp_stats", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


_S = _stats()
Z999, wilson = _S.Z999, _S.wilson

COLORS = {"always_nudge": "#d62728", "no_trust": "#ff7f0e", "ta_ebp": "#1f77b4",
          "full_reveal": "#2ca02c", "no_ebp": "#7f7f7f"}
FIRST = 40  # encounters per HV in panel (c)


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def label_of(run_dir, policy):
    with open(os.path.join(run_dir, "config.yaml"), encoding="utf-8") as f:
        text = f.read()
    if policy == "ta_ebp" and "design: paper" in text:
        return "ta_ebp (paper's scheme)"
    if policy == "ta_ebp":
        return "ta_ebp (guarded)"
    return policy


def load(run_dirs):
    """Per label: interval rows pooled, long run, first-encounter tallies."""
    out = {}
    for d in run_dirs:
        summary = json.load(open(os.path.join(d, "summary.json"), encoding="utf-8"))
        series = defaultdict(list)
        for r in read_csv(os.path.join(d, "timeseries.csv")):
            series[r["policy"]].append(r)
        per_hv = defaultdict(list)
        for r in read_csv(os.path.join(d, "encounters.csv")):
            per_hv[(r["policy"], r["hv"])].append(r)
        for policy, rows in series.items():
            lab = label_of(d, policy)
            e = out.setdefault(lab, {"policy": policy, "bins": defaultdict(lambda: [0] * 5),
                                     "long_run": None, "first": defaultdict(lambda: [0, 0, 0.0]),
                                     "runs": 0})
            e["runs"] += 1
            rows.sort(key=lambda r: float(r["time"]))
            for a, b in zip(rows, rows[1:]):
                key = (float(a["time"]), float(b["time"]))
                acc = e["bins"][key]
                acc[0] += int(b["encounters"]) - int(a["encounters"])
                acc[1] += int(b["dc"]) - int(a["dc"])
                acc[2] += int(b["collisions"]) - int(a["collisions"])
                acc[3] += float(b["theory_dc"]) - float(a["theory_dc"])
                acc[4] += float(b["theory_collisions"]) - float(a["theory_collisions"])
            p = summary["policies"][policy]
            e["long_run"] = (p.get("long_run_theory_dc_rate"), p.get("long_run_theory_collision_rate"))
        for (policy, _hv), rows in per_hv.items():
            lab = label_of(d, policy)
            rows.sort(key=lambda r: float(r["time"]))
            for i, r in enumerate(rows[:FIRST]):
                t = out[lab]["first"][i]
                t[0] += 1
                t[1] += r["hv_action"] == "DC"
                t[2] += float(r["theory_dc"])
    return out


def rows_of_table(data):
    lines = ["| policy | runs | first hour DC [95 %] | first hour collisions [95 %] | "
             "last hour DC [95 %] | last hour collisions [95 %] | last hour mean field DC / coll. | "
             "long-run theory DC / coll. | long run in last hour's 99.9 % |",
             "|---|---|---|---|---|---|---|---|---|"]
    for lab, e in data.items():
        bins = sorted(e["bins"].items())
        per_hour = max(1, round(3600 / (bins[0][0][1] - bins[0][0][0])))

        def pool(chosen):
            n = dc = co = tdc = tco = 0
            for _, acc in chosen:
                n += acc[0]; dc += acc[1]; co += acc[2]; tdc += acc[3]; tco += acc[4]
            return n, dc, co, tdc, tco

        def fmt(k, n):
            lo, hi = wilson(k, n)
            return "%.3f [%.3f, %.3f]" % (k / n if n else float("nan"), lo, hi)

        f = pool(bins[:per_hour])  # the first hour's intervals
        l = pool(bins[-per_hour:])  # the last hour's
        lr_dc, lr_co = e["long_run"]
        inside = []
        for k, want in ((l[1], lr_dc), (l[2], lr_co)):
            lo, hi = wilson(k, l[0], Z999)
            inside.append(lo <= want <= hi)
        lines.append("| %s | %d | %s | %s | %s | %s | %.3f / %.3f | %.3f / %.3f | %s |" % (
            lab, e["runs"], fmt(f[1], f[0]), fmt(f[2], f[0]), fmt(l[1], l[0]), fmt(l[2], l[0]),
            l[3] / l[0], l[4] / l[0], lr_dc, lr_co,
            "DC %s, collisions %s (n = %d)" % ("yes" if inside[0] else "**no**",
                                               "yes" if inside[1] else "**no**", l[0])))
    return "\n".join(lines) + "\n"


def main(argv):
    table = None
    if "--table" in argv:
        i = argv.index("--table")
        table = argv[i + 1]
        argv = argv[:i] + argv[i + 2:]
    if len(argv) < 3:
        sys.exit(__doc__)
    png, runs = argv[1], argv[2:]
    data = load(runs)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(17, 5.2))
    styles = {}
    for lab, e in data.items():
        color = COLORS.get(e["policy"], "black")
        ls = ":" if "paper's" in lab else "-"
        marker = "s" if "paper's" in lab else "o"
        styles[lab] = (color, ls, marker)
        bins = sorted(e["bins"].items())
        x = [(a + b) / 2 / 3600 for (a, b), _ in bins]
        for ax, k, th, lr in ((axes[0], 1, 3, e["long_run"][0]), (axes[1], 2, 4, e["long_run"][1])):
            y = [acc[k] / acc[0] for _, acc in bins]
            ci = [wilson(acc[k], acc[0]) for _, acc in bins]
            ax.errorbar(x, y, yerr=[[yy - c[0] for yy, c in zip(y, ci)], [c[1] - yy for yy, c in zip(y, ci)]],
                        fmt=marker, color=color, ms=4, capsize=2, lw=1)
            ax.plot(x, [acc[th] / acc[0] for _, acc in bins], ls, color=color, lw=1.5)
            ax.axhline(lr, color=color, ls="--", lw=0.8, alpha=0.7)
        first = sorted(e["first"].items())
        xs = [i + 1 for i, _ in first]
        axes[2].plot(xs, [t[1] / t[0] for _, t in first], marker, color=color, ms=4)
        axes[2].plot(xs, [t[2] / t[0] for _, t in first], ls, color=color, lw=1.5)
    axes[0].set_title("(a) DC rate per 30 simulated minutes")
    axes[1].set_title("(b) collision rate per 30 simulated minutes")
    axes[2].set_title("(c) DC rate by each HV's own encounter number")
    for ax in axes[:2]:
        ax.set_xlabel("simulated time (h)")
    axes[0].set_ylabel("share of AV-HV encounters")
    axes[2].set_xlabel("the HV's encounter number (1 = its first)")
    for ax in axes:
        ax.set_ylim(-0.02, 1.02 if ax is axes[2] else 0.5)
        ax.grid(alpha=0.3)
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color=c, ls=ls, marker=m, label=lab) for lab, (c, ls, m) in styles.items()]
    handles += [Line2D([], [], color="k", marker="o", ls="none", label="SUMO, pooled over the runs (95 %)"),
                Line2D([], [], color="k", ls="-", label="mean field (exact expected learning path)"),
                Line2D([], [], color="k", ls="--", lw=0.8, label="long-run theory (fixed point)")]
    fig.legend(handles=handles, loc="lower center", ncol=4, fontsize=9, frameon=False)
    n_runs = max(e["runs"] for e in data.values())
    fig.suptitle("HVs who learn what a nudge meant (figure-8, 8 AVs + 8 HVs, lambda = 0.2, r = 3, "
                 "theta = 0.6, k = 20; up to %d seeds per policy)" % n_runs)
    fig.tight_layout(rect=(0, 0.1, 1, 0.95))
    fig.savefig(png, dpi=110)
    print("wrote", png)
    if table:
        with open(table, "w", encoding="utf-8") as f:
            f.write(rows_of_table(data))
        print("wrote", table)


if __name__ == "__main__":
    main(sys.argv)
