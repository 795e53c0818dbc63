"""The manual's Python runs as written from any folder (extracted from
docs/python.md and README.md, run in an empty temporary folder): it
reproduces Table I as `taebp run` prints it and draws the trust-sweep
figures (taebp.plot.sweep, and a seaborn view of SweepResult.tidy())."""
import os
import re
import subprocess
import sys

from PIL import Image

import taebp
from conftest import readme


def example():
    m = re.search(r"<!-- python example -->\n```python\n(.*?)\n```", readme(), re.S)
    assert m, "no page (README.md, docs/**/*.md) has a '<!-- python example -->' python block"
    return m.group(1)


def table_block():
    m = re.search(r"which prints\s+\(and writes to `results/paper/`\):\n\n```\n(.*?)\n```", readme(), re.S)
    assert m
    return m.group(1)


def ta_ebp_dc():
    """TA-EBP's DC rate in the README's Table I (the same seed-1 run)."""
    m = re.search(r"\| DC rate \| TA-EBP \| [^|]+ \| [^|]+ \| ([0-9.]+) \[", readme())
    assert m, "README.md's Table I has no TA-EBP DC rate"
    return float(m.group(1))


def test_readme_python_example_runs_as_written(tmp_path):
    (tmp_path / "example.py").write_text(example())
    # As the README says: PYTHONPATH points at build/python.
    env = dict(os.environ, MPLBACKEND="Agg",
               PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(taebp.__file__))))
    r = subprocess.run([sys.executable, "example.py"], cwd=tmp_path, env=env,
                       capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, r.stderr
    printed = "\n".join(l.rstrip() for l in r.stdout.splitlines())
    # Table I as the README shows it (the same run as `taebp run configs/paper.yaml`).
    assert table_block() in printed
    assert "ta_ebp    collisions 0.000  DC %.3f  (theory 0.375)" % ta_ebp_dc() in printed
    for f in ("summary.json", "encounters.csv", "config.yaml"):
        assert (tmp_path / "results" / "paper_py" / f).is_file()
    assert (tmp_path / "results" / "sweep_trust_py" / "aggregate.csv").is_file()
    assert (tmp_path / "results" / "figures_py" / "trust_dc_collision.png").is_file()
    picture = Image.open(tmp_path / "results" / "trust_dc_py.png")
    assert picture.size == (600, 400)
    # Not a blank canvas: the three policies' colours are drawn.
    colours = set(picture.convert("RGB").getdata())
    for policy in ("ta_ebp", "no_trust", "full_reveal"):  # each in its colour of the table
        rgb = tuple(int(taebp.plot.style.policy_colour(policy)[i:i + 2], 16) for i in (1, 3, 5))
        assert rgb in colours, policy


def test_readmes_python_lines_run_from_any_folder(tmp_path):
    m = re.search(r"## Python in five lines\n\n```python\n(.*?)```", readme(), re.S)
    assert m, "README.md has no 'Python in five lines' block"
    (tmp_path / "five.py").write_text(m.group(1))
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(
        os.path.abspath(taebp.__file__))))
    r = subprocess.run(["/usr/bin/python3", "five.py"], cwd=tmp_path, env=env,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.split()
    assert abs(float(lines[0]) - 64 / 39) < 1e-12 and 0 < float(lines[1]) < 1, r.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["five.py"]  # nothing left behind
