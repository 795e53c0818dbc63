"""Tier studies: Table I over 40 seeds, the grids' theory per encounter and
efficiency, the efficiency and city studies, their pictures, the OSM
example and the town study."""

import csv
import glob
import json
import os

from .commands import (CITY, CITY_MAP_PLOT, CITY_MAP_RUN, EFF_F8, EFF_GRID, EFF_GRID_PLOT, GRID,
                       GRID_PLOT, OSM, POOLED40, TWO_WAY, TWO_WAY_PLOT)
from .context import ROOT
from .formats import md, same_file
from .tables import EFF_NAMES, EFF_POLICIES, mean_ci, paired, per_seed, stats, summary


def pooled40(ctx, m):
    ctx.run(POOLED40)
    rows = {}
    with open(ctx.path("results", "paper40", "aggregate.csv"), newline="") as f:
        for r in csv.DictReader(f):
            rows[r["policy"]] = r
    def rate(r, k, digits):
        v, lo, hi = (float(r[k + x]) for x in ("", "_lo", "_hi"))
        fmt = lambda x: "0" if x == 0 else "%.*f" % (digits, x)
        return "%s [%s, %s]" % (fmt(v), fmt(lo), fmt(hi))
    out = {}
    inside = True
    for name, key in (("no_ebp", "ne"), ("no_trust", "nt"), ("ta_ebp", "ta")):
        r = rows[name]
        out[key + "_enc"] = r["encounters"]
        out[key + "_coll"] = rate(r, "collision_rate", 4)
        out[key + "_dc"] = rate(r, "dc_rate", 4)
        for k in ("collision_rate", "dc_rate"):
            inside = inside and float(r[k + "_lo"]) - 1e-12 <= float(r["theory_" + k]) <= float(r[k + "_hi"]) + 1e-12
    out["inside"] = m.group("inside") if inside else "(a theory value outside its interval)"
    return out


def pooled_theory_table(ctx, folder):
    """The pooled per-encounter table of a sweep folder, and No Trust's both-proceed
    pairs and their SUMO collisions."""
    per = {}
    for r in ctx.csv("results", folder, "encounters.csv"):
        per.setdefault(r["policy"], []).append(r)
    theory = {"no_ebp": (0, 0), "no_trust": (0, 0.2), "ta_ebp": (0.375, 0)}
    names = {"no_ebp": "No EBP", "no_trust": "No Trust", "ta_ebp": "TA-EBP"}
    inside = True
    def cell(rows, hit, th):
        # Clustered by HV within each seed's run and by run (docs/metrics.md).
        nonlocal inside
        c = stats.encounter_rate(rows, hit, run=lambda r: (r["point"], r["seed"]), z=stats.Z999)
        inside = inside and c["low"] - 1e-12 <= th <= c["high"] + 1e-12
        f = lambda x: "0" if abs(x) < 1e-12 else "%.4f" % x
        return "%s [%s, %s]" % (f(c["rate"]), f(c["low"]), f(c["high"]))
    dc = lambda r: r["hv_action"] == "DC"
    both = lambda r: r["av_action"] == "go" and r["hv_action"] == "DR"
    coll = lambda r: r["collision"] == "1"
    rows = ["| policy | AV-HV encounters | DC rate [99.9%] | theory | both proceed [99.9%] | SUMO collisions [99.9%] | theory |",
            "|---|---|---|---|---|---|---|"]
    for p in ("no_ebp", "no_trust", "ta_ebp"):
        rs = per[p]
        rows.append("| %s | %d | %s | %g | %s | %s | %g |" % (
            names[p], len(rs), cell(rs, dc, theory[p][0]), theory[p][0], cell(rs, both, theory[p][1]),
            cell(rs, coll, theory[p][1]), theory[p][1]))
    nt = per["no_trust"]
    return "\n".join(rows), sum(map(both, nt)), sum(map(coll, nt)), inside


def theory_values(folder, command):
    def values(ctx, m):
        ctx.run(command)
        table, both, coll, inside = pooled_theory_table(ctx, folder)
        return {"table": table, "both": str(both), "coll": str(coll),
                "inside": m.group("inside") if inside else "(a theory value outside its interval)"}
    return values


