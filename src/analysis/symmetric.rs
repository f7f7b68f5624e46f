//! The paper's domains H^r and H^s (§2), the regime of a point and the critical quantities
//! of a symmetric arch under self-weight, in two unknowns (h = H/W_half and the crown
//! moment m).
//!
//! H^r is {h : Φ(h) ≥ 0} with Φ(h) = min_θ U(θ, h) − max_θ L(θ, h) concave; H^s is the
//! intersection of the sliding intervals of eqs. (4a, 4b). The arch stands iff
//! Ψ = max_h min(Φ(h), h_s,max − h, h − h_s,min) ≥ 0, a margin continuous in K and μ whose
//! zero is the collapse condition; its active terms at the maximiser name the mechanism.

use super::circular::{SlidingBound, SymmetricCircular};
use super::roots::{argmax_concave, brent};
use super::types::{Face, Hinge, Interval, Mechanism, Regime, Sense, SlidingJoint};
use crate::model::{Arch, Friction};
use std::f64::consts::FRAC_PI_2;

/// Tolerance on margins for classification (thrust over W_half, moments over W_half·r): a
/// state within it of a limit is a limit state and counts as admissible. It is far below the
/// 1e-9 to which critical values are reported, and above the rounding of the inputs (a
/// μ_min or K_c typed to 12 digits lies within it).
pub const MARGIN_TOL: f64 = 1e-12;
/// Tolerance under which a condition counts as active when naming a mechanism.
const ACTIVE_TOL: f64 = 1e-9;
/// Largest |h| or K − 1 explored when looking for brackets.
const FAR: f64 = 1e9;

/// The rotational domain H^r with the location of its widest point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotationalDomain {
    /// H^r as an interval of h (empty when the arch is too thin).
    pub interval: Interval,
    /// The h maximising Φ (may be infinite).
    pub peak_thrust: f64,
    /// max_h Φ(h): positive inside the rotational region, zero at K_c.
    pub peak_margin: f64,
}

/// The sliding domain H^s and the joints that bound it.
#[derive(Debug, Clone, PartialEq)]
pub struct SlidingDomain {
    /// H^s as an interval of h.
    pub interval: Interval,
    /// Joint (θ in radians) and sense of the row giving the lower end.
    pub lower_joint: Option<(f64, Sense)>,
    /// Joint (θ in radians) and sense of the row giving the upper end.
    pub upper_joint: Option<(f64, Sense)>,
}

/// Both domains of a point (K, μ).
#[derive(Debug, Clone, PartialEq)]
pub struct Domains {
    /// H^r.
    pub rotational: RotationalDomain,
    /// H^s.
    pub sliding: SlidingDomain,
}

/// Maximiser and maximum of a concave function given by value and supergradient.
fn concave_peak(value: impl Fn(f64) -> f64, slope: impl Fn(f64) -> f64) -> (f64, f64) {
    let (mut lo, mut hi) = (-1.0_f64, 1.0_f64);
    while slope(lo) <= 0.0 && lo > -FAR {
        lo *= 2.0;
    }
    if slope(lo) <= 0.0 {
        return (f64::NEG_INFINITY, value(-FAR).max(value(lo)));
    }
    while slope(hi) > 0.0 && hi < FAR {
        hi *= 2.0;
    }
    if slope(hi) > 0.0 {
        return (f64::INFINITY, value(FAR).max(value(hi)));
    }
    let h = argmax_concave(&slope, lo, hi, 1e-15);
    (h, value(h))
}

