"""The figure-8 studies' presets: trust (theory lines, theta*), mismatch
(a heat map), penetration (throughput beside collisions)."""

import os

from .common import add_stall_legend, die, mark_stalled, number, save, style, warn


def plot_trust(plt, sweep, theory, out_dir):
    """DC and collision rate against theta; theory lines, simulation points."""
    rows = [r for r in sweep.rows if number(r.get("model.trust")) is not None]
    others = [k for k in sweep.keys if k != "model.trust"]
    if others:
        warn("also swept: %s; their points share the θ axis" % ", ".join(others))
    thetas = sorted({number(r["model.trust"]) for r in rows})
    # As ModelConfig::Knowledge(): unset means "assumed" when assumed_trust is given.
    knowledge = sweep.model("trust_knowledge") or (
        "assumed" if sweep.model("assumed_trust") is not None else "exact")
    assumed = sweep.model("assumed_trust") if knowledge == "assumed" else None

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3), sharex=True)
    panels = (("dc_rate", "DC rate (HV drives if clear)"), ("collision_rate", "collision rate"))

    theta_star = None
    dense = None
    if theory.available():
        lo, hi = min(thetas + [0.0]), max(thetas + [1.0])
        grid = [lo + (hi - lo) * i / 40 for i in range(41)]
        try:
            first = theory.one(grid[len(grid) // 2], assumed)
            theta_star = first["theta_star"]
            # The curves jump at theta* (TA-EBP starts persuading), at the
            # assumed trust and at theta = 1 (No Trust designs for 1): both
            # sides of each (outside the library's tie tolerance, ~1e-9), so
            # that the jumps are drawn vertical.
            for jump in (theta_star, assumed, 1.0):
                if jump is not None and lo < jump <= hi:
                    grid += [jump - 1e-6] + ([jump + 1e-6] if jump < hi else [])
            grid = sorted(set(grid))
            dense = (grid, theory.many([(t, assumed) for t in grid]))
        except (RuntimeError, ValueError, KeyError) as e:
            warn("theory from taebp failed (%s): drawing the theory columns instead" % e)
            dense = None

    for ax, (metric, title) in zip(axes, panels):
        for i, policy in enumerate(sweep.policies):
            colour, label = style(policy, i)
            prs = sorted((r for r in rows if r["policy"] == policy), key=lambda r: number(r["model.trust"]))
            if not prs:
                continue
            # Theory: a line.
            if dense is not None and policy in dense[1][0].get("policies", {}):
                ax.plot(dense[0], [d["policies"][policy][metric] for d in dense[1]], "-",
                        color=colour, lw=1.6, alpha=0.9)
            else:
                pts = [(number(r["model.trust"]), number(r.get("theory_" + metric))) for r in prs]
                pts = [p for p in pts if p[1] is not None]
                if pts:
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color=colour, lw=1.6, alpha=0.9)
            # Simulation: points with the 95% interval.
            xs, ys, lo_err, hi_err = [], [], [], []
            for r in prs:
                y = number(r.get(metric))
                if y is None:
                    continue
                lo_, hi_ = number(r.get(metric + "_lo")), number(r.get(metric + "_hi"))
                xs.append(number(r["model.trust"]))
                ys.append(y)
                lo_err.append(max(0.0, y - lo_) if lo_ is not None else 0.0)
                hi_err.append(max(0.0, hi_ - y) if hi_ is not None else 0.0)
            if xs:
                # Policies side by side around each theta, so that their
                # intervals do not hide each other.
                dodge = (i - (len(sweep.policies) - 1) / 2) * 0.006 * (max(thetas) - min(thetas) or 1)
                ax.errorbar([x + dodge for x in xs], ys, yerr=[lo_err, hi_err], fmt="o", color=colour,
                            ms=5, capsize=3, lw=1, label=label)
        label = None
        if theta_star is not None:
            at, label = theta_star, " θ* = %.3g" % theta_star
        else:
            # Without taebp: theta* lies between the largest swept theta where
            # TA-EBP does not persuade and the smallest where it does.
            ta = [(number(r["model.trust"]), (number(r.get("theory_dc_rate")) or 0) > 0)
                  for r in rows if r["policy"] == "ta_ebp"]
            yes = [t for t, p in ta if p]
            if yes:
                at = min(yes)
                no = [t for t, p in ta if not p and t < at]
                label = (" θ* in (%.3g, %.3g]" % (max(no), at)) if no else (" θ* ≤ %.3g" % at)
        if label is not None:
            ax.axvline(at, color="k", ls="--", lw=1)
            ax.annotate(label, xy=(at, 1), xycoords=("data", "axes fraction"),
                        va="top", ha="left", fontsize=9)
        ax.set_title(title)
        ax.set_xlabel("HV trust θ")
        ax.set_ylabel("rate per AV-HV encounter")
        ax.set_ylim(bottom=-0.02)
        ax.grid(alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    from matplotlib.lines import Line2D
    handles += [Line2D([], [], color="k", lw=1.6), Line2D([], [], color="k", marker="o", ls="", ms=5)]
    labels += ["theory", "simulation (95% CI)"]
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), frameon=False)
    ctx = sweep.context()
    fig.suptitle("Trust sweep" + (": " + ctx if ctx else ""), fontsize=11)
    fig.tight_layout(rect=(0, 0.08, 1, 0.95))
    path = os.path.join(out_dir, "trust_dc_collision.png")
    save(fig, path, dpi=130)
    plt.close(fig)
    return path


