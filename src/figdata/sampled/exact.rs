//! The probability that an arch under self-weight does not stand, exactly, when only its
//! thickness and its friction are uncertain: the set of thicknesses at which the arch stands
//! at μ (the windows of the thickness find, [K_c(μ), ∞) for the circular arch) is known, so
//! the probability is one integral over μ of the probability that K falls outside it,
//! computed by adaptive Gauss–Kronrod quadrature. With K alone uncertain no integral is
//! needed; with μ alone the arch stands for μ ≥ μ_c(K) (the Coulomb cones only widen with μ).

use crate::manifest::{ParamName, Sampling};
use crate::model::{Friction, Load, t_over_r_from_k};
use crate::sampling::{Distribution, QuadratureError, integrate};
use crate::scene::{self, Find, Outcome, Scene};
use std::cell::Cell;

/// Settings of the exact probability.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactSettings {
    /// Absolute tolerance of the quadrature (default 1e-10).
    pub abs_tol: f64,
    /// Largest number of thickness finds the quadrature may spend (default 4000).
    pub max_evaluations: usize,
}

impl ExactSettings {
    /// The defaults.
    pub const DEFAULT: Self = ExactSettings {
        abs_tol: 1e-10,
        max_evaluations: 4000,
    };
}

/// The exact probability of not standing, with the quadrature's error estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exact {
    /// P(the arch does not stand).
    pub value: f64,
    /// The quadrature's error estimate (0 when no integral was needed).
    pub error: f64,
    /// Thickness or friction finds spent.
    pub evaluations: usize,
}

/// Why no exact value is given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NoExact {
    /// The scene or the sampling is not one the exact route covers.
    #[error("{0}")]
    NotCovered(&'static str),
    /// A thickness or friction find gave no answer.
    #[error("the {find} find at μ = {mu} gave no answer ({outcome})")]
    NoAnswer {
        /// The find.
        find: &'static str,
        /// Its μ.
        mu: f64,
        /// What it said.
        outcome: String,
    },
    /// The quadrature did not reach its tolerance.
    #[error("the quadrature did not converge: {0}")]
    Quadrature(#[from] QuadratureError),
}

/// The distribution of the thickness, as K: the uncertain K, or the uncertain t/R_c read
/// through K ↦ t/R_c (increasing).
struct Thickness<'a> {
    dist: &'a Distribution,
    as_t_over_r: bool,
}

impl Thickness<'_> {
    /// P(K ≤ k).
    fn cdf(&self, k: f64) -> f64 {
        if k.is_infinite() {
            return 1.0;
        }
        let x = if self.as_t_over_r {
            t_over_r_from_k(k)
        } else {
            k
        };
        self.dist.cdf(x)
    }
}

/// The exact probability that the scene `base` (self-weight, at one grid point) does not
/// stand under the uncertain K and μ of `sampling`, or why it is not given.
pub fn probability(
    sampling: &Sampling,
    base: &Scene,
    settings: &ExactSettings,
) -> Result<Exact, NoExact> {
    if base.load != Load::SelfWeight {
        return Err(NoExact::NotCovered("the exact value is for self-weight"));
    }
    let covered = sampling
        .params
        .iter()
        .all(|p| matches!(p.name, ParamName::K | ParamName::TOverR | ParamName::Mu));
    if !covered {
        return Err(NoExact::NotCovered(
            "the exact value is for an uncertain thickness and friction only",
        ));
    }
    let thickness = sampling
        .params
        .iter()
        .find(|p| matches!(p.name, ParamName::K | ParamName::TOverR))
        .map(|p| Thickness {
            dist: &p.distribution,
            as_t_over_r: p.name == ParamName::TOverR,
        });
    let mu = sampling.param(ParamName::Mu).map(|p| &p.distribution);
    let rho = sampling.correlation.map_or(0.0, |c| c.value);
    let evaluations = Cell::new(0usize);
    match (thickness, mu) {
        (Some(k), None) => {
            let w = windows(base, base.friction.mu(), &evaluations)?;
            Ok(Exact {
                value: outside(&k, &w, None),
                error: 0.0,
                evaluations: evaluations.get(),
            })
        }
        (None, Some(mu)) => {
            let c = friction_limit(base, &evaluations)?;
            // Stands for μ ≥ μ_c: P(μ < μ_c).
            let value = match mu {
                Distribution::Discrete { values, weights } => values
                    .iter()
                    .zip(weights)
                    .filter(|(v, _)| **v < c)
                    .map(|(_, w)| w)
                    .sum(),
                d => d.cdf(c),
            };
            Ok(Exact {
                value,
                error: 0.0,
                evaluations: evaluations.get(),
            })
        }
        (Some(k), Some(mu)) => {
            let g = |m: f64, z: Option<f64>| -> Result<f64, NoExact> {
                let w = windows(base, m, &evaluations)?;
                Ok(outside(&k, &w, z.map(|z| (z, rho))))
            };
            if let Distribution::Discrete { values, weights } = mu {
                let mut value = 0.0;
                for (&v, &w) in values.iter().zip(weights) {
                    let z = (rho != 0.0).then(|| normal_score(mu.cdf(v) - 0.5 * w));
                    value += w * g(v, z)?;
                }
                return Ok(Exact {
                    value,
                    error: 0.0,
                    evaluations: evaluations.get(),
                });
            }
            // P = ∫₀¹ g(Q_μ(u)) du: bounded, and needs no density.
            let failure = Cell::new(None);
            let q = integrate(
                |u| {
                    let z = (rho != 0.0).then(|| normal_score(u));
                    match g(mu.quantile(u), z) {
                        Ok(v) => v,
                        Err(e) => {
                            failure.set(Some(e));
                            f64::NAN
                        }
                    }
                },
                (0.0, 1.0),
                &[],
                settings.abs_tol,
                0.0,
                settings.max_evaluations,
            );
            if let Some(e) = failure.take() {
                return Err(e);
            }
            let q = q?;
            Ok(Exact {
                value: q.value,
                error: q.error,
                evaluations: evaluations.get(),
            })
        }
        (None, None) => Err(NoExact::NotCovered(
            "neither the thickness nor the friction is uncertain",
        )),
    }
}

