//! The general statics of an arch in three redundant unknowns, with no symmetry assumed:
//! x = (F_x, F_y, M₀), the force and moment the left part exerts on the right part at the
//! crown (over W_half and W_half·r), and optionally the load factor λ (DESIGN.md §1).
//!
//! Every joint θ gives four rows a·x + a_λ λ ≤ b ([`joint_rows`], paper eqs. 1 and 3). The
//! arch can stand iff the rows of all joints have a common solution. Feasibility is measured
//! by a continuous margin, the largest τ with
//!
//! a_i·x + τ |a_i| ≤ b_i − a_λ,i λ  for every row i,  τ ≤ τ_cap,
//!
//! (τ is the distance of x to the nearest row plane in (F_x, F_y, M₀) space, negative when
//! no x satisfies all rows); its sign says whether the arch stands, its zero is the collapse
//! condition, and the rows that attain it there name the mechanism.
//!
//! Discrete arches give one linear programme ([`lp`]). For the continuum the joints form a
//! semi-infinite family, solved by an exchange (cutting-plane) method: solve with a few
//! joints, find the most violated joint of each condition over [−α, α] by sampling and a
//! 1-D maximisation, add it, repeat until no joint is violated by more than a relative
//! tolerance. Critical values are roots of the margin in K or φ (Brent), as in
//! [`super::symmetric`], which this module reproduces by an independent route.

use super::circular::CircularArch;
use super::lp;
use super::roots::brent;
use super::statics::{ArchGeometry, Condition, Row, joint_rows};
use super::types::{Face, Hinge, Mechanism, Regime, Sense, SlidingJoint};
use crate::model::{Arch, Friction};
use std::cell::Cell;
use std::f64::consts::FRAC_PI_2;

/// The objective of every programme here: maximise the fourth unknown (τ or λ).
pub const OBJECTIVE: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

/// The auxiliary row −λ ≤ 0 of a load-factor programme.
const LAMBDA_NON_NEGATIVE: [f64; 4] = [0.0, 0.0, 0.0, -1.0];

/// Largest K − 1 explored when bracketing a critical thickness.
const FAR: f64 = 1e9;

/// Which conditions enter a problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RowSet {
    /// The no-tension rows of eq. (1) only (intrados and extrados): the domain H^r.
    Rotational,
    /// The Coulomb rows of eq. (3) only: the domain H^s.
    Sliding,
    /// All four rows at every joint.
    All,
}

impl RowSet {
    /// True when rows of `condition` belong to the set.
    pub fn includes(self, condition: Condition) -> bool {
        match self {
            RowSet::Rotational => condition.is_rotational(),
            RowSet::Sliding => !condition.is_rotational(),
            RowSet::All => true,
        }
    }
}

/// Settings of the general route; tolerances are relative to 1 + |x|∞ unless stated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Settings of the linear programme solver.
    pub lp: lp::Settings,
    /// Largest number of exchange steps for a continuum (default 200).
    pub exchange_max_iter: usize,
    /// The exchange stops when no joint violates a row by more than this distance
    /// (default 1e-13).
    pub exchange_tol: f64,
    /// Joints of the first exchange step, equally spaced over [−α, α], ends included
    /// (default 17).
    pub exchange_initial_joints: usize,
    /// Sampling intervals over [−α, α] in the search for the most violated joint
    /// (default 64).
    pub exchange_samples: usize,
    /// Local maxima of each condition refined per search (default 4).
    pub exchange_maxima: usize,
    /// Upper bound τ_cap of the margin, in units of x (default 1).
    pub margin_cap: f64,
    /// A margin ≥ −`margin_tol` counts as feasible: limit states are admissible
    /// (default 1e-12, absolute; keep it above `exchange_tol`).
    pub margin_tol: f64,
    /// A row is active when its distance to x is within this of the margin (default 1e-9).
    pub active_tol: f64,
    /// Load factor λ held fixed in margins, regimes and critical values (default 0).
    pub lambda: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            lp: lp::Settings::default(),
            exchange_max_iter: 200,
            exchange_tol: 1e-13,
            exchange_initial_joints: 17,
            exchange_samples: 64,
            exchange_maxima: 4,
            margin_cap: 1.0,
            margin_tol: 1e-12,
            active_tol: 1e-9,
            lambda: 0.0,
        }
    }
}

/// How a general solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// Solved: every joint satisfies the rows within tolerance.
    Solved,
    /// No admissible state (for the load factor: no λ lets the arch stand).
    Infeasible,
    /// The objective is unbounded (for the load factor: the arch stands for every λ ≥ 0).
    Unbounded,
    /// The exchange hit its iteration cap (or stalled) before the violation fell below
    /// tolerance.
    NotConverged,
    /// The linear programme solver failed.
    Failed(lp::Status),
}

/// A row that holds with equality at a solution (within `active_tol`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActiveRow {
    /// Joint angle from the crown, degrees, positive to the right.
    pub angle_deg: f64,
    /// The condition at the limit there.
    pub condition: Condition,
    /// Distance of x to the row plane minus the margin (≥ 0, ≤ `active_tol`·scale).
    pub slack: f64,
}

/// The crown force and moment of a state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CrownState {
    /// F_x / W_half: the horizontal thrust at the crown.
    pub thrust_over_half_weight: f64,
    /// F_y / W_half: the vertical shear at the crown (zero under symmetric loading).
    pub shear_over_half_weight: f64,
    /// M₀ / (W_half·r): moment about the centre of the circle (−h·y_P for a thrust at height
    /// y_P).
    pub moment_about_centre: f64,
}

impl CrownState {
    fn from_x(x: &[f64; 4]) -> Self {
        CrownState {
            thrust_over_half_weight: x[0],
            shear_over_half_weight: x[1],
            moment_about_centre: x[2],
        }
    }
}

/// The margin of one point: the largest τ (see the module docs) and the state attaining it.
#[derive(Debug, Clone, PartialEq)]
pub struct MarginSolution {
    /// How the solve ended.
    pub outcome: Outcome,
    /// τ, a lower bound on the exact margin (the LP value less the residual violation of the
    /// continuum), in units of x; ≤ `margin_cap`.
    pub margin: f64,
    /// The state x attaining it.
    pub crown: CrownState,
    /// Largest distance by which a joint violates a row at (x, τ): ≤ 0 up to tolerance.
    pub max_violation: f64,
    /// Rows whose distance to x equals τ within `active_tol`.
    pub active: Vec<ActiveRow>,
    /// Rows in the final programme.
    pub rows: usize,
    /// Exchange steps (1 for a discrete arch).
    pub iterations: usize,
}

impl MarginSolution {
    /// True when the margin says the rows have a common solution (τ ≥ −`margin_tol`).
    pub fn feasible(&self, settings: &Settings) -> bool {
        self.outcome == Outcome::Solved && self.margin >= -settings.margin_tol
    }

    /// The mechanism named by the active rows, if any.
    pub fn mechanism(&self) -> Option<Mechanism> {
        mechanism_of(&self.active)
    }
}

/// The joint and condition of a row of a [`LinearRows`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointRow {
    /// Joint parameter θ, radians.
    pub theta: f64,
    /// The condition.
    pub condition: Condition,
}

/// A programme "maximise [`OBJECTIVE`]·z subject to a z ≤ b" over z = (F_x, F_y, M₀, t),
/// with t = τ (margin) or λ (load factor). The first `joints.len()` rows belong to joints;
/// the rest (the cap τ ≤ τ_cap) are auxiliary.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LinearRows {
    /// Row coefficients.
    pub a: Vec<[f64; 4]>,
    /// Right-hand sides.
    pub b: Vec<f64>,
    /// The joint of each joint row.
    pub joints: Vec<JointRow>,
}

