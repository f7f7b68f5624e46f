//! The other end of the non-associative gap: the first complete solution along a find's path.
//!
//! With Coulomb friction and no dilatancy the flow rule is non-associative and the static
//! theorem does not hold: the static limit (the largest λ at which an admissible state exists)
//! is only the upper end of a gap within which the collapse "is a priori not unique"
//! (docs/mechanics.md §5). A *complete solution* at a value is an admissible state together
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
//! [`walk`] visits every vertex from the static limit along the edges.

pub mod hull;
mod mechanism;
mod rows;
mod walk;

pub use mechanism::{MovingMechanism, StateY, WorkCheck};

use self::mechanism::JointMove;
use self::rows::{RowKind, StateRows};
use self::walk::{Vertex, WalkLimits};
use super::lp;
use super::statics::ArchGeometry;
pub use crate::analysis::settings::GapSettings as Settings;

/// Which end of the gap a find's answer sits at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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
}

impl GapSearch {
    fn failed(range: [f64; 2]) -> Self {
        GapSearch {
            status: GapStatus::Failed,
            first: None,
            static_limit: None,
            range,
            vertices: 0,
        }
    }
}

/// The joints a search uses: a discrete arch's own; for a continuum, `continuum_joints` per
/// family, ends included, and the isolated joints.
fn joints_of<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> Vec<f64> {
    if let Some(j) = geom.discrete_joints() {
        return j;
    }
    let n = settings.continuum_joints.max(2);
    let mut out: Vec<f64> = geom.isolated_joints();
    for [a, b] in geom.families() {
        for k in 0..n {
            out.push(a + (b - a) * k as f64 / (n - 1) as f64);
        }
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// The first complete solution along increasing λ ≥ 0 at friction angle φ (radians): the
/// lowest load factor at which the live load of `geom` on its dead load can start a mechanism.
pub fn first_complete_load_factor<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    settings: &Settings,
) -> GapSearch {
    let range = [0.0, settings.lambda_cap];
    let thetas = joints_of(geom, settings);
    let rows = StateRows::new(geom, &thetas, phi, settings.lambda_cap, settings.state_cap);
    let lp_settings = lp::Settings::for_rows(rows.len());
    let Ok(top) = lp::maximise(&[0.0, 0.0, 0.0, 1.0], &rows.a, &rows.b, &lp_settings) else {
        return GapSearch::failed(range);
    };
    match top.status {
        lp::Status::Optimal => {}
        lp::Status::Infeasible => {
            return GapSearch {
                status: GapStatus::NoCompleteSolution,
                first: None,
                static_limit: None,
                range,
                vertices: 0,
            };
        }
        _ => return GapSearch::failed(range),
    }
    let limits = WalkLimits {
        tol_tight: settings.tol_tight,
        max_vertices: settings.max_vertices,
        max_tight: settings.max_tight,
    };
    let Ok(vertices) = walk::vertices(&rows.a, &rows.b, top.x, &limits) else {
        return GapSearch::failed(range);
    };
    let mu = phi.tan();
    let mut best: Option<(f64, Vec<JointMove>, [f64; 4])> = None;
    for v in &vertices {
        if best.as_ref().is_some_and(|(l, _, _)| *l <= v.y[3]) {
            continue;
        }
        if let Some(moves) = complete_moves(geom, &rows, v, settings) {
            best = Some((v.y[3], moves, v.y));
        }
    }
    let static_limit = top.x[3];
    let first = best.and_then(|(_, moves, y)| {
        let state = StateY { y, mu };
        let angle = |t: f64| geom.angle_deg(t);
        mechanism::check(geom, &moves, &state, &angle).map(|m| Complete {
            state,
            mechanism: m,
        })
    });
    let status = match &first {
        None => GapStatus::NoCompleteSolution,
        Some(c) if static_limit - c.state.y[3] > settings.tol_gap * (1.0 + static_limit.abs()) => {
            GapStatus::Gap
        }
        Some(_) => GapStatus::NoGap,
    };
    GapSearch {
        status,
        first,
        static_limit: Some(static_limit),
        range,
        vertices: vertices.len(),
    }
}

/// The moving joints of a complete solution at vertex `v`, or `None` when the twists of its
/// tight rows are not positively dependent.
fn complete_moves<G: ArchGeometry + ?Sized>(
    geom: &G,
    rows: &StateRows,
    v: &Vertex,
    settings: &Settings,
) -> Option<Vec<JointMove>> {
    let mut twists: Vec<[f64; 3]> = Vec::new();
    let mut joints: Vec<usize> = Vec::new();
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
        if zero_force_only && !carries_no_force(geom, rows.thetas[joint], &v.y, settings) {
            continue;
        }
        twists.push(t);
        joints.push(joint);
    }
    if twists.len() < 2 {
        return None;
    }
    let m = hull::min_norm_point(&twists, settings.tol_hull)?;
    if m.norm() > settings.tol_complete {
        return None;
    }
    let mut moves: Vec<JointMove> = Vec::new();
    for (k, w) in m.weights.iter().enumerate() {
        if *w <= settings.tol_hull {
            continue;
        }
        let theta = rows.thetas[joints[k]];
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
        for c in 0..3 {
            moves[idx].relative[c] -= w * twists[k][c];
        }
    }
    moves.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    Some(moves)
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

#[cfg(test)]
mod tests;
