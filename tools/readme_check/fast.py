"""Tier fast: the figures of configs/paper.yaml's run (Table I, its notes,
the stop distance 1.7), the theory, the LP, the snapshot, the network map
and Getting started's step-by-step block."""

import json
import os
import re

from .commands import (MAP_PLOT, MAP_RUN, PAPER, SEEDS, SNAPSHOT, SOLVE_AVHV, SOLVE_PROSECUTOR,
                       STOP17, THEORY, THEORY_NO_TRUST)
from .context import ROOT
from .formats import f3, frac, md, png_size, same_file, strip_lines
from .tables import summary


def table_printout(ctx, m):
    return {"block": strip_lines(ctx.run(PAPER).stdout)}


def table_markdown(ctx, m):
    s = summary(ctx, "results", "paper")
    out = {}
    for policy in ("no_ebp", "no_trust", "ta_ebp"):
        for metric in ("collision", "dc"):
            p = s[policy]
            lo, hi = p[metric + "_rate_lo"], p[metric + "_rate_hi"]
            out["%s_%s" % (policy, metric)] = "%s [%s, %s]" % (md(p[metric + "_rate"]), md(lo), md(hi))
    out["no_trust_th"] = "%g" % s["no_trust"]["theory_collision_rate"]
    out["ta_ebp_th"] = "%g" % s["ta_ebp"]["theory_dc_rate"]
    return out


def table_notes(ctx, m):
    s = summary(ctx, "results", "paper")
    half = max((p[k + "_rate_hi"] - p[k + "_rate_lo"]) / 2
               for p in s.values() for k in ("collision", "dc"))
    ta = s["ta_ebp"]
    out = {"width": "0.05" if half < 0.05 else "%.2f" % half,
           "nudge_share": "%.1f" % (100 * ta["nudges"] / ta["encounters"]),
           "encounters": str(ta["encounters"])}
    ctx.run(SEEDS)
    rates, inside = [], True
    for seed in (2, 3, 4, 5):
        p = summary(ctx, "results", "paper_seed%d" % seed)["ta_ebp"]
        rates.append(f3(p["dc_rate"]))
        inside = inside and p["dc_rate_lo"] <= p["theory_dc_rate"] <= p["dc_rate_hi"]
    out["seeds"] = ", ".join(rates)
    out["containing"] = "%g" % ta["theory_dc_rate"] if inside else "(not every interval)"
    return out


def stop17(ctx, m):
    r = ctx.run(STOP17)
    s = summary(ctx, "results", "paper_stop17")
    return {"no_trust": f3(s["no_trust"]["collision_rate"]),
            "ta_ebp": f3(s["ta_ebp"]["collision_rate"]),
            "block": strip_lines(r.stdout)}


def theory_block(ctx, m):
    out = ctx.run(THEORY).stdout.splitlines()
    shown = [l for l in m.group("block").splitlines() if l.startswith("  ")]
    missing = [l for l in shown if l.rstrip() not in [o.rstrip() for o in out]]
    # The README shows a subset of the lines: each must be printed as shown.
    return {"block": m.group("block") if not missing else
            "lines not printed: %s\n(output:\n%s)" % (missing, "\n".join(out))}


def theory_numbers(ctx, m):
    ta = json.loads(ctx.run(THEORY + " --json").stdout)
    nt = json.loads(ctx.run(THEORY_NO_TRUST).stdout)
    return {"s_star": f3(ta["s_star"]), "s_hat": "%.4f" % nt["s_star"]}


def solve_values(ctx, m):
    # The README shows the table form; the values come from the same calls' --json.
    j_av = json.loads(ctx.run(SOLVE_AVHV + " --json").stdout)
    j_pr = json.loads(ctx.run(SOLVE_PROSECUTOR + " --json").stdout)
    dc = j_av["actions"].index("DC")
    convict, innocent = j_pr["actions"].index("convict"), j_pr["states"].index("innocent")
    return {"lp_dc": "%g" % round(j_av["signal_probability"][dc], 12),
            "prosecutor": "%g" % round(j_pr["sender_value"], 12),
            "convict": frac(j_pr["scheme"][innocent][convict])}


def snapshot_caption(ctx, m):
    ctx.run(PAPER)
    at = 20.0
    rows = [r for r in ctx.csv("results", "paper", "encounters.csv")
            if r["policy"] == "ta_ebp" and float(r["time"]) <= at]
    last = rows[-1]
    return {"av": last["av"], "hv": last["hv"], "nudge": f3(float(last["commanded_nudge"])),
            "stays": "stays there" if last["intent"] == "stop" else "goes",
            "hv_action": "chose to drive if clear" if last["hv_action"] == "DC"
            else "chose to drive recklessly"}


def snapshot_picture(ctx, m):
    ctx.run(SNAPSHOT)
    fresh = ctx.path("docs", "img", "figure8.png")
    w, h = png_size(fresh)
    raw = ctx.path("results", "figure8_raw.png")
    ctx.run(SNAPSHOT.replace("--out docs/img/figure8.png", "--out results/figure8_raw.png") + " --no-legend")
    rw, rh = png_size(raw)
    return {"picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs/img/figure8.png"))
            else "a different picture (%s)" % fresh,
            "view": "%d x %d" % (rw, rh), "size": "%d x %d" % (w, h)}


def network_map(ctx, m):
    ctx.run(MAP_RUN)
    ctx.run(MAP_PLOT)
    s = ctx.json("results", "grid_map", "summary.json")
    fresh = ctx.path("docs", "img", "network_map.png")
    return {"block": MAP_RUN + "\n" + MAP_PLOT + "\n",
            "picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs", "img", "network_map.png"))
            else "a different picture (%s)" % fresh,
            "no_ebp": str(s["policies"]["no_ebp"]["encounters"]),
            "ta": str(s["policies"]["ta_ebp"]["encounters"])}


def newcomer(ctx, m):
    """README "Your own network, step by step": its block run as written (bash,
    in the scratch directory), then the figures its text quotes."""
    r = ctx.run(m.group("block"))
    s = ctx.json("results", "mynet", "summary.json")["policies"]
    ta = s["ta_ebp"]
    with open(ctx.path("mynet", "trips.xml"), encoding="utf-8") as f:
        trips = f.read().count("<trip ")
    if not os.path.exists(ctx.path("results", "mynet_demand", "network_throughput.png")):
        raise ValueError("tools/plot drew no network_throughput.png")
    if not os.path.exists(ctx.path("results", "mynet_B1.png")):
        raise ValueError("the snapshot is missing")
    printed = [l for l in r.stdout.splitlines() if re.match(r"^[A-Z]\d+ \d+ ", l)]
    return {"trips": str(trips),
            "no_ebp": str(s["no_ebp"]["encounters"]), "ta": str(ta["encounters"]),
            "dc": f3(ta["dc_rate"]), "th": "%g" % ta["theory_dc_rate"],
            "native_flow": "%.0f" % s["sumo_native"]["served_flow"],
            "ta_flow": "%.0f" % ta["served_flow"],
            "printed": "\n".join(printed)}