/// What the fourth unknown is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Objective {
    /// τ, with λ held fixed.
    Margin { lambda: f64, cap: f64 },
    /// λ.
    LoadFactor,
}

/// |(a_x, a_y, a_M)|.
fn norm3(a: &[f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// The programme row of a joint row.
fn lp_row(r: &Row, objective: Objective) -> ([f64; 4], f64) {
    match objective {
        Objective::Margin { lambda, .. } => (
            [r.a[0], r.a[1], r.a[2], norm3(&r.a)],
            r.b - r.a_lambda * lambda,
        ),
        Objective::LoadFactor => ([r.a[0], r.a[1], r.a[2], r.a_lambda], r.b),
    }
}

/// Distance by which z violates the row (a·z − b)/|a|; with `homogeneous`, a·z/|a| (for a
/// ray of an unbounded programme).
fn violation(r: &Row, objective: Objective, z: &[f64; 4], homogeneous: bool) -> f64 {
    let (a, b) = lp_row(r, objective);
    let s =
        a[0] * z[0] + a[1] * z[1] + a[2] * z[2] + a[3] * z[3] - if homogeneous { 0.0 } else { b };
    let n = norm3(&r.a);
    if n > 0.0 { s / n } else { s }
}

impl LinearRows {
    fn push_joint<G: ArchGeometry + ?Sized>(
        &mut self,
        geom: &G,
        theta: f64,
        phi: f64,
        set: RowSet,
        objective: Objective,
    ) {
        for r in joint_rows(geom, theta, phi) {
            if set.includes(r.condition) {
                self.push_row(&r, objective);
            }
        }
    }

    fn push_row(&mut self, r: &Row, objective: Objective) {
        let (a, b) = lp_row(r, objective);
        // Joint rows come first: insert before the auxiliary rows.
        let at = self.joints.len();
        self.a.insert(at, a);
        self.b.insert(at, b);
        self.joints.push(JointRow {
            theta: r.theta,
            condition: r.condition,
        });
    }

    /// The margin programme at the given joints: rows a·x + τ|a| ≤ b − a_λ λ, and τ ≤ cap.
    pub fn margin<G: ArchGeometry + ?Sized>(
        geom: &G,
        thetas: &[f64],
        phi: f64,
        set: RowSet,
        lambda: f64,
        cap: f64,
    ) -> Self {
        let mut rows = LinearRows {
            a: vec![OBJECTIVE],
            b: vec![cap],
            joints: Vec::new(),
        };
        for &t in thetas {
            rows.push_joint(geom, t, phi, set, Objective::Margin { lambda, cap });
        }
        rows
    }

    /// The load-factor programme at the given joints: rows a·x + a_λ λ ≤ b, and λ ≥ 0.
    pub fn load_factor<G: ArchGeometry + ?Sized>(
        geom: &G,
        thetas: &[f64],
        phi: f64,
        set: RowSet,
    ) -> Self {
        let mut rows = LinearRows::new(Objective::LoadFactor);
        for &t in thetas {
            rows.push_joint(geom, t, phi, set, Objective::LoadFactor);
        }
        rows
    }

    fn new(objective: Objective) -> Self {
        match objective {
            Objective::Margin { cap, .. } => LinearRows {
                a: vec![OBJECTIVE],
                b: vec![cap],
                joints: Vec::new(),
            },
            // λ ≥ 0: the live load acts in its own sense.
            Objective::LoadFactor => LinearRows {
                a: vec![LAMBDA_NON_NEGATIVE],
                b: vec![0.0],
                joints: Vec::new(),
            },
        }
    }
}

/// Brent's method for a local maximum of `f` on [a, b] (golden section with parabolic
/// steps), to an absolute tolerance `tol` in the argument. Returns (argmax, max).
fn maximise_1d<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, tol: f64) -> (f64, f64) {
    const CGOLD: f64 = 0.381_966_011_250_105_1;
    let (mut a, mut b) = (a.min(b), a.max(b));
    let mut x = a + CGOLD * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = -f(x);
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e): (f64, f64) = (0.0, 0.0);
    for _ in 0..200 {
        let xm = 0.5 * (a + b);
        let tol1 = tol + 1e-15 * x.abs();
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
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
        let fu = -f(u);
        if fu.is_nan() {
            break;
        }
        if fu <= fx {
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
            if fu <= fw || w == x {
                (v, w) = (w, u);
                (fv, fw) = (fw, fu);
            } else if fu <= fv || v == x || v == w {
                v = u;
                fv = fu;
            }
        }
    }
    (x, -fx)
}

/// A joint where a row is (nearly) most violated.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    theta: f64,
    condition: Condition,
    violation: f64,
}

/// One problem: a geometry, a friction angle, a row set and an objective.
struct Problem<'g, G: ?Sized> {
    geom: &'g G,
    phi: f64,
    set: RowSet,
    objective: Objective,
}

/// The raw answer of a problem: programme solution, rows and residual.
struct Solved {
    outcome: Outcome,
    /// z = (x, t) (the ray when unbounded).
    z: [f64; 4],
    rows: LinearRows,
    /// Largest violation over all joints at z.
    max_violation: f64,
    active: Vec<ActiveRow>,
    /// The joint and condition of each active row.
    active_joints: Vec<JointRow>,
    iterations: usize,
}

