//! One general problem (geometry, friction, row set, objective) and its solution at a
//! finite set of joints: the discrete programme, the active rows and the solver call.

use super::rows::{JointRow, LinearRows, OBJECTIVE, Objective, norm3};
use super::working_set::maximise_on_working_set;
use super::{ActiveRow, Outcome, RowSet, Settings};
use crate::analysis::lp;
use crate::analysis::statics::{ArchGeometry, Condition, Row, joint_rows};

/// One problem: a geometry, a friction angle, a row set and an objective.
pub(super) struct Problem<'g, G: ?Sized> {
    pub(super) geom: &'g G,
    pub(super) phi: f64,
    pub(super) set: RowSet,
    pub(super) objective: Objective,
    /// True on the half of a mirror-symmetric arch ([`super::half`]): the crown shear is
    /// held at zero by two auxiliary rows.
    pub(super) half: bool,
}

/// The raw answer of a problem: programme solution, rows and residual.
pub(super) struct Solved {
    pub(super) outcome: Outcome,
    /// z = (x, t) (the ray when unbounded).
    pub(super) z: [f64; 4],
    pub(super) rows: LinearRows,
    /// Largest violation over all joints at z.
    pub(super) max_violation: f64,
    pub(super) active: Vec<ActiveRow>,
    /// The joint and condition of each active row.
    pub(super) active_joints: Vec<JointRow>,
    pub(super) iterations: usize,
}

impl Solved {
    /// The answer when the programme has no solution (infeasible or failed): no state, no
    /// active rows.
    pub(super) fn without_state(
        outcome: Outcome,
        z: [f64; 4],
        rows: LinearRows,
        iterations: usize,
    ) -> Self {
        Solved {
            outcome,
            z,
            rows,
            max_violation: f64::INFINITY,
            active: Vec::new(),
            active_joints: Vec::new(),
            iterations,
        }
    }
}

/// The answer of a programme the solver refused (malformed rows: not expected).
fn failed() -> lp::Solution<4> {
    lp::Solution {
        status: lp::Status::NumericalFailure,
        x: [0.0; 4],
        objective: 0.0,
        basis: [None; 4],
        duals: [0.0; 4],
        ray: [0.0; 4],
        max_violation: 0.0,
        iterations: 0,
    }
}

impl<G: ArchGeometry + ?Sized> Problem<'_, G> {
    pub(super) fn conditions(&self) -> impl Iterator<Item = Condition> + '_ {
        Condition::ALL.into_iter().filter(|c| self.set.includes(*c))
    }

    pub(super) fn row(&self, theta: f64, condition: Condition) -> Row {
        let rows = joint_rows(self.geom, theta, self.phi);
        match condition {
            Condition::Intrados => rows[0],
            Condition::Extrados => rows[1],
            Condition::SlideOutward => rows[2],
            Condition::SlideInward => rows[3],
        }
    }

    pub(super) fn lp(&self, rows: &LinearRows, settings: &Settings) -> lp::Solution<4> {
        let s = settings.lp.scaled_to(rows.a.len());
        match lp::maximise(&OBJECTIVE, &rows.a, &rows.b, &s) {
            Ok(sol) => sol,
            Err(_) => failed(),
        }
    }

    /// [`Problem::lp`] solved on a working set of the rows, starting from `start`: the same
    /// optimum (see [`maximise_on_working_set`]).
    pub(super) fn lp_on(
        &self,
        rows: &LinearRows,
        start: &[usize],
        settings: &Settings,
    ) -> lp::Solution<4> {
        match maximise_on_working_set(&OBJECTIVE, &rows.a, &rows.b, start, &settings.lp) {
            Ok(sol) => sol,
            Err(_) => failed(),
        }
    }

    pub(super) fn scale(z: &[f64; 4]) -> f64 {
        1.0 + z[..3].iter().fold(0.0_f64, |m, v| m.max(v.abs()))
    }

    pub(super) fn active_tol(&self, z: &[f64; 4], settings: &Settings) -> f64 {
        settings.tol_active * Self::scale(z)
    }

    pub(super) fn solve(&self, settings: &Settings) -> Solved {
        let joints = self.geom.discrete_joints();
        let mut s = match &joints {
            Some(thetas) => self.solve_discrete(thetas, settings),
            None => self.solve_continuum(settings),
        };
        // Only a limit state names a mechanism: τ ≈ 0 for a margin, any λ_max.
        let limit = match self.objective {
            Objective::Margin { .. } => {
                s.z[3].abs() <= settings.tol_limit_state * Self::scale(&s.z)
            }
            Objective::LoadFactor => true,
        };
        if s.outcome == Outcome::Solved && limit && !s.active.is_empty() {
            self.keep_necessary(&mut s, settings);
            if let Some(thetas) = &joints {
                thin_bands(&mut s, thetas, settings.band_joint_spacing);
            }
        }
        s
    }

    pub(super) fn solve_discrete(&self, thetas: &[f64], settings: &Settings) -> Solved {
        let mut rows = LinearRows::new(self.objective).fixing_crown_shear(self.half);
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
                    theta: j.theta,
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
}

/// Keeps one joint of each band of neighbouring active joints of one condition closer than
/// `spacing` (the one of least slack): the thrust line touches the boundary once there, and
/// its neighbours are active only because their slack is below the tolerance.
pub(super) fn thin_bands(s: &mut Solved, thetas: &[f64], spacing: f64) {
    // Each active row's place among the joints, found once.
    let index: Vec<Option<usize>> = (s.active.iter())
        .map(|r| thetas.iter().position(|&x| x == r.theta))
        .collect();
    let n = s.active.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        (s.active[a].condition as u8, s.active[a].theta)
            .partial_cmp(&(s.active[b].condition as u8, s.active[b].theta))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut keep = vec![true; n];
    let mut run: Vec<usize> = Vec::new();
    let close_run = |run: &mut Vec<usize>, keep: &mut Vec<bool>| {
        if let Some(&best) = run
            .iter()
            .min_by(|&&a, &&b| s.active[a].slack.total_cmp(&s.active[b].slack))
        {
            for &i in run.iter() {
                keep[i] = i == best;
            }
        }
        run.clear();
    };
    for &i in &order {
        let joined = run.last().is_some_and(|&j| {
            let (a, b) = (&s.active[j], &s.active[i]);
            a.condition == b.condition
                && (b.theta - a.theta).abs() < spacing
                && matches!((index[j], index[i]), (Some(x), Some(y)) if y == x + 1)
        });
        if !joined {
            close_run(&mut run, &mut keep);
        }
        run.push(i);
    }
    close_run(&mut run, &mut keep);
    let mut k = keep.iter();
    s.active.retain(|_| *k.next().unwrap_or(&true));
    let mut k = keep.iter();
    s.active_joints.retain(|_| *k.next().unwrap_or(&true));
}
