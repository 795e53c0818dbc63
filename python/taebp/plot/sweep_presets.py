"""The shipped studies' sweep presets (presets.PRESETS): the trust sweep
(trust_dc_collision.png), the trust mismatch's heat maps, the AV
penetration on the figure-8 and the networks' throughput and delay against
demand; each names what SweepView draws and the few marks the study adds."""

from . import style, tidy
from .common import die, number, warn
from .view import Figure, Mark, Panel, SweepView


def _has(sweep, metric):
    return any(number(r.get(metric)) is not None for r in sweep.rows)


def _save(plt, figures, out):
    return [f.save(plt, out) for f in figures]


# ------------------------------------------------------------------ trust
def trust(plt, sweep, theory, out):
    """DC and collision rate against theta: theory as lines, simulation as
    points with their intervals, theta* dashed."""
    others = [k for k in sweep.keys if k != "model.trust"]
    if others:
        warn("also swept: %s; told apart by line style" % ", ".join(others))
    thetas = sorted({number(r["model.trust"]) for r in sweep.rows} - {None})
    # As ModelConfig::Knowledge(): unset means "assumed" when assumed_trust is given.
    knowledge = sweep.model("trust_knowledge") or (
        "assumed" if sweep.model("assumed_trust") is not None else "exact")
    assumed = sweep.model("assumed_trust") if knowledge == "assumed" else None
    theta_star, dense = None, None
    if theory.available():
        lo, hi = min(thetas + [0.0]), max(thetas + [1.0])
        grid = [lo + (hi - lo) * i / 40 for i in range(41)]
        try:
            theta_star = theory.one(grid[len(grid) // 2], assumed)["theta_star"]
            # The curves jump at theta*, at the assumed trust and at 1 (No
            # Trust designs for 1): both sides of each, drawn vertical.
            for jump in (theta_star, assumed, 1.0):
                if jump is not None and lo < jump <= hi:
                    grid += [jump - 1e-6] + ([jump + 1e-6] if jump < hi else [])
            grid = sorted(set(grid))
            dense = (grid, theory.many([(t, assumed) for t in grid]))
        except (RuntimeError, ValueError, KeyError) as e:
            warn("theory from taebp failed (%s): drawing the theory columns instead" % e)

    def curve(metric, policy, facet, variant):
        if dense is not None and policy in dense[1][0].get("policies", {}):
            return dense[0], [d["policies"][policy][metric] for d in dense[1]]
        pts = sorted((number(r["model.trust"]), number(r.get("theory_" + metric)))
                     for r in sweep.rows if r["policy"] == policy)
        pts = [p for p in pts if p[0] is not None and p[1] is not None]
        return ([p[0] for p in pts], [p[1] for p in pts]) if pts else None

    def extra(panel, metric, facet):
        if theta_star is not None:
            panel.add(Mark("vline", [theta_star], note=" θ* = %.3g" % theta_star, simulated=False))
            return
        # Without taebp: theta* lies between the largest swept theta where
        # TA-EBP does not persuade and the smallest where it does.
        ta = [(number(r["model.trust"]), (number(r.get("theory_dc_rate")) or 0) > 0)
              for r in sweep.rows if r["policy"] == "ta_ebp"]
        yes = [t for t, p in ta if p]
        if yes:
            at = min(yes)
            no = [t for t, p in ta if not p and t < at]
            note = (" θ* in (%.3g, %.3g]" % (max(no), at)) if no else (" θ* ≤ %.3g" % at)
            panel.add(Mark("vline", [at], note=note, simulated=False))

    ctx = sweep.context()
    v = SweepView(sweep, "model.trust", ["dc_rate", "collision_rate"],
                  name="trust_dc_collision.png", x_title="HV trust θ", theory=curve, extra=extra,
                  title="Trust sweep" + (": " + ctx if ctx else ""), ncols=2)
    return _save(plt, v.figures(), out)


# ------------------------------------------------------------------ mismatch
def mismatch(plt, sweep, theory, out, policy="ta_ebp"):
    """Heat maps of the collision and the DC rate over (true theta, assumed
    theta_hat), each cell its rate and 95 % interval; the cells where the
    theory predicts collisions outlined."""
    if policy not in sweep.policies:
        policy = sweep.policies[0]
        warn("no ta_ebp rows: the heat maps show %s" % policy)
    rows = [r for r in sweep.rows if r["policy"] == policy]
    xs = sorted({number(r["model.trust"]) for r in rows} - {None})
    ys = sorted({number(r["model.assumed_trust"]) for r in rows} - {None})
    if not xs or not ys:
        die("mismatch: no numeric model.trust / model.assumed_trust values")
    cell = {(number(r["model.trust"]), number(r["model.assumed_trust"])): r for r in rows}
    ex, ey = _edges(xs), _edges(ys)
    predicted = {k: number(r.get("theory_collision_rate")) > 1e-12 for k, r in cell.items()
                 if number(r.get("theory_collision_rate")) is not None}
    theta_star = None
    if theory.available():
        try:
            missing = [k for k in cell if k not in predicted]
            for k, d in zip(missing, theory.many(missing)):
                predicted[k] = d["policies"][policy]["collision_rate"] > 1e-12
            theta_star = theory.one(xs[0], ys[0])["theta_star"]
        except (RuntimeError, ValueError, KeyError) as e:
            warn("theory from taebp failed (%s)" % e)
    outline = _outline(xs, ys, ex, ey, predicted)
    figures = []
    ctx = sweep.context()
    for metric, file, cmap_name in (("collision_rate", "mismatch_collision_heatmap.png", "magma_r"),
                                    ("dc_rate", "mismatch_dc_heatmap.png", "viridis")):
        panel = _heat_panel(plt, sweep, cell, xs, ys, (ex, ey), metric, cmap_name, policy,
                            outline)
        lo, hi = min(ex[0], ey[0]), max(ex[-1], ey[-1])
        panel.add(Mark("curve", [lo, hi], [lo, hi], colour="#2a9d8f", ls=":", lw=1.4,
                       legend=r"$\hat{\theta} = \theta$", simulated=False))
        if theta_star is not None:
            panel.add(Mark("hline", [theta_star], colour="#2a9d8f", ls="--", lw=1.4,
                           legend=r"$\hat{\theta} = \theta^* = %.3g$" % theta_star,
                           simulated=False))
        figures.append(Figure(file, [panel], ncols=1, panel_height=5.2,
                              title="Trust mismatch" + (": " + ctx if ctx else ""),
                              caption="Each cell: the rate over its seeds' encounters and its "
                                      "95 % interval (leading 0 dropped); grey: no value."))
    return _save(plt, figures, out)


def _edges(v):
    """The cells' edges around the values v: halfway between neighbours."""
    if len(v) == 1:
        return [v[0] - 0.05, v[0] + 0.05]
    mids = [(a + b) / 2 for a, b in zip(v, v[1:])]
    return [v[0] - (mids[0] - v[0])] + mids + [v[-1] + (v[-1] - mids[-1])]


def _outline(xs, ys, ex, ey, predicted):
    """The edges between the cells where the theory predicts collisions and
    the others (or the map's border): [(xs, ys)] segments."""
    outline = []
    for i, x in enumerate(xs):
        for j, y in enumerate(ys):
            if not predicted.get((x, y)):
                continue
            if i == 0 or not predicted.get((xs[i - 1], y)):
                outline.append(([ex[i], ex[i]], [ey[j], ey[j + 1]]))
            if i + 1 == len(xs) or not predicted.get((xs[i + 1], y)):
                outline.append(([ex[i + 1], ex[i + 1]], [ey[j], ey[j + 1]]))
            if j == 0 or not predicted.get((x, ys[j - 1])):
                outline.append(([ex[i], ex[i + 1]], [ey[j], ey[j]]))
            if j + 1 == len(ys) or not predicted.get((x, ys[j + 1])):
                outline.append(([ex[i], ex[i + 1]], [ey[j + 1], ey[j + 1]]))
    return outline


def _short(v):
    text = "%.2f" % v
    return text[1:] if text.startswith("0.") else text


def _heat_panel(plt, sweep, cell, xs, ys, edges, metric, cmap_name, policy, outline):
    """One metric's heat map over the cells: each cell its rate and 95 %
    interval (or why it has none), the predicted cells outlined."""
    import matplotlib.colors as mcolors
    ex, ey = edges
    z = [[None] * len(xs) for _ in ys]
    texts = []
    for (x, y), r in cell.items():
        if x is None or y is None:
            continue
        v, lo, hi, _ = tidy.value_of(sweep, r, metric)
        ok, bad = sweep.runs(r)
        if v is None:
            texts.append((x, y, "failed\n%d/%d" % (bad, ok + bad) if bad else "n/a", None))
            continue
        z[ys.index(y)][xs.index(x)] = v
        interval = ("\n%s–%s" % (_short(lo), _short(hi))) if lo is not None else ""
        texts.append((x, y, "%.2f%s" % (v, interval), v))
    vals = [v for row in z for v in row if v is not None]
    vmax = max([0.05] + vals)
    cmap = plt.get_cmap(cmap_name).copy()
    cmap.set_bad("#d9d9d9")
    panel = Panel(title="%s, %s" % (style.metric_title(metric), style.policy_label(policy)),
                  xlabel=r"true HV trust $\theta$",
                  ylabel=r"trust $\hat{\theta}$ the AV designs for", name=metric)
    panel.add(Mark("heat", edges_x=ex, edges_y=ey,
                   values=[[float("nan") if v is None else v for v in row] for row in z],
                   texts=texts, cmap=cmap, norm=mcolors.Normalize(vmin=0, vmax=vmax),
                   colourbar="%s (%s)" % (metric, style.policy_label(policy)),
                   outline=outline,
                   outline_label=r"theory: collisions ($\hat{\theta} > \theta$ and "
                                 r"$\hat{\theta} \geq \theta^*$)"))
    return panel


# ------------------------------------------------------------------ penetration
def penetration(plt, sweep, theory, out):
    """Throughput, collisions, waits and encounters against the AV share
    avs / (avs + hvs); fleets of another size at one share told apart."""
    def count(r, key):
        return number(r.get(key)) if key in sweep.keys else number(str(sweep.scenario(
            key.split(".", 1)[1], "")))

    def share(r):
        avs, hvs = count(r, "scenario.avs"), count(r, "scenario.hvs")
        if avs is None or hvs is None or avs + hvs <= 0:
            return None
        return avs / (avs + hvs)

    totals = sorted({int(count(r, "scenario.avs") + count(r, "scenario.hvs")) for r in sweep.rows
                     if share(r) is not None})
    variant_of = lambda r: totals.index(int(count(r, "scenario.avs") +  # noqa: E731
                                            count(r, "scenario.hvs")))
    labels = ["%d vehicles" % t for t in totals] if len(totals) > 1 else [""]
    loop = sweep.scenario("loop_length")
    track = ("%g m loops of the figure-8" % loop) if loop else "the figure-8"
    fleet = ("%d vehicles" % totals[0]) if len(totals) == 1 else \
        "%s vehicles" % " or ".join(str(t) for t in totals)
    ctx = sweep.context(keys=sweep.keys + ["scenario.avs", "scenario.hvs"])
    v = SweepView(sweep, "AV share", ["throughput_all", "throughput_av", "throughput_hv",
                                      "collision_rate", "wait_mean", "encounters_per_hour"],
                  x_of=share, x_title="AV share avs / (avs + hvs)",
                  variant_of=variant_of if len(totals) > 1 else (lambda r: 0),
                  variant_labels=labels, name="penetration_throughput.png",
                  zero={"throughput_all": False, "throughput_av": True, "throughput_hv": True},
                  title="AV penetration on %s (%s)%s" % (track, fleet, ": " + ctx if ctx else ""),
                  caption="Caveat: crossings per hour are this small track's (%s on two short "
                          "loops; README, Penetration). TA-EBP's encounters take longer (the "
                          "nudge, the confirmation delay): a few per cent fewer crossings than No "
                          "EBP; read No Trust's throughput beside its collisions." % fleet)
    return _save(plt, v.figures(), out)


# ------------------------------------------------------------------ networks
def _demand(sweep):
    key = "scenario.demand.flow" if "scenario.demand.flow" in sweep.keys else "scenario.routes_scale"
    title = ("demand per fringe edge (veh/h)" if key == "scenario.demand.flow"
             else "route files' demand scale (scenario.routes_scale)")
    return key, title


def _game_shares(sweep):
    """(select, caption note): the AV shares at which an AV-HV pair can
    meet; at 0 and 1 every policy is SUMO's own traffic (one curve)."""
    key = "scenario.av_share" if "scenario.av_share" in sweep.keys else None
    if key is None:
        return None, ""
    shares = {r.get(key) for r in sweep.rows}
    met = {r.get(key) for r in sweep.rows if (number(r.get("encounters")) or 0) > 0}
    dropped = sorted(shares - met, key=lambda c: number(c) or 0)
    if not met or not dropped:
        return None, ""
    note = ("AV share %s left out: no AV-HV pair can meet there, so every policy is SUMO's own "
            "traffic (sumo_native's line in every panel). " % " and ".join(dropped))
    return (lambda r: r.get(key) in met), note


def network(plt, sweep, theory, out):
    """Served flow, delay and encounters per hour against the offered demand,
    a panel column per AV share; with AV and HV delays, those apart too."""
    key, x_title = _demand(sweep)
    share = "scenario.av_share" if "scenario.av_share" in sweep.keys else None
    select, note = _game_shares(sweep)
    grid = sweep.scenario("grid") or {}
    kinds = {"allway_stop": "all-way stops", "priority_stop": "two-way stops"}
    where = ("%d x %d grid of %s" % (grid.get("columns"), grid.get("rows"),
                                     kinds.get(grid.get("junction_type"), "stop-controlled junctions"))
             if grid else "")
    ctx = sweep.context()
    facet = (lambda f: "AV share %s" % f) if share else None
    def served_equals_offered(panel, metric, facet):
        if metric == "served_share":
            panel.add(Mark("hline", [1.0], ls=":", lw=1.0, simulated=False,
                           legend="served = offered (all the demand served)"))

    views = [SweepView(sweep, key, ["served_share", "time_loss_mean", "encounters_per_hour"],
                       by=share, select=select, x_title=x_title, name="network_throughput.png",
                       facet_title=facet, extra=served_equals_offered,
                       zero={"served_share": False},
                       title="Throughput and delay against demand: " + ", ".join(
                           t for t in (where, ctx) if t),
                       caption=note + "SUMO native: SUMO's own junction logic, no controller.")]
    if _has(sweep, "time_loss_mean_av"):
        views.append(SweepView(
            sweep, key, [("time_loss_mean_av", "time_loss_mean_hv"),
                         ("wait_mean_av", "wait_mean_hv")],
            by=share, select=select, x_title=x_title, name="network_delay_av_hv.png",
            facet_title=facet, pair_labels=["AVs", "HVs"],
            metric_titles={("time_loss_mean_av", "time_loss_mean_hv"):
                           "Delay per trip (SUMO's timeLoss)",
                           ("wait_mean_av", "wait_mean_hv"): "Wait of a held vehicle at the line"},
            title="AVs and HVs apart: " + ", ".join(t for t in (where, ctx) if t),
            caption=note + "Delay: SUMO's timeLoss of every trip departed after the warm-up, "
                           "unfinished trips included; wait: vehicles the controller held at a "
                           "stop line."))
    return [p for v in views for p in _save(plt, v.figures(), out)]
