#!/usr/bin/env bash
# The Python package: the wheel built by maturin from python/ (sharing the workspace's target
# directory, so the core crate's dependencies built by `cargo build --release` are reused),
# installed in a clean virtual environment, then its pytest suite, mypy's stubtest of the
# type stubs and the example notebook executed. Needs target/release/archstudy (the tests
# compare with the command line).
set -euo pipefail
cd "$(dirname "$0")/.."

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
pip_quiet=(--quiet --disable-pip-version-check)

echo "-- wheel (maturin)"
python3 -m venv "$work/build"
"$work/build/bin/pip" install "${pip_quiet[@]}" "maturin>=1.7,<2"
CARGO_TARGET_DIR="$PWD/target" "$work/build/bin/maturin" build --release --locked \
  --manifest-path python/Cargo.toml --out "$work/wheels"

echo "-- clean environment"
python3 -m venv "$work/test"
"$work/test/bin/pip" install "${pip_quiet[@]}" "$work"/wheels/archstudy-*.whl \
  pytest pyarrow pandas polars mypy nbclient nbformat ipykernel

echo "-- pytest"
ARCHSTUDY_BIN="$PWD/target/release/archstudy" "$work/test/bin/python" -m pytest -q python/tests

echo "-- stubtest"
"$work/test/bin/python" -m mypy.stubtest archstudy

echo "-- example notebook"
artefacts="${CI_ARTIFACTS:-$PWD/output/ci-artifacts}"
mkdir -p "$artefacts"
(cd "$work" && "$work/test/bin/python" - "$OLDPWD/python/examples/notebook.ipynb" "$artefacts" <<'PY'
import sys
import nbclient
import nbformat

nb = nbformat.read(sys.argv[1], as_version=4)
nbclient.NotebookClient(nb, timeout=600, kernel_name="python3").execute()
print(f"executed {sum(c.cell_type == 'code' for c in nb.cells)} code cells")
# Kept to be looked at: the executed notebook, and its displayed outputs as one HTML page.
out = sys.argv[2]
nbformat.write(nb, f"{out}/notebook.ipynb")
parts = []
for cell in nb.cells:
    for o in cell.get("outputs", []):
        data = o.get("data", {})
        for kind in ("text/html", "image/svg+xml"):
            if kind in data:
                parts.append(data[kind])
                break
        else:
            text = data.get("text/plain") or o.get("text") or ""
            parts.append("<pre>" + text.replace("&", "&amp;").replace("<", "&lt;") + "</pre>")
with open(f"{out}/notebook-outputs.html", "w", encoding="utf-8") as f:
    f.write("<!doctype html><meta charset=utf-8><body>" + "<hr>".join(parts) + "</body>")
print(f"executed notebook and its outputs: {out}/notebook.ipynb, notebook-outputs.html")
PY
)
