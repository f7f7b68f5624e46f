//! The events of a path between two of its steps: a vertex of the earlier step cut off
//! before the later one where its three rows meet a fourth, located by Brent's method on the
//! fourth row's slack and kept when the four rows' twists are positively dependent there.

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

    /// The first complete event between two slices: a vertex of `prev` cut off before `cur`
    /// where its three rows meet a fourth whose twists with theirs are positively dependent.
    pub(super) fn events(&self, prev: &Slice, cur: &Slice) -> Option<Found> {
        let mut found: Option<Found> = None;
        let forward = (cur.p - prev.p).signum();
        let tol_p = self.settings.tol_path * (1.0 + prev.p.abs());
        // The rows of the later slice by name, with their twists there.
        let mut by_name: BTreeMap<(usize, u8), usize> = BTreeMap::new();
        for (r, kind) in cur.rows.kind.iter().enumerate() {
            if let RowKind::Joint {
                joint, condition, ..
            } = kind
            {
                by_name.insert((*joint, order(*condition)), r);
            }
        }
        let twist = |r: usize| match cur.rows.kind[r] {
            RowKind::Joint { twist, .. } => twist,
            RowKind::Bound => None,
        };
        for (k, v) in &prev.vertices {
            if cur.vertices.contains_key(k) || k.len() != 3 {
                continue;
            }
            let Some(key_rows) = k
                .iter()
                .map(|n| by_name.get(n).copied())
                .collect::<Option<Vec<usize>>>()
            else {
                continue;
            };
            let Some(key_twists) = key_rows
                .iter()
                .map(|&r| twist(r))
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let three: [RowName; 3] = std::array::from_fn(|i| (k[i].0, condition_of(k[i].1)));
            let Some(y_end) = self.meet(cur, &key_rows) else {
                continue;
            };
            let scale = 1.0 + y_end.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
            let tol = self.settings.tol_tight * scale;
            for (r, a) in cur.rows.a.iter().enumerate() {
                let RowKind::Joint {
                    joint,
                    condition,
                    twist: Some(t),
                    ..
                } = cur.rows.kind[r]
                else {
                    continue;
                };
                let name = (joint, condition);
                if three.contains(&name) {
                    continue;
                }
                let s_end = cur.rows.b[r] - (0..4).map(|c| a[c] * y_end[c]).sum::<f64>();
                if s_end >= -tol {
                    continue;
                }
                // The four twists must be positively dependent where the rows meet; they move
                // with p on a thickness path, so a loose test at the later step first.
                let four = [key_twists[0], key_twists[1], key_twists[2], t];
                if hull::farther_than(&four, self.settings.tol_event)
                    || hull::min_norm_point(&four, self.settings.tol_hull)
                        .is_none_or(|m| m.norm() > self.settings.tol_event)
                {
                    continue;
                }
                let slack = |p: f64| self.slack(p, &three, name).map_or(f64::NAN, |v| v.1);
                if !(slack(prev.p) >= -tol) {
                    continue;
                }
                let Some(p_star) = roots::brent(slack, prev.p, cur.p, tol_p) else {
                    continue;
                };
                if found
                    .as_ref()
                    .is_some_and(|f| forward * (p_star - f.p) >= 0.0)
                {
                    continue;
                }
                if let Some(f) = self.complete_at(p_star, &v.y) {
                    found = Some(f);
                }
            }
        }
        found
    }
}
