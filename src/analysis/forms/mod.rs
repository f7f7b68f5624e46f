//! Arch forms and load cases for the general three-unknown statics: circular or pointed
//! outline, radial or vertical joints, self-weight plus a live load scaled by λ.
//!
//! Lengths over the intrados radius r, forces over W_half (the weight of the half arch),
//! moments over W_half·r, as in [`crate::analysis::statics`].
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
//! - patch: the same P spread uniformly over the horizontal length w·L of the extrados
//!   centred on the load's position ([x₀, x₁]); between the crown and θ its resultant is
//!   −2·(share of [x₀, x₁] between x = 0 and the extrados end of θ) with the matching first
//!   moment, continuous in θ, so no sliver carries a finite part of it.

use super::settings::GeometrySettings;
use super::statics::Point;
use crate::model::{
    Arch, ArchForm, Discretisation, JointOrientation, KeystoneRefusal, Load, WeightModel,
};
use geometry::{arc_primitive, segment};
use loads::Patch;
use std::f64::consts::FRAC_PI_2;

/// The numerical thresholds of the forms (see [`GeometrySettings`]).
const GEOMETRY: GeometrySettings = GeometrySettings::DEFAULT;

/// The largest eccentricity of a pointed arch. Its critical thickness falls as
/// t/R_c ≈ 0.175 (1 − e), so beyond e = 0.9999 (t/R_c below 2·10⁻⁵) the margins no longer
/// resolve the thrust line within the arch: at e = 0.99999 a finite μ would give a critical
/// K below the K of infinite friction, which cannot be.
pub const MAX_ECCENTRICITY: f64 = 0.9999;

/// The eccentricities a pointed arch may have, as messages print them.
pub const ECCENTRICITY_RANGE: &str = "[0, 0.9999]";

/// Whether `e` is an eccentricity a pointed arch may have ([`MAX_ECCENTRICITY`]).
pub fn eccentricity_allowed(e: f64) -> bool {
    (0.0..=MAX_ECCENTRICITY).contains(&e)
}

/// Why a form, an arch and a load do not make a valid scene.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FormError {
    /// The extrados must lie outside the intrados: K = R/r > 1.
    #[error("K = R/r must exceed 1 (the extrados outside the intrados), not {0}")]
    NotThick(f64),
    /// The eccentricity must lie in [`ECCENTRICITY_RANGE`].
    #[error(
        "eccentricity {0} is not allowed: it must lie in [0, 0.9999] (beyond, the critical thickness t/R_c ≈ 0.175 (1 − e) is below what the margins resolve)"
    )]
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
        "a point load at {at_deg}° is not at a joint of this pointed arch: its crown joint is at 0° and the next ones at ±{first_joint_deg}°; a load between them needs a keystone"
    )]
    LoadInsideKeystone {
        /// Position given.
        at_deg: f64,
        /// ψ₁ in degrees.
        first_joint_deg: f64,
    },
    /// A point load on a keystone between the crown and the extrados apex's angle.
    #[error(
        "a point load at {at_deg}° is not on the extrados: the keystone's extrados runs from the apex at ±{apex_deg}° (named 0°) to ±{first_joint_deg}°"
    )]
    LoadOffExtrados {
        /// Position given.
        at_deg: f64,
        /// ψ of the extrados apex, asin(d/K), in degrees.
        apex_deg: f64,
        /// ψ₁ in degrees.
        first_joint_deg: f64,
    },
    /// A point load given as x/L outside the span, or on an arch beyond a semicircle.
    #[error(
        "a point load at x/L = {at_x} is not allowed with a half-angle of {half_angle_deg}°: x/L must lie in [0, 1], on an arch with α ≤ 90° (beyond, a vertical line meets the extrados twice)"
    )]
    LoadOffSpan {
        /// Position given.
        at_x: f64,
        /// α in degrees.
        half_angle_deg: f64,
    },
    /// A patch load on an arch beyond a semicircle, or running past a springing.
    #[error(
        "a point load spread over {width} of the span at x/L = {at_x} runs from x/L = {from} to {to}: a patch load must lie within the span [0, 1] of an arch with α ≤ 90° (α = {half_angle_deg}°)"
    )]
    PatchOffSpan {
        /// Width given, a fraction of the extrados span.
        width: f64,
        /// Its centre as x/L.
        at_x: f64,
        /// Its ends as x/L.
        from: f64,
        /// Its ends as x/L.
        to: f64,
        /// α in degrees.
        half_angle_deg: f64,
    },
    /// A point load given as x/L above the wedge between the crown and the first joints of a
    /// pointed arch without a keystone.
    #[error(
        "a point load at x/L = {at_x} ({at_deg}° from its arc's centre) lies between the crown joint and the first joints at ±{first_joint_deg}° of this pointed arch: a load there needs a keystone"
    )]
    XInsideKeystone {
        /// Position given.
        at_x: f64,
        /// Its angle at the arc's centre, degrees.
        at_deg: f64,
        /// ψ₁ in degrees.
        first_joint_deg: f64,
    },
    /// A keystone asked for where the form has none.
    #[error("{0}")]
    NoKeystone(KeystoneRefusal),
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
/// [`ArchGeometry`](crate::analysis::statics::ArchGeometry).
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
    /// The point load's parameter a (radians) and position X; for a patch load, its centre.
    point: Option<(f64, Point)>,
    /// A patch load: the extrados x range (over r) it is spread over, and the joint
    /// parameters at its ends where joints exist there.
    patch: Option<Patch>,
    /// True when a point load at the apex of a pointed arch with radial joints is shared
    /// freely between the halves ([`ArchModel::with_shared_apex`]).
    shared_apex: bool,
}

