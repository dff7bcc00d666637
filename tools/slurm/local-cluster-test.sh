#!/bin/bash
# Proves tools/slurm/bench-array.sbatch on a real Slurm: starts a single-node cluster on this machine (Debian's
# slurm-wlm and munge; slurmctld and slurmd on localhost, unprivileged ports, every file in a temporary folder),
# submits the tiny suite as a 3-task array with its dependent merge + report job, waits, compares the merged results
# with a single run of the same command (everything but times), and stops the daemons it started.
#
#   tools/slurm/local-cluster-test.sh BUILD/tools/smcbench      (ctest -L slurm runs it; see docs/cluster.md)
#
# Exit status 0 when the merged run equals the single run, 1 when not, 77 (ctest: skipped) when Slurm is not
# installed and cannot be (apt-get needs root).
set -euo pipefail

smcbench=$(realpath "${1:?usage: $0 PATH/TO/smcbench}")
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
shards=3
bench_args=(--suite tiny --quick --no-stepper --solver lemke --solver psor --solver enum)

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  if [[ $(id -u) -ne 0 ]]; then
    echo "local-cluster-test: slurm-wlm and munge are not installed (apt-get install slurm-wlm munge); skipped"
    exit 77
  fi
  echo "local-cluster-test: installing slurm-wlm and munge (Debian packages)"
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends slurm-wlm munge >/dev/null
fi

tmp=$(mktemp -d /tmp/smcbench-slurm.XXXXXX)
chmod 755 "$tmp"
pids=()
stop() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [[ $status -ne 0 ]]; then
    echo "local-cluster-test: FAILED (exit $status); logs:"
    tail -n 20 "$tmp"/log/* "$tmp"/run/*.log 2>/dev/null || true
  fi
  rm -rf "$tmp"
  exit $status
}
trap stop EXIT
start=$(date +%s)

# munge: a fresh key, its own socket, run as this user.
mkdir -p "$tmp/munge" "$tmp/log" "$tmp/state" "$tmp/spool"
chmod 700 "$tmp/munge"
mungekey --create --keyfile="$tmp/munge/munge.key" --bits=1024
munged --foreground --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/munge.socket" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/log/munged.log" --seed-file="$tmp/munge/seed" \
  >"$tmp/log/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [[ -S "$tmp/munge/munge.socket" ]] && break; sleep 0.1; done

# Slurm: one node (this host), ports chosen from the pid so two runs do not collide.
node=$(hostname -s)
port=$((20000 + ($$ % 10000) * 2))
user=$(id -un)
cpus=$(nproc)
cat > "$tmp/slurm.conf" <<CONF
ClusterName=smcbench-local
SlurmctldHost=$node(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/munge.socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" >"$tmp/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N "$node" -f "$SLURM_CONF" >"$tmp/log/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  state=$(sinfo -h -N -o %t 2>/dev/null || true)
  [[ "$state" == idle* ]] && break
  sleep 0.2
done
[[ "$state" == idle* ]] || { echo "local-cluster-test: node not idle (state '$state')"; exit 1; }
echo "local-cluster-test: slurm $(sinfo -V | cut -d' ' -f2) up on $node (ports $port, $((port + 1))) after $(($(date +%s) - start)) s"

# The array, its merge job, and a single run of the same command to compare with.
mkdir -p "$tmp/run"
cd "$tmp/run"
SMCBENCH="$smcbench" "$here/bench-array.sbatch" submit "$shards" "$tmp/run" "${bench_args[@]}"
read -r array merge < "$tmp/run/jobs"
for _ in $(seq 600); do
  [[ -z "$(squeue -h -j "$array,$merge" 2>/dev/null)" ]] && break
  sleep 0.5
done
[[ -z "$(squeue -h -j "$array,$merge" 2>/dev/null)" ]] || { echo "local-cluster-test: jobs still queued"; exit 1; }
echo "local-cluster-test: array $array and merge $merge finished after $(($(date +%s) - start)) s"
cat "$tmp/run/merge.log"
[[ -f "$tmp/run/merged/results.json" && -f "$tmp/run/merged/report.md" ]] ||
  { echo "local-cluster-test: no merged results.json / report.md"; exit 1; }
"$smcbench" bench "${bench_args[@]}" --out "$tmp/single" >/dev/null

python3 - "$tmp/single/results.json" "$tmp/run/merged/results.json" <<'PY'
import json, sys
clock = {"time_median", "time_min", "time_max", "time_mad", "samples", "solves_per_sample", "host", "concurrent_jobs"}
def timeless(path):
    d = json.load(open(path))
    out = []
    for s in d["suites"]:
        out.append({k: s[k] for k in ("suite", "problems", "checksum")})
        out += [{k: v for k, v in r.items() if k not in clock} for part in ("records", "sweep") for r in s[part]]
    return out, d
single, _ = timeless(sys.argv[1])
merged, doc = timeless(sys.argv[2])
shared = sum(r.get("concurrent_jobs", 0) > 1 for s in doc["suites"] for p in ("records", "sweep") for r in s[p])
print(f"local-cluster-test: single run {len(single) - 1} records, merged {len(merged) - 1} records; "
      f"{shared} merged records measured beside another shard; hosts {doc['environment'].get('hosts')}")
if single != merged:
    for a, b in zip(single, merged):
        if a != b:
            print("first difference:\n single:", a, "\n merged:", b)
            break
    sys.exit(1)
print("local-cluster-test: merged == single run (everything but times)")
PY
grep -q "shared hosts" "$tmp/run/merged/report.md" && echo "local-cluster-test: report.md warns about shared hosts"
echo "local-cluster-test: passed in $(($(date +%s) - start)) s"
