#!/usr/bin/env bash
# Browser checks of `archstudy explore`: drives the page in Debian's Chromium with
# playwright-core (.ci/browser/explore-check.mjs, versions pinned by its package-lock.json),
# first on a live scene, then on the run directory of studies/coarse-seed.yaml, and keeps a
# screenshot of every view in $CI_ARTIFACTS/explore (default: output/ci-artifacts/explore).
#
# Usage: .ci/explore-check.sh path/to/archstudy
set -euo pipefail
cd "$(dirname "$0")/.."

bin="$(cd "$(dirname "${1:?usage: .ci/explore-check.sh ARCHSTUDY}")" && pwd)/$(basename "$1")"
as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
if ! command -v chromium >/dev/null 2>&1; then
  echo "== installing chromium"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
fi
if ! command -v npm >/dev/null 2>&1; then
  echo "== installing nodejs and npm"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nodejs npm >/dev/null
fi
(cd .ci/browser && npm ci --no-audit --no-fund --loglevel=error)

shots="${CI_ARTIFACTS:-$PWD/output/ci-artifacts}/explore"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$bin" run studies/coarse-seed.yaml --out "$work" --quiet
node .ci/browser/explore-check.mjs "$bin" "$work/coarse-seed" "$shots"
echo "screenshots of every view: $shots"
ls "$shots"
