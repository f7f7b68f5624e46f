//! The search for the most violated joints of a continuum: the rows of a fixed set of
//! sampled joints, built once per solve and re-priced at every exchange step, and the
//! refinement of the local maxima of each condition's violation that may matter.

use super::problem::Problem;
use super::refine::{Tolerance, refine_end, refine_interior};
use super::rows::{JointRow, LinearRows, Objective, lp_row, norm3};
use super::{RowSet, Settings};
use crate::analysis::statics::{ArchGeometry, Condition, joint_rows};

/// A joint where a row is (nearly) most violated.
#[derive(Debug, Clone, Copy)]
pub(super) struct Candidate {
    pub(super) theta: f64,
    pub(super) condition: Condition,
    pub(super) violation: f64,
}

/// One row of a sampled joint as the programme sees it: a·z ≤ b with |(a_x, a_y, a_M)|.
#[derive(Debug, Clone, Copy)]
struct Priced {
    a: [f64; 4],
    b: f64,
    norm: f64,
}

impl Priced {
    /// The distance by which z violates the row, as [`super::rows::violation`] computes it.
    fn violation(&self, z: &[f64; 4], homogeneous: bool) -> f64 {
        let a = &self.a;
        let s = a[0] * z[0] + a[1] * z[1] + a[2] * z[2] + a[3] * z[3]
            - if homogeneous { 0.0 } else { self.b };
        if self.norm > 0.0 { s / self.norm } else { s }
    }
}

/// The four rows of a joint, in the order of [`Condition::ALL`].
type PricedJoint = [Priced; 4];

/// One family of joints sampled at n + 1 parameters, ends included.
struct Family {
    thetas: Vec<f64>,
    rows: Vec<PricedJoint>,
}

/// The sampled joints of a continuum and its isolated joints, with their rows.
pub(super) struct Samples {
    families: Vec<Family>,
    points: Vec<(f64, PricedJoint)>,
}

impl Samples {
    /// The rows of the first exchange step: `exchange_initial_joints` sampled joints spread
    /// over the families in proportion to their length (ends included), and the isolated
    /// joints.
    pub(super) fn initial_rows(
        &self,
        settings: &Settings,
        set: RowSet,
        objective: Objective,
    ) -> LinearRows {
        let n0 = settings.exchange_initial_joints.max(2);
        let length = |f: &Family| f.thetas[f.thetas.len() - 1] - f.thetas[0];
        let total: f64 = self.families.iter().map(length).sum();
        let mut rows = LinearRows::new(objective);
        let mut push = |theta: f64, joint: &PricedJoint| {
            for (p, condition) in joint.iter().zip(Condition::ALL) {
                if set.includes(condition) {
                    rows.push_lp_row(p.a, p.b, JointRow { theta, condition });
                }
            }
        };
        for f in &self.families {
            let n = f.thetas.len() - 1;
            let m = ((n0 as f64 * length(f) / total).ceil() as usize).clamp(2, n + 1);
            let mut last = None;
            for i in 0..m {
                let k = (i * n + (m - 1) / 2) / (m - 1);
                if last != Some(k) {
                    push(f.thetas[k], &f.rows[k]);
                    last = Some(k);
                }
            }
        }
        for (t, joint) in &self.points {
            push(*t, joint);
        }
        rows
    }
}

/// Where a sampled local maximum lies in its family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Place {
    /// Between two samples.
    Interior,
    /// At the first sample (the other end of the bracket is the second).
    Low,
    /// At the last sample.
    High,
}

