//! The error function and standard normal probabilities to about one ulp.
//!
//! statrs 0.18's `erf`/`erfc` (and so `Normal::cdf`) carry a relative error near `1e-10`;
//! the tail probabilities of the truncated normal need full precision, so `erf` and `erfc`
//! come from the `libm` crate (the Rust port of the C mathematical library, correctly rounded
//! to within an ulp or two).

use sobol_qmc::statrs::distribution::{ContinuousCDF, Normal};

/// The error function.
pub(super) fn erf(x: f64) -> f64 {
    libm::erf(x)
}

/// The complementary error function `1 - erf(x)`, accurate in relative terms for large `x`.
pub(super) fn erfc(x: f64) -> f64 {
    libm::erfc(x)
}

/// The standard normal CDF `Phi(x)`, accurate in relative terms in the lower tail.
pub(super) fn std_cdf(x: f64) -> f64 {
    0.5 * erfc(-x * std::f64::consts::FRAC_1_SQRT_2)
}

/// The standard normal upper-tail probability `Q(x) = 1 - Phi(x)`, accurate in the upper tail.
pub(super) fn std_sf(x: f64) -> f64 {
    0.5 * erfc(x * std::f64::consts::FRAC_1_SQRT_2)
}

/// The standard normal quantile `Phi^-1(p)`: statrs' value polished by a Newton step on the
/// accurate CDF (on the survival function above the median).
pub(super) fn std_inv_cdf(p: f64) -> f64 {
    if !(p > 0.0 && p < 1.0) {
        return if p == 0.0 {
            f64::NEG_INFINITY
        } else if p == 1.0 {
            f64::INFINITY
        } else {
            f64::NAN
        };
    }
    let std = Normal::standard();
    let x = std.inverse_cdf(p);
    let density = (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt();
    let residual = if p <= 0.5 {
        std_cdf(x) - p
    } else {
        (1.0 - p) - std_sf(x)
    };
    let step = residual / density;
    if step.is_finite() { x - step } else { x }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_probabilities_match_reference_values() {
        // Reference values to 17 digits (Python math.erfc, itself correctly rounded here).
        // Reference values from 30-digit arithmetic. Rounding x / sqrt(2) costs about x^2 ulp.
        let cases = [
            (-1.0, 1.586_552_539_314_570_5e-1),
            (1.5, 9.331_927_987_311_419e-1),
            (-5.0, 2.866_515_718_791_939e-7),
            (-8.0, 6.220_960_574_271_784e-16),
            (-20.0, 2.753_624_118_606_233_7e-89),
            (-37.0, 5.725_571_222_524_577e-300),
        ];
        for (x, p) in cases {
            let tol = 4e-16 * (4.0 + x * x) * p;
            let got = std_cdf(x);
            assert!((got - p).abs() <= tol, "Phi({x}) = {got:e}, want {p:e}");
            assert!((std_sf(-x) - p).abs() <= tol);
        }
        assert_eq!(std_cdf(0.0), 0.5);
        assert!((erf(0.5) - 0.520_499_877_813_046_5).abs() < 2e-16);
        assert!((erf(-2.0) + 0.995_322_265_018_952_7).abs() < 2e-16);
        assert!((erfc(3.0) - 2.209_049_699_858_544e-5).abs() < 1e-15 * 2.2e-5);
    }

    #[test]
    fn quantile_inverts_the_cdf_in_both_tails() {
        for p in [
            1e-300,
            1e-20,
            1e-9,
            0.025,
            0.3,
            0.5,
            0.7,
            0.975,
            1.0 - 1e-12,
        ] {
            let x = std_inv_cdf(p);
            let back = if p <= 0.5 {
                std_cdf(x)
            } else {
                1.0 - std_sf(x)
            };
            assert!(
                (back - p).abs() <= 1e-14 * p.min(1.0 - p).max(1e-300) + 1e-16,
                "{p} {x}"
            );
        }
        assert!((std_inv_cdf(0.975) - 1.959_963_984_540_054).abs() < 1e-15);
    }
}
