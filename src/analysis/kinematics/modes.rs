//! The mechanisms of a pattern of active joints: the null space of its compatibility system
//! (SVD, relative rank tolerance `tol_rank`) and, within it, the fields obeying the flow
//! rules: the extreme rays of the cone of admissible fields (one for a single mechanism, two at
//! a bifurcation).

use super::{
    ActiveJoint, Compatibility, FlowRule, KinematicsError, KinematicsSettings, VelocityField,
};
use crate::analysis::statics::ArchGeometry;
use nalgebra::DMatrix;

/// An orthonormal basis (as columns) of the null space of `a`, by SVD with the relative
/// tolerance `tol_rank`; `None` when an entry is not finite.
///
/// The system is equilibrated first (rows and columns scaled to unit length; the null space
/// is mapped back through the column scaling and orthonormalised): the rotation columns of a
/// compatibility system carry lengths over r, so on a very thick arch (K = 10⁶) they dwarf
/// the translation columns and a tolerance relative to the largest singular value would
/// drop genuine constraints.
pub fn null_space(a: &DMatrix<f64>, settings: &KinematicsSettings) -> Option<DMatrix<f64>> {
    let (m, n) = a.shape();
    if n == 0 {
        return Some(DMatrix::zeros(0, 0));
    }
    if a.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let scale: Vec<f64> = (0..n)
        .map(|j| {
            let c = a.column(j).norm();
            if c > 0.0 { 1.0 / c } else { 1.0 }
        })
        .collect();
    // Pad to at least n rows so that the SVD returns the full V.
    let mut padded = DMatrix::zeros(m.max(n), n);
    for i in 0..m {
        let r = (0..n).map(|j| a[(i, j)] * scale[j]).collect::<Vec<f64>>();
        let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        let k = if norm > 0.0 { 1.0 / norm } else { 1.0 };
        for (j, v) in r.iter().enumerate() {
            padded[(i, j)] = v * k;
        }
    }
    let svd = nalgebra::SVD::try_new(
        padded,
        false,
        true,
        f64::EPSILON,
        settings.max_svd_iterations,
    )?;
    let v_t = svd.v_t?;
    let top = svd.singular_values.iter().fold(0.0_f64, |x, &s| x.max(s));
    let tol = settings.tol_rank * top.max(1.0);
    let cols: Vec<usize> = (0..n).filter(|&i| svd.singular_values[i] <= tol).collect();
    let basis = DMatrix::from_fn(n, cols.len(), |r, c| scale[r] * v_t[(cols[c], r)]);
    if cols.is_empty() {
        return Some(basis);
    }
    Some(basis.qr().q())
}

/// Outcome of the search for a mechanism of a pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModeStatus {
    /// At least one mode obeys normality and dissipation.
    Admissible,
    /// Modes exist but every one breaches a flow rule; the least-violating one is given.
    Inadmissible,
    /// The pattern does not move (null space of dimension 0).
    Rigid,
    /// The system could not be solved (non-finite geometry or an SVD failure).
    Failed,
}

impl ModeStatus {
    /// `admissible`, `inadmissible`, `rigid` or `failed`.
    pub fn as_str(self) -> &'static str {
        match self {
            ModeStatus::Admissible => "admissible",
            ModeStatus::Inadmissible => "inadmissible",
            ModeStatus::Rigid => "rigid",
            ModeStatus::Failed => "failed",
        }
    }
}

/// The mechanisms of a pattern of active joints.
#[derive(Debug, Clone, PartialEq)]
pub struct Modes {
    /// How the search ended.
    pub status: ModeStatus,
    /// Dimension of the null space of the compatibility system (`mechanism_dof`).
    pub dof: u32,
    /// Dimension of its mirror-symmetric part, when the pattern is symmetric and the symmetric
    /// modes were asked for.
    pub symmetric_dof: Option<u32>,
    /// The admissible modes: the extreme rays of the cone of (symmetric, when asked) fields
    /// obeying the flow rules, normalised; one for a single-mechanism state, two at a
    /// bifurcation. When none is admissible, the least-violating mode alone.
    pub fields: Vec<VelocityField>,
}

