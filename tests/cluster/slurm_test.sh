#!/usr/bin/env bash
# A stimulus set made by a real Slurm: munged, slurmctld and slurmd started on 127.0.0.1 from a
# slurm.conf written here (its own munge key and socket, ports, state; no accounting, no
# systemd), the scripts of `stimuli --slurm 4` submitted and chained, and the set compared with
# one made on this machine: every file the same bytes, the manifest too apart from its run
# record (timestamps). Then one shard is cancelled mid-way, resubmitted alone and merged again,
# with the same result. The daemons are stopped by their process ids.
#   tests/cluster/slurm_test.sh COUNTERSHADE_BINARY
# Exit 77 (skipped) only where starting the daemons is impossible: not root.
set -euo pipefail
bin=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)

if [ "$(id -u)" != 0 ]; then
  echo "SKIPPED: starting munged, slurmctld and slurmd needs root, and this runs as $(id -un)"
  exit 77
fi
for tool in munged slurmctld slurmd sbatch squeue scancel scontrol; do
  command -v "$tool" > /dev/null || { echo "FAIL: $tool is missing (scripts/setup installs slurmctld slurmd slurm-client munge)"; exit 1; }
done

tmp=$(mktemp -d /tmp/countershade-slurm.XXXXXX)
stop_daemons() {
  for name in slurmd slurmctld munged; do
    [ -f "$tmp/$name.pid" ] && kill "$(cat "$tmp/$name.pid")" 2> /dev/null || true
  done
  sleep 1
  rm -rf "$tmp"
}
trap stop_daemons EXIT

free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
host=$(hostname -s)
mkdir -p "$tmp/state" "$tmp/spool"
head -c 1024 /dev/urandom > "$tmp/munge.key"
chmod 400 "$tmp/munge.key"
cat > "$tmp/slurm.conf" <<CONF
ClusterName=countershade-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
PlugStackConfig=/dev/null
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
munged --force --key-file="$tmp/munge.key" --socket="$tmp/munge.socket" --pid-file="$tmp/munged.pid" \
  --log-file="$tmp/munged.log" --seed-file="$tmp/munge.seed"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"

# Waits until `$1` succeeds; the limit ($2 s) only catches a daemon that hangs, not a slow machine.
wait_for() {
  local deadline=$((SECONDS + $2))
  until eval "$1"; do
    [ $SECONDS -lt $deadline ] || { echo "FAIL: timed out waiting for: $1"; tail -5 "$tmp"/slurm*.log; exit 1; }
    sleep 0.2
  done
}
wait_for 'sinfo -h -o %t 2> /dev/null | grep -qx idle' 900
no_jobs() { [ -z "$(squeue -h 2> /dev/null)" ]; }

# A small design: a 24-frame sequence and a still, two methods.
cp "$here/scenes/orbit.json" "$here/scenes/still.json" "$tmp/"
cat > "$tmp/experiment.json" <<'JSON'
{"version": 1, "name": "cluster", "seed": 3, "lambda": {"min": 0, "max": 1, "step": 0.5},
 "scenes": [{"name": "orbit", "file": "orbit.json", "frames": "all"}, {"name": "still", "file": "still.json"}],
 "methods": [{"method": "usm2d", "sigma_px": [2]}, {"method": "depth-usm", "operator": "darken", "sigma_px": [3]}]}
JSON
"$bin" stimuli "$tmp/experiment.json" -o "$tmp/single" --jobs 2 > /dev/null 2>&1

same_set() {  # every file and the manifest (without its run record) as in the single run
  (cd "$tmp/single" && find . -type f ! -name 'manifest*' | sort | xargs sha256sum) > "$tmp/a.sums"
  (cd "$1" && find . -type f ! -name 'manifest*' ! -path './slurm/*' ! -name '.journal*' | sort | xargs sha256sum) > "$tmp/b.sums"
  diff "$tmp/a.sums" "$tmp/b.sums" > /dev/null || { echo "FAIL: $1 holds other files or bytes than the single run"; diff "$tmp/a.sums" "$tmp/b.sums" | head; exit 1; }
  python3 - "$tmp/single/manifest.json" "$1/manifest.json" <<'PY' || { echo "FAIL: $1/manifest.json differs from the single run's"; exit 1; }
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
a.pop("run"); b.pop("run")
sys.exit(json.dumps(a, sort_keys=False) != json.dumps(b, sort_keys=False))
PY
}

