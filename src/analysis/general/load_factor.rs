//! The collapse load factor λ_max of a proportional live load (static theorem).

use super::active::mechanism_of;
use super::problem::Problem;
use super::rows::Objective;
use super::{ActiveRow, CrownState, Outcome, RowSet, Settings};
use crate::analysis::statics::ArchGeometry;
use crate::analysis::types::Mechanism;

/// The largest load factor λ (multiples of the total weight) at friction angle φ (radians).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadFactor {
    /// Solved, infeasible (no λ), unbounded (every λ), not converged or failed.
    pub outcome: Outcome,
    /// λ_max: finite when solved, +∞ when unbounded, −∞ otherwise.
    pub lambda: f64,
    /// The crown state of the limit (the ray when unbounded).
    pub crown: CrownState,
    /// Active rows at the limit: the collapse mechanism.
    pub active: Vec<ActiveRow>,
    /// The mechanism named by the active rows.
    pub mechanism: Option<Mechanism>,
    /// Largest violation of a row at the solution (≤ 0 up to tolerance).
    pub max_violation: f64,
    /// Exchange steps (1 for a discrete arch).
    pub iterations: usize,
}

/// Maximises λ ≥ 0 subject to all rows (the static theorem for a proportional live load):
/// the collapse load factor of the live load of `geom` on top of its dead load. Infeasible
/// when no λ ≥ 0 admits a state, unbounded when every λ ≥ 0 does.
pub fn load_factor<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    settings: &Settings,
) -> LoadFactor {
    let p = Problem {
        geom,
        phi,
        set: RowSet::All,
        objective: Objective::LoadFactor,
        half: false,
    };
    let s = p.solve(settings);
    let lambda = match s.outcome {
        Outcome::Solved => s.z[3],
        Outcome::Unbounded => f64::INFINITY,
        _ => f64::NEG_INFINITY,
    };
    LoadFactor {
        outcome: s.outcome,
        lambda,
        crown: CrownState::from_x(&s.z),
        mechanism: mechanism_of(&s.active, settings),
        active: s.active,
        max_violation: s.max_violation,
        iterations: s.iterations,
    }
}

/// The joints of a continuum at which the state z = (F_x, F_y, M₀, λ) violates a row by more
/// than the exchange tolerance ([`Settings::tol_exchange`]), each with the largest such
/// violation (distance over |(a_x, a_y, a_M)|): the refined local maxima of every condition,
/// as one exchange step finds them. Empty when z is admissible everywhere.
pub fn violated_joints<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    z: &[f64; 4],
    settings: &Settings,
) -> Vec<(f64, f64)> {
    let p = Problem {
        geom,
        phi,
        set: RowSet::All,
        objective: Objective::LoadFactor,
        half: false,
    };
    let samples = p.samples(settings);
    let tol = settings.tol_exchange * Problem::<G>::scale(z);
    p.scan(&samples, z, false, settings)
        .into_iter()
        .filter(|c| c.violation > tol)
        .map(|c| (c.theta, c.violation))
        .collect()
}
