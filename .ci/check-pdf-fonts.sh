#!/usr/bin/env bash
# Every PDF figure of a run directory has all of its fonts embedded: `pdffonts` (poppler-utils)
# lists each font with `emb yes`, and every PDF has at least one font (its text is text).
#
# Usage: .ci/check-pdf-fonts.sh RUN_DIR
set -euo pipefail

run="${1:?usage: .ci/check-pdf-fonts.sh RUN_DIR}"
shopt -s nullglob
pdfs=("$run"/plots/*.pdf)
if [ "${#pdfs[@]}" -eq 0 ]; then
  echo "check-pdf-fonts: no PDF in $run/plots" >&2
  exit 1
fi
fail=0
for pdf in "${pdfs[@]}"; do
  # Columns: name type encoding emb sub uni object ID; the first two lines are headers. The
  # name may not contain spaces (subset names do not), the type may ("CID TrueType").
  listing="$(pdffonts "$pdf")"
  fonts="$(printf '%s\n' "$listing" | tail -n +3)"
  if [ -z "$fonts" ]; then
    echo "check-pdf-fonts: $pdf has no font" >&2
    fail=1
    continue
  fi
  # emb is the fourth column from the right (emb sub uni object ID).
  bad="$(printf '%s\n' "$fonts" | awk '{ if ($(NF-4) != "yes") print }')"
  if [ -n "$bad" ]; then
    echo "check-pdf-fonts: $pdf has a font that is not embedded:" >&2
    printf '%s\n' "$bad" >&2
    fail=1
  fi
done
if [ "$fail" -ne 0 ]; then
  exit 1
fi
echo "check-pdf-fonts: ${#pdfs[@]} PDFs, every font embedded"
