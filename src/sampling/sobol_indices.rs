//! First-order and total Sobol sensitivity indices of a model output (e.g. the collapse load
//! factor of an arch) from the Saltelli design, with percentile-bootstrap intervals.

use super::design::mix64;
use super::estimate::Interval;

/// Sobol indices of each input, with 95 % bootstrap intervals.
#[derive(Debug, Clone, PartialEq)]
pub struct Indices {
    /// First-order index `S_i`: the share of the output variance explained by input `i` alone.
    pub first: Vec<Interval>,
    /// Total index `ST_i`: the share of the variance involving input `i`, interactions included.
    pub total: Vec<Interval>,
    /// Output variance over the `A` and `B` samples together.
    pub variance: f64,
    /// Output mean over the `A` and `B` samples together.
    pub mean: f64,
}

/// Sobol indices from the outputs of the Saltelli design: `ya[j] = f(A_j)`, `yb[j] = f(B_j)`,
/// `yab[i][j] = f(A_j` with column `i` from `B_j)`.
///
/// First order by Saltelli et al. (2010, table 2 (b)): `S_i = mean(yb (yab_i - ya)) / V`;
/// total by Jansen (1999): `ST_i = mean((ya - yab_i)^2) / (2 V)`; `V` is the variance of
/// `ya` and `yb` pooled (divisor `2 n`). Intervals are 95 % percentile-bootstrap intervals
/// from `resamples` resamplings of the rows `j` with replacement, seeded by `seed` so that they
/// are reproducible; with `resamples = 0` they collapse to the estimate.
///
/// `None` when the lengths disagree, there are no rows, `V = 0`, or any output is not finite.
pub fn indices(
    ya: &[f64],
    yb: &[f64],
    yab: &[Vec<f64>],
    resamples: usize,
    seed: u64,
) -> Option<Indices> {
    let n = ya.len();
    if n == 0 || yb.len() != n || yab.iter().any(|c| c.len() != n) {
        return None;
    }
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    if !finite(ya) || !finite(yb) || !yab.iter().all(|c| finite(c)) {
        return None;
    }
    let all: Vec<usize> = (0..n).collect();
    let point = estimate(ya, yb, yab, &all)?;

    let d = yab.len();
    let mut boot_first: Vec<Vec<f64>> = vec![Vec::with_capacity(resamples); d];
    let mut boot_total: Vec<Vec<f64>> = vec![Vec::with_capacity(resamples); d];
    let mut rows = vec![0_usize; n];
    for r in 0..resamples as u64 {
        let stream = mix64(seed ^ mix64(r));
        for (k, row) in rows.iter_mut().enumerate() {
            let h = mix64(stream ^ (k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
            // Lemire's multiply-shift: a row uniform on 0..n (bias below n / 2^64).
            *row = ((u128::from(h) * n as u128) >> 64) as usize;
        }
        if let Some(b) = estimate(ya, yb, yab, &rows) {
            for i in 0..d {
                boot_first[i].push(b.first[i]);
                boot_total[i].push(b.total[i]);
            }
        }
    }
    let interval = |value: f64, boot: &mut Vec<f64>| {
        if boot.is_empty() {
            return Interval {
                value,
                lo: value,
                hi: value,
            };
        }
        boot.sort_by(f64::total_cmp);
        Interval {
            value,
            lo: percentile(boot, 0.025),
            hi: percentile(boot, 0.975),
        }
    };
    Some(Indices {
        first: (0..d)
            .map(|i| interval(point.first[i], &mut boot_first[i]))
            .collect(),
        total: (0..d)
            .map(|i| interval(point.total[i], &mut boot_total[i]))
            .collect(),
        variance: point.variance,
        mean: point.mean,
    })
}

/// Point estimates over the rows `rows` (a resample may repeat rows).
struct Estimate {
    first: Vec<f64>,
    total: Vec<f64>,
    variance: f64,
    mean: f64,
}

fn estimate(ya: &[f64], yb: &[f64], yab: &[Vec<f64>], rows: &[usize]) -> Option<Estimate> {
    let m = rows.len() as f64;
    let mean = rows.iter().map(|&j| ya[j] + yb[j]).sum::<f64>() / (2.0 * m);
    let variance = rows
        .iter()
        .map(|&j| (ya[j] - mean).powi(2) + (yb[j] - mean).powi(2))
        .sum::<f64>()
        / (2.0 * m);
    if variance.is_nan() || variance <= 0.0 {
        return None;
    }
    let first = yab
        .iter()
        .map(|c| rows.iter().map(|&j| yb[j] * (c[j] - ya[j])).sum::<f64>() / (m * variance))
        .collect();
    let total = yab
        .iter()
        .map(|c| rows.iter().map(|&j| (ya[j] - c[j]).powi(2)).sum::<f64>() / (2.0 * m * variance))
        .collect();
    Some(Estimate {
        first,
        total,
        variance,
        mean,
    })
}

/// The `q`-percentile of sorted values with linear interpolation between order statistics
/// (Hyndman & Fan type 7).
fn percentile(sorted: &[f64], q: f64) -> f64 {
    let h = (sorted.len() - 1) as f64 * q;
    let lo = h.floor() as usize;
    let hi = (lo + 1).min(sorted.len() - 1);
    sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo])
}

