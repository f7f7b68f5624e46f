//! The convergence of each quantity to its continuum value, when each voussoir count is one
//! case: value, error and time per model, with the observed order of convergence.

use crate::report::charts::{self, AccuracyRow};
use crate::report::data::RunData;
use crate::report::format::{self, micros};
use serde::Serialize;
use std::collections::BTreeMap;

/// One model of a convergence table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ConvergenceRow {
    /// Voussoir count, or `continuum`.
    pub voussoirs: String,
    /// The value.
    pub value: String,
    /// |value − continuum value| (`0` for the continuum).
    pub abs_error: String,
    /// Solve time of the case.
    pub time: String,
}

/// The convergence of one quantity to its continuum value.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ConvergenceTable {
    /// Quantity, as in the paper.
    pub quantity: String,
    /// The results column it comes from.
    pub column: String,
    /// One row per model, by N, then the continuum.
    pub rows: Vec<ConvergenceRow>,
    /// The observed order of convergence and the N range of its fit, or why there is none.
    pub order: String,
    /// Whether the error falls monotonically with N, and where it does not.
    pub monotone: String,
}

/// Convergence tables, when the study varies only the voussoir count (one case per N).
pub fn convergence(data: &RunData) -> Vec<ConvergenceTable> {
    let rows = charts::accuracy_rows(data);
    if rows.is_empty() || rows.iter().any(|r| r.cases != 1) {
        return Vec::new();
    }
    let orders = charts::orders(&rows);
    let mut by_q: BTreeMap<(usize, String), Vec<&AccuracyRow>> = BTreeMap::new();
    for r in &rows {
        by_q.entry((charts::quantity_rank(&r.quantity), r.quantity.clone()))
            .or_default()
            .push(r);
    }
    by_q.into_iter()
        .map(|((_, q), mut rs)| {
            rs.sort_by_key(|r| r.voussoirs);
            let mut out: Vec<ConvergenceRow> = rs
                .iter()
                .map(|r| ConvergenceRow {
                    voussoirs: r.voussoirs.to_string(),
                    value: format::value(r.value),
                    abs_error: format!("{:.3e}", r.max_abs_error),
                    time: micros(r.median_time_us),
                })
                .collect();
            if let Some(last) = rs.last() {
                out.push(ConvergenceRow {
                    voussoirs: "continuum".into(),
                    value: format::value(last.continuum_value),
                    abs_error: "0".into(),
                    time: micros(last.continuum_median_time_us),
                });
            }
            let o = orders.get(&q).and_then(Option::as_ref);
            let order = o.map_or(
                "not available: fewer than three non-zero errors".to_string(),
                |o| {
                    format!(
                        "{:.2} (least-squares slope of log|error| against log N over the {} largest counts, N = {} to {})",
                        o.order, o.points, o.n_from, o.n_to
                    )
                },
            );
            let monotone = match o {
                Some(o) if !o.rises_at.is_empty() => format!(
                    "not monotone: the error grows from the previous count at N = {}",
                    o.rises_at
                        .iter()
                        .map(u32::to_string)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                Some(_) => "the error falls monotonically with N".into(),
                None => String::new(),
            };
            ConvergenceTable {
                quantity: charts::quantity_label(&q).to_string(),
                column: q,
                rows: out,
                order,
                monotone,
            }
        })
        .collect()
}
