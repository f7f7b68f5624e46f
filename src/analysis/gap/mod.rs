//! The other end of the non-associative gap: the first complete solution along a find's path.
//!
//! With Coulomb friction and no dilatancy the flow rule is non-associative and the static
//! theorem does not hold: the static limit (the largest λ at which an admissible state exists)
//! is only the upper end of a gap within which the collapse "is a priori not unique"
//! (docs/mechanics.md §4). A *complete solution* at a value is an admissible state together
//! with a mechanism whose moving joints obey the flow rules at that state: a hinge turns about
//! the face where the resultant sits and opens at the other, a sliding joint slips without
//! opening against a friction force μN, a joint that carries no force may open freely
//! (lift-off), a group of blocks may translate; every other joint stays closed. From the first
//! complete solution met along the path a mechanism can start.
//!
//! Every row of the statics ([`rows`]) allows one twist at its limit; a state y is complete
//! exactly when the twists of its tight rows are positively dependent (a non-negative, not all
//! zero, combination vanishes: the blocks then close up between the fixed supports), which
//! [`hull`] decides as "the origin lies in their convex hull". In the space y = (F_x, F_y, M₀,
//! λ) the admissible states form a convex polytope (a discrete arch); a complete solution at λ
//! lies on a face whose rows are positively dependent, and the lowest λ on that face is a
//! vertex with at least those rows tight. So the first complete λ is the lowest complete vertex:
//! [`walk`] visits every vertex from the static limit along the edges. A continuum is walked
//! on sampled joints, and joints where the lowest complete vertex violates a row are added
//! until it violates none (an exchange, as for the static limit): an admissible state whose
//! tight rows at real joints are positively dependent is a complete solution of the continuum.

pub mod hull;
mod joints;
mod load_factor;
mod mechanism;
mod path;
mod refine;
mod rows;
mod walk;

pub use load_factor::first_complete_load_factor;
pub use mechanism::{MovingMechanism, StateY, WorkCheck};

use self::mechanism::JointMove;
use self::rows::{RowKind, StateRows};
use self::walk::Vertex;
use super::statics::ArchGeometry;
pub use crate::analysis::settings::GapSettings as Settings;

/// Which end of the gap a find's answer sits at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GapStatus {
    /// The static limit is the first complete solution: no gap.
    NoGap,
    /// A complete solution comes before the static limit along the path.
    Gap,
    /// No complete solution within the searched range.
    NoCompleteSolution,
    /// The search could not finish (too many vertices or a failed programme).
    Failed,
}

impl GapStatus {
    /// Every status.
    pub const ALL: [GapStatus; 4] = [
        GapStatus::NoGap,
        GapStatus::Gap,
        GapStatus::NoCompleteSolution,
        GapStatus::Failed,
    ];

    /// `no_gap`, `gap`, `no_complete_solution` or `failed`.
    pub fn as_str(self) -> &'static str {
        match self {
            GapStatus::NoGap => "no_gap",
            GapStatus::Gap => "gap",
            GapStatus::NoCompleteSolution => "no_complete_solution",
            GapStatus::Failed => "failed",
        }
    }
}

/// A complete solution: the value, the state and the mechanism that starts there.
#[derive(Debug, Clone, PartialEq)]
pub struct Complete {
    /// The value of the find's parameter there: λ, K or μ.
    pub value: f64,
    /// The state (F_x, F_y, M₀, λ) and μ.
    pub state: StateY,
    /// The mechanism, with its work equation and flow rules checked.
    pub mechanism: MovingMechanism,
}

/// The result of a search for the first complete solution.
#[derive(Debug, Clone, PartialEq)]
pub struct GapSearch {
    /// Which case holds.
    pub status: GapStatus,
    /// The first complete solution along the path, when one was found.
    pub first: Option<Complete>,
    /// The static limit the path ends at (λ_max), when the arch stands anywhere on it.
    pub static_limit: Option<f64>,
    /// The searched range of the path's parameter.
    pub range: [f64; 2],
    /// Vertices visited.
    pub vertices: usize,
    /// True when a thickness or friction path was walked from its start through its static
    /// limit without meeting any complete state (false when one was met but could not be
    /// finished, when the search failed, and on the λ search).
    pub met_nothing: bool,
}

impl GapSearch {
    pub(super) fn failed(range: [f64; 2]) -> Self {
        GapSearch {
            status: GapStatus::Failed,
            first: None,
            static_limit: None,
            range,
            vertices: 0,
            met_nothing: false,
        }
    }
}

/// The moving joints of a complete solution at vertex `v` and the rows (indices into `rows`)
/// whose twists move them, or `None` when the twists of its tight rows are not positively
/// dependent.
fn complete_moves<G: ArchGeometry + ?Sized>(
    geom: &G,
    rows: &StateRows,
    v: &Vertex,
    settings: &Settings,
) -> Option<(Vec<JointMove>, Vec<usize>)> {
    // A vertex on the box of the state or on the cap of λ is an artefact of those bounds.
    if v.tight
        .iter()
        .any(|&r| rows.kind[r] == RowKind::Bound && rows.a[r][3] >= 0.0)
    {
        return None;
    }
    let mut twists: Vec<([f64; 3], f64)> = Vec::new();
    let mut index: Vec<usize> = Vec::new();
    for &r in &v.tight {
        let RowKind::Joint {
            joint,
            twist: Some(t),
            zero_force_only,
            ..
        } = rows.kind[r]
        else {
            continue;
        };
        let theta = rows.thetas[joint];
        if zero_force_only && !carries_no_force(geom, theta, &v.y, settings) {
            continue;
        }
        twists.push((t, theta));
        index.push(r);
    }
    let (moves, support) = moves_of(&twists, settings)?;
    Some((moves, support.into_iter().map(|i| index[i]).collect()))
}

