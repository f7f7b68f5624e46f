//! The domains H^r and H^s of a symmetric arch, the peak of Φ and the stability margin Ψ.

use super::{Domains, RotationalDomain, Settings, SlidingDomain};
use crate::analysis::circular::{SlidingBound, SymmetricCircular};
use crate::analysis::roots::{argmax_concave, brent};
use crate::analysis::types::{Interval, Sense};
use crate::model::{Arch, Friction};

/// Maximiser and maximum of a concave function given by value and supergradient.
pub(super) fn concave_peak(
    value: impl Fn(f64) -> f64,
    slope: impl Fn(f64) -> f64,
    settings: &Settings,
) -> (f64, f64) {
    let far = settings.max_bracket;
    let (mut lo, mut hi) = (-1.0_f64, 1.0_f64);
    while slope(lo) <= 0.0 && lo > -far {
        lo *= 2.0;
    }
    if slope(lo) <= 0.0 {
        return (f64::NEG_INFINITY, value(-far).max(value(lo)));
    }
    while slope(hi) > 0.0 && hi < far {
        hi *= 2.0;
    }
    if slope(hi) > 0.0 {
        return (f64::INFINITY, value(far).max(value(hi)));
    }
    let h = argmax_concave(&slope, lo, hi, settings.tol_thrust);
    (h, value(h))
}

/// H^r: the thrusts for which a line of thrust fits in the arch (eqs. 2a, 2b).
pub fn rotational_domain_with(sym: &SymmetricCircular, settings: &Settings) -> RotationalDomain {
    let phi = |h: f64| sym.rotational_margin(h);
    let (sp, sm) = sym.rotational_asymptotic_slopes();
    let flat = settings.tol_flat;
    if sp.abs() <= flat && sm.abs() <= flat {
        // Φ is constant (a single joint): H^r is everything or nothing.
        let g = phi(0.0);
        let interval = if g >= -settings.tol_margin {
            Interval {
                lo: f64::NEG_INFINITY,
                hi: f64::INFINITY,
            }
        } else {
            Interval::EMPTY
        };
        return RotationalDomain {
            interval,
            peak_thrust: 0.0,
            peak_margin: g,
        };
    }
    let (h_peak, g) = rotational_peak_with(sym, settings);
    if g < -settings.tol_margin {
        return RotationalDomain {
            interval: Interval::EMPTY,
            peak_thrust: h_peak,
            peak_margin: g,
        };
    }
    let start = if h_peak.is_finite() {
        h_peak
    } else {
        h_peak.signum() * settings.max_bracket
    };
    let root_toward = |dir: f64| -> f64 {
        if phi(start) < 0.0 {
            return start;
        }
        match bracket_negative(&phi, start, dir, settings) {
            Some(x) => brent(phi, x, start, settings.tol_thrust).unwrap_or(start),
            None => dir * f64::INFINITY,
        }
    };
    let lo = if h_peak == f64::NEG_INFINITY {
        f64::NEG_INFINITY
    } else {
        root_toward(-1.0)
    };
    let hi = if h_peak == f64::INFINITY {
        f64::INFINITY
    } else {
        root_toward(1.0)
    };
    RotationalDomain {
        interval: Interval { lo, hi },
        peak_thrust: h_peak,
        peak_margin: g,
    }
}

/// H^s: the thrusts for which no joint slides (eqs. 4a, 4b), friction angle φ in radians.
pub fn sliding_domain_with(
    sym: &SymmetricCircular,
    phi: f64,
    settings: &Settings,
) -> SlidingDomain {
    let mut d = SlidingDomain {
        interval: Interval {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
        },
        lower_joint: None,
        upper_joint: None,
    };
    let mut infeasible = false;
    for theta in sym.sliding_candidates(phi) {
        for (row, bound) in sym.sliding_bounds(theta, phi).into_iter().enumerate() {
            let sense = if row == 0 {
                Sense::Outward
            } else {
                Sense::Inward
            };
            match bound {
                SlidingBound::Upper(v) if v < d.interval.hi => {
                    d.interval.hi = v;
                    d.upper_joint = Some((theta, sense));
                }
                SlidingBound::Lower(v) if v > d.interval.lo => {
                    d.interval.lo = v;
                    d.lower_joint = Some((theta, sense));
                }
                SlidingBound::Infeasible => infeasible = true,
                _ => {}
            }
        }
    }
    if phi == 0.0 && sym.voussoirs.is_none() {
        // w cot θ → 1/α as θ → 0⁺: the supremum of the lower bounds is not attained.
        let v = 1.0 / sym.alpha;
        if v > d.interval.lo {
            d.interval.lo = v;
            d.lower_joint = Some((0.0, Sense::Inward));
        }
    }
    if infeasible {
        d.interval = Interval::EMPTY;
    } else if d.interval.lo > d.interval.hi
        && d.interval.lo - d.interval.hi <= settings.tol_margin * (1.0 + d.interval.lo.abs())
    {
        // Crossed by less than the tolerance: H^s is the single limit value (μ = μ_min).
        let mid = 0.5 * (d.interval.lo + d.interval.hi);
        d.interval = Interval { lo: mid, hi: mid };
    }
    d
}

