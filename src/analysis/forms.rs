//! Arch forms and load cases for the general three-unknown statics: circular or pointed
//! outline, radial or vertical joints, self-weight plus a live load scaled by λ.
//!
//! Lengths over the intrados radius r, forces over W_half (the weight of the half arch),
//! moments over W_half·r, as in [`super::statics`].
//!
//! # Geometry
//! The right half of the arch is the part of an annulus of radii 1 and K about the centre
//! C = (−d, 0) with x ≥ 0; the left half is its mirror image. d = e·ρ_c with ρ_c = (1 + K)/2
//! the centreline radius and e the eccentricity: d = 0 is the circular arch, d > 0 a pointed
//! one whose halves meet on the axis x = 0. A point of the right half is (−d + ρ sin ψ,
//! ρ cos ψ) with ψ its angle at C from the vertical; the springing joint is radial at ψ = α.
//!
//! A joint is named by θ, the signed angle ψ of its intrados end (θ > 0 on the right):
//! - radial joints are the radii at ψ = |θ|;
//! - vertical joints run from the intrados point at ψ = |θ| straight up to the extrados
//!   (so their extrados end is at sin ψ_E = sin ψ/K); the supports stay radial at ψ = α and
//!   carry the parameters ±α⁺ (the float just beyond α), reported as ±α; on a pointed arch
//!   the vertical joints at ±ψ₁ are the crown joint and are reported as 0;
//! - the crown joint is the segment of x = 0 between the intrados apex (ψ₁ = asin d) and the
//!   extrados apex (ψ_e = asin(d/K)), named 0. Joints with 0 < |θ| < ψ₁ do not exist: the
//!   radius through them would leave the half arch.
//!
//! # Weights (docs/mechanics.md §1)
//! `annular`: the true area of the region R(θ) between the crown joint and joint θ. Its area
//! and first moments (A, S_x = ∫x dA, S_y = ∫y dA) are exact closed forms by Green's theorem
//! on the boundary of R(θ) (two straight joints and two circular arcs):
//! A = ∮x dy, S_x = ∮x²/2 dy, S_y = −∮y²/2 dx. For the circular arch with radial joints they
//! reduce to w(θ) = θ/α and S = ρ_s(1 − cos θ)/α, ρ_s sin θ/α ([`Arch::weight_radius`]),
//! which are used directly. `centreline`: weight t per unit length of the centreline arc
//! between the points where the crown joint and joint θ cross it.
//!
//! # Loads (per unit λ, docs/mechanics.md §1)
//! - horizontal: the body force λ·dW toward +x; between the crown and θ its resultant is
//!   (w(θ), 0) with moment −∫y dW about the origin;
//! - point: P = λ·W_total = 2λ W_half downward at the extrados end X of the joint at θ = a;
//!   its resultant between the crown and θ is (0, −2) with moment −2 x_X when the load lies
//!   there. A load exactly at a joint belongs to the part nearer the crown, a load at the
//!   crown to the right half: R(θ) contains it iff 0 ≤ a ≤ θ (θ > 0) or θ ≤ a < 0 (θ < 0).
//!   The continuum has both sides of the load as joints: the joint at a (load on the crown
//!   side) and the joint at the adjacent float on the far side.

use super::settings::GeometrySettings;
use super::statics::{ArchGeometry, Condition, Joint, Point, Resultant};
use crate::model::{Arch, ArchForm, Discretisation, JointOrientation, Load, WeightModel};
use std::f64::consts::FRAC_PI_2;

/// The numerical thresholds of the forms (see [`GeometrySettings`]).
const GEOMETRY: GeometrySettings = GeometrySettings::DEFAULT;

/// Why a form, an arch and a load do not make a valid scene.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FormError {
    /// The eccentricity must lie in [0, 1).
    #[error("eccentricity {0} is not allowed: it must lie in [0, 1)")]
    Eccentricity(f64),
    /// The intrados arcs of a pointed arch must meet above the springings.
    #[error(
        "a pointed arch with eccentricity {eccentricity} and half-angle {half_angle_deg}° exists only for K < {max_k}; K = {k} is too thick"
    )]
    PointedTooThick {
        /// e.
        eccentricity: f64,
        /// α in degrees.
        half_angle_deg: f64,
        /// K given.
        k: f64,
        /// The bound on K.
        max_k: f64,
    },
    /// Vertical joints need α ≤ 90°.
    #[error(
        "vertical joints need a half-angle of at most 90°, not {0}°: beyond, a vertical plane through the intrados crosses the opening"
    )]
    VerticalBeyondQuadrant(f64),
    /// A point load outside the arch.
    #[error(
        "a point load at {at_deg}° is not on the arch: it must lie in [−{half_angle_deg}°, {half_angle_deg}°]"
    )]
    LoadOutside {
        /// Position given.
        at_deg: f64,
        /// α in degrees.
        half_angle_deg: f64,
    },
    /// A point load between the crown and the first joint of a pointed arch.
    #[error(
        "a point load at {at_deg}° is not at a joint of this pointed arch: its crown joint is at 0° and the next ones at ±{first_joint_deg}°"
    )]
    LoadInsideKeystone {
        /// Position given.
        at_deg: f64,
        /// ψ₁ in degrees.
        first_joint_deg: f64,
    },
}

