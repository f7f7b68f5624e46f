//! The standard normal truncated to `[alpha, beta]`, kept accurate far in either tail.
//!
//! When both bounds lie on one side of the mean, every probability is taken relative to the
//! upper-tail survival `Q(alpha)` in log space, so that a truncation such as `[8, 9]` (where
//! `Phi(alpha)` rounds to 1) or `[40, 41]` (where `Q(alpha)` underflows) keeps full precision.

use super::gauss::{erf, std_cdf, std_inv_cdf, std_sf};
use sobol_qmc::statrs::distribution::{Continuous, Normal};

/// `ln sqrt(2 pi)`.
const LN_SQRT_2PI: f64 = 0.918_938_533_204_672_8;

/// Above this point `ln Q(x)` comes from the asymptotic series of the Mills ratio.
const ASYMPTOTIC_FROM: f64 = 26.0;

/// `ln phi(x)` of the standard normal density.
fn ln_phi(x: f64) -> f64 {
    -0.5 * x * x - LN_SQRT_2PI
}

/// `x phi(x)`, zero at both infinities.
fn x_phi(x: f64) -> f64 {
    if x.is_infinite() {
        0.0
    } else {
        x * Normal::standard().pdf(x)
    }
}

/// `ln Q(x)`, the log of the standard normal upper-tail probability, accurate for large `x`.
pub(super) fn ln_q(x: f64) -> f64 {
    if x == f64::INFINITY {
        return f64::NEG_INFINITY;
    }
    if x < ASYMPTOTIC_FROM {
        return std_sf(x).ln();
    }
    // Q(x) = phi(x)/x (1 - 1/x^2 + 3/x^4 - 15/x^6 + ...), the terms' error is below 1e-16 here.
    let r = 1.0 / (x * x);
    let mut term = 1.0;
    let mut sum = 1.0;
    for k in 1..=8 {
        term *= -f64::from(2 * k - 1) * r;
        sum += term;
    }
    ln_phi(x) - x.ln() + sum.ln()
}

/// The `x >= 0` with `ln Q(x) = t`, for `t <= ln 0.5`.
pub(super) fn inverse_ln_q(t: f64) -> f64 {
    if t == f64::NEG_INFINITY {
        return f64::INFINITY;
    }
    let mut x = if t > -700.0 {
        -std_inv_cdf(t.exp())
    } else {
        (-2.0 * t).sqrt()
    };
    // Newton on ln Q, whose derivative is -phi/Q: a few steps polish the last bits.
    for _ in 0..8 {
        let step = (ln_q(x) - t) * (ln_q(x) - ln_phi(x)).exp();
        if !step.is_finite() {
            break;
        }
        x += step;
        if step.abs() <= 1e-16 * x.abs().max(1.0) {
            break;
        }
    }
    x
}

/// A one-sided truncation `[alpha, beta]` with `0 <= alpha < beta`, relative to `Q(alpha)`.
#[derive(Debug, Clone, Copy)]
pub(super) struct UpperTail {
    alpha: f64,
    beta: f64,
    /// `ln Q(alpha)`.
    ln_qa: f64,
    /// `Q(beta) / Q(alpha)`.
    qb_rel: f64,
    /// `(Q(alpha) - Q(beta)) / Q(alpha)`, the truncated mass relative to `Q(alpha)`.
    mass_rel: f64,
}

impl UpperTail {
    fn new(alpha: f64, beta: f64) -> Self {
        let ln_qa = ln_q(alpha);
        let db = ln_q(beta) - ln_qa;
        Self {
            alpha,
            beta,
            ln_qa,
            qb_rel: db.exp(),
            mass_rel: -db.exp_m1(),
        }
    }

    /// `P(X >= y)` within the truncation.
    fn sf(&self, y: f64) -> f64 {
        ((ln_q(y) - self.ln_qa).exp() - self.qb_rel) / self.mass_rel
    }

    /// `P(X <= y)` within the truncation.
    fn cdf(&self, y: f64) -> f64 {
        -(ln_q(y) - self.ln_qa).exp_m1() / self.mass_rel
    }

    fn pdf(&self, y: f64) -> f64 {
        (ln_phi(y) - self.ln_qa).exp() / self.mass_rel
    }

    /// The `y` with `P(X <= y) = u`.
    fn quantile(&self, u: f64) -> f64 {
        inverse_ln_q(self.ln_qa + (-u * self.mass_rel).ln_1p()).clamp(self.alpha, self.beta)
    }

    /// The `y` with `P(X >= y) = s`.
    fn quantile_sf(&self, s: f64) -> f64 {
        inverse_ln_q(self.ln_qa + (self.qb_rel + s * self.mass_rel).ln())
            .clamp(self.alpha, self.beta)
    }

    /// Mean and variance.
    fn moments(&self) -> (f64, f64) {
        // Inverse Mills ratios phi(alpha)/Q(alpha) and phi(beta)/Q(alpha).
        let la = (ln_phi(self.alpha) - self.ln_qa).exp();
        let lb = if self.beta.is_infinite() {
            0.0
        } else {
            (ln_phi(self.beta) - self.ln_qa).exp()
        };
        let blb = if self.beta.is_infinite() {
            0.0
        } else {
            self.beta * lb
        };
        let mean = (la - lb) / self.mass_rel;
        let var = 1.0 + (self.alpha * la - blb) / self.mass_rel - mean * mean;
        (mean, var.max(0.0))
    }
}

