"""The one way a figure is drawn: panels of marks, laid out at the printed
width, with one legend inside the canvas.

A Mark is one thing a panel shows: simulated points with their intervals,
each seed's value, a curve, theory (a line, or a bar at the point),
reference lines, stalled and failed runs. A policy's marks take the
policy's colour and label (style.py); marks that tell apart points sharing
an x take a line style and marker (`variant`). Figure.draw() lays the panels
out at style.PRINT_WIDTH, shares the y range of panels in one group (one
metric), starts a rate or count at 0 exactly, and puts the legend (the
policies, the variants, then what each kind of mark means) and a caption
below the panels, measured so that they fit inside the canvas. Every shipped
figure (presets.py) and the generic view (generic()) are Figures.
"""

import math
import os
import textwrap

from . import style, tidy
from .common import SIMULATED, PlotError, save

def wrap_to(fig, text, fontsize, width_in, italic=False):
    """`text` wrapped (its own line breaks kept) so that every line, as the
    figure's renderer draws it at `fontsize`, is at most `width_in` wide."""
    renderer = fig.canvas.get_renderer()
    chars = max(10, int(width_in * 72 / (fontsize * 0.45)))
    while True:
        wrapped = "\n".join(textwrap.fill(line, chars) if line else ""
                             for line in text.split("\n"))
        probe = fig.text(0, 0, wrapped, fontsize=fontsize, style="italic" if italic else "normal")
        width = probe.get_window_extent(renderer).width / fig.dpi
        probe.remove()
        if width <= width_in or chars <= 10:
            return wrapped
        chars = max(10, int(chars * min(0.95, width_in / width)))


STALL_RING = dict(ls="", marker="o", ms=10, mfc="none", mec="red", mew=1.4)
FAILED_MARK = dict(ls="", marker="X", ms=7, mfc="white", mec="red", mew=1.3)


class Mark:
    """One thing drawn in a panel.

    kind: "points" (markers joined by a line, error bars lo/hi), "seeds"
    (each seed's value, small and hollow), "curve" (a line; `simulated` says
    whether it is data), "bar" (theory: a bar across the point), "theory"
    (a theory line), "step", "special" (one marked point), "stalled" and
    "failed" (rings / crosses, with a note), "hline" / "vline" (reference
    lines), "heat" (a heat map: opts edges, values, texts, cmap, norm).
    policy: colours and labels the mark (style.py); else `colour`.
    variant: index of its line style and marker; legend: its entry's text."""

    def __init__(self, kind, xs=(), ys=(), lo=None, hi=None, policy=None, colour=None,
                 variant=0, legend=None, simulated=None, **opts):
        self.kind = kind
        self.xs, self.ys = list(xs), list(ys)
        self.lo, self.hi = lo, hi
        self.policy = policy
        self.colour = colour or (style.policy_colour(policy) if policy else "black")
        self.variant = variant
        self.legend = legend
        self.simulated = kind in ("points", "seeds", "heat") if simulated is None else simulated
        self.opts = opts


class Panel:
    """One axes: its marks, title, axis labels and scales. `group`: panels
    of one group share their y range; `zero`: the y axis starts at 0
    exactly (a rate, a count); `categories`: tick labels of a categorical x."""

    def __init__(self, title="", xlabel="", ylabel="", group=None, zero=True, xscale="linear",
                 yscale="linear", categories=None, ylim=None, xlim=None, name=None):
        self.title, self.xlabel, self.ylabel = title, xlabel, ylabel
        self.group, self.zero = group, zero
        self.xscale, self.yscale = xscale, yscale
        self.categories = categories
        self.ylim, self.xlim = ylim, xlim
        self.name = name  # what --describe calls it (a metric)
        self.marks = []
        self.notes = []  # (x, y, text, colour, offset points, axes-fraction y?)

    def add(self, mark):
        self.marks.append(mark)
        return mark

    def has_data(self):
        return any(m.simulated and (m.ys or m.kind == "heat") for m in self.marks)


