"""The commands the pages show, each written once (a figure's commands must
appear verbatim on its page)."""


PAPER = "build/taebp run configs/paper.yaml"
STOP17 = "build/taebp run configs/paper.yaml --set scenario.stop_distance=1.7 --out results/paper_stop17"
SEEDS = ("for s in 2 3 4 5; do build/taebp run configs/paper.yaml --set scenario.seed=$s "
         "--set 'policies=[ta_ebp]' --out results/paper_seed$s; done")
THEORY = "build/taebp theory --prior 0.2 --penalty 3 --trust 0.6"
THEORY_NO_TRUST = "build/taebp theory --prior 0.2 --penalty 3 --trust 0.6 --assumed-trust 1 --json"
SOLVE_AVHV = "build/taebp solve configs/problems/av_hv.yaml"
SOLVE_PROSECUTOR = "build/taebp solve configs/problems/prosecutor.yaml"
SNAPSHOT = "build/taebp snapshot configs/paper.yaml --policy ta_ebp --at 20 --out docs/img/figure8.png"
JUNCTION_SNAPSHOT = ("build/taebp snapshot configs/grid_throughput.yaml --policy ta_ebp --at 531 "
                     "--junction B1 --zoom 1.5 --out docs/img/grid_junction.png")
PEN110 = ("build/taebp run configs/sweep_penetration.yaml --set scenario.avs=10 --set scenario.hvs=6 "
          "--set scenario.loop_length=110 --set 'policies=[ta_ebp, no_trust]' --out results/pen_110")
MAP_RUN = ("build/taebp run configs/grid_throughput.yaml --quiet --out results/grid_map --set "
           "'scenario.grid={columns: 3, rows: 3}' --set scenario.duration=600 --set scenario.warmup=60 "
           "--set scenario.demand.flow=300 --set 'policies=[sumo_native, no_ebp, ta_ebp]'")
MAP_PLOT = "tools/plot results/grid_map --out docs/img"
GRID = "build/taebp sweep configs/grid_throughput.yaml --out results/grid_throughput --jobs 2"
GRID_PLOT = "tools/plot results/grid_throughput"
OSM = "build/taebp run configs/osm_city.yaml"
TWO_WAY = "build/taebp sweep configs/grid_two_way.yaml --set scenario.major_road.enabled=false --out results/grid_two_way --jobs 2"
TWO_WAY_PLOT = "tools/plot results/grid_two_way"
# The theory per encounter, pooled over 20 independent seeds at one point of
# each grid (sweep points share random streams per seed: pooling points
# would count one draw several times).
THEORY_ALL = ("build/taebp sweep configs/grid_throughput.yaml --set 'sweep={replicates: 20, grid: {}}' "
              "--set scenario.demand.flow=200 --set scenario.av_share=0.5 "
              "--set 'policies=[no_ebp, no_trust, ta_ebp]' --out results/theory_all_way --jobs 2")
THEORY_TWO = ("build/taebp sweep configs/grid_two_way.yaml --set scenario.major_road.enabled=false --set 'sweep={replicates: 20, grid: {}}' "
              "--set scenario.demand.flow=150 --set scenario.av_share=0.5 "
              "--set 'policies=[no_ebp, no_trust, ta_ebp]' --out results/theory_two_way --jobs 2")
POOLED40 = ("build/taebp sweep configs/paper.yaml --set 'sweep={replicates: 40, grid: {}}' "
            "--out results/paper40 --jobs 2")
SWEEP = {s: "build/taebp sweep configs/sweep_%s.yaml" % s for s in ("trust", "mismatch", "penetration")}
PLOT = {s: "tools/plot results/sweep_%s" % s for s in ("trust", "mismatch", "penetration")}
EFF_GRID = "build/taebp sweep configs/efficiency_grid.yaml --out results/efficiency_grid --jobs 2"
EFF_GRID_PLOT = "tools/plot results/efficiency_grid"
EFF_F8 = "build/taebp sweep configs/efficiency_figure8.yaml --out results/efficiency_figure8 --jobs 2"
CITY = "build/taebp sweep configs/city_drt.yaml --out results/city_drt --jobs 2"
CITY_MAP_RUN = "build/taebp run configs/city_drt.yaml --quiet --out results/city_map --set 'policies=[sumo_native, no_ebp, ta_ebp]'"
CITY_MAP_PLOT = "tools/plot results/city_map"
BOLOGNA = "build/taebp sweep configs/bologna_acosta.yaml --out results/bologna_acosta --jobs 2"
SSM_GRID = ("build/taebp sweep configs/grid_two_way.yaml --set scenario.major_road.enabled=false --set 'scenario.outputs.ssm={}' "
            "--set 'sweep.grid={policies: [[sumo_native], [no_ebp], [no_trust], [ta_ebp]]}' "
            "--set sweep.replicates=10 --out results/ssm_grid --jobs 2")
SSM_TWELVE = ("for s in 1 3 8 22; do for p in sumo_native no_trust ta_ebp; do build/taebp run "
              "configs/grid_two_way.yaml --set scenario.major_road.enabled=false --set 'scenario.outputs.ssm={}' --set scenario.seed=$s "
              "--set \"policies=[$p]\" --quiet --out results/ssm12/$s-$p || echo \"lost $s $p\"; done; done")
PAIRED_SSM = ("build/taebp run configs/grid_two_way.yaml --set scenario.major_road.enabled=false --paired --set 'policies=[no_trust, ta_ebp]' "
              "--set scenario.duration=900 --set 'scenario.outputs.ssm={}' --out results/paired_ssm --quiet")
# Beyond the paper (tier beyond): learned trust, dynamic trust, noise.
LEARNED = "build/taebp run configs/learned_trust.yaml"
DYNAMIC = "build/taebp run configs/dynamic_trust.yaml"
ROBUST = ("build/taebp run configs/influence.yaml --set model.experience.forgetting=0.95 "
          "--set model.experience.design=robust --set 'policies=[ta_ebp, full_reveal]' "
          "--out results/influence_robust")
NOISE = "build/taebp sweep configs/noise.yaml"
BEYOND_PLOT = {"learned": "tools/plot results/learned_trust", "dynamic": "tools/plot results/dynamic_trust",
               "noise": "tools/plot results/noise"}
LEARNERS = ("build/taebp sweep configs/influence_learners.yaml --set sweep.replicates=10 "
            "--out results/influence_learners --jobs 2")
LEARNERS_PLOT = "tools/plot results/influence_learners --out results/influence_learners"
LEARNERS_K = ("build/taebp sweep configs/influence_learners.yaml --set sweep.replicates=10 "
              "--set 'model.experience.strengths=[2, 20, 200]' "
              "--set 'sweep.grid={model.experience.forgetting: [1, 0.95], "
              "model.experience.design: [robust, guarded, paper]}' "
              "--out results/influence_learners_k --jobs 2")
NOISY = {d: ("build/taebp run configs/influence.yaml --set 'model.noise={kind: gaussian, scale: 0.1, "
             "design: paper}' --set model.experience.design=%s --set 'policies=%s' --out results/noisy_%s"
             % (d, "[ta_ebp, full_reveal, always_nudge, random_nudge]" if d == "robust" else "[ta_ebp]", d))
         for d in ("robust", "guarded", "paper")}
