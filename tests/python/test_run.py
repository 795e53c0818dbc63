"""taebp.run gives the files `taebp run` writes, errors as exceptions, the GIL
released and one simulation per process."""
import multiprocessing
import os
import signal
import threading
import time

import pytest

import taebp
from conftest import PAPER, cli, cli_error, sumo_rejected_network

SHORT = ["scenario.duration=300"]


def test_run_equals_the_cli_files_and_table(tmp_path):
    cli_out = tmp_path / "cli"
    printed = cli("run", PAPER, "--set", SHORT[0], "--out", cli_out, "--quiet").stdout
    r = taebp.run(PAPER, overrides=SHORT, out=tmp_path / "py")
    for name in ("summary.json", "encounters.csv", "config.yaml"):
        cli_text = (cli_out / name).read_text()
        assert r.files[name] == cli_text, name
        assert (tmp_path / "py" / name).read_text() == cli_text, name
    assert r.table == printed
    assert r.policies == ["no_ebp", "no_trust", "ta_ebp"]
    # Data as in the files: summary as a dict, encounters as typed rows.
    ta = r.summary["policies"]["ta_ebp"]
    rows = [e for e in r.encounters if e["policy"] == "ta_ebp"]
    assert ta["encounters"] == len(rows) > 20
    assert ta["dc"] == sum(e["hv_action"] == "DC" for e in rows)
    assert r.encounters.columns == taebp.encounter_columns()
    assert all(isinstance(t, float) for t in r.encounters["time"])
    assert set(r.encounters["collision"]) <= {0, 1}
    loaded = taebp.load_run(tmp_path / "py")
    assert loaded.summary == r.summary and loaded.encounters.rows == r.encounters.rows


def test_network_run_has_the_network_column():
    """A network scenario's encounters.csv adds both_proceed_collides,
    premise (the meeting is the paper's game), collision_after_handback and
    encounter_kind after the paper's columns."""
    grid = os.path.join(os.path.dirname(PAPER), "grid_throughput.yaml")
    r = taebp.run(grid, overrides=["policies=[no_trust]", "scenario.duration=600",
                                   "scenario.warmup=0"])
    cols = taebp.encounter_columns(network=True)
    assert cols == taebp.encounter_columns() + ["both_proceed_collides", "premise",
                                                "collision_after_handback", "encounter_kind"]
    assert r.encounters.columns == cols
    assert len(r.encounters) > 20
    assert set(r.encounters["both_proceed_collides"]) == {1}
    assert set(r.encounters["premise"]) == {"holds"}
    assert set(r.encounters["encounter_kind"]) == {"stop_lines"}
    # Every encounter is the game: SUMO collided exactly where the AV went
    # and the HV drove recklessly.
    for e in r.encounters:
        assert e["collision"] == (e["av_action"] == "go" and e["hv_action"] == "DR")


def test_run_without_out_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = taebp.run(PAPER, overrides=SHORT + ["policies=[ta_ebp]"])
    assert r.out is None and os.listdir(tmp_path) == []
    assert r.summary["provenance"]["seed"] == 1


def test_pandas_frames():
    r = taebp.run(PAPER, overrides=SHORT + ["policies=[no_trust, ta_ebp]"])
    frames = r.to_pandas()
    enc, pol = frames["encounters"], frames["policies"]
    assert list(enc.columns) == taebp.encounter_columns()
    assert len(enc) == len(r.encounters)
    rates = enc.groupby("policy")["collision"].mean()
    assert rates["no_trust"] == r.summary["policies"]["no_trust"]["collision_rate"]
    assert list(pol["policy"]) == ["no_trust", "ta_ebp"]
    assert list(pol["theory_dc_rate"]) == [0.0, 0.375]
    assert taebp.to_pandas(r.encounters).shape == enc.shape
    # junctions.csv: one row per policy and junction (the figure-8's C).
    j = frames["junctions"]
    assert list(j["policy"]) == ["no_trust", "ta_ebp"] and set(j["junction"]) == {"C"}
    assert list(j["encounters"]) == [r.summary["policies"][p]["encounters"]
                                     for p in ("no_trust", "ta_ebp")]


def test_errors_are_exceptions_with_the_cli_message(tmp_path):
    message, code = cli_error("run", PAPER, "--set", "scenario.avs=-1", "--out", tmp_path / "x")
    assert code == 2
    with pytest.raises(taebp.ConfigError) as e:
        taebp.run(PAPER, overrides=["scenario.avs=-1"])
    assert str(e.value) == message and isinstance(e.value, ValueError)
    assert "scenario.avs" in message
    with pytest.raises(taebp.ConfigError, match="missing.yaml: no such file"):
        taebp.run(tmp_path / "missing.yaml")
    with pytest.raises(TypeError, match="list of 'KEY=VALUE'"):
        taebp.run(PAPER, overrides="scenario.duration=10")
    # A failed call leaves the process able to run again.
    assert taebp.run(PAPER, overrides=["scenario.duration=60", "policies=[no_ebp]"]).policies == \
        ["no_ebp"]


