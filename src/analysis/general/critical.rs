//! Critical values of the general route: K_c, μ_c and μ_min as roots of the margin in K or
//! φ (Brent).

use super::margin::{MarginSolution, margin};
use super::{ActiveRow, Outcome, RowSet, Settings};
use crate::analysis::circular::CircularArch;
use crate::analysis::roots::brent;
use crate::analysis::statics::{ArchGeometry, Condition};
use crate::analysis::types::Mechanism;
use crate::analysis::windows::{self, WindowSettings, Windows};
use crate::model::{Arch, Friction};
use std::cell::Cell;
use std::f64::consts::FRAC_PI_2;

/// A limit state found by a critical-value search.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitState {
    /// K = R/r at the limit for a thickness search; `None` for a friction search (the
    /// geometry's own K applies).
    pub k: Option<f64>,
    /// μ at the limit (infinite when friction plays no part).
    pub mu: f64,
    /// The margin solution there: crown state and active rows.
    pub state: MarginSolution,
    /// The mechanism named by the active rows.
    pub mechanism: Option<Mechanism>,
}

/// The outcome of a critical-value search.
#[derive(Debug, Clone, PartialEq)]
pub enum Critical {
    /// A limit state exists.
    Found(LimitState),
    /// No value of the searched parameter lets the arch stand.
    NeverStands,
    /// The arch stands for every admissible value of the searched parameter.
    AlwaysStands,
    /// A margin could not be computed.
    Failed(Outcome),
}

impl Critical {
    /// The limit state when found.
    pub fn found(&self) -> Option<&LimitState> {
        match self {
            Critical::Found(s) => Some(s),
            _ => None,
        }
    }
}

/// Brent on `psi` over [lo, hi] where psi(lo) < 0 ≤ psi(hi); a failed margin inside is
/// reported through `failed`.
fn root_of_margin(
    psi: impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    tol: f64,
    failed: &Cell<Option<Outcome>>,
) -> Result<Option<f64>, Outcome> {
    let r = brent(&psi, lo, hi, tol);
    match failed.get() {
        Some(o) => Err(o),
        None => Ok(r),
    }
}

/// The margin of all rows shifted for a root search: τ − τ_ref + tol, where τ_ref ≤ 0 is
/// the margin of the rows the search does not relax (see [`thickness`]). NaN on failure
/// (which stops Brent), recorded in `failed`.
fn shifted_margin(
    m: &MarginSolution,
    reference: f64,
    settings: &Settings,
    failed: &Cell<Option<Outcome>>,
) -> f64 {
    if m.outcome == Outcome::Solved {
        m.margin - reference + settings.tol_margin
    } else {
        failed.set(Some(m.outcome));
        f64::NAN
    }
}

/// A search that ends without a limit state.
#[derive(Debug, Clone, Copy)]
enum Stop {
    Never,
    Always,
    Failed(Outcome),
}

impl From<Stop> for Critical {
    fn from(s: Stop) -> Critical {
        match s {
            Stop::Never => Critical::NeverStands,
            Stop::Always => Critical::AlwaysStands,
            Stop::Failed(o) => Critical::Failed(o),
        }
    }
}

/// The reference τ_ref = min(τ, 0) of a margin that a search cannot improve, or the outcome
/// of the search when that margin already decides it.
fn reference(m: &MarginSolution, settings: &Settings) -> Result<f64, Stop> {
    if m.outcome != Outcome::Solved {
        return Err(Stop::Failed(m.outcome));
    }
    if !m.feasible(settings) {
        return Err(Stop::Never);
    }
    Ok(m.margin.min(0.0))
}

/// The bracket and tolerance of a [`search`].
#[derive(Debug, Clone, Copy)]
struct Bracket {
    /// The lower end, where the arch is expected not to stand.
    lo: f64,
    /// The first upper end.
    hi: f64,
    /// `hi` never goes beyond this.
    cap: f64,
    /// Absolute tolerance of the root.
    tol: f64,
    /// Whether `hi` doubles away from `lo` while psi(hi) < 0.
    grow_hi: bool,
    /// Largest hi − lo explored.
    max_span: f64,
}

