//! Regime boundaries and bifurcation points of a study, located to a tolerance.
//!
//! A grid only brackets where the behaviour of the arch changes; this module locates the
//! crossings. For a `state` study every grid edge (along K at fixed μ, along μ at fixed K,
//! per load case and per value of the other axes) across which the regime differs is
//! refined by bracketing root-finding (Brent) on the continuous quantity that changes sign
//! there (DESIGN.md §1):
//! - H^r emptiness, the peak margin max_h Φ(h) of the rotational domain: depends on K only,
//!   so it is crossed by K-edges only and located once per K-edge;
//! - H^s emptiness, the width of the sliding domain: depends on μ only, crossed by μ-edges
//!   only and located once per μ-edge;
//! - stability (H^r ∩ H^s ≠ ∅), the signed overlap of both domains: a K-edge varies H^r
//!   with H^s fixed, a μ-edge varies H^s with H^r fixed.
//!
//! An edge whose ends lie in regimes that are not adjacent (rotational → stable with a thin
//! mixed band inside the cell) yields one point per crossing. Points on the boundary of the
//! stable region (the collapse curve) carry the collapse state of the one-parameter problem
//! through them: K_c(μ) ([`thickness`](crate::analysis::symmetric::thickness)) for a
//! K-edge, μ_c(K) ([`friction`](crate::analysis::symmetric::friction)) for a μ-edge. Points
//! between two unstable regimes carry the state of the domain that empties: the rotational
//! limit state (K_c at infinite friction) where H^r shrinks to a point, the sliding
//! threshold state (μ_min) where H^s does.
//!
//! Bifurcations are where the mechanism along the collapse curve changes (paper §5,
//! Figs. 6, 7): the rotational/mixed one is μ_c at the rotational K_c, the mixed/sliding one
//! K_c at μ_min; which exist is read from the mechanism changes between consecutive located
//! collapse points, and each is confirmed by a bracketing search between them.
//! `thickness` and `friction` studies trace one collapse curve each: their mechanism
//! changes along the swept parameter are located by bisection and reported as
//! bifurcations; their boundary table is empty (the critical points are the rows of
//! results.parquet). `thrust` studies have neither.

mod bifurcation;
mod general;
mod grid;
mod probe;
mod state_grid;
mod sweep;

use crate::analysis::symmetric::CriticalState;
use crate::analysis::{MechanismKind, Regime};
use crate::engine::CaseResult;
use crate::model::t_over_r_from_k;
use crate::plan::Plan;
use crate::scene::Find;
use std::sync::atomic::{AtomicU64, Ordering};

/// The axis along which a crossed grid edge runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EdgeAxis {
    /// An edge between two K values at fixed μ.
    K,
    /// An edge between two μ values at fixed K.
    Mu,
}

impl EdgeAxis {
    /// `k` or `mu`.
    pub fn as_str(self) -> &'static str {
        match self {
            EdgeAxis::K => "k",
            EdgeAxis::Mu => "mu",
        }
    }
}

/// A located crossing of a regime boundary by a grid edge.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryPoint {
    /// Index of the load case in the manifest.
    pub load_case: usize,
    /// Half-embrace angle α of the arch, degrees.
    pub half_angle_deg: f64,
    /// Voussoir count, `None` for the continuum.
    pub voussoirs: Option<u32>,
    /// Position of the point load of the group, degrees from the crown (`None` for other
    /// loads).
    pub at_deg: Option<f64>,
    /// K = R/r at the point (located to the tolerance on a K-edge, a grid value otherwise).
    pub k: f64,
    /// μ at the point (located on a μ-edge, a grid value, possibly infinite, otherwise).
    pub mu: f64,
    /// The axis along which the crossed edge runs.
    pub axis: EdgeAxis,
    /// Regime on the lower-value side of the crossing (lower K or lower μ).
    pub regime_low: Regime,
    /// Regime on the higher-value side of the crossing.
    pub regime_high: Regime,
    /// True when one side is stable: the point lies on the collapse curve.
    pub on_collapse_curve: bool,
    /// The collapse mechanism (points on the collapse curve only).
    pub mechanism: Option<MechanismKind>,
    /// The limit state that characterises the point (thrust over W_half, crown moment over
    /// W_half·r, hinges, sliding joints): the collapse state on the collapse curve, the state
    /// of the emptying domain elsewhere; `None` when no consistent state was found.
    pub state: Option<CriticalState>,
}

