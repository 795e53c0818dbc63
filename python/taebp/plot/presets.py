"""The figures we ship (README, docs/img/), each a preset: a declaration over
the tidy core (declare.py's vocabulary) naming what to draw (x, y, by, which
rows, the title) and the few marks a study adds (theta*, the bound delta *
lambda, the theory's region), with a data function for the study's own
numbers (sweep_data.py, run_data.py, netmap.py). The views (view.py,
view_heat.py, view_pairs.py, view_runs.py) turn every declaration into
panels of marks, and figure.py draws them all the same way (a network run's
map, MAP, in figure.py's map layout, figure_map.py): nothing here draws.

Sweep presets are chosen by the swept keys (PRESETS: the keys each covers,
when it applies, its data and figures); the keys no applying preset covers
get the generic view. Run presets (RUN_PRESETS) draw runs beyond the paper
from their time series, pooling only runs of one config (a sweep's point,
or run folders that differ only in their seed). Titles and units come from
the metric table, colours and labels from the policy table (style.py)."""

from . import netmap, run_data, sweep_data
from .common import number
from .declare import (Axes, From, Heat, Lines, Map, Pairs, Preset, Ref, Role, RunPreset, Series,
                      Variants, Zoom)
from .declare import draw as _draw, draw_map as _draw_map, draw_runs as _draw_runs
from .run_data import _experienced, influence_data, influence_table  # noqa: F401 (the API)


def _numeric(sweep, key):
    vals = [r.get(key) for r in sweep.rows]
    return bool(vals) and all(number(v) is not None for v in vals)


# ------------------------------------------------------------------ sweeps
TEAL = "#2a9d8f"  # the mismatch maps' reference lines (no policy's colour)
HEAT = dict(x="model.trust", y="model.assumed_trust", policy=From("policy"),
            region=From("predicted"), x_title=r"true HV trust $\theta$",
            y_title=r"trust $\hat{\theta}$ the AV designs for",
            region_label=r"theory: collisions ($\hat{\theta} > \theta$ and "
                         r"$\hat{\theta} \geq \theta^*$)",
            marks=[Ref("diagonal", colour=TEAL, ls=":", lw=1.4, simulated=False,
                       legend=r"$\hat{\theta} = \theta$"),
                   Ref("hline", From("theta_star"), colour=TEAL, ls="--", lw=1.4, simulated=False,
                       legend=lambda t: r"$\hat{\theta} = \theta^* = %.3g$" % t)],
            title="Trust mismatch{ctx}", ncols=1, panel_height=5.2,
            caption="Each cell: the rate over its seeds' encounters and its 95 % interval "
                    "(leading 0 dropped); grey: no value.")

NETWORK = dict(x=From("demand"), by=From("share"), select=From("select"),
               x_title=From("x_title"), facet_title="AV share {}")

NOISE_DESIGNS = {"aware": "noise-aware design s_δ", "paper": "the paper's s*"}
NOISE_MARKS = [
    Ref("special", From("at_zero"), colour="black", simulated=False,
        legend="σ = 0: the paper's result (both designs)"),
    Ref("hline", From("bound"), metrics=["collision_rate"], note=lambda v: " δλ = %g" % v,
        legend="the bound δλ", simulated=False),
    Ref("shade", From("gave_up"), legend="s_δ > s_max: the aware AV yields", simulated=False)]

# The collision rate a design may cost and still be called safe (issue 42's
# acceptance: at most 0.01 per encounter).
SAFE_COLLISIONS = 0.01