def plot_mismatch(plt, sweep, theory, out_dir, policy="ta_ebp"):
    """Heat map of the collision rate over (true theta, assumed theta_hat)."""
    import matplotlib.colors as mcolors
    rows = [r for r in sweep.rows if r["policy"] == policy]
    if not rows:
        policy = sweep.policies[0]
        warn("no ta_ebp rows: the heat map shows %s" % policy)
        rows = [r for r in sweep.rows if r["policy"] == policy]
    xs = sorted({number(r["model.trust"]) for r in rows if number(r["model.trust"]) is not None})
    ys = sorted({number(r["model.assumed_trust"]) for r in rows
                 if number(r["model.assumed_trust"]) is not None})
    if not xs or not ys:
        die("mismatch: no numeric model.trust / model.assumed_trust values")
    cells = {}
    theory_cells = {}
    for r in rows:
        x, y = number(r["model.trust"]), number(r["model.assumed_trust"])
        if x is None or y is None:
            continue
        cells[(x, y)] = number(r.get("collision_rate"))
        theory_cells[(x, y)] = number(r.get("theory_collision_rate"))

    def edges(v):
        if len(v) == 1:
            return [v[0] - 0.05, v[0] + 0.05]
        mids = [(a + b) / 2 for a, b in zip(v, v[1:])]
        return [v[0] - (mids[0] - v[0])] + mids + [v[-1] + (v[-1] - mids[-1])]

    ex, ey = edges(xs), edges(ys)
    import numpy as np
    z = np.full((len(ys), len(xs)), np.nan)
    for (x, y), v in cells.items():
        if v is not None:
            z[ys.index(y), xs.index(x)] = v
    fig, ax = plt.subplots(figsize=(7.6, 6.4))
    cmap = plt.get_cmap("magma_r").copy()
    cmap.set_bad("#d9d9d9")
    vmax = max(0.05, np.nanmax(z) if np.isfinite(z).any() else 0.05)
    mesh = ax.pcolormesh(ex, ey, np.ma.masked_invalid(z), cmap=cmap,
                         norm=mcolors.Normalize(vmin=0, vmax=vmax), shading="flat")
    fig.colorbar(mesh, ax=ax, label="simulated collision rate per encounter (%s)" % style(policy, 0)[1])
    import matplotlib.patheffects as pe
    for (x, y), v in cells.items():
        text = "n/a" if v is None else "%.2f" % v
        dark = v is not None and mesh.norm(v) > 0.45
        # White on dark cells, black on light ones, each with a halo of the
        # other colour so that it stays readable on any cell.
        ax.text(x, y, text, ha="center", va="center", fontsize=7.5 if len(xs) > 8 else 9,
                color="white" if dark else "black",
                path_effects=[pe.withStroke(linewidth=2, foreground="black" if dark else "white")])

    # Theory: the cells where the library predicts collisions (the theory
    # column, the runner's own prediction for each point; taebp theory per
    # cell when the column is empty), outlined along the cell edges.
    predicted = {k: v > 1e-12 for k, v in theory_cells.items() if v is not None}
    theta_star = None
    if theory.available():
        try:
            missing = [k for k in cells if k not in predicted]
            for (x, y), d in zip(missing, theory.many(missing)):
                predicted[(x, y)] = d["policies"][policy]["collision_rate"] > 1e-12
            theta_star = theory.one(xs[0], ys[0])["theta_star"]
        except (RuntimeError, ValueError, KeyError) as e:
            warn("theory from taebp failed (%s)" % e)
    for i, x in enumerate(xs):
        for j, y in enumerate(ys):
            if not predicted.get((x, y)):
                continue
            # Draw each cell edge that borders a cell outside the region.
            if not predicted.get((xs[i - 1], y)) if i > 0 else True:
                ax.plot([ex[i], ex[i]], [ey[j], ey[j + 1]], color="#00b4d8", lw=2.5)
            if not predicted.get((xs[i + 1], y)) if i + 1 < len(xs) else True:
                ax.plot([ex[i + 1], ex[i + 1]], [ey[j], ey[j + 1]], color="#00b4d8", lw=2.5)
            if not predicted.get((x, ys[j - 1])) if j > 0 else True:
                ax.plot([ex[i], ex[i + 1]], [ey[j], ey[j]], color="#00b4d8", lw=2.5)
            if not predicted.get((x, ys[j + 1])) if j + 1 < len(ys) else True:
                ax.plot([ex[i], ex[i + 1]], [ey[j + 1], ey[j + 1]], color="#00b4d8", lw=2.5)
    lo, hi = min(ex[0], ey[0]), max(ex[-1], ey[-1])
    # The reference lines in a colour visible on light and dark cells alike.
    ref = "#2a9d8f"
    ax.plot([lo, hi], [lo, hi], color=ref, lw=1.4, ls=":")
    if theta_star is not None:
        ax.axhline(theta_star, color=ref, lw=1.4, ls="--")
    ax.set_xlim(ex[0], ex[-1])
    ax.set_ylim(ey[0], ey[-1])
    ax.set_xlabel(r"true HV trust $\theta$")
    ax.set_ylabel(r"trust $\hat{\theta}$ the AV designs for")
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color="#00b4d8", lw=2.5), Line2D([], [], color=ref, lw=1.4, ls=":")]
    labels = [r"theory: collisions ($\hat{\theta} > \theta$ and $\hat{\theta} \geq \theta^*$)",
              r"$\hat{\theta} = \theta$"]
    if theta_star is not None:
        handles.append(Line2D([], [], color=ref, lw=1.4, ls="--"))
        labels.append(r"$\hat{\theta} = \theta^* = %.3g$" % theta_star)
    ax.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, -0.09), ncol=len(labels),
              frameon=False, fontsize=9)
    ctx = sweep.context()
    ax.set_title("Trust mismatch" + (": " + ctx if ctx else ""), fontsize=10)
    fig.tight_layout()
    path = os.path.join(out_dir, "mismatch_collision_heatmap.png")
    save(fig, path, dpi=130)
    plt.close(fig)
    return path


