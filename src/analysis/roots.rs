//! Bracketing root finding and concave maximisation in one variable.
//!
//! Everything here is guaranteed to terminate and keeps a valid bracket: the critical
//! values of archstudy are roots of continuous, monotone margin functions, found by Brent's
//! method, never by fixed-step scans.

/// Largest number of steps of [`brent`]; it converges in far fewer, this only bounds a
/// pathological function.
const MAX_ROOT_STEPS: usize = 400;
/// Largest number of steps of [`maximise_1d`].
const MAX_MAXIMISE_STEPS: usize = 200;
/// Relative tolerance on the argument added to the absolute one in [`maximise_1d`]: about
/// the spacing of doubles near x.
const REL_ARG_TOL: f64 = 1e-15;

/// Brent's method for a root of `f` in `[a, b]`, where `f(a)` and `f(b)` differ in sign (or one
/// is zero). Stops when the bracket is shorter than `tol` (absolute) plus four ulps.
///
/// Returns the end of the final bracket on the side where `f` has the sign of `f(b)` (the
/// "feasible" side when `f(b) ≥ 0`), so a caller can rely on which side of the root it gets.
pub fn brent<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, tol: f64) -> Option<f64> {
    let (fa, fb) = (f(a), f(b));
    brent_with_values(&mut f, a, fa, b, fb, tol)
}

/// [`brent`] with the end values already known.
pub fn brent_with_values<F: FnMut(f64) -> f64>(
    f: &mut F,
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    tol: f64,
) -> Option<f64> {
    if fa.is_nan() || fb.is_nan() {
        return None;
    }
    if fb == 0.0 {
        return Some(b);
    }
    if fa == 0.0 {
        return Some(a);
    }
    if fa.signum() == fb.signum() {
        return None;
    }
    let target_sign = fb.signum();
    // Classic Brent (Numerical Recipes "zbrent" structure), b is the best estimate.
    let (mut a, mut b, mut fa, mut fb) = (a, b, fa, fb);
    let mut c = a;
    let mut fc = fa;
    let mut d = b - a;
    let mut e = d;
    for _ in 0..MAX_ROOT_STEPS {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb == 0.0 {
            // [b, c] brackets the root; return the end with the requested sign.
            return Some(if fb == 0.0 || fb.signum() == target_sign {
                b
            } else {
                c
            });
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            let min1 = 3.0 * xm * q - (tol1 * q).abs();
            let min2 = (e * q).abs();
            if 2.0 * p < min1.min(min2) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
        fb = f(b);
        if fb.is_nan() {
            return None;
        }
    }
    Some(if fb.signum() == target_sign { b } else { c })
}

/// Maximiser of a concave function on `[lo, hi]` given its (super)gradient `slope`, which is
/// non-increasing. Returns `lo` when the slope is already ≤ 0 there and `hi` when it is still
/// > 0 at `hi`. Bisection with secant steps (Brent on the slope), to `tol`.
pub fn argmax_concave<D: FnMut(f64) -> f64>(mut slope: D, lo: f64, hi: f64, tol: f64) -> f64 {
    let slo = slope(lo);
    if slo <= 0.0 {
        return lo;
    }
    let shi = slope(hi);
    if shi > 0.0 {
        return hi;
    }
    // The slope may jump at kinks; Brent falls back to bisection there.
    brent_with_values(&mut slope, lo, slo, hi, shi, tol).unwrap_or(0.5 * (lo + hi))
}

/// The golden section's smaller fraction, 1 − 1/φ.
const CGOLD: f64 = 0.381_966_011_250_105_1;

/// Brent's method for a local maximum of `f` on [a, b] (golden section with parabolic
/// steps), to an absolute tolerance `tol` in the argument. Returns (argmax, max).
pub fn maximise_1d<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, tol: f64) -> (f64, f64) {
    let (a, b) = (a.min(b), a.max(b));
    let x = a + CGOLD * (b - a);
    let first = (x, f(x));
    let start = MaxBracket {
        a,
        b,
        x: first,
        w: first,
        v: first,
        step: 0.0,
    };
    maximise_from(f, start, tol, None)
}

