//! The arch as data: geometry options, weight model, discretisation and friction.
//!
//! Pure types, validated once on construction. Lengths are normalised by the intrados
//! radius r (so R = K), angles are stored in radians and reported in degrees.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::fmt;

/// How the self-weight of the arch is distributed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum WeightModel {
    /// True weight of each annular sector, acting at its centroid (the paper's model).
    #[default]
    Annular,
    /// Weight γ·t per unit length of the centreline, acting on the centreline.
    Centreline,
}

impl WeightModel {
    /// The name used on the command line, in manifests and in stored results.
    pub fn as_str(self) -> &'static str {
        match self {
            WeightModel::Annular => "annular",
            WeightModel::Centreline => "centreline",
        }
    }

    /// Parses `annular` or `centreline`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "annular" => Some(WeightModel::Annular),
            "centreline" | "centerline" => Some(WeightModel::Centreline),
            _ => None,
        }
    }
}

impl fmt::Display for WeightModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Where the arch may open or slide: every section, or the joints between N voussoirs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum Discretisation {
    /// Every section is a potential joint (the paper's mono-dimensional continuum).
    #[default]
    Continuum,
    /// N voussoirs with N + 1 joints equally spaced in angle; odd N puts a keystone at the crown.
    Voussoirs(u32),
}

impl Discretisation {
    /// The voussoir count, `None` for the continuum.
    pub fn voussoirs(self) -> Option<u32> {
        match self {
            Discretisation::Continuum => None,
            Discretisation::Voussoirs(n) => Some(n),
        }
    }
}

impl fmt::Display for Discretisation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Discretisation::Continuum => f.write_str("continuum"),
            Discretisation::Voussoirs(n) => write!(f, "{n} voussoirs"),
        }
    }
}

/// The Coulomb friction coefficient μ = tan φ, finite (≥ 0) or infinite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    mu: f64,
}

impl Friction {
    /// Friction large enough to prevent any sliding.
    pub const INFINITE: Friction = Friction { mu: f64::INFINITY };

    /// A friction coefficient; `None` for a negative or NaN value.
    pub fn new(mu: f64) -> Option<Self> {
        (mu >= 0.0).then_some(Friction { mu })
    }

    /// μ itself (possibly infinite).
    pub fn mu(self) -> f64 {
        self.mu
    }

    /// The friction angle φ = atan μ in radians, in [0, π/2].
    pub fn angle(self) -> f64 {
        if self.mu.is_infinite() {
            PI / 2.0
        } else {
            self.mu.atan()
        }
    }

    /// True when sliding can never occur.
    pub fn is_infinite(self) -> bool {
        self.mu.is_infinite()
    }
}

impl fmt::Display for Friction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.mu.is_infinite() {
            f.write_str("inf")
        } else {
            write!(f, "{}", self.mu)
        }
    }
}

/// Why a set of arch parameters was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// K must exceed 1.
    #[error("thickness ratio K = {0} is not allowed: K = R/r must be a number greater than 1")]
    ThicknessRatio(f64),
    /// t/R_c must lie in (0, 2).
    #[error("t/R_c = {0} is not allowed: it must be a number in (0, 2)")]
    ThicknessOverRadius(f64),
    /// The half-angle must lie in (0°, 180°).
    #[error("half-angle {0}° is not allowed: it must lie in (0°, 180°)")]
    HalfAngle(f64),
    /// At least one voussoir.
    #[error("voussoir count {0} is not allowed: it must be an integer ≥ 1")]
    Voussoirs(i64),
    /// μ must be ≥ 0 or infinite.
    #[error("friction coefficient μ = {0} is not allowed: it must be ≥ 0 or inf")]
    Friction(f64),
}

/// t/R_c for a thickness ratio K: 2(K − 1)/(K + 1).
pub fn t_over_r_from_k(k: f64) -> f64 {
    if k.is_infinite() {
        2.0
    } else {
        2.0 * (k - 1.0) / (k + 1.0)
    }
}

