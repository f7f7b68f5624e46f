//! Solve-time statistics per model and find.

use crate::report::data::RunData;
use crate::report::format::{self, micros, millis};
use serde::Serialize;

/// Solve-time statistics of a group of cases.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TimingRow {
    /// Which cases (model and find).
    pub group: String,
    /// Number of cases.
    pub cases: String,
    /// Median.
    pub median: String,
    /// 90th percentile.
    pub p90: String,
    /// Largest.
    pub max: String,
    /// Sum of all solve times (CPU time spent in analyses).
    pub total: String,
}

/// Solve-time statistics per model and find, over the cases that succeeded.
pub fn timing(data: &RunData) -> Vec<TimingRow> {
    data.totals
        .solve_times
        .iter()
        .map(|((n, find), t)| TimingRow {
            group: format!(
                "{}, {find}",
                n.map_or("continuum".to_string(), |n| format!("N = {n}"))
            ),
            cases: t.len().to_string(),
            median: micros(format::quantile(t, 0.5)),
            p90: micros(format::quantile(t, 0.9)),
            max: micros(t.last().copied().unwrap_or(f64::NAN)),
            total: millis(t.iter().sum::<f64>() / 1e3),
        })
        .collect()
}
