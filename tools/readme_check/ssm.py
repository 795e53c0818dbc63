"""Tier studies, SUMO's SSM device: the Bologna study, the SSM grid study,
the twelve runs of issue 41 and the paired runs' pair measures against the
device's."""

import csv
import glob
import json
import os

from .commands import BOLOGNA, PAIRED_SSM, SSM_GRID, SSM_TWELVE
from .context import CommandFailed
from .tables import EFF_NAMES, mean_ci, paired, per_seed, stats


SSM_ABORT = "SSM device (scenario.outputs.ssm) aborts"


def ssm_aborts(ctx, folder):
    """{policy: runs that ended in SUMO's SSM assertion} of a sweep (one policy
    per task); a run that failed for any other reason fails the figure."""
    out = {}
    for r in ctx.csv("results", folder, "results.csv"):
        if r["status"] == "ok":
            continue
        if SSM_ABORT not in r["error"]:
            raise CommandFailed("%s: point %s seed %s (%s) failed, not in SUMO's SSM assertion: %s"
                                % (folder, r["point"], r["seed"], r["policy"], r["error"]))
        out[r["policy"]] = out.get(r["policy"], 0) + 1
    return out


def bologna_values(ctx, m):
    """Real demand (docs/bologna.md): per policy, per measured hour and mean
    [95 % t interval] over the seeds, the junction crossings, the candidate
    meetings (games formed + the meetings that were not games, by reason, from
    every run's junctions.csv), the games; the served flow, the mean delay and
    SUMO's SSM conflicts (per hour and per 1,000 crossings)."""
    ctx.run(BOLOGNA, failed_tasks=True)
    aborts = ssm_aborts(ctx, "bologna_acosta")
    runs = per_seed(ctx, "bologna_acosta", lambda r: 0)
    why = ("meetings_not_game", "meetings_unpredictable", "meetings_abandoned")
    meetings = {}  # (policy, replicate) -> [not_game, unpredictable, abandoned]
    for task in glob.glob(ctx.path("results", "bologna_acosta", "tasks", "*", "junctions.csv")):
        replicate = int(os.path.basename(os.path.dirname(task)).split("-")[1])
        with open(task, newline="", encoding="utf-8") as f:
            for r in csv.DictReader(f):
                sums = meetings.setdefault((r["policy"], replicate), [0, 0, 0])
                for i, k in enumerate(why):
                    sums[i] += int(float(r[k] or 0))
    seeds = len({r["replicate"] for r in ctx.csv("results", "bologna_acosta", "results.csv")})
    head = ["| policy | junction crossings /h | candidate meetings /h | games /h | not a game /h: no collision, unpredictable, abandoned |",
            "|---|---|---|---|---|"]
    flow = ["| policy | runs (SSM aborts) | served flow (veh/h) | delay (s) | SSM conflicts /h | SSM conflicts per 1,000 crossings | collisions (all) | stalled runs |",
            "|---|---|---|---|---|---|---|---|"]
    for p in ("sumo_native", "no_ebp", "no_trust", "ta_ebp"):
        rs = runs.get((0, p), {})
        hour = lambda r: float(r["measured_seconds"]) / 3600
        per_h = lambda f: mean_ci([f(k, r) / hour(r) for k, r in rs.items()], 0)
        games = lambda k, r: float(r["encounters_formed"] or 0)
        cand = lambda k, r: games(k, r) + sum(meetings.get((p, k), [0, 0, 0]))
        reasons = ", ".join(per_h(lambda k, r, i=i: meetings.get((p, k), [0, 0, 0])[i]) for i in range(3))
        head.append("| %s | %s | %s | %s | %s |" % (
            EFF_NAMES[p], per_h(lambda k, r: float(r["crossings_all"])),
            "–" if p == "sumo_native" else per_h(cand), "–" if p == "sumo_native" else per_h(games),
            "–" if p == "sumo_native" else reasons))
        collisions = sum(int(float(r["collisions"] or 0)) + int(float(r["other_collisions"] or 0))
                         for r in rs.values())
        flow.append("| %s | %d (%d) | %s | %s | %s | %s | %d | %d |" % (
            EFF_NAMES[p], len(rs), aborts.get(p, 0), mean_ci([r["served_flow"] for r in rs.values()], 0),
            mean_ci([r["time_loss_mean"] for r in rs.values()], 1),
            mean_ci([r["ssm_conflicts_per_hour"] for r in rs.values()], 0),
            mean_ci([r["ssm_conflicts_per_1000_crossings"] for r in rs.values()], 1),
            collisions, sum(float(r["stalled"] or 0) > 0 for r in rs.values())))
    return {"meetings": "\n".join(head), "flow": "\n".join(flow),
            "seeds": str(seeds)}


