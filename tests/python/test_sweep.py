"""taebp.sweep runs the sweep engine: the CLI's files, typed swept values, the
pooled encounters.csv, failures as SweepError, Python's signals restored."""
import csv
import io
import json
import os
import signal
import time

import pytest

import taebp
from conftest import CLI, ROOT, cli, sumo_rejected_network

CONFIG = """\
scenario: {duration: 90, seed: 3}
model: {prior_go: 0.2, collision_penalty: 3.0, trust: 0.6}
policies: [no_trust, ta_ebp]
sweep:
  replicates: 2
  grid:
    model.trust: [0.3, 0.9]
    "scenario.avs,scenario.hvs": [[8, 8], [6, 10]]
"""


@pytest.fixture
def config(tmp_path):
    path = tmp_path / "study.yaml"
    path.write_text(CONFIG)
    return path


def test_sweep_equals_the_cli_sweep(tmp_path, config):
    cli("sweep", config, "--out", tmp_path / "cli", "--jobs", 2, "--quiet")
    s = taebp.sweep(config, out=tmp_path / "py", jobs=2)
    for name in ("results.csv", "results.jsonl", "aggregate.csv", "encounters.csv", "sweep.json"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert s.keys == ["model.trust", "scenario.avs", "scenario.hvs"]
    assert len(s.results) == 4 * 2 * 2 and len(s.aggregate) == 4 * 2
    assert s.aggregate["model.trust"] == [0.3] * 4 + [0.9] * 4
    assert s.aggregate["scenario.avs"] == [8, 8, 6, 6, 8, 8, 6, 6]
    assert set(s.results["status"]) == {"ok"}
    # A task's own files.
    one = s.run(1, 1)
    assert one.summary["provenance"]["seed"] == 4
    frames = s.to_pandas()
    assert set(frames) == {"results", "aggregate", "encounters", "junctions"}
    assert len(frames["encounters"]) == len(s.encounters)
    # One row per task, policy and junction (the figure-8 has one, C), with
    # the task's point, replicate, seed and swept values in front; its
    # encounters are the task's.
    j = frames["junctions"]
    assert list(j.columns[:6]) == ["point", "replicate", "seed"] + s.keys
    assert len(j) == 4 * 2 * 2 and set(j["junction"]) == {"C"}
    res = frames["results"].set_index(["point", "replicate", "policy"])["encounters"]
    for _, row in j.iterrows():
        assert row["encounters"] == res[(row["point"], row["replicate"], row["policy"])]


def test_swept_values_keep_their_yaml_types_in_sweep_json(tmp_path):
    path = tmp_path / "typed.yaml"
    path.write_text("scenario: {duration: 30}\npolicies: [ta_ebp]\nsweep:\n  replicates: 1\n"
                    "  grid:\n    model.trust: [0.5, 1]\n    policies: [[ta_ebp], [no_ebp, ta_ebp]]\n"
                    "    scenario.auto_length: [true]\n"
                    "    \"scenario.avs,scenario.hvs\": [[8, 8]]\n")
    s = taebp.sweep(path, out=tmp_path / "out", jobs=2)
    axes = s.info["axes"]
    assert axes[0] == {"keys": ["model.trust"], "values": [[0.5], [1]]}
    assert isinstance(axes[0]["values"][0][0], float) and isinstance(axes[0]["values"][1][0], int)
    assert axes[1]["values"] == [[["ta_ebp"]], [["no_ebp", "ta_ebp"]]]
    assert axes[2]["values"] == [[True]]
    assert axes[3] == {"keys": ["scenario.avs", "scenario.hvs"], "values": [[8, 8]]}
    with open(tmp_path / "out" / "results.jsonl") as f:
        first = json.loads(f.readline())
    assert first["model.trust"] == 0.5 and first["policies"] == ["ta_ebp"]
    assert first["scenario.auto_length"] is True and first["scenario.avs"] == 8


def test_pooled_encounters_are_the_tasks_rows_with_the_task_in_front(tmp_path, config):
    s = taebp.sweep(config, out=tmp_path / "out", jobs=2)
    with open(tmp_path / "out" / "encounters.csv", newline="") as f:
        pooled = list(csv.DictReader(f))
    front = ["point", "replicate", "seed", "model.trust", "scenario.avs", "scenario.hvs"]
    assert s.encounters.columns == front + taebp.encounter_columns()
    total = 0
    for point in range(4):
        for rep in range(2):
            with open(tmp_path / "out" / "tasks" / ("%d-%d" % (point, rep)) / "encounters.csv",
                      newline="") as f:
                task_rows = list(csv.DictReader(f))
            mine = [r for r in pooled if r["point"] == str(point) and r["replicate"] == str(rep)]
            assert [{k: r[k] for k in taebp.encounter_columns()} for r in mine] == task_rows
            assert {r["seed"] for r in mine} == {str(3 + rep)}
            total += len(task_rows)
            # Encounters per policy agree with results.csv.
            for policy in ("no_trust", "ta_ebp"):
                row = [r for r in s.results if r["point"] == point and r["replicate"] == rep
                       and r["policy"] == policy][0]
                assert row["encounters"] == sum(r["policy"] == policy for r in mine)
    assert len(pooled) == total > 0


def test_a_failed_task_is_a_sweep_error_with_the_cli_message(tmp_path):
    path = tmp_path / "bad.yaml"
    # Both points are valid configs (checked before any task); the second
    # one's network is refused by SUMO when its task starts.
    good = os.path.join(os.path.dirname(CLI), "sumo_net", "figure8.net.xml")
    bad = sumo_rejected_network(tmp_path)
    path.write_text("scenario: {duration: 30}\npolicies: [ta_ebp]\nsweep:\n  replicates: 1\n"
                    "  grid:\n    scenario.network: [%s, %s]\n" % (good, bad))
    r = cli("sweep", path, "--out", tmp_path / "cli", "--jobs", 2, "--quiet", check=False)
    assert r.returncode == 1
    with open(tmp_path / "cli" / "journal.jsonl") as f:
        cli_errors = {json.loads(l)["point"]: json.loads(l)["error"] for l in f}
    with pytest.raises(taebp.SweepError) as e:
        taebp.sweep(path, out=tmp_path / "py", jobs=2)
    assert e.value.failed == [(1, 0, cli_errors[1])]
    assert "bad_speed.net.xml" in cli_errors[1] and cli_errors[1] in str(e.value)
    assert len(e.value.result.aggregate) == 2  # the ok point and the failed one
    assert e.value.result.aggregate["runs_failed"] == [0, 1]


def test_signals_are_python_s_again_and_a_second_sweep_resumes(tmp_path, config):
    taebp.sweep(config, out=tmp_path / "out", jobs=2)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    start = time.monotonic()
    again = taebp.sweep(config, out=tmp_path / "out", jobs=2)  # all tasks already done
    assert time.monotonic() - start < 5
    assert len(again.results) == 16
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1)


