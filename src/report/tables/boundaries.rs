//! The located boundaries grouped by the regimes on their sides, and the collapse curve
//! condensed to about two dozen points.

use crate::report::data::RunData;
use crate::report::format::{self, num, value};
use crate::store::BoundaryRow;
use serde::Serialize;
use std::collections::BTreeMap;

/// A group of boundary points (same regimes on both sides, same search axis).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct BoundaryGroup {
    /// `low → high`.
    pub regimes: String,
    /// `K` or `μ`.
    pub axis: String,
    /// `yes` if on the collapse curve.
    pub collapse: String,
    /// Mechanism or `—`.
    pub mechanism: String,
    /// Number of points.
    pub points: String,
    /// μ range.
    pub mu_range: String,
    /// K range.
    pub k_range: String,
}

/// A point of the collapse curve in the condensed table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CollapsePoint {
    /// μ.
    pub mu: String,
    /// K.
    pub k: String,
    /// t/R_c.
    pub t_over_r: String,
    /// Mechanism.
    pub mechanism: String,
    /// H/W_half.
    pub thrust: String,
    /// Hinges.
    pub hinges: String,
    /// Sliding joints.
    pub sliding: String,
}

/// The boundary tables of a run (all empty without boundaries.parquet).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BoundaryTables {
    /// Boundary points grouped.
    pub groups: Vec<BoundaryGroup>,
    /// The collapse curve, condensed.
    pub collapse_points: Vec<CollapsePoint>,
    /// How the collapse curve was condensed.
    pub collapse_note: String,
}

/// Boundary points grouped, and the collapse curve condensed to about 24 points.
pub fn boundary_tables(data: &RunData) -> BoundaryTables {
    let Some(rows) = &data.boundaries else {
        return BoundaryTables::default();
    };
    let (collapse_points, collapse_note) = collapse_points(rows);
    BoundaryTables {
        groups: groups(rows),
        collapse_points,
        collapse_note,
    }
}

/// The boundary points grouped by collapse curve, mechanism, regimes and search axis, with
/// the μ and K ranges of each group.
fn groups(rows: &[BoundaryRow]) -> Vec<BoundaryGroup> {
    let mut groups: BTreeMap<(bool, String, String, String, String), Vec<&BoundaryRow>> =
        BTreeMap::new();
    for b in rows {
        groups
            .entry((
                !b.on_collapse_curve,
                b.mechanism.clone().unwrap_or_default(),
                b.regime_low.clone(),
                b.regime_high.clone(),
                b.axis.clone(),
            ))
            .or_default()
            .push(b);
    }
    let range = |v: Vec<f64>| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if (hi - lo).abs() <= 1e-12 * (1.0 + hi.abs()) {
            value(lo)
        } else {
            format!("{} – {}", format::short(lo), format::short(hi))
        }
    };
    groups
        .into_iter()
        .map(|((off, mech, lo, hi, axis), v)| BoundaryGroup {
            regimes: format!("{lo} → {hi}"),
            axis: if axis == "k" { "K".into() } else { "μ".into() },
            collapse: if off { "no".into() } else { "yes".into() },
            mechanism: if mech.is_empty() { "—".into() } else { mech },
            points: v.len().to_string(),
            mu_range: range(v.iter().map(|b| b.mu).collect()),
            k_range: range(v.iter().map(|b| b.k).collect()),
        })
        .collect()
}

/// The collapse curve in order along it, condensed to about 24 points when it has more
/// than 30 (the ends of each mechanism's segment are kept), with a note saying so.
fn collapse_points(rows: &[BoundaryRow]) -> (Vec<CollapsePoint>, String) {
    let mut curve: Vec<&BoundaryRow> = rows.iter().filter(|b| b.on_collapse_curve).collect();
    let (mu0, mu1, k0, k1) = curve.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), r| (a.min(r.mu), b.max(r.mu), c.min(r.k), d.max(r.k)),
    );
    let key = |r: &BoundaryRow| r.k / (k1 - k0).max(1e-12) - r.mu / (mu1 - mu0).max(1e-12);
    curve.sort_by(|a, b| key(a).total_cmp(&key(b)));
    let n = curve.len();
    let keep: Vec<usize> = if n <= 30 {
        (0..n).collect()
    } else {
        let mut k: Vec<usize> = (0..24).map(|i| i * (n - 1) / 23).collect();
        // Segment ends (mechanism changes) are kept too.
        for i in 1..n {
            if curve[i].mechanism != curve[i - 1].mechanism {
                k.push(i - 1);
                k.push(i);
            }
        }
        k.sort_unstable();
        k.dedup();
        k
    };
    let points = keep
        .iter()
        .map(|&i| {
            let b = curve[i];
            CollapsePoint {
                mu: value(b.mu),
                k: value(b.k),
                t_over_r: value(b.t_over_r),
                mechanism: b.mechanism.clone().unwrap_or_else(|| "—".into()),
                thrust: num(b.thrust_over_half_weight, format::VALUE_DECIMALS),
                hinges: format::joints(&b.joints.hinge_angles_deg, &b.joints.hinge_faces),
                sliding: format::joints(&b.joints.sliding_angles_deg, &b.joints.sliding_senses),
            }
        })
        .collect();
    let note = if keep.len() < n {
        format!(
            "{} of the {n} collapse-curve points, in order along the curve (every row is in boundaries.parquet).",
            keep.len()
        )
    } else {
        format!("All {n} collapse-curve points, in order along the curve.")
    };
    (points, note)
}
