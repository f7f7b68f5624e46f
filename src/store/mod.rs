//! The store: the only user of polars. Parquet schemas of the run's tables, written
//! atomically (a temporary file renamed into place) and read back.

mod boundaries;
mod cases;
pub mod compare;
mod estimates;
mod figures;
mod results;
mod rows;
mod schema;
mod table;

pub use boundaries::{bifurcations_frame, boundaries_frame};
pub use cases::{
    read_case_ids, read_case_results, read_case_results_rows, read_foreign_case_results_rows,
};
pub use estimates::{EstimateRow, estimates_frame, read_estimates};
pub use figures::{
    BifurcationGroup, CurvePoint, LoadFactorCase, MechanismRow, ReferenceRow, RowArch, StateRow,
    bifurcation_groups_of_frame, curves_frame, mechanisms_frame, read_bifurcation_groups,
    read_curves, read_load_factor_cases, read_load_factor_cases_in_blocks, read_mechanisms,
    read_reference, read_row_arches, read_states, reference_frame, states_frame,
};
pub use results::{BLOCK_ROWS, filled_by, results_frame, scenes_frame, state_results_frame};
pub use rows::{
    BifurcationRow, BoundaryRow, JointLists, ResultRow, append_results_in_blocks,
    bifurcations_of_frame, boundaries_of_frame, extend_results_of_frame, read_bifurcations,
    read_boundaries, read_results, read_results_in_blocks, read_results_rows, results_of_frame,
};
pub use schema::column_doc;
pub use table::{
    ColumnData, TABLE_FRAME_ROWS, Table, TableColumn, TableReader, read_table, table_from_frame,
};

use anyhow::Context as _;
use anyhow::Result;
use polars::prelude::{
    AnyValue, Column, DataFrame, DataType, Float64Type, IntoSeries, KeyValueMetadata,
    ListBuilderTrait, ListPrimitiveChunkedBuilder, ListStringChunkedBuilder, ParquetCompression,
    ParquetReader, ParquetWriter, Scalar, SerReader,
};
use std::fs::File;
use std::path::Path;

/// Builds named columns of a table.
#[derive(Default)]
pub struct TableBuilder {
    columns: Vec<Column>,
}

impl TableBuilder {
    /// An empty table.
    pub fn new() -> Self {
        TableBuilder::default()
    }

    /// A UInt64 column.
    pub fn u64(mut self, name: &str, v: Vec<u64>) -> Self {
        self.columns.push(Column::new(name.into(), v));
        self
    }

    /// A nullable UInt32 column.
    pub fn opt_u32(mut self, name: &str, v: Vec<Option<u32>>) -> Self {
        if v.iter().all(Option::is_none) {
            self.columns
                .push(Column::full_null(name.into(), v.len(), &DataType::UInt32));
            return self;
        }
        self.columns.push(Column::new(name.into(), v));
        self
    }

    /// A Float64 column.
    pub fn f64(mut self, name: &str, v: Vec<f64>) -> Self {
        self.columns.push(Column::new(name.into(), v));
        self
    }

    /// A nullable Float64 column.
    pub fn opt_f64(mut self, name: &str, v: Vec<Option<f64>>) -> Self {
        if v.iter().all(Option::is_none) {
            self.columns
                .push(Column::full_null(name.into(), v.len(), &DataType::Float64));
            return self;
        }
        self.columns.push(Column::new(name.into(), v));
        self
    }

    /// A String column.
    pub fn str<S: AsRef<str>>(mut self, name: &str, v: Vec<S>) -> Self {
        if let Some(first) = v.first()
            && v.iter().all(|x| x.as_ref() == first.as_ref())
        {
            // One value in every row (a load case, a status): a constant column.
            let value = AnyValue::StringOwned(first.as_ref().into());
            let scalar = Scalar::new(DataType::String, value);
            self.columns
                .push(Column::new_scalar(name.into(), scalar, v.len()));
            return self;
        }
        let v: Vec<&str> = v.iter().map(AsRef::as_ref).collect();
        self.columns.push(Column::new(name.into(), v));
        self
    }

