"""`run` and `open`: the same run directory as `archstudy run`, tables read by pyarrow,
pandas and polars, manifest errors, and Ctrl-C leaving nothing behind."""

from __future__ import annotations

import os
import pathlib
import signal
import subprocess
import sys
import textwrap
import time

import pyarrow as pa
import pyarrow.parquet as pq
import pytest

import archstudy

MANIFEST = {
    "name": "small",
    "grid": {"k": {"from": 1.05, "to": 1.5, "steps": 7},
             "mu": {"values": [0.2, 0.35, 0.5, 0.8, float("inf")]}},
    "load_cases": [{"name": "gravity", "kind": "self_weight"}],
    "find": "state",
    "scenes": [{"k": 1.35, "mu": 0.4}],
}
YAML = textwrap.dedent("""\
    name: small
    grid:
      k: {from: 1.05, to: 1.5, steps: 7}
      mu: {values: [0.2, 0.35, 0.5, 0.8, inf]}
    load_cases:
      - {name: gravity, kind: self_weight}
    find: state
    scenes:
      - {k: 1.35, mu: 0.4}
    """)
TABLES = ["results.parquet", "boundaries.parquet", "bifurcations.parquet", "states.parquet"]


def data(path: pathlib.Path) -> pa.Table:
    t = pq.read_table(path)
    return t.drop_columns([c for c in t.column_names if c.endswith("time_us")])


@pytest.fixture(scope="module")
def three_runs(tmp_path_factory, cli):
    base = tmp_path_factory.mktemp("runs")
    path = base / "small.yaml"
    path.write_text(YAML, encoding="utf-8")
    by_dict = archstudy.run(MANIFEST, out=base / "dict", jobs=2)
    by_path = archstudy.run(path, out=base / "path", jobs=2)
    subprocess.run([str(cli), "run", str(path), "--out", str(base / "cli"), "--quiet",
                    "--jobs", "2"], check=True)
    return by_dict, by_path, archstudy.open(base / "cli" / "small")


def test_run_of_a_dict_a_path_and_the_cli_store_the_same_data(three_runs):
    by_dict, by_path, by_cli = three_runs
    for name in TABLES:
        want = data(by_cli.dir / name)
        assert want.num_rows > 0 or name != "results.parquet"
        assert data(by_dict.dir / name).equals(want), name
        assert data(by_path.dir / name).equals(want), name
    files = lambda r: sorted(p.relative_to(r.dir).as_posix() for p in r.dir.rglob("*"))
    assert files(by_dict) == files(by_cli) == files(by_path)
    assert by_dict.results.num_rows == 35


def test_every_table_reads_in_pyarrow_pandas_and_polars(three_runs):
    run = three_runs[0]
    for name in ("results", "boundaries", "bifurcations", "states"):
        table = getattr(run, name)
        t = pa.table(table)
        stored = data(run.dir / archstudy._TABLES[name])
        assert t.num_rows == stored.num_rows, name
        assert t.select(stored.column_names).cast(stored.schema).equals(stored.cast(stored.schema)) \
            or t.num_rows == 0, name
        pd = pytest.importorskip("pandas")
        df = table.to_pandas()
        assert isinstance(df, pd.DataFrame) and len(df) == t.num_rows
        pl = pytest.importorskip("polars")
        p = table.to_polars()
        assert isinstance(p, pl.DataFrame) and p.height == t.num_rows
    r = run.results.to_pandas()
    assert set(r["regime"]) <= {"stable", "rotational", "mixed", "sliding", "none"}
    assert "<h3>archstudy run <code>small</code></h3>" in run._repr_html_()
    assert "<svg" in run._repr_html_()
    # The key results: those the report prints, each value the one stored where it says.
    keys = run.key_results()
    assert keys and {"quantity", "value", "stored in"} <= set(keys[0])
    stored_rows = {name: data(run.dir / name).to_pylist()
                   for name in ("boundaries.parquet", "bifurcations.parquet")}
    checked = 0
    for row in keys:
        where = row["stored in"].split()  # FILE row N COLUMN
        if where[0] in stored_rows and where[-1] in ("mu", "k", "t_over_r"):
            stored = stored_rows[where[0]][int(where[2])][where[-1]]
            # Printed to 10 decimals.
            assert abs(float(row["value"]) - stored) <= 1e-9 * max(1.0, abs(stored)), row
            checked += 1
    assert checked >= 4, keys
    assert "<h4>Key results</h4>" in run._repr_html_()
    assert row_html(keys[0]["quantity"]) in run._repr_html_()


