//! The exchange (cutting-plane) method for a continuum: solve at a few joints, find the
//! most violated joint of each condition by sampling and a 1-D maximisation, add it, repeat.

use super::problem::{Problem, Solved};
use super::rows::{JointRow, LinearRows, violation};
use super::{ActiveRow, Outcome, Settings};
use crate::analysis::lp;
use crate::analysis::roots::maximise_1d;
use crate::analysis::statics::{ArchGeometry, Condition, Row, joint_rows};

/// A joint where a row is (nearly) most violated.
#[derive(Debug, Clone, Copy)]
pub(super) struct Candidate {
    theta: f64,
    condition: Condition,
    violation: f64,
}

impl<G: ArchGeometry + ?Sized> Problem<'_, G> {
    /// The refined local maxima of the violation of each condition at z over every family
    /// of joints ([`ArchGeometry::families`]), and the violations at the isolated joints.
    pub(super) fn scan(
        &self,
        z: &[f64; 4],
        homogeneous: bool,
        settings: &Settings,
    ) -> Vec<Candidate> {
        let families = self.geom.families();
        let total: f64 = families.iter().map(|f| (f[1] - f[0]).max(0.0)).sum();
        let samples = settings.exchange_samples.max(2);
        let mut out = Vec::new();
        let mut points = self.geom.isolated_joints();
        for &[lo, hi] in &families {
            if hi > lo && total > 0.0 {
                let n = ((samples as f64 * (hi - lo) / total).ceil() as usize).max(2);
                let family = Sampling { lo, hi, n };
                self.scan_family(family, z, homogeneous, settings, &mut out);
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
    pub(super) fn scan_family(
        &self,
        family: Sampling,
        z: &[f64; 4],
        homogeneous: bool,
        settings: &Settings,
        out: &mut Vec<Candidate>,
    ) {
        let Sampling { lo, hi, n } = family;
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
                let (mut t, mut fv) = maximise_1d(
                    f,
                    a,
                    b,
                    settings.tol_joint_search * alpha.max(settings.joint_search_min_span),
                );
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

    /// The rows of the first exchange step: `exchange_initial_joints` joints spread over the
    /// families in proportion to their length (ends included), and the isolated joints.
    fn initial_rows(&self, settings: &Settings) -> LinearRows {
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
        rows
    }

    /// The exchange method for a continuum: solve, scan for violated joints, add them, repeat.
    pub(super) fn solve_continuum(&self, settings: &Settings) -> Solved {
        let mut rows = self.initial_rows(settings);
        let mut iterations = 0;
        loop {
            iterations += 1;
            let sol = self.lp(&rows, settings);
            let (z, homogeneous) = match sol.status {
                lp::Status::Optimal => (sol.x, false),
                lp::Status::Unbounded => (sol.ray, true),
                lp::Status::Infeasible => {
                    return Solved::without_state(Outcome::Infeasible, sol.x, rows, iterations);
                }
                s => return Solved::without_state(Outcome::Failed(s), sol.x, rows, iterations),
            };
            let candidates = self.scan(&z, homogeneous, settings);
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
            if self.add_violated(&mut rows, &step.candidates, tol) == 0 {
                let outcome = stalled_outcome(&step, settings);
                return self.finish(step, outcome, rows, settings);
            }
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

/// A family of joints [lo, hi] sampled at n intervals.
#[derive(Debug, Clone, Copy)]
pub(super) struct Sampling {
    /// First joint, radians.
    lo: f64,
    /// Last joint, radians.
    hi: f64,
    /// Sampling intervals.
    n: usize,
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
