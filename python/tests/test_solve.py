"""`solve`, `thresholds` and the drawing of a solution, against the command line."""

from __future__ import annotations

import math

import pytest

import archstudy
from conftest import cli_json

# (keyword arguments, the same scene as command-line options)
SCENES = [
    (dict(k=1.35, mu=0.4), ["--k", "1.35", "--mu", "0.4"]),
    (dict(k=1.2, mu=math.inf), ["--k", "1.2"]),
    (dict(find="thickness", mu=0.35), ["--find", "thickness", "--mu", "0.35"]),
    (dict(find="friction", k=1.3), ["--find", "friction", "--k", "1.3"]),
    (dict(find="thrust", k=1.2, mu=0.5), ["--find", "thrust", "--k", "1.2", "--mu", "0.5"]),
    (dict(find="thresholds"), ["--find", "thresholds"]),
    (dict(find="thickness", mu=0.4, voussoirs=9),
     ["--find", "thickness", "--mu", "0.4", "--voussoirs", "9"]),
    (dict(find="load_factor", k=1.3, mu=0.6, load="horizontal"),
     ["--find", "load-factor", "--k", "1.3", "--mu", "0.6", "--load", "horizontal"]),
    (dict(find="load_factor", k=1.25, mu=0.5, load="point", at=30.0),
     ["--find", "load-factor", "--k", "1.25", "--mu", "0.5", "--load", "point", "--at", "30"]),
    (dict(k=1.3, mu=0.5, shape="pointed", eccentricity=0.5, load="point", at_x=0.3,
          lambda_=0.05),
     ["--k", "1.3", "--mu", "0.5", "--shape", "pointed", "--eccentricity", "0.5", "--load",
      "point", "--at-x", "0.3", "--lambda", "0.05"]),
    (dict(find="friction", k=1.3, joints="vertical", half_angle=80.0),
     ["--find", "friction", "--k", "1.3", "--joints", "vertical", "--half-angle", "80"]),
    (dict(find="load_factor", k=1.25, mu=0.3, half_angle=60.0, load="point", at_x=0.25,
          width=0.05),
     ["--find", "load-factor", "--k", "1.25", "--mu", "0.3", "--half-angle", "60", "--load",
      "point", "--at-x", "0.25", "--width", "0.05"]),
]


def test_a_patch_load_replaces_the_sliver_by_the_block_under_it():
    # α = 60°, x/L = 0.25, μ = 0.3: concentrated, λ_max 0.4893568 at every K (a sliver);
    # spread over 0.05 of the span, 0.5427678 (the block under the patch slides).
    point = archstudy.solve(find="load_factor", k=1.25, mu=0.3, half_angle=60.0,
                            load="point", at_x=0.25)
    patch = archstudy.solve(find="load_factor", k=1.25, mu=0.3, half_angle=60.0,
                            load="point", at_x=0.25, width=0.05)
    assert abs(point.load_factor - 0.4893567758) < 1e-9
    assert abs(patch.load_factor - 0.5427678387) < 1e-9
    assert patch.to_dict()["load_width"] == 0.05
    with pytest.raises(ValueError, match="width"):
        archstudy.solve(load="horizontal", width=0.1)


def close(a, b, tol: float) -> bool:
    """Equal values, floats to `tol` relative to their size, recursively."""
    if isinstance(a, float) or isinstance(b, float):
        if a is None or b is None:
            return a is b
        return abs(a - b) <= tol * max(1.0, abs(a), abs(b))
    if isinstance(a, list):
        return len(a) == len(b) and all(close(x, y, tol) for x, y in zip(a, b))
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(close(a[k], b[k], tol) for k in a)
    return a == b


@pytest.mark.parametrize("kwargs,argv", SCENES)
def test_solve_gives_the_json_of_the_command_line_to_1e_12(cli, kwargs, argv):
    want = cli_json(cli, *argv)
    got = archstudy.solve(**kwargs).to_dict()
    want.pop("solve_time_us")
    got.pop("solve_time_us")
    assert got.keys() == want.keys()
    bad = [k for k in want if not close(got[k], want[k], 1e-12)]
    assert not bad, {k: (got[k], want[k]) for k in bad}


