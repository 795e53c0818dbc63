"""The generic view of a sweep: any swept key against any metrics, from the
tidy table (SweepView), and the standard panels tools/plot draws against
every swept key no preset covers (default_views). The figures are drawn as
figure.py draws every figure; Mark, Panel, Figure and wrap_to are importable
from here too."""

import os

from . import style, tidy
from .common import SIMULATED, PlotError, save  # noqa: F401 (as before the split)
from .declare import resolve, text
from .figure import FAILED_MARK, STALL_RING, Figure, Mark, Panel, wrap_to  # noqa: F401 (the API)


# ------------------------------------------------------------------ sweeps
class SweepView:
    """Any sweep's metrics against a swept key, from the tidy table: one
    panel per metric (and per value of `by`: one column each), one line per
    policy in its colour, the other swept keys that vary at one x as line
    styles and markers (so points sharing an x are told apart), a rate's
    interval from aggregate.csv (METRIC_lo, METRIC_hi), a mean's t interval
    with 5 seeds or more and each seed's value below that, theory as a bar
    at the point (or the preset's curves), stalled runs ringed and failed
    runs marked. Panels of one metric share their y range.

    x: a swept key, or a derived one (`x_of(row)` -> number, `x_title`).
    select(row): the aggregate rows drawn. styles: the keys told apart by
    line style (default: every other swept key that varies at one x).
    theory: "bar", None, or f(metric, policy, facet, variant) -> (xs, ys) curves.
    marks: the preset's own marks (declare.Ref: theta*, reference lines),
    their values looked up in `data` (what the preset's data function gave)."""

    def __init__(self, sweep, x, ys, by=None, name=None, select=None, x_of=None, x_title=None,
                 styles=None, variant_of=None, variant_labels=None, theory="bar", marks=(),
                 title=None, caption="", metric_titles=None, zero=None, facet_title=None,
                 ncols=None, pair_labels=None, connect=None, data=None):
        self.sweep = tidy.load(sweep)
        # Simulated points joined by a line, unless theory draws the lines.
        self.connect = (not callable(theory)) if connect is None else connect
        self.pair_labels = pair_labels
        s = self.sweep
        self.rows = [r for r in s.rows if select is None or select(r)]
        if x_of is None:
            if x not in s.keys:
                raise cannot(s, "--x %s is not a swept key of this sweep" % x)
            self.xkey = tidy.Key(x, [r.get(x) for r in self.rows])
            self.x_of = lambda r: self.xkey.position(r.get(x))
        else:
            self.xkey = None
            self.x_of = x_of
        self.x, self.x_title = x, x_title or x
        known = tidy.metric_names(s)
        bad = [m for y in ys for m in _metrics_of(y) if m not in known]
        if bad:
            raise cannot(s, "--y %s: not a metric of this sweep's aggregate.csv" % ", ".join(bad))
        self.ys = [y for y in ys if self._has(y)]
        if not self.ys:
            raise cannot(s, "no plot for the swept keys %s: none of the metrics asked for has "
                         "a simulated value" % ", ".join(s.keys or ["(none)"]))
        if by is not None and (by not in s.keys or by == x):
            raise cannot(s, "--by %s is not another swept key" % by)
        self.by = by
        self.facets = [None]
        if by:
            self.bykey = tidy.Key(by, [r.get(by) for r in self.rows])
            self.facets = list(self.bykey.cells)
        if variant_of is None:
            self.styles = styles if styles is not None else self._varying()
            combos = []
            for r in self.rows:
                c = tuple(r.get(k) for k in self.styles)
                if c not in combos:
                    combos.append(c)
            keys = {k: tidy.Key(k, [r.get(k) for r in self.rows]) for k in self.styles}
            combos.sort(key=lambda c: tuple(keys[k].cells.index(v) for k, v in zip(self.styles, c)))
            if len(combos) > len(style.LINESTYLES):
                raise cannot(s, "the swept keys %s give %d combinations at one x (at most %d line "
                             "styles): choose --x and --by" % (", ".join(self.styles), len(combos),
                                                               len(style.LINESTYLES)))
            self.variant_of = lambda r: combos.index(tuple(r.get(k) for k in self.styles))
            self.variant_labels = [", ".join("%s = %s" % (k, keys[k].label(v))
                                             for k, v in zip(self.styles, c)) for c in combos]
        else:
            self.styles = []
            self.variant_of, self.variant_labels = variant_of, list(variant_labels or [""])
        self.name = name or "sweep_%s.png" % x
        self.theory, self.marks, self.data = theory, list(marks), data or {}
        self.title = title
        self.caption = caption
        self.metric_titles = metric_titles or {}
        self.zero = zero or {}
        self.facet_title = facet_title
        self.ncols = ncols

    def _has(self, item):
        return any(tidy.value_of(self.sweep, r, m)[0] is not None
                   for m in _metrics_of(item) for r in self.rows)

    def _varying(self):
        """The swept keys besides x and by that take more than one value among
        the rows sharing an x (a key zipped with x moves with it: no style)."""
        out = []
        for k in self.sweep.keys:
            if k in (self.x, self.by):
                continue
            at_x = {}
            for r in self.rows:
                at_x.setdefault((self.x_of(r), r.get(self.by) if self.by else None),
                                set()).add(r.get(k))
            if any(len(v) > 1 for v in at_x.values()):
                out.append(k)
        return out

    def _dodge(self, slots):
        """x offset of a series' slot: the policies (and their variants) side by
        side within half the smallest x spacing, so that equal values stay visible."""
        xs = sorted({self.x_of(r) for r in self.rows if self.x_of(r) is not None})
        gaps = [b - a for a, b in zip(xs, xs[1:]) if b > a]
        spacing = min(gaps) if gaps else 1.0
        n = max(1, slots)
        width = spacing * 0.2
        return lambda slot: (slot - (n - 1) / 2) * width / n if n > 1 else 0.0

    def figures(self):
        """The Figures: one, or (more than style.MAX_COLUMNS values of `by`)
        one per metric, its facets in rows of MAX_COLUMNS."""
        if len(self.facets) <= style.MAX_COLUMNS:
            return [self.figure(self.name, self.panels(),
                                len(self.facets) if self.by else None)]
        base, ext = os.path.splitext(self.name)
        return [self.figure("%s.%s%s" % (base, "_".join(_metrics_of(m)), ext),
                             [self._panel(m, f) for f in self.facets], style.MAX_COLUMNS)
                for m in self.ys]

    def _x_text(self, row):
        if self.xkey is not None:
            return self.xkey.label(row.get(self.x))
        x = self.x_of(row)
        return "?" if x is None else "%g" % x

    def panels(self):
        """Every panel: the metrics in rows, the facets in columns."""
        return [self._panel(m, f) for m in self.ys for f in self.facets]

    def figure(self, name, panels, ncols):
        s = self.sweep
        title = self.title if self.title is not None else "Against %s%s" % (
            self.x_title, (": " + s.context()) if s.context() else "")
        variants = []
        pairs = [y for y in self.ys if isinstance(y, tuple)]
        if pairs:  # one panel, several metrics: a line style each
            labels = self.pair_labels or [" / ".join(style.metric_title(m) for m in col)
                                          for col in zip(*pairs)]
            variants = [(lab, style.LINESTYLES[i], style.MARKERS[i]) for i, lab in enumerate(labels)]
        elif len(self.variant_labels) > 1:
            variants = [(lab, style.LINESTYLES[i % len(style.LINESTYLES)],
                         style.MARKERS[i % len(style.MARKERS)])
                        for i, lab in enumerate(self.variant_labels)]
        extra = []
        caption = self.caption
        if self.by:  # the rows' metrics, as the metric table describes them
            def described(y):
                ms = _metrics_of(y)
                if len(ms) > 1:
                    stem = os.path.commonprefix(ms)
                    name = "%s{%s}" % (stem, ", ".join(m[len(stem):] for m in ms))
                    return "%s: %s" % (name, "; ".join(
                        style.metric(m)["description"] for m in ms if style.metric(m)))
                m = style.metric(ms[0])
                return "%s: %s" % (ms[0], m["description"] if m else ms[0])
            rows = "; ".join(described(y) for y in self.ys)
            caption = "Rows: %s.%s" % (rows, (" " + caption) if caption else "")
        failed = [(r["policy"], r, sum(s.runs(r))) for r in self.rows if s.runs(r)[1]]
        if failed:
            shown = ["%s at %s = %s (%d/%d)" % (style.policy_label(policy), self.x_title,
                                                 self._x_text(r), s.runs(r)[1], n)
                     for policy, r, n in failed[:6]]
            caption = ((caption + " ") if caption else "") + "Failed runs (✕): " + \
                "; ".join(shown) + ("; ..." if len(failed) > 6 else "") + "."
        flat = [m for y in self.ys for m in _metrics_of(y)]
        if any(style.is_rate(m) for m in flat):
            extra.append((dict(color="black", marker="o", ls="none", ms=4),
                          "rate over the seeds' encounters, 95 % interval clustered by HV and seed"))
        if any(style.pooled_by_mean(m) for m in flat):
            extra.append((dict(color="black", marker="o", ls="none", ms=4),
                          "mean over the seeds (95 %% t interval from %d seeds; "
                          "with fewer, each seed's value)" % tidy.SEEDS_FOR_INTERVAL))
        return Figure(name, panels, title=title, caption=caption,
                      ncols=self.ncols or ncols, variants=variants, legend_extra=extra,
                      description={"view": "generic", "x": self.x, "y": list(self.ys),
                                   "by": self.by, "styles": list(self.styles)})

    def _panel(self, item, facet):
        metrics = _metrics_of(item)
        metric = metrics[0]
        p = self._new_panel(item, facet, metrics)
        policies = [q for q in style.policy_order() if q in self.sweep.policies] + \
                   [q for q in self.sweep.policies if q not in style.policy_order()]
        per_policy = len(metrics) if isinstance(item, tuple) else len(self.variant_labels)
        dodge = self._dodge(len(policies) * per_policy)
        stalled = ([], [], [])  # x, y, note of each stalled point
        for p_i, policy in enumerate(policies):
            if isinstance(item, tuple):
                pairs = list(enumerate(metrics))
            else:
                pairs = [(v, metric) for v in range(len(self.variant_labels))]
            for v, metric in pairs:
                pts = self._points(item, facet, policy, v, metric)
                if pts:
                    self._series(p, item, facet, policy, v, metric, pts,
                                 dodge(p_i * per_policy + v), stalled)
        if stalled[0]:
            p.add(Mark("stalled", stalled[0], stalled[1], notes=stalled[2]))
        self._failed(p, facet)
        # `metric`: the last series' (a pair's last metric), as the loop left it.
        if metric == "served_flow":
            self._offered(p, facet)
        add_refs(p, self.marks, self.data, item)
        return p

    def _new_panel(self, item, facet, metrics):
        """The panel of one metric (or pair of metrics) and facet: its title,
        labels, group and y axis, no mark yet."""
        metric = metrics[0]
        facet_text = None
        if facet is not None:
            facet_text = (self.facet_title(facet) if self.facet_title else
                          "%s = %s" % (self.by, self.bykey.label(facet)))
        title = self.metric_titles.get(item, style.metric_title(metric))
        if facet_text is not None:
            # Panel columns: the facet on top of each column, each row's metric
            # by its y label (name and unit) and in the caption.
            title = facet_text if self.ys.index(item) == 0 or len(self.facets) > \
                style.MAX_COLUMNS else ""
            facet_text = None
        ylabel = style.axis_label(metric)
        if len(metrics) > 1:  # time_loss_mean_av, time_loss_mean_hv -> time_loss_mean_{av, hv}
            stem = os.path.commonprefix(metrics)
            ylabel = "%s{%s}" % (stem, ", ".join(m[len(stem):] for m in metrics)) + \
                (" (%s)" % style.metric_unit(metric) if style.metric_unit(metric) else "")
        p = Panel(title=title + ("\n" + facet_text if facet_text else ""), xlabel=self.x_title,
                  ylabel=ylabel, group=item,
                  zero=self.zero.get(item, metric != "served_flow"),
                  categories=(self.xkey.labels if self.xkey is not None and
                              not self.xkey.numeric else None), name=metric)
        p.facet, p.lines = facet_text, []
        return p

    def _points(self, item, facet, policy, v, metric):
        """One series' points: (x, y, lo, hi, theory, seeds' values, stalled
        seeds, seeds that ran) of the policy's rows in the facet and variant."""
        s = self.sweep
        pts = []
        for r in self.rows:
            if r["policy"] != policy or (facet is not None and r.get(self.by) != facet):
                continue
            if not isinstance(item, tuple) and self.variant_of(r) != v:
                continue
            x = self.x_of(r)
            if x is None:
                continue
            ok, bad = s.runs(r)
            y, lo, hi, th = tidy.value_of(s, r, metric)
            if y is None:
                continue
            seeds = []
            if style.pooled_by_mean(metric) and ok < tidy.SEEDS_FOR_INTERVAL:
                seeds = s.seeds(r["point"], policy, metric)
                if seeds:
                    lo = hi = None
            stall = int(tidy.number(r.get("stalled")) or 0)
            pts.append((x, y, lo, hi, th, seeds, stall, ok))
        return pts

    def _series(self, p, item, facet, policy, v, metric, pts, d, stalled):
        """One series' marks on the panel, shifted by d: its points, each seed's
        value, its theory; its stalled points added to `stalled`."""
        pts.sort(key=lambda q: q[0])
        xs = [q[0] + d for q in pts]
        connect = self.connect and (self.xkey is None or self.xkey.numeric)
        p.add(Mark("points", xs, [q[1] for q in pts], lo=[q[2] for q in pts],
                   hi=[q[3] for q in pts], policy=policy, variant=v,
                   ls=style.LINESTYLES[v % 4] if connect else "none"))
        seeds_x = [x for x, q in zip(xs, pts) for _ in q[5]]
        if seeds_x:
            p.add(Mark("seeds", seeds_x, [y for q in pts for y in q[5]], policy=policy,
                       variant=v))
        th = [(x, q[4]) for x, q in zip(xs, pts) if q[4] is not None]
        if self.theory == "bar" and th:
            p.add(Mark("bar", [t[0] for t in th], [t[1] for t in th], policy=policy))
        elif callable(self.theory):
            curve = self.theory(metric, policy, facet, v)
            if curve:
                p.add(Mark("theory", curve[0], curve[1], policy=policy, variant=v,
                           legend="theory", lw=1.3, alpha=0.9,
                           ls=style.LINESTYLES[v % len(style.LINESTYLES)]))
        for x, q in zip(xs, pts):
            if q[6] > 0:
                stalled[0].append(x)
                stalled[1].append(q[1])
                stalled[2].append("%d/%d stalled" % (q[6], q[7]))
        p.lines.append({"policy": policy, "metric": metric,
                        "style": metric if isinstance(item, tuple) else
                        self.variant_labels[v], "points": len(pts),
                        "theory_points": len(th)})

    def _failed(self, p, facet):
        """The failed runs at each x of the facet, marked with k/n."""
        s = self.sweep
        failed = {}
        for r in self.rows:
            if facet is not None and r.get(self.by) != facet:
                continue
            ok, bad = s.runs(r)
            if bad and self.x_of(r) is not None:
                failed.setdefault(self.x_of(r), []).append((bad, ok + bad))
        if failed:
            xs = sorted(failed)
            at_x = {}
            for r in self.rows:
                if facet is None or r.get(self.by) == facet:
                    at_x[self.x_of(r)] = at_x.get(self.x_of(r), 0) + sum(s.runs(r))
            notes = ["%d/%d runs failed" % (sum(b for b, _ in failed[x]), at_x[x]) for x in xs]
            p.add(Mark("failed", xs, [0] * len(xs), notes=notes))

    def _offered(self, p, facet):
        """served = offered: the demand offered in the measured time (the
        mean of the policies' offered_flow) at each x."""
        offered = {}
        for r in self.rows:
            if facet is not None and r.get(self.by) != facet:
                continue
            o, x = tidy.number(r.get("offered_flow")), self.x_of(r)
            if o is not None and x is not None:
                offered.setdefault(x, []).append(o)
        if offered:
            xs = sorted(offered)
            p.add(Mark("curve", xs, [sum(offered[x]) / len(offered[x]) for x in xs],
                       colour="black", legend="served = offered (the demand offered)",
                       simulated=False, ls=":", lw=1.0))


