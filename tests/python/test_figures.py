"""Figures a reader would publish (issue 44), on sweeps written by hand (no
simulation; tests/python/test_figure_studies.py runs the two studies for
real): every figure passes figure_checks.problems (no empty panel, no policy
line without values, points sharing an x told apart, the legend inside the
canvas, text of 8 pt or more at the printed width); taebp.plot.sweep draws
exactly what tools/plot draws; failed points are marked or refused, a place
that cannot be written is one line and a non-zero exit; the tidy frames go
into numpy as they are and load without a warning."""
import glob
import json
import os
import subprocess
import warnings

import numpy as np

import taebp
from conftest import ROOT
from figure_checks import captured, problems, write_sweep
from taebp.plot import style

PLOT = os.path.join(ROOT, "tools", "plot")
NARROW, WIDE = "{dist: beta, alpha: 12, beta: 8}", "{dist: beta, alpha: 1.2, beta: 0.8}"
POLICIES = [p["name"] for p in taebp.policy_table()]


def grid_study(folder, seeds=3, shares=(0.25, 0.5, 0.75), failed=()):
    """A two-way grid's study by hand: AV share x two trust distributions x
    every policy x `seeds` seeds; `failed`: (share, policy, failed runs)."""
    rows, runs, point = [], [], 0
    for share in shares:
        for trust in (NARROW, WIDE):
            for i, policy in enumerate(POLICIES):
                game = style.plays_game(policy)
                bad = sum(f for s, p, f in failed if s == share and p == policy)
                ok = seeds - bad
                flow = 1500 + 40 * share - 3 * i
                row = {"point": point, "scenario.av_share": share, "model.trust": trust,
                       "policy": policy, "runs_ok": ok, "runs_failed": bad}
                if ok:
                    row.update({"served_flow": flow, "served_flow_sd": 12.0,
                                "offered_flow": 1600, "time_loss_mean_av": 30 + 2 * i,
                                "time_loss_mean_av_sd": 1.5, "time_loss_mean_hv": 28 + i,
                                "time_loss_mean_hv_sd": 1.0, "stalled": 0})
                    if game:
                        n = 120 * seeds
                        k = int(0.1 * (i % 3) * n)
                        row.update({"encounters": n, "collisions": k,
                                    "collision_rate": k / n, "collision_rate_lo": k / n * 0.7,
                                    "collision_rate_hi": k / n * 1.3 + 0.01,
                                    "dc": n // 3, "dc_rate": (n // 3) / n,
                                    "dc_rate_lo": 0.28, "dc_rate_hi": 0.38,
                                    "theory_collision_rate": 0.1 * (i % 3),
                                    "theory_dc_rate": 1 / 3,
                                    "encounters_per_hour": 120 / (1680 / 3600),
                                    "encounters_per_hour_sd": 9.0})
                    else:
                        row.update({"encounters": 0})
                rows.append(row)
                for rep in range(ok):
                    runs.append({"point": point, "replicate": rep, "scenario.av_share": share,
                                 "model.trust": trust, "policy": policy,
                                 "served_flow": flow + 10 * (rep - 1),
                                 "time_loss_mean_av": 30 + 2 * i + rep,
                                 "time_loss_mean_hv": 28 + i - rep,
                                 "encounters_per_hour": 257 + rep if game else None,
                                 "measured_seconds": 1680})
                for rep in range(ok, seeds):
                    runs.append({"point": point, "replicate": rep, "policy": policy,
                                 "status": "failed", "error": "SUMO aborted"})
            point += 1
    return write_sweep(str(folder), ["scenario.av_share", "model.trust"], rows, runs,
                       config={"scenario": {"kind": "network", "duration": 1800, "warmup": 120},
                               "model": {"prior_go": 0.2, "collision_penalty": 3.0}},
                       replicates=seeds)


