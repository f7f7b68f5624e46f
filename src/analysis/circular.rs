//! Closed forms for the circular arch with radial joints under self-weight.
//!
//! Lengths over r (so R = K), forces over the half weight W_half, moments over W_half·r.
//! Between the crown and joint θ ∈ [0, α] the weight is w(θ) = θ/α and its first moment
//! about the vertical through the centre is s(θ) = ρ_s(1 − cos θ)/α, where ρ_s is the radius
//! at which the weight of a radial slice acts ([`Arch::weight_radius`]).
//!
//! Symmetric loading (paper §2.1): the crown carries a horizontal thrust h = H/W_half at
//! height y_P; with m = h·y_P the line of thrust lies inside joint θ iff
//!
//! L(θ, h) = h cos θ + w sin θ − s ≤ m ≤ K(h cos θ + w sin θ) − s = U(θ, h),
//!
//! the linear form of eqs. (2a, 2b). Both are unimodal in θ on (0, π):
//! ∂L/∂θ = (sin θ/α)(θ cot θ − c_L) with c_L = hα + ρ_s − 1, so L has a single maximum at
//! θ cot θ = c_L and U, whose derivative has the same form, a single maximum and hence its
//! minimum at an end joint. The sliding rows (eqs. 4a, 4b) are
//! h sin(θ − φ) ≤ w cos(θ − φ) and h sin(θ + φ) ≥ w cos(θ + φ).

use super::settings::GeometrySettings;
use super::statics::{ArchGeometry, Joint, Resultant};
use crate::model::{Arch, Discretisation};

/// The numerical thresholds of the closed forms: series switches and rounding zeros, fixed
/// for every arch (see [`GeometrySettings`]).
const GEOMETRY: GeometrySettings = GeometrySettings::DEFAULT;
/// Floor of the bracket scale in the Newton stopping test, so that a zero end does not make
/// the test impossible.
const MIN_BRACKET_SCALE: f64 = 1e-300;

/// The circular arch as a general [`ArchGeometry`] (radial joints, self-weight).
#[derive(Debug, Clone, Copy)]
pub struct CircularArch {
    /// The arch.
    pub arch: Arch,
    rho_s: f64,
}

impl CircularArch {
    /// Wraps an arch.
    pub fn new(arch: Arch) -> Self {
        CircularArch {
            arch,
            rho_s: arch.weight_radius(),
        }
    }

    /// Radius at which the weight acts, over r.
    pub fn weight_radius(&self) -> f64 {
        self.rho_s
    }
}

/// θ_i = α(2i + p)/N for the joints of the right half (p = N mod 2), or `None`.
pub fn half_joint(n: u32, alpha: f64, i: u32) -> f64 {
    alpha * f64::from(2 * i + n % 2) / f64::from(n)
}

impl ArchGeometry for CircularArch {
    fn half_angle(&self) -> f64 {
        self.arch.half_angle
    }

    fn joint(&self, theta: f64) -> Joint {
        let (s, c) = theta.sin_cos();
        Joint {
            theta,
            intrados: [s, c],
            extrados: [self.arch.k * s, self.arch.k * c],
        }
    }

    fn dead_load(&self, theta: f64) -> Resultant {
        let a = self.arch.half_angle;
        Resultant {
            fx: 0.0,
            fy: -theta / a,
            m: -self.rho_s * (1.0 - theta.cos()) / a,
        }
    }

    fn discrete_joints(&self) -> Option<Vec<f64>> {
        match self.arch.joints {
            Discretisation::Continuum => None,
            Discretisation::Voussoirs(n) => {
                let a = self.arch.half_angle;
                Some(
                    (0..=n)
                        .map(|j| -a + 2.0 * a * f64::from(j) / f64::from(n))
                        .collect(),
                )
            }
        }
    }
}

/// θ cot θ, accurate near 0.
pub fn theta_cot_theta(t: f64) -> f64 {
    if t.abs() < GEOMETRY.series_switch {
        let t2 = t * t;
        1.0 - t2 / 3.0 - t2 * t2 / 45.0
    } else {
        t * t.cos() / t.sin()
    }
}