/// Area and first moments of a region: (A, ∫x dA, ∫y dA).
type Moments = [f64; 3];

/// The right-half description of a joint: intrados and extrados angles at the centre C and
/// the angle at which it crosses the centreline.
#[derive(Debug, Clone, Copy, PartialEq)]
struct HalfJoint {
    psi_i: f64,
    psi_e: f64,
    psi_c: f64,
}

/// An arch of any form under self-weight and the live part of one load case, as a general
/// [`ArchGeometry`].
#[derive(Debug, Clone, Copy)]
pub struct ArchModel {
    arch: Arch,
    form: ArchForm,
    load: Load,
    /// Centre offset d over r.
    d: f64,
    /// Centreline radius ρ_c over r.
    rho_c: f64,
    /// ψ of the intrados apex, asin d.
    psi_1: f64,
    /// ψ of the extrados apex, asin(d/K).
    psi_e0: f64,
    /// ψ of the centreline apex, asin(d/ρ_c).
    psi_c0: f64,
    /// Weight of the half arch in r² (annular) or t·r (centreline) units.
    w_half: f64,
    /// Antiderivatives of the intrados and extrados arcs at the apexes.
    crown_int: Moments,
    crown_ext: Moments,
    /// The crown joint's own contribution (the segment from Ec down to Ic).
    crown_seg: Moments,
    /// The point load's parameter a (radians) and position X.
    point: Option<(f64, Point)>,
    /// True when a point load at the apex of a pointed arch with radial joints is shared
    /// freely between the halves ([`ArchModel::with_shared_apex`]).
    shared_apex: bool,
}

/// Antiderivatives (∫x dy, ∫x²/2 dy, −∫y²/2 dx) along the arc of radius ρ about (−d, 0) at
/// angle ψ (x = −d + ρ sin ψ, y = ρ cos ψ).
fn arc_primitive(rho: f64, d: f64, psi: f64) -> Moments {
    let (s, c) = psi.sin_cos();
    let int_s = -c;
    let int_s2 = 0.5 * (psi - s * c);
    let int_s3 = -c + c * c * c / 3.0;
    let int_c3 = s - s * s * s / 3.0;
    [
        d * rho * int_s - rho * rho * int_s2,
        -0.5 * rho * (d * d * int_s - 2.0 * d * rho * int_s2 + rho * rho * int_s3),
        -0.5 * rho * rho * rho * int_c3,
    ]
}

/// (∫x dy, ∫x²/2 dy, −∫y²/2 dx) along the segment from p to q.
fn segment(p: Point, q: Point) -> Moments {
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    [
        0.5 * dy * (p[0] + q[0]),
        dy * (p[0] * p[0] + p[0] * q[0] + q[0] * q[0]) / 6.0,
        -dx * (p[1] * p[1] + p[1] * q[1] + q[1] * q[1]) / 6.0,
    ]
}

