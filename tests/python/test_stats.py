"""taebp.stats.wilson: the one Wilson interval of the Python code, against the
values tests/report/wilson_test.cc checks the C++ one with; and no second copy
of the interval anywhere in the tree."""
import os
import re
import subprocess

import pytest

import taebp
from taebp import stats
from conftest import ROOT, cli


# Newcombe (1998), Statistics in Medicine 17:857-872, Table II, method 3
# (Wilson score, no continuity correction), 95 %, four decimals as printed.
@pytest.mark.parametrize("k,n,low,high", [(81, 263, 0.2553, 0.3662), (15, 148, 0.0624, 0.1605),
                                          (0, 20, 0.0, 0.1611), (1, 29, 0.0061, 0.1718)])
def test_newcombes_published_examples(k, n, low, high):
    lo, hi = stats.wilson(k, n)
    assert abs(lo - low) < 5e-5 and abs(hi - high) < 5e-5


@pytest.mark.parametrize("z", [stats.Z95, stats.Z999])
@pytest.mark.parametrize("n", [1, 2, 10, 1000])
def test_edges_are_exact_closed_forms(z, n):
    edge = z * z / (n + z * z)
    lo, hi = stats.wilson(0, n, z)
    assert lo == 0.0 and abs(hi - edge) < 1e-14
    lo, hi = stats.wilson(n, n, z)
    assert abs(lo - (1 - edge)) < 1e-14 and hi == 1.0


# Student's t, two-sided 95 % (Abramowitz & Stegun Table 26.10; any t table),
# and df 1 / df 2 in closed form: tan(0.95 pi / 2) and sqrt(2 / (1 - 0.95^2) - 2).
@pytest.mark.parametrize("df,t", [(1, 12.7062047), (2, 4.3026527), (3, 3.1824463),
                                  (5, 2.5705818), (9, 2.2621572), (19, 2.0930241),
                                  (30, 2.0422725), (120, 1.9799304)])
def test_student_t_quantile_against_the_table(df, t):
    assert abs(stats.student_t_quantile(df) - t) < 5e-7


def test_student_t_closed_forms_and_limits():
    import math
    assert abs(stats.student_t_quantile(1) - math.tan(0.95 * math.pi / 2)) < 1e-9
    assert abs(stats.student_t_quantile(2) - math.sqrt(2 / (1 - 0.95 ** 2) - 2)) < 1e-9
    assert abs(stats.student_t_quantile(2, 0.5) - math.sqrt(2 / (1 - 0.5 ** 2) - 2)) < 1e-9
    # Large df: the Cornish-Fisher expansion t = z + (z^3 + z) / (4 df) + O(1/df^2).
    z = stats.Z95
    assert abs(stats.student_t_quantile(2000) - (z + (z ** 3 + z) / 8000)) < 1e-6
    for bad in ((0, 0.95), (2.5, 0.95), (3, 1.0)):
        with pytest.raises(ValueError):
            stats.student_t_quantile(*bad)


def test_mean_interval():
    m, lo, hi = stats.mean_interval([1, 2, 3, 4])
    half = stats.student_t_quantile(3) * (5 / 3) ** 0.5 / 2  # sd = sqrt(5/3), n = 4
    assert m == 2.5 and abs(lo - (2.5 - half)) < 1e-12 and abs(hi - (2.5 + half)) < 1e-12
    assert stats.mean_interval([7.0]) == (7.0, 7.0, 7.0)
    assert stats.mean_interval([]) == (None, None, None)
    assert stats.mean_interval([3, 3, 3]) == (3.0, 3.0, 3.0)


def test_welch_interval_by_hand():
    # a = 1, 2, 3 and b = 4, 5, 6: variances 1, standard error sqrt(2/3), and
    # Welch-Satterthwaite df (2/3)^2 / (2 (1/3)^2 / 2) = 4; t(0.975, 4) = 2.776445
    # from the printed table: -3 -+ 2.776445 * 0.816497.
    d, lo, hi = stats.welch_interval([1, 2, 3], [4, 5, 6])
    assert d == pytest.approx(-3.0)
    assert lo == pytest.approx(-3.0 - 2.776445 * 0.8164966, abs=1e-5)
    assert hi == pytest.approx(-3.0 + 2.776445 * 0.8164966, abs=1e-5)
    # Unequal spread: df 1.07... rounds down to 1 (t = 12.7062), the conservative side.
    d, lo, hi = stats.welch_interval([0, 10], [5, 5, 5.0001])
    assert hi - d == pytest.approx(12.7062 * (50 / 2 + 0.0000000033 / 3) ** 0.5, rel=1e-4)
    assert stats.welch_interval([1], [1, 2]) == (None, None, None)
    assert stats.welch_interval([1, 1], [2, 2]) == (None, None, None)


