//! A complete state found on sampled joints of a continuum, solved on the continuum itself:
//! its tight rows stay tight, and a row at a joint inside a family of joints is tangent there
//! (its value is stationary in the joint parameter), as at a hinge of the continuum. Newton's
//! method on those equations in (F_x, F_y, M₀, p, θ of each inner joint), from the sampled
//! state; the result counts only when it violates no joint of the continuum and its twists
//! stay positively dependent.

use super::path::{FoundState, SceneAt};
use super::rows::row_at;
use super::{Settings, moves_of};
use crate::analysis::general;
use crate::analysis::statics::{ArchGeometry, Condition};

/// Where a row of a pattern sits.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Joint {
    /// The i-th end of a family or isolated joint (they move with p on some forms).
    End(usize),
    /// A joint inside a family, free to move; the value is where Newton starts.
    Inner(f64),
}

/// The tight rows of a complete state on a continuum.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Pattern {
    rows: Vec<(Joint, Condition)>,
}

/// The ends of the families and the isolated joints of a continuum, increasing.
fn ends<G: ArchGeometry + ?Sized>(geom: &G) -> Vec<f64> {
    let mut e = geom.isolated_joints();
    for [a, b] in geom.families() {
        e.push(a);
        e.push(b);
    }
    e.sort_by(f64::total_cmp);
    e.dedup();
    e
}

impl Pattern {
    /// The pattern of tight rows `tight` (joint parameter and condition) of a state on the
    /// sampled joints `thetas`: rows at family ends or isolated joints stay there; rows of one
    /// condition at neighbouring samples inside a family are one inner joint between them.
    pub(super) fn of<G: ArchGeometry + ?Sized>(
        geom: &G,
        tight: &[(f64, Condition)],
        thetas: &[f64],
    ) -> Self {
        let e = ends(geom);
        let index = |t: f64| thetas.iter().position(|&s| s == t);
        let mut rows: Vec<(Joint, Condition, Option<usize>)> = Vec::new();
        for &(t, c) in tight {
            if let Some(i) = e
                .iter()
                .position(|&x| (x - t).abs() <= 1e-12 * (1.0 + x.abs()))
            {
                if !rows.iter().any(|r| r.0 == Joint::End(i) && r.1 == c) {
                    rows.push((Joint::End(i), c, None));
                }
                continue;
            }
            let at = index(t);
            let neighbour = rows.iter_mut().find(|r| {
                r.1 == c
                    && matches!(r.0, Joint::Inner(_))
                    && matches!((r.2, at), (Some(a), Some(b)) if a.abs_diff(b) == 1)
            });
            match neighbour {
                Some(r) => {
                    if let Joint::Inner(s) = r.0 {
                        r.0 = Joint::Inner(0.5 * (s + t));
                    }
                }
                None => rows.push((Joint::Inner(t), c, at)),
            }
        }
        Pattern {
            rows: rows.into_iter().map(|(j, c, _)| (j, c)).collect(),
        }
    }

    fn inner(&self) -> usize {
        self.rows
            .iter()
            .filter(|r| matches!(r.0, Joint::Inner(_)))
            .count()
    }
}

/// Step of the central difference of a row's value in the joint parameter (radians).
const H_THETA: f64 = 1e-6;
/// Relative step of the forward differences of the Jacobian.
const H_JACOBIAN: f64 = 1e-7;
/// Newton steps.
const MAX_NEWTON: usize = 40;
/// Tolerance of a tangency equation, relative to 1 + |y|∞: rounding in the central
/// difference of a row's value is about 1e-16/H_THETA.
const TOL_TANGENCY: f64 = 1e-8;

/// Newton's method on `residual` from `u` (forward-difference Jacobian, least-squares
/// steps) until `converged`; the last residual.
fn newton(
    residual: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    u: &mut [f64],
    n_eq: usize,
    converged: &dyn Fn(&[f64]) -> bool,
) -> Option<Vec<f64>> {
    let mut f = residual(u)?;
    for _ in 0..MAX_NEWTON {
        if converged(&f) {
            break;
        }
        let mut jac = nalgebra::DMatrix::<f64>::zeros(n_eq, u.len());
        for c in 0..u.len() {
            let h = H_JACOBIAN * (1.0 + u[c].abs());
            let mut v = u.to_vec();
            v[c] += h;
            let g = residual(&v)?;
            for r in 0..n_eq {
                jac[(r, c)] = (g[r] - f[r]) / h;
            }
        }
        let rhs = nalgebra::DVector::from_iterator(n_eq, f.iter().map(|v| -v));
        let step = least_squares(jac, &rhs)?;
        for (ui, si) in u.iter_mut().zip(step.iter()) {
            *ui += si;
        }
        f = residual(u)?;
    }
    Some(f)
}

