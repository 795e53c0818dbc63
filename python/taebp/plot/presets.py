"""The figures we ship (README, docs/img/): each a preset over the tidy core,
naming what to draw (x, y, by, which rows, the title) and the few marks a
study adds (theta*, the bound delta * lambda, the theory's region); view.py
draws them all the same way.

Sweep presets are chosen by the swept keys (PRESETS: the keys each covers,
when it applies, what it draws); the keys no applying preset covers get the
generic view. Run presets (RUN_PRESETS) draw runs beyond the paper from
their time series, pooling only runs of one config (a sweep's point, or run
folders that differ only in their seed)."""


import bisect
import math

from . import style, tidy
from .common import PlotError, die, number, warn
from .view import Figure, Mark, Panel, SweepView


def _numeric(sweep, key):
    vals = [r.get(key) for r in sweep.rows]
    return bool(vals) and all(number(v) is not None for v in vals)


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
    import matplotlib.colors as mcolors
    if policy not in sweep.policies:
        policy = sweep.policies[0]
        warn("no ta_ebp rows: the heat maps show %s" % policy)
    rows = [r for r in sweep.rows if r["policy"] == policy]
    xs = sorted({number(r["model.trust"]) for r in rows} - {None})
    ys = sorted({number(r["model.assumed_trust"]) for r in rows} - {None})
    if not xs or not ys:
        die("mismatch: no numeric model.trust / model.assumed_trust values")
    cell = {(number(r["model.trust"]), number(r["model.assumed_trust"])): r for r in rows}

    def edges(v):
        if len(v) == 1:
            return [v[0] - 0.05, v[0] + 0.05]
        mids = [(a + b) / 2 for a, b in zip(v, v[1:])]
        return [v[0] - (mids[0] - v[0])] + mids + [v[-1] + (v[-1] - mids[-1])]

    ex, ey = edges(xs), edges(ys)
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

    def short(v):
        text = "%.2f" % v
        return text[1:] if text.startswith("0.") else text

    figures = []
    ctx = sweep.context()
    for metric, file, cmap_name in (("collision_rate", "mismatch_collision_heatmap.png", "magma_r"),
                                    ("dc_rate", "mismatch_dc_heatmap.png", "viridis")):
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
            interval = ("\n%s–%s" % (short(lo), short(hi))) if lo is not None else ""
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


