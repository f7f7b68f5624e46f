//! The events of a path between two of its steps: a vertex of one step that the other lacks
//! (cut off on the way, or made on the way) where its three rows meet a fourth, located by
//! Brent's method on the fourth row's slack and kept when the four rows' twists are
//! positively dependent there.

use super::{Found, RowName, Slice, Walker, condition_of, joints_at, order};
use crate::analysis::gap::hull;
use crate::analysis::gap::rows::{JointRowAt, RowKind, row_at};
use crate::analysis::gap::walk::Vertex;
use crate::analysis::roots;
use crate::analysis::statics::ArchGeometry;
use std::collections::BTreeMap;

impl<G: ArchGeometry> Walker<'_, G> {
    /// The named rows at p, scaled to unit length.
    fn rows_at(&self, p: f64, names: &[RowName]) -> Option<Vec<JointRowAt>> {
        let (geom, phi) = (self.at)(p)?;
        let joints = joints_at(&geom, self.thetas)?;
        names
            .iter()
            .map(|(j, c)| row_at(&geom, *joints.get(*j)?, phi, *c))
            .collect()
    }

    /// The vertex of three named rows at p and the slack b − a·y of a fourth.
    fn slack(&self, p: f64, three: &[RowName; 3], fourth: RowName) -> Option<([f64; 3], f64)> {
        let r = self.rows_at(p, &[three[0], three[1], three[2], fourth])?;
        let mut m = nalgebra::Matrix3::zeros();
        let mut rhs = nalgebra::Vector3::zeros();
        for i in 0..3 {
            for c in 0..3 {
                m[(i, c)] = r[i].a[c];
            }
            rhs[i] = r[i].b - r[i].a[3] * self.lambda;
        }
        let x = m.lu().solve(&rhs)?;
        let x = [x[0], x[1], x[2]];
        let a = r[3].a;
        Some((
            x,
            r[3].b - (a[0] * x[0] + a[1] * x[1] + a[2] * x[2] + a[3] * self.lambda),
        ))
    }

    /// The complete vertex at p nearest to `near` whose mechanism the loads drive.
    fn complete_at(&self, p: f64, near: &[f64; 4]) -> Option<Found> {
        let (geom, s) = self.slice(p)?;
        let dist = |v: &Vertex| (0..3).map(|c| (v.y[c] - near[c]).abs()).fold(0.0, f64::max);
        let mut vs: Vec<(&Vec<(usize, u8)>, &Vertex)> = s.vertices.iter().collect();
        vs.sort_by(|a, b| dist(a.1).total_cmp(&dist(b.1)));
        vs.into_iter()
            .take(4)
            .filter_map(|(k, v)| self.found_at(&geom, &s, k, v))
            .find(|f| self.drives(&geom, f))
    }

    /// Where three rows of slice `s` meet, at the path's λ.
    fn meet(&self, s: &Slice, rows: &[usize]) -> Option<[f64; 4]> {
        let mut m = nalgebra::Matrix3::zeros();
        let mut rhs = nalgebra::Vector3::zeros();
        for (i, &r) in rows.iter().enumerate() {
            for c in 0..3 {
                m[(i, c)] = s.rows.a[r][c];
            }
            rhs[i] = s.rows.b[r] - s.rows.a[r][3] * self.lambda;
        }
        let x = m.lu().solve(&rhs)?;
        Some([x[0], x[1], x[2], self.lambda])
    }

    /// The first complete event between two slices: three rows of a vertex of one slice that
    /// is not a vertex of the other meet a fourth between them, and the four twists are
    /// positively dependent there. Vertices of `prev` cut off on the way and vertices of `cur`
    /// made on the way are both followed, so that two events chained within the step (a vertex
    /// made by one and cut off by the next) are both seen.
    pub(super) fn events(&self, prev: &Slice, cur: &Slice) -> Option<Found> {
        let forward = (cur.p - prev.p).signum();
        let mut candidates = self.event_candidates(prev, cur);
        candidates.extend(self.event_candidates(cur, prev));
        candidates.sort_by(|a, b| (forward * a.0).total_cmp(&(forward * b.0)));
        candidates
            .into_iter()
            .find_map(|(p_star, near)| self.complete_at(p_star, &near))
    }

    /// Where a vertex of slice `from` that is not one of `to` has its three rows meet a fourth
    /// between the two slices, with positively dependent twists: p and the vertex at `from`.
    fn event_candidates(&self, from: &Slice, to: &Slice) -> Vec<(f64, [f64; 4])> {
        let mut out = Vec::new();
        let tol_p = self.settings.tol_path * (1.0 + from.p.abs());
        // The rows of `to` by name, with their twists there.
        let mut by_name: BTreeMap<(usize, u8), usize> = BTreeMap::new();
        for (r, kind) in to.rows.kind.iter().enumerate() {
            if let RowKind::Joint {
                joint, condition, ..
            } = kind
            {
                by_name.insert((*joint, order(*condition)), r);
            }
        }
        let twist = |r: usize| match to.rows.kind[r] {
            RowKind::Joint { twist, .. } => twist,
            RowKind::Bound => None,
        };
        for (k, v) in &from.vertices {
            if to.vertices.contains_key(k) || k.len() < 3 {
                continue;
            }
            let Some(all) = k
                .iter()
                .map(|n| {
                    let r = *by_name.get(n)?;
                    Some((*n, r, twist(r)?))
                })
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            // Two tight rows with one twist are one plane at the path's λ (the extrados hinge
            // rows on the two sides of a point load, which acts at that point): one of them
            // stands for both.
            let mut named: Vec<((usize, u8), usize, [f64; 3])> = Vec::with_capacity(all.len());
            for n in all {
                let tol = self.settings.tol_same_twist;
                if !named.iter().any(|m| same_twist(&m.2, &n.2, tol)) {
                    named.push(n);
                }
            }
            if named.len() != 3 {
                continue;
            }
            let key_rows: Vec<usize> = named.iter().map(|n| n.1).collect();
            let key_twists: Vec<[f64; 3]> = named.iter().map(|n| n.2).collect();
            let three: [RowName; 3] =
                std::array::from_fn(|i| (named[i].0.0, condition_of(named[i].0.1)));
            let Some(y_end) = self.meet(to, &key_rows) else {
                continue;
            };
            let scale = 1.0 + y_end.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
            let tol = self.settings.tol_tight * scale;
            for (r, a) in to.rows.a.iter().enumerate() {
                let RowKind::Joint {
                    joint,
                    condition,
                    twist: Some(t),
                    ..
                } = to.rows.kind[r]
                else {
                    continue;
                };
                let name = (joint, condition);
                if three.contains(&name) {
                    continue;
                }
                let s_end = to.rows.b[r] - (0..4).map(|c| a[c] * y_end[c]).sum::<f64>();
                if s_end >= -tol {
                    continue;
                }
                // The four twists must be positively dependent where the rows meet; they move
                // with p on a thickness path, so a loose test at the other slice first.
                let four = [key_twists[0], key_twists[1], key_twists[2], t];
                if hull::farther_than(&four, self.settings.tol_event)
                    || hull::min_norm_point(&four, self.settings.tol_hull)
                        .is_none_or(|m| m.norm() > self.settings.tol_event)
                {
                    continue;
                }
                let slack = |p: f64| self.slack(p, &three, name).map_or(f64::NAN, |v| v.1);
                if !(slack(from.p) >= -tol) {
                    continue;
                }
                if let Some(p_star) = roots::brent(slack, from.p, to.p, tol_p) {
                    out.push((p_star, v.y));
                }
            }
        }
        out
    }
}

/// True when two unit twists are one: no component differs by more than `tol`.
fn same_twist(a: &[f64; 3], b: &[f64; 3], tol: f64) -> bool {
    (0..3).all(|c| (a[c] - b[c]).abs() <= tol)
}
