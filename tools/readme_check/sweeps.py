"""Tier sweeps: the three shipped sweeps (trust, mismatch, penetration) and
their plots."""

import math
import os

from .commands import PEN110, PLOT, SWEEP
from .context import ROOT
from .formats import f3, same_file, tens
from .tables import inside, num, summary


# Sweep figures.
def agg(ctx, name):
    ctx.run(SWEEP[name])
    return ctx.csv("results", "sweep_" + name, "aggregate.csv")


def trust_sweep(ctx, m):
    rows = agg(ctx, "trust")
    enc = [int(r["encounters"]) for r in rows]
    ok = sum(1 for r in rows if inside(r, "dc_rate") and inside(r, "collision_rate"))
    ta6 = [r for r in rows if r["policy"] == "ta_ebp" and float(r["model.trust"]) == 0.6][0]
    pooled = ctx.csv("results", "sweep_trust", "encounters.csv")  # every encounter of the study
    go = sum(r["intent"] == "go" for r in pooled) / len(pooled)
    ta0 = [r for r in rows if r["policy"] == "ta_ebp" and num(r, "collision_rate") != 0]
    return {"enc": "%d–%d" % (min(enc), max(enc)), "inside": "%d of %d" % (ok, len(rows)),
            "dc6": f3(num(ta6, "dc_rate")), "th6": f3(num(ta6, "theory_dc_rate")),
            "go": "%.1f" % (100 * go),
            "ta_zero": "zero" if not ta0 else "collisions at %d points, not zero" % len(ta0)}


def mismatch_sweep(ctx, m):
    rows = [r for r in agg(ctx, "mismatch") if r["policy"] == "ta_ebp"]
    pred = [r for r in rows if num(r, "theory_collision_rate") > 1e-12]
    none = [r for r in rows if num(r, "theory_collision_rate") <= 1e-12]
    hit = sum(1 for r in pred if (num(r, "collision_rate") or 0) > 0)
    clean = sum(1 for r in none if (num(r, "collision_rate") or 0) == 0)
    return {"hit": "%d of %d" % (hit, len(pred)), "clean": "%d of %d" % (clean, len(none))}


def penetration_sweep(ctx, m):
    rows = agg(ctx, "penetration")
    results = ctx.csv("results", "sweep_penetration", "results.csv")
    gap = max(float(r["longest_gap_without_crossing"]) for r in results if r["status"] == "ok")
    teleports = sum(int(r["teleports"]) for r in results if r["status"] == "ok")

    def span(policy):
        v = [num(r, "throughput_all") for r in rows if r["policy"] == policy
             and r["scenario.avs"] != r["scenario.hvs"] and "0" not in (r["scenario.avs"], r["scenario.hvs"])]
        return "%s–%s" % (tens(min(v)), tens(max(v)))

    no_ebp = [num(r, "throughput_all") for r in rows if r["policy"] == "no_ebp"]
    point = [r["point"] for r in rows if r["scenario.avs"] == "10" and r["scenario.hvs"] == "6"][0]
    s80 = summary(ctx, "results", "sweep_penetration", "tasks", "%s-0" % point)  # seed 1
    ctx.run(PEN110)
    s110 = summary(ctx, "results", "pen_110")
    return {"gap": "%.1f" % gap, "teleports": "no teleport" if teleports == 0 else "%d teleports" % teleports,
            "no_ebp_all": "%s–%s" % (tens(min(no_ebp)), tens(max(no_ebp))),
            "ta": span("ta_ebp"), "nt": span("no_trust"), "ne": span("no_ebp"),
            "ta80": "%.0f" % s80["ta_ebp"]["throughput_all"],
            "nt80": "%.0f" % s80["no_trust"]["throughput_all"],
            "ta110": "%.0f" % s110["ta_ebp"]["throughput_all"],
            "nt110": "%.0f" % s110["no_trust"]["throughput_all"]}


def pooled_sizes(ctx, m):
    mb = max(os.path.getsize(ctx.path("results", "sweep_" + n, "encounters.csv"))
             for n in ("trust", "mismatch", "penetration")) / 1e6
    return {"mb": m.group("mb") if mb < float(m.group("mb")) else "%d" % math.ceil(mb)}


def plot_picture(name, png):
    def values(ctx, m):
        ctx.run(SWEEP[name])
        ctx.run(PLOT[name])
        fresh = ctx.path("results", "sweep_" + name, png)
        return {"picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs", "img", png))
                else "a different picture (fresh: %s)" % fresh}
    return values
