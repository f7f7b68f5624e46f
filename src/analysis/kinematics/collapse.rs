//! The collapse mechanism of a critical state of the symmetric circular arch, with its work
//! equation (eqs. 9, 11), and the associative mechanism at the same state (paper §1: the
//! normality-based treatment of friction gets the mechanism wrong).
//!
//! The blocks are cut at the state's hinges and sliding joints. A symmetric state with five
//! active joints has two degrees of freedom (a symmetric and an antisymmetric mode); the
//! collapse mechanism is taken in the symmetric subspace, with its sign fixed by normality at
//! the hinges and by the state's sliding senses. At a bifurcation the admissible symmetric
//! fields form a cone with two extreme rays, one per coexisting mechanism: the one of the
//! state's kind is the collapse mechanism, the other is kept as an alternative.

use super::work::{LimitState, WorkEquation, work_equation};
use super::{
    FlowRule, KinematicsSettings, ModeStatus, VelocityField, Violation, mechanism_modes_with,
    pattern_of,
};
use crate::analysis::circular::CircularArch;
use crate::analysis::symmetric::CriticalState;
use crate::analysis::types::Sense;
use crate::model::Arch;

/// The mechanism of a critical state under one flow rule.
#[derive(Debug, Clone, PartialEq)]
pub struct CollapseMechanism {
    /// How the search for the mechanism ended.
    pub status: ModeStatus,
    /// Dimension of the null space of the compatibility system (`mechanism_dof`).
    pub mechanism_dof: u32,
    /// Dimension of its symmetric part (symmetric states).
    pub symmetric_dof: Option<u32>,
    /// The collapse mechanism (normalised: largest block-corner speed 1).
    pub field: Option<VelocityField>,
    /// The other admissible mechanisms at the state (a bifurcation has one).
    pub alternatives: Vec<VelocityField>,
    /// Breaches of normality or dissipation by `field` (empty when admissible).
    pub violations: Vec<Violation>,
    /// The work equation of `field` at the state.
    pub work: Option<WorkEquation>,
}

/// The arch at the state's thickness (the state's K when it has one, else the arch's).
fn arch_at(arch: &Arch, state: &CriticalState) -> Arch {
    if state.k.is_finite() && state.k > 1.0 {
        arch.with_k(state.k)
    } else {
        *arch
    }
}

/// The mechanism of `state` on `arch` (its K replaced by the state's) under `rule`.
pub fn mechanism_at(
    arch: &Arch,
    state: &CriticalState,
    rule: FlowRule,
    settings: &KinematicsSettings,
) -> CollapseMechanism {
    let geom = CircularArch::new(arch_at(arch, state));
    let joints = pattern_of(&state.mechanism);
    let Ok(modes) = mechanism_modes_with(&geom, &joints, rule, true, settings) else {
        return CollapseMechanism {
            status: ModeStatus::Failed,
            mechanism_dof: 0,
            symmetric_dof: None,
            field: None,
            alternatives: Vec::new(),
            violations: Vec::new(),
            work: None,
        };
    };
    let mut fields = modes.fields;
    let pick = fields
        .iter()
        .position(|f| f.kind() == Some(state.mechanism.kind))
        .unwrap_or(0);
    let field = (pick < fields.len()).then(|| fields.remove(pick));
    let limit = LimitState::symmetric(state);
    CollapseMechanism {
        status: modes.status,
        mechanism_dof: modes.dof,
        symmetric_dof: modes.symmetric_dof,
        violations: field.as_ref().map(|f| f.violations()).unwrap_or_default(),
        work: field.as_ref().map(|f| work_equation(&geom, &limit, f)),
        field,
        alternatives: fields,
    }
}

/// The collapse mechanism of a critical state (non-associative friction, the paper's).
pub fn collapse_mechanism(arch: &Arch, state: &CriticalState) -> CollapseMechanism {
    collapse_mechanism_with(arch, state, &KinematicsSettings::DEFAULT)
}

/// [`collapse_mechanism`] with the given settings.
pub fn collapse_mechanism_with(
    arch: &Arch,
    state: &CriticalState,
    settings: &KinematicsSettings,
) -> CollapseMechanism {
    mechanism_at(arch, state, FlowRule::NonAssociative, settings)
}

/// Slip and dilatancy at one sliding joint under both flow rules.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DilatancyRow {
    /// Joint angle, degrees.
    pub angle_deg: f64,
    /// Sense of sliding required by the state.
    pub sense: Sense,
    /// δr^t of the non-associative mechanism (normalised field).
    pub slip_non_associative: f64,
    /// Normal separation of the non-associative mechanism (zero: pure sliding).
    pub dilatancy_non_associative: f64,
    /// δr^t of the associative mechanism (normalised field).
    pub slip_associative: f64,
    /// Normal separation of the associative mechanism: tan φ |δr^t|.
    pub dilatancy_associative: f64,
}

/// The non-associative and the associative mechanisms at one state, side by side.
#[derive(Debug, Clone, PartialEq)]
pub struct FlowRuleComparison {
    /// Pure sliding (the paper).
    pub non_associative: CollapseMechanism,
    /// Sliding with dilatancy tan φ (normality to the Coulomb cone). Its `work` has
    /// dL^(a) ≈ 0: with dilatancy the friction dissipates nothing, so the associative upper
    /// bound sees the same state as a collapse state although its mechanism differs.
    pub associative: CollapseMechanism,
    /// One row per sliding joint of the state.
    pub rows: Vec<DilatancyRow>,
}

/// Both mechanisms at a critical state (the table of the report: per bifurcation point, the
/// thickness or friction, the mechanism and the dilatancy at its sliding joints).
pub fn compare_flow_rules(arch: &Arch, state: &CriticalState) -> FlowRuleComparison {
    compare_flow_rules_with(arch, state, &KinematicsSettings::DEFAULT)
}

/// [`compare_flow_rules`] with the given settings.
pub fn compare_flow_rules_with(
    arch: &Arch,
    state: &CriticalState,
    settings: &KinematicsSettings,
) -> FlowRuleComparison {
    let non_associative = collapse_mechanism_with(arch, state, settings);
    let associative = if state.mu.is_finite() {
        let rule = FlowRule::Associative { tan_phi: state.mu };
        mechanism_at(arch, state, rule, settings)
    } else {
        non_associative.clone()
    };
    let rows = state
        .mechanism
        .sliding_joints
        .iter()
        .map(|s| {
            let find = |m: &CollapseMechanism| {
                m.field
                    .as_ref()
                    .and_then(|f| {
                        f.joints
                            .iter()
                            .find(|j| (j.angle_deg() - s.angle_deg).abs() < settings.tol_match_deg)
                            .map(|j| (j.slip, j.dilatancy))
                    })
                    .unwrap_or((f64::NAN, f64::NAN))
            };
            let (sn, dn) = find(&non_associative);
            let (sa, da) = find(&associative);
            DilatancyRow {
                angle_deg: s.angle_deg,
                sense: s.sense,
                slip_non_associative: sn,
                dilatancy_non_associative: dn,
                slip_associative: sa,
                dilatancy_associative: da,
            }
        })
        .collect();
    FlowRuleComparison {
        non_associative,
        associative,
        rows,
    }
}
