//! Probability laws of uncertain arch parameters (unit weight, friction, geometry, loads).
//!
//! Every law is sampled by its inverse CDF (`quantile`), so a unit design point maps to a
//! parameter value without rejection and stratification carries over to the parameter.
//! Parameters are checked where a study is read; a law with invalid parameters (a non-positive
//! spread, `from >= to`, weights that do not sum to a positive number) gives NaN everywhere.

use super::gauss::{std_cdf, std_inv_cdf};
use super::truncated_normal::StdTruncatedNormal;
use sobol_qmc::statrs::distribution::{Beta, Continuous, ContinuousCDF, LogNormal, Normal};

/// A probability law of one scalar parameter.
#[derive(Debug, Clone, PartialEq)]
pub enum Distribution {
    /// Normal with mean `mean` and standard deviation `sd`.
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation (> 0).
        sd: f64,
    },
    /// Lognormal: `ln X ~ N(mu, sigma)`.
    LogNormal {
        /// Mean of `ln X`.
        mu: f64,
        /// Standard deviation of `ln X` (> 0).
        sigma: f64,
    },
    /// Uniform on `[from, to]`.
    Uniform {
        /// Lower bound.
        from: f64,
        /// Upper bound (> `from`).
        to: f64,
    },
    /// Normal of mean `mean` and standard deviation `sd`, conditioned on `[from, to]`.
    TruncatedNormal {
        /// Mean of the parent normal.
        mean: f64,
        /// Standard deviation of the parent normal (> 0).
        sd: f64,
        /// Lower bound (may be `-inf`).
        from: f64,
        /// Upper bound (may be `+inf`, > `from`).
        to: f64,
    },
    /// `Beta(alpha, beta)` scaled from `[0, 1]` to `[from, to]`.
    Beta {
        /// First shape parameter (> 0).
        alpha: f64,
        /// Second shape parameter (> 0).
        beta: f64,
        /// Lower bound.
        from: f64,
        /// Upper bound (> `from`).
        to: f64,
    },
    /// Finitely many values with probabilities `weights` (summing to 1), values strictly increasing.
    Discrete {
        /// The possible values, strictly increasing.
        values: Vec<f64>,
        /// The probability of each value, summing to 1.
        weights: Vec<f64>,
    },
}

impl Distribution {
    /// Lognormal of median `median` (> 0) and coefficient of variation `cov` (> 0):
    /// `sigma = sqrt(ln(1 + cov^2))`, `mu = ln median`.
    pub fn lognormal_from_median_cov(median: f64, cov: f64) -> Self {
        Self::LogNormal {
            mu: median.ln(),
            sigma: (cov * cov).ln_1p().sqrt(),
        }
    }

    /// Lognormal of mean `mean` (> 0) and standard deviation `sd` (> 0):
    /// `sigma^2 = ln(1 + (sd/mean)^2)`, `mu = ln mean - sigma^2 / 2`.
    pub fn lognormal_from_mean_sd(mean: f64, sd: f64) -> Self {
        let cov = sd / mean;
        let var_ln = (cov * cov).ln_1p();
        Self::LogNormal {
            mu: mean.ln() - 0.5 * var_ln,
            sigma: var_ln.sqrt(),
        }
    }

    /// Discrete law of `values` with relative `weights` (same length, non-negative): the pairs
    /// are sorted by value, equal values merged, and the weights normalised to sum 1.
    pub fn discrete(values: Vec<f64>, weights: Vec<f64>) -> Self {
        let mut pairs: Vec<(f64, f64)> = values.into_iter().zip(weights).collect();
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut values: Vec<f64> = Vec::with_capacity(pairs.len());
        let mut weights: Vec<f64> = Vec::with_capacity(pairs.len());
        for (v, w) in pairs {
            match (values.last(), weights.last_mut()) {
                (Some(&last), Some(lw)) if last == v => *lw += w,
                _ => {
                    values.push(v);
                    weights.push(w);
                }
            }
        }
        let total: f64 = weights.iter().sum();
        for w in &mut weights {
            *w /= total;
        }
        Self::Discrete { values, weights }
    }