impl BoundaryPoint {
    /// t/R_c = 2(K − 1)/(K + 1) at the point.
    pub fn t_over_r(&self) -> f64 {
        t_over_r_from_k(self.k)
    }
}

/// A bifurcation point of the collapse curve: two collapse mechanisms coexist.
#[derive(Debug, Clone, PartialEq)]
pub struct Bifurcation {
    /// Index of the load case in the manifest.
    pub load_case: usize,
    /// Half-embrace angle α of the arch, degrees.
    pub half_angle_deg: f64,
    /// Voussoir count, `None` for the continuum.
    pub voussoirs: Option<u32>,
    /// Position of the point load of the group, degrees from the crown (`None` for other
    /// loads).
    pub at_deg: Option<f64>,
    /// For a change of mechanism located on a grid edge (studies on the general route): the
    /// axis of that edge; `None` for the bifurcations of the symmetric collapse curve.
    pub axis: Option<EdgeAxis>,
    /// The collapse load factor λ there (`load_factor` studies), multiples of the total
    /// weight.
    pub load_factor: Option<f64>,
    /// K = R/r at the bifurcation.
    pub k: f64,
    /// μ at the bifurcation.
    pub mu: f64,
    /// The mechanism on the lower-μ side (toward thicker arches along the collapse curve); on
    /// a grid edge (`axis` set), on the lower-value side of the edge.
    pub mechanism_a: MechanismKind,
    /// The mechanism on the higher-μ side (toward thinner arches); on a grid edge, on the
    /// higher-value side.
    pub mechanism_b: MechanismKind,
    /// The coexisting limit state: thrust over W_half, crown moment over W_half·r and every
    /// joint active at the bifurcation (the union of both mechanisms' joints).
    pub state: CriticalState,
}

impl Bifurcation {
    /// t/R_c = 2(K − 1)/(K + 1) at the bifurcation.
    pub fn t_over_r(&self) -> f64 {
        t_over_r_from_k(self.k)
    }
}

/// Everything located after a grid: boundary points, bifurcations and their cost.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Located {
    /// Boundary points, by load case and arch group, K-edges (by μ, then K) before μ-edges
    /// (by K, then μ).
    pub boundaries: Vec<BoundaryPoint>,
    /// Bifurcation points, by load case and arch group, then by increasing K.
    pub bifurcations: Vec<Bifurcation>,
    /// Analyses spent beyond the grid: every domain solve, margin evaluation and critical
    /// value computed while refining.
    pub refinement_analyses: u64,
}

/// Counts analyses; shared by parallel tasks.
#[derive(Debug, Default)]
pub(crate) struct Counter(AtomicU64);

impl Counter {
    /// Adds one analysis.
    pub(crate) fn tick(&self) {
        self.0.fetch_add(1, Ordering::Relaxed);
    }

    /// The count so far.
    pub(crate) fn get(&self) -> u64 {
        self.0.load(Ordering::Relaxed)
    }
}

/// Locates the regime boundaries and bifurcations of a run, to the manifest's
/// `boundary_tolerance` in K and μ. `results` are the engine's rows in plan order.
pub fn locate(plan: &Plan, results: &[CaseResult]) -> Located {
    let counter = Counter::default();
    let tol = plan.manifest.boundary_tolerance;
    let groups = grid::groups(plan, results);
    let mut boundaries = Vec::new();
    let mut bifurcations = Vec::new();
    for g in &groups {
        let one = std::slice::from_ref(g);
        let (b, f) = if !g.scene.uses_closed_forms() {
            general::locate(g, results, tol, &counter)
        } else {
            match g.scene.find {
                Find::State => state_grid::locate(one, results, tol, &counter),
                Find::Thickness => (
                    Vec::new(),
                    sweep::locate(one, results, sweep::Swept::Mu, tol, &counter),
                ),
                Find::Friction => (
                    Vec::new(),
                    sweep::locate(one, results, sweep::Swept::K, tol, &counter),
                ),
                // Thresholds are the bifurcations themselves, one set per row.
                Find::Thrust | Find::Thresholds | Find::LoadFactor => (Vec::new(), Vec::new()),
            }
        };
        boundaries.extend(b);
        bifurcations.extend(f);
    }
    Located {
        boundaries,
        bifurcations,
        refinement_analyses: counter.get(),
    }
}

#[cfg(test)]
mod tests;