# ------------------------------------------------------------------ noise
def noise(plt, sweep, theory, out):
    """DC and collision rate against the noise's sigma, the noise-aware
    design and the paper's s* apart (line styles), theory exact over the
    noise, the bound delta * lambda; a panel zooms on the aware design."""
    cfg = sweep.model("noise", {}) or {}
    kind = cfg.get("kind", "gaussian")
    delta = number(str(cfg.get("delta", 0.01)))
    bias = number(str(cfg.get("bias", 0.0))) or 0.0
    lam = sweep.model("prior_go", 0.2)
    trust_ = sweep.model("trust")
    assumed = sweep.model("assumed_trust")

    def design_of(r):
        return r.get("model.noise.design") or cfg.get("design", "aware")

    designs = []
    for r in sweep.rows:
        if design_of(r) not in designs:
            designs.append(design_of(r))
    designs.sort(key=lambda d: (d != "aware", d))
    names = {"aware": "noise-aware design s_δ", "paper": "the paper's s*"}
    sigmas = sorted({number(r["model.noise.scale"]) for r in sweep.rows} - {None})
    dense = None
    if theory.available() and isinstance(trust_, (int, float)):
        top = max(sigmas) * 1.05
        grid = sorted(set([top * i / 80 for i in range(1, 81)] + sigmas))
        extra_args = lambda sg: ("--noise", kind, "--noise-scale", repr(sg),  # noqa: E731
                                 "--noise-bias", repr(bias), "--noise-delta", repr(delta))
        try:
            results = theory.many([(trust_, assumed, extra_args(sg)) for sg in grid])
            edge = [g for g, d in zip(grid, results) if d["noise"]["aware"]["status"] != "ok"]
            if edge:  # where the aware design gives up: both sides, drawn vertical
                first = min(edge)
                lo_, hi_ = max([g for g in grid if g < first] or [first]), first
                for _ in range(30):
                    mid = (lo_ + hi_) / 2
                    ok = theory.one(trust_, assumed, extra_args(mid))["noise"]["aware"]["status"] == "ok"
                    lo_, hi_ = (mid, hi_) if ok else (lo_, mid)
                grid = sorted(set(grid + [lo_, hi_]))
                results = theory.many([(trust_, assumed, extra_args(sg)) for sg in grid])
            zero = theory.one(trust_, assumed)["policies"]["ta_ebp"]
            dense = (grid, results, zero)
        except (RuntimeError, ValueError, KeyError) as e:
            warn("theory from taebp failed (%s): drawing the theory columns instead" % e)
    elif not isinstance(trust_, (int, float)):
        warn("model.trust is a distribution: theory drawn through the theory columns")

    def curve(metric, policy, facet, variant):
        design = designs[variant]
        if dense is not None and policy in ("ta_ebp", "population_mean"):
            if design == "aware":
                return dense[0], [d["noise"]["aware"][metric] for d in dense[1]]
            return dense[0], [d["noise"]["policies"]["ta_ebp"][metric] for d in dense[1]]
        pts = sorted((number(r["model.noise.scale"]), number(r.get("theory_" + metric)))
                     for r in sweep.rows if r["policy"] == policy and design_of(r) == design)
        pts = [p for p in pts if p[0] is not None and p[1] is not None]
        return ([p[0] for p in pts], [p[1] for p in pts]) if pts else None

    gave_up = []
    if dense is not None:
        gave_up = [g for g, d in zip(dense[0], dense[1])
                   if d["noise"]["aware"]["status"] == "unachievable"]

    def extra(panel, metric, facet):
        if dense is not None:
            panel.add(Mark("special", [0], [dense[2][metric]], colour="black", simulated=False,
                           legend="σ = 0: the paper's result (both designs)"))
        if metric == "collision_rate" and delta is not None and lam is not None:
            panel.add(Mark("hline", [delta * lam], note=" δλ = %g" % (delta * lam),
                           legend="the bound δλ", simulated=False))
        if gave_up:
            panel.add(Mark("shade", [min(gave_up), max(dense[0])], simulated=False,
                           legend="s_δ > s_max: the aware AV yields"))

    common = dict(x_title="noise σ of the HV's reading (m)", theory=curve, extra=extra,
                  variant_of=lambda r: designs.index(design_of(r)),
                  variant_labels=[names.get(d, d) for d in designs])
    main = SweepView(sweep, "model.noise.scale", ["dc_rate", "collision_rate"], **common)
    panels = main.panels()
    if "aware" in designs:
        zoom = SweepView(sweep, "model.noise.scale", ["collision_rate"],
                         select=lambda r: design_of(r) == "aware",
                         metric_titles={"collision_rate": "Collisions, noise-aware design (zoom)"},
                         **dict(common, variant_of=lambda r: 0,
                                variant_labels=[names["aware"]]))
        zp = zoom.panels()[0]
        zp.group = "zoom"
        his = [number(r.get("collision_rate_hi")) for r in sweep.rows if design_of(r) == "aware"]
        zp.ylim = (0, max([3 * (delta or 0.01) * (lam or 0.2)] + [h for h in his if h]) * 1.1)
        panels.append(zp)
    for p in panels:
        p.xlim = (-0.01 * max(sigmas), max(sigmas) * 1.05)
    ctx = sweep.context()
    fig = main.figure("noise_sigma.png", panels, 3)
    fig.title = "Perception noise (%s, δ = %g)%s" % (kind, delta, (": " + ctx) if ctx else "")
    return _save(plt, [fig], out)


