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
figure (the presets) and the generic view (view.SweepView) are Figures.
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
    lines), "shade" (an x span), "heat" (a heat map: opts edges_x, edges_y,
    values, texts, the colour map's name cmap, bad (no value), vmin, vmax,
    colourbar, outline, outline_label).
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
        for m in panel.marks:
            self._draw_mark(fig, ax, m)
        for (x, y, text, colour) in panel.notes:
            ax.annotate(text, (x, y), fontsize=style.FONT, color=colour)
        self._axes(fig, ax, panel)
        panel.ax = ax

    def _draw_mark(self, fig, ax, m):
        """One mark, as its kind draws it, and its legend entry."""
        ls = style.LINESTYLES[m.variant % len(style.LINESTYLES)]
        marker = style.MARKERS[m.variant % len(style.MARKERS)]
        gid = SIMULATED if m.simulated else None
        if m.kind == "points":
            self._draw_points(ax, m, ls, marker, gid)
        elif m.kind == "seeds":
            self._draw_seeds(ax, m, marker, gid)
        elif m.kind in ("curve", "theory", "step"):
            self._draw_line(ax, m, ls, gid)
        elif m.kind == "bar":
            self._draw_bar(ax, m)
        elif m.kind == "special":
            self._draw_special(ax, m)
        elif m.kind == "stalled":
            self._draw_stalled(ax, m)
        elif m.kind == "failed":
            self._draw_failed(ax, m)
        elif m.kind in ("hline", "vline"):
            self._draw_reference(ax, m)
        elif m.kind == "heat":
            self._heat(fig, ax, m)
        elif m.kind == "shade":
            self._draw_shade(ax, m)

    def _draw_points(self, ax, m, ls, marker, gid):
        from matplotlib.lines import Line2D
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

    def _draw_seeds(self, ax, m, marker, gid):
        from matplotlib.lines import Line2D
        ax.plot(m.xs, m.ys, ls="", marker=marker, ms=3, mfc="none", mec=m.colour,
                mew=0.8, alpha=0.8, gid=gid, clip_on=False, zorder=2)
        self._entry(("seeds",), Line2D([], [], ls="", marker="o", ms=3, mfc="none",
                                       mec="black", mew=0.8),
                    m.legend or "one seed (fewer than %d: no interval)"
                    % tidy.SEEDS_FOR_INTERVAL)

    def _draw_line(self, ax, m, ls, gid):
        """A curve, a theory line or a step."""
        from matplotlib.lines import Line2D
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

    def _draw_bar(self, ax, m):
        from matplotlib.lines import Line2D
        ax.plot(m.xs, m.ys, ls="none", marker="_", ms=12, mew=2.0, color=m.colour,
                alpha=0.75, zorder=2)
        self._entry(("bar",), Line2D([], [], color="black", ls="none", marker="_", ms=12,
                                     mew=2.0), m.legend or "theory (bar at the point)")

    def _draw_special(self, ax, m):
        from matplotlib.lines import Line2D
        ax.plot(m.xs, m.ys, ls="", marker=m.opts.get("marker", "D"), mfc="white",
                mec=m.colour, ms=6, mew=1.3, clip_on=False, zorder=5)
        self._entry(("special", m.legend), Line2D([], [], ls="", marker=m.opts.get(
            "marker", "D"), mfc="white", mec="black", ms=6, mew=1.3), m.legend)

    def _draw_stalled(self, ax, m):
        from matplotlib.lines import Line2D
        ax.plot(m.xs, m.ys, zorder=5, clip_on=False, **STALL_RING)
        for x, y, note in zip(m.xs, m.ys, m.opts.get("notes", [])):
            if note:
                ax.annotate(note, (x, y), xytext=(6, -4), textcoords="offset points",
                            fontsize=style.MIN_FONT, color="red", va="top")
        self._entry(("stalled",), Line2D([], [], **STALL_RING), "a seed stalled (k/n)")

    def _draw_failed(self, ax, m):
        from matplotlib.lines import Line2D
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

    def _draw_reference(self, ax, m):
        """Horizontal or vertical reference lines, each with its note."""
        from matplotlib.lines import Line2D
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

    def _draw_shade(self, ax, m):
        ax.axvspan(m.xs[0], m.xs[1], color=m.opts.get("shade", "0.9"), zorder=0)
        if m.legend:
            from matplotlib.patches import Patch
            self._entry(("shade", m.legend), Patch(color=m.opts.get("shade", "0.9")),
                        m.legend)

    def _axes(self, fig, ax, panel):
        """The panel's titles, labels, scales, ticks, limits and grid."""
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

    def _heat(self, fig, ax, m):
        import matplotlib
        import matplotlib.colors as mcolors
        import matplotlib.patheffects as pe
        import numpy as np
        ex, ey, z = m.opts["edges_x"], m.opts["edges_y"], np.asarray(m.opts["values"], dtype=float)
        cmap = matplotlib.colormaps[m.opts["cmap"]].copy()
        cmap.set_bad(m.opts.get("bad", "white"))
        mesh = ax.pcolormesh(ex, ey, np.ma.masked_invalid(z), cmap=cmap, shading="flat",
                             norm=mcolors.Normalize(vmin=m.opts["vmin"], vmax=m.opts["vmax"]))
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
