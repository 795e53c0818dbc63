#!/usr/bin/python3
"""Plots as views of tidy data (issue 46): every shipped figure is a preset
declared as data, and one generic path draws them all. Checked on the
package python/taebp/plot/:
  - only figure.py (and its map layout, figure_map.py) calls matplotlib's
    drawing methods (plot, errorbar, pcolormesh, axhline, annotate, legend,
    subplots, ...) and imports matplotlib (common.py too: it saves);
  - only the views (view*.py) and figure.py make panels and marks (Mark,
    Panel, Figure, SweepView);
  - presets.py and the data modules (sweep_data.py, run_data.py, netmap.py)
    import no view and no figure; presets.py's functions are small (at most
    SMALL_LINES lines: the registry's API), its entries data;
  - loaded, every PRESETS entry is a declare.Preset of Lines, Heat and Pairs,
    every RUN_PRESETS entry a declare.RunPreset of Series, MAP a declare.Map,
    each data function a function of the data modules.
The check first proves itself on planted violations (a drawing call in a
data module, a mark made in presets.py, a long function there, a preset
that is a function). Usage: plot_declared_test.py [SOURCE_DIR]"""
import ast
import glob
import os
import sys
import types

ROOT = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(__file__))))
PACKAGE = os.path.join(ROOT, "python", "taebp", "plot")
DRAWS = {"figure.py", "figure_map.py"}
VIEWS = {"figure.py", "view.py", "view_heat.py", "view_pairs.py", "view_runs.py"}
DATA = {"presets.py", "sweep_data.py", "run_data.py", "netmap.py"}
SMALL_LINES = 6
DRAWING = {"plot", "errorbar", "scatter", "step", "bar", "barh", "hist", "fill_between",
           "fill_betweenx", "axhline", "axvline", "axhspan", "axvspan", "pcolormesh", "pcolor",
           "imshow", "contour", "contourf", "quiver", "arrow", "annotate", "text", "legend",
           "colorbar", "subplots", "add_subplot", "add_axes", "suptitle", "set_title",
           "set_xlabel", "set_ylabel", "set_xlim", "set_ylim", "set_xscale", "set_yscale",
           "add_patch", "add_collection", "add_artist"}
MAKERS = {"Mark", "Panel", "Figure", "SweepView"}
VIEWS_MODULES = {os.path.splitext(v)[0] for v in VIEWS}


def findings(name, source):
    """[(line, what)] of what file `name` (its base name) may not do."""
    tree = ast.parse(source)
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            f = node.func
            called = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", None)
            if isinstance(f, ast.Attribute) and called in DRAWING and name not in DRAWS:
                out.append((node.lineno, "calls matplotlib's %s (only figure.py draws)" % called))
            if called in MAKERS and name not in VIEWS:
                out.append((node.lineno, "makes a %s (only the views and figure.py do)" % called))
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            mods = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module or ""] + ["%s.%s" % (node.module or "", a.name) for a in node.names]
            if any(m.startswith("matplotlib") for m in mods) and \
                    name not in DRAWS | {"common.py"}:
                out.append((node.lineno, "imports matplotlib (only figure.py draws)"))
            if name in DATA and isinstance(node, ast.ImportFrom) and \
                    (node.module or "").split(".")[-1] in VIEWS_MODULES:
                out.append((node.lineno, "imports %s (a preset declares; the views draw)"
                            % node.module))
        elif isinstance(node, ast.FunctionDef) and name == "presets.py":
            length = node.end_lineno - node.lineno + 1
            if length > SMALL_LINES:
                out.append((node.lineno, "%s: %d lines (a preset's functions are small: at most "
                            "%d; study math belongs in sweep_data.py or run_data.py)"
                            % (node.name, length, SMALL_LINES)))
    return sorted(set(out))



def load_presets():
    """python/taebp/plot's presets module, loaded by path as tools/plot does
    (no compiled module needed)."""
    if "taebp" not in sys.modules:
        pkg = types.ModuleType("taebp")
        pkg.__path__ = [os.path.join(ROOT, "python", "taebp")]
        sys.modules["taebp"] = pkg
    from taebp.plot import declare, netmap, presets, run_data, sweep_data
    return declare, presets, (run_data, sweep_data, netmap)


def registry_problems(declare, presets, data_modules):
    """What in PRESETS / RUN_PRESETS is not a declaration."""
    out = []
    kinds = {"PRESETS": (declare.Preset, (declare.Lines, declare.Heat, declare.Pairs)),
             "RUN_PRESETS": (declare.RunPreset, (declare.Series,))}
    data_functions = {f for m in data_modules for f in vars(m).values() if callable(f)}
    for table, (cls, figure_classes) in kinds.items():
        for name, p in getattr(presets, table).items():
            if not isinstance(p, cls):
                out.append("%s[%r] is a %s, not a declare.%s" % (table, name, type(p).__name__,
                                                                 cls.__name__))
                continue
            data = [p.data] if table == "PRESETS" else [f.data for f in p.figures]
            for f in p.figures:
                if not isinstance(f, figure_classes):
                    out.append("%s[%r]: a figure %s, not one of %s" % (
                        table, name, type(f).__name__, [c.__name__ for c in figure_classes]))
            for d in data:
                if d is not None and d not in data_functions:
                    out.append("%s[%r]: data function %r not in sweep_data.py / run_data.py"
                               % (table, name, d))
    the_map = getattr(presets, "MAP", None)
    if not isinstance(the_map, declare.Map) or the_map.data not in data_functions:
        out.append("MAP is not a declare.Map over netmap.py's data (%r)" % (the_map,))
    return out


def main():
    failures = []
    planted = {
        "sweep_data.py": "def f(ax):\n    ax.axvline(0.3)\n",
        "run_data.py": "from .figure import Mark\nrows = [Mark('curve', [1], [2])]\n",
        "presets.py": "def study(plt):\n" + "    x = 1\n" * SMALL_LINES + "    return x\n",
        "view_runs.py": "def f(ax):\n    ax.errorbar([1], [2])\n",
        "common.py": "import matplotlib.pyplot as plt\nplt.subplots(1, 1)\n",
        "netmap.py": "import matplotlib.colors as mcolors\n",
    }
    for name, snippet in planted.items():
        if not findings(name, snippet):
            failures.append("the check misses a planted violation in %s" % name)
    if findings("figure.py", "def f(ax):\n    ax.plot([1], [2])\n"):
        failures.append("the check flags figure.py's own drawing")
    declare, presets, data_modules = load_presets()
    fake = types.SimpleNamespace(PRESETS={"bad": (set(), None, print)}, RUN_PRESETS={},
                                 MAP=presets.MAP)
    if not registry_problems(declare, fake, data_modules):
        failures.append("the check misses a preset that is a function, not a declaration")
    checked = 0
    for path in sorted(glob.glob(os.path.join(PACKAGE, "*.py"))):
        checked += 1
        with open(path, encoding="utf-8") as f:
            for line, what in findings(os.path.basename(path), f.read()):
                failures.append("%s:%d: %s" % (os.path.relpath(path, ROOT), line, what))
    failures += registry_problems(declare, presets, data_modules)
    for f in failures:
        print("FAIL " + f)
    print("plots declared: %d files, %d presets, %d run presets and the map; %d problem(s)"
          % (checked, len(presets.PRESETS), len(presets.RUN_PRESETS), len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
