#!/usr/bin/env python3
"""Each policy name is written once in the C++ sources: in the table of
config/src/policies.cc. Any other string literal of a library, tool, bench or
binding source that spells one (alone or inside a message) fails here, naming
the file and line: read the name from the table (config/policies.h:
FindPolicy, PolicyOf, PolicyChoices, SumoNative()). Tests may spell names
(they check the table). One exemption: enums.h's trust_knowledge value
`population_mean`, a different concept with the same spelling."""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TABLE = "config/src/policies.cc"
SOURCES = ["persuasion", "config", "report", "encounter", "junction", "scenario", "controller",
           "runner", "sweep", "rundir", "tools", "python", "bench", "fuzz", "sumo_net"]
# (file, name): a literal that spells a policy name but is not one.
EXEMPT = {("config/include/taebp/config/enums.h", "population_mean")}
ROW = re.compile(r'\{PolicyKind::k\w+,\s*"(\w+)"')
LITERAL = re.compile(r'"(?:[^"\\\n]|\\.)*"')


def names():
    with open(os.path.join(ROOT, TABLE), encoding="utf-8") as f:
        found = ROW.findall(f.read())
    return found


def code_only(line):
    """The line without a // comment (outside string literals)."""
    out, i, in_str = [], 0, False
    while i < len(line):
        c = line[i]
        if in_str:
            out.append(c)
            if c == "\\" and i + 1 < len(line):
                out.append(line[i + 1])
                i += 1
            elif c == '"':
                in_str = False
        elif c == '"':
            in_str = True
            out.append(c)
        elif line.startswith("//", i):
            break
        else:
            out.append(c)
        i += 1
    return "".join(out)


def main():
    policy_names = names()
    problems = []
    if len(policy_names) < 7:
        problems.append("%s: found only %d policy rows (%s): wrong pattern?" % (
            TABLE, len(policy_names), ", ".join(policy_names)))
    word = re.compile(r"\b(%s)\b" % "|".join(map(re.escape, policy_names)))
    checked = 0
    for top in SOURCES:
        for base, dirs, files in os.walk(os.path.join(ROOT, top)):
            dirs[:] = [d for d in dirs if not d.startswith("build")]
            for name in files:
                if not name.endswith((".h", ".cc", ".inc", ".cpp", ".hpp")):
                    continue
                rel = os.path.relpath(os.path.join(base, name), ROOT)
                if rel == TABLE:
                    continue
                checked += 1
                with open(os.path.join(base, name), encoding="utf-8") as f:
                    for n, line in enumerate(f, 1):
                        for lit in LITERAL.findall(code_only(line)):
                            for m in word.finditer(lit):
                                if (rel, m.group(1)) in EXEMPT:
                                    continue
                                problems.append("%s:%d: policy name %s written outside %s: %s" % (
                                    rel, n, m.group(1), TABLE, lit))
    if checked < 50:
        problems.append("only %d source files found under %s: wrong root?" % (checked, ROOT))
    for p in problems:
        print(p, file=sys.stderr)
    print("policy names: %d names, %d files, %d problems" % (len(policy_names), checked,
                                                          len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
