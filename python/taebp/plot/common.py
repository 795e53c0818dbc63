"""What every plot shares: reading a sweep's aggregate.csv (Sweep), the
policies' colours and names, the stalled-run mark, the theory from the
taebp binary, and save(), which refuses to write a figure with nothing drawn."""

import concurrent.futures
import csv
import json
import math
import os
import shutil
import subprocess
import sys

from .. import stats  # noqa: F401  (re-exported: the one Wilson / t interval of the Python code)


class PlotError(Exception):
    """What tools/plot cannot draw, with its exit code (main prints it)."""

    def __init__(self, message, code=1):
        super().__init__(message)
        self.code = code


def die(msg, code=1):
    raise PlotError(msg, code)


def warn(msg):
    print("tools/plot: warning: " + msg, file=sys.stderr)


def import_matplotlib():
    try:
        import matplotlib
    except ImportError:
        die("matplotlib is missing for %s: install the Debian package python3-matplotlib "
            "(tools/setup.sh does)" % sys.executable)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def drawn(fig):
    """The number of data artists with at least one finite point across the
    figure's axes (lines, markers, bars, meshes, images)."""
    import numpy as np
    n = 0
    for ax in fig.axes:
        for line in ax.get_lines():
            x, y = line.get_xdata(), line.get_ydata()
            try:
                ok = np.isfinite(np.asarray(x, dtype=float)) & np.isfinite(np.asarray(y, dtype=float))
            except (TypeError, ValueError):
                ok = [True]
            if len(x) and np.any(ok):
                n += 1
        for c in ax.collections:
            if len(getattr(c, "get_offsets", lambda: [])()) or getattr(c, "get_array", lambda: None)() is not None:
                n += 1
        n += len(ax.images) + len([p for p in ax.patches if p.get_visible()])
    return n


def save(fig, path, **kwargs):
    """fig.savefig(path, **kwargs), unless nothing is drawn (then PlotError:
    never an empty figure)."""
    if drawn(fig) == 0:
        import matplotlib.pyplot as plt
        plt.close(fig)
        die("%s: nothing to draw (no data in any panel); not written" % os.path.basename(path))
    fig.savefig(path, **kwargs)


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

POLICY_COLOUR = {
    "sumo_native": "#000000",
    "no_ebp": "#7f7f7f",
    "no_trust": "#d62728",
    "ta_ebp": "#1f77b4",
    "full_reveal": "#2ca02c",
    "population_mean": "#ff7f0e",
    "ta_ebp_learned": "#9467bd",
    "always_nudge": "#17becf",
}
# name -> label ("TA-EBP"), from the one table of policies (`taebp policies
# --print json`, config/src/policies.cc); filled by load_policy_labels.
POLICY_LABEL = {}
EXTRA_COLOURS = ["#8c564b", "#e377c2", "#17becf", "#bcbd22"]


# --------------------------------------------------------------- reading
def number(text):
    """A float, or None for an empty / non-numeric cell."""
    if text is None:
        return None
    text = text.strip()
    if text == "":
        return None
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


class Sweep:
    def __init__(self, where):
        # A sweep directory, or an aggregate CSV file itself (e.g. a test fixture).
        if os.path.isfile(where):
            path, directory = where, os.path.dirname(where) or "."
        else:
            directory, path = where, os.path.join(where, "aggregate.csv")
        self.dir = directory
        if not os.path.isfile(path):
            die("%s: no aggregate.csv (is this the --out directory of `taebp sweep`?)" % directory)
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            self.header = reader.fieldnames or []
            self.rows = list(reader)
        for need in ("point", "policy"):
            if need not in self.header:
                die("%s: column '%s' is missing" % (path, need))
        a, b = self.header.index("point"), self.header.index("policy")
        self.keys = self.header[a + 1:b]
        self.info = {}
        info_path = os.path.join(directory, "sweep.json")
        if os.path.isfile(info_path):
            try:
                with open(info_path) as f:
                    self.info = json.load(f)
            except (OSError, ValueError) as e:
                warn("%s unreadable (%s): plotting without its context" % (info_path, e))
        self.config = self.info.get("config", {}) if isinstance(self.info, dict) else {}
        self.policies = []
        for r in self.rows:
            if r["policy"] not in self.policies:
                self.policies.append(r["policy"])

    def stalls(self):
        """{(point, policy): (stalled runs, runs)} from aggregate.csv's
        stalled (runs that stalled) and runs_ok (empty for older files without
        the column)."""
        out = {}
        for r in self.rows:
            k, n = number(r.get("stalled")), number(r.get("runs_ok"))
            if k is not None and n is not None:
                out[(int(r["point"]), r["policy"])] = (int(k), int(n))
        return out

    def model(self, key, default=None):
        return self.config.get("model", {}).get(key, default)

    def scenario(self, key, default=None):
        return self.config.get("scenario", {}).get(key, default)

    def context(self):
        """One line: the fixed parameters and the sample behind each point."""
        parts = []
        lam, r = self.model("prior_go"), self.model("collision_penalty")
        if lam is not None and "model.prior_go" not in self.keys:
            parts.append("λ = %g" % lam)
        if r is not None and "model.collision_penalty" not in self.keys:
            parts.append("r = %g" % r)
        if "model.trust" not in self.keys and isinstance(self.model("trust"), (int, float)):
            parts.append("θ = %g" % self.model("trust"))
        avs, hvs = self.scenario("avs"), self.scenario("hvs")
        if avs is not None and self.scenario("kind", "figure8") != "network" and not any(
                k.startswith("scenario.avs") or k.startswith("scenario.hvs") for k in self.keys):
            parts.append("%d AVs + %d HVs" % (avs, hvs))
        dur, reps = self.scenario("duration"), self.info.get("replicates") if isinstance(self.info, dict) else None
        if dur is not None:
            parts.append("%g s × %s seed%s per point" % (dur, reps if reps else "?",
                                                      "" if reps == 1 else "s"))
        return ", ".join(parts)


