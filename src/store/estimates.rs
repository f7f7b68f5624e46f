//! estimates.parquet: what the samples of a sampling study say, one value per row in long
//! form (a probability with its interval, a point of a fragility curve, a quantile, a Sobol
//! index, an error of the convergence study, a grid value of the point), so that one schema
//! holds every question's answers.

use super::{TableBuilder, f64_column, str_column, u64_column};
use anyhow::{Context, Result};
use polars::prelude::DataFrame;
use std::path::Path;

/// One row of estimates.parquet.
#[derive(Debug, Clone, PartialEq)]
pub struct EstimateRow {
    /// Load-case name.
    pub load_case: String,
    /// Index of the grid point among the load case's points (0 without grid axes).
    pub point: u64,
    /// What the row holds: `probability`, `exact_probability`, `mechanism`, `samples`,
    /// `errors`, `fragility_cdf`, `quantile`, `mean`, `sd`, `first_order`, `total`,
    /// `convergence`, `grid`.
    pub quantity: String,
    /// The mechanism, quantile level, uncertain parameter, sampling method or grid axis the
    /// row is about (empty when none).
    pub parameter: String,
    /// The abscissa of a curve point (λ of a fragility curve, n of a convergence point).
    pub x: Option<f64>,
    /// The value.
    pub value: f64,
    /// Lower end of its 95 % interval.
    pub lo: Option<f64>,
    /// Upper end of its 95 % interval.
    pub hi: Option<f64>,
    /// Why a value is missing or how it was obtained (empty when nothing needs saying).
    pub note: String,
}

impl EstimateRow {
    /// A row without abscissa, interval or note.
    pub fn value(load_case: &str, point: u64, quantity: &str, parameter: &str, value: f64) -> Self {
        EstimateRow {
            load_case: load_case.to_string(),
            point,
            quantity: quantity.to_string(),
            parameter: parameter.to_string(),
            x: None,
            value,
            lo: None,
            hi: None,
            note: String::new(),
        }
    }

    /// The same row with an interval.
    pub fn with_interval(mut self, lo: f64, hi: f64) -> Self {
        (self.lo, self.hi) = (Some(lo), Some(hi));
        self
    }

    /// The same row at abscissa x.
    pub fn at(mut self, x: f64) -> Self {
        self.x = Some(x);
        self
    }

    /// The same row with a note.
    pub fn noted(mut self, note: impl Into<String>) -> Self {
        self.note = note.into();
        self
    }
}

/// The frame of estimates.parquet.
pub fn estimates_frame(rows: &[EstimateRow]) -> Result<DataFrame> {
    TableBuilder::new()
        .str(
            "load_case",
            rows.iter().map(|r| r.load_case.as_str()).collect(),
        )
        .u64("point", rows.iter().map(|r| r.point).collect())
        .str(
            "quantity",
            rows.iter().map(|r| r.quantity.as_str()).collect(),
        )
        .str(
            "parameter",
            rows.iter().map(|r| r.parameter.as_str()).collect(),
        )
        .opt_f64("x", rows.iter().map(|r| r.x).collect())
        .f64("value", rows.iter().map(|r| r.value).collect())
        .opt_f64("lo", rows.iter().map(|r| r.lo).collect())
        .opt_f64("hi", rows.iter().map(|r| r.hi).collect())
        .str("note", rows.iter().map(|r| r.note.as_str()).collect())
        .finish()
}

/// Reads estimates.parquet.
pub fn read_estimates(path: &Path) -> Result<Vec<EstimateRow>> {
    let df = super::read_parquet(path)?;
    rows_of(&df).with_context(|| format!("in {}", path.display()))
}

fn rows_of(df: &DataFrame) -> Result<Vec<EstimateRow>> {
    let s = |name: &str| str_column(df, name);
    let (lc, quantity, parameter, note) =
        (s("load_case")?, s("quantity")?, s("parameter")?, s("note")?);
    let point = u64_column(df, "point")?;
    let (x, value, lo, hi) = (
        f64_column(df, "x")?,
        f64_column(df, "value")?,
        f64_column(df, "lo")?,
        f64_column(df, "hi")?,
    );
    Ok((0..df.height())
        .map(|i| EstimateRow {
            load_case: lc[i].clone().unwrap_or_default(),
            point: point[i],
            quantity: quantity[i].clone().unwrap_or_default(),
            parameter: parameter[i].clone().unwrap_or_default(),
            x: x[i],
            value: value[i].unwrap_or(f64::NAN),
            lo: lo[i],
            hi: hi[i],
            note: note[i].clone().unwrap_or_default(),
        })
        .collect())
}
