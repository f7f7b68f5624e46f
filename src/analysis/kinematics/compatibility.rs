//! The compatibility system of a pattern of active joints: one row per constraint, three
//! columns (u_x, u_y, ω) per free block.

use super::{
    ActiveJoint, FlowRule, JointMotion, KinematicsError, KinematicsSettings, Part, RigidVelocity,
    VelocityField, cross, dot, face_sign, normalise_pattern, sense_sign, sub,
};
use crate::analysis::statics::{ArchGeometry, Point};
use crate::analysis::types::{Face, Sense};
use nalgebra::DMatrix;

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
    /// The tolerances the system and its fields use.
    pub settings: KinematicsSettings,
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
        settings: &KinematicsSettings,
    ) -> Result<Self, KinematicsError> {
        let joints = normalise_pattern(geom, joints, settings)?;
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
            settings: *settings,
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
            (a.theta + b.theta).abs() <= self.settings.tol_same_joint
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
                    tol_motion: self.settings.tol_motion,
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
    /// The admissibility rows g·x ≥ 0 of the pattern, each with `true` when it is a
    /// dissipation row (the sense of a sliding joint) and `false` for normality at a hinge.
    pub(super) fn admissibility_rows(&self) -> Vec<(Vec<f64>, bool)> {
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
                out.push((r.coeffs, false));
            }
            if let (true, Some(sense)) = (joint.slides, joint.sense) {
                let f = self.frames[j];
                let p = joint.hinge.map_or(f.centre, |face| f.face_point(face));
                let mut r = RowBuilder {
                    sys: self,
                    coeffs: vec![0.0; cols],
                };
                r.relative(j, -joint.crown_side() * sense_sign(sense), p, f.along);
                out.push((r.coeffs, true));
            }
        }
        out
    }
}

fn to_matrix(rows: &[Vec<f64>], cols: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows.len(), cols, |i, j| rows[i][j])
}
