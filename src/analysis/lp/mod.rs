//! A dense linear programme in a few free unknowns and many rows:
//! maximise c·x subject to A x ≤ b (x ∈ ℝᴰ, D ≤ 5 in practice, up to ~10⁵ rows).
//!
//! Method: the simplex method applied to the dual, min b·y s.t. Aᵀy = c, y ≥ 0, with an
//! explicit D × D basis (refactorised at every step, which costs nothing next to the O(mD)
//! pricing pass). A basis is a set of D rows B with multipliers y_B = A_B⁻ᵀ c ≥ 0; its vertex
//! x = A_B⁻¹ b_B. Each step brings in the row that x violates most (distance to its plane)
//! and drops a basic row by the ratio test on y, so c·x = b·y never increases.
//!
//! Phase 1 is a symbolic big-M: D artificial rows s_i x_i ≤ M (s_i = sign c_i, M → ∞) form
//! the starting basis with y_i = |c_i|. Every quantity is a pair (finite part, M-part)
//! compared lexicographically, so no numerical M is ever chosen. Artificial rows left in the
//! final basis with y_i > 0 mean the programme is unbounded; with y_i = 0 they only say that
//! some direction is free. Harris' two-pass ratio test keeps pivots large; Bland's rule takes
//! over after a run of degenerate steps, so the method terminates.
//!
//! Outcomes (optimal, infeasible, unbounded, iteration limit) are [`Status`] values; `Err`
//! means malformed input only (NaN, mismatched lengths).

mod lu;
mod pricing;
mod ratio;
mod simplex;
mod tableau;
#[cfg(test)]
mod tests;

use simplex::simplex;
use tableau::Tableau;

pub use crate::analysis::settings::LpSettings as Settings;

/// Floor of the multiplier scale max |c|, so that a zero objective divides by no zero.
const MIN_MULTIPLIER_SCALE: f64 = 1e-300;

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Status {
    /// x is optimal within the tolerances.
    Optimal,
    /// No x satisfies all rows (a violated row is a non-positive combination of basic rows).
    Infeasible,
    /// The objective is unbounded above along [`Solution::ray`].
    Unbounded,
    /// `max_iterations` steps were taken without reaching an answer.
    IterationLimit,
    /// A basis turned out singular in floating point (not expected; reported, not hidden).
    NumericalFailure,
}

impl Status {
    /// `optimal`, `infeasible`, `unbounded`, `iteration_limit` or `numerical_failure`.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Optimal => "optimal",
            Status::Infeasible => "infeasible",
            Status::Unbounded => "unbounded",
            Status::IterationLimit => "iteration_limit",
            Status::NumericalFailure => "numerical_failure",
        }
    }
}

/// Malformed input (the only `Err` of [`maximise`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LpError {
    /// `a` and `b` have different lengths.
    #[error("the programme has {rows} rows but {rhs} right-hand sides")]
    DimensionMismatch {
        /// Rows of A.
        rows: usize,
        /// Entries of b.
        rhs: usize,
    },
    /// A coefficient is NaN or infinite, or a right-hand side is NaN.
    #[error("{what} {index} is not a finite number")]
    NotFinite {
        /// `objective`, `row` or `rhs`.
        what: &'static str,
        /// Index of the offending entry (row index for rows).
        index: usize,
    },
    /// Zero unknowns.
    #[error("the programme has no unknowns")]
    NoUnknowns,
}

/// The result of [`maximise`]; every number is finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solution<const D: usize> {
    /// How the solve ended.
    pub status: Status,
    /// The optimal point when `status` is optimal, else the last iterate (finite).
    pub x: [f64; D],
    /// c·x.
    pub objective: f64,
    /// The basic rows (`None` for an artificial row: a free direction).
    pub basis: [Option<usize>; D],
    /// Multipliers y ≥ 0 of the basic rows (dual solution: c = Σ y_k a_k).
    pub duals: [f64; D],
    /// When unbounded: a direction d with A d ≤ 0 and c·d > 0; zero otherwise.
    pub ray: [f64; D],
    /// Largest a·x − b over all rows at `x` (≤ 0 up to tolerance when optimal).
    pub max_violation: f64,
    /// Simplex steps taken.
    pub iterations: usize,
}

