//! The geometry of a form: areas and first moments by Green's theorem, joints, families.

use super::loads::split;
use super::{ArchModel, HalfJoint, Moments};
use crate::analysis::statics::{Joint, Point};
use crate::model::{JointOrientation, WeightModel};

/// Antiderivatives (∫x dy, ∫x²/2 dy, −∫y²/2 dx) along the arc of radius ρ about (−d, 0) at
/// angle ψ (x = −d + ρ sin ψ, y = ρ cos ψ).
pub(super) fn arc_primitive(rho: f64, d: f64, psi: f64) -> Moments {
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
pub(super) fn segment(p: Point, q: Point) -> Moments {
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
    pub(super) fn circular_radial(&self) -> bool {
        self.d == 0.0 && self.form.joints == JointOrientation::Radial
    }

    pub(super) fn support(&self) -> HalfJoint {
        let a = self.arch.half_angle;
        HalfJoint {
            psi_i: a,
            psi_e: a,
            psi_c: a,
        }
    }

    /// The right-half joint at |θ|.
    pub(super) fn half_joint(&self, theta: f64) -> HalfJoint {
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

    pub(super) fn ends(&self, j: &HalfJoint) -> (Point, Point) {
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
    pub(super) fn region(&self, j: &HalfJoint) -> (Moments, Point, Point) {
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
    /// the resultants of [`crate::analysis::statics`]: for θ < 0 they are those of the mirrored region
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

    pub(super) fn joint_at(&self, theta: f64) -> Joint {
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
    pub(super) fn support_param(&self, side: f64) -> f64 {
        let a = self.arch.half_angle;
        match self.form.joints {
            JointOrientation::Radial => side * a,
            JointOrientation::Vertical => side * a.next_up(),
        }
    }

    /// The joints of the family over one half, from the crown outward, at fractions
    /// s ∈ [0, 1] of the half: s = 0 is the crown, s = 1 the springing.
    pub(super) fn at_fraction(&self, s: f64) -> f64 {
        let a = self.arch.half_angle;
        if s == 0.0 {
            0.0
        } else if self.psi_1 == 0.0 {
            a * s
        } else {
            self.psi_1 + s * (a - self.psi_1)
        }
    }

    pub(super) fn base_families(&self) -> (Vec<[f64; 2]>, Vec<f64>) {
        let a = self.arch.half_angle;
        let mut fam = if self.psi_1 == 0.0 {
            vec![[-a, a]]
        } else {
            vec![[-a, -self.psi_1], [self.psi_1, a]]
        };
        let mut iso = Vec::new();
        if self.psi_1 > 0.0 && self.form.joints == JointOrientation::Radial && !self.has_keystone()
        {
            iso.push(0.0);
            if self.shared_apex {
                iso.push(0.0f64.next_up());
            }
        }
        if self.form.joints == JointOrientation::Vertical {
            iso.push(self.support_param(-1.0));
            iso.push(self.support_param(1.0));
        }
        if let Some(patch) = self.patch {
            // The resultant is continuous with kinks at the ends: each side a family.
            for p in patch.ends.into_iter().flatten() {
                fam = split(&fam, p);
            }
        } else if let Some((p, _)) = self.point {
            fam = split(&fam, p);
        }
        (fam, iso)
    }
}
