//! Any Parquet table of a run, read column by column into plain Rust values, so that code
//! outside the store (e.g. `verify`) can compare tables without touching polars.

use anyhow::{Context, Result};
use polars::prelude::{AnyValue, Column, DataFrame, DataType, SerReader};
use std::path::Path;

/// The values of one column, in the form they are compared in.
#[derive(Debug, Clone, PartialEq)]
pub enum ColumnData {
    /// A floating-point column (Float16/32/64 widened to f64); `None` is null.
    Float(Vec<Option<f64>>),
    /// A list of floating-point values per row; `None` is a null list or element.
    FloatList(Vec<Option<Vec<Option<f64>>>>),
    /// Any other column (strings, integers, booleans, lists of strings, …), each value
    /// rendered as exact text: strings quoted, lists bracketed; `None` is null.
    Exact(Vec<Option<String>>),
}

impl ColumnData {
    /// Number of rows.
    pub fn len(&self) -> usize {
        match self {
            ColumnData::Float(v) => v.len(),
            ColumnData::FloatList(v) => v.len(),
            ColumnData::Exact(v) => v.len(),
        }
    }

    /// Whether the column has no rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One named column with its Parquet/polars type.
#[derive(Debug, Clone, PartialEq)]
pub struct TableColumn {
    /// Column name.
    pub name: String,
    /// The data type as polars names it (e.g. `f64`, `list[str]`).
    pub dtype: String,
    /// The values.
    pub data: ColumnData,
}

/// A whole table: its height and its columns in file order.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Number of rows.
    pub rows: usize,
    /// The columns, in file order.
    pub columns: Vec<TableColumn>,
}

impl Table {
    /// The column of this name, if any.
    pub fn column(&self, name: &str) -> Option<&TableColumn> {
        self.columns.iter().find(|c| c.name == name)
    }
}

/// Reads any Parquet file as a [`Table`].
pub fn read_table(path: &Path) -> Result<Table> {
    let df = super::read_parquet(path)?;
    table_from_frame(&df).with_context(|| format!("cannot read the columns of {}", path.display()))
}

/// Rows of a Parquet file decoded at a time by a [`TableReader`]: a block of a run's
/// results table ([`super::BLOCK_ROWS`]), whose row groups it spans.
pub const TABLE_FRAME_ROWS: usize = super::BLOCK_ROWS;

/// A Parquet file read as [`Table`]s of a few rows at a time, so that a table larger than
/// memory can be compared: it holds one decoded frame of at most [`TABLE_FRAME_ROWS`] rows
/// (only its row groups decoded) and converts the rows asked for.
pub struct TableReader {
    path: std::path::PathBuf,
    rows: usize,
    /// Rows decoded at a time.
    frame_rows: usize,
    /// The decoded frame and its first row.
    frame: Option<(usize, DataFrame)>,
    /// The most rows decoded at once.
    largest_frame: usize,
}

impl TableReader {
    /// Opens a Parquet file (its footer only), to be decoded [`TABLE_FRAME_ROWS`] rows at a
    /// time.
    pub fn open(path: &Path) -> Result<Self> {
        Self::with_frame_rows(path, TABLE_FRAME_ROWS)
    }

    /// [`TableReader::open`], decoding `frame_rows` rows at a time.
    pub fn with_frame_rows(path: &Path, frame_rows: usize) -> Result<Self> {
        Ok(TableReader {
            path: path.to_path_buf(),
            rows: super::parquet_rows(path)?,
            frame_rows: frame_rows.max(1),
            frame: None,
            largest_frame: 0,
        })
    }

    /// Rows of the file.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The most rows this reader has held decoded at once.
    pub fn largest_frame(&self) -> usize {
        self.largest_frame
    }

    /// The rows `offset .. offset + len` (clamped to the file) as a table, every column in
    /// file order; a read within one frame of the last decodes nothing.
    pub fn read(&mut self, offset: usize, len: usize) -> Result<Table> {
        let end = (offset + len).min(self.rows);
        let offset = offset.min(end);
        let held = |f: &Option<(usize, DataFrame)>| {
            f.as_ref()
                .is_some_and(|(at, df)| *at <= offset && end <= at + df.height())
        };
        if !held(&self.frame) {
            self.frame = None;
            let at = offset - offset % self.frame_rows;
            let n = self.frame_rows.min(self.rows - at).max(end - at);
            let file = std::fs::File::open(&self.path)
                .with_context(|| format!("cannot open {}", self.path.display()))?;
            let df = polars::prelude::ParquetReader::new(file)
                .with_slice(Some((at, n)))
                .finish()
                .with_context(|| format!("cannot read {} as Parquet", self.path.display()))?;
            self.largest_frame = self.largest_frame.max(df.height());
            self.frame = Some((at, df));
        }
        let Some((at, df)) = &self.frame else {
            anyhow::bail!("no rows decoded from {}", self.path.display());
        };
        table_from_frame(&df.slice((offset - at) as i64, end - offset))
            .with_context(|| format!("cannot read the columns of {}", self.path.display()))
    }
}

