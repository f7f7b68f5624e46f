//! The refinement of a sampled local maximum of a joint's violation: Brent's method started
//! from the samples around it, whose values are already known, stopped once the violation
//! no longer changes above its rounding.

/// Largest number of steps of one refinement; it converges in far fewer, this only bounds
/// a pathological function.
const MAX_STEPS: usize = 200;
/// Relative tolerance on the argument added to the absolute one: about the spacing of
/// doubles near the argument.
const REL_ARG_TOL: f64 = 1e-15;
/// The golden section's smaller fraction, 1 − 1/φ.
const CGOLD: f64 = 0.381_966_011_250_105_1;
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
    brent(
        f,
        Bracket {
            a: lo.0,
            b: hi.0,
            x: mid,
            w,
            v,
        },
        tol,
    )
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
    brent(
        f,
        Bracket {
            a: end.0.min(next.0),
            b: end.0.max(next.0),
            x: inside,
            w: end,
            v: next,
        },
        tol,
    )
}

/// Brent's state: the bracket [a, b], the best point x, the second best w and the third v.
struct Bracket {
    a: f64,
    b: f64,
    x: Point,
    w: Point,
    v: Point,
}

/// Brent's method for a maximum from a bracket whose points are known (Numerical Recipes'
/// "brent", maximising). Besides the bracket shrinking to the argument tolerance, it stops
/// after a local parabolic step that puts the vertex within the argument tolerance or
/// changes the value by no more than `tol.flat`: near a smooth maximum the parabola's vertex
/// is the maximum, and shrinking the bracket around it as well would cost a dozen values
/// that only rounding tells apart.
fn brent<F: FnMut(f64) -> f64>(mut f: F, start: Bracket, tol: Tolerance) -> Point {
    let Bracket { mut a, mut b, .. } = start;
    let (mut x, mut fx) = start.x;
    let (mut w, mut fw) = start.w;
    let (mut v, mut fv) = start.v;
    let local = LOCAL_STEP * (b - a);
    // The first parabolic step is accepted as long as it stays inside the bracket.
    let (mut d, mut e): (f64, f64) = (b - a, b - a);
    for _ in 0..MAX_STEPS {
        let xm = 0.5 * (a + b);
        let tol1 = tol.arg + REL_ARG_TOL * x.abs();
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol1 {
            // The vertex of the parabola through x, w, v.
            let r = (x - w) * (fv - fx);
            let mut q = (x - v) * (fw - fx);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let etemp = e;
            if !(p.abs() >= (0.5 * q * etemp).abs() || p <= q * (a - x) || p >= q * (b - x)) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = tol1.copysign(xm - x);
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= xm { a - x } else { b - x };
            d = CGOLD * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else {
            x + tol1.copysign(d)
        };
        let fu = f(u);
        if fu.is_nan() {
            break;
        }
        let converged =
            !golden && (d.abs() < tol1 || (d.abs() < local && (fu - fx).abs() <= tol.flat));
        if fu >= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, w, x) = (w, x, u);
            (fv, fw, fx) = (fw, fx, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu >= fw || w == x {
                (v, w) = (w, u);
                (fv, fw) = (fw, fu);
            } else if fu >= fv || v == x || v == w {
                v = u;
                fv = fu;
            }
        }
        if converged {
            break;
        }
    }
    (x, fx)
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
