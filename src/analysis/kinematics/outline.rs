//! Geometry for drawing a mechanism: the outline of every part before and after a small
//! virtual displacement, the hinge points and the sliding joints with their sense.
//!
//! A block with virtual velocity (u, ω) is displaced by the finite rigid motion of amplitude
//! ε: a rotation by εω about its instant centre (a translation εu when ω = 0), so its shape is
//! kept exactly and adjacent blocks still meet at their hinges to first order in ε. Lengths
//! over r; the field is normalised (largest block-corner speed 1), so ε is the largest corner
//! displacement over r.

use super::{KinematicsSettings, RigidVelocity, VelocityField};
use crate::analysis::statics::{ArchGeometry, Point};
use crate::analysis::types::{Face, Sense};
use serde::{Deserialize, Serialize};

/// The outline of one part of the arch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BlockOutline {
    /// Joint parameter of the left end (radians).
    pub theta_from: f64,
    /// Joint parameter of the right end (radians).
    pub theta_to: f64,
    /// True for a part held by a support.
    pub fixed: bool,
    /// Closed polygon (intrados left to right, then extrados back), first point not repeated.
    pub original: Vec<Point>,
    /// The same polygon after the displacement.
    pub displaced: Vec<Point>,
}

/// A hinge to mark.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HingeMark {
    /// Hinge point before the displacement.
    pub point: Point,
    /// Hinge point after it (as carried by the block on its left).
    pub displaced: Point,
    /// Face of the hinge.
    pub face: Face,
    /// δα at the hinge.
    pub relative_rotation: f64,
}

/// A sliding joint to mark.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SlideMark {
    /// Joint centre before the displacement.
    pub centre: Point,
    /// Unit vector along the joint, from intrados to extrados.
    pub along: [f64; 2],
    /// Slip of the crown-side part (positive outward), normalised field.
    pub slip: f64,
    /// Sense of the slip (`None` when it does not slip in this mode).
    pub sense: Option<Sense>,
    /// +1 when the crown-side part is the left part (θ ≥ 0), −1 otherwise.
    pub crown_side: f64,
}

/// A support: the springing joint and the side the ground lies on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SupportMark {
    /// Intrados end of the springing joint.
    pub intrados: Point,
    /// Extrados end of the springing joint.
    pub extrados: Point,
    /// Unit normal of the joint pointing into the ground.
    pub into_ground: [f64; 2],
}

/// Everything needed to draw a mechanism.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MechanismDrawing {
    /// All parts, left to right (fixed ones unmoved).
    pub outlines: Vec<BlockOutline>,
    /// Hinges.
    pub hinges: Vec<HingeMark>,
    /// Sliding joints.
    pub slides: Vec<SlideMark>,
    /// The two supports, left then right.
    pub supports: [SupportMark; 2],
    /// Joints between voussoirs inside the parts (intrados and extrados ends), displaced
    /// with their part; empty for a continuum.
    pub voussoir_joints: Vec<[Point; 2]>,
    /// The displacement amplitude ε used (over r).
    pub amplitude: f64,
}

impl MechanismDrawing {
    /// Bounding box (x_min, x_max, y_min, y_max) of all outlines, before and after.
    pub fn bounds(&self) -> [f64; 4] {
        let mut b = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for o in &self.outlines {
            for p in o.original.iter().chain(&o.displaced) {
                b[0] = b[0].min(p[0]);
                b[1] = b[1].max(p[0]);
                b[2] = b[2].min(p[1]);
                b[3] = b[3].max(p[1]);
            }
        }
        b
    }
}

/// The point p moved by the rigid motion of amplitude ε of a virtual velocity (small-angle
/// series below `settings.small_rotation`).
pub fn displace(
    v: &RigidVelocity,
    p: Point,
    amplitude: f64,
    settings: &KinematicsSettings,
) -> Point {
    let beta = amplitude * v.rotation;
    let d = [p[0] - v.reference[0], p[1] - v.reference[1]];
    let u = v.translation;
    let (sb, cb) = beta.sin_cos();
    // Rotation by β about the instant centre c = ref + k×u/ω, written without dividing by ω:
    // p' = p + (cos β − 1) d + sin β k×d + (sin β/ω) u + ((1 − cos β)/ω) k×u.
    let (f1, f2) = if beta.abs() < settings.small_rotation {
        (amplitude, 0.5 * amplitude * beta)
    } else {
        (sb / v.rotation, (1.0 - cb) / v.rotation)
    };
    [
        p[0] + (cb - 1.0) * d[0] - sb * d[1] + f1 * u[0] - f2 * u[1],
        p[1] + (cb - 1.0) * d[1] + sb * d[0] + f1 * u[1] + f2 * u[0],
    ]
}

