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

/// The joint the arch stands on at side `sign` (±1): the joint at ±α, or the springing plane
/// beyond it when the form has one there (the radial support of an arch with vertical
/// joints, whose joint at ±α is the vertical section through the intrados springing).
fn support_joint<G: ArchGeometry + ?Sized>(
    geom: &G,
    sign: f64,
    settings: &KinematicsSettings,
) -> crate::analysis::statics::Joint {
    let a = geom.half_angle();
    if plane_beyond(geom, sign, settings) {
        geom.joint(sign * a.next_up())
    } else {
        geom.joint(sign * a)
    }
}

/// Whether the form has a springing plane beyond ±α other than the joint at ±α.
fn plane_beyond<G: ArchGeometry + ?Sized>(
    geom: &G,
    sign: f64,
    settings: &KinematicsSettings,
) -> bool {
    let a = geom.half_angle();
    let (u, v) = (
        geom.joint(sign * a).along(),
        geom.joint(sign * a.next_up()).along(),
    );
    (u[0] - v[0]).abs() + (u[1] - v[1]).abs() > settings.tol_same_ray
}

/// Points of the circle through `p`, `q` and `r` from `p` towards `q` (both excluded), at
/// most `step` radians apart; none when the three are collinear or `p` is `q`.
fn arc_between(p: Point, q: Point, r: Point, step: f64) -> Vec<Point> {
    let d = 2.0 * (p[0] * (q[1] - r[1]) + q[0] * (r[1] - p[1]) + r[0] * (p[1] - q[1]));
    if d.abs() < f64::EPSILON || p == q {
        return Vec::new();
    }
    let n = |a: Point| a[0] * a[0] + a[1] * a[1];
    let c = [
        (n(p) * (q[1] - r[1]) + n(q) * (r[1] - p[1]) + n(r) * (p[1] - q[1])) / d,
        (n(p) * (r[0] - q[0]) + n(q) * (p[0] - r[0]) + n(r) * (q[0] - p[0])) / d,
    ];
    let rho = n([p[0] - c[0], p[1] - c[1]]).sqrt();
    let (a0, a1) = (
        (p[1] - c[1]).atan2(p[0] - c[0]),
        (q[1] - c[1]).atan2(q[0] - c[0]),
    );
    let mut da = a1 - a0;
    if da > std::f64::consts::PI {
        da -= std::f64::consts::TAU;
    } else if da < -std::f64::consts::PI {
        da += std::f64::consts::TAU;
    }
    let m = ((da.abs() / step).ceil() as usize).max(1);
    (1..m)
        .map(|i| {
            let t = a0 + da * i as f64 / m as f64;
            [c[0] + rho * t.cos(), c[1] + rho * t.sin()]
        })
        .collect()
}

/// The outline polygon of the arch between two joints, `step` radians between samples. An
/// end beyond ±α (a springing plane past the joint at ±α) meets the joint at ±α along the
/// extrados arc: the circle through that end's extrados point and two extrados points at
/// and just inside ±α.
fn polygon<G: ArchGeometry + ?Sized>(
    geom: &G,
    (from, to): (f64, f64),
    step: f64,
    beyond: [bool; 2],
) -> Vec<Point> {
    let n = (((to - from).abs() / step).ceil() as usize).max(1);
    let ts: Vec<f64> = (0..=n)
        .map(|i| from + (to - from) * i as f64 / n as f64)
        .collect();
    let a = geom.half_angle();
    // The extrados from the springing plane beyond ±α to the joint at ±α: the plane's
    // extrados point, the arc, the joint's extrados point.
    let wedge = |sign: f64| -> Vec<Point> {
        let inner = if sign > 0.0 { from.max(-a) } else { to.min(a) };
        let h = 0.5 * step.min((sign * a - inner).abs());
        let e = geom.joint(sign * a.next_up()).extrados;
        let at = geom.joint(sign * a).extrados;
        let near = geom.joint(sign * (a - h)).extrados;
        let mut v = vec![e];
        v.extend(arc_between(e, at, near, step));
        v.push(at);
        v
    };
    let right_end = to >= a && beyond[1];
    let left_end = from <= -a && beyond[0];
    let mut out: Vec<Point> = ts.iter().map(|&t| geom.joint(t).intrados).collect();
    let mut extrados: Vec<Point> = Vec::new();
    if right_end {
        extrados.extend(wedge(1.0));
    } else {
        extrados.push(geom.joint(ts[n]).extrados);
    }
    extrados.extend(ts[1..n].iter().rev().map(|&t| geom.joint(t).extrados));
    if left_end {
        extrados.extend(wedge(-1.0).into_iter().rev());
    } else {
        extrados.push(geom.joint(ts[0]).extrados);
    }
    out.extend(extrados);
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
    let beyond = [-1.0, 1.0].map(|sign| plane_beyond(geom, sign, settings));
    let outlines = field
        .parts
        .iter()
        .filter(|p| p.theta_to > p.theta_from)
        .map(|p| {
            let original = polygon(geom, (p.theta_from, p.theta_to), step, beyond);
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
    let support = |sign: f64| {
        let j = support_joint(geom, sign, settings);
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
        supports: [support(-1.0), support(1.0)],
        voussoir_joints,
        amplitude,
    }
}
