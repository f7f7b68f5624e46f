//! Boundaries of a `state` grid: every edge whose ends differ in regime, refined.
//!
//! Along a K-edge (μ fixed) H^s is fixed and only H^r varies; along a μ-edge (K fixed) only
//! H^s varies. The regime along an edge is a function of three indicators: H^r ≠ ∅, H^s ≠ ∅
//! and stability. One of the first two is constant along the edge; the other (the edge's
//! "primary" indicator) flips at a place that does not depend on the fixed parameter, so it
//! is located once per edge index and shared by every row or column. Stability flips on the
//! collapse curve, located per edge.

use super::bifurcation::{self, Landmarks, slack};
use super::grid::Grid;
use super::probe::{Probe, root, rotational_margin, sliding_margin, stable_margin};
use super::{Bifurcation, BoundaryPoint, Counter, EdgeAxis};
use crate::analysis::symmetric::{Critical, CriticalState, RotationalDomain, SlidingDomain};
use crate::analysis::{MechanismKind, Regime};
use std::cell::OnceCell;

pub(super) fn h_r_nonempty(r: Regime) -> bool {
    matches!(r, Regime::Stable | Regime::Mixed | Regime::Sliding)
}

pub(super) fn h_s_nonempty(r: Regime) -> bool {
    matches!(r, Regime::Stable | Regime::Mixed | Regime::Rotational)
}

/// Where the primary indicator of an edge index flips, with the varying domain there.
struct Flip<D> {
    x: f64,
    domain: D,
}

/// A crossing inside one edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Crossing {
    /// Where the regime changes.
    pub x: f64,
    /// The regime below x.
    pub low: Regime,
    /// The regime above x.
    pub high: Regime,
}

/// The crossings inside an edge [lo, hi] with regimes `a` at lo and `b` at hi.
/// `primary` is the indicator that may flip along the edge, `flip` where it does,
/// `stable_at_flip` whether the point is already stable there and `stable_root(lo, hi,
/// good_hi)` locates the collapse curve in a sub-bracket.
pub(super) fn crossings(
    (lo, hi): (f64, f64),
    (a, b): (Regime, Regime),
    primary: fn(Regime) -> bool,
    flip: Option<f64>,
    stable_at_flip: &mut dyn FnMut() -> bool,
    stable_root: &mut dyn FnMut(f64, f64, bool) -> Option<f64>,
) -> Vec<Crossing> {
    let stable = |r: Regime| r == Regime::Stable;
    let one = |x: f64| vec![Crossing { x, low: a, high: b }];
    if primary(a) != primary(b) {
        let Some(xf) = flip else {
            return Vec::new();
        };
        let v_is_hi = primary(b);
        let v = if v_is_hi { b } else { a };
        if !stable(v) {
            return one(xf);
        }
        if stable_at_flip() {
            return one(xf);
        }
        // A mixed band lies between the flip and the stable end.
        let xv = if v_is_hi { hi } else { lo };
        let Some(xs) = stable_root(xf.min(xv), xf.max(xv), v_is_hi) else {
            return one(xf);
        };
        let m = Regime::Mixed;
        let (p, s) = if v_is_hi {
            ((a, m), (m, b))
        } else {
            ((m, b), (a, m))
        };
        let mut out = vec![
            Crossing {
                x: xf,
                low: p.0,
                high: p.1,
            },
            Crossing {
                x: xs,
                low: s.0,
                high: s.1,
            },
        ];
        out.sort_by(|p, q| p.x.total_cmp(&q.x));
        out
    } else if stable(a) != stable(b) {
        match stable_root(lo, hi, stable(b)) {
            Some(x) => one(x),
            None => Vec::new(),
        }
    } else {
        Vec::new()
    }
}

/// One grid being refined.
struct GridRefiner<'a> {
    grid: &'a Grid,
    lm: Landmarks<'a>,
    tol: f64,
    regimes: Vec<Option<Regime>>,
    k_flips: Vec<Option<Flip<RotationalDomain>>>,
    mu_flips: Vec<Option<Flip<SlidingDomain>>>,
}

