//! Kinematics of rigid-block mechanisms (paper §3): the blocks between the active joints,
//! the compatibility system of their virtual velocities and its null space.
//!
//! Conventions (DESIGN.md §1, statics.rs): origin at the centre, x right, y up, lengths over
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
//! dimension of the null space, computed by SVD with the rank tolerance [`RANK_TOL`].

use super::statics::{ArchGeometry, Point};
use super::types::{Face, Mechanism, MechanismKind, Sense};
use nalgebra::DMatrix;

pub mod collapse;
pub mod families;
pub mod modes;
pub mod outline;
pub mod work;

#[cfg(test)]
mod tests;

pub use collapse::{
    CollapseMechanism, DilatancyRow, FlowRuleComparison, collapse_mechanism, compare_flow_rules,
};
pub use families::{Family, FamilyTemplate, REPRESENTATIVE, families, family};
pub use modes::{ModeStatus, Modes, mechanism_modes, null_space};
pub use outline::{MechanismDrawing, drawing};
pub use work::{JointForce, LimitState, WorkEquation, joint_force, work_equation};

/// Relative rank tolerance of the compatibility system: a singular value below `RANK_TOL`
/// times the largest one (or 1, whichever is larger) counts as zero. The entries are unit
/// vector components and lengths over r, so this is far above rounding (1e-15) and far below
/// any genuine stiffness of a pattern of joints a fraction of a degree apart.
pub const RANK_TOL: f64 = 1e-9;
/// A relative rotation or slip below this, on a field normalised to a largest block-corner
/// speed of 1, counts as zero: the joint does not move in that mode.
pub const ACTIVE_TOL: f64 = 1e-9;
/// Two joints closer than this (radians, about 1e-9°) are the same joint.
const SAME_JOINT: f64 = 1e-11;

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
        self.theta.to_degrees()
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

/// Checks a pattern against the arch: finite, inside [−α, α] (joints within 1e-9° of a
/// springing are put on it), sorted, coincident joints merged (a hinge and a slide become La
/// Hire).
pub fn normalise_pattern<G: ArchGeometry + ?Sized>(
    geom: &G,
    joints: &[ActiveJoint],
) -> Result<Vec<ActiveJoint>, KinematicsError> {
    let alpha = geom.half_angle();
    let mut out: Vec<ActiveJoint> = Vec::with_capacity(joints.len());
    for j in joints {
        if !j.theta.is_finite() {
            return Err(KinematicsError::NotFinite(j.theta.to_degrees()));
        }
        if j.theta.abs() > alpha + 1e-9_f64.to_radians() {
            return Err(KinematicsError::Outside {
                angle_deg: j.angle_deg(),
                alpha_deg: alpha.to_degrees(),
            });
        }
        let mut j = *j;
        j.theta = j.theta.clamp(-alpha, alpha);
        out.push(j);
    }
    out.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    let mut merged: Vec<ActiveJoint> = Vec::with_capacity(out.len());
    for j in out {
        match merged.last_mut() {
            Some(last) if (last.theta - j.theta).abs() <= SAME_JOINT => {
                match (last.hinge, j.hinge) {
                    (Some(a), Some(b)) if a != b => {
                        return Err(KinematicsError::BothFaces(j.angle_deg()));
                    }
                    (None, h) => last.hinge = h,
                    _ => {}
                }
                last.slides |= j.slides;
                last.sense = last.sense.or(j.sense);
            }
            _ => merged.push(j),
        }
    }
    Ok(merged)
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

/// A rigid-body virtual velocity: translation of a reference point and rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidVelocity {
    /// The reference point, over r.
    pub reference: Point,
    /// Velocity of the reference point (over r per unit virtual time).
    pub translation: [f64; 2],
    /// Angular velocity, counter-clockwise positive (radians per unit virtual time).
    pub rotation: f64,
}

impl RigidVelocity {
    /// The velocity of point `p`: u + ω k × (p − reference).
    pub fn at(&self, p: Point) -> [f64; 2] {
        let d = sub(p, self.reference);
        [
            self.translation[0] - self.rotation * d[1],
            self.translation[1] + self.rotation * d[0],
        ]
    }

