"""The sweep presets beyond the paper (presets.PRESETS): perception noise
(noise_sigma.png: the noise-aware design and the paper's s* against the
noise's sigma) and the learners the AV is not told (influence_learners.png,
influence_learners_frontier.png)."""

from . import style
from .common import number, warn
from .sweep_presets import _save
from .view import Figure, Mark, Panel, SweepView


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

    def design_of(r):
        return r.get("model.noise.design") or cfg.get("design", "aware")

    designs = []
    for r in sweep.rows:
        if design_of(r) not in designs:
            designs.append(design_of(r))
    designs.sort(key=lambda d: (d != "aware", d))
    names = {"aware": "noise-aware design s_δ", "paper": "the paper's s*"}
    sigmas = sorted({number(r["model.noise.scale"]) for r in sweep.rows} - {None})
    dense = _noise_theory(sweep, theory, sigmas, kind, bias, delta)

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

    common = dict(x_title="noise σ of the HV's reading (m)", theory=curve,
                  extra=_noise_marks(dense, delta, lam),
                  variant_of=lambda r: designs.index(design_of(r)),
                  variant_labels=[names.get(d, d) for d in designs])
    main = SweepView(sweep, "model.noise.scale", ["dc_rate", "collision_rate"], **common)
    panels = main.panels()
    if "aware" in designs:
        panels.append(_noise_zoom(sweep, common, design_of, names["aware"], delta, lam))
    for p in panels:
        p.xlim = (-0.01 * max(sigmas), max(sigmas) * 1.05)
    ctx = sweep.context()
    fig = main.figure("noise_sigma.png", panels, 3)
    fig.title = "Perception noise (%s, δ = %g)%s" % (kind, delta, (": " + ctx) if ctx else "")
    return _save(plt, [fig], out)


def _noise_theory(sweep, theory, sigmas, kind, bias, delta):
    """The theory over a dense grid of sigma from taebp: (grid, results, the
    paper's result at sigma 0), both sides of where the aware design gives up
    in the grid; None without taebp, when it fails, or for a distribution of
    trust (the theory columns are drawn then)."""
    trust_ = sweep.model("trust")
    assumed = sweep.model("assumed_trust")
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
    return dense


def _noise_marks(dense, delta, lam):
    """extra(panel, metric, facet) of the noise figure: the paper's result at
    sigma 0, the bound delta * lambda, where the aware AV yields (shaded)."""
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
    return extra


def _noise_zoom(sweep, common, design_of, aware_name, delta, lam):
    """The panel that zooms on the aware design's collisions."""
    zoom = SweepView(sweep, "model.noise.scale", ["collision_rate"],
                     select=lambda r: design_of(r) == "aware",
                     metric_titles={"collision_rate": "Collisions, noise-aware design (zoom)"},
                     **dict(common, variant_of=lambda r: 0,
                            variant_labels=[aware_name]))
    zp = zoom.panels()[0]
    zp.group = "zoom"
    his = [number(r.get("collision_rate_hi")) for r in sweep.rows if design_of(r) == "aware"]
    zp.ylim = (0, max([3 * (delta or 0.01) * (lam or 0.2)] + [h for h in his if h]) * 1.1)
    return zp


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
