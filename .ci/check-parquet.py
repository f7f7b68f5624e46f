"""Reads every Parquet file of a run directory as a notebook user would.

Usage: python check-parquet.py RUN_DIR [--seed]

Each file must open with pandas (pyarrow engine) and with pyarrow directly, hold no view
types, and carry a description for every column of results.parquet. With --seed, the
results of the seed study must select rows by the decimals of its grid (mu == 0.3).
"""

import pathlib
import sys

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq


def is_view(t: pa.DataType) -> bool:
    if pa.types.is_string_view(t) or pa.types.is_binary_view(t):
        return True
    if pa.types.is_list(t) or pa.types.is_large_list(t):
        return is_view(t.value_type)
    return False


def main() -> int:
    run = pathlib.Path(sys.argv[1])
    seed = "--seed" in sys.argv[2:]
    files = sorted(run.glob("*.parquet"))
    if not files:
        print(f"no Parquet files in {run}")
        return 1
    failures = []
    for f in files:
        try:
            df = pd.read_parquet(f)
            schema = pq.read_schema(f)
        except Exception as e:  # a file a reader cannot open is the failure we look for
            failures.append(f"{f.name}: {type(e).__name__}: {e}")
            continue
        views = [fl.name for fl in schema if is_view(fl.type)]
        if views:
            failures.append(f"{f.name}: view types in {views}")
        print(f"{f.name}: {len(df)} rows, {len(df.columns)} columns")
    results = run / "results.parquet"
    if results.exists():
        schema = pq.read_schema(results)
        undocumented = [fl.name for fl in schema if not (fl.metadata or {}).get(b"description")]
        if undocumented:
            failures.append(f"results.parquet: no description for {undocumented}")
        if seed:
            df = pd.read_parquet(results)
            for mu in (0.3, 0.35, 0.31):
                n = int((df["mu"] == mu).sum())
                print(f"results.parquet: mu == {mu} selects {n} rows")
                if n == 0:
                    failures.append(f"results.parquet: mu == {mu} selects nothing")
    print(f"pandas {pd.__version__}, pyarrow {pa.__version__}")
    for msg in failures:
        print("FAILED", msg)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
