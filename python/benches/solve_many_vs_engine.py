"""solve_many against the engine of `archstudy run` on the same cases, same machine.

Two batches: the seed study's state grid refined to 1000 × 1000 = 10⁶ scenes (K from 1.05 to
1.5, μ from 0.2 to 0.8), and 100 × 100 = 10⁴ load factors of a horizontal load (K from 1.1
to 1.5, μ from 0.3 to 0.9). The engine's time is run.json's `stages.engine_ms` of the
command line's run of the same grid; solve_many's is its wall time, from the NumPy arrays to
the table, and (with pyarrow installed) on to a `pyarrow.Table` read through the Arrow stream.

    python python/benches/solve_many_vs_engine.py [--small] [--repeat 3] [--bin target/release/archstudy]
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import subprocess
import tempfile
import time

import numpy as np

import archstudy

try:
    import pyarrow as pa  # type: ignore[import-untyped]
except ImportError:
    pa = None


def grid(n: int, k: tuple[float, float], mu: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    ks = np.array([float(f"{x:.12g}") for x in np.linspace(k[0], k[1], n)])
    mus = np.array([float(f"{x:.12g}") for x in np.linspace(mu[0], mu[1], n)])
    return ks, mus


def engine_ms(cli: str, manifest: str, tmp: pathlib.Path, jobs: int) -> float:
    path = tmp / "bench.yaml"
    path.write_text(manifest, encoding="utf-8")
    subprocess.run([cli, "run", str(path), "--out", str(tmp / "out"), "--quiet", "--jobs",
                    str(jobs)], check=True)
    info = json.loads((tmp / "out" / "bench" / "run.json").read_text(encoding="utf-8"))
    return float(info["stages"]["engine_ms"])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="target/release/archstudy")
    ap.add_argument("--small", action="store_true", help="10⁴ states and 10² load factors")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=3, help="best of this many runs of each")
    a = ap.parse_args()
    n_state, n_lf = (100, 10) if a.small else (1000, 100)
    cases = [
        ("state", n_state, (1.05, 1.5), (0.2, 0.8), {}, "self_weight"),
        ("load_factor", n_lf, (1.1, 1.5), (0.3, 0.9), {"load": "horizontal"}, "horizontal"),
    ]
    if pa is not None:
        pa.table(archstudy.solve_many(k=1.2, mu=0.5))  # pyarrow's one-off set-up, not timed
    for find, n, kr, mr, extra, kind in cases:
        manifest = (
            f"name: bench\nfind: {find}\nload_cases:\n  - {{name: l, kind: {kind}}}\n"
            f"grid:\n  k: {{from: {kr[0]}, to: {kr[1]}, steps: {n}}}\n"
            f"  mu: {{from: {mr[0]}, to: {mr[1]}, steps: {n}}}\n"
        )
        ks, mus = grid(n, kr, mr)
        # Each the best of `repeat`, the engine and solve_many taking turns (a shared machine).
        e, p, q = math.inf, math.inf, math.inf
        for _ in range(a.repeat):
            with tempfile.TemporaryDirectory() as tmp:
                e = min(e, engine_ms(a.bin, manifest, pathlib.Path(tmp), a.jobs))
            t = time.perf_counter()
            table = archstudy.solve_many(k=ks[:, None], mu=mus[None, :], find=find,
                                         jobs=a.jobs, **extra)
            p = min(p, (time.perf_counter() - t) * 1e3)
            # The table read by pyarrow: string columns leave as Arrow large strings here.
            arrow = pa.table(table) if pa is not None else None
            q = min(q, (time.perf_counter() - t) * 1e3)
            assert table.num_rows == n * n
            assert arrow is None or arrow.num_rows == n * n
            del table, arrow
        line = (f"{find:12s} {n * n:>8d} scenes: engine {e:9.1f} ms, solve_many {p:9.1f} ms "
                f"(ratio {p / e:.2f})")
        if pa is not None:
            line += f", with pyarrow.table {q:9.1f} ms (ratio {q / e:.2f})"
        print(line)

if __name__ == "__main__":
    main()
