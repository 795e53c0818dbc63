"""network_map.png: a network run's controlled junctions on its map."""

import json
import math
import os

from . import style
from .common import SIMULATED, die, save


def run_network_file(run_dir, summary):
    """The network a run ran on: the run folder's network.net.xml (generated or
    patched), else the config's scenario.network or the net-file of its
    scenario.sumocfg (absolute since taebp writes the inputs so, $SUMO_HOME, or
    relative to the config file)."""
    kept = os.path.join(run_dir, "network.net.xml")
    if os.path.isfile(kept):
        return kept
    prov = summary.get("provenance", {})
    scenario = prov.get("config", {}).get("scenario", {}) or {}
    home = os.environ.get("SUMO_HOME", "/usr/share/sumo")

    def resolve(path, base):
        path = path.replace("${SUMO_HOME}", home).replace("$SUMO_HOME", home)
        return path if os.path.isabs(path) else os.path.join(base, path)
    config_dir = os.path.dirname(prov.get("config_path", "") or ".")
    net = scenario.get("network") or ""
    if not net and scenario.get("sumocfg"):
        import xml.etree.ElementTree as ET
        cfg = resolve(scenario["sumocfg"], config_dir)
        try:
            node = ET.parse(cfg).getroot().find(".//net-file")
        except (OSError, ET.ParseError):
            return None
        if node is None or not node.get("value"):
            return None
        net, config_dir = node.get("value").split(",")[0].strip(), os.path.dirname(cfg)
    if not net:
        return None
    net = resolve(net, config_dir)
    return net if os.path.isfile(net) else None


def read_net(path):
    """(lane polylines, {junction id: (x, y)}) of a SUMO .net.xml, internal lanes left out."""
    import xml.etree.ElementTree as ET
    lanes, junctions = [], {}
    internal = False
    for event, el in ET.iterparse(path, events=("start", "end")):
        if event == "start":
            if el.tag == "edge":
                internal = el.get("function") == "internal"
            continue
        if el.tag == "lane" and not internal and el.get("shape"):
            pts = [tuple(float(c) for c in xy.split(",")[:2]) for xy in el.get("shape").split()]
            if len(pts) >= 2:
                lanes.append(pts)
        elif el.tag == "junction" and el.get("type") != "internal":
            junctions[el.get("id")] = (float(el.get("x")), float(el.get("y")))
            el.clear()
        elif el.tag == "edge":
            el.clear()
    return lanes, junctions


def queueing_delay(junction):
    """Mean time a crossing vehicle spends halted on the junction's approaches
    (s/veh): Little's law, the approaches' summed mean queue over the crossing
    rate. None when nothing crossed."""
    rate = (junction.get("throughput_all") or 0) / 3600.0
    if rate <= 0:
        return None
    return sum(a.get("queue_mean") or 0.0 for a in junction.get("approaches", [])) / rate


def nice_length(span):
    """A round scale-bar length near a fifth of `span` metres."""
    target = max(span / 5.0, 1.0)
    base = 10 ** math.floor(math.log10(target))
    for m in (5, 2, 1):
        if m * base <= target:
            return int(m * base) if m * base >= 1 else m * base
    return base


def plot_map(plt, run_dir, out_dir):
    """network_map.png: the net's lanes as thin lines, each controlled junction a
    marker sized by its AV-HV encounters and coloured by its queueing delay
    against sumo_native's (one panel per controller policy), north up, a scale."""
    import matplotlib.colors as mcolors
    with open(os.path.join(run_dir, "summary.json")) as f:
        summary = json.load(f)
    pols = summary.get("policies", {})
    if not any("served_flow" in p for p in pols.values()):  # a network run
        return None
    net = run_network_file(run_dir, summary)
    if net is None:
        die("%s: the network of this run was not found (no network.net.xml in the folder, "
            "and the config's scenario.network is not a file)" % run_dir)
    lanes, nodes = read_net(net)
    native = pols.get("sumo_native")
    panels = _junction_rows(pols, nodes, native)
    if not panels:
        return None
    # The colour scale spans the 95th percentile of the changes (outliers take the
    # end colours; the colour bar's arrows say so): one junction's gridlock
    # would otherwise wash out every other.
    changes = sorted(abs(c) for _, rows in panels for _, _, c in rows if c is not None)
    limit = changes[min(len(changes) - 1, int(0.95 * len(changes)))] if changes else 0.0
    limit = float("%.2g" % limit) if limit > 0 else 1.0
    norm = (mcolors.TwoSlopeNorm(vcenter=0.0, vmin=-limit, vmax=limit) if native
            else mcolors.Normalize(vmin=0.0, vmax=limit))
    cmap = plt.get_cmap("RdBu_r" if native else "viridis")
    max_enc = max([e for _, rows in panels for _, e, _ in rows] + [1])

    def size(e):  # marker area (pt^2) by encounters; a junction without any: a small dot
        return 14 + 110 * math.sqrt(e / max_enc) if e > 0 else 8

    xs = [x for line in lanes for x, _ in line] or [x for x, _ in nodes.values()]
    ys = [y for line in lanes for _, y in line] or [y for _, y in nodes.values()]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    w, h = max(x1 - x0, 1.0), max(y1 - y0, 1.0)
    n = len(panels)
    panel_w = (style.PRINT_WIDTH - 0.9) / n  # at the printed width, the colour bar beside
    fig, axes = plt.subplots(1, n, figsize=(style.PRINT_WIDTH, panel_w * 1.11 * h / w + 1.6),
                             squeeze=False)
    colour = (cmap, norm, limit)
    for ax, (p, rows) in zip(axes[0], panels):
        _draw_panel(ax, p, rows, lanes, colour, size, (x0, x1, y0, y1))
    # Panels first, then the colour bar beside the last one at its height.
    fig.subplots_adjust(left=0.02, right=0.86, wspace=0.06)
    fig.canvas.draw()  # the panels' places, their aspect applied
    cax = _colour_bar(plt, fig, axes, norm, cmap, native)
    handles = _legend_handles(size, max_enc, cmap, norm)
    _title(fig, axes, cax, net, summary.get("provenance", {}))
    # The legend hugs the panels (their aspect is the net's, so the figure's
    # height is not theirs); savefig's tight box keeps what is drawn.
    bottom = min(ax.get_position().y0 for ax in axes[0])
    fig.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, bottom - 0.01),
               ncol=3, frameon=False, fontsize=style.FONT)
    path = os.path.join(out_dir, "network_map.png")
    return save(fig, path, bbox_inches="tight")


