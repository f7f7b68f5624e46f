//! The statics of a form under its load case: [`ArchGeometry`] for [`ArchModel`].

use super::{ArchModel, FormError, GEOMETRY};
use crate::analysis::statics::{ArchGeometry, Condition, Joint, Point, Resultant};
use crate::model::{Discretisation, JointOrientation, Load};
use std::f64::consts::FRAC_PI_2;

/// A point load spread uniformly over a horizontal length of the extrados.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Patch {
    /// The extrados x range it covers, over r (x = 0 at the crown).
    pub(super) x: [f64; 2],
    /// The joint parameters whose extrados ends are the patch's ends, where such joints
    /// exist (not over a keystone, nor over the springing wedge of a vertical-joint arch).
    pub(super) ends: [Option<f64>; 2],
}

impl ArchModel {
    /// The centre (parameter and extrados point, as [`ArchModel::point_position`] reports
    /// it) and the extent of a patch load: the load's width·L of the extrados, L the
    /// extrados span, centred on its position. Needs α ≤ 90° (where a vertical meets the
    /// extrados once) and the patch within the span.
    pub(super) fn place_patch(&self, load: Load) -> Result<((f64, Point), Patch), FormError> {
        let alpha = self.arch.half_angle;
        let half_span = self.arch.k * alpha.sin() - self.d;
        let (centre, width) = match load {
            Load::Point { at_deg, width } => (self.place_centre_deg(at_deg)?, width),
            Load::PointX { at_x, width } => (self.place_centre_x(at_x)?, width),
            Load::SelfWeight | Load::Horizontal => unreachable!("only a point load has a width"),
        };
        let at_x = 0.5 + 0.5 * centre.1[0] / half_span;
        let (from, to) = (at_x - 0.5 * width, at_x + 0.5 * width);
        let tol = GEOMETRY.tol_patch_span;
        if alpha > FRAC_PI_2 + GEOMETRY.tol_vertical_alpha || from < -tol || to > 1.0 + tol {
            return Err(FormError::PatchOffSpan {
                width,
                at_x,
                from,
                to,
                half_angle_deg: self.arch.half_angle_deg(),
            });
        }
        let x = [from, to].map(|f| ((2.0 * f - 1.0) * half_span).clamp(-half_span, half_span));
        let ends = x.map(|x| self.param_under(x));
        Ok((centre, Patch { x, ends }))
    }

    /// The extrados point at abscissa `x` (over r; |x| at most the half span, α ≤ 90°).
    pub fn extrados_above(&self, x: f64) -> Point {
        let k = self.arch.k;
        let s = ((x.abs() + self.d) / k).min(1.0);
        self.extrados_point(x.signum() * s.asin())
    }

    /// The centre of a patch given in degrees: the point a concentrated load there would
    /// take, or on a keystone-less pointed crown the extrados point at that angle.
    fn place_centre_deg(&self, at_deg: f64) -> Result<(f64, Point), FormError> {
        let a = at_deg.to_radians();
        match self.place_point(at_deg) {
            Err(FormError::LoadInsideKeystone { .. }) if a.abs() >= self.psi_e0 => {
                Ok((a, self.extrados_point(a)))
            }
            other => other,
        }
    }

    /// The centre of a patch given as x/L, as [`ArchModel::place_centre_deg`].
    fn place_centre_x(&self, at_x: f64) -> Result<(f64, Point), FormError> {
        match self.place_point_x(at_x) {
            Err(FormError::XInsideKeystone { at_deg, .. }) => {
                let a = at_deg.to_radians();
                Ok((a, self.extrados_point(a)))
            }
            other => other,
        }
    }

    /// The parameter of the joint whose extrados end lies at abscissa `x`, where one does.
    fn param_under(&self, x: f64) -> Option<f64> {
        let (k, alpha) = (self.arch.k, self.arch.half_angle);
        let side = if x < 0.0 { -1.0 } else { 1.0 };
        let s = x.abs() + self.d;
        let psi = match self.form.joints {
            JointOrientation::Radial => (s / k).min(1.0).asin(),
            JointOrientation::Vertical => (s <= alpha.sin()).then(|| s.asin())?,
        };
        let jointed = x == 0.0 || (psi >= self.psi_1 && psi <= alpha);
        jointed.then_some(side * psi)
    }

    /// The resultant (per unit λ) of the part of a patch load between the crown and joint
    /// θ: the share of the load over [0, x_θ], x_θ the abscissa of θ's extrados end,
    /// signed as the resultants of the parts on the left (∫ from 0 to θ).
    fn patch_resultant(&self, patch: &Patch, theta: f64) -> Resultant {
        if theta == 0.0 {
            return Resultant::default();
        }
        let [lo, hi] = patch.x;
        let xe = self.joint_at(theta).extrados[0];
        let (u, v, sign) = if theta > 0.0 {
            (lo.max(0.0), hi.min(xe), 1.0)
        } else {
            (lo.max(xe), hi.min(0.0), -1.0)
        };
        if v <= u {
            return Resultant::default();
        }
        let len = hi - lo;
        Resultant {
            fx: 0.0,
            fy: -2.0 * sign * (v - u) / len,
            m: -sign * (v * v - u * u) / len,
        }
    }

