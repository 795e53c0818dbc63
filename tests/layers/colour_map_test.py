#!/usr/bin/python3
"""One colour per policy, from the policy table (config/src/policies.cc ->
python/taebp/plot/tables.json -> taebp.plot.style): no other Python file of
the tree (the package, tools/, tests/, the manual's python blocks) spells a
policy's colour. Caught, on the syntax tree of each file:
  - a dict whose keys include a policy's name and whose values a colour,
  - a tuple or list holding a policy's name and a colour,
  - an `if` comparing with a policy's name whose branch sets a colour,
  - any string equal to a policy's colour in the table (a map keyed by
    something else, e.g. a design, drawn in a policy's colour).
The check first proves itself on planted second maps (each form above).
Usage: colour_map_test.py [SOURCE_DIR]"""
import ast
import glob
import json
import os
import re
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(__file__))))
TABLES = os.path.join(ROOT, "python", "taebp", "plot", "tables.json")
THE_ONE_PLACE = {os.path.join("python", "taebp", "plot", "style.py"),
                 os.path.join("tests", "layers", "colour_map_test.py")}

with open(TABLES, encoding="utf-8") as f:
    POLICIES = json.load(f)["policies"]
NAMES = {p["name"] for p in POLICIES}
TABLE_COLOURS = {p["colour"].lower() for p in POLICIES}
COLOUR = re.compile(r"^(#[0-9a-fA-F]{6}([0-9a-fA-F]{2})?|#[0-9a-fA-F]{3}|tab:[a-z]+|C[0-9]|"
                    r"xkcd:[a-z ]+|(dark|light)?(red|blue|green|orange|purple|cyan|magenta|"
                    r"grey|gray|brown|pink|olive|black|yellow))$")


def strings(node):
    return [n.value for n in ast.walk(node) if isinstance(n, ast.Constant) and
            isinstance(n.value, str)]


def is_colour(s):
    return bool(COLOUR.match(s.strip()))


def second_maps(source, name):
    """[(line, what)] of the ways `source` spells a policy's colour."""
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return []
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Dict):
            keys = [k.value for k in node.keys if isinstance(k, ast.Constant)]
            if NAMES & set(k for k in keys if isinstance(k, str)) and \
                    any(is_colour(s) for v in node.values for s in strings(v)):
                found.append((node.lineno, "a dict from policies to colours"))
        elif isinstance(node, (ast.Tuple, ast.List)):
            items = [e.value for e in node.elts if isinstance(e, ast.Constant) and
                     isinstance(e.value, str)]
            if NAMES & set(items) and any(is_colour(s) for s in items):
                found.append((node.lineno, "a policy paired with a colour"))
        elif isinstance(node, ast.If):
            test = set(strings(node.test))
            assigned = [n for b in node.body for n in ast.walk(b) if isinstance(n, ast.Assign)
                        and any("col" in ast.unparse(t).lower() for t in n.targets)]
            if NAMES & test and any(is_colour(s) for a in assigned for s in strings(a.value)):
                found.append((node.lineno, "a colour chosen by comparing with a policy"))
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and \
                node.value.lower() in TABLE_COLOURS:
            found.append((node.lineno, "the policy table's colour %s" % node.value))
    return sorted(set(found))


def sources():
    """(relative path, text) of every Python source and the manual's python blocks."""
    files = glob.glob(os.path.join(ROOT, "python", "**", "*.py"), recursive=True) + \
        glob.glob(os.path.join(ROOT, "tests", "**", "*.py"), recursive=True)
    for tool in glob.glob(os.path.join(ROOT, "tools", "*")):
        if os.path.isfile(tool):
            with open(tool, encoding="utf-8", errors="replace") as f:
                if f.readline().startswith("#!/usr/bin/python3"):
                    files.append(tool)
    for path in sorted(set(files)):
        rel = os.path.relpath(path, ROOT)
        if rel in THE_ONE_PLACE:
            continue
        with open(path, encoding="utf-8") as f:
            yield rel, f.read()
    for page in [os.path.join(ROOT, "README.md")] + glob.glob(os.path.join(ROOT, "docs", "**",
                                                                           "*.md"), recursive=True):
        if os.path.islink(page):
            continue
        with open(page, encoding="utf-8") as f:
            text = f.read()
        for i, block in enumerate(re.findall(r"```python\n(.*?)```", text, re.S)):
            yield "%s (python block %d)" % (os.path.relpath(page, ROOT), i + 1), block


def main():
    failures = []
    planted = {
        "dict": 'COLORS = {"always_nudge": "#d62728", "ta_ebp": "#1f77b4"}\n',
        "pairs": 'for p, c in [("ta_ebp", "tab:blue"), ("no_trust", "tab:red")]: pass\n',
        "if": 'if policy == "no_trust":\n    colour = "red"\n',
        "by design": 'colours = {"aware": "%s", "paper": "#123456"}\n' % POLICIES[3]["colour"],
    }
    for what, snippet in planted.items():
        if not second_maps(snippet, what):
            failures.append("the check misses a planted second colour map (%s)" % what)
    if second_maps('colour = style.policy_colour("ta_ebp")\nref = "#2a9d8f"\n', "fine"):
        failures.append("the check flags a colour taken from the table")
    checked = 0
    for rel, text in sources():
        checked += 1
        for line, what in second_maps(text, rel):
            failures.append("%s:%d: %s (a policy's colour belongs to the policy table: "
                            "taebp.plot.style.policy_colour)" % (rel, line, what))
    for f in failures:
        print("FAIL " + f)
    print("%d sources checked, %d finding(s)" % (checked, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
