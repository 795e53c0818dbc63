"""Issue 44's acceptance, for real: the two studies of its researchers, made
small (a 3 x 3 two-way-stop grid, 150 simulated s; a 2 x 2 mismatch sweep,
60 s), each plotted with one `tools/plot` command and with
taebp.plot.sweep: the same files byte for byte, and every figure passes
figure_checks.problems (no empty panel, no policy line without values,
points sharing an x told apart, the legend inside the canvas, text of 8 pt
or more at the printed width)."""
import os
import subprocess


import taebp
from conftest import ROOT
from figure_checks import captured, problems

PLOT = os.path.join(ROOT, "tools", "plot")
BETA_NARROW = {"dist": "beta", "alpha": 12, "beta": 8}
BETA_WIDE = {"dist": "beta", "alpha": 1.2, "beta": 0.8}


def plot_both_ways(folder, tmp_path):
    """tools/plot into the sweep folder and taebp.plot.sweep into another;
    the figures the API saved, checked."""
    r = subprocess.run([PLOT, folder], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    from_cli = sorted(os.path.basename(p) for p in r.stdout.split())
    with captured() as saved:
        written = taebp.plot.sweep(folder, out=str(tmp_path / "api"))
    assert sorted(os.path.basename(p) for p in written) == from_cli
    for name in from_cli:
        with open(os.path.join(folder, name), "rb") as a, open(tmp_path / "api" / name, "rb") as b:
            assert a.read() == b.read(), name
    found = []
    for path, fig in saved:
        found += problems(fig, os.path.basename(path))
    assert found == []
    return from_cli, saved


def test_a_two_way_grid_av_share_by_trust_spread_by_every_policy(tmp_path):
    config = os.path.join(ROOT, "configs", "grid_two_way.yaml")
    out = str(tmp_path / "grid")
    s = taebp.sweep(config, out=out, jobs=2, replicates=1,
                    overrides={"scenario.grid.columns": 3, "scenario.grid.rows": 3,
                               "scenario.duration": 150, "scenario.warmup": 30,
                               "scenario.demand.flow": 150, "policies": taebp.policies()},
                    grid={"scenario.av_share": [0.25, 0.75],
                          "model.trust": [BETA_NARROW, BETA_WIDE]})
    files, saved = plot_both_ways(s.out, tmp_path)
    assert {"sweep_scenario.av_share.png", "sweep_model.trust.png"} <= set(files)
    # ta_ebp_learned among the policies: its figures per point, never pooled
    # across the points.
    assert "learned_rates_point0.png" in files and "learned_rates.png" not in files


def test_a_mismatch_sweep(tmp_path):
    config = os.path.join(ROOT, "configs", "sweep_mismatch.yaml")
    s = taebp.sweep(config, out=str(tmp_path / "mismatch"), jobs=2, replicates=1,
                    overrides={"scenario.duration": 60},
                    grid={"model.trust": [0.3, 0.9], "model.assumed_trust": [0.3, 0.9]})
    files, _ = plot_both_ways(s.out, tmp_path)
    assert files == ["mismatch_collision_heatmap.png", "mismatch_dc_heatmap.png"]
