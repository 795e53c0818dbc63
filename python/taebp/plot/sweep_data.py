"""The sweep presets' data functions (presets.PRESETS): what is the study's
own math, not drawing. Each takes (sweep, theory) and returns the entries
its declaration reads (declare.From): dense theory curves and theta* from
`taebp theory --json`, the cells where the theory predicts collisions, the
AV share of a fleet, the AV shares at which pairs can meet, the noise
design's theory and bound. Nothing here makes a panel or a mark."""

from .common import die, number, warn


def _numbers(sweep, key, rows=None):
    return sorted({number(r[key]) for r in (sweep.rows if rows is None else rows)} - {None})


def _theory_columns(sweep, key, metric, keep):
    """(xs, ys) of aggregate.csv's theory_METRIC against `key` over the rows
    `keep(row)` keeps, or None without values."""
    pts = sorted((number(r[key]), number(r.get("theory_" + metric)))
                 for r in sweep.rows if keep(r))
    pts = [p for p in pts if p[0] is not None and p[1] is not None]
    return ([p[0] for p in pts], [p[1] for p in pts]) if pts else None


# ------------------------------------------------------------------ trust
def trust(sweep, theory):
    """curve(metric, policy, facet, variant): the dense theory (both sides of
    each jump) or the theory columns; theta_star: its vline and note (from
    taebp, else bracketed by the swept thetas where TA-EBP persuades)."""
    others = [k for k in sweep.keys if k != "model.trust"]
    if others:
        warn("also swept: %s; told apart by line style" % ", ".join(others))
    thetas = _numbers(sweep, "model.trust")
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
        return _theory_columns(sweep, "model.trust", metric, lambda r: r["policy"] == policy)

    return {"curve": curve, "theta_star": _theta_star_line(sweep, theta_star)}


def _theta_star_line(sweep, theta_star):
    """theta* as a vline and its note; without taebp, between the largest
    swept theta where TA-EBP does not persuade and the smallest where it does."""
    if theta_star is not None:
        return {"xs": [theta_star], "note": " θ* = %.3g" % theta_star}
    ta = [(number(r["model.trust"]), (number(r.get("theory_dc_rate")) or 0) > 0)
          for r in sweep.rows if r["policy"] == "ta_ebp"]
    yes = [t for t, p in ta if p]
    if not yes:
        return None
    at = min(yes)
    no = [t for t, p in ta if not p and t < at]
    return {"xs": [at], "note": (" θ* in (%.3g, %.3g]" % (max(no), at)) if no else
            (" θ* ≤ %.3g" % at)}


# ------------------------------------------------------------------ mismatch
def mismatch(sweep, theory, policy="ta_ebp"):
    """The policy drawn (ta_ebp, else the first), the cells where the theory
    predicts collisions ({(theta, theta_hat): bool}: the theory columns,
    the rest from taebp) and theta*."""
    if policy not in sweep.policies:
        policy = sweep.policies[0]
        warn("no ta_ebp rows: the heat maps show %s" % policy)
    rows = [r for r in sweep.rows if r["policy"] == policy]
    xs, ys = _numbers(sweep, "model.trust", rows), _numbers(sweep, "model.assumed_trust", rows)
    if not xs or not ys:
        die("mismatch: no numeric model.trust / model.assumed_trust values")
    cell = {(number(r["model.trust"]), number(r["model.assumed_trust"])): r for r in rows}
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
    return {"policy": policy, "predicted": predicted, "theta_star": theta_star}


# ------------------------------------------------------------------ penetration
def penetration(sweep, theory):
    """share(row): avs / (avs + hvs); total(row): the fleet's size; the
    track and the fleet for the title, the context with the fleet's keys."""
    def count(r, key):
        return number(r.get(key)) if key in sweep.keys else number(str(sweep.scenario(
            key.split(".", 1)[1], "")))

    def share(r):
        avs, hvs = count(r, "scenario.avs"), count(r, "scenario.hvs")
        if avs is None or hvs is None or avs + hvs <= 0:
            return None
        return avs / (avs + hvs)

    def total(r):
        return int(count(r, "scenario.avs") + count(r, "scenario.hvs"))

    totals = sorted({total(r) for r in sweep.rows if share(r) is not None})
    loop = sweep.scenario("loop_length")
    ctx = sweep.context(keys=sweep.keys + ["scenario.avs", "scenario.hvs"])
    return {"share": share, "total": total, "ctx": (": " + ctx) if ctx else "",
            "track": ("%g m loops of the figure-8" % loop) if loop else "the figure-8",
            "fleet": ("%d vehicles" % totals[0]) if len(totals) == 1 else
            "%s vehicles" % " or ".join(str(t) for t in totals)}