def test_the_grid_study_draws_figures_a_reader_would_publish(tmp_path):
    d = grid_study(tmp_path / "grid")
    with captured() as saved:
        written = taebp.plot.sweep(d, out=str(tmp_path / "api"), theory_binary=False)
    assert sorted(os.path.basename(p) for p in written) == [
        "sweep_model.trust.png", "sweep_scenario.av_share.png"]
    for path, fig in saved:
        assert problems(fig, os.path.basename(path)) == []
    fig = dict((os.path.basename(p), f) for p, f in saved)["sweep_scenario.av_share.png"]
    panels = {" ".join(ax.get_title().split()): ax for ax in fig.axes if ax.get_title()}
    panels = {m: ax for m in ("collision_rate", "dc_rate", "encounters_per_hour", "served_flow",
                              "time_loss_mean_av") for t, ax in panels.items()
              if t.startswith(style.metric_title(m))}
    native = style.policy_colour("sumo_native")

    def colours(ax):
        from matplotlib.colors import to_hex
        return {to_hex(l.get_color()) for l in ax.get_lines() if l.get_gid() == "simulated"}
    # sumo_native plays no game: no line in the rate and encounter panels,
    # a line in the flow panel.
    for metric in ("collision_rate", "dc_rate", "encounters_per_hour"):
        assert native not in colours(panels[metric]), metric
    flow = panels["served_flow"]
    assert native in colours(flow)
    # Served flow around the offered demand (1600 veh/h), not from 0.
    assert flow.get_ylim()[0] > 1000 and flow.get_ylim()[1] >= 1600
    assert "served = offered" in " ".join(t.get_text() for leg in fig.legends
                                         for t in leg.get_texts())
    # 3 seeds: each seed's value beside the mean, no t interval on a mean.
    delay = panels["time_loss_mean_av"]
    hollow = [l for l in delay.get_lines() if l.get_markerfacecolor() == "none"]
    assert sum(len(l.get_xdata()) for l in hollow) == 3 * 3 * 2 * len(POLICIES)
    # Titles say the measured time, the legend tells the trust spreads apart.
    assert "1680 s measured" in fig._suptitle.get_text()
    labels = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    assert "model.trust = Beta mean 0.6 sd 0.11" in labels
    assert "model.trust = Beta mean 0.6 sd 0.28" in labels
    # One plotting API: tools/plot draws the same files, byte for byte.
    r = subprocess.run([PLOT, d, "--out", str(tmp_path / "cli"), "--no-theory-binary"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for name in ("sweep_model.trust.png", "sweep_scenario.av_share.png"):
        with open(tmp_path / "api" / name, "rb") as a, open(tmp_path / "cli" / name, "rb") as b:
            assert a.read() == b.read(), name


def test_many_panels_split_into_files_and_a_metric_shares_its_y_range(tmp_path):
    d = grid_study(tmp_path / "grid", shares=(0.1, 0.25, 0.5, 0.75, 0.9))
    with captured() as saved:
        written = taebp.plot.sweep(d, out=str(tmp_path), x="model.trust", by="scenario.av_share",
                                   y=["served_flow", "collision_rate"], theory_binary=False)
    # Five panel columns would not be legible: one file per metric.
    assert sorted(os.path.basename(p) for p in written) == [
        "sweep_model.trust.collision_rate.png", "sweep_model.trust.served_flow.png"]
    for path, fig in saved:
        assert problems(fig, os.path.basename(path)) == []
        limits = {ax.get_ylim() for ax in fig.axes if ax.get_visible() and ax.get_title()}
        assert len(limits) == 1, (path, limits)


def mismatch_study(folder, zipped=False):
    rows, point = [], 0
    for theta in (0.2, 0.6, 1.0):
        for hat in (0.2, 0.6, 1.0):
            n = 200
            k = 40 if hat > theta and hat >= 0.25 else 0
            rows.append({"point": point, "model.trust": theta, "model.assumed_trust": hat,
                         "policy": "ta_ebp", "runs_ok": 2, "runs_failed": 0, "encounters": n,
                         "collisions": k, "collision_rate": k / n,
                         "collision_rate_lo": max(0, k / n - 0.05), "collision_rate_hi": k / n + 0.05,
                         "dc_rate": 0.3, "dc_rate_lo": 0.24, "dc_rate_hi": 0.37,
                         "theory_collision_rate": 0.2 if k else 0.0, "theory_dc_rate": 0.3})
            point += 1
    return write_sweep(str(folder), ["model.trust", "model.assumed_trust"], rows,
                       config={"model": {"prior_go": 0.2, "collision_penalty": 3.0,
                                         "likelihood": {"type": "linear", "s_max": 2.0}},
                               "scenario": {"duration": 600}}, replicates=2)


def test_the_mismatch_heat_maps_show_dc_and_intervals(tmp_path):
    d = mismatch_study(tmp_path / "m")
    with captured() as saved:
        written = taebp.plot.sweep(d, theory_binary=False)
    names = sorted(os.path.basename(p) for p in written)
    assert names == ["mismatch_collision_heatmap.png", "mismatch_dc_heatmap.png"]
    for path, fig in saved:
        assert problems(fig, os.path.basename(path)) == []
        notes = [t.get_text() for t in fig.axes[0].texts]
        assert len(notes) == 9 and all("\n" in t and "–" in t for t in notes), notes
    dc = dict((os.path.basename(p), f) for p, f in saved)["mismatch_dc_heatmap.png"]
    assert ".24–.37" in [t.get_text().split("\n")[1] for t in dc.axes[0].texts]


def test_points_sharing_an_x_are_told_apart(tmp_path):
    """A zipped axis ([exact, 0.5], [assumed, 0.5]) puts two points of one
    policy at assumed_trust 0.5: a line style each, named in the legend."""
    rows = []
    for point, (knowledge, hat) in enumerate((("exact", 0.5), ("assumed", 0.5), ("assumed", 0.8))):
        rows.append({"point": point, "model.trust_knowledge": knowledge,
                     "model.assumed_trust": hat, "policy": "ta_ebp", "runs_ok": 5,
                     "runs_failed": 0, "encounters": 100, "collisions": point,
                     "collision_rate": point / 100, "collision_rate_lo": 0,
                     "collision_rate_hi": 0.05, "throughput_all": 1500 + point,
                     "throughput_all_sd": 4})
    d = write_sweep(str(tmp_path / "z"), ["model.trust_knowledge", "model.assumed_trust"], rows,
                    replicates=5)
    with captured() as saved:
        taebp.plot.sweep(d, x="model.assumed_trust", y="collision_rate", theory_binary=False)
    (path, fig), = saved
    assert problems(fig) == []
    labels = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    assert "model.trust_knowledge = exact" in labels and "model.trust_knowledge = assumed" in labels


def test_fleets_of_two_sizes_at_one_share_are_told_apart(tmp_path):
    rows = []
    for point, (avs, hvs) in enumerate(((2, 6), (4, 4), (8, 8), (6, 2))):
        for policy in ("no_ebp", "ta_ebp"):
            rows.append({"point": point, "scenario.avs": avs, "scenario.hvs": hvs,
                         "policy": policy, "runs_ok": 5, "runs_failed": 0, "encounters": 90,
                         "collisions": 0, "collision_rate": 0.0, "collision_rate_lo": 0.0,
                         "collision_rate_hi": 0.04, "throughput_all": 1400 + 20 * avs,
                         "throughput_all_sd": 9, "throughput_av": 100 * avs,
                         "throughput_av_sd": 3, "throughput_hv": 100 * hvs, "throughput_hv_sd": 3,
                         "wait_mean": 2.0, "wait_mean_sd": 0.1, "encounters_per_hour": 180,
                         "encounters_per_hour_sd": 5})
    d = write_sweep(str(tmp_path / "p"), ["scenario.avs", "scenario.hvs"], rows,
                    config={"scenario": {"duration": 1800, "loop_length": 80},
                            "model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6}},
                    replicates=5)
    with captured() as saved:
        taebp.plot.sweep(d, theory_binary=False)
    (path, fig), = saved
    assert os.path.basename(path) == "penetration_throughput.png"
    assert problems(fig) == []
    labels = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    assert "8 vehicles" in labels and "16 vehicles" in labels
    caption = " ".join(t.get_text() for t in fig.texts)
    assert "8 or 16 vehicles" in caption


def test_failed_points_are_marked_and_a_figure_without_a_value_is_refused(tmp_path):
    d = grid_study(tmp_path / "g", seeds=2, failed=[(0.5, "ta_ebp", 2), (0.25, "no_ebp", 1)])
    r = subprocess.run([PLOT, d, "--no-theory-binary"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "point 2, ta_ebp: 2 of 2 runs failed (marked ✕; no value)" in r.stderr
    with captured() as saved:
        taebp.plot.sweep(d, out=str(tmp_path / "again"), theory_binary=False)
    fig = dict((os.path.basename(p), f) for p, f in saved)["sweep_scenario.av_share.png"]
    crosses = [l for ax in fig.axes for l in ax.get_lines() if l.get_marker() == "X"]
    assert crosses and all(sorted(l.get_xdata()) == [0.25, 0.5] for l in crosses)
    notes = {t.get_text() for ax in fig.axes for t in ax.texts}
    # Every run at an x counted: 8 policies x 2 trust spreads x 2 seeds.
    assert {"2/32 runs failed", "4/32 runs failed"} <= notes, notes
    caption = " ".join(t.get_text() for t in fig.texts)
    assert "Failed runs (✕): No EBP at scenario.av_share = 0.25 (1/2)" in caption.replace("\n", " ")
    assert "failed runs at" in fig._suptitle.get_text()
    # Every point failed: nothing simulated to draw, no figure, exit 1.
    every = grid_study(tmp_path / "none", seeds=2,
                       failed=[(s, p, 2) for s in (0.25, 0.5, 0.75) for p in POLICIES])
    r = subprocess.run([PLOT, every, "--no-theory-binary"], capture_output=True, text=True)
    assert r.returncode == 1 and "has a simulated value" in r.stderr, r.stderr
    assert len(r.stderr.splitlines()) <= 10  # the failures summed up, not one line each
    assert not glob.glob(os.path.join(every, "*.png"))


def test_a_place_it_cannot_write_is_one_line_and_a_non_zero_exit(tmp_path):
    d = mismatch_study(tmp_path / "m")
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder")
    for out in (str(blocker), str(blocker / "sub")):
        r = subprocess.run([PLOT, d, "--out", out, "--no-theory-binary"], capture_output=True,
                           text=True)
        assert r.returncode == 2, r.stderr
        lines = r.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("tools/plot: --out " + out), r.stderr
        assert "Traceback" not in r.stderr
    r = subprocess.run([PLOT, d, "--no-theory-binary", "--describe", str(blocker / "d.json")],
                       capture_output=True, text=True)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr


def test_tidy_frames_go_into_numpy_as_they_are_and_load_without_a_warning(tmp_path):
    d = grid_study(tmp_path / "g")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = taebp.load_sweep(d)
        agg = s.aggregate.to_pandas()
        tidy = s.tidy()
        res = s.results.to_pandas()
    # Counts are numpy int64 (float64 where a cell is empty), never pandas' Int64.
    assert agg["runs_ok"].dtype == np.int64 and agg["point"].dtype == np.int64
    assert agg["encounters"].dtype == np.int64
    assert agg["collisions"].dtype == np.float64  # empty for sumo_native
    assert all(not str(t).startswith(("Int", "Float", "boolean")) for t in agg.dtypes)
    # What failed on pandas' nullable Int64 (TypeError, or an object array):
    corr = np.corrcoef(agg["encounters"], agg["served_flow"])
    assert corr.dtype == np.float64 and np.isfinite(corr).all()
    assert np.log(agg["encounters"] + 1).dtype == np.float64
    assert np.isfinite(agg["encounters"].corr(agg["served_flow"]))
    # The long frame: swept keys as numbers, floats for values.
    assert list(tidy.columns[:5]) == ["point", "scenario.av_share", "model.trust",
                                      "model.trust.dist", "model.trust.mean"]
    assert tidy["scenario.av_share"].dtype == np.float64
    assert tidy["model.trust.mean"].dtype == np.float64
    for c in ("value", "lo", "hi", "theory"):
        assert tidy[c].dtype == np.float64, c
    for c in ("runs", "failed", "stalled"):
        assert tidy[c].dtype == np.int64, c
    rate = tidy[(tidy.metric == "collision_rate")]
    assert set(rate.policy) == {p for p in POLICIES if style.plays_game(p)}
    np.log1p(tidy["value"].to_numpy())
    assert res["replicate"].dtype == np.int64
    # The documented spelling works too.
    assert len(taebp.plot.tidy.to_pandas(taebp.load_sweep(d))) == len(tidy)


def learned_task(folder, trust, seed, policies=("ta_ebp", "ta_ebp_learned")):
    """A sweep task's folder of a learned-trust run (2 simulated hours)."""
    os.makedirs(folder)
    config = {"scenario": {"avs": 8, "hvs": 8, "duration": 7200, "warmup": 0, "seed": seed},
              "model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": trust,
                        "learning": {"delta": 0.01}}}
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"policies": {p: {"encounters": 40} for p in policies},
                   "provenance": {"config": config}}, f)
    cols = ["policy", "time", "hv", "hv_action", "collision", "oracle_dc", "regret",
            "commanded_nudge", "failure_probability"]
    with open(os.path.join(folder, "encounters.csv"), "w") as f:
        f.write(",".join(cols) + "\n")
        for p in policies:
            for i in range(40):
                f.write("%s,%d,hv%d,%s,0,0.375,%g,%g,0.01\n" % (
                    p, 90 * i + 10, i % 8, "DC" if i % 3 == 0 else "DR",
                    0.01 if p == "ta_ebp_learned" else 0.0, 1.6 if i % 2 else 0))
    with open(os.path.join(folder, "timeseries.csv"), "w") as f:
        f.write("policy,time,mean_trust\n")


def test_runs_beyond_the_paper_pool_only_one_point(tmp_path):
    d = grid_study(tmp_path / "s", seeds=1, shares=(0.5,))
    for point, trust in ((0, 0.6), (1, "{dist: beta, alpha: 12, beta: 8}")):
        for rep in (0, 1):
            t = trust if isinstance(trust, float) else {"dist": "beta", "alpha": 12, "beta": 8}
            learned_task(os.path.join(d, "tasks", "%d-%d" % (point, rep)), t, rep + 1)
    with captured() as saved:
        written = taebp.plot.run(d, out=str(tmp_path / "out"))
    names = sorted(os.path.basename(p) for p in written)
    assert names == ["learned_rates_point0.png", "learned_rates_point1.png",
                     "learned_regret_point0.png", "learned_regret_point1.png"]
    for path, fig in saved:
        assert problems(fig, os.path.basename(path)) == []
        title = fig._suptitle.get_text()
        assert "2 seeds" in title, title
        if "point0" in path:
            assert "θ = 0.6" in title
        else:
            assert "Beta(12, 8)" in title
    rates = dict((os.path.basename(p), f) for p, f in saved)["learned_rates_point0.png"]
    ax = rates.axes[0]
    # Hours of simulated time: 2 bins, points within their hour.
    xs = [x for l in ax.get_lines() if l.get_gid() == "simulated" for x in l.get_xdata()]
    assert xs and all(0 < x < 2 for x in xs)
