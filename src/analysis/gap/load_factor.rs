//! The first complete solution along increasing λ: a walk over the vertices of the state
//! polytope, with an exchange of joints on a continuum.

use super::joints;
use super::mechanism::{self, JointMove, StateY};
use super::refine::{self, Pattern};
use super::rows::{RowKind, StateRows};
use super::walk::{self, WalkLimits};
use super::{Complete, GapSearch, GapStatus, Settings, complete_moves};
use crate::analysis::general::{self, Outcome};
use crate::analysis::lp;
use crate::analysis::statics::{ArchGeometry, Condition};

/// A complete vertex: its moving joints, its state and the joint rows tight there.
struct Lowest {
    moves: Vec<JointMove>,
    y: [f64; 4],
    tight: Vec<(f64, Condition)>,
    /// Whether a bound of the walk (λ = 0, the cap of λ, the box of the state) is tight there:
    /// its joint rows alone then do not fix the state.
    on_bound: bool,
}

/// The lowest complete vertex of the polytope of one set of joints.
struct Pass {
    /// The lowest complete vertex.
    best: Option<Lowest>,
    /// The highest λ of the polytope (the static limit of these joints).
    top: f64,
    vertices: usize,
}

/// Why a pass gives no vertex.
enum PassError {
    /// No admissible state for any λ in the range.
    Infeasible,
    /// The programme or the walk failed.
    Failed,
}

fn pass<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    thetas: &[f64],
    settings: &Settings,
) -> Result<Pass, PassError> {
    let rows = StateRows::new(
        geom,
        thetas,
        phi,
        [0.0, settings.lambda_cap],
        settings.state_cap,
    );
    let lp_settings = lp::Settings::for_rows(rows.len());
    let top = lp::maximise(&[0.0, 0.0, 0.0, 1.0], &rows.a, &rows.b, &lp_settings)
        .map_err(|_| PassError::Failed)?;
    match top.status {
        lp::Status::Optimal => {}
        lp::Status::Infeasible => return Err(PassError::Infeasible),
        _ => return Err(PassError::Failed),
    }
    let limits = WalkLimits {
        tol_tight: settings.tol_tight,
        max_vertices: settings.max_vertices,
        max_tight: settings.max_tight,
    };
    // The facet λ = 0 fences the walk: every vertex off it rises to the start along vertices
    // off it. The bounds of the box and of λ do not: vertices on them are walked through.
    let fence: Vec<bool> = rows
        .kind
        .iter()
        .zip(&rows.a)
        .map(|(k, a)| *k == RowKind::Bound && a[3] < 0.0)
        .collect();
    let vertices =
        walk::vertices(&rows.a, &rows.b, &fence, top.x, &limits).map_err(|_| PassError::Failed)?;
    // The lowest complete vertex, the first of the walk's order among equal λ.
    let mut by_lambda: Vec<&walk::Vertex> = vertices.iter().collect();
    by_lambda.sort_by(|p, q| p.y[3].total_cmp(&q.y[3]));
    let best = by_lambda.into_iter().find_map(|v| {
        let (moves, _) = complete_moves(geom, &rows, v, settings)?;
        let tight = v
            .tight
            .iter()
            .filter_map(|&r| match rows.kind[r] {
                RowKind::Joint {
                    joint, condition, ..
                } => Some((rows.thetas[joint], condition)),
                RowKind::Bound => None,
            })
            .collect();
        Some(Lowest {
            moves,
            y: v.y,
            tight,
            on_bound: v.tight.iter().any(|&r| rows.kind[r] == RowKind::Bound),
        })
    });
    Ok(Pass {
        best,
        top: top.x[3],
        vertices: vertices.len(),
    })
}

