//! The first complete solution along a path of scenes at a fixed λ: decreasing μ (friction
//! find) or decreasing K (thickness find).
//!
//! At each parameter value p the admissible states form a polytope in (F_x, F_y, M₀); its
//! vertices are walked at a sequence of values from the start of the path to its static
//! limit and on until the polytope is empty. A complete solution at one p needs as many tight
//! rows as a vertex in (x, p), one more than a vertex at fixed p: it shows up between two steps
//! as a vertex that is cut off (its three rows meet a fourth), and is located there by Brent's
//! method on the fourth row's slack. Families of complete states (two sliding joints whose
//! twists cancel, as when a crown part drops between vertical joints) are complete at the
//! steps themselves; their onset is located by bisection. A continuum is walked on sampled
//! joints; its first complete state is then solved on the continuum itself ([`refine`]), and
//! where that fails the joints it violates are added and the path walked again.

use super::mechanism::{self, JointMove, StateY};
use super::refine::{self, Pattern};
use super::rows::{RowKind, StateRows, row_at};
use super::walk::{self, Vertex, WalkLimits};
use super::{Complete, GapSearch, GapStatus, Settings, complete_moves, joints};
use crate::analysis::lp;
use crate::analysis::statics::{ArchGeometry, Condition, JointFrame};
use std::collections::BTreeMap;

#[path = "path_events.rs"]
mod events;
#[path = "path_skip.rs"]
mod skip;

/// A row named by its joint (index into the joint list) and condition.
type RowName = (usize, Condition);

fn order(c: Condition) -> u8 {
    match c {
        Condition::Intrados => 0,
        Condition::Extrados => 1,
        Condition::SlideOutward => 2,
        Condition::SlideInward => 3,
    }
}

/// The joint rows tight at a vertex, by name.
fn key(rows: &StateRows, v: &Vertex) -> Vec<(usize, u8)> {
    let mut k: Vec<(usize, u8)> = v
        .tight
        .iter()
        .filter_map(|&r| match rows.kind[r] {
            RowKind::Joint {
                joint, condition, ..
            } => Some((joint, order(condition))),
            RowKind::Bound => None,
        })
        .collect();
    k.sort_unstable();
    k
}

fn condition_of(code: u8) -> Condition {
    Condition::ALL[code as usize]
}

/// The joint parameter and condition of rows of `rows`.
fn names(rows: &StateRows, joints: &[f64], index: &[usize]) -> Vec<(f64, Condition)> {
    index
        .iter()
        .filter_map(|&r| match rows.kind[r] {
            RowKind::Joint {
                joint, condition, ..
            } => Some((joints[joint], condition)),
            RowKind::Bound => None,
        })
        .collect()
}

/// What one scan of a path found: the first complete state, the vertices seen, and a vertex of
/// the last slice that had any (with its p): the joints walked stand there.
struct Scan {
    found: Option<Found>,
    visited: usize,
    last: Option<(f64, [f64; 4])>,
}

/// A scene along the path: the geometry and friction angle at parameter p.
pub(super) type SceneAt<'a, G> = &'a dyn Fn(f64) -> Option<(G, f64)>;

/// The joints a path walks, grown by the exchange.
#[derive(Debug)]
pub(super) enum Joints {
    /// Every joint of a discrete arch.
    Every,
    /// Joints of a continuum by parameter: sampled, then added by the exchange.
    Sampled(Vec<f64>),
    /// Joints of a large discrete arch by index into its joints, which on a thickness path
    /// move with K (a pointed arch's joints divide the arc beyond its crown joint ψ₁(K)).
    Picked(Vec<usize>),
}

/// The joints `thetas` of `geom`, increasing; `None` when an index lies past its last joint.
fn joints_at<G: ArchGeometry>(geom: &G, thetas: &Joints) -> Option<Vec<f64>> {
    match thetas {
        Joints::Every => geom.discrete_joints(),
        Joints::Sampled(t) => Some(t.clone()),
        Joints::Picked(ix) => {
            let all = geom.discrete_joints()?;
            ix.iter().map(|&i| all.get(i).copied()).collect()
        }
    }
}

impl Joints {
    /// The first joints walked on the arch `g0`.
    fn initial<G: ArchGeometry>(g0: &G, settings: &Settings) -> Self {
        match g0.discrete_joints() {
            None => Joints::Sampled(joints::initial(g0, settings).unwrap_or_default()),
            Some(all) => match joints::initial_picks(all.len(), settings) {
                None => Joints::Every,
                Some(ix) => Joints::Picked(ix),
            },
        }
    }