def load_policy_labels(binary):
    """The policies' labels from `taebp policies --print json`; without a
    binary the plots label policies by their names (and say so)."""
    if binary is None:
        warn("no taebp binary found: policies labelled by their names")
        return
    out = subprocess.run([binary, "policies", "--print", "json"], capture_output=True, text=True)
    if out.returncode != 0:
        warn("%s policies failed (%s): policies labelled by their names"
             % (binary, out.stderr.strip()))
        return
    POLICY_LABEL.update({row["name"]: row["label"] for row in json.loads(out.stdout)})


def style(policy, i):
    """(colour, label) of a policy."""
    colour = POLICY_COLOUR.get(policy) or EXTRA_COLOURS[i % len(EXTRA_COLOURS)]
    return colour, POLICY_LABEL.get(policy, policy)


# --------------------------------------------------------------- theory
class Theory:
    """Dense theory curves from `taebp theory --json` (None when unavailable)."""

    def __init__(self, binary, sweep):
        self.binary = binary
        self.sweep = sweep
        self.cache = {}

    def available(self):
        return self.binary is not None

    def args(self, theta, assumed=None, extra=()):
        s = self.sweep
        lik = s.model("likelihood", {}) or {}
        cmd = [self.binary, "theory", "--json", "--trust", repr(float(theta))]
        if s.model("prior_go") is not None:
            cmd += ["--prior", repr(float(s.model("prior_go")))]
        if s.model("collision_penalty") is not None:
            cmd += ["--penalty", repr(float(s.model("collision_penalty")))]
        if lik.get("type"):
            cmd += ["--likelihood", str(lik["type"])]
        for key, opt in (("s_max", "--s-max"), ("steepness", "--steepness"), ("midpoint", "--midpoint")):
            if lik.get(key) is not None:
                cmd += [opt, repr(float(lik[key]))]
        if assumed is not None:
            cmd += ["--assumed-trust", repr(float(assumed))]
        return cmd + list(extra)

    def one(self, theta, assumed=None, extra=()):
        key = (round(theta, 12), None if assumed is None else round(assumed, 12), tuple(extra))
        if key not in self.cache:
            out = subprocess.run(self.args(theta, assumed, extra), capture_output=True, text=True)
            if out.returncode != 0:
                raise RuntimeError("%s: %s" % (" ".join(self.args(theta, assumed, extra)),
                                               out.stderr.strip()))
            self.cache[key] = json.loads(out.stdout)
        return self.cache[key]

    def many(self, pairs):
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(2, os.cpu_count() or 2)) as pool:
            return list(pool.map(lambda p: self.one(*p), pairs))


def find_taebp(explicit):
    if explicit:
        if not (os.path.isfile(explicit) and os.access(explicit, os.X_OK)):
            die("--taebp %s: not an executable" % explicit, 2)
        return explicit
    candidates = []
    if os.environ.get("TAEBP_BUILD_DIR"):
        candidates.append(os.path.join(os.environ["TAEBP_BUILD_DIR"], "taebp"))
    candidates.append(os.path.join(ROOT, "build", "taebp"))
    for c in candidates:
        if os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    return shutil.which("taebp")


STALL_RING = dict(ls="", marker="o", ms=11, mfc="none", mec="red", mew=1.6)


def mark_stalled(ax, x, y, stalled, note=None, va="baseline"):
    ax.plot([x], [y], zorder=5, **STALL_RING)
    if note is not None:
        ax.annotate("%d/%d stalled" % stalled, (x, y), xytext=note, textcoords="offset points",
                    fontsize=7, color="red", va=va)


def add_stall_legend(handles, labels):
    from matplotlib.lines import Line2D
    handles.append(Line2D([], [], **STALL_RING))
    labels.append("a seed stalled (k/n)")
