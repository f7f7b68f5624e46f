"""`solve_many`: broadcasting, and one row equal to one `solve` on random scenes of every
arch, load and find."""

from __future__ import annotations

import math

import numpy as np
import pyarrow as pa
import pytest

import archstudy

RNG = np.random.default_rng(20261127)


def rows(table: archstudy.Table) -> list[dict]:
    return pa.table(table).to_pylist()


def same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    return a == b


# Every arch, load and find, with the ranges their random scenes are drawn from.
FAMILIES = {
    "state circular": (dict(), dict(k=(1.05, 1.5), mu=(0.2, 0.8))),
    "state pointed": (dict(shape="pointed"), dict(k=(1.1, 1.4), mu=(0.3, 0.9),
                                                   eccentricity=(0.1, 0.5))),
    "state horizontal": (dict(load="horizontal"), dict(k=(1.1, 1.5), mu=(0.3, 0.9),
                                                        lambda_=(0.0, 0.1))),
    "thickness voussoirs": (dict(find="thickness", voussoirs=11), dict(mu=(0.3, 0.9))),
    "friction vertical joints": (dict(find="friction", joints="vertical", half_angle=80.0),
                                 dict(k=(1.15, 1.4))),
    "thrust": (dict(find="thrust"), dict(k=(1.15, 1.4), mu=(0.4, 0.9))),
    "load_factor horizontal": (dict(find="load_factor", load="horizontal"),
                               dict(k=(1.1, 1.5), mu=(0.3, 0.9))),
    "load_factor point": (dict(find="load_factor", load="point"),
                          dict(k=(1.1, 1.5), mu=(0.4, 0.9), at=(-60.0, 60.0))),
}


@pytest.mark.parametrize("family", FAMILIES)
def test_each_row_is_the_answer_of_solve_for_that_scene(family):
    fixed, ranges = FAMILIES[family]
    n = 4
    drawn = {k: RNG.uniform(lo, hi, n) for k, (lo, hi) in ranges.items()}
    table = archstudy.solve_many(**fixed, **drawn)
    assert table.num_rows == n
    got = rows(table)
    for i in range(n):
        one = archstudy.solve(**fixed, **{k: float(v[i]) for k, v in drawn.items()})
        d = one.to_dict()
        row = got[i]
        assert row["case_id"] == i
        assert row["status"] == "ok", row["message"]
        for key in ("k", "t_over_r", "half_angle_deg", "outcome", "regime", "k_crit", "mu_crit",
                    "load_factor", "thrust_r_min", "thrust_r_max", "thrust_s_min",
                    "thrust_s_max", "thrust_min", "thrust_max", "mechanism",
                    "thrust_over_half_weight", "crown_moment", "collapse_value", "gap"):
            if key in row:
                assert same(row[key], d[key]), (family, i, key, row[key], d[key])
        if "hinge_angles_deg" in row:
            assert row["hinge_angles_deg"] == [h["angle_deg"] for h in d["hinges"]]


def test_arrays_and_scalars_broadcast_in_c_order():
    k = np.array([[1.1], [1.2], [1.3]])
    mu = np.array([0.3, 0.5, math.inf, 0.7])
    t = pa.table(archstudy.solve_many(k=k, mu=mu))
    assert t.num_rows == 12
    assert t.column("case_id").to_pylist() == list(range(12))
    assert t.column("k").to_pylist() == [1.1] * 4 + [1.2] * 4 + [1.3] * 4
    assert t.column("mu").to_pylist()[:4] == [0.3, 0.5, math.inf, 0.7]
    one = archstudy.solve(k=1.2, mu=0.5)
    r = t.slice(5, 1).to_pylist()[0]
    assert (r["regime"], r["thrust_r_min"], r["thrust_s_max"]) == (
        one.regime, one.thrust_r_min, one.thrust_s_max)


def test_a_batch_of_several_blocks_keeps_its_rows_in_order():
    # 200 × 200 scenes are solved and handed over in three blocks: the table reads them as
    # record batches in turn, every row where a single solve puts it.
    k = np.linspace(1.05, 1.5, 200)
    mu = np.linspace(0.2, 0.8, 200)
    t = pa.table(archstudy.solve_many(k=k[:, None], mu=mu[None, :]))
    assert t.num_rows == 40_000 and len(t.to_batches()) >= 3
    assert t.column("case_id").to_pylist() == list(range(40_000))
    assert t.column("k").to_pylist()[::200] == k.tolist()
    assert t.column("mu").to_pylist()[:200] == mu.tolist()
    for i in RNG.integers(0, 40_000, 25):
        r = t.slice(int(i), 1).to_pylist()[0]
        one = archstudy.solve(k=r["k"], mu=r["mu"])
        assert (r["regime"], r["thrust_r_min"], r["thrust_s_max"]) == (
            one.regime, one.thrust_r_min, one.thrust_s_max), i
    empty = archstudy.solve_many(k=np.array([]), mu=0.5)
    assert empty.num_rows == 0 and pa.table(empty).num_rows == 0
    assert empty.column_names == t.column_names


def test_the_columns_are_those_of_results_parquet_for_the_find():
    t = archstudy.solve_many(k=[1.2, 1.3], mu=0.4)
    names = t.column_names
    assert names[:4] == ["case_id", "load_case", "load_kind", "find"]
    assert "regime" in names and "k_crit" not in names
    assert names[-3:] == ["status", "message", "solve_time_us"]
    f = archstudy.solve_many(mu=[0.3, 0.4], find="thickness").column_names
    assert "k_crit" in f and "regime" not in f


def test_a_bad_value_names_its_scene_and_keyword():
    with pytest.raises(ValueError, match=r"scene 2: invalid value '0.9' for 'k'"):
        archstudy.solve_many(k=[1.1, 1.2, 0.9], mu=0.5)
    with pytest.raises(ValueError, match="for 'voussoirs'"):
        archstudy.solve_many(k=1.2, voussoirs=[3, 4.5])
    with pytest.raises(ValueError, match="shape mismatch|broadcast"):
        archstudy.solve_many(k=[1.1, 1.2], mu=[0.3, 0.4, 0.5])
