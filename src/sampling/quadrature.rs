//! Adaptive Gauss–Kronrod quadrature of one-dimensional integrals, e.g. a probability of
//! failure as the integral of a fragility curve against a hazard density.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// The value of an integral with its estimated absolute error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quadrature {
    /// The integral.
    pub value: f64,
    /// Estimated absolute error of `value`.
    pub error: f64,
    /// Number of integrand evaluations used.
    pub evaluations: usize,
}

/// Why an integral could not be computed to the requested tolerance.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
pub enum QuadratureError {
    /// The error estimate stayed above the tolerance within the evaluation budget.
    #[error(
        "integral not converged: {value} with estimated error {error} after {evaluations} evaluations"
    )]
    NotConverged {
        /// Best value reached.
        value: f64,
        /// Its estimated absolute error.
        error: f64,
        /// Evaluations used.
        evaluations: usize,
    },
    /// The integrand (or an end of the interval) is not finite.
    #[error("integrand not finite at x = {at}")]
    NonFinite {
        /// Where the non-finite value occurred.
        at: f64,
    },
}

/// Kronrod nodes of the 15-point rule on `[-1, 1]` (non-negative half, QUADPACK `qk15`); the
/// odd entries (1, 3, 5, 7) are the 7-point Gauss nodes.
#[allow(clippy::excessive_precision)] // the digits as published
const XGK: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];

/// Kronrod weights matching `XGK`.
#[allow(clippy::excessive_precision)] // the digits as published
const WGK: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];

/// Gauss weights of the nodes `XGK[1], XGK[3], XGK[5], XGK[7]`.
#[allow(clippy::excessive_precision)] // the digits as published
const WG: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// One subinterval with its Kronrod value and error estimate.
#[derive(Debug, Clone, Copy)]
struct Piece {
    a: f64,
    b: f64,
    value: f64,
    error: f64,
}

