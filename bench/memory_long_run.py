#!/usr/bin/env python3
"""Peak memory of a long learning run against a run a quarter as long.

Issue 45 item 7: configs/influence.yaml with outputs.interval 1 and
outputs.per_hv true (a timeseries.csv row every simulated second, an
hv_trust.csv row per HV) held every row in memory: 157 MB at 40,000 simulated
s, 374 MB at 160,000, then std::bad_alloc. The rows now stream to disk as they
are sampled (report/sample_spool.h), so the peak should barely grow with
simulated time; what still grows is the encounters kept for summary.json
(a few hundred bytes each).

usage: memory_long_run.py TAEBP CONFIG [--short S] [--long L] [--target R]

Runs `TAEBP run CONFIG` with policy ta_ebp for S and for L simulated seconds
(defaults 40,000 and 160,000), each in its own process, and reads each
process's peak resident memory from wait4 (ru_maxrss). Prints one line per run
and the ratio; exit 0 when long/short <= R (default 1.3), 1 when missed, 2
when a run failed. Also checks that the long run wrote every row it sampled
(timeseries.csv: L rows; hv_trust.csv: 8 per row).
"""
import argparse
import os
import subprocess
import sys
import tempfile


def run(taebp, config, seconds, out):
    args = [taebp, "run", config, "--set", f"scenario.duration={seconds}",
            "--set", "outputs.interval=1", "--set", "outputs.per_hv=true",
            "--set", "policies=[ta_ebp]", "--out", out]
    with open(os.path.join(os.path.dirname(out), f"run-{seconds}.log"), "w") as log:
        proc = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(proc.pid, 0)
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        print(f"taebp run ({seconds} s) exited {code}: see {log.name}", file=sys.stderr)
        sys.exit(2)
    return usage.ru_maxrss / 1024.0  # KiB -> MiB


def rows(path):
    with open(path, "rb") as f:
        return sum(1 for _ in f) - 1


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("taebp")
    p.add_argument("config")
    p.add_argument("--short", type=int, default=40000)
    p.add_argument("--long", type=int, default=160000)
    p.add_argument("--target", type=float, default=1.3)
    a = p.parse_args()
    with tempfile.TemporaryDirectory(prefix="taebp-memory-") as tmp:
        peaks = {}
        for seconds in (a.short, a.long):
            out = os.path.join(tmp, f"run-{seconds}")
            peaks[seconds] = run(a.taebp, a.config, seconds, out)
            n_time = rows(os.path.join(out, "timeseries.csv"))
            n_hv = rows(os.path.join(out, "hv_trust.csv"))
            print(f"{seconds} simulated s: peak resident {peaks[seconds]:.1f} MiB, "
                  f"timeseries.csv {n_time} rows, hv_trust.csv {n_hv} rows")
            if n_time != seconds:
                print(f"timeseries.csv has {n_time} rows, not {seconds}", file=sys.stderr)
                sys.exit(2)
    ratio = peaks[a.long] / peaks[a.short]
    print(f"ratio {ratio:.3f} (target <= {a.target})")
    return 0 if ratio <= a.target else 1


if __name__ == "__main__":
    sys.exit(main())