    /// The joints of `geom` that the state y violates and the walk does not hold, added to
    /// it: `Ok(true)` when some were, `Err(())` when the walk would grow too large or its
    /// joints cannot be named on `geom` (then no answer is given rather than one checked on
    /// fewer joints).
    fn add_violated<G: ArchGeometry>(
        &mut self,
        geom: &G,
        phi: f64,
        y: &[f64; 4],
        settings: &Settings,
    ) -> Result<bool, ()> {
        if matches!(self, Joints::Every) {
            return Ok(false);
        }
        let walked = joints_at(geom, self).ok_or(())?;
        let cuts = joints::violated_elsewhere(geom, phi, y, &walked);
        let before = walked.len();
        let len = match self {
            Joints::Every => before,
            Joints::Sampled(t) => joints::add_angles(t, cuts),
            Joints::Picked(ix) => {
                let all = geom.discrete_joints().ok_or(())?;
                for c in &cuts {
                    ix.push(all.binary_search_by(|a| a.total_cmp(c)).map_err(|_| ())?);
                }
                ix.sort_unstable();
                ix.dedup();
                ix.len()
            }
        };
        if len > settings.max_walk_joints {
            return Err(());
        }
        Ok(len > before)
    }
}

/// The polytope at one parameter value: its rows and vertices by key.
pub(super) struct Slice {
    p: f64,
    rows: StateRows,
    pub(super) vertices: BTreeMap<Vec<(usize, u8)>, Vertex>,
}

/// What a path search holds fixed: λ, the joints, the settings.
pub(super) struct Walker<'a, G> {
    /// Slices walked so far, over every scan of one search.
    pub(super) slices: &'a std::cell::Cell<usize>,
    pub(super) at: SceneAt<'a, G>,
    pub(super) thetas: &'a Joints,
    pub(super) lambda: f64,
    pub(super) settings: &'a Settings,
    /// What the path's parameter is.
    pub(super) path: Path,
    /// The static limit the path runs to.
    pub(super) end: f64,
    /// The frames of the joints walked, on a friction path (one geometry throughout).
    pub(super) frames: std::cell::OnceCell<Option<Vec<JointFrame>>>,
}

/// What a path's parameter p is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Path {
    /// The friction angle of one fixed geometry: only the Coulomb rows move with p, so each
    /// polytope holds the next.
    Friction,
    /// The thickness ratio K: every row moves with p.
    Thickness,
}

/// A complete solution found on the path: where, its state, the moving joints and the
/// joint rows tight there.
struct Found {
    p: f64,
    y: [f64; 4],
    moves: Vec<JointMove>,
    tight: Vec<(f64, Condition)>,
    /// The rows whose twists move the joints.
    support: Vec<(f64, Condition)>,
    /// The work of the loads on the mechanism, once computed ([`Walker::work_of`]).
    work: std::cell::OnceCell<f64>,
}

