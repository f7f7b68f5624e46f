//! Regime boundaries and bifurcation points of a study, located to a tolerance.
//!
//! A grid only brackets where the behaviour of the arch changes; this module locates the
//! crossings. For a `state` study every grid edge (along K at fixed μ, along μ at fixed K,
//! per load case and per value of the other axes) across which the regime differs is
//! refined by bracketing root-finding (Brent) on the continuous quantity that changes sign
//! there (docs/mechanics.md §1):
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
//! A `state` study of self-weight on another form (pointed arches, vertical joints) has the
//! same three indicators on the margins of the general route, with H^s depending on K as
//! well (`lines`).
//! `thickness` and `friction` studies trace one collapse curve each: their mechanism
//! changes along the swept parameter are located by bisection and reported as
//! bifurcations; their boundary table is empty (the critical points are the rows of
//! results.parquet). `thrust` studies have neither.

mod bifurcation;
mod cells;
mod general;
mod grid;
mod lines;
mod probe;
mod state_grid;
mod sweep;

pub use crate::records::{Bifurcation, BoundaryPoint, EdgeAxis, Located};
pub use cells::{NO_CELL, cell_code, state_cell_code};

use crate::engine::CaseResult;
use crate::manifest::Manifest;
use crate::model::Load;
use crate::plan::Plan;
use crate::progress::{Progress, Silent};
use crate::scene::Find;
use std::sync::atomic::{AtomicU64, Ordering};

/// Counts analyses, shared by parallel tasks, and reports each to the run's progress.
pub(crate) struct Counter<'p> {
    n: AtomicU64,
    progress: &'p dyn Progress,
}

impl Default for Counter<'static> {
    fn default() -> Self {
        Counter::new(&Silent)
    }
}

impl<'p> Counter<'p> {
    /// A counter at zero that advances `progress` by one per analysis.
    pub(crate) fn new(progress: &'p dyn Progress) -> Self {
        Counter {
            n: AtomicU64::new(0),
            progress,
        }
    }

    /// Adds one analysis.
    pub(crate) fn tick(&self) {
        self.n.fetch_add(1, Ordering::Relaxed);
        self.progress.advance(1);
    }

    /// The count so far.
    pub(crate) fn get(&self) -> u64 {
        self.n.load(Ordering::Relaxed)
    }
}

/// Locates the regime boundaries and bifurcations of a run, to the manifest's
/// `boundary_tolerance` in K and μ. `results` are the engine's rows in plan order.
pub fn locate(plan: &Plan, results: &[CaseResult]) -> Located {
    locate_with(plan, results, &Silent)
}

/// [`locate`], advancing `progress` by one per refinement analysis (the caller begins and
/// ends the [`Stage::Boundaries`](crate::progress::Stage::Boundaries) stage).
pub fn locate_with(plan: &Plan, results: &[CaseResult], progress: &dyn Progress) -> Located {
    let total = usize::try_from(crate::plan::case_count(&plan.manifest)).unwrap_or(usize::MAX);
    let mut codes = vec![NO_CELL; total];
    for (case, r) in plan.cases.iter().zip(results) {
        if r.case_id == case.id
            && let Some(slot) = usize::try_from(case.id).ok().and_then(|n| codes.get_mut(n))
        {
            *slot = cell_code(r);
        }
    }
    locate_codes(&plan.manifest, &codes, progress)
}

/// Locates the regime boundaries and bifurcations of a manifest's plan from the
/// [cell code](cell_code) of every case (`codes[n]` of case n): the plan is read a chunk at a
/// time and only the cells of each grid are held, one byte a case.
pub fn locate_codes(manifest: &Manifest, codes: &[u8], progress: &dyn Progress) -> Located {
    if manifest.sampling.is_some() {
        // Samples are scattered, not a lattice: the collapse curve of a sampling study is
        // computed along μ by the figure data, and nothing is located between samples.
        return Located::default();
    }
    let counter = Counter::new(progress);
    let tol = manifest.boundary_tolerance;
    let groups = grid::groups(manifest, codes);
    let mut boundaries = Vec::new();
    let mut bifurcations = Vec::new();
    for g in &groups {
        let one = std::slice::from_ref(g);
        let symmetric_state = g.scene.find == Find::State && g.scene.load == Load::SelfWeight;
        let (b, f) = if !g.scene.uses_closed_forms() && symmetric_state {
            lines::locate(g, tol, &counter)
        } else if !g.scene.uses_closed_forms() {
            general::locate(g, tol, &counter)
        } else {
            match g.scene.find {
                Find::State => state_grid::locate(one, tol, &counter),
                Find::Thickness => (
                    Vec::new(),
                    sweep::locate(one, sweep::Swept::Mu, tol, &counter),
                ),
                Find::Friction => (
                    Vec::new(),
                    sweep::locate(one, sweep::Swept::K, tol, &counter),
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