PRESETS = {
    "mismatch": Preset(
        {"model.trust", "model.assumed_trust"},
        lambda s, k: {"model.trust", "model.assumed_trust"} <= k and
        _numeric(s, "model.trust") and _numeric(s, "model.assumed_trust"),
        data=sweep_data.mismatch,
        figures=[Heat("mismatch_collision_heatmap.png", metric="collision_rate", cmap="magma_r",
                      **HEAT),
                 Heat("mismatch_dc_heatmap.png", metric="dc_rate", cmap="viridis", **HEAT)]),
    "trust": Preset(
        {"model.trust"}, lambda s, k: k == {"model.trust"} and _numeric(s, "model.trust"),
        data=sweep_data.trust,
        figures=[Lines("trust_dc_collision.png", x="model.trust", y=["dc_rate", "collision_rate"],
                       x_title="HV trust θ", theory=From("curve"), ncols=2,
                       marks=[Ref("vline", From("theta_star"), simulated=False)],
                       title="Trust sweep{ctx}")]),
    "penetration": Preset(
        {"scenario.avs", "scenario.hvs"},
        lambda s, k: bool(k & {"scenario.avs", "scenario.hvs"}) and
        k <= {"scenario.avs", "scenario.hvs"},
        data=sweep_data.penetration,
        figures=[Lines(
            "penetration_throughput.png", x="AV share", x_of=From("share"),
            y=["throughput_all", "throughput_av", "throughput_hv", "collision_rate", "wait_mean",
               "encounters_per_hour"],
            x_title="AV share avs / (avs + hvs)", variants=Variants(From("total"), "{} vehicles"),
            zero={"throughput_all": False, "throughput_av": True, "throughput_hv": True},
            title="AV penetration on {track} ({fleet}){ctx}",
            caption="Caveat: crossings per hour are this small track's ({fleet} on two short "
                    "loops; README, Penetration). TA-EBP's encounters take longer (the nudge, "
                    "the confirmation delay): a few per cent fewer crossings than No EBP; read "
                    "No Trust's throughput beside its collisions.")]),
    "network": Preset(
        {"scenario.demand.flow", "scenario.routes_scale", "scenario.av_share"},
        lambda s, k: bool(k & {"scenario.demand.flow", "scenario.routes_scale"}) and
        k <= {"scenario.demand.flow", "scenario.routes_scale", "scenario.av_share"},
        data=sweep_data.network,
        figures=[
            Lines("network_throughput.png", y=["served_share", "time_loss_mean",
                                               "encounters_per_hour"],
                  zero={"served_share": False},
                  marks=[Ref("hline", 1.0, metrics=["served_share"], ls=":", lw=1.0,
                             simulated=False, legend="served = offered (all the demand served)")],
                  title="Throughput and delay against demand: {place}",
                  caption="{note}SUMO native: SUMO's own junction logic, no controller.",
                  **NETWORK),
            Lines("network_delay_av_hv.png", when=From("av_hv"),
                  y=[("time_loss_mean_av", "time_loss_mean_hv"), ("wait_mean_av", "wait_mean_hv")],
                  pair_labels=["AVs", "HVs"],
                  metric_titles={("time_loss_mean_av", "time_loss_mean_hv"):
                                 "Delay per trip (SUMO's timeLoss)",
                                 ("wait_mean_av", "wait_mean_hv"):
                                 "Wait of a held vehicle at the line"},
                  title="AVs and HVs apart: {place}",
                  caption="{note}Delay: SUMO's timeLoss of every trip departed after the "
                          "warm-up, unfinished trips included; wait: vehicles the controller "
                          "held at a stop line.", **NETWORK)]),
    "noise": Preset(
        {"model.noise.scale", "model.noise.design"},
        lambda s, k: "model.noise.scale" in k and k <= {"model.noise.scale", "model.noise.design"},
        data=sweep_data.noise,
        figures=[Lines(
            "noise_sigma.png", x="model.noise.scale", y=["dc_rate", "collision_rate"],
            x_title="noise σ of the HV's reading (m)", theory=From("curve"), marks=NOISE_MARKS,
            variants=Variants(From("design_of"), NOISE_DESIGNS, order=lambda d: (d != "aware", d)),
            zoom=Zoom("collision_rate", select=From("aware"), label=NOISE_DESIGNS["aware"],
                      title="Collisions, noise-aware design (zoom)", ylim=From("zoom_ylim"),
                      when=From("has_aware")),
            xlim=From("xlim"), ncols=3, split=False,
            title="Perception noise ({kind}, δ = {delta:g}){ctx}")]),
    "learners": Preset(
        {"model.experience.forgetting", "model.experience.design"},
        lambda s, k: "model.experience.forgetting" in k and
        k <= {"model.experience.forgetting", "model.experience.design"} and
        _numeric(s, "model.experience.forgetting"),
        data=sweep_data.learners,
        figures=[
            Lines("influence_learners.png", x="model.experience.forgetting",
                  y=["dc_rate", "collision_rate"], by=From("design"),
                  x_title="the HVs' weight on their past ρ (1 = exact counts)",
                  facet_title="ta_ebp's design: {}", ncols=3, split=False,
                  title="Learners the AV is not told{ctx}"),
            Pairs("influence_learners_frontier.png", x="collision_rate", y="dc_rate",
                  facet="model.experience.forgetting", facet_order=lambda rho: -rho,
                  facet_title=lambda rho: "ρ = %g%s" % (rho, " (exact counts)" if rho == 1
                                                        else ""),
                  xlabel="collisions per encounter", ylabel="DC per encounter",
                  variant="model.experience.design", variant_policies=["ta_ebp"],
                  variant_label="ta_ebp's design: {}",
                  marks=[Ref("vline", SAFE_COLLISIONS, colour="black", ls=":",
                             legend="safe: at most %g collisions per encounter"
                             % SAFE_COLLISIONS)],
                  title="DC against collisions per learner{ctx}",
                  caption="Each point one policy pooled over the seeds (bars: DC's 95 % "
                          "interval clustered by HV and run); the safe frontier is the highest "
                          "point left of the dotted bound.")]),
}