/// The root in (0, π) of θ cot θ = c (c < 1), by safeguarded Newton; 0 when c ≥ 1.
pub fn solve_theta_cot(c: f64) -> f64 {
    if c >= 1.0 {
        return 0.0;
    }
    // q(θ) = θ cot θ − c is strictly decreasing from 1 − c > 0 to −∞ on (0, π).
    let (mut lo, mut hi) = (0.0_f64, std::f64::consts::PI);
    // Initial guess: small-angle series for c near 1, else midpoint-ish.
    let mut t = if c > 0.9 {
        (3.0 * (1.0 - c)).sqrt()
    } else {
        0.5 * (lo + hi)
    };
    for _ in 0..GEOMETRY.max_newton_steps {
        let q = theta_cot_theta(t) - c;
        if q > 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        if hi - lo < 4.0 * f64::EPSILON * hi.max(MIN_BRACKET_SCALE) {
            break;
        }
        let s = t.sin();
        let dq = if t.abs() < GEOMETRY.series_switch {
            -2.0 * t / 3.0
        } else {
            (s * t.cos() - t) / (s * s)
        };
        let mut next = t - q / dq;
        if !(next > lo && next < hi) || dq == 0.0 {
            next = 0.5 * (lo + hi);
        }
        if (next - t).abs() <= 2.0 * f64::EPSILON * t.abs() {
            t = next;
            break;
        }
        t = next;
    }
    t
}

/// Which bound of the thrust a sliding row gives, and the bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SlidingBound {
    /// h ≤ value.
    Upper(f64),
    /// h ≥ value.
    Lower(f64),
    /// Always satisfied.
    Free,
    /// Never satisfied.
    Infeasible,
}

/// The bound on h from a row a·h ≤ b.
fn bound_from_row(a: f64, b: f64) -> SlidingBound {
    // Coefficients are sines of angles in [0, 2π): below this they are rounding noise of an
    // exact zero (θ = φ or θ + φ = π), where the row reads 0 ≤ b.
    let zero = GEOMETRY.tol_zero_coefficient;
    let a = if a.abs() < zero { 0.0 } else { a };
    if a > 0.0 {
        SlidingBound::Upper(b / a)
    } else if a < 0.0 {
        SlidingBound::Lower(b / a)
    } else if b >= 0.0 {
        SlidingBound::Free
    } else {
        SlidingBound::Infeasible
    }
}

/// The closed forms of the symmetric problem for one arch (K, α, weight model, joints).
#[derive(Debug, Clone, Copy)]
pub struct SymmetricCircular {
    /// K = R/r.
    pub k: f64,
    /// α in radians.
    pub alpha: f64,
    /// ρ_s over r.
    pub rho_s: f64,
    /// Voussoir count, `None` for the continuum.
    pub voussoirs: Option<u32>,
}

impl SymmetricCircular {
    /// The symmetric model of an arch.
    pub fn new(arch: &Arch) -> Self {
        SymmetricCircular {
            k: arch.k,
            alpha: arch.half_angle,
            rho_s: arch.weight_radius(),
            voussoirs: arch.joints.voussoirs(),
        }
    }

    /// Weight fraction w(θ) = W(θ)/W_half.
    pub fn w(&self, theta: f64) -> f64 {
        theta / self.alpha
    }

    /// First moment s(θ) = S(θ)/(W_half·r).
    pub fn s(&self, theta: f64) -> f64 {
        self.rho_s * (1.0 - theta.cos()) / self.alpha
    }

    /// L(θ, h): the crown moment m at which the line of thrust touches the intrados at θ
    /// (eq. 2a in linear form).
    pub fn intrados(&self, theta: f64, h: f64) -> f64 {
        let (s, c) = theta.sin_cos();
        h * c + self.w(theta) * s - self.s(theta)
    }

    /// U(θ, h): the crown moment m at which the line of thrust touches the extrados at θ
    /// (eq. 2b in linear form).
    pub fn extrados(&self, theta: f64, h: f64) -> f64 {
        let (s, c) = theta.sin_cos();
        self.k * (h * c + self.w(theta) * s) - self.s(theta)
    }

    /// Number of joints in the right half (crown included when it is a joint).
    pub fn half_joint_count(&self) -> Option<u32> {
        self.voussoirs.map(|n| n / 2 + 1)
    }

