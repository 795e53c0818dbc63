"""The vocabulary a preset is declared in (presets.py), and the one generic
path that draws a declaration.

A preset is data: which swept keys it covers and when it applies, a data
function (the study's own numbers: a dense theory curve, theta*, the cells
the theory predicts collisions in, a run's time bins), and its figures, each
a declaration of what to draw:

    Lines   metrics against a swept key (view.SweepView): x, y, by, select,
            variants, theory, the study's marks (Ref), the title
    Heat    one metric over two swept keys, a cell each (view_heat)
    Pairs   one metric against another, a point per policy (view_pairs)
    Series  the time series of runs (view_runs): panels (Axes) and how
            each role of the data's long rows is drawn (Role)
    Map     a network run's junctions on its lanes (figure_map)

Any field may be `From("name")`: the entry `name` of what the data function
returned (a swept key, a select function, a number). Titles, captions and
file names are templates filled from the same entries ("Trust sweep{ctx}");
`ctx` is, unless the data function says otherwise, the sweep's context
after ": ". Nothing here draws: the views turn a declaration into panels of
marks and figure.py draws them all the same way."""

from .common import PlotError, warn


class From:
    """A field's value taken from the data function's result."""

    def __init__(self, key):
        self.key = key

    def __repr__(self):
        return "From(%r)" % self.key


def resolve(value, data):
    """A field's value: From(key) looked up in `data`, a list resolved item by
    item, anything else as it is."""
    if isinstance(value, From):
        return data.get(value.key)
    if isinstance(value, list):
        return [resolve(v, data) for v in value]
    return value


def text(template, data):
    """A title, caption or file name: a template filled from `data` (or a
    function called with it); None stays None."""
    if template is None:
        return None
    if callable(template):
        return template(data)
    return template.format(**data) if ("{" in template and "}" in template) else template


class Ref:
    """A mark a study adds to every panel (or to those of `metrics`): kind
    "vline" / "hline" (lines at the values `at`), "shade" (an x span),
    "special" (one point (x, y)), "diagonal" (y = x across a heat map),
    "curve" ((xs, ys)).
    `at`: a value, From(key), or a dict {metric: value}; None draws nothing.
    `legend` and `note` are text or a function of the value; the rest is
    the mark's look (colour, ls, lw, ...)."""

    def __init__(self, kind, at=None, metrics=None, legend=None, note=None, **look):
        self.kind, self.at, self.metrics = kind, at, metrics
        self.legend, self.note, self.look = legend, note, look

    def marks(self, data, metric):
        """[(kind, xs, ys, options)] of this reference in a panel of `metric`."""
        if self.metrics is not None and metric not in self.metrics:
            return []
        v = resolve(self.at, data)
        if isinstance(v, dict) and "xs" not in v:
            v = v.get(metric)
        if v is None and self.kind != "diagonal":
            return []
        opts = dict(self.look)
        for field in ("legend", "note"):
            f = getattr(self, field)
            if f is not None:
                opts[field] = f(v) if callable(f) else f
        if isinstance(v, dict):
            opts.update({k: w for k, w in v.items() if k not in ("xs", "ys")})
            return [(self.kind, list(v["xs"]), list(v.get("ys", [])), opts)]
        if self.kind == "special":
            return [(self.kind, [v[0]], [v[1]], opts)]
        if self.kind == "curve":
            return [(self.kind, list(v[0]), list(v[1]), opts)]
        xs = list(v) if isinstance(v, (list, tuple)) else ([] if v is None else [v])
        return [(self.kind, xs, [], opts)]


class Variants:
    """Points sharing an x told apart by line style: `of(row)` the value
    (From a data function's entry), `labels` a dict or a template per value,
    `order` the values' sort key (default: as they sort)."""

    def __init__(self, of, labels="{}", order=None):
        self.of, self.labels, self.order = of, labels, order


class Preset:
    """A sweep preset: the swept keys it covers, applies(sweep, keys), the
    data function data(sweep, theory) -> {name: value} and its figures."""

    def __init__(self, keys, applies, figures, data=None):
        self.keys, self.applies = set(keys), applies
        self.figures, self.data = list(figures), data


class RunPreset:
    """A run preset: applies(runs), its figures (Series); `groups`: one
    figure per group of runs that may be pooled (a sweep's point), else
    one of them all."""

    def __init__(self, applies, figures, groups=True):
        self.applies, self.figures, self.groups = applies, list(figures), groups


class Declared:
    """What every figure declaration has: its file, title, caption, columns,
    and when it is drawn (From a data entry, or always)."""

    def __init__(self, file, title=None, caption="", ncols=None, when=None, **rest):
        self.file, self.title, self.caption = file, title, caption
        self.ncols, self.when = ncols, when
        self.rest = rest

    def drawn(self, data):
        return self.when is None or bool(resolve(self.when, data))


class Lines(Declared):
    """Metrics against a swept key (view.SweepView's arguments: x, y, by,
    select, x_of, x_title, theory, zero, metric_titles, facet_title,
    pair_labels; `variants` a Variants; `marks` Refs; `zoom` a Zoom panel
    added; `xlim` every panel's; `split`: False keeps every panel in one file)."""

    def __init__(self, file, x, y, marks=(), variants=None, zoom=None, xlim=None, split=True,
                 **rest):
        super().__init__(file, **rest)
        self.x, self.y, self.marks, self.variants = x, y, list(marks), variants
        self.zoom, self.xlim, self.split = zoom, xlim, split


class Zoom:
    """One more panel of a Lines figure: `y` over the rows `select` keeps,
    one variant (`label`), titled `title`, its own y range `ylim`; drawn
    when `when` (From) holds."""

    def __init__(self, y, select, title, label, ylim, group="zoom", when=None):
        self.y, self.select, self.title, self.label = y, select, title, label
        self.ylim, self.group, self.when = ylim, group, when