/// The standard normal truncated to `[alpha, beta]` (`alpha < beta`, either may be infinite).
#[derive(Debug, Clone, Copy)]
pub(super) enum StdTruncatedNormal {
    /// `0 <= alpha`.
    Upper(UpperTail),
    /// `beta <= 0`, stored as the mirror image `[-beta, -alpha]` of `-X`.
    Lower(UpperTail),
    /// `alpha < 0 < beta`, with the mass `Phi(beta) - Phi(alpha)`.
    Straddling { alpha: f64, beta: f64, mass: f64 },
}

impl StdTruncatedNormal {
    /// `None` unless `alpha < beta` and neither is NaN.
    pub(super) fn new(alpha: f64, beta: f64) -> Option<Self> {
        if alpha.is_nan() || beta.is_nan() || alpha >= beta {
            return None;
        }
        Some(if alpha >= 0.0 {
            Self::Upper(UpperTail::new(alpha, beta))
        } else if beta <= 0.0 {
            Self::Lower(UpperTail::new(-beta, -alpha))
        } else {
            let r = std::f64::consts::FRAC_1_SQRT_2;
            let mass = 0.5 * (erf(beta * r) - erf(alpha * r));
            Self::Straddling { alpha, beta, mass }
        })
    }

    pub(super) fn cdf(&self, x: f64) -> f64 {
        let (lo, hi) = self.bounds();
        if x <= lo {
            return 0.0;
        }
        if x >= hi {
            return 1.0;
        }
        let p = match self {
            Self::Upper(t) => t.cdf(x),
            Self::Lower(t) => t.sf(-x),
            Self::Straddling { alpha, beta, mass } => {
                if x <= 0.0 {
                    (std_cdf(x) - std_cdf(*alpha)) / mass
                } else {
                    1.0 - (std_sf(x) - std_sf(*beta)) / mass
                }
            }
        };
        p.clamp(0.0, 1.0)
    }

    pub(super) fn pdf(&self, x: f64) -> f64 {
        let (lo, hi) = self.bounds();
        if x < lo || x > hi {
            return 0.0;
        }
        match self {
            Self::Upper(t) => t.pdf(x),
            Self::Lower(t) => t.pdf(-x),
            Self::Straddling { mass, .. } => Normal::standard().pdf(x) / mass,
        }
    }

    pub(super) fn quantile(&self, u: f64) -> f64 {
        match self {
            Self::Upper(t) => t.quantile(u),
            Self::Lower(t) => -t.quantile_sf(u),
            Self::Straddling { alpha, beta, mass } => {
                let p = std_cdf(*alpha) + u * mass;
                let x = if p <= 0.5 {
                    std_inv_cdf(p)
                } else {
                    -std_inv_cdf(std_sf(*beta) + (1.0 - u) * mass)
                };
                x.clamp(*alpha, *beta)
            }
        }
    }

    /// Mean and variance.
    pub(super) fn moments(&self) -> (f64, f64) {
        match self {
            Self::Upper(t) => t.moments(),
            Self::Lower(t) => {
                let (m, v) = t.moments();
                (-m, v)
            }
            Self::Straddling { alpha, beta, mass } => {
                let std = Normal::standard();
                let mean = (std.pdf(*alpha) - std.pdf(*beta)) / mass;
                let var = 1.0 + (x_phi(*alpha) - x_phi(*beta)) / mass - mean * mean;
                (mean, var.max(0.0))
            }
        }
    }

    fn bounds(&self) -> (f64, f64) {
        match self {
            Self::Upper(t) => (t.alpha, t.beta),
            Self::Lower(t) => (-t.beta, -t.alpha),
            Self::Straddling { alpha, beta, .. } => (*alpha, *beta),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ln_q_series_joins_erfc_at_the_switch() {
        let x = ASYMPTOTIC_FROM;
        let direct = std_sf(x).ln();
        let series = {
            let r = 1.0 / (x * x);
            let (mut term, mut sum) = (1.0, 1.0);
            for k in 1..=8 {
                term *= -f64::from(2 * k - 1) * r;
                sum += term;
            }
            ln_phi(x) - x.ln() + f64::ln(sum)
        };
        assert!(
            (direct - series).abs() < 1e-13 * direct.abs(),
            "{direct} {series}"
        );
    }

    #[test]
    fn inverse_ln_q_round_trips_from_the_centre_to_far_tails() {
        for x in [0.0, 0.5, 1.0, 3.0, 8.0, 20.0, 30.0, 40.0, 100.0] {
            let back = inverse_ln_q(ln_q(x));
            assert!((back - x).abs() < 1e-12 * x.max(1.0), "{x} -> {back}");
        }
    }

    #[test]
    fn far_tail_truncation_keeps_its_quantiles_inside_and_monotone() {
        // [40, 41]: Q(40) ~ 3.7e-350 underflows, yet the conditional law is ~ 40 + Exp(40).
        let t = StdTruncatedNormal::new(40.0, 41.0).expect("valid bounds");
        let med = t.quantile(0.5);
        let approx = 40.0 + std::f64::consts::LN_2 / 40.0;
        assert!((med - approx).abs() < 1e-3, "{med}");
        assert!((t.cdf(med) - 0.5).abs() < 1e-12);
        let mirrored = StdTruncatedNormal::new(-41.0, -40.0).expect("valid bounds");
        assert!((mirrored.quantile(0.5) + med).abs() < 1e-12);
        let (m, v) = t.moments();
        assert!((m - (40.0 + 1.0 / 40.0)).abs() < 1e-3, "{m}");
        assert!((v.sqrt() - 1.0 / 40.0).abs() < 1e-3, "{v}");
    }
}