impl<G: ArchGeometry + ?Sized> Problem<'_, G> {
    /// The rows at the joints every exchange step samples: `exchange_samples` intervals over
    /// the families in proportion to their length, and the isolated joints.
    pub(super) fn samples(&self, settings: &Settings) -> Samples {
        let families = self.geom.families();
        let total: f64 = families.iter().map(|f| (f[1] - f[0]).max(0.0)).sum();
        let samples = settings.exchange_samples.max(2);
        let mut points = self.geom.isolated_joints();
        let mut sampled = Vec::with_capacity(families.len());
        for &[lo, hi] in &families {
            if hi > lo && total > 0.0 {
                let n = ((samples as f64 * (hi - lo) / total).ceil() as usize).max(2);
                let step = (hi - lo) / n as f64;
                let thetas: Vec<f64> = (0..=n)
                    .map(|i| if i == n { hi } else { lo + step * i as f64 })
                    .collect();
                let rows = thetas.iter().map(|&t| self.priced(t)).collect();
                sampled.push(Family { thetas, rows });
            } else {
                points.push(lo);
            }
        }
        Samples {
            families: sampled,
            points: points.into_iter().map(|t| (t, self.priced(t))).collect(),
        }
    }

    fn priced(&self, theta: f64) -> PricedJoint {
        joint_rows(self.geom, theta, self.phi).map(|r| {
            let (a, b) = lp_row(&r, self.objective);
            Priced {
                a,
                b,
                norm: norm3(&r.a),
            }
        })
    }

    /// The refined local maxima of the violation of each condition at z over the sampled
    /// families, and the violations at the isolated joints.
    ///
    /// A sampled local maximum is refined (to `tol_joint_search`) unless it cannot come
    /// near a violation: when its sample lies below −`tol_refine` (relative) by more than
    /// twice the sum of its differences to its two neighbours, the largest rise a smooth
    /// violation can make between them (a parabola rises by at most an eighth of the larger
    /// difference). Such a joint is neither violated nor active, and keeps its sample.
    pub(super) fn scan(
        &self,
        samples: &Samples,
        z: &[f64; 4],
        homogeneous: bool,
        settings: &Settings,
    ) -> Vec<Candidate> {
        let mut out = Vec::new();
        let floor = -settings.tol_refine * Self::scale(z);
        let mut v = Vec::new();
        let mut maxima = Vec::new();
        for family in &samples.families {
            let n = family.thetas.len() - 1;
            for condition in self.conditions() {
                let ci = condition_index(condition);
                v.clear();
                v.extend(family.rows.iter().map(|r| r[ci].violation(z, homogeneous)));
                maxima.clear();
                maxima.extend(
                    (0..=n)
                        .filter(|&i| (i == 0 || v[i] >= v[i - 1]) && (i == n || v[i] > v[i + 1])),
                );
                maxima.sort_by(|&i, &j| v[j].total_cmp(&v[i]));
                maxima.truncate(settings.exchange_maxima.max(1));
                for &i in &maxima {
                    let place = match i {
                        0 => Place::Low,
                        i if i == n => Place::High,
                        _ => Place::Interior,
                    };
                    let (l, r) = match place {
                        Place::Interior => (i - 1, i + 1),
                        Place::Low => (1, 2.min(n)),
                        Place::High => (n - 1, n.saturating_sub(2)),
                    };
                    let rise = 2.0 * ((v[i] - v[l]).abs() + (v[i] - v[r]).abs());
                    let (theta, violation) = if v[i] + rise < floor {
                        (family.thetas[i], v[i])
                    } else {
                        let f = |t: f64| self.violation_at(t, condition, z, homogeneous);
                        let tol = Tolerance {
                            arg: settings.tol_joint_search
                                * self.geom.half_angle().max(settings.joint_search_min_span),
                            flat: settings.tol_refine_flat * Self::scale(z),
                        };
                        let th = &family.thetas;
                        match place {
                            Place::Interior => refine_interior(
                                f,
                                [(th[l], v[l]), (th[i], v[i]), (th[r], v[r])],
                                tol,
                            ),
                            Place::Low | Place::High => {
                                refine_end(f, (th[i], v[i]), (th[l], v[l]), tol)
                            }
                        }
                    };
                    out.push(Candidate {
                        theta,
                        condition,
                        violation,
                    });
                }
            }
        }
        for (t, rows) in &samples.points {
            for (ci, condition) in Condition::ALL.into_iter().enumerate() {
                if self.set.includes(condition) {
                    out.push(Candidate {
                        theta: *t,
                        condition,
                        violation: rows[ci].violation(z, homogeneous),
                    });
                }
            }
        }
        out
    }

    /// The violation of one condition at joint θ.
    fn violation_at(
        &self,
        theta: f64,
        condition: Condition,
        z: &[f64; 4],
        homogeneous: bool,
    ) -> f64 {
        super::rows::violation(&self.row(theta, condition), self.objective, z, homogeneous)
    }
}

/// The index of a condition in [`Condition::ALL`].
fn condition_index(condition: Condition) -> usize {
    match condition {
        Condition::Intrados => 0,
        Condition::Extrados => 1,
        Condition::SlideOutward => 2,
        Condition::SlideInward => 3,
    }
}