/// The smallest p in [lo, hi] with psi(p) ≥ 0, for psi whose sign is non-decreasing; `hi`
/// doubles away from `lo` (up to `cap`) while psi(hi) < 0 when `grow_hi`.
fn search(
    psi: impl Fn(f64) -> f64,
    bracket: &Bracket,
    failed: &Cell<Option<Outcome>>,
) -> Result<f64, Stop> {
    let Bracket {
        lo,
        hi,
        cap,
        tol,
        grow_hi,
        max_span,
    } = *bracket;
    let check = |f: f64| match failed.get() {
        Some(o) => Err(Stop::Failed(o)),
        None => Ok(f),
    };
    if check(psi(lo))? >= 0.0 {
        return Err(Stop::Always);
    }
    let mut hi = hi.min(cap);
    while check(psi(hi))? < 0.0 {
        if !grow_hi || hi >= cap {
            return Err(Stop::Never);
        }
        hi = (lo + 2.0 * (hi - lo)).min(cap);
        if hi - lo > max_span {
            return Err(Stop::Never);
        }
    }
    match root_of_margin(psi, lo, hi, tol, failed) {
        Err(o) => Err(Stop::Failed(o)),
        Ok(None) => Err(Stop::Never),
        Ok(Some(p)) => Ok(p),
    }
}

/// The collapse thickness K_c of a circular arch at friction μ: the smallest K at which all
/// rows are feasible (the collapse condition of the paper's §5), by Brent on the margin in
/// K ∈ (1, ∞).
///
/// The root is taken of τ_all(K) − τ_ref + tol with τ_ref = min(τ_sliding, 0): thickness
/// cannot make the sliding rows more feasible, so when μ sits at μ_min (τ_sliding ≈ 0⁻) the
/// search measures the thickness against what sliding allows instead of against noise.
/// Invariant: τ_all ≥ τ_ref − `tol_margin` ≥ −2 `tol_margin` at the returned K.
pub fn thickness(arch: &Arch, friction: Friction, settings: &Settings) -> Critical {
    thickness_with(
        |k| Some(CircularArch::new(arch.with_k(k))),
        f64::INFINITY,
        Some(arch.k),
        friction,
        settings,
    )
}

/// The collapse thickness of any family of arches K ↦ `at(K)`, K ∈ (1, `k_max`), at
/// friction μ and the load factor `settings.lambda`: as [`thickness`].
///
/// `at(K)` is `None` where the family does not exist (it counts as not standing there).
/// `sliding_reference` is a K at which to take τ_ref when the sliding rows do not depend on
/// K (circular arches with radial joints: the loads over W_half are the same at every K);
/// `None` takes τ_ref = 0. A family that does not stand up to `k_max` never stands.
pub fn thickness_with<G: ArchGeometry, F: Fn(f64) -> Option<G>>(
    at: F,
    k_max: f64,
    sliding_reference: Option<f64>,
    friction: Friction,
    settings: &Settings,
) -> Critical {
    let family = match ThicknessFamily::new(at, k_max, sliding_reference, friction, settings) {
        Ok(f) => f,
        Err(c) => return c.into(),
    };
    family.search()
}

/// A family of arches K ↦ `at(K)` at one friction and load factor, with the shifted margin
/// ψ(K) = τ_all(K) − τ_ref + tol whose sign says whether the arch stands at K.
struct ThicknessFamily<'s, F> {
    at: F,
    /// The upper end of K searched, clear of the end of the family.
    cap: f64,
    tau_ref: f64,
    friction: Friction,
    settings: &'s Settings,
    failed: Cell<Option<Outcome>>,
}

impl<'s, G: ArchGeometry, F: Fn(f64) -> Option<G>> ThicknessFamily<'s, F> {
    fn new(
        at: F,
        k_max: f64,
        sliding_reference: Option<f64>,
        friction: Friction,
        settings: &'s Settings,
    ) -> Result<Self, Stop> {
        let phi = friction.angle();
        let tau_ref = match sliding_reference.and_then(&at) {
            Some(g) => reference(&margin(&g, phi, RowSet::Sliding, settings), settings)?,
            None => 0.0,
        };
        // Stay clear of the end of the family, where it degenerates.
        let cap = if k_max.is_finite() {
            1.0 + (k_max - 1.0) * (1.0 - settings.family_end_clearance)
        } else {
            f64::INFINITY
        };
        Ok(ThicknessFamily {
            at,
            cap,
            tau_ref,
            friction,
            settings,
            failed: Cell::new(None),
        })
    }

