"""The generic view of one metric against another (declare.Pairs): a panel
per value of a swept key, a point per policy with the y metric's interval;
the policies that read the `variant` key once per its value (by marker),
the others once per panel (their runs are the same under every value).
figure.py draws it."""

from . import style, tidy
from .common import number
from .declare import text
from .figure import Figure, Mark, Panel
from .view import add_refs


def pairs_figure(decl, sweep, data):
    """A declare.Pairs' one figure."""
    variant = decl.variant if decl.variant in sweep.keys else None
    values = []
    for r in sweep.rows:
        if variant and r[variant] not in values:
            values.append(r[variant])
    facets = sorted({number(r[decl.facet]) for r in sweep.rows} - {None}, key=decl.facet_order)
    panels = []
    for f in facets:
        panel = Panel(title=decl.facet_title(f), xlabel=decl.xlabel, ylabel=decl.ylabel,
                      group=decl.y, name=decl.y)
        add_refs(panel, decl.marks, data, decl.y)
        seen = set()
        for r in sweep.rows:
            if number(r[decl.facet]) != f:
                continue
            x = tidy.value_of(sweep, r, decl.x)[0]
            y, lo, hi, _ = tidy.value_of(sweep, r, decl.y)
            if x is None or y is None:
                continue
            told_apart = r["policy"] in decl.variant_policies
            if not told_apart and r["policy"] in seen:
                continue  # the same runs under every value of the variant key
            seen.add(r["policy"])
            v = values.index(r[variant]) if told_apart and values else 0
            panel.add(Mark("points", [x], [y], lo=[lo], hi=[hi], policy=r["policy"], variant=v))
        panels.append(panel)
    variants = [(decl.variant_label.format(d), "", style.MARKERS[i % len(style.MARKERS)])
                for i, d in enumerate(values)]
    return [Figure(decl.file, panels, title=text(decl.title, data),
                   caption=text(decl.caption, data),
                   ncols=min(decl.max_columns, len(panels)), variants=variants)]
