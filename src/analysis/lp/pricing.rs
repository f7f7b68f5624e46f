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

/// Pricing tolerances at one vertex: violations above them count.
#[derive(Debug, Clone, Copy)]
struct Tolerances {
    /// On the finite part, relative to 1 + |x0|∞.
    finite: f64,
    /// On the M-part, relative to 1 + |x1|∞.
    m_part: f64,
}

/// The candidates pricing has found so far.
struct Choice {
    /// Best (violation, row) in the M-part.
    m_part: Option<(f64, usize)>,
    /// Best (violation, row) in the finite part.
    finite: Option<(f64, usize)>,
    /// Largest finite-part violation seen.
    max_violation: f64,
    /// Bland's rule: the first candidate wins, not the largest.
    bland: bool,
}

impl Choice {
    /// Offers row `k` with M-part violation `v1` above tolerance.
    fn offer_m_part(&mut self, v1: f64, k: usize) {
        if self.m_part.is_none_or(|(s, _)| !self.bland && v1 > s) {
            self.m_part = Some((v1, k));
        }
    }

    /// Offers row `k` with zero M-part (within tolerance) and finite violation `v0`.
    fn offer_finite(&mut self, v0: f64, k: usize, tol: &Tolerances) {
        if v0 > self.max_violation {
            self.max_violation = v0;
        }
        if v0 > tol.finite && self.finite.is_none_or(|(s, _)| !self.bland && v0 > s) {
            self.finite = Some((v0, k));
        }
    }

    /// The entering row: the M-part dominates the finite part (in Bland mode the lowest
    /// index wins; real rows come before artificial ones).
    fn into_pricing(self) -> Pricing {
        let entering = match (self.m_part, self.finite) {
            (Some((_, k)), _) => Some(k),
            (None, Some((_, k))) => Some(k),
            (None, None) => None,
        };
        Pricing {
            entering,
            max_violation: self.max_violation.max(0.0),
        }
    }
}

/// The entering row at a vertex: the real or artificial row it violates most (or first,
/// under Bland's rule), the M-part before the finite part.
pub(super) fn price<const D: usize>(
    t: &Tableau<'_, D>,
    v: &Vertex<D>,
    in_basis: &[bool],
    settings: &Settings,
    bland: bool,
) -> Pricing {
    let phase1 = v.x1.iter().any(|&z| z != 0.0);
    let tol = Tolerances {
        finite: settings.tol_feasibility * (1.0 + inf_norm(&v.x0)),
        m_part: settings.tol_feasibility * (1.0 + inf_norm(&v.x1)),
    };
    let mut choice = Choice {
        m_part: None,
        finite: None,
        max_violation: f64::NEG_INFINITY,
        bland,
    };
    if phase1 {
        price_real_phase1(t, v, in_basis, &tol, &mut choice);
    } else {
        price_real_phase2(t, v, &tol, &mut choice);
    }
    price_artificial(t, v, in_basis, &tol, &mut choice);
    choice.into_pricing()
}

/// Phase 2: the M-part of every real row is zero, so only its finite violation counts;
/// basic and ignored rows have b/|a| = +∞ and never win.
fn price_real_phase2<const D: usize>(
    t: &Tableau<'_, D>,
    v: &Vertex<D>,
    tol: &Tolerances,
    choice: &mut Choice,
) {
    let mut best = (f64::NEG_INFINITY, usize::MAX);
    if choice.bland {
        for (k, (row, &bk)) in t.unit.iter().zip(&t.unit_b).enumerate() {
            let v0 = dot(row, &v.x0) - bk;
            if v0 > tol.finite && choice.finite.is_none() {
                choice.finite = Some((v0, k));
            }
            best = if v0 > best.0 { (v0, k) } else { best };
        }
    } else {
        best = most_violated(&t.unit, &t.unit_b, &v.x0);
        if best.0 > tol.finite {
            choice.finite = Some(best);
        }
    }
    choice.max_violation = best.0;
}

/// Phase 1: real rows have no M-part in b, so their M-violation is a·x1/|a|. Ignored rows
/// (a = 0 here) and basic rows have b/|a| = +∞, so only a row whose M-violation is positive
/// needs the basis test.
fn price_real_phase1<const D: usize>(
    t: &Tableau<'_, D>,
    v: &Vertex<D>,
    in_basis: &[bool],
    tol: &Tolerances,
    choice: &mut Choice,
) {
    for (k, (row, &bk)) in t.unit.iter().zip(&t.unit_b).enumerate() {
        let v1 = dot(row, &v.x1);
        if v1 > tol.m_part {
            if !in_basis[k] {
                choice.offer_m_part(v1, k);
            }
            continue;
        }
        if v1 < -tol.m_part {
            continue;
        }
        choice.offer_finite(dot(row, &v.x0) - bk, k, tol);
    }
}

/// The artificial rows s_i x_i ≤ M that are not basic.
fn price_artificial<const D: usize>(
    t: &Tableau<'_, D>,
    v: &Vertex<D>,
    in_basis: &[bool],
    tol: &Tolerances,
    choice: &mut Choice,
) {
    let phase1 = v.x1.iter().any(|&z| z != 0.0);
    for i in 0..D {
        let k = t.m + i;
        if in_basis[k] {
            continue;
        }
        // Right-hand side (0, 1): no finite part, unit M-part.
        let row = t.row(k);
        let v1 = if phase1 { dot(&row, &v.x1) - 1.0 } else { -1.0 };
        if v1 > tol.m_part {
            choice.offer_m_part(v1, k);
            continue;
        }
        if v1 < -tol.m_part {
            continue;
        }
        choice.offer_finite(dot(&row, &v.x0), k, tol);
    }
}