/// The thickness ratio K for a given t/R_c: (2 + x)/(2 − x).
pub fn k_from_t_over_r(x: f64) -> f64 {
    (2.0 + x) / (2.0 - x)
}

/// A circular arch with radial joints: shape, thickness, weight model and joints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arch {
    /// Thickness ratio K = R/r (> 1).
    pub k: f64,
    /// Half-embrace angle α in radians, in (0, π).
    pub half_angle: f64,
    /// α in degrees as given: kept beside the radians so that 60° reads back as 60, not as
    /// the 59.99999999999999 of a round trip through radians.
    half_angle_given_deg: f64,
    /// How the self-weight is distributed.
    pub weight: WeightModel,
    /// Continuum or N voussoirs.
    pub joints: Discretisation,
}

impl Arch {
    /// A validated arch; `half_angle_deg` in degrees.
    pub fn new(
        k: f64,
        half_angle_deg: f64,
        weight: WeightModel,
        joints: Discretisation,
    ) -> Result<Self, ModelError> {
        if !(k > 1.0) || !k.is_finite() {
            return Err(ModelError::ThicknessRatio(k));
        }
        if !(half_angle_deg > 0.0 && half_angle_deg < 180.0) {
            return Err(ModelError::HalfAngle(half_angle_deg));
        }
        if let Discretisation::Voussoirs(0) = joints {
            return Err(ModelError::Voussoirs(0));
        }
        Ok(Arch::from_valid(k, half_angle_deg, weight, joints))
    }

    /// An arch from values already validated (K > 1, α in (0°, 180°), N ≥ 1); `half_angle_deg`
    /// in degrees, kept as given.
    pub fn from_valid(
        k: f64,
        half_angle_deg: f64,
        weight: WeightModel,
        joints: Discretisation,
    ) -> Self {
        Arch {
            k,
            half_angle: half_angle_deg.to_radians(),
            half_angle_given_deg: half_angle_deg,
            weight,
            joints,
        }
    }

    /// The semicircular arch of the paper: α = 90°, annular weight, continuum.
    pub fn semicircular(k: f64) -> Result<Self, ModelError> {
        Arch::new(k, 90.0, WeightModel::Annular, Discretisation::Continuum)
    }

    /// The same arch with another thickness ratio (unchecked: K > 1 is the caller's promise).
    pub fn with_k(self, k: f64) -> Self {
        Arch { k, ..self }
    }

    /// The same arch with another weight model.
    pub fn with_weight(self, weight: WeightModel) -> Self {
        Arch { weight, ..self }
    }

    /// Thickness over centreline radius, t/R_c = 2(K − 1)/(K + 1).
    pub fn t_over_r(&self) -> f64 {
        t_over_r_from_k(self.k)
    }

    /// Half-embrace angle in degrees, as given.
    pub fn half_angle_deg(&self) -> f64 {
        self.half_angle_given_deg
    }

    /// Radius (over r) at which the weight of a radial slice acts: ρ_s with
    /// first moment S(θ) = ρ_s · W_half · (1 − cos θ)/α.
    pub fn weight_radius(&self) -> f64 {
        let k = self.k;
        match self.weight {
            // ∫ρ² dρ / ∫ρ dρ over [1, K] = 2(K³ − 1) / (3(K² − 1)).
            WeightModel::Annular => 2.0 * (k * k + k + 1.0) / (3.0 * (k + 1.0)),
            WeightModel::Centreline => 0.5 * (k + 1.0),
        }
    }

    /// Weight of the half arch per unit depth and unit density, in r² units: (K² − 1)α/2.
    pub fn half_weight(&self) -> f64 {
        0.5 * (self.k * self.k - 1.0) * self.half_angle
    }
}

