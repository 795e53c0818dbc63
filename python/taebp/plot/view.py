"""The generic view of any sweep: x = a swept key, y = metrics (one panel
each), one line per policy (its colour), the other swept keys as line styles
(up to four combinations) or as panel columns (--by), intervals from the
replicates, theory a bar at the point where the policy has one, stalled runs ringed.
A key's values that are numbers make a numeric axis; others (a trust
distribution) are categories labelled by what they are. describe() gives
what a figure holds (axes, lines, point counts) for --describe."""

import itertools
import math
import os

from . import tidy
from .common import STALL_RING, PlotError, save, style

# The standard panels, in order; a metric without data in the sweep is left out.
STANDARD = ["collision_rate", "dc_rate", "served_flow", "time_loss_mean_av", "time_loss_mean_hv",
            "encounters_per_hour"]
# On a track without network measures: the figure-8's throughput and wait.
FALLBACK = {"served_flow": "throughput_all", "time_loss_mean_av": "wait_mean_av",
            "time_loss_mean_hv": "wait_mean_hv"}
TITLES = {
    "collision_rate": "collisions per AV-HV encounter (95 % CI)",
    "dc_rate": "DC per AV-HV encounter (95 % CI)",
    "served_flow": "served flow (veh/h)",
    "throughput_all": "crossings per hour",
    "time_loss_mean_av": "mean delay per AV trip (s)",
    "time_loss_mean_hv": "mean delay per HV trip (s)",
    "time_loss_mean": "mean delay per trip (s)",
    "wait_mean_av": "mean wait of a held AV (s)",
    "wait_mean_hv": "mean wait of a held HV (s)",
    "encounters_per_hour": "AV-HV encounters per hour",
}
DEMAND_KEYS = ("scenario.demand.flow", "scenario.routes_scale")
STYLES = ["-", "--", ":", "-."]


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