fn add(a: Moments, b: Moments) -> Moments {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: Moments, b: Moments) -> Moments {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

impl ArchModel {
    /// The model of an arch of a given form under a load case; checks that the form exists
    /// at this K and α and that a point load sits at a joint.
    pub fn new(arch: Arch, form: ArchForm, load: Load) -> Result<Self, FormError> {
        let k = arch.k;
        let alpha = arch.half_angle;
        let e = form.shape.eccentricity();
        if !(0.0..1.0).contains(&e) {
            return Err(FormError::Eccentricity(e));
        }
        let max_k = form.max_k(alpha);
        if !(k < max_k) {
            return Err(FormError::PointedTooThick {
                eccentricity: e,
                half_angle_deg: arch.half_angle_deg(),
                k,
                max_k,
            });
        }
        if form.joints == JointOrientation::Vertical
            && alpha > FRAC_PI_2 + GEOMETRY.tol_vertical_alpha
        {
            return Err(FormError::VerticalBeyondQuadrant(arch.half_angle_deg()));
        }
        let d = form.centre_offset(k);
        let rho_c = 0.5 * (1.0 + k);
        let psi_1 = d.asin();
        let psi_e0 = (d / k).asin();
        let psi_c0 = (d / rho_c).asin();
        let crown_i = [0.0, psi_1.cos()];
        let crown_e = [0.0, (k * k - d * d).sqrt()];
        let mut m = ArchModel {
            arch,
            form,
            load,
            d,
            rho_c,
            psi_1,
            psi_e0,
            psi_c0,
            w_half: 1.0,
            crown_int: arc_primitive(1.0, d, psi_1),
            crown_ext: arc_primitive(k, d, psi_e0),
            crown_seg: segment(crown_e, crown_i),
            point: None,
            shared_apex: false,
        };
        m.w_half = match arch.weight {
            WeightModel::Annular => m.region(&m.support()).0[0],
            WeightModel::Centreline => (k - 1.0) * rho_c * (alpha - psi_c0),
        };
        if let Load::Point { at_deg } = load {
            let a = at_deg.to_radians();
            if !(a.abs() <= alpha * (1.0 + GEOMETRY.tol_joint_range)) {
                return Err(FormError::LoadOutside {
                    at_deg,
                    half_angle_deg: arch.half_angle_deg(),
                });
            }
            let a = a.clamp(-alpha, alpha);
            if a != 0.0 && a.abs() < psi_1 {
                return Err(FormError::LoadInsideKeystone {
                    at_deg,
                    first_joint_deg: psi_1.to_degrees(),
                });
            }
            let x = m.joint_at(a).extrados;
            m.point = Some((a, x));
        }
        Ok(m)
    }

    /// True when the scene has a point load at the apex of a pointed arch with radial
    /// joints and a crown joint (the continuum, an even voussoir count): the load sits on the
    /// crown joint between the two halves, and how it is shared between them is statically
    /// indeterminate.
    pub fn has_apex_load(&self) -> bool {
        // An odd voussoir count has a keystone over the apex: the load lies on one block.
        let crown_joint = match self.arch.joints {
            Discretisation::Voussoirs(n) => n % 2 == 0,
            Discretisation::Continuum => true,
        };
        crown_joint
            && self.psi_1 > 0.0
            && self.form.joints == JointOrientation::Radial
            && self.point.is_some_and(|(a, _)| a == 0.0)
    }

    /// The same scene with the apex load shared freely between the halves (the most
    /// favourable split, a bound of the critical values; docs/loads-and-geometries.md). The
    /// load P at the extrados apex X lies on the crown joint x = 0: moving a part of it across
    /// the joint changes only the joint's shear (a vertical force at X has no normal component
    /// and no moment about a point of x = 0). A free split therefore asks only that some
    /// shear between T(0⁺) = T(0) − P and T(0) lie within ±μN: T(0⁺) ≤ μN and T(0) ≥ −μN.
    /// The crown joint gets a twin 0⁺ carrying the load; 0 keeps its no-tension rows and the
    /// inward Coulomb row, 0⁺ the outward one. Unchanged when the scene has no apex load.
    pub fn with_shared_apex(mut self) -> Self {
        self.shared_apex = self.has_apex_load();
        self
    }

    /// The arch.
    pub fn arch(&self) -> &Arch {
        &self.arch
    }

    /// The form.
    pub fn form(&self) -> &ArchForm {
        &self.form
    }

    /// The load case.
    pub fn load(&self) -> Load {
        self.load
    }

    /// ψ₁ = asin d: the angle (radians) of the first joint after the crown of a pointed arch
    /// (0 for a circular arch).
    pub fn first_joint(&self) -> f64 {
        self.psi_1
    }

    fn circular_radial(&self) -> bool {
        self.d == 0.0 && self.form.joints == JointOrientation::Radial
    }

    fn support(&self) -> HalfJoint {
        let a = self.arch.half_angle;
        HalfJoint {
            psi_i: a,
            psi_e: a,
            psi_c: a,
        }
    }

    /// The right-half joint at |θ|.
    fn half_joint(&self, theta: f64) -> HalfJoint {
        let alpha = self.arch.half_angle;
        let t = theta.abs();
        if t > alpha {
            return self.support();
        }
        if t == 0.0 || t < self.psi_1 {
            return HalfJoint {
                psi_i: self.psi_1,
                psi_e: self.psi_e0,
                psi_c: self.psi_c0,
            };
        }
        match self.form.joints {
            JointOrientation::Radial => HalfJoint {
                psi_i: t,
                psi_e: t,
                psi_c: t,
            },
            JointOrientation::Vertical => {
                let s = t.sin();
                HalfJoint {
                    psi_i: t,
                    psi_e: (s / self.arch.k).asin(),
                    psi_c: (s / self.rho_c).asin(),
                }
            }
        }
    }

    fn ends(&self, j: &HalfJoint) -> (Point, Point) {
        let (si, ci) = j.psi_i.sin_cos();
        // Radial joints have both ends at one angle: one sine and cosine.
        let (se, ce) = if j.psi_e == j.psi_i {
            (si, ci)
        } else {
            j.psi_e.sin_cos()
        };
        let k = self.arch.k;
        ([-self.d + si, ci], [-self.d + k * se, k * ce])
    }

    /// Area and first moments of the right-half region between the crown joint and `j`
    /// (raw units), with the joint's ends.
    fn region(&self, j: &HalfJoint) -> (Moments, Point, Point) {
        let (i, e) = self.ends(j);
        let k = self.arch.k;
        // Counter-clockwise: intrados arc from the apex to I, the joint from I to E, the
        // extrados arc from E back to the apex, the crown joint down to the intrados apex.
        let intrados = sub(arc_primitive(1.0, self.d, j.psi_i), self.crown_int);
        let extrados = sub(self.crown_ext, arc_primitive(k, self.d, j.psi_e));
        let m = add(add(intrados, segment(i, e)), add(extrados, self.crown_seg));
        (m, i, e)
    }

    /// (w, s_x, s_y): weight and first moments of R(θ) over W_half (and W_half·r), signed as
    /// the resultants of [`super::statics`]: for θ < 0 they are those of the mirrored region
    /// with the sign of −∫_θ^0.
    pub fn weight_moments(&self, theta: f64) -> [f64; 3] {
        let t = theta.abs();
        let m = if self.circular_radial() {
            let a = self.arch.half_angle;
            let rho_s = self.arch.weight_radius();
            let t = t.min(a);
            let (s, c) = t.sin_cos();
            [t / a, rho_s * (1.0 - c) / a, rho_s * s / a]
        } else {
            let j = self.half_joint(theta);
            let raw = match self.arch.weight {
                WeightModel::Annular => self.region(&j).0,
                WeightModel::Centreline => {
                    let t = self.arch.k - 1.0;
                    let rc = self.rho_c;
                    let dpsi = j.psi_c - self.psi_c0;
                    [
                        t * rc * dpsi,
                        t * rc * (-self.d * dpsi + rc * (self.psi_c0.cos() - j.psi_c.cos())),
                        t * rc * rc * (j.psi_c.sin() - self.psi_c0.sin()),
                    ]
                }
            };
            raw.map(|v| v / self.w_half)
        };
        if theta < 0.0 {
            // Mirror: x → −x flips S_x; the sign of −∫_θ^0 flips A and S_y.
            [-m[0], m[1], -m[2]]
        } else {
            m
        }
    }

    fn joint_at(&self, theta: f64) -> Joint {
        let j = self.half_joint(theta);
        let (mut i, mut e) = self.ends(&j);
        if theta < 0.0 {
            i[0] = -i[0];
            e[0] = -e[0];
        }
        Joint {
            theta,
            intrados: i,
            extrados: e,
        }
    }

    /// The parameter of the support at the right (+1) or left (−1) springing.
    fn support_param(&self, side: f64) -> f64 {
        let a = self.arch.half_angle;
        match self.form.joints {
            JointOrientation::Radial => side * a,
            JointOrientation::Vertical => side * a.next_up(),
        }
    }

    /// The joints of the family over one half, from the crown outward, at fractions
    /// s ∈ [0, 1] of the half: s = 0 is the crown, s = 1 the springing.
    fn at_fraction(&self, s: f64) -> f64 {
        let a = self.arch.half_angle;
        if s == 0.0 {
            0.0
        } else if self.psi_1 == 0.0 {
            a * s
        } else {
            self.psi_1 + s * (a - self.psi_1)
        }
    }

    fn base_families(&self) -> (Vec<[f64; 2]>, Vec<f64>) {
        let a = self.arch.half_angle;
        let mut fam = if self.psi_1 == 0.0 {
            vec![[-a, a]]
        } else {
            vec![[-a, -self.psi_1], [self.psi_1, a]]
        };
        let mut iso = Vec::new();
        if self.psi_1 > 0.0 && self.form.joints == JointOrientation::Radial {
            iso.push(0.0);
            if self.shared_apex {
                iso.push(0.0f64.next_up());
            }
        }
        if self.form.joints == JointOrientation::Vertical {
            iso.push(self.support_param(-1.0));
            iso.push(self.support_param(1.0));
        }
        if let Some((p, _)) = self.point {
            fam = split(&fam, p);
        }
        (fam, iso)
    }
}

/// Splits the families at a point load at `a`, so that each side of the load is a closed
/// family: the joint at `a` carries the load on its crown side.
fn split(fam: &[[f64; 2]], a: f64) -> Vec<[f64; 2]> {
    let mut out = Vec::with_capacity(fam.len() + 1);
    for &[lo, hi] in fam {
        // The first parameter on the far side of the load from the crown … and the last one
        // on the crown side, as an ordered cut (left part ends at `l`, right part starts at
        // `r`).
        let (l, r) = if a > 0.0 {
            (a.next_down(), a)
        } else if a < 0.0 {
            (a, a.next_up())
        } else {
            (0.0, 0.0f64.next_up())
        };
        if lo <= l && r <= hi {
            out.push([lo, l]);
            out.push([r, hi]);
        } else {
            out.push([lo, hi]);
        }
    }
    out
}

impl ArchGeometry for ArchModel {
    fn half_angle(&self) -> f64 {
        self.arch.half_angle
    }

    fn joint(&self, theta: f64) -> Joint {
        self.joint_at(theta)
    }

    fn dead_load(&self, theta: f64) -> Resultant {
        let [w, sx, _] = self.weight_moments(theta);
        Resultant {
            fx: 0.0,
            fy: -w,
            m: -sx,
        }
    }

    fn live_load(&self, theta: f64) -> Resultant {
        match self.load {
            Load::SelfWeight => Resultant::default(),
            Load::Horizontal => {
                let [w, _, sy] = self.weight_moments(theta);
                Resultant {
                    fx: w,
                    fy: 0.0,
                    m: -sy,
                }
            }
            Load::Point { .. } => {
                let Some((a, x)) = self.point else {
                    return Resultant::default();
                };
                let sign = if theta > 0.0 && 0.0 <= a && a <= theta {
                    1.0
                } else if theta < 0.0 && theta <= a && a < 0.0 {
                    -1.0
                } else {
                    0.0
                };
                Resultant {
                    fx: 0.0,
                    fy: -2.0 * sign,
                    m: -2.0 * sign * x[0],
                }
            }
        }
    }

    fn relaxed(&self, theta: f64, condition: Condition) -> bool {
        if !self.shared_apex {
            return false;
        }
        if theta == 0.0 {
            condition == Condition::SlideOutward
        } else if theta == 0.0f64.next_up() {
            condition != Condition::SlideOutward
        } else {
            false
        }
    }

    fn discrete_joints(&self) -> Option<Vec<f64>> {
        let Discretisation::Voussoirs(n) = self.arch.joints else {
            return None;
        };
        let a = self.arch.half_angle;
        let mut joints: Vec<f64> = (0..=n)
            .map(|j| {
                if j == 0 {
                    self.support_param(-1.0)
                } else if j == n {
                    self.support_param(1.0)
                } else if self.psi_1 == 0.0 {
                    -a + 2.0 * a * f64::from(j) / f64::from(n)
                } else {
                    let s = -1.0 + 2.0 * f64::from(j) / f64::from(n);
                    self.at_fraction(s.abs()).copysign(s)
                }
            })
            .collect();
        if self.shared_apex && joints.contains(&0.0) {
            joints.push(0.0f64.next_up());
            joints.sort_by(f64::total_cmp);
        }
        Some(joints)
    }

    fn families(&self) -> Vec<[f64; 2]> {
        self.base_families().0
    }

    fn isolated_joints(&self) -> Vec<f64> {
        self.base_families().1
    }

    fn angle_deg(&self, theta: f64) -> f64 {
        let a = self.arch.half_angle;
        if theta.abs() > a {
            a.to_degrees().copysign(theta)
        } else if self.form.joints == JointOrientation::Vertical && theta.abs() == self.psi_1 {
            // The vertical joints through the intrados apex are the crown joint.
            0.0
        } else {
            theta.to_degrees()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::circular::CircularArch;
    use crate::analysis::statics::joint_rows;
    use crate::model::Shape;
    use approx::{abs_diff_eq, assert_abs_diff_eq};

    fn arch(k: f64, alpha: f64, weight: WeightModel, joints: Discretisation) -> Arch {
        Arch::new(k, alpha, weight, joints).unwrap()
    }

    fn form(e: f64, joints: JointOrientation) -> ArchForm {
        ArchForm {
            shape: if e == 0.0 {
                Shape::Circular
            } else {
                Shape::Pointed { eccentricity: e }
            },
            joints,
        }
    }

    /// Area and first moments of the right half region up to joint θ by brute-force
    /// quadrature over a fine polar grid about C (midpoint rule in ρ, Gauss–Legendre would
    /// be overkill): a check of the Green's-theorem closed forms.
    fn quadrature(m: &ArchModel, theta: f64) -> [f64; 3] {
        let (k, d) = (m.arch.k, m.d);
        let j = m.joint_at(theta);
        let (i, e) = (j.intrados, j.extrados);
        let inside = |x: f64, y: f64| {
            // Right of the crown plane, left of the joint line I→E (crossing z ≥ 0).
            let z = (e[0] - i[0]) * (y - i[1]) - (e[1] - i[1]) * (x - i[0]);
            x >= 0.0 && z >= 0.0
        };
        let (nr, np) = (400, 4000);
        let mut s = [0.0; 3];
        for a in 0..nr {
            let rho = 1.0 + (k - 1.0) * (a as f64 + 0.5) / nr as f64;
            for b in 0..np {
                let psi = std::f64::consts::FRAC_PI_2 * (b as f64 + 0.5) / np as f64;
                let (x, y) = (-d + rho * psi.sin(), rho * psi.cos());
                if inside(x, y) {
                    let da = rho * (k - 1.0) / nr as f64 * std::f64::consts::FRAC_PI_2 / np as f64;
                    s[0] += da;
                    s[1] += x * da;
                    s[2] += y * da;
                }
            }
        }
        s
    }

    #[test]
    fn green_moments_match_quadrature() {
        for (e, joints, theta) in [
            (0.3, JointOrientation::Radial, 1.0),
            (0.3, JointOrientation::Vertical, 1.2),
            (0.0, JointOrientation::Vertical, 0.7),
        ] {
            let a = arch(1.2, 90.0, WeightModel::Annular, Discretisation::Continuum);
            let m = ArchModel::new(a, form(e, joints), Load::SelfWeight).unwrap();
            let exact = m.region(&m.half_joint(theta)).0;
            let q = quadrature(&m, theta);
            for c in 0..3 {
                assert!(
                    abs_diff_eq!(exact[c], q[c], epsilon = 2e-3 * exact[0]),
                    "e = {e}, {joints:?}: {exact:?} vs {q:?}"
                );
            }
        }
    }

    #[test]
    fn semicircle_by_green_equals_the_closed_forms() {
        // Force the Green route on the circular radial arch by asking for the region.
        for weight in [WeightModel::Annular] {
            let a = arch(1.3, 90.0, weight, Discretisation::Continuum);
            let m = ArchModel::new(a, ArchForm::default(), Load::SelfWeight).unwrap();
            for theta in [0.0, 0.1, 0.7, 1.5, FRAC_PI_2] {
                let raw = m.region(&m.half_joint(theta)).0.map(|v| v / m.w_half);
                let cf = m.weight_moments(theta);
                for c in 0..3 {
                    assert!(
                        abs_diff_eq!(raw[c], cf[c], epsilon = 1e-14),
                        "{theta}: {raw:?} vs {cf:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn circular_radial_rows_equal_circular_arch_rows() {
        for weight in [WeightModel::Annular, WeightModel::Centreline] {
            let a = arch(1.25, 75.0, weight, Discretisation::Continuum);
            let m = ArchModel::new(a, ArchForm::default(), Load::SelfWeight).unwrap();
            let c = CircularArch::new(a);
            for theta in [-1.3, -0.4, 0.0, 0.2, 1.3] {
                let (r1, r2) = (joint_rows(&m, theta, 0.4), joint_rows(&c, theta, 0.4));
                for (x, y) in r1.iter().zip(&r2) {
                    assert_eq!(x.condition, y.condition);
                    assert_abs_diff_eq!(x.b, y.b, epsilon = 1e-15);
                    assert_abs_diff_eq!(x.a_lambda, y.a_lambda, epsilon = 1e-15);
                    for i in 0..3 {
                        assert_abs_diff_eq!(x.a[i], y.a[i], epsilon = 1e-15);
                    }
                }
            }
        }
    }

    #[test]
    fn centreline_pointed_weight_is_the_centreline_length() {
        // Half the centreline of a pointed arch runs from ψ_c0 = asin e to α.
        let a = arch(
            1.2,
            90.0,
            WeightModel::Centreline,
            Discretisation::Continuum,
        );
        let m = ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::SelfWeight).unwrap();
        assert_abs_diff_eq!(
            m.w_half,
            0.2 * 1.1 * (FRAC_PI_2 - 0.5f64.asin()),
            epsilon = 1e-15
        );
        assert_abs_diff_eq!(m.weight_moments(FRAC_PI_2)[0], 1.0, epsilon = 1e-15);
        assert_eq!(m.weight_moments(0.0), [0.0, 0.0, 0.0]);
    }

    #[test]
    fn total_weight_and_continuity() {
        for (e, joints) in [
            (0.0, JointOrientation::Vertical),
            (0.4, JointOrientation::Radial),
            (0.4, JointOrientation::Vertical),
        ] {
            let a = arch(1.15, 90.0, WeightModel::Annular, Discretisation::Continuum);
            let m = ArchModel::new(a, form(e, joints), Load::SelfWeight).unwrap();
            // The support carries the whole half weight; the crown nothing.
            let s = m.support_param(1.0);
            assert_abs_diff_eq!(m.weight_moments(s)[0], 1.0, epsilon = 1e-14);
            assert_abs_diff_eq!(m.weight_moments(-s)[0], -1.0, epsilon = 1e-14);
            assert!(m.weight_moments(0.0).iter().all(|v| v.abs() < 1e-15));
            // The first joint of the family next to the crown: a vertical one is the crown
            // joint itself; a radial one of a pointed arch encloses the keystone wedge.
            let w1 = m.weight_moments(m.psi_1.max(1e-300))[0];
            if joints == JointOrientation::Vertical {
                assert!(abs_diff_eq!(w1, 0.0, epsilon = 1e-14), "{w1}");
            } else {
                assert!(w1 > 0.0);
            }
        }
    }

    #[test]
    fn point_load_belongs_to_the_crown_side_of_its_joint() {
        let a = arch(1.3, 90.0, WeightModel::Annular, Discretisation::Continuum);
        let m = ArchModel::new(a, ArchForm::default(), Load::Point { at_deg: 30.0 }).unwrap();
        let at = 30f64.to_radians();
        assert_eq!(m.live_load(at).fy, -2.0);
        assert_eq!(m.live_load(at.next_down()).fy, 0.0);
        assert_eq!(
            m.families(),
            vec![[-FRAC_PI_2, at.next_down()], [at, FRAC_PI_2]]
        );
        let m = ArchModel::new(a, ArchForm::default(), Load::Point { at_deg: -30.0 }).unwrap();
        assert_eq!(m.live_load(-at).fy, 2.0);
        assert_eq!(m.live_load((-at).next_up()).fy, 0.0);
        let m = ArchModel::new(a, ArchForm::default(), Load::Point { at_deg: 0.0 }).unwrap();
        assert_eq!(m.live_load(0.0).fy, 0.0);
        assert_eq!(m.live_load(1e-300).fy, -2.0);
        assert_eq!(m.live_load(-1e-300).fy, 0.0);
        // Its moment is that of P at the extrados point.
        let x = 1.3 * at.sin();
        let m = ArchModel::new(a, ArchForm::default(), Load::Point { at_deg: 30.0 }).unwrap();
        assert_abs_diff_eq!(m.live_load(1.0).m, -2.0 * x, epsilon = 1e-15);
    }

    #[test]
    fn invalid_forms_are_refused() {
        let a = arch(3.2, 90.0, WeightModel::Annular, Discretisation::Continuum);
        assert!(matches!(
            ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::SelfWeight),
            Err(FormError::PointedTooThick { .. })
        ));
        let a = arch(1.2, 120.0, WeightModel::Annular, Discretisation::Continuum);
        assert!(matches!(
            ArchModel::new(a, form(0.0, JointOrientation::Vertical), Load::SelfWeight),
            Err(FormError::VerticalBeyondQuadrant(_))
        ));
        let a = arch(1.2, 60.0, WeightModel::Annular, Discretisation::Continuum);
        assert!(matches!(
            ArchModel::new(a, ArchForm::default(), Load::Point { at_deg: 61.0 }),
            Err(FormError::LoadOutside { .. })
        ));
        let a = arch(1.2, 90.0, WeightModel::Annular, Discretisation::Continuum);
        assert!(matches!(
            ArchModel::new(
                a,
                form(0.5, JointOrientation::Radial),
                Load::Point { at_deg: 10.0 }
            ),
            Err(FormError::LoadInsideKeystone { .. })
        ));
    }

    #[test]
    fn pointed_margins_converge_even_without_friction() {
        // At φ = 0 the sliding rows pin the tangential force to zero; the programme solver's
        // residual on rows it already holds must not read as a missing joint.
        use crate::analysis::general::{self, Outcome, RowSet, Settings};
        let a = arch(1.3, 90.0, WeightModel::Annular, Discretisation::Continuum);
        let m = ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::SelfWeight).unwrap();
        for phi in [0.0, 0.1, 0.6, FRAC_PI_2] {
            for set in [RowSet::Rotational, RowSet::Sliding, RowSet::All] {
                let r = general::margin(&m, phi, set, &Settings::default());
                assert_eq!(r.outcome, Outcome::Solved, "φ = {phi}, {set:?}");
            }
        }
    }

    #[test]
    fn load_factor_programmes_agree_with_clarabel() {
        use crate::analysis::general::{self, LinearRows, OBJECTIVE, RowSet, Settings};
        use crate::analysis::lp;
        use clarabel::algebra::CscMatrix;
        use clarabel::solver::{
            DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
        };
        let a = arch(
            1.3,
            90.0,
            WeightModel::Annular,
            Discretisation::Voussoirs(64),
        );
        for (f, load, phi) in [
            (ArchForm::default(), Load::Horizontal, 0.6f64.atan()),
            (ArchForm::default(), Load::Point { at_deg: 22.5 }, FRAC_PI_2),
            (form(0.3, JointOrientation::Vertical), Load::Horizontal, 1.4),
            (
                form(0.3, JointOrientation::Radial),
                Load::Point { at_deg: -45.0 },
                0.7,
            ),
        ] {
            let g = ArchModel::new(a, f, load).unwrap();
            let thetas = g.discrete_joints().unwrap();
            let rows = LinearRows::load_factor(&g, &thetas, phi, RowSet::All);
            let ours =
                lp::maximise(&OBJECTIVE, &rows.a, &rows.b, &lp::Settings::default()).unwrap();
            assert_eq!(ours.status, lp::Status::Optimal, "{f:?} {load:?}");
            let p = CscMatrix::<f64>::zeros((4, 4));
            let q = OBJECTIVE.map(|c| -c);
            let am = CscMatrix::from(rows.a.iter());
            let cones = [NonnegativeConeT(rows.b.len())];
            let settings = DefaultSettingsBuilder::default()
                .verbose(false)
                .tol_gap_abs(1e-11)
                .tol_gap_rel(1e-11)
                .tol_feas(1e-11)
                .build()
                .unwrap();
            let mut solver = DefaultSolver::new(&p, &q, &am, &rows.b, &cones, settings).unwrap();
            solver.solve();
            assert_eq!(solver.solution.status, SolverStatus::Solved);
            let oracle = solver.solution.x[3];
            assert!(
                abs_diff_eq!(ours.x[3], oracle, epsilon = 1e-7 * (1.0 + oracle.abs())),
                "{f:?} {load:?}: {} vs {oracle}",
                ours.x[3]
            );
            // The analysis solves the same programme.
            let lf = general::load_factor(&g, phi, &Settings::default());
            assert!(
                abs_diff_eq!(lf.lambda, ours.x[3], epsilon = 1e-12),
                "{} vs {}",
                lf.lambda,
                ours.x[3]
            );
        }
    }

    #[test]
    fn discrete_joints_of_each_form() {
        let a = arch(
            1.2,
            90.0,
            WeightModel::Annular,
            Discretisation::Voussoirs(4),
        );
        let radial = ArchModel::new(a, ArchForm::default(), Load::SelfWeight).unwrap();
        let j = radial.discrete_joints().unwrap();
        assert_eq!(j, CircularArch::new(a).discrete_joints().unwrap());
        let v = ArchModel::new(a, form(0.0, JointOrientation::Vertical), Load::SelfWeight).unwrap();
        let jv = v.discrete_joints().unwrap();
        assert!(jv[0] < -FRAC_PI_2 && jv[4] > FRAC_PI_2 && jv[2] == 0.0);
        assert_eq!(v.angle_deg(jv[4]), 90.0);
        let p = ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::SelfWeight).unwrap();
        let jp = p.discrete_joints().unwrap();
        let psi1 = p.first_joint();
        assert_abs_diff_eq!(jp[3], psi1 + 0.5 * (FRAC_PI_2 - psi1), epsilon = 1e-15);
        assert_eq!(jp[2], 0.0);
    }
}