#[cfg(test)]
mod tests {
    use super::super::design::{Design, Method, saltelli_point, saltelli_rows};
    use super::*;

    /// Evaluates `f` on the Saltelli design of `d` inputs with `n` base rows.
    fn run(f: impl Fn(&[f64]) -> f64, d: usize, n: u64) -> (Vec<f64>, Vec<f64>, Vec<Vec<f64>>) {
        let design = Design::new(Method::Sobol, 2024, n, 2 * d);
        let (mut ya, mut yb, mut yab) = (Vec::new(), Vec::new(), vec![Vec::new(); d]);
        let mut x = vec![0.0; d];
        for row in 0..n * saltelli_rows(d) {
            saltelli_point(&design, d, row, &mut x);
            let y = f(&x);
            match (row % saltelli_rows(d)) as usize {
                0 => ya.push(y),
                1 => yb.push(y),
                b => yab[b - 2].push(y),
            }
        }
        (ya, yb, yab)
    }

    fn check(got: &Interval, known: f64, what: &str) {
        assert!(
            (got.value - known).abs() < 0.02,
            "{what}: {got:?} vs {known}"
        );
        let gap = (got.lo - known).max(known - got.hi).max(0.0);
        assert!(gap <= 0.01, "{what}: {known} outside {got:?}");
        assert!(
            got.lo <= got.value && got.value <= got.hi,
            "{what}: {got:?}"
        );
    }

    #[test]
    fn ishigami_indices_match_the_analytic_values() {
        let pi = std::f64::consts::PI;
        let ishigami = |u: &[f64]| {
            let x: Vec<f64> = u.iter().map(|v| -pi + 2.0 * pi * v).collect();
            x[0].sin() + 7.0 * x[1].sin().powi(2) + 0.1 * x[2].powi(4) * x[0].sin()
        };
        let (ya, yb, yab) = run(ishigami, 3, 1 << 14);
        let s = indices(&ya, &yb, &yab, 200, 7).expect("non-degenerate output");
        // a = 7, b = 0.1: V = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2.
        let v = 49.0 / 8.0 + 0.1 * pi.powi(4) / 5.0 + 0.01 * pi.powi(8) / 18.0 + 0.5;
        assert!((s.variance - v).abs() < 0.05 * v, "{} vs {v}", s.variance);
        assert!((s.mean - 3.5).abs() < 0.02, "{}", s.mean);
        for (i, known) in [0.3139, 0.4424, 0.0].iter().enumerate() {
            check(&s.first[i], *known, &format!("S{}", i + 1));
        }
        for (i, known) in [0.5576, 0.4424, 0.2437].iter().enumerate() {
            check(&s.total[i], *known, &format!("ST{}", i + 1));
        }
    }

    #[test]
    fn linear_model_splits_variance_by_squared_coefficients() {
        // y = 2 x1 + x2 with uniform inputs: S1 = ST1 = 4/5, S2 = ST2 = 1/5.
        let (ya, yb, yab) = run(|x| 2.0 * x[0] + x[1], 2, 1 << 12);
        let s = indices(&ya, &yb, &yab, 100, 1).expect("non-degenerate output");
        for (i, known) in [0.8, 0.2].iter().enumerate() {
            check(&s.first[i], *known, "first");
            check(&s.total[i], *known, "total");
            // Scrambled Sobol points make the point estimates far tighter than Monte Carlo.
            assert!((s.first[i].value - known).abs() < 2e-3, "{:?}", s.first[i]);
            assert!((s.total[i].value - known).abs() < 2e-3, "{:?}", s.total[i]);
        }
        assert!((s.variance - 5.0 / 12.0).abs() < 1e-3, "{}", s.variance);
        assert!((s.mean - 1.5).abs() < 1e-3);
    }

    #[test]
    fn bootstrap_is_reproducible_and_seed_dependent() {
        let (ya, yb, yab) = run(|x| x[0] * x[1] + x[0], 2, 256);
        let a = indices(&ya, &yb, &yab, 50, 3);
        let b = indices(&ya, &yb, &yab, 50, 3);
        let c = indices(&ya, &yb, &yab, 50, 4);
        assert_eq!(a, b);
        assert_ne!(a, c);
        let a = a.expect("non-degenerate output");
        assert!(a.first[0].hi - a.first[0].lo > 1e-3);
    }

    #[test]
    fn degenerate_outputs_give_none() {
        let ones = vec![1.0; 8];
        assert!(indices(&ones, &ones, std::slice::from_ref(&ones), 10, 0).is_none());
        let mut bad = vec![0.5, 1.0, 2.0, 3.0];
        let good = bad.clone();
        bad[2] = f64::INFINITY;
        assert!(indices(&good, &bad, std::slice::from_ref(&good), 10, 0).is_none());
        assert!(indices(&good, &good[..3], std::slice::from_ref(&good), 10, 0).is_none());
        let s = indices(
            &good,
            &[3.0, 2.0, 1.0, 0.5],
            std::slice::from_ref(&good),
            0,
            0,
        )
        .expect("finite");
        assert_eq!(s.first[0].lo, s.first[0].value);
    }
}
