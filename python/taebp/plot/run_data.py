"""The run presets' data functions (presets.RUN_PRESETS): the time series of
runs beyond the paper as long rows, pooling only runs of one config (a
sweep's point, or run folders that differ only in their seed). Each takes
(runs, group name, run indices) and returns {"rows": [...], name: value}
(None: no figure for this group); a row is one point of a series: panel,
role, x, y and optionally policy, series (a run), variant, lo, hi, note
(declare.Series). Learned trust (rates per hour, regret, failures),
dynamic trust (the mean trust), HVs who learn what a nudge meant (rates per
interval, by encounter number, and docs/influence.md's table). Nothing here
makes a panel or a mark."""

import bisect
import math

from . import style, tidy
from .common import number, warn


def _policies(runs, idx):
    return [p for p in style.policy_order() if any(
        p in runs.summaries[i].get("policies", {}) for i in idx)]


# ------------------------------------------------------------------ learned trust
def learned_rates(runs, name, idx):
    """DC and collision rate per simulated hour for every policy (95 %
    intervals), the oracle's expected DC on the learner's encounters."""
    if not any("ta_ebp_learned" in runs.summaries[i].get("policies", {}) for i in idx):
        return None
    policies = _policies(runs, idx)
    bins = tidy.binned_rates(runs, idx, 3600.0)
    rows = []
    for policy in policies:
        got = bins.get(policy, [])
        for panel, k in (("dc", 3), ("coll", 4)):
            for b in got:
                lo, hi = tidy.rate_interval(b[6], k - 2)
                rows.append({"panel": panel, "role": "rate", "policy": policy,
                             "x": (b[0] + b[1]) / 2 / 3600, "y": b[k] / b[2], "lo": lo, "hi": hi})
        if policy == "ta_ebp_learned":
            rows += [{"panel": "dc", "role": "oracle", "policy": policy,
                      "x": (b[0] + b[1]) / 2 / 3600, "y": b[5] / b[2]} for b in got]
    return {"rows": rows, "policies": policies}


def _regret_curves(runs, idx, policy):
    """Each run's cumulative expected regret of `policy` over its encounters."""
    curves = []
    for i in idx:
        acc, curve = 0.0, []
        for r in runs.csv(i, "encounters.csv"):
            if r["policy"] == policy:
                acc += number(r.get("regret")) or 0.0
                curve.append(acc)
        if curve:
            curves.append(curve)
    return curves


def learned_regret(runs, name, idx):
    """The cumulative expected regret against the oracle over the encounters
    (each seed and their mean; the learner alone and every policy), the
    learner's failures against the number its posterior predicted and the
    budget, a line of slope 1; `zero`: the policies whose regret is 0."""
    if not any("ta_ebp_learned" in runs.summaries[i].get("policies", {}) for i in idx):
        return None
    rows, zero, ends = [], [], []
    for policy in _policies(runs, idx):
        curves = _regret_curves(runs, idx, policy)
        if not curves:
            continue
        n = min(len(c) for c in curves)
        mean = [sum(c[t] for c in curves) / len(curves) for t in range(n)]
        if max(abs(v) for v in mean) < 1e-9:
            zero.append(style.policy_label(policy))
            continue
        for panel in ["every"] + (["learner"] if policy == "ta_ebp_learned" else []):
            if len(curves) > 1:
                rows += [{"panel": panel, "role": "seed", "policy": policy, "series": j,
                          "x": t + 1, "y": v} for j, c in enumerate(curves)
                         for t, v in enumerate(c)]
            rows += [{"panel": panel, "role": "mean", "policy": policy, "x": t + 1, "y": v}
                     for t, v in enumerate(mean)]
        ends.append((n, mean[-1]))
        if policy == "ta_ebp_learned":
            rows += _failures(runs, idx, policy)
    if ends:
        t_max = max(e[0] for e in ends)
        ref = min(e[1] for e in ends) / t_max / 3  # slope 1 below every curve's end
        rows += [{"panel": "every", "role": "linear", "x": x, "y": y}
                 for x, y in ((1, ref), (t_max, ref * t_max))]
    return {"rows": rows, "zero": ", ".join(zero), "several": len(idx) > 1}


def _failures(runs, idx, policy):
    """Per run: the learner's failures to persuade over its nudges, the
    number its posterior expected, and delta x nudges (the budget)."""
    delta = ((runs.config(idx[0]).get("model", {}) or {}).get("learning") or {}).get(
        "delta", 0.01)
    rows = []
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
        for role, ys in (("failures", fx), ("expected", ex), ("budget", [delta * v for v in x])):
            rows += [{"panel": "fails", "role": role, "policy": policy, "series": j,
                      "x": a, "y": b} for a, b in zip(x, ys)]
    return rows


