"""Runs beyond the paper: learned trust (rates, regret) and dynamic trust
from the runs' time series."""

import csv
import json
import os

from .common import number, save, stats, style


class Runs:
    """Runs beyond the paper: a run directory, or the tasks of a sweep directory."""

    def __init__(self, where):
        self.dirs = []
        if os.path.isfile(os.path.join(where, "summary.json")):
            self.dirs = [where]
        elif os.path.isdir(os.path.join(where, "tasks")):
            tasks = os.path.join(where, "tasks")
            def order(name):
                try:
                    return tuple(int(x) for x in name.split("-"))
                except ValueError:
                    return (1 << 30, 0)
            self.dirs = [os.path.join(tasks, d) for d in sorted(os.listdir(tasks), key=order)
                         if not d.startswith(".")  # a run's staging folder (RunFolder)
                         and os.path.isfile(os.path.join(tasks, d, "timeseries.csv"))]
        self.summaries = []
        for d in self.dirs:
            with open(os.path.join(d, "summary.json")) as f:
                self.summaries.append(json.load(f))
        self.policies = []
        for s in self.summaries:
            for p in s.get("policies", {}):
                if p not in self.policies:
                    self.policies.append(p)

    def __bool__(self):
        return bool(self.dirs)

    def config(self):
        return self.summaries[0].get("provenance", {}).get("config", {}) if self.summaries else {}

    def csv(self, name):
        """[(run index, rows)] of one CSV per run."""
        out = []
        for i, d in enumerate(self.dirs):
            path = os.path.join(d, name)
            if os.path.isfile(path):
                with open(path, newline="") as f:
                    out.append((i, list(csv.DictReader(f))))
        return out

    def context(self):
        c = self.config()
        m, sc = c.get("model", {}), c.get("scenario", {})
        parts = []
        if m.get("prior_go") is not None:
            parts.append("λ = %g" % m["prior_go"])
        if m.get("collision_penalty") is not None:
            parts.append("r = %g" % m["collision_penalty"])
        t = m.get("trust")
        if isinstance(t, (int, float)):
            parts.append("θ0 = %g" % t)
        elif isinstance(t, dict) and t.get("dist") == "beta":
            parts.append("θ ~ Beta(%g, %g)" % (t.get("alpha"), t.get("beta")))
        if sc.get("avs") is not None and sc.get("kind", "figure8") == "figure8":
            parts.append("%d AVs + %d HVs" % (sc.get("avs"), sc.get("hvs")))
        n = len(self.dirs)
        parts.append("%d seed%s" % (n, "" if n == 1 else "s"))
        return ", ".join(parts)


