"""Tier beyond (and the influence studies of tier studies): learned and
dynamic trust, the noise sweep, the robust design, the learners the AV is
not told, and their pictures."""

import math
import os

from .commands import LEARNERS, LEARNERS_K, LEARNERS_PLOT, NOISY
from .context import ROOT
from .formats import fixed, rate_ci, same_file
from .tables import num, summary


POLICY_NAMES = {"no_trust": "No Trust", "population_mean": "population_mean", "ta_ebp": "TA-EBP (oracle)",
                "ta_ebp_learned": "ta_ebp_learned", "full_reveal": "full_reveal", "no_ebp": "No EBP"}


def learned_table(ctx):
    rows = ["| policy | encounters | collision rate [95 % interval] | DC rate [95 % interval] | "
            "theory for these 8 HVs: DC / collisions | last hour: DC rate [95 % interval] | regret per encounter |",
            "|---|---|---|---|---|---|---|"]
    for name, p in summary(ctx, "results", "learned_trust").items():
        rows.append("| %s | %d | %s | %s | %s / %s | %s | %.4f |" % (
            POLICY_NAMES.get(name, name), p["encounters"], rate_ci(p, "collision_rate"),
            rate_ci(p, "dc_rate"), fixed(p["theory_given_hvs_dc_rate"]),
            fixed(p["theory_given_hvs_collision_rate"]), rate_ci(p, "last_hour_dc_rate"),
            p["regret_per_encounter"]))
    return "\n".join(rows)


def learned_values(ctx, m):
    s = summary(ctx, "results", "learned_trust")
    ln, ta = s["ta_ebp_learned"], s["ta_ebp"]
    curve, acc = [], 0.0
    for r in ctx.csv("results", "learned_trust", "encounters.csv"):
        if r["policy"] == "ta_ebp_learned":
            acc += float(r["regret"])
            curve.append(acc)
    return {"table": learned_table(ctx),
            "ratio": "%.0f" % (100 * ln["last_hour_dc_rate"] / ta["last_hour_dc_rate"]),
            "failures": str(ln["failures"]),
            "expected": "%.1f" % ln["expected_failures"],
            "probes": str(ln["learning_probes"]),
            "r100": "%.0f" % curve[99], "r1000": "%.0f" % curve[999], "r3000": "%.0f" % curve[2999],
            "rend": "%.0f" % curve[-1], "tend": str(len(curve))}


def dynamic_table(ctx):
    rows = ["| policy | encounters | mean trust after 6 h: simulation / mean field | long-run trust (theory) | "
            "collision rate [95 % interval] | DC rate [95 % interval] | theory at the long-run trust: DC / collisions |",
            "|---|---|---|---|---|---|---|"]
    for name, p in summary(ctx, "results", "dynamic_trust").items():
        td = p["trust_dynamics"]
        rows.append("| %s | %d | %.3f / %.3f | %s | %s | %s | %s / %s |" % (
            POLICY_NAMES.get(name, name).replace(" (oracle)", ""), p["encounters"], p["final_mean_trust"],
            p["final_mean_field_trust"], ", ".join("%.4g" % a for a in td["attractors"]),
            rate_ci(p, "collision_rate"), rate_ci(p, "dc_rate"),
            fixed(p["long_run_theory_dc_rate"]), fixed(p["long_run_theory_collision_rate"])))
    return "\n".join(rows)


def robust_values(ctx, m):
    """docs/influence.md: the robust design against HVs who forget (issue 42's acceptance)."""
    rows = ["| policy | encounters | collision rate [95 % interval] | DC rate [95 % interval] | "
            "long run (theory): DC / collisions |", "|---|---|---|---|---|"]
    s = summary(ctx, "results", "influence_robust")
    for name, p in s.items():
        rows.append("| %s | %d | %s | %s | %s / %s |" % (
            name, p["encounters"], rate_ci(p, "collision_rate"), rate_ci(p, "dc_rate"),
            fixed(round(p["long_run_theory_dc_rate"], 12)),
            fixed(round(p["long_run_theory_collision_rate"], 12))))
    gap = s["ta_ebp"]["dc_rate"] - s["full_reveal"]["dc_rate"]
    return {"table": "\n".join(rows), "gap": "%.3f" % gap}


# issue 42's bound: a design is safe at most this many collisions per encounter.
SAFE_COLLISIONS = 0.01


