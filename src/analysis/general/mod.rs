//! The general statics of an arch in three redundant unknowns, with no symmetry assumed:
//! x = (F_x, F_y, M₀), the force and moment the left part exerts on the right part at the
//! crown (over W_half and W_half·r), and optionally the load factor λ (docs/mechanics.md §1).
//!
//! Every joint θ gives four rows a·x + a_λ λ ≤ b ([`joint_rows`](super::statics::joint_rows),
//! paper eqs. 1 and 3). The arch can stand iff the rows of all joints have a common
//! solution. Feasibility is measured by a continuous margin, the largest τ with
//!
//! a_i·x + τ |a_i| ≤ b_i − a_λ,i λ  for every row i,  τ ≤ τ_cap,
//!
//! (τ is the distance of x to the nearest row plane in (F_x, F_y, M₀) space, negative when
//! no x satisfies all rows); its sign says whether the arch stands, its zero is the collapse
//! condition, and the rows that attain it there name the mechanism.
//!
//! Discrete arches give one linear programme ([`lp`]). For the continuum the joints form a
//! semi-infinite family, solved by an exchange (cutting-plane) method: solve with a few
//! joints, find the most violated joint of each condition over [−α, α] by sampling and a
//! 1-D maximisation, add it, repeat until no joint is violated by more than a relative
//! tolerance. The rows of the sampled joints are built once and re-priced at every step;
//! only the local maxima that may come near a violation are refined, by Brent's method
//! started from the samples around them; after the first step each programme is solved on
//! a working set of its rows (the previous basis and the new cuts), which gives the same
//! optimum as all of them. Critical values are roots of the margin in K or φ (Brent), as in
//! [`super::symmetric`], which this module reproduces by an independent route.
//!
//! An arch whose form and loads are mirror images about the crown (any shape, joints, weight
//! model or voussoir count under self-weight) has its margins solved on the right half in
//! the symmetric unknowns (F_x, M₀), the crown shear held at zero (`half`): the same margin
//! from half the joints, the active rows mirrored onto the left half.

mod active;
mod critical;
mod exchange;
mod half;
mod load_factor;
mod margin;
mod problem;
mod refine;
mod rows;
mod samples;
#[cfg(test)]
mod tests;
mod working_set;

pub use active::{mechanism_of, pattern_of_rows};
pub use critical::{
    Critical, LimitState, friction, sliding_threshold, thickness, thickness_windows, thickness_with,
};
pub use load_factor::{LoadFactor, load_factor, violated_joints};
pub use margin::{MarginSolution, RegimeReport, margin, regime};
pub use rows::{JointRow, LinearRows, OBJECTIVE};

use super::lp;
use super::statics::Condition;

/// Which conditions enter a problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RowSet {
    /// The no-tension rows of eq. (1) only (intrados and extrados): the domain H^r.
    Rotational,
    /// The Coulomb rows of eq. (3) only: the domain H^s.
    Sliding,
    /// All four rows at every joint.
    All,
}

impl RowSet {
    /// True when rows of `condition` belong to the set.
    pub fn includes(self, condition: Condition) -> bool {
        match self {
            RowSet::Rotational => condition.is_rotational(),
            RowSet::Sliding => !condition.is_rotational(),
            RowSet::All => true,
        }
    }
}

pub use crate::analysis::settings::GeneralSettings as Settings;

/// How a general solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// Solved: every joint satisfies the rows within tolerance.
    Solved,
    /// No admissible state (for the load factor: no λ lets the arch stand).
    Infeasible,
    /// The objective is unbounded (for the load factor: the arch stands for every λ ≥ 0).
    Unbounded,
    /// The exchange hit its iteration cap (or stalled) before the violation fell below
    /// tolerance.
    NotConverged,
    /// The linear programme solver failed.
    Failed(lp::Status),
}

/// A row that holds with equality at a solution (within `tol_active`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActiveRow {
    /// Joint angle from the crown, degrees, positive to the right.
    pub angle_deg: f64,
    /// The joint parameter θ in radians, exactly as the statics used it: the two sides of a
    /// point load are distinct parameters one float apart (`forms/`), which degrees lose.
    pub theta: f64,
    /// The condition at the limit there.
    pub condition: Condition,
    /// Distance of x to the row plane minus the margin (≥ 0, ≤ `tol_active`·scale).
    pub slack: f64,
}

/// The crown force and moment of a state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CrownState {
    /// F_x / W_half: the horizontal thrust at the crown.
    pub thrust_over_half_weight: f64,
    /// F_y / W_half: the vertical shear at the crown (zero under symmetric loading).
    pub shear_over_half_weight: f64,
    /// M₀ / (W_half·r): moment about the centre of the circle (−h·y_P for a thrust at height
    /// y_P).
    pub moment_about_centre: f64,
}

impl CrownState {
    pub(super) fn from_x(x: &[f64; 4]) -> Self {
        CrownState {
            thrust_over_half_weight: x[0],
            shear_over_half_weight: x[1],
            moment_about_centre: x[2],
        }
    }
}
