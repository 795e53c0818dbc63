#!/usr/bin/env python3
"""Whole-process paired runs: the per-step cost of each policy against a
baseline policy, as a researcher pays it (the process's start, libsumo's
loading, the simulation and the controller, the writing of the results).

    bench/paired_runs.py TAEBP CONFIG --policy P [--policy P]... [--pairs N]
                         [--baseline P | --baseline-command CMD] [--set K=V]...
                         [--target R]

For each policy, N pairs
of `TAEBP run CONFIG --set policies=[X] --quiet` processes, the two of a pair
back to back and their order alternating from pair to pair (B A, A B, B A,
...) so that a drift of the machine's speed hits both alike. Each run's CPU
time (user + system of the process and its children, from wait4: what it
costs, whatever else shares the machine) and wall time. Prints per policy the
median CPU of each side and the ratio policy / baseline pair by pair: its
median, with the min and max of the pairs as the spread. Against a baseline
policy also where the difference lies (each run's timing.json): the ratio of
SUMO's own steps (the traffic the policy makes) and the controller's steps
beyond the baseline's as a share of the baseline run (what the controller
itself costs), medians with their spread. A benchmark, run by
tools/bench on demand; never a timed test.

--baseline-command CMD: the baseline is the process CMD (split as a shell
would, without a shell), e.g. the `sumo` binary on the same scenario, in
place of `TAEBP run` with the baseline policy.

--target R: exit 1 when a policy's median ratio is above R (its line says
"missed"). The last line per policy is machine-readable:
    pairs POLICY MEDIAN_RATIO MIN MAX N
"""
import argparse
import json
import os
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def run_once(cmd):
    """(cpu seconds, wall seconds) of one whole process; fails on a non-zero exit."""
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    err = proc.stderr.read().decode(errors="replace")
    proc.stderr.close()
    if proc.returncode != 0:
        sys.exit("paired_runs: %s exited %d:\n%s" % (" ".join(cmd), proc.returncode, err[-2000:]))
    return usage.ru_utime + usage.ru_stime, wall


def parse_args():
    """The command line: (args, the baseline command split, or None, the
    scratch folder of the runs, the --set arguments)."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("taebp")
    ap.add_argument("config")
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--baseline", default="sumo_native")
    ap.add_argument("--baseline-command", metavar="CMD")
    ap.add_argument("--policy", action="append", default=[])
    ap.add_argument("--set", action="append", default=[], metavar="K=V")
    ap.add_argument("--target", type=float)
    args = ap.parse_args()
    if args.pairs < 1:
        ap.error("--pairs must be at least 1 (got %d)" % args.pairs)
    if not args.policy:
        ap.error("name at least one policy to compare with the baseline (--policy P)")
    scratch = tempfile.mkdtemp(prefix="paired_runs.")
    sets = [a for kv in args.set for a in ("--set", kv)]

    baseline_cmd = (shlex.split(args.baseline_command)
                    if args.baseline_command is not None else None)
    if baseline_cmd == []:
        ap.error("--baseline-command is empty")
    if baseline_cmd and shutil.which(baseline_cmd[0]) is None:
        ap.error("--baseline-command: %s is not a program on PATH" % baseline_cmd[0])
    return args, baseline_cmd, scratch, sets


class Runs:
    """The runs of one comparison: their commands and output folders (in
    `scratch`), and what each run's timing.json says."""

    def __init__(self, args, baseline_cmd, scratch, sets):
        self.args, self.baseline_cmd, self.scratch, self.sets = args, baseline_cmd, scratch, sets

    def out_dir(self, policy, k):
        return os.path.join(self.scratch, "%s-%d" % (policy, k))

    def split(self, policy, k):
        """(SUMO's steps, the controller's steps, all of the run) in wall
        seconds, from the run's timing.json; None for the baseline command."""
        if policy is None:
            return None
        with open(os.path.join(self.out_dir(policy, k), "timing.json")) as f:
            t = json.load(f)["policies"][policy]
        return (t["wall_seconds_sumo_steps"], t["wall_seconds_controller_steps"],
                t["wall_seconds_start"] + t["wall_seconds_sumo_steps"] +
                t["wall_seconds_controller_steps"])

    def command(self, policy, k):
        if self.baseline_cmd and policy is None:
            return self.baseline_cmd
        out = self.out_dir(policy, k)
        return [self.args.taebp, "run", self.args.config, *self.sets, "--set",
                "policies=[%s]" % policy, "--out", out, "--quiet"]


def measure(runs, policy):
    """The policy's pairs against the baseline, each pair's order alternating:
    (baseline CPU, policy CPU, CPU ratios, wall ratios, SUMO steps' ratios,
    the controller's extra share), one value per pair."""
    args, baseline_cmd = runs.args, runs.baseline_cmd
    base, pol, ratios, walls, sumo_ratios, shares = [], [], [], [], [], []
    for k in range(args.pairs):
        order = [(None if baseline_cmd else args.baseline, base), (policy, pol)]
        if k % 2 == 0:
            order.reverse()
        got = {}
        for name, sink in order:
            cpu, wall = run_once(runs.command(name, k))
            sink.append(cpu)
            got[name] = (cpu, wall)
        b = None if baseline_cmd else args.baseline
        ratios.append(got[policy][0] / got[b][0])
        walls.append(got[policy][1] / got[b][1])
        sp, sb = runs.split(policy, k), runs.split(b, k)
        if sb:
            sumo_ratios.append(sp[0] / sb[0])
            shares.append((sp[1] - sb[1]) / sb[2])
    return base, pol, ratios, walls, sumo_ratios, shares


def report(args, policy, measured):
    """Prints the policy's lines; 1 when it missed --target, else 0."""
    base, pol, ratios, walls, sumo_ratios, shares = measured
    med = statistics.median(ratios)
    verdict = ""
    missed = 0
    if args.target is not None:
        verdict = "  met" if med <= args.target else "  missed"
        missed += med > args.target
    print("%-12s %10.3f %10.3f %8.3f %8.3f %8.3f %10.3f%s" % (
        policy, statistics.median(base), statistics.median(pol), med, min(ratios),
        max(ratios), statistics.median(walls), verdict))
    print("pairs %s %.3f %.3f %.3f %d" % (policy, med, min(ratios), max(ratios), len(ratios)))
    if sumo_ratios:
        # Where the difference is (timing.json, wall seconds inside the
        # runs): SUMO's own steps on this policy's traffic against the
        # baseline's, and the controller's steps beyond the baseline's
        # as a share of the baseline run.
        print("split %s sumo_steps_ratio %.3f (%.3f-%.3f) controller_extra %.3f (%.3f-%.3f)"
              % (policy, statistics.median(sumo_ratios), min(sumo_ratios),
                 max(sumo_ratios), statistics.median(shares), min(shares), max(shares)))
    return missed


def main():
    args, baseline_cmd, scratch, sets = parse_args()
    runs = Runs(args, baseline_cmd, scratch, sets)
    missed = 0
    try:
        print("%s %s, %d pairs per policy, order alternating; CPU = user + system of the "
              "whole process; baseline %s" % (
                  os.path.basename(args.config), " ".join(args.set), args.pairs,
                  " ".join(baseline_cmd) if baseline_cmd else args.baseline))
        print("%-12s %10s %10s %8s %8s %8s %10s" % ("policy", "cpu base", "cpu pol", "ratio",
                                                   "min", "max", "wall ratio"))
        for policy in args.policy:
            missed += report(args, policy, measure(runs, policy))
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return 1 if missed else 0


if __name__ == "__main__":
    sys.exit(main())