impl<G: ArchGeometry + ?Sized> Problem<'_, G> {
    fn conditions(&self) -> impl Iterator<Item = Condition> + '_ {
        Condition::ALL.into_iter().filter(|c| self.set.includes(*c))
    }

    fn row(&self, theta: f64, condition: Condition) -> Row {
        let rows = joint_rows(self.geom, theta, self.phi);
        match condition {
            Condition::Intrados => rows[0],
            Condition::Extrados => rows[1],
            Condition::SlideOutward => rows[2],
            Condition::SlideInward => rows[3],
        }
    }

    /// The refined local maxima of the violation of each condition at z over every family
    /// of joints ([`ArchGeometry::families`]), and the violations at the isolated joints.
    fn scan(&self, z: &[f64; 4], homogeneous: bool, settings: &Settings) -> Vec<Candidate> {
        let families = self.geom.families();
        let total: f64 = families.iter().map(|f| (f[1] - f[0]).max(0.0)).sum();
        let samples = settings.exchange_samples.max(2);
        let mut out = Vec::new();
        let mut points = self.geom.isolated_joints();
        for &[lo, hi] in &families {
            if hi > lo && total > 0.0 {
                let n = ((samples as f64 * (hi - lo) / total).ceil() as usize).max(2);
                self.scan_family(lo, hi, n, z, homogeneous, settings, &mut out);
            } else {
                points.push(lo);
            }
        }
        for t in points {
            let rows = joint_rows(self.geom, t, self.phi);
            for (ci, condition) in Condition::ALL.into_iter().enumerate() {
                if self.set.includes(condition) {
                    out.push(Candidate {
                        theta: t,
                        condition,
                        violation: violation(&rows[ci], self.objective, z, homogeneous),
                    });
                }
            }
        }
        out
    }

    /// The refined local maxima over [lo, hi] (n sampling intervals) of the violation of each
    /// condition at z.
    #[allow(clippy::too_many_arguments)]
    fn scan_family(
        &self,
        lo: f64,
        hi: f64,
        n: usize,
        z: &[f64; 4],
        homogeneous: bool,
        settings: &Settings,
        out: &mut Vec<Candidate>,
    ) {
        let alpha = self.geom.half_angle();
        let step = (hi - lo) / n as f64;
        let thetas: Vec<f64> = (0..=n)
            .map(|i| if i == n { hi } else { lo + step * i as f64 })
            .collect();
        let samples: Vec<[Row; 4]> = thetas
            .iter()
            .map(|&t| joint_rows(self.geom, t, self.phi))
            .collect();
        for condition in self.conditions() {
            let ci = Condition::ALL
                .iter()
                .position(|c| *c == condition)
                .unwrap_or(0);
            let v: Vec<f64> = samples
                .iter()
                .map(|r| violation(&r[ci], self.objective, z, homogeneous))
                .collect();
            let mut maxima: Vec<usize> = (0..=n)
                .filter(|&i| (i == 0 || v[i] >= v[i - 1]) && (i == n || v[i] > v[i + 1]))
                .collect();
            maxima.sort_by(|&i, &j| v[j].total_cmp(&v[i]));
            maxima.truncate(settings.exchange_maxima.max(1));
            for i in maxima {
                let a = thetas[i.saturating_sub(1)];
                let b = thetas[(i + 1).min(n)];
                let f = |t: f64| violation(&self.row(t, condition), self.objective, z, homogeneous);
                let (mut t, mut fv) = maximise_1d(f, a, b, 1e-10 * alpha.max(1e-3));
                // Brent never evaluates the ends of its bracket: the sample may be better.
                if v[i] >= fv {
                    (t, fv) = (thetas[i], v[i]);
                }
                out.push(Candidate {
                    theta: t,
                    condition,
                    violation: fv,
                });
            }
        }
    }

    fn lp(&self, rows: &LinearRows, settings: &Settings) -> lp::Solution<4> {
        let s = lp::Settings {
            max_iter: settings.lp.max_iter.max(10_000 + 4 * rows.a.len()),
            ..settings.lp
        };
        match lp::maximise(&OBJECTIVE, &rows.a, &rows.b, &s) {
            Ok(sol) => sol,
            Err(_) => lp::Solution {
                status: lp::Status::NumericalFailure,
                x: [0.0; 4],
                objective: 0.0,
                basis: [None; 4],
                duals: [0.0; 4],
                ray: [0.0; 4],
                max_violation: 0.0,
                iterations: 0,
            },
        }
    }

    fn scale(z: &[f64; 4]) -> f64 {
        1.0 + z[..3].iter().fold(0.0_f64, |m, v| m.max(v.abs()))
    }

    fn active_tol(&self, z: &[f64; 4], settings: &Settings) -> f64 {
        settings.active_tol * Self::scale(z)
    }

    fn solve(&self, settings: &Settings) -> Solved {
        let mut s = match self.geom.discrete_joints() {
            Some(thetas) => self.solve_discrete(&thetas, settings),
            None => self.solve_continuum(settings),
        };
        // Only a limit state names a mechanism: τ ≈ 0 for a margin, any λ_max.
        let limit = match self.objective {
            Objective::Margin { .. } => s.z[3].abs() <= 1e-6 * Self::scale(&s.z),
            Objective::LoadFactor => true,
        };
        if s.outcome == Outcome::Solved && limit && !s.active.is_empty() {
            self.keep_necessary(&mut s, settings);
        }
        s
    }

    /// Keeps the active rows that name the mechanism: those that hold with equality in
    /// every optimal state, at joints that transmit a force.
    ///
    /// The programme's optimum may be a face rather than a point (at μ_min, say, the crown
    /// moment M₀ is free within a range): the vertex returned touches rows that other
    /// optimal states leave slack. With the fourth unknown fixed at its optimum, a row is
    /// kept iff the largest distance x can take from its plane over the optimal face is
    /// within `active_tol` (one small programme per active row, over the programme's rows
    /// and the active ones). A joint without normal force (a support that lifts off) holds
    /// its rows with 0 = 0 but neither hinges nor slides: it is open, and left out.
    fn keep_necessary(&self, s: &mut Solved, settings: &Settings) {
        let t = s.z[3];
        let scale = Self::scale(&s.z);
        let tol = self.active_tol(&s.z, settings);
        // x = z[..3] violates no row by more than the residual: relax every row by it.
        let relax = s.max_violation.max(0.0) + 1e-14 * scale;
        let mut a3: Vec<[f64; 3]> = Vec::with_capacity(s.rows.a.len() + s.active.len());
        let mut b3: Vec<f64> = Vec::with_capacity(a3.capacity());
        let mut push = |a: [f64; 4], b: f64| {
            let n = norm3(&[a[0], a[1], a[2]]);
            if n > 0.0 {
                a3.push([a[0], a[1], a[2]]);
                b3.push(b - a[3] * t + relax * n);
            }
        };
        for (a, b) in s.rows.a.iter().zip(&s.rows.b) {
            push(*a, *b);
        }
        let active: Vec<([f64; 4], f64)> = s
            .active_joints
            .iter()
            .map(|j| lp_row(&self.row(j.theta, j.condition), self.objective))
            .collect();
        for (a, b) in &active {
            push(*a, *b);
        }
        let lp_settings = lp::Settings {
            max_iter: settings.lp.max_iter.max(10_000 + 4 * a3.len()),
            ..settings.lp
        };
        let lambda = match self.objective {
            Objective::Margin { lambda, .. } => lambda,
            Objective::LoadFactor => t,
        };
        let mut keep = Vec::with_capacity(active.len());
        for ((a, b), j) in active.iter().zip(&s.active_joints) {
            let n = norm3(&[a[0], a[1], a[2]]);
            let c = [-a[0] / n, -a[1] / n, -a[2] / n];
            let necessary = match lp::maximise(&c, &a3, &b3, &lp_settings) {
                Ok(sol) if sol.status == lp::Status::Optimal => {
                    // Largest distance from the plane (t fixed) over the optimal face.
                    let d = (b - a[3] * t) / n + sol.objective;
                    d <= tol + relax
                }
                Ok(sol) if sol.status == lp::Status::Unbounded => false,
                _ => true,
            };
            // The normal force N = F·t at the joint (compression > 0).
            let d = self.geom.dead_load(j.theta);
            let l = self.geom.live_load(j.theta);
            let normal = self.geom.joint(j.theta).normal();
            let f = [s.z[0] + d.fx + lambda * l.fx, s.z[1] + d.fy + lambda * l.fy];
            let n_force = f[0] * normal[0] + f[1] * normal[1];
            keep.push(necessary && n_force > tol);
        }
        let mut k = keep.iter();
        s.active.retain(|_| *k.next().unwrap_or(&true));
        let mut k = keep.iter();
        s.active_joints.retain(|_| *k.next().unwrap_or(&true));
    }

    fn solve_discrete(&self, thetas: &[f64], settings: &Settings) -> Solved {
        let mut rows = LinearRows::new(self.objective);
        for &t in thetas {
            rows.push_joint(self.geom, t, self.phi, self.set, self.objective);
        }
        let sol = self.lp(&rows, settings);
        let outcome = match sol.status {
            lp::Status::Optimal => Outcome::Solved,
            lp::Status::Infeasible => Outcome::Infeasible,
            lp::Status::Unbounded => Outcome::Unbounded,
            s => Outcome::Failed(s),
        };
        let z = if outcome == Outcome::Unbounded {
            sol.ray
        } else {
            sol.x
        };
        let mut max_violation = f64::NEG_INFINITY;
        let mut active = Vec::new();
        let mut active_joints = Vec::new();
        let tol = self.active_tol(&z, settings);
        for (a, (b, j)) in rows.a.iter().zip(rows.b.iter().zip(&rows.joints)) {
            let n = norm3(&[a[0], a[1], a[2]]);
            let s = a[0] * z[0] + a[1] * z[1] + a[2] * z[2] + a[3] * z[3] - b;
            let v = if n > 0.0 { s / n } else { s };
            max_violation = max_violation.max(v);
            if outcome == Outcome::Solved && v >= -tol {
                active.push(ActiveRow {
                    angle_deg: self.geom.angle_deg(j.theta),
                    condition: j.condition,
                    slack: (-v).max(0.0),
                });
                active_joints.push(*j);
            }
        }
        Solved {
            outcome,
            z,
            rows,
            max_violation,
            active,
            active_joints,
            iterations: 1,
        }
    }

    fn solve_continuum(&self, settings: &Settings) -> Solved {
        let n0 = settings.exchange_initial_joints.max(2);
        let mut rows = LinearRows::new(self.objective);
        let families = self.geom.families();
        let total: f64 = families.iter().map(|f| (f[1] - f[0]).max(0.0)).sum();
        for &[lo, hi] in &families {
            if hi > lo && total > 0.0 {
                let n = ((n0 as f64 * (hi - lo) / total).ceil() as usize).max(2);
                for i in 0..n {
                    let t = if i + 1 == n {
                        hi
                    } else {
                        lo + (hi - lo) * i as f64 / (n - 1) as f64
                    };
                    rows.push_joint(self.geom, t, self.phi, self.set, self.objective);
                }
            } else {
                rows.push_joint(self.geom, lo, self.phi, self.set, self.objective);
            }
        }
        for t in self.geom.isolated_joints() {
            rows.push_joint(self.geom, t, self.phi, self.set, self.objective);
        }
        let mut iterations = 0;
        loop {
            iterations += 1;
            let sol = self.lp(&rows, settings);
            let (z, homogeneous) = match sol.status {
                lp::Status::Optimal => (sol.x, false),
                lp::Status::Unbounded => (sol.ray, true),
                lp::Status::Infeasible => {
                    return Solved {
                        outcome: Outcome::Infeasible,
                        z: sol.x,
                        rows,
                        max_violation: f64::INFINITY,
                        active: Vec::new(),
                        active_joints: Vec::new(),
                        iterations,
                    };
                }
                s => {
                    return Solved {
                        outcome: Outcome::Failed(s),
                        z: sol.x,
                        rows,
                        max_violation: f64::INFINITY,
                        active: Vec::new(),
                        active_joints: Vec::new(),
                        iterations,
                    };
                }
            };
            let candidates = self.scan(&z, homogeneous, settings);
            let vmax = candidates
                .iter()
                .fold(f64::NEG_INFINITY, |m, c| m.max(c.violation));
            let tol = settings.exchange_tol * Self::scale(&z);
            let done = |outcome: Outcome, rows: LinearRows| {
                let atol = self.active_tol(&z, settings);
                let mut pairs: Vec<(ActiveRow, JointRow)> = if outcome == Outcome::Solved {
                    candidates
                        .iter()
                        .filter(|c| c.violation >= vmax.max(0.0) - atol)
                        .map(|c| {
                            (
                                ActiveRow {
                                    angle_deg: self.geom.angle_deg(c.theta),
                                    condition: c.condition,
                                    slack: (vmax.max(0.0) - c.violation).max(0.0),
                                },
                                JointRow {
                                    theta: c.theta,
                                    condition: c.condition,
                                },
                            )
                        })
                        .collect()
                } else {
                    Vec::new()
                };
                pairs.sort_by(|a, b| a.0.angle_deg.total_cmp(&b.0.angle_deg));
                let (active, active_joints): (Vec<ActiveRow>, Vec<JointRow>) =
                    pairs.into_iter().unzip();
                Solved {
                    outcome,
                    z,
                    rows,
                    max_violation: vmax,
                    active,
                    active_joints,
                    iterations,
                }
            };
            if vmax <= tol {
                let outcome = if homogeneous {
                    Outcome::Unbounded
                } else {
                    Outcome::Solved
                };
                return done(outcome, rows);
            }
            if iterations >= settings.exchange_max_iter {
                return done(Outcome::NotConverged, rows);
            }
            let mut added = 0;
            for c in candidates.iter().filter(|c| c.violation > tol) {
                let known = rows
                    .joints
                    .iter()
                    .any(|j| j.condition == c.condition && j.theta == c.theta);
                if !known {
                    rows.push_row(&self.row(c.theta, c.condition), self.objective);
                    added += 1;
                }
            }
            if added == 0 {
                // Every violated joint is already a row: the residual is what the programme
                // solver accepted (its tolerance also scales with t), not a missing joint.
                let lp_tol = 10.0
                    * settings.lp.tol_feas
                    * (1.0 + z.iter().fold(0.0, |m: f64, v| m.max(v.abs())));
                let outcome = if vmax <= lp_tol {
                    if homogeneous {
                        Outcome::Unbounded
                    } else {
                        Outcome::Solved
                    }
                } else {
                    Outcome::NotConverged
                };
                return done(outcome, rows);
            }
        }
    }
}