def test_attributes_are_typed_records():
    s = archstudy.solve(find="thickness", mu=0.35)
    assert s.outcome == "found"
    assert isinstance(s.k_crit, float) and 1.1 < s.k_crit < 1.3
    assert s.k is None and s.regime is None
    assert s.hinges and all(isinstance(h, archstudy.Hinge) for h in s.hinges)
    assert {h.face for h in s.hinges} <= {"intrados", "extrados"}
    assert s.k_windows[0][0] == s.k_crit
    assert "k_crit=" in repr(s) and "regime" not in repr(s)
    p = archstudy.solve(find="load_factor", k=1.3, mu=0.6, load="horizontal")
    assert p.lambda_ is None and p.load_factor is not None and p.load_factor > 0


def test_thresholds_are_the_papers_four_critical_values():
    t = archstudy.thresholds()
    # The semicircle of the paper: K_c = 1.1136 at μ = ∞, the bifurcations at
    # (K = 1.1136, μ = 0.395) and (K = 1.2205, μ = 0.309).
    assert t.k_c_rotational == pytest.approx(1.1136, abs=1e-4)
    assert t.mu_rotational_mixed == pytest.approx(0.395, abs=1e-3)
    assert t.mu_min == pytest.approx(0.309, abs=1e-3)
    assert t.k_mixed_sliding == pytest.approx(1.2205, abs=1e-4)
    assert t == archstudy.Thresholds(*(archstudy.solve(find="thresholds").to_dict()[k] for k in
                                       archstudy.Thresholds._fields))


def test_the_svg_draws_the_collapse_state_of_the_asked_arch():
    s = archstudy.solve(find="thickness", mu=0.35)
    svg = s._repr_svg_()
    assert svg.startswith("<svg") and svg.rstrip().endswith("</svg>")
    assert f"K = {s.k_crit:.4g}"[:8] in svg, "the title names the collapse thickness"
    assert "pointed" not in svg
    p = archstudy.solve(k=1.3, mu=0.6, shape="pointed", eccentricity=0.5)
    psvg = p._repr_svg_()
    assert "pointed, e = 0.5" in psvg, "the pointed arch is named in the title"
    v = archstudy.solve(k=1.3, mu=0.6, voussoirs=7)
    assert "N = 7 voussoirs" in v._repr_svg_()
    # A find with a gap draws its collapse, below the static limit it names.
    g = archstudy.solve(find="load_factor", voussoirs=12, k=1.5278, mu=1.0396,
                        half_angle=50.367, load="horizontal")
    assert g.gap == "gap" and abs(g.collapse_value - 7.383083) < 1e-6
    gsvg = g._repr_svg_()
    assert "first complete solution" in gsvg
    assert "collapse λ = 7.3831" in gsvg and "static limit λ = 8.5180" in gsvg


def test_a_bad_keyword_value_raises_value_error_naming_it():
    with pytest.raises(ValueError, match=r"invalid value '0.9' for 'k': K = R/r must be"):
        archstudy.solve(k=0.9)
    with pytest.raises(ValueError, match=r"for 'mu': μ must be a number ≥ 0 or inf"):
        archstudy.solve(mu=-1.0)
    with pytest.raises(ValueError, match=r"for 'find': one of state, thickness"):
        archstudy.solve(find="collapse")
    with pytest.raises(ValueError, match=r"for 'at_x': x/L must lie in \[0, 1\]"):
        archstudy.solve(load="point", at_x=1.5, lambda_=0.1)
    with pytest.raises(ValueError, match=r"for 'voussoirs': N must be an integer"):
        archstudy.solve(voussoirs=2.5)
    with pytest.raises(ValueError, match=r"for 'eccentricity'"):
        archstudy.solve(eccentricity=0.3)
    # What a find computes is not also an input: the value would be left out unseen.
    with pytest.raises(ValueError, match=r"invalid value '1.3' for 'k': the thickness find"):
        archstudy.solve(find="thickness", k=1.3, mu=0.4)
    with pytest.raises(ValueError, match=r"invalid value '0.4' for 'mu': the friction find"):
        archstudy.solve(find="friction", k=1.3, mu=0.4)