def _junction_rows(pols, nodes, native):
    """[(policy, [((x, y), encounters, change of queueing delay against
    sumo_native's, or the delay itself without it)])] per controller policy;
    [] when the run has none."""
    base = {j["junction"]: queueing_delay(j) for j in native.get("junctions", [])} if native else {}
    controllers = [p for p in pols if p != "sumo_native"]
    panels = []
    for p in controllers:
        rows = []
        for j in pols[p].get("junctions", []):
            if j["junction"] not in nodes:
                continue
            d = queueing_delay(j)
            b = base.get(j["junction"])
            change = (d - b) if (d is not None and b is not None) else (None if native else d)
            rows.append((nodes[j["junction"]], j.get("encounters", 0) or 0, change))
        panels.append((p, rows))
    return panels


def _draw_panel(ax, p, rows, lanes, colour, size, bounds):
    """One policy's panel: the lanes, its junctions (those without an
    encounter first, small), its title, north and a scale bar."""
    from matplotlib.collections import LineCollection
    cmap, norm, limit = colour
    x0, x1, y0, y1 = bounds
    w, h = max(x1 - x0, 1.0), max(y1 - y0, 1.0)
    ax.add_collection(LineCollection(lanes, colors="0.6", linewidths=0.4, zorder=1))
    none = [r for r in rows if r[1] == 0]
    some = sorted([r for r in rows if r[1] > 0], key=lambda r: -r[1])
    for group, edge in ((none, "0.45"), (some, "black")):
        if not group:
            continue
        cols = [cmap(norm(max(-limit, min(limit, c)))) if c is not None else (0.6, 0.6, 0.6, 1)
                for _, _, c in group]
        ax.scatter([q[0][0] for q in group], [q[0][1] for q in group],
                   s=[size(e) for _, e, _ in group], c=cols, edgecolors=edge,
                   linewidths=0.4 if group is none else 0.7, zorder=3 if group is none else 4,
                   gid=SIMULATED)
    label = style.policy_label(p)
    total = sum(e for _, e, _ in rows)
    ax.set_title("%s: %d AV-HV encounter%s\nat %d controlled junctions"
                 % (label, total, "" if total == 1 else "s", len(rows)),
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
    bar = nice_length(w)
    bx, by = x0, y0 - 0.05 * h
    ax.plot([bx, bx + bar], [by, by], color="black", lw=2.5, solid_capstyle="butt", zorder=4)
    ax.text(bx + bar / 2, by + 0.012 * h, ("%g km" % (bar / 1000)) if bar >= 1000 else "%g m" % bar,
            ha="center", va="bottom", fontsize=style.FONT)


def _colour_bar(plt, fig, axes, norm, cmap, native):
    """The colour bar beside the last panel, at its height; its axes."""
    last = axes[0][-1].get_position()
    # Each panel's place with its aspect applied (get_position applies it).
    min(ax.get_position().y0 for ax in axes[0])
    cax = fig.add_axes([last.x1 + 0.015, last.y0, 0.02, last.height])
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    sm.set_array([])
    cbar = fig.colorbar(sm, cax=cax, extend="both" if native else "max")
    cbar.set_label(("queueing delay against SUMO native (s per crossing vehicle)\n"
                    "red: slower, blue: faster") if native else
                   "queueing delay (s per crossing vehicle; no sumo_native in this run)",
                   fontsize=style.FONT)
    return cax


def _legend_handles(size, max_enc, cmap, norm):
    """The legend's markers: encounters by area, no encounter, no vehicle crossed."""
    from matplotlib.lines import Line2D
    ticks = sorted({1, nice_length(max_enc * 2.5) if max_enc >= 10 else 1, max_enc})
    handles = [Line2D([], [], ls="", marker="o", markersize=math.sqrt(size(t)), markerfacecolor="0.8",
                      markeredgecolor="black", label="%d encounter%s" % (t, "" if t == 1 else "s"))
               for t in ticks]
    handles.append(Line2D([], [], ls="", marker="o", markersize=math.sqrt(size(0)),
                          markerfacecolor=cmap(norm(0.0)), markeredgecolor="0.45",
                          label="no encounter"))
    handles.append(Line2D([], [], ls="", marker="o", markersize=math.sqrt(size(0)),
                          markerfacecolor=(0.6, 0.6, 0.6, 1), markeredgecolor="0.45",
                          label="no vehicle crossed"))
    return handles


def _title(fig, axes, cax, net, prov):
    """The figure's title above the panels' titles, inside the figure: the
    figure grows by the title's height."""
    from .figure import wrap_to
    title = wrap_to(fig, "Controlled junctions of %s: marker area by AV-HV encounters, colour by "
                    "the queueing delay on the approaches (Little's law: summed mean queue / "
                    "crossing rate), seed %s" % (os.path.basename(net), prov.get("seed")),
                    style.TITLE_FONT, style.PRINT_WIDTH - 0.2)
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
