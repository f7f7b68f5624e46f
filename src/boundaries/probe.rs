//! Counted analyses of one arch and the continuous margins whose sign changes at a regime
//! boundary, with the bracketing root search that locates them.
//!
//! Every margin here agrees in sign with [`symmetric::regime_of`] at the same point, so a
//! located crossing lies between grid points of the regimes it separates.

use super::Counter;
use crate::analysis::circular::SymmetricCircular;
use crate::analysis::roots::brent;
use crate::analysis::symmetric::{
    self, Critical, MARGIN_TOL, RotationalDomain, SlidingDomain, rotational_domain, sliding_domain,
};
use crate::analysis::{Interval, Regime};
use crate::model::{Arch, Friction};

/// Largest |margin| handed to Brent (infinite ends of a domain give infinite overlaps).
const CLAMP: f64 = 1e6;
/// Largest μ explored when a μ-edge ends at infinite friction.
const MU_FAR: f64 = 1e15;

/// The analyses of one arch (its K is replaced where a K is given), each counted.
#[derive(Clone, Copy)]
pub(crate) struct Probe<'a> {
    /// The arch (half-angle, weight model, joints).
    pub arch: Arch,
    counter: &'a Counter<'a>,
}

impl<'a> Probe<'a> {
    /// Probes of an arch, counted by `counter`.
    pub fn new(arch: Arch, counter: &'a Counter) -> Self {
        Probe { arch, counter }
    }

    fn sym(&self, k: f64) -> SymmetricCircular {
        SymmetricCircular::new(&self.arch.with_k(k))
    }

    /// H^r at K.
    pub fn rotational(&self, k: f64) -> RotationalDomain {
        self.counter.tick();
        rotational_domain(&self.sym(k))
    }

    /// H^s at μ (empty for an invalid μ).
    pub fn sliding(&self, mu: f64) -> SlidingDomain {
        self.counter.tick();
        match Friction::new(mu) {
            Some(f) => sliding_domain(&self.sym(self.arch.k), f.angle()),
            None => SlidingDomain {
                interval: Interval::EMPTY,
                lower_joint: None,
                upper_joint: None,
            },
        }
    }

    /// Φ(h) at K plus the classification tolerance: ≥ 0 iff h ∈ H^r(K).
    pub fn rotational_margin_at(&self, k: f64, h: f64) -> f64 {
        self.counter.tick();
        clamp(self.sym(k).rotational_margin(h) + MARGIN_TOL)
    }

    /// The collapse thickness K_c at μ.
    pub fn thickness(&self, mu: f64) -> Critical {
        self.counter.tick();
        match Friction::new(mu) {
            Some(f) => symmetric::thickness(&self.arch, f),
            None => Critical::NeverStands,
        }
    }

    /// The critical friction μ_c at K.
    pub fn friction(&self, k: f64) -> Critical {
        self.counter.tick();
        symmetric::friction(&self.arch.with_k(k))
    }

    /// μ_min, the friction below which H^s is empty.
    pub fn sliding_threshold(&self) -> Critical {
        self.counter.tick();
        symmetric::sliding_threshold(&self.arch)
    }
}

fn clamp(x: f64) -> f64 {
    if x.is_nan() {
        -CLAMP
    } else {
        x.clamp(-CLAMP, CLAMP)
    }
}

/// ≥ 0 iff H^r is non-empty (the peak margin of Φ with the classification tolerance).
pub(crate) fn rotational_margin(rot: &RotationalDomain) -> f64 {
    let m = clamp(rot.peak_margin + MARGIN_TOL);
    if rot.interval.is_empty() {
        m.min(-f64::MIN_POSITIVE)
    } else {
        m.max(0.0)
    }
}

/// ≥ 0 iff H^s is non-empty (its width; positive when an end is infinite).
pub(crate) fn sliding_margin(sld: &SlidingDomain) -> f64 {
    let i = sld.interval;
    if i.is_empty() {
        let w = i.hi - i.lo;
        if w.is_finite() {
            w.min(-f64::MIN_POSITIVE)
        } else {
            -1.0
        }
    } else if i.lo.is_finite() && i.hi.is_finite() {
        i.hi - i.lo
    } else {
        1.0
    }
}