/// H^r: the thrusts for which a line of thrust fits in the arch (eqs. 2a, 2b).
pub fn rotational_domain(sym: &SymmetricCircular) -> RotationalDomain {
    let phi = |h: f64| sym.rotational_margin(h);
    let (sp, sm) = sym.rotational_asymptotic_slopes();
    let flat = 1e-13;
    if sp.abs() <= flat && sm.abs() <= flat {
        // Φ is constant (a single joint): H^r is everything or nothing.
        let g = phi(0.0);
        let interval = if g >= -MARGIN_TOL {
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
    let (h_peak, g) = rotational_peak(sym);
    if g < -MARGIN_TOL {
        return RotationalDomain {
            interval: Interval::EMPTY,
            peak_thrust: h_peak,
            peak_margin: g,
        };
    }
    let start = if h_peak.is_finite() {
        h_peak
    } else {
        h_peak.signum() * FAR
    };
    let root_toward = |dir: f64| -> f64 {
        if phi(start) < 0.0 {
            return start;
        }
        match bracket_negative(&phi, start, dir) {
            Some(x) => brent(phi, x, start, 1e-15).unwrap_or(start),
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
pub fn sliding_domain(sym: &SymmetricCircular, phi: f64) -> SlidingDomain {
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
        && d.interval.lo - d.interval.hi <= MARGIN_TOL * (1.0 + d.interval.lo.abs())
    {
        // Crossed by less than the tolerance: H^s is the single limit value (μ = μ_min).
        let mid = 0.5 * (d.interval.lo + d.interval.hi);
        d.interval = Interval { lo: mid, hi: mid };
    }
    d
}

/// Both domains at a point.
pub fn domains(arch: &Arch, friction: Friction) -> Domains {
    let sym = SymmetricCircular::new(arch);
    Domains {
        rotational: rotational_domain(&sym),
        sliding: sliding_domain(&sym, friction.angle()),
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
pub fn rotational_peak(sym: &SymmetricCircular) -> (f64, f64) {
    let phi = |h: f64| sym.rotational_margin(h);
    if let Some(n) = sym.voussoirs {
        return discrete_rotational_peak(sym, n)
            .unwrap_or_else(|| concave_peak(phi, |h| sym.rotational_slope(h)));
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
        return (f64::INFINITY, phi(FAR).max(phi(h_k)));
    }
    let t = c.acos();
    let h = (super::circular::theta_cot_theta(t) + 1.0 - sym.rho_s) / alpha;
    let h = h.max(h_k);
    (h, phi(h))
}

/// The peak of Φ for N voussoirs, exactly: the same structure as the continuum with the
/// joints of the half arch θ_i = α(2i + p)/N. Right of the kink, max_i L(θ_i, h) passes from
/// joint i + 1 to joint i at the breakpoint h_i = (b_{i+1} − b_i)/(cos θ_i − cos θ_{i+1})
/// (b_i = L(θ_i, 0); L is unimodal in θ, so the maximiser moves through consecutive joints),
/// and Φ stops rising at the breakpoint where cos θ_i first reaches K cos α. `None` when the
/// half arch has a single joint.
fn discrete_rotational_peak(sym: &SymmetricCircular, n: u32) -> Option<(f64, f64)> {
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
        return Some((f64::INFINITY, phi(FAR).max(phi(h_k))));
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
fn stability_margin(sym: &SymmetricCircular, sd: &Interval) -> (f64, f64) {
    if sd.is_empty() {
        // Within the classification tolerance H^s may be a point with its ends crossed by
        // rounding (μ = μ_min): that point, not 0, is the thrust of the limit state.
        let mid = 0.5 * (sd.lo + sd.hi);
        return (sd.hi - sd.lo, if mid.is_finite() { mid } else { 0.0 });
    }
    let phi = |h: f64| sym.rotational_margin(h);
    let value = |h: f64| phi(h).min(sd.hi - h).min(h - sd.lo);
    let (hp, g) = rotational_peak(sym);
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
        if let Some(lo) = bracket_negative(&f, top, -1.0)
            && let Some(h) = brent(&f, lo, top, 1e-15)
        {
            consider(h);
        }
    }
    // Φ(h) = h − h_s,min right of the peak (Φ − h falls there).
    if sd.lo.is_finite() && hp.is_finite() && hp - sd.lo < g {
        let f = |h: f64| phi(h) - h + sd.lo;
        if let Some(hi) = bracket_negative(&f, hp, 1.0)
            && let Some(h) = brent(&f, hi, hp, 1e-15)
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
fn bracket_negative(f: &impl Fn(f64) -> f64, x: f64, dir: f64) -> Option<f64> {
    let mut step = 1.0;
    while step < 4.0 * FAR {
        let y = x + dir * step;
        if f(y) < 0.0 {
            return Some(y);
        }
        step *= 2.0;
    }
    None
}

/// The regime of a point (DESIGN.md §1), tolerance-aware: limit states count as admissible.
pub fn regime_of(rot: &RotationalDomain, sld: &SlidingDomain) -> Regime {
    let r_ok = !rot.interval.is_empty();
    let s_ok = !sld.interval.is_empty();
    match (r_ok, s_ok) {
        (false, false) => Regime::None,
        (false, true) => Regime::Rotational,
        (true, false) => Regime::Sliding,
        (true, true) => {
            let tol = MARGIN_TOL * (1.0 + rot.interval.lo.abs().min(rot.interval.hi.abs()));
            let r = &rot.interval;
            let s = &sld.interval;
            if r.lo <= s.hi + tol && s.lo <= r.hi + tol {
                Regime::Stable
            } else {
                Regime::Mixed
            }
        }
    }
}

/// What a point looks like: its regime and both domains.
#[derive(Debug, Clone, PartialEq)]
pub struct StateReport {
    /// Regime.
    pub regime: Regime,
    /// H^r and H^s.
    pub domains: Domains,
}

/// The `state` analysis of a symmetric self-weight scene.
pub fn state(arch: &Arch, friction: Friction) -> StateReport {
    let domains = domains(arch, friction);
    StateReport {
        regime: regime_of(&domains.rotational, &domains.sliding),
        domains,
    }
}

/// A critical state: the parameters where the arch is at the limit, with its mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct CriticalState {
    /// K at the limit.
    pub k: f64,
    /// μ at the limit (infinite when friction plays no part).
    pub mu: f64,
    /// Crown thrust H/W_half of the limit state.
    pub thrust_over_half_weight: f64,
    /// Crown moment m/(W_half·r) of the limit state (line of thrust at height m/h).
    pub crown_moment: f64,
    /// Collapse mechanism.
    pub mechanism: Mechanism,
}

/// The outcome of a search for a critical value.
#[derive(Debug, Clone, PartialEq)]
pub enum Critical {
    /// A limit state exists.
    Found(CriticalState),
    /// No value of the searched parameter lets the arch stand (e.g. μ < μ_min).
    NeverStands,
    /// The arch stands for every admissible value (e.g. a single block, or μ = 0 suffices).
    AlwaysStands,
}

impl Critical {
    /// The state when found.
    pub fn found(&self) -> Option<&CriticalState> {
        match self {
            Critical::Found(s) => Some(s),
            _ => None,
        }
    }

    /// `found`, `never_stands` or `always_stands`.
    pub fn outcome_str(&self) -> &'static str {
        match self {
            Critical::Found(_) => "found",
            Critical::NeverStands => "never_stands",
            Critical::AlwaysStands => "always_stands",
        }
    }
}

/// Symmetric copies of a list of half-arch joints (θ ≥ 0), in degrees.
fn mirror<T: Copy>(items: &[(f64, T)]) -> Vec<(f64, T)> {
    let mut out = Vec::new();
    for &(t, x) in items {
        let d = t.to_degrees();
        if d.abs() < 1e-12 {
            out.push((0.0, x));
        } else {
            out.push((-d, x));
            out.push((d, x));
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-9);
    out
}

/// The hinges of the limit line of thrust at thrust h (half arch, θ in radians), the crown
/// moment m and whether Φ is active.
fn hinges_at(sym: &SymmetricCircular, h: f64) -> (Vec<(f64, Face)>, f64, bool) {
    let (lmax, t0, t1) = sym.intrados_max(h);
    let (umin, _, _) = sym.extrados_min(h);
    let m = 0.5 * (lmax + umin);
    let scale = 1.0 + m.abs();
    if umin - lmax > ACTIVE_TOL * scale {
        return (Vec::new(), m, false);
    }
    let tol = ACTIVE_TOL * scale;
    let mut out = Vec::new();
    let (e0, e1) = sym.end_joints();
    let mut intrados_candidates = vec![t0, t1, e0];
    intrados_candidates.dedup();
    for t in intrados_candidates {
        if sym.intrados(t, h) >= m - tol && !out.iter().any(|&(x, f)| x == t && f == Face::Intrados)
        {
            out.push((t, Face::Intrados));
        }
    }
    for t in [e0, e1] {
        if sym.extrados(t, h) <= m + tol && !out.iter().any(|&(x, f)| x == t && f == Face::Extrados)
        {
            out.push((t, Face::Extrados));
        }
    }
    (out, m, true)
}

/// The limit state of a symmetric arch at thrust h with sliding domain `sd` (both ends of
/// H^s that are active at h slide).
fn limit_state(
    sym: &SymmetricCircular,
    sd: &SlidingDomain,
    h: f64,
    k: f64,
    mu: f64,
) -> Option<CriticalState> {
    let (hinges, m, _) = hinges_at(sym, h);
    let tol = ACTIVE_TOL * (1.0 + h.abs());
    let mut sliding = Vec::new();
    // A joint that carries no normal force (an open crown at zero thrust) cannot slide.
    let carries = |t: f64| h * t.cos() + sym.w(t) * t.sin() > tol;
    if let Some((t, s)) = sd.upper_joint
        && (sd.interval.hi - h).abs() <= tol
        && carries(t)
    {
        sliding.push((t, s));
    }
    if let Some((t, s)) = sd.lower_joint
        && (h - sd.interval.lo).abs() <= tol
        && carries(t)
    {
        sliding.push((t, s));
    }
    let hinges = mirror(&hinges)
        .into_iter()
        .map(|(angle_deg, face)| Hinge { angle_deg, face })
        .collect();
    let sliding = mirror(&sliding)
        .into_iter()
        .map(|(angle_deg, sense)| SlidingJoint { angle_deg, sense })
        .collect();
    let mechanism = Mechanism::from_parts(hinges, sliding)?;
    Some(CriticalState {
        k,
        mu,
        thrust_over_half_weight: h,
        crown_moment: m,
        mechanism,
    })
}

/// Offset below which a margin counts as having reached its plateau when locating a limit.
const PLATEAU_TOL: f64 = 1e-13;

/// The limit between `lo` (margin below −tolerance) and `hi` (admissible within tolerance),
/// for a margin that is non-decreasing in the searched parameter.
///
/// Beyond the limit the margin either keeps rising (a clean root) or stays on a plateau: at
/// K = K_c the rotational margin is 0 for every larger μ, at μ = μ_min the sliding one is 0
/// for every larger K, and rounding makes such a plateau noise of ±1e-16. The root is taken
/// of margin − min(margin(hi), 0) + 1e-13, which is positive on the plateau and crosses
/// zero where the margin reaches it; the returned point is admissible.
fn limit_root(margin: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Option<f64> {
    let plateau = margin(hi).min(0.0);
    let f = |x: f64| margin(x) - plateau + PLATEAU_TOL;
    if f(lo) >= 0.0 {
        return Some(lo);
    }
    brent(f, lo, hi, 1e-15)
}

/// The collapse thickness K_c at friction μ (paper §5): the smallest K at which the arch
/// stands. Invariant: the arch stands at the returned K and not below it.
pub fn thickness(arch: &Arch, friction: Friction) -> Critical {
    let phi = friction.angle();
    let base = SymmetricCircular::new(arch);
    let sd = sliding_domain(&base, phi);
    if sd.interval.is_empty() {
        return Critical::NeverStands;
    }
    let sym_at = |k: f64| SymmetricCircular::new(&arch.with_k(k));
    let margin = |k: f64| stability_margin(&sym_at(k), &sd.interval).0;
    let k_lo = 1.0 + 1e-12;
    if margin(k_lo) >= -MARGIN_TOL {
        return Critical::AlwaysStands;
    }
    let mut k_hi = 1.5;
    while margin(k_hi) < -MARGIN_TOL {
        k_hi = 1.0 + 2.0 * (k_hi - 1.0);
        if k_hi > FAR {
            return Critical::NeverStands;
        }
    }
    let Some(k) = limit_root(margin, k_lo, k_hi) else {
        return Critical::NeverStands;
    };
    let sym = sym_at(k);
    let (_, h) = stability_margin(&sym, &sd.interval);
    match limit_state(&sym, &sd, h, k, friction.mu()) {
        Some(s) => Critical::Found(s),
        None => Critical::NeverStands,
    }
}

/// The critical friction μ_c at K: the smallest μ at which the arch stands.
pub fn friction(arch: &Arch) -> Critical {
    let sym = SymmetricCircular::new(arch);
    let margin = |phi: f64| stability_margin(&sym, &sliding_domain(&sym, phi).interval).0;
    if margin(FRAC_PI_2) < -MARGIN_TOL {
        return Critical::NeverStands;
    }
    if margin(0.0) >= -MARGIN_TOL {
        return Critical::AlwaysStands;
    }
    let Some(phi) = limit_root(margin, 0.0, FRAC_PI_2) else {
        return Critical::NeverStands;
    };
    let sd = sliding_domain(&sym, phi);
    let (_, h) = stability_margin(&sym, &sd.interval);
    let mu = phi.tan();
    match limit_state(&sym, &sd, h, arch.k, mu) {
        Some(s) => Critical::Found(s),
        None => Critical::AlwaysStands,
    }
}

/// μ_min: the friction below which H^s is empty for every K (it shrinks to one value there).
pub fn sliding_threshold(arch: &Arch) -> Critical {
    let sym = SymmetricCircular::new(arch);
    let width = |phi: f64| {
        let i = sliding_domain(&sym, phi).interval;
        if i.hi.is_infinite() || i.lo.is_infinite() {
            1.0
        } else {
            i.hi - i.lo
        }
    };
    if width(0.0) >= 0.0 {
        return Critical::AlwaysStands;
    }
    if width(FRAC_PI_2) < 0.0 {
        return Critical::NeverStands;
    }
    let Some(phi) = brent(width, 0.0, FRAC_PI_2, 1e-16) else {
        return Critical::NeverStands;
    };
    let sd = sliding_domain(&sym, phi);
    let h = sd.interval.hi;
    let sliding = [sd.lower_joint, sd.upper_joint]
        .into_iter()
        .flatten()
        .collect::<Vec<_>>();
    let sliding = mirror(&sliding)
        .into_iter()
        .map(|(angle_deg, sense)| SlidingJoint { angle_deg, sense })
        .collect();
    match Mechanism::from_parts(Vec::new(), sliding) {
        Some(mechanism) => Critical::Found(CriticalState {
            k: f64::NAN,
            mu: phi.tan(),
            thrust_over_half_weight: h,
            crown_moment: f64::NAN,
            mechanism,
        }),
        None => Critical::NeverStands,
    }
}

/// One extreme admissible state: the thrust and the active joints.
#[derive(Debug, Clone, PartialEq)]
pub struct ThrustState {
    /// H/W_half.
    pub thrust_over_half_weight: f64,
    /// Crown moment over W_half·r (NaN when the state is not a rotational limit).
    pub crown_moment: f64,
    /// Hinges of the whole arch.
    pub hinges: Vec<Hinge>,
    /// Sliding joints of the whole arch.
    pub sliding_joints: Vec<SlidingJoint>,
}

/// The minimum and maximum thrust states at (K, μ); `None` when the arch cannot stand.
pub fn thrust(arch: &Arch, friction: Friction) -> Option<(ThrustState, ThrustState)> {
    let sym = SymmetricCircular::new(arch);
    let rot = rotational_domain(&sym);
    let sd = sliding_domain(&sym, friction.angle());
    if regime_of(&rot, &sd) != Regime::Stable {
        return None;
    }
    let both = rot.interval.intersect(&sd.interval);
    let (lo, hi) = if both.is_empty() {
        // Limit state within tolerance: a single admissible thrust.
        let h = 0.5 * (rot.interval.lo.max(sd.interval.lo) + rot.interval.hi.min(sd.interval.hi));
        (h, h)
    } else {
        (both.lo, both.hi)
    };
    let at = |h: f64| -> ThrustState {
        if !h.is_finite() {
            return ThrustState {
                thrust_over_half_weight: h,
                crown_moment: f64::NAN,
                hinges: Vec::new(),
                sliding_joints: Vec::new(),
            };
        }
        match limit_state(&sym, &sd, h, arch.k, friction.mu()) {
            Some(s) => ThrustState {
                thrust_over_half_weight: h,
                crown_moment: s.crown_moment,
                hinges: s.mechanism.hinges,
                sliding_joints: s.mechanism.sliding_joints,
            },
            None => ThrustState {
                thrust_over_half_weight: h,
                crown_moment: f64::NAN,
                hinges: Vec::new(),
                sliding_joints: Vec::new(),
            },
        }
    };
    Some((at(lo), at(hi)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Discretisation, WeightModel};

    const K_C: f64 = 1.113581813339;
    const MU_ROT: f64 = 0.395265252140;
    const MU_MIN: f64 = 0.309215444330;
    const K_BIF: f64 = 1.220507754643;

    fn semi(k: f64) -> Arch {
        Arch::semicircular(k).unwrap()
    }

    #[test]
    fn rotational_collapse_thickness_matches_reference() {
        let c = thickness(&semi(1.5), Friction::INFINITE);
        let s = c.found().expect("K_c exists");
        assert!((s.k - K_C).abs() < 1e-9, "K_c = {}", s.k);
        assert!((crate::model::t_over_r_from_k(s.k) - 0.107478038107).abs() < 1e-9);
        assert!((s.thrust_over_half_weight - MU_ROT).abs() < 1e-9);
        assert_eq!(s.mechanism.kind, crate::analysis::MechanismKind::Rotational);
        let haunch = s
            .mechanism
            .hinges
            .iter()
            .find(|h| h.face == Face::Intrados)
            .unwrap();
        assert!(
            (haunch.angle_deg.abs() - 54.48397403).abs() < 1e-6,
            "{haunch:?}"
        );
        // Crown extrados, two haunches, two springings.
        assert_eq!(s.mechanism.hinges.len(), 5, "{:?}", s.mechanism.hinges);
    }

    #[test]
    fn sliding_threshold_matches_reference() {
        let c = sliding_threshold(&semi(1.3));
        let s = c.found().unwrap();
        assert!((s.mu - MU_MIN).abs() < 1e-9, "μ_min = {}", s.mu);
        let angles: Vec<f64> = s
            .mechanism
            .sliding_joints
            .iter()
            .map(|j| j.angle_deg)
            .collect();
        assert_eq!(angles.len(), 4);
        assert!((angles[2] - 28.63619468).abs() < 1e-6, "{angles:?}");
        assert!((angles[3] - 90.0).abs() < 1e-9);
    }

    #[test]
    fn bifurcations_match_reference() {
        // Rotational/mixed: μ_c at K_c equals the thrust there.
        let kc = thickness(&semi(1.5), Friction::INFINITE).found().unwrap().k;
        let f = friction(&semi(kc));
        let s = f.found().unwrap();
        assert!((s.mu - MU_ROT).abs() < 1e-9, "μ = {}", s.mu);
        // Mixed/sliding: K_c at μ_min.
        let mu_min = sliding_threshold(&semi(1.3)).found().unwrap().mu;
        let t = thickness(&semi(1.5), Friction::new(mu_min).unwrap());
        let s = t.found().unwrap();
        assert!((s.k - K_BIF).abs() < 1e-8, "K = {}", s.k);
    }

    #[test]
    fn friction_on_the_sliding_segment_is_the_sliding_mechanism() {
        // Beyond the mixed/sliding bifurcation μ_c = μ_min, where H^s is a single thrust
        // (μ_min·W_half at the springings) inside H^r: no hinge, four sliding joints.
        let s = friction(&semi(1.3)).found().cloned().unwrap();
        assert!((s.mu - MU_MIN).abs() < 1e-9, "μ = {}", s.mu);
        assert_eq!(s.mechanism.kind, crate::analysis::MechanismKind::Sliding);
        assert!((s.thrust_over_half_weight - MU_MIN).abs() < 1e-9);
        assert!(s.mechanism.hinges.is_empty(), "{:?}", s.mechanism.hinges);
        let angles: Vec<f64> = s
            .mechanism
            .sliding_joints
            .iter()
            .map(|j| j.angle_deg)
            .collect();
        assert_eq!(angles.len(), 4, "{angles:?}");
        assert!((angles[2] - 28.63619468).abs() < 1e-6 && (angles[3] - 90.0).abs() < 1e-9);
    }

    #[test]
    fn closed_form_peak_matches_bisection_on_the_supergradient() {
        for alpha in [20.0, 45.0, 90.0, 120.0, 160.0] {
            for k in [1.05, 1.2, 1.6, 3.0] {
                for w in [WeightModel::Annular, WeightModel::Centreline] {
                    let a = Arch::new(k, alpha, w, Discretisation::Continuum).unwrap();
                    let sym = SymmetricCircular::new(&a);
                    let (h1, g1) = rotational_peak(&sym);
                    let (h2, g2) =
                        concave_peak(|h| sym.rotational_margin(h), |h| sym.rotational_slope(h));
                    if h1.is_infinite() || h2.is_infinite() {
                        assert_eq!(h1.is_infinite(), h2.is_infinite(), "α = {alpha}, K = {k}");
                        continue;
                    }
                    assert!(
                        (g1 - g2).abs() < 1e-13,
                        "α = {alpha}, K = {k}: {g1} vs {g2}"
                    );
                    assert!(g1 >= g2 - 1e-15, "the closed form is the true maximum");
                    assert!(
                        (h1 - h2).abs() < 1e-6 * (1.0 + h1.abs()),
                        "α = {alpha}, K = {k}: {h1} vs {h2}"
                    );
                }
            }
        }
    }

    #[test]
    fn discrete_peak_matches_bisection_on_the_supergradient() {
        for n in [2u32, 3, 4, 5, 7, 8, 16, 33, 64, 101, 512] {
            for alpha in [30.0, 90.0, 140.0] {
                for k in [1.02, 1.1, 1.3, 2.0] {
                    let a = Arch::new(k, alpha, WeightModel::Annular, Discretisation::Voussoirs(n))
                        .unwrap();
                    let sym = SymmetricCircular::new(&a);
                    let Some((h1, g1)) = discrete_rotational_peak(&sym, n) else {
                        continue;
                    };
                    let (h2, g2) =
                        concave_peak(|h| sym.rotational_margin(h), |h| sym.rotational_slope(h));
                    if h1.is_infinite() || h2.is_infinite() {
                        assert_eq!(
                            h1.is_infinite(),
                            h2.is_infinite(),
                            "N = {n}, α = {alpha}, K = {k}"
                        );
                        continue;
                    }
                    assert!(
                        (g1 - g2).abs() < 1e-12,
                        "N = {n}, α = {alpha}, K = {k}: {g1} vs {g2} at {h1} / {h2}"
                    );
                }
            }
        }
    }

    #[test]
    fn min_thrust_hinge_at_k_1_35() {
        let (lo, _) = thrust(&semi(1.35), Friction::INFINITE).unwrap();
        let haunch = lo.hinges.iter().find(|h| h.face == Face::Intrados).unwrap();
        assert!(
            (haunch.angle_deg.abs() - 63.2903024).abs() < 1e-6,
            "{:?}",
            lo.hinges
        );
    }

    #[test]
    fn discrete_approaches_continuum_from_below() {
        let mut prev = 1.0;
        for n in [8u32, 16, 64, 512, 4096] {
            let a = Arch::new(
                1.5,
                90.0,
                WeightModel::Annular,
                Discretisation::Voussoirs(n),
            )
            .unwrap();
            let k = thickness(&a, Friction::INFINITE).found().unwrap().k;
            assert!(k <= K_C + 1e-12, "N = {n}: {k}");
            assert!(k >= prev - 1e-4, "N = {n}: {k} < {prev}");
            prev = k;
            if n >= 512 {
                assert!(K_C - k < 1e-6, "N = {n}: {k}");
            }
        }
    }
}
