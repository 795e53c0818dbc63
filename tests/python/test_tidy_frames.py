"""Sweeps as data in a notebook: SweepResult.tidy() and the tables' frames go
into numpy as they are (numpy dtypes, no pandas Int64) and load without a
warning (issue 44)."""
import warnings

import numpy as np

import taebp
from figure_checks import POLICIES, grid_study
from taebp.plot import style


def test_tidy_frames_go_into_numpy_as_they_are_and_load_without_a_warning(tmp_path):
    d = grid_study(tmp_path / "g")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = taebp.load_sweep(d)
        agg = s.aggregate.to_pandas()
        tidy = s.tidy()
        res = s.results.to_pandas()
    # Counts are numpy int64 (float64 where a cell is empty), never pandas' Int64.
    assert agg["runs_ok"].dtype == np.int64 and agg["point"].dtype == np.int64
    assert agg["encounters"].dtype == np.int64
    assert agg["collisions"].dtype == np.float64  # empty for sumo_native
    assert all(not str(t).startswith(("Int", "Float", "boolean")) for t in agg.dtypes)
    # What failed on pandas' nullable Int64 (TypeError, or an object array):
    corr = np.corrcoef(agg["encounters"], agg["served_flow"])
    assert corr.dtype == np.float64 and np.isfinite(corr).all()
    assert np.log(agg["encounters"] + 1).dtype == np.float64
    assert np.isfinite(agg["encounters"].corr(agg["served_flow"]))
    # The long frame: swept keys as numbers, floats for values.
    assert list(tidy.columns[:5]) == ["point", "scenario.av_share", "model.trust",
                                      "model.trust.dist", "model.trust.mean"]
    assert tidy["scenario.av_share"].dtype == np.float64
    assert tidy["model.trust.mean"].dtype == np.float64
    for c in ("value", "lo", "hi", "theory"):
        assert tidy[c].dtype == np.float64, c
    for c in ("runs", "failed", "stalled"):
        assert tidy[c].dtype == np.int64, c
    rate = tidy[(tidy.metric == "collision_rate")]
    assert set(rate.policy) == {p for p in POLICIES if style.plays_game(p)}
    np.log1p(tidy["value"].to_numpy())
    assert res["replicate"].dtype == np.int64
    # The documented spelling works too.
    assert len(taebp.plot.tidy.to_pandas(taebp.load_sweep(d))) == len(tidy)