impl<G: ArchGeometry> Walker<'_, G> {
    pub(super) fn slice(&self, p: f64) -> Option<(G, Slice)> {
        self.slices.set(self.slices.get() + 1);
        if self.exhausted() {
            return None;
        }
        let (geom, phi) = (self.at)(p)?;
        let lambda = [self.lambda, self.lambda];
        let rows = match self.path {
            // One geometry along the whole path: its joints' frames are built once.
            Path::Friction => {
                let frames = self
                    .frames
                    .get_or_init(|| {
                        joints_at(&geom, self.thetas).map(|j| super::rows::frames(&geom, &j))
                    })
                    .as_ref()?;
                StateRows::from_frames(frames, phi, lambda, self.settings.state_cap)
            }
            Path::Thickness => {
                let joints = joints_at(&geom, self.thetas)?;
                StateRows::new(&geom, &joints, phi, lambda, self.settings.state_cap)
            }
        };
        let mut out = Slice {
            p,
            rows,
            vertices: BTreeMap::new(),
        };
        // The polytope in (F_x, F_y, M₀) at the pinned λ: rows with an x part, renormalised.
        let mut a3: Vec<[f64; 3]> = Vec::with_capacity(out.rows.len());
        let mut b3: Vec<f64> = Vec::with_capacity(out.rows.len());
        let mut index: Vec<usize> = Vec::with_capacity(out.rows.len());
        let mut fence: Vec<bool> = Vec::with_capacity(out.rows.len());
        for (r, a) in out.rows.a.iter().enumerate() {
            let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            if n <= 0.0 {
                continue;
            }
            a3.push([a[0] / n, a[1] / n, a[2] / n]);
            b3.push((out.rows.b[r] - a[3] * self.lambda) / n);
            index.push(r);
            fence.push(false);
        }
        let lp_settings = lp::Settings::for_rows(a3.len());
        let sol = lp::maximise(&[1.0, 0.0, 0.0], &a3, &b3, &lp_settings).ok()?;
        if sol.status == lp::Status::Optimal {
            let limits = WalkLimits {
                tol_tight: self.settings.tol_tight,
                max_vertices: self.settings.max_vertices,
                max_tight: self.settings.max_tight,
            };
            let vs = walk::vertices(&a3, &b3, &fence, sol.x, &limits).ok()?;
            for v in vs {
                let v4 = Vertex {
                    y: [v.y[0], v.y[1], v.y[2], self.lambda],
                    tight: v.tight.iter().map(|&i| index[i]).collect(),
                };
                out.vertices.insert(key(&out.rows, &v4), v4);
            }
        }
        Some((geom, out))
    }

    /// A point of the path between `inside` (where the form exists) and `outside` (where it
    /// does not): halfway from `inside` to the edge of the form's domain, found by bisection;
    /// `outside` itself when no point nearer it exists, which ends the scan there.
    fn halfway_to_edge(&self, inside: f64, outside: f64) -> f64 {
        let (mut lo, mut hi) = (inside, outside);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if mid == lo || mid == hi {
                break;
            }
            if (self.at)(mid).is_some() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        // Halfway to the edge of the domain: the form degenerates at its edge (K → 1).
        if lo == inside {
            outside
        } else {
            0.5 * (inside + lo)
        }
    }

    /// True when the search has walked as many slices as it may.
    fn exhausted(&self) -> bool {
        self.slices.get() > self.settings.max_slices
    }

    /// The complete solution at vertex `v` (key `k`) of slice `s`, if it is one.
    fn found_at(&self, geom: &G, s: &Slice, k: &[(usize, u8)], v: &Vertex) -> Option<Found> {
        let joints = &s.rows.thetas;
        let (moves, support) = complete_moves(geom, &s.rows, v, self.settings)?;
        Some(Found {
            p: s.p,
            y: v.y,
            moves,
            tight: k
                .iter()
                .map(|(j, c)| (joints[*j], condition_of(*c)))
                .collect(),
            support: names(&s.rows, joints, &support),
            work: std::cell::OnceCell::new(),
        })
    }

    /// True when the loads drive the mechanism of `f` (they do more work on it than
    /// [`Settings::tol_driving_work`]), or when `f` lies at or past the path's static limit,
    /// where a limit state counts whatever that work (none on a mechanism of hinges alone,
    /// as the four- and five-hinge mechanisms at K_c). Before the limit, a
    /// mechanism that the loads do no work on (and which dissipates nothing) is a neutral
    /// configuration that nothing starts: thick pointed arches have such complete states
    /// near their largest K.
    fn drives(&self, geom: &G, f: &Found) -> bool {
        // Both paths run down to their static limit; a state at it, or past it on sampled
        // joints (which stand a little further than the arch), is a limit state.
        f.p - self.end <= self.settings.tol_gap * (1.0 + self.end.abs())
            || self.work_of(geom, f) > self.settings.tol_driving_work
    }

    /// The work of the loads on the mechanism of `f` (largest block-corner speed 1); +∞ when
    /// it cannot be checked, so that such a state is left to the other tests.
    fn work_of(&self, geom: &G, f: &Found) -> f64 {
        *f.work.get_or_init(|| {
            let Some((_, phi)) = (self.at)(f.p) else {
                return f64::INFINITY;
            };
            let state = StateY {
                y: f.y,
                mu: phi.tan(),
            };
            let angle = |t: f64| geom.angle_deg(t);
            mechanism::check(geom, &f.moves, &state, &angle)
                .map_or(f64::INFINITY, |m| m.work.work_loads)
        })
    }

    /// The first complete vertex of a slice that `accept` takes, one the loads drive before
    /// one they do no work on. On a friction path, a vertex whose rows were tight together at
    /// the `checked` slice is skipped: a row's twist does not move with μ (a hinge turns about
    /// its face point, a slip runs along the joint), so those rows were found not positively
    /// dependent there and are not here (or were complete with the same work of the loads,
    /// which does not move with μ either). Vertices on a bound of the walk (never complete,
    /// whatever their joint rows) and rows that allow a slip only without force (μ = ∞,
    /// which depends on the state) are checked again.
    fn complete_in(
        &self,
        geom: &G,
        s: &Slice,
        checked: Option<&Slice>,
        accept: &dyn Fn(&G, &Found) -> bool,
    ) -> Option<Found> {
        let plain = |rows: &StateRows, v: &Vertex| {
            v.tight.iter().all(|&r| {
                matches!(
                    rows.kind[r],
                    RowKind::Joint {
                        zero_force_only: false,
                        ..
                    }
                )
            })
        };
        let known = |k: &Vec<(usize, u8)>, v: &Vertex| {
            self.path == Path::Friction
                && plain(&s.rows, v)
                && checked.is_some_and(|c| c.vertices.get(k).is_some_and(|w| plain(&c.rows, w)))
        };
        let mut neutral: Option<Found> = None;
        let complete = s
            .vertices
            .iter()
            .filter(|(k, v)| !known(k, v))
            .filter_map(|(k, v)| self.found_at(geom, s, k, v))
            .filter(|f| accept(geom, f));
        for f in complete {
            // A state the loads drive comes before one they do no work on (accepted at the
            // static limit, where a neutral mechanism may sit beside the limit's own).
            if self.work_of(geom, &f) > self.settings.tol_driving_work {
                return Some(f);
            }
            neutral = neutral.or(Some(f));
        }
        neutral
    }

    /// A complete vertex of the slice at p that `accept` takes.
    fn has_complete(&self, p: f64, accept: &dyn Fn(&G, &Found) -> bool) -> Option<Found> {
        let (geom, s) = self.slice(p)?;
        self.complete_in(&geom, &s, None, accept)
    }

    /// The onset of a family of complete states between `from` (none) and `to` (one), by
    /// bisection: states of the same family (the same moving rows), whose driving work may
    /// grow from zero at the onset, and driven states of any other.
    fn onset(&self, mut from: f64, mut to: Found) -> Found {
        let family = to.support.clone();
        let accept = |g: &G, f: &Found| f.support == family || self.drives(g, f);
        let tol = self.settings.tol_path * (1.0 + to.p.abs());
        for _ in 0..200 {
            if (to.p - from).abs() <= tol {
                break;
            }
            let mid = 0.5 * (from + to.p);
            match self.has_complete(mid, &accept) {
                Some(f) => to = f,
                None => from = mid,
            }
        }
        to
    }

    /// The first complete solution from slice `prev` (none there) to slice `cur`: an event
    /// between them, or the onset of a family of complete states found at `cur`, whichever
    /// comes first along the path.
    fn advance(&self, prev: &Slice, cur: &(G, Slice)) -> Option<Found> {
        let event = self.events(prev, &cur.1);
        // A complete vertex at a step: a family of complete states (its moving rows are fewer
        // than four, so they stay tight over an interval of p) began somewhere in the step,
        // and its onset is bisected; four or more moving rows meet at this p alone.
        let drives = |g: &G, f: &Found| self.drives(g, f);
        let family = self
            .complete_in(&cur.0, &cur.1, Some(prev), &drives)
            .map(|f| {
                if f.support.len() < 4 {
                    self.onset(prev.p, f)
                } else {
                    f
                }
            });
        let forward = (cur.1.p - prev.p).signum();
        match (event, family) {
            (Some(e), Some(f)) => Some(if forward * (f.p - e.p) < 0.0 { f } else { e }),
            (e, f) => e.or(f),
        }
    }

    /// One scan of the path on fixed joints, from `start` past `end` until the polytope is
    /// empty: the first complete solution and the vertices seen.
    fn scan(&self, start: f64, end: f64, step: f64) -> Scan {
        let mut prev: Option<Slice> = None;
        let mut visited = 0;
        let mut last: Option<(f64, [f64; 4])> = None;
        let forward = (end - start).signum();
        let n = (((end - start).abs() / step).ceil() as usize).max(1);
        let mut i = 0;
        loop {
            // The static limit itself is a degenerate polytope (a point or a segment): the step
            // there stops just short of it, where every row of the limit is tight within the
            // walk's tolerance.
            let p = if i < n {
                start + (end - start) * i as f64 / n as f64
            } else if i == n {
                end - forward * self.settings.end_offset * (1.0 + end.abs())
            } else {
                end + forward * step * (i - n) as f64
            };
            i += 1;
            let beyond = i > n;
            // Past the static limit a step may leave the form's domain (K ≤ 1 on a thickness
            // path whose K_c lies near 1): the slice is then taken inside it,
            // halfway to the domain's edge, so that the events at the static limit are still seen.
            let p = match &prev {
                Some(pr) if beyond && (self.at)(p).is_none() => self.halfway_to_edge(pr.p, p),
                _ => p,
            };
            let Some(cur) = self.slice(p) else {
                if beyond || self.exhausted() {
                    break;
                }
                prev = None;
                continue;
            };
            visited += cur.1.vertices.len();
            if let Some(v) = cur.1.vertices.values().next() {
                last = Some((p, v.y));
            }
            let fresh = prev.is_none();
            let found = match &prev {
                Some(pr) => self.advance(pr, &cur),
                None => self.complete_in(&cur.0, &cur.1, None, &|g, f| self.drives(g, f)),
            };
            if found.is_some() {
                return Scan {
                    found,
                    visited,
                    last,
                };
            }
            if fresh && self.path == Path::Friction && i < n {
                // Down to the steepest resultant of this polytope's vertices every polytope is
                // this one: the path goes on from the last step above it as from a start.
                let skip_to = self.skip_to(&cur, start, end, n);
                if skip_to > i {
                    i = skip_to;
                    prev = None;
                    continue;
                }
            }
            if beyond && (cur.1.vertices.is_empty() || i > n + self.settings.max_steps_beyond) {
                break;
            }
            prev = Some(cur.1);
        }
        Scan {
            found: None,
            visited,
            last,
        }
    }
}

