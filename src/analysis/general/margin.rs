//! The margin τ of a point over a set of rows, and the regime its three margins name.

use super::active::mechanism_of;
use super::half::{HalfArch, half_settings, mirrored};
use super::problem::Problem;
use super::rows::Objective;
use super::{ActiveRow, CrownState, Outcome, RowSet, Settings};
use crate::analysis::statics::ArchGeometry;
use crate::analysis::types::{Mechanism, Regime};

/// The margin of one point: the largest τ (see the module docs) and the state attaining it.
#[derive(Debug, Clone, PartialEq)]
pub struct MarginSolution {
    /// How the solve ended.
    pub outcome: Outcome,
    /// τ, a lower bound on the exact margin (the LP value less the residual violation of the
    /// continuum), in units of x; ≤ `margin_cap`.
    pub margin: f64,
    /// The state x attaining it.
    pub crown: CrownState,
    /// Largest distance by which a joint violates a row at (x, τ): ≤ 0 up to tolerance.
    pub max_violation: f64,
    /// Rows whose distance to x equals τ within `tol_active`.
    pub active: Vec<ActiveRow>,
    /// Rows in the final programme.
    pub rows: usize,
    /// Exchange steps (1 for a discrete arch).
    pub iterations: usize,
}

impl MarginSolution {
    /// True when the margin says the rows have a common solution (τ ≥ −`tol_margin`).
    pub fn feasible(&self, settings: &Settings) -> bool {
        self.outcome == Outcome::Solved && self.margin >= -settings.tol_margin
    }

    /// The mechanism named by the active rows, if any, with the default settings.
    pub fn mechanism(&self) -> Option<Mechanism> {
        self.mechanism_with(&Settings::DEFAULT)
    }

    /// True when the state is a limit state: |τ| within `tol_limit_state` of the scale of
    /// the crown unknowns (as the programme decides which active rows are necessary).
    pub fn is_limit(&self, settings: &Settings) -> bool {
        let c = &self.crown;
        let scale = 1.0
            + c.thrust_over_half_weight
                .abs()
                .max(c.shear_over_half_weight.abs())
                .max(c.moment_about_centre.abs());
        self.outcome == Outcome::Solved && self.margin.abs() <= settings.tol_limit_state * scale
    }

    /// The mechanism named by the active rows of a limit state; `None` for a state that is
    /// not one. A critical search whose margin jumps across zero (a thickness search in which
    /// a point load passes from the joint beyond a keystone's edge onto the keystone) ends
    /// at a state with a margin well away from zero: its active rows are those of the
    /// largest margin, not of a collapse, and name no mechanism.
    pub fn mechanism_with(&self, settings: &Settings) -> Option<Mechanism> {
        if !self.is_limit(settings) {
            return None;
        }
        mechanism_of(&self.active, settings)
    }
}

/// The margin of a geometry at friction angle φ (radians) over a set of rows, with λ fixed
/// at `settings.lambda`. A mirror-symmetric geometry is solved on its right half in the
/// symmetric unknowns when `settings.symmetric_half` ([`super::half`]): the same margin, the
/// active rows of both halves, zero crown shear.
///
/// Invariant: `margin ≥ −tol_margin` iff the rows of `set` admit a common solution (up to the
/// exchange tolerance for a continuum).
pub fn margin<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    set: RowSet,
    settings: &Settings,
) -> MarginSolution {
    if settings.symmetric_half && geom.mirror_symmetric() {
        let mut m = margin_on(&HalfArch(geom), phi, set, &half_settings(settings), true);
        m.active = mirrored(geom, m.active);
        m.crown.shear_over_half_weight = 0.0;
        return m;
    }
    margin_on(geom, phi, set, settings, false)
}

/// The margin of one problem: the whole arch, or a half (`half`) with zero crown shear.
fn margin_on<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    set: RowSet,
    settings: &Settings,
    half: bool,
) -> MarginSolution {
    let p = Problem {
        geom,
        phi,
        set,
        objective: Objective::Margin {
            lambda: settings.lambda,
            cap: settings.margin_cap,
        },
        half,
    };
    let s = p.solve(settings);
    // A lower bound on the exact margin: shift τ down by the residual violation.
    let tau = s.z[3] - s.max_violation.max(0.0);
    MarginSolution {
        outcome: s.outcome,
        margin: if s.outcome == Outcome::Solved {
            tau
        } else {
            f64::NEG_INFINITY
        },
        crown: CrownState::from_x(&s.z),
        max_violation: s.max_violation,
        active: s.active,
        rows: s.rows.a.len(),
        iterations: s.iterations,
    }
}

/// The regime of a point with its three margins (docs/mechanics.md §1 "Regimes").
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeReport {
    /// The regime; `None` when a margin could not be computed.
    pub regime: Option<Regime>,
    /// Margin of the rotational rows alone (H^r ≠ ∅ iff feasible).
    pub rotational: MarginSolution,
    /// Margin of the sliding rows alone (H^s ≠ ∅ iff feasible).
    pub sliding: MarginSolution,
    /// Margin of all rows (the arch stands iff feasible).
    pub all: MarginSolution,
}

/// The regime at friction angle φ (radians): stable when all rows are feasible, rotational
/// when only the sliding rows are, sliding when only the rotational rows are, mixed when both
/// are but not together, none when neither is.
pub fn regime<G: ArchGeometry + ?Sized>(geom: &G, phi: f64, settings: &Settings) -> RegimeReport {
    let rotational = margin(geom, phi, RowSet::Rotational, settings);
    let sliding = margin(geom, phi, RowSet::Sliding, settings);
    let all = margin(geom, phi, RowSet::All, settings);
    let solved = [&rotational, &sliding, &all]
        .iter()
        .all(|m| m.outcome == Outcome::Solved);
    let regime = solved.then(|| {
        match (
            rotational.feasible(settings),
            sliding.feasible(settings),
            all.feasible(settings),
        ) {
            (_, _, true) => Regime::Stable,
            (true, true, false) => Regime::Mixed,
            (false, true, false) => Regime::Rotational,
            (true, false, false) => Regime::Sliding,
            (false, false, false) => Regime::None,
        }
    });
    RegimeReport {
        regime,
        rotational,
        sliding,
        all,
    }
}
