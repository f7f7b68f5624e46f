//! Boundaries and bifurcations of a symmetric self-weight `state` grid on any form other than
//! the circular arch with radial joints (pointed arches, vertical joints), located on the
//! margins of the general route.
//!
//! The regime of a point is a function of three indicators (docs/mechanics.md §1): the
//! rotational rows alone feasible (H^r ≠ ∅), the sliding rows alone feasible (H^s ≠ ∅) and all
//! rows feasible (stable). Each is the sign of a continuous margin τ + tol_margin of the
//! general route ([`general::margin`]). H^r does not involve μ, so its flip on a K-edge is
//! located once per edge index and shared by every row; the weights and joints of these forms
//! depend on K, so H^s, unlike the semicircle's, flips along K-edges too. Each indicator that
//! differs between the ends of an edge is located by Brent on its margin, to the manifest's
//! tolerance; an edge whose ends are not adjacent regimes gives one point per crossing.
//!
//! Along a K line the stable set starts at the critical friction μ_m(K) and H^s at the
//! sliding threshold μ_s(K) ≤ μ_m(K). The collapse curve is rotational at the thickness K_r
//! where H^r empties, mixed where μ_s(K) < μ_m(K), and sliding where they coincide. Hence
//! the two bifurcations: rotational/mixed at (K_r, μ_m(K_r)), and mixed/sliding at the K
//! where the mixed band μ_s < μ < μ_m closes, located by bisection in K on whether the arch
//! stands just above its own sliding threshold.

use super::bifurcation::{Kind, merge_coincident, record};
use super::grid::Grid;
use super::probe::root;
use super::state_grid::{Crossing, crossings, h_r_nonempty, h_s_nonempty};
use super::{Bifurcation, BoundaryPoint, Counter, EdgeAxis};
use crate::analysis::forms::ArchModel;
use crate::analysis::general::{self, RowSet, Settings};
use crate::analysis::settings::LineSettings;
use crate::analysis::symmetric::CriticalState;
use crate::analysis::{MechanismKind, Regime};
use rayon::prelude::*;

fn stable(r: Regime) -> bool {
    r == Regime::Stable
}

/// The regime named by the three indicators.
fn regime_of(rot: bool, sld: bool, all: bool) -> Regime {
    match (rot, sld, all) {
        (_, _, true) => Regime::Stable,
        (true, true, false) => Regime::Mixed,
        (false, true, false) => Regime::Rotational,
        (true, false, false) => Regime::Sliding,
        (false, false, false) => Regime::None,
    }
}

/// The row set whose feasibility an indicator is.
fn indicator(set: RowSet) -> fn(Regime) -> bool {
    match set {
        RowSet::Rotational => h_r_nonempty,
        RowSet::Sliding => h_s_nonempty,
        RowSet::All => stable,
    }
}

/// Counted margins of one grid's arch at any (K, μ).
struct Margins<'a> {
    grid: &'a Grid,
    counter: &'a Counter<'a>,
    settings: Settings,
    tol: f64,
}

impl Margins<'_> {
    fn model(&self, k: f64) -> Option<ArchModel> {
        let s = &self.grid.scene;
        ArchModel::new(s.arch.with_k(k), s.form, s.load).ok()
    }

    /// τ + tol_margin of a row set at (K, μ): ≥ 0 iff the rows are feasible there (as the
    /// general route decides); −1 where the form does not exist or the margin failed.
    fn psi(&self, k: f64, mu: f64, set: RowSet) -> f64 {
        self.counter.tick();
        let Some(model) = self.model(k) else {
            return -1.0;
        };
        let m = general::margin(&model, mu.atan(), set, &self.settings);
        if m.outcome == general::Outcome::Solved {
            m.margin + self.settings.tol_margin
        } else {
            -1.0
        }
    }

    /// The margin of `set` along an edge, as a function of the edge's parameter.
    fn along(&self, axis: EdgeAxis, fixed: f64, set: RowSet) -> impl Fn(f64) -> f64 + '_ {
        move |x| match axis {
            EdgeAxis::K => self.psi(x, fixed, set),
            EdgeAxis::Mu => self.psi(fixed, x, set),
        }
    }

    /// The root of the indicator of `set` in [lo, hi] on its feasible side.
    fn root(&self, axis: EdgeAxis, fixed: f64, set: RowSet, (lo, hi): (f64, f64)) -> Option<f64> {
        let f = self.along(axis, fixed, set);
        let good_hi = f(lo) < 0.0;
        root(f, lo, hi, good_hi, self.tol)
    }

    /// The state of largest margin of the rows of `set` at (K, μ) and the mechanism its active
    /// rows name.
    fn state(&self, k: f64, mu: f64, set: RowSet) -> Option<CriticalState> {
        self.counter.tick();
        let model = self.model(k)?;
        let m = general::margin(&model, mu.atan(), set, &self.settings);
        Some(CriticalState {
            k,
            mu,
            thrust_over_half_weight: m.crown.thrust_over_half_weight,
            crown_moment: -m.crown.moment_about_centre,
            mechanism: m.mechanism_with(&self.settings)?,
        })
    }

    /// The regime at (K, μ) from its three margins.
    fn regime(&self, k: f64, mu: f64) -> Regime {
        regime_of(
            self.psi(k, mu, RowSet::Rotational) >= 0.0,
            self.psi(k, mu, RowSet::Sliding) >= 0.0,
            self.psi(k, mu, RowSet::All) >= 0.0,
        )
    }
}