/// The first complete solution along the path from `start` to `end` (the static limit), at
/// load factor `lambda`, scanned at steps no longer than `step`: the path parameter and the
/// solution, the vertices visited, and whether the walk went through the static limit
/// without meeting any complete state (false when it met one it could not finish).
pub(super) fn first_complete<G: ArchGeometry + Copy>(
    at: SceneAt<'_, G>,
    (start, end, step): (f64, f64, f64),
    lambda: f64,
    path: Path,
    settings: &Settings,
) -> (Option<(f64, Complete)>, usize, bool) {
    let slices = std::cell::Cell::new(0);
    let out = first_complete_counted(at, (start, end, step), (lambda, path), settings, &slices);
    if slices.get() > settings.max_slices {
        // Out of budget: no answer rather than a partial one.
        return (None, usize::MAX, false);
    }
    out
}

fn first_complete_counted<G: ArchGeometry + Copy>(
    at: SceneAt<'_, G>,
    (start, end, step): (f64, f64, f64),
    (lambda, path): (f64, Path),
    settings: &Settings,
    slices: &std::cell::Cell<usize>,
) -> (Option<(f64, Complete)>, usize, bool) {
    let Some((g0, _)) = at(start).or_else(|| at(end)) else {
        return (None, 0, false);
    };
    let mut walked = Joints::initial(&g0, settings);
    let mut visited = 0;
    for _ in 0..settings.max_exchange_rounds {
        let walker = Walker {
            slices,
            at,
            thetas: &walked,
            lambda,
            settings,
            path,
            end,
            frames: std::cell::OnceCell::new(),
        };
        let scan = walker.scan(start, end, step);
        visited += scan.visited;
        let Some(mut f) = scan.found else {
            // Sampled joints stand further than the arch: the joints that the last standing
            // state of the walk violates are added, and the path walked again.
            let Some((p, y)) = scan.last.filter(|_| !matches!(walked, Joints::Every)) else {
                return (None, visited, true);
            };
            let Some((geom, phi)) = at(p) else {
                return (None, visited, false);
            };
            match walked.add_violated(&geom, phi, &y, settings) {
                Err(()) => return (None, usize::MAX, false),
                Ok(false) => return (None, visited, true),
                Ok(true) => continue,
            }
        };
        // A complete state found within the gap's tolerance of the static limit is the static
        // limit's own (the step there stops just short of it, and tightness holds to the walk's
        // tolerance): it is solved there.
        if (f.p - end).abs() <= settings.tol_gap * (1.0 + end.abs()) {
            f.p = end;
        }
        if matches!(walked, Joints::Every) {
            return (finish(at, f, settings), visited, false);
        }
        let Some((geom, phi)) = at(f.p) else {
            return (None, visited, false);
        };
        // On a continuum the sampled state is solved on the continuum's own joints first.
        if let Joints::Sampled(t) = &walked {
            let pattern = Pattern::of(&geom, &f.tight, t);
            if let Some(r) = refine::on_continuum(at, &pattern, f.p, &f.y, Some(lambda), settings) {
                return (finish(at, r, settings), visited, false);
            }
        }
        match walked.add_violated(&geom, phi, &f.y, settings) {
            Err(()) => return (None, usize::MAX, false),
            Ok(false) => return (finish(at, f, settings), visited, false),
            Ok(true) => {}
        }
    }
    (None, visited, false)
}

