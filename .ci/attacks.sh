#!/usr/bin/env bash
# The attack catalogue of issue 20 against a built binary (argument 1): every manifest of
# tests/corpus and every hostile solve is refused with exit 2 naming its key or option, and
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
for m in tests/corpus/*.yaml; do
  if [ "$(basename "$m")" = grid-3001-squared.yaml ]; then
    expect2 "GiB of memory" sh -c 'ulimit -v 4000000; exec "$0" check "$1"' "$bin" "$m"
  else
    expect2 "key \`" "$bin" check "$m"
  fi
done
expect2 "not a regular file" "$bin" check /dev/zero
expect2 "--t-over-r" "$bin" solve --t-over-r 1e-300
expect2 "at most 100" "$bin" solve --k 1e300 --mu 0.4
expect2 "--voussoirs" timeout 20 "$bin" solve --load horizontal --find load-factor --voussoirs 1000000
exit "$fail"
