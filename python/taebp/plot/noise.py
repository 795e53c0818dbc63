"""The perception-noise preset: rates against the noise's sigma, the
noise-aware design beside the paper's s*."""

import os

from .common import EXTRA_COLOURS, number, save, style, warn


def plot_noise(plt, sweep, theory, out_dir):
    """DC and collision rate against the noise's sigma: aware design vs the paper's s*."""
    noise = sweep.model("noise", {}) or {}
    kind = noise.get("kind", "gaussian")
    delta = number(str(noise.get("delta", 0.01)))
    bias = number(str(noise.get("bias", 0.0))) or 0.0
    lam = sweep.model("prior_go", 0.2)
    trust = sweep.model("trust")
    assumed = sweep.model("assumed_trust")

    def design_of(r):
        return r.get("model.noise.design") or noise.get("design", "aware")

    series = []  # (design, policy)
    for r in sweep.rows:
        key = (design_of(r), r["policy"])
        if number(r.get("model.noise.scale")) is not None and key not in series:
            series.append(key)
    colours = {"aware": "#1f77b4", "paper": "#d62728"}
    labels = {"aware": "noise-aware s_δ", "paper": "paper's s*"}
    sigmas = sorted({number(r["model.noise.scale"]) for r in sweep.rows
                     if number(r.get("model.noise.scale")) is not None})
    dense = None
    if theory.available() and isinstance(trust, (int, float)):
        hi = max(sigmas) * 1.05
        grid = sorted(set([hi * i / 80 for i in range(1, 81)] + sigmas))
        extra = lambda sg: ("--noise", kind, "--noise-scale", repr(sg), "--noise-bias", repr(bias),
                            "--noise-delta", repr(delta))
        try:
            # The aware design gives up (always yields) where s_delta > s_max:
            # both sides of that sigma, so that the jump is drawn vertical.
            results = theory.many([(trust, assumed, extra(sg)) for sg in grid])
            edge = [g for g, d in zip(grid, results) if d["noise"]["aware"]["status"] != "ok"]
            if edge:
                first = min(edge)
                prev = max([g for g in grid if g < first] or [first])
                lo_, hi_ = prev, first
                for _ in range(30):
                    mid = (lo_ + hi_) / 2
                    ok = theory.one(trust, assumed, extra(mid))["noise"]["aware"]["status"] == "ok"
                    lo_, hi_ = (mid, hi_) if ok else (lo_, mid)
                grid = sorted(set(grid + [lo_, hi_]))
                results = theory.many([(trust, assumed, extra(sg)) for sg in grid])
            # sigma = 0 exactly is the paper (both designs nudge s*, no failure
            # budget spent): a point of its own, the curves start at sigma > 0.
            zero = theory.one(trust, assumed)["policies"]["ta_ebp"]
            dense = (grid, results, zero)
        except (RuntimeError, ValueError, KeyError) as e:
            warn("theory from taebp failed (%s): drawing the theory columns instead" % e)
    elif not isinstance(trust, (int, float)):
        warn("model.trust is a distribution: theory drawn through the theory columns")

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    panels = [(axes[0], "dc_rate", "DC rate (HV drives if clear)"),
              (axes[1], "collision_rate", "collision rate"),
              (axes[2], "collision_rate", "collision rate, noise-aware design (zoom)")]
    for k, (ax, metric, title) in enumerate(panels):
        for i, (design, policy) in enumerate(series):
            if k == 2 and design != "aware":
                continue
            colour = colours.get(design, EXTRA_COLOURS[i % len(EXTRA_COLOURS)])
            if len(set(p for _, p in series)) > 1:
                label = "%s, %s" % (style(policy, i)[1], labels.get(design, design))
            else:
                label = "%s, %s" % (style(policy, i)[1], labels.get(design, design))
            prs = sorted((r for r in sweep.rows if design_of(r) == design and r["policy"] == policy
                          and number(r.get("model.noise.scale")) is not None),
                         key=lambda r: number(r["model.noise.scale"]))
            if dense is not None and policy in ("ta_ebp", "population_mean"):
                if design == "aware":
                    ys = [d["noise"]["aware"][metric] for d in dense[1]]
                else:
                    ys = [d["noise"]["policies"]["ta_ebp"][metric] for d in dense[1]]
                ax.plot(dense[0], ys, "-", color=colour, lw=1.6, alpha=0.9)
            else:
                pts = [(number(r["model.noise.scale"]), number(r.get("theory_" + metric))) for r in prs]
                pts = [p for p in pts if p[1] is not None]
                if pts:
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color=colour, lw=1.6)
            xs, ys, lo_e, hi_e = [], [], [], []
            for r in prs:
                y = number(r.get(metric))
                if y is None:
                    continue
                lo_, hi_ = number(r.get(metric + "_lo")), number(r.get(metric + "_hi"))
                xs.append(number(r["model.noise.scale"]))
                ys.append(y)
                lo_e.append(max(0.0, y - lo_) if lo_ is not None else 0.0)
                hi_e.append(max(0.0, hi_ - y) if hi_ is not None else 0.0)
            if xs:
                dodge = (i - (len(series) - 1) / 2) * 0.004 * (max(sigmas) or 1) if k < 2 else 0
                ax.errorbar([x + dodge for x in xs], ys, yerr=[lo_e, hi_e], fmt="o", color=colour,
                            ms=5, capsize=3, lw=1, label=label if k == 0 else None)
        if dense is not None:
            ax.plot([0], [dense[2][metric]], "D", mfc="white", mec="k", ms=6, mew=1.3, clip_on=False,
                    zorder=5, label="σ = 0: the paper's result (both designs)" if k == 0 else None)
        if metric == "collision_rate" and delta is not None and lam is not None:
            ax.axhline(delta * lam, color="k", ls="--", lw=1)
            ax.annotate(" δλ = %g" % (delta * lam), xy=(0, delta * lam), xycoords=("axes fraction", "data"),
                        va="bottom", ha="left", fontsize=9)
        if dense is not None:
            gave_up = [g for g, d in zip(dense[0], dense[1]) if d["noise"]["aware"]["status"] == "unachievable"]
            if gave_up:
                ax.axvspan(min(gave_up), max(dense[0]), color="0.9", zorder=0)
                if k == 0:
                    ax.annotate(" s_δ > s_max:\n aware AV yields", xy=(min(gave_up), 0.6),
                                xycoords=("data", "axes fraction"), va="center", ha="left", fontsize=8)
        ax.set_title(title)
        ax.set_xlabel("noise σ of the HV's reading (m)")
        ax.set_ylabel("rate per AV-HV encounter")
        ax.set_xlim(-0.01 * max(sigmas), max(sigmas) * 1.05)
        ax.grid(alpha=0.3)
        if k < 2:
            ax.set_ylim(bottom=-0.005)
        else:
            zoom = [number(r.get("collision_rate_hi")) for r in sweep.rows
                    if design_of(r) == "aware" and number(r.get("collision_rate_hi")) is not None]
            ax.set_ylim(-0.0005, max([3 * (delta or 0.01) * (lam or 0.2)] + zoom) * 1.1)
    handles, lbls = axes[0].get_legend_handles_labels()
    from matplotlib.lines import Line2D
    handles += [Line2D([], [], color="k", lw=1.6), Line2D([], [], color="k", marker="o", ls="", ms=5),
                Line2D([], [], color="k", ls="--", lw=1)]
    lbls += ["theory (exact over the noise)", "simulation (95% CI)", "bound δλ"]
    fig.legend(handles, lbls, loc="lower center", ncol=len(lbls), frameon=False)
    ctx = sweep.context()
    fig.suptitle("Perception noise (%s, δ = %g)%s" % (kind, delta, (": " + ctx) if ctx else ""),
                 fontsize=11)
    fig.tight_layout(rect=(0, 0.08, 1, 0.95))
    path = os.path.join(out_dir, "noise_sigma.png")
    save(fig, path, dpi=120)
    plt.close(fig)
    return path