    /// The lower end of every search.
    fn lo(&self) -> f64 {
        1.0 + self.settings.k_search_offset
    }

    /// ψ(K): ≥ 0 where the arch stands; NaN on failure, recorded in `failed`.
    fn psi(&self, k: f64) -> f64 {
        match (self.at)(k) {
            Some(g) => shifted_margin(
                &margin(&g, self.friction.angle(), RowSet::All, self.settings),
                self.tau_ref,
                self.settings,
                &self.failed,
            ),
            None => -1.0,
        }
    }

    /// ψ(K), or the outcome of the first margin that failed.
    fn checked_psi(&self, k: f64) -> Result<f64, Outcome> {
        let v = self.psi(k);
        self.failed.get().map_or(Ok(v), Err)
    }

    /// The smallest K at which the arch stands, by Brent from K = 1.
    fn search(&self) -> Critical {
        let bracket = Bracket {
            lo: self.lo(),
            hi: self.settings.k_search_start,
            cap: self.cap,
            tol: self.settings.tol_thickness,
            grow_hi: true,
            max_span: self.settings.max_bracket,
        };
        match search(|k| self.psi(k), &bracket, &self.failed) {
            Ok(k) => self.limit_state(k),
            Err(c) => c.into(),
        }
    }

    /// The limit state at K, the start of a window.
    fn limit_state(&self, k: f64) -> Critical {
        let Some(g) = (self.at)(k) else {
            return Critical::NeverStands;
        };
        let state = margin(&g, self.friction.angle(), RowSet::All, self.settings);
        let mechanism = state.mechanism_with(self.settings);
        if mechanism.is_some() && hinges_on_both_faces(&g, &state.active, self.settings) {
            // The thrust touches both faces of one joint: the joint has shrunk to a point, so
            // the root is K → 1, where the arch stands with a thrust line through its joint
            // points (a three-voussoir pointed arch at μ = ∞): it stands at every thickness.
            return Critical::AlwaysStands;
        }
        Critical::Found(LimitState {
            k: Some(k),
            mu: self.friction.mu(),
            mechanism,
            state,
        })
    }

    /// The start K of a window that is no limit state of a mechanism (the lower end of the
    /// search, or a joint shrunk to a point): its state, no mechanism.
    fn start_without_mechanism(&self, k: f64) -> Critical {
        match (self.at)(k) {
            Some(g) => Critical::Found(LimitState {
                k: Some(k),
                mu: self.friction.mu(),
                mechanism: None,
                state: margin(&g, self.friction.angle(), RowSet::All, self.settings),
            }),
            None => Critical::NeverStands,
        }
    }

    /// The windows of K over the scan, with the outcome of the search made to agree with
    /// them: K_c is the start of the first window; `always_stands` only when the arch stands
    /// over the whole scan, `never_stands` only when it stands nowhere in it.
    fn windows(&self, searched: Critical, ws: &WindowSettings) -> (Critical, Option<Windows>) {
        let k_c = searched.found().and_then(|s| s.k);
        let lo = self.lo();
        let hi = ws.upper_end(k_c, self.cap);
        if !(hi > lo) {
            return (searched, None);
        }
        let found = match windows::scan(|k| self.checked_psi(k), lo, hi, k_c, ws) {
            Ok(w) => w,
            Err(o) => return (Critical::Failed(o), None),
        };
        let first = found.windows.first().copied();
        let critical = match (searched, first) {
            // The scan keeps the search's K_c as the start of its first window.
            (Critical::Found(s), Some(w)) if Some(w.from) == s.k => Critical::Found(s),
            (Critical::AlwaysStands, Some(w)) if w.from == lo && w.to.is_none() => {
                Critical::AlwaysStands
            }
            (Critical::NeverStands, None) => Critical::NeverStands,
            (Critical::Failed(o), _) => Critical::Failed(o),
            // The search and the scan disagree: the scan, which saw the whole range, decides.
            (_, None) => Critical::NeverStands,
            (_, Some(w)) if w.from == lo => self.start_without_mechanism(lo),
            (_, Some(w)) => match self.limit_state(w.from) {
                Critical::AlwaysStands => self.start_without_mechanism(w.from),
                c => c,
            },
        };
        (critical, Some(found))
    }
}