/// The margin of a geometry at friction angle φ (radians) over a set of rows, with λ fixed
/// at `settings.lambda`.
///
/// Invariant: `margin ≥ −margin_tol` iff the rows of `set` admit a common solution (up to the
/// exchange tolerance for a continuum).
pub fn margin<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    set: RowSet,
    settings: &Settings,
) -> MarginSolution {
    let p = Problem {
        geom,
        phi,
        set,
        objective: Objective::Margin {
            lambda: settings.lambda,
            cap: settings.margin_cap,
        },
    };
    let s = p.solve(settings);
    // A lower bound on the exact margin: shift τ down by the residual violation.
    let tau = s.z[3] - s.max_violation.max(0.0);
    MarginSolution {
        outcome: s.outcome,
        margin: if s.outcome == Outcome::Solved {
            tau
        } else {
            f64::NEG_INFINITY
        },
        crown: CrownState::from_x(&s.z),
        max_violation: s.max_violation,
        active: s.active,
        rows: s.rows.a.len(),
        iterations: s.iterations,
    }
}

/// The regime of a point with its three margins (DESIGN.md §1 "Regimes").
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeReport {
    /// The regime; `None` when a margin could not be computed.
    pub regime: Option<Regime>,
    /// Margin of the rotational rows alone (H^r ≠ ∅ iff feasible).
    pub rotational: MarginSolution,
    /// Margin of the sliding rows alone (H^s ≠ ∅ iff feasible).
    pub sliding: MarginSolution,
    /// Margin of all rows (the arch stands iff feasible).
    pub all: MarginSolution,
}

/// The regime at friction angle φ (radians): stable when all rows are feasible, rotational
/// when only the sliding rows are, sliding when only the rotational rows are, mixed when both
/// are but not together, none when neither is.
pub fn regime<G: ArchGeometry + ?Sized>(geom: &G, phi: f64, settings: &Settings) -> RegimeReport {
    let rotational = margin(geom, phi, RowSet::Rotational, settings);
    let sliding = margin(geom, phi, RowSet::Sliding, settings);
    let all = margin(geom, phi, RowSet::All, settings);
    let solved = [&rotational, &sliding, &all]
        .iter()
        .all(|m| m.outcome == Outcome::Solved);
    let regime = solved.then(|| {
        match (
            rotational.feasible(settings),
            sliding.feasible(settings),
            all.feasible(settings),
        ) {
            (_, _, true) => Regime::Stable,
            (true, true, false) => Regime::Mixed,
            (false, true, false) => Regime::Rotational,
            (true, false, false) => Regime::Sliding,
            (false, false, false) => Regime::None,
        }
    });
    RegimeReport {
        regime,
        rotational,
        sliding,
        all,
    }
}

