//! Kinematics of rigid-block mechanisms (paper §3): the blocks between the active joints,
//! the compatibility system of their virtual velocities and its null space.
//!
//! Conventions (docs/mechanics.md §1, statics.rs): origin at the centre, x right, y up, lengths over
//! r. The active joints θ₁ < … < θ_n cut the arch into n + 1 parts; the first and the last
//! part are held by the supports (they are empty when the joint is a springing), the n − 1
//! parts between are free rigid blocks with virtual velocity (u_x, u_y, ω) (u the velocity of
//! the block's reference point, ω counter-clockwise). At joint θ with intrados I, extrados E,
//! unit vector τ along the joint (I → E) and normal ν from the left part into the right part,
//! the relative velocity is v_rel = v_right − v_left and
//! - the relative rotation is δα = ω_left − ω_right, positive when the joint opens at the
//!   extrados about a hinge at the intrados (the paper's sign, §3.1);
//! - the opening is δr_G^n = v_rel(G)·ν at the joint centre G (eq. 5: |δα| ≤ (2/h) δr_G^n);
//! - the slip δr^t is the tangential displacement of the crown-side part relative to the
//!   springing-side part, along τ (positive: [`Sense::Outward`]); the crown side is the left
//!   part for θ ≥ 0 and the right part for θ < 0.
//!
//! Constraints (one linear row each): a hinge at a face point P has v_rel(P) = 0 (eq. 5 as an
//! equality); a sliding joint has δα = 0 and v_rel·ν = 0 (pure sliding, no dilatancy) or,
//! under the associative rule, v_rel·ν = tan φ |v_rel·τ|; a La Hire joint (hinge and sliding)
//! keeps only the normal row at its hinge point. The mechanism degrees of freedom are the
//! dimension of the null space, computed by SVD with the rank tolerance
//! [`KinematicsSettings::tol_rank`].

pub use super::settings::KinematicsSettings;
use super::statics::{ArchGeometry, Point};
use super::types::{Face, Mechanism, Sense};

pub mod collapse;
mod compatibility;
pub mod families;
mod field;
pub mod modes;
pub mod outline;
pub mod work;

#[cfg(test)]
mod tests;

pub use collapse::{
    CollapseMechanism, DilatancyRow, FlowRuleComparison, collapse_mechanism,
    collapse_mechanism_with, compare_flow_rules, compare_flow_rules_with, mechanism_at,
};
pub use compatibility::Compatibility;
pub use families::{
    Family, FamilyTemplate, REPRESENTATIVE, families, families_with, family, family_with,
};
pub use field::{JointMotion, Part, RigidVelocity, VelocityField, Violation};
pub use modes::{ModeStatus, Modes, mechanism_modes, mechanism_modes_with, null_space};
pub use outline::{MechanismDrawing, drawing, drawing_with};
pub use work::{JointForce, LimitState, WorkEquation, joint_force, work_equation};

/// The default relative rank tolerance of the compatibility system
/// ([`KinematicsSettings::tol_rank`]).
pub const RANK_TOL: f64 = KinematicsSettings::DEFAULT.tol_rank;
/// The default threshold below which a relative rotation or slip counts as zero
/// ([`KinematicsSettings::tol_motion`]).
pub const MOTION_TOL: f64 = KinematicsSettings::DEFAULT.tol_motion;

/// Why a pattern of joints cannot be analysed (bad input, not an outcome).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KinematicsError {
    /// A joint angle is NaN or infinite.
    #[error("joint angle {0}° is not a finite number")]
    NotFinite(f64),
    /// A joint lies outside [−α, α].
    #[error("joint at {angle_deg}° lies outside the arch, whose springings are at ±{alpha_deg}°")]
    Outside {
        /// The joint angle, degrees.
        angle_deg: f64,
        /// The half-embrace angle α, degrees.
        alpha_deg: f64,
    },
    /// Two hinges on opposite faces at the same joint.
    #[error("joint at {0}° has hinges on both faces")]
    BothFaces(f64),
}

/// An active joint of a mechanism: a hinge, a sliding joint or both (La Hire).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActiveJoint {
    /// Joint parameter θ in radians (the angle from the crown for radial joints).
    pub theta: f64,
    /// Face of the hinge when the joint rotates (eq. 5 as an equality).
    pub hinge: Option<Face>,
    /// True when the joint slides.
    pub slides: bool,
    /// Sense in which the crown-side part must slide (from the friction force of a limit
    /// state, principle of maximum dissipation); `None` leaves it free.
    pub sense: Option<Sense>,
}

impl ActiveJoint {
    /// A hinge at θ (radians) on a face.
    pub fn hinge(theta: f64, face: Face) -> Self {
        ActiveJoint {
            theta,
            hinge: Some(face),
            slides: false,
            sense: None,
        }
    }

    /// A sliding joint at θ (radians) with an optional required sense.
    pub fn sliding(theta: f64, sense: Option<Sense>) -> Self {
        ActiveJoint {
            theta,
            hinge: None,
            slides: true,
            sense,
        }
    }

    /// A La Hire joint at θ (radians): a hinge on `face` that also slides.
    pub fn la_hire(theta: f64, face: Face, sense: Option<Sense>) -> Self {
        ActiveJoint {
            theta,
            hinge: Some(face),
            slides: true,
            sense,
        }
    }

