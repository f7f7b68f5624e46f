//! The regimes of one K line of a symmetric self-weight state grid on any form (pointed
//! arches, vertical joints, voussoirs), from a few margins of the general route.
//!
//! At fixed K the rotational rows do not involve the friction angle φ, and the feasible sets
//! of the sliding rows alone and of all rows grow with φ (each Coulomb cone |T| ≤ N tan φ
//! contains the cones of smaller φ). Hence along a K line: H^r ≠ ∅ is one answer for every
//! φ, H^s ≠ ∅ holds from a sliding threshold φ_s(K) up, and the arch stands from a critical
//! friction angle φ_m(K) ≥ φ_s(K) up. The line's regimes are read from these two thresholds,
//! each located among the line's own friction values by bisection on their index. Every
//! margin is the one the general route evaluates at that point (the same geometry, angle,
//! rows and settings), so a point the bisection visits has exactly the general route's
//! answer, and every other point is decided by monotonicity from two visited neighbours.

use crate::analysis::forms::ArchModel;
use crate::analysis::general::{self, Critical, Outcome, RowSet, Settings};
use crate::analysis::statics::ArchGeometry;
use crate::analysis::types::Regime;
use crate::model::{Arch, ArchForm, Friction, Load};

/// The thresholds of one K line among its sorted friction angles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LineRegimes {
    /// Whether the rotational rows alone are feasible (H^r ≠ ∅) on this line.
    pub rotational: bool,
    /// Index of the first angle at which the sliding rows alone are feasible (the count of
    /// angles when none is).
    pub first_sliding: usize,
    /// Index of the first angle at which all rows are feasible (the count of angles when
    /// none is).
    pub first_stable: usize,
    /// Margins (linear programmes) evaluated to find them.
    pub margins: usize,
}

impl LineRegimes {
    /// The regime at the angle of index `i` (as [`general::regime`] names it).
    pub fn regime(&self, i: usize) -> Regime {
        match (
            self.rotational,
            i >= self.first_sliding,
            i >= self.first_stable,
        ) {
            (_, _, true) => Regime::Stable,
            (true, true, false) => Regime::Mixed,
            (false, true, false) => Regime::Rotational,
            (true, false, false) => Regime::Sliding,
            (false, false, false) => Regime::None,
        }
    }
}