class Heat(Declared):
    """`metric` of one policy over two swept keys x and y: a cell each with
    its rate and interval, the cells of `region` outlined, `marks` Refs."""

    def __init__(self, file, x, y, metric, policy, cmap, x_title, y_title, region=None,
                 region_label=None, marks=(), panel_height=None, **rest):
        super().__init__(file, **rest)
        self.x, self.y, self.metric, self.policy, self.cmap = x, y, metric, policy, cmap
        self.x_title, self.y_title = x_title, y_title
        self.region, self.region_label = region, region_label
        self.marks, self.panel_height = list(marks), panel_height


class Pairs(Declared):
    """`y` against `x` (two metrics), a point per policy and panel (one
    panel per value of `facet`, in `facet_order`); the policies of
    `variant_policies` once per value of `variant` (by marker), the others
    once per panel; `marks` Refs."""

    def __init__(self, file, x, y, facet, facet_title, xlabel, ylabel, variant=None,
                 variant_policies=(), variant_label="{}", facet_order=None, marks=(),
                 max_columns=4, **rest):
        super().__init__(file, **rest)
        self.x, self.y, self.facet, self.facet_title = x, y, facet, facet_title
        self.xlabel, self.ylabel = xlabel, ylabel
        self.variant, self.variant_policies = variant, set(variant_policies)
        self.variant_label, self.facet_order = variant_label, facet_order
        self.marks, self.max_columns = list(marks), max_columns


class Axes:
    """A panel of a Series figure: its key (the rows' `panel`), title
    (a template), x label, y label (default: the metric table's name and
    unit of `metric`), scales, limits, y group, whether y starts at 0."""

    def __init__(self, key, title, xlabel, ylabel=None, metric=None, name=None, xscale="linear",
                 yscale="linear", ylim=None, group=None, zero=True):
        self.key, self.title, self.xlabel = key, title, xlabel
        self.ylabel, self.metric, self.name = ylabel, metric, name or metric or key
        self.xscale, self.yscale, self.ylim = xscale, yscale, ylim
        self.group, self.zero = group, zero


class Role:
    """How the rows of one role are drawn: a mark `kind` ("points",
    "curve", "theory", "step", "hline"), `policy`: True (the policy's
    colour and legend entry), "colour" (its colour only) or False;
    `dodge`: the policies side by side within this width; the rest is the
    mark's look (ls, lw, alpha, ms, legend, legend_colour, simulated)."""

    def __init__(self, kind, policy=True, dodge=None, **look):
        self.kind, self.policy, self.dodge, self.look = kind, policy, dodge, look


class Series(Declared):
    """The time series of runs: `data(runs, name, idx)` -> {"rows": [...],
    name: value, ...} or None (no figure for this group); each row a dict
    with panel, role, x, y and optionally policy, series (a run), variant,
    lo, hi, note. `panels`: Axes; `roles`: {role: Role}; `variants`:
    From(the values told apart) with `variant_labels`; `legend_extra`
    [(look, text)], shown when `extra_when` (From) holds."""

    def __init__(self, file, data, panels, roles, variants=None, variant_labels=None,
                 legend_extra=(), extra_when=None, panel_height=None, **rest):
        super().__init__(file, **rest)
        self.data, self.panels, self.roles = data, list(panels), dict(roles)
        self.variants, self.variant_labels = variants, variant_labels or {}
        self.legend_extra, self.extra_when = list(legend_extra), extra_when
        self.panel_height = panel_height


class Map(Declared):
    """A network run's map (figure_map.py): `data(run_dir)` -> netmap.map_data's
    dict or None; `panel_title(label, encounters, junctions)`; `cmap` and
    `colourbar` (the label): (against sumo_native, without it)."""

    def __init__(self, file, data, panel_title, cmap, colourbar, **rest):
        super().__init__(file, **rest)
        self.data, self.panel_title = data, panel_title
        self.cmap, self.colourbar = cmap, colourbar


# ------------------------------------------------------------------ drawing
def sweep_data(preset, sweep, theory):
    """The data a sweep preset's declarations read: ctx and its data function's."""
    ctx = sweep.context()
    data = {"ctx": (": " + ctx) if ctx else "", "sweep": sweep}
    if preset.data is not None:
        data.update(preset.data(sweep, theory))
    return data


def draw(preset, plt, sweep, theory, out):
    """A sweep preset's figures, drawn the one way (the views, figure.py)."""
    from . import view, view_heat, view_pairs
    data = sweep_data(preset, sweep, theory)
    makers = {Lines: view.lines_figure, Heat: view_heat.heat_figure,
              Pairs: view_pairs.pairs_figure}
    figures = [fig for f in preset.figures if f.drawn(data)
               for fig in makers[type(f)](f, sweep, data)]
    return [fig.save(plt, out) for fig in figures]


def draw_runs(preset, plt, runs, out):
    """A run preset's figures: one per group of runs (a group without a
    simulated value skipped with a warning) or one of all the runs."""
    from . import view_runs
    paths = []
    groups = runs.groups() if preset.groups else [("", list(range(len(runs.dirs))))]
    for name, idx in groups:
        for decl in preset.figures:
            fig = view_runs.series_figure(decl, runs, name, idx)
            if fig is None:
                continue
            if not preset.groups:
                paths.append(fig.save(plt, out))
                continue
            try:
                paths.append(fig.save(plt, out))
            except PlotError as e:
                warn("%s (skipped)" % e)
    return paths


def draw_map(decl, plt, run_dir, out):
    """A declare.Map of one run, or None when the run has no map."""
    from . import figure_map
    data = decl.data(run_dir)
    return figure_map.map_figure(decl, plt, data, out) if data is not None else None
