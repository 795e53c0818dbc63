"""The researcher's study of issue 26, end to end: a town built at test time
(netgenerate --rand, every junction an all-way stop; randomTrips.py --validate
demand; neither shipped), a sweep of scenario.av_share x two trust
distributions x 2 seeds with the five policies, driven from Python by dicts
(config, grid), read back as tidy frames, and drawn by one `tools/plot`
command whose figures are checked: content (not blank), axes labelled with
the swept keys, one line per policy and line style, the distributions
labelled by what they are; and a view it cannot draw exits non-zero naming
what it could draw. Short runs (240 simulated s) keep it under 2 minutes."""
import json
import os
import shutil
import subprocess
import sys

import pytest

import taebp
from conftest import CLI, ROOT

SUMO_HOME = os.environ.get("SUMO_HOME", "/usr/share/sumo")
POLICIES = ["sumo_native", "no_ebp", "no_trust", "ta_ebp", "population_mean"]
BETA_NARROW = {"dist": "beta", "alpha": 12, "beta": 8}     # mean 0.6, sd 0.107
BETA_WIDE = {"dist": "beta", "alpha": 1.2, "beta": 0.8}    # mean 0.6, sd 0.283
SHARES = [0.25, 0.5, 0.75]


def build_town(folder):
    """A random town of all-way stops and validated random trips (SUMO's tools)."""
    for tool in ("netgenerate",):
        if shutil.which(tool) is None:
            pytest.fail("%s is missing (Debian package sumo: tools/setup.sh installs it)" % tool)
    trips = os.path.join(SUMO_HOME, "tools", "randomTrips.py")
    if not os.path.isfile(trips):
        pytest.fail("%s is missing (Debian package sumo-tools)" % trips)
    net, routes = os.path.join(folder, "town.net.xml"), os.path.join(folder, "town.rou.xml")
    subprocess.run(["netgenerate", "--rand", "--rand.iterations", "30", "--rand.bidi-probability",
                    "1", "--rand.min-distance", "80", "--rand.max-distance", "160",
                    "--default.lanenumber", "1", "--default-junction-type", "allway_stop",
                    "--no-turnarounds", "true", "--seed", "3", "-o", net],
                   check=True, capture_output=True, text=True)
    subprocess.run([sys.executable, trips, "-n", net, "-o", routes, "--validate",
                    "--fringe-factor", "10", "--period", "2", "--end", "300", "--seed", "3"],
                   check=True, capture_output=True, text=True, env=dict(os.environ, SUMO_HOME=SUMO_HOME))
    return net, routes


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    work = tmp_path_factory.mktemp("town")
    net, routes = build_town(str(work))
    config = {
        "scenario": {"kind": "network", "network": net, "routes": [routes], "av_share": 0.5,
                     "duration": 240, "warmup": 30, "stall_action": "record", "seed": 1},
        "model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6},
        "policies": POLICIES,
    }
    s = taebp.sweep(config, out=str(work / "sweep"), jobs=2, replicates=2,
                    grid={"scenario.av_share": SHARES, "model.trust": [BETA_NARROW, BETA_WIDE]})
    return work, s


def test_the_dict_study_ran_every_task(study):
    _, s = study
    assert s.keys == ["scenario.av_share", "model.trust"]
    assert s.info["replicates"] == 2
    assert len(s.aggregate) == len(SHARES) * 2 * len(POLICIES)
    assert set(s.results["status"]) == {"ok"}
    assert sum(s.aggregate["encounters"]) > 0  # the games were played


def test_swept_distributions_are_numeric_columns_and_dtypes_agree(study):
    _, s = study
    agg = s.aggregate.to_pandas()
    cols = list(agg.columns)
    at = cols.index("model.trust")
    assert cols[at + 1:at + 4] == ["model.trust.dist", "model.trust.mean", "model.trust.sd"]
    assert set(agg["model.trust.dist"]) == {"beta"}
    assert agg["model.trust.mean"].dtype == "float64"
    assert agg["model.trust.mean"].round(12).unique().tolist() == [0.6]
    sds = sorted(agg["model.trust.sd"].round(6).unique())
    assert sds == [round((12 * 8 / (20 ** 2 * 21)) ** 0.5, 6), round((1.2 * 0.8 / (2 ** 2 * 3)) ** 0.5, 6)]
    res = s.results.to_pandas()
    assert res["stalled"].dtype == bool
    run_frame = s.run(0, 0).to_pandas()["policies"]
    assert run_frame["stalled"].dtype == bool
    # A real metric stays float in every frame, even where all values are whole.
    for frame in (agg, res, run_frame):
        assert frame["collision_rate"].dtype == "float64"
    assert res["served_flow"].dtype == agg["served_flow"].dtype == run_frame["served_flow"].dtype
    # Junction rows slice like a list.
    j = s.run(0, 0).junctions
    assert len(j[:3]) == 3 and isinstance(j[0], dict)