/// Converts a data frame to a [`Table`].
pub fn table_from_frame(df: &DataFrame) -> Result<Table> {
    let mut columns = Vec::with_capacity(df.width());
    for c in df.columns() {
        let data =
            column_data(c).with_context(|| format!("column `{}` ({})", c.name(), c.dtype()))?;
        columns.push(TableColumn {
            name: c.name().to_string(),
            dtype: c.dtype().to_string(),
            data,
        });
    }
    Ok(Table {
        rows: df.height(),
        columns,
    })
}

fn column_data(c: &Column) -> Result<ColumnData> {
    let dtype = c.dtype();
    if dtype.is_float() {
        let s = c.as_materialized_series().cast(&DataType::Float64)?;
        let ca = s.f64()?;
        return Ok(ColumnData::Float(
            (0..ca.len()).map(|i| ca.get(i)).collect(),
        ));
    }
    if let DataType::List(inner) = dtype
        && inner.is_float()
    {
        let l = c.as_materialized_series().list()?.clone();
        let mut out = Vec::with_capacity(l.len());
        for i in 0..l.len() {
            out.push(match l.get_as_series(i) {
                Some(s) => {
                    let s = s.cast(&DataType::Float64)?;
                    let ca = s.f64()?;
                    Some((0..ca.len()).map(|j| ca.get(j)).collect())
                }
                None => None,
            });
        }
        return Ok(ColumnData::FloatList(out));
    }
    let mut out = Vec::with_capacity(c.len());
    for i in 0..c.len() {
        let v = c.get(i)?;
        out.push(match v {
            AnyValue::Null => None,
            v => Some(render_exact(&v)?),
        });
    }
    Ok(ColumnData::Exact(out))
}

/// Renders a value as text that is equal exactly when the values are equal.
fn render_exact(v: &AnyValue) -> Result<String> {
    Ok(match v {
        AnyValue::Null => "null".to_string(),
        AnyValue::String(s) => format!("{s:?}"),
        AnyValue::StringOwned(s) => format!("{:?}", s.as_str()),
        // Floats inside other types (never at the top level here): shortest round-trip form.
        AnyValue::Float64(x) => format!("{x:?}"),
        AnyValue::Float32(x) => format!("{x:?}"),
        AnyValue::List(s) => {
            let mut parts = Vec::with_capacity(s.len());
            for i in 0..s.len() {
                parts.push(render_exact(&s.get(i)?)?);
            }
            format!("[{}]", parts.join(", "))
        }
        other => other.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::TableBuilder;

    #[test]
    fn columns_are_read_by_kind() {
        let df = TableBuilder::new()
            .u64("id", vec![1, 2])
            .opt_f64("x", vec![Some(1.5), None])
            .str("s", vec!["a", "b"])
            .list_f64("xs", vec![vec![1.0, 2.0], vec![]])
            .list_str("ss", vec![vec!["p", "q"], vec![]])
            .bool("b", vec![true, false])
            .finish()
            .unwrap();
        let t = table_from_frame(&df).unwrap();
        assert_eq!(t.rows, 2);
        let data = |n: &str| t.column(n).unwrap().data.clone();
        assert_eq!(
            data("id"),
            ColumnData::Exact(vec![Some("1".into()), Some("2".into())])
        );
        assert_eq!(data("x"), ColumnData::Float(vec![Some(1.5), None]));
        assert_eq!(
            data("s"),
            ColumnData::Exact(vec![Some("\"a\"".into()), Some("\"b\"".into())])
        );
        assert_eq!(
            data("xs"),
            ColumnData::FloatList(vec![Some(vec![Some(1.0), Some(2.0)]), Some(vec![])])
        );
        assert_eq!(
            data("ss"),
            ColumnData::Exact(vec![Some("[\"p\", \"q\"]".into()), Some("[]".into())])
        );
        assert_eq!(
            data("b"),
            ColumnData::Exact(vec![Some("true".into()), Some("false".into())])
        );
    }
}