/// The state [`maximise_from`] starts from: the bracket [a, b] of a local maximum, the best
/// point x seen so far with its value, the second best w and the third v, and the length of
/// the step before last (0 for a fresh start; the bracket's length lets the first parabolic
/// step through x, w and v be taken as long as it stays inside the bracket).
#[derive(Debug, Clone, Copy)]
pub struct MaxBracket {
    /// Lower end of the bracket.
    pub a: f64,
    /// Upper end of the bracket.
    pub b: f64,
    /// The best point and its value; a ≤ x ≤ b.
    pub x: (f64, f64),
    /// The second best point and its value.
    pub w: (f64, f64),
    /// The third best point and its value.
    pub v: (f64, f64),
    /// The length of the step before last.
    pub step: f64,
}

/// An early stop of [`maximise_from`] for a smooth maximum known only to the rounding of its
/// value: a parabolic step shorter than `local` that changes the value by no more than `flat`
/// (or is shorter than the argument tolerance) ends the search, since near a smooth maximum
/// the parabola's vertex is the maximum and shrinking the bracket around it as well would cost
/// a dozen values that only rounding tells apart.
#[derive(Debug, Clone, Copy)]
pub struct FlatStop {
    /// Length below which a parabolic step counts as a local one.
    pub local: f64,
    /// Change of the value a local step must exceed for the search to go on.
    pub flat: f64,
}

/// Brent's method for a local maximum from a bracket whose points are known (Numerical
/// Recipes' "brent", maximising), to an absolute tolerance `tol` in the argument, and with
/// `stop` also after a local parabolic step that no longer changes the value. Returns
/// (argmax, max); the value is never below the start's best.
pub fn maximise_from<F: FnMut(f64) -> f64>(
    mut f: F,
    start: MaxBracket,
    tol: f64,
    stop: Option<FlatStop>,
) -> (f64, f64) {
    let MaxBracket { mut a, mut b, .. } = start;
    let (mut x, mut fx) = start.x;
    let (mut w, mut fw) = start.w;
    let (mut v, mut fv) = start.v;
    let (mut d, mut e): (f64, f64) = (start.step, start.step);
    for _ in 0..MAX_MAXIMISE_STEPS {
        let xm = 0.5 * (a + b);
        let tol1 = tol + REL_ARG_TOL * x.abs();
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
        let converged = stop.is_some_and(|s| {
            !golden && (d.abs() < tol1 || (d.abs() < s.local && (fu - fx).abs() <= s.flat))
        });
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

    #[test]
    fn brent_finds_cube_root_of_two() {
        let x = brent(|x| x * x * x - 2.0, 0.0, 2.0, 1e-15).unwrap();
        assert_abs_diff_eq!(x, 2f64.cbrt(), epsilon = 1e-14);
    }

    #[test]
    fn brent_returns_the_side_with_the_sign_of_fb() {
        // Step function: root at 0.3, feasible side (f ≥ 0) to the right.
        let x = brent(|x| if x >= 0.3 { 1.0 } else { -1.0 }, 0.0, 1.0, 1e-12).unwrap();
        assert!(x >= 0.3 && x - 0.3 < 1e-11);
    }

    #[test]
    fn brent_rejects_a_bracket_without_sign_change() {
        assert!(brent(|x| x * x + 1.0, -1.0, 1.0, 1e-12).is_none());
    }

    #[test]
    fn argmax_of_a_kinked_concave_function() {
        // f = min(2x, 3 - x): maximum at x = 1.
        let x = argmax_concave(
            |x| if 2.0 * x < 3.0 - x { 2.0 } else { -1.0 },
            -5.0,
            5.0,
            1e-14,
        );
        assert_abs_diff_eq!(x, 1.0, epsilon = 1e-13);
    }

    #[test]
    fn maximise_1d_finds_interior_and_end_maxima() {
        let (x, f) = maximise_1d(|t| -(t - 0.3) * (t - 0.3), 0.0, 1.0, 1e-12);
        assert_abs_diff_eq!(x, 0.3, epsilon = 1e-8);
        assert_abs_diff_eq!(f, 0.0, epsilon = 1e-16);
        let (x, _) = maximise_1d(|t| t, 0.0, 1.0, 1e-12);
        assert!(x > 1.0 - 1e-9);
    }
}
