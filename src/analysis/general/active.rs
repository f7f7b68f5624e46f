//! Active rows at a limit state: which of them name the mechanism, and the mechanism they
//! name.

use super::problem::{Problem, Solved};
use super::rows::{Objective, lp_row, norm3};
use super::working_set::maximise_on_working_set;
use super::{ActiveRow, Settings};
use crate::analysis::kinematics::ActiveJoint;
use crate::analysis::lp;
use crate::analysis::statics::{ArchGeometry, Condition};
use crate::analysis::types::{Face, Hinge, Mechanism, Sense, SlidingJoint};

impl<G: ArchGeometry + ?Sized> Problem<'_, G> {
    /// Keeps the active rows that name the mechanism: those that hold with equality in
    /// every optimal state, at joints that transmit a force.
    ///
    /// The programme's optimum may be a face rather than a point (at μ_min, say, the crown
    /// moment M₀ is free within a range): the vertex returned touches rows that other
    /// optimal states leave slack. With the fourth unknown fixed at its optimum, a row is
    /// kept iff the largest distance x can take from its plane over the optimal face is
    /// within `tol_active` (one small programme per active row, over the programme's rows
    /// and the active ones, solved on a working set that starts from the active rows). A joint without normal force (a support that lifts off) holds
    /// its rows with 0 = 0 but neither hinges nor slides: it is open, and left out.
    pub(super) fn keep_necessary(&self, s: &mut Solved, settings: &Settings) {
        let t = s.z[3];
        let scale = Self::scale(&s.z);
        let tol = self.active_tol(&s.z, settings);
        // x = z[..3] violates no row by more than the residual: relax every row by it.
        let relax = s.max_violation.max(0.0) + settings.tol_necessary_relax * scale;
        let mut a3: Vec<[f64; 3]> = Vec::with_capacity(s.rows.a.len() + s.active.len());
        let mut b3: Vec<f64> = Vec::with_capacity(a3.capacity());
        let push = |a3: &mut Vec<[f64; 3]>, b3: &mut Vec<f64>, a: [f64; 4], b: f64| {
            let n = norm3(&[a[0], a[1], a[2]]);
            if n > 0.0 {
                a3.push([a[0], a[1], a[2]]);
                b3.push(b - a[3] * t + relax * n);
            }
        };
        for (a, b) in s.rows.a.iter().zip(&s.rows.b) {
            push(&mut a3, &mut b3, *a, *b);
        }
        let active: Vec<([f64; 4], f64)> = s
            .active_joints
            .iter()
            .map(|j| lp_row(&self.row(j.theta, j.condition), self.objective))
            .collect();
        let first_active = a3.len();
        for (a, b) in &active {
            push(&mut a3, &mut b3, *a, *b);
        }
        // The optimal face is pinned by the active rows: start from them.
        let start: Vec<usize> = (first_active..a3.len()).collect();
        let lambda = match self.objective {
            Objective::Margin { lambda, .. } => lambda,
            Objective::LoadFactor => t,
        };
        let mut keep = Vec::with_capacity(active.len());
        for ((a, b), j) in active.iter().zip(&s.active_joints) {
            let n = norm3(&[a[0], a[1], a[2]]);
            let c = [-a[0] / n, -a[1] / n, -a[2] / n];
            let necessary = match maximise_on_working_set(&c, &a3, &b3, &start, &settings.lp) {
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
}

/// The sense of sliding of the crown-side part at a joint whose sliding row `condition` is
/// active. The rows are written for the part right of the joint; on the left half that part
/// is the crown side only when θ > 0, so the sense flips for θ < 0.
fn sense_of(condition: Condition, right_half: bool) -> Sense {
    if (condition == Condition::SlideOutward) == right_half {
        Sense::Outward
    } else {
        Sense::Inward
    }
}

/// The active joints of a set of active rows at their exact parameters θ, for the kinematics
/// (docs/mechanics.md §1): each row is a hinge or a sliding joint with its sense; a row
/// repeated at the same parameter is one joint. The two sides of a point load stay two
/// parameters one float apart, so that [`normalise_pattern`](crate::analysis::kinematics::normalise_pattern)
/// can tell on which side of the load a joint slides.
pub fn pattern_of_rows(active: &[ActiveRow]) -> Vec<ActiveJoint> {
    let mut joints: Vec<ActiveJoint> = Vec::with_capacity(active.len());
    for r in active {
        let j = match r.condition {
            Condition::Intrados => ActiveJoint::hinge(r.theta, Face::Intrados),
            Condition::Extrados => ActiveJoint::hinge(r.theta, Face::Extrados),
            Condition::SlideOutward | Condition::SlideInward => {
                ActiveJoint::sliding(r.theta, Some(sense_of(r.condition, r.theta >= 0.0)))
            }
        };
        if !joints.contains(&j) {
            joints.push(j);
        }
    }
    joints.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    joints
}

/// The mechanism named by a set of active rows; joints within `settings.tol_same_joint` are
/// one joint.
pub fn mechanism_of(active: &[ActiveRow], settings: &Settings) -> Option<Mechanism> {
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
                sliding.push(SlidingJoint {
                    angle_deg: r.angle_deg,
                    sense: sense_of(r.condition, r.angle_deg >= 0.0),
                });
            }
        }
    }
    // Both sides of a point load are joints at (nearly) the same angle: one joint each.
    let same = |a: f64, b: f64| (a - b).abs() <= settings.tol_same_joint * (1.0 + a.abs());
    hinges.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
    hinges.dedup_by(|a, b| a.face == b.face && same(a.angle_deg, b.angle_deg));
    sliding.sort_by(|a, b| a.angle_deg.total_cmp(&b.angle_deg));
    sliding.dedup_by(|a, b| a.sense == b.sense && same(a.angle_deg, b.angle_deg));
    Mechanism::from_parts(hinges, sliding)
}