    /// The joint angle in degrees.
    pub fn angle_deg(&self) -> f64 {
        crate::analysis::statics::joint_angle_deg(self.theta)
    }

    /// +1 when the crown-side part is the left part (θ ≥ 0), −1 otherwise.
    fn crown_side(&self) -> f64 {
        if self.theta >= 0.0 { 1.0 } else { -1.0 }
    }
}

/// The active joints of a limit state's pattern, in increasing angle, each sliding joint with
/// the state's sense; a hinge and a sliding joint at the same angle are merged into one La Hire
/// joint by [`normalise_pattern`].
pub fn pattern_of(m: &Mechanism) -> Vec<ActiveJoint> {
    let mut joints: Vec<ActiveJoint> = m
        .hinges
        .iter()
        .map(|h| ActiveJoint::hinge(h.angle_deg.to_radians(), h.face))
        .collect();
    for s in &m.sliding_joints {
        joints.push(ActiveJoint::sliding(
            s.angle_deg.to_radians(),
            Some(s.sense),
        ));
    }
    joints.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    joints
}

/// Checks a pattern against the arch: finite, inside [−α, α] (joints within
/// `tol_springing_deg` of a springing are put on it, except the support parameters ±α⁺ of
/// forms with vertical joints), sorted, coincident joints (within
/// `tol_same_joint`) and joints that are one segment ([`same_segment`]) merged (a hinge and a
/// slide become La Hire).
pub fn normalise_pattern<G: ArchGeometry + ?Sized>(
    geom: &G,
    joints: &[ActiveJoint],
    settings: &KinematicsSettings,
) -> Result<Vec<ActiveJoint>, KinematicsError> {
    let alpha = geom.half_angle();
    let mut out: Vec<ActiveJoint> = Vec::with_capacity(joints.len());
    for j in joints {
        if !j.theta.is_finite() {
            return Err(KinematicsError::NotFinite(j.theta.to_degrees()));
        }
        if j.theta.abs() > alpha + settings.tol_springing_deg.to_radians() {
            return Err(KinematicsError::Outside {
                angle_deg: j.angle_deg(),
                alpha_deg: alpha.to_degrees(),
            });
        }
        let mut j = *j;
        // The float just beyond α is a support joint of its own on forms whose joints are
        // not radial (vertical joints end at radial supports, `forms/`): it stays.
        let edge = alpha.next_up();
        if j.theta.abs() != edge {
            j.theta = j.theta.clamp(-alpha, alpha);
        }
        out.push(j);
    }
    out.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    let mut merged: Vec<ActiveJoint> = Vec::with_capacity(out.len());
    for j in out {
        match merged.last_mut() {
            // Two sliding joints on the two sides of a point load stay apart: the sliver
            // between them carries the load and slides on its own (a load at the crown
            // punching down between the halves).
            Some(last)
                if same_segment(geom, last.theta, j.theta, settings)
                    && !(last.slides && j.slides && last.theta != j.theta) =>
            {
                match (last.hinge, j.hinge) {
                    (Some(a), Some(b)) if a != b => {
                        return Err(KinematicsError::BothFaces(j.angle_deg()));
                    }
                    (None, h) => last.hinge = h,
                    _ => {}
                }
                // A hinge and a sliding joint on the two sides of a point load act as one
                // La Hire joint whose sliding side decides where the load goes: the load sits
                // at the hinge point, so it moves with the hinged block, and the friction force
                // is that of the joint that slides. The merged joint takes the sliding joint's
                // parameter.
                if j.slides && !last.slides {
                    last.theta = j.theta;
                }
                last.slides |= j.slides;
                last.sense = last.sense.or(j.sense);
            }
            _ => merged.push(j),
        }
    }
    Ok(merged)
}

/// True when the joints at parameters `a` and `b` are one segment (both ends within
/// `tol_same_joint`): the two sides of a point load are, and so are the vertical joints at ±ψ₁
/// of a pointed arch (both the crown joint); a vertical joint at α and the radial support just
/// beyond it are not (a wedge lies between them).
fn same_segment<G: ArchGeometry + ?Sized>(
    geom: &G,
    a: f64,
    b: f64,
    settings: &KinematicsSettings,
) -> bool {
    let (p, q) = (geom.joint(a), geom.joint(b));
    let d = |u: Point, v: Point| (u[0] - v[0]).hypot(u[1] - v[1]);
    d(p.intrados, q.intrados) <= settings.tol_same_joint
        && d(p.extrados, q.extrados) <= settings.tol_same_joint
}

/// The flow rule at sliding joints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FlowRule {
    /// Pure sliding, no dilatancy (the paper's non-associative Coulomb friction).
    NonAssociative,
    /// Normality to the Coulomb cone: relative normal separation tan φ · |slip|. The sign of
    /// the slip that |slip| stands for is the joint's required sense (outward when it has
    /// none), which keeps the system linear.
    Associative {
        /// μ = tan φ.
        tan_phi: f64,
    },
}

/// +1 for the intrados (δα ≥ 0 there), −1 for the extrados.
fn face_sign(face: Face) -> f64 {
    match face {
        Face::Intrados => 1.0,
        Face::Extrados => -1.0,
    }
}

/// +1 outward, −1 inward.
fn sense_sign(sense: Sense) -> f64 {
    match sense {
        Sense::Outward => 1.0,
        Sense::Inward => -1.0,
    }
}

fn sub(a: Point, b: Point) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// a × b (z component).
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
