//! The skip of a friction path over the steps where nothing can change: above the steepest
//! resultant of a polytope's vertices no Coulomb row is tight, so smaller μ leave it as it is.

use super::{RowKind, Slice, Walker};
use crate::analysis::statics::{ArchGeometry, Condition};

impl<G: ArchGeometry> Walker<'_, G> {
    /// The index of the last step of a friction path (steps `start` to `end` in `n`) whose
    /// polytope is still `cur`'s: above the steepest resultant of `cur`'s vertices, no Coulomb
    /// row can be tight, so smaller μ leave the polytope as it is and no complete solution
    /// appears. Resultants are taken on the joints walked, as the walk takes them.
    pub(super) fn skip_to(&self, cur: &(G, Slice), start: f64, end: f64, n: usize) -> usize {
        let (geom, s) = cur;
        if s.vertices.is_empty() {
            // Nothing stands, or the programme failed: nothing to go on from.
            return 0;
        }
        // Each slip row once: its sense, the joint's directions and the force the loads put
        // on it at the path's λ (every vertex of a slice has that λ).
        let slips: Vec<_> = s
            .rows
            .kind
            .iter()
            .filter_map(|kind| {
                let RowKind::Joint {
                    joint, condition, ..
                } = *kind
                else {
                    return None;
                };
                let sign = match condition {
                    Condition::SlideOutward => 1.0,
                    Condition::SlideInward => -1.0,
                    Condition::Intrados | Condition::Extrados => return None,
                };
                let theta = s.rows.thetas[joint];
                let c = geom
                    .dead_load(theta)
                    .plus(geom.live_load(theta).scale(self.lambda));
                let j = geom.joint(theta);
                Some((sign, j.along(), j.normal(), [c.fx, c.fy]))
            })
            .collect();
        let mut steepest = f64::NEG_INFINITY;
        for v in s.vertices.values() {
            let tol =
                self.settings.tol_tight * (1.0 + v.y.iter().fold(0.0_f64, |m, c| m.max(c.abs())));
            for (sign, tau, nu, c) in &slips {
                let force = [v.y[0] + c[0], v.y[1] + c[1]];
                let t = sign * (tau[0] * force[0] + tau[1] * force[1]);
                let normal = nu[0] * force[0] + nu[1] * force[1];
                if normal <= tol {
                    // A joint that carries (almost) no normal force slides at any μ.
                    return 0;
                }
                steepest = steepest.max((t / normal).atan());
            }
        }
        let floor = steepest + self.settings.friction_skip_margin;
        if !(floor < start) || end >= start {
            return 0;
        }
        // p_i = start + (end − start)·i/n decreases with i; the last i with p_i ≥ floor.
        let last = ((start - floor) / (start - end) * n as f64).floor();
        (last.max(0.0) as usize).min(n - 1)
    }
}
