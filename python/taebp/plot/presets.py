"""Presets: the figures we ship (README, docs/img/), each a named choice of
what to draw for a study's swept keys: which keys it covers, when it applies
and how it draws (the trust sweep's theory lines and theta*, the mismatch
heat map, ...). A sweep's keys that no applying preset covers are drawn by
the generic view (view.py)."""

from . import figure8, network, noise
from .common import number


def _numeric(sweep, key):
    vals = [r.get(key) for r in sweep.rows]
    return bool(vals) and all(number(v) is not None for v in vals)


def _has(sweep, metric):
    return any(number(r.get(metric)) is not None for r in sweep.rows)


# name: (the swept keys it covers, applies(sweep, keys), draw(plt, sweep, theory, out) -> [paths])
PRESETS = {
    "mismatch": (
        {"model.trust", "model.assumed_trust"},
        lambda s, k: {"model.trust", "model.assumed_trust"} <= k and _numeric(s, "model.trust")
        and _numeric(s, "model.assumed_trust"),
        lambda plt, s, th, out: [figure8.plot_mismatch(plt, s, th, out)]),
    "trust": (
        {"model.trust"},
        lambda s, k: k == {"model.trust"} and _numeric(s, "model.trust"),
        lambda plt, s, th, out: [figure8.plot_trust(plt, s, th, out)]),
    "penetration": (
        {"scenario.avs", "scenario.hvs"},
        lambda s, k: bool(k & {"scenario.avs", "scenario.hvs"}) and
        k <= {"scenario.avs", "scenario.hvs"},
        lambda plt, s, th, out: [figure8.plot_penetration(plt, s, out)]),
    "network": (
        {"scenario.demand.flow", "scenario.routes_scale", "scenario.av_share"},
        lambda s, k: bool(k & {"scenario.demand.flow", "scenario.routes_scale"}) and
        k <= {"scenario.demand.flow", "scenario.routes_scale", "scenario.av_share"},
        lambda plt, s, th, out: [network.plot_network(plt, s, out)] +
        ([network.plot_network_classes(plt, s, out)] if _has(s, "time_loss_mean_av") else [])),
    "noise": (
        {"model.noise.scale", "model.noise.design"},
        lambda s, k: "model.noise.scale" in k and k <= {"model.noise.scale", "model.noise.design"},
        lambda plt, s, th, out: [noise.plot_noise(plt, s, th, out)]),
}


def applying(sweep):
    """The presets whose keys this sweep swept, in PRESETS order."""
    keys = set(sweep.keys)
    return [name for name, (_, applies, _) in PRESETS.items() if applies(sweep, keys)]


def covered(names):
    out = set()
    for n in names:
        out |= PRESETS[n][0]
    return out


def draw(name, plt, sweep, theory, out_dir):
    return PRESETS[name][2](plt, sweep, theory, out_dir)
