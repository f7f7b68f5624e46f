//! A table of results as Arrow data: a function that hands pyarrow, polars or pandas an Arrow
//! C stream of its record batches in a PyCapsule (the Arrow PyCapsule stream interface; no
//! copy through Python objects).

use polars::prelude::{CompatLevel, DataFrame};
use polars_arrow::array::{Array, StructArray};
use polars_arrow::datatypes::{ArrowDataType, Field};
use polars_arrow::ffi;
use pyo3::prelude::*;
use pyo3::types::{PyCFunction, PyCapsule, PyDict, PyTuple};
use std::ffi::CString;

/// A table of results (one row per scene or case): frames of the same columns, one under
/// the other.
pub struct Table {
    frames: Vec<DataFrame>,
}

impl Table {
    /// A table of a data frame, its columns' chunks aligned (one record batch per chunk).
    pub fn new(df: DataFrame) -> Self {
        Table::of_blocks(vec![df])
    }

    /// A table of frames of the same columns (each block's chunks aligned), read as their
    /// record batches in order: no copy into one frame.
    pub fn of_blocks(mut frames: Vec<DataFrame>) -> Self {
        for df in &mut frames {
            df.align_chunks_par();
        }
        Table { frames }
    }

    /// The number of rows.
    fn height(&self) -> usize {
        self.frames.iter().map(DataFrame::height).sum()
    }

    /// The table as record batches of plain Arrow types (large strings and lists, never view
    /// types), each a struct array, with the struct's field.
    fn batches(&self) -> (Vec<Box<dyn Array>>, Field) {
        let fields: Vec<Field> = self.frames.first().map_or_else(Vec::new, |df| {
            df.columns()
                .iter()
                .map(|c| c.field().to_arrow(CompatLevel::oldest()))
                .collect()
        });
        let dtype = ArrowDataType::Struct(fields);
        let batches = self
            .frames
            .iter()
            .flat_map(|df| df.iter_chunks(CompatLevel::oldest(), true))
            .map(|b| {
                let len = b.height();
                Box::new(StructArray::new(dtype.clone(), len, b.into_arrays(), None))
                    as Box<dyn Array>
            })
            .collect();
        (batches, Field::new("".into(), dtype, false))
    }

    /// An Arrow C stream of the table in a PyCapsule named `arrow_array_stream`.
    fn capsule<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyCapsule>> {
        let (batches, field) = self.batches();
        let stream = ffi::export_iterator(Box::new(batches.into_iter().map(Ok)), field);
        let name = CString::new("arrow_array_stream").map_err(crate::runtime_error)?;
        PyCapsule::new(py, stream, Some(name))
    }

    /// `(rows, column names, stream)`: `stream(requested_schema=None)` returns a new capsule
    /// at each call (the table's own schema; a requested one is not honoured).
    pub fn into_py(self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let rows = self.height();
        let names: Vec<String> = self.frames.first().map_or_else(Vec::new, |df| {
            df.get_column_names()
                .iter()
                .map(|s| s.to_string())
                .collect()
        });
        let stream = PyCFunction::new_closure(
            py,
            Some(c"__arrow_c_stream__"),
            Some(c"An Arrow C stream of the table, in a PyCapsule `arrow_array_stream`."),
            move |a: &Bound<'_, PyTuple>, _: Option<&Bound<'_, PyDict>>| {
                self.capsule(a.py()).map(Bound::unbind)
            },
        )?;
        Ok((rows, names, stream).into_pyobject(py)?.into_any().unbind())
    }
}