# A stalled run's mark, the same on every throughput picture: a red ring around
# the point and, with `note` (an offset in points), "k/n stalled" beside it.


def plot_penetration(plt, sweep, out_dir):
    """Throughput, collisions and mean wait against the AV share."""
    def share(r):
        avs = number(r.get("scenario.avs")) if "scenario.avs" in sweep.keys else sweep.scenario("avs")
        hvs = number(r.get("scenario.hvs")) if "scenario.hvs" in sweep.keys else sweep.scenario("hvs")
        if avs is None or hvs is None or avs + hvs <= 0:
            return None
        return avs / (avs + hvs)

    reps = sweep.info.get("replicates") if isinstance(sweep.info, dict) else None
    seeds = ("%d seeds" % reps) if reps else "seeds"
    if "wait_mean_sd" not in sweep.header:
        warn("aggregate.csv has no wait_mean_sd column (an older sweep): waits without error bars")
    fig, axes = plt.subplots(1, 4, figsize=(17, 4.6), sharex=True)
    stalls, stalled_seen = sweep.stalls(), False
    for i, policy in enumerate(sweep.policies):
        colour, label = style(policy, i)
        prs = [(share(r), r) for r in sweep.rows if r["policy"] == policy]
        prs = sorted(((p, r) for p, r in prs if p is not None), key=lambda t: t[0])
        if not prs:
            continue
        x = [p for p, _ in prs]

        def col(name):
            return [number(r.get(name)) for _, r in prs]

        def line(ax, ys, **kw):
            pts = [(a, b) for a, b in zip(x, ys) if b is not None]
            if pts:
                ax.plot([a for a, _ in pts], [b for _, b in pts], **kw)

        def bars(ax, ys, sds, **kw):
            pts = [(a, b, s or 0.0) for a, b, s in zip(x, ys, sds) if b is not None]
            if pts:
                ax.errorbar([p[0] for p in pts], [p[1] for p in pts], yerr=[p[2] for p in pts],
                            fmt="-o", color=colour, ms=4, capsize=3, lw=1.5, **kw)

        bars(axes[0], col("throughput_all"), col("throughput_all_sd"), label=label)
        # Stalled runs: a red ring and how many of the point's seeds stalled.
        for (xv, r), yv in zip(prs, col("throughput_all")):
            st = stalls.get((int(r["point"]), policy))
            if yv is not None and st and st[0] > 0:
                stalled_seen = True
                mark_stalled(axes[0], xv, yv, st, note=(6, -10))
        line(axes[1], col("throughput_av"), color=colour, marker="o", ms=4, lw=1.5, ls="-")
        line(axes[1], col("throughput_hv"), color=colour, marker="s", ms=4, lw=1.5, ls="--")
        # Collisions per AV-HV encounter with the pooled 95% Wilson interval
        # (no point where a mix has no AV-HV encounter: all-HV, all-AV).
        rate, lo, hi = col("collision_rate"), col("collision_rate_lo"), col("collision_rate_hi")
        pts = [(a, y, y - l, h - y) for a, y, l, h in zip(x, rate, lo, hi)
               if y is not None and l is not None and h is not None]
        if pts:
            # Policies side by side, so that equal rates (e.g. 0) stay visible.
            dodge = (i - (len(sweep.policies) - 1) / 2) * 0.012
            axes[2].errorbar([p[0] + dodge for p in pts], [p[1] for p in pts],
                             yerr=[[max(0.0, p[2]) for p in pts], [max(0.0, p[3]) for p in pts]],
                             fmt="-o", color=colour, ms=4, capsize=3, lw=1.5)
        bars(axes[3], col("wait_mean"), col("wait_mean_sd"))
    axes[0].set_title("all crossings (± sd over %s)" % seeds)
    axes[0].set_ylabel("crossings per hour")
    axes[1].set_title("AV (solid) and HV (dashed) crossings")
    axes[1].set_ylabel("crossings per hour")
    axes[2].set_title("collisions per AV-HV encounter (95% CI)")
    axes[2].set_ylabel("collision rate")
    axes[3].set_title("mean stop-line wait (± sd over %s)" % seeds)
    axes[3].set_ylabel("s")
    for ax in axes:
        ax.set_xlabel("AV penetration  avs / (avs + hvs)")
        ax.grid(alpha=0.3)
        ax.set_ylim(bottom=0)
    axes[2].set_ylim(bottom=-0.01)  # rates of exactly 0 stay visible above the axis
    handles, labels = axes[0].get_legend_handles_labels()
    if stalled_seen:
        add_stall_legend(handles, labels)
    fig.legend(handles, labels, loc="lower center", ncol=max(1, len(labels)), frameon=False,
               bbox_to_anchor=(0.5, 0.07))
    ctx = sweep.context()
    loop = sweep.scenario("loop_length")
    track = ("%g m loops of the figure-8" % loop) if loop else "the figure-8"
    fig.suptitle("AV penetration on %s" % track + (": " + ctx if ctx else ""), fontsize=11)
    fig.text(0.5, 0.015,
             "Caveat: crossings per hour are this small track's (16 vehicles on two short loops; "
             "README, Penetration). TA-EBP's encounters take longer (the nudge, the confirmation "
             "delay): a few per cent fewer crossings than No EBP; read No Trust's throughput "
             "beside its collisions.",
             ha="center", va="bottom", fontsize=9, style="italic", wrap=True)
    fig.tight_layout(rect=(0, 0.13, 1, 0.95))
    path = os.path.join(out_dir, "penetration_throughput.png")
    save(fig, path, dpi=130)
    plt.close(fig)
    return path