/// The mechanism named by a set of active rows.
pub fn mechanism_of(active: &[ActiveRow]) -> Option<Mechanism> {
    let mut hinges = Vec::new();
    let mut sliding = Vec::new();
    for r in active {
        match r.condition {
            Condition::Intrados => hinges.push(Hinge {
                angle_deg: r.angle_deg,
                face: Face::Intrados,
            }),
            Condition::Extrados => hinges.push(Hinge {
                angle_deg: r.angle_deg,
                face: Face::Extrados,
            }),
            Condition::SlideOutward | Condition::SlideInward => {
                // The rows are written for the part right of the joint; on the left half
                // that part is the crown side only when θ > 0, so the sense flips for θ < 0.
                let outward_row = r.condition == Condition::SlideOutward;
                let sense = if outward_row == (r.angle_deg >= 0.0) {
                    Sense::Outward
                } else {
                    Sense::Inward
                };
                sliding.push(SlidingJoint {
                    angle_deg: r.angle_deg,
                    sense,
                });
            }
        }
    }
    // Both sides of a point load are joints at (nearly) the same angle: one joint each.
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + a.abs());
    hinges.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
    hinges.dedup_by(|a, b| a.face == b.face && same(a.angle_deg, b.angle_deg));
    sliding.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
    sliding.dedup_by(|a, b| a.sense == b.sense && same(a.angle_deg, b.angle_deg));
    Mechanism::from_parts(hinges, sliding)
}

/// A limit state found by a critical-value search.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitState {
    /// K = R/r at the limit for a thickness search; `None` for a friction search (the
    /// geometry's own K applies).
    pub k: Option<f64>,
    /// μ at the limit (infinite when friction plays no part).
    pub mu: f64,
    /// The margin solution there: crown state and active rows.
    pub state: MarginSolution,
    /// The mechanism named by the active rows.
    pub mechanism: Option<Mechanism>,
}

/// The outcome of a critical-value search.
#[derive(Debug, Clone, PartialEq)]
pub enum Critical {
    /// A limit state exists.
    Found(LimitState),
    /// No value of the searched parameter lets the arch stand.
    NeverStands,
    /// The arch stands for every admissible value of the searched parameter.
    AlwaysStands,
    /// A margin could not be computed.
    Failed(Outcome),
}

impl Critical {
    /// The limit state when found.
    pub fn found(&self) -> Option<&LimitState> {
        match self {
            Critical::Found(s) => Some(s),
            _ => None,
        }
    }
}

/// Brent on `psi` over [lo, hi] where psi(lo) < 0 ≤ psi(hi); a failed margin inside is
/// reported through `failed`.
fn root_of_margin(
    psi: impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    tol: f64,
    failed: &Cell<Option<Outcome>>,
) -> Result<Option<f64>, Outcome> {
    let r = brent(&psi, lo, hi, tol);
    match failed.get() {
        Some(o) => Err(o),
        None => Ok(r),
    }
}

/// The margin of all rows shifted for a root search: τ − τ_ref + tol, where τ_ref ≤ 0 is
/// the margin of the rows the search does not relax (see [`thickness`]). NaN on failure
/// (which stops Brent), recorded in `failed`.
fn shifted_margin(
    m: &MarginSolution,
    reference: f64,
    settings: &Settings,
    failed: &Cell<Option<Outcome>>,
) -> f64 {
    if m.outcome == Outcome::Solved {
        m.margin - reference + settings.margin_tol
    } else {
        failed.set(Some(m.outcome));
        f64::NAN
    }
}

/// A search that ends without a limit state.
#[derive(Debug, Clone, Copy)]
enum Stop {
    Never,
    Always,
    Failed(Outcome),
}

impl From<Stop> for Critical {
    fn from(s: Stop) -> Critical {
        match s {
            Stop::Never => Critical::NeverStands,
            Stop::Always => Critical::AlwaysStands,
            Stop::Failed(o) => Critical::Failed(o),
        }
    }
}

/// The reference τ_ref = min(τ, 0) of a margin that a search cannot improve, or the outcome
/// of the search when that margin already decides it.
fn reference(m: &MarginSolution, settings: &Settings) -> Result<f64, Stop> {
    if m.outcome != Outcome::Solved {
        return Err(Stop::Failed(m.outcome));
    }
    if !m.feasible(settings) {
        return Err(Stop::Never);
    }
    Ok(m.margin.min(0.0))
}

/// The smallest p in [lo, hi] with psi(p) ≥ 0, for psi whose sign is non-decreasing; `hi`
/// doubles away from `lo` (up to `cap`) while psi(hi) < 0 when `grow_hi`.
fn search(
    psi: impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    tol: f64,
    grow_hi: bool,
    failed: &Cell<Option<Outcome>>,
) -> Result<f64, Stop> {
    search_capped(psi, lo, hi, f64::INFINITY, tol, grow_hi, failed)
}

/// [`search`] with `hi` never beyond `cap`.
fn search_capped(
    psi: impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    cap: f64,
    tol: f64,
    grow_hi: bool,
    failed: &Cell<Option<Outcome>>,
) -> Result<f64, Stop> {
    let check = |f: f64| match failed.get() {
        Some(o) => Err(Stop::Failed(o)),
        None => Ok(f),
    };
    if check(psi(lo))? >= 0.0 {
        return Err(Stop::Always);
    }
    let mut hi = hi.min(cap);
    while check(psi(hi))? < 0.0 {
        if !grow_hi || hi >= cap {
            return Err(Stop::Never);
        }
        hi = (lo + 2.0 * (hi - lo)).min(cap);
        if hi - lo > FAR {
            return Err(Stop::Never);
        }
    }
    match root_of_margin(psi, lo, hi, tol, failed) {
        Err(o) => Err(Stop::Failed(o)),
        Ok(None) => Err(Stop::Never),
        Ok(Some(p)) => Ok(p),
    }
}

/// The collapse thickness K_c of a circular arch at friction μ: the smallest K at which all
/// rows are feasible (the collapse condition of the paper's §5), by Brent on the margin in
/// K ∈ (1, ∞).
///
/// The root is taken of τ_all(K) − τ_ref + tol with τ_ref = min(τ_sliding, 0): thickness
/// cannot make the sliding rows more feasible, so when μ sits at μ_min (τ_sliding ≈ 0⁻) the
/// search measures the thickness against what sliding allows instead of against noise.
/// Invariant: τ_all ≥ τ_ref − `margin_tol` ≥ −2 `margin_tol` at the returned K.
pub fn thickness(arch: &Arch, friction: Friction, settings: &Settings) -> Critical {
    thickness_with(
        |k| Some(CircularArch::new(arch.with_k(k))),
        f64::INFINITY,
        Some(arch.k),
        friction,
        settings,
    )
}

