//! The accuracy of each discrete model against the continuum.

use crate::report::charts;
use crate::report::data::RunData;
use crate::report::format::micros;
use serde::Serialize;

/// A row of the accuracy table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ErrorRow {
    /// Quantity.
    pub quantity: String,
    /// Voussoir count.
    pub voussoirs: String,
    /// Cases compared.
    pub cases: String,
    /// Largest absolute error.
    pub max_abs_error: String,
    /// Largest relative error.
    pub max_rel_error: String,
    /// Median solve time.
    pub median_time: String,
    /// Median solve time of the continuum.
    pub continuum_time: String,
}

/// The accuracy rows, one per quantity and voussoir count (empty without references).
pub fn errors(data: &RunData) -> Vec<ErrorRow> {
    charts::accuracy_rows(data)
        .into_iter()
        .map(|r| ErrorRow {
            quantity: charts::quantity_label(&r.quantity).to_string(),
            voussoirs: r.voussoirs.to_string(),
            cases: r.cases.to_string(),
            max_abs_error: format!("{:.3e}", r.max_abs_error),
            max_rel_error: format!("{:.3e}", r.max_rel_error),
            median_time: micros(r.median_time_us),
            continuum_time: micros(r.continuum_median_time_us),
        })
        .collect()
}
