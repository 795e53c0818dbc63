"""The data of network_map.png (presets.MAP): a network run's lanes, its
controlled junctions' places, AV-HV encounters and queueing delay (against
sumo_native's), the colour scale's limit and the scale bar's length.
Nothing here draws: figure_map.py does."""

import json
import math
import os

from .common import die


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


def map_data(run_dir):
    """What the map of a run draws, or None (not a network run, or no
    controller policy): lanes, panels [(policy, rows)], native (sumo_native
    ran: colours are changes against it), limit (the colour scale's end: the
    95th percentile of the changes), max_enc, bounds (x0, x1, y0, y1), bar
    (the scale bar, m), net (the network file's name), seed."""
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
    xs = [x for line in lanes for x, _ in line] or [x for x, _ in nodes.values()]
    ys = [y for line in lanes for _, y in line] or [y for _, y in nodes.values()]
    x0, x1 = min(xs), max(xs)
    return {"lanes": lanes, "panels": panels, "native": bool(native), "limit": limit,
            "max_enc": max([e for _, rows in panels for _, e, _ in rows] + [1]),
            "bounds": (x0, x1, min(ys), max(ys)), "bar": nice_length(max(x1 - x0, 1.0)),
            "net": os.path.basename(net),
            "seed": summary.get("provenance", {}).get("seed")}


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