/// The moving joints of the twists (each with its joint parameter) when they are positively
/// dependent with some joint moving: each joint moves by −Σ w_i t_i over its own rows, w the
/// weights of the origin in their hull.
///
/// A joint whose cone of twists holds a line (both Coulomb rows of a joint carrying no force:
/// ±τ; both faces of a joint shrunk to a point) would let the weights cancel within it while
/// nothing moves; each such opposite pair is tried with one of its twists at a time, so that
/// every joint's cone is pointed and a vanishing combination moves some joint.
fn moves_of(
    twists: &[([f64; 3], f64)],
    settings: &Settings,
) -> Option<(Vec<JointMove>, Vec<usize>)> {
    if twists.len() < 2 {
        return None;
    }
    let vectors: Vec<[f64; 3]> = twists.iter().map(|t| t.0).collect();
    if hull::farther_than(&vectors, settings.tol_complete) {
        return None;
    }
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for i in 0..twists.len() {
        for j in i + 1..twists.len() {
            let (a, b) = (twists[i], twists[j]);
            if a.1 == b.1 && (0..3).all(|c| (a.0[c] + b.0[c]).abs() <= settings.tol_complete) {
                pairs.push((i, j));
            }
        }
    }
    let variants = 1usize << pairs.len().min(MAX_OPPOSITE_PAIRS);
    (0..variants).find_map(|mask| {
        let dropped: Vec<usize> = pairs
            .iter()
            .take(MAX_OPPOSITE_PAIRS)
            .enumerate()
            .map(|(k, &(i, j))| if mask >> k & 1 == 0 { j } else { i })
            .collect();
        let kept: Vec<usize> = (0..twists.len()).filter(|i| !dropped.contains(i)).collect();
        let sub: Vec<([f64; 3], f64)> = kept.iter().map(|&i| twists[i]).collect();
        moves_of_pointed(&sub, settings)
            .map(|(m, support)| (m, support.into_iter().map(|i| kept[i]).collect()))
    })
}

/// Opposite pairs of twists tried one at a time, at most (2^this variants).
const MAX_OPPOSITE_PAIRS: usize = 4;

/// [`moves_of`] for twists whose joint cones are pointed; the support is the indices of the
/// twists with positive weight.
fn moves_of_pointed(
    twists: &[([f64; 3], f64)],
    settings: &Settings,
) -> Option<(Vec<JointMove>, Vec<usize>)> {
    if twists.len() < 2 {
        return None;
    }
    let vectors: Vec<[f64; 3]> = twists.iter().map(|t| t.0).collect();
    let m = hull::min_norm_point(&vectors, settings.tol_hull)?;
    if m.norm() > settings.tol_complete {
        return None;
    }
    let mut moves: Vec<JointMove> = Vec::new();
    let mut support = Vec::new();
    for (k, w) in m.weights.iter().enumerate() {
        if *w <= settings.tol_hull {
            continue;
        }
        support.push(k);
        let (t, theta) = twists[k];
        let idx = match moves.iter().position(|mv| mv.theta == theta) {
            Some(i) => i,
            None => {
                moves.push(JointMove {
                    theta,
                    relative: [0.0; 3],
                });
                moves.len() - 1
            }
        };
        for (r, tc) in moves[idx].relative.iter_mut().zip(&t) {
            *r -= w * tc;
        }
    }
    moves.retain(|mv| mv.relative.iter().any(|v| v.abs() > settings.tol_complete));
    if moves.len() < 2 {
        return None;
    }
    moves.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    Some((moves, support))
}

/// True when the joint at θ transmits no force and no moment at state y.
fn carries_no_force<G: ArchGeometry + ?Sized>(
    geom: &G,
    theta: f64,
    y: &[f64; 4],
    settings: &Settings,
) -> bool {
    let c = geom
        .dead_load(theta)
        .plus(geom.live_load(theta).scale(y[3]));
    let size = 1.0 + y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let f = (y[0] + c.fx).hypot(y[1] + c.fy).max((y[2] + c.m).abs());
    f <= settings.tol_tight * size
}

/// The first complete solution along decreasing μ, from [`Settings::mu_start`] down to the
/// static limit `mu_static` (the critical friction), at the fixed load factor `lambda` of the
/// live load of `geom`.
pub fn first_complete_friction<G: ArchGeometry + Copy>(
    geom: &G,
    lambda: f64,
    mu_static: f64,
    settings: &Settings,
) -> GapSearch {
    let g = *geom;
    let at = move |phi: f64| Some((g, phi));
    let start = settings.mu_start.max(mu_static).atan();
    let end = mu_static.atan();
    let walked = path::first_complete(
        &at,
        (start, end, settings.phi_step_deg.to_radians()),
        lambda,
        path::Path::Friction,
        settings,
    );
    path::search_result(walked, f64::tan, mu_static, start, settings)
}

/// The first complete solution along decreasing K, from `k_start` down to the static limit
/// `k_static` (the critical thickness), at friction angle φ and the fixed load factor
/// `lambda`; `make` gives the arch at K (`None` where the form does not exist).
pub fn first_complete_thickness<G: ArchGeometry + Copy>(
    make: &dyn Fn(f64) -> Option<G>,
    phi: f64,
    lambda: f64,
    k_static: f64,
    k_start: f64,
    settings: &Settings,
) -> GapSearch {
    let at = |k: f64| make(k).map(|g| (g, phi));
    let walked = path::first_complete(
        &at,
        (k_start.max(k_static), k_static, settings.k_step),
        lambda,
        path::Path::Thickness,
        settings,
    );
    path::search_result(walked, |k| k, k_static, k_start, settings)
}

#[cfg(test)]
mod tests;
