#!/usr/bin/env bash
# A sharded study on a real Slurm scheduler: installs Debian's slurmctld, slurmd,
# slurm-client and munge, starts a one-node cluster on localhost from .ci/slurm/slurm.conf.in,
# submits the small study .ci/slurm/study.yaml as a 4-task job array plus an afterok merge
# job (the scripts `archstudy slurm` writes), waits for both (bounded), and checks with
# `archstudy verify --tolerance 0` that the merged run holds the same Parquet data as an
# unsharded run of the same study (timing columns aside). The daemons are stopped on exit. Runs as root, without systemd.
# Usage: bash .ci/slurm-check.sh path/to/archstudy
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$(realpath "${1:-target/release/archstudy}")"
limit_s="${SLURM_CHECK_TIMEOUT:-180}"

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null \
  || ! command -v sbatch >/dev/null || ! command -v slurmd >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends slurmctld slurmd slurm-client munge >/dev/null
fi

scratch="$(mktemp -d /tmp/archstudy-slurm.XXXXXX)"
pids=()
stop() {
  local status=$?
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
  done
  if [ "$status" -ne 0 ]; then
    echo "-- slurmctld.log"; tail -n 30 "$scratch/slurmctld.log" 2>/dev/null || true
    echo "-- slurmd.log"; tail -n 30 "$scratch/slurmd.log" 2>/dev/null || true
    for f in "$scratch"/out/*.slurm/logs/*; do echo "-- $f"; cat "$f"; done 2>/dev/null || true
  fi
  rm -rf "$scratch"
  exit "$status"
}
trap stop EXIT

mkdir -p "$scratch/state" "$scratch/spool" "$scratch/out"
hardware="$(slurmd -C | head -n 1 | sed 's/^NodeName=[^ ]* //; s/ UpTime=.*//')"
sed -e "s|@SCRATCH@|$scratch|g" -e "s|@NODE_HARDWARE@|$hardware|" \
  .ci/slurm/slurm.conf.in >"$scratch/slurm.conf"
export SLURM_CONF="$scratch/slurm.conf"

# munged refuses to run as root.
mkdir -p /run/munge && chown munge:munge /run/munge && chmod 0755 /run/munge
runuser -u munge -- /usr/sbin/munged --pid-file=/run/munge/ci.pid
pids+=("$(cat /run/munge/ci.pid)")
slurmctld -i
for _ in $(seq 50); do [ -s "$scratch/slurmctld.pid" ] && break; sleep 0.1; done
pids+=("$(cat "$scratch/slurmctld.pid")")
slurmd
for _ in $(seq 50); do [ -s "$scratch/slurmd.pid" ] && break; sleep 0.1; done
pids+=("$(cat "$scratch/slurmd.pid")")
for _ in $(seq 100); do
  sinfo -h -o '%t' 2>/dev/null | grep -qE '^(idle|mix|alloc)' && break
  sleep 0.2
done
sinfo

study="$scratch/study.yaml"
cp .ci/slurm/study.yaml "$study"
t0=$(date +%s)
"$bin" slurm "$study" --shards 4 --time 00:05:00 --out "$scratch/out" >"$scratch/submit.sh"
array=$(sbatch --parsable "$scratch/out/slurm-ci.slurm/array.sh")
array=${array%%;*}
merge=$(sbatch --parsable --dependency="afterok:$array" "$scratch/out/slurm-ci.slurm/merge.sh")
merge=${merge%%;*}
echo "array job $array, merge job $merge"
state=""
while :; do
  state=$(scontrol show job "$merge" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1)
  case "$state" in
    COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | DEADLINE) break ;;
  esac
  if [ $(($(date +%s) - t0)) -gt "$limit_s" ]; then
    echo "the jobs did not finish within ${limit_s} s (merge job: ${state:-unknown})"
    scancel "$array" "$merge" || true
    exit 1
  fi
  sleep 1
done
echo "merge job $merge: $state after $(($(date +%s) - t0)) s"
scontrol show job "$array" | grep -E 'JobState|ArrayTaskId' | head -n 8 || true
[ "$state" = COMPLETED ]
test -s "$scratch/out/slurm-ci/results.parquet"
test -s "$scratch/out/slurm-ci/report.html"

# `verify` runs the same study unsharded and compares every Parquet table of the merged run
# with it: --tolerance 0 asks for equal values (timing columns are not compared).
"$bin" verify "$scratch/out/slurm-ci" --tolerance 0 >"$scratch/verify.txt" || {
  cat "$scratch/verify.txt"
  exit 1
}
tail -n 1 "$scratch/verify.txt"
echo "slurm check: OK in $(($(date +%s) - t0)) s"
