#!/usr/bin/env bash
# A taebp sweep on a Slurm cluster: a job array with one shard of the sweep per
# array task, then a merge job that runs once every shard succeeded.
#
# Usage, on the login node (build taebp first: tools/setup.sh or cmake):
#   tools/slurm_sweep.sh CONFIG [SHARDS] [OUT] [-- EXTRA TAEBP SWEEP ARGS]
# e.g.
#   tools/slurm_sweep.sh configs/sweep_mismatch.yaml 8 results/mismatch
#   tools/slurm_sweep.sh configs/sweep_trust.yaml 4 results/trust -- --set sweep.replicates=20
# SHARDS defaults to 4, OUT to results/<config name>.
#
# It submits two jobs (this same script, in two modes):
#   1. sbatch --array=0-(SHARDS-1): array task I runs
#        taebp sweep CONFIG --shard I/SHARDS --out OUT/shards/I --jobs $SLURM_CPUS_PER_TASK
#      i.e. the grid tasks whose index % SHARDS == I, SLURM_CPUS_PER_TASK worker
#      processes at a time (one SUMO per process);
#   2. sbatch --dependency=afterok:<array job>: runs
#        taebp merge OUT OUT/shards/0 ... OUT/shards/(SHARDS-1)
#      which writes OUT/results.csv, results.jsonl, aggregate.csv, journal.jsonl,
#      sweep.json and OUT/tasks/ (the same files as one `taebp sweep --out OUT`).
# The jobs' own logs go to OUT/slurm/ (shard-I.ARRAYID.out, merge.JOBID.out),
# not to the directory you submit from.
# If a shard fails (a task failed, time limit, node crash), afterok keeps the
# merge from running and Slurm cancels it (--kill-on-invalid-dep=yes): fix the
# cause and submit the same command again. Each shard resumes from its journal
# (finished tasks are not re-run), so only the missing work is redone.
# `taebp merge` can also be run by hand at any time on the finished shards.
#
# Resources: the #SBATCH lines below are the defaults of the array tasks; set
# others on the command line through the environment, e.g.
#   SBATCH_PARTITION=short SBATCH_ACCOUNT=myproj SBATCH_TIMELIMIT=4:00:00 tools/slurm_sweep.sh ...
# (sbatch reads SBATCH_* variables) or edit the lines. TAEBP_CPUS overrides
# --cpus-per-task of the shards. TAEBP=/path/to/taebp picks another binary
# (default: build/taebp of this checkout). OUT must be on a file system that
# the compute nodes share with the login node.
#
#SBATCH --job-name=taebp-sweep
#SBATCH --cpus-per-task=4
#SBATCH --mem-per-cpu=1G
#SBATCH --time=02:00:00
#SBATCH --output=slurm-%x-%A_%a.out
# (--output above applies only when this file is submitted by hand: the
# submit mode below sends every log to OUT/slurm/.)
set -euo pipefail

export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

case ${TAEBP_SLURM_MODE:-submit} in
shard)  # one array task
  : "${SLURM_ARRAY_TASK_ID:?not in a Slurm array task}"
  exec "$TAEBP" sweep "$TAEBP_CONFIG" --shard "$SLURM_ARRAY_TASK_ID/$TAEBP_SHARDS" \
    --out "$TAEBP_OUT/shards/$SLURM_ARRAY_TASK_ID" --jobs "${SLURM_CPUS_PER_TASK:-1}" "$@"
  ;;
merge)  # after every shard succeeded
  dirs=()
  for ((i = 0; i < TAEBP_SHARDS; i++)); do dirs+=("$TAEBP_OUT/shards/$i"); done
  exec "$TAEBP" merge "$TAEBP_OUT" "${dirs[@]}"
  ;;
submit) ;;
*)
  echo "slurm_sweep.sh: unknown TAEBP_SLURM_MODE=$TAEBP_SLURM_MODE" >&2
  exit 2
  ;;
esac

usage() {
  sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
(($# >= 1)) || usage
[[ $1 == -h || $1 == --help ]] && usage
config=$1
shift
shards=4
out=
if (($# > 0)) && [[ $1 != -- ]]; then shards=$1; shift; fi
if (($# > 0)) && [[ $1 != -- ]]; then out=$1; shift; fi
if (($# > 0)) && [[ $1 == -- ]]; then shift; fi
extra=("$@")
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "slurm_sweep.sh: SHARDS must be a positive integer, got '$shards'" >&2; exit 2; }
[[ -f $config ]] || { echo "slurm_sweep.sh: no such config: $config" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
taebp=${TAEBP:-$root/build/taebp}
[[ -x $taebp ]] || { echo "slurm_sweep.sh: $taebp is not built (run tools/setup.sh or set TAEBP)" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "slurm_sweep.sh: sbatch not found (not a Slurm login node?)" >&2; exit 2; }
[[ -n $out ]] || out=results/$(basename "${config%.*}")
config=$(realpath "$config")
taebp=$(realpath "$taebp")
mkdir -p "$out/shards" "$out/slurm"
out=$(realpath "$out")

# Fail here rather than in every array task: the config and the grid must load.
"$taebp" sweep "$config" --list "${extra[@]}" >/dev/null

common="ALL,TAEBP=$taebp,TAEBP_CONFIG=$config,TAEBP_OUT=$out,TAEBP_SHARDS=$shards"
cpus=()
[[ -n ${TAEBP_CPUS:-} ]] && cpus=(--cpus-per-task="$TAEBP_CPUS")
array_job=$(sbatch --parsable --array="0-$((shards - 1))" "${cpus[@]}" \
  --output="$out/slurm/shard-%a.%A.out" \
  --export="$common,TAEBP_SLURM_MODE=shard" "$0" "${extra[@]}")
array_job=${array_job%%;*}
merge_job=$(sbatch --parsable --dependency="afterok:$array_job" --kill-on-invalid-dep=yes \
  --job-name=taebp-merge --cpus-per-task=1 --time=00:30:00 --output="$out/slurm/merge.%j.out" \
  --export="$common,TAEBP_SLURM_MODE=merge" "$0")
merge_job=${merge_job%%;*}
echo "submitted: shards job array $array_job (0-$((shards - 1))), merge job $merge_job -> $out"
