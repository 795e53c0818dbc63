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


def expand(columns, swept, run_columns):
    out = []
    for c in columns:
        if c == "<swept keys>":
            out += swept
        elif c == "<encounters.csv of a run>":
            out += run_columns
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
                         (False, "results.csv"), (False, "aggregate.csv"),
                         (True, "encounters.csv")}, docs
    run_columns = docs[(False, "encounters.csv")]
    assert run_columns == taebp.encounter_columns()

    cli("run", PAPER, "--set", "scenario.duration=120", "--out", tmp_path / "run", "--quiet")
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    cli("sweep", study, "--out", tmp_path / "sweep", "--jobs", 2, "--quiet")
    swept = ["model.trust", "scenario.avs", "scenario.hvs"]

    written = sorted(glob.glob(str(tmp_path / "**" / "*.csv"), recursive=True))
    # run (encounters, junctions); sweep tables + pooled; 8 tasks x 2
    assert len(written) == 2 + 3 + 8 * 2
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
        # Only the all-HV tasks (no AV-HV encounter) have a header and no row.
        assert rows or name == "encounters.csv", path
        if name == "aggregate.csv":
            # No encounter at [0, 16]: empty rates, not a broken row.
            empty = [r for r in rows if r["scenario.avs"] == "0"]
            assert empty and all(r["collision_rate"] == "" for r in empty)
    assert read > 100
