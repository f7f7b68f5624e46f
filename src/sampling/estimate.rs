//! Estimators of a probability of failure, a fragility curve (empirical CDF of the capacity)
//! and capacity quantiles, each with a confidence interval.
//!
//! Sorted inputs are ascending in `f64::total_cmp` order without NaN; an unbounded capacity is
//! `+inf` and sorts last, so a high quantile may be `+inf`.

/// A point estimate with the lower and upper ends of its confidence interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// The point estimate.
    pub value: f64,
    /// Lower end of the interval.
    pub lo: f64,
    /// Upper end of the interval.
    pub hi: f64,
}

/// The standard normal quantile of 0.975, for two-sided 95 % intervals.
pub const Z95: f64 = 1.959_963_984_540_054;

/// The Wilson score interval of a proportion `successes / n` at normal quantile `z`
/// (Wilson 1927). Unlike the Wald interval it stays inside `[0, 1]` and is not empty at 0 or
/// `n` successes. With `n = 0` the estimate is NaN and the interval `[0, 1]`.
pub fn wilson(successes: u64, n: u64, z: f64) -> Interval {
    if n == 0 {
        return Interval {
            value: f64::NAN,
            lo: 0.0,
            hi: 1.0,
        };
    }
    let s = successes.min(n);
    let nf = n as f64;
    let p = s as f64 / nf;
    let z2 = z * z;
    let denom = 1.0 + z2 / nf;
    let centre = (p + z2 / (2.0 * nf)) / denom;
    let half = z / denom * (p * (1.0 - p) / nf + z2 / (4.0 * nf * nf)).sqrt();
    Interval {
        value: p,
        lo: if s == 0 {
            0.0
        } else {
            (centre - half).max(0.0)
        },
        hi: if s == n {
            1.0
        } else {
            (centre + half).min(1.0)
        },
    }
}

/// The empirical CDF of `sorted` at each point of `at`, `F(x) = #{v <= x} / n`, with the
/// Dvoretzky–Kiefer–Wolfowitz band at confidence `conf` (simultaneous over all `x`):
/// `eps = sqrt(ln(2 / (1 - conf)) / (2 n))`, the band clamped to `[0, 1]`. With an empty sample
/// every estimate is NaN and every band `[0, 1]`.
pub fn ecdf_band(sorted: &[f64], at: &[f64], conf: f64) -> Vec<Interval> {
    let n = sorted.len();
    let eps = if n == 0 {
        1.0
    } else {
        ((2.0 / (1.0 - conf)).ln() / (2.0 * n as f64)).sqrt()
    };
    at.iter()
        .map(|&x| {
            let value = if n == 0 {
                f64::NAN
            } else {
                sorted.partition_point(|v| *v <= x) as f64 / n as f64
            };
            Interval {
                value,
                lo: if n == 0 { 0.0 } else { (value - eps).max(0.0) },
                hi: if n == 0 { 1.0 } else { (value + eps).min(1.0) },
            }
        })
        .collect()
}

