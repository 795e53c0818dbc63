"""Shared fixtures of the Python tests (ctest runs each test_*.py with pytest;
PYTHONPATH points at build/python, TAEBP_CLI at build/taebp)."""
import json
import os
import re
import subprocess

import pytest

ROOT = os.environ.get("TAEBP_SOURCE_DIR") or os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(__file__))))
CLI = os.environ.get("TAEBP_CLI") or os.path.join(ROOT, "build", "taebp")
PAPER = os.path.join(ROOT, "configs", "paper.yaml")
SWEEP_TRUST = os.path.join(ROOT, "configs", "sweep_trust.yaml")


def cli(*args, check=True, cwd=None):
    """Runs build/taebp; returns the CompletedProcess (text)."""
    r = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, cwd=cwd)
    if check and r.returncode != 0:
        raise AssertionError("taebp %s failed (%d): %s" % (" ".join(map(str, args)),
                                                          r.returncode, r.stderr))
    return r


def cli_json(*args):
    return json.loads(cli(*args).stdout)


def cli_error(*args):
    """The message of a failing taebp call: its last stderr line without the
    'taebp: <kind>: ' prefix, and the exit code."""
    r = cli(*args, check=False)
    assert r.returncode != 0, "taebp %s succeeded" % " ".join(map(str, args))
    line = [l for l in r.stderr.splitlines() if l.strip()][-1]
    return re.sub(r"^taebp: (config error: |invalid argument: |error: )?", "", line), r.returncode


def readme():
    """The manual's text: README.md and every page of the site (docs/**/*.md),
    one after the other."""
    import glob
    texts = []
    for path in [os.path.join(ROOT, "README.md")] + sorted(
            glob.glob(os.path.join(ROOT, "docs", "**", "*.md"), recursive=True)):
        if not os.path.islink(path):
            with open(path, encoding="utf-8") as f:
                texts.append(f.read())
    return "\n".join(texts)


@pytest.fixture
def root():
    return ROOT


def sumo_rejected_network(folder):
    """The shipped figure-8 network with one lane speed that is not a number:
    well-formed XML that taebp accepts as a scenario and SUMO refuses at start."""
    net = open(os.path.join(os.path.dirname(CLI), "sumo_net", "figure8.net.xml")).read()
    net = re.sub(r'speed="[^"]*"', 'speed="fast"', net, count=1)
    path = os.path.join(str(folder), "bad_speed.net.xml")
    with open(path, "w") as f:
        f.write(net)
    return path