impl PartialEq for Piece {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Piece {}
impl PartialOrd for Piece {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Piece {
    fn cmp(&self, other: &Self) -> Ordering {
        self.error.total_cmp(&other.error)
    }
}

/// The G7–K15 pair on `[a, b]`, with QUADPACK's error estimate (Piessens et al. 1983, §2.2.1).
fn kronrod(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> Result<Piece, QuadratureError> {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let eval = |x: f64| {
        let y = f(x);
        if y.is_finite() {
            Ok(y)
        } else {
            Err(QuadratureError::NonFinite { at: x })
        }
    };
    let fc = eval(c)?;
    let mut fv = [(0.0, 0.0); 7];
    let mut kronrod_sum = WGK[7] * fc;
    let mut gauss_sum = WG[3] * fc;
    let mut abs_sum = WGK[7] * fc.abs();
    for k in 0..7 {
        let dx = h * XGK[k];
        let (f1, f2) = (eval(c - dx)?, eval(c + dx)?);
        fv[k] = (f1, f2);
        kronrod_sum += WGK[k] * (f1 + f2);
        abs_sum += WGK[k] * (f1.abs() + f2.abs());
        if k % 2 == 1 {
            gauss_sum += WG[k / 2] * (f1 + f2);
        }
    }
    let mean = 0.5 * kronrod_sum;
    let mut asc = WGK[7] * (fc - mean).abs();
    for k in 0..7 {
        asc += WGK[k] * ((fv[k].0 - mean).abs() + (fv[k].1 - mean).abs());
    }
    let (value, res_abs, res_asc) = (kronrod_sum * h, abs_sum * h.abs(), asc * h.abs());
    let mut error = ((kronrod_sum - gauss_sum) * h).abs();
    if res_asc != 0.0 && error != 0.0 {
        error = res_asc * (200.0 * error / res_asc).powf(1.5).min(1.0);
    }
    if res_abs > f64::MIN_POSITIVE / (50.0 * f64::EPSILON) {
        error = error.max(50.0 * f64::EPSILON * res_abs);
    }
    Ok(Piece { a, b, value, error })
}

/// Globally adaptive Gauss–Kronrod (G7–K15) quadrature of `f` on `[a, b]`.
///
/// The interval is first split at `breaks` (kinks or jumps of the integrand; points outside
/// `(a, b)` are ignored), then the subinterval of largest error estimate is bisected until the
/// summed error estimate is `<= max(abs_tol, rel_tol |value|)` or `max_evals` evaluations are
/// spent. `a > b` gives the negated integral over `[b, a]`. The ends must be finite.
pub fn integrate(
    f: impl Fn(f64) -> f64,
    (a, b): (f64, f64),
    breaks: &[f64],
    abs_tol: f64,
    rel_tol: f64,
    max_evals: usize,
) -> Result<Quadrature, QuadratureError> {
    for end in [a, b] {
        if !end.is_finite() {
            return Err(QuadratureError::NonFinite { at: end });
        }
    }
    if a == b {
        return Ok(Quadrature {
            value: 0.0,
            error: 0.0,
            evaluations: 0,
        });
    }
    let (lo, hi, sign) = if a < b { (a, b, 1.0) } else { (b, a, -1.0) };
    let mut cuts: Vec<f64> = breaks
        .iter()
        .copied()
        .filter(|x| *x > lo && *x < hi)
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut edges = vec![lo];
    edges.extend(cuts);
    edges.push(hi);

    let mut heap = BinaryHeap::new();
    let mut evaluations = 0;
    let (mut value, mut error) = (0.0, 0.0);
    // Pieces too small to bisect further: their values and errors are final.
    let (mut done_value, mut done_error) = (0.0, 0.0);
    for w in edges.windows(2) {
        let p = kronrod(&f, w[0], w[1])?;
        evaluations += 15;
        value += p.value;
        error += p.error;
        heap.push(p);
    }
    let tolerance = |v: f64| abs_tol.max(rel_tol * v.abs());
    loop {
        if error <= tolerance(value) {
            // Re-add from scratch so that the running sums' drift cannot fake convergence.
            value = done_value + heap.iter().map(|p| p.value).sum::<f64>();
            error = done_error + heap.iter().map(|p| p.error).sum::<f64>();
            if error <= tolerance(value) {
                return Ok(Quadrature {
                    value: sign * value,
                    error,
                    evaluations,
                });
            }
        }
        let Some(worst) = heap.pop() else { break };
        let mid = 0.5 * (worst.a + worst.b);
        if evaluations + 30 > max_evals {
            heap.push(worst);
            break;
        }
        if mid <= worst.a || mid >= worst.b {
            done_value += worst.value;
            done_error += worst.error;
            continue;
        }
        let left = kronrod(&f, worst.a, mid)?;
        let right = kronrod(&f, mid, worst.b)?;
        evaluations += 30;
        value += left.value + right.value - worst.value;
        error += left.error + right.error - worst.error;
        heap.push(left);
        heap.push(right);
    }
    let value = done_value + heap.iter().map(|p| p.value).sum::<f64>();
    let error = done_error + heap.iter().map(|p| p.error).sum::<f64>();
    Err(QuadratureError::NotConverged {
        value: sign * value,
        error,
        evaluations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodes_and_weights_integrate_polynomials_exactly() {
        // K15 is exact to degree 22 and G7 to degree 13 on [-1, 1].
        for deg in (0..=22).step_by(2) {
            let exact = 2.0 / f64::from(deg + 1);
            let mut k = WGK[7] * if deg == 0 { 1.0 } else { 0.0 };
            let mut g = WG[3] * if deg == 0 { 1.0 } else { 0.0 };
            for i in 0..7 {
                k += 2.0 * WGK[i] * XGK[i].powi(deg);
                if i % 2 == 1 {
                    g += 2.0 * WG[i / 2] * XGK[i].powi(deg);
                }
            }
            assert!((k - exact).abs() < 2e-16 * 8.0, "K15 degree {deg}: {k}");
            if deg <= 13 {
                assert!((g - exact).abs() < 2e-16 * 8.0, "G7 degree {deg}: {g}");
            }
        }
    }

    #[test]
    fn smooth_integrals_reach_full_precision() {
        // The error estimate never drops below 50 eps of the integral of |f|, so ask for 1e-13.
        let q = integrate(|x| x.powi(20), (0.0, 1.0), &[], 0.0, 1e-13, 10_000).expect("conv");
        assert!((q.value - 1.0 / 21.0).abs() < 1e-15, "{q:?}");
        let q = integrate(
            f64::sin,
            (0.0, std::f64::consts::PI),
            &[],
            1e-13,
            0.0,
            10_000,
        )
        .expect("converges");
        assert!((q.value - 2.0).abs() < 1e-14, "{q:?}");
        assert_eq!(q.evaluations, 15);
        let q = integrate(f64::exp, (1.0, 0.0), &[], 1e-13, 0.0, 10_000).expect("converges");
        assert!(
            (q.value + (std::f64::consts::E - 1.0)).abs() < 1e-14,
            "{q:?}"
        );
        // Asking for less than the rounding floor is reported, with the value still good.
        let e = integrate(f64::sin, (0.0, 3.0), &[], 1e-16, 0.0, 3_000).expect_err("floor");
        let QuadratureError::NotConverged { value, .. } = e else {
            panic!("unexpected {e:?}");
        };
        assert!((value - (1.0 - 3f64.cos())).abs() < 1e-14);
    }

    #[test]
    fn kink_converges_with_and_without_the_break() {
        let f = |x: f64| (x - 1.3).abs();
        let with = integrate(f, (0.0, 2.0), &[1.3, 5.0], 1e-13, 0.0, 10_000).expect("converges");
        assert!((with.value - 1.09).abs() < 1e-12, "{with:?}");
        assert_eq!(with.evaluations, 30);
        let without = integrate(f, (0.0, 2.0), &[], 1e-13, 0.0, 100_000).expect("converges");
        assert!((without.value - 1.09).abs() < 1e-12, "{without:?}");
        assert!(without.evaluations > with.evaluations);
    }

    #[test]
    fn step_function_converges_with_a_break_at_the_step() {
        let step = |x: f64| if x < 0.3 { 1.0 } else { 2.0 };
        let q = integrate(step, (0.0, 1.0), &[0.3], 1e-12, 0.0, 1_000).expect("converges");
        assert!((q.value - 1.7).abs() < 1e-14, "{q:?}");
        // Without the break a small budget is not enough: the outcome says so.
        let e = integrate(step, (0.0, 1.0), &[], 1e-12, 0.0, 300).expect_err("budget too small");
        let QuadratureError::NotConverged { value, error, .. } = e else {
            panic!("unexpected {e:?}");
        };
        assert!((value - 1.7).abs() < error.max(1e-3), "{value} {error}");
    }

    #[test]
    fn non_finite_integrand_is_reported() {
        let e = integrate(|x| 1.0 / x, (-1.0, 1.0), &[], 1e-10, 0.0, 1_000).expect_err("pole");
        assert_eq!(e, QuadratureError::NonFinite { at: 0.0 });
        let e = integrate(|x| x, (0.0, f64::INFINITY), &[], 1e-10, 0.0, 100).expect_err("inf");
        assert!(matches!(e, QuadratureError::NonFinite { .. }));
    }
}
