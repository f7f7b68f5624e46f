//! What a row of results.parquet echoes of its scene ([`Inputs`]), and the answer of a
//! `state` case computed from its two domains ([`StateAnswer`]): together the whole row of
//! a case of a separable `state` grid, about 300 bytes where a [`Solution`] holds every
//! column of every find in about a kilobyte.

use super::solution::finite;
use super::{Find, Scene, Solution};
use crate::analysis::Regime;
use crate::analysis::symmetric::{self, RotationalDomain, SlidingDomain};
use crate::model::{Discretisation, Shape, WeightModel};

/// The inputs of a scene as its row echoes them (the fields of the same names in
/// [`Solution`], which [`Solution::empty`] fills from here). The default is no scene's: a
/// placeholder for a row about to be written.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Inputs {
    /// The question asked.
    pub find: Find,
    /// K = R/r given (null for `thickness`).
    pub k: Option<f64>,
    /// t/R_c given (null for `thickness`).
    pub t_over_r: Option<f64>,
    /// μ given (null for infinite friction and for `friction`).
    pub mu: Option<f64>,
    /// True when μ is infinite.
    pub mu_infinite: bool,
    /// Half-embrace angle α in degrees.
    pub half_angle_deg: f64,
    /// The weight model.
    pub weight: WeightModel,
    /// Voussoir count, null for the continuum.
    pub voussoirs: Option<u32>,
    /// `circular` or `pointed`.
    pub shape: &'static str,
    /// Eccentricity e of a pointed arch (null for a circular one).
    pub eccentricity: Option<f64>,
    /// `radial` or `vertical` joint planes.
    pub joints: &'static str,
    /// True when the crown lies inside one block.
    pub keystone: bool,
    /// The load case kind.
    pub load: &'static str,
    /// Position of a point load, degrees from the crown, as given.
    pub at_deg: Option<f64>,
    /// Position of a point load as x/L, as given.
    pub at_x: Option<f64>,
    /// Width of a point load spread over the extrados.
    pub load_width: Option<f64>,
    /// The given load factor λ of the live part (null for self-weight and for `load_factor`).
    pub lambda: Option<f64>,
}

impl Inputs {
    /// The inputs of a scene.
    pub fn of(scene: &Scene) -> Self {
        let a = &scene.arch;
        let (k, t_over_r) = if scene.find.needs_k() {
            (Some(a.k), Some(a.t_over_r()))
        } else {
            (None, None)
        };
        let mu = if scene.find.needs_mu() {
            finite(scene.friction.mu())
        } else {
            None
        };
        Inputs {
            find: scene.find,
            k,
            t_over_r,
            mu,
            mu_infinite: scene.find.needs_mu() && scene.friction.is_infinite(),
            half_angle_deg: a.half_angle_deg(),
            weight: a.weight,
            voussoirs: a.joints.voussoirs(),
            shape: scene.form.shape.as_str(),
            eccentricity: match scene.form.shape {
                Shape::Pointed { eccentricity } => Some(eccentricity),
                Shape::Circular => None,
            },
            joints: scene.form.joints.as_str(),
            keystone: match a.joints {
                Discretisation::Voussoirs(n) => n % 2 == 1,
                Discretisation::Continuum => scene.form.keystone,
            },
            load: scene.load.as_str(),
            at_deg: scene.load.at_deg(),
            at_x: scene.load.at_x(),
            load_width: scene.load.width(),
            lambda: (scene.load.is_live() && scene.find != Find::LoadFactor)
                .then_some(scene.lambda),
        }
    }
}

/// The answer of a `state` find from its rotational and sliding domains: the regime and the
/// ends of both thrust domains over W_half (null for an empty domain or an unbounded end).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateAnswer {
    /// The regime.
    pub regime: Regime,
    /// Lower end of H^r.
    pub thrust_r_min: Option<f64>,
    /// Upper end of H^r.
    pub thrust_r_max: Option<f64>,
    /// Lower end of H^s.
    pub thrust_s_min: Option<f64>,
    /// Upper end of H^s.
    pub thrust_s_max: Option<f64>,
}

impl StateAnswer {
    /// The answer of the domains of one case.
    pub fn of(rot: &RotationalDomain, sld: &SlidingDomain) -> Self {
        let (hr, hs) = (rot.interval, sld.interval);
        let end = |empty: bool, v: f64| if empty { None } else { finite(v) };
        StateAnswer {
            regime: symmetric::regime_of(rot, sld),
            thrust_r_min: end(hr.is_empty(), hr.lo),
            thrust_r_max: end(hr.is_empty(), hr.hi),
            thrust_s_min: end(hs.is_empty(), hs.lo),
            thrust_s_max: end(hs.is_empty(), hs.hi),
        }
    }

    /// Writes the answer into the fields of the same names of a solution.
    pub fn fill(&self, s: &mut Solution) {
        s.regime = Some(self.regime);
        s.thrust_r_min = self.thrust_r_min;
        s.thrust_r_max = self.thrust_r_max;
        s.thrust_s_min = self.thrust_s_min;
        s.thrust_s_max = self.thrust_s_max;
    }
}
