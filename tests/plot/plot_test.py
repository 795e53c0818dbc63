#!/usr/bin/python3
"""ctest for tools/plot: each committed fixture tests/data/aggregate_*.csv gives
its PNG (signature, plausible size), and so does a fresh (short) sweep of each
shipped study config; --help works; bad input exits non-zero.
Usage: plot_test.py SOURCE_DIR TAEBP_BINARY WORK_DIR. Fails when /usr/bin/python3
has no matplotlib (tools/setup.sh installs python3-matplotlib)."""
import os
import shutil
import struct
import subprocess
import sys

try:
    import matplotlib  # noqa: F401
except ImportError:
    # tools/setup.sh installs it: a missing package is a set-up bug, not a skip.
    print("FAIL: /usr/bin/python3 lacks matplotlib (Debian package python3-matplotlib)")
    sys.exit(1)

source, taebp, work = sys.argv[1:4]
plot = os.path.join(source, "tools", "plot")
data = os.path.join(source, "tests", "data")
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(*args):
    return subprocess.run([plot, *args], capture_output=True, text=True)


def check_png(path, what):
    if not os.path.isfile(path):
        check(False, "%s: %s written" % (what, path))
        return
    with open(path, "rb") as f:
        head = f.read(24)
    size = os.path.getsize(path)
    check(head[:8] == b"\x89PNG\r\n\x1a\n" and head[12:16] == b"IHDR", "%s: PNG signature" % what)
    w, h = struct.unpack(">II", head[16:24])
    check(400 <= w <= 4000 and 300 <= h <= 4000, "%s: %d x %d pixels" % (what, w, h))
    check(size > 20 * 1024, "%s: %d bytes (a drawn plot, not an empty canvas)" % (what, size))


MISMATCH = ["mismatch_collision_heatmap.png", "mismatch_dc_heatmap.png"]
cases = [
    ("trust", ["trust_dc_collision.png"], ["--taebp", taebp]),          # dense theory from taebp
    ("trust", ["trust_dc_collision.png"], ["--no-theory-binary"]),       # theory columns
    ("mismatch", MISMATCH, ["--taebp", taebp]),
    ("penetration", ["penetration_throughput.png"], ["--no-theory-binary"]),
]
for i, (kind, pngs, extra) in enumerate(cases):
    out = os.path.join(work, "%d_%s" % (i, kind))
    r = run(os.path.join(data, "aggregate_%s.csv" % kind), "--out", out, *extra)
    check(r.returncode == 0, "%s %s: exit 0 (%s)" % (kind, " ".join(extra), r.stderr.strip()))
    for png in pngs:
        check_png(os.path.join(out, png), "%s %s" % (kind, " ".join(extra)))
    check(sorted(os.listdir(out)) == pngs, "%s: only %s written (%s)" % (kind, pngs, os.listdir(out)))

# A sweep directory (aggregate.csv + sweep.json) is the normal input.
sweep_dir = os.path.join(work, "sweep_dir")
os.makedirs(sweep_dir)
shutil.copy(os.path.join(data, "aggregate_penetration.csv"), os.path.join(sweep_dir, "aggregate.csv"))
with open(os.path.join(sweep_dir, "sweep.json"), "w") as f:
    f.write('{"replicates": 1, "config": {"scenario": {"avs": 8, "hvs": 8, "duration": 300},'
            ' "model": {"prior_go": 0.2, "collision_penalty": 3.0, "trust": 0.6}}}')
r = run(sweep_dir, "--no-theory-binary")
check(r.returncode == 0, "sweep directory: exit 0 (%s)" % r.stderr.strip())
check_png(os.path.join(sweep_dir, "penetration_throughput.png"), "sweep directory")

# From fresh sweeps: each shipped study config, shortened (60 simulated s, one
# seed), swept by taebp and plotted from its output directory.
for kind, pngs in [("trust", ["trust_dc_collision.png"]), ("mismatch", MISMATCH),
                   ("penetration", ["penetration_throughput.png"])]:
    out = os.path.join(work, "fresh_" + kind)
    sw = subprocess.run([taebp, "sweep", os.path.join(source, "configs", "sweep_%s.yaml" % kind),
                         "--set", "scenario.duration=60", "--set", "sweep.replicates=1",
                         "--quiet", "--out", out], capture_output=True, text=True)
    check(sw.returncode == 0, "fresh %s sweep: exit 0 (%s)" % (kind, sw.stderr.strip()[-300:]))
    r = run(out, "--taebp", taebp)
    check(r.returncode == 0, "fresh %s sweep plotted: exit 0 (%s)" % (kind, r.stderr.strip()))
    for png in pngs:
        check_png(os.path.join(out, png), "fresh %s sweep" % kind)

r = run("--help")
check(r.returncode == 0 and "taebp.plot.sweep" in r.stdout and "encounters_per_hour" in r.stdout,
      "--help (names the Python calls and the metric table's metrics)")
r = run(os.path.join(work, "missing"))
check(r.returncode != 0 and "no such" in r.stderr, "missing directory: non-zero exit")
other = os.path.join(work, "other.csv")
with open(other, "w") as f:
    f.write("point,scenario.seed,policy,runs_ok\n0,1,ta_ebp,1\n")
r = run(other, "--out", os.path.join(work, "other"))
check(r.returncode != 0 and "no plot for the swept keys" in r.stderr, "unsupported swept keys: non-zero exit")

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