    /// The centre of the rigid rotation (`None` for a translation).
    pub fn instant_centre(&self) -> Option<Point> {
        (self.rotation != 0.0).then(|| {
            let u = self.translation;
            [
                self.reference[0] - u[1] / self.rotation,
                self.reference[1] + u[0] / self.rotation,
            ]
        })
    }
}

/// One part of the arch between consecutive active joints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Part {
    /// Joint parameter of its left end (radians).
    pub theta_from: f64,
    /// Joint parameter of its right end (radians).
    pub theta_to: f64,
    /// True for the two end parts, held by the supports.
    pub fixed: bool,
    /// Its virtual velocity (zero for fixed parts).
    pub velocity: RigidVelocity,
}

/// The relative motion at one active joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointMotion {
    /// The joint.
    pub joint: ActiveJoint,
    /// δα = ω_left − ω_right: positive opens the extrados (hinge at the intrados).
    pub relative_rotation: f64,
    /// δr_G^n: relative normal separation at the joint centre (eq. 5).
    pub opening: f64,
    /// δr^t: slip of the crown-side part relative to the springing-side part along the
    /// joint, positive outward.
    pub slip: f64,
    /// Relative normal separation at the point that slides (the hinge point of a La Hire
    /// joint, else the centre): the dilatancy, zero for pure sliding.
    pub dilatancy: f64,
    /// Largest |row value| of this joint's compatibility equations (zero up to rounding).
    pub constraint_residual: f64,
}

impl JointMotion {
    /// The joint angle in degrees.
    pub fn angle_deg(&self) -> f64 {
        self.joint.angle_deg()
    }

    /// The sense of the slip, `None` below [`ACTIVE_TOL`].
    pub fn slip_sense(&self) -> Option<Sense> {
        if self.slip > ACTIVE_TOL {
            Some(Sense::Outward)
        } else if self.slip < -ACTIVE_TOL {
            Some(Sense::Inward)
        } else {
            None
        }
    }

    /// True when the joint rotates (|δα| above [`ACTIVE_TOL`]).
    pub fn rotates(&self) -> bool {
        self.relative_rotation.abs() > ACTIVE_TOL
    }

    /// True when the joint slides (|δr^t| above [`ACTIVE_TOL`]).
    pub fn slips(&self) -> bool {
        self.slip.abs() > ACTIVE_TOL
    }
}

/// A breach of the flow rules by a mechanism.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Violation {
    /// A hinge rotates against the normality rule: it would close the opposite face
    /// (δα < 0 at an intrados hinge, δα > 0 at an extrados hinge).
    Normality {
        /// Joint angle, degrees.
        angle_deg: f64,
        /// Face of the hinge.
        face: Face,
        /// δα found.
        relative_rotation: f64,
    },
    /// A joint slips against the friction force of the state: the friction would do positive
    /// work (principle of maximum dissipation, eq. 10).
    Dissipation {
        /// Joint angle, degrees.
        angle_deg: f64,
        /// Sense required by the state.
        expected: Sense,
        /// δr^t found.
        slip: f64,
    },
}

/// A kinematically determined velocity field of the whole arch.
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityField {
    /// The flow rule it was built with.
    pub rule: FlowRule,
    /// The n + 1 parts, left to right (the first and the last are fixed).
    pub parts: Vec<Part>,
    /// The motion at each of the n active joints, left to right.
    pub joints: Vec<JointMotion>,
}

impl VelocityField {
    /// Rotational, mixed or sliding, from the joints that actually move.
    pub fn kind(&self) -> Option<MechanismKind> {
        let h = self
            .joints
            .iter()
            .filter(|j| j.joint.hinge.is_some() && j.rotates())
            .count();
        let s = self
            .joints
            .iter()
            .filter(|j| j.joint.slides && j.slips())
            .count();
        MechanismKind::from_counts(h, s)
    }

