"""tools/plot's generic view and the tidy tables, on a small hand-made sweep
(no simulation): one line per policy and line style, an empty rate (a policy
with no game, sumo_native) drawn as nothing rather than 0, distributions
labelled by what they are, intervals from the replicates, what cannot be
drawn named, never an empty figure; typed frames."""
import csv
import json
import math
import os
import subprocess

import pytest

import taebp
from conftest import ROOT
from taebp.plot import common, style, tidy, view

NARROW, WIDE = "{dist: beta, alpha: 12, beta: 8}", "{dist: beta, alpha: 1.2, beta: 0.8}"
COLUMNS = ["point", "scenario.av_share", "model.trust", "policy", "runs_ok", "runs_failed",
           "encounters", "collision_rate", "collision_rate_lo", "collision_rate_hi",
           "theory_collision_rate", "served_flow", "served_flow_sd", "offered_flow", "stalled"]


def write_sweep(folder):
    rows, point = [], 0
    for share in (0.25, 0.5):
        for trust in (NARROW, WIDE):
            for policy in ("sumo_native", "ta_ebp"):
                game = policy != "sumo_native"
                rows.append({"point": point, "scenario.av_share": share, "model.trust": trust,
                             "policy": policy, "runs_ok": 2, "runs_failed": 0,
                             "encounters": 40 if game else 0,
                             "collision_rate": 0.0 if game else "",
                             "collision_rate_lo": 0.0 if game else "",
                             "collision_rate_hi": 0.087 if game else "",
                             "theory_collision_rate": 0.0 if game else "",
                             "served_flow": 1000 + 100 * share, "served_flow_sd": 10.0,
                             "offered_flow": 1050, "stalled": 1 if (game and share == 0.5) else 0})
            point += 1
    with open(os.path.join(folder, "aggregate.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, COLUMNS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(folder, "sweep.json"), "w") as f:
        json.dump({"replicates": 2, "columns": ["scenario.av_share", "model.trust"],
                   "config": {"scenario": {"duration": 3630, "warmup": 30}}}, f)
    return str(folder)


@pytest.fixture
def sweep(tmp_path):
    return tidy.Sweep(write_sweep(tmp_path))


def test_long_table_leaves_out_empty_rates_and_derives_encounters_per_hour(sweep):
    rows = tidy.long_table(sweep, ["collision_rate", "encounters_per_hour", "served_flow"])
    rates = [r for r in rows if r["metric"] == "collision_rate"]
    assert {r["policy"] for r in rates} == {"ta_ebp"}  # sumo_native plays no game
    per_hour = [r for r in rows if r["metric"] == "encounters_per_hour" and r["policy"] == "ta_ebp"]
    assert all(abs(r["value"] - 40 / 2 / 1.0) < 1e-12 for r in per_hour)  # 2 runs of 1 h
    flow = [r for r in rows if r["metric"] == "served_flow"][0]
    half = 12.706204736174705 * 10.0 / math.sqrt(2)  # t(1) 95 % of the mean of 2 seeds
    assert abs(flow["hi"] - flow["value"] - half) < 1e-9


def test_view_draws_one_line_per_policy_and_style(sweep, tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, = view.SweepView(sweep, "scenario.av_share", ["collision_rate", "served_flow"]).figures()
    path = fig.save(plt, str(tmp_path))
    assert os.path.basename(path) == "sweep_scenario.av_share.png"
    d = fig.description
    assert d["styles"] == ["model.trust"]
    rate, flow = d["panels"]
    assert [(l["policy"], l["style"]) for l in rate["lines"]] == [
        ("ta_ebp", "model.trust = Beta mean 0.6 sd 0.11"),
        ("ta_ebp", "model.trust = Beta mean 0.6 sd 0.28")]
    assert all(l["points"] == 2 and l["theory_points"] == 2 for l in rate["lines"])
    assert len(flow["lines"]) == 4 and all(l["points"] == 2 for l in flow["lines"])
    assert rate["xlabel"] == "scenario.av_share" and rate["ylabel"] == "collision_rate"
    assert flow["ylabel"] == "served_flow (veh/h)"  # the unit of the metric table
    assert rate["title"] == style.metric_title("collision_rate") == "Collisions per encounter"
    assert "a seed stalled (k/n)" in d["legend"]
    # A distribution on the x axis: categories labelled by what they are.
    v = view.SweepView(sweep, "model.trust", ["served_flow"])
    v.figures()[0].save(plt, str(tmp_path))
    assert v.xkey.labels == ["Beta mean 0.6 sd 0.11", "Beta mean 0.6 sd 0.28"]
    assert not v.xkey.numeric
    assert view.SweepView(sweep, "scenario.av_share", ["served_flow"]).xkey.numeric


def test_never_an_empty_figure(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    ax.set_title("nothing")
    ax.plot([1, 2], [float("nan"), float("nan")])
    with pytest.raises(common.PlotError, match="no simulated value"):
        common.save(fig, str(tmp_path / "empty.png"))
    assert not (tmp_path / "empty.png").exists()
    # Theory alone (a line not marked as simulated) is no figure either.
    fig, ax = plt.subplots()
    ax.plot([0.1, 0.9], [0.2, 0.375])
    with pytest.raises(common.PlotError, match="no simulated value"):
        common.save(fig, str(tmp_path / "theory.png"))
    assert not (tmp_path / "theory.png").exists()


def test_what_cannot_be_drawn_names_what_can(sweep, tmp_path):
    plot = os.path.join(ROOT, "tools", "plot")
    r = subprocess.run([plot, sweep.dir, "--y", "dc_rate", "--no-theory-binary"],
                       capture_output=True, text=True)
    assert r.returncode == 1 and not list(tmp_path.glob("*.png"))
    assert "--y dc_rate: not a metric" in r.stderr
    assert "--x one of scenario.av_share, model.trust" in r.stderr
    assert "collision_rate" in r.stderr and "served_flow" in r.stderr
    r = subprocess.run([plot, sweep.dir, "--no-theory-binary", "--describe",
                        str(tmp_path / "d.json")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    files = [f["file"] for f in json.loads((tmp_path / "d.json").read_text())["figures"]]
    assert files == ["sweep_scenario.av_share.png", "sweep_model.trust.png"]


def test_distributions_are_described_exactly():
    d = taebp.dists
    assert d.describe("{dist: beta, alpha: 12, beta: 8}") == (
        "beta", 0.6, math.sqrt(12 * 8 / (20 ** 2 * 21)))
    assert d.describe({"dist": "uniform", "low": 0.2, "high": 0.8}) == (
        "uniform", 0.5, (0.8 - 0.2) / math.sqrt(12))
    kind, mean, sd = d.describe("{dist: discrete, values: [0.2, 0.8], weights: [1, 3]}")
    assert kind == "discrete" and abs(mean - 0.65) < 1e-12 and abs(sd - math.sqrt(0.0675)) < 1e-12
    assert d.describe(0.6) == ("fixed", 0.6, 0.0)
    assert d.label("{dist: beta, alpha: 1.2, beta: 0.8}") == "Beta mean 0.6 sd 0.28"


def test_tables_slice_and_keep_their_types():
    t = taebp.Table.from_csv("junction,policy,collision_rate,stalled\nA,ta_ebp,0,false\n"
                             "B,ta_ebp,0,true\nC,no_ebp,0,false\n", "junctions.csv")
    assert len(t[:2]) == 2 and t[0]["junction"] == "A" and t[-1]["policy"] == "no_ebp"
    df = t.to_pandas()
    assert df["collision_rate"].dtype == "float64"  # all 0, still a rate
    assert df["stalled"].dtype == bool and list(df["stalled"]) == [False, True, False]
