//! Typed rows of the tables a run writes beside results.parquet: the located regime boundary
//! points and bifurcations. The boundaries stage produces them and the store writes them, so
//! they sit below both.

use crate::analysis::symmetric::CriticalState;
use crate::analysis::{MechanismKind, Regime};
use crate::model::t_over_r_from_k;

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
    /// Outline and joint planes of the arch (they vary along `eccentricity` and `joints`
    /// axes).
    pub form: crate::model::ArchForm,
    /// Position of the point load of the group, degrees from the crown (`None` for other
    /// loads, and for a position given as x/L, whose angle depends on K).
    pub at_deg: Option<f64>,
    /// Position of the point load of the group given as x/L (`None` otherwise).
    pub at_x: Option<f64>,
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
    /// Outline and joint planes of the arch (they vary along `eccentricity` and `joints`
    /// axes).
    pub form: crate::model::ArchForm,
    /// Position of the point load of the group, degrees from the crown (`None` for other
    /// loads, and for a position given as x/L, whose angle depends on K).
    pub at_deg: Option<f64>,
    /// Position of the point load of the group given as x/L (`None` otherwise).
    pub at_x: Option<f64>,
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