def efficiency_values(folder, command):
    """Served flow and mean time loss at AV share 0.5 per demand, each policy against
    sumo_native (mean over the seeds), and whether any run stalled."""
    def values(ctx, m):
        ctx.run(command)
        acc = {}
        for r in ctx.csv("results", folder, "results.csv"):
            if float(r["scenario.av_share"]) != 0.5 or r["status"] != "ok":
                continue
            a = acc.setdefault((int(float(r["scenario.demand.flow"])), r["policy"]), [0.0, 0.0, 0.0, 0])
            a[0] += float(r["served_flow"])
            a[1] += float(r["time_loss_mean"])
            a[2] += float(r["encounters"] or 0)
            a[3] += 1
        stalled = 0
        for f in glob.glob(ctx.path("results", folder, "tasks", "*", "summary.json")):
            with open(f, encoding="utf-8") as fh:
                for v in json.load(fh)["policies"].values():
                    stalled += bool(v.get("stalls"))
        rows = ["| demand (veh/h per entry) | policy | served flow (veh/h) | of sumo_native's | mean time loss (s) | limit 1.25 x native + 5 s | AV-HV encounters per run |",
                "|---|---|---|---|---|---|---|"]
        for flow in sorted({k[0] for k in acc}):
            nf, nt, _, nn = acc[(flow, "sumo_native")]
            nf, nt = nf / nn, nt / nn
            for p in ("sumo_native", "no_ebp", "no_trust", "ta_ebp"):
                f, t, e, n = acc[(flow, p)]
                f, t, e = f / n, t / n, e / n
                rows.append("| %d | %s | %.0f | %s | %.1f | %s | %s |" % (
                    flow, p, f, "–" if p == "sumo_native" else "%.1f %%" % (100 * f / nf), t,
                    "–" if p == "sumo_native" else ("%.1f%s" % (1.25 * nt + 5, "" if t <= 1.25 * nt + 5 else " (over)")),
                    "–" if p == "sumo_native" else "%.0f" % e))
        out = {"table": "\n".join(rows), "stalled": str(stalled)}
        if "game_move" in m.re.groupindex:
            out["game_move"] = game_moves(ctx, folder)
        return out
    return values


def game_moves(ctx, folder):
    """Issue 30's safety figure over a whole sweep: per controller policy, the
    collisions of a game move with a third vehicle in all its runs, the
    encounters behind them, and SUMO's own collisions (sumo_native's runs) to
    read them against."""
    native, hits, enc = [], {}, {}
    for r in ctx.csv("results", folder, "results.csv"):
        if r["status"] != "ok":
            continue
        p = r["policy"]
        if p == "sumo_native":
            native.append(int(float(r["other_collisions"] or 0)))
            continue
        hits[p] = hits.get(p, 0) + int(float(r["other_collisions_game_move"] or 0))
        enc[p] = enc.get(p, 0) + int(float(r["encounters"] or 0))
    order = [p for p in EFF_POLICIES if p in hits]
    return "%s (in %s encounters, all runs; sumo_native's own collisions: %d, in %d of %d runs)" % (
        ", ".join("%s %d" % (EFF_NAMES[p], hits[p]) for p in order),
        ", ".join("%d" % enc[p] for p in order), sum(native), sum(v > 0 for v in native), len(native))


def efficiency_grid_values(ctx, m):
    ctx.run(EFF_GRID)
    key = lambda r: (int(float(r["scenario.demand.flow"])), float(r["scenario.av_share"]))
    runs = per_seed(ctx, "efficiency_grid", key)
    points = sorted({k[0] for k in runs})
    seeds = {len(v) for v in runs.values()}
    rows = ["| demand (veh/h per entry) | policy | served flow (veh/h) | AV delay (s) | HV delay (s) | AV wait at the line (s) | HV wait at the line (s) | AV-HV encounters per run |",
            "|---|---|---|---|---|---|---|---|"]
    for flow, share in points:
        if share != 0.5:
            continue
        for p in EFF_POLICIES:
            rs = list(runs[((flow, share), p)].values())
            col = lambda c, d: mean_ci([r[c] for r in rs], d)
            rows.append("| %d | %s | %s | %s | %s | %s | %s | %s |" % (
                flow, EFF_NAMES[p], col("served_flow", 0), col("time_loss_mean_av", 1),
                col("time_loss_mean_hv", 1), "–" if p == "sumo_native" else col("wait_mean_av", 1),
                "–" if p == "sumo_native" else col("wait_mean_hv", 1),
                "–" if p == "sumo_native" else "%.0f" % (sum(float(r["encounters"]) for r in rs) / len(rs))))
    diff = ["| demand (veh/h per entry) | AV share | served flow (veh/h) | AV delay (s) | HV delay (s) | delay, all trips (s) | AV-HV encounters per run |",
            "|---|---|---|---|---|---|---|"]
    zero_flow = True
    for flow, share in points:
        pr = {p: runs[((flow, share), p)] for p in ("ta_ebp", "no_ebp")}
        cell = lambda c, d: mean_ci(paired(pr, "ta_ebp", "no_ebp", c), d)
        flows = paired(pr, "ta_ebp", "no_ebp", "served_flow")
        _, lo, hi = stats.mean_interval(flows)
        zero_flow = zero_flow and lo <= 0 <= hi
        diff.append("| %d | %g | %s | %s | %s | %s | %.0f |" % (
            flow, share, cell("served_flow", 0), cell("time_loss_mean_av", 1),
            cell("time_loss_mean_hv", 1), cell("time_loss_mean", 1),
            sum(float(r["encounters"]) for r in pr["ta_ebp"].values()) / len(pr["ta_ebp"])))
    stalled = sum(float(r["stalled"] or 0) for v in runs.values() for r in v.values())
    return {"table": "\n".join(rows), "diff": "\n".join(diff),
            "seeds": str(min(seeds)) if len(seeds) == 1 else "%d-%d" % (min(seeds), max(seeds)),
            "stalled": "%d" % stalled,
            "flow_verdict": m.group("flow_verdict") if zero_flow else "(an interval without 0)"}