def test_small_samples_and_bad_counts():
    assert abs(stats.wilson(0, 1)[1] - 0.7935) < 5e-5
    assert abs(stats.wilson(1, 1)[0] - 0.2065) < 5e-5
    assert stats.wilson(0, 0) == (0.0, 1.0)
    for k, n in ((2, 1), (-1, 3)):
        with pytest.raises(ValueError, match="0 <= k <= n"):
            stats.wilson(k, n)


def test_the_same_numbers_as_the_cpp_interval_in_a_run(tmp_path):
    # summary.json's intervals come from taebp::ClusteredRate: the Python one
    # gives the same bounds for the same encounters, and where the design
    # effect is at most 1 (the paper's one trust, here) they are Wilson's.
    r = taebp.run(os.path.join(ROOT, "configs", "paper.yaml"),
                  overrides=["scenario.duration=300", "policies=[no_trust,ta_ebp]"])
    rows = list(r.encounters)
    checked = wilson = 0
    for name, p in r.summary["policies"].items():
        mine = [e for e in rows if e["policy"] == name]
        n = p["encounters"]
        for key, k, hit in (("collision_rate", p["collisions"], lambda e: e["collision"] in (1, "1", True)),
                            ("dc_rate", p["dc"], lambda e: e["hv_action"] == "DC")):
            c = stats.encounter_rate(mine, hit)
            assert p[key + "_lo"] == pytest.approx(c["low"], abs=1e-12), (name, key)
            assert p[key + "_hi"] == pytest.approx(c["high"], abs=1e-12), (name, key)
            assert p[key + "_deff"] == pytest.approx(c["deff"], rel=1e-12), (name, key)
            if p[key + "_deff"] <= 1:
                lo, hi = stats.wilson(k, n)
                assert (p[key + "_lo"], p[key + "_hi"]) == pytest.approx((lo, hi), abs=1e-12)
                wilson += 1
            checked += 1
    assert checked == 4 and wilson >= 1


# The formula's signature, as any copy would spell it: z^2 / (4 n^2) under the root.
WILSON_BODY = re.compile(r"z2?\s*\*?\s*z?\s*/\s*\(\s*4(\.0)?\s*\*\s*n\s*\*\s*n\s*\)")


def test_no_second_wilson_interval_in_the_tree():
    files = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=ROOT, capture_output=True, text=True,
                           check=True).stdout.split()
    homes = {"report/src/clustered.cc", "python/taebp/stats.py"}
    found = set()
    for f in files:
        if not f.endswith((".cc", ".h", ".py")) and not f.startswith("tools/"):
            continue
        path = os.path.join(ROOT, f)
        if not os.path.isfile(path):
            continue
        with open(path, encoding="utf-8", errors="replace") as fh:
            if WILSON_BODY.search(fh.read()):
                found.add(f)
    assert found == homes, "Wilson's formula outside its two homes: %s" % sorted(found - homes)


# ------------------------------------------------------------ clustered intervals
# The Python twin of report/clustered.h (docs/metrics.md "Intervals"): the same
# worked cases as tests/report/clustered_test.cc, and the outputs' own values.

def test_clustered_rate_worked_cases():
    # HVs of equal rates: Wilson's interval exactly; a design effect of 0.
    c = stats.clustered_rate([3, 6, 9, 3, 6], [10, 20, 30, 10, 20])
    assert (c["low"], c["high"]) == stats.wilson(27, 90)
    assert c["clusters"] == 5 and not c["few_clusters"]
    # Two HVs, 2 and 8 of 10: design effect 7.2, its excess scaled by (t_1 / z)^2.
    c = stats.clustered_rate([2, 8], [10, 10])
    assert c["deff"] == pytest.approx(7.2, abs=1e-12)
    adj = 1 + 6.2 * (12.7062047361747 / stats.Z95) ** 2
    lo, hi = stats.wilson_at(0.5, 20 / adj)
    assert c["low"] == pytest.approx(lo, abs=1e-9) and c["high"] == pytest.approx(hi, abs=1e-9)
    assert c["few_clusters"]
    # Pooled: two runs of 10 HVs (design effect 4) at 0.10 and 0.15: the runs'
    # level (deff 16/7 from 2 runs) sets it, as in the sweep test.
    p = stats.pooled_rate([20, 30], [200, 200], [4.0, 4.0], [10, 10])
    assert p["deff"] == pytest.approx(16 / 7, abs=1e-9) and p["clusters"] == 2
    adj = 1 + (16 / 7 - 1) * (12.7062047361747 / stats.Z95) ** 2
    lo, hi = stats.wilson_at(0.125, 400 / adj)
    assert p["low"] == pytest.approx(lo, abs=1e-9) and p["high"] == pytest.approx(hi, abs=1e-9)


