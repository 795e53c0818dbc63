#!/usr/bin/env bash
# ctest for tools/slurm_sweep.sh with a stand-in sbatch (tests/slurm/sbatch):
# the job array of shards plus the afterok merge job must give the same tables
# as one `taebp sweep --jobs 1`; a failing shard must keep the merge from running.
# Usage: slurm_test.sh SOURCE_DIR TAEBP_BINARY WORK_DIR
set -euo pipefail
src=$1 taebp=$2 work=$3
rm -rf "$work"
mkdir -p "$work/spool" "$work/bin"
cp "$src/tests/slurm/sbatch" "$work/bin/sbatch"
chmod +x "$work/bin/sbatch"
export PATH="$work/bin:$PATH" FAKE_SLURM_SPOOL="$work/spool" TAEBP="$taebp"
fail() { echo "FAIL: $*" >&2; exit 1; }
args=(--set scenario.duration=60 --set sweep.replicates=2
      --set 'sweep.grid={model.trust: [0.2, 0.6, 1.0]}' --set 'policies=[no_trust, ta_ebp]')

"$taebp" sweep "$src/configs/sweep_trust.yaml" "${args[@]}" --jobs 1 --quiet --out "$work/single"

# Submitted from a scratch directory: no log may land there.
mkdir -p "$work/cwd"
out=$(cd "$work/cwd" && "$src/tools/slurm_sweep.sh" "$src/configs/sweep_trust.yaml" 3 "$work/cluster" -- "${args[@]}")
echo "$out"
[[ $out == submitted:* ]] || fail "no 'submitted:' line"
[[ $(cat "$work/spool/jobs") == $'1000 ok\n1001 ok' ]] || fail "jobs: $(cat "$work/spool/jobs")"
[[ -z $(ls -A "$work/cwd") ]] || fail "logs in the submit directory: $(ls -A "$work/cwd")"
for f in shard-0.1000.out shard-1.1000.out shard-2.1000.out merge.1001.out; do
  [[ -f $work/cluster/slurm/$f ]] || fail "no log $work/cluster/slurm/$f"
done
for i in 0 1 2; do [[ -s $work/cluster/shards/$i/journal.jsonl ]] || fail "shard $i did not run"; done
for f in results.csv aggregate.csv results.jsonl; do
  cmp "$work/single/$f" "$work/cluster/$f" || fail "$f differs from the single run"
done
echo "ok: 3 shards + merge equal one --jobs 1 sweep"

# A failing task (80 vehicles on loops that may not grow) fails its shard, and afterok
# keeps the merge from running; the other shard's results are kept.
rm -f "$work/spool/jobs"
"$src/tools/slurm_sweep.sh" "$src/configs/sweep_trust.yaml" 2 "$work/failing" -- "${args[@]}" \
  --set 'sweep.grid={"scenario.avs,scenario.hvs": [[4, 4], [40, 40]]}' --set sweep.replicates=1 \
  --set scenario.auto_length=false
[[ $(cat "$work/spool/jobs") == $'1000 failed\n1001 skipped' ]] || fail "jobs: $(cat "$work/spool/jobs")"
[[ ! -e $work/failing/results.csv ]] || fail "merged although a shard failed"
grep -q '"status":"ok"' "$work/failing/shards/0/journal.jsonl" || fail "shard 0 lost its result"
grep -q 'loop_length' "$work/failing/shards/1/journal.jsonl" || fail "shard 1 did not record its failure"
echo "ok: a failing shard keeps the merge from running"

# A config that does not load is refused before anything is submitted.
rm -f "$work/spool/jobs"
"$src/tools/slurm_sweep.sh" "$src/configs/sweep_trust.yaml" 2 "$work/broken" -- "${args[@]}" \
  --set scenario.confirm_delay=-1 > "$work/broken.log" 2>&1 && fail "a config error was submitted"
grep -q "scenario.confirm_delay" "$work/broken.log" || fail "the submit error does not name the key"
[[ ! -s $work/spool/jobs ]] || fail "jobs were submitted for a broken config"
echo "ok: a broken config is refused before submitting"