def add_refs(panel, refs, data, metric):
    """The study's own marks (declare.Ref) on a panel of `metric`."""
    for ref in refs:
        for kind, xs, ys, opts in ref.marks(data, metric):
            panel.add(Mark(kind, xs, ys, **opts))


# ------------------------------------------------------------------ a preset's lines
def _variants(decl, rows, data):
    """(variant_of, labels) of a declare.Variants over the rows."""
    of = resolve(decl.of, data)
    values = []
    for r in rows:
        v = of(r)
        if v is not None and v not in values:
            values.append(v)
    values.sort(key=decl.order)
    labels = [decl.labels.get(v, v) if isinstance(decl.labels, dict) else decl.labels.format(v)
              for v in values]
    return (lambda r: values.index(of(r))), labels


def lines_figure(decl, sweep, data):
    """A declare.Lines: its SweepView's figures (one file, or split by metric)."""
    kw = {k: resolve(v, data) for k, v in decl.rest.items()}
    if isinstance(kw.get("facet_title"), str):
        kw["facet_title"] = kw["facet_title"].format
    if decl.variants is not None:
        kw["variant_of"], kw["variant_labels"] = _variants(decl.variants, sweep.rows, data)
    v = SweepView(sweep, resolve(decl.x, data), resolve(decl.y, data), name=decl.file,
                  title=text(decl.title, data), caption=text(decl.caption, data),
                  ncols=decl.ncols, marks=decl.marks, data=data, **kw)
    if decl.split:
        return v.figures()
    panels = v.panels()
    z = decl.zoom
    if z is not None and (z.when is None or resolve(z.when, data)):
        common = {k: kw[k] for k in ("x_title", "theory") if k in kw}
        zoom = SweepView(sweep, resolve(decl.x, data), [z.y], select=resolve(z.select, data),
                         metric_titles={z.y: z.title}, variant_of=lambda r: 0,
                         variant_labels=[z.label], marks=decl.marks, data=data, **common)
        zp = zoom.panels()[0]
        zp.group, zp.ylim = z.group, resolve(z.ylim, data)
        panels.append(zp)
    xlim = resolve(decl.xlim, data)
    for p in panels:
        p.xlim = xlim if xlim is not None else p.xlim
    return [v.figure(decl.file, panels, decl.ncols)]


