//! The weakest position of a moving point load refined between the grid's positions: the
//! grid gives λ_max at its positions only, and the weakest of them is the least of those, not
//! the least over the arch. Between the grid positions either side of the weakest one, λ_max
//! of the load's position is minimised by golden-section search to the study's boundary
//! tolerance (positions at which no state stands, or λ is unbounded, count as +∞), and the
//! least value met is kept: it is never above the grid's.

/// 1/φ, the golden-section ratio.
const INV_GOLDEN: f64 = 0.618_033_988_749_894_9;

/// Most evaluations of λ_max in one refinement (a bracket of 180° closes to 10⁻⁹ in about
/// 50).
pub const MAX_EVALUATIONS: usize = 200;

/// The bracket around the grid position `at` of a sorted axis: its neighbours on the axis
/// (`at` itself at an end of the axis). `None` when `at` is not within `tol` of a value of
/// the axis.
pub fn bracket(axis: &[f64], at: f64, tol: f64) -> Option<(f64, f64)> {
    let mut v: Vec<f64> = axis.iter().copied().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    let i = v
        .iter()
        .position(|&x| (x - at).abs() <= tol * (1.0 + at.abs()))?;
    let lo = if i > 0 { v[i - 1] } else { v[i] };
    let hi = v.get(i + 1).copied().unwrap_or(v[i]);
    Some((lo, hi))
}

/// The least λ_max over positions in `bracket`, starting from the grid's `(at, λ)`: the
/// position and λ_max there (the grid's own when nothing smaller is found).
pub fn refine(
    (lo, hi): (f64, f64),
    grid: (f64, f64),
    tol: f64,
    lambda_at: impl Fn(f64) -> Option<f64>,
) -> (f64, f64) {
    let f = |p: f64| {
        lambda_at(p)
            .filter(|l| l.is_finite())
            .unwrap_or(f64::INFINITY)
    };
    let mut best = grid;
    let mut keep = |p: f64, v: f64| {
        if v < best.1 {
            best = (p, v);
        }
        v
    };
    let (mut a, mut b) = (lo, hi);
    let mut c = b - INV_GOLDEN * (b - a);
    let mut d = a + INV_GOLDEN * (b - a);
    let (mut fc, mut fd) = (keep(c, f(c)), keep(d, f(d)));
    let mut evaluations = 2;
    while b - a > tol * (1.0 + a.abs().max(b.abs())) && evaluations < MAX_EVALUATIONS {
        // Ties (both +∞ in a region where no state stands) keep the half nearer the grid's
        // position, which is finite.
        let left = fc < fd || (fc == fd && (c - grid.0).abs() <= (d - grid.0).abs());
        if left {
            (b, d, fd) = (d, c, fc);
            c = b - INV_GOLDEN * (b - a);
            fc = keep(c, f(c));
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + INV_GOLDEN * (b - a);
            fd = keep(d, f(d));
        }
        evaluations += 1;
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bracket_is_the_neighbouring_grid_positions() {
        let axis = [-30.0, 0.0, 15.0, 20.0, 30.0];
        assert_eq!(bracket(&axis, 15.0, 1e-9), Some((0.0, 20.0)));
        assert_eq!(bracket(&axis, -30.0, 1e-9), Some((-30.0, 0.0)));
        assert_eq!(bracket(&axis, 30.0, 1e-9), Some((20.0, 30.0)));
        assert_eq!(bracket(&axis, 15.0 + 1e-14, 1e-9), Some((0.0, 20.0)));
        assert_eq!(bracket(&axis, 16.0, 1e-9), None);
    }

    #[test]
    fn a_minimum_between_grid_points_is_found_to_the_tolerance() {
        // λ(p) = 0.2 + (p − 13.7)² on a grid of 5° steps: the grid's least is 0.2 + 1.3²
        // at 15°.
        let l = |p: f64| Some(0.2 + (p - 13.7).powi(2));
        let (p, v) = refine((10.0, 20.0), (15.0, l(15.0).unwrap()), 1e-9, l);
        assert!((p - 13.7).abs() < 1e-6, "{p}");
        assert!((v - 0.2).abs() < 1e-12, "{v}");
        // A kink (a change of mechanism) is found as well.
        let k = |p: f64| Some(0.3 + (p - 12.25).abs());
        let (p, _) = refine((10.0, 15.0), (10.0, 2.55), 1e-9, k);
        assert!((p - 12.25).abs() < 1e-8, "{p}");
    }

    #[test]
    fn positions_where_nothing_stands_never_win_and_the_grid_value_is_kept() {
        // No state below 13°: the least lies at its edge, never inside the hole.
        let l = |p: f64| (p >= 13.0).then_some(0.2 + 0.01 * p);
        let (p, v) = refine((0.0, 20.0), (15.0, l(15.0).unwrap()), 1e-9, l);
        assert!(p >= 13.0 && p - 13.0 < 1e-6, "{p}");
        assert!(v <= 0.2 + 0.01 * 15.0);
        // Nothing smaller than the grid's: the grid's own.
        let flat = |_: f64| Some(1.0);
        assert_eq!(refine((0.0, 20.0), (15.0, 0.5), 1e-9, flat), (15.0, 0.5));
    }
}