/// The outline of the arch: one circle, or two circular arcs meeting at the crown.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Shape {
    /// Intrados and extrados are concentric circles about the origin (radii r and R = K r).
    #[default]
    Circular,
    /// A pointed arch: the right half is an annulus of radii r and K r about the centre
    /// (−e·ρ_c, 0), the left half its mirror image, so the halves meet on x = 0 at the crown.
    /// ρ_c = (1 + K)/2 is the centreline radius of each arc (over r); e = 0 is the semicircle
    /// and e = 0.5 the equilateral arch (centres at the centreline springings).
    Pointed {
        /// Eccentricity e ∈ [0, 0.9999]: distance of each centre from the axis over ρ_c.
        eccentricity: f64,
    },
}

impl Shape {
    /// `circular` or `pointed`.
    pub fn as_str(self) -> &'static str {
        match self {
            Shape::Circular => "circular",
            Shape::Pointed { .. } => "pointed",
        }
    }

    /// The eccentricity e (0 for a circular arch).
    pub fn eccentricity(self) -> f64 {
        match self {
            Shape::Circular => 0.0,
            Shape::Pointed { eccentricity } => eccentricity,
        }
    }
}

/// How the joint planes of the arch are oriented.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum JointOrientation {
    /// Joints along the radii of the arc (the paper's model).
    #[default]
    Radial,
    /// Vertical joint planes through the intrados points, as in the stereotomy literature;
    /// the springings stay radial (they are the supports).
    Vertical,
}

impl JointOrientation {
    /// `radial` or `vertical`.
    pub fn as_str(self) -> &'static str {
        match self {
            JointOrientation::Radial => "radial",
            JointOrientation::Vertical => "vertical",
        }
    }

    /// Parses `radial` or `vertical`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "radial" => Some(JointOrientation::Radial),
            "vertical" => Some(JointOrientation::Vertical),
            _ => None,
        }
    }
}

/// Why a form has no keystone (the rigid block between the first joints of the two halves).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum KeystoneRefusal {
    /// The continuum of a circular arch.
    #[error(
        "a circular arch has no keystone in the continuum: every section is a joint, so the first joints of the two halves are the crown plane itself (an odd voussoir count puts a keystone at the crown)"
    )]
    Circular,
    /// The continuum of a pointed arch with vertical joints.
    #[error(
        "a pointed arch with vertical joints has no keystone in the continuum: the vertical joint through the intrados apex is the crown plane itself (an odd voussoir count puts a keystone at the crown)"
    )]
    Vertical,
    /// An even voussoir count.
    #[error("{0} voussoirs put a joint at the crown: a keystone needs an odd voussoir count")]
    EvenVoussoirs(u32),
}

/// The form of an arch beyond the data of [`Arch`]: its outline and its joint planes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ArchForm {
    /// Circular or pointed.
    pub shape: Shape,
    /// Radial or vertical joint planes.
    pub joints: JointOrientation,
    /// True when the crown is inside one rigid block, the keystone between the first joints
    /// of the two halves: the crown plane x = 0 is then no joint, and a point load may sit on
    /// the keystone. The continuum has one only on a pointed arch with radial joints (the
    /// wedge between ±ψ₁); N voussoirs have one when N is odd.
    pub keystone: bool,
}

impl ArchForm {
    /// The form as a hashable key: whether it is pointed, its eccentricity's bits, its joint
    /// planes and its keystone (cases of one key share their outline and joints).
    pub fn key(&self) -> (bool, u64, JointOrientation, bool) {
        (
            matches!(self.shape, Shape::Pointed { .. }),
            self.shape.eccentricity().to_bits(),
            self.joints,
            self.keystone,
        )
    }

    /// Checks that a form asked to have a keystone has one with these joints.
    pub fn check_keystone(&self, joints: Discretisation) -> Result<(), KeystoneRefusal> {
        if !self.keystone {
            return Ok(());
        }
        match joints {
            Discretisation::Voussoirs(n) if n % 2 == 0 => Err(KeystoneRefusal::EvenVoussoirs(n)),
            Discretisation::Voussoirs(_) => Ok(()),
            Discretisation::Continuum if self.shape.eccentricity() == 0.0 => {
                Err(KeystoneRefusal::Circular)
            }
            Discretisation::Continuum if self.joints == JointOrientation::Vertical => {
                Err(KeystoneRefusal::Vertical)
            }
            Discretisation::Continuum => Ok(()),
        }
    }

