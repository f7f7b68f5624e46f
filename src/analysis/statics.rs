//! General statics of an arch of rigid blocks: joints, cumulative loads and the linear
//! conditions at every joint (paper eqs. 1 and 3).
//!
//! Conventions (docs/mechanics.md §1): origin at the centre, x right, y up, lengths over r. A joint is
//! named by a parameter θ (its angle from the crown for radial joints). The internal force F at
//! joint θ is the resultant the part left of θ exerts on the part to its right, with moment M
//! about the origin. With the crown force F₀ = (F_x, F_y) and moment M₀ as redundant unknowns
//! and a load factor λ,
//!
//! F(θ) = F₀ + C_d(θ) + λ C_l(θ),  M(θ) = M₀ + C_d^M(θ) + λ C_l^M(θ),
//!
//! where C(θ) is the resultant of the loads between the crown and θ, signed so that
//! C(θ) = ∫₀^θ dP for θ > 0 and −∫_θ^0 dP for θ < 0. Every condition is linear in
//! x = (F_x, F_y, M₀, λ).

/// A point of the plane, over r.
pub type Point = [f64; 2];

/// A force resultant with its moment about the origin, over W_half (and W_half·r).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Resultant {
    /// Horizontal component.
    pub fx: f64,
    /// Vertical component.
    pub fy: f64,
    /// Moment about the origin, counter-clockwise positive.
    pub m: f64,
}

impl Resultant {
    /// Sum of two resultants.
    pub fn plus(self, o: Resultant) -> Resultant {
        Resultant {
            fx: self.fx + o.fx,
            fy: self.fy + o.fy,
            m: self.m + o.m,
        }
    }

    /// The resultant scaled by `s`.
    pub fn scale(self, s: f64) -> Resultant {
        Resultant {
            fx: s * self.fx,
            fy: s * self.fy,
            m: s * self.m,
        }
    }
}

/// The geometry of one joint: its intrados and extrados points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// Parameter of the joint: the angle from the crown in radians for radial joints.
    pub theta: f64,
    /// Intrados end I.
    pub intrados: Point,
    /// Extrados end E.
    pub extrados: Point,
}

impl Joint {
    /// Unit vector along the joint, from intrados to extrados (n for radial joints).
    pub fn along(&self) -> [f64; 2] {
        let d = [
            self.extrados[0] - self.intrados[0],
            self.extrados[1] - self.intrados[1],
        ];
        let l = d[0].hypot(d[1]);
        [d[0] / l, d[1] / l]
    }

    /// Unit normal of the joint pointing from the left part into the right part
    /// (t = (cos θ, −sin θ) for radial joints).
    pub fn normal(&self) -> [f64; 2] {
        let a = self.along();
        [a[1], -a[0]]
    }

    /// Length of the joint (its thickness h).
    pub fn length(&self) -> f64 {
        (self.extrados[0] - self.intrados[0]).hypot(self.extrados[1] - self.intrados[1])
    }
}

/// What an arch model must provide for the general statics: joints and cumulative loads.
pub trait ArchGeometry {
    /// Half-embrace angle α in radians: joints lie in [−α, α].
    fn half_angle(&self) -> f64;
    /// The joint at parameter θ.
    fn joint(&self, theta: f64) -> Joint;
    /// Resultant of the dead load between the crown and θ, signed (see module docs).
    fn dead_load(&self, theta: f64) -> Resultant;
    /// Resultant of the live load (per unit λ) between the crown and θ; zero by default.
    fn live_load(&self, _theta: f64) -> Resultant {
        Resultant::default()
    }
    /// The joints of a discrete arch in increasing θ, `None` for a continuum.
    fn discrete_joints(&self) -> Option<Vec<f64>>;
    /// The potential joints of the continuum: closed intervals of θ, increasing and
    /// disjoint, over each of which the joints and loads vary continuously; default
    /// [−α, α]. A load concentrated at θ = a splits an interval into [.., a] and
    /// [next float after a, ..], so that both sides of the load are joints.
    fn families(&self) -> Vec<[f64; 2]> {
        let a = self.half_angle();
        vec![[-a, a]]
    }
    /// Joints of the continuum outside [`ArchGeometry::families`] (e.g. supports that are
    /// not members of a family); default none.
    fn isolated_joints(&self) -> Vec<f64> {
        Vec::new()
    }
    /// The angle that names joint θ in results, degrees from the crown, positive to the
    /// right; default θ itself.
    fn angle_deg(&self, theta: f64) -> f64 {
        joint_angle_deg(theta)
    }

    /// True when the row of `condition` at `theta` is left out (always satisfied): the two
    /// sides of a load whose split between two parts is free keep one Coulomb row each
    /// ([`crate::analysis::forms::ArchModel::with_shared_apex`]).
    fn relaxed(&self, _theta: f64, _condition: Condition) -> bool {
        false
    }

    /// True when the arch, its joints and its loads are mirror images about the crown's
    /// vertical x = 0, joint θ of the right half matching joint −θ of the left: then every
    /// admissible state has a mirror image, and their mean, with zero crown shear, is
    /// admissible too. Default false.
    fn mirror_symmetric(&self) -> bool {
        false
    }
}

/// Which condition a linear row expresses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Condition {
    /// Line of thrust not inside the intrados: M_I ≤ 0.
    Intrados,
    /// Line of thrust not outside the extrados: M_E ≥ 0.
    Extrados,
    /// T ≤ μN: the crown-side part is about to move outward.
    SlideOutward,
    /// −T ≤ μN: the crown-side part is about to move inward.
    SlideInward,
}