def learners(plt, sweep, theory, out):
    """Influence against learners the AV is not told (docs/influence.md,
    issue 42): DC and collision rate against the HVs' forgetting, one column
    per design ta_ebp commits to (full revelation and always-nudge, which read
    no design key, drawn in each), the mean field as the bar at each point."""
    by = "model.experience.design" if "model.experience.design" in sweep.keys else None
    view = SweepView(sweep, "model.experience.forgetting", ["dc_rate", "collision_rate"], by=by,
                     x_title="the HVs' weight on their past ρ (1 = exact counts)",
                     facet_title=(lambda f: "ta_ebp's design: %s" % f) if by else None)
    fig = view.figure("influence_learners.png", view.panels(), 3)
    ctx = sweep.context()
    fig.title = "Learners the AV is not told%s" % ((": " + ctx) if ctx else "")
    return _save(plt, [fig, learners_frontier(sweep, ctx)], out)


# The collision rate a design may cost and still be called safe (issue 42's
# acceptance: at most 0.01 per encounter).
SAFE_COLLISIONS = 0.01


def learners_frontier(sweep, ctx):
    """DC against collisions, one panel per learner (forgetting rho): each
    policy a point (ta_ebp once per design, by marker; the policies that read
    no design key once), DC's 95 % interval as its bar, the safe bound
    dashed. The safe frontier is the highest point left of the bound."""
    design = "model.experience.design"
    designs = []
    for r in sweep.rows:
        if design in sweep.keys and r[design] not in designs:
            designs.append(r[design])
    rhos = sorted({number(r["model.experience.forgetting"]) for r in sweep.rows} - {None},
                  reverse=True)
    panels = []
    for rho in rhos:
        panel = Panel(title="ρ = %g%s" % (rho, " (exact counts)" if rho == 1 else ""),
                      xlabel="collisions per encounter", ylabel="DC per encounter",
                      group="dc", name="dc_rate")
        panel.add(Mark("vline", [SAFE_COLLISIONS], colour="black", ls=":",
                       legend="safe: at most %g collisions per encounter" % SAFE_COLLISIONS))
        seen = set()
        for r in sweep.rows:
            if number(r["model.experience.forgetting"]) != rho:
                continue
            x, y = number(r.get("collision_rate")), number(r.get("dc_rate"))
            if x is None or y is None:
                continue
            reads_design = r["policy"] == "ta_ebp"
            if not reads_design and r["policy"] in seen:
                continue  # the same runs under every design
            seen.add(r["policy"])
            variant = designs.index(r[design]) if reads_design and designs else 0
            panel.add(Mark("points", [x], [y], lo=[number(r.get("dc_rate_lo"))],
                           hi=[number(r.get("dc_rate_hi"))], policy=r["policy"], variant=variant))
        panels.append(panel)
    variants = [("ta_ebp's design: %s" % d, "", style.MARKERS[i % len(style.MARKERS)])
                for i, d in enumerate(designs)]
    return Figure("influence_learners_frontier.png", panels,
                  title="DC against collisions per learner%s" % ((": " + ctx) if ctx else ""),
                  caption="Each point one policy pooled over the seeds (bars: DC's 95 % interval "
                          "clustered by HV and run); the safe frontier is the highest point left "
                          "of the dotted bound.",
                  ncols=min(4, len(panels)), variants=variants)


# name: (the swept keys it covers, applies(sweep, keys), draw(plt, sweep, theory, out) -> [paths])
PRESETS = {
    "mismatch": ({"model.trust", "model.assumed_trust"},
                 lambda s, k: {"model.trust", "model.assumed_trust"} <= k and
                 _numeric(s, "model.trust") and _numeric(s, "model.assumed_trust"),
                 mismatch),
    "trust": ({"model.trust"},
              lambda s, k: k == {"model.trust"} and _numeric(s, "model.trust"), trust),
    "penetration": ({"scenario.avs", "scenario.hvs"},
                    lambda s, k: bool(k & {"scenario.avs", "scenario.hvs"}) and
                    k <= {"scenario.avs", "scenario.hvs"}, penetration),
    "network": ({"scenario.demand.flow", "scenario.routes_scale", "scenario.av_share"},
                lambda s, k: bool(k & {"scenario.demand.flow", "scenario.routes_scale"}) and
                k <= {"scenario.demand.flow", "scenario.routes_scale", "scenario.av_share"},
                network),
    "noise": ({"model.noise.scale", "model.noise.design"},
              lambda s, k: "model.noise.scale" in k and
              k <= {"model.noise.scale", "model.noise.design"}, noise),
    "learners": ({"model.experience.forgetting", "model.experience.design"},
                 lambda s, k: "model.experience.forgetting" in k and
                 k <= {"model.experience.forgetting", "model.experience.design"} and
                 _numeric(s, "model.experience.forgetting"), learners),
}


