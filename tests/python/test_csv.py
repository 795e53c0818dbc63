"""Every CSV the tool writes opens with csv.DictReader as it is (header on the
first line, no comment lines) and yields the columns the README documents."""
import csv
import glob
import os
import re

import taebp
from conftest import PAPER, cli, readme

STUDY = """\
scenario: {duration: 60}
policies: [no_ebp, ta_ebp]
sweep:
  replicates: 2
  grid:
    model.trust: [0.2, 0.7]
    "scenario.avs,scenario.hvs": [[8, 8], [0, 16]]
"""


def documented():
    """{(pooled?, file name): [columns]} from the README's `X.csv` ... columns: `a, b` lines."""
    docs = {}
    for m in re.finditer(r"(pooled )?`(\w+\.csv)` columns: `([^`]+)`", readme()):
        docs[(bool(m.group(1)), m.group(2))] = [c.strip() for c in m.group(3).split(",")]
    return docs


def metric_columns(level, aggregate=False):
    """The metric columns of a level from the one table (taebp.metrics())."""
    key = "aggregate_columns" if aggregate else "columns"
    return [c for m in taebp.metrics() if level in m["levels"] for c in m[key]]


def expand(columns, swept, run_columns):
    out = []
    for c in columns:
        if c == "<swept keys>":
            out += swept
        elif c == "<encounters.csv of a run>":
            out += run_columns
        elif c == "<run metrics>":
            out += metric_columns("run")
        elif c == "<pooled run metrics>":
            out += metric_columns("run", aggregate=True)
        elif c == "<junction metrics>":
            out += metric_columns("junction")
        else:
            out.append(c)
    return out


def check(path, expected):
    with open(path, newline="", encoding="utf-8") as f:
        first = f.readline()
        assert not first.startswith("#"), path
        f.seek(0)
        reader = csv.DictReader(f)
        assert reader.fieldnames == expected, path
        rows = list(reader)
    for row in rows:
        assert None not in row, "%s: a row with more cells than columns" % path
        assert None not in row.values(), "%s: a row with fewer cells than columns" % path
    return rows


def test_every_csv_of_a_run_and_a_sweep(tmp_path):
    docs = documented()
    assert set(docs) == {(False, "encounters.csv"), (False, "junctions.csv"),
                         (False, "collisions.csv"), (False, "results.csv"),
                         (False, "aggregate.csv"), (True, "encounters.csv")}, docs
    run_columns = docs[(False, "encounters.csv")]
    assert run_columns == taebp.encounter_columns()

    cli("run", PAPER, "--set", "scenario.duration=120", "--out", tmp_path / "run", "--quiet")
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    cli("sweep", study, "--out", tmp_path / "sweep", "--jobs", 2, "--quiet")
    swept = ["model.trust", "scenario.avs", "scenario.hvs"]

    written = sorted(glob.glob(str(tmp_path / "**" / "*.csv"), recursive=True))
    # run (encounters, junctions, collisions); sweep tables + pooled; 8 tasks x 3
    assert len(written) == 3 + 3 + 8 * 3
    read = 0
    for path in written:
        rel = os.path.relpath(path, tmp_path)
        name = os.path.basename(path)
        if rel == os.path.join("sweep", "encounters.csv"):
            expected = expand(docs[(True, name)], swept, run_columns)
        else:
            expected = expand(docs[(False, name)], swept, run_columns)
        rows = check(path, expected)
        read += len(rows)
        # Only the all-HV tasks (no AV-HV encounter) have a header and no row;
        # collisions.csv has a row per collision SUMO reported (maybe none).
        assert rows or name in ("encounters.csv", "collisions.csv"), path
        if name == "aggregate.csv":
            # No encounter at [0, 16]: empty rates, not a broken row.
            empty = [r for r in rows if r["scenario.avs"] == "0"]
            assert empty and all(r["collision_rate"] == "" for r in empty)
    assert read > 100


def test_a_run_reports_exactly_the_tables_metrics_under_their_names(tmp_path):
    # summary.json of a real run: every key of a policy is a metric of the
    # table (or a rate's interval) or one of its sections, and every run-level
    # metric of the run's scope is there; a sweep's aggregate has the same names.
    metrics = taebp.metrics()
    sections = {s["name"] for s in taebp.metric_sections() if s["level"] == "run"}
    r = taebp.run(PAPER, overrides=["scenario.duration=120"])
    for name, p in r.summary["policies"].items():
        declared = {c for m in metrics if "run" in m["levels"] for c in m["columns"]}
        assert set(p) - declared - sections == set(), name
        paper_scope = [c for m in metrics if "run" in m["levels"] and m["scope"] == "all"
                       for c in m["columns"]]
        assert [k for k in p if k in declared] == paper_scope, name
    frame = r.to_pandas()["policies"] if _has_pandas() else None
    if frame is not None:
        assert "theory_dc_rate" in frame.columns and "dc_rate_lo" in frame.columns


def _has_pandas():
    try:
        import pandas  # noqa: F401
        return True
    except ImportError:
        return False
