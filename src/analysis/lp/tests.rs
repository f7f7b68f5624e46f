//! Tests of the dense LP solver.

use super::pricing::most_violated;
use super::*;
use approx::{abs_diff_eq, assert_abs_diff_eq};

fn solve<const D: usize>(c: [f64; D], a: &[[f64; D]], b: &[f64]) -> Solution<D> {
    maximise(&c, a, b, &Settings::default()).unwrap()
}

proptest::proptest! {
    #[test]
    fn most_violated_is_the_first_largest_of_one_scan(
        rows in proptest::collection::vec(
            (proptest::array::uniform3(-3i32..3), -2i32..2, proptest::bool::ANY),
            0..23,
        ),
        x in proptest::array::uniform3(-2i32..2),
    ) {
        // Small integers make ties common; masked rows (b = +∞) never win.
        let a: Vec<[f64; 3]> = rows.iter().map(|r| r.0.map(f64::from)).collect();
        let b: Vec<f64> = rows
            .iter()
            .map(|r| if r.2 { f64::INFINITY } else { f64::from(r.1) })
            .collect();
        let x = x.map(f64::from);
        let mut want = (f64::NEG_INFINITY, usize::MAX);
        for (k, (row, bk)) in a.iter().zip(&b).enumerate() {
            let v = dot(row, &x) - bk;
            if v > want.0 {
                want = (v, k);
            }
        }
        proptest::prop_assert_eq!(most_violated(&a, &b, &x), want);
    }
}

#[test]
fn square_corner() {
    // max x + y, x ≤ 1, y ≤ 2, x + y ≥ −5.
    let s = solve(
        [1.0, 1.0],
        &[[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]],
        &[1.0, 2.0, 5.0],
    );
    assert_eq!(s.status, Status::Optimal);
    assert_abs_diff_eq!(s.x[0], 1.0, epsilon = 1e-15);
    assert_abs_diff_eq!(s.x[1], 2.0, epsilon = 1e-15);
    assert_abs_diff_eq!(s.objective, 3.0, epsilon = 1e-15);
    let mut basis: Vec<_> = s.basis.iter().flatten().copied().collect();
    basis.sort();
    assert_eq!(basis, vec![0, 1]);
    assert_abs_diff_eq!(s.duals[0], 1.0, epsilon = 1e-15);
    assert_abs_diff_eq!(s.duals[1], 1.0, epsilon = 1e-15);
}

#[test]
fn textbook_three_unknowns() {
    // max 3x + 2y + 4z  s.t.  x + y + 2z ≤ 4, 2x + 3z ≤ 5, 2x + y + 3z ≤ 7, x, y, z ≥ 0.
    // Optimum: x = 2.5, y = 1.5, z = 0, value 10.5.
    let a = [
        [1.0, 1.0, 2.0],
        [2.0, 0.0, 3.0],
        [2.0, 1.0, 3.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, -1.0],
    ];
    let b = [4.0, 5.0, 7.0, 0.0, 0.0, 0.0];
    let s = solve([3.0, 2.0, 4.0], &a, &b);
    assert_eq!(s.status, Status::Optimal);
    assert!(abs_diff_eq!(s.objective, 10.5, epsilon = 1e-13), "{s:?}");
    assert_abs_diff_eq!(s.x[0], 2.5, epsilon = 1e-13);
    assert_abs_diff_eq!(s.x[1], 1.5, epsilon = 1e-13);
    assert_abs_diff_eq!(s.x[2], 0.0, epsilon = 1e-13);
}

#[test]
fn infeasible_strip() {
    // x ≤ 1 and x ≥ 2.
    let s = solve([1.0, 0.0], &[[1.0, 0.0], [-1.0, 0.0]], &[1.0, -2.0]);
    assert_eq!(s.status, Status::Infeasible);
    assert!(s.x.iter().all(|v| v.is_finite()));
}

#[test]
fn unbounded_with_a_ray() {
    // max x s.t. x − 2y ≤ 0, −y ≤ 0: unbounded along (2, 1).
    let s = solve([1.0, 0.0], &[[1.0, -2.0], [0.0, -1.0]], &[0.0, 0.0]);
    assert_eq!(s.status, Status::Unbounded);
    assert!(s.ray[0] > 0.0);
    assert!(s.ray[0] - 2.0 * s.ray[1] <= 1e-15 && -s.ray[1] <= 1e-15);
}

