"""Only games have per-encounter rates (issue 26): the empty cells and nulls
sumo_native's rates and theory have come to pandas as NaN in float columns,
also where no row has a value."""
import math

import pytest

import taebp

pd = pytest.importorskip("pandas")

JUNCTIONS = (
    "policy,junction,encounters,collisions,collision_rate,collision_rate_lo,collision_rate_hi,"
    "theory_given_hvs_dc_rate\n"
    "sumo_native,C,0,0,,,,\n"
    "sumo_native,D,0,0,,,,\n")


def test_empty_rates_are_float_nan():
    frame = taebp.Table.from_csv(JUNCTIONS, "junctions.csv").to_pandas()
    for c in ("collision_rate", "collision_rate_lo", "collision_rate_hi",
              "theory_given_hvs_dc_rate"):
        assert frame[c].dtype == float, c
        assert frame[c].isna().all(), c
    assert frame["encounters"].dtype.kind == "i"
    # With a game beside it: its numbers, sumo_native's NaN.
    mixed = taebp.Table.from_csv(JUNCTIONS + "ta_ebp,C,4,1,0.25,0.04,0.7,0.3\n").to_pandas()
    assert mixed["collision_rate"].dtype == float
    assert math.isnan(mixed["collision_rate"][0]) and mixed["collision_rate"][2] == 0.25


def test_summary_nulls_are_nan_in_the_policies_frame():
    r = taebp.RunResult({"summary.json": '{"policies": {"sumo_native": {"encounters": 0, '
                                         '"collision_rate": null, "theory_dc_rate": null}}}',
                         "encounters.csv": "policy\n"})
    pol = r.to_pandas()["policies"]
    assert pol["collision_rate"].dtype == float and pol["collision_rate"].isna().all()
    assert pol["theory_dc_rate"].dtype == float