def test_sweep_config_errors_raise_config_error(tmp_path):
    with pytest.raises(taebp.ConfigError, match="no 'sweep:' section"):
        taebp.sweep(os.path.join(ROOT, "configs", "paper.yaml"), out=tmp_path / "x")


@pytest.mark.parametrize("jobs", [0, -1, 1.5, True])
def test_jobs_below_one_is_refused_as_the_command_line_does(tmp_path, jobs):
    config = os.path.join(ROOT, "configs", "sweep_trust.yaml")
    with pytest.raises(ValueError, match=r"jobs = .*>= 1"):
        taebp.sweep(config, out=tmp_path / "out", jobs=jobs)
    assert not (tmp_path / "out").exists()


def test_a_task_lists_the_runs_it_reused(tmp_path):
    """Issue 45 item 1: a point that differs from an earlier one only in a key
    a policy does not read reuses that policy's run; load_sweep(DIR).run(P, R)
    still lists every policy of the point, with the reused run's summary and
    rows (summary["reused_from"] says whence), and the sweep's junctions and
    encounters hold them: as a sweep without the reuse has them."""
    path = tmp_path / "reuse.yaml"
    path.write_text("scenario: {avs: 4, hvs: 4, stop_distance: 3.0, duration: 300, seed: 4}\n"
                    "model: {trust_knowledge: assumed, assumed_trust: 0.5}\n"
                    "policies: [no_trust, ta_ebp]\n"
                    "sweep:\n  replicates: 1\n  grid:\n    model.assumed_trust: [0.4, 0.9]\n")
    cli("sweep", path, "--out", tmp_path / "with", "--jobs", 1, "--quiet")
    cli("sweep", path, "--out", tmp_path / "without", "--jobs", 1, "--quiet", "--no-reuse")
    w, wo = taebp.load_sweep(tmp_path / "with"), taebp.load_sweep(tmp_path / "without")
    assert [r["reused_from"] for r in w.results] == [None, None, "0-0", None]
    run = w.run(1, 0)
    assert run.policies == ["no_trust", "ta_ebp"]
    assert run.summary["reused_from"] == {"no_trust": "0-0"}
    plain = wo.run(1, 0)
    assert len(run.encounters) == len(plain.encounters) > 0
    assert run.encounters.rows == plain.encounters.rows
    for p in ("no_trust", "ta_ebp"):
        assert run.summary["policies"][p] == plain.summary["policies"][p], p
    assert w.junctions.rows == wo.junctions.rows
    assert len(w.encounters) == len(wo.encounters) == sum(
        len(w.run(p, 0).encounters) for p in (0, 1))