class View:
    def __init__(self, sweep, x, ys, by=None):
        self.sweep = sweep
        if x not in sweep.keys:
            raise cannot(sweep, "--x %s is not a swept key of this sweep" % x)
        bad = [y for y in ys if y not in tidy.metric_names(sweep)]
        if bad:
            raise cannot(sweep, "--y %s: not a metric of this sweep's aggregate.csv" % ", ".join(bad))
        ys = [y for y in ys if has_data(sweep, y)]
        if not ys:
            raise cannot(sweep, "no plot for the swept keys %s: none of the metrics asked for has "
                         "a value" % ", ".join(sweep.keys))
        if by is not None and (by not in sweep.keys or by == x):
            raise cannot(sweep, "--by %s is not another swept key" % by)
        self.x, self.ys, self.by = x, ys, by
        col = lambda k: [r.get(k) for r in sweep.rows]  # noqa: E731
        self.keys = {k: tidy.Key(k, col(k)) for k in sweep.keys}
        # Keys zipped with x on one sweep axis move with it: not a style.
        zipped = set()
        for axis in (sweep.info.get("axes", []) if isinstance(sweep.info, dict) else []):
            if x in axis.get("keys", []):
                zipped |= set(axis["keys"])
        others = [k for k in sweep.keys if k not in (x, by) and k not in zipped]
        combos = self._present(others)
        if by is None and len(combos) > len(STYLES):
            # Too many for line styles: the key with most values as panels.
            by = max(others, key=lambda k: len(self.keys[k].cells))
            self.by = by
            others = [k for k in others if k != by]
            combos = self._present(others)
        if len(combos) > len(STYLES):
            raise cannot(sweep, "swept keys %s give %d line styles (at most %d): choose --x and "
                         "--by" % (", ".join(others), len(combos), len(STYLES)))
        self.others, self.combos = others, combos
        self.facets = self.keys[by].cells if by else [None]

    def _present(self, keys):
        """The combinations of the keys' values that some row has, in sweep order."""
        combos = list(itertools.product(*[self.keys[k].cells for k in keys]))
        seen = {tuple(r.get(k) for k in keys) for r in self.sweep.rows}
        return [c for c in combos if c in seen]

    def file_name(self):
        return "sweep_%s.png" % self.x

    def combo_label(self, combo):
        return ", ".join("%s = %s" % (k, self.keys[k].label(c)) for k, c in zip(self.others, combo))

    def draw(self, plt, out_dir, name=None):
        sweep, xkey = self.sweep, self.keys[self.x]
        n_m, n_f = len(self.ys), len(self.facets)
        if n_f == 1:
            ncols = min(3, n_m)
            nrows = int(math.ceil(n_m / ncols))
            cells = [(i // ncols, i % ncols, m, None) for i, m in enumerate(self.ys)]
        else:
            ncols, nrows = n_f, n_m
            cells = [(i, j, m, f) for i, m in enumerate(self.ys) for j, f in enumerate(self.facets)]
        width = 4.4 * ncols + 0.6
        if not xkey.numeric:
            width += 0.5 * ncols * max(0, len(xkey.cells) - 2)
        fig, axes = plt.subplots(nrows, ncols, figsize=(width, 3.3 * nrows + 1.4), squeeze=False)
        used = set()
        self.description = {"file": name or self.file_name(), "view": "generic", "x": self.x,
                            "y": list(self.ys), "by": self.by, "styles": self.others,
                            "panels": []}
        theory_seen = stall_seen = False
        policies = sweep.policies
        for (i, j, metric, facet) in cells:
            ax = axes[i][j]
            used.add((i, j))
            panel = {"metric": metric, "facet": None if facet is None else
                     self.keys[self.by].label(facet), "lines": []}
            for p_i, policy in enumerate(policies):
                colour, plabel = style(policy, p_i)
                for s_i, combo in enumerate(self.combos):
                    pts = []
                    for r in sweep.rows:
                        if r["policy"] != policy:
                            continue
                        if facet is not None and r.get(self.by) != facet:
                            continue
                        if any(r.get(k) != c for k, c in zip(self.others, combo)):
                            continue
                        y, lo, hi, th = tidy.value_of(sweep, r, metric)
                        if y is None:
                            continue
                        st = tidy.number(r.get("stalled"))
                        pts.append((xkey.position(r.get(self.x)), y, lo, hi, th, st or 0,
                                    tidy.number(r.get("runs_ok")) or 0))
                    if not pts:
                        continue
                    pts.sort()
                    # Policies side by side, so that equal values (0) stay visible.
                    span = 1.0
                    if xkey.numeric and len(xkey.values) > 1:
                        span = float(max(xkey.values) - min(xkey.values)) * 0.1
                    dodge = (p_i - (len(policies) - 1) / 2) * 0.06 * span
                    xs = [p[0] + dodge for p in pts]
                    ys = [p[1] for p in pts]
                    err = [[max(0.0, p[1] - p[2]) if p[2] is not None else 0.0 for p in pts],
                           [max(0.0, p[3] - p[1]) if p[3] is not None else 0.0 for p in pts]]
                    ax.errorbar(xs, ys, yerr=err, fmt="o", ls=STYLES[s_i], color=colour, ms=4,
                                capsize=3, lw=1.4, label=plabel)
                    th = [(x, p[4]) for x, p in zip(xs, pts) if p[4] is not None]
                    if th:
                        theory_seen = True
                        # Theory: a bar across each point (no line: line styles
                        # belong to the other swept keys).
                        ax.plot([t[0] for t in th], [t[1] for t in th], ls="none", marker="_",
                                ms=16, mew=2.2, color=colour, alpha=0.75)
                    for x, p in zip(xs, pts):
                        if p[5] > 0:
                            stall_seen = True
                            ax.plot([x], [p[1]], zorder=5, **STALL_RING)
                            ax.annotate("%d/%d stalled" % (p[5], p[6]), (x, p[1]), xytext=(5, 4),
                                        textcoords="offset points", fontsize=6, color="red")
                    panel["lines"].append({"policy": policy, "style": self.combo_label(combo),
                                           "points": len(pts), "theory_points": len(th)})
            if metric == "served_flow" and self.x in DEMAND_KEYS:
                offered = {}
                for r in sweep.rows:
                    if facet is not None and r.get(self.by) != facet:
                        continue
                    o = tidy.number(r.get("offered_flow"))
                    if o is not None:
                        offered.setdefault(xkey.position(r.get(self.x)), []).append(o)
                if offered:
                    xs = sorted(offered)
                    ax.plot(xs, [sum(offered[x]) / len(offered[x]) for x in xs], ":", color="black",
                            lw=1, label="served = offered")
                    panel["offered_line"] = True
            ax.set_title(TITLES.get(metric, metric) + ("" if facet is None else "\n%s = %s" % (
                self.by, self.keys[self.by].label(facet))), fontsize=9)
            ax.set_ylabel(metric, fontsize=8)
            ax.set_xlabel(self.x, fontsize=8)
            if not xkey.numeric:
                ax.set_xticks(range(len(xkey.cells)))
                ax.set_xticklabels(xkey.labels, fontsize=7)
                ax.set_xlim(-0.5, len(xkey.cells) - 0.5)
            if metric.endswith("_rate"):
                ax.set_ylim(bottom=-0.02)
            else:
                ax.set_ylim(bottom=0)
            ax.grid(alpha=0.3)
            panel.update(xlabel=ax.get_xlabel(), ylabel=ax.get_ylabel(), title=ax.get_title())
            self.description["panels"].append(panel)
        for i in range(nrows):
            for j in range(ncols):
                if (i, j) not in used:
                    axes[i][j].set_visible(False)
        from matplotlib.lines import Line2D
        handles, labels = [], []
        for p_i, policy in enumerate(policies):
            if any(l["policy"] == policy for pan in self.description["panels"] for l in pan["lines"]):
                colour, plabel = style(policy, p_i)
                handles.append(Line2D([], [], color=colour, marker="o", lw=1.4))
                labels.append(plabel)
        if len(self.combos) > 1:
            for s_i, combo in enumerate(self.combos):
                handles.append(Line2D([], [], color="black", ls=STYLES[s_i], lw=1.4))
                labels.append(self.combo_label(combo))
        if theory_seen:
            handles.append(Line2D([], [], color="black", ls="none", marker="_", ms=16, mew=2.2))
            labels.append("theory (bar at the point)")
        if any(p.get("offered_line") for p in self.description["panels"]):
            handles.append(Line2D([], [], color="black", ls=":", lw=1))
            labels.append("served = offered")
        if stall_seen:
            handles.append(Line2D([], [], **STALL_RING))
            labels.append("a seed stalled (k/n)")
        # As many entries a row as fit the figure's width (about 7 characters an inch).
        longest = max([len(l) for l in labels] + [1])
        ncol = max(1, min(len(labels), int(fig.get_figwidth() * 7.5 / (longest + 6))))
        legend_rows = int(math.ceil(len(labels) / ncol))
        fig.legend(handles, labels, loc="lower center", ncol=ncol, frameon=False, fontsize=8)
        self.description["legend"] = labels
        ctx = sweep.context()
        title = "Against %s%s" % (self.x, (": " + ctx) if ctx else "")
        fig.suptitle(title, fontsize=10)
        bottom = min(0.35, (0.2 + 0.22 * legend_rows) / fig.get_figheight())
        fig.tight_layout(rect=(0, bottom, 1, 1 - 0.35 / fig.get_figheight()))
        path = os.path.join(out_dir, name or self.file_name())
        save(fig, path, dpi=110)
        plt.close(fig)
        return path


def default_views(sweep, keys):
    """The standard panels against each key in ``keys``."""
    metrics = standard_metrics(sweep)
    if not metrics:
        raise cannot(sweep, "no plot for the swept keys %s: no standard metric (%s) has a value"
                     % (", ".join(sweep.keys) or "(none)", ", ".join(STANDARD)))
    return [View(sweep, k, metrics) for k in keys]