def row_html(text: str) -> str:
    import html
    return f"<td>{html.escape(text)}</td>"


def test_a_bad_manifest_raises_manifest_error_with_its_position(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(YAML.replace("steps: 7", "steps: -3"), encoding="utf-8")
    with pytest.raises(archstudy.ManifestError) as e:
        archstudy.run(bad, out=tmp_path / "out")
    err = e.value
    assert err.file == str(bad)
    assert err.line == 3 and err.column is not None
    assert err.key is not None and "steps" in err.key
    assert "-3" in err.message
    assert err.value == "-3" and err.allowed == "steps must be an integer in [1, 100000]"
    assert str(err).startswith(f"{bad}:3:")
    with pytest.raises(archstudy.ManifestError, match="unknown|not a key|colour") as e:
        archstudy.run({**MANIFEST, "colour": "red"}, out=tmp_path / "out")
    assert e.value.key == "colour" and e.value.value == "colour"
    assert e.value.allowed.startswith("one of name, title")
    with pytest.raises(archstudy.ManifestError) as e:
        archstudy.run({**MANIFEST, "find": "nope"}, out=tmp_path / "out")
    assert (e.value.key, e.value.value) == ("find", "nope")
    assert e.value.allowed.startswith("use state, thickness, friction")
    assert not (tmp_path / "out" / "small").exists()
    with pytest.raises(ValueError, match="'jobs'"):
        archstudy.run(MANIFEST, out=tmp_path / "out", jobs=0)
    with pytest.raises(ValueError, match="not a run directory"):
        archstudy.open(tmp_path)


SLOW = textwrap.dedent("""\
    import sys, archstudy
    print("start", flush=True)
    archstudy.run({"name": "slow", "find": "load_factor",
                   "load_cases": [{"name": "h", "kind": "horizontal"}],
                   "grid": {"k": {"from": 1.1, "to": 1.6, "steps": 400},
                            "mu": {"from": 0.3, "to": 0.9, "steps": 400}}},
                  out=sys.argv[1], jobs=2)
    """)


@pytest.mark.parametrize("what", ["run", "solve_many"])
def test_ctrl_c_stops_within_a_second_and_leaves_nothing(tmp_path, what):
    script = SLOW if what == "run" else textwrap.dedent("""\
        import sys, numpy as np, archstudy
        print("start", flush=True)
        archstudy.solve_many(k=np.linspace(1.1, 1.6, 200000), mu=0.5, find="load_factor",
                             load="horizontal", jobs=2)
        """)
    out = tmp_path / "out"
    out.mkdir()
    p = subprocess.Popen([sys.executable, "-c", script, str(out)], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    assert p.stdout is not None
    assert p.stdout.readline().strip() == "start"
    time.sleep(2.0)
    assert p.poll() is None, "still working when interrupted"
    t = time.monotonic()
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=30)
    took = time.monotonic() - t
    assert "KeyboardInterrupt" in err, err
    assert took < 1.0, f"stopped {took:.2f} s after Ctrl-C"
    assert list(out.iterdir()) == [], "nothing is left in the output directory"


def test_a_sampling_run_gives_its_samples_and_estimates(tmp_path):
    manifest = {
        "name": "sampled",
        "uncertain": {
            "k": {"distribution": "uniform", "from": 1.08, "to": 1.2},
            "mu": {"distribution": "uniform", "from": 0.3, "to": 0.5},
        },
        "samples": {"n": 128, "seed": 1},
        "find": "probability",
    }
    run = archstudy.run(manifest, out=tmp_path, jobs=2)
    samples = pa.table(run.samples)
    assert samples.num_rows == 128
    assert set(samples.column_names) >= {"k", "mu", "stands", "mechanism"}
    est = pa.table(run.estimates).to_pylist()
    p = next(r for r in est if r["quantity"] == "probability")
    exact = next(r for r in est if r["quantity"] == "exact_probability")
    assert p["lo"] <= exact["value"] <= p["hi"]
    assert "probability" in run._repr_html_()


def test_a_grid_run_has_no_samples(three_runs):
    with pytest.raises(ValueError, match="has no samples.parquet"):
        three_runs[0].samples
