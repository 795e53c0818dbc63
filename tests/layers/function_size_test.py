#!/usr/bin/env python3
"""Functions of a readable size (issue 46): no function of the tree's C++ or
Python (tests and developer scripts included) over MAX_LINES lines, head to
closing brace (a Python def to its last line). A long one fails here, named
by file, line, function and length.

C++ functions are found by their head at the start of a line (not a
namespace, class, struct, enum or a declaration) and brace matching, string
and character literals and comments skipped; Python ones with ast."""
import ast
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MAX_LINES = 80
SKIP_DIRS = {".git", "node_modules", "__pycache__", "site"}
CPP = (".cc", ".h", ".inc", ".cpp")
HEAD = re.compile(r"^(?!namespace\b|class\b|struct\b|enum\b|union\b|using\b|typedef\b|#|//|}|"
                  r"template\s*<[^>]*>\s*$|extern\s+\"C\"\s*\{)[A-Za-z_].*\(")
LITERAL = re.compile(r'"(?:\\.|[^"\\])*"|\'(?:\\.|[^\'\\])*\'|//.*$')


def code_of(line):
    return LITERAL.sub('""', line)


def cpp_functions(path):
    """(name, first line, length) of each function defined at column 0."""
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().split("\n")
    found, i, in_comment = [], 0, False
    while i < len(lines):
        line = lines[i]
        if in_comment:
            in_comment = "*/" not in line
            i += 1
            continue
        if line.lstrip().startswith("/*") and "*/" not in line:
            in_comment = True
            i += 1
            continue
        if not HEAD.match(line) or code_of(line).rstrip().endswith(";"):
            i += 1
            continue
        # the body's opening brace: on this line or a following one, before any ';'
        j, opened = i, False
        while j < len(lines) and j < i + 12:
            code = code_of(lines[j])
            if "{" in code:
                opened = True
                break
            if code.rstrip().endswith(";"):
                break
            j += 1
        if not opened:
            i += 1
            continue
        depth, k = 0, j
        while k < len(lines):
            code = code_of(lines[k])
            depth += code.count("{") - code.count("}")
            if depth <= 0 and "}" in code:
                break
            k += 1
        name = re.split(r"\s*\(", line, 1)[0].split()[-1].lstrip("*&")
        if name in ("TEST", "TEST_F", "TEST_P", "PYBIND11_MODULE"):  # named by its arguments
            name += "(" + re.sub(r"\s+", "", line.split("(", 1)[1].split(")", 1)[0]) + ")"
        found.append((name, i + 1, k - i + 1))
        i = k + 1
    return found


def py_functions(path):
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    return [(n.name, n.lineno, n.end_lineno - n.lineno + 1) for n in ast.walk(tree)
            if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))]


def is_python_script(path):
    with open(path, "rb") as f:
        first = f.readline()
    return first.startswith(b"#!") and b"python" in first


def main():
    problems, checked, longest, found = [], 0, 0, 0
    for base, dirs, files in os.walk(ROOT):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("build"))
        for name in sorted(files):
            path = os.path.join(base, name)
            rel = os.path.relpath(path, ROOT)
            if name.endswith(CPP):
                functions = cpp_functions(path)
            elif name.endswith(".py") or (not os.path.splitext(name)[1] and is_python_script(path)):
                functions = py_functions(path)
            else:
                continue
            checked += 1
            found += len(functions)
            for fn, first, length in functions:
                longest = max(longest, length)
                if length > MAX_LINES:
                    problems.append("%s:%d: %s is %d lines, over %d: split it into functions "
                                    "that do one step each" % (rel, first, fn, length, MAX_LINES))
    if checked < 300:
        problems.append("only %d source files read: wrong root?" % checked)
    # The heads the C++ pattern finds (about 1,800 functions and 600 defs in
    # December 2026): far fewer means the pattern no longer matches them.
    if found < 1500:
        problems.append("only %d functions found in %d files: the function pattern is stale" % (
            found, checked))
    for p in problems:
        print(p, file=sys.stderr)
    print("function sizes: %d files, the longest function %d lines, %d problems" % (
        checked, longest, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
