//! The ratio test: the basic row that leaves when a row enters (Harris two-pass, or Bland).

use super::simplex::Context;
use super::tableau::{Tableau, Vertex};

/// The basic slot that leaves when row `r` enters (Harris two-pass, or Bland's rule).
/// `None`: no positive pivot, the programme is infeasible. Also returns the step length.
pub(super) fn ratio_test<const D: usize>(
    ctx: &Context<'_, D>,
    t: &Tableau<'_, D>,
    v: &Vertex<D>,
    basis: &[usize; D],
    r: usize,
    bland: bool,
) -> Option<(usize, f64)> {
    let (settings, ymax) = (ctx.settings, ctx.ymax);
    let ar = t.row(r);
    let u = v.lu.solve_t(&ar);
    let nr = t.row_norm(r);
    let tol_d = settings.tol_dual * ymax;
    let mut eligible = [false; D];
    let mut bound = f64::INFINITY;
    let mut any = false;
    for k in 0..D {
        let scaled = u[k] * t.row_norm(basis[k]) / nr;
        if scaled > settings.tol_pivot && u[k] > 0.0 {
            eligible[k] = true;
            any = true;
            bound = bound.min((v.y[k].max(0.0) + tol_d) / u[k]);
        }
    }
    if !any {
        return None;
    }
    let mut pick: Option<usize> = None;
    if bland {
        let mut min_ratio = f64::INFINITY;
        for k in 0..D {
            if eligible[k] {
                min_ratio = min_ratio.min(v.y[k].max(0.0) / u[k]);
            }
        }
        for k in 0..D {
            if eligible[k] {
                let ratio = v.y[k].max(0.0) / u[k];
                if ratio <= min_ratio + tol_d / u[k] && pick.is_none_or(|p| basis[k] < basis[p]) {
                    pick = Some(k);
                }
            }
        }
    } else {
        let mut best = 0.0;
        for k in 0..D {
            if eligible[k] {
                let ratio = v.y[k].max(0.0) / u[k];
                let scaled = u[k] * t.row_norm(basis[k]);
                if ratio <= bound && scaled > best {
                    best = scaled;
                    pick = Some(k);
                }
            }
        }
    }
    pick.map(|k| (k, v.y[k].max(0.0) / u[k]))
}
