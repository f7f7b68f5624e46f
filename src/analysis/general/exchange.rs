//! The exchange (cutting-plane) method for a continuum: solve at a few joints, find the
//! most violated joint of each condition by sampling and a 1-D maximisation, add it, repeat.

use super::problem::{Problem, Solved};
use super::rows::{JointRow, LinearRows};
use super::samples::Candidate;
use super::{ActiveRow, Outcome, Settings};
use crate::analysis::lp;
use crate::analysis::statics::ArchGeometry;

impl<G: ArchGeometry + ?Sized> Problem<'_, G> {
    /// The exchange method for a continuum: solve, scan for violated joints, add them, repeat.
    ///
    /// After the first step the programme is solved on a working set (the previous step's
    /// basic rows, the rows just added and the auxiliary rows, with every row its answer
    /// violates): the same optimum as the whole programme, from a programme of a dozen rows.
    /// A step that finds only rows already present violated is solved again on all rows.
    pub(super) fn solve_continuum(&self, settings: &Settings) -> Solved {
        let samples = self.samples(settings);
        let mut rows = samples
            .initial_rows(settings, self.set, self.objective)
            .fixing_crown_shear(self.half);
        let mut iterations = 0;
        let mut start: Option<Vec<usize>> = None;
        loop {
            iterations += 1;
            let sol = match &start {
                None => self.lp(&rows, settings),
                Some(set) => self.lp_on(&rows, set, settings),
            };
            let (z, homogeneous) = match sol.status {
                lp::Status::Optimal => (sol.x, false),
                lp::Status::Unbounded => (sol.ray, true),
                lp::Status::Infeasible => {
                    return Solved::without_state(Outcome::Infeasible, sol.x, rows, iterations);
                }
                s => return Solved::without_state(Outcome::Failed(s), sol.x, rows, iterations),
            };
            let candidates = self.scan(&samples, &z, homogeneous, settings);
            let step = Step {
                z,
                homogeneous,
                max_violation: candidates
                    .iter()
                    .fold(f64::NEG_INFINITY, |m, c| m.max(c.violation)),
                candidates,
                iterations,
            };
            let tol = settings.tol_exchange * Self::scale(&z);
            if step.max_violation <= tol {
                return self.finish(step, step_outcome(homogeneous), rows, settings);
            }
            if iterations >= settings.max_exchange_iterations {
                return self.finish(step, Outcome::NotConverged, rows, settings);
            }
            let before = rows.joints.len();
            if self.add_violated(&mut rows, &step.candidates, tol) == 0 {
                if start.take().is_some() {
                    // Every violated joint is a row already, and the working set's optimum
                    // leaves it violated within the solver's tolerance: settle it on all
                    // the rows at once before calling the exchange stalled.
                    continue;
                }
                let outcome = stalled_outcome(&step, settings);
                return self.finish(step, outcome, rows, settings);
            }
            start = Some(next_working_set(&sol.basis, before, &rows));
        }
    }

    /// Adds a row for every candidate violated by more than `tol` that is not a row yet;
    /// returns how many were added.
    fn add_violated(&self, rows: &mut LinearRows, candidates: &[Candidate], tol: f64) -> usize {
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
        added
    }

    /// The answer of the last exchange step: the candidates within the active tolerance of
    /// the largest violation are the active rows (none unless solved).
    fn finish(
        &self,
        step: Step,
        outcome: Outcome,
        rows: LinearRows,
        settings: &Settings,
    ) -> Solved {
        let vmax = step.max_violation;
        let atol = self.active_tol(&step.z, settings);
        let mut pairs: Vec<(ActiveRow, JointRow)> = if outcome == Outcome::Solved {
            step.candidates
                .iter()
                .filter(|c| c.violation >= vmax.max(0.0) - atol)
                .map(|c| {
                    (
                        ActiveRow {
                            angle_deg: self.geom.angle_deg(c.theta),
                            theta: c.theta,
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
        let (active, active_joints): (Vec<ActiveRow>, Vec<JointRow>) = pairs.into_iter().unzip();
        Solved {
            outcome,
            z: step.z,
            rows,
            max_violation: vmax,
            active,
            active_joints,
            iterations: step.iterations,
        }
    }
}

/// One exchange step: the programme's solution and the most violated joints there.
struct Step {
    /// z = (x, t), or the ray when the programme is unbounded.
    z: [f64; 4],
    /// True when `z` is a ray.
    homogeneous: bool,
    /// The refined most violated joints.
    candidates: Vec<Candidate>,
    /// The largest of their violations.
    max_violation: f64,
    /// Exchange steps so far.
    iterations: usize,
}

/// The rows to start the next step's programme from: the basic rows of this step (the
/// auxiliary rows after the `before` joint rows moved down by the rows added since), the
/// rows added and the auxiliary rows.
fn next_working_set<const D: usize>(
    basis: &[Option<usize>; D],
    before: usize,
    rows: &LinearRows,
) -> Vec<usize> {
    let joints = rows.joints.len();
    let added = joints - before;
    let mut set: Vec<usize> = basis
        .iter()
        .flatten()
        .map(|&k| if k >= before { k + added } else { k })
        .chain(before..rows.a.len())
        .collect();
    set.sort_unstable();
    set.dedup();
    set
}

/// Solved, or unbounded when the step's point is a ray.
fn step_outcome(homogeneous: bool) -> Outcome {
    if homogeneous {
        Outcome::Unbounded
    } else {
        Outcome::Solved
    }
}

/// The outcome when every violated joint is already a row: the residual is what the
/// programme solver accepted (its tolerance also scales with t), not a missing joint.
fn stalled_outcome(step: &Step, settings: &Settings) -> Outcome {
    let lp_tol = settings.lp_residual_factor
        * settings.lp.tol_feasibility
        * (1.0 + step.z.iter().fold(0.0, |m: f64, v| m.max(v.abs())));
    if step.max_violation <= lp_tol {
        step_outcome(step.homogeneous)
    } else {
        Outcome::NotConverged
    }
}
