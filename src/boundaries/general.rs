//! Boundaries and bifurcations of the groups answered by the general three-unknown
//! formulation (live loads, pointed arches, vertical joints, `load_factor` studies).
//!
//! Generic and simple: every grid edge (along K at fixed μ, along μ at fixed K) whose ends
//! differ in the stored answer is bisected on the edge's parameter (K itself, or φ = atan μ
//! so that μ = ∞ is an end like any other) with a full analysis of the scene at each step,
//! until the bracket is no wider than the tolerance in K or μ. What counts as a difference:
//! - `state`: the regime. Each crossing is a boundary point; one on the collapse curve
//!   carries the limit state of all rows on its stable side (its active rows name the
//!   mechanism).
//! - `load_factor`, `thickness`, `friction`: the collapse mechanism kind (rotational, mixed,
//!   sliding). Where it changes, both mechanisms coexist at the limit: a bifurcation, with
//!   the joints of both sides and the edge's axis. Changes to or from an unbounded load
//!   factor, or an arch that never stands, are not recorded.

use super::cells::Cell;
use super::grid::Grid;
use super::{Bifurcation, BoundaryPoint, Counter, EdgeAxis};
use crate::analysis::forms::ArchModel;
use crate::analysis::general::{self, Settings};
use crate::analysis::symmetric::CriticalState;
use crate::analysis::{Mechanism, MechanismKind, Regime};
use crate::model::Friction;
use crate::scene::{self, Find, Outcome, Scene, Solution};
use std::f64::consts::FRAC_PI_2;

/// What is compared between the ends of an edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Label {
    /// The regime (state studies).
    Regime(Regime),
    /// A limit state with its mechanism kind (other studies).
    Found(Option<MechanismKind>),
    /// Any other outcome (unbounded, never or always stands, failed).
    Other(Outcome),
}

impl From<Cell> for Label {
    fn from(c: Cell) -> Self {
        match c {
            Cell::Regime(g) => Label::Regime(g),
            Cell::Found(m) => Label::Found(m),
            Cell::Other(o) => Label::Other(o),
        }
    }
}

fn label(find: Find, s: &Solution) -> Option<Label> {
    if find == Find::State {
        return s.regime().map(Label::Regime);
    }
    match s.outcome? {
        Outcome::Found => Some(Label::Found(s.mechanism)),
        other => Some(Label::Other(other)),
    }
}

/// The limit state of a stored answer, rebuilt from its records.
fn critical_state(s: &Solution, k: f64, mu: f64) -> Option<CriticalState> {
    let hinges = s.hinges.clone();
    let sliding = s.sliding_joints.clone();
    Some(CriticalState {
        k: s.k_crit.unwrap_or(k),
        mu: s.mu_crit.unwrap_or(mu),
        thrust_over_half_weight: s.thrust_over_half_weight.unwrap_or(f64::NAN),
        crown_moment: s.crown_moment.unwrap_or(f64::NAN),
        mechanism: Mechanism::from_parts(hinges, sliding)?,
    })
}

/// Two joints of the two sides of a located change closer than this (degrees) are one: the
/// hinges of a continuum are located to about 1e-5° on either side of a bracket 1e-9 wide.
const SAME_JOINT_DEG: f64 = 1e-4;

/// The state with every joint of two states (the one on the lower side first).
fn union(a: &CriticalState, b: &CriticalState) -> CriticalState {
    let same = |x: f64, y: f64| (x - y).abs() <= SAME_JOINT_DEG;
    let mut hinges = a.mechanism.hinges.clone();
    for h in &b.mechanism.hinges {
        if !hinges
            .iter()
            .any(|g| g.face == h.face && same(g.angle_deg, h.angle_deg))
        {
            hinges.push(*h);
        }
    }
    let mut sliding = a.mechanism.sliding_joints.clone();
    for j in &b.mechanism.sliding_joints {
        if !sliding
            .iter()
            .any(|g| g.sense == j.sense && same(g.angle_deg, j.angle_deg))
        {
            sliding.push(*j);
        }
    }
    let mut out = a.clone();
    if let Some(m) = Mechanism::from_parts(hinges, sliding) {
        out.mechanism = m;
    }
    out
}

/// The parameter of an edge as a bisection variable, and back.
fn to_t(axis: EdgeAxis, x: f64) -> f64 {
    match axis {
        EdgeAxis::K => x,
        EdgeAxis::Mu => x.atan(),
    }
}

fn to_x(axis: EdgeAxis, t: f64) -> f64 {
    match axis {
        EdgeAxis::K => t,
        EdgeAxis::Mu if t >= FRAC_PI_2 => f64::INFINITY,
        EdgeAxis::Mu => t.tan(),
    }
}

/// An answer at one end of an edge: its label and the stored or computed solution.
type Answer = (Label, Solution);

