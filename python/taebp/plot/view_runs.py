"""The generic view of runs' time series: a declare.Series over the long rows
its data function gives (run_data.py). Rows of one panel, role, policy,
run and variant are one series, in the order the rows come; each series is
one mark, drawn as its role says (declare.Role): the policy's colour and
label from the policy table, a variant's line style and marker, the
policies side by side (dodge). figure.py draws the marks."""

from . import style
from .declare import resolve, text
from .figure import Figure, Mark, Panel


def _suffix(name):
    return "" if not name else "_" + name.replace(" ", "")


def _dodge(i, n, width):
    return (i - (n - 1) / 2) * width / max(1, n)


def series_figure(decl, runs, name, idx):
    """The Figure of one group of runs (None: the data function has none)."""
    got = decl.data(runs, name, idx)
    if got is None:
        return None
    data = {"ctx": runs.context(idx) + (" (%s)" % runs.group_title(name) if name else ""),
            "suffix": _suffix(name)}
    data.update(got)
    panels = {a.key: Panel(title=text(a.title, data), xlabel=a.xlabel,
                           ylabel=a.ylabel or style.axis_label(a.metric), group=a.group,
                           zero=a.zero, xscale=a.xscale, yscale=a.yscale, ylim=a.ylim,
                           name=a.name) for a in decl.panels}
    series = {}
    for r in data["rows"]:
        key = (r["panel"], r["role"], r.get("policy"), r.get("series"), r.get("variant"))
        series.setdefault(key, []).append(r)
    domain = data.get("policies") or []
    for (panel, role, policy, _, variant), rows in series.items():
        panels[panel].add(_mark(decl.roles[role], rows, policy, variant, domain))
    variants = []
    values = resolve(decl.variants, data) or []
    if len(values) > 1:
        variants = [(decl.variant_labels.get(d, d), style.LINESTYLES[i], style.MARKERS[i])
                    for i, d in enumerate(values)]
    extra = decl.legend_extra if decl.extra_when is None or resolve(decl.extra_when, data) \
        else []
    return Figure(text(decl.file, data), [panels[a.key] for a in decl.panels],
                  title=text(decl.title, data), caption=text(decl.caption, data),
                  ncols=decl.ncols, panel_height=decl.panel_height, variants=variants,
                  legend_extra=extra)


def _mark(role, rows, policy, variant, domain):
    """One series' mark as its role draws it."""
    kw = dict(role.look)
    if role.policy is True:
        kw["policy"] = policy
    elif role.policy == "colour":
        kw["colour"] = style.policy_colour(policy)
    if role.kind == "hline":  # levels: the rows' y
        if rows[0].get("note") is not None:
            kw["note"] = rows[0]["note"]
        return Mark("hline", [r["y"] for r in rows], variant=variant or 0, **kw)
    xs = [r["x"] for r in rows]
    if role.dodge and policy in domain:
        d = _dodge(domain.index(policy), len(domain), role.dodge)
        xs = [x + d for x in xs]
    if any("lo" in r for r in rows):
        kw["lo"], kw["hi"] = [r.get("lo") for r in rows], [r.get("hi") for r in rows]
    return Mark(role.kind, xs, [r["y"] for r in rows], variant=variant or 0, **kw)