    /// A nullable String column.
    pub fn opt_str<S: AsRef<str>>(mut self, name: &str, v: Vec<Option<S>>) -> Self {
        if v.iter().all(Option::is_none) {
            self.columns
                .push(Column::full_null(name.into(), v.len(), &DataType::String));
            return self;
        }
        let v: Vec<Option<&str>> = v.iter().map(|s| s.as_ref().map(AsRef::as_ref)).collect();
        self.columns.push(Column::new(name.into(), v));
        self
    }

    /// A Boolean column.
    pub fn bool(mut self, name: &str, v: Vec<bool>) -> Self {
        self.columns.push(Column::new(name.into(), v));
        self
    }

    /// A nullable Boolean column.
    pub fn opt_bool(mut self, name: &str, v: Vec<Option<bool>>) -> Self {
        if v.iter().all(Option::is_none) {
            self.columns
                .push(Column::full_null(name.into(), v.len(), &DataType::Boolean));
            return self;
        }
        self.columns.push(Column::new(name.into(), v));
        self
    }

    /// A List(Float64) column.
    pub fn list_f64(mut self, name: &str, v: Vec<Vec<f64>>) -> Self {
        let values: usize = v.iter().map(Vec::len).sum();
        if values == 0 {
            // No row has a list (e.g. hinges of a state grid): a null column, built at once.
            let dtype = DataType::List(Box::new(DataType::Float64));
            self.columns
                .push(Column::full_null(name.into(), v.len(), &dtype));
            return self;
        }
        let mut b = ListPrimitiveChunkedBuilder::<Float64Type>::new(
            name.into(),
            v.len(),
            values,
            DataType::Float64,
        );
        for x in &v {
            b.append_slice(x);
        }
        self.columns.push(b.finish().into_series().into());
        self
    }

    /// A List(String) column.
    pub fn list_str<S: AsRef<str>>(mut self, name: &str, v: Vec<Vec<S>>) -> Self {
        let values: usize = v.iter().map(Vec::len).sum();
        if values == 0 {
            let dtype = DataType::List(Box::new(DataType::String));
            self.columns
                .push(Column::full_null(name.into(), v.len(), &dtype));
            return self;
        }
        let mut b = ListStringChunkedBuilder::new(name.into(), v.len(), values);
        for x in &v {
            b.append_values_iter(x.iter().map(AsRef::as_ref));
        }
        self.columns.push(b.finish().into_series().into());
        self
    }

    /// The data frame.
    pub fn finish(self) -> Result<DataFrame> {
        Ok(DataFrame::new_infer_height(self.columns)?)
    }
}

/// A file that remembers the first error of a write: the Parquet writer reports a failed
/// write as its own error ("Invalid thrift: transport error"), which hides the cause (a full
/// disk); [`WriteErrors::cause`] gives it back.
pub struct RecordingFile {
    file: File,
    first_error: std::sync::Arc<std::sync::Mutex<Option<std::io::Error>>>,
}

/// The first write error of a [`RecordingFile`], read after the writer has failed.
#[derive(Clone)]
pub struct WriteErrors(std::sync::Arc<std::sync::Mutex<Option<std::io::Error>>>);

impl WriteErrors {
    /// `err` with the write error that caused it as its context (the cause named first:
    /// "No space left on device"), or `err` as it is when no write failed.
    fn cause(&self, err: anyhow::Error, path: &Path) -> anyhow::Error {
        let recorded = self.0.lock().ok().and_then(|mut e| e.take());
        match recorded {
            Some(io) => anyhow::Error::new(io).context(format!("cannot write {}", path.display())),
            None => err.context(format!("cannot write {}", path.display())),
        }
    }
}

impl RecordingFile {
    fn create(path: &Path) -> Result<(Self, WriteErrors)> {
        let file =
            File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
        let first_error = std::sync::Arc::new(std::sync::Mutex::new(None));
        let errors = WriteErrors(first_error.clone());
        Ok((RecordingFile { file, first_error }, errors))
    }

