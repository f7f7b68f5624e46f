//! Pricing: the entering row, the one the vertex violates most (Dantzig on distances, or
//! Bland's rule after degenerate steps).

use super::tableau::{Tableau, Vertex};
use super::{Settings, dot, inf_norm};

/// The largest a·x − b over the rows and the first row that attains it ((−∞, usize::MAX) for
/// no rows). Four running maxima over interleaved rows keep the comparisons independent of
/// one another, so the loop is not bound by their latency; merging them by value, then by
/// index, gives the same row as one scan in order.
pub(super) fn most_violated<const D: usize>(
    a: &[[f64; D]],
    b: &[f64],
    x: &[f64; D],
) -> (f64, usize) {
    const LANES: usize = 4;
    let mut best = [(f64::NEG_INFINITY, usize::MAX); LANES];
    let n = a.len().min(b.len());
    let whole = n - n % LANES;
    for (i, (rows, bs)) in a[..whole]
        .chunks_exact(LANES)
        .zip(b[..whole].chunks_exact(LANES))
        .enumerate()
    {
        for l in 0..LANES {
            let v = dot(&rows[l], x) - bs[l];
            if v > best[l].0 {
                best[l] = (v, i * LANES + l);
            }
        }
    }
    for k in whole..n {
        let v = dot(&a[k], x) - b[k];
        let l = k % LANES;
        if v > best[l].0 {
            best[l] = (v, k);
        }
    }
    best.into_iter()
        .fold((f64::NEG_INFINITY, usize::MAX), |m, c| {
            if c.0 > m.0 || (c.0 == m.0 && c.1 < m.1) {
                c
            } else {
                m
            }
        })
}

/// The entering row chosen by pricing, or `None` when no row is violated.
pub(super) struct Pricing {
    pub(super) entering: Option<usize>,
    /// Largest finite-part violation a·x0 − b over rows (at M-part ≈ 0).
    pub(super) max_violation: f64,
}

pub(super) fn price<const D: usize>(
    t: &Tableau<'_, D>,
    v: &Vertex<D>,
    in_basis: &[bool],
    settings: &Settings,
    bland: bool,
) -> Pricing {
    let phase1 = v.x1.iter().any(|&z| z != 0.0);
    let tol0 = settings.tol_feasibility * (1.0 + inf_norm(&v.x0));
    let tol1 = settings.tol_feasibility * (1.0 + inf_norm(&v.x1));
    // Best (score, index) in the M-part and in the finite part.
    let mut best1: Option<(f64, usize)> = None;
    let mut best0: Option<(f64, usize)> = None;
    let mut max_violation = f64::NEG_INFINITY;
    if !phase1 {
        // Phase 2: the M-part of every real row is zero, so only its finite violation counts;
        // basic and ignored rows have b/|a| = +∞ and never win.
        let mut best = (f64::NEG_INFINITY, usize::MAX);
        if bland {
            for (k, (row, &bk)) in t.unit.iter().zip(&t.unit_b).enumerate() {
                let v0 = dot(row, &v.x0) - bk;
                if v0 > tol0 && best0.is_none() {
                    best0 = Some((v0, k));
                }
                best = if v0 > best.0 { (v0, k) } else { best };
            }
        } else {
            best = most_violated(&t.unit, &t.unit_b, &v.x0);
            if best.0 > tol0 {
                best0 = Some(best);
            }
        }
        max_violation = best.0;
    }
    if phase1 {
        // Real rows have no M-part in b: their M-violation is a·x1/|a|. Ignored rows (a = 0
        // here) and basic rows have b/|a| = +∞, so only a row whose M-violation is positive
        // needs the basis test.
        for (k, (row, &bk)) in t.unit.iter().zip(&t.unit_b).enumerate() {
            let v1 = dot(row, &v.x1);
            if v1 > tol1 {
                if !in_basis[k] && best1.is_none_or(|(s, _)| !bland && v1 > s) {
                    best1 = Some((v1, k));
                }
                continue;
            }
            if v1 < -tol1 {
                continue;
            }
            let v0 = dot(row, &v.x0) - bk;
            if v0 > max_violation {
                max_violation = v0;
            }
            if v0 > tol0 && best0.is_none_or(|(s, _)| !bland && v0 > s) {
                best0 = Some((v0, k));
            }
        }
    }
    let mut consider = |k: usize, row: &[f64; D], inv: f64, b0: f64, b1: f64| {
        let v1 = if phase1 {
            (dot(row, &v.x1) - b1) * inv
        } else {
            -b1 * inv
        };
        if v1 > tol1 {
            if best1.is_none_or(|(s, _)| !bland && v1 > s) {
                best1 = Some((v1, k));
            }
            return;
        }
        if v1 < -tol1 {
            return;
        }
        let v0 = (dot(row, &v.x0) - b0) * inv;
        if v0 > max_violation {
            max_violation = v0;
        }
        if v0 > tol0 && best0.is_none_or(|(s, _)| !bland && v0 > s) {
            best0 = Some((v0, k));
        }
    };
    for i in 0..D {
        let k = t.m + i;
        if in_basis[k] {
            continue;
        }
        consider(k, &t.row(k), 1.0, 0.0, 1.0);
    }
    // In Bland mode the lowest index wins; real rows come before artificial ones, and the
    // M-part dominates the finite part.
    let entering = match (best1, best0) {
        (Some((_, k)), _) => Some(k),
        (None, Some((_, k))) => Some(k),
        (None, None) => None,
    };
    Pricing {
        entering,
        max_violation: max_violation.max(0.0),
    }
}