    /// The parameter a (radians) and the extrados point X of a point load at `at_deg`: the
    /// extrados end of the joint at a. On the keystone of a pointed arch with radial joints
    /// (0 < |a| < ψ₁, where no joint exists) X is the extrados point at angle |a| from its
    /// arc's centre, which needs |a| ≥ ψ_e, the angle of the extrados apex.
    pub(super) fn place_point(&self, at_deg: f64) -> Result<(f64, Point), FormError> {
        let alpha = self.arch.half_angle;
        let a = at_deg.to_radians();
        if !(a.abs() <= alpha * (1.0 + GEOMETRY.tol_joint_range)) {
            return Err(FormError::LoadOutside {
                at_deg,
                half_angle_deg: self.arch.half_angle_deg(),
            });
        }
        self.place_angle(a.clamp(-alpha, alpha), at_deg)
    }

    fn place_angle(&self, a: f64, at_deg: f64) -> Result<(f64, Point), FormError> {
        if a == 0.0 || a.abs() >= self.psi_1 {
            return Ok((a, self.joint_at(a).extrados));
        }
        let on_keystone = self.form.keystone && self.form.joints == JointOrientation::Radial;
        if !on_keystone {
            return Err(FormError::LoadInsideKeystone {
                at_deg,
                first_joint_deg: self.psi_1.to_degrees(),
            });
        }
        if a.abs() < self.psi_e0 {
            return Err(FormError::LoadOffExtrados {
                at_deg,
                apex_deg: self.psi_e0.to_degrees(),
                first_joint_deg: self.psi_1.to_degrees(),
            });
        }
        Ok((a, self.extrados_point(a)))
    }

    /// The extrados point at angle |a| from its arc's centre, on the side of a.
    fn extrados_point(&self, a: f64) -> Point {
        let (s, c) = a.abs().sin_cos();
        let k = self.arch.k;
        [(-self.d + k * s).copysign(a), k * c]
    }

    /// The parameter a and the extrados point X of a point load at x/L = `at_x`
    /// ([`ArchForm::extrados_at_x`]): radial joints take the joint through the point (or the
    /// keystone under it), vertical joints the vertical joint through it; a point beyond the
    /// vertical joint at α lies on the wedge against the radial support and takes the
    /// support's parameter.
    pub(super) fn place_point_x(&self, at_x: f64) -> Result<(f64, Point), FormError> {
        let (k, alpha) = (self.arch.k, self.arch.half_angle);
        let Some((side, x, psi)) = self.form.extrados_at_x(k, alpha, at_x) else {
            return Err(FormError::LoadOffSpan {
                at_x,
                half_angle_deg: self.arch.half_angle_deg(),
            });
        };
        if x == 0.0 {
            return Ok((0.0, self.joint_at(0.0).extrados));
        }
        match self.form.joints {
            JointOrientation::Radial => self
                .place_angle(side * psi, side * psi.to_degrees())
                .map_err(|e| match e {
                    FormError::LoadInsideKeystone {
                        first_joint_deg, ..
                    } => FormError::XInsideKeystone {
                        at_x,
                        at_deg: side * psi.to_degrees(),
                        first_joint_deg,
                    },
                    other => other,
                }),
            JointOrientation::Vertical => {
                let s = x.abs() + self.d;
                if s <= alpha.sin() {
                    let theta = side * s.asin();
                    Ok((theta, self.joint_at(theta).extrados))
                } else {
                    Ok((self.support_param(side), self.extrados_point(side * psi)))
                }
            }
        }
    }

    /// The point load's position as reported: degrees from the crown (the joint angle of
    /// its parameter, the angle at its arc's centre on a keystone) and x/L (`None` when
    /// α > 90°). `None` without a point load.
    pub fn point_position(&self) -> Option<(f64, Option<f64>)> {
        let (a, x) = self.point?;
        let alpha = self.arch.half_angle;
        let half_span = self.arch.k * alpha.sin() - self.d;
        let at_x = (alpha <= std::f64::consts::FRAC_PI_2).then(|| 0.5 + 0.5 * x[0] / half_span);
        Some((self.angle_deg(a), at_x))
    }
}

/// Splits the families at a point load at `a`, so that each side of the load is a closed
/// family: the joint at `a` carries the load on its crown side.
pub(super) fn split(fam: &[[f64; 2]], a: f64) -> Vec<[f64; 2]> {
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
            Load::Point { .. } | Load::PointX { .. } => {
                if let Some(patch) = &self.patch {
                    return self.patch_resultant(patch, theta);
                }
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

    fn mirror_symmetric(&self) -> bool {
        // Every form is symmetric; a live load is not (horizontal loads and point loads act
        // on one side), nor is an apex load shared freely between the halves.
        self.load == Load::SelfWeight && !self.shared_apex
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
            crate::analysis::statics::joint_angle_deg(theta)
        }
    }
}
