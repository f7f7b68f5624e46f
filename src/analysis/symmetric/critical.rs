//! Critical values of a symmetric arch (K_c, μ_c, μ_min), its limit states and the
//! extreme thrust states.

use super::domains::{rotational_domain_with, sliding_domain_with, stability_margin};
use super::{Critical, CriticalState, Settings, SlidingDomain, ThrustState, regime_of_with};
use crate::analysis::circular::SymmetricCircular;
use crate::analysis::roots::brent;
use crate::analysis::types::{Face, Hinge, Mechanism, Regime, SlidingJoint};
use crate::analysis::windows::{self, WindowSettings, Windows};
use crate::model::{Arch, Friction};
use std::f64::consts::FRAC_PI_2;

/// Symmetric copies of a list of half-arch joints (θ ≥ 0), in degrees.
fn mirror<T: Copy>(items: &[(f64, T)], settings: &Settings) -> Vec<(f64, T)> {
    let mut out = Vec::new();
    for &(t, x) in items {
        let d = t.to_degrees();
        if d.abs() < settings.tol_crown_deg {
            out.push((0.0, x));
        } else {
            out.push((-d, x));
            out.push((d, x));
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.dedup_by(|a, b| (a.0 - b.0).abs() < settings.tol_same_joint_deg);
    out
}

/// The hinges of the limit line of thrust at thrust h (half arch, θ in radians), the crown
/// moment m and whether Φ is active.
fn hinges_at(
    sym: &SymmetricCircular,
    h: f64,
    settings: &Settings,
) -> (Vec<(f64, Face)>, f64, bool) {
    let (lmax, t0, t1) = sym.intrados_max(h);
    let (umin, _, _) = sym.extrados_min(h);
    let m = 0.5 * (lmax + umin);
    let scale = 1.0 + m.abs();
    if umin - lmax > settings.tol_hinge * scale {
        return (Vec::new(), m, false);
    }
    let tol = settings.tol_hinge * scale;
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
    at: LimitPoint,
    settings: &Settings,
) -> Option<CriticalState> {
    let LimitPoint { h, k, mu } = at;
    let (hinges, m, _) = hinges_at(sym, h, settings);
    let tol = settings.tol_hinge * (1.0 + h.abs());
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
    let hinges = mirror(&hinges, settings)
        .into_iter()
        .map(|(angle_deg, face)| Hinge { angle_deg, face })
        .collect();
    let sliding = mirror(&sliding, settings)
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

/// The limit between `lo` (margin below −tolerance) and `hi` (admissible within tolerance),
/// for a margin that is non-decreasing in the searched parameter.
///
/// Beyond the limit the margin either keeps rising (a clean root) or stays on a plateau: at
/// K = K_c the rotational margin is 0 for every larger μ, at μ = μ_min the sliding one is 0
/// for every larger K, and rounding makes such a plateau noise of ±1e-16. The root is taken
/// of margin − min(margin(hi), 0) + `tol_plateau`, which is positive on the plateau and crosses
/// zero where the margin reaches it; the returned point is admissible.
fn limit_root(margin: impl Fn(f64) -> f64, lo: f64, hi: f64, settings: &Settings) -> Option<f64> {
    let plateau = margin(hi).min(0.0);
    let f = |x: f64| margin(x) - plateau + settings.tol_plateau;
    if f(lo) >= 0.0 {
        return Some(lo);
    }
    brent(f, lo, hi, settings.tol_limit_root)
}

/// The collapse thickness K_c at friction μ (paper §5): the smallest K at which the arch
/// stands. Invariant: the arch stands at the returned K and not below it.
pub fn thickness_with(arch: &Arch, friction: Friction, settings: &Settings) -> Critical {
    let phi = friction.angle();
    let base = SymmetricCircular::new(arch);
    let sd = sliding_domain_with(&base, phi, settings);
    if sd.interval.is_empty() {
        return Critical::NeverStands;
    }
    let sym_at = |k: f64| SymmetricCircular::new(&arch.with_k(k));
    let margin = |k: f64| stability_margin(&sym_at(k), &sd.interval, settings).0;
    let k_lo = 1.0 + settings.k_search_offset;
    if margin(k_lo) >= -settings.tol_margin {
        return Critical::AlwaysStands;
    }
    let mut k_hi = settings.k_search_start;
    while margin(k_hi) < -settings.tol_margin {
        k_hi = 1.0 + 2.0 * (k_hi - 1.0);
        if k_hi > settings.max_bracket {
            return Critical::NeverStands;
        }
    }
    let Some(k) = limit_root(margin, k_lo, k_hi, settings) else {
        return Critical::NeverStands;
    };
    let sym = sym_at(k);
    let (_, h) = stability_margin(&sym, &sd.interval, settings);
    let at = LimitPoint {
        h,
        k,
        mu: friction.mu(),
    };
    match limit_state(&sym, &sd, at, settings) {
        Some(s) => Critical::Found(s),
        None => Critical::NeverStands,
    }
}

/// The windows of K in which the arch stands ([`crate::analysis::windows`]), scanned with
/// the margin of [`thickness_with`], when they agree with its answer `found`: K_c starts the
/// first window, `always_stands` is one window from the lower end of the search to the end
/// of the scan, `never_stands` none. `None` when they disagree (the caller answers by
/// another route).
pub fn thickness_windows_with(
    arch: &Arch,
    friction: Friction,
    found: &Critical,
    settings: &Settings,
    ws: &WindowSettings,
) -> Option<Windows> {
    let sd = sliding_domain_with(&SymmetricCircular::new(arch), friction.angle(), settings);
    let psi = |k: f64| {
        let m = stability_margin(
            &SymmetricCircular::new(&arch.with_k(k)),
            &sd.interval,
            settings,
        );
        Ok::<f64, ()>(m.0 + settings.tol_margin)
    };
    let k_c = found.found().map(|s| s.k);
    let lo = 1.0 + settings.k_search_offset;
    let w = windows::scan(psi, lo, ws.upper_end(k_c, f64::INFINITY), k_c, ws).ok()?;
    let first = w.windows.first();
    let agree = match found {
        Critical::Found(s) => first.is_some_and(|f| f.from == s.k),
        Critical::AlwaysStands => w.windows.len() == 1 && first.is_some_and(|f| f.from == lo),
        Critical::NeverStands => first.is_none(),
    };
    agree.then_some(w)
}

/// The critical friction μ_c at K: the smallest μ at which the arch stands.
pub fn friction_with(arch: &Arch, settings: &Settings) -> Critical {
    let sym = SymmetricCircular::new(arch);
    let margin = |phi: f64| {
        stability_margin(
            &sym,
            &sliding_domain_with(&sym, phi, settings).interval,
            settings,
        )
        .0
    };
    if margin(FRAC_PI_2) < -settings.tol_margin {
        return Critical::NeverStands;
    }
    if margin(0.0) >= -settings.tol_margin {
        return Critical::AlwaysStands;
    }
    // H^r does not move with μ and H^s grows with it: the limit is where they first meet,
    // found on the width of their overlap without solving the rotational margin at each step.
    let hr = rotational_domain_with(&sym, settings).interval;
    let overlap = |phi: f64| {
        let both = sliding_domain_with(&sym, phi, settings)
            .interval
            .intersect(&hr);
        let w = both.width();
        if w.is_nan() {
            f64::NEG_INFINITY
        } else {
            w.clamp(-1e300, 1e300)
        }
    };
    let root = if hr.is_empty() {
        limit_root(margin, 0.0, FRAC_PI_2, settings)
    } else {
        limit_root(overlap, 0.0, FRAC_PI_2, settings)
    };
    let Some(phi) = root else {
        return Critical::NeverStands;
    };
    let sd = sliding_domain_with(&sym, phi, settings);
    let (_, h) = stability_margin(&sym, &sd.interval, settings);
    let at = LimitPoint {
        h,
        k: arch.k,
        mu: phi.tan(),
    };
    match limit_state(&sym, &sd, at, settings) {
        Some(s) => Critical::Found(s),
        None => Critical::AlwaysStands,
    }
}

/// μ_min: the friction below which H^s is empty for every K (it shrinks to one value there).
pub fn sliding_threshold_with(arch: &Arch, settings: &Settings) -> Critical {
    let sym = SymmetricCircular::new(arch);
    let width = |phi: f64| {
        let i = sliding_domain_with(&sym, phi, settings).interval;
        if i.hi.is_infinite() || i.lo.is_infinite() {
            1.0
        } else {
            i.width()
        }
    };
    if width(0.0) >= 0.0 {
        return Critical::AlwaysStands;
    }
    if width(FRAC_PI_2) < 0.0 {
        return Critical::NeverStands;
    }
    let Some(phi) = brent(width, 0.0, FRAC_PI_2, settings.tol_friction_angle) else {
        return Critical::NeverStands;
    };
    let sd = sliding_domain_with(&sym, phi, settings);
    let h = sd.interval.hi;
    let sliding = [sd.lower_joint, sd.upper_joint]
        .into_iter()
        .flatten()
        .collect::<Vec<_>>();
    let sliding = mirror(&sliding, settings)
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
/// The minimum and maximum thrust states at (K, μ); `None` when the arch cannot stand.
pub fn thrust_with(
    arch: &Arch,
    friction: Friction,
    settings: &Settings,
) -> Option<(ThrustState, ThrustState)> {
    let sym = SymmetricCircular::new(arch);
    let rot = rotational_domain_with(&sym, settings);
    let sd = sliding_domain_with(&sym, friction.angle(), settings);
    if regime_of_with(&rot, &sd, settings) != Regime::Stable {
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
        let point = LimitPoint {
            h,
            k: arch.k,
            mu: friction.mu(),
        };
        match limit_state(&sym, &sd, point, settings) {
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

/// Where a limit state is taken: thrust h = H/W_half, K and μ.
#[derive(Debug, Clone, Copy)]
struct LimitPoint {
    /// Crown thrust over W_half.
    h: f64,
    /// K = R/r.
    k: f64,
    /// Friction coefficient.
    mu: f64,
}