# ------------------------------------------------------------------ runs
HOURS = "simulated time (h)"
POINTS = (dict(color="black", marker="o", ls="none", ms=4),)
SEEDS = [(dict(color="black", lw=0.7, alpha=0.35), "one seed")]
SEED = Role("curve", lw=0.7, alpha=0.35, simulated=True)  # one seed's curve, thin
REGRET = "cumulative expected regret"
ENCOUNTERS_LOG = "AV-HV encounters T (log scale)"
FIELD = "mean field (exact expected learning path)"

RUN_PRESETS = {
    "learned": RunPreset(lambda runs: "ta_ebp_learned" in runs.policies, figures=[
        Series("learned_rates{suffix}.png", data=run_data.learned_rates, ncols=2,
               title="Learned trust: {ctx}",
               panels=[Axes("dc", "DC per AV-HV encounter, per simulated hour", HOURS,
                            metric="dc_rate"),
                       Axes("coll", "Collisions per AV-HV encounter, per simulated hour", HOURS,
                            metric="collision_rate")],
               roles={"rate": Role("points", dodge=0.3),
                      "oracle": Role("curve", policy="colour", ls="--", lw=1.2, simulated=False,
                                     legend="the oracle's expected DC on the learner's "
                                            "encounters")},
               legend_extra=[POINTS + ("rate over the hour's encounters, 95 % interval "
                                       "clustered by HV and seed",)]),
        Series("learned_regret{suffix}.png", data=run_data.learned_regret, ncols=3,
               title="Learned trust, regret growth: {ctx}",
               caption=lambda d: ("%s: regret 0 (the oracle itself)." % d["zero"])
               if d["zero"] else "",
               panels=[Axes("learner", "TA-EBP learned: regret against the oracle",
                            ENCOUNTERS_LOG, REGRET, name="regret", xscale="log"),
                       Axes("every", "Every policy (log-log)", ENCOUNTERS_LOG, REGRET,
                            name="regret_all", xscale="log", yscale="log", zero=False),
                       Axes("fails", "TA-EBP learned: failures to persuade",
                            "nudges of TA-EBP learned (log scale)", "cumulative count",
                            name="failures", xscale="log")],
               roles={"seed": SEED, "mean": Role("curve", lw=1.8, simulated=True),
                      "failures": Role("step", lw=1.4, simulated=True),
                      "expected": Role("theory", policy=False, colour="black", ls="--", lw=1.2,
                                       legend="expected (Σ posterior failure probability)",
                                       simulated=False),
                      "budget": Role("theory", policy=False, colour="0.4", ls=":", lw=1.2,
                                     legend="δ × nudges (the budget)", simulated=False),
                      "linear": Role("theory", policy=False, colour="0.4", ls=":", lw=1.0,
                                     legend="∝ T (linear growth)", simulated=False)},
               legend_extra=SEEDS + [(dict(color="black", lw=1.8), "mean of the seeds")],
               extra_when=From("several"))]),
    "dynamic": RunPreset(lambda runs: any(
        (runs.config(i).get("model", {}) or {}).get("trust_dynamics")
        for i in range(len(runs.dirs))), figures=[
        Series("dynamic_trust{suffix}.png", data=run_data.dynamic, ncols=1, panel_height=3.4,
               title="Dynamic trust: {ctx}; w_s = {w_s:g}, w_f = {w_f:g}, ρ = {rho:g}, "
                     "α0+β0 = {strength:g}",
               panels=[Axes("trust", "Mean trust of the HVs in the network", HOURS, "mean trust",
                            name="mean_trust", ylim=(0, 1.05))],
               roles={"seed": SEED, "mean": Role("curve", lw=2.0, simulated=True),
                      "field": Role("theory", ls="--", lw=1.3, legend="mean field (theory)",
                                    simulated=False),
                      "long": Role("hline", ls=":", lw=1.4, legend="long-run trust (theory)",
                                   legend_colour="black", simulated=False)},
               legend_extra=SEEDS + [(dict(color="black", lw=2.0), "mean of the seeds")],
               extra_when=From("several"))]),
    "influence": RunPreset(_experienced, groups=False, figures=[
        Series("influence.png", data=run_data.influence, ncols=3,
               title="HVs who learn what a nudge meant: {ctx}; up to {runs} seeds per policy",
               panels=[Axes("a", "(a) DC, per {minutes} simulated minutes", HOURS,
                            metric="dc_rate", group="time"),
                       Axes("b", "(b) Collisions, per {minutes} simulated minutes", HOURS,
                            metric="collision_rate", group="time"),
                       Axes("c", "(c) DC by each HV's own encounter number",
                            "the HV's encounter number", metric="dc_rate",
                            name="dc_by_encounter", ylim=(0, 1.02))],
               roles={"rate": Role("points", ls="none"),
                      "first": Role("points", ls="none", ms=3),
                      "field": Role("theory", lw=1.4, legend=FIELD, simulated=False),
                      "long": Role("hline", ls="--", lw=0.8, simulated=False,
                                   legend="long-run theory (fixed point)",
                                   legend_colour="black")},
               variants=From("designs"),
               variant_labels={"guarded": "designed for each HV's experience (guarded)",
                               "paper": "the paper's scheme kept as it is"},
               legend_extra=[POINTS + ("SUMO, pooled over the runs (95 % interval clustered "
                                       "by HV and run)",)])]),
}