fn finish<G: ArchGeometry>(
    at: SceneAt<'_, G>,
    f: impl Into<FoundState>,
    _settings: &Settings,
) -> Option<(f64, Complete)> {
    let f: FoundState = f.into();
    let (geom, phi) = at(f.p)?;
    let state = StateY {
        y: polish(&geom, phi, f.y, &f.support),
        mu: phi.tan(),
    };
    let angle = |t: f64| geom.angle_deg(t);
    mechanism::check(&geom, &f.moves, &state, &angle).map(|m| {
        (
            f.p,
            Complete {
                value: f.p,
                state,
                mechanism: m,
            },
        )
    })
}

/// A complete state at path parameter p with its moving joints and the rows that move them
/// (empty when the state already holds them exactly).
pub(super) struct FoundState {
    pub p: f64,
    pub y: [f64; 4],
    pub moves: Vec<JointMove>,
    pub support: Vec<(f64, Condition)>,
}

impl From<Found> for FoundState {
    fn from(f: Found) -> Self {
        FoundState {
            p: f.p,
            y: f.y,
            moves: f.moves,
            support: f.support,
        }
    }
}

/// The state nearest to y (λ fixed) on which the rows `support` hold exactly at (geometry,
/// φ): the walk's tolerance leaves them tight only to within it, the flow rules of the
/// mechanism they move want them exact.
fn polish<G: ArchGeometry>(
    geom: &G,
    phi: f64,
    y: [f64; 4],
    support: &[(f64, Condition)],
) -> [f64; 4] {
    let rows: Vec<_> = support
        .iter()
        .filter_map(|&(t, c)| row_at(geom, t, phi, c))
        .collect();
    if rows.is_empty() {
        return y;
    }
    let a = nalgebra::DMatrix::from_fn(rows.len(), 3, |i, j| rows[i].a[j]);
    let r = nalgebra::DVector::from_iterator(
        rows.len(),
        rows.iter()
            .map(|r| r.b - (r.a[0] * y[0] + r.a[1] * y[1] + r.a[2] * y[2] + r.a[3] * y[3])),
    );
    match refine::least_squares(a, &r) {
        Some(d) => [y[0] + d[0], y[1] + d[1], y[2] + d[2], y[3]],
        None => y,
    }
}