def applying(sweep):
    """The presets whose keys match the sweep's, in PRESETS order."""
    keys = set(sweep.keys)
    return [name for name, (_, applies, _) in PRESETS.items() if applies(sweep, keys)]


def covered(names):
    out = set()
    for n in names:
        out |= PRESETS[n][0]
    return out


def draw(name, plt, sweep, theory, out):
    return PRESETS[name][2](plt, sweep, theory, out)


# ------------------------------------------------------------------ runs
def _save_group(plt, fig, out):
    """One group's figure; a group without a simulated value (a sweep point
    whose runs met no AV-HV pair) is skipped with a warning, not the others."""
    try:
        return [fig.save(plt, out)]
    except PlotError as e:
        warn("%s (skipped)" % e)
        return []


def _suffix(name):
    return "" if not name else "_" + name.replace(" ", "")


def _dodge(i, n, width):
    return (i - (n - 1) / 2) * width / max(1, n)


def learned(plt, runs, out):
    """Per group of runs (a sweep's point): DC and collision rate per
    simulated hour for every policy (95 % intervals; the oracle's expected DC
    on the learner's encounters dashed), and the cumulative expected regret
    against the oracle over the encounters, with the learner's failures
    against the number its posterior predicted."""
    paths = []
    for name, idx in runs.groups():
        if not any("ta_ebp_learned" in runs.summaries[i].get("policies", {}) for i in idx):
            continue
        policies = [p for p in style.policy_order() if any(
            p in runs.summaries[i].get("policies", {}) for i in idx)]
        bins = tidy.binned_rates(runs, idx, 3600.0)
        dc = Panel(title="DC per AV-HV encounter, per simulated hour",
                   xlabel="simulated time (h)", ylabel="dc_rate", name="dc_rate")
        coll = Panel(title="Collisions per AV-HV encounter, per simulated hour",
                     xlabel="simulated time (h)", ylabel="collision_rate", name="collision_rate")
        for i, policy in enumerate(policies):
            rows = bins.get(policy, [])
            if not rows:
                continue
            xs = [(a + b) / 2 / 3600 + _dodge(i, len(policies), 0.3) for a, b, *_ in rows]
            for panel, k in ((dc, 3), (coll, 4)):
                ivs = [tidy.rate_interval(row[6], k - 2) for row in rows]
                panel.add(Mark("points", xs, [row[k] / row[2] for row in rows],
                               lo=[c[0] for c in ivs], hi=[c[1] for c in ivs], policy=policy))
            if policy == "ta_ebp_learned":
                dc.add(Mark("curve", [(a + b) / 2 / 3600 for a, b, *_ in rows],
                            [row[5] / row[2] for row in rows], colour=style.policy_colour(policy),
                            ls="--", lw=1.2, simulated=False,
                            legend="the oracle's expected DC on the learner's encounters"))
        ctx = runs.context(idx) + (" (%s)" % runs.group_title(name) if name else "")
        paths += _save_group(plt, Figure(
            "learned_rates%s.png" % _suffix(name), [dc, coll], ncols=2,
            title="Learned trust: " + ctx,
            legend_extra=[(dict(color="black", marker="o", ls="none", ms=4),
                           "rate over the hour's encounters, 95 % interval clustered by "
                           "HV and seed")]), out)
        paths += _save_group(plt, _regret(runs, idx, policies, name, ctx), out)
    return paths


