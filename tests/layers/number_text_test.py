#!/usr/bin/env python3
"""Numbers become text in one place (issue 27): taebp::NumberText
(base/include/taebp/base/number_text.h). Any other formatter of a
double in the C++ sources (a std::to_chars, a stream precision, a "%g"
conversion) fails here, naming the file and line. Fixed-point conversions
("%.2f": a column with a set number of decimals) are a different job and
allowed."""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FOLDERS = ("base", "persuasion", "config", "rundir", "report", "encounter", "junction", "scenario",
           "controller", "runner", "sweep", "cli", "python/src")
HOME = "base/src/number_text.cc"
FORMATTER = re.compile(r"std::to_chars\s*\(|\bprecision\s*\(|setprecision\s*\(|"
                       r'"[^"\n]*%[-+ #0]*[0-9]*(\.[0-9*]+)?[gG]')


def main():
    problems, checked, home_seen = [], 0, False
    for folder in FOLDERS:
        for base, _, files in os.walk(os.path.join(ROOT, folder)):
            for name in files:
                if not name.endswith((".h", ".cc", ".inc")):
                    continue
                rel = os.path.relpath(os.path.join(base, name), ROOT)
                checked += 1
                with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
                    for n, line in enumerate(f, 1):
                        code = line.split("//", 1)[0]
                        if not FORMATTER.search(code):
                            continue
                        if rel == HOME:
                            home_seen = True
                            continue
                        problems.append("%s:%d: a number formatted here (%s); use "
                                        "taebp::NumberText (taebp/base/number_text.h)"
                                        % (rel, n, line.strip()))
    if not home_seen:
        problems.append("%s does not format numbers: the check looks in the wrong place" % HOME)
    if checked < 50:
        problems.append("only %d source files found under %s: wrong root?" % (checked, ROOT))
    for p in problems:
        print(p, file=sys.stderr)
    print("number text: %d files, %d problems" % (checked, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
