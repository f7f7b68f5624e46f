//! The collapse mechanisms at each bifurcation of a run (paper §§3–4): both coexisting
//! mechanisms under the paper's non-associative rule and the associative ones at the same
//! state, with their work equation, their slip and dilatancy at the sliding joints and their
//! drawing, for mechanisms.parquet.

use crate::analysis::circular::CircularArch;
use crate::analysis::kinematics::{
    CollapseMechanism, FlowRule, LimitState, VelocityField, WorkEquation, compare_flow_rules,
    drawing, work_equation,
};
use crate::analysis::symmetric::CriticalState;
use crate::analysis::{Face, Hinge, Mechanism, MechanismKind, Sense, SlidingJoint};
use crate::model::Arch;
use crate::store::{BifurcationRow, MechanismRow};

/// Largest block-corner displacement of a drawing, over r: large enough to see, small
/// enough that the blocks still meet at their hinges.
pub const DRAWING_AMPLITUDE: f64 = 0.08;

/// The limit state of a stored bifurcation (`None` when its joints cannot be read back).
fn critical_state(b: &BifurcationRow) -> Option<CriticalState> {
    let j = &b.joints;
    let hinges = j
        .hinge_angles_deg
        .iter()
        .zip(&j.hinge_faces)
        .map(|(&angle_deg, f)| {
            Some(Hinge {
                angle_deg,
                face: Face::parse(f)?,
            })
        })
        .collect::<Option<Vec<_>>>()?;
    let sliding_joints = j
        .sliding_angles_deg
        .iter()
        .zip(&j.sliding_senses)
        .map(|(&angle_deg, s)| {
            Some(SlidingJoint {
                angle_deg,
                sense: Sense::parse(s)?,
            })
        })
        .collect::<Option<Vec<_>>>()?;
    let kind = MechanismKind::from_counts(hinges.len(), sliding_joints.len())?;
    Some(CriticalState {
        k: b.k,
        mu: b.mu,
        thrust_over_half_weight: b.thrust_over_half_weight?,
        crown_moment: b.crown_moment?,
        mechanism: Mechanism {
            kind,
            hinges,
            sliding_joints,
        },
    })
}

/// The work residual stored for a mechanism under `rule`: eq. (11)'s under the paper's
/// rule; under the associative rule the dilatancy makes the normal reactions work
/// (dL^(r,n) = μ R^n |dr^t|), so the check is the whole virtual-work balance, over the
/// largest of its terms.
pub fn work_residual(rule: FlowRule, w: &WorkEquation) -> f64 {
    match rule {
        FlowRule::NonAssociative => w.work_residual,
        FlowRule::Associative { .. } => {
            let scale = w
                .work_loads
                .abs()
                .max(w.work_normal.abs())
                .max(w.work_tangential.abs())
                .max(w.load_scale);
            (w.work_loads + w.work_normal + w.work_tangential).abs() / scale.max(f64::MIN_POSITIVE)
        }
    }
}

/// The name of a flow rule in mechanisms.parquet.
pub fn rule_name(rule: FlowRule) -> &'static str {
    match rule {
        FlowRule::NonAssociative => "non_associative",
        FlowRule::Associative { .. } => "associative",
    }
}

/// The rows of one bifurcation: every admissible mechanism under each flow rule, the
/// state's own kind first. Empty when the state cannot be rebuilt.
pub fn bifurcation_mechanisms(
    arch: &Arch,
    b: &BifurcationRow,
    state_id: &str,
    index: u32,
) -> Vec<MechanismRow> {
    let Some(state) = critical_state(b) else {
        return Vec::new();
    };
    let geom = CircularArch::new(arch.with_k(b.k));
    let limit = LimitState::symmetric(&state);
    let cmp = compare_flow_rules(arch, &state);
    let row = |m: &CollapseMechanism, f: &VelocityField| {
        let w = work_equation(&geom, &limit, f);
        let residual = work_residual(f.rule, &w);
        let slides: Vec<_> = f.joints.iter().filter(|j| j.slips()).collect();
        MechanismRow {
            state_id: state_id.to_string(),
            load_case: b.load_case.clone(),
            bifurcation: index,
            k: b.k,
            mu: b.mu,
            mechanism: f.kind().map_or("none", |k| k.as_str()).to_string(),
            flow_rule: rule_name(f.rule).to_string(),
            work_loads: w.work_loads,
            work_normal: w.work_normal,
            work_friction: w.work_friction,
            work_residual: residual,
            dof: m.mechanism_dof,
            sliding_angles_deg: slides.iter().map(|j| j.angle_deg()).collect(),
            slip: slides.iter().map(|j| j.slip).collect(),
            dilatancy: slides.iter().map(|j| j.dilatancy).collect(),
            drawing_json: serde_json::to_string(&drawing(&geom, f, DRAWING_AMPLITUDE))
                .unwrap_or_default(),
        }
    };
    let mut out = Vec::new();
    let same = !b.mu.is_finite();
    let mechanisms = if same {
        vec![&cmp.non_associative]
    } else {
        vec![&cmp.non_associative, &cmp.associative]
    };
    for m in mechanisms {
        for f in m.field.iter().chain(&m.alternatives) {
            out.push(row(m, f));
        }
    }
    out
}
