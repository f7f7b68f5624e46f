//! The programme as the simplex method sees it (real and artificial rows) and the vertex
//! and multipliers of one basis.

use super::dot;
use super::lu::Lu;
use super::simplex::Context;

/// The problem as the solver sees it: real rows 0..m, then the D artificial rows.
pub(super) struct Tableau<'a, const D: usize> {
    pub(super) a: &'a [[f64; D]],
    pub(super) b: &'a [f64],
    /// 1/|a_r| for real rows (0 for ignored rows).
    pub(super) inv_norm: Vec<f64>,
    /// Sign s_i of artificial row i: s_i x_i ≤ M.
    pub(super) signs: [f64; D],
    pub(super) m: usize,
    /// The real rows scaled to unit normal, a_r/|a_r|, for pricing (zero for ignored rows).
    pub(super) unit: Vec<[f64; D]>,
    /// Their right-hand sides b_r/|a_r|; +∞ for ignored rows and for the rows of the current
    /// basis, so that pricing needs no test to pass over them.
    pub(super) unit_b: Vec<f64>,
}

impl<const D: usize> Tableau<'_, D> {
    pub(super) fn row(&self, k: usize) -> [f64; D] {
        if k < self.m {
            self.a[k]
        } else {
            let mut r = [0.0; D];
            r[k - self.m] = self.signs[k - self.m];
            r
        }
    }

    /// Right-hand side as (finite part, M-part).
    pub(super) fn rhs(&self, k: usize) -> (f64, f64) {
        if k < self.m {
            (self.b[k], 0.0)
        } else {
            (0.0, 1.0)
        }
    }

    /// b_r/|a_r| of a real row (+∞ when it is ignored).
    pub(super) fn unit_rhs(&self, k: usize) -> f64 {
        if self.inv_norm[k] > 0.0 {
            self.b[k] * self.inv_norm[k]
        } else {
            f64::INFINITY
        }
    }

    /// Marks a real row as basic (`true`) or not for pricing.
    pub(super) fn set_basic(&mut self, k: usize, basic: bool) {
        if k < self.m {
            self.unit_b[k] = if basic {
                f64::INFINITY
            } else {
                self.unit_rhs(k)
            };
        }
    }

    pub(super) fn row_norm(&self, k: usize) -> f64 {
        if k < self.m {
            if self.inv_norm[k] > 0.0 {
                1.0 / self.inv_norm[k]
            } else {
                0.0
            }
        } else {
            1.0
        }
    }
}

/// The state of one basis.
pub(super) struct Vertex<const D: usize> {
    /// Finite and M-parts of the vertex.
    pub(super) x0: [f64; D],
    pub(super) x1: [f64; D],
    /// Multipliers.
    pub(super) y: [f64; D],
    pub(super) lu: Lu<D>,
}

/// The vertex and multipliers of a basis; `None` when the basis is singular.
pub(super) fn vertex<const D: usize>(
    ctx: &Context<'_, D>,
    t: &Tableau<'_, D>,
    basis: &[usize; D],
) -> Option<Vertex<D>> {
    let mut mat = [[0.0; D]; D];
    let mut r0 = [0.0; D];
    let mut r1 = [0.0; D];
    for (i, &k) in basis.iter().enumerate() {
        mat[i] = t.row(k);
        (r0[i], r1[i]) = t.rhs(k);
    }
    let lu = Lu::factor(mat, ctx.settings.tol_singular)?;
    let mut x0 = lu.solve(&r0);
    // One step of iterative refinement on the finite part.
    let mut res = [0.0; D];
    for i in 0..D {
        res[i] = r0[i] - dot(&mat[i], &x0);
    }
    let dx = lu.solve(&res);
    for i in 0..D {
        x0[i] += dx[i];
    }
    let x1 = if basis.iter().any(|&k| k >= t.m) {
        lu.solve(&r1)
    } else {
        [0.0; D]
    };
    let y = lu.solve_t(ctx.c);
    if x0.iter().chain(&x1).chain(&y).any(|v| !v.is_finite()) {
        return None;
    }
    Some(Vertex { x0, x1, y, lu })
}