    /// True for the paper's circular arch with radial joints (closed forms exist).
    pub fn is_circular_radial(&self) -> bool {
        self.shape == Shape::Circular && self.joints == JointOrientation::Radial
    }

    /// Offset d of each arc's centre from the axis, over r: e·ρ_c = e(1 + K)/2.
    pub fn centre_offset(&self, k: f64) -> f64 {
        self.shape.eccentricity() * 0.5 * (1.0 + k)
    }

    /// Largest K for which the form exists at half-angle α (radians): a pointed arch needs
    /// its intrados arcs to meet above the springings, d = e(1 + K)/2 < min(1, sin α) for
    /// α ≤ 90° (< 1 beyond), i.e. K < 2 min(1, sin α)/e − 1. Infinite for e = 0.
    pub fn max_k(&self, half_angle: f64) -> f64 {
        let e = self.shape.eccentricity();
        if e <= 0.0 {
            return f64::INFINITY;
        }
        let reach = if half_angle <= std::f64::consts::FRAC_PI_2 {
            half_angle.sin()
        } else {
            1.0
        };
        2.0 * reach / e - 1.0
    }

    /// The K below `k_max` at which the extrados point at x/L = `at_x` reaches the first
    /// joint ψ₁ of a pointed arch (beyond, it lies above the wedge between the crown joint
    /// and ψ₁): the root of u(K sin α − d) − (K − 1)d, u = |2x/L − 1|, found by bisection
    /// (positive at K = 1 where the form exists).
    fn max_k_at_x(&self, half_angle: f64, at_x: f64, k_max: f64) -> f64 {
        let u = (2.0 * at_x - 1.0).abs();
        let s = half_angle.min(std::f64::consts::FRAC_PI_2).sin();
        let f = |k: f64| {
            let d = self.centre_offset(k);
            u * (k * s - d) - (k - 1.0) * d
        };
        let hi_start = if k_max.is_finite() { k_max } else { 1e3 };
        if f(hi_start) >= 0.0 {
            return k_max;
        }
        // Bisection down to adjacent floats.
        let (mut lo, mut hi) = (1.0, hi_start);
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if f(mid) >= 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    }

    /// The extrados point at x/L = `at_x` of the arch of thickness K and half-angle α
    /// (radians): its side (+1 right, −1 left; the crown counts as right), its signed
    /// abscissa x over r, and its angle ψ at its arc's centre, from the vertical. x/L is
    /// measured horizontally from the left extrados springing, L = 2(K sin α − d) the
    /// extrados span. `None` when α > 90° (a vertical line meets the extrados twice) or x/L
    /// is outside [0, 1].
    pub fn extrados_at_x(&self, k: f64, half_angle: f64, at_x: f64) -> Option<(f64, f64, f64)> {
        if half_angle > std::f64::consts::FRAC_PI_2 || !(0.0..=1.0).contains(&at_x) {
            return None;
        }
        let d = self.centre_offset(k);
        let x = (2.0 * at_x - 1.0) * (k * half_angle.sin() - d);
        let side = if x < 0.0 { -1.0 } else { 1.0 };
        Some((side, x, ((x.abs() + d) / k).min(1.0).asin()))
    }