    /// Breaches of normality at the hinges and of dissipation at sliding joints with a
    /// required sense (tolerance [`ACTIVE_TOL`]).
    pub fn violations(&self) -> Vec<Violation> {
        let mut out = Vec::new();
        for m in &self.joints {
            if let Some(face) = m.joint.hinge {
                let s = face_sign(face);
                if s * m.relative_rotation < -ACTIVE_TOL {
                    out.push(Violation::Normality {
                        angle_deg: m.angle_deg(),
                        face,
                        relative_rotation: m.relative_rotation,
                    });
                }
            }
            if let (true, Some(sense)) = (m.joint.slides, m.joint.sense)
                && sense_sign(sense) * m.slip < -ACTIVE_TOL
            {
                out.push(Violation::Dissipation {
                    angle_deg: m.angle_deg(),
                    expected: sense,
                    slip: m.slip,
                });
            }
        }
        out
    }

    /// The largest compatibility residual over all joints.
    pub fn constraint_residual(&self) -> f64 {
        self.joints
            .iter()
            .map(|j| j.constraint_residual)
            .fold(0.0, f64::max)
    }

    /// The moving parts (blocks).
    pub fn blocks(&self) -> impl Iterator<Item = &Part> {
        self.parts.iter().filter(|p| !p.fixed)
    }
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

/// The geometry the rows need at one joint.
#[derive(Debug, Clone, Copy)]
struct JointFrame {
    intrados: Point,
    extrados: Point,
    centre: Point,
    along: [f64; 2],
    normal: [f64; 2],
}

impl JointFrame {
    fn new<G: ArchGeometry + ?Sized>(geom: &G, theta: f64) -> Self {
        let j = geom.joint(theta);
        JointFrame {
            intrados: j.intrados,
            extrados: j.extrados,
            centre: [
                0.5 * (j.intrados[0] + j.extrados[0]),
                0.5 * (j.intrados[1] + j.extrados[1]),
            ],
            along: j.along(),
            normal: j.normal(),
        }
    }

    fn face_point(&self, face: Face) -> Point {
        match face {
            Face::Intrados => self.intrados,
            Face::Extrados => self.extrados,
        }
    }
}

/// The compatibility system of a pattern: one row per constraint, three columns per block.
#[derive(Debug, Clone)]
pub struct Compatibility {
    /// The normalised pattern.
    pub joints: Vec<ActiveJoint>,
    /// The flow rule at sliding joints.
    pub rule: FlowRule,
    /// The n + 1 parts with zero velocity (references set).
    pub parts: Vec<Part>,
    /// The matrix A: A x = 0 for x = (u_x, u_y, ω) of each block in turn.
    pub matrix: DMatrix<f64>,
    /// The joint each row belongs to (`None` for symmetry rows).
    pub row_joint: Vec<Option<usize>>,
    frames: Vec<JointFrame>,
}

/// A row under construction: coefficient per column.
struct RowBuilder<'a> {
    sys: &'a Compatibility,
    coeffs: Vec<f64>,
}

impl RowBuilder<'_> {
    /// Adds sign × (v_part(p)·e).
    fn add_point(&mut self, part: usize, sign: f64, p: Point, e: [f64; 2]) {
        if let Some(b) = self.sys.block_of(part) {
            let d = sub(p, self.sys.parts[part].velocity.reference);
            self.coeffs[3 * b] += sign * e[0];
            self.coeffs[3 * b + 1] += sign * e[1];
            self.coeffs[3 * b + 2] += sign * cross(d, e);
        }
    }

    /// Adds sign × ω_part.
    fn add_rotation(&mut self, part: usize, sign: f64) {
        if let Some(b) = self.sys.block_of(part) {
            self.coeffs[3 * b + 2] += sign;
        }
    }

    /// Adds c × (v_rel(p)·e) at joint j.
    fn relative(&mut self, j: usize, c: f64, p: Point, e: [f64; 2]) {
        self.add_point(j + 1, c, p, e);
        self.add_point(j, -c, p, e);
    }
}