#[test]
fn free_direction_is_not_unbounded() {
    // max x s.t. x ≤ 3 and a zero row: y and z appear nowhere and stay free.
    let s = solve(
        [1.0, 0.0, 0.0],
        &[[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        &[3.0, 1.0],
    );
    assert_eq!(s.status, Status::Optimal);
    assert_abs_diff_eq!(s.objective, 3.0, epsilon = 1e-15);
    assert_eq!(s.basis.iter().flatten().count(), 1);
}

#[test]
fn free_direction_needing_a_shift() {
    // max x s.t. x ≤ 1, x − y ≤ −5: y is free but must reach x + 5.
    let s = solve([1.0, 0.0], &[[1.0, 0.0], [1.0, -1.0]], &[1.0, -5.0]);
    assert_eq!(s.status, Status::Optimal);
    assert_abs_diff_eq!(s.x[0], 1.0, epsilon = 1e-15);
    assert!(s.x[0] - s.x[1] <= -5.0 + 1e-12, "{s:?}");
    assert!(s.max_violation <= 1e-12);
}

#[test]
fn zero_objective_is_a_feasibility_problem() {
    let s = solve(
        [0.0, 0.0],
        &[[1.0, 1.0], [-1.0, 0.0], [0.0, -1.0]],
        &[1.0, -0.2, -0.3],
    );
    assert_eq!(s.status, Status::Optimal);
    assert!(s.max_violation <= 1e-15);
    let s = solve(
        [0.0, 0.0],
        &[[1.0, 1.0], [-1.0, 0.0], [0.0, -1.0]],
        &[1.0, -0.6, -0.6],
    );
    assert_eq!(s.status, Status::Infeasible);
}

#[test]
fn zero_rows_and_infinite_rhs() {
    let a = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 5.0]];
    let s = solve([1.0, 1.0], &a, &[0.0, 1.0, 1.0, f64::INFINITY]);
    assert_eq!(s.status, Status::Optimal);
    assert_abs_diff_eq!(s.objective, 2.0, epsilon = 1e-15);
    let s = solve([1.0, 1.0], &a, &[-1e-300, 1.0, 1.0, 3.0]);
    assert_eq!(s.status, Status::Infeasible);
    let s = solve([1.0, 1.0], &a, &[0.0, 1.0, 1.0, f64::NEG_INFINITY]);
    assert_eq!(s.status, Status::Infeasible);
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let s = maximise(&[1.0], &[[f64::NAN]], &[1.0], &Settings::default());
    assert!(matches!(s, Err(LpError::NotFinite { what: "row", .. })));
    let s = maximise(&[1.0], &[[1.0]], &[f64::NAN], &Settings::default());
    assert!(matches!(s, Err(LpError::NotFinite { what: "rhs", .. })));
    let s = maximise(&[1.0], &[[1.0]], &[], &Settings::default());
    assert!(matches!(s, Err(LpError::DimensionMismatch { .. })));
    let s = maximise::<0>(&[], &[], &[], &Settings::default());
    assert!(matches!(s, Err(LpError::NoUnknowns)));
}

#[test]
fn no_rows() {
    let s = solve([0.0, 0.0], &[], &[]);
    assert_eq!(s.status, Status::Optimal);
    let s = solve([0.0, -1.0], &[], &[]);
    assert_eq!(s.status, Status::Unbounded);
}

#[test]
fn heavily_degenerate_polygon() {
    // max y over the regular 2000-gon inscribed in the unit circle, each edge repeated
    // three times and a thousand rows through the top vertex: the optimum is 1.
    let n = 2000;
    let mut a = Vec::new();
    let mut b = Vec::new();
    for i in 0..n {
        let t = 2.0 * std::f64::consts::PI * (i as f64 + 0.5) / n as f64;
        let h = (std::f64::consts::PI / n as f64).cos();
        for _ in 0..3 {
            a.push([t.cos(), t.sin()]);
            b.push(h);
        }
    }
    // Rows through (0, 1) after a rotation by π/2 … the top vertex is at angle π/2 only
    // for n ≡ 0 mod 4; add rows touching the optimum of the polygon instead.
    let s0 = solve([0.0, 1.0], &a, &b);
    assert_eq!(s0.status, Status::Optimal);
    for j in 0..1000 {
        let t = 0.2 + 0.6 * std::f64::consts::PI * j as f64 / 1000.0;
        let (st, ct) = t.sin_cos();
        a.push([ct, st]);
        b.push(ct * s0.x[0] + st * s0.x[1]);
    }
    let s = solve([0.0, 1.0], &a, &b);
    assert_eq!(s.status, Status::Optimal);
    assert!(
        abs_diff_eq!(s.objective, s0.objective, epsilon = 1e-13),
        "{s:?} vs {s0:?}"
    );
    assert_abs_diff_eq!(s0.objective, 1.0, epsilon = 1e-5);
}

#[test]
fn parallel_and_duplicate_rows() {
    // max x + y + z over the unit cube given by duplicated and scaled faces.
    let mut a = Vec::new();
    let mut b = Vec::new();
    for s in [1.0, 2.0, 1e-3, 1e3] {
        for i in 0..3 {
            let mut r = [0.0; 3];
            r[i] = s;
            a.push(r);
            b.push(s);
            r[i] = -s;
            a.push(r);
            b.push(0.0);
        }
    }
    let s = solve([1.0, 1.0, 1.0], &a, &b);
    assert_eq!(s.status, Status::Optimal);
    assert_abs_diff_eq!(s.objective, 3.0, epsilon = 1e-14);
}

