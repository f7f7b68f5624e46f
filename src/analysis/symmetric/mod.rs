//! The paper's domains H^r and H^s (§2), the regime of a point and the critical quantities
//! of a symmetric arch under self-weight, in two unknowns (h = H/W_half and the crown
//! moment m).
//!
//! H^r is {h : Φ(h) ≥ 0} with Φ(h) = min_θ U(θ, h) − max_θ L(θ, h) concave; H^s is the
//! intersection of the sliding intervals of eqs. (4a, 4b). The arch stands iff
//! Ψ = max_h min(Φ(h), h_s,max − h, h − h_s,min) ≥ 0, a margin continuous in K and μ whose
//! zero is the collapse condition; its active terms at the maximiser name the mechanism.

mod critical;
mod domains;
mod lines;
#[cfg(test)]
mod tests;

pub use critical::{
    friction_with, sliding_threshold_with, thickness_windows_with, thickness_with, thrust_with,
};
pub use domains::{
    domains_with, rotational_domain_with, rotational_peak_with, sliding_domain_with,
};
pub use lines::{LineRegimes, collapse_thickness, critical_friction, line_regimes};

use crate::analysis::circular::SymmetricCircular;
pub use crate::analysis::settings::SymmetricSettings as Settings;
use crate::analysis::types::{Hinge, Interval, Mechanism, Regime, Sense, SlidingJoint};
use crate::model::{Arch, Friction};

/// Tolerance on margins for classification: [`SymmetricSettings::tol_margin`] of the
/// defaults (thrust over W_half, moments over W_half·r).
///
/// [`SymmetricSettings::tol_margin`]: crate::analysis::settings::SymmetricSettings::tol_margin
pub const MARGIN_TOL: f64 = Settings::DEFAULT.tol_margin;

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

/// The regime of a point (docs/mechanics.md §1), tolerance-aware: limit states count as admissible.
pub fn regime_of_with(rot: &RotationalDomain, sld: &SlidingDomain, settings: &Settings) -> Regime {
    let r_ok = !rot.interval.is_empty();
    let s_ok = !sld.interval.is_empty();
    match (r_ok, s_ok) {
        (false, false) => Regime::None,
        (false, true) => Regime::Rotational,
        (true, false) => Regime::Sliding,
        (true, true) => {
            let tol =
                settings.tol_margin * (1.0 + rot.interval.lo.abs().min(rot.interval.hi.abs()));
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
pub fn state_with(arch: &Arch, friction: Friction, settings: &Settings) -> StateReport {
    let domains = domains_with(arch, friction, settings);
    StateReport {
        regime: regime_of_with(&domains.rotational, &domains.sliding, settings),
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

// Entry points with the default settings, for callers that do not tune tolerances.

/// H^r with the default settings ([`rotational_domain_with`]).
pub fn rotational_domain(sym: &SymmetricCircular) -> RotationalDomain {
    rotational_domain_with(sym, &Settings::DEFAULT)
}

/// H^s at friction angle φ (radians) with the default settings ([`sliding_domain_with`]).
pub fn sliding_domain(sym: &SymmetricCircular, phi: f64) -> SlidingDomain {
    sliding_domain_with(sym, phi, &Settings::DEFAULT)
}

/// Both domains at a point with the default settings ([`domains_with`]).
pub fn domains(arch: &Arch, friction: Friction) -> Domains {
    domains_with(arch, friction, &Settings::DEFAULT)
}

/// The peak of Φ with the default settings ([`rotational_peak_with`]).
pub fn rotational_peak(sym: &SymmetricCircular) -> (f64, f64) {
    rotational_peak_with(sym, &Settings::DEFAULT)
}

/// The regime of a point with the default settings ([`regime_of_with`]).
pub fn regime_of(rot: &RotationalDomain, sld: &SlidingDomain) -> Regime {
    regime_of_with(rot, sld, &Settings::DEFAULT)
}

/// The `state` analysis with the default settings ([`state_with`]).
pub fn state(arch: &Arch, friction: Friction) -> StateReport {
    state_with(arch, friction, &Settings::DEFAULT)
}

/// K_c at friction μ with the default settings ([`thickness_with`]).
pub fn thickness(arch: &Arch, friction: Friction) -> Critical {
    thickness_with(arch, friction, &Settings::DEFAULT)
}

/// μ_c at K with the default settings ([`friction_with`]).
pub fn friction(arch: &Arch) -> Critical {
    friction_with(arch, &Settings::DEFAULT)
}

/// μ_min with the default settings ([`sliding_threshold_with`]).
pub fn sliding_threshold(arch: &Arch) -> Critical {
    sliding_threshold_with(arch, &Settings::DEFAULT)
}

/// The extreme thrust states at (K, μ) with the default settings ([`thrust_with`]).
pub fn thrust(arch: &Arch, friction: Friction) -> Option<(ThrustState, ThrustState)> {
    thrust_with(arch, friction, &Settings::DEFAULT)
}
