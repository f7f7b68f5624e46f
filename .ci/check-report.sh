#!/usr/bin/env bash
# Headless check of an HTML report: opens it in Debian's Chromium, takes a screenshot and
# dumps the DOM, and fails when
#   - the page renders blank (the screenshot's pixel variance is near zero),
#   - a figure is missing (fewer inline <svg class="figure"> than the report announces in
#     data-figure-count, an empty SVG, or an <img> whose file does not exist),
#   - the page would fetch anything from the network (external stylesheet, script, image,
#     font or url()),
#   - the console shows a message (the report has no scripts, so any is an error) or a
#     resource failed to load.
#
# Usage: .ci/check-report.sh path/to/report.html [screenshot.png]
set -euo pipefail

html="${1:?usage: .ci/check-report.sh REPORT.html [SCREENSHOT.png]}"
if [ ! -f "$html" ]; then
  echo "check-report: no such file: $html" >&2
  exit 2
fi
html="$(cd "$(dirname "$html")" && pwd)/$(basename "$html")"

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

if ! command -v chromium >/dev/null 2>&1; then
  echo "== installing chromium"
  as_root apt-get update
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y chromium
fi
# Pillow reads the screenshot: the python3 on PATH if it has it, else Debian's python3 with
# python3-pil, else pip.
py=python3
if ! "$py" -c "import PIL" >/dev/null 2>&1; then
  if ! /usr/bin/python3 -c "import PIL" >/dev/null 2>&1; then
    echo "== installing pillow"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y python3-pil >/dev/null || true
  fi
  if /usr/bin/python3 -c "import PIL" >/dev/null 2>&1; then
    py=/usr/bin/python3
  else
    python3 -m pip install --quiet pillow \
      || python3 -m pip install --quiet --break-system-packages pillow
  fi
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
shot="${2:-$work/screenshot.png}"

flags=(
  --headless --no-sandbox --disable-gpu --no-first-run
  --disable-background-networking --disable-component-update --disable-sync
  --hide-scrollbars --force-device-scale-factor=1
)

echo "== screenshot of $html"
# Chromium exits 0 even when the page has errors; they are read from its log below.
chromium "${flags[@]}" --user-data-dir="$(mktemp -d -p "$work")" \
  --enable-logging=stderr --v=0 \
  --window-size=1280,4000 --screenshot="$shot" "file://$html" \
  >"$work/stdout.log" 2>"$work/console.log" || true
echo "== DOM"
chromium "${flags[@]}" --user-data-dir="$(mktemp -d -p "$work")" \
  --enable-logging=stderr --v=0 \
  --dump-dom "file://$html" >"$work/dom.html" 2>"$work/console-dom.log" || true

"$py" - "$html" "$shot" "$work/dom.html" "$work/console.log" "$work/console-dom.log" <<'PY'
import os
import re
import sys

from PIL import Image, ImageStat

html, shot, dom_path, *logs = sys.argv[1:]
failures = []

# 1. The page is not blank.
if not os.path.exists(shot) or os.path.getsize(shot) == 0:
    failures.append("no screenshot was written")
else:
    img = Image.open(shot).convert("L")
    var = ImageStat.Stat(img).var[0]
    # The top of the page (title, tables) must show something too.
    top = ImageStat.Stat(img.crop((0, 0, img.width, min(img.height, 800)))).var[0]
    print(f"screenshot {img.width}x{img.height}, pixel variance {var:.1f} (top {top:.1f})")
    if var < 50 or top < 50:
        failures.append(f"the page looks blank (pixel variance {var:.1f}, top {top:.1f})")

# 2. Every figure is there.
dom = open(dom_path, encoding="utf-8", errors="replace").read()
if "<main" not in dom:
    failures.append("the DOM has no <main>: the page did not load")
m = re.search(r'data-figure-count="(\d+)"', dom)
expected = int(m.group(1)) if m else None
svgs = re.findall(r'<svg class="figure"[^>]*>(.*?)</svg>', dom, flags=re.S)
print(f"figures: {len(svgs)} inline SVG, {expected} announced")
if expected is None:
    failures.append("the report does not announce its figure count")
elif len(svgs) != expected:
    failures.append(f"{expected} figures announced but {len(svgs)} inline SVG found")
for i, body in enumerate(svgs, 1):
    if body.count("<") < 20 or "<text" not in body:
        failures.append(f"figure {i} is empty or has no text")
base = os.path.dirname(html)
for src in re.findall(r'<img[^>]*\bsrc="([^"]*)"', dom):
    if re.match(r"^[a-z]+:", src) and not src.startswith("file:"):
        failures.append(f"<img> fetches {src}")
    elif not os.path.exists(os.path.join(base, src.replace("file://", ""))):
        failures.append(f"<img> file missing: {src}")

# 3. Nothing is fetched from the network.
fetches = re.findall(
    r'<link[^>]+href="https?:[^"]*"|<script[^>]+src="[^"]*"|<iframe|@import|url\(\s*["\']?https?:',
    dom,
)
for f in fetches:
    failures.append(f"the page fetches a resource: {f[:80]}")

# 4. No console message, no failed load.
bad = re.compile(r"CONSOLE|Uncaught|Failed to load|net::ERR_|Not allowed to load")
for path in logs:
    for line in open(path, encoding="utf-8", errors="replace"):
        if bad.search(line):
            failures.append("console: " + line.strip()[:200])

if failures:
    print("check-report: FAILED")
    for f in failures:
        print("  - " + f)
    sys.exit(1)
print("check-report: OK")
PY