    /// The inverse CDF at `u` in `(0, 1)`: the value with probability `u` of not being exceeded.
    /// For a discrete law, the smallest value whose cumulative weight is `>= u`.
    /// `u <= 0` and `u >= 1` give the ends of the support.
    pub fn quantile(&self, u: f64) -> f64 {
        if u.is_nan() {
            return f64::NAN;
        }
        let (lo, hi) = self.support();
        if u <= 0.0 {
            return lo;
        }
        if u >= 1.0 {
            return hi;
        }
        match self {
            Self::Normal { mean, sd } => {
                Normal::new(*mean, *sd).map_or(f64::NAN, |_| mean + sd * std_inv_cdf(u))
            }
            Self::LogNormal { mu, sigma } => LogNormal::new(*mu, *sigma)
                .map_or(f64::NAN, |_| (mu + sigma * std_inv_cdf(u)).exp()),
            Self::Uniform { from, to } => from + u * (to - from),
            Self::TruncatedNormal { mean, sd, from, to } => {
                truncated(*mean, *sd, *from, *to).map_or(f64::NAN, |t| mean + sd * t.quantile(u))
            }
            Self::Beta {
                alpha,
                beta,
                from,
                to,
            } => Beta::new(*alpha, *beta)
                .map_or(f64::NAN, |d| from + (to - from) * beta_quantile(&d, u)),
            Self::Discrete { values, weights } => {
                let mut cumulative = 0.0;
                for (v, w) in values.iter().zip(weights) {
                    cumulative += w;
                    if cumulative >= u {
                        return *v;
                    }
                }
                hi
            }
        }
    }

    /// The cumulative distribution function `P(X <= x)`.
    pub fn cdf(&self, x: f64) -> f64 {
        match self {
            Self::Normal { mean, sd } => {
                Normal::new(*mean, *sd).map_or(f64::NAN, |_| std_cdf((x - mean) / sd))
            }
            Self::LogNormal { mu, sigma } => LogNormal::new(*mu, *sigma).map_or(f64::NAN, |_| {
                if x > 0.0 {
                    std_cdf((x.ln() - mu) / sigma)
                } else {
                    0.0
                }
            }),
            Self::Uniform { from, to } => {
                if from < to {
                    ((x - from) / (to - from)).clamp(0.0, 1.0)
                } else {
                    f64::NAN
                }
            }
            Self::TruncatedNormal { mean, sd, from, to } => {
                truncated(*mean, *sd, *from, *to).map_or(f64::NAN, |t| t.cdf((x - mean) / sd))
            }
            Self::Beta {
                alpha,
                beta,
                from,
                to,
            } => Beta::new(*alpha, *beta).map_or(f64::NAN, |d| {
                d.cdf(((x - from) / (to - from)).clamp(0.0, 1.0))
            }),
            Self::Discrete { values, weights } => values
                .iter()
                .zip(weights)
                .take_while(|(v, _)| **v <= x)
                .map(|(_, w)| w)
                .sum::<f64>()
                .min(1.0),
        }
    }

    /// The probability density at `x` (per unit of the parameter). A discrete law has no
    /// density: this returns 0 everywhere for it.
    pub fn pdf(&self, x: f64) -> f64 {
        match self {
            Self::Normal { mean, sd } => Normal::new(*mean, *sd).map_or(f64::NAN, |d| d.pdf(x)),
            Self::LogNormal { mu, sigma } => {
                LogNormal::new(*mu, *sigma).map_or(f64::NAN, |d| d.pdf(x))
            }
            Self::Uniform { from, to } => {
                if from.partial_cmp(to) != Some(std::cmp::Ordering::Less) {
                    f64::NAN
                } else if (*from..=*to).contains(&x) {
                    1.0 / (to - from)
                } else {
                    0.0
                }
            }
            Self::TruncatedNormal { mean, sd, from, to } => {
                truncated(*mean, *sd, *from, *to).map_or(f64::NAN, |t| t.pdf((x - mean) / sd) / sd)
            }
            Self::Beta {
                alpha,
                beta,
                from,
                to,
            } => Beta::new(*alpha, *beta).map_or(f64::NAN, |d| {
                let y = (x - from) / (to - from);
                if (0.0..=1.0).contains(&y) {
                    d.pdf(y) / (to - from)
                } else {
                    0.0
                }
            }),
            Self::Discrete { .. } => 0.0,
        }
    }

    /// The smallest interval holding all the probability: `(-inf, inf)` for a normal,
    /// `(0, inf)` for a lognormal, `[from, to]` for the bounded laws, `[min, max]` of a
    /// discrete law's values.
    pub fn support(&self) -> (f64, f64) {
        match self {
            Self::Normal { .. } => (f64::NEG_INFINITY, f64::INFINITY),
            Self::LogNormal { .. } => (0.0, f64::INFINITY),
            Self::Uniform { from, to }
            | Self::TruncatedNormal { from, to, .. }
            | Self::Beta { from, to, .. } => (*from, *to),
            Self::Discrete { values, .. } => match (values.first(), values.last()) {
                (Some(a), Some(b)) => (*a, *b),
                _ => (f64::NAN, f64::NAN),
            },
        }
    }

    /// The mean of the law.
    pub fn mean(&self) -> f64 {
        self.moments().0
    }

    /// The standard deviation of the law.
    pub fn sd(&self) -> f64 {
        self.moments().1.sqrt()
    }