echo "== the set over 4 shards, chained with its merge"
"$bin" stimuli "$tmp/experiment.json" -o "$tmp/cluster" --slurm 4 --cpus 1 --time 00:10:00 --partition test | tee "$tmp/submit.txt"
bash -n "$tmp/cluster/slurm/array.sbatch"
bash -n "$tmp/cluster/slurm/merge.sbatch"
(cd / && eval "$(sed -n 's/^  //p' "$tmp/submit.txt")")  # the printed commands, from another folder
wait_for no_jobs 900
[ -f "$tmp/cluster/manifest.json" ] || { echo "FAIL: the merge did not run"; cat "$tmp/cluster/slurm/logs/"*; exit 1; }
same_set "$tmp/cluster"
echo "same files and manifest as the single run"

echo "== shard 2 cancelled mid-way, resubmitted alone, merged again"
"$bin" stimuli "$tmp/experiment.json" -o "$tmp/cut" --slurm 4 --cpus 1 > /dev/null
array=$(sbatch --parsable "$tmp/cut/slurm/array.sbatch" | cut -d';' -f1)
journal="$tmp/cut/.journal.shard-2-of-4.jsonl"
wait_for "[ -f '$journal' ] && [ \$(wc -l < '$journal') -ge 4 ]" 900  # its header and three images
scontrol suspend "${array}_2" 2> /dev/null || true
if [ -f "$tmp/cut/manifest.shard-2-of-4.json" ]; then echo "FAIL: shard 2 finished before it could be cancelled"; exit 1; fi
scancel "${array}_2"
wait_for no_jobs 900
done_before=$(($(wc -l < "$journal") - 1))
[ ! -f "$tmp/cut/manifest.shard-2-of-4.json" ] || { echo "FAIL: the cancelled shard wrote its manifest"; exit 1; }
if "$bin" stimuli "$tmp/experiment.json" -o "$tmp/cut" --merge > "$tmp/merge.txt" 2>&1; then echo "FAIL: a merge with a shard missing succeeded"; exit 1; fi
grep -q "shard 2 of 4 has not finished" "$tmp/merge.txt" || { echo "FAIL: the merge did not name the missing shard"; cat "$tmp/merge.txt"; exit 1; }
[ ! -f "$tmp/cut/manifest.json" ] || { echo "FAIL: a refused merge wrote manifest.json"; exit 1; }
echo "cancelled with $done_before images of shard 2 journalled; the merge names the missing shard: $(head -1 "$tmp/merge.txt")"
sbatch --array=2 "$tmp/cut/slurm/array.sbatch" > /dev/null
wait_for no_jobs 900
sbatch "$tmp/cut/slurm/merge.sbatch" > /dev/null
wait_for no_jobs 900
same_set "$tmp/cut"
kept=$(sed -n 's/.* \([0-9]*\) kept from an earlier run.*/\1/p' "$tmp/cut/slurm/logs/shard-2.log")
[ "${kept:-0}" -ge 3 ] || { echo "FAIL: the resubmitted shard did not resume its own work"; cat "$tmp/cut/slurm/logs/shard-2.log"; exit 1; }
echo "resubmitted shard 2 resumed: $(grep 'kept from an earlier run' "$tmp/cut/slurm/logs/shard-2.log")"
echo "same files and manifest as the single run"

echo "== a resubmitted shard whose experiment changed is refused"
echo " " >> "$tmp/experiment.json"
sbatch --array=3 "$tmp/cut/slurm/array.sbatch" > /dev/null
wait_for no_jobs 900
grep -q "changed since its job scripts were written" "$tmp/cut/slurm/logs/shard-3.log" || { echo "FAIL: a changed experiment was not refused"; cat "$tmp/cut/slurm/logs/shard-3.log"; exit 1; }
echo "refused: $(cat "$tmp/cut/slurm/logs/shard-3.log")"
echo "PASS"