/// The outline polygon of the arch between two joints, `step` radians between samples.
fn polygon<G: ArchGeometry + ?Sized>(geom: &G, from: f64, to: f64, step: f64) -> Vec<Point> {
    let n = (((to - from).abs() / step).ceil() as usize).max(1);
    let ts: Vec<f64> = (0..=n)
        .map(|i| from + (to - from) * i as f64 / n as f64)
        .collect();
    let mut out: Vec<Point> = ts.iter().map(|&t| geom.joint(t).intrados).collect();
    out.extend(ts.iter().rev().map(|&t| geom.joint(t).extrados));
    out
}

/// The drawing of a field with the default settings ([`drawing_with`]).
pub fn drawing<G: ArchGeometry + ?Sized>(
    geom: &G,
    field: &VelocityField,
    amplitude: f64,
) -> MechanismDrawing {
    drawing_with(geom, field, amplitude, &KinematicsSettings::DEFAULT)
}

/// The drawing of a field with displacement amplitude ε (over r; 0.08 shows a mechanism
/// clearly on a semicircle).
pub fn drawing_with<G: ArchGeometry + ?Sized>(
    geom: &G,
    field: &VelocityField,
    amplitude: f64,
    settings: &KinematicsSettings,
) -> MechanismDrawing {
    let step = 1.0_f64.to_radians();
    let outlines = field
        .parts
        .iter()
        .filter(|p| p.theta_to > p.theta_from)
        .map(|p| {
            let original = polygon(geom, p.theta_from, p.theta_to, step);
            let displaced = original
                .iter()
                .map(|&q| displace(&p.velocity, q, amplitude, settings))
                .collect();
            BlockOutline {
                theta_from: p.theta_from,
                theta_to: p.theta_to,
                fixed: p.fixed,
                original,
                displaced,
            }
        })
        .collect();
    let mut hinges = Vec::new();
    let mut slides = Vec::new();
    for (k, m) in field.joints.iter().enumerate() {
        let j = geom.joint(m.joint.theta);
        let left = field.parts[k].velocity;
        if let Some(face) = m.joint.hinge {
            let point = match face {
                Face::Intrados => j.intrados,
                Face::Extrados => j.extrados,
            };
            hinges.push(HingeMark {
                point,
                displaced: displace(&left, point, amplitude, settings),
                face,
                relative_rotation: m.relative_rotation,
            });
        }
        if m.joint.slides {
            slides.push(SlideMark {
                centre: [
                    0.5 * (j.intrados[0] + j.extrados[0]),
                    0.5 * (j.intrados[1] + j.extrados[1]),
                ],
                along: j.along(),
                slip: m.slip,
                sense: m.slip_sense(),
                crown_side: if m.joint.theta >= 0.0 { 1.0 } else { -1.0 },
            });
        }
    }
    let mut voussoir_joints = Vec::new();
    for t in geom.discrete_joints().unwrap_or_default() {
        let Some(p) = field
            .parts
            .iter()
            .find(|p| p.theta_from < t && t < p.theta_to)
        else {
            continue;
        };
        let j = geom.joint(t);
        voussoir_joints.push([
            displace(&p.velocity, j.intrados, amplitude, settings),
            displace(&p.velocity, j.extrados, amplitude, settings),
        ]);
    }
    let alpha = geom.half_angle();
    let support = |theta: f64, sign: f64| {
        let j = geom.joint(theta);
        let n = j.normal();
        SupportMark {
            intrados: j.intrados,
            extrados: j.extrados,
            into_ground: [sign * n[0], sign * n[1]],
        }
    };
    MechanismDrawing {
        outlines,
        hinges,
        slides,
        supports: [support(-alpha, -1.0), support(alpha, 1.0)],
        voussoir_joints,
        amplitude,
    }
}