    /// The law's identifier: `normal`, `lognormal`, `uniform`, `truncated_normal`, `beta` or
    /// `discrete`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Normal { .. } => "normal",
            Self::LogNormal { .. } => "lognormal",
            Self::Uniform { .. } => "uniform",
            Self::TruncatedNormal { .. } => "truncated_normal",
            Self::Beta { .. } => "beta",
            Self::Discrete { .. } => "discrete",
        }
    }

    /// A short description for tables and reports, e.g.
    /// `truncated normal, mean 1.15, sd 0.03, on [1, 1.3]`.
    pub fn describe(&self) -> String {
        match self {
            Self::Normal { mean, sd } => format!("normal, mean {}, sd {}", g(*mean), g(*sd)),
            Self::LogNormal { mu, sigma } => format!(
                "lognormal, median {}, sigma of ln {} (mean {}, sd {})",
                g(mu.exp()),
                g(*sigma),
                g(self.mean()),
                g(self.sd())
            ),
            Self::Uniform { from, to } => format!("uniform on [{}, {}]", g(*from), g(*to)),
            Self::TruncatedNormal { mean, sd, from, to } => format!(
                "truncated normal, mean {}, sd {}, on [{}, {}]",
                g(*mean),
                g(*sd),
                g(*from),
                g(*to)
            ),
            Self::Beta {
                alpha,
                beta,
                from,
                to,
            } => format!(
                "beta({}, {}) on [{}, {}]",
                g(*alpha),
                g(*beta),
                g(*from),
                g(*to)
            ),
            Self::Discrete { values, weights } if values.len() <= 6 => {
                let items: Vec<String> = values
                    .iter()
                    .zip(weights)
                    .map(|(v, w)| format!("{} (p {})", g(*v), g(*w)))
                    .collect();
                format!("discrete: {}", items.join(", "))
            }
            Self::Discrete { values, .. } => {
                let (lo, hi) = self.support();
                format!(
                    "discrete, {} values on [{}, {}]",
                    values.len(),
                    g(lo),
                    g(hi)
                )
            }
        }
    }

    /// Mean and variance.
    fn moments(&self) -> (f64, f64) {
        match self {
            Self::Normal { mean, sd } => (*mean, sd * sd),
            Self::LogNormal { mu, sigma } => {
                let s2 = sigma * sigma;
                let mean = (mu + 0.5 * s2).exp();
                (mean, mean * mean * s2.exp_m1())
            }
            Self::Uniform { from, to } => (0.5 * (from + to), (to - from).powi(2) / 12.0),
            Self::TruncatedNormal { mean, sd, from, to } => truncated(*mean, *sd, *from, *to)
                .map_or((f64::NAN, f64::NAN), |t| {
                    let (m, v) = t.moments();
                    (mean + sd * m, sd * sd * v)
                }),
            Self::Beta {
                alpha,
                beta,
                from,
                to,
            } => {
                let s = alpha + beta;
                let w = to - from;
                (
                    from + w * alpha / s,
                    w * w * alpha * beta / (s * s * (s + 1.0)),
                )
            }
            Self::Discrete { values, weights } => {
                let mean: f64 = values.iter().zip(weights).map(|(v, w)| v * w).sum();
                let var: f64 = values
                    .iter()
                    .zip(weights)
                    .map(|(v, w)| w * (v - mean).powi(2))
                    .sum();
                (mean, var)
            }
        }
    }
}

/// The standardised truncation, or `None` for invalid parameters.
fn truncated(mean: f64, sd: f64, from: f64, to: f64) -> Option<StdTruncatedNormal> {
    if sd.is_nan() || sd <= 0.0 || !mean.is_finite() || !sd.is_finite() {
        return None;
    }
    StdTruncatedNormal::new((from - mean) / sd, (to - mean) / sd)
}

/// The Beta inverse CDF, polished by safeguarded Newton steps on the CDF (bisection when a
/// step leaves the bracket) until the residual is below `1e-15` relative to `min(u, 1 - u)` or
/// no representable point is closer. statrs' `inv_beta_reg` alone is good to about `1e-15`
/// in the cases checked, but nothing in statrs guarantees it.
fn beta_quantile(d: &Beta, u: f64) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let mut x = d.inverse_cdf(u);
    if !(x > 0.0 && x < 1.0) {
        x = 0.5;
    }
    let target = 1e-15 * u.min(1.0 - u);
    for _ in 0..200 {
        let f = d.cdf(x) - u;
        if f.abs() <= target {
            return x;
        }
        if f < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let newton = x - f / d.pdf(x);
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if next == x || next <= lo || next >= hi {
            return x;
        }
        x = next;
    }
    x
}

/// A number rounded to six significant digits and printed in its shortest form.
fn g(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    let rounded: f64 = format!("{x:.5e}").parse().unwrap_or(x);
    format!("{rounded}")
}

#[cfg(test)]
mod tests;