/// One grid being refined.
struct Refiner<'a> {
    m: Margins<'a>,
    regimes: Vec<Option<Regime>>,
    /// Where H^r flips on each K-edge index (the same in every row).
    k_flips: Vec<Option<f64>>,
}

impl<'a> Refiner<'a> {
    fn new(grid: &'a Grid, tol: f64, counter: &'a Counter) -> Self {
        let (nk, nmu) = (grid.ks.len(), grid.mus.len());
        let regimes = super::grid::regimes(grid);
        let settings = Settings {
            lambda: grid.scene.lambda,
            ..Settings::default()
        };
        let mut r = Refiner {
            m: Margins {
                grid,
                counter,
                settings,
                tol,
            },
            regimes,
            k_flips: Vec::new(),
        };
        let flips: Vec<Option<f64>> = (0..nk.saturating_sub(1))
            .into_par_iter()
            .map(|i| {
                let flips = (0..nmu).any(|j| {
                    matches!((r.regime(i, j), r.regime(i + 1, j)),
                        (Some(a), Some(b)) if h_r_nonempty(a) != h_r_nonempty(b))
                });
                let mu = grid.mus.first().copied().unwrap_or(f64::INFINITY);
                flips
                    .then(|| {
                        r.m.root(
                            EdgeAxis::K,
                            mu,
                            RowSet::Rotational,
                            (grid.ks[i], grid.ks[i + 1]),
                        )
                    })
                    .flatten()
            })
            .collect();
        r.k_flips = flips;
        r
    }

    fn regime(&self, i: usize, j: usize) -> Option<Regime> {
        let n = self.m.grid.ks.len();
        self.regimes.get(j * n + i).copied().flatten()
    }

    /// The crossings of one edge from `lo` (regime a) to `hi` (regime b).
    fn edge(
        &self,
        axis: EdgeAxis,
        fixed: f64,
        (lo, hi): (f64, f64),
        (a, b): (Regime, Regime),
        k_flip: Option<f64>,
    ) -> Vec<Crossing> {
        let differs = |set: RowSet| indicator(set)(a) != indicator(set)(b);
        let (rot, sld) = (differs(RowSet::Rotational), differs(RowSet::Sliding));
        let m = &self.m;
        let stable_root = |l: f64, h: f64, good_hi: bool| {
            root(m.along(axis, fixed, RowSet::All), l, h, good_hi, m.tol)
        };
        if rot && sld {
            return self.several((lo, hi), (a, b), axis, fixed);
        }
        let primary = if rot {
            RowSet::Rotational
        } else {
            RowSet::Sliding
        };
        let flip = if !(rot || sld) {
            None
        } else if rot && axis == EdgeAxis::K {
            k_flip
        } else {
            m.root(axis, fixed, primary, (lo, hi))
        };
        crossings(
            (lo, hi),
            (a, b),
            indicator(primary),
            flip,
            &mut || flip.is_some_and(|x| m.along(axis, fixed, RowSet::All)(x) >= 0.0),
            &mut |l, h, g| stable_root(l, h, g),
        )
    }