/// The collapse thickness of any family of arches K ↦ `at(K)`, K ∈ (1, `k_max`), at
/// friction μ and the load factor `settings.lambda`: as [`thickness`].
///
/// `at(K)` is `None` where the family does not exist (it counts as not standing there).
/// `sliding_reference` is a K at which to take τ_ref when the sliding rows do not depend on
/// K (circular arches with radial joints: the loads over W_half are the same at every K);
/// `None` takes τ_ref = 0. A family that does not stand up to `k_max` never stands.
pub fn thickness_with<G: ArchGeometry, F: Fn(f64) -> Option<G>>(
    at: F,
    k_max: f64,
    sliding_reference: Option<f64>,
    friction: Friction,
    settings: &Settings,
) -> Critical {
    let phi = friction.angle();
    let failed = Cell::new(None);
    let tau_ref = match sliding_reference {
        Some(k) => match at(k).map(|g| margin(&g, phi, RowSet::Sliding, settings)) {
            Some(m) => match reference(&m, settings) {
                Ok(r) => r,
                Err(c) => return c.into(),
            },
            None => 0.0,
        },
        None => 0.0,
    };
    let psi = |k: f64| match at(k) {
        Some(g) => shifted_margin(
            &margin(&g, phi, RowSet::All, settings),
            tau_ref,
            settings,
            &failed,
        ),
        None => -1.0,
    };
    // Stay clear of the end of the family, where it degenerates.
    let cap = if k_max.is_finite() {
        1.0 + (k_max - 1.0) * (1.0 - 1e-9)
    } else {
        f64::INFINITY
    };
    let k = match search_capped(psi, 1.0 + 1e-12, 1.5, cap, 1e-15, true, &failed) {
        Ok(k) => k,
        Err(c) => return c.into(),
    };
    let Some(g) = at(k) else {
        return Critical::NeverStands;
    };
    let state = margin(&g, phi, RowSet::All, settings);
    Critical::Found(LimitState {
        k: Some(k),
        mu: friction.mu(),
        mechanism: state.mechanism(),
        state,
    })
}

/// The smallest μ = tan φ at which the rows of `set` are feasible, by Brent on the margin
/// in φ ∈ [0, π/2], shifted by the reference margin `tau_ref` ≤ 0.
fn friction_search<G: ArchGeometry + ?Sized>(
    geom: &G,
    set: RowSet,
    tau_ref: f64,
    settings: &Settings,
) -> Critical {
    let failed = Cell::new(None);
    let psi = |phi: f64| {
        shifted_margin(
            &margin(geom, phi, set, settings),
            tau_ref,
            settings,
            &failed,
        )
    };
    let phi = match search(psi, 0.0, FRAC_PI_2, 1e-16, false, &failed) {
        Ok(p) => p,
        Err(c) => return c.into(),
    };
    let state = margin(geom, phi, set, settings);
    Critical::Found(LimitState {
        k: None,
        mu: phi.tan(),
        mechanism: state.mechanism(),
        state,
    })
}

/// The critical friction μ_c (paper §5): the smallest μ = tan φ at which the arch stands
/// (all rows feasible), by Brent on the margin in φ.
///
/// As in [`thickness`], the root is taken of τ_all(φ) − τ_ref + tol with
/// τ_ref = min(τ_rotational, 0), so that at K = K_c (τ_rotational ≈ 0⁻) the result is the
/// bifurcation friction rather than noise. Invariant: τ_all ≥ −2 `margin_tol` at the result.
pub fn friction<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> Critical {
    let rotational = margin(geom, FRAC_PI_2, RowSet::Rotational, settings);
    match reference(&rotational, settings) {
        Ok(r) => friction_search(geom, RowSet::All, r, settings),
        Err(c) => c.into(),
    }
}

/// μ_min: the smallest μ at which the sliding rows alone are feasible (H^s shrinks to a
/// point there, paper §2); below it no thickness lets the arch stand.
pub fn sliding_threshold<G: ArchGeometry + ?Sized>(geom: &G, settings: &Settings) -> Critical {
    friction_search(geom, RowSet::Sliding, 0.0, settings)
}

/// The largest load factor λ (multiples of the total weight) at friction angle φ (radians).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadFactor {
    /// Solved, infeasible (no λ), unbounded (every λ), not converged or failed.
    pub outcome: Outcome,
    /// λ_max: finite when solved, +∞ when unbounded, −∞ otherwise.
    pub lambda: f64,
    /// The crown state of the limit (the ray when unbounded).
    pub crown: CrownState,
    /// Active rows at the limit: the collapse mechanism.
    pub active: Vec<ActiveRow>,
    /// The mechanism named by the active rows.
    pub mechanism: Option<Mechanism>,
    /// Largest violation of a row at the solution (≤ 0 up to tolerance).
    pub max_violation: f64,
    /// Exchange steps (1 for a discrete arch).
    pub iterations: usize,
}

