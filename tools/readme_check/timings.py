"""Tier timings (and bench): wall times the pages state, within half to twice
the stated one, and tools/bench's targets met."""

import os
import subprocess

from .commands import JUNCTION_SNAPSHOT, PAPER, SNAPSHOT, SWEEP
from .context import ROOT
from .formats import seconds


def sweep_times(ctx, m):
    return {name: seconds(m.group(name), ctx.run(SWEEP[name]).seconds)
            for name in ("trust", "mismatch", "penetration")}


def run_time(ctx, m):
    return {"run": seconds(m.group("run"), ctx.run(PAPER).seconds)}


def snapshot_time(ctx, m):
    return {"snap": seconds(m.group("snap"), ctx.run(SNAPSHOT).seconds)}


def newcomer_time(ctx, m):
    return {"secs": seconds(m.group("secs"), ctx.run(m.group("block")).seconds)}


def junction_snapshot_time(ctx, m):
    return {"snap": seconds(m.group("snap"), ctx.run(JUNCTION_SNAPSHOT).seconds)}


def bench(ctx, m):
    r = subprocess.run([os.path.join(ROOT, "tools", "bench")], capture_output=True, text=True,
                       env=dict(os.environ, TAEBP_BUILD_DIR=ctx.build))
    return {"met": "all targets met" if r.returncode == 0 else
            "tools/bench: %s" % r.stdout.strip().splitlines()[-1]}