    fn record<T>(&self, r: std::io::Result<T>) -> std::io::Result<T> {
        if let Err(e) = &r
            && let Ok(mut slot) = self.first_error.lock()
            && slot.is_none()
        {
            *slot = Some(std::io::Error::new(e.kind(), e.to_string()));
        }
        r
    }
}

impl std::io::Write for RecordingFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let r = self.file.write(buf);
        self.record(r)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let r = self.file.flush();
        self.record(r)
    }
}

/// Writes a data frame as Parquet, atomically: a temporary file in the same directory is
/// renamed into place once complete.
pub fn write_parquet(df: &mut DataFrame, path: &Path) -> Result<()> {
    let tmp = crate::output::temp_sibling(path);
    crate::output::register_pending(&tmp);
    let result = (|| -> Result<()> {
        let (file, errors) = RecordingFile::create(&tmp)?;
        let metadata = KeyValueMetadata::Static(vec![schema::stored_schema(df)]);
        ParquetWriter::new(file)
            .with_compression(ParquetCompression::Lz4Raw)
            .with_key_value_metadata(Some(metadata))
            .finish(df)
            .map_err(|e| errors.cause(e.into(), &tmp))?;
        std::fs::rename(&tmp, path)
            .with_context(|| format!("cannot move {} into place", path.display()))?;
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    crate::output::unregister_pending(&tmp);
    result
}

/// A Parquet file written in row groups as its chunks arrive, in order: the rows of a
/// large slice of a plan need not be in memory at once. Written to a temporary sibling and
/// renamed into place by [`ParquetAppender::finish`]; dropped unfinished, it leaves nothing.
pub struct ParquetAppender {
    writer: polars::prelude::BatchedWriter<RecordingFile>,
    errors: WriteErrors,
    tmp: std::path::PathBuf,
    path: std::path::PathBuf,
    finished: bool,
}

impl ParquetAppender {
    /// Starts `path` with the schema (and the stored column units and meanings) of `first`,
    /// and writes `first`.
    pub fn create(path: &Path, first: &mut DataFrame) -> Result<Self> {
        let tmp = crate::output::temp_sibling(path);
        crate::output::register_pending(&tmp);
        let started = RecordingFile::create(&tmp).and_then(|(file, errors)| {
            ParquetWriter::new(file)
                .with_compression(ParquetCompression::Lz4Raw)
                .with_key_value_metadata(Some(KeyValueMetadata::Static(vec![
                    schema::stored_schema(first),
                ])))
                .batched(first.schema())
                .map_err(|e| errors.cause(e.into(), &tmp))
                .map(|writer| (writer, errors))
        });
        let (writer, errors) = match started {
            Ok(w) => w,
            Err(e) => {
                // Nothing was started: no temporary file is left or still registered.
                let _ = std::fs::remove_file(&tmp);
                crate::output::unregister_pending(&tmp);
                return Err(e);
            }
        };
        // From here on, dropping the appender removes its temporary file.
        let mut appender = ParquetAppender {
            writer,
            errors,
            tmp,
            path: path.to_path_buf(),
            finished: false,
        };
        appender.append(first)?;
        Ok(appender)
    }

    /// Appends `df` to the file of `appender`, or starts `path` with it when `appender` is
    /// `None` (the first of a table's chunks).
    pub fn append_or_create(
        appender: &mut Option<Self>,
        path: &Path,
        df: &mut DataFrame,
    ) -> Result<()> {
        match appender.as_mut() {
            Some(a) => a.append(df),
            None => {
                *appender = Some(Self::create(path, df)?);
                Ok(())
            }
        }
    }

    /// Appends the rows of `df` (the columns of the first chunk) as row groups.
    pub fn append(&mut self, df: &mut DataFrame) -> Result<()> {
        let chunked = polars::frame::chunk_df_for_writing(df, 512 * 512)?;
        self.writer
            .write_batch(&chunked)
            .map_err(|e| self.errors.cause(e.into(), &self.tmp))
    }

    /// Writes the footer and moves the file into place.
    pub fn finish(mut self) -> Result<()> {
        self.writer
            .finish()
            .map_err(|e| self.errors.cause(e.into(), &self.tmp))?;
        std::fs::rename(&self.tmp, &self.path)
            .with_context(|| format!("cannot move {} into place", self.path.display()))?;
        self.finished = true;
        crate::output::unregister_pending(&self.tmp);
        Ok(())
    }
}

impl Drop for ParquetAppender {
    fn drop(&mut self) {
        if !self.finished {
            let _ = std::fs::remove_file(&self.tmp);
            crate::output::unregister_pending(&self.tmp);
        }
    }
}

/// Reads a Parquet file.
pub fn read_parquet(path: &Path) -> Result<DataFrame> {
    let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    ParquetReader::new(file)
        .finish()
        .with_context(|| format!("cannot read {} as Parquet", path.display()))
}

/// A stored column whose type is not the one archstudy writes (a damaged or edited table).
#[derive(Debug, thiserror::Error)]
#[error("column `{column}` holds {found} values, not numbers")]
pub struct ColumnTypeError {
    /// The column.
    pub column: String,
    /// The type found.
    pub found: String,
}

/// The number of rows of a Parquet file, from its metadata (no column is decoded).
pub fn parquet_rows(path: &Path) -> Result<usize> {
    let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    ParquetReader::new(file)
        .num_rows()
        .with_context(|| format!("cannot read {} as Parquet", path.display()))
}

/// Reads those of the named columns that a Parquet file has (the others are not decoded; a
/// study's results hold only the columns its finds fill).
pub fn read_parquet_columns(path: &Path, columns: &[&str]) -> Result<DataFrame> {
    read_parquet_rows(path, columns, None)
}

/// [`read_parquet_columns`] of the rows `slice` (offset, length) only: only the row groups
/// that hold them are decoded.
pub fn read_parquet_rows(
    path: &Path,
    columns: &[&str],
    slice: Option<(usize, usize)>,
) -> Result<DataFrame> {
    let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    let mut reader = ParquetReader::new(file);
    let schema = reader
        .schema()
        .with_context(|| format!("cannot read {} as Parquet", path.display()))?;
    let present: Vec<String> = columns
        .iter()
        .filter(|c| schema.contains(c))
        .map(|c| c.to_string())
        .collect();
    reader
        .with_columns(Some(present))
        .with_slice(slice)
        .finish()
        .with_context(|| format!("cannot read {} as Parquet", path.display()))
}

/// Reads the named columns of a Parquet file a block of `block` rows at a time, in order:
/// `each` is given the first row of the block and its frame (only the block's row groups
/// are decoded). A file without rows gives one empty block.
pub fn read_parquet_in_blocks(
    path: &Path,
    columns: &[&str],
    block: usize,
    mut each: impl FnMut(usize, &DataFrame) -> Result<()>,
) -> Result<()> {
    let rows = parquet_rows(path)?;
    let block = block.max(1);
    let mut offset = 0;
    loop {
        let df = read_parquet_rows(path, columns, Some((offset, block)))?;
        let n = df.height();
        each(offset, &df)?;
        offset += n;
        if n == 0 || offset >= rows {
            return Ok(());
        }
    }
}

/// Rewrites one value of a float column of a Parquet file in place (atomically), leaving
/// every other value and column as it was: how tests tamper with stored results.
pub fn rewrite_f64_value(path: &Path, column: &str, row: usize, value: Option<f64>) -> Result<()> {
    let mut df = read_parquet(path)?;
    let mut values = f64_column(&df, column).with_context(|| format!("in {}", path.display()))?;
    let slot = values.get_mut(row).with_context(|| {
        format!(
            "{} has no row {row} (it has {} rows)",
            path.display(),
            df.height()
        )
    })?;
    *slot = value;
    df.with_column(Column::new(column.into(), values))
        .with_context(|| format!("cannot replace column `{column}` of {}", path.display()))?;
    write_parquet(&mut df, path)
}

/// A nullable f64 column as a vector.
pub fn f64_column(df: &DataFrame, name: &str) -> Result<Vec<Option<f64>>> {
    let c = df
        .column(name)
        .with_context(|| format!("column `{name}` is missing"))?;
    if !(c.dtype().is_primitive_numeric() || c.dtype().is_null()) {
        return Err(ColumnTypeError {
            column: name.to_string(),
            found: c.dtype().to_string(),
        }
        .into());
    }
    let s = c.as_materialized_series().cast(&DataType::Float64)?;
    Ok(s.f64()?.iter().collect())
}

/// A nullable string column as a vector.
pub fn str_column(df: &DataFrame, name: &str) -> Result<Vec<Option<String>>> {
    let c = df
        .column(name)
        .with_context(|| format!("column `{name}` is missing"))?;
    let ca = c.as_materialized_series().str()?;
    Ok(ca.iter().map(|v| v.map(str::to_string)).collect())
}

/// A list column as vectors, each list's values converted by `values` (null lists become
/// empty).
fn list_column<T>(
    df: &DataFrame,
    name: &str,
    values: impl Fn(&polars::prelude::Series) -> Result<Vec<T>>,
) -> Result<Vec<Vec<T>>> {
    let c = df
        .column(name)
        .with_context(|| format!("column `{name}` is missing"))?;
    let l = c.as_materialized_series().list()?;
    // A column of nulls (a state grid's hinges, say) needs no per-row work.
    if l.null_count() == l.len() {
        return Ok(std::iter::repeat_with(Vec::new).take(l.len()).collect());
    }
    let mut out = Vec::with_capacity(l.len());
    for s in l.amortized_iter() {
        out.push(match s {
            Some(s) => values(s.as_ref())?,
            None => Vec::new(),
        });
    }
    Ok(out)
}

/// A List(Float64) column as vectors (null lists become empty, null values NaN).
pub fn list_f64_column(df: &DataFrame, name: &str) -> Result<Vec<Vec<f64>>> {
    list_column(df, name, |s| {
        Ok(s.f64()?.iter().map(|v| v.unwrap_or(f64::NAN)).collect())
    })
}

/// A List(String) column as vectors (null lists become empty, null values "").
pub fn list_str_column(df: &DataFrame, name: &str) -> Result<Vec<Vec<String>>> {
    list_column(df, name, |s| {
        Ok(s.str()?
            .iter()
            .map(|v| v.unwrap_or("").to_string())
            .collect())
    })
}

/// A non-null UInt64 column as a vector (nulls are an error).
pub fn u64_column(df: &DataFrame, name: &str) -> Result<Vec<u64>> {
    let c = df
        .column(name)
        .with_context(|| format!("column `{name}` is missing"))?;
    let s = c.as_materialized_series().cast(&DataType::UInt64)?;
    s.u64()?
        .iter()
        .enumerate()
        .map(|(i, v)| v.with_context(|| format!("column `{name}`: row {i} is null")))
        .collect()
}

/// A nullable Boolean column as a vector.
pub fn bool_column(df: &DataFrame, name: &str) -> Result<Vec<Option<bool>>> {
    let c = df
        .column(name)
        .with_context(|| format!("column `{name}` is missing"))?;
    Ok(c.as_materialized_series().bool()?.iter().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A write that fails for want of space (/dev/full) is named as such, not as the Parquet
    /// writer's "transport error".
    #[test]
    fn a_full_disk_is_named_not_hidden_behind_the_parquet_writer() {
        let full = Path::new("/dev/full");
        if !full.exists() {
            eprintln!("no /dev/full here; nothing checked");
            return;
        }
        let (file, errors) = RecordingFile::create(full).unwrap();
        let mut df = TableBuilder::new()
            .f64("x", (0..100_000).map(f64::from).collect())
            .finish()
            .unwrap();
        let e = ParquetWriter::new(file)
            .finish(&mut df)
            .map_err(|e| errors.cause(e.into(), full))
            .unwrap_err();
        let text = format!("{e:#}");
        assert!(text.contains("No space left on device"), "{text}");
        assert!(!text.contains("thrift"), "{text}");
    }
}