    /// An edge across which both H^r and H^s change: each indicator located, and the regime
    /// between consecutive roots read from its margins.
    fn several(
        &self,
        (lo, hi): (f64, f64),
        (a, b): (Regime, Regime),
        axis: EdgeAxis,
        fixed: f64,
    ) -> Vec<Crossing> {
        let mut xs: Vec<f64> = [RowSet::Rotational, RowSet::Sliding, RowSet::All]
            .into_iter()
            .filter(|&s| indicator(s)(a) != indicator(s)(b))
            .filter_map(|s| self.m.root(axis, fixed, s, (lo, hi)))
            .collect();
        xs.sort_by(f64::total_cmp);
        let at = |x: f64| match axis {
            EdgeAxis::K => self.m.regime(x, fixed),
            EdgeAxis::Mu => self.m.regime(fixed, x),
        };
        let mut out = Vec::new();
        let mut low = a;
        for (n, &x) in xs.iter().enumerate() {
            let high = match xs.get(n + 1) {
                Some(&y) if y.is_finite() => at(0.5 * (x + y)),
                _ => b,
            };
            if high != low {
                out.push(Crossing { x, low, high });
                low = high;
            }
        }
        out
    }

    /// A boundary point from a crossing: on the collapse curve it carries the limit state of
    /// all rows there, otherwise the state of the row set that empties.
    fn point(&self, axis: EdgeAxis, (k, mu): (f64, f64), c: &Crossing) -> BoundaryPoint {
        let on_curve = stable(c.low) || stable(c.high);
        let set = if on_curve {
            RowSet::All
        } else if h_r_nonempty(c.low) != h_r_nonempty(c.high) {
            RowSet::Rotational
        } else {
            RowSet::Sliding
        };
        let state = self.m.state(k, mu, set);
        let grid = self.m.grid;
        BoundaryPoint {
            load_case: grid.load_case,
            half_angle_deg: grid.arch.half_angle_deg(),
            voussoirs: grid.arch.joints.voussoirs(),
            form: grid.scene.form,
            at_deg: grid.scene.load.at_deg(),
            at_x: grid.scene.load.at_x(),
            k,
            mu,
            axis,
            regime_low: c.low,
            regime_high: c.high,
            on_collapse_curve: on_curve,
            mechanism: if on_curve {
                state.as_ref().map(|s| s.mechanism.kind)
            } else {
                None
            },
            state,
        }
    }

    /// The crossings of the K-edges of row j (μ fixed).
    fn row(&self, j: usize) -> Vec<BoundaryPoint> {
        let (ks, mu) = (&self.m.grid.ks, self.m.grid.mus[j]);
        let mut out = Vec::new();
        for i in 0..ks.len().saturating_sub(1) {
            let (Some(a), Some(b)) = (self.regime(i, j), self.regime(i + 1, j)) else {
                continue;
            };
            if a == b {
                continue;
            }
            let flip = self.k_flips.get(i).copied().flatten();
            for c in self.edge(EdgeAxis::K, mu, (ks[i], ks[i + 1]), (a, b), flip) {
                out.push(self.point(EdgeAxis::K, (c.x, mu), &c));
            }
        }
        out
    }

    /// The crossings of the μ-edges of column i (K fixed).
    fn column(&self, i: usize) -> Vec<BoundaryPoint> {
        let (k, mus) = (self.m.grid.ks[i], &self.m.grid.mus);
        let mut out = Vec::new();
        for j in 0..mus.len().saturating_sub(1) {
            let (Some(a), Some(b)) = (self.regime(i, j), self.regime(i, j + 1)) else {
                continue;
            };
            if a == b {
                continue;
            }
            for c in self.edge(EdgeAxis::Mu, k, (mus[j], mus[j + 1]), (a, b), None) {
                out.push(self.point(EdgeAxis::Mu, (k, c.x), &c));
            }
        }
        out
    }
}