/// The first joints of a continuum: `continuum_joints` per family, ends included, and the
/// isolated joints.
pub(super) fn initial_joints<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> Vec<f64> {
    let n = settings.continuum_joints.max(2);
    let mut out: Vec<f64> = geom.isolated_joints();
    for [a, b] in geom.families() {
        for k in 0..n {
            out.push(if k + 1 == n {
                b
            } else {
                a + (b - a) * k as f64 / (n - 1) as f64
            });
        }
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// The first complete solution along increasing λ ≥ 0 at friction angle φ (radians): the
/// lowest load factor at which the live load of `geom` on its dead load can start a
/// mechanism, searched up to [`Settings::lambda_cap`].
///
/// A continuum is walked on sampled joints; the lowest complete vertex there is solved on the
/// continuum itself (its hinges moved to where their rows are tangent, as for a path), and
/// only where that fails are the joints it violates added and the polytope walked again.
pub fn first_complete_load_factor<G: ArchGeometry + Copy>(
    geom: &G,
    phi: f64,
    settings: &Settings,
) -> GapSearch {
    let range = [0.0, settings.lambda_cap];
    let mut thetas = joints::initial(geom, settings);
    let walked = match walk_and_exchange(geom, phi, &mut thetas, settings) {
        Ok(w) => w,
        Err(None) => return GapSearch::failed(range),
        Err(Some(visited)) => {
            return GapSearch {
                status: GapStatus::NoCompleteSolution,
                first: None,
                static_limit: None,
                range,
                vertices: visited,
                met_nothing: false,
            };
        }
    };
    // The static limit: the walk's own top when it walked every joint of a discrete arch; the
    // general route's otherwise.
    let static_limit = if thetas.is_none() {
        Some(walked.top)
    } else {
        let lf = general::load_factor(geom, phi, &general::Settings::default());
        match lf.outcome {
            Outcome::Solved => Some(lf.lambda),
            Outcome::Unbounded => Some(f64::INFINITY),
            _ => None,
        }
    };
    let static_limit = static_limit.map(|l| {
        if l >= settings.lambda_cap {
            f64::INFINITY
        } else {
            l
        }
    });
    let mu = phi.tan();
    let first = walked.best.and_then(|(moves, y)| {
        let state = StateY { y, mu };
        let angle = |t: f64| geom.angle_deg(t);
        mechanism::check(geom, &moves, &state, &angle).map(|m| Complete {
            value: y[3],
            state,
            mechanism: m,
        })
    });
    let status = match (&first, static_limit) {
        (None, _) => GapStatus::NoCompleteSolution,
        (Some(c), Some(l)) if l - c.state.y[3] > settings.tol_gap * (1.0 + l.abs().min(1e300)) => {
            GapStatus::Gap
        }
        (Some(_), _) => GapStatus::NoGap,
    };
    GapSearch {
        status,
        first,
        static_limit,
        range,
        vertices: walked.vertices,
        met_nothing: false,
    }
}

/// What the walks of a load-factor search found: the lowest complete state (solved on the
/// continuum where it could be), the highest λ of the last walk and the vertices visited.
struct Walked {
    best: Option<(Vec<JointMove>, [f64; 4])>,
    top: f64,
    vertices: usize,
}

/// Walks the polytope of the joints `thetas` (a small discrete arch's own when `None`) and,
/// where joints are sampled, solves its lowest complete vertex on the continuum or adds the
/// joints that vertex violates and walks again. `Err(Some(vertices))` when no state is
/// admissible at any λ, `Err(None)` when a walk or the exchange failed.
fn walk_and_exchange<G: ArchGeometry + Copy>(
    geom: &G,
    phi: f64,
    thetas: &mut Option<Vec<f64>>,
    settings: &Settings,
) -> Result<Walked, Option<usize>> {
    let discrete = geom.discrete_joints();
    let continuum = discrete.is_none();
    let mut visited = 0;
    for _ in 0..settings.max_exchange_rounds {
        let walked = thetas
            .clone()
            .or_else(|| discrete.clone())
            .unwrap_or_default();
        let p = match pass(geom, phi, &walked, settings) {
            Ok(p) => p,
            Err(PassError::Infeasible) => return Err(Some(visited)),
            Err(PassError::Failed) => return Err(None),
        };
        visited += p.vertices;
        let done = |best: Option<(Vec<JointMove>, [f64; 4])>| Walked {
            best,
            top: p.top,
            vertices: visited,
        };
        let (Some(t), Some(low)) = (thetas.as_mut(), &p.best) else {
            return Ok(done(p.best.map(|l| (l.moves, l.y))));
        };
        // A vertex on a bound of the walk is left to the exchange: its joint rows do not fix λ,
        // which Newton could then move out of the searched range.
        if continuum && !low.on_bound {
            let pattern = Pattern::of(geom, &low.tight, t);
            let at = |_: f64| Some((*geom, phi));
            let solved = refine::on_continuum(&at, &pattern, low.y[3], &low.y, None, settings);
            if let Some(r) = solved.filter(|r| (0.0..=settings.lambda_cap).contains(&r.y[3])) {
                return Ok(done(Some((r.moves, r.y))));
            }
        }
        let cuts = joints::violated_elsewhere(geom, phi, &low.y, t);
        if cuts.is_empty() {
            return Ok(done(p.best.map(|l| (l.moves, l.y))));
        }
        let before = t.len();
        if joints::add_angles(t, cuts) == before || joints::too_many(t, settings) {
            return Err(None);
        }
    }
    Err(None)
}