def ssm_grid_values(ctx, m):
    """SSM on the two-way grid (docs/ssm.md): per policy, the runs (and how many
    were lost), the games and their collisions, the near misses among the games
    without a collision by measure (pooled over the seeds, 95 % intervals
    clustered by HV and run), the network's conflicts per hour by measure and per
    1,000 crossings (mean [95 % t] over the seeds); then No Trust against TA-EBP
    on the two families of measures, each Bonferroni-corrected for its four
    measures: the network's conflicts paired by seed, and the near misses (not
    paired: each run's own games; MOVER intervals)."""
    ctx.run(SSM_GRID, failed_tasks=True)
    lost = ssm_aborts(ctx, "ssm_grid")
    runs = per_seed(ctx, "ssm_grid", lambda r: 0)
    measures = (("any", "ssm_near_misses", "ssm_near_miss_rate"),
                ("TTC", "ssm_ttc_near_misses", "ssm_ttc_near_miss_rate"),
                ("DRAC", "ssm_drac_near_misses", "ssm_drac_near_miss_rate"),
                ("PET", "ssm_pet_near_misses", "ssm_pet_near_miss_rate"))
    per_hour = (("conflicts", "ssm_conflicts_per_hour"), ("TTC", "ssm_ttc_conflicts_per_hour"),
                ("DRAC", "ssm_drac_conflicts_per_hour"), ("PET", "ssm_pet_conflicts_per_hour"))
    level = stats.bonferroni_level(4)
    z = stats.normal_quantile(level)

    def near(rs, count, rate, zz=stats.Z95):
        num = lambda r, c: float(r[c]) if r.get(c) not in ("", None) else 0.0
        return stats.pooled_rate([num(r, count) for r in rs], [num(r, "encounters_no_collision") for r in rs],
                                 [num(r, rate + "_deff") or 1.0 for r in rs],
                                 [int(num(r, rate + "_clusters")) for r in rs], zz)

    rows = ["| policy | runs (lost) | games | game collisions | near misses per game without a collision [95 %]: any | TTC | DRAC | PET | conflicts /h | TTC /h | DRAC /h | PET /h | per 1,000 crossings |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    total = lambda rs, c: sum(int(float(r[c] or 0)) for r in rs.values())
    for p in ("sumo_native", "no_ebp", "no_trust", "ta_ebp"):
        rs = runs.get((0, p), {})
        col = lambda c, d: mean_ci([r[c] for r in rs.values()], d)
        games = total(rs, "encounters")
        cells = []
        for name, count, rate in measures:
            if not games:
                cells.append("–")
                continue
            c = near(list(rs.values()), count, rate)
            cells.append("%d/%d %.3f [%.3f, %.3f]" % (total(rs, count), total(rs, "encounters_no_collision"),
                                                   c["rate"], c["low"], c["high"]))
        rows.append("| %s | %d (%d) | %d | %d | %s | %s | %s | %s | %s | %s |" % (
            EFF_NAMES[p], len(rs), lost.get(p, 0), games, total(rs, "collisions"), " | ".join(cells),
            col("ssm_conflicts_per_hour", 0), col("ssm_ttc_conflicts_per_hour", 0),
            col("ssm_drac_conflicts_per_hour", 0), col("ssm_pet_conflicts_per_hour", 0),
            col("ssm_conflicts_per_1000_crossings", 1)))
    pr = {p: runs.get((0, p), {}) for p in ("no_trust", "ta_ebp")}
    cells, above = [], []
    for name, c in per_hour:
        d = paired(pr, "no_trust", "ta_ebp", c)
        if len(d) < 2:
            cells.append("%s –" % name)
            continue
        mean, lo, hi = stats.mean_interval(d, level)
        cells.append("%s %.0f [%.0f, %.0f]" % (name, mean, lo, hi))
        if lo > 0 or hi < 0:
            above.append(name)
    ncells, nabove = [], []
    for name, count, rate in measures:
        a = near(list(pr["no_trust"].values()), count, rate, z)
        b = near(list(pr["ta_ebp"].values()), count, rate, z)
        d, lo, hi = stats.rate_difference(a, b)
        ncells.append("%s %.3f [%.3f, %.3f]" % (name, d, lo, hi))
        if lo > 0 or hi < 0:
            nabove.append(name)
    pairs = len(set(pr["no_trust"]) & set(pr["ta_ebp"]))
    return {"table": "\n".join(rows), "pairs": str(pairs), "diff": "; ".join(cells),
            "above": ", ".join(above) if above else "none",
            "near": "; ".join(ncells), "nabove": ", ".join(nabove) if nabove else "none",
            "lost": str(sum(lost.values())), "total": str(sum(len(v) for v in runs.values()) + sum(lost.values()))}


def ssm_twelve_values(ctx, m):
    """The 12 runs of issue 41 (seeds 1, 3, 8, 22 x sumo_native, No Trust,
    TA-EBP, the device on): how many ran to their end, and the device's
    "detected collision" situations they went through."""
    r = ctx.run(SSM_TWELVE)
    lost = sum(1 for line in r.stdout.splitlines() if line.startswith("lost "))
    ended = 0
    for s_ in (1, 3, 8, 22):
        for p in ("sumo_native", "no_trust", "ta_ebp"):
            path = ctx.path("results", "ssm12", "%d-%s" % (s_, p), "summary.json")
            if os.path.exists(path):
                q = json.load(open(path))["policies"][p]
                ended += abs(float(q["simulated_seconds"]) - 1200) < 1e-6
    return {"ended": str(ended), "lost": str(lost)}


def paired_ssm_values(ctx, m):
    """A paired run with SUMO's SSM device on: the branches under the run's own
    policy against the run's encounters.csv, game by game: how many games have
    both PETs, and the median, 90th percentile and largest absolute difference
    of the branch's pair PET from the device's; the same median for TTC."""
    ctx.run(PAIRED_SSM)
    enc = {(e["policy"], e["time"], e["av"], e["hv"]): e
           for e in ctx.csv("results", "paired_ssm", "encounters.csv")}
    pet, ttc = [], []
    for r in ctx.csv("results", "paired_ssm", "paired.csv"):
        e = enc.get((r["host"], r["time"], r["av"], r["hv"]))
        if r["policy"] != r["host"] or r["status"] != "ok" or e is None:
            continue
        if r["pair_min_pet"] and e["ssm_min_pet"]:
            pet.append(abs(float(r["pair_min_pet"]) - float(e["ssm_min_pet"])))
        if r["pair_min_ttc"] and e["ssm_min_ttc"]:
            ttc.append(abs(float(r["pair_min_ttc"]) - float(e["ssm_min_ttc"])))
    pet.sort()
    ttc.sort()
    med = lambda xs: "%.2f" % (xs[(len(xs) - 1) // 2] if len(xs) % 2 else (xs[len(xs) // 2 - 1] + xs[len(xs) // 2]) / 2)
    return {"pet_n": str(len(pet)), "pet_median": med(pet), "pet_p90": "%.2f" % pet[int(0.9 * (len(pet) - 1))],
            "pet_max": "%.2f" % pet[-1], "ttc_n": str(len(ttc)), "ttc_median": med(ttc)}
