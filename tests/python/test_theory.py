"""taebp.theory / design / predict / solve give the CLI's fields and numbers."""
import itertools
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import taebp
from conftest import CLI, ROOT, cli_error, cli_json


def test_acceptance_s_star_with_the_documented_path():
    # The README's check: PYTHONPATH=build/python python3 -c "...".
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(taebp.__file__)))
    env.pop("SUMO_HOME", None)
    out = subprocess.run([sys.executable, "-c", "import taebp; print(taebp.theory(prior_go=0.2, "
                          "collision_penalty=3, trust=0.6)['s_star'])"],
                         capture_output=True, text=True, env=env, cwd="/", check=True).stdout
    assert out.startswith("1.641025641")
    assert abs(float(out) - 64 / 39) < 1e-12  # s* = 2R/(1+R), R = 32/7 (the paper's point)


GRID = list(itertools.product([0.1, 0.2, 0.5], [1.0, 3.0], [0.0, 0.25, 0.6, 1.0], [None, 0.3, 1.0]))


@pytest.mark.parametrize("prior,penalty,trust,assumed", GRID[::5])
def test_theory_equals_cli_json(prior, penalty, trust, assumed):
    args = ["theory", "--json", "--prior", prior, "--penalty", penalty, "--trust", trust]
    if assumed is not None:
        args += ["--assumed-trust", assumed]
    assert taebp.theory(prior_go=prior, collision_penalty=penalty, trust=trust,
                        assumed_trust=assumed) == \
        cli_json(*args)


def test_theory_logistic_equals_cli_json():
    kw = dict(prior_go=0.3, collision_penalty=2.0, trust=0.7, s_max=3.0, likelihood="logistic",
              steepness=5.0, midpoint=1.2)
    args = ["theory", "--json", "--prior", 0.3, "--penalty", 2, "--trust", 0.7, "--s-max", 3,
            "--likelihood", "logistic", "--steepness", 5, "--midpoint", 1.2]
    assert taebp.theory(**kw) == cli_json(*args)


def test_design_and_predict_agree_with_theory_and_closed_forms():
    d = taebp.design(prior_go=0.2, collision_penalty=3, trust=0.6)
    # The paper's worked example by hand: p* = 2/(2+r), theta* = 0.25, b = 7/32.
    assert d["persuadable"] is True
    assert d["p_star"] == pytest.approx(0.4, abs=1e-15)
    assert d["theta_star"] == pytest.approx(0.25, abs=1e-12)
    assert d["b"] == pytest.approx(7 / 32, abs=1e-12)
    assert d["p_nudge"] == pytest.approx(0.2 + 0.8 * 7 / 32, abs=1e-12)
    t = taebp.theory(prior_go=0.2, collision_penalty=3, trust=0.6)
    for key in ("p_star", "theta_star", "s_star", "a", "b", "p_nudge", "persuadable"):
        assert d[key] == t[key]
    for policy, expected in t["policies"].items():
        p = taebp.predict(policy, prior_go=0.2, collision_penalty=3, trust=0.6)
        assert p["dc_rate"] == expected["dc_rate"]
        assert p["collision_rate"] == expected["collision_rate"]
        assert p["nudge_rate"] == expected["nudge_rate"]
    # No Trust designs for 1: the HV of trust 0.6 is not persuaded, collides at rate lambda.
    assert taebp.predict("no_trust", prior_go=0.2, collision_penalty=3, trust=0.6)["collision_rate"] == \
        pytest.approx(0.2, abs=1e-12)


def test_theory_errors_are_exceptions_with_the_cli_message_in_the_configs_names():
    # The CLI's message, its options named as the config (and the Python
    # arguments) name them, after the call's arguments.
    message, code = cli_error("theory", "--trust", 1.5)
    assert code == 2
    with pytest.raises(taebp.InvalidArgument) as e:
        taebp.theory(trust=1.5)
    assert str(e.value).endswith(message.replace("--trust theta", "trust"))
    assert "trust=1.5" in str(e.value) and "--" not in str(e.value)
    assert isinstance(e.value, ValueError)
    message, _ = cli_error("theory", "--prior", 1.2)
    with pytest.raises(ValueError, match="prior_go") as e:
        taebp.theory(prior_go=1.2)
    assert "prior_go=1.2" in str(e.value)
    message, _ = cli_error("theory", "--likelihood", "cubic")
    with pytest.raises(taebp.InvalidArgument) as e:
        taebp.theory(likelihood="cubic")
    assert str(e.value).endswith(message)
    with pytest.raises(taebp.InvalidArgument, match="policy"):
        taebp.predict("always_go")


# ------------------------------------------------------------------ solve
PROBLEMS = [os.path.join(ROOT, "configs", "problems", p) for p in ("av_hv.yaml", "prosecutor.yaml")]


@pytest.mark.parametrize("path", PROBLEMS)
def test_solve_file_equals_cli_json(path):
    assert taebp.solve(path) == cli_json("solve", path, "--json")


def test_solve_dict_and_numpy_equal_the_file():
    # The prosecutor example (Kamenica-Gentzkow): value 0.6, pi(convict | innocent) = 3/7.
    problem = {
        "states": ["guilty", "innocent"],
        "actions": ["acquit", "convict"],
        "prior": np.array([0.3, 0.7]),
        "receiver_utility": np.array([[0.0, 1.0], [1.0, 0.0]]),
        "sender_utility": [[0, 1], [0, 1]],
        "trust": 1.0,
    }
    out = taebp.solve(problem)
    assert out["status"] == "optimal"
    assert out["sender_value"] == pytest.approx(0.6, abs=1e-9)
    assert out["scheme"][1][1] == pytest.approx(3 / 7, abs=1e-9)
    assert out["scheme"][0][1] == pytest.approx(1.0, abs=1e-9)
    as_lists = dict(problem, prior=[0.3, 0.7], receiver_utility=[[0, 1], [1, 0]])
    assert taebp.solve(as_lists) == out


def test_solve_errors_have_the_cli_message(tmp_path):
    bad = {"states": ["a", "b"], "actions": ["x", "y"], "prior": [0.5, 0.5],
           "receiver_utility": [[1, 0]], "sender_utility": [[1, 0], [0, 1]], "trust": 1}
    path = tmp_path / "bad.yaml"
    path.write_text(json.dumps(bad))
    message, code = cli_error("solve", path, "--json")
    assert code == 2
    with pytest.raises(taebp.ConfigError) as e:
        taebp.solve(str(path))
    assert str(e.value) == message
    assert "receiver_utility" in message and "1 rows but there are 2 states" in message
    with pytest.raises(taebp.ConfigError, match="^problem: key 'receiver_utility' has 1 rows"):
        taebp.solve(bad)
    with pytest.raises(taebp.ConfigError, match="unknown key 'colour'"):
        taebp.solve(dict(bad, colour="red"))
    # Not a file: the program's message (a FIFO used to block the read).
    for name, why in (("missing.yaml", "no such file"), ("fifo.yaml", "a FIFO")):
        if name == "fifo.yaml":
            os.mkfifo(tmp_path / name)
        message, code = cli_error("solve", tmp_path / name, "--json")
        assert code == 2 and why in message
        with pytest.raises(taebp.ConfigError) as e:
            taebp.solve(str(tmp_path / name))
        assert str(e.value) == message
