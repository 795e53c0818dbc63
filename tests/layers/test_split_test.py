#!/usr/bin/env python3
"""The plain/sanitizer split of the tests rests on markers the tests carry,
never on names kept in tests/CMakeLists.txt (issue 46: a renamed suite
silently changed halves).

Checks: every TEST_FILTER of tests/CMakeLists.txt is a filter that
taebp_marked_filter computed ("${VAR}" or "-${VAR}"); every marker in a test
source is of a known kind and marks something (a `// taebp-test:` line right
above a TEST line, a `// taebp-tests:` line before the file's first TEST).
Fails naming the file, the line and the rule."""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
KINDS = {"study", "sanitize"}
FILTER = re.compile(r'TEST_FILTER\s+"([^"]*)"')
COMPUTED = re.compile(r'taebp_marked_filter\((\w+)\s+(\w+)\s')
TEST = re.compile(r"^TEST(_F|_P)?\(")
MARK = re.compile(r"^// taebp-tests?: (\S+)")


def main():
    problems = []
    cmake = os.path.join(ROOT, "tests", "CMakeLists.txt")
    with open(cmake, encoding="utf-8") as f:
        text = f.read()
    computed = {}
    for m in COMPUTED.finditer(text):
        computed[m.group(2)] = m.group(1)
        if m.group(1) not in KINDS:
            problems.append("tests/CMakeLists.txt: taebp_marked_filter(%s ...): unknown kind "
                            "(known: %s)" % (m.group(1), ", ".join(sorted(KINDS))))
    filters = 0
    for m in FILTER.finditer(text):
        filters += 1
        line = text.count("\n", 0, m.start()) + 1
        value = m.group(1)
        var = re.fullmatch(r"-?\$\{(\w+)\}", value)
        if not var or var.group(1) not in computed:
            problems.append("tests/CMakeLists.txt:%d: TEST_FILTER \"%s\" is not a filter of "
                            "marked tests (taebp_marked_filter): mark the tests in their "
                            "source instead" % (line, value))
    if filters < 4:
        problems.append("only %d TEST_FILTERs in tests/CMakeLists.txt: stale check?" % filters)
    marks = 0
    for base, _, files in os.walk(os.path.join(ROOT, "tests")):
        for name in files:
            if not name.endswith(".cc"):
                continue
            rel = os.path.relpath(os.path.join(base, name), ROOT)
            with open(os.path.join(base, name), encoding="utf-8") as f:
                lines = f.read().split("\n")
            seen_test = False
            for n, line in enumerate(lines, 1):
                if TEST.match(line):
                    seen_test = True
                m = MARK.match(line)
                if not m:
                    continue
                marks += 1
                kind = m.group(1)
                if kind not in KINDS:
                    problems.append("%s:%d: unknown marker kind '%s' (known: %s)" % (
                        rel, n, kind, ", ".join(sorted(KINDS))))
                if line.startswith("// taebp-tests:") and seen_test:
                    problems.append("%s:%d: '// taebp-tests:' after the file's first TEST "
                                    "marks nothing" % (rel, n))
                if line.startswith("// taebp-test:") and (
                        n >= len(lines) or not TEST.match(lines[n])):
                    problems.append("%s:%d: '// taebp-test:' not right above a TEST line "
                                    "marks nothing" % (rel, n))
    if marks == 0:
        problems.append("no marker found under tests/: stale check?")
    for p in problems:
        print(p, file=sys.stderr)
    print("test split: %d filters, %d markers, %d problems" % (filters, marks, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