def _regret(runs, idx, policies, name, ctx):
    learner = Panel(title="TA-EBP learned: regret against the oracle",
                    xlabel="AV-HV encounters T (log scale)", ylabel="cumulative expected regret",
                    xscale="log", name="regret")
    every = Panel(title="Every policy (log-log)", xlabel="AV-HV encounters T (log scale)",
                  ylabel="cumulative expected regret", xscale="log", yscale="log", name="regret_all")
    fails = Panel(title="TA-EBP learned: failures to persuade",
                  xlabel="nudges of TA-EBP learned (log scale)", ylabel="cumulative count",
                  xscale="log", name="failures")
    zero, ends = [], []
    for policy in policies:
        curves = []
        for i in idx:
            acc, curve = 0.0, []
            for r in runs.csv(i, "encounters.csv"):
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
            zero.append(style.policy_label(policy))
            continue
        for panel in [every] + ([learner] if policy == "ta_ebp_learned" else []):
            if len(curves) > 1:
                for c in curves:
                    panel.add(Mark("curve", range(1, len(c) + 1), c, policy=policy, lw=0.7,
                                   alpha=0.35, simulated=True))
            panel.add(Mark("curve", range(1, n + 1), mean, policy=policy, lw=1.8,
                           simulated=True))
        ends.append((n, mean[-1]))
        if policy == "ta_ebp_learned":
            delta = ((runs.config(idx[0]).get("model", {}) or {}).get("learning") or {}).get(
                "delta", 0.01)
            for j, i in enumerate(idx):
                f = e = k = 0
                fx, ex, x = [], [], []
                for r in runs.csv(i, "encounters.csv"):
                    if r["policy"] != policy or not (number(r.get("commanded_nudge")) or 0) > 0:
                        continue
                    k += 1
                    f += r.get("hv_action") == "DR"
                    e += number(r.get("failure_probability")) or 0.0
                    x.append(k)
                    fx.append(f)
                    ex.append(e)
                if x:
                    fails.add(Mark("step", x, fx, policy=policy, lw=1.4, simulated=True))
                    fails.add(Mark("theory", x, ex, colour="black", ls="--", lw=1.2,
                                   legend="expected (Σ posterior failure probability)",
                                   simulated=False))
                    fails.add(Mark("theory", x, [delta * v for v in x], colour="0.4", ls=":",
                                   lw=1.2, legend="δ × nudges (the budget)", simulated=False))
    if ends:
        t_max = max(e[0] for e in ends)
        ref = min(e[1] for e in ends) / t_max / 3  # slope 1 below every curve's end
        every.add(Mark("theory", [1, t_max], [ref, ref * t_max], colour="0.4", ls=":", lw=1.0,
                       legend="∝ T (linear growth)", simulated=False))
    caption = ("%s: regret 0 (the oracle itself)." % ", ".join(zero)) if zero else ""
    for p in (learner, every, fails):
        p.zero = p.yscale != "log"
    return Figure("learned_regret%s.png" % _suffix(name), [learner, every, fails], ncols=3,
                  title="Learned trust, regret growth: " + ctx, caption=caption,
                  legend_extra=[(dict(color="black", lw=0.7, alpha=0.35), "one seed"),
                                (dict(color="black", lw=1.8), "mean of the seeds")]
                  if len(idx) > 1 else [])


