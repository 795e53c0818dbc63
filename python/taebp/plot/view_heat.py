"""The generic view of one metric over two swept keys (declare.Heat): a heat
map of one policy's cells, each its value and 95 % interval (or why it has
none), the cells of a region (the theory's prediction) outlined, and the
study's marks (declare.Ref; "diagonal" is y = x across the map). figure.py
draws it."""

from . import style, tidy
from .common import number
from .declare import resolve, text
from .figure import Figure, Mark, Panel
from .view import add_refs

NO_VALUE = "#d9d9d9"  # a cell without a value


def edges(v):
    """The cells' edges around the values v: halfway between neighbours."""
    if len(v) == 1:
        return [v[0] - 0.05, v[0] + 0.05]
    mids = [(a + b) / 2 for a, b in zip(v, v[1:])]
    return [v[0] - (mids[0] - v[0])] + mids + [v[-1] + (v[-1] - mids[-1])]


def outline(xs, ys, ex, ey, inside):
    """The edges between the cells `inside` ({(x, y): bool}) and the others
    (or the map's border): [(xs, ys)] segments."""
    out = []
    for i, x in enumerate(xs):
        for j, y in enumerate(ys):
            if not inside.get((x, y)):
                continue
            if i == 0 or not inside.get((xs[i - 1], y)):
                out.append(([ex[i], ex[i]], [ey[j], ey[j + 1]]))
            if i + 1 == len(xs) or not inside.get((xs[i + 1], y)):
                out.append(([ex[i + 1], ex[i + 1]], [ey[j], ey[j + 1]]))
            if j == 0 or not inside.get((x, ys[j - 1])):
                out.append(([ex[i], ex[i + 1]], [ey[j], ey[j]]))
            if j + 1 == len(ys) or not inside.get((x, ys[j + 1])):
                out.append(([ex[i], ex[i + 1]], [ey[j + 1], ey[j + 1]]))
    return out


def _short(v):
    text_ = "%.2f" % v
    return text_[1:] if text_.startswith("0.") else text_


def _cells(sweep, cell, xs, ys, metric):
    """The map's values (rows of y, None: no value) and each cell's text."""
    z = [[None] * len(xs) for _ in ys]
    texts = []
    for (x, y), r in cell.items():
        if x is None or y is None:
            continue
        v, lo, hi, _ = tidy.value_of(sweep, r, metric)
        ok, bad = sweep.runs(r)
        if v is None:
            texts.append((x, y, "failed\n%d/%d" % (bad, ok + bad) if bad else "n/a", None))
            continue
        z[ys.index(y)][xs.index(x)] = v
        interval = ("\n%s–%s" % (_short(lo), _short(hi))) if lo is not None else ""
        texts.append((x, y, "%.2f%s" % (v, interval), v))
    return z, texts


def heat_figure(decl, sweep, data):
    """A declare.Heat: one panel, the metric's title and the policy's label."""
    policy = resolve(decl.policy, data)
    kx, ky, metric = decl.x, decl.y, decl.metric
    rows = [r for r in sweep.rows if r["policy"] == policy]
    xs = sorted({number(r[kx]) for r in rows} - {None})
    ys = sorted({number(r[ky]) for r in rows} - {None})
    cell = {(number(r[kx]), number(r[ky])): r for r in rows}
    ex, ey = edges(xs), edges(ys)
    z, texts = _cells(sweep, cell, xs, ys, metric)
    vals = [v for row in z for v in row if v is not None]
    panel = Panel(title="%s, %s" % (style.metric_title(metric), style.policy_label(policy)),
                  xlabel=decl.x_title, ylabel=decl.y_title, name=metric)
    region = resolve(decl.region, data)
    panel.add(Mark("heat", edges_x=ex, edges_y=ey,
                   values=[[float("nan") if v is None else v for v in row] for row in z],
                   texts=texts, cmap=decl.cmap, bad=NO_VALUE, vmin=0, vmax=max([0.05] + vals),
                   colourbar="%s (%s)" % (metric, style.policy_label(policy)),
                   outline=outline(xs, ys, ex, ey, region or {}),
                   outline_label=decl.region_label))
    lo, hi = min(ex[0], ey[0]), max(ex[-1], ey[-1])
    for ref in decl.marks:
        if ref.kind == "diagonal":
            for _, _, _, opts in ref.marks(data, metric):
                panel.add(Mark("curve", [lo, hi], [lo, hi], **opts))
        else:
            add_refs(panel, [ref], data, metric)
    return [Figure(decl.file, [panel], ncols=decl.ncols, panel_height=decl.panel_height,
                   title=text(decl.title, data), caption=text(decl.caption, data))]