/// Both domains at a point.
pub fn domains_with(arch: &Arch, friction: Friction, settings: &Settings) -> Domains {
    let sym = SymmetricCircular::new(arch);
    Domains {
        rotational: rotational_domain_with(&sym, settings),
        sliding: sliding_domain_with(&sym, friction.angle(), settings),
    }
}

/// The maximiser and maximum of Φ (the widest point of H^r).
///
/// Continuum: min_θ U is the crown extrados A(h) = Kh left of the kink h_k where it meets the
/// springing extrados B(h) = Kh cos α + b_α, and B right of it. A − max_θ L rises (slope
/// K − cos θ* > 0), so the peak is h_k unless B − max_θ L still rises there, in which case it
/// is the stationary point cos θ*(h) = K cos α, i.e. θ* = acos(K cos α) and, from
/// θ* cot θ* = hα + ρ_s − 1, h = (θ* cot θ* + 1 − ρ_s)/α. One solve of θ*, no iteration.
/// Voussoirs: bisection on the supergradient of the piecewise-linear Φ.
pub fn rotational_peak_with(sym: &SymmetricCircular, settings: &Settings) -> (f64, f64) {
    let phi = |h: f64| sym.rotational_margin(h);
    if let Some(n) = sym.voussoirs {
        return discrete_rotational_peak(sym, n, settings)
            .unwrap_or_else(|| concave_peak(phi, |h| sym.rotational_slope(h), settings));
    }
    let (k, alpha) = (sym.k, sym.alpha);
    // U(θ, h) = a(θ) h + b(θ).
    let b_alpha = sym.extrados(alpha, 0.0);
    let (a0, a1) = (k, k * alpha.cos());
    let h_k = b_alpha / (a0 - a1);
    let theta_k = sym.intrados_max(h_k).1;
    if a1 - theta_k.cos() <= 0.0 {
        return (h_k, phi(h_k));
    }
    let c = k * alpha.cos();
    if c >= 1.0 {
        // Φ rises for ever: a thick flat segment carries any thrust.
        return (f64::INFINITY, phi(settings.max_bracket).max(phi(h_k)));
    }
    let t = c.acos();
    let h = (crate::analysis::circular::theta_cot_theta(t) + 1.0 - sym.rho_s) / alpha;
    let h = h.max(h_k);
    (h, phi(h))
}