def efficiency_figure8_values(ctx, m):
    ctx.run(EFF_F8)
    key = lambda r: (int(r["scenario.avs"]), int(r["scenario.hvs"]))
    runs = per_seed(ctx, "efficiency_figure8", key)
    points = sorted({k[0] for k in runs}, key=lambda x: (x[0] + x[1], x[0]))
    rows = ["| policy | crossings / h, AVs | crossings / h, HVs | all | AV wait at the line (s) | HV wait at the line (s) | AV-HV encounters per run |",
            "|---|---|---|---|---|---|---|"]
    for p in EFF_POLICIES[1:]:
        rs = list(runs[((8, 8), p)].values())
        col = lambda c, d: mean_ci([r[c] for r in rs], d)
        rows.append("| %s | %s | %s | %s | %s | %s | %.0f |" % (
            EFF_NAMES[p], col("throughput_av", 0), col("throughput_hv", 0),
            col("throughput_all", 0), col("wait_mean_av", 1), col("wait_mean_hv", 1),
            sum(float(r["encounters"]) for r in rs) / len(rs)))
    diff = ["| AVs + HVs | crossings / h, AVs | crossings / h, HVs | all | AV wait at the line (s) | HV wait at the line (s) |",
            "|---|---|---|---|---|---|"]
    for avs, hvs in points:
        pr = {p: runs[((avs, hvs), p)] for p in ("ta_ebp", "no_ebp")}
        cell = lambda c, d: mean_ci(paired(pr, "ta_ebp", "no_ebp", c), d)
        diff.append("| %d + %d | %s | %s | %s | %s | %s |" % (
            avs, hvs, cell("throughput_av", 0), cell("throughput_hv", 0), cell("throughput_all", 0),
            cell("wait_mean_av", 1), cell("wait_mean_hv", 1)))
    return {"table": "\n".join(rows), "diff": "\n".join(diff)}