# ------------------------------------------------------------------ networks
def network(sweep, theory):
    """The demand key and its title, the AV share key (panel columns), the
    shares at which an AV-HV pair can meet (select, and the caption's note),
    the grid for the title, and whether AV and HV delays were measured."""
    key = "scenario.demand.flow" if "scenario.demand.flow" in sweep.keys else \
        "scenario.routes_scale"
    share = "scenario.av_share" if "scenario.av_share" in sweep.keys else None
    select, note = _game_shares(sweep, share)
    grid = sweep.scenario("grid") or {}
    kinds = {"allway_stop": "all-way stops", "priority_stop": "two-way stops"}
    where = ("%d x %d grid of %s" % (grid.get("columns"), grid.get("rows"),
                                     kinds.get(grid.get("junction_type"),
                                               "stop-controlled junctions"))
             if grid else "")
    return {"demand": key, "share": share, "select": select, "note": note,
            "place": ", ".join(t for t in (where, sweep.context()) if t),
            "x_title": ("demand per fringe edge (veh/h)" if key == "scenario.demand.flow"
                        else "route files' demand scale (scenario.routes_scale)"),
            "av_hv": any(number(r.get("time_loss_mean_av")) is not None for r in sweep.rows)}


def _game_shares(sweep, key):
    """(select, caption note): the AV shares at which an AV-HV pair can
    meet; at 0 and 1 every policy is SUMO's own traffic (one curve)."""
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


# ------------------------------------------------------------------ noise
def noise(sweep, theory):
    """design_of(row); the theory curve exact over the noise (or the theory
    columns); the paper's result at sigma 0; the bound delta * lambda; the
    sigmas where the aware AV yields; the zoom's rows and y range; x range."""
    cfg = sweep.model("noise", {}) or {}
    kind = cfg.get("kind", "gaussian")
    delta = number(str(cfg.get("delta", 0.01)))
    bias = number(str(cfg.get("bias", 0.0))) or 0.0
    lam = sweep.model("prior_go", 0.2)

    def design_of(r):
        return r.get("model.noise.design") or cfg.get("design", "aware")

    designs = sorted({design_of(r) for r in sweep.rows}, key=lambda d: (d != "aware", d))
    sigmas = _numbers(sweep, "model.noise.scale")
    dense = _noise_theory(sweep, theory, sigmas, kind, bias, delta)

    def curve(metric, policy, facet, variant):
        design = designs[variant]
        if dense is not None and policy in ("ta_ebp", "population_mean"):
            if design == "aware":
                return dense[0], [d["noise"]["aware"][metric] for d in dense[1]]
            return dense[0], [d["noise"]["policies"]["ta_ebp"][metric] for d in dense[1]]
        return _theory_columns(sweep, "model.noise.scale", metric,
                               lambda r: r["policy"] == policy and design_of(r) == design)

    gave_up = [g for g, d in zip(dense[0], dense[1])
               if d["noise"]["aware"]["status"] == "unachievable"] if dense else []
    his = [number(r.get("collision_rate_hi")) for r in sweep.rows if design_of(r) == "aware"]
    return {"kind": kind, "delta": delta, "design_of": design_of, "curve": curve,
            "has_aware": "aware" in designs, "aware": lambda r: design_of(r) == "aware",
            "at_zero": {m: (0, dense[2][m]) for m in dense[2]} if dense else None,
            "bound": delta * lam if delta is not None and lam is not None else None,
            "gave_up": (min(gave_up), max(dense[0])) if gave_up else None,
            "zoom_ylim": (0, max([3 * (delta or 0.01) * (lam or 0.2)] + [h for h in his if h])
                          * 1.1),
            "xlim": (-0.01 * max(sigmas), max(sigmas) * 1.05)}


def _noise_theory(sweep, theory, sigmas, kind, bias, delta):
    """The theory over a dense grid of sigma from taebp: (grid, results, the
    paper's result at sigma 0), both sides of where the aware design gives up
    in the grid; None without taebp, when it fails, or for a distribution of
    trust (the theory columns are drawn then)."""
    trust_ = sweep.model("trust")
    assumed = sweep.model("assumed_trust")
    if not isinstance(trust_, (int, float)):
        warn("model.trust is a distribution: theory drawn through the theory columns")
        return None
    if not theory.available():
        return None
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
        return (grid, results, zero)
    except (RuntimeError, ValueError, KeyError) as e:
        warn("theory from taebp failed (%s): drawing the theory columns instead" % e)
        return None


# ------------------------------------------------------------------ learners
def learners(sweep, theory):
    """The design key (panel columns) when ta_ebp's design is swept."""
    return {"design": "model.experience.design" if "model.experience.design" in sweep.keys
            else None}