/// The peak of Φ for N voussoirs, exactly: the same structure as the continuum with the
/// joints of the half arch θ_i = α(2i + p)/N. Right of the kink, max_i L(θ_i, h) passes from
/// joint i + 1 to joint i at the breakpoint h_i = (b_{i+1} − b_i)/(cos θ_i − cos θ_{i+1})
/// (b_i = L(θ_i, 0); L is unimodal in θ, so the maximiser moves through consecutive joints),
/// and Φ stops rising at the breakpoint where cos θ_i first reaches K cos α. `None` when the
/// half arch has a single joint.
pub(super) fn discrete_rotational_peak(
    sym: &SymmetricCircular,
    n: u32,
    settings: &Settings,
) -> Option<(f64, f64)> {
    let phi = |h: f64| sym.rotational_margin(h);
    let last = n / 2;
    if last == 0 {
        return None;
    }
    let (t0, t1) = sym.end_joints();
    let (a0, a1) = (sym.k * t0.cos(), sym.k * t1.cos());
    let h_k = (sym.extrados(t1, 0.0) - sym.extrados(t0, 0.0)) / (a0 - a1);
    if !h_k.is_finite() {
        return None;
    }
    let (_, ta, tb) = sym.intrados_max(h_k);
    if a1 - ta.cos().max(tb.cos()) <= 0.0 {
        return Some((h_k, phi(h_k)));
    }
    let c = a1;
    if c >= t0.cos() {
        return Some((f64::INFINITY, phi(settings.max_bracket).max(phi(h_k))));
    }
    // Largest joint index i with cos θ_i ≥ K cos α.
    let t_s = c.max(-1.0).acos();
    let x = (t_s * f64::from(n) / sym.alpha - f64::from(n % 2)) / 2.0;
    let mut i = if x <= 0.0 {
        0
    } else {
        (x.floor() as u32).min(last - 1)
    };
    while i > 0 && sym.joint_angle(i).cos() < c {
        i -= 1;
    }
    while i + 1 < last && sym.joint_angle(i + 1).cos() >= c {
        i += 1;
    }
    let (ti, tj) = (sym.joint_angle(i), sym.joint_angle(i + 1));
    let h_b = (sym.intrados(tj, 0.0) - sym.intrados(ti, 0.0)) / (ti.cos() - tj.cos());
    let h = if h_b.is_finite() { h_b.max(h_k) } else { h_k };
    Some((h, phi(h)))
}

/// Ψ and its maximiser: the stability margin of a symmetric arch with sliding domain `sd`,
/// max_h min(Φ(h), h_s,max − h, h − h_s,min).
///
/// The maximum of this concave function is at the peak of Φ, at the middle of H^s, or where
/// Φ crosses one of the two lines; each crossing is a bracketed root of a monotone function.
pub(super) fn stability_margin(
    sym: &SymmetricCircular,
    sd: &Interval,
    settings: &Settings,
) -> (f64, f64) {
    if sd.is_empty() {
        // Within the classification tolerance H^s may be a point with its ends crossed by
        // rounding (μ = μ_min): that point, not 0, is the thrust of the limit state.
        let mid = 0.5 * (sd.lo + sd.hi);
        return (sd.hi - sd.lo, if mid.is_finite() { mid } else { 0.0 });
    }
    let phi = |h: f64| sym.rotational_margin(h);
    let value = |h: f64| phi(h).min(sd.hi - h).min(h - sd.lo);
    let (hp, g) = rotational_peak_with(sym, settings);
    let mut best = (f64::NEG_INFINITY, 0.0);
    let mut consider = |h: f64| {
        if h.is_finite() {
            let v = value(h);
            if v > best.0 {
                best = (v, h);
            }
        }
    };
    consider(hp);
    if sd.lo.is_finite() && sd.hi.is_finite() {
        consider(0.5 * (sd.lo + sd.hi));
    }
    // Φ(h) = h_s,max − h left of the peak (Φ + h rises there).
    if sd.hi.is_finite() && (hp.is_infinite() || sd.hi - hp < g) {
        let top = if hp.is_finite() { hp } else { sd.hi };
        let f = |h: f64| phi(h) + h - sd.hi;
        if let Some(lo) = bracket_negative(&f, top, -1.0, settings)
            && let Some(h) = brent(&f, lo, top, settings.tol_thrust)
        {
            consider(h);
        }
    }
    // Φ(h) = h − h_s,min right of the peak (Φ − h falls there).
    if sd.lo.is_finite() && hp.is_finite() && hp - sd.lo < g {
        let f = |h: f64| phi(h) - h + sd.lo;
        if let Some(hi) = bracket_negative(&f, hp, 1.0, settings)
            && let Some(h) = brent(&f, hi, hp, settings.tol_thrust)
        {
            consider(h);
        }
    }
    if hp.is_infinite() && sd.hi.is_infinite() {
        return (f64::INFINITY, f64::INFINITY);
    }
    best
}

/// A point beyond `x` in direction `dir` (±1) where `f` is negative, stepping by doubling:
/// left of `x` for an increasing `f`, right of it for a decreasing one.
fn bracket_negative(f: &impl Fn(f64) -> f64, x: f64, dir: f64, settings: &Settings) -> Option<f64> {
    let mut step = 1.0;
    while step < 4.0 * settings.max_bracket {
        let y = x + dir * step;
        if f(y) < 0.0 {
            return Some(y);
        }
        step *= 2.0;
    }
    None
}