# ------------------------------------------------------------------ dynamic trust
def dynamic(runs, name, idx):
    """The population's mean trust over time per policy (each seed, their
    mean), its mean-field prediction and the long-run trust the theory
    derives; the dynamics' weights for the title."""
    d = (runs.config(idx[0]).get("model", {}) or {}).get("trust_dynamics")
    if not d:
        return None
    rows = []
    for policy in [p for p in style.policy_order() if p in runs.policies]:
        rows += _mean_trust(runs, idx, policy)
    return {"rows": rows, "several": len(idx) > 1, "w_s": d.get("success_weight", 1),
            "w_f": d.get("failure_weight", 1), "rho": d.get("forgetting", 0),
            "strength": d.get("strength", 10)}


def _mean_trust(runs, idx, policy):
    """One policy's rows of the dynamic trust figure."""
    per_run = []
    for i in idx:
        pts = [(float(r["time"]) / 3600, number(r["mean_trust"]), number(r.get("mean_field_trust")))
               for r in runs.csv(i, "timeseries.csv")
               if r["policy"] == policy and number(r["mean_trust"]) is not None]
        if pts:
            per_run.append(pts)
    if not per_run:
        return []
    n = min(len(p) for p in per_run)
    row = {"panel": "trust", "policy": policy}
    rows = [dict(row, role="seed", series=j, x=p[0], y=p[1])
            for j, pts in enumerate(per_run) for p in pts] if len(per_run) > 1 else []
    rows += [dict(row, role="mean", x=per_run[0][t][0],
                  y=sum(p[t][1] for p in per_run) / len(per_run)) for t in range(n)]
    rows += [dict(row, role="field", x=per_run[0][t][0],
                  y=sum(p[t][2] for p in per_run) / len(per_run))
             for t in range(n) if all(p[t][2] is not None for p in per_run)]
    longs = [runs.summaries[i]["policies"][policy].get("expected_long_run_trust")
             for i in idx if policy in runs.summaries[i].get("policies", {})]
    longs = [v for v in longs if v is not None]
    if longs:
        rows.append(dict(row, role="long", y=longs[0], note=" long run %.3f" % longs[0]))
    return rows


# ------------------------------------------------------------------ influence
def influence(runs, name, idx):
    """HVs who learn what a nudge meant (docs/influence.md): DC and collision
    rate per outputs.interval (95 % intervals), the mean field and the long
    run, and the DC rate by each HV's own encounter number; the designs
    (ta_ebp's, told apart), the interval in minutes, the most seeds pooled."""
    data = influence_data(runs)
    designs = sorted({e["design"] for e in data.values()}, key=lambda d: d != "guarded")
    rows = []
    for (policy, design), e in sorted(data.items(), key=lambda kv: (
            style.policy_order().index(kv[0][0]) if kv[0][0] in style.policy_order() else 99,
            kv[0][1] != "guarded")):
        rows += _influence_rows(e, policy, designs.index(design))
    return {"rows": rows, "designs": designs, "minutes": "%g" % round(_width(data) / 60),
            "runs": max(e["runs"] for e in data.values()),
            "ctx": runs.context([0]).rsplit(",", 1)[0]}


def _influence_rows(e, policy, v):
    """One (policy, design)'s rows of influence.png."""
    row = {"policy": policy, "variant": v}
    rows = []
    bins = sorted(e["bins"].items())
    x = [(a + b) / 2 / 3600 for (a, b), _ in bins]
    for panel, k, th, lr in (("a", 1, 3, e["long_run"][0]), ("b", 2, 4, e["long_run"][1])):
        ivs = [tidy.rate_interval(acc[5], k) for _, acc in bins]
        rows += [dict(row, panel=panel, role="rate", x=t, y=acc[k] / acc[0], lo=c[0], hi=c[1])
                 for t, (_, acc), c in zip(x, bins, ivs)]
        rows += [dict(row, panel=panel, role="field", x=t, y=acc[th] / acc[0])
                 for t, (_, acc) in zip(x, bins)]
        if lr is not None:
            rows.append(dict(row, panel=panel, role="long", y=lr))
    first = sorted(e["first"].items())
    rows += [dict(row, panel="c", role="first", x=i + 1, y=t[1] / t[0]) for i, t in first]
    rows += [dict(row, panel="c", role="field", x=i + 1, y=t[2] / t[0]) for i, t in first]
    return rows


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