/// One located change: a bracket no wider than the tolerance and the answers at its ends.
struct Change {
    lo: f64,
    hi: f64,
    at_lo: (Label, Solution),
    at_hi: (Label, Solution),
}

/// One grid being refined.
struct Refiner<'a> {
    grid: &'a Grid,
    tol: f64,
    counter: &'a Counter<'a>,
}

impl Refiner<'_> {
    fn scene(&self, k: f64, mu: f64) -> Scene {
        Scene {
            arch: self.grid.scene.arch.with_k(k),
            friction: Friction::new(mu).unwrap_or(Friction::INFINITE),
            ..self.grid.scene
        }
    }

    fn eval(&self, k: f64, mu: f64) -> Option<(Label, Solution)> {
        self.counter.tick();
        let s = scene::solve_static(&self.scene(k, mu));
        Some((label(self.grid.scene.find, &s)?, s))
    }

    /// Every change of answer along an edge from x0 to x1 (the other coordinate fixed), by
    /// bisection; at most a few per cell.
    fn changes(
        &self,
        axis: EdgeAxis,
        fixed: f64,
        (x0, a0): (f64, (Label, Solution)),
        (x1, a1): (f64, (Label, Solution)),
    ) -> Vec<Change> {
        let at = |x: f64| match axis {
            EdgeAxis::K => self.eval(x, fixed),
            EdgeAxis::Mu => self.eval(fixed, x),
        };
        let target = a1.0;
        let mut out = Vec::new();
        let (mut lo, mut at_lo) = (to_t(axis, x0), a0);
        let end = to_t(axis, x1);
        for _ in 0..4 {
            let (mut hi, mut at_hi) = (end, a1.clone());
            let mut steps = 0;
            while to_x(axis, hi) - to_x(axis, lo) > self.tol && steps < 200 {
                let mid = 0.5 * (lo + hi);
                let Some(v) = at(to_x(axis, mid)) else {
                    break;
                };
                if v.0 == at_lo.0 {
                    (lo, at_lo) = (mid, v);
                } else {
                    (hi, at_hi) = (mid, v);
                }
                steps += 1;
            }
            let reached = at_hi.0 == target;
            out.push(Change {
                lo: to_x(axis, lo),
                hi: to_x(axis, hi),
                at_lo: at_lo.clone(),
                at_hi: at_hi.clone(),
            });
            if reached {
                break;
            }
            (lo, at_lo) = (hi, at_hi);
        }
        out
    }

    /// The point of a change: the end of the bracket nearer the true crossing is unknown,
    /// so the midpoint (within tol/2 of it) when finite.
    fn located(c: &Change) -> f64 {
        if c.hi.is_finite() {
            0.5 * (c.lo + c.hi)
        } else {
            c.lo
        }
    }

    /// A boundary point of a state study.
    fn boundary(&self, axis: EdgeAxis, fixed: f64, c: &Change) -> Option<BoundaryPoint> {
        let (Label::Regime(low), Label::Regime(high)) = (c.at_lo.0, c.at_hi.0) else {
            return None;
        };
        let x = Self::located(c);
        let (k, mu) = match axis {
            EdgeAxis::K => (x, fixed),
            EdgeAxis::Mu => (fixed, x),
        };
        let on_curve = low == Regime::Stable || high == Regime::Stable;
        // The limit state of all rows on the stable side of the crossing.
        let state = if on_curve {
            let xs = if high == Regime::Stable { c.hi } else { c.lo };
            let (ks, ms) = match axis {
                EdgeAxis::K => (xs, fixed),
                EdgeAxis::Mu => (fixed, xs),
            };
            self.limit_state(ks, ms)
        } else {
            None
        };
        Some(BoundaryPoint {
            load_case: self.grid.load_case,
            half_angle_deg: self.grid.arch.half_angle_deg(),
            voussoirs: self.grid.arch.joints.voussoirs(),
            form: self.grid.scene.form,
            at_deg: self.grid.scene.load.at_deg(),
            at_x: self.grid.scene.load.at_x(),
            k,
            mu,
            axis,
            regime_low: low,
            regime_high: high,
            on_collapse_curve: on_curve,
            mechanism: state.as_ref().map(|s| s.mechanism.kind),
            state,
        })
    }

    /// The state of largest margin of all rows at (K, μ) and its active rows.
    fn limit_state(&self, k: f64, mu: f64) -> Option<CriticalState> {
        self.counter.tick();
        let sc = self.scene(k, mu);
        let model = ArchModel::new(sc.arch, sc.form, sc.load).ok()?;
        let settings = Settings {
            lambda: sc.lambda,
            ..Settings::default()
        };
        let m = general::margin(&model, sc.friction.angle(), general::RowSet::All, &settings);
        Some(CriticalState {
            k,
            mu,
            thrust_over_half_weight: m.crown.thrust_over_half_weight,
            crown_moment: -m.crown.moment_about_centre,
            mechanism: m.mechanism()?,
        })
    }

    /// A bifurcation where the collapse mechanism kind changes along an edge.
    fn bifurcation(&self, axis: EdgeAxis, fixed: f64, c: &Change) -> Option<Bifurcation> {
        let (Label::Found(Some(a)), Label::Found(Some(b))) = (c.at_lo.0, c.at_hi.0) else {
            return None;
        };
        if a == b {
            return None;
        }
        let x = Self::located(c);
        let (k, mu) = match axis {
            EdgeAxis::K => (x, fixed),
            EdgeAxis::Mu => (fixed, x),
        };
        let (k_lo, mu_lo) = match axis {
            EdgeAxis::K => (c.lo, fixed),
            EdgeAxis::Mu => (fixed, c.lo),
        };
        let (k_hi, mu_hi) = match axis {
            EdgeAxis::K => (c.hi, fixed),
            EdgeAxis::Mu => (fixed, c.hi),
        };
        let sa = critical_state(&c.at_lo.1, k_lo, mu_lo)?;
        let sb = critical_state(&c.at_hi.1, k_hi, mu_hi)?;
        let mut state = union(&sa, &sb);
        // Thickness and friction studies locate the critical value itself.
        let (k, mu) = match self.grid.scene.find {
            Find::Thickness => (0.5 * (sa.k + sb.k), mu),
            Find::Friction => (k, 0.5 * (sa.mu + sb.mu)),
            _ => (k, mu),
        };
        state.k = k;
        state.mu = mu;
        Some(Bifurcation {
            load_case: self.grid.load_case,
            half_angle_deg: self.grid.arch.half_angle_deg(),
            voussoirs: self.grid.arch.joints.voussoirs(),
            form: self.grid.scene.form,
            at_deg: self.grid.scene.load.at_deg(),
            at_x: self.grid.scene.load.at_x(),
            axis: Some(axis),
            load_factor: c.at_lo.1.load_factor,
            k,
            mu,
            mechanism_a: a,
            mechanism_b: b,
            state,
        })
    }
}

