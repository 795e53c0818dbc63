"""The run presets (presets.RUN_PRESETS): the time series of runs beyond the
paper, pooling only runs of one config (a sweep's point, or run folders that
differ only in their seed): learned trust (learned_rates.png,
learned_regret.png), dynamic trust (dynamic_trust.png) and HVs who learn
what a nudge meant (influence.png, and docs/influence.md's table)."""

import bisect
import math

from . import style, tidy
from .common import PlotError, number, warn
from .view import Figure, Mark, Panel


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
