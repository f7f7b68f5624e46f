//! The simplex iteration on the dual and the answer at its last basis.

use super::pricing::price;
use super::ratio::ratio_test;
use super::tableau::{Tableau, Vertex, vertex};
use super::{MIN_MULTIPLIER_SCALE, Settings, Solution, Status, dot, inf_norm};

/// What every step of one solve shares: the objective, the settings and the scale of the
/// multipliers (max |c|).
pub(super) struct Context<'a, const D: usize> {
    /// The objective c.
    pub(super) c: &'a [f64; D],
    /// The solver settings.
    pub(super) settings: &'a Settings,
    /// max |c|, floored at [`MIN_MULTIPLIER_SCALE`].
    pub(super) ymax: f64,
}

/// The simplex method on the dual from the artificial basis, to an optimal, infeasible or
/// unbounded answer or the iteration limit.
pub(super) fn simplex<const D: usize>(
    c: &[f64; D],
    t: &mut Tableau<'_, D>,
    settings: &Settings,
) -> Solution<D> {
    let m = t.m;
    let mut basis = [0usize; D];
    for (i, k) in basis.iter_mut().enumerate() {
        *k = m + i;
    }
    let mut in_basis = vec![false; m + D];
    for &k in &basis {
        in_basis[k] = true;
    }
    let ymax = c
        .iter()
        .fold(0.0_f64, |s, v| s.max(v.abs()))
        .max(MIN_MULTIPLIER_SCALE);
    let ctx = Context { c, settings, ymax };
    let mut degenerate_run = 0;
    let mut last: Option<Vertex<D>> = None;
    let finish = |status: Status,
                  basis: &[usize; D],
                  v: Option<&Vertex<D>>,
                  iterations: usize,
                  max_violation: f64| {
        let mut s = Solution {
            status,
            x: [0.0; D],
            objective: 0.0,
            basis: [None; D],
            duals: [0.0; D],
            ray: [0.0; D],
            max_violation,
            iterations,
        };
        for (slot, &k) in s.basis.iter_mut().zip(basis) {
            *slot = (k < m).then_some(k);
        }
        if let Some(v) = v {
            s.x = v.x0;
            s.duals = v.y.map(|y| y.max(0.0));
            s.objective = dot(c, &v.x0);
        }
        s
    };
    for iter in 0..settings.max_iterations {
        let Some(v) = vertex(&ctx, t, &basis) else {
            return finish(Status::NumericalFailure, &basis, last.as_ref(), iter, 0.0);
        };
        let bland = degenerate_run >= settings.degenerate_steps_before_bland;
        let p = price(t, &v, &in_basis, settings, bland);
        let Some(r) = p.entering else {
            return optimal(&ctx, t, &basis, &v, iter, p.max_violation);
        };
        let Some((slot, step)) = ratio_test(&ctx, t, &v, &basis, r, bland) else {
            return finish(Status::Infeasible, &basis, Some(&v), iter, p.max_violation);
        };
        if step * ymax.recip() <= settings.tol_dual {
            degenerate_run += 1;
        } else {
            degenerate_run = 0;
        }
        in_basis[basis[slot]] = false;
        t.set_basic(basis[slot], false);
        basis[slot] = r;
        in_basis[r] = true;
        t.set_basic(r, true);
        last = Some(v);
    }
    finish(
        Status::IterationLimit,
        &basis,
        last.as_ref(),
        settings.max_iterations,
        0.0,
    )
}

/// The answer at a basis that no row violates: optimal, or unbounded when an artificial
/// row carries a positive multiplier.
pub(super) fn optimal<const D: usize>(
    ctx: &Context<'_, D>,
    t: &Tableau<'_, D>,
    basis: &[usize; D],
    v: &Vertex<D>,
    iterations: usize,
    max_violation: f64,
) -> Solution<D> {
    let Context { c, settings, ymax } = *ctx;
    let m = t.m;
    let mut s = Solution {
        status: Status::Optimal,
        x: v.x0,
        objective: 0.0,
        basis: [None; D],
        duals: v.y.map(|y| y.max(0.0)),
        ray: [0.0; D],
        max_violation,
        iterations,
    };
    for (slot, &k) in s.basis.iter_mut().zip(basis) {
        *slot = (k < m).then_some(k);
    }
    let unbounded = basis
        .iter()
        .zip(&v.y)
        .any(|(&k, &y)| k >= m && y > settings.tol_dual * ymax);
    if unbounded {
        s.status = Status::Unbounded;
        s.ray = v.x1;
        s.objective = dot(c, &v.x0);
        return s;
    }
    if v.x1.iter().any(|&z| z != 0.0) {
        // A free direction remains: move along it just far enough to satisfy the rows that
        // are satisfied only for large M (their M-part is negative).
        let tol1 = settings.tol_feasibility * (1.0 + inf_norm(&v.x1));
        let mut big_m: f64 = 0.0;
        for k in 0..m {
            let inv = t.inv_norm[k];
            if inv == 0.0 {
                continue;
            }
            let v1 = dot(&t.a[k], &v.x1) * inv;
            if v1 < -tol1 {
                let v0 = (dot(&t.a[k], &v.x0) - t.b[k]) * inv;
                if v0 > 0.0 {
                    big_m = big_m.max(v0 / -v1);
                }
            }
        }
        if big_m > 0.0 && big_m.is_finite() {
            for i in 0..D {
                s.x[i] += big_m * v.x1[i];
            }
            s.max_violation =
                t.a.iter()
                    .zip(t.b)
                    .zip(&t.inv_norm)
                    .filter(|(_, inv)| **inv > 0.0)
                    .map(|((row, bi), _)| dot(row, &s.x) - bi)
                    .fold(0.0, f64::max);
        }
    }
    s.objective = dot(c, &s.x);
    s
}