/// The mechanisms of a pattern with the default settings ([`mechanism_modes_with`]).
pub fn mechanism_modes<G: ArchGeometry + ?Sized>(
    geom: &G,
    joints: &[ActiveJoint],
    rule: FlowRule,
    prefer_symmetric: bool,
) -> Result<Modes, KinematicsError> {
    mechanism_modes_with(
        geom,
        joints,
        rule,
        prefer_symmetric,
        &KinematicsSettings::DEFAULT,
    )
}

/// The mechanisms of a pattern: the null space of its compatibility system and, within it
/// (within its symmetric part when `prefer_symmetric`, the pattern is symmetric and that part
/// is not empty; otherwise in the whole null space), the
/// fields obeying the normality rule at the hinges (eq. 5 with δα of the sign of the face)
/// and maximum dissipation at sliding joints that carry a sense (eq. 10).
pub fn mechanism_modes_with<G: ArchGeometry + ?Sized>(
    geom: &G,
    joints: &[ActiveJoint],
    rule: FlowRule,
    prefer_symmetric: bool,
    settings: &KinematicsSettings,
) -> Result<Modes, KinematicsError> {
    let sys = Compatibility::new(geom, joints, rule, settings)?;
    let failed = |dof| Modes {
        status: ModeStatus::Failed,
        dof,
        symmetric_dof: None,
        fields: Vec::new(),
    };
    let Some(full) = null_space(&sys.matrix, settings) else {
        return Ok(failed(0));
    };
    let dof = full.ncols() as u32;
    let (basis, symmetric_dof) = if prefer_symmetric && sys.is_symmetric() {
        let sym = sys.symmetry_rows();
        let stacked = DMatrix::from_fn(sys.matrix.nrows() + sym.nrows(), sys.columns(), |i, j| {
            if i < sys.matrix.nrows() {
                sys.matrix[(i, j)]
            } else {
                sym[(i - sys.matrix.nrows(), j)]
            }
        });
        let Some(b) = null_space(&stacked, settings) else {
            return Ok(failed(dof));
        };
        let d = b.ncols() as u32;
        // A symmetric state whose only modes are antisymmetric (a sway) collapses in those.
        if d == 0 {
            (full, Some(d))
        } else {
            (b, Some(d))
        }
    } else {
        (full, None)
    };
    if basis.ncols() == 0 {
        return Ok(Modes {
            status: ModeStatus::Rigid,
            dof,
            symmetric_dof,
            fields: Vec::new(),
        });
    }
    let (g, dissipation) = admissibility_in_basis(&sys, &basis);
    let rays = extreme_rays(&g, basis.ncols(), settings);
    let (status, coeffs) = if rays.is_empty() {
        (
            ModeStatus::Inadmissible,
            vec![least_violating(&g, &dissipation, basis.ncols(), settings)],
        )
    } else {
        (ModeStatus::Admissible, rays)
    };
    let fields = coeffs
        .iter()
        .filter_map(|c| {
            let x = &basis * nalgebra::DVector::from_column_slice(c);
            sys.normalised_field(x.as_slice())
        })
        .collect();
    Ok(Modes {
        status,
        dof,
        symmetric_dof,
        fields,
    })
}

/// The admissibility rows expressed on the basis coefficients, each scaled to unit length
/// (rows that vanish on the basis are dropped: those joints cannot move), and which of them
/// are dissipation rows.
fn admissibility_in_basis(sys: &Compatibility, basis: &DMatrix<f64>) -> (Vec<Vec<f64>>, Vec<bool>) {
    sys.admissibility_rows()
        .into_iter()
        .filter_map(|(r, dissipation)| {
            let row = nalgebra::RowDVector::from_row_slice(&r) * basis;
            let norm = row.norm();
            (norm > sys.settings.tol_rank)
                .then(|| (row.iter().map(|v| v / norm).collect(), dissipation))
        })
        .unzip()
}

