"""The shipped figures' presets on sweeps and runs written by hand: the
mismatch heat maps of collisions and DC with their intervals, points that
share an x told apart (a zipped axis; fleets of two sizes at one AV share),
runs beyond the paper pooled per point and titled by it, each policy's colour
and label from the package's tables without the program."""
import json
import os
import subprocess


import taebp
from conftest import ROOT
from figure_checks import captured, grid_study, mismatch_study, problems, write_sweep

PLOT = os.path.join(ROOT, "tools", "plot")


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


def test_colours_and_labels_come_with_the_package_not_the_program(tmp_path):
    """Plotting from a copy of the package (as installed, or outside the
    repository) with no taebp program anywhere: the policies keep their
    labels and colours (tables.json, written from the policy table)."""
    import shutil
    pkg = tmp_path / "site" / "taebp"
    shutil.copytree(os.path.dirname(taebp.__file__), pkg,
                    ignore=shutil.ignore_patterns("_taebp*", "__pycache__"))
    (pkg / "__init__.py").write_text("")  # no compiled module either
    d = grid_study(tmp_path / "g", seeds=1, shares=(0.5,))
    script = ("import sys, json; import taebp.plot as p; "
              "from figure_checks import captured\n"
              "with captured() as saved:\n"
              "    p.sweep(sys.argv[1], out=sys.argv[2], x='model.trust', y='served_flow')\n"
              "fig = saved[0][1]\n"
              "from matplotlib.colors import to_hex\n"
              "print(json.dumps([[t.get_text(), to_hex(h.get_color())] for leg in fig.legends "
              "for t, h in zip(leg.get_texts(), leg.legendHandles)]))\n")
    env = {"PATH": "/usr/bin:/bin", "PYTHONPATH": "%s:%s" % (tmp_path / "site",
                                                             os.path.dirname(__file__))}
    r = subprocess.run(["/usr/bin/python3", "-c", script, d, str(tmp_path / "out")], env=env,
                       cwd=str(tmp_path), capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "no taebp binary found" in r.stderr  # really without the program
    legend = dict(json.loads(r.stdout))
    for p in taebp.policy_table():
        assert legend.get(p["label"]) == p["colour"], (p["name"], legend)



class _Runs:
    """Stands in for tidy.Runs: the configs of a few run folders."""

    def __init__(self, configs):
        self.configs = configs
        self.dirs = ["run%d" % i for i in range(len(configs))]

    def config(self, i):
        return self.configs[i]


def test_influence_pools_runs_of_one_learner_only():
    from taebp.plot import presets
    exp = {"strength": 20, "bin_width": 0.1, "forgetting": 1.0, "design": "guarded", "margin": 0.1}
    one = [{"model": {"experience": dict(exp, design=d)}} for d in ("guarded", "paper", "robust")]
    assert presets._experienced(_Runs(one))  # designs differ: one learner
    forgetting = one + [{"model": {"experience": dict(exp, forgetting=0.95)}}]
    assert not presets._experienced(_Runs(forgetting))  # a learners sweep: not pooled
    noisy = one + [{"model": {"experience": exp, "noise": {"kind": "gaussian", "scale": 0.1}}}]
    assert not presets._experienced(_Runs(noisy))
    assert not presets._experienced(_Runs([{"model": {}}]))  # nobody learns
