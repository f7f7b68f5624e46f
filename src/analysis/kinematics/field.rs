//! Velocity fields of a mechanism: rigid velocities of the parts, the relative motion at
//! each active joint and the breaches of the flow rules.

use super::{ActiveJoint, FlowRule, face_sign, sense_sign, sub};
use crate::analysis::statics::Point;
use crate::analysis::types::{Face, MechanismKind, Sense};

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
    /// A rotation or slip below this counts as zero ([`KinematicsSettings::tol_motion`] of
    /// the settings the field was computed with).
    ///
    /// [`KinematicsSettings::tol_motion`]: super::KinematicsSettings::tol_motion
    pub tol_motion: f64,
}

impl JointMotion {
    /// The joint angle in degrees.
    pub fn angle_deg(&self) -> f64 {
        self.joint.angle_deg()
    }

    /// The sense of the slip, `None` below `tol_motion`.
    pub fn slip_sense(&self) -> Option<Sense> {
        if self.slip > self.tol_motion {
            Some(Sense::Outward)
        } else if self.slip < -self.tol_motion {
            Some(Sense::Inward)
        } else {
            None
        }
    }

    /// True when the joint rotates (|δα| above `tol_motion`).
    pub fn rotates(&self) -> bool {
        self.relative_rotation.abs() > self.tol_motion
    }

    /// True when the joint slides (|δr^t| above `tol_motion`).
    pub fn slips(&self) -> bool {
        self.slip.abs() > self.tol_motion
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
    /// required sense (tolerance `tol_motion` of each joint).
    pub fn violations(&self) -> Vec<Violation> {
        let mut out = Vec::new();
        for m in &self.joints {
            if let Some(face) = m.joint.hinge {
                let s = face_sign(face);
                if s * m.relative_rotation < -m.tol_motion {
                    out.push(Violation::Normality {
                        angle_deg: m.angle_deg(),
                        face,
                        relative_rotation: m.relative_rotation,
                    });
                }
            }
            if let (true, Some(sense)) = (m.joint.slides, m.joint.sense)
                && sense_sign(sense) * m.slip < -m.tol_motion
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