/// A grid edge whose ends differ: its axis, the fixed coordinate and both ends with their
/// labels.
type LabelledEdge = (EdgeAxis, f64, (f64, Label), (f64, Label));

/// Boundary points and bifurcations of one grid of the general route. The grid holds the
/// label of every case; the answers at the ends of an edge whose labels differ are solved
/// again (the same scene by the same route as the engine's, so the same answer).
pub(crate) fn locate(
    grid: &Grid,
    tol: f64,
    counter: &Counter,
) -> (Vec<BoundaryPoint>, Vec<Bifurcation>) {
    let r = Refiner { grid, tol, counter };
    let find = grid.scene.find;
    let stored = |i: usize, j: usize| grid.cell(i, j).map(Label::from);
    let mut edges: Vec<LabelledEdge> = Vec::new();
    for j in 0..grid.mus.len() {
        for i in 1..grid.ks.len() {
            if let (Some(a), Some(b)) = (stored(i - 1, j), stored(i, j))
                && a != b
            {
                edges.push((
                    EdgeAxis::K,
                    grid.mus[j],
                    (grid.ks[i - 1], a),
                    (grid.ks[i], b),
                ));
            }
        }
    }
    for i in 0..grid.ks.len() {
        for j in 1..grid.mus.len() {
            if let (Some(a), Some(b)) = (stored(i, j - 1), stored(i, j))
                && a != b
            {
                edges.push((
                    EdgeAxis::Mu,
                    grid.ks[i],
                    (grid.mus[j - 1], a),
                    (grid.mus[j], b),
                ));
            }
        }
    }
    let answer = |axis: EdgeAxis, fixed: f64, (x, l): (f64, Label)| -> (f64, Answer) {
        let (k, mu) = match axis {
            EdgeAxis::K => (x, fixed),
            EdgeAxis::Mu => (fixed, x),
        };
        (x, (l, scene::solve_static(&r.scene(k, mu))))
    };
    use rayon::prelude::*;
    let found: Vec<(Vec<BoundaryPoint>, Vec<Bifurcation>)> = edges
        .into_par_iter()
        .map(|(axis, fixed, a, b)| {
            let (a, b) = (answer(axis, fixed, a), answer(axis, fixed, b));
            let mut points = Vec::new();
            let mut bifs = Vec::new();
            for c in r.changes(axis, fixed, a, b) {
                if find == Find::State {
                    points.extend(r.boundary(axis, fixed, &c));
                } else {
                    bifs.extend(r.bifurcation(axis, fixed, &c));
                }
            }
            (points, bifs)
        })
        .collect();
    let mut points = Vec::new();
    let mut bifs = Vec::new();
    for (p, b) in found {
        points.extend(p);
        bifs.extend(b);
    }
    (points, bifs)
}
