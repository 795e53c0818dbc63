"""The network demand presets: served flow, delay and the demand left
waiting against the offered demand; AV and HV delays apart."""

import math
import os

from .common import add_stall_legend, mark_stalled, number, save, stats, style


def plot_network(plt, sweep, out_dir):
    """Served flow, delay and the demand left waiting against the offered demand
    (generated demand's flow per fringe edge, or the route files' scale)."""
    flow_key = "scenario.demand.flow" if "scenario.demand.flow" in sweep.keys else "scenario.routes_scale"
    share_key = "scenario.av_share" if "scenario.av_share" in sweep.keys else None
    shares = sorted({number(r.get(share_key)) for r in sweep.rows} - {None}) if share_key else [None]
    grid = sweep.scenario("grid") or {}
    entries = 2 * (grid.get("columns", 0) + grid.get("rows", 0)) if grid.get("attach_length", 0) else None
    metrics = [("served_flow", "served_flow_sd", "served flow (veh/h)"),
               ("time_loss_mean", "time_loss_mean_sd", "mean delay per trip (s)"),
               ("waiting_to_depart_end", None, "vehicles waiting to depart (end)")]
    width = max(8.0, 3.6 * len(shares) + 1)
    fig, axes = plt.subplots(len(metrics), len(shares), figsize=(width, 9),
                             sharex=True, squeeze=False)
    stalls = sweep.stalls()
    stalled_seen = [False]
    for c, share in enumerate(shares):
        for i, policy in enumerate(sweep.policies):
            colour, label = style(policy, i)
            rows = [r for r in sweep.rows if r["policy"] == policy and
                    (share_key is None or number(r.get(share_key)) == share)]
            rows = sorted(((number(r.get(flow_key)), r) for r in rows if number(r.get(flow_key)) is not None),
                          key=lambda t: t[0])
            if not rows:
                continue
            x = [f for f, _ in rows]
            for k, (col, sd_col, _) in enumerate(metrics):
                ys = [number(r.get(col)) for _, r in rows]
                sds = [number(r.get(sd_col)) or 0.0 if sd_col else 0.0 for _, r in rows]
                pts = [(a, b, e) for a, b, e in zip(x, ys, sds) if b is not None]
                if pts:
                    axes[k][c].errorbar([p[0] for p in pts], [p[1] for p in pts],
                                        yerr=[p[2] for p in pts], fmt="-o", color=colour, ms=4,
                                        capsize=3, lw=1.5, label=label)
                # Stalled runs: a ring around the point on every panel, the count beside it.
                for (f, r), yv in zip(rows, ys):
                    st = stalls.get((int(r["point"]), policy))
                    if yv is None or not st or st[0] == 0:
                        continue
                    stalled_seen[0] = True
                    mark_stalled(axes[k][c], f, yv, st, va="top",
                                 note=(7, -4 - 9 * i) if k == 0 else None)
            # The AV-HV encounters behind each point (pooled over its seeds): a
            # row per controller policy along the foot of the served-flow panel,
            # in the policy's colour (none where no AV-HV pair met).
            if policy != "sumo_native":
                row = sum(1 for q in sweep.policies[:i] if q != "sumo_native")
                for f, r in rows:
                    enc = number(r.get("encounters"))
                    if enc:
                        axes[0][c].text(f, 0.03 + 0.065 * row, "%d" % enc, ha="center",
                                        va="bottom", fontsize=6, color=colour,
                                        transform=axes[0][c].get_xaxis_transform())
        xs = sorted({number(r.get(flow_key)) for r in sweep.rows} - {None})
        if entries and flow_key == "scenario.demand.flow":
            axes[0][c].plot(xs, [entries * f for f in xs], ":", color="black", lw=1,
                            label="served = offered")
        else:
            # The demand due in the measured time, as SUMO's insertion saw it
            # (summary.json offered_flow; the mean over the policies).
            offered = []
            for f in xs:
                vals = [number(r.get("offered_flow")) for r in sweep.rows
                        if number(r.get(flow_key)) == f and
                        (share_key is None or number(r.get(share_key)) == share)]
                vals = [v for v in vals if v is not None]
                offered.append(sum(vals) / len(vals) if vals else None)
            pts = [(f, o) for f, o in zip(xs, offered) if o is not None]
            if pts:
                axes[0][c].plot([p[0] for p in pts], [p[1] for p in pts], ":", color="black",
                                lw=1, label="served = offered")
        axes[0][c].set_title("AV share %g" % share if share is not None else "")
        for k, (_, _, ylabel) in enumerate(metrics):
            ax = axes[k][c]
            ax.grid(alpha=0.3)
            ax.set_ylim(bottom=0)
            if c == 0:
                ax.set_ylabel(ylabel)
            if k == len(metrics) - 1:
                ax.set_xlabel("demand per fringe edge (veh/h)" if flow_key == "scenario.demand.flow"
                              else "route files' demand scale (scenario.routes_scale)")
    handles, labels = axes[0][0].get_legend_handles_labels()
    if stalled_seen[0]:
        add_stall_legend(handles, labels)
    fig.legend(handles, labels, loc="lower center", ncol=max(1, len(labels)), frameon=False)
    ctx = sweep.context()
    kinds = {"allway_stop": "all-way stops", "priority_stop": "two-way stops"}
    where = ("%d x %d grid of %s, " % (grid.get("columns"), grid.get("rows"),
                                       kinds.get(grid.get("junction_type"), "stop-controlled junctions"))
             if grid else "")
    entries_note = ("%d fringe entries; " % entries) if entries else ""
    import textwrap
    chars = int(width * 12)  # about 12 characters per inch at this size
    title = "\n".join(textwrap.fill(t, chars) for t in (
        "Throughput and delay against demand: " + where + ctx,
        entries_note + "at AV share 0 and 1 no AV-HV pair can meet, so every policy is SUMO's "
        "own traffic (one curve); SUMO native: SUMO's own junction logic, no controller; small "
        "numbers at the foot of the served flow: AV-HV encounters behind each point, pooled over "
        "its seeds, one row per policy"))
    fig.suptitle(title, fontsize=10)
    top = 1 - 0.022 * (title.count("\n") + 1)
    fig.tight_layout(rect=(0, 0.05, 1, top))
    path = os.path.join(out_dir, "network_throughput.png")
    save(fig, path, dpi=120)
    plt.close(fig)
    return path