def test_encounter_rate_gives_the_intervals_the_outputs_report(tmp_path):
    """From a run's encounters.csv, stats.encounter_rate reproduces summary.json's
    rate intervals (computed in C++) to the last digits: HVs who learn (an
    influence run), whose design effect is far from 1."""
    import csv
    import json
    out = tmp_path / "run"
    cli("run", os.path.join(ROOT, "configs", "influence.yaml"), "--set", "scenario.duration=3600",
        "--set", "model.experience.design=paper", "--set", "policies=[ta_ebp]",
        "--set", "scenario.seed=41", "--out", out, "--quiet")
    p = json.load(open(out / "summary.json"))["policies"]["ta_ebp"]
    with open(out / "encounters.csv") as f:
        rows = list(csv.DictReader(f))
    for rate, hit in (("dc_rate", lambda r: r["hv_action"] == "DC"),
                      ("collision_rate", lambda r: r["collision"] == "1")):
        c = stats.encounter_rate(rows, hit)
        assert c["rate"] == pytest.approx(p[rate], abs=1e-12), rate
        assert c["low"] == pytest.approx(p[rate + "_lo"], abs=1e-12), rate
        assert c["high"] == pytest.approx(p[rate + "_hi"], abs=1e-12), rate
        assert c["deff"] == pytest.approx(p[rate + "_deff"], rel=1e-12), rate
        assert c["clusters"] == p[rate + "_clusters"] == 8
    assert p["dc_rate_deff"] > 3
    # The plots' and docs/influence.md's table's intervals are the same
    # clustered ones: over the run's one hour, the table's DC and collisions.
    from taebp.plot import presets, tidy
    clusters = {}
    for r in rows:
        c = clusters.setdefault((0, r["hv"]), [0, 0, 0])
        c[0] += 1
        c[1] += r["hv_action"] == "DC"
        c[2] += r["collision"] == "1"
    for k, rate in ((1, "dc_rate"), (2, "collision_rate")):
        lo, hi = tidy.rate_interval(clusters, k)
        assert (lo, hi) == (pytest.approx(p[rate + "_lo"], abs=1e-12),
                            pytest.approx(p[rate + "_hi"], abs=1e-12)), rate
    row = [c.strip() for c in presets.influence_table(tidy.Runs(out)).splitlines()[2].split("|")]
    last_dc, last_coll = row[5], row[6]
    assert last_dc == "%.3f [%.3f, %.3f]" % (p["dc_rate"], p["dc_rate_lo"], p["dc_rate_hi"])
    assert last_coll == "%.3f [%.3f, %.3f]" % (p["collision_rate"], p["collision_rate_lo"],
                                                p["collision_rate_hi"])
    assert row[10].startswith("%.2f / " % p["dc_rate_deff"]), row[10]


def test_normal_quantile_bonferroni_and_the_mover_difference():
    assert stats.normal_quantile(0.95) == pytest.approx(stats.Z95, abs=1e-12)
    assert stats.normal_quantile(0.999) == pytest.approx(stats.Z999, abs=1e-12)
    assert stats.bonferroni_level(4) == pytest.approx(0.9875)
    # Newcombe (1998b), Statistics in Medicine 17:873-890, Table II, method 10
    # (the score-based hybrid): 56/70 - 48/80 = 0.2000 [0.0524, 0.3339].
    a = dict(zip(("low", "high"), stats.wilson(56, 70)), rate=56 / 70)
    b = dict(zip(("low", "high"), stats.wilson(48, 80)), rate=48 / 80)
    d, lo, hi = stats.rate_difference(a, b)
    assert d == pytest.approx(0.2)
    assert lo == pytest.approx(0.0524, abs=5e-5) and hi == pytest.approx(0.3339, abs=5e-5)