    /// Angle of joint i of the right half.
    pub fn joint_angle(&self, i: u32) -> f64 {
        match self.voussoirs {
            None => 0.0,
            Some(n) => half_joint(n, self.alpha, i),
        }
    }

    /// All joints of the right half, in increasing angle (for the continuum: a sampling).
    pub fn half_joints(&self) -> Vec<f64> {
        match self.voussoirs {
            Some(n) => (0..n / 2 + 1)
                .map(|i| half_joint(n, self.alpha, i))
                .collect(),
            None => (0..=256)
                .map(|i| self.alpha * f64::from(i) / 256.0)
                .collect(),
        }
    }

    /// First and last joint of the right half.
    pub fn end_joints(&self) -> (f64, f64) {
        match self.voussoirs {
            None => (0.0, self.alpha),
            Some(n) => (half_joint(n, self.alpha, 0), self.alpha),
        }
    }

    /// The continuum maximiser of L(·, h) on [0, α].
    fn intrados_argmax_continuum(&self, h: f64) -> f64 {
        let c = h * self.alpha + self.rho_s - 1.0;
        solve_theta_cot(c).min(self.alpha)
    }

    /// max over joints of L(θ, h), with the maximising joint(s): (value, θ₁, θ₂) where
    /// θ₂ = θ₁ unless two joints tie.
    pub fn intrados_max(&self, h: f64) -> (f64, f64, f64) {
        let t = self.intrados_argmax_continuum(h);
        match self.voussoirs {
            None => (self.intrados(t, h), t, t),
            Some(n) => {
                let last = n / 2;
                let p = f64::from(n % 2);
                // θ_i = α(2i + p)/N  ⇒  i = (θN/α − p)/2.
                let x = (t * f64::from(n) / self.alpha - p) / 2.0;
                let i0 = if x <= 0.0 {
                    0
                } else {
                    (x.floor() as u32).min(last)
                };
                let i1 = (i0 + 1).min(last);
                let (t0, t1) = (self.joint_angle(i0), self.joint_angle(i1));
                let (l0, l1) = (self.intrados(t0, h), self.intrados(t1, h));
                if l0 > l1 {
                    (l0, t0, t0)
                } else if l1 > l0 {
                    (l1, t1, t1)
                } else {
                    (l0, t0, t1)
                }
            }
        }
    }

    /// min over joints of U(θ, h): attained at the first or the last joint of the half.
    /// Returns (value, slope dU/dh of the minimiser, minimising joints).
    pub fn extrados_min(&self, h: f64) -> (f64, f64, [Option<f64>; 2]) {
        let (t0, t1) = self.end_joints();
        let (u0, u1) = (self.extrados(t0, h), self.extrados(t1, h));
        let (s0, s1) = (self.k * t0.cos(), self.k * t1.cos());
        if t0 == t1 {
            return (u0, s0, [Some(t0), None]);
        }
        let tie = (u0 - u1).abs() <= GEOMETRY.tol_tie * (1.0 + u0.abs());
        if tie {
            (u0.min(u1), s0.min(s1), [Some(t0), Some(t1)])
        } else if u0 < u1 {
            (u0, s0, [Some(t0), None])
        } else {
            (u1, s1, [None, Some(t1)])
        }
    }

    /// Φ(h) = min_θ U − max_θ L: the rotational margin at thrust h (concave in h). H^r is
    /// {h : Φ(h) ≥ 0}.
    pub fn rotational_margin(&self, h: f64) -> f64 {
        self.extrados_min(h).0 - self.intrados_max(h).0
    }

    /// A supergradient of Φ at h (non-increasing in h).
    pub fn rotational_slope(&self, h: f64) -> f64 {
        let (_, su, _) = self.extrados_min(h);
        let (_, t0, t1) = self.intrados_max(h);
        // Use the larger L slope at a tie (right derivative of the max).
        su - t0.cos().max(t1.cos())
    }

