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

/// A table of results (one row per scene or case).
pub struct Table {
    df: DataFrame,
}

impl Table {
    /// A table of a data frame, its columns in one chunk each.
    pub fn new(mut df: DataFrame) -> Self {
        df.rechunk_mut();
        Table { df }
    }

    /// The table as record batches of plain Arrow types (large strings and lists, never view
    /// types), each a struct array, with the struct's field.
    fn batches(&self) -> (Vec<Box<dyn Array>>, Field) {
        let fields: Vec<Field> = self
            .df
            .columns()
            .iter()
            .map(|c| c.field().to_arrow(CompatLevel::oldest()))
            .collect();
        let dtype = ArrowDataType::Struct(fields);
        let batches = self
            .df
            .iter_chunks(CompatLevel::oldest(), false)
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
        let rows = self.df.height();
        let names: Vec<String> = self
            .df
            .get_column_names()
            .iter()
            .map(|s| s.to_string())
            .collect();
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