#[test]
fn cycling_example_of_beale() {
    // Beale's classic cycling LP (as a maximisation with x ≥ 0):
    // max 0.75x4 − 20x5 + 0.5x6 − 6x7 s.t.
    // 0.25x4 − 8x5 − x6 + 9x7 ≤ 0, 0.5x4 − 12x5 − 0.5x6 + 3x7 ≤ 0, x6 ≤ 1. Value 1.25.
    let mut a = vec![
        [0.25, -8.0, -1.0, 9.0],
        [0.5, -12.0, -0.5, 3.0],
        [0.0, 0.0, 1.0, 0.0],
    ];
    let mut b = vec![0.0, 0.0, 1.0];
    for i in 0..4 {
        let mut r = [0.0; 4];
        r[i] = -1.0;
        a.push(r);
        b.push(0.0);
    }
    let s = solve([0.75, -20.0, 0.5, -6.0], &a, &b);
    assert_eq!(s.status, Status::Optimal);
    assert!(abs_diff_eq!(s.objective, 1.25, epsilon = 1e-13), "{s:?}");
}

#[test]
fn random_programmes_match_vertex_enumeration() {
    // Small random LPs in 2 unknowns inside a box: brute force over all row pairs.
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    };
    for _ in 0..200 {
        let mut a = vec![[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]];
        let mut b = vec![3.0, 3.0, 3.0, 3.0];
        for _ in 0..8 {
            a.push([rnd(), rnd()]);
            b.push(rnd());
        }
        let c = [rnd(), rnd()];
        let s = solve(c, &a, &b);
        let always_bland = Settings {
            degenerate_steps_before_bland: 0,
            ..Settings::default()
        };
        let s_bland = maximise(&c, &a, &b, &always_bland).unwrap();
        assert_eq!(s.status, s_bland.status);
        if s.status == Status::Optimal {
            assert_abs_diff_eq!(s.objective, s_bland.objective, epsilon = 1e-12);
        }
        let mut best = f64::NEG_INFINITY;
        for i in 0..a.len() {
            for j in i + 1..a.len() {
                let det = a[i][0] * a[j][1] - a[i][1] * a[j][0];
                if det.abs() < 1e-12 {
                    continue;
                }
                let x = [
                    (b[i] * a[j][1] - a[i][1] * b[j]) / det,
                    (a[i][0] * b[j] - b[i] * a[j][0]) / det,
                ];
                if a.iter().zip(&b).all(|(r, bi)| dot(r, &x) <= bi + 1e-12) {
                    best = best.max(dot(&c, &x));
                }
            }
        }
        if best.is_finite() {
            assert_eq!(s.status, Status::Optimal);
            assert!(
                abs_diff_eq!(s.objective, best, epsilon = 1e-10),
                "{} vs {best}",
                s.objective
            );
        } else {
            assert_eq!(s.status, Status::Infeasible);
        }
    }
}

#[test]
fn random_four_unknown_programmes_match_clarabel() {
    use clarabel::algebra::CscMatrix;
    use clarabel::solver::{
        DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    };
    let mut seed = 987654321u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    };
    for _ in 0..40 {
        // A bounded polytope: random rows with positive right-hand sides around the origin
        // plus a loose box, and rows duplicated to make the optimum degenerate.
        let mut a = Vec::new();
        let mut b = Vec::new();
        for i in 0..4 {
            for s in [1.0, -1.0] {
                let mut r = [0.0; 4];
                r[i] = s;
                a.push(r);
                b.push(10.0);
            }
        }
        for _ in 0..60 {
            let r = [rnd(), rnd(), rnd(), rnd()];
            let bi = 0.1 + rnd().abs();
            a.push(r);
            b.push(bi);
            a.push(r.map(|v| 3.0 * v));
            b.push(3.0 * bi);
        }
        let c = [rnd(), rnd(), rnd(), rnd()];
        let ours = solve(c, &a, &b);
        assert_eq!(ours.status, Status::Optimal);
        assert!(ours.max_violation <= 1e-12);
        let p = CscMatrix::<f64>::zeros((4, 4));
        let q = c.map(|v| -v);
        let am = CscMatrix::from(a.iter());
        let cones = [NonnegativeConeT(b.len())];
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .build()
            .unwrap();
        let mut solver = DefaultSolver::new(&p, &q, &am, &b, &cones, settings).unwrap();
        solver.solve();
        assert_eq!(solver.solution.status, SolverStatus::Solved);
        let theirs = dot(&c, &[0, 1, 2, 3].map(|i| solver.solution.x[i]));
        assert!(
            abs_diff_eq!(
                ours.objective,
                theirs,
                epsilon = 1e-6 * (1.0 + theirs.abs())
            ),
            "{} vs {theirs}",
            ours.objective
        );
    }
}