# A network run's map (a run folder of a network: served_flow among its results).
MAP = Map("network_map.png", data=netmap.map_data,
          panel_title=lambda label, n, junctions: "%s: %d AV-HV encounter%s\nat %d controlled "
          "junctions" % (label, n, "" if n == 1 else "s", junctions),
          cmap=("RdBu_r", "viridis"),
          colourbar=("queueing delay against SUMO native (s per crossing vehicle)\n"
                     "red: slower, blue: faster",
                     "queueing delay (s per crossing vehicle; no sumo_native in this run)"),
          title="Controlled junctions of {net}: marker area by AV-HV encounters, colour by the "
                "queueing delay on the approaches (Little's law: summed mean queue / crossing "
                "rate), seed {seed}")


# ------------------------------------------------------------------ the registry's API
def applying(sweep):
    """The presets whose keys match the sweep's, in PRESETS order."""
    keys = set(sweep.keys)
    return [name for name, p in PRESETS.items() if p.applies(sweep, keys)]


def covered(names):
    out = set()
    for n in names:
        out |= PRESETS[n].keys
    return out


def draw(name, plt, sweep, theory, out):
    return _draw(PRESETS[name], plt, sweep, theory, out)


def run_applies(name, runs):
    return RUN_PRESETS[name].applies(runs)


def draw_runs(name, plt, runs, out):
    return _draw_runs(RUN_PRESETS[name], plt, runs, out)


def draw_map(plt, run_dir, out):
    return _draw_map(MAP, plt, run_dir, out)
