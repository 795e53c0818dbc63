"""The one look of every figure.

Each policy's colour and label come from the policy table
(config/src/policies.cc, `taebp policies --print json`), each metric's title
and unit from the metric table (report/src/metrics.cc, `taebp metrics --print
json`). Both are read from tables.json beside this file, which
tools/refresh-docs writes from the program (ctest docs.generated_pages fails
when it drifts from the tables), so that a figure drawn anywhere (tools/plot
outside the repository, the module installed, no binary) has the same colours
and names. No other file of the plots spells a policy's colour or label
(tests/layers/colour_map_test.py).

Size: every figure is drawn at its printed width (PRINT_WIDTH, a journal
page's two columns) with text of at least MIN_FONT points, so that nothing
shrinks when it is placed in a paper.
"""

import json
import os
import re

PRINT_WIDTH = 7.0   # in: a two-column journal page's text width (figures are drawn at it)
MIN_FONT = 8.0      # pt: the smallest text at the printed width
FONT = 8.5          # pt: ticks, legends, notes
TITLE_FONT = 9.5    # pt: panel titles and the figure's title
DPI = 200           # PNG pixels per inch (1400 px across)
PANEL_HEIGHT = 2.3  # in: one row of panels
MAX_COLUMNS = 3     # panels side by side at the printed width

# A policy the table does not know (an older result folder): drawn in grey.
UNKNOWN_COLOUR = "#8c564b"
# Line styles and markers that tell apart points sharing an x (other swept
# keys), in order.
LINESTYLES = ["-", "--", ":", "-."]
MARKERS = ["o", "s", "^", "D", "v", "P"]

_TABLES = {}


def tables():
    """{"policies": [...], "metrics": [...]}: the program's tables (tables.json)."""
    if not _TABLES:
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "tables.json")
        with open(path, encoding="utf-8") as f:
            _TABLES.update(json.load(f))
    return _TABLES


def _policy(name):
    for p in tables()["policies"]:
        if p["name"] == name:
            return p
    return None


def policy_colour(name):
    p = _policy(name)
    return p["colour"] if p else UNKNOWN_COLOUR


def policy_label(name):
    p = _policy(name)
    return p["label"] if p else name


def style(policy):
    """(colour, label) of a policy."""
    return policy_colour(policy), policy_label(policy)


def plays_game(name):
    """Whether a policy plays the AV-HV game (False: SUMO's own logic, no rate)."""
    p = _policy(name)
    return bool(p and p["plays_game"])


def policy_order():
    return [p["name"] for p in tables()["policies"]]


# What the figures derive from two of the table's metrics (tidy.value_of
# computes them): not results of a run, so not in the metric table.
DERIVED = {
    "served_share": {"name": "served_share", "type": "real", "unit": "", "pool": "mean",
                     "levels": ["run"], "description": "served flow over the offered flow "
                     "(served_flow / offered_flow; 1: all the demand offered was served)"},
}


def metric(name):
    """The metric table's row of `name` (name, type, unit, pool, description,
    ...), a derived metric's (DERIVED), or None."""
    for m in tables()["metrics"]:
        if m["name"] == name:
            return m
    return DERIVED.get(name)


def metric_title(name):
    """A panel's title: the metric's description without its parenthetical
    remarks, e.g. "collisions per encounter"."""
    m = metric(name)
    if m is None:
        return name
    text = re.sub(r"\s*\([^()]*\)", "", m["description"]).strip()
    text = re.split(r";\s", text)[0]
    return text[:1].upper() + text[1:]


def metric_unit(name):
    m = metric(name)
    return (m or {}).get("unit", "")


def is_rate(name):
    m = metric(name)
    return bool(m) and m.get("pool") == "rate"


def pooled_by_mean(name):
    """A mean over the seeds (aggregate.csv: NAME, NAME_sd)."""
    m = metric(name)
    return bool(m) and m.get("pool") == "mean"


def axis_label(name):
    """A y axis: the metric's name and unit, e.g. "served_flow (veh/h)"."""
    unit = metric_unit(name)
    return "%s (%s)" % (name, unit) if unit else name


def setup(matplotlib):
    """Fonts at the printed size for every figure drawn after."""
    matplotlib.rcParams.update({
        "font.size": FONT, "axes.titlesize": TITLE_FONT, "axes.labelsize": FONT,
        "xtick.labelsize": FONT, "ytick.labelsize": FONT, "legend.fontsize": FONT,
        "figure.titlesize": TITLE_FONT, "savefig.dpi": DPI, "figure.dpi": 100,
        "axes.grid": True, "grid.alpha": 0.3,
    })