def dynamic(plt, runs, out):
    """Per group of runs: the population's mean trust over time per policy
    (seeds thin, their mean thick), its mean-field prediction dashed and the
    long-run trust the theory derives dotted."""
    paths = []
    for name, idx in runs.groups():
        d = (runs.config(idx[0]).get("model", {}) or {}).get("trust_dynamics")
        if not d:
            continue
        panel = Panel(title="Mean trust of the HVs in the network", xlabel="simulated time (h)",
                      ylabel="mean trust", ylim=(0, 1.05), name="mean_trust")
        for policy in [p for p in style.policy_order() if p in runs.policies]:
            per_run = []
            for i in idx:
                pts = [(float(r["time"]) / 3600, number(r["mean_trust"]),
                        number(r.get("mean_field_trust")))
                       for r in runs.csv(i, "timeseries.csv")
                       if r["policy"] == policy and number(r["mean_trust"]) is not None]
                if pts:
                    per_run.append(pts)
            if not per_run:
                continue
            n = min(len(p) for p in per_run)
            xs = [per_run[0][t][0] for t in range(n)]
            if len(per_run) > 1:
                for pts in per_run:
                    panel.add(Mark("curve", [p[0] for p in pts], [p[1] for p in pts],
                                   policy=policy, lw=0.7, alpha=0.35, simulated=True))
            panel.add(Mark("curve", xs, [sum(p[t][1] for p in per_run) / len(per_run)
                                         for t in range(n)], policy=policy, lw=2.0,
                           simulated=True))
            mf = [(per_run[0][t][0], sum(p[t][2] for p in per_run) / len(per_run))
                  for t in range(n) if all(p[t][2] is not None for p in per_run)]
            if mf:
                panel.add(Mark("theory", [p[0] for p in mf], [p[1] for p in mf], policy=policy,
                               ls="--", lw=1.3, legend="mean field (theory)", simulated=False))
            longs = [runs.summaries[i]["policies"][policy].get("expected_long_run_trust")
                     for i in idx if policy in runs.summaries[i].get("policies", {})]
            longs = [v for v in longs if v is not None]
            if longs:
                panel.add(Mark("hline", [longs[0]], policy=policy, ls=":", lw=1.4,
                               note=" long run %.3f" % longs[0], legend="long-run trust (theory)",
                               legend_colour="black", simulated=False))
        ctx = runs.context(idx) + (" (%s)" % runs.group_title(name) if name else "")
        title = "Dynamic trust: %s; w_s = %g, w_f = %g, ρ = %g, α0+β0 = %g" % (
            ctx, d.get("success_weight", 1), d.get("failure_weight", 1), d.get("forgetting", 0),
            d.get("strength", 10))
        extra = [(dict(color="black", lw=0.7, alpha=0.35), "one seed"),
                 (dict(color="black", lw=2.0), "mean of the seeds")] if len(idx) > 1 else []
        paths += _save_group(plt, Figure("dynamic_trust%s.png" % _suffix(name), [panel], ncols=1,
                                         panel_height=3.4, title=title, legend_extra=extra), out)
    return paths


def _experienced(runs):
    """Runs of HVs who learn, all of one learner (the experience settings but
    the design, and the noise, the same in every run): influence.png pools
    them by policy and design. Runs of different learners (a learners sweep)
    are not pooled: the learners preset draws them point by point."""
    learners = set()
    for i in range(len(runs.dirs)):
        model = runs.config(i).get("model", {}) or {}
        exp = model.get("experience")
        if exp:
            rest = {k: v for k, v in exp.items() if k not in ("design", "margin")}
            learners.add(repr((sorted(rest.items()), model.get("noise"))))
    if len(learners) > 1:
        warn("influence.png not drawn: the runs are of %d different learners (forgetting, "
             "strengths or noise differ), and pooling them would mix them" % len(learners))
    return len(learners) == 1