/// The extreme rays of the cone {c : g c ≥ 0} in R^d (d ≤ 4), unit vectors in a stable
/// order; for a cone without constraints in one dimension, both directions.
fn extreme_rays(g: &[Vec<f64>], d: usize, settings: &KinematicsSettings) -> Vec<Vec<f64>> {
    if d > 4 {
        return Vec::new();
    }
    let mut rays: Vec<Vec<f64>> = Vec::new();
    for subset in combinations(g.len(), d - 1) {
        let a = DMatrix::from_fn(subset.len(), d, |i, j| g[subset[i]][j]);
        let Some(ns) = null_space(&a, settings) else {
            continue;
        };
        if ns.ncols() != 1 {
            continue;
        }
        for sign in [1.0, -1.0] {
            let c: Vec<f64> = ns.column(0).iter().map(|v| sign * v).collect();
            let feasible = g
                .iter()
                .all(|r| r.iter().zip(&c).map(|(a, b)| a * b).sum::<f64>() >= -settings.tol_cone);
            let known = rays.iter().any(|q| {
                q.iter().zip(&c).map(|(a, b)| (a - b).abs()).sum::<f64>() < settings.tol_same_ray
            });
            if feasible && !known {
                rays.push(c);
            }
        }
    }
    rays
}

/// All k-subsets of 0..n, in lexicographic order.
fn combinations(n: usize, k: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut cur = Vec::with_capacity(k);
    fn rec(start: usize, n: usize, k: usize, cur: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        if cur.len() == k {
            out.push(cur.clone());
            return;
        }
        for i in start..n {
            cur.push(i);
            rec(i + 1, n, k, cur, out);
            cur.pop();
        }
    }
    rec(0, n, k, &mut cur, &mut out);
    out
}

/// The mode kept when none obeys every flow rule. Friction must dissipate: among the extreme
/// rays of the cone of the dissipation rows alone (every sliding joint slips in the sense of
/// its state), the one whose worst normality value is largest; such a mode satisfies the work
/// equation (eq. 11), since a hinge's normal row makes its reactive work vanish whatever the
/// sign of its rotation. When no mode slides in the required senses, the basis direction
/// (±e_i) whose worst admissibility value is largest.
fn least_violating(
    g: &[Vec<f64>],
    dissipation: &[bool],
    d: usize,
    settings: &KinematicsSettings,
) -> Vec<f64> {
    let worst = |c: &[f64], rows: &mut dyn Iterator<Item = &Vec<f64>>| {
        rows.map(|r| r.iter().zip(c).map(|(a, b)| a * b).sum::<f64>())
            .fold(f64::INFINITY, f64::min)
    };
    let sliding: Vec<Vec<f64>> = g
        .iter()
        .zip(dissipation)
        .filter(|(_, s)| **s)
        .map(|(r, _)| r.clone())
        .collect();
    if !sliding.is_empty() {
        let best = extreme_rays(&sliding, d, settings)
            .into_iter()
            .map(|c| {
                let mut hinges = g
                    .iter()
                    .zip(dissipation)
                    .filter(|(_, s)| !**s)
                    .map(|(r, _)| r);
                (worst(&c, &mut hinges), c)
            })
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, c)) = best {
            return c;
        }
    }
    let mut best = (f64::NEG_INFINITY, vec![0.0; d]);
    for i in 0..d {
        for sign in [1.0, -1.0] {
            let worst = g.iter().map(|r| sign * r[i]).fold(f64::INFINITY, f64::min);
            if worst > best.0 {
                let mut c = vec![0.0; d];
                c[i] = sign;
                best = (worst, c);
            }
        }
    }
    best.1
}
