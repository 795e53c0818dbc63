"""Results never lost from Python (issue 32): Ctrl-C stops a run promptly with
the folder's old results intact (item 4); a sweep into a run's folder is
refused (item 1); SweepResult.run names a bad point (item 14)."""
import os
import signal
import threading
import time

import pytest

import taebp
from conftest import PAPER

SHORT = ["scenario.duration=60", "policies=[ta_ebp]"]


def files(folder):
    out = {}
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if name == ".taebp.lock" or os.path.isdir(path):
            continue
        with open(path, "rb") as f:
            out[name] = f.read()
    return out


def test_ctrl_c_stops_a_run_at_once_and_the_old_results_stay(tmp_path):
    out = tmp_path / "R"
    taebp.run(PAPER, SHORT, out=out)
    before = files(out)
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt) as e:
        taebp.run(PAPER, ["scenario.seed=2", "scenario.duration=3000"], out=out)
    stopped = time.monotonic() - start
    timer.join()
    assert "SIGINT" in str(e.value)
    # Before: 3.42 s of a 3.58 s run, the folder already replaced.
    assert stopped < 0.3 + 1.0, "KeyboardInterrupt %.2f s after the start" % stopped
    assert files(out) == before
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    # The folder is free again (unlocked) and Python's Ctrl-C works as before.
    taebp.run(PAPER, SHORT, out=out)
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1)


def test_a_sweep_into_a_runs_folder_is_refused(tmp_path):
    out = tmp_path / "R"
    taebp.run(PAPER, SHORT, out=out)
    before = files(out)
    config = tmp_path / "sweep.yaml"
    config.write_text("scenario: {duration: 30, seed: 3}\npolicies: [ta_ebp]\n"
                      "sweep: {replicates: 1, grid: {model.trust: [0.3, 0.9]}}\n")
    with pytest.raises(taebp.OutputError, match="holds a run's results"):
        taebp.sweep(config, out=out, jobs=1)
    assert files(out) == before


def test_sweep_result_run_names_a_point_that_is_not_a_number(tmp_path):
    config = tmp_path / "sweep.yaml"
    config.write_text("scenario: {duration: 30, seed: 3}\npolicies: [ta_ebp]\n"
                      "sweep: {replicates: 1, grid: {model.trust: [0.3, 0.9]}}\n")
    result = taebp.sweep(config, out=tmp_path / "S", jobs=1)
    with pytest.raises(TypeError, match=r"point must be a grid point's number.*'a'"):
        result.run("a", 0)
    with pytest.raises(TypeError, match=r"replicate must be.*1\.5"):
        result.run(0, 1.5)
    assert result.run(1, 0).summary["policies"]["ta_ebp"]