class Figure:
    """Panels in rows of at most `ncols`, a title, a caption and the legend,
    drawn at the printed width."""

    def __init__(self, file, panels, title="", caption="", ncols=None, panel_height=None,
                 variants=None, legend_extra=(), heat=False, description=None):
        self.file = file
        self.panels = [p for p in panels]
        self.title, self.caption = title, caption
        self.ncols = ncols or min(style.MAX_COLUMNS, max(1, len(self.panels)))
        self.panel_height = panel_height or style.PANEL_HEIGHT
        self.variants = variants or []  # [(label, linestyle, marker)] of the variant indices
        self.legend_extra = list(legend_extra)  # [(handle kwargs, label)]
        self.heat = heat
        self.description = description or {}

    # -- drawing
    def draw(self, plt):
        panels = [p for p in self.panels if p.has_data()]
        if not panels:
            raise PlotError("%s: no simulated value to draw (every point empty or failed); "
                            "not written" % self.file)
        ncols = min(self.ncols, len(panels))
        nrows = int(math.ceil(len(panels) / ncols))
        fig, axes = plt.subplots(nrows, ncols, squeeze=False,
                                 figsize=(style.PRINT_WIDTH, nrows * self.panel_height + 1.5))
        for i in range(nrows * ncols):
            if i >= len(panels):
                axes[i // ncols][i % ncols].set_visible(False)
        self._legend = {}
        self._panel_width = style.PRINT_WIDTH / ncols
        for i, panel in enumerate(panels):
            self._draw_panel(fig, axes[i // ncols][i % ncols], panel)
        self._share(panels, axes, ncols)
        handles, labels = self._legend_entries()
        self._finish(fig, handles, labels)
        self.description.update({"file": self.file, "legend": labels, "panels": [
            {"metric": p.name, "title": p.title, "xlabel": p.xlabel, "ylabel": p.ylabel,
             "facet": getattr(p, "facet", None), "lines": getattr(p, "lines", [])}
            for p in panels]})
        return fig

    def save(self, plt, out_dir):
        fig = self.draw(plt)
        return save(fig, os.path.join(out_dir, self.file))

    def _entry(self, key, handle, label):
        if label and key not in self._legend:
            self._legend[key] = (handle, label)

    def _draw_panel(self, fig, ax, panel):
        from matplotlib.lines import Line2D
        for m in panel.marks:
            ls = style.LINESTYLES[m.variant % len(style.LINESTYLES)]
            marker = style.MARKERS[m.variant % len(style.MARKERS)]
            gid = SIMULATED if m.simulated else None
            if m.kind == "points":
                err = None
                if m.lo is not None and any(v is not None for v in m.lo):
                    err = [[max(0.0, y - l) if l is not None else 0.0 for y, l in zip(m.ys, m.lo)],
                           [max(0.0, h - y) if h is not None else 0.0 for y, h in zip(m.ys, m.hi)]]
                line = ax.errorbar(m.xs, m.ys, yerr=err, fmt=marker, ls=m.opts.get("ls", ls),
                                   color=m.colour, ms=m.opts.get("ms", 4), capsize=2.5, lw=1.2,
                                   elinewidth=1.0, clip_on=False, zorder=3)
                line[0].set_gid(gid)
                if m.policy:
                    self._entry(("policy", m.policy), Line2D([], [], color=m.colour, marker="o",
                                                             lw=1.2, ms=4),
                                style.policy_label(m.policy))
                elif m.legend:
                    self._entry(("own", m.legend), Line2D([], [], color=m.colour, marker=marker,
                                                          ls=ls, lw=1.2, ms=4), m.legend)
            elif m.kind == "seeds":
                ax.plot(m.xs, m.ys, ls="", marker=marker, ms=3, mfc="none", mec=m.colour,
                        mew=0.8, alpha=0.8, gid=gid, clip_on=False, zorder=2)
                self._entry(("seeds",), Line2D([], [], ls="", marker="o", ms=3, mfc="none",
                                               mec="black", mew=0.8),
                            m.legend or "one seed (fewer than %d: no interval)"
                            % tidy.SEEDS_FOR_INTERVAL)
            elif m.kind in ("curve", "theory", "step"):
                kw = dict(color=m.colour, lw=m.opts.get("lw", 1.4), ls=m.opts.get("ls", ls),
                          alpha=m.opts.get("alpha", 1.0), gid=gid, zorder=m.opts.get("zorder", 2))
                if m.kind == "step":
                    ax.step(m.xs, m.ys, where="post", **kw)
                else:
                    ax.plot(m.xs, m.ys, **kw)
                if m.legend:
                    c = m.opts.get("legend_colour", "black" if m.policy else m.colour)
                    self._entry(("line", m.legend), Line2D([], [], color=c, lw=kw["lw"],
                                                           ls=kw["ls"]), m.legend)
                elif m.policy and m.simulated:
                    self._entry(("policy", m.policy), Line2D([], [], color=m.colour, lw=1.4),
                                style.policy_label(m.policy))
            elif m.kind == "bar":
                ax.plot(m.xs, m.ys, ls="none", marker="_", ms=12, mew=2.0, color=m.colour,
                        alpha=0.75, zorder=2)
                self._entry(("bar",), Line2D([], [], color="black", ls="none", marker="_", ms=12,
                                             mew=2.0), m.legend or "theory (bar at the point)")
            elif m.kind == "special":
                ax.plot(m.xs, m.ys, ls="", marker=m.opts.get("marker", "D"), mfc="white",
                        mec=m.colour, ms=6, mew=1.3, clip_on=False, zorder=5)
                self._entry(("special", m.legend), Line2D([], [], ls="", marker=m.opts.get(
                    "marker", "D"), mfc="white", mec="black", ms=6, mew=1.3), m.legend)
            elif m.kind == "stalled":
                ax.plot(m.xs, m.ys, zorder=5, clip_on=False, **STALL_RING)
                for x, y, note in zip(m.xs, m.ys, m.opts.get("notes", [])):
                    if note:
                        ax.annotate(note, (x, y), xytext=(6, -4), textcoords="offset points",
                                    fontsize=style.MIN_FONT, color="red", va="top")
                self._entry(("stalled",), Line2D([], [], **STALL_RING), "a seed stalled (k/n)")
            elif m.kind == "failed":
                trans = ax.get_xaxis_transform()
                ax.plot(m.xs, [0.04] * len(m.xs), transform=trans, zorder=6, clip_on=False,
                        **FAILED_MARK)
                for x, note in zip(m.xs, m.opts.get("notes", [])):
                    if note:
                        ax.annotate(note, (x, 0.04), xycoords=trans, xytext=(0, 6),
                                    textcoords="offset points", ha="center", va="bottom",
                                    fontsize=style.MIN_FONT, color="red")
                self._entry(("failed",), Line2D([], [], **FAILED_MARK),
                            "failed seeds (k/n failed; all failed: no value)")
            elif m.kind in ("hline", "vline"):
                for v in m.xs:
                    (ax.axhline if m.kind == "hline" else ax.axvline)(
                        v, color=m.colour, ls=m.opts.get("ls", "--"), lw=m.opts.get("lw", 1.0),
                        zorder=1)
                    if m.opts.get("note"):
                        if m.kind == "vline":
                            ax.annotate(m.opts["note"], xy=(v, 1), xycoords=("data", "axes fraction"),
                                        xytext=(2, -2), textcoords="offset points", va="top",
                                        ha="left", fontsize=style.FONT)
                        else:  # at the right end, above the line
                            ax.annotate(m.opts["note"], xy=(1, v), xycoords=("axes fraction", "data"),
                                        xytext=(-2, 2), textcoords="offset points", va="bottom",
                                        ha="right", fontsize=style.FONT, color=m.colour)
                if m.legend:
                    self._entry(("ref", m.legend), Line2D([], [], color=m.opts.get(
                        "legend_colour", m.colour), ls=m.opts.get("ls", "--"),
                        lw=m.opts.get("lw", 1.0)), m.legend)
            elif m.kind == "heat":
                self._heat(fig, ax, m)
            elif m.kind == "shade":
                ax.axvspan(m.xs[0], m.xs[1], color=m.opts.get("shade", "0.9"), zorder=0)
                if m.legend:
                    from matplotlib.patches import Patch
                    self._entry(("shade", m.legend), Patch(color=m.opts.get("shade", "0.9")),
                                m.legend)
        for (x, y, text, colour) in panel.notes:
            ax.annotate(text, (x, y), fontsize=style.FONT, color=colour)
        # Titles and labels wrapped to the panel's width at the printed size.
        ax.set_title(wrap_to(fig, panel.title, style.TITLE_FONT, self._panel_width - 0.7),
                     fontsize=style.TITLE_FONT)
        ax.set_xlabel(wrap_to(fig, panel.xlabel, style.FONT, self._panel_width - 0.7))
        ax.set_ylabel(wrap_to(fig, panel.ylabel, style.FONT, self.panel_height - 0.3))
        ax.set_xscale(panel.xscale)
        ax.set_yscale(panel.yscale)
        from matplotlib.ticker import NullFormatter
        for axis, scale in ((ax.xaxis, panel.xscale), (ax.yaxis, panel.yscale)):
            if scale == "log":  # decades only: minor labels collide at the printed size
                axis.set_minor_formatter(NullFormatter())
        if panel.categories:
            ax.set_xticks(range(len(panel.categories)))
            ax.set_xticklabels(["\n".join(textwrap.wrap(c, 14)) for c in panel.categories])
            ax.set_xlim(-0.5, len(panel.categories) - 0.5)
        if panel.xlim:
            ax.set_xlim(*panel.xlim)
        if not any(m.kind == "heat" for m in panel.marks):
            ax.grid(alpha=0.3, which="both" if "log" in (panel.xscale, panel.yscale) else "major")
        panel.ax = ax

    def _heat(self, fig, ax, m):
        import matplotlib.patheffects as pe
        import numpy as np
        ex, ey, z = m.opts["edges_x"], m.opts["edges_y"], np.asarray(m.opts["values"], dtype=float)
        mesh = ax.pcolormesh(ex, ey, np.ma.masked_invalid(z), cmap=m.opts["cmap"],
                             norm=m.opts["norm"], shading="flat")
        mesh.set_gid(SIMULATED)
        fig.colorbar(mesh, ax=ax, label=m.opts.get("colourbar", ""), fraction=0.05, pad=0.02)
        def is_dark(v):  # the cell's colour, by its luminance
            r, g, b, _ = mesh.cmap(mesh.norm(v))
            return 0.2126 * r + 0.7152 * g + 0.0722 * b < 0.45

        for (x, y, text, v) in m.opts.get("texts", []):
            dark = v is not None and is_dark(v)
            ax.text(x, y, text, ha="center", va="center", fontsize=style.MIN_FONT,
                    linespacing=1.0, color="white" if dark else "black",
                    path_effects=[pe.withStroke(linewidth=1.6,
                                                foreground="black" if dark else "white")])
        for (xs, ys) in m.opts.get("outline", []):
            ax.plot(xs, ys, color=m.opts.get("outline_colour", "#00b4d8"), lw=2.2, zorder=4)
        if m.opts.get("outline"):
            from matplotlib.lines import Line2D
            self._entry(("outline",), Line2D([], [], color=m.opts.get("outline_colour", "#00b4d8"),
                                             lw=2.2), m.opts.get("outline_label"))
        ax.set_xlim(ex[0], ex[-1])
        ax.set_ylim(ey[0], ey[-1])
        ax.grid(False)

    def _share(self, panels, axes, ncols):
        """One x range per x axis (panels with one x label), one y range per
        group, a rate or count from 0 exactly, room at the top."""
        xs = {}
        for p in panels:
            if p.categories or p.xlim or p.xscale == "log" or \
                    any(m.kind == "heat" for m in p.marks):
                continue
            vals = [x for m in p.marks if m.kind not in ("hline", "shade", "failed")
                    for x in m.xs if x is not None and math.isfinite(x)]
            if vals:
                lo_hi = xs.setdefault(p.xlabel, [math.inf, -math.inf])
                lo_hi[0], lo_hi[1] = min(lo_hi[0], min(vals)), max(lo_hi[1], max(vals))
        for p in panels:
            if p.xlabel in xs and not (p.categories or p.xlim or p.xscale == "log"):
                lo, hi = xs[p.xlabel]
                pad = (hi - lo) * 0.04 or 0.5
                p.ax.set_xlim(lo - pad, hi + pad)
        groups = {}
        for i, p in enumerate(panels):
            if any(m.kind == "heat" for m in p.marks):
                continue
            groups.setdefault(p.group if p.group is not None else ("own", i), []).append(p)
        for members in groups.values():
            lo, hi = math.inf, -math.inf
            for p in members:
                for m in p.marks:
                    if m.kind in ("failed", "vline", "shade", "stalled"):
                        continue
                    vals = [v for v in m.ys if v is not None]
                    if m.kind == "hline":
                        vals = list(m.xs)
                    for extra in (m.lo, m.hi):
                        if extra:
                            vals += [v for v in extra if v is not None]
                    vals = [v for v in vals if v is not None and math.isfinite(v) and
                            (p.yscale != "log" or v > 0)]
                    if vals:
                        lo, hi = min(lo, min(vals)), max(hi, max(vals))
            if not math.isfinite(lo):
                continue
            for p in members:
                ax = p.ax
                if p.ylim:
                    ax.set_ylim(*p.ylim)
                    continue
                if p.yscale == "log":
                    ax.set_ylim(lo / 1.5, hi * 1.5)
                    continue
                if p.zero and lo >= 0:
                    top = hi * 1.08 if hi > 0 else 1.0
                    if style.is_rate(p.name or "") or p.name is None and hi <= 1:
                        top = min(1.0, top) if hi > 0 else 0.05
                    ax.set_ylim(0, top)
                else:
                    pad = (hi - lo) * 0.08 or abs(hi) * 0.05 or 1.0
                    ax.set_ylim(lo - pad, hi + pad)

    def _legend_entries(self):
        from matplotlib.lines import Line2D
        entries = list(self._legend.items())
        order = {"policy": 0}
        policies = [e for e in entries if e[0][0] == "policy"]
        rank = {p: i for i, p in enumerate(style.policy_order())}
        policies.sort(key=lambda e: rank.get(e[0][1], 99))
        rest = [e for e in entries if e[0][0] not in order]
        handles = [h for _, (h, _) in policies]
        labels = [l for _, (_, l) in policies]
        for label, ls, marker in self.variants:
            handles.append(Line2D([], [], color="black", ls=ls, marker=marker, ms=4, lw=1.2))
            labels.append(label)
        for _, (h, l) in rest:
            handles.append(h)
            labels.append(l)
        for kw, label in self.legend_extra:
            handles.append(Line2D([], [], **kw))
            labels.append(label)
        return handles, labels

    def _finish(self, fig, handles, labels):
        """Title on top, legend and caption below the panels, all measured to
        fit inside the canvas at the printed width."""
        renderer = fig.canvas.get_renderer()
        width_px = fig.bbox.width
        per_inch = fig.dpi
        title = wrap_to(fig, self.title, style.TITLE_FONT, style.PRINT_WIDTH - 0.2) \
            if self.title else ""
        top_in = 0.06
        suptitle = None
        if title:
            suptitle = fig.suptitle(title, fontsize=style.TITLE_FONT, y=1.0, va="top")
            suptitle.set_in_layout(False)  # its room is the rect's top below
            top_in += suptitle.get_window_extent(renderer).height / per_inch + 0.04
        legend = None
        legend_in = 0.0
        if labels:
            ncol = len(labels)
            while True:
                legend = fig.legend(handles, labels, loc="lower center", ncol=ncol, frameon=False,
                                    fontsize=style.FONT, handlelength=2.2, columnspacing=1.2,
                                    borderaxespad=0.2)
                w = legend.get_window_extent(renderer).width
                if w <= 0.98 * width_px or ncol == 1:
                    break
                legend.remove()
                ncol -= 1
            legend_in = legend.get_window_extent(renderer).height / per_inch + 0.05
        caption_in = 0.0
        caption = None
        if self.caption:
            text = wrap_to(fig, self.caption, style.FONT, style.PRINT_WIDTH - 0.2, italic=True)
            caption = fig.text(0.5, 0.0, text, ha="center", va="bottom", fontsize=style.FONT,
                               style="italic")
            caption_in = caption.get_window_extent(renderer).height / per_inch + 0.08
        panels_in = fig.get_figheight() - 1.5
        height = panels_in + top_in + legend_in + caption_in + 0.1
        fig.set_figheight(height)
        if suptitle is not None:
            suptitle.set_y(1 - 0.05 / height)
        if caption is not None:
            caption.set_y(0.04 / height)
        if legend is not None:
            legend.set_bbox_to_anchor((0.5, (caption_in + 0.02) / height), transform=fig.transFigure)
        bottom = (caption_in + legend_in + 0.05) / height
        fig.tight_layout(rect=(0, bottom, 1, 1 - top_in / height), pad=0.4, h_pad=0.9, w_pad=0.8)


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
    theory: "bar", None, or f(metric, policy, facet) -> (xs, ys) curves.
    extra(panel, metric, facet): the preset's own marks (reference lines)."""

    def __init__(self, sweep, x, ys, by=None, name=None, select=None, x_of=None, x_title=None,
                 styles=None, variant_of=None, variant_labels=None, theory="bar", extra=None,
                 title=None, caption="", metric_titles=None, zero=None, facet_title=None,
                 ncols=None, pair_labels=None, connect=None):
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
        self.theory, self.extra = theory, extra
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
        s = self.sweep
        metrics = _metrics_of(item)
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
        policies = [q for q in style.policy_order() if q in s.policies] + \
                   [q for q in s.policies if q not in style.policy_order()]
        per_policy = len(metrics) if isinstance(item, tuple) else len(self.variant_labels)
        dodge = self._dodge(len(policies) * per_policy)
        stalled_x, stalled_y, stalled_notes = [], [], []
        failed = {}
        for p_i, policy in enumerate(policies):
            if isinstance(item, tuple):
                pairs = list(enumerate(metrics))
            else:
                pairs = [(v, metric) for v in range(len(self.variant_labels))]
            for v, metric in pairs:
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
                if not pts:
                    continue
                pts.sort(key=lambda q: q[0])
                d = dodge(p_i * per_policy + v)
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
                        stalled_x.append(x)
                        stalled_y.append(q[1])
                        stalled_notes.append("%d/%d stalled" % (q[6], q[7]))
                p.lines.append({"policy": policy, "metric": metric,
                                "style": metric if isinstance(item, tuple) else
                                self.variant_labels[v], "points": len(pts),
                                "theory_points": len(th)})
        if stalled_x:
            p.add(Mark("stalled", stalled_x, stalled_y, notes=stalled_notes))
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
        if metric == "served_flow":
            self._offered(p, facet)
        if self.extra:
            self.extra(p, item, facet)
        return p

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