impl<const D: usize> Solution<D> {
    /// Indices of the rows with a·x − b ≥ −tol·|a| (rows active at x within a distance tol).
    pub fn active_rows(&self, a: &[[f64; D]], b: &[f64], tol: f64) -> Vec<usize> {
        a.iter()
            .zip(b)
            .enumerate()
            .filter(|(_, (row, bi))| {
                let n = norm(row);
                n > 0.0 && dot(row, &self.x) - **bi >= -tol * n
            })
            .map(|(i, _)| i)
            .collect()
    }
}

pub(super) fn dot<const D: usize>(a: &[f64; D], x: &[f64; D]) -> f64 {
    let mut s = 0.0;
    for i in 0..D {
        s += a[i] * x[i];
    }
    s
}

pub(super) fn norm<const D: usize>(a: &[f64; D]) -> f64 {
    dot(a, a).sqrt()
}

pub(super) fn inf_norm<const D: usize>(x: &[f64; D]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Maximises c·x subject to a\[r\]·x ≤ b\[r\] for every row r, x free.
///
/// Rows with b = +∞ are ignored; a row with b = −∞, or with a = 0 and b < 0, makes the
/// programme infeasible. Invariants: the multipliers stay non-negative, c·x never increases
/// along the iterations, every returned number is finite.
pub fn maximise<const D: usize>(
    c: &[f64; D],
    a: &[[f64; D]],
    b: &[f64],
    settings: &Settings,
) -> Result<Solution<D>, LpError> {
    if D == 0 {
        return Err(LpError::NoUnknowns);
    }
    if a.len() != b.len() {
        return Err(LpError::DimensionMismatch {
            rows: a.len(),
            rhs: b.len(),
        });
    }
    if let Some(i) = c.iter().position(|v| !v.is_finite()) {
        return Err(LpError::NotFinite {
            what: "objective",
            index: i,
        });
    }
    if let Some(i) = a.iter().position(|r| r.iter().any(|v| !v.is_finite())) {
        return Err(LpError::NotFinite {
            what: "row",
            index: i,
        });
    }
    if let Some(i) = b.iter().position(|v| v.is_nan()) {
        return Err(LpError::NotFinite {
            what: "rhs",
            index: i,
        });
    }
    let m = a.len();
    let mut signs = [1.0; D];
    for (s, ci) in signs.iter_mut().zip(c) {
        if *ci < 0.0 {
            *s = -1.0;
        }
    }
    let mut out = Solution {
        status: Status::Optimal,
        x: [0.0; D],
        objective: 0.0,
        basis: [None; D],
        duals: [0.0; D],
        ray: [0.0; D],
        max_violation: 0.0,
        iterations: 0,
    };
    let mut inv_norm = vec![0.0; m];
    for (r, (row, &bi)) in a.iter().zip(b).enumerate() {
        let n = norm(row);
        if bi == f64::INFINITY {
            continue;
        }
        if bi == f64::NEG_INFINITY || (n == 0.0 && bi < 0.0) {
            out.status = Status::Infeasible;
            out.basis[0] = Some(r);
            out.max_violation = f64::MAX;
            return Ok(out);
        }
        if n > 0.0 {
            inv_norm[r] = 1.0 / n;
        }
    }
    // Separate simple passes: each vectorises, which one pass with three pushes a row does not.
    let unit = a
        .iter()
        .zip(&inv_norm)
        .map(|(row, &inv)| row.map(|v| v * inv))
        .collect();
    let mut t = Tableau {
        a,
        b,
        inv_norm,
        signs,
        m,
        unit,
        unit_b: Vec::new(),
    };
    t.unit_b = (0..m).map(|k| t.unit_rhs(k)).collect();
    Ok(simplex(c, &mut t, settings))
}