impl Compatibility {
    /// Builds the system of a pattern (normalised with [`normalise_pattern`]).
    pub fn new<G: ArchGeometry + ?Sized>(
        geom: &G,
        joints: &[ActiveJoint],
        rule: FlowRule,
    ) -> Result<Self, KinematicsError> {
        let joints = normalise_pattern(geom, joints)?;
        let alpha = geom.half_angle();
        let n = joints.len();
        let mut parts = Vec::with_capacity(n + 1);
        for k in 0..=n {
            let from = if k == 0 { -alpha } else { joints[k - 1].theta };
            let to = if k == n { alpha } else { joints[k].theta };
            let reference = JointFrame::new(geom, 0.5 * (from + to)).centre;
            parts.push(Part {
                theta_from: from,
                theta_to: to,
                fixed: k == 0 || k == n,
                velocity: RigidVelocity {
                    reference,
                    translation: [0.0, 0.0],
                    rotation: 0.0,
                },
            });
        }
        let frames: Vec<JointFrame> = joints
            .iter()
            .map(|j| JointFrame::new(geom, j.theta))
            .collect();
        let mut sys = Compatibility {
            joints,
            rule,
            parts,
            matrix: DMatrix::zeros(0, 0),
            row_joint: Vec::new(),
            frames,
        };
        let mut rows: Vec<Vec<f64>> = Vec::new();
        for j in 0..n {
            for r in sys.joint_rows(j) {
                rows.push(r);
                sys.row_joint.push(Some(j));
            }
        }
        sys.matrix = to_matrix(&rows, sys.columns());
        Ok(sys)
    }

    /// Number of unknowns: three per block.
    pub fn columns(&self) -> usize {
        3 * self.parts.len().saturating_sub(2)
    }

    /// The block index (column group) of a part, `None` when it is fixed.
    fn block_of(&self, part: usize) -> Option<usize> {
        (!self.parts[part].fixed).then(|| part - 1)
    }

    /// The compatibility rows of joint j.
    fn joint_rows(&self, j: usize) -> Vec<Vec<f64>> {
        let joint = self.joints[j];
        let f = self.frames[j];
        let new = || RowBuilder {
            sys: self,
            coeffs: vec![0.0; self.columns()],
        };
        // |v_rel·τ| = σ v_rel·τ for the required sense (slip = crown_side · (−v_rel·τ)).
        let dilat = match (self.rule, joint.sense) {
            (FlowRule::Associative { tan_phi }, sense) => {
                let s = sense_sign(sense.unwrap_or(Sense::Outward));
                tan_phi * (-joint.crown_side() * s)
            }
            (FlowRule::NonAssociative, _) => 0.0,
        };
        let mut rows = Vec::new();
        match (joint.hinge, joint.slides) {
            (Some(face), false) => {
                let p = f.face_point(face);
                for e in [f.normal, f.along] {
                    let mut r = new();
                    r.relative(j, 1.0, p, e);
                    rows.push(r.coeffs);
                }
            }
            (Some(face), true) => {
                let p = f.face_point(face);
                let mut r = new();
                r.relative(j, 1.0, p, f.normal);
                r.relative(j, -dilat, p, f.along);
                rows.push(r.coeffs);
            }
            (None, _) => {
                let mut r = new();
                r.add_rotation(j + 1, 1.0);
                r.add_rotation(j, -1.0);
                rows.push(r.coeffs);
                let mut r = new();
                r.relative(j, 1.0, f.centre, f.normal);
                r.relative(j, -dilat, f.centre, f.along);
                rows.push(r.coeffs);
            }
        }
        rows
    }

    /// True when the pattern is its own mirror image about the crown (same faces and senses
    /// at ±θ); the geometry is assumed symmetric.
    pub fn is_symmetric(&self) -> bool {
        let n = self.joints.len();
        (0..n).all(|i| {
            let (a, b) = (self.joints[i], self.joints[n - 1 - i]);
            (a.theta + b.theta).abs() <= SAME_JOINT
                && a.hinge == b.hinge
                && a.slides == b.slides
                && a.sense == b.sense
        })
    }

    /// The rows that restrict the field to mirror-symmetric ones: block b and its mirror b′
    /// have u_b′ = (−u_x, u_y) and ω_b′ = −ω_b (their references are mirror images).
    pub fn symmetry_rows(&self) -> DMatrix<f64> {
        let cols = self.columns();
        let nb = cols / 3;
        let mut rows = Vec::new();
        for b in 0..nb {
            let m = nb - 1 - b;
            if m < b {
                break;
            }
            for (k, sign) in [(0usize, 1.0), (1, -1.0), (2, 1.0)] {
                let mut r = vec![0.0; cols];
                r[3 * b + k] += 1.0;
                r[3 * m + k] += sign;
                rows.push(r);
            }
        }
        to_matrix(&rows, cols)
    }