/// ≥ 0 iff the point is stable: the overlap of H^r and H^s with the tolerance of
/// [`symmetric::regime_of`]; an empty domain gives its own (negative) margin.
pub(crate) fn stable_margin(rot: &RotationalDomain, sld: &SlidingDomain) -> f64 {
    if rot.interval.is_empty() {
        return rotational_margin(rot);
    }
    if sld.interval.is_empty() {
        return sliding_margin(sld);
    }
    let (r, s) = (rot.interval, sld.interval);
    let tol = MARGIN_TOL * (1.0 + r.lo.abs().min(r.hi.abs()));
    let g = clamp((s.hi + tol - r.lo).min(r.hi + tol - s.lo));
    debug_assert_eq!(g >= 0.0, symmetric::regime_of(rot, sld) == Regime::Stable);
    g
}

/// ≥ 0 iff thrust h lies in H^s: its distance inside the nearer end (the width when H^s is
/// empty).
pub(crate) fn thrust_inside(sld: &SlidingDomain, h: f64) -> f64 {
    if sld.interval.is_empty() {
        return sliding_margin(sld);
    }
    clamp((sld.interval.hi - h).min(h - sld.interval.lo))
}

/// The root of a margin between `lo` < `hi` (`hi` may be +∞ for μ), located by Brent to
/// within `tol`: the returned point lies on the side where the margin is ≥ 0, `good_hi`
/// telling which end that is. `None` when the margin does not change sign.
pub(crate) fn root(
    mut f: impl FnMut(f64) -> f64,
    lo: f64,
    hi: f64,
    good_hi: bool,
    tol: f64,
) -> Option<f64> {
    let (mut lo, mut hi) = (lo, hi);
    if hi.is_infinite() {
        // +∞ is only a limit: walk up until the margin changes sign.
        let sign_lo = f(lo) >= 0.0;
        let mut x = (2.0 * lo).max(1.0);
        loop {
            if (f(x) >= 0.0) != sign_lo {
                hi = x;
                break;
            }
            lo = x;
            x *= 4.0;
            if x > MU_FAR {
                return None;
            }
        }
    }
    // Brent returns the end of its last bracket on the side of its second argument; the
    // bracket is shorter than tol/2 plus a few ulps, so the error is below tol.
    let (a, b) = if good_hi { (lo, hi) } else { (hi, lo) };
    brent(&mut f, a, b, 0.5 * tol)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn root_lands_on_the_good_side_within_tolerance() {
        let x = root(|x| x - 0.3, 0.0, 1.0, true, 1e-9).unwrap();
        assert!(x >= 0.3 && x - 0.3 <= 1e-9, "{x}");
        let x = root(|x| 0.3 - x, 0.0, 1.0, false, 1e-9).unwrap();
        assert!(x <= 0.3 && 0.3 - x <= 1e-9, "{x}");
    }

    #[test]
    fn root_walks_up_to_an_infinite_end() {
        let x = root(|x| x - 123.0, 2.0, f64::INFINITY, true, 1e-9).unwrap();
        assert!((x - 123.0).abs() <= 1e-9, "{x}");
        assert!(root(|_| -1.0, 2.0, f64::INFINITY, true, 1e-9).is_none());
    }

    #[test]
    fn margins_agree_with_the_classification() {
        let counter = Counter::default();
        let p = Probe::new(Arch::semicircular(1.2).unwrap(), &counter);
        for &k in &[1.05, 1.11, 1.12, 1.2, 1.4] {
            let rot = p.rotational(k);
            assert_eq!(rotational_margin(&rot) >= 0.0, !rot.interval.is_empty());
            for &mu in &[0.0, 0.2, 0.31, 0.35, 0.5, f64::INFINITY] {
                let sld = p.sliding(mu);
                assert_eq!(sliding_margin(&sld) >= 0.0, !sld.interval.is_empty());
                let stable = symmetric::regime_of(&rot, &sld) == Regime::Stable;
                assert_eq!(stable_margin(&rot, &sld) >= 0.0, stable, "K {k} μ {mu}");
            }
        }
        assert_eq!(counter.get(), 5 + 5 * 6);
    }
}