/// The collapse thickness of a family of arches as [`thickness_with`], and every window of K
/// in which the arch stands ([`windows`](crate::analysis::windows)): the first window starts
/// at K_c. The outcome is the one the whole scan supports: `always_stands` only when the
/// arch stands from the lower end of the search to the end of the scan, `never_stands` only
/// when it stands nowhere in it. The windows are `None` when no margin could be computed.
pub fn thickness_windows<G: ArchGeometry, F: Fn(f64) -> Option<G>>(
    at: F,
    k_max: f64,
    sliding_reference: Option<f64>,
    friction: Friction,
    settings: &Settings,
    ws: &WindowSettings,
) -> (Critical, Option<Windows>) {
    let family = match ThicknessFamily::new(at, k_max, sliding_reference, friction, settings) {
        Ok(f) => f,
        Err(Stop::Never) => {
            // The sliding rows alone never stand: no thickness helps.
            return (Critical::NeverStands, None);
        }
        Err(c) => return (c.into(), None),
    };
    let searched = family.search();
    family.windows(searched, ws)
}

/// True when the active rows put hinges on both faces of one joint that has shrunk to a
/// point (shorter than `settings.tol_point_joint`). Joints are told apart by their parameter
/// θ and their length, not by the angle that names them: on a vertical-joint arch the
/// vertical joint at −α and the radial support joint beyond it (its parameter one float
/// further out) are two joints with a wedge between them, and hinges on opposite faces of the
/// two are an ordinary mechanism.
fn hinges_on_both_faces<G: ArchGeometry>(
    geom: &G,
    active: &[ActiveRow],
    settings: &Settings,
) -> bool {
    let hinge = |r: &ActiveRow| matches!(r.condition, Condition::Intrados | Condition::Extrados);
    active.iter().filter(|a| hinge(a)).any(|a| {
        geom.joint(a.theta).length() <= settings.tol_point_joint
            && active.iter().filter(|b| hinge(b)).any(|b| {
                a.condition != b.condition
                    && (a.theta - b.theta).abs() <= settings.tol_same_joint * (1.0 + a.theta.abs())
            })
    })
}

/// The smallest μ = tan φ at which the rows of `set` are feasible, by Brent on the margin
/// in φ ∈ [0, π/2], shifted by the reference margin `tau_ref` ≤ 0.
fn friction_search<G: ArchGeometry + ?Sized>(
    geom: &G,
    set: RowSet,
    tau_ref: f64,
    settings: &Settings,
) -> Critical {
    let failed = Cell::new(None);
    let psi = |phi: f64| {
        shifted_margin(
            &margin(geom, phi, set, settings),
            tau_ref,
            settings,
            &failed,
        )
    };
    let bracket = Bracket {
        lo: 0.0,
        hi: FRAC_PI_2,
        cap: f64::INFINITY,
        tol: settings.tol_friction_angle,
        grow_hi: false,
        max_span: settings.max_bracket,
    };
    let phi = match search(psi, &bracket, &failed) {
        Ok(p) => p,
        Err(c) => return c.into(),
    };
    let state = margin(geom, phi, set, settings);
    Critical::Found(LimitState {
        k: None,
        mu: phi.tan(),
        mechanism: state.mechanism_with(settings),
        state,
    })
}

/// The critical friction μ_c (paper §5): the smallest μ = tan φ at which the arch stands
/// (all rows feasible), by Brent on the margin in φ.
///
/// As in [`thickness`], the root is taken of τ_all(φ) − τ_ref + tol with
/// τ_ref = min(τ_rotational, 0), so that at K = K_c (τ_rotational ≈ 0⁻) the result is the
/// bifurcation friction rather than noise. Invariant: τ_all ≥ −2 `tol_margin` at the result.
pub fn friction<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> Critical {
    let rotational = margin(geom, FRAC_PI_2, RowSet::Rotational, settings);
    match reference(&rotational, settings) {
        Ok(r) => friction_search(geom, RowSet::All, r, settings),
        Err(c) => c.into(),
    }
}

/// μ_min: the smallest μ at which the sliding rows alone are feasible (H^s shrinks to a
/// point there, paper §2); below it no thickness lets the arch stand.
pub fn sliding_threshold<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> Critical {
    friction_search(geom, RowSet::Sliding, 0.0, settings)
}