/// The bifurcations of a grid's collapse curve (see the module docs), each kept when the
/// located collapse points on either side of it change mechanism accordingly.
fn bifurcations(r: &Refiner, points: &[BoundaryPoint]) -> Vec<Bifurcation> {
    use MechanismKind::{Mixed, Rotational, Sliding};
    let m = &r.m;
    let curve: Vec<(f64, f64, MechanismKind)> = points
        .iter()
        .filter(|p| p.on_collapse_curve)
        .filter_map(|p| Some((p.k, p.mu, p.mechanism?)))
        .collect();
    let has = |kind: MechanismKind| curve.iter().any(|p| p.2 == kind);
    let mut out = Vec::new();
    if has(Rotational)
        && (has(Mixed) || has(Sliding))
        && let Some(k_r) = r.k_flips.iter().flatten().next().copied()
        && let Some(state) = rotational_mixed(m, k_r)
    {
        out.push(record(m.grid, Kind::RotationalMixed, &state));
    }
    let thin = curve
        .iter()
        .filter(|p| p.2 != Sliding)
        .map(|p| p.0)
        .reduce(f64::max);
    let thick = curve
        .iter()
        .filter(|p| p.2 == Sliding)
        .map(|p| p.0)
        .reduce(f64::min);
    if let (Some(lo), Some(hi)) = (thin, thick)
        && let Some(state) = mixed_sliding(m, (lo.min(hi), lo.max(hi)))
    {
        out.push(record(m.grid, Kind::MixedSliding, &state));
    }
    merge_coincident(&mut out, m.tol);
    out.sort_by(|a, b| a.k.total_cmp(&b.k));
    out
}

/// The rotational/mixed bifurcation: the critical friction at the thickness K_r where H^r
/// empties, with the limit state of all rows there.
fn rotational_mixed(m: &Margins, k_r: f64) -> Option<CriticalState> {
    m.counter.tick();
    let model = m.model(k_r)?;
    let c = general::friction(&model, &m.settings);
    let s = c.found()?;
    Some(CriticalState {
        k: k_r,
        mu: s.mu,
        thrust_over_half_weight: s.state.crown.thrust_over_half_weight,
        crown_moment: -s.state.crown.moment_about_centre,
        mechanism: s.mechanism.clone()?,
    })
}

/// μ_s(K), the sliding threshold at K, on its feasible side (within the tolerance).
fn sliding_threshold(m: &Margins, k: f64) -> Option<f64> {
    let f = |mu: f64| m.psi(k, mu, RowSet::Sliding);
    if f(0.0) >= 0.0 {
        return Some(0.0);
    }
    root(f, 0.0, f64::INFINITY, true, m.tol)
}

/// Whether a mixed band lies above the sliding threshold at K: the arch does not stand a
/// friction step above μ_s(K). `None` when H^s never fills.
fn mixed_band(m: &Margins, k: f64) -> Option<bool> {
    let mu_s = sliding_threshold(m, k)?;
    let step = LineSettings::DEFAULT.band_friction_step;
    let mu = (mu_s.atan() + step).tan();
    Some(m.psi(k, mu, RowSet::All) < 0.0)
}

/// The mixed/sliding bifurcation in [lo, hi]: the K where the mixed band closes, located by
/// bisection to the tolerance, with the limit state of all rows at its sliding threshold.
fn mixed_sliding(m: &Margins, (lo, hi): (f64, f64)) -> Option<CriticalState> {
    let (mut lo, mut hi) = (lo, hi);
    if !mixed_band(m, lo)? || mixed_band(m, hi)? {
        return None;
    }
    while hi - lo > m.tol {
        let mid = 0.5 * (lo + hi);
        if mixed_band(m, mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mu = sliding_threshold(m, hi)?;
    m.state(hi, mu, RowSet::All)
}

/// Boundary points and bifurcations of one symmetric self-weight state grid.
pub(crate) fn locate(
    grid: &Grid,
    tol: f64,
    counter: &Counter,
) -> (Vec<BoundaryPoint>, Vec<Bifurcation>) {
    let r = Refiner::new(grid, tol, counter);
    let found = super::grid::every_line(grid, |j| r.row(j), |i| r.column(i));
    let bifs = bifurcations(&r, &found);
    (found, bifs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indicators_name_the_regimes() {
        for r in [
            Regime::Stable,
            Regime::Mixed,
            Regime::Rotational,
            Regime::Sliding,
            Regime::None,
        ] {
            let got = regime_of(
                indicator(RowSet::Rotational)(r),
                indicator(RowSet::Sliding)(r),
                indicator(RowSet::All)(r),
            );
            assert_eq!(got, r);
        }
    }
}