    /// Largest K at which the form exists at half-angle α (radians) and a point load of
    /// `load` still sits at a joint: a pointed arch's first joint ψ₁ = asin(e(1 + K)/2)
    /// moves away from the crown as K grows, so a load at a ≠ 0 needs e(1 + K)/2 ≤ sin|a|.
    /// With a keystone and radial joints a load the first joint passes lies on the keystone.
    pub fn max_k_with_load(&self, half_angle: f64, load: Load) -> f64 {
        let k = self.max_k(half_angle);
        let e = self.shape.eccentricity();
        let on_keystone = self.keystone && self.joints == JointOrientation::Radial;
        match load {
            // A patch needs no joint under its centre.
            _ if load.is_patch() => k,
            Load::Point { at_deg, .. } if at_deg != 0.0 && e > 0.0 && !on_keystone => {
                let s = at_deg
                    .to_radians()
                    .abs()
                    .min(std::f64::consts::FRAC_PI_2)
                    .sin();
                k.min(2.0 * s / e - 1.0)
            }
            Load::PointX { at_x, .. } if at_x != 0.5 && e > 0.0 && !on_keystone => {
                k.min(self.max_k_at_x(half_angle, at_x, k))
            }
            _ => k,
        }
    }
}

/// The live part of a load case, scaled by the load factor λ (docs/mechanics.md §1: load factors are
/// multiples of the total weight). Self-weight is always present.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Load {
    /// Self-weight only: no live part.
    #[default]
    SelfWeight,
    /// A horizontal body force λ·(weight) on every voussoir, toward +x (quasi-static seismic
    /// load).
    Horizontal,
    /// A vertical point load λ·W_total at the extrados end of the joint at `at_deg` from the
    /// crown. A load exactly at a joint belongs to the part nearer the crown; a load at the
    /// crown itself to the right half. With a `width` > 0 it is a patch load centred on that
    /// extrados point ([`Load::width`]).
    Point {
        /// Position, degrees from the crown, positive to the right.
        at_deg: f64,
        /// Patch width as a fraction of the extrados span (0: concentrated).
        width: f64,
    },
    /// A vertical point load λ·W_total at the extrados point at a fraction `at_x` of the
    /// span: x/L ∈ [0, 1] measured horizontally from the left extrados springing, L the
    /// extrados span (0.5 is the crown). Its joint angle depends on K and the form
    /// ([`ArchForm::extrados_at_x`]). With a `width` > 0 it is a patch load centred there.
    PointX {
        /// Position as x/L.
        at_x: f64,
        /// Patch width as a fraction of the extrados span (0: concentrated).
        width: f64,
    },
}

impl Load {
    /// `self_weight`, `horizontal` or `point`.
    pub fn as_str(self) -> &'static str {
        match self {
            Load::SelfWeight => "self_weight",
            Load::Horizontal => "horizontal",
            Load::Point { .. } | Load::PointX { .. } => "point",
        }
    }

    /// The position of a point load given in degrees, `None` for the other loads (and for a
    /// position given as x/L, whose angle depends on K and the form).
    pub fn at_deg(self) -> Option<f64> {
        match self {
            Load::Point { at_deg, .. } => Some(at_deg),
            _ => None,
        }
    }

    /// The position of a point load given as x/L, `None` for the other loads.
    pub fn at_x(self) -> Option<f64> {
        match self {
            Load::PointX { at_x, .. } => Some(at_x),
            _ => None,
        }
    }

    /// True when the load case has a live part scaled by λ.
    pub fn is_live(self) -> bool {
        self != Load::SelfWeight
    }

    /// A concentrated point load at `at_deg` from the crown.
    pub fn point(at_deg: f64) -> Self {
        Load::Point { at_deg, width: 0.0 }
    }

    /// A concentrated point load at x/L = `at_x`.
    pub fn point_x(at_x: f64) -> Self {
        Load::PointX { at_x, width: 0.0 }
    }

    /// The width of a point load spread over the extrados, as a fraction of the extrados
    /// span L: the load λ·W_total is spread uniformly over the horizontal length width·L
    /// centred on its position. 0 for a concentrated load; `None` for the other loads.
    pub fn width(self) -> Option<f64> {
        match self {
            Load::Point { width, .. } | Load::PointX { width, .. } => Some(width),
            _ => None,
        }
    }

    /// True for a point load spread over a length of the extrados (a patch load).
    pub fn is_patch(self) -> bool {
        self.width().is_some_and(|w| w > 0.0)
    }
}
