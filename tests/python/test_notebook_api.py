"""taebp as a notebook expects it: theory/predict/design broadcast over arrays
to DataFrames under the config's names (defaults from the C++ request),
solve with DataFrames, run/sweep with dicts, `import taebp` gives the whole
API, docstrings that list every policy and option."""
import inspect
import warnings

import numpy as np
import pandas as pd
import pytest

import taebp
from taebp import _taebp


def theta_star_closed_form(lam, r):
    """Theorem 1 for the AV-HV game (paper Sec. IV-A, eq. after (12)):
    theta* = (2(1 - lambda) - r lambda) / ((1 - lambda)(r + 2)), and 0 where
    that is negative (the HV is persuadable at any trust)."""
    return np.maximum(0.0, (2 * (1 - lam) - r * lam) / ((1 - lam) * (r + 2)))


def test_theta_star_grid_over_lambda_and_r_in_one_call():
    lam = np.linspace(0.05, 0.5, 46)
    r = np.linspace(0.5, 5.0, 46)
    df = taebp.theory(prior_go=lam[:, None], collision_penalty=r[None, :])
    assert isinstance(df, pd.DataFrame) and len(df) == 46 * 46
    assert {"prior_go", "collision_penalty", "trust", "theta_star", "s_star",
            "policies.ta_ebp.dc_rate"} <= set(df.columns)
    expected = theta_star_closed_form(df["prior_go"].astype(float).to_numpy(),
                                      df["collision_penalty"].astype(float).to_numpy())
    assert np.allclose(df["theta_star"].astype(float).to_numpy(), expected, atol=1e-12)
    # Row order: numpy's (lambda slowest), the inputs as given.
    assert df["prior_go"].iloc[46] == lam[1] and df["collision_penalty"].iloc[1] == r[1]
    # The paper's point.
    one = df[(np.isclose(df["prior_go"].astype(float), 0.2)) &
             (np.isclose(df["collision_penalty"].astype(float), 3.0))]
    assert len(one) == 1 and abs(one["theta_star"].iloc[0] - 0.25) < 1e-12


def test_scalars_still_give_the_dict_and_lists_broadcast():
    d = taebp.theory(prior_go=0.2, collision_penalty=3, trust=0.6)
    assert isinstance(d, dict) and abs(d["s_star"] - 64 / 39) < 1e-12
    df = taebp.theory(trust=[0.1, 0.6, 1.0])
    assert list(df["trust"]) == [0.1, 0.6, 1.0]
    assert df["s_star"].iloc[1] == d["s_star"]
    p = taebp.predict(["no_ebp", "no_trust", "ta_ebp"], trust=0.6)
    assert list(p["policy"]) == ["no_ebp", "no_trust", "ta_ebp"]
    assert abs(p.set_index("policy").loc["no_trust", "collision_rate"] - 0.2) < 1e-12
    des = taebp.design(trust=np.array([0.2, 0.6]))
    assert list(des["persuadable"]) == [False, True]


def test_defaults_are_the_cpp_requests_and_names_are_the_configs():
    defaults = _taebp.theory_defaults()
    for f in (taebp.theory, taebp.predict, taebp.design):
        params = inspect.signature(f).parameters
        for name, value in defaults.items():
            assert params[name].default == value, (f.__name__, name)
        assert "prior" not in params and "penalty" not in params
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        old = taebp.theory(prior=0.2, penalty=3, trust=0.6)
    assert old == taebp.theory(prior_go=0.2, collision_penalty=3, trust=0.6)
    assert any(issubclass(x.category, DeprecationWarning) and "prior_go" in str(x.message) for x in w)
    with pytest.raises(TypeError, match="colour"):
        taebp.theory(colour=1)


def test_errors_name_the_argument_and_its_value():
    with pytest.raises(taebp.InvalidArgument) as e:
        taebp.theory(trust=[0.5, 1.5])
    message = str(e.value)
    assert "trust=1.5" in message and "--" not in message
    with pytest.raises(ValueError) as e:
        taebp.theory(prior_go=1.2)
    assert "prior_go" in str(e.value) and "--prior" not in str(e.value)


