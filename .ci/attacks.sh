#!/usr/bin/env bash
# The attack catalogue against a built binary (argument 1): every manifest of tests/corpus
# and every hostile solve is refused with exit 2 naming its key or option (the one valid
# manifest too large for an unsharded run is refused by `run` and described by `check`), and
# nothing panics or aborts. Fails on the first regression; runs in seconds.
set -uo pipefail
bin="${1:?usage: attacks.sh BINARY}"
cd "$(dirname "$0")/.."
fail=0
expect2() { # expect2 NEEDLE COMMAND...
  local needle="$1"; shift
  local err rc
  err="$("$@" 2>&1 >/dev/null)"; rc=$?
  if [ "$rc" != 2 ] || ! grep -qF -- "$needle" <<<"$err" || grep -q panicked <<<"$err"; then
    echo "REGRESSION: $* -> exit $rc: $err"; fail=1
  else
    echo "ok: $*"
  fi
}
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
for m in tests/corpus/*.yaml; do
  if [ "$(basename "$m")" = grid-5001-squared.yaml ]; then
    # A valid plan too large for one unsharded run: `run` refuses it before writing
    # anything, naming --shard; `check` describes it (exit 0) and says it runs in shards.
    expect2 "--shard I/N" "$bin" run "$m" --out "$scratch/out"
    if [ -e "$scratch/out" ]; then
      echo "REGRESSION: $bin run $m wrote $scratch/out"; fail=1
    fi
    if "$bin" check "$m" | grep -q "runs in shards only"; then
      echo "ok: $bin check $m (runs in shards only)"
    else
      echo "REGRESSION: $bin check $m does not describe a plan that runs in shards only"; fail=1
    fi
  else
    expect2 "key \`" "$bin" check "$m"
  fi
done
expect2 "not a regular file" "$bin" check /dev/zero
refused() { # refused NEEDLE COMMAND...: fails (not by the timeout) naming NEEDLE, no panic
  local needle="$1"; shift
  local err rc
  err="$(timeout 20 "$@" 2>&1)"; rc=$?
  if [ "$rc" = 0 ] || [ "$rc" = 124 ] || ! grep -qF -- "$needle" <<<"$err" || grep -q panicked <<<"$err"; then
    echo "REGRESSION: $* -> exit $rc: $err"; fail=1
  else
    echo "ok: $*"
  fi
}
# FIFOs and devices are refused before they are opened (opening a FIFO waits for a writer).
mkfifo "$scratch/fifo.yaml"
expect2 "not a regular file" timeout 20 "$bin" check "$scratch/fifo.yaml"
expect2 "not a regular file" timeout 20 "$bin" run "$scratch/fifo.yaml" --out "$scratch/o"
expect2 "not a regular file" timeout 20 "$bin" slurm "$scratch/fifo.yaml" --shards 2 --out "$scratch/o"
expect2 "FIFO or device" timeout 20 "$bin" verify "$scratch/fifo.yaml"
for kind in fifo zero; do
  d="$scratch/run-$kind"
  mkdir -p "$d"
  if [ "$kind" = fifo ]; then mkfifo "$d/run.json"; else ln -s /dev/zero "$d/run.json"; fi
  refused "not a regular file" "$bin" report "$d"
  refused "not a regular file" "$bin" merge "$d" --out "$scratch/o"
  refused "run.json" "$bin" verify "$d" --no-rerun
done
expect2 "--t-over-r" "$bin" solve --t-over-r 1e-300
expect2 "at most 100" "$bin" solve --k 1e300 --mu 0.4
expect2 "--voussoirs" timeout 20 "$bin" solve --load horizontal --find load-factor --voussoirs 1000000
# explore: a port out of range, a missing run directory, a run directory that is a FIFO's
# parent without run.json, and a host that is no address: refused before serving.
expect2 "--port" timeout 20 "$bin" explore --port 70000
expect2 "/no/such/run" timeout 20 "$bin" explore /no/such/run --port 0
expect2 "run.json" timeout 20 "$bin" explore "$scratch/run-fifo" --port 0
expect2 "--host" timeout 20 "$bin" explore --host "no such host" --port 0
exit "$fail"
