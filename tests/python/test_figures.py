"""Figures a reader would publish (issue 44), on sweeps written by hand (no
simulation; test_figure_studies.py runs the two studies for real): every
figure passes figure_checks.problems (no empty panel, no policy line without
values, points sharing an x told apart, the legend inside the canvas, text of
8 pt or more at the printed width); taebp.plot.sweep draws exactly what
tools/plot draws; failed points are marked or refused (issue 45, item 5); a
place that cannot be written is one line and a non-zero exit (item 9)."""
import glob
import os
import subprocess


import taebp
from conftest import ROOT
from figure_checks import POLICIES, captured, grid_study, mismatch_study, problems
from taebp.plot import style

PLOT = os.path.join(ROOT, "tools", "plot")


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


def test_failed_points_are_marked_and_a_figure_without_a_value_is_refused(tmp_path):
    d = grid_study(tmp_path / "g", seeds=2, failed=[(0.5, "ta_ebp", 2), (0.25, "no_ebp", 1)])
    r = subprocess.run([PLOT, d, "--no-theory-binary", "--x", "scenario.av_share", "--y",
                        "dc_rate"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "point 2, ta_ebp: 2 of 2 runs failed (marked ✕; no value)" in r.stderr
    with captured() as saved:
        taebp.plot.sweep(d, out=str(tmp_path / "again"), x="scenario.av_share",
                         y=["served_flow", "collision_rate"], theory_binary=False)
    fig = dict((os.path.basename(p), f) for p, f in saved)["sweep_scenario.av_share.png"]
    crosses = [l for ax in fig.axes for l in ax.get_lines() if l.get_marker() == "X"]
    assert crosses and all(sorted(l.get_xdata()) == [0.25, 0.5] for l in crosses)
    notes = {t.get_text() for ax in fig.axes for t in ax.texts}
    # Every run at an x counted: every policy x 2 trust spreads x 2 seeds.
    runs = len(POLICIES) * 2 * 2
    assert {"2/%d runs failed" % runs, "4/%d runs failed" % runs} <= notes, notes
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
