//! The refinement of a sampled local maximum of a joint's violation: Brent's method started
//! from the samples around it, whose values are already known, stopped once the violation
//! no longer changes above its rounding.

use crate::analysis::roots::{FlatStop, MaxBracket, maximise_from};

/// A parabolic step counts as a local one (eligible to stop on a flat value) when it is
/// shorter than this fraction of the first bracket.
const LOCAL_STEP: f64 = 1e-3;

/// A point and the value of the function there.
pub(super) type Point = (f64, f64);

/// When a refinement stops.
#[derive(Debug, Clone, Copy)]
pub(super) struct Tolerance {
    /// Absolute tolerance in the argument.
    pub(super) arg: f64,
    /// A local parabolic step that changes the value by no more than this ends the search:
    /// the maximum is then known to this, and the rounding of the value hides where it lies
    /// any closer.
    pub(super) flat: f64,
}

/// The local maximum of `f` between two samples `lo` and `hi` around an interior sample
/// `mid` at least as high as both: Brent's method (parabolic steps with a golden-section
/// safeguard) started from the three samples, so that its first step is the vertex of the
/// parabola through them. Returns (argmax, max); never worse than `mid`.
pub(super) fn refine_interior<F: FnMut(f64) -> f64>(
    f: F,
    pts: [Point; 3],
    tol: Tolerance,
) -> Point {
    let [lo, mid, hi] = pts;
    let (w, v) = if lo.1 >= hi.1 { (lo, hi) } else { (hi, lo) };
    let (a, b) = (lo.0, hi.0);
    let start = MaxBracket {
        a,
        b,
        x: mid,
        w,
        v,
        step: b - a,
    };
    brent(f, start, tol)
}

/// The local maximum of `f` next to a sample `end` at the end of a family that is at least
/// as high as its neighbour `next`. When `f` does not rise from the end into the family by
/// more than `tol.flat` (one value, two argument tolerances inside), the end is the maximum:
/// a smooth violation does not turn twice between two samples. Otherwise the maximum lies inside, and Brent's method finds it
/// from the point inside. Returns (argmax, max).
pub(super) fn refine_end<F: FnMut(f64) -> f64>(
    mut f: F,
    end: Point,
    next: Point,
    tol: Tolerance,
) -> Point {
    let t = end.0 + (2.0 * tol.arg).copysign(next.0 - end.0);
    let inside = (t, f(t));
    if !(inside.1 > end.1 + tol.flat) {
        return end;
    }
    let (a, b) = (end.0.min(next.0), end.0.max(next.0));
    let start = MaxBracket {
        a,
        b,
        x: inside,
        w: end,
        v: next,
        step: b - a,
    };
    brent(f, start, tol)
}

/// Brent's method from a bracket whose points are known ([`maximise_from`]), stopped as well
/// after a local parabolic step (shorter than [`LOCAL_STEP`] of the first bracket) that
/// changes the value by no more than `tol.flat`.
fn brent<F: FnMut(f64) -> f64>(f: F, start: MaxBracket, tol: Tolerance) -> Point {
    let stop = FlatStop {
        local: LOCAL_STEP * (start.b - start.a),
        flat: tol.flat,
    };
    maximise_from(f, start, tol.arg, Some(stop))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    const TOL: Tolerance = Tolerance {
        arg: 1e-10,
        flat: 1e-16,
    };

    #[test]
    fn interior_maximum_from_three_samples() {
        let f = |t: f64| (t - 0.31).cos() - 1.0;
        let pts = [0.2, 0.3, 0.4].map(|t| (t, f(t)));
        let mut calls = 0;
        let (x, v) = refine_interior(
            |t| {
                calls += 1;
                f(t)
            },
            pts,
            TOL,
        );
        assert_abs_diff_eq!(x, 0.31, epsilon = 1e-9);
        assert_abs_diff_eq!(v, 0.0, epsilon = 1e-16);
        // The samples are not evaluated again; parabolic steps converge in a few calls.
        assert!(calls <= 12, "{calls} calls");
    }

    #[test]
    fn end_maximum_of_a_rising_function_is_the_end() {
        let f = |t: f64| t.sin();
        let mut calls = 0;
        let (x, v) = refine_end(
            |t| {
                calls += 1;
                f(t)
            },
            (1.0, f(1.0)),
            (0.9, f(0.9)),
            TOL,
        );
        assert_eq!((x, v), (1.0, 1f64.sin()));
        assert_eq!(calls, 1);
    }

    #[test]
    fn end_maximum_inside_the_last_interval_is_found() {
        // Peak at 0.97, between the samples 0.9 and 1.0.
        let f = |t: f64| -(t - 0.97) * (t - 0.97);
        let (x, v) = refine_end(f, (1.0, f(1.0)), (0.9, f(0.9)), TOL);
        assert_abs_diff_eq!(x, 0.97, epsilon = 1e-8);
        assert_abs_diff_eq!(v, 0.0, epsilon = 1e-15);
    }
}