def plot_network_classes(plt, sweep, out_dir):
    """AVs and HVs apart: delay per trip and wait of held vehicles at the line
    against the demand, one panel column per AV share, 95 % intervals of the
    mean over seeds (t interval from the aggregate's mean, sd and runs_ok)."""
    flow_key = "scenario.demand.flow" if "scenario.demand.flow" in sweep.keys else "scenario.routes_scale"
    share_key = "scenario.av_share" if "scenario.av_share" in sweep.keys else None
    shares = sorted({number(r.get(share_key)) for r in sweep.rows} - {None}) if share_key else [None]
    metrics = [("time_loss_mean_av", "delay per AV trip (s)"),
               ("time_loss_mean_hv", "delay per HV trip (s)"),
               ("wait_mean_av", "wait of a held AV at the line (s)"),
               ("wait_mean_hv", "wait of a held HV at the line (s)")]
    width = max(8.0, 3.6 * len(shares) + 1)
    fig, axes = plt.subplots(len(metrics), len(shares), figsize=(width, 11), sharex=True,
                             squeeze=False)
    for c, share in enumerate(shares):
        for i, policy in enumerate(sweep.policies):
            colour, label = style(policy, i)
            rows = sorted(((number(r.get(flow_key)), r) for r in sweep.rows if r["policy"] == policy
                           and (share_key is None or number(r.get(share_key)) == share)
                           and number(r.get(flow_key)) is not None), key=lambda t: t[0])
            for k, (col, _) in enumerate(metrics):
                pts = []
                for f, r in rows:
                    m, sd, n = number(r.get(col)), number(r.get(col + "_sd")), number(r.get("runs_ok"))
                    if m is None:
                        continue
                    half = (stats.student_t_quantile(int(n) - 1) * sd / math.sqrt(n)
                            if sd is not None and n and n > 1 else 0.0)
                    pts.append((f, m, half))
                if pts:
                    axes[k][c].errorbar([p[0] for p in pts], [p[1] for p in pts],
                                        yerr=[p[2] for p in pts], fmt="-o", color=colour, ms=4,
                                        capsize=3, lw=1.5, label=label)
        axes[0][c].set_title("AV share %g" % share if share is not None else "")
        for k, (_, ylabel) in enumerate(metrics):
            ax = axes[k][c]
            ax.grid(alpha=0.3)
            ax.set_ylim(bottom=0)
            if c == 0:
                ax.set_ylabel(ylabel, fontsize=9)
            if k == len(metrics) - 1:
                ax.set_xlabel("demand per fringe edge (veh/h)" if flow_key == "scenario.demand.flow"
                              else "route files' demand scale (scenario.routes_scale)")
    handles, labels = [], []
    for ax in axes.flat:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    fig.legend(handles, labels, loc="lower center", ncol=max(1, len(labels)), frameon=False)
    import textwrap
    title = textwrap.fill(
        "AVs and HVs apart: delay per trip (SUMO's timeLoss, unfinished trips included) and the "
        "wait of vehicles the controller held at a stop line, mean over seeds with 95 % "
        "intervals; " + sweep.context(), int(width * 12))
    fig.suptitle(title, fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 1 - 0.022 * (title.count("\n") + 1)))
    path = os.path.join(out_dir, "network_delay_av_hv.png")
    save(fig, path, dpi=120)
    plt.close(fig)
    return path