/// Iterations of an SVD before it is given up.
const MAX_SVD_ITERATIONS: usize = 200;

/// The least-squares solution of a x = b by SVD; `None` for non-finite input or an SVD that
/// does not converge.
pub(super) fn least_squares(
    a: nalgebra::DMatrix<f64>,
    b: &nalgebra::DVector<f64>,
) -> Option<nalgebra::DVector<f64>> {
    if a.iter().chain(b.iter()).any(|v| !v.is_finite()) {
        return None;
    }
    let svd = nalgebra::SVD::try_new(a, true, true, f64::EPSILON, MAX_SVD_ITERATIONS)?;
    let x = svd.solve(b, 1e-14).ok()?;
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The complete state of the continuum near a sampled one: `None` when Newton does not
/// converge, the state violates a joint of the continuum, or its twists are not positively
/// dependent. On a path λ is fixed (`Some`); on a load-factor find (`None`) the path's
/// parameter p is λ itself.
pub(super) fn on_continuum<G: ArchGeometry>(
    at: SceneAt<'_, G>,
    pattern: &Pattern,
    p0: f64,
    y0: &[f64; 4],
    lambda: Option<f64>,
    settings: &Settings,
) -> Option<FoundState> {
    let inner = pattern.inner();
    let mut u: Vec<f64> = vec![y0[0], y0[1], y0[2], p0];
    for r in &pattern.rows {
        if let Joint::Inner(t) = r.0 {
            u.push(t);
        }
    }
    let n_eq = pattern.rows.len() + inner;
    let residual = |u: &[f64]| -> Option<Vec<f64>> {
        let (geom, phi) = at(u[3])?;
        let e = ends(&geom);
        let lambda = lambda.unwrap_or(u[3]);
        let value = |t: f64, c: Condition| -> Option<f64> {
            let r = row_at(&geom, t, phi, c)?;
            Some(r.a[0] * u[0] + r.a[1] * u[1] + r.a[2] * u[2] + r.a[3] * lambda - r.b)
        };
        let mut out = Vec::with_capacity(n_eq);
        let mut k = 4;
        for &(j, c) in &pattern.rows {
            match j {
                Joint::End(i) => out.push(value(*e.get(i)?, c)?),
                Joint::Inner(_) => {
                    let t = u[k];
                    k += 1;
                    out.push(value(t, c)?);
                    let d = (value(t + H_THETA, c)? - value(t - H_THETA, c)?) / (2.0 * H_THETA);
                    out.push(d);
                }
            }
        }
        Some(out)
    };
    let scale = 1.0 + y0.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    // The rows must hold to `tol_refine`; the tangency equations, differences of rounded
    // values over 2·H_THETA, only to where they place θ well enough (a row at a tangency
    // changes quadratically with θ).
    let is_value: Vec<bool> = pattern
        .rows
        .iter()
        .flat_map(|r| match r.0 {
            Joint::End(_) => vec![true],
            Joint::Inner(_) => vec![true, false],
        })
        .collect();
    let converged = |f: &[f64]| {
        f.iter().zip(&is_value).all(|(v, value)| {
            v.abs()
                <= if *value {
                    settings.tol_refine * scale
                } else {
                    TOL_TANGENCY * scale
                }
        })
    };
    let f = newton(&residual, &mut u, n_eq, &converged)?;
    if !converged(&f) {
        return None;
    }
    let (geom, phi) = at(u[3])?;
    let y = [u[0], u[1], u[2], lambda.unwrap_or(u[3])];
    if !general::violated_joints(&geom, phi, &y, &general::Settings::default()).is_empty() {
        return None;
    }
    let e = ends(&geom);
    let mut twists = Vec::new();
    let mut k = 4;
    for &(j, c) in &pattern.rows {
        let t = match j {
            Joint::End(i) => *e.get(i)?,
            Joint::Inner(_) => {
                k += 1;
                u[k - 1]
            }
        };
        if let Some(tw) = row_at(&geom, t, phi, c)?.twist {
            twists.push((tw, t));
        }
    }
    let (moves, _) = moves_of(&twists, settings)?;
    Some(FoundState {
        p: u[3],
        y,
        moves,
        support: Vec::new(),
    })
}