def influence(plt, runs, out):
    """HVs who learn what a nudge meant (docs/influence.md): DC and collision
    rate per outputs.interval against simulated time (points, 95 %
    intervals), the mean field (lines) and the long run (dashed), and the DC
    rate by each HV's own encounter number."""
    data = influence_data(runs)
    designs = sorted({e["design"] for e in data.values()}, key=lambda d: d != "guarded")
    labels = {"guarded": "designed for each HV's experience (guarded)",
              "paper": "the paper's scheme kept as it is"}
    minutes = "%g" % round(_width(data) / 60)
    panels = [Panel(title="(a) DC, per %s simulated minutes" % minutes,
                    xlabel="simulated time (h)", ylabel="dc_rate", name="dc_rate"),
              Panel(title="(b) Collisions, per %s simulated minutes" % minutes,
                    xlabel="simulated time (h)", ylabel="collision_rate", name="collision_rate"),
              Panel(title="(c) DC by each HV's own encounter number",
                    xlabel="the HV's encounter number", ylabel="dc_rate",
                    name="dc_by_encounter", ylim=(0, 1.02))]
    for (policy, design), e in sorted(data.items(), key=lambda kv: (
            style.policy_order().index(kv[0][0]) if kv[0][0] in style.policy_order() else 99,
            kv[0][1] != "guarded")):
        v = designs.index(design)
        bins = sorted(e["bins"].items())
        x = [(a + b) / 2 / 3600 for (a, b), _ in bins]
        for panel, k, th, lr in ((panels[0], 1, 3, e["long_run"][0]),
                                 (panels[1], 2, 4, e["long_run"][1])):
            ivs = [tidy.rate_interval(acc[5], k) for _, acc in bins]
            panel.add(Mark("points", x, [acc[k] / acc[0] for _, acc in bins],
                           lo=[c[0] for c in ivs], hi=[c[1] for c in ivs], policy=policy,
                           variant=v, ls="none"))
            panel.add(Mark("theory", x, [acc[th] / acc[0] for _, acc in bins], policy=policy,
                           ls=style.LINESTYLES[v], lw=1.4, legend="mean field (exact expected "
                           "learning path)", simulated=False))
            if lr is not None:
                panel.add(Mark("hline", [lr], policy=policy, ls="--", lw=0.8,
                               legend="long-run theory (fixed point)", legend_colour="black",
                               simulated=False))
        first = sorted(e["first"].items())
        xs = [i + 1 for i, _ in first]
        panels[2].add(Mark("points", xs, [t[1] / t[0] for _, t in first], policy=policy,
                           variant=v, ls="none", ms=3))
        panels[2].add(Mark("theory", xs, [t[2] / t[0] for _, t in first], policy=policy,
                           ls=style.LINESTYLES[v], lw=1.4, simulated=False,
                           legend="mean field (exact expected learning path)"))
    for p in panels[:2]:
        p.group = "time"
    n_runs = max(e["runs"] for e in data.values())
    variants = [(labels.get(d, d), style.LINESTYLES[i], style.MARKERS[i])
                for i, d in enumerate(designs)] if len(designs) > 1 else []
    fig = Figure("influence.png", panels, ncols=3, variants=variants,
                 title="HVs who learn what a nudge meant: %s; up to %d seeds per policy"
                 % (runs.context([0]).rsplit(",", 1)[0], n_runs),
                 legend_extra=[(dict(color="black", marker="o", ls="none", ms=4),
                                "SUMO, pooled over the runs (95 % interval clustered by HV and run)")])
    return [fig.save(plt, out)]


def _width(data):
    """The time series' interval (s): the most common width of its bins."""
    widths = [round(b - a) for e in data.values() for (a, b) in e["bins"]]
    return max(set(widths), key=widths.count)


def influence_data(runs):
    """{(policy, design): {"bins": {(t0, t1): [n, dc, coll, theory dc, theory
    coll, clusters]}, "long_run": (dc, coll), "first": {k: [n, dc, theory
    dc]}, "runs", "design"}} pooled over the runs of each policy and design:
    the bins are timeseries.csv's (outputs.interval), filled from
    encounters.csv's rows with t0 < time <= t1, clusters = {(run, hv): [n, dc,
    coll]} for the intervals (tidy.rate_interval); each HV's first encounters
    for (c)."""
    out = {}
    for i in range(len(runs.dirs)):
        exp = (runs.config(i).get("model", {}) or {}).get("experience") or {}
        design = exp.get("design", "guarded")
        edges = {}
        for r in runs.csv(i, "timeseries.csv"):
            edges.setdefault(r["policy"], set()).add(float(r["time"]))
        per_policy = {}
        for r in runs.csv(i, "encounters.csv"):
            per_policy.setdefault(r["policy"], []).append(r)
        for policy, times in edges.items():
            times = sorted(times)
            e = out.setdefault((policy, design), {"bins": {}, "long_run": (None, None),
                                                  "first": {}, "runs": 0, "design": design})
            e["runs"] += 1
            rows = sorted(per_policy.get(policy, []), key=lambda r: float(r["time"]))
            for a, b in zip(times, times[1:]):
                e["bins"].setdefault((a, b), [0, 0, 0, 0.0, 0.0, {}])
            for r in rows:
                t = float(r["time"])
                k = bisect.bisect_left(times, t)  # times[k-1] < t <= times[k]
                if k == 0 or k == len(times):
                    continue
                acc = e["bins"][(times[k - 1], times[k])]
                dc, coll = r["hv_action"] == "DC", r["collision"] == "1"
                acc[0] += 1
                acc[1] += dc
                acc[2] += coll
                # An empty theory cell (a run without a theory: the guarded
                # design against HVs who forget or read with noise) is NaN:
                # its mean-field line has a gap there, nothing is invented.
                acc[3] += _theory(r, "theory_dc")
                acc[4] += _theory(r, "theory_collision")
                c = acc[5].setdefault((i, r["hv"]), [0, 0, 0])
                c[0] += 1
                c[1] += dc
                c[2] += coll
            p = runs.summaries[i]["policies"][policy]
            e["long_run"] = (p.get("long_run_theory_dc_rate"), p.get("long_run_theory_collision_rate"))
            per_hv = {}
            for r in rows:
                per_hv.setdefault(r["hv"], []).append(r)
            for hv_rows in per_hv.values():
                for k, r in enumerate(hv_rows[:40]):
                    t = e["first"].setdefault(k, [0, 0, 0.0])
                    t[0] += 1
                    t[1] += r["hv_action"] == "DC"
                    t[2] += _theory(r, "theory_dc")
    for e in out.values():
        e["bins"] = {k: v for k, v in e["bins"].items() if v[0] > 0}
    return out