def test_solve_takes_and_returns_dataframes():
    # configs/problems/av_hv.yaml as DataFrames (rows = states).
    states, actions = ["go", "stop"], ["DR", "DC"]
    receiver = pd.DataFrame([[-3.0, 0.0], [1.0, -1.0]], index=states, columns=actions)
    sender = pd.DataFrame([[-1.0, 1.0], [-1.0, 1.0]], index=states, columns=actions)
    out = taebp.solve({"prior": pd.Series([0.2, 0.8], index=states), "receiver_utility": receiver,
                       "sender_utility": sender, "trust": 0.6})
    assert isinstance(out["scheme"], pd.DataFrame)
    assert list(out["scheme"].index) == states and list(out["scheme"].columns) == actions
    assert np.allclose(out["scheme"].sum(axis=1), 1.0)
    plain = taebp.solve({"states": states, "actions": actions, "prior": [0.2, 0.8],
                         "receiver_utility": receiver.values.tolist(),
                         "sender_utility": sender.values.tolist(), "trust": 0.6})
    assert isinstance(plain["scheme"], list)
    assert np.allclose(out["scheme"].to_numpy(), np.array(plain["scheme"]))
    assert abs(out["sender_value"] - plain["sender_value"]) < 1e-12


def test_run_takes_a_dict_config_and_dict_overrides(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    text = ("scenario: {duration: 60, seed: 2}\nmodel: {prior_go: 0.2, collision_penalty: 3.0, "
            "trust: 0.6}\npolicies: [ta_ebp]\n")
    (tmp_path / "c.yaml").write_text(text)
    from_file = taebp.run(str(tmp_path / "c.yaml"))
    config = {"scenario": {"duration": 90, "seed": 2},
              "model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6},
              "policies": ["no_trust"]}
    from_dict = taebp.run(config, overrides={"scenario.duration": 60, "policies": ["ta_ebp"]})
    assert from_dict.files["encounters.csv"] == from_file.files["encounters.csv"]
    assert [p.name for p in tmp_path.iterdir()] == ["c.yaml"]  # the dict's file is gone
    with pytest.raises(TypeError, match="dict"):
        taebp.run(42)


def test_import_taebp_gives_the_whole_api_and_docstrings_list_the_tables():
    assert taebp.stats.wilson(0, 10)[0] == 0.0
    assert taebp.dists.label({"dist": "beta", "alpha": 12, "beta": 8}) == "Beta mean 0.6 sd 0.11"
    for name in taebp.__all__:
        assert hasattr(taebp, name), name
    policies = taebp.policies()
    assert policies[0] == "sumo_native" and "population_mean" in policies
    for p in policies:
        assert p in taebp.run.__doc__, p
    for name in inspect.signature(taebp.sweep).parameters:
        assert "``%s``" % name in taebp.sweep.__doc__, name


# ---- notebook manners (issue 44)
def test_a_dict_configs_errors_name_the_dict_and_the_key(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    config = {"scenario": {"duration": 60, "avs": -3}, "policies": ["ta_ebp"]}
    with pytest.raises(taebp.ConfigError) as e:
        taebp.run(config)
    message = str(e.value)
    assert message.startswith("config dict") and "scenario.avs" in message, message
    assert ".taebp-config-" not in message and ".yaml" not in message, message
    assert list(tmp_path.iterdir()) == []  # the dict's file is gone
    with pytest.raises(taebp.ConfigError) as e:
        taebp.sweep(dict(config), out=str(tmp_path / "s"))
    assert str(e.value).startswith("config dict") and ".taebp-config-" not in str(e.value)


def test_dict_values_follow_the_yaml_loaders_rule(tmp_path, monkeypatch):
    """An integral float for an integer key is the integer (a DataFrame gives
    8.0); a string for a number is refused, as in a YAML file."""
    monkeypatch.chdir(tmp_path)
    base = {"scenario": {"duration": 30, "avs": 8.0, "hvs": 8},
            "model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6},
            "policies": ["ta_ebp"]}
    r = taebp.run(base)
    assert "avs: 8\n" in r.config
    frame_like = json_roundtrip(base)
    frame_like["scenario"]["avs"] = np.float64(8.0)
    assert taebp.run(frame_like).files["encounters.csv"] == r.files["encounters.csv"]
    for bad in ({"scenario": {"avs": 8.5}}, {"model": {"trust": "0.7"}},
                {"scenario": {"duration": "30"}}):
        config = json_roundtrip(base)
        for section, values in bad.items():
            config[section].update(values)
        with pytest.raises(taebp.ConfigError) as e:
            taebp.run(config)
        key = "%s.%s" % next((s, k) for s, v in bad.items() for k in v)
        assert key in str(e.value) and str(e.value).startswith("config dict"), str(e.value)
    (tmp_path / "c.yaml").write_text("model: {trust: '0.7'}\npolicies: [ta_ebp]\n")
    with pytest.raises(taebp.ConfigError) as e:
        taebp.run(str(tmp_path / "c.yaml"))
    assert "model.trust" in str(e.value)


def json_roundtrip(d):
    import json
    return json.loads(json.dumps(d))


def test_theory_functions_name_a_bad_argument():
    for f in (taebp.theory, taebp.design):
        with pytest.raises(taebp.InvalidArgument) as e:
            f(trust="high")
        assert "trust" in str(e.value) and "'high'" in str(e.value) and \
            str(e.value).startswith(f.__name__ + "("), str(e.value)
        assert isinstance(e.value, ValueError)
    with pytest.raises(taebp.InvalidArgument, match=r"prior_go must be a number, got '0.2'"):
        taebp.predict("ta_ebp", prior_go="0.2")
    with pytest.raises(taebp.InvalidArgument, match="likelihood"):
        taebp.theory(likelihood=3)
    # numpy numbers are numbers
    assert taebp.theory(trust=np.float64(0.6))["s_star"] == taebp.theory(trust=0.6)["s_star"]
    assert taebp.theory(trust=np.array(0.6))["s_star"] == taebp.theory(trust=0.6)["s_star"]


def test_stats_wilson_broadcasts():
    k = np.array([0, 3, 10, 0])
    n = np.array([10, 10, 10, 0])
    lo, hi = taebp.stats.wilson(k, n)
    assert lo.shape == hi.shape == (4,)
    for i in range(4):
        assert (lo[i], hi[i]) == taebp.stats.wilson(int(k[i]), int(n[i]))
    lo, hi = taebp.stats.wilson(pd.Series([1, 2]), 10)
    assert np.allclose(lo, [taebp.stats.wilson(1, 10)[0], taebp.stats.wilson(2, 10)[0]])
    grid_lo, _ = taebp.stats.wilson(np.arange(3)[:, None], np.array([5, 10]))
    assert grid_lo.shape == (3, 2)
    with pytest.raises(ValueError, match="0 <= k <= n"):
        taebp.stats.wilson([1, 11], [10, 10])


def test_run_stops_at_its_timeout_and_writes_nothing(tmp_path):
    import time
    start = time.monotonic()
    with pytest.raises(TimeoutError) as e:
        taebp.run(taebp.shipped_config("paper.yaml"), out=str(tmp_path / "out"), timeout=1.5)
    assert time.monotonic() - start < 15
    assert "timeout=1.5" in str(e.value) and "nothing written" in str(e.value)
    assert not (tmp_path / "out").exists() or not list((tmp_path / "out").iterdir())
    # The lock is gone: the same folder takes a (short) run after it.
    r = taebp.run(taebp.shipped_config("paper.yaml"), out=str(tmp_path / "out"),
                  overrides={"scenario.duration": 30, "policies": ["ta_ebp"]}, timeout=120)
    assert (tmp_path / "out" / "summary.json").is_file() and r.summary
    with pytest.raises(ValueError, match="timeout"):
        taebp.run(taebp.shipped_config("paper.yaml"), timeout=0)
    with pytest.raises(FileNotFoundError, match="paper.yaml"):
        taebp.shipped_config("no_such.yaml")
