//! The observed order of convergence of a discrete arch to the continuum: statistics of the
//! stored errors (no analysis, no formatting).

/// How fast the error of a quantity falls with the voussoir count N: |error| ≈ C·N^(−order).
#[derive(Debug, Clone, PartialEq)]
pub struct ObservedOrder {
    /// Least-squares slope of log|error| against log N, negated (2 means error ∝ N⁻²).
    pub order: f64,
    /// Smallest N of the fit.
    pub n_from: u32,
    /// Largest N of the fit.
    pub n_to: u32,
    /// Points of the fit.
    pub points: usize,
    /// The counts N at which |error| is larger than at the previous N (empty when the error
    /// falls monotonically over all the counts given).
    pub rises_at: Vec<u32>,
}

/// Fewest points of a fit.
const MIN_FIT_POINTS: usize = 3;

/// The observed order of convergence from (N, |error|) pairs: the least-squares slope of
/// log|error| against log N over the larger half of the counts with a positive error (at
/// least three points). `None` with fewer than three positive errors.
pub fn observed_order(points: &[(u32, f64)]) -> Option<ObservedOrder> {
    let mut pts: Vec<(u32, f64)> = points
        .iter()
        .copied()
        .filter(|p| p.1.is_finite() && p.1 > 0.0)
        .collect();
    pts.sort_by_key(|p| p.0);
    if pts.len() < MIN_FIT_POINTS {
        return None;
    }
    let rises_at = pts
        .windows(2)
        .filter(|w| w[1].1 > w[0].1)
        .map(|w| w[1].0)
        .collect();
    let take = (pts.len() / 2).max(MIN_FIT_POINTS);
    let fit = &pts[pts.len() - take..];
    let xy: Vec<(f64, f64)> = fit
        .iter()
        .map(|&(n, e)| (f64::from(n).ln(), e.ln()))
        .collect();
    let m = xy.len() as f64;
    let (mx, my) = (
        xy.iter().map(|p| p.0).sum::<f64>() / m,
        xy.iter().map(|p| p.1).sum::<f64>() / m,
    );
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    (sxx > 0.0).then(|| ObservedOrder {
        order: -sxy / sxx,
        n_from: fit[0].0,
        n_to: fit[fit.len() - 1].0,
        points: fit.len(),
        rises_at,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn power_law_gives_its_exponent() {
        let pts: Vec<(u32, f64)> = [4u32, 8, 16, 32, 64, 128]
            .iter()
            .map(|&n| (n, 3.0 * f64::from(n).powf(-2.0)))
            .collect();
        let o = observed_order(&pts).unwrap();
        assert_abs_diff_eq!(o.order, 2.0, epsilon = 1e-12);
        assert_eq!((o.n_from, o.n_to, o.points), (32, 128, 3));
        assert!(o.rises_at.is_empty());
    }

    #[test]
    fn rises_are_reported_and_zero_errors_skipped() {
        let pts = [(3, 1e-1), (4, 2e-1), (5, 0.0), (8, 1e-2), (16, 2e-3)];
        let o = observed_order(&pts).unwrap();
        assert_eq!(o.rises_at, vec![4]);
        assert_eq!(o.points, 3);
        assert!(observed_order(&pts[..2]).is_none());
    }
}