impl<'a> GridRefiner<'a> {
    fn new(grid: &'a Grid, tol: f64, counter: &'a Counter) -> Self {
        let (nk, nmu) = (grid.ks.len(), grid.mus.len());
        let regimes = super::grid::regimes(grid);
        let mut g = GridRefiner {
            grid,
            lm: Landmarks::new(Probe::new(grid.arch, counter)),
            tol,
            regimes,
            k_flips: Vec::new(),
            mu_flips: Vec::new(),
        };
        let p = g.lm.probe;
        g.k_flips = (0..nk.saturating_sub(1))
            .map(|i| {
                let good_hi = g.flip_side(EdgeAxis::K, i)?;
                let x = root(
                    |k| rotational_margin(&p.rotational(k)),
                    grid.ks[i],
                    grid.ks[i + 1],
                    good_hi,
                    tol,
                )?;
                Some(Flip {
                    x,
                    domain: p.rotational(x),
                })
            })
            .collect();
        g.mu_flips = (0..nmu.saturating_sub(1))
            .map(|j| {
                let good_hi = g.flip_side(EdgeAxis::Mu, j)?;
                let x = root(
                    |mu| sliding_margin(&p.sliding(mu)),
                    grid.mus[j],
                    grid.mus[j + 1],
                    good_hi,
                    tol,
                )?;
                Some(Flip {
                    x,
                    domain: p.sliding(x),
                })
            })
            .collect();
        g
    }

    fn regime(&self, i: usize, j: usize) -> Option<Regime> {
        self.regimes
            .get(j * self.grid.ks.len() + i)
            .copied()
            .flatten()
    }

    /// Whether the primary indicator of edge index `e` flips in some row (K-edges) or column
    /// (μ-edges), and if so whether it holds at the upper end.
    fn flip_side(&self, axis: EdgeAxis, e: usize) -> Option<bool> {
        let (n_other, primary): (usize, fn(Regime) -> bool) = match axis {
            EdgeAxis::K => (self.grid.mus.len(), h_r_nonempty),
            EdgeAxis::Mu => (self.grid.ks.len(), h_s_nonempty),
        };
        (0..n_other).find_map(|o| {
            let (a, b) = match axis {
                EdgeAxis::K => (self.regime(e, o)?, self.regime(e + 1, o)?),
                EdgeAxis::Mu => (self.regime(o, e)?, self.regime(o, e + 1)?),
            };
            (primary(a) != primary(b)).then_some(primary(b))
        })
    }

    /// A boundary point from a crossing; `critical` is the collapse state of the
    /// one-parameter problem through the point (K_c at its μ, or μ_c at its K).
    fn point(
        &self,
        axis: EdgeAxis,
        (k, mu): (f64, f64),
        c: &Crossing,
        critical: &dyn Fn() -> Option<CriticalState>,
    ) -> BoundaryPoint {
        let on_curve = c.low == Regime::Stable || c.high == Regime::Stable;
        // The located coordinate, and the same coordinate of a characterising state.
        let coord = |s: &CriticalState| match axis {
            EdgeAxis::K => s.k,
            EdgeAxis::Mu => s.mu,
        };
        let agrees = |s: &CriticalState| (coord(s) - c.x).abs() <= slack(self.tol, c.x);
        let state = if on_curve {
            critical()
        } else {
            match axis {
                EdgeAxis::K => self.lm.rotational().cloned(),
                EdgeAxis::Mu => self.lm.sliding().cloned(),
            }
        }
        .filter(agrees);
        let mechanism: Option<MechanismKind> = if on_curve {
            state.as_ref().map(|s| s.mechanism.kind)
        } else {
            None
        };
        BoundaryPoint {
            load_case: self.grid.load_case,
            half_angle_deg: self.grid.arch.half_angle_deg(),
            voussoirs: self.grid.arch.joints.voussoirs(),
            form: self.grid.scene.form,
            at_deg: self.grid.scene.load.at_deg(),
            at_x: self.grid.scene.load.at_x(),
            k,
            mu,
            axis,
            regime_low: c.low,
            regime_high: c.high,
            on_collapse_curve: on_curve,
            mechanism,
            state,
        }
    }

    /// The crossings of the K-edges of row j (μ fixed).
    fn row(&self, j: usize) -> Vec<BoundaryPoint> {
        let (ks, mu) = (&self.grid.ks, self.grid.mus[j]);
        let p = self.lm.probe;
        let sld: OnceCell<SlidingDomain> = OnceCell::new();
        let crit: OnceCell<Critical> = OnceCell::new();
        let sld = || sld.get_or_init(|| p.sliding(mu));
        let critical = || crit.get_or_init(|| p.thickness(mu)).found().cloned();
        let mut out = Vec::new();
        for i in 0..ks.len().saturating_sub(1) {
            let (Some(a), Some(b)) = (self.regime(i, j), self.regime(i + 1, j)) else {
                continue;
            };
            if a == b || h_s_nonempty(a) != h_s_nonempty(b) {
                continue;
            }
            let flip = self.k_flips.get(i).and_then(Option::as_ref);
            let found = crossings(
                (ks[i], ks[i + 1]),
                (a, b),
                h_r_nonempty,
                flip.map(|f| f.x),
                &mut || flip.is_some_and(|f| stable_margin(&f.domain, sld()) >= 0.0),
                &mut |lo, hi, good_hi| {
                    root(
                        |k| stable_margin(&p.rotational(k), sld()),
                        lo,
                        hi,
                        good_hi,
                        self.tol,
                    )
                },
            );
            for c in &found {
                out.push(self.point(EdgeAxis::K, (c.x, mu), c, &critical));
            }
        }
        out
    }

