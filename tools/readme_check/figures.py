"""FIGURES: every figure of the pages, by tier (fast, sweeps, studies, beyond,
timings, bench)."""

import re

from .beyond import (beyond_picture, dynamic_values, learned_values, learners_k_values,
                     learners_picture, learners_values, noise_values, noisy_values, robust_values)
from .commands import (BEYOND_PLOT, BOLOGNA, CITY, CITY_MAP_PLOT, CITY_MAP_RUN, DYNAMIC, EFF_F8,
                       EFF_GRID, EFF_GRID_PLOT, GRID, GRID_PLOT, JUNCTION_SNAPSHOT, LEARNED,
                       LEARNERS, LEARNERS_K, LEARNERS_PLOT, NOISE, NOISY, OSM, PAIRED_SSM, PAPER,
                       PEN110, PLOT, POOLED40, ROBUST, SEEDS, SNAPSHOT, SOLVE_AVHV,
                       SOLVE_PROSECUTOR, SSM_GRID, SSM_TWELVE, STOP17, SWEEP, THEORY, THEORY_ALL,
                       THEORY_NO_TRUST, THEORY_TWO, TWO_WAY, TWO_WAY_PLOT)
from .fast import (network_map, newcomer, snapshot_caption, snapshot_picture, solve_values, stop17,
                   table_markdown, table_notes, table_printout, theory_block, theory_numbers)
from .figure import Figure
from .ssm import bologna_values, paired_ssm_values, ssm_grid_values, ssm_twelve_values
from .static import (bench_targets, dependencies, five_steps, layout_configs, readme_links,
                     times_consistent)
from .studies import (city_map, city_values, efficiency_figure8_values, efficiency_grid_values,
                      efficiency_picture, efficiency_values, grid_picture, osm_values, pooled40,
                      theory_values, town_study, two_way_picture)
from .sweeps import mismatch_sweep, penetration_sweep, plot_picture, pooled_sizes, trust_sweep
from .timings import (bench, junction_snapshot_time, newcomer_time, run_time, snapshot_time,
                      sweep_times)