def plot_learned(plt, runs, out_dir):
    """Per-hour DC and collision rates, and cumulative regret on a log axis."""
    encs = runs.csv("encounters.csv")
    hours = {}  # (policy, hour) -> [n, dc, collisions, oracle_dc_sum]
    last_hour = 0
    for _, rows in encs:
        for r in rows:
            h = int(float(r["time"]) // 3600)
            last_hour = max(last_hour, h)
            a = hours.setdefault((r["policy"], h), [0, 0, 0, 0.0])
            a[0] += 1
            a[1] += r["hv_action"] == "DC"
            a[2] += r["collision"] == "1"
            a[3] += number(r.get("oracle_dc")) or 0.0
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4), sharex=True)
    n_pol = len(runs.policies)
    for i, policy in enumerate(runs.policies):
        colour, label = style(policy, i)
        hs = sorted(h for p, h in hours if p == policy)
        for ax, k in ((axes[0], 1), (axes[1], 2)):
            xs, ys, lo_e, hi_e = [], [], [], []
            for h in hs:
                a = hours[(policy, h)]
                lo_, hi_ = stats.wilson(a[k], a[0])
                y = a[k] / a[0]
                xs.append(h + 0.5 + (i - (n_pol - 1) / 2) * 0.06)
                ys.append(y)
                lo_e.append(y - lo_)
                hi_e.append(hi_ - y)
            if xs:
                ax.errorbar(xs, ys, yerr=[lo_e, hi_e], fmt="-o", color=colour, ms=3.5, lw=1.2,
                            capsize=2, label=label if k == 1 else None)
        if policy == "ta_ebp_learned":
            xs = [h + 0.5 for h in hs]
            axes[0].plot(xs, [hours[(policy, h)][3] / hours[(policy, h)][0] for h in hs], "--",
                         color="k", lw=1.2, label="oracle's expected DC (learner's encounters)")
    axes[0].set_title("DC rate per simulated hour")
    axes[1].set_title("collision rate per simulated hour")
    for ax in axes:
        ax.set_xlabel("simulated time (h)")
        ax.set_ylabel("rate per AV-HV encounter")
        ax.set_ylim(bottom=-0.01)
        ax.grid(alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), frameon=False)
    fig.suptitle("Learned trust: " + runs.context() + " (95% intervals)", fontsize=11)
    fig.tight_layout(rect=(0, 0.08, 1, 0.95))
    rates_path = os.path.join(out_dir, "learned_rates.png")
    save(fig, rates_path, dpi=120)
    plt.close(fig)

    # Cumulative expected regret over the encounters (T), per run, on a log axis:
    # the learner's alone (log T growth is a straight line there), every
    # policy's on log-log axes (linear growth is a line of slope 1), and the
    # learner's failures against its posterior's prediction.
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.6))
    zero = []
    for i, policy in enumerate(runs.policies):
        colour, label = style(policy, i)
        curves = []
        for _, rows in encs:
            acc, curve = 0.0, []
            for r in rows:
                if r["policy"] == policy:
                    acc += number(r.get("regret")) or 0.0
                    curve.append(acc)
            if curve:
                curves.append(curve)
        if not curves:
            continue
        n = min(len(c) for c in curves)
        mean = [sum(c[t] for c in curves) / len(curves) for t in range(n)]
        if max(abs(v) for v in mean) < 1e-9:
            zero.append(label)
            continue
        panels = [axes[1]] + ([axes[0]] if policy == "ta_ebp_learned" else [])
        for ax in panels:
            if len(curves) > 1:
                for c in curves:
                    ax.plot(range(1, len(c) + 1), c, color=colour, lw=0.7, alpha=0.35)
            ax.plot(range(1, n + 1), mean, color=colour, lw=1.8,
                    label=label + (" (mean of %d seeds)" % len(curves) if len(curves) > 1 else ""))
        if policy == "ta_ebp_learned":
            for j, (_, rows) in enumerate(encs):
                fails, expected, nudges, fx, ex, x = 0, 0.0, 0, [], [], []
                for r in rows:
                    if r["policy"] != policy:
                        continue
                    if (number(r.get("commanded_nudge")) or 0) > 0:
                        nudges += 1
                        fails += r["hv_action"] == "DR"
                        expected += number(r.get("failure_probability")) or 0.0
                        x.append(nudges)
                        fx.append(fails)
                        ex.append(expected)
                if x:
                    axes[2].step(x, fx, where="post", color=colour, lw=1.4,
                                 label="failures (nudged, then DR)" if j == 0 else None)
                    axes[2].plot(x, ex, "--", color="k", lw=1.2,
                                 label="expected (Σ posterior failure probability)" if j == 0 else None)
                    delta = runs.config().get("model", {}).get("learning", {}) or {}
                    delta = delta.get("delta", 0.01)
                    axes[2].plot(x, [delta * v for v in x], ":", color="0.4", lw=1.2,
                                 label="δ × nudges (the budget)" if j == 0 else None)
    ends = [l.get_xdata()[-1] for l in axes[1].get_lines()]
    if ends:
        t_max = max(ends)
        ys = [l.get_ydata()[-1] for l in axes[1].get_lines()]
        ref = min(ys) / t_max / 3  # a line of slope 1 below every curve's end
        axes[1].plot([1, t_max], [ref, ref * t_max], ":", color="0.4", lw=1, label="∝ T (linear growth)")
    axes[0].set_xscale("log")
    axes[0].set_xlabel("AV-HV encounters T (log scale)")
    axes[0].set_ylabel("cumulative expected regret")
    axes[0].set_title("ta_ebp_learned: regret vs the oracle")
    axes[0].set_ylim(bottom=0)
    axes[0].grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8, loc="upper left")
    axes[1].set_xscale("log")
    axes[1].set_yscale("log")
    axes[1].set_xlabel("AV-HV encounters T (log scale)")
    axes[1].set_ylabel("cumulative expected regret (log scale)")
    axes[1].set_title("every policy (log-log)")
    axes[1].grid(alpha=0.3, which="both")
    if zero:
        axes[1].plot([], [], " ", label="%s: regret 0 (the oracle)" % ", ".join(zero))
    axes[1].legend(fontsize=8, loc="upper left")
    axes[2].set_xscale("log")
    axes[2].set_xlabel("nudges of ta_ebp_learned (log scale)")
    axes[2].set_ylabel("cumulative count")
    axes[2].set_title("ta_ebp_learned: failures to persuade")
    axes[2].grid(alpha=0.3, which="both")
    axes[2].legend(fontsize=8, loc="upper left")
    fig.suptitle("Learned trust, regret growth: " + runs.context(), fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    regret_path = os.path.join(out_dir, "learned_regret.png")
    save(fig, regret_path, dpi=120)
    plt.close(fig)
    return [rates_path, regret_path]


def plot_dynamic(plt, runs, out_dir):
    """Mean trust over time per policy, the mean-field path and the long-run trust."""
    series = runs.csv("timeseries.csv")
    fig, ax = plt.subplots(figsize=(9, 5))
    for i, policy in enumerate(runs.policies):
        colour, label = style(policy, i)
        per_run = []
        for _, rows in series:
            pts = [(float(r["time"]) / 3600, number(r["mean_trust"]), number(r.get("mean_field_trust")))
                   for r in rows if r["policy"] == policy and number(r["mean_trust"]) is not None]
            if pts:
                per_run.append(pts)
        if not per_run:
            continue
        many = len(per_run) > 1
        for pts in per_run:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=colour,
                    lw=0.7 if many else 1.8, alpha=0.35 if many else 1.0,
                    label=None if many else label + " (simulation)")
        n = min(len(p) for p in per_run)
        xs = [per_run[0][t][0] for t in range(n)]
        if many:
            ax.plot(xs, [sum(p[t][1] for p in per_run) / len(per_run) for t in range(n)], color=colour,
                    lw=2, label=label + " (simulation, mean of seeds)")
        mf = [(per_run[0][t][0], sum(p[t][2] for p in per_run) / len(per_run)) for t in range(n)
              if all(p[t][2] is not None for p in per_run)]
        if mf:
            ax.plot([p[0] for p in mf], [p[1] for p in mf], "--", color=colour, lw=1.3,
                    label=label + " (mean field)")
        longs = [s["policies"][policy].get("expected_long_run_trust") for s in runs.summaries
                 if policy in s.get("policies", {})]
        longs = [l for l in longs if l is not None]
        if longs:
            y = longs[0]
            ax.axhline(y, color=colour, ls=":", lw=1.4)
            ax.annotate("long run %.3f" % y, xy=(1.0, y), xycoords=("axes fraction", "data"),
                        xytext=(-4, 3), textcoords="offset points", ha="right", va="bottom",
                        fontsize=8, color=colour)
    c = runs.config()
    d = (c.get("model", {}) or {}).get("trust_dynamics") or {}
    ax.set_xlabel("simulated time (h)")
    ax.set_ylabel("mean trust of the HVs")
    ax.set_ylim(0, 1.05)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower left", ncol=2)
    ax.set_title("Dynamic trust: %s; w_s = %g, w_f = %g, ρ = %g, α0+β0 = %g" % (
        runs.context(), d.get("success_weight", 1), d.get("failure_weight", 1),
        d.get("forgetting", 0), d.get("strength", 10)), fontsize=10)
    fig.tight_layout()
    path = os.path.join(out_dir, "dynamic_trust.png")
    save(fig, path, dpi=120)
    plt.close(fig)
    return path


def plot_runs(plt, runs, out_dir):
    written = []
    if "ta_ebp_learned" in runs.policies:
        written += plot_learned(plt, runs, out_dir)
    if (runs.config().get("model", {}) or {}).get("trust_dynamics"):
        written.append(plot_dynamic(plt, runs, out_dir))
    return written