    /// The velocity field of a solution x of the system.
    pub fn field(&self, x: &[f64]) -> VelocityField {
        let mut parts = self.parts.clone();
        for (k, p) in parts.iter_mut().enumerate() {
            if let Some(b) = self.block_of(k) {
                p.velocity.translation = [x[3 * b], x[3 * b + 1]];
                p.velocity.rotation = x[3 * b + 2];
            }
        }
        let xs = nalgebra::DVector::from_column_slice(x);
        let residuals = &self.matrix * xs;
        let joints = self
            .joints
            .iter()
            .enumerate()
            .map(|(j, joint)| {
                let f = self.frames[j];
                let (l, r) = (parts[j].velocity, parts[j + 1].velocity);
                let rel = |p: Point| {
                    let (a, b) = (r.at(p), l.at(p));
                    [a[0] - b[0], a[1] - b[1]]
                };
                let slide_point = joint.hinge.map_or(f.centre, |face| f.face_point(face));
                let constraint_residual = self
                    .row_joint
                    .iter()
                    .zip(residuals.iter())
                    .filter(|(rj, _)| **rj == Some(j))
                    .map(|(_, v)| v.abs())
                    .fold(0.0, f64::max);
                JointMotion {
                    joint: *joint,
                    relative_rotation: l.rotation - r.rotation,
                    opening: dot(rel(f.centre), f.normal),
                    slip: -joint.crown_side() * dot(rel(slide_point), f.along),
                    dilatancy: dot(rel(slide_point), f.normal),
                    constraint_residual,
                }
            })
            .collect();
        VelocityField {
            rule: self.rule,
            parts,
            joints,
        }
    }

    /// The field of x scaled so that the largest speed of a block corner (the intrados and
    /// extrados ends of its joints) is 1; `None` when nothing moves.
    pub fn normalised_field(&self, x: &[f64]) -> Option<VelocityField> {
        let raw = self.field(x);
        let mut top = 0.0_f64;
        for (k, p) in raw.parts.iter().enumerate() {
            if p.fixed {
                continue;
            }
            for f in [&self.frames[k - 1], &self.frames[k]] {
                for q in [f.intrados, f.extrados] {
                    let v = p.velocity.at(q);
                    top = top.max(v[0].hypot(v[1]));
                }
            }
        }
        (top > 0.0 && top.is_finite()).then(|| {
            let y: Vec<f64> = x.iter().map(|v| v / top).collect();
            self.field(&y)
        })
    }

    /// The admissibility functionals of the pattern, as rows acting on x: each is ≥ 0 for a
    /// field obeying normality at a hinge or dissipation at a sliding joint with a sense.
    fn admissibility_rows(&self) -> Vec<Vec<f64>> {
        let cols = self.columns();
        let n = self.joints.len();
        let mut out = Vec::new();
        for j in 0..n {
            let joint = self.joints[j];
            if let Some(face) = joint.hinge {
                // face_sign · δα = face_sign · (ω_left − ω_right).
                let mut r = RowBuilder {
                    sys: self,
                    coeffs: vec![0.0; cols],
                };
                r.add_rotation(j, face_sign(face));
                r.add_rotation(j + 1, -face_sign(face));
                out.push(r.coeffs);
            }
            if let (true, Some(sense)) = (joint.slides, joint.sense) {
                let f = self.frames[j];
                let p = joint.hinge.map_or(f.centre, |face| f.face_point(face));
                let mut r = RowBuilder {
                    sys: self,
                    coeffs: vec![0.0; cols],
                };
                r.relative(j, -joint.crown_side() * sense_sign(sense), p, f.along);
                out.push(r.coeffs);
            }
        }
        out
    }
}

fn to_matrix(rows: &[Vec<f64>], cols: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows.len(), cols, |i, j| rows[i][j])
}