def learners_table(rows):
    """docs/influence.md's table of the learners study (aggregate.csv rows):
    per learner (forgetting rho), ta_ebp under each design, then the policies
    that read no design key (their runs are the same under every design)."""
    out = ["| learner ρ | policy (design) | encounters | collisions [95 %%] | DC [95 %%] | "
           "mean field DC / collisions | safe (collisions' upper bound ≤ %g) |" % SAFE_COLLISIONS,
           "|---|---|---|---|---|---|---|"]
    seen = set()
    for r in rows:
        rho, design, policy = r["model.experience.forgetting"], r["model.experience.design"], r["policy"]
        if policy != "ta_ebp":
            if (rho, policy) in seen:
                continue
            seen.add((rho, policy))
            name = policy
        else:
            name = "ta_ebp (%s)" % design
        # Empty where the runner has no theory (the guarded design against
        # HVs who forget: its path is not modelled).
        theory = ("not modelled" if num(r, "theory_dc_rate") is None
                  else "%s / %s" % (fixed(round(num(r, "theory_dc_rate"), 12)),
                                    fixed(round(num(r, "theory_collision_rate"), 12))))
        out.append("| %s | %s | %s | %s | %s | %s | %s |" % (
            rho, name, r["encounters"], rate_ci(r, "collision_rate"), rate_ci(r, "dc_rate"), theory,
            "yes" if num(r, "collision_rate_hi") <= SAFE_COLLISIONS else "no"))
    return "\n".join(out)


def learners_within(rows):
    """The largest gap between a measured rate and its mean field, rounded up
    to 0.001, over the rows whose theory is modelled."""
    gap = 0.0
    for r in rows:
        for metric in ("dc_rate", "collision_rate"):
            th = num(r, "theory_" + metric)
            if th is not None:
                gap = max(gap, abs(num(r, metric) - th))
    return "%.3f" % (math.ceil(gap * 1000 - 1e-9) / 1000)


def learners_values(ctx, m):
    ctx.run(LEARNERS)
    rows = ctx.csv("results", "influence_learners", "aggregate.csv")
    return {"table": learners_table(rows), "within": learners_within(rows)}


def learners_k_values(ctx, m):
    ctx.run(LEARNERS_K)
    return {"table": learners_table(ctx.csv("results", "influence_learners_k", "aggregate.csv"))}


def noisy_table(summaries):
    """docs/influence.md's noisy learners: (design, summary.json's policies) in order."""
    out = ["| ta_ebp's design | policy | encounters | collisions [95 %] | DC [95 %] |",
           "|---|---|---|---|---|"]
    for design, policies in summaries:
        for name, p in policies.items():
            out.append("| %s | %s | %d | %s | %s |" % (design, name, p["encounters"],
                                                       rate_ci(p, "collision_rate"), rate_ci(p, "dc_rate")))
    return "\n".join(out)


def noisy_values(ctx, m):
    for d in NOISY:
        ctx.run(NOISY[d])
    return {"table": noisy_table([(d, summary(ctx, "results", "noisy_" + d)) for d in NOISY])}


def learners_picture(png):
    def values(ctx, m):
        ctx.run(LEARNERS)
        ctx.run(LEARNERS_PLOT)
        fresh = ctx.path("results", "influence_learners", png)
        return {"picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs", "img", png))
                else "a different picture (fresh: %s)" % fresh}
    return values


def dynamic_values(ctx, m):
    return {"table": dynamic_table(ctx)}


def noise_table(ctx):
    rows = ["| σ (m) | design | encounters | collision rate [95 % interval] | theory | DC rate [95 % interval] | theory |",
            "|---|---|---|---|---|---|---|"]
    for r in ctx.csv("results", "noise", "aggregate.csv"):
        rows.append("| %s | %s | %s | %s | %s | %s | %s |" % (
            r["model.noise.scale"], r["model.noise.design"], r["encounters"],
            rate_ci(r, "collision_rate", 4),
            fixed(round(num(r, "theory_collision_rate"), 12), 4),
            rate_ci(r, "dc_rate", 4),
            fixed(round(num(r, "theory_dc_rate"), 12), 4)))
    return "\n".join(rows)


def noise_values(ctx, m):
    rows = ctx.csv("results", "noise", "aggregate.csv")
    aware = [r for r in rows if r["model.noise.design"] == "aware"]
    within = sum(1 for r in aware if num(r, "collision_rate_lo") <= 0.01 * 0.2 + 1e-12)
    return {"table": noise_table(ctx), "within": "%d of %d" % (within, len(aware))}


def beyond_picture(name, png):
    def values(ctx, m):
        fresh = ctx.path("results", {"learned": "learned_trust", "dynamic": "dynamic_trust",
                                     "noise": "noise"}[name], png)
        return {"picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs", "img", png))
                else "a different picture (fresh: %s)" % fresh}
    return values