/// The `p`-quantile of `sorted` as the order statistic of rank `ceil(n p)` (clamped to
/// `1..=n`; the inverse of the empirical CDF), with the distribution-free order-statistic
/// interval of ranks `n p -/+ z sqrt(n p (1 - p))` rounded outwards and clamped to `1..=n`.
/// When a rank is clamped the coverage at that end is below the nominal one.
/// An empty sample gives NaN throughout.
pub fn quantile_interval(sorted: &[f64], p: f64, z: f64) -> Interval {
    let n = sorted.len();
    if n == 0 || p.is_nan() {
        return Interval {
            value: f64::NAN,
            lo: f64::NAN,
            hi: f64::NAN,
        };
    }
    let p = p.clamp(0.0, 1.0);
    let nf = n as f64;
    let at_rank = |r: f64| sorted[(r.clamp(1.0, nf) as usize) - 1];
    let np = nf * p;
    let half = z * (np * (1.0 - p)).sqrt();
    Interval {
        // The relative nudge keeps an integral n p (e.g. 100 x 0.95) from rounding up a rank.
        value: at_rank((np * (1.0 - 4.0 * f64::EPSILON)).ceil()),
        lo: at_rank((np - half).floor()),
        hi: at_rank((np + half).ceil()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wilson_matches_textbook_values() {
        // 8 of 20, z = 1.96: Newcombe (1998) gives 0.2188 to 0.6134.
        let w = wilson(8, 20, Z95);
        assert!((w.value - 0.4).abs() < 1e-15);
        assert!((w.lo - 0.218_8).abs() < 1e-4, "{}", w.lo);
        assert!((w.hi - 0.613_4).abs() < 1e-4, "{}", w.hi);
        // No success in 100: [0, z^2 / (n + z^2)].
        let w = wilson(0, 100, Z95);
        assert_eq!((w.value, w.lo), (0.0, 0.0));
        assert!((w.hi - Z95 * Z95 / (100.0 + Z95 * Z95)).abs() < 1e-15);
        let w = wilson(100, 100, Z95);
        assert_eq!((w.value, w.hi), (1.0, 1.0));
        assert!((w.lo - 100.0 / (100.0 + Z95 * Z95)).abs() < 1e-15);
        assert!(wilson(0, 0, Z95).value.is_nan());
    }

    #[test]
    fn wilson_covers_the_true_proportion_about_95_percent_of_the_time() {
        // Exact coverage by summing the binomial pmf over the outcomes whose interval covers p.
        let (n, p) = (200_u64, 0.05_f64);
        let mut coverage = 0.0;
        let mut ln_pmf = (n as f64) * (1.0 - p).ln();
        for k in 0..=n {
            if k > 0 {
                ln_pmf += ((n - k + 1) as f64 / k as f64).ln() + (p / (1.0 - p)).ln();
            }
            let w = wilson(k, n, Z95);
            if w.lo <= p && p <= w.hi {
                coverage += ln_pmf.exp();
            }
        }
        assert!((coverage - 0.95).abs() < 0.02, "{coverage}");
    }

    #[test]
    fn ecdf_band_counts_ties_and_infinities() {
        let sorted = [1.0, 2.0, 2.0, 3.0, f64::INFINITY];
        let band = ecdf_band(&sorted, &[0.5, 2.0, 10.0, f64::INFINITY], 0.5);
        let values: Vec<f64> = band.iter().map(|b| b.value).collect();
        assert_eq!(values, [0.0, 0.6, 0.8, 1.0]);
        // eps = sqrt(ln(2 / 0.5) / 10) = 0.3723.
        let eps = (4.0_f64.ln() / 10.0).sqrt();
        assert!((band[1].lo - (0.6 - eps)).abs() < 1e-15);
        assert!((band[1].hi - (0.6 + eps)).abs() < 1e-15);
        assert_eq!((band[2].hi, band[3].lo), (1.0, 1.0 - eps));
        assert_eq!(band[0].lo, 0.0);
        assert!((band[0].hi - eps).abs() < 1e-15);
        // At 95 % with n = 5 the band is wider than 0.6: eps = sqrt(ln 40 / 10).
        let wide = ecdf_band(&sorted, &[2.0], 0.95);
        assert_eq!((wide[0].lo, wide[0].hi), (0.0, 1.0));
    }

    #[test]
    fn quantile_interval_uses_order_statistics() {
        let sorted: Vec<f64> = (1..=100).map(f64::from).collect();
        // Median: rank 50; ranks 50 -/+ 1.96 * 5 = 40.2 .. 59.8 -> 40 .. 60.
        let q = quantile_interval(&sorted, 0.5, Z95);
        assert_eq!((q.value, q.lo, q.hi), (50.0, 40.0, 60.0));
        // 5 %: rank 5; 5 -/+ 1.96 * sqrt(4.75) = 0.73 .. 9.27 -> clamped 1 .. 10.
        let q = quantile_interval(&sorted, 0.05, Z95);
        assert_eq!((q.value, q.lo, q.hi), (5.0, 1.0, 10.0));
        assert_eq!(quantile_interval(&sorted, 0.0, Z95).value, 1.0);
        assert_eq!(quantile_interval(&sorted, 1.0, Z95).value, 100.0);
        assert!(quantile_interval(&[], 0.5, Z95).value.is_nan());
    }

    #[test]
    fn quantile_of_unbounded_capacities_may_be_infinite() {
        let mut sorted: Vec<f64> = (1..=90).map(f64::from).collect();
        sorted.extend([f64::INFINITY; 10]);
        let q = quantile_interval(&sorted, 0.95, Z95);
        assert_eq!(q.value, f64::INFINITY);
        assert_eq!(q.lo, 90.0); // rank floor(95 - 1.96 * 2.18) = 90
        let q = quantile_interval(&sorted, 0.5, Z95);
        assert_eq!(q.value, 50.0);
    }
}