FIGURES = [
    # ---- fast
    Figure("Table I printout", "fast",
           r"`build/taebp run configs/paper\.yaml`, which prints\s+\(and writes to `results/paper/`\):\n\n```\n(?P<block>.*?)\n```",
           [PAPER], table_printout),
    Figure("Table I, markdown", "fast",
           r"\| collision rate \| No EBP \| [^|]+ \| [^|]+ \| (?P<no_ebp_collision>[^|]+?) \|\n"
           r"\| DC rate \| No EBP \| [^|]+ \| [^|]+ \| (?P<no_ebp_dc>[^|]+?) \|\n"
           r"\| collision rate \| No Trust \| [^|]+ \| (?P<no_trust_th>[\d.]+) [^|]+ \| (?P<no_trust_collision>[^|]+?) \|\n"
           r"\| DC rate \| No Trust \| [^|]+ \| [^|]+ \| (?P<no_trust_dc>[^|]+?) \|\n"
           r"\| collision rate \| TA-EBP \| [^|]+ \| [^|]+ \| (?P<ta_ebp_collision>[^|]+?) \|\n"
           r"\| DC rate \| TA-EBP \| [^|]+ \| (?P<ta_ebp_th>[\d.]+) [^|]+ \| (?P<ta_ebp_dc>[^|]+?) \|",
           [PAPER], table_markdown),
    Figure("Table I notes: interval width, seed 1's nudges, seeds 2-5", "fast",
           r"Each\s+interval is under ±(?P<width>[\d.]+) wide.*?nudge on (?P<nudge_share>[\d.]+) % of the first\s+"
           r"(?P<encounters>\d+) encounters.*?seeds 2–5 give (?P<seeds>[\d., ]+?), every\s+interval\s+"
           r"containing (?P<containing>[\d.]+)",
           [PAPER, SEEDS], table_notes),
    Figure("stop distance 1.7: collision rates and printout", "fast",
           r"SUMO reports (?P<no_trust>[\d.]+) collisions per encounter\s+for No Trust and "
           r"(?P<ta_ebp>[\d.]+) for TA-EBP.*?```\n\$ " + re.escape(STOP17) + r"\n(?P<block>.*?)\n```",
           [STOP17], stop17),
    Figure("theory worked example", "fast",
           r"```sh\n\$ " + re.escape(THEORY) + r"\n(?P<block>.*?)\n\$ ", [THEORY], theory_block),
    Figure("nudges s* and s-hat", "fast",
           r"paper \(s\* = (?P<s_star>[\d.]+) m, ŝ = (?P<s_hat>[\d.]+) m\)",
           [THEORY_NO_TRUST], theory_numbers),
    Figure("LP: AV-HV and prosecutor", "fast",
           re.escape("`" + SOLVE_AVHV + "`") + r" finds the same (?P<lp_dc>[\d.]+) by LP.*?the textbook "
           r"(?P<prosecutor>[\d.]+) with π\(convict\|innocent\) = (?P<convict>[\d/]+)",
           [SOLVE_AVHV, SOLVE_PROSECUTOR], solve_values),
    Figure("your own network, step by step", "fast",
           r"## Your own network, step by step.*?```sh\n(?P<block>.*?)```.*?writes (?P<trips>\d+) trips"
           r".*?No EBP formed (?P<no_ebp>\d+) encounters and TA-EBP (?P<ta>\d+), with a DC rate of "
           r"(?P<dc>[0-9.]+) against the theory's (?P<th>[0-9.]+); the network served "
           r"(?P<native_flow>\d+) veh/h under SUMO's own logic and (?P<ta_flow>\d+) under TA-EBP"
           r".*?at the line \(s\):\n\n```\n(?P<printed>.*?)\n```",
           [], newcomer),
    Figure("README's five steps are Getting started's commands", "fast",
           r"## Your own network in five steps\n\n```sh\n(?P<block>.*?)```", [], five_steps, page="README.md"),
    Figure("README's links resolve", "fast",
           r"## Where each question is answered\n\n(?P<table>(?:\|.*\n)+)", [], readme_links, page="README.md"),
    Figure("snapshot caption", "fast",
           r"t = 20 s: AV `(?P<av>\w+)` \(yellow\) has nudged (?P<nudge>[\d.]+) m\s+towards the centre and "
           r"(?P<stays>stays there|goes); HV `(?P<hv>\w+)` \(green\) read the nudge and (?P<hv_action>chose to [a-z ]+)",
           [PAPER], snapshot_caption),
    Figure("snapshot picture and its size", "fast",
           r"!\[[^\]]*\]\((?P<picture>docs/img/figure8\.png)\).*?the view is about (?P<view>\d+ x \d+) pixels.*?"
           r"picture is (?P<size>\d+ x \d+) pixels",
           [SNAPSHOT], snapshot_picture),
    Figure("network map", "fast",
           r"#+ A map of a network run.*?```sh\n(?P<block>.*?)```\s*!\[[^\]]*\]\((?P<picture>docs/img/network_map\.png)\)"
           r".*?No EBP formed (?P<no_ebp>\d+) encounters and TA-EBP (?P<ta>\d+)\.",
           [], network_map),
    Figure("sweep times: README = configs' comments", "fast",
           r"The three shipped studies \(about (?P<trust>\d+), (?P<mismatch>\d+) and (?P<penetration>\d+) s",
           [], times_consistent),
    Figure("dependency table = tools/setup.sh's packages", "fast",
           r"\| package \| why \|\n\|---\|---\|\n(?P<table>(?:\|.*\n)+)", [], dependencies),
    Figure("layout names every config", "fast", r"\nconfigs/ (?P<configs>.*?)\ntests/", [], layout_configs),
    Figure("bench targets = tools/bench's", "fast",
           r"target: median ratio ≤ (?P<overhead>[\d.]+) for every policy.*?"
           r"Controller overhead on a network\*\* \(target: median ratio ≤ (?P<grid>[\d.]+).*?"
           r"Controller overhead on a city\*\* \(target: median ratio ≤ (?P<osm>[\d.]+).*?"
           r"target: best-of ratio ≤ (?P<sweep>[\d.]+)",
           [], bench_targets),
    # ---- sweeps
    Figure("trust sweep", "sweeps",
           r"(?P<enc>\d+–\d+)\s+encounters per point and policy\)\. TA-EBP's DC rate follows .*?theory\s+"
           r"inside every interval \((?P<inside>\d+ of \d+) point-policy pairs.*?it has (?P<ta_zero>zero)\s+collisions at\s+"
           r"every θ.*?\(e\.g\. (?P<dc6>[\d.]+) vs (?P<th6>[\d.]+) at θ = 0\.6\).*?\(Go on (?P<go>[\d.]+) % of the study's encounters",
           [SWEEP["trust"]], trust_sweep),
    Figure("trust sweep picture", "sweeps", r"!\[Trust sweep\]\((?P<picture>docs/img/trust_dc_collision\.png)\)",
           [SWEEP["trust"], PLOT["trust"]], plot_picture("trust", "trust_dc_collision.png")),
    Figure("mismatch sweep", "sweeps", r"and none anywhere else \((?P<hit>\d+ of \d+) and (?P<clean>\d+ of \d+) cells\)",
           [SWEEP["mismatch"]], mismatch_sweep),
    Figure("mismatch sweep picture", "sweeps",
           r"!\[Trust mismatch\]\((?P<picture>docs/img/mismatch_collision_heatmap\.png)\)",
           [SWEEP["mismatch"], PLOT["mismatch"]], plot_picture("mismatch", "mismatch_collision_heatmap.png")),
    Figure("mismatch sweep picture, DC", "sweeps",
           r"!\[Trust mismatch, DC\]\((?P<picture>docs/img/mismatch_dc_heatmap\.png)\)",
           [SWEEP["mismatch"], PLOT["mismatch"]], plot_picture("mismatch", "mismatch_dc_heatmap.png")),
    Figure("penetration sweep", "sweeps",
           r"with (?P<teleports>no teleport) and no stall \(the longest time without a crossing is (?P<gap>[\d.]+) s\)\. "
           r"With No EBP the centre serves (?P<no_ebp_all>\d+–\d+) crossings an hour.*?TA-EBP serves "
           r"(?P<ta>\d+–\d+) crossings an hour at the unbalanced mixes \(No Trust (?P<nt>\d+–\d+), No EBP "
           r"(?P<ne>\d+–\d+)\).*?gives (?P<ta80>\d+) \(TA-EBP\) and (?P<nt80>\d+) \(No Trust\) crossings an hour "
           r"on 80 m loops and (?P<ta110>\d+) and (?P<nt110>\d+) with 110 m loops",
           [SWEEP["penetration"], PEN110], penetration_sweep),
    Figure("penetration sweep picture", "sweeps",
           r"!\[AV penetration\]\((?P<picture>docs/img/penetration_throughput\.png)\)",
           [SWEEP["penetration"], PLOT["penetration"]], plot_picture("penetration", "penetration_throughput.png")),
    Figure("pooled encounters.csv sizes", "sweeps", r"the shipped studies' are under (?P<mb>\d+) MB each",
           list(SWEEP.values()), pooled_sizes),
    # ---- studies (on demand: tools/readme-check --tier studies)
    Figure("Table I pooled over 40 seeds", "studies",
           r"\| No EBP \| (?P<ne_enc>\d+) \| (?P<ne_coll>[^|]+?) \| (?P<ne_dc>[^|]+?) \| [^|]+ \|\n"
           r"\| No Trust \| (?P<nt_enc>\d+) \| (?P<nt_coll>[^|]+?) \| (?P<nt_dc>[^|]+?) \| [^|]+ \|\n"
           r"\| TA-EBP \| (?P<ta_enc>\d+) \| (?P<ta_coll>[^|]+?) \| (?P<ta_dc>[^|]+?) \| [^|]+ \|\n\n"
           r"(?P<inside>every theory value inside its interval)",
           [POOLED40], pooled40),
    Figure("influence: learners the AV is not told, the study", "studies",
           r"<!-- learners -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*).*?The mean field agrees with every rate "
           r"it models \(within (?P<within>[\d.]+) for DC and collisions\)", [LEARNERS], learners_values,
           page="docs/influence.md"),
    Figure("influence: learners of different k", "studies",
           r"<!-- learners-k -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)", [LEARNERS_K], learners_k_values,
           page="docs/influence.md"),
    Figure("influence: noisy learners", "studies",
           r"<!-- learners-noise -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)", list(NOISY.values()), noisy_values,
           page="docs/influence.md"),
    Figure("influence: learners study picture", "studies",
           r"!\[Learners the AV is not told\]\((?P<picture>img/influence_learners\.png)\)",
           [LEARNERS, LEARNERS_PLOT], learners_picture("influence_learners.png"), page="docs/influence.md"),
    Figure("influence: learners frontier picture", "studies",
           r"!\[DC against collisions per learner\]\((?P<picture>img/influence_learners_frontier\.png)\)",
           [LEARNERS, LEARNERS_PLOT], learners_picture("influence_learners_frontier.png"),
           page="docs/influence.md"),
    # ---- beyond (opt-in: about 5 minutes on 2 cores)
    Figure("learned trust: table, last hour, failures, regret", "beyond",
           r"<!-- learned -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*).*?reaches (?P<ratio>\d+) % of the oracle's.*?"
           r"(?P<failures>\d+) nudges failed to persuade \(its posterior expected (?P<expected>[\d.]+)\), "
           r"(?P<probes>\d+) of them.*?R\(100\) = (?P<r100>\d+), R\(1000\) = (?P<r1000>\d+), "
           r"R\(3000\) = (?P<r3000>\d+) and R\((?P<tend>\d+)\) = (?P<rend>\d+)",
           [LEARNED], learned_values),
    Figure("learned trust rates picture", "beyond",
           r"!\[Learned trust, rates\]\((?P<picture>docs/img/learned_rates\.png)\)",
           [LEARNED, BEYOND_PLOT["learned"]], beyond_picture("learned", "learned_rates.png")),
    Figure("learned trust regret picture", "beyond",
           r"!\[Learned trust, regret\]\((?P<picture>docs/img/learned_regret\.png)\)",
           [LEARNED, BEYOND_PLOT["learned"]], beyond_picture("learned", "learned_regret.png")),
    Figure("influence: the robust design against HVs who forget", "beyond",
           r"<!-- robust -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*).*?DC (?P<gap>[\d.]+) above full revelation's",
           [ROBUST], robust_values, page="docs/influence.md"),
    Figure("dynamic trust: table", "beyond", r"<!-- dynamic -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)", [DYNAMIC], dynamic_values),
    Figure("dynamic trust picture", "beyond",
           r"!\[Dynamic trust\]\((?P<picture>docs/img/dynamic_trust\.png)\)",
           [DYNAMIC, BEYOND_PLOT["dynamic"]], beyond_picture("dynamic", "dynamic_trust.png")),
    Figure("noise sweep: table", "beyond",
           r"<!-- noise -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*).*?the bound δλ = 0\.002 lies inside or above the interval at "
           r"(?P<within>\d+ of \d+) σ",
           [NOISE], noise_values),
    Figure("noise sweep picture", "beyond",
           r"!\[Perception noise\]\((?P<picture>docs/img/noise_sigma\.png)\)",
           [NOISE, BEYOND_PLOT["noise"]], beyond_picture("noise", "noise_sigma.png")),
    Figure("all-way grid: theory per encounter", "studies",
           r"<!-- theory-all-way -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)\n\n(?P<inside>Every theory value lies inside its interval)"
           r"[^<]*?Of No Trust's (?P<both>\d+) pairs where the AV went and the HV drove recklessly, (?P<coll>\d+) collided in SUMO",
           [THEORY_ALL], theory_values("theory_all_way", THEORY_ALL)),
    Figure("two-way grid: theory per encounter", "studies",
           r"<!-- theory-two-way -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)\n\n(?P<inside>Every theory value lies inside its interval)"
           r"[^<]*?Of No Trust's (?P<both>\d+) pairs where the AV went and the HV drove recklessly, (?P<coll>\d+) collided in SUMO",
           [THEORY_TWO], theory_values("theory_two_way", THEORY_TWO)),
    Figure("all-way grid: efficiency at AV share 0.5", "studies",
           r"<!-- efficiency-all-way -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)\n\nStalled runs in the all-way study: (?P<stalled>\d+)\.",
           [GRID], efficiency_values("grid_throughput", GRID)),
    Figure("two-way grid: efficiency at AV share 0.5", "studies",
           r"<!-- efficiency-two-way -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)\n\nStalled runs in the two-way study: (?P<stalled>\d+)\. "
           r"Game moves that hit a third vehicle, over the whole study: (?P<game_move>[^\n]*?\))\.",
           [TWO_WAY], efficiency_values("grid_two_way", TWO_WAY)),
    Figure("grid study picture", "studies",
           r"!\[Throughput against demand\]\((?P<picture>docs/img/network_throughput\.png)\)",
           [GRID, GRID_PLOT], grid_picture),
    Figure("two-way grid study picture", "studies",
           r"!\[Throughput against demand, two-way stops\]\((?P<picture>docs/img/network_throughput_two_way\.png)\)",
           [TWO_WAY, TWO_WAY_PLOT], two_way_picture),
    Figure("city study", "studies",
           r"<!-- city-study -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)\n\nOver (?P<seeds>[0-9-]+) seeds; "
           r"every measured rate's theory is (?P<verdict>inside its 99\.9 % interval)\. "
           r"Game moves that hit a third vehicle: (?P<game_move>[^\n]*?\))\.",
           [CITY], city_values),
    Figure("city study map", "studies",
           r"!\[[^\]]*\]\((?P<picture>docs/img/city_map\.png)\).*?seed 1's TA-EBP run formed (?P<ta>\d+) "
           r"encounters at (?P<junctions>\d+) junctions",
           [CITY_MAP_RUN, CITY_MAP_PLOT], city_map),
    Figure("ssm grid study", "studies",
           r"<!-- ssm-grid -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)\n\n"
           r"Runs lost to SUMO's assertion: (?P<lost>\d+) of (?P<total>\d+)\. "
           r"No Trust minus TA-EBP, the network's conflicts per hour, the same seed's runs paired, mean over "
           r"(?P<pairs>\d+) seeds \[98\.75 % interval: 95 % Bonferroni-corrected for the 4 measures\]: "
           r"(?P<diff>[^\n]*)\. The measures whose interval excludes 0: (?P<above>[^\n.]*)\.\n\n"
           r"No Trust minus TA-EBP, the near misses per game without a collision \(each run's own games, not paired; "
           r"MOVER interval from the clustered ones, 98\.75 %: Bonferroni for the 4 measures\): (?P<near>[^\n]*)\. "
           r"The measures whose interval excludes 0: (?P<nabove>[^\n.]*)\.",
           [SSM_GRID], ssm_grid_values, page="docs/ssm.md", failed_tasks=True),
    Figure("ssm twelve runs", "studies",
           r"seeds 1, 3, 8 and 22 under `sumo_native`, No Trust and TA-EBP, each alone, the device on: "
           r"(?P<ended>\d+) of 12 runs end at 1200 s, (?P<lost>\d+) lost",
           [SSM_TWELVE], ssm_twelve_values, page="docs/ssm.md"),
    Figure("paired pair measures against the SSM device", "studies",
           r"PET, which needs no extrapolation, agrees with the device's: on (?P<pet_n>\d+) games "
           r"the two PETs differ by (?P<pet_median>[\d.]+) s at the median, (?P<pet_p90>[\d.]+) s at "
           r"the 90th percentile and (?P<pet_max>[\d.]+) s at most; the TTCs of (?P<ttc_n>\d+) games by "
           r"(?P<ttc_median>[\d.]+) s at the median",
           [PAIRED_SSM], paired_ssm_values, page="docs/paired.md"),
    Figure("bologna study", "studies",
           r"<!-- bologna-meetings -->\n(?P<meetings>\|[^\n]*(?:\n\|[^\n]*)*)\n\n"
           r"<!-- bologna-flow -->\n(?P<flow>\|[^\n]*(?:\n\|[^\n]*)*)\n\nOver (?P<seeds>[0-9-]+) seeds\.",
           [BOLOGNA], bologna_values, page="docs/bologna.md", failed_tasks=True),
    Figure("efficiency study: grid", "studies",
           r"<!-- efficiency-study-grid -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)\n\n"
           r"TA-EBP minus No EBP, the same seed's runs paired, mean over (?P<seeds>[\d-]+) seeds \[95 % interval\]:\n\n"
           r"<!-- efficiency-study-grid-diff -->\n(?P<diff>\|[^\n]*(?:\n\|[^\n]*)*)\n\n"
           r"Stalled runs: (?P<stalled>\d+)\. (?P<flow_verdict>Every served-flow interval holds 0)",
           [EFF_GRID], efficiency_grid_values),
    Figure("efficiency study: grid picture", "studies",
           r"!\[Efficiency study, grid\]\((?P<picture>docs/img/efficiency_grid\.png)\)",
           [EFF_GRID, EFF_GRID_PLOT], efficiency_picture),
    Figure("efficiency study: figure-8", "studies",
           r"<!-- efficiency-study-figure8 -->\n(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)\n\n"
           r"[^<]*<!-- efficiency-study-figure8-diff -->\n(?P<diff>\|[^\n]*(?:\n\|[^\n]*)*)",
           [EFF_F8], efficiency_figure8_values),
    Figure("town study: any sweep plotted", "studies",
           r"<!-- town study -->\n```sh\n(?P<block>.*?)```\s*!\[A town study\]\((?P<picture>docs/img/town_av_share\.png)\)",
           [], town_study),
    Figure("OSM example", "studies",
           r"runs 20 simulated minutes per policy to the end (?P<clean>with no teleport and no stall):\n\n"
           r"(?P<table>\|[^\n]*(?:\n\|[^\n]*)*)",
           [OSM], osm_values),
    # ---- timings
    Figure("sweep wall times", "timings",
           r"The three shipped studies \(about (?P<trust>\d+), (?P<mismatch>\d+) and (?P<penetration>\d+) s",
           list(SWEEP.values()), sweep_times),
    Figure("Table I run time", "timings", r"then reproduces the paper's Table I in SUMO \(~(?P<run>\d+) s\)",
           [PAPER], run_time),
    Figure("snapshot time", "timings", r"It takes about (?P<snap>\d+) s\. sumo-gui writes the picture", [SNAPSHOT], snapshot_time),
    Figure("your own network, step by step: time", "timings",
           r"## Your own network, step by step.*?```sh\n(?P<block>.*?)```.*?"
           r"The whole block takes about (?P<secs>\d+) s\.", [], newcomer_time),
    Figure("junction snapshot time", "timings", r"so this one takes about (?P<snap>\d+) s\.",
           [JUNCTION_SNAPSHOT], junction_snapshot_time),
    # ---- bench
    Figure("tools/bench targets met", "bench", r"(?P<met>all targets met)", [], bench),
]