/// The result of a path search as a [`GapSearch`]: `found` is the first complete solution at
/// path parameter p, `value` turns p into the find's value (μ from φ, K from K),
/// `static_value` is the static limit and `start` the far end of the path.
pub(super) fn search_result(
    (found, visited, met_nothing): (Option<(f64, Complete)>, usize, bool),
    value: impl Fn(f64) -> f64,
    static_value: f64,
    start: f64,
    settings: &Settings,
) -> GapSearch {
    let range = [static_value, value(start)];
    let met_nothing = met_nothing && found.is_none();
    // A complete state beyond the static limit (past it no state is admissible) can only be
    // an artefact of sampled joints or of a failed refinement: the search failed.
    let tol = settings.tol_gap * (1.0 + static_value.abs());
    let beyond = |p: f64| {
        (value(p) - static_value) * (value(start) - static_value) < 0.0
            && (value(p) - static_value).abs() > tol
    };
    if found.as_ref().is_some_and(|(p, _)| beyond(*p)) {
        return GapSearch {
            static_limit: Some(static_value),
            vertices: visited,
            ..GapSearch::failed(range)
        };
    }
    let status = match &found {
        None if visited == usize::MAX => GapStatus::Failed,
        None => GapStatus::NoCompleteSolution,
        Some((p, _)) => {
            let v = value(*p);
            if (v - static_value).abs() > settings.tol_gap * (1.0 + static_value.abs()) {
                GapStatus::Gap
            } else {
                GapStatus::NoGap
            }
        }
    };
    GapSearch {
        status,
        first: found.map(|(p, c)| Complete {
            value: value(p),
            ..c
        }),
        static_limit: Some(static_value),
        range,
        vertices: visited,
        met_nothing,
    }
}

#[cfg(test)]
#[path = "path_tests.rs"]
mod tests;
