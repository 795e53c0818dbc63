#!/usr/bin/env python3
"""Each SUMO call is written twice: declared once in the interface
(controller/include/taebp/controller/sumo_world.h: SumoWorld, SumoSimulation)
and defined once, for both backends, in controller/src/sumo_adapter_impl.inc.
Fails naming the call and where else it is written:
- a virtual of the interface that the .inc does not define exactly once;
- an override of one of them in a library, tool or binding source (a second
  adapter; a test's fake world may override them);
- a libsumo/libtraci call (`S::Class::method`, `libsumo::`, `libtraci::`)
  outside the .inc (the backends' two translation units only include it)."""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
INTERFACE = "controller/include/taebp/controller/sumo_world.h"
BODY = "controller/src/sumo_adapter_impl.inc"
SOURCES = ["persuasion", "config", "report", "encounter", "junction", "scenario", "controller",
           "runner", "sweep", "rundir", "tools", "python", "bench", "fuzz"]
# Where a libsumo name may appear outside the body: the backends' includes,
# and SumoError's catch of TraCIException is in the body too.
SUMO_API_ALLOWED = {BODY, "controller/src/sumo_adapter.cc", "controller/src/sumo_adapter_libtraci.cc"}
VIRTUAL = re.compile(r"virtual\s+[\w:<>, ]+?[\s&*]+(\w+)\s*\(")
SUMO_API = re.compile(r"\bS::\w+::\w+\s*\(|\blib(?:sumo|traci)::\w+::\w+\s*\(")


def read(rel):
    with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
        return f.read()


def main():
    problems = []
    calls = [n for n in VIRTUAL.findall(read(INTERFACE)) if n != "SumoWorld"]
    if len(calls) < 40:
        problems.append("%s: only %d calls found (%s): has the interface moved?"
                        % (INTERFACE, len(calls), ", ".join(calls)))
    body = read(BODY)
    for name in calls:
        n = len(re.findall(r"\b%s\s*\([^;{]*\)\s*override\b" % name, body))
        if n != 1:
            problems.append("%s: %s defined %d times (once, for both backends)" % (BODY, name, n))
    override = re.compile(r"\b(%s)\s*\([^;{]*\)\s*(?:const\s*)?override\b" % "|".join(calls))
    api_files = 0
    for folder in SOURCES:
        for base, _, files in os.walk(os.path.join(ROOT, folder)):
            for fname in files:
                if not fname.endswith((".h", ".cc", ".inc")):
                    continue
                rel = os.path.relpath(os.path.join(base, fname), ROOT)
                text = read(rel)
                if rel != BODY:
                    for m in override.finditer(text):
                        line = text.count("\n", 0, m.start()) + 1
                        problems.append("%s:%d: %s overridden outside %s (a second adapter)"
                                        % (rel, line, m.group(1), BODY))
                for m in SUMO_API.finditer(text):
                    if rel in SUMO_API_ALLOWED:
                        api_files += rel == BODY
                        continue
                    line = text.count("\n", 0, m.start()) + 1
                    problems.append("%s:%d: SUMO's API (%s) outside %s"
                                    % (rel, line, m.group(0).rstrip("("), BODY))
    if api_files < 40:
        problems.append("%s: only %d SUMO API calls found: has the body moved?" % (BODY, api_files))
    for p in problems:
        print(p, file=sys.stderr)
    print("sumo calls: %d, each declared in %s and defined in %s; %d problems"
          % (len(calls), INTERFACE, BODY, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