def _theory(row, column):
    v = number(row.get(column))
    return math.nan if v is None else v


def influence_table(runs):
    """docs/influence.md's table (markdown): first and last hour pooled over
    the runs (95 % interval), the last hour's mean field, the long run, and
    whether the long run lies in the last hour's 99.9 % interval."""
    from .. import stats
    lines = ["| policy | runs | first hour DC [95 %] | first hour collisions [95 %] | "
             "last hour DC [95 %] | last hour collisions [95 %] | last hour mean field DC / coll. | "
             "long-run theory DC / coll. | long run in last hour's 99.9 % | "
             "last hour design effect DC / coll. (clusters) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    names = {"guarded": "(guarded)", "paper": "(paper's scheme)"}
    for (policy, design), e in influence_data(runs).items():
        bins = sorted(e["bins"].items())
        per_hour = max(1, round(3600 / (bins[0][0][1] - bins[0][0][0])))

        def pool(chosen):
            sums = [sum(acc[j] for _, acc in chosen) for j in range(5)]
            clusters = {}
            for _, acc in chosen:
                for key, c in acc[5].items():
                    m = clusters.setdefault(key, [0, 0, 0])
                    for j in range(3):
                        m[j] += c[j]
            return sums + [clusters]

        def fmt(k, counts):
            n = counts[0]
            lo, hi = tidy.rate_interval(counts[5], k)
            return "%.3f [%.3f, %.3f]" % (counts[k] / n if n else float("nan"), lo, hi)

        f, l = pool(bins[:per_hour]), pool(bins[-per_hour:])
        lr_dc, lr_co = e["long_run"]
        inside = []
        for k, want in ((1, lr_dc), (2, lr_co)):
            lo, hi = tidy.rate_interval(l[5], k, stats.Z999)
            inside.append(lo <= want <= hi)
        d_dc, d_co = tidy.clustered_counts(l[5], 1), tidy.clustered_counts(l[5], 2)
        label = policy + (" " + names.get(design, design) if policy == "ta_ebp" else "")
        lines.append("| %s | %d | %s | %s | %s | %s | %.3f / %.3f | %.3f / %.3f | %s | %s |" % (
            label, e["runs"], fmt(1, f), fmt(2, f), fmt(1, l), fmt(2, l),
            l[3] / l[0], l[4] / l[0], lr_dc, lr_co,
            "DC %s, collisions %s (n = %d)" % ("yes" if inside[0] else "**no**",
                                               "yes" if inside[1] else "**no**", l[0]),
            "%.2f / %.2f (%d%s)" % (d_dc["deff"], d_co["deff"], d_dc["clusters"],
                                    " ~ too few" if d_dc["few_clusters"] else "")))
    return "\n".join(lines) + "\n"


# name: (applies(runs), draw(plt, runs, out) -> [paths])
RUN_PRESETS = {
    "learned": (lambda runs: "ta_ebp_learned" in runs.policies, learned),
    "dynamic": (lambda runs: any((runs.config(i).get("model", {}) or {}).get("trust_dynamics")
                                 for i in range(len(runs.dirs))), dynamic),
    "influence": (_experienced, influence),
}
