"""What every plot shares: the error tools/plot prints in one line, cells
read as numbers, matplotlib (headless), save() (which refuses a figure
without a simulated value and names a place it cannot write), the taebp
binary and the theory it computes."""

import concurrent.futures
import json
import math
import os
import shutil
import subprocess
import sys

# The marks of simulated values (artists carry it as their gid): save()
# writes a figure only when one of them has a finite point. Theory, reference
# lines and notes alone are never a figure.
SIMULATED = "simulated"


class PlotError(Exception):
    """What cannot be drawn or written, with the exit code tools/plot exits
    with (1: nothing to draw; 2: bad input or a place it cannot write)."""

    def __init__(self, message, code=1):
        super().__init__(message)
        self.code = code


def die(msg, code=1):
    raise PlotError(msg, code)


def warn(msg):
    print("tools/plot: warning: " + msg, file=sys.stderr)


def number(text):
    """A float, or None for an empty / non-numeric / non-finite cell."""
    if text is None:
        return None
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return float(text) if math.isfinite(text) else None
    text = str(text).strip()
    if text == "":
        return None
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def import_matplotlib():
    try:
        import matplotlib
    except ImportError:
        die("matplotlib is missing for %s: install the Debian package python3-matplotlib "
            "(tools/setup.sh does) or use Debian's /usr/bin/python3" % sys.executable)
    matplotlib.use("Agg")
    from . import style
    style.setup(matplotlib)
    import matplotlib.pyplot as plt
    return plt


def simulated_points(fig):
    """How many simulated values a figure draws: the finite points of its
    artists marked SIMULATED (points, seeds, curves, heat-map cells)."""
    import numpy as np
    n = 0
    for ax in fig.axes:
        for line in ax.get_lines():
            if line.get_gid() != SIMULATED:
                continue
            try:
                x = np.asarray(line.get_xdata(), dtype=float)
                y = np.asarray(line.get_ydata(), dtype=float)
                n += int(np.sum(np.isfinite(x) & np.isfinite(y)))
            except (TypeError, ValueError):
                n += len(line.get_xdata())
        for c in ax.collections:
            if c.get_gid() != SIMULATED:
                continue
            a = c.get_array()
            if a is not None:
                n += int(np.sum(np.isfinite(np.ma.filled(np.asarray(a, dtype=float), np.nan))))
            else:
                n += len(c.get_offsets())
    return n


def ensure_dir(out_dir):
    """The folder to write into, made if missing; a place that cannot be one
    (a file, no permission) is a PlotError in one line (exit 2)."""
    if os.path.exists(out_dir) and not os.path.isdir(out_dir):
        die("--out %s: not a folder (a file is in the way)" % out_dir, 2)
    try:
        os.makedirs(out_dir, exist_ok=True)
    except OSError as e:
        die("--out %s: cannot make the folder (%s)" % (out_dir, e.strerror or e), 2)
    if not os.access(out_dir, os.W_OK | os.X_OK):
        die("--out %s: cannot write there (permission denied)" % out_dir, 2)
    return out_dir


def save(fig, path, **kwargs):
    """fig.savefig(path) at the style's resolution, unless the figure draws no
    simulated value (PlotError: never a figure of theory alone, never an
    empty one); a file it cannot write is a PlotError naming it (exit 2)."""
    import matplotlib.pyplot as plt
    if simulated_points(fig) == 0:
        plt.close(fig)
        die("%s: no simulated value to draw (every point empty or failed); not written"
            % os.path.basename(path))
    try:
        fig.savefig(path, **kwargs)
    except OSError as e:
        die("%s: cannot write it (%s)" % (path, e.strerror or e), 2)
    finally:
        plt.close(fig)
    return path


# ------------------------------------------------------------------ taebp
PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # .../taebp


def find_taebp(explicit=None):
    """The taebp program: `explicit`, $TAEBP_BUILD_DIR/taebp, the build of the
    source tree this package is in (python/taebp -> build/taebp), the build
    tree this package was copied into (build/python/taebp -> build/taebp),
    then PATH; None when there is none."""
    if explicit:
        if not (os.path.isfile(explicit) and os.access(explicit, os.X_OK)):
            die("--taebp %s: not an executable" % explicit, 2)
        return explicit
    candidates = []
    if os.environ.get("TAEBP_BUILD_DIR"):
        candidates.append(os.path.join(os.environ["TAEBP_BUILD_DIR"], "taebp"))
    root = os.path.dirname(os.path.dirname(PACKAGE))
    candidates += [os.path.join(root, "build", "taebp"), os.path.join(root, "taebp")]
    for c in candidates:
        if os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    return shutil.which("taebp")


class Theory:
    """Dense theory curves from `taebp theory --json` (unavailable without
    the binary: the presets then draw the theory columns)."""

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
        for key, opt in (("s_max", "--s-max"), ("steepness", "--steepness"),
                         ("midpoint", "--midpoint")):
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