/// The smallest index in `from..n` at which `feasible` holds, for a predicate that holds on
/// a final segment of the indices (`n` when it holds nowhere); `None` when a margin fails.
fn first_feasible(
    from: usize,
    n: usize,
    mut feasible: impl FnMut(usize) -> Option<bool>,
) -> Option<usize> {
    let (mut lo, mut hi) = (from, n);
    // Invariant: the predicate fails below lo (or lo = from) and holds at hi (or hi = n).
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if feasible(mid)? {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    Some(lo)
}

/// [`first_feasible`] from `from` up to `hi`, where the predicate is known to hold at `hi`:
/// steps of 1, 2, 4, … down from `hi` until it fails, then bisection.
fn gallop_down(
    from: usize,
    hi: usize,
    feasible: &mut impl FnMut(usize) -> Option<bool>,
) -> Option<usize> {
    let (mut hi, mut step) = (hi, 1);
    while hi > from {
        let probe = hi.saturating_sub(step).max(from);
        if !feasible(probe)? {
            return first_feasible(probe + 1, hi, feasible);
        }
        hi = probe;
        step *= 2;
    }
    Some(from)
}

/// [`first_feasible`] over `lo..n`, where the predicate is known to fail below `lo`: steps
/// of 1, 2, 4, … up from `lo` until it holds, then bisection.
fn gallop_up(
    lo: usize,
    n: usize,
    feasible: &mut impl FnMut(usize) -> Option<bool>,
) -> Option<usize> {
    let (mut lo, mut step) = (lo, 1);
    while lo < n {
        let probe = (lo + step - 1).min(n - 1);
        if feasible(probe)? {
            return first_feasible(lo, probe, feasible);
        }
        lo = probe + 1;
        step *= 2;
    }
    Some(n)
}

/// [`first_feasible`] starting from a guess (the answer of a neighbouring K line): two
/// margins when the guess is right, a few more when it is near.
fn first_feasible_near(
    from: usize,
    n: usize,
    guess: Option<usize>,
    mut feasible: impl FnMut(usize) -> Option<bool>,
) -> Option<usize> {
    let Some(g) = guess else {
        return first_feasible(from, n, feasible);
    };
    if n <= from {
        return Some(n);
    }
    let g = g.clamp(from, n - 1);
    if feasible(g)? {
        gallop_down(from, g, &mut feasible)
    } else {
        gallop_up(g + 1, n, &mut feasible)
    }
}

/// The regimes of a K line of geometry `geom` at the friction angles `phis` (radians,
/// ascending; π/2 for μ = ∞), with the general route's settings. `None` when a margin could
/// not be computed (the general route gives no regime there either): the caller then
/// analyses the line point by point.
///
/// `near`, the regimes of a neighbouring K line, only makes the search cheaper: the thresholds
/// move little from one K to the next.
pub fn line_regimes<G: ArchGeometry + ?Sized>(
    geom: &G,
    phis: &[f64],
    settings: &Settings,
    near: Option<&LineRegimes>,
) -> Option<LineRegimes> {
    let n = phis.len();
    let mut margins = 0usize;
    let mut feasible = |set: RowSet, phi: f64| {
        margins += 1;
        let m = general::margin(geom, phi, set, settings);
        (m.outcome == Outcome::Solved).then(|| m.feasible(settings))
    };
    // The rotational rows do not involve φ.
    let phi_any = phis.first().copied().unwrap_or(std::f64::consts::FRAC_PI_2);
    let rotational = feasible(RowSet::Rotational, phi_any)?;
    let first_sliding = first_feasible_near(0, n, near.map(|l| l.first_sliding), |i| {
        feasible(RowSet::Sliding, phis[i])
    })?;
    // All rows feasible needs the sliding rows feasible, and the rotational ones.
    let first_stable = if rotational {
        let guess = near.filter(|l| l.rotational).map(|l| l.first_stable);
        first_feasible_near(first_sliding, n, guess, |i| feasible(RowSet::All, phis[i]))?
    } else {
        n
    };
    Some(LineRegimes {
        rotational,
        first_sliding,
        first_stable,
        margins,
    })
}

/// The collapse thickness K_c(μ) of an arch of any form under self-weight (its own K is
/// ignored): the closed forms for the circular arch with radial joints, the general route
/// otherwise. NaN where no K lets it stand, or every K does.
pub fn collapse_thickness(arch: &Arch, form: ArchForm, mu: f64) -> f64 {
    let Some(friction) = Friction::new(mu) else {
        return f64::NAN;
    };
    if form.is_circular_radial() {
        return super::thickness(arch, friction)
            .found()
            .map_or(f64::NAN, |s| s.k);
    }
    let make = |k: f64| ArchModel::new(arch.with_k(k), form, Load::SelfWeight).ok();
    let k_max = form.max_k(arch.half_angle);
    general::thickness_with(make, k_max, None, friction, &Settings::default())
        .found()
        .and_then(|s| s.k)
        .unwrap_or(f64::NAN)
}

/// The critical friction μ_c(K) of an arch of any form under self-weight at thickness `k`:
/// 0 where it stands without friction, NaN where no friction lets it stand.
pub fn critical_friction(arch: &Arch, form: ArchForm, k: f64) -> f64 {
    let arch = arch.with_k(k);
    if form.is_circular_radial() {
        return match super::friction(&arch) {
            super::Critical::Found(s) => s.mu,
            super::Critical::AlwaysStands => 0.0,
            super::Critical::NeverStands => f64::NAN,
        };
    }
    let Ok(model) = ArchModel::new(arch, form, Load::SelfWeight) else {
        return f64::NAN;
    };
    match general::friction(&model, &Settings::default()) {
        Critical::Found(s) => s.mu,
        Critical::AlwaysStands => 0.0,
        _ => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_finds_the_first_feasible_index() {
        for n in 0..12 {
            for t in 0..=n {
                let mut calls = 0;
                let r = first_feasible(0, n, |i| {
                    calls += 1;
                    Some(i >= t)
                });
                assert_eq!(r, Some(t), "n {n} t {t}");
                assert!(calls <= 4, "n {n}: {calls} calls");
            }
        }
        assert_eq!(first_feasible(0, 5, |_| None), None);
        // From a guess: the same answer whatever the guess, two calls when it is right.
        for n in 0..40 {
            for t in 0..=n {
                for g in 0..=n + 2 {
                    let mut calls = 0;
                    let r = first_feasible_near(0, n, Some(g), |i| {
                        calls += 1;
                        Some(i >= t)
                    });
                    assert_eq!(r, Some(t), "n {n} t {t} guess {g}");
                    if g == t && t > 0 && t < n {
                        assert_eq!(calls, 2);
                    }
                }
            }
        }
        assert_eq!(first_feasible(3, 8, |i| Some(i >= 1)), Some(3));
    }

    #[test]
    fn regimes_follow_the_thresholds() {
        let line = LineRegimes {
            rotational: true,
            first_sliding: 2,
            first_stable: 4,
            margins: 0,
        };
        let got: Vec<Regime> = (0..6).map(|i| line.regime(i)).collect();
        use Regime as R;
        assert_eq!(
            got,
            [
                R::Sliding,
                R::Sliding,
                R::Mixed,
                R::Mixed,
                R::Stable,
                R::Stable
            ]
        );
        let thin = LineRegimes {
            rotational: false,
            first_stable: 3,
            ..line
        };
        assert_eq!(thin.regime(1), R::None);
        assert_eq!(thin.regime(2), R::Rotational);
    }
}