def test_a_second_run_in_the_same_process_is_refused_while_the_gil_is_released():
    first = {}

    def long_run():
        first["result"] = taebp.run(PAPER, overrides=["scenario.duration=2400"])

    t = threading.Thread(target=long_run)
    t.start()
    # Python code keeps running while SUMO does (the GIL is released) ...
    ticks = 0
    deadline = time.monotonic() + 1.0
    while time.monotonic() < deadline:
        ticks += 1
    assert t.is_alive(), "the first run finished too early to test"
    assert ticks > 1000
    # ... and a second simulation in this process is refused, clearly.
    with pytest.raises(taebp.BusyError, match="one simulation per process") as e:
        taebp.run(PAPER, overrides=SHORT)
    assert "multiprocessing" in str(e.value)
    with pytest.raises(taebp.BusyError):
        taebp.sweep(PAPER, out="/nonexistent")
    t.join()
    # The first run was not disturbed: same result as on its own.
    again = taebp.run(PAPER, overrides=["scenario.duration=2400"])
    assert first["result"].files["summary.json"] == again.files["summary.json"]
    assert first["result"].files["encounters.csv"] == again.files["encounters.csv"]


def _seed_run(seed):
    r = taebp.run(PAPER, overrides=SHORT + ["policies=[ta_ebp]", "scenario.seed=%d" % seed])
    return r.files["encounters.csv"]


def test_multiprocessing_runs_in_parallel_like_sequential_runs():
    seeds = [1, 2, 3]
    with multiprocessing.get_context("fork").Pool(2) as pool:
        parallel = pool.map(_seed_run, seeds)
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        spawned = pool.map(_seed_run, seeds)
    sequential = [_seed_run(s) for s in seeds]
    assert parallel == sequential == spawned
    assert len(set(sequential)) == 3


def test_python_signal_handling_is_untouched_by_a_run():
    taebp.run(PAPER, overrides=["scenario.duration=30", "policies=[no_ebp]"])
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1)


def test_table_flags_rates_outside_their_interval_and_repeats_the_geometry_warning():
    # The paper's 1.7 m stop: nudged AVs intrude, SUMO reports collisions the
    # theory does not predict (README, Geometry).
    r = taebp.run(PAPER, overrides=["scenario.stop_distance=1.7", "scenario.duration=1200"])
    lines = r.table.splitlines()
    collision = [l for l in lines if l.startswith("Collision Rate")][0]
    s = r.summary["policies"]
    for policy in ("no_trust", "ta_ebp"):
        lo, hi = s[policy]["collision_rate_lo"], s[policy]["collision_rate_hi"]
        assert not lo <= s[policy]["theory_collision_rate"] <= hi
    assert collision.count(" !") == 2  # no_trust and ta_ebp, not no_ebp
    assert "! the theory lies outside the measured rate's 95% interval" in lines
    warning = [l for l in lines if l.startswith("warning: ")]
    assert warning == ["warning: " + w for w in r.warnings] and len(warning) == 1
    assert "scenario.stop_distance = 1.7 m" in warning[0]
    # The shipped geometry: no flag, no warning.
    ok = taebp.run(PAPER, overrides=SHORT)
    assert " !" not in ok.table and "warning" not in ok.table and ok.warnings == []


def test_a_sumo_failure_is_sumo_error_with_the_cli_message_and_the_process_runs_again(tmp_path):
    bad = sumo_rejected_network(tmp_path)
    over = ["scenario.network=%s" % bad, "scenario.duration=10"]
    message, code = cli_error("run", PAPER, *sum([["--set", o] for o in over], []),
                              "--out", tmp_path / "cli")
    assert code == 3
    with pytest.raises(taebp.SumoError) as e:
        taebp.run(PAPER, overrides=over)
    # SUMO's own first error leads the message, the command comes last.
    assert str(e.value) == message and message.startswith("SUMO failed to start: ")
    assert "the command was: sumo " in message
    assert isinstance(e.value, RuntimeError)
    # libsumo was closed: the next simulation in this process runs normally.
    assert len(taebp.run(PAPER, overrides=SHORT + ["policies=[ta_ebp]"]).encounters) > 20


def _blocked_grid(tmp_path):
    """The C++ suites' gridlocking grid (tests/common/stall_support.h)."""
    from conftest import ROOT
    import re
    with open(os.path.join(ROOT, "tests", "common", "stall_support.h"), encoding="utf-8") as f:
        header = f.read()
    (tmp_path / "blocked.rou.xml").write_text(re.search(r'R"\((.*?)\)"', header, re.S).group(1))
    config = tmp_path / "blocked.yaml"
    config.write_text("scenario:\n  kind: network\n"
                      "  grid: {columns: 2, rows: 2, length: 100, attach_length: 100}\n"
                      "  routes: [blocked.rou.xml]\n  av_share: 0.5\n  cruise_speed: 10\n"
                      "  duration: 900\n  seed: 5\n"
                      "model: {prior_go: 0.2, collision_penalty: 3.0, trust: 0.6}\n")
    return config


def test_a_stall_under_stall_action_error_is_stall_error_with_the_result_so_far(tmp_path):
    config = _blocked_grid(tmp_path)
    over = ["policies=[no_ebp, ta_ebp]", "scenario.stall_action=error"]
    r = cli("run", config, *sum([["--set", o] for o in over], []), "--out", tmp_path / "cli",
            check=False)
    assert r.returncode == 4, r.stderr
    message = r.stderr.splitlines()[-1]
    assert message.startswith("taebp: stalled: no_ebp: junction 'B0'")
    with pytest.raises(taebp.StallError) as e:
        taebp.run(config, overrides=over, out=tmp_path / "py")
    assert isinstance(e.value, RuntimeError)
    assert "taebp: stalled: " + str(e.value) == message
    s = e.value.result.summary
    assert s["stopped"] == "stall" and list(s["policies"]) == ["no_ebp"]
    assert s["policies"]["no_ebp"]["stalled"] and s["policies"]["no_ebp"]["stalls"]
    assert s["policies"]["no_ebp"]["trips_unfinished"] > 0
    assert (tmp_path / "py" / "summary.json").is_file()