impl Condition {
    /// The four conditions at a joint.
    pub const ALL: [Condition; 4] = [
        Condition::Intrados,
        Condition::Extrados,
        Condition::SlideOutward,
        Condition::SlideInward,
    ];

    /// True for the rotational (no-tension) conditions of eq. (1).
    pub fn is_rotational(self) -> bool {
        matches!(self, Condition::Intrados | Condition::Extrados)
    }
}

/// One linear condition a·(F_x, F_y, M₀) + a_λ λ ≤ b at a joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Joint parameter θ (radians).
    pub theta: f64,
    /// The condition.
    pub condition: Condition,
    /// Coefficients of (F_x, F_y, M₀).
    pub a: [f64; 3],
    /// Coefficient of λ.
    pub a_lambda: f64,
    /// Right-hand side.
    pub b: f64,
}

impl Row {
    /// a·x + a_λ λ − b: positive when violated.
    pub fn violation(&self, x: &[f64; 3], lambda: f64) -> f64 {
        self.a[0] * x[0] + self.a[1] * x[1] + self.a[2] * x[2] + self.a_lambda * lambda - self.b
    }
}

/// The linear forms of the four conditions at joint θ, given the friction angle φ.
///
/// With I, E the joint ends, τ the unit vector along the joint and ν its normal:
/// - intrados (eq. 1): M − I×F ≤ 0;
/// - extrados (eq. 1): −(M − E×F) ≤ 0;
/// - sliding (eq. 3), scaled by cos φ so that μ = ∞ stays finite:
///   cos φ (F·τ) − sin φ (F·ν) ≤ 0 and −cos φ (F·τ) − sin φ (F·ν) ≤ 0.
pub fn joint_rows<G: ArchGeometry + ?Sized>(geom: &G, theta: f64, phi: f64) -> [Row; 4] {
    JointFrame::of(geom, theta).rows(phi)
}

/// What the rows of one joint need whatever the friction angle: the joint, the dead and live
/// loads on the part between it and the crown, and which conditions the geometry relaxes. A
/// path over μ builds each joint's frame once and its rows at every φ from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointFrame {
    /// Joint parameter θ (radians).
    pub theta: f64,
    /// The joint.
    pub joint: Joint,
    /// The dead load between the crown and θ.
    pub dead: Resultant,
    /// The live load (per unit λ) between the crown and θ.
    pub live: Resultant,
    /// The conditions left out at this joint, in [`Condition::ALL`] order.
    pub relaxed: [bool; 4],
}

impl JointFrame {
    /// The frame of joint θ of `geom`.
    pub fn of<G: ArchGeometry + ?Sized>(geom: &G, theta: f64) -> Self {
        JointFrame {
            theta,
            joint: geom.joint(theta),
            dead: geom.dead_load(theta),
            live: geom.live_load(theta),
            relaxed: Condition::ALL.map(|c| geom.relaxed(theta, c)),
        }
    }

    /// The four rows at friction angle φ ([`joint_rows`]).
    pub fn rows(&self, phi: f64) -> [Row; 4] {
        let (theta, j, d, l) = (self.theta, &self.joint, self.dead, self.live);
        let cross = |p: Point, fx: f64, fy: f64| p[0] * fy - p[1] * fx;
        let (ix, iy) = (j.intrados[0], j.intrados[1]);
        let (ex, ey) = (j.extrados[0], j.extrados[1]);
        // M − I×F with F = F0 + C, M = M0 + C_M: coefficients on (Fx, Fy, M0) are (Iy, −Ix, 1).
        let intrados = Row {
            theta,
            condition: Condition::Intrados,
            a: [iy, -ix, 1.0],
            a_lambda: l.m - cross(j.intrados, l.fx, l.fy),
            b: -(d.m - cross(j.intrados, d.fx, d.fy)),
        };
        let extrados = Row {
            theta,
            condition: Condition::Extrados,
            a: [-ey, ex, -1.0],
            a_lambda: -(l.m - cross(j.extrados, l.fx, l.fy)),
            b: d.m - cross(j.extrados, d.fx, d.fy),
        };
        let tau = j.along();
        let nu = j.normal();
        let (c, s) = (phi.cos(), phi.sin());
        let sliding = |sign: f64, condition| {
            let g = [sign * c * tau[0] - s * nu[0], sign * c * tau[1] - s * nu[1]];
            Row {
                theta,
                condition,
                a: [g[0], g[1], 0.0],
                a_lambda: g[0] * l.fx + g[1] * l.fy,
                b: -(g[0] * d.fx + g[1] * d.fy),
            }
        };
        let mut rows = [
            intrados,
            extrados,
            sliding(1.0, Condition::SlideOutward),
            sliding(-1.0, Condition::SlideInward),
        ];
        for (r, relaxed) in rows.iter_mut().zip(self.relaxed) {
            if relaxed {
                // 0 ≤ 1: never violated, never active.
                r.a = [0.0; 3];
                r.a_lambda = 0.0;
                r.b = 1.0;
            }
        }
        rows
    }
}

/// Largest |angle| in degrees reported as the crown itself: a family's end next to a load at
/// the crown lies a few ulps from it (−4.9e-324 rad, 2.8e-322° once in degrees), and −0.
pub const CROWN_ANGLE_DEG: f64 = 1e-9;

/// A joint parameter θ (radians) in degrees from the crown as reported: within
/// [`CROWN_ANGLE_DEG`] of the crown, exactly 0.
pub fn joint_angle_deg(theta: f64) -> f64 {
    let deg = theta.to_degrees();
    if deg.abs() <= CROWN_ANGLE_DEG {
        0.0
    } else {
        deg
    }
}
