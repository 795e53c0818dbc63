"""The map layout of figure.py: a declare.Map drawn over its data
(netmap.map_data): one panel per controller policy with the net's lanes as
thin lines and each controlled junction a marker, its area by the AV-HV
encounters and its colour by the queueing delay (against sumo_native's),
north up, a scale bar, the colour bar beside the last panel, the legend
hugging the panels and the title above them, all at the printed width."""

import math
import os

from . import style
from .common import SIMULATED, save
from .declare import text
from .figure import wrap_to

NO_CROSSING = (0.6, 0.6, 0.6, 1)  # a junction no vehicle crossed


def map_figure(decl, plt, data, out_dir):
    """The map's PNG in out_dir; its path."""
    import matplotlib.colors as mcolors
    native, limit = data["native"], data["limit"]
    norm = (mcolors.TwoSlopeNorm(vcenter=0.0, vmin=-limit, vmax=limit) if native
            else mcolors.Normalize(vmin=0.0, vmax=limit))
    cmap = plt.get_cmap(decl.cmap[0] if native else decl.cmap[1])
    max_enc = data["max_enc"]

    def size(e):  # marker area (pt^2) by encounters; a junction without any: a small dot
        return 14 + 110 * math.sqrt(e / max_enc) if e > 0 else 8

    x0, x1, y0, y1 = data["bounds"]
    w, h = max(x1 - x0, 1.0), max(y1 - y0, 1.0)
    n = len(data["panels"])
    panel_w = (style.PRINT_WIDTH - 0.9) / n  # at the printed width, the colour bar beside
    fig, axes = plt.subplots(1, n, figsize=(style.PRINT_WIDTH, panel_w * 1.11 * h / w + 1.6),
                             squeeze=False)
    for ax, (p, rows) in zip(axes[0], data["panels"]):
        _draw_panel(ax, decl, p, rows, data, (cmap, norm, limit), size)
    # Panels first, then the colour bar beside the last one at its height.
    fig.subplots_adjust(left=0.02, right=0.86, wspace=0.06)
    fig.canvas.draw()  # the panels' places, their aspect applied
    cax = _colour_bar(plt, fig, axes, norm, cmap,
                      decl.colourbar[0] if native else decl.colourbar[1], native)
    handles = _legend_handles(size, max_enc, cmap, norm)
    _title(fig, axes, cax, text(decl.title, data))
    # The legend hugs the panels (their aspect is the net's, so the figure's
    # height is not theirs); savefig's tight box keeps what is drawn.
    bottom = min(ax.get_position().y0 for ax in axes[0])
    fig.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, bottom - 0.01),
               ncol=3, frameon=False, fontsize=style.FONT)
    return save(fig, os.path.join(out_dir, decl.file), bbox_inches="tight")


def _draw_panel(ax, decl, p, rows, data, colour, size):
    """One policy's panel: the lanes, its junctions (those without an
    encounter first, small), its title, north and a scale bar."""
    from matplotlib.collections import LineCollection
    cmap, norm, limit = colour
    x0, x1, y0, y1 = data["bounds"]
    w, h = max(x1 - x0, 1.0), max(y1 - y0, 1.0)
    ax.add_collection(LineCollection(data["lanes"], colors="0.6", linewidths=0.4, zorder=1))
    none = [r for r in rows if r[1] == 0]
    some = sorted([r for r in rows if r[1] > 0], key=lambda r: -r[1])
    for group, edge in ((none, "0.45"), (some, "black")):
        if not group:
            continue
        cols = [cmap(norm(max(-limit, min(limit, c)))) if c is not None else NO_CROSSING
                for _, _, c in group]
        ax.scatter([q[0][0] for q in group], [q[0][1] for q in group],
                   s=[size(e) for _, e, _ in group], c=cols, edgecolors=edge,
                   linewidths=0.4 if group is none else 0.7, zorder=3 if group is none else 4,
                   gid=SIMULATED)
    ax.set_title(decl.panel_title(style.policy_label(p), sum(e for _, e, _ in rows), len(rows)),
                 fontsize=style.TITLE_FONT)
    ax.grid(False)
    ax.set_xlim(x0 - 0.03 * w, x1 + 0.03 * w)
    ax.set_ylim(y0 - 0.08 * h, y1 + 0.03 * h)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    # North up (SUMO's net coordinates: +y is north) and a scale bar.
    ax.annotate("N", xy=(0.97, 0.97), xytext=(0.97, 0.86), xycoords="axes fraction",
                ha="center", va="bottom", fontsize=style.TITLE_FONT, fontweight="bold",
                arrowprops=dict(arrowstyle="-|>", color="black", lw=1.2))
    bar = data["bar"]
    bx, by = x0, y0 - 0.05 * h
    ax.plot([bx, bx + bar], [by, by], color="black", lw=2.5, solid_capstyle="butt", zorder=4)
    ax.text(bx + bar / 2, by + 0.012 * h, ("%g km" % (bar / 1000)) if bar >= 1000 else "%g m" % bar,
            ha="center", va="bottom", fontsize=style.FONT)


def _colour_bar(plt, fig, axes, norm, cmap, label, native):
    """The colour bar beside the last panel, at its height; its axes."""
    last = axes[0][-1].get_position()
    cax = fig.add_axes([last.x1 + 0.015, last.y0, 0.02, last.height])
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    sm.set_array([])
    cbar = fig.colorbar(sm, cax=cax, extend="both" if native else "max")
    cbar.set_label(label, fontsize=style.FONT)
    return cax


def _legend_handles(size, max_enc, cmap, norm):
    """The legend's markers: encounters by area, no encounter, no vehicle crossed."""
    from matplotlib.lines import Line2D
    from .netmap import nice_length
    ticks = sorted({1, nice_length(max_enc * 2.5) if max_enc >= 10 else 1, max_enc})
    handles = [Line2D([], [], ls="", marker="o", markersize=math.sqrt(size(t)), markerfacecolor="0.8",
                      markeredgecolor="black", label="%d encounter%s" % (t, "" if t == 1 else "s"))
               for t in ticks]
    handles.append(Line2D([], [], ls="", marker="o", markersize=math.sqrt(size(0)),
                          markerfacecolor=cmap(norm(0.0)), markeredgecolor="0.45",
                          label="no encounter"))
    handles.append(Line2D([], [], ls="", marker="o", markersize=math.sqrt(size(0)),
                          markerfacecolor=NO_CROSSING, markeredgecolor="0.45",
                          label="no vehicle crossed"))
    return handles


def _title(fig, axes, cax, title):
    """The figure's title above the panels' titles, inside the figure: the
    figure grows by the title's height."""
    title = wrap_to(fig, title, style.TITLE_FONT, style.PRINT_WIDTH - 0.2)
    lines = title.count("\n") + 1
    title_in = lines * style.TITLE_FONT * 1.35 / 72 + 0.1
    above = max(ax.get_tightbbox(fig.canvas.get_renderer()).y1 for ax in axes[0]) / fig.dpi
    height = fig.get_figheight()
    grow = max(0.0, above + title_in - height)
    if grow:
        fig.set_figheight(height + grow)
        for ax in list(axes[0]) + [cax]:
            box = ax.get_position()
            scale = height / (height + grow)
            ax.set_position([box.x0, box.y0 * scale, box.width, box.height * scale])
    fig.suptitle(title, fontsize=style.TITLE_FONT, y=1 - 0.05 / fig.get_figheight(), va="top")