def _png_pixels(path):
    import matplotlib.image as mpimg
    import numpy as np
    img = mpimg.imread(path)[..., :3]
    return float(np.std(img)), float((img.mean(axis=2) < 0.9).mean())


def test_one_plot_command_draws_the_figures(study):
    work, s = study
    desc = work / "figures.json"
    r = subprocess.run([os.path.join(ROOT, "tools", "plot"), s.out, "--describe", str(desc)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    d = json.loads(desc.read_text())
    files = {f["file"]: f for f in d["figures"]}
    assert set(files) == {"sweep_scenario.av_share.png", "sweep_model.trust.png"}
    for name, fig in files.items():
        std, ink = _png_pixels(os.path.join(s.out, name))
        assert std > 0.05 and ink > 0.02, (name, std, ink)  # not blank
        other = "model.trust" if fig["x"] == "scenario.av_share" else "scenario.av_share"
        assert fig["styles"] == [other] or fig["by"] == other
        metrics = [p["metric"] for p in fig["panels"]]
        for m in ("collision_rate", "dc_rate", "served_flow", "time_loss_mean_av",
                  "time_loss_mean_hv", "encounters_per_hour"):
            assert m in metrics, (name, m)
        for p in fig["panels"]:
            assert p["xlabel"] == fig["x"]  # the axis is the swept key
            assert p["ylabel"].split(" (")[0] == p["metric"]  # its name, and its unit
            keys = [(l["policy"], l["style"], p.get("facet")) for l in p["lines"]]
            assert len(keys) == len(set(keys)), "one line per policy and style"
            assert {l["policy"] for l in p["lines"]} <= set(POLICIES)
            if p["metric"] in ("served_flow", "time_loss_mean_av"):
                # Every policy drew; every point of the sweep is on its line.
                assert {l["policy"] for l in p["lines"]} == set(POLICIES), p["metric"]
            if p["metric"] == "encounters_per_hour":
                # Every policy that plays the game; sumo_native has no value (no line at 0).
                assert {l["policy"] for l in p["lines"]} == set(POLICIES) - {"sumo_native"}
            if p["metric"] == "dc_rate":
                assert {"no_ebp", "ta_ebp", "population_mean"} <= {l["policy"] for l in p["lines"]}
                assert all(l["theory_points"] > 0 for l in p["lines"] if l["policy"] == "ta_ebp")
    av = files["sweep_scenario.av_share.png"]
    served = [p for p in av["panels"] if p["metric"] == "served_flow"][0]
    assert len(served["lines"]) == len(POLICIES) * 2
    assert all(l["points"] == len(SHARES) for l in served["lines"])
    assert "model.trust = Beta mean 0.6 sd 0.11" in av["legend"]
    assert "model.trust = Beta mean 0.6 sd 0.28" in av["legend"]


def test_what_cannot_be_drawn_exits_non_zero_naming_what_can(study):
    _, s = study
    plot = os.path.join(ROOT, "tools", "plot")
    r = subprocess.run([plot, s.out, "--y", "no_such_metric"], capture_output=True, text=True)
    assert r.returncode != 0
    assert "no_such_metric" in r.stderr
    assert "scenario.av_share" in r.stderr and "model.trust" in r.stderr
    assert "collision_rate" in r.stderr and "served_flow" in r.stderr
    r = subprocess.run([plot, s.out, "--x", "scenario.demand.flow"], capture_output=True, text=True)
    assert r.returncode != 0 and "--x one of scenario.av_share, model.trust" in r.stderr


def test_a_task_folder_reruns_itself_and_plots_its_map_from_another_directory(study, tmp_path):
    """A sweep point's folder is a run folder: its saved config.yaml names its
    inputs (absolute paths), so `taebp run TASK/config.yaml` from elsewhere
    gives the same encounters byte for byte, and `tools/plot TASK` draws that
    point's map (the network found from the saved config)."""
    _, s = study
    task = os.path.join(s.out, "tasks", "1-0")  # av_share 0.25, the wide Beta: sumo_native reused
    assert os.path.isfile(os.path.join(task, "config.yaml"))
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    r = subprocess.run([CLI, "run", os.path.join(task, "config.yaml"), "--out", "again",
                        "--quiet"], cwd=str(elsewhere), capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(task, "encounters.csv"), "rb") as a, \
            open(elsewhere / "again" / "encounters.csv", "rb") as b:
        first, second = a.read(), b.read()
    assert first.count(b"\n") > 1, "the point played games"
    assert first == second
    r = subprocess.run([os.path.join(ROOT, "tools", "plot"), task], cwd=str(elsewhere),
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    std, ink = _png_pixels(os.path.join(task, "network_map.png"))
    assert std > 0.05 and ink > 0.01, (std, ink)  # the net's lanes and the junction markers