def city_values(ctx, m):
    """The city study: per policy the served flow and delays (mean and 95 % t
    interval over the seeds), the AV-HV encounters per simulated hour, the
    collision and DC rates pooled over the seeds (k/n, 99.9 % interval clustered by HV and run)
    against their theory, and the stalled runs."""
    ctx.run(CITY)
    runs = per_seed(ctx, "city_drt", lambda r: 0)
    seeds = {len(v) for v in runs.values()}
    rows = ["| policy | served flow (veh/h) | AV delay (s) | HV delay (s) | AV-HV encounters per hour | collisions: k/n [99.9 %] (theory) | DC: k/n [99.9 %] (theory) | stalled runs |",
            "|---|---|---|---|---|---|---|---|"]
    outside = []
    for p in ("sumo_native", "no_ebp", "no_trust", "ta_ebp"):
        rs = list(runs[(0, p)].values())
        col = lambda c, d: mean_ci([r[c] for r in rs], d)
        per_hour = [float(r["encounters"]) / float(r["measured_seconds"]) * 3600 for r in rs]
        stalled = sum(float(r["stalled"] or 0) > 0 for r in rs)
        cells = []
        n = sum(int(float(r["encounters"] or 0)) for r in rs)
        for k_col, th_col in (("collisions", "theory_collision_rate"), ("dc", "theory_dc_rate")):
            k = sum(int(float(r[k_col] or 0)) for r in rs)
            if p == "sumo_native" or n == 0:
                cells.append("–")
                continue
            # Pooled over the seeds, clustered by HV and by run (docs/metrics.md).
            rate = {"collisions": "collision_rate", "dc": "dc_rate"}[k_col]
            c = stats.pooled_rate([float(r[k_col] or 0) for r in rs], [float(r["encounters"] or 0) for r in rs],
                                  [float(r[rate + "_deff"]) if r.get(rate + "_deff") else 1.0 for r in rs],
                                  [int(float(r[rate + "_clusters"])) if r.get(rate + "_clusters") else 0 for r in rs],
                                  stats.Z999)
            lo, hi = c["low"], c["high"]
            th = float(rs[0][th_col])
            if not lo <= th <= hi:
                outside.append("%s %s" % (p, k_col))
            cells.append("%d/%d [%.3f, %.3f] (%s)" % (k, n, lo, hi, md(th)))
        rows.append("| %s | %s | %s | %s | %s | %s | %s | %d |" % (
            EFF_NAMES[p], col("served_flow", 0), col("time_loss_mean_av", 1), col("time_loss_mean_hv", 1),
            "–" if p == "sumo_native" else mean_ci(per_hour, 0), cells[0], cells[1], stalled))
    return {"table": "\n".join(rows),
            "seeds": str(min(seeds)) if len(seeds) == 1 else "%d-%d" % (min(seeds), max(seeds)),
            "verdict": m.group("verdict") if not outside else "outside: " + ", ".join(outside),
            "game_move": game_moves(ctx, "city_drt")}


def city_map(ctx, m):
    ctx.run(CITY_MAP_RUN)
    ctx.run(CITY_MAP_PLOT)
    fresh = ctx.path("results", "city_map", "network_map.png")
    s = ctx.json("results", "city_map", "summary.json")
    return {"picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs", "img", "city_map.png"))
            else "a different picture (fresh: %s)" % fresh,
            "ta": str(s["policies"]["ta_ebp"]["encounters"]),
            "junctions": str(sum(1 for j in s["policies"]["ta_ebp"]["junctions"] if j["encounters"] > 0))}


def efficiency_picture(ctx, m):
    ctx.run(EFF_GRID)
    ctx.run(EFF_GRID_PLOT)
    fresh = ctx.path("results", "efficiency_grid", "network_delay_av_hv.png")
    return {"picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs", "img", "efficiency_grid.png"))
            else "a different picture (fresh: %s)" % fresh}


def grid_picture(ctx, m, sweep=GRID, plot=GRID_PLOT, folder="grid_throughput", name="network_throughput.png"):
    ctx.run(sweep)
    ctx.run(plot)
    fresh = ctx.path("results", folder, "network_throughput.png")
    return {"picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs", "img", name))
            else "a different picture (fresh: %s)" % fresh}


def two_way_picture(ctx, m):
    return grid_picture(ctx, m, TWO_WAY, TWO_WAY_PLOT, "grid_two_way", "network_throughput_two_way.png")


def osm_values(ctx, m):
    ctx.run(OSM)
    s = summary(ctx, "results", "osm_city")
    names = {"sumo_native": "sumo_native", "no_ebp": "no_ebp", "ta_ebp": "ta_ebp"}
    rows = ["| policy | served flow (veh/h) | junction crossings / h | mean time loss (s) | AV-HV encounters | max vehicles at once |",
            "|---|---|---|---|---|---|"]
    clean = True
    for p, v in s.items():
        clean = clean and v["teleports"] == 0 and not v["stalls"]
        rows.append("| %s | %.0f | %.0f | %.1f | %s | %d |" % (
            names.get(p, p), v["served_flow"], v["throughput_all"], v["time_loss_mean"],
            "–" if p == "sumo_native" else str(v["encounters"]), v["vehicles_max"]))
    return {"table": "\n".join(rows), "clean": m.group("clean") if clean else "(a teleport or a stall)"}


def town_study(ctx, m):
    """README "Any sweep": its block run as written (a random town, a sweep of
    AV share x two trust distributions), its figure against docs/img."""
    ctx.run(m.group("block"))
    fresh = ctx.path("results", "town", "sweep_scenario.av_share.png")
    if not os.path.exists(ctx.path("results", "town", "sweep_model.trust.png")):
        raise ValueError("tools/plot drew no sweep_model.trust.png")
    return {"picture": m.group("picture") if same_file(fresh, os.path.join(ROOT, "docs", "img", "town_av_share.png"))
            else "a different picture (fresh: %s)" % fresh}