/// Φ⁻¹(u).
fn normal_score(u: f64) -> f64 {
    Distribution::Normal { mean: 0.0, sd: 1.0 }.quantile(u.clamp(1e-300, 1.0 - 1e-16))
}

/// P(K outside the windows), for K independent of μ, or (z, ρ) for the Gaussian copula with
/// the normal score z of μ.
fn outside(k: &Thickness, windows: &[(f64, f64)], copula: Option<(f64, f64)>) -> f64 {
    let cdf = |x: f64| -> f64 {
        let p = k.cdf(x);
        match copula {
            None => p,
            Some((z, rho)) => {
                if p <= 0.0 || p >= 1.0 {
                    return p;
                }
                let s = (1.0 - rho * rho).sqrt();
                let zk = normal_score(p);
                Distribution::Normal { mean: 0.0, sd: 1.0 }.cdf((zk - rho * z) / s)
            }
        }
    };
    let inside: f64 = windows.iter().map(|&(a, b)| cdf(b) - cdf(a)).sum();
    (1.0 - inside).clamp(0.0, 1.0)
}

/// The windows of K on which the arch of `base` stands at μ (the last open at the end of
/// the scan is taken to stay open).
fn windows(base: &Scene, mu: f64, evaluations: &Cell<usize>) -> Result<Vec<(f64, f64)>, NoExact> {
    let scene = Scene {
        friction: Friction::new(mu).unwrap_or(Friction::INFINITE),
        find: Find::Thickness,
        ..*base
    };
    evaluations.set(evaluations.get() + 1);
    let s = scene::solve_static(&scene);
    match s.outcome {
        Some(Outcome::Found) => Ok(s
            .k_windows
            .iter()
            .map(|&(a, b)| (a, b.unwrap_or(f64::INFINITY)))
            .collect()),
        Some(Outcome::NeverStands) => Ok(Vec::new()),
        Some(Outcome::AlwaysStands) => Ok(vec![(1.0, f64::INFINITY)]),
        other => Err(NoExact::NoAnswer {
            find: "thickness",
            mu,
            outcome: other.map_or("no outcome".into(), |o| o.as_str().to_string()),
        }),
    }
}

/// The least μ at which the arch of `base` stands (0 when it always stands, +inf when it
/// never does).
fn friction_limit(base: &Scene, evaluations: &Cell<usize>) -> Result<f64, NoExact> {
    let scene = Scene {
        find: Find::Friction,
        ..*base
    };
    evaluations.set(evaluations.get() + 1);
    let s = scene::solve_static(&scene);
    match (s.outcome, s.mu_crit) {
        (Some(Outcome::Found), Some(m)) => Ok(m),
        (Some(Outcome::AlwaysStands), _) => Ok(0.0),
        (Some(Outcome::NeverStands), _) => Ok(f64::INFINITY),
        (other, _) => Err(NoExact::NoAnswer {
            find: "friction",
            mu: base.friction.mu(),
            outcome: other.map_or("no outcome".into(), |o| o.as_str().to_string()),
        }),
    }
}