/// Maximises λ ≥ 0 subject to all rows (the static theorem for a proportional live load):
/// the collapse load factor of the live load of `geom` on top of its dead load. Infeasible
/// when no λ ≥ 0 admits a state, unbounded when every λ ≥ 0 does.
pub fn load_factor<G: ArchGeometry + ?Sized>(
    geom: &G,
    phi: f64,
    settings: &Settings,
) -> LoadFactor {
    let p = Problem {
        geom,
        phi,
        set: RowSet::All,
        objective: Objective::LoadFactor,
    };
    let s = p.solve(settings);
    let lambda = match s.outcome {
        Outcome::Solved => s.z[3],
        Outcome::Unbounded => f64::INFINITY,
        _ => f64::NEG_INFINITY,
    };
    LoadFactor {
        outcome: s.outcome,
        lambda,
        crown: CrownState::from_x(&s.z),
        mechanism: mechanism_of(&s.active),
        active: s.active,
        max_violation: s.max_violation,
        iterations: s.iterations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::MechanismKind;
    use crate::analysis::statics::Resultant;
    use crate::analysis::symmetric;
    use crate::model::{Discretisation, WeightModel};

    const K_C: f64 = 1.113581813339;
    const MU_ROT: f64 = 0.395265252140;
    const MU_MIN: f64 = 0.309215444330;
    const K_BIF: f64 = 1.220507754643;

    fn arch(k: f64, alpha_deg: f64, weight: WeightModel, joints: Discretisation) -> Arch {
        Arch::new(k, alpha_deg, weight, joints).unwrap()
    }

    fn semi(k: f64, joints: Discretisation) -> Arch {
        arch(k, 90.0, WeightModel::Annular, joints)
    }

    fn mu(m: f64) -> Friction {
        Friction::new(m).unwrap()
    }

    fn k_of(c: &Critical) -> f64 {
        c.found().and_then(|s| s.k).expect("a critical thickness")
    }

    fn mu_of(c: &Critical) -> f64 {
        c.found().map(|s| s.mu).expect("a critical friction")
    }

    fn sym_k(c: &symmetric::Critical) -> f64 {
        c.found().expect("symmetric K").k
    }

    fn sym_mu(c: &symmetric::Critical) -> f64 {
        c.found().expect("symmetric μ").mu
    }

    /// The five critical values of the paper for one arch by the general route:
    /// K_c (μ = ∞), μ_c at K_c, μ_min, K at μ_min, K at μ = 0.35.
    fn general_values(a: &Arch) -> [f64; 5] {
        let s = Settings::default();
        let kc = k_of(&thickness(a, Friction::INFINITE, &s));
        let mu_rot = mu_of(&friction(&CircularArch::new(a.with_k(kc)), &s));
        let mu_min = mu_of(&sliding_threshold(&CircularArch::new(*a), &s));
        let k_bif = k_of(&thickness(a, mu(mu_min), &s));
        let k_mixed = k_of(&thickness(a, mu(0.35), &s));
        [kc, mu_rot, mu_min, k_bif, k_mixed]
    }

    /// The same five values by the symmetric closed forms. The bifurcation friction is the
    /// thrust of the K_c state (sliding at the springings, where H_max^s = μ W_half):
    /// `symmetric::friction` at exactly K_c(N) is ill-conditioned for discrete arches (it
    /// gives 0.41844 for N = 64 where H^s at μ = 0.3953 already contains H^r = {0.39524}).
    fn symmetric_values(a: &Arch) -> [f64; 5] {
        let at_kc = symmetric::thickness(a, Friction::INFINITE);
        let kc = sym_k(&at_kc);
        let mu_rot = at_kc.found().expect("K_c state").thrust_over_half_weight;
        let mu_min = sym_mu(&symmetric::sliding_threshold(a));
        let k_bif = sym_k(&symmetric::thickness(a, mu(mu_min)));
        let k_mixed = sym_k(&symmetric::thickness(a, mu(0.35)));
        [kc, mu_rot, mu_min, k_bif, k_mixed]
    }

    fn assert_close(what: &str, got: [f64; 5], want: [f64; 5], tol: f64) {
        let names = ["K_c", "mu_rot", "mu_min", "K_bif", "K(0.35)"];
        for i in 0..5 {
            assert!(
                (got[i] - want[i]).abs() < tol,
                "{what}: {} = {} vs {} (diff {:e})",
                names[i],
                got[i],
                want[i],
                got[i] - want[i]
            );
        }
    }

    #[test]
    fn continuum_reproduces_the_reference_values() {
        let a = semi(1.5, Discretisation::Continuum);
        let g = general_values(&a);
        let mut want = symmetric_values(&a);
        want[..4].copy_from_slice(&[K_C, MU_ROT, MU_MIN, K_BIF]);
        assert_close("continuum", g, want, 1e-9);
    }

    #[test]
    fn discrete_arches_agree_with_the_symmetric_route() {
        for n in [16, 64] {
            let a = semi(1.5, Discretisation::Voussoirs(n));
            assert_close(
                &format!("N = {n}"),
                general_values(&a),
                symmetric_values(&a),
                1e-9,
            );
            // Away from K_c both friction searches are well conditioned.
            for k in [1.15, 1.3] {
                let g = mu_of(&friction(
                    &CircularArch::new(a.with_k(k)),
                    &Settings::default(),
                ));
                let w = sym_mu(&symmetric::friction(&a.with_k(k)));
                assert!((g - w).abs() < 1e-9, "N = {n}, K = {k}: {g} vs {w}");
            }
        }
    }

    #[test]
    fn centreline_weight_agrees_with_the_symmetric_route() {
        for joints in [Discretisation::Continuum, Discretisation::Voussoirs(16)] {
            let a = arch(1.5, 90.0, WeightModel::Centreline, joints);
            assert_close(
                &format!("centreline {joints}"),
                general_values(&a),
                symmetric_values(&a),
                1e-9,
            );
        }
    }

    #[test]
    fn segmental_and_horseshoe_arches_agree_with_the_symmetric_route() {
        // (α, a μ above μ_min, a K above K_c): μ_min is 0.0944 at 60°, 0.739 at 120°.
        for (alpha, m, k) in [(60.0, 0.5, 1.3), (120.0, 0.8, 1.6)] {
            let a = arch(1.5, alpha, WeightModel::Annular, Discretisation::Continuum);
            let s = Settings::default();
            let g = [
                k_of(&thickness(&a, Friction::INFINITE, &s)),
                mu_of(&sliding_threshold(&CircularArch::new(a), &s)),
                k_of(&thickness(&a, mu(m), &s)),
                mu_of(&friction(&CircularArch::new(a.with_k(k)), &s)),
            ];
            let w = [
                sym_k(&symmetric::thickness(&a, Friction::INFINITE)),
                sym_mu(&symmetric::sliding_threshold(&a)),
                sym_k(&symmetric::thickness(&a, mu(m))),
                sym_mu(&symmetric::friction(&a.with_k(k))),
            ];
            for i in 0..4 {
                assert!(
                    (g[i] - w[i]).abs() < 1e-9,
                    "α = {alpha}: value {i}: {} vs {} ({:e})",
                    g[i],
                    w[i],
                    g[i] - w[i]
                );
            }
        }
    }

    #[test]
    fn rotational_mechanism_at_k_c() {
        let c = thickness(
            &semi(1.5, Discretisation::Continuum),
            Friction::INFINITE,
            &Settings::default(),
        );
        let s = c.found().unwrap();
        let m = s.mechanism.as_ref().unwrap();
        assert_eq!(m.kind, MechanismKind::Rotational);
        let angles: Vec<(f64, Face)> = m.hinges.iter().map(|h| (h.angle_deg, h.face)).collect();
        assert_eq!(angles.len(), 5, "{angles:?}");
        let want = [
            (-90.0, Face::Extrados),
            (-54.48397403, Face::Intrados),
            (0.0, Face::Extrados),
            (54.48397403, Face::Intrados),
            (90.0, Face::Extrados),
        ];
        for ((a, f), (wa, wf)) in angles.iter().zip(want) {
            assert_eq!(*f, wf);
            assert!((a - wa).abs() < 1e-6, "{angles:?}");
        }
        // The limit state is symmetric: no shear at the crown, thrust = μ at the bifurcation.
        let crown = s.state.crown;
        assert!(crown.shear_over_half_weight.abs() < 1e-12);
        assert!((crown.thrust_over_half_weight - MU_ROT).abs() < 1e-9);
    }

    #[test]
    fn sliding_mechanism_at_mu_min() {
        let c = sliding_threshold(
            &CircularArch::new(semi(1.3, Discretisation::Continuum)),
            &Settings::default(),
        );
        let m = c.found().unwrap().mechanism.clone().unwrap();
        assert_eq!(m.kind, MechanismKind::Sliding);
        let j: Vec<(f64, Sense)> = m
            .sliding_joints
            .iter()
            .map(|j| (j.angle_deg, j.sense))
            .collect();
        assert_eq!(j.len(), 4, "{j:?}");
        assert!(
            (j[2].0 - 28.63619468).abs() < 1e-6 && j[2].1 == Sense::Inward,
            "{j:?}"
        );
        assert!(
            (j[3].0 - 90.0).abs() < 1e-12 && j[3].1 == Sense::Outward,
            "{j:?}"
        );
        assert_eq!((j[0].1, j[1].1), (Sense::Outward, Sense::Inward), "{j:?}");
    }

    #[test]
    fn mixed_mechanism_between_the_bifurcations() {
        let c = thickness(
            &semi(1.5, Discretisation::Continuum),
            mu(0.35),
            &Settings::default(),
        );
        let m = c.found().unwrap().mechanism.clone().unwrap();
        assert_eq!(m.kind, MechanismKind::Mixed, "{m:?}");
        // Sliding at both springings, outward.
        assert_eq!(m.sliding_joints.len(), 2, "{m:?}");
        assert!(m.sliding_joints.iter().all(|j| j.sense == Sense::Outward));
    }

    #[test]
    fn regimes_agree_with_the_symmetric_route() {
        let s = Settings::default();
        let points = [
            (1.3, 0.6),
            (1.2, f64::INFINITY),
            (1.05, 0.6),
            (1.1, f64::INFINITY),
            (1.15, 0.33),
            (1.12, 0.36),
            (1.3, 0.2),
            (1.5, 0.3),
            (1.05, 0.2),
            (1.1, 0.0),
        ];
        let mut seen = std::collections::HashSet::new();
        for joints in [
            Discretisation::Continuum,
            Discretisation::Voussoirs(16),
            Discretisation::Voussoirs(64),
        ] {
            for (k, m) in points {
                let a = semi(k, joints);
                let f = if m.is_infinite() {
                    Friction::INFINITE
                } else {
                    mu(m)
                };
                let want = symmetric::state(&a, f).regime;
                let got = regime(&CircularArch::new(a), f.angle(), &s);
                assert_eq!(got.regime, Some(want), "K = {k}, μ = {m}, {joints}");
                seen.insert(want);
            }
        }
        assert_eq!(seen.len(), 5, "{seen:?}");
    }

    #[test]
    fn degenerate_points_give_finite_answers() {
        let s = Settings::default();
        for joints in [Discretisation::Continuum, Discretisation::Voussoirs(3)] {
            for k in [1.0 + 1e-9, 1.1, 3.0] {
                let g = CircularArch::new(semi(k, joints));
                for phi in [0.0, 0.3, FRAC_PI_2] {
                    let r = regime(&g, phi, &s);
                    assert!(r.regime.is_some(), "K = {k}, φ = {phi}, {joints}");
                    for m in [&r.rotational, &r.sliding, &r.all] {
                        assert!(m.margin.is_finite() && m.margin <= s.margin_cap);
                        assert!(m.crown.thrust_over_half_weight.is_finite());
                    }
                }
            }
        }
        // A single voussoir on two springings: the thinnest arch stands at μ = ∞.
        let one = semi(1.5, Discretisation::Voussoirs(1));
        let t = thickness(&one, Friction::INFINITE, &s);
        assert_eq!(
            t,
            Critical::AlwaysStands,
            "{:?}",
            symmetric::thickness(&one, Friction::INFINITE)
        );
    }

    /// The semicircular arch with a horizontal body force λ·g to the right (DESIGN.md §1).
    struct Horizontal(CircularArch);

    impl ArchGeometry for Horizontal {
        fn half_angle(&self) -> f64 {
            self.0.half_angle()
        }
        fn joint(&self, theta: f64) -> crate::analysis::statics::Joint {
            self.0.joint(theta)
        }
        fn dead_load(&self, theta: f64) -> Resultant {
            self.0.dead_load(theta)
        }
        fn live_load(&self, theta: f64) -> Resultant {
            // Per unit λ the force is the weight, acting at the weight radius ρ_s.
            let a = self.0.half_angle();
            Resultant {
                fx: theta / a,
                fy: 0.0,
                m: -self.0.weight_radius() * theta.sin() / a,
            }
        }
        fn discrete_joints(&self) -> Option<Vec<f64>> {
            self.0.discrete_joints()
        }
    }

    #[test]
    fn load_factor_vanishes_at_collapse_and_matches_the_margin() {
        let s = Settings::default();
        let kc = k_of(&thickness(
            &semi(1.5, Discretisation::Continuum),
            Friction::INFINITE,
            &s,
        ));
        // Just above K_c the arch carries only a vanishing horizontal load.
        let near_kc = load_factor(
            &Horizontal(CircularArch::new(semi(
                kc + 1e-9,
                Discretisation::Continuum,
            ))),
            FRAC_PI_2,
            &s,
        );
        assert_eq!(near_kc.outcome, Outcome::Solved);
        assert!(
            near_kc.lambda > 0.0 && near_kc.lambda < 1e-7,
            "λ = {}",
            near_kc.lambda
        );
        for joints in [Discretisation::Continuum, Discretisation::Voussoirs(64)] {
            let g = Horizontal(CircularArch::new(semi(1.3, joints)));
            let lf = load_factor(&g, 0.6f64.atan(), &s);
            assert_eq!(lf.outcome, Outcome::Solved, "{joints}");
            assert!(lf.lambda > 0.05 && lf.lambda < 1.0, "λ = {}", lf.lambda);
            assert!(lf.mechanism.is_some());
            // At λ_max the margin is zero; a little less λ leaves it positive.
            let at = |lambda: f64| {
                let s = Settings { lambda, ..s };
                margin(&g, 0.6f64.atan(), RowSet::All, &s).margin
            };
            assert!(at(lf.lambda).abs() < 1e-10, "{}", at(lf.lambda));
            assert!(at(lf.lambda - 1e-3) > 0.0);
            assert!(at(lf.lambda + 1e-3) < 0.0);
        }
        // Without any live load λ is unbounded.
        let plain = load_factor(
            &CircularArch::new(semi(1.3, Discretisation::Voussoirs(8))),
            FRAC_PI_2,
            &s,
        );
        assert_eq!(plain.outcome, Outcome::Unbounded);
        assert_eq!(plain.lambda, f64::INFINITY);
    }

    #[test]
    fn discrete_load_factor_tends_to_the_continuum() {
        let s = Settings::default();
        let phi = 0.6f64.atan();
        let cont = load_factor(
            &Horizontal(CircularArch::new(semi(1.3, Discretisation::Continuum))),
            phi,
            &s,
        );
        let fine = load_factor(
            &Horizontal(CircularArch::new(semi(
                1.3,
                Discretisation::Voussoirs(4096),
            ))),
            phi,
            &s,
        );
        // Fewer potential joints: the discrete arch carries at least as much.
        assert!(cont.lambda <= fine.lambda + 1e-12);
        assert!(
            fine.lambda - cont.lambda < 1e-5,
            "{} {}",
            cont.lambda,
            fine.lambda
        );
    }

    /// Solves maximise z₄ subject to a z ≤ b with clarabel (the oracle).
    fn clarabel_max(rows: &LinearRows) -> f64 {
        use clarabel::algebra::CscMatrix;
        use clarabel::solver::{
            DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
        };
        let p = CscMatrix::<f64>::zeros((4, 4));
        let q = OBJECTIVE.map(|c| -c);
        let a = CscMatrix::from(rows.a.iter());
        let cones = [NonnegativeConeT(rows.b.len())];
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_gap_abs(1e-11)
            .tol_gap_rel(1e-11)
            .tol_feas(1e-11)
            .build()
            .unwrap();
        let mut solver = DefaultSolver::new(&p, &q, &a, &rows.b, &cones, settings).unwrap();
        solver.solve();
        assert_eq!(solver.solution.status, SolverStatus::Solved);
        solver.solution.x[3]
    }

    #[test]
    fn clarabel_agrees_on_the_n64_programmes() {
        let s = Settings::default();
        let g = Horizontal(CircularArch::new(semi(1.2, Discretisation::Voussoirs(64))));
        let thetas = g.discrete_joints().unwrap();
        for (set, phi) in [
            (RowSet::All, 0.35f64.atan()),
            (RowSet::All, FRAC_PI_2),
            (RowSet::Rotational, 1.0),
        ] {
            let rows = LinearRows::margin(&g, &thetas, phi, set, 0.0, s.margin_cap);
            let ours = lp::maximise(&OBJECTIVE, &rows.a, &rows.b, &s.lp).unwrap();
            assert_eq!(ours.status, lp::Status::Optimal);
            let oracle = clarabel_max(&rows);
            assert!(
                (ours.x[3] - oracle).abs() < 1e-7,
                "{set:?}: {} vs {oracle}",
                ours.x[3]
            );
            // The general route uses the same programme.
            let m = margin(&g, phi, set, &s);
            assert!((m.margin - ours.x[3]).abs() < 1e-14);
        }
        let rows = LinearRows::load_factor(&g, &thetas, 0.6f64.atan(), RowSet::All);
        let ours = lp::maximise(&OBJECTIVE, &rows.a, &rows.b, &s.lp).unwrap();
        assert_eq!(ours.status, lp::Status::Optimal);
        let oracle = clarabel_max(&rows);
        assert!(
            (ours.x[3] - oracle).abs() < 1e-7,
            "λ: {} vs {oracle}",
            ours.x[3]
        );
    }

    #[test]
    fn maximise_1d_finds_interior_and_end_maxima() {
        let (x, f) = maximise_1d(|t| -(t - 0.3) * (t - 0.3), 0.0, 1.0, 1e-12);
        assert!((x - 0.3).abs() < 1e-8 && f.abs() < 1e-16);
        let (x, _) = maximise_1d(|t| t, 0.0, 1.0, 1e-12);
        assert!(x > 1.0 - 1e-9);
    }
}