mod geometry;
mod loads;
#[cfg(test)]
mod tests;

impl ArchModel {
    /// The model of an arch of a given form under a load case; checks that the form exists
    /// at this K and α and that a point load sits at a joint.
    pub fn new(arch: Arch, form: ArchForm, load: Load) -> Result<Self, FormError> {
        Self::build(arch, form, load, true)
    }

    /// The model, its half weight computed when `weigh` (else left at 1).
    fn build(arch: Arch, form: ArchForm, load: Load, weigh: bool) -> Result<Self, FormError> {
        let k = arch.k;
        if !(k > 1.0) {
            return Err(FormError::NotThick(k));
        }
        let alpha = arch.half_angle;
        let e = form.shape.eccentricity();
        if !eccentricity_allowed(e) {
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
            patch: None,
            shared_apex: false,
        };
        form.check_keystone(arch.joints)
            .map_err(FormError::NoKeystone)?;
        if load.is_patch() {
            let (centre, patch) = m.place_patch(load)?;
            m.point = Some(centre);
            m.patch = Some(patch);
        } else {
            m.point = match load {
                Load::Point { at_deg, .. } => Some(m.place_point(at_deg)?),
                Load::PointX { at_x, .. } => Some(m.place_point_x(at_x)?),
                Load::SelfWeight | Load::Horizontal => None,
            };
        }
        if weigh {
            m.w_half = match arch.weight {
                WeightModel::Annular => m.region(&m.support()).0[0],
                WeightModel::Centreline => (k - 1.0) * rho_c * (alpha - psi_c0),
            };
        }
        Ok(m)
    }

    /// Whether the scene has a model: [`ArchModel::new`]'s checks without weighing the arch
    /// (a batch of a million scenes is checked at a fraction of the cost of building them).
    pub fn check(arch: Arch, form: ArchForm, load: Load) -> Result<(), FormError> {
        Self::build(arch, form, load, false).map(|_| ())
    }

    /// True when the scene has a point load at the apex of a pointed arch with radial
    /// joints and a crown joint (the continuum, an even voussoir count): the load sits on the
    /// crown joint between the two halves, and how it is shared between them is statically
    /// indeterminate.
    pub fn has_apex_load(&self) -> bool {
        // A keystone over the apex carries the load on one block.
        !self.has_keystone()
            && self.psi_1 > 0.0
            && self.form.joints == JointOrientation::Radial
            && self.patch.is_none()
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

    /// True when the crown lies inside one block, the keystone: the continuum with the
    /// form's keystone, or an odd voussoir count.
    pub fn has_keystone(&self) -> bool {
        match self.arch.joints {
            Discretisation::Voussoirs(n) => n % 2 == 1,
            Discretisation::Continuum => self.form.keystone,
        }
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

    /// The point load's joint parameter a (radians; the support's parameter for a load on the
    /// springing wedge of a vertical-joint arch) and its own point X on the extrados, where
    /// it acts. `None` without a concentrated point load (a patch load has no such point:
    /// [`ArchModel::patch_load`]).
    pub fn point_load(&self) -> Option<(f64, Point)> {
        if self.patch.is_some() {
            return None;
        }
        self.point
    }

    /// The extrados x range (over r, x = 0 at the crown) a patch load is spread over;
    /// `None` without one.
    pub fn patch_load(&self) -> Option<[f64; 2]> {
        self.patch.map(|p| p.x)
    }

    /// ψ₁ = asin d: the angle (radians) of the first joint after the crown of a pointed arch
    /// (0 for a circular arch).
    pub fn first_joint(&self) -> f64 {
        self.psi_1
    }
}