def _metrics_of(item):
    """A panel's metrics: one name, or a tuple drawn in one panel."""
    return list(item) if isinstance(item, tuple) else [item]


# The standard panels, in order; a metric without data in the sweep is left out.
STANDARD = ["collision_rate", "dc_rate", "served_flow", "time_loss_mean_av", "time_loss_mean_hv",
            "encounters_per_hour"]
# On a track without network measures: the figure-8's throughput and wait.
FALLBACK = {"served_flow": "throughput_all", "time_loss_mean_av": "wait_mean_av",
            "time_loss_mean_hv": "wait_mean_hv"}


def has_data(sweep, metric):
    return any(tidy.value_of(sweep, r, metric)[0] is not None for r in sweep.rows)


def standard_metrics(sweep):
    out = []
    for m in STANDARD:
        if has_data(sweep, m):
            out.append(m)
        elif m in FALLBACK and has_data(sweep, FALLBACK[m]):
            out.append(FALLBACK[m])
    return out


def drawable(sweep):
    """(keys, metrics) a view can draw: the swept keys with values, the
    metrics with at least one value."""
    keys = [k for k in sweep.keys if any((r.get(k) or "") != "" for r in sweep.rows)]
    return keys, [m for m in tidy.metric_names(sweep) if has_data(sweep, m)]


def cannot(sweep, why):
    keys, metrics = drawable(sweep)
    return PlotError("%s. Drawable: --x one of %s; --y any of %s" % (
        why, ", ".join(keys) or "(no swept key)", ", ".join(metrics) or "(no metric with data)"))


def asked(sweep, x, ys, by=None, name=None):
    """The figures of the view --x, --y, --by ask for."""
    return SweepView(sweep, x, ys, by=by, name=name).figures()


def default_views(sweep, keys):
    """The standard panels against each key in `keys`: a SweepView each."""
    metrics = standard_metrics(sweep)
    if not metrics:
        raise cannot(sweep, "no plot for the swept keys %s: no standard metric (%s) has a "
                     "simulated value" % (", ".join(sweep.keys) or "(none)", ", ".join(STANDARD)))
    views = []
    for k in keys:
        others = [o for o in sweep.keys if o != k]
        try:
            views.append(SweepView(sweep, k, metrics))
        except PlotError:
            # Too many combinations for line styles: the other key with most
            # values as panel columns.
            by = max(others, key=lambda o: len({r.get(o) for r in sweep.rows}))
            views.append(SweepView(sweep, k, metrics, by=by))
    return views
