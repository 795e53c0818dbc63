"""The figures we ship (README, docs/img/): each a preset over the tidy core,
naming what to draw (x, y, by, which rows, the title) and the few marks a
study adds (theta*, the bound delta * lambda, the theory's region); figure.py
draws them all the same way.

Sweep presets are chosen by the swept keys (PRESETS: the keys each covers,
when it applies, what it draws); the keys no applying preset covers get the
generic view. Run presets (RUN_PRESETS) draw runs beyond the paper from
their time series, pooling only runs of one config (a sweep's point, or run
folders that differ only in their seed).

The presets are drawn by the modules next to this one: sweep_presets (the
shipped studies: trust, mismatch, penetration, network), beyond_presets
(noise, learners) and run_presets (learned, dynamic, influence); their
functions are importable from here too."""

from . import style, tidy  # noqa: F401 (as before the split)
from .beyond_presets import SAFE_COLLISIONS, learners, learners_frontier, noise  # noqa: F401
from .common import PlotError, die, number, warn  # noqa: F401
from .run_presets import (_experienced, dynamic, influence, influence_data,  # noqa: F401
                          influence_table, learned)
from .sweep_presets import mismatch, network, penetration, trust  # noqa: F401
from .view import Figure, Mark, Panel, SweepView  # noqa: F401


def _numeric(sweep, key):
    vals = [r.get(key) for r in sweep.rows]
    return bool(vals) and all(number(v) is not None for v in vals)


# name: (the swept keys it covers, applies(sweep, keys), draw(plt, sweep, theory, out) -> [paths])
PRESETS = {
    "mismatch": ({"model.trust", "model.assumed_trust"},
                 lambda s, k: {"model.trust", "model.assumed_trust"} <= k and
                 _numeric(s, "model.trust") and _numeric(s, "model.assumed_trust"),
                 mismatch),
    "trust": ({"model.trust"},
              lambda s, k: k == {"model.trust"} and _numeric(s, "model.trust"), trust),
    "penetration": ({"scenario.avs", "scenario.hvs"},
                    lambda s, k: bool(k & {"scenario.avs", "scenario.hvs"}) and
                    k <= {"scenario.avs", "scenario.hvs"}, penetration),
    "network": ({"scenario.demand.flow", "scenario.routes_scale", "scenario.av_share"},
                lambda s, k: bool(k & {"scenario.demand.flow", "scenario.routes_scale"}) and
                k <= {"scenario.demand.flow", "scenario.routes_scale", "scenario.av_share"},
                network),
    "noise": ({"model.noise.scale", "model.noise.design"},
              lambda s, k: "model.noise.scale" in k and
              k <= {"model.noise.scale", "model.noise.design"}, noise),
    "learners": ({"model.experience.forgetting", "model.experience.design"},
                 lambda s, k: "model.experience.forgetting" in k and
                 k <= {"model.experience.forgetting", "model.experience.design"} and
                 _numeric(s, "model.experience.forgetting"), learners),
}


def applying(sweep):
    """The presets whose keys match the sweep's, in PRESETS order."""
    keys = set(sweep.keys)
    return [name for name, (_, applies, _) in PRESETS.items() if applies(sweep, keys)]


def covered(names):
    out = set()
    for n in names:
        out |= PRESETS[n][0]
    return out


def draw(name, plt, sweep, theory, out):
    return PRESETS[name][2](plt, sweep, theory, out)


# name: (applies(runs), draw(plt, runs, out) -> [paths])
RUN_PRESETS = {
    "learned": (lambda runs: "ta_ebp_learned" in runs.policies, learned),
    "dynamic": (lambda runs: any((runs.config(i).get("model", {}) or {}).get("trust_dynamics")
                                 for i in range(len(runs.dirs))), dynamic),
    "influence": (_experienced, influence),
}
