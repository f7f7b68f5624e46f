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
        Ok(Arch {
            k,
            half_angle: half_angle_deg.to_radians(),
            weight,
            joints,
        })
    }

    /// The semicircular arch of the paper: α = 90°, annular weight, continuum.
    pub fn semicircular(k: f64) -> Result<Self, ModelError> {
        Arch::new(k, 90.0, WeightModel::Annular, Discretisation::Continuum)
    }

    /// The same arch with another thickness ratio (unchecked: K > 1 is the caller's promise).
    pub fn with_k(self, k: f64) -> Self {
        Arch { k, ..self }
    }

    /// Thickness over centreline radius, t/R_c = 2(K − 1)/(K + 1).
    pub fn t_over_r(&self) -> f64 {
        t_over_r_from_k(self.k)
    }

    /// Half-embrace angle in degrees.
    pub fn half_angle_deg(&self) -> f64 {
        self.half_angle.to_degrees()
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
