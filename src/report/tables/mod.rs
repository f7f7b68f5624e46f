//! The tables of both reports, one module per table: every number already formatted, so
//! the templates only lay out text. Each builds its rows from the stored data of a run.

pub mod accuracy;
pub mod boundaries;
pub mod convergence;
pub mod export;
pub mod figures;
pub mod key_results;
pub mod mechanisms;
pub mod notes;
pub mod provenance;
pub mod study;
pub mod timing;
pub mod uncertainty;
pub mod values;

use serde::Serialize;

/// A label and a value.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Item {
    /// Label.
    pub label: String,
    /// Value (formatted).
    pub value: String,
}

fn item(label: impl Into<String>, value: impl Into<String>) -> Item {
    Item {
        label: label.into(),
        value: value.into(),
    }
}
