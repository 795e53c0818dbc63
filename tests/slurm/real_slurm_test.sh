#!/usr/bin/env bash
# ctest for tools/slurm_sweep.sh on a real single-node Slurm cluster (Debian's
# slurm-wlm and munge, started here as root in a scratch folder and stopped by
# their pid files on exit, also on failure):
#  1. the shard array + afterok merge give tables byte-identical to one local
#     `taebp sweep --jobs 1`, and every job's log lands in OUT/slurm/;
#  2. a failing shard blocks the merge (Slurm cancels it), and submitting the
#     same command again after fixing the cause finishes the sweep.
# Exits 77 (ctest: skipped, with the reason on stdout) only when the cluster
# cannot exist here: slurm-wlm/munge not installed, or not root.
# Usage: real_slurm_test.sh SOURCE_DIR TAEBP_BINARY WORK_DIR
set -euo pipefail
src=$1 taebp=$2 work=$3
skip() { echo "SKIPPED: $*"; exit 77; }
fail() {
  echo "FAIL: $*" >&2
  for f in "$work"/log/*.log "$work"/munge/*.log "$work"/cluster*/slurm/*.out "$work"/failing/slurm/*.out; do
    [[ -f $f ]] && { echo "--- $f" >&2; tail -20 "$f" >&2; }
  done
  exit 1
}

for p in /usr/sbin/slurmctld /usr/sbin/slurmd /usr/sbin/munged /usr/bin/sbatch; do
  [[ -x $p ]] || skip "$p is missing: Debian packages slurm-wlm and munge (tools/setup.sh installs them)"
done
[[ $(id -u) -eq 0 ]] || skip "a Slurm node (slurmd) needs root; run the tests as root"
[[ -r /etc/munge/munge.key ]] || skip "/etc/munge/munge.key is missing (reinstall munge)"

# ------------------------------------------------------------------ the cluster
rm -rf "$work"
mkdir -p "$work"/{munge,state,spool,log,cwd}
work=$(realpath "$work")
stop_cluster() {
  set +e
  if [[ -f $work/slurm.conf ]]; then SLURM_CONF=$work/slurm.conf scancel --user=root 2>/dev/null; fi
  local f pid
  for f in "$work/slurmctld.pid" "$work/slurmd.pid" "$work/munge/munged.pid"; do
    [[ -f $f ]] || continue
    pid=$(cat "$f")
    [[ -n $pid ]] && kill "$pid" 2>/dev/null
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null
  done
}
trap stop_cluster EXIT

# munged with its own socket: it insists the folder be owned by munge.
chown munge:munge "$work/munge"
chmod 0711 "$work/munge"
runuser -u munge -- /usr/sbin/munged --socket="$work/munge/munge.socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" \
  --seed-file="$work/munge/munged.seed" || fail "munged did not start"
munge -S "$work/munge/munge.socket" -n | unmunge -S "$work/munge/munge.socket" >/dev/null ||
  fail "munge does not work"

host=$(hostname -s)
cpus=$(nproc)
mem=$(($(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2))  # MB, half the machine
read -r ctld_port slurmd_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
cat > "$work/slurm.conf" <<EOF
ClusterName=taebptest
SlurmctldHost=$host
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
MinJobAge=600
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf
/usr/sbin/slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
/usr/sbin/slurmd -f "$SLURM_CONF" || fail "slurmd did not start"
for _ in $(seq 120); do
  [[ $(sinfo -h -o %t 2>/dev/null) == idle ]] && break
  sleep 0.5
done
[[ $(sinfo -h -o %t 2>/dev/null) == idle ]] || fail "the node did not come up: $(sinfo 2>&1)"
echo "ok: a single-node cluster on $host ($cpus CPUs, ${mem} MB) is up"

# The state of a job (COMPLETED, FAILED, CANCELLED, PENDING, ...).
job_state() { scontrol show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | head -1 | cut -d= -f2; }
# Waits until job $1 (an array: every task) has left PENDING/RUNNING.
wait_job() {
  local i s
  for i in $(seq 600); do
    s=$(scontrol show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | sort -u | tr '\n' ' ')
    [[ -n $s && ! $s =~ PENDING|RUNNING|CONFIGURING|COMPLETING ]] && return 0
    sleep 0.5
  done
  fail "job $1 did not finish: $(scontrol show job "$1" 2>&1 | head -5)"
}
# "submitted: shards job array A (0-N), merge job M -> OUT" -> "A M".
job_ids() { sed -n 's/^submitted: shards job array \([0-9]*\) .*merge job \([0-9]*\) .*/\1 \2/p' <<<"$1"; }

# ------------------------------------------------------------------ 1. shards + merge
args=(--set scenario.duration=60 --set sweep.replicates=2
      --set 'sweep.grid={model.trust: [0.2, 0.6, 1.0]}' --set 'policies=[no_trust, ta_ebp]')
"$taebp" sweep "$src/configs/sweep_trust.yaml" "${args[@]}" --jobs 1 --quiet --out "$work/single"
export TAEBP=$taebp TAEBP_CPUS=1
submitted=$(cd "$work/cwd" && "$src/tools/slurm_sweep.sh" "$src/configs/sweep_trust.yaml" 3 \
  "$work/cluster" -- "${args[@]}")
echo "$submitted"
read -r array merge < <(job_ids "$submitted")
[[ -n $array && -n $merge ]] || fail "no job ids in: $submitted"
wait_job "$array"
wait_job "$merge"
[[ $(job_state "$merge") == COMPLETED ]] || fail "merge job $merge: $(job_state "$merge")"
for f in results.csv aggregate.csv results.jsonl; do
  cmp "$work/single/$f" "$work/cluster/$f" || fail "$f differs from the local sweep"
done
for i in 0 1 2; do
  [[ -s $work/cluster/slurm/shard-$i.$array.out || -f $work/cluster/slurm/shard-$i.$array.out ]] ||
    fail "no log of shard $i in $work/cluster/slurm"
done
[[ -f $work/cluster/slurm/merge.$merge.out ]] || fail "no merge log in $work/cluster/slurm"
[[ -z $(ls -A "$work/cwd") ]] || fail "logs in the submit directory: $(ls -A "$work/cwd")"
echo "ok: 3 shards + merge on Slurm equal one local --jobs 1 sweep; logs in OUT/slurm"

# ------------------------------------------------------------------ 2. a failing shard
# Shard 1 cannot write its folder (a file is in the way): its array task
# fails, afterok never holds and Slurm cancels the merge.
mkdir -p "$work/failing/shards"
echo "in the way" > "$work/failing/shards/1"
submitted=$(cd "$work/cwd" && "$src/tools/slurm_sweep.sh" "$src/configs/sweep_trust.yaml" 3 \
  "$work/failing" -- "${args[@]}")
read -r array merge < <(job_ids "$submitted")
wait_job "$array"
wait_job "$merge"
states=$(scontrol show job "$array" | grep -o 'JobState=[A-Z_]*' | sort | uniq -c | tr -s ' ' | tr '\n' ';')
[[ $states == *FAILED* ]] || fail "no shard failed: $states"
[[ $(job_state "$merge") == CANCELLED ]] || fail "merge job $merge: $(job_state "$merge"), not cancelled"
[[ ! -e $work/failing/results.csv ]] || fail "merged although a shard failed"
grep -q "is a file" "$work/failing/slurm/shard-1.$array.out" || fail "shard 1's log does not say why"
echo "ok: a failing shard blocks the merge ($states merge CANCELLED)"

rm "$work/failing/shards/1"
submitted=$(cd "$work/cwd" && "$src/tools/slurm_sweep.sh" "$src/configs/sweep_trust.yaml" 3 \
  "$work/failing" -- "${args[@]}")
read -r array merge < <(job_ids "$submitted")
wait_job "$array"
wait_job "$merge"
[[ $(job_state "$merge") == COMPLETED ]] || fail "resubmitted merge job $merge: $(job_state "$merge")"
for f in results.csv aggregate.csv results.jsonl; do
  cmp "$work/single/$f" "$work/failing/$f" || fail "$f differs from the local sweep after resubmitting"
done
grep -q "resuming" "$work/failing/slurm/shard-0.$array.out" || fail "shard 0 did not resume"
echo "ok: resubmitting after the fix finishes the sweep (shards resume), tables equal the local sweep"