    /// Slope of Φ as h → +∞ and as h → −∞ (for unbounded domains).
    pub fn rotational_asymptotic_slopes(&self) -> (f64, f64) {
        let (t0, t1) = self.end_joints();
        // h → +∞: L is maximal at the first joint, U minimal at the joint with the smaller cos.
        let plus = self.k * t0.cos().min(t1.cos()) - t0.cos();
        // h → −∞: L maximal at the last joint (θ* → α), U minimal at the larger cos.
        let minus = self.k * t0.cos().max(t1.cos()) - t1.cos();
        (plus, minus)
    }

    /// The sliding rows at joint θ for friction angle φ, as bounds on h (eqs. 4a, 4b).
    pub fn sliding_bounds(&self, theta: f64, phi: f64) -> [SlidingBound; 2] {
        let w = self.w(theta);
        let (sm, cm) = (theta - phi).sin_cos();
        let (sp, cp) = (theta + phi).sin_cos();
        // h sin(θ − φ) ≤ w cos(θ − φ)   and   −h sin(θ + φ) ≤ −w cos(θ + φ)
        [bound_from_row(sm, w * cm), bound_from_row(-sp, -w * cp)]
    }

    /// The interior joint where the lower sliding bound w cot(θ + φ) peaks: the root of
    /// sin(2(θ + φ))/2 = θ on (0, π/2 − φ); `None` when φ = π/2.
    pub fn sliding_peak(&self, phi: f64) -> Option<f64> {
        let top = std::f64::consts::FRAC_PI_2 - phi;
        if top <= 0.0 {
            return None;
        }
        let g = |t: f64| 0.5 * (2.0 * (t + phi)).sin() - t;
        super::roots::brent(g, 0.0, top, GEOMETRY.tol_sliding_peak)
    }

    /// Candidate joints for the extreme sliding bounds: the end joints and the joints at or
    /// next to the peak of w cot(θ + φ) (both bound functions are monotone elsewhere).
    pub fn sliding_candidates(&self, phi: f64) -> Vec<f64> {
        let (t0, t1) = self.end_joints();
        let mut c = vec![t0, t1];
        if let Some(p) = self.sliding_peak(phi) {
            match self.voussoirs {
                None => {
                    if p < self.alpha {
                        c.push(p)
                    }
                }
                Some(n) => {
                    let last = n / 2;
                    let x = (p * f64::from(n) / self.alpha - f64::from(n % 2)) / 2.0;
                    let i0 = if x <= 0.0 {
                        0
                    } else {
                        (x.floor() as u32).min(last)
                    };
                    c.push(self.joint_angle(i0));
                    c.push(self.joint_angle((i0 + 1).min(last)));
                }
            }
        }
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::{abs_diff_eq, assert_abs_diff_eq};

    #[test]
    fn theta_cot_root_is_inverse() {
        for c in [0.99, 0.5, 0.0, -1.0, -10.0, 0.999999999] {
            let t = solve_theta_cot(c);
            assert!(
                abs_diff_eq!(theta_cot_theta(t), c, epsilon = 1e-12),
                "c = {c}, t = {t}"
            );
        }
        assert_eq!(solve_theta_cot(1.0), 0.0);
    }

    #[test]
    fn closed_form_rows_match_the_general_rows() {
        use super::super::statics::{Condition, joint_rows};
        let arch = Arch::semicircular(1.3).unwrap();
        let geom = CircularArch::new(arch);
        let sym = SymmetricCircular::new(&arch);
        let phi = 0.4f64.atan();
        for &theta in &[0.0, 0.3, 1.0, std::f64::consts::FRAC_PI_2] {
            let rows = joint_rows(&geom, theta, phi);
            let h = 0.37;
            for m in [0.2, 0.45] {
                // Symmetric state: F0 = (h, 0), M0 = −m.
                let x = [h, 0.0, -m];
                let v_i = rows[0].violation(&x, 0.0);
                let v_e = rows[1].violation(&x, 0.0);
                assert_eq!(rows[0].condition, Condition::Intrados);
                // Intrados violated iff m < L; extrados violated iff m > U.
                assert_abs_diff_eq!(v_i, (sym.intrados(theta, h) - m), epsilon = 1e-14);
                assert_abs_diff_eq!(v_e, (m - sym.extrados(theta, h)), epsilon = 1e-14);
            }
        }
    }
}