    /// The crossings of the μ-edges of column i (K fixed).
    fn column(&self, i: usize) -> Vec<BoundaryPoint> {
        let (k, mus) = (self.grid.ks[i], &self.grid.mus);
        let p = self.lm.probe;
        let rot: OnceCell<RotationalDomain> = OnceCell::new();
        let crit: OnceCell<Critical> = OnceCell::new();
        let rot = || rot.get_or_init(|| p.rotational(k));
        let critical = || crit.get_or_init(|| p.friction(k)).found().cloned();
        let mut out = Vec::new();
        for j in 0..mus.len().saturating_sub(1) {
            let (Some(a), Some(b)) = (self.regime(i, j), self.regime(i, j + 1)) else {
                continue;
            };
            if a == b || h_r_nonempty(a) != h_r_nonempty(b) {
                continue;
            }
            let flip = self.mu_flips.get(j).and_then(Option::as_ref);
            let found = crossings(
                (mus[j], mus[j + 1]),
                (a, b),
                h_s_nonempty,
                flip.map(|f| f.x),
                &mut || flip.is_some_and(|f| stable_margin(rot(), &f.domain) >= 0.0),
                &mut |lo, hi, good_hi| {
                    root(
                        |mu| stable_margin(rot(), &p.sliding(mu)),
                        lo,
                        hi,
                        good_hi,
                        self.tol,
                    )
                },
            );
            for c in &found {
                out.push(self.point(EdgeAxis::Mu, (k, c.x), c, &critical));
            }
        }
        out
    }
}

/// Boundary points and bifurcations of every grid of a `state` study.
pub(crate) fn locate(
    grids: &[Grid],
    tol: f64,
    counter: &Counter,
) -> (Vec<BoundaryPoint>, Vec<Bifurcation>) {
    let mut points = Vec::new();
    let mut bifurcations = Vec::new();
    for grid in grids {
        let g = GridRefiner::new(grid, tol, counter);
        let found = super::grid::every_line(grid, |j| g.row(j), |i| g.column(i));
        bifurcations.extend(bifurcation::on_collapse_curve(grid, &g.lm, &found, tol));
        points.extend(found);
    }
    (points, bifurcations)
}

#[cfg(test)]
mod tests {
    use super::*;
    use Regime as R;

    fn run(
        edge: (f64, f64),
        ends: (Regime, Regime),
        flip: Option<f64>,
        stable_at_flip: bool,
        stable_x: f64,
    ) -> Vec<(f64, Regime, Regime)> {
        crossings(
            edge,
            ends,
            h_r_nonempty,
            flip,
            &mut || stable_at_flip,
            &mut |lo, hi, _| (lo <= stable_x && stable_x <= hi).then_some(stable_x),
        )
        .into_iter()
        .map(|c| (c.x, c.low, c.high))
        .collect()
    }

    #[test]
    fn an_edge_across_a_thin_mixed_band_gives_two_crossings() {
        let c = run(
            (1.0, 2.0),
            (R::Rotational, R::Stable),
            Some(1.2),
            false,
            1.5,
        );
        assert_eq!(
            c,
            vec![(1.2, R::Rotational, R::Mixed), (1.5, R::Mixed, R::Stable)]
        );
        // The same edge read the other way round (stability decreasing with K).
        let c = run(
            (1.0, 2.0),
            (R::Stable, R::Rotational),
            Some(1.8),
            false,
            1.5,
        );
        assert_eq!(
            c,
            vec![(1.5, R::Stable, R::Mixed), (1.8, R::Mixed, R::Rotational)]
        );
    }

    #[test]
    fn adjacent_regimes_give_one_crossing() {
        let c = run((1.0, 2.0), (R::Rotational, R::Stable), Some(1.2), true, 1.5);
        assert_eq!(c, vec![(1.2, R::Rotational, R::Stable)]);
        let c = run((1.0, 2.0), (R::Rotational, R::Mixed), Some(1.2), false, 1.5);
        assert_eq!(c, vec![(1.2, R::Rotational, R::Mixed)]);
        let c = run((1.0, 2.0), (R::Mixed, R::Stable), None, false, 1.5);
        assert_eq!(c, vec![(1.5, R::Mixed, R::Stable)]);
        let c = run((1.0, 2.0), (R::None, R::Sliding), Some(1.1), false, 1.5);
        assert_eq!(c, vec![(1.1, R::None, R::Sliding)]);
        // A flip that could not be located gives nothing rather than a guess.
        assert!(run((1.0, 2.0), (R::None, R::Sliding), None, false, 1.5).is_empty());
    }
}
