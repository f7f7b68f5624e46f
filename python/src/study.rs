//! Studies: `run` a manifest as `archstudy run` does (the same run directory), and read a
//! stored table of a run directory.

use crate::arg;
use crate::interrupt::run_stoppable;
use crate::table::Table;
use archstudy::runner::{self, RunOptions};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::path::PathBuf;
use std::sync::Arc;

/// Runs the manifest at `study` into `out/<name>/`: `(study, out, jobs, quiet,
/// command_line)` in; `("ok", run_dir)` out, or `("manifest", file, line, column, key,
/// (value, allowed, message), text)` for a manifest that is not valid (the Python layer
/// raises ManifestError).
pub fn run(args: &Bound<'_, PyTuple>) -> PyResult<Py<PyAny>> {
    let py = args.py();
    let study: PathBuf = arg(args, 0)?;
    let out: PathBuf = arg(args, 1)?;
    let jobs: Option<usize> = arg(args, 2)?;
    let quiet: bool = arg(args, 3)?;
    let command_line: Vec<String> = arg(args, 4)?;
    if jobs == Some(0) {
        return Err(crate::value_error(
            "invalid value '0' for 'jobs': the number of threads must be at least 1",
        ));
    }
    let result = run_stoppable(py, quiet, move |progress| {
        let opts = RunOptions {
            jobs,
            progress: progress as Arc<dyn archstudy::progress::Progress>,
            command_line,
            ..RunOptions::new(study, out)
        };
        runner::run_study(&opts)
    })?;
    let e = match result {
        Ok(summary) => {
            let dir = summary.dir.display().to_string();
            return Ok(("ok", dir).into_pyobject(py)?.into_any().unbind());
        }
        Err(e) => e,
    };
    if let Some(m) = e.downcast_ref::<archstudy::manifest::ManifestError>() {
        let (line, column) = m.position.unzip();
        let (value, allowed) = m.value_and_allowed();
        let fields = (
            "manifest",
            m.path.display().to_string(),
            line,
            column,
            m.key.clone(),
            (value, allowed, m.message.clone()),
            m.to_string(),
        );
        Ok(fields.into_pyobject(py)?.into_any().unbind())
    } else if e.is::<archstudy::error::UsageError>() || e.is::<archstudy::plan::PlanTooLarge>() {
        Err(crate::value_error(format!("{e:#}")))
    } else {
        Err(crate::runtime_error(format!("{e:#}")))
    }
}

/// Reads a Parquet table of a run directory: `(path)` in, a table out.
pub fn read_table(args: &Bound<'_, PyTuple>) -> PyResult<Py<PyAny>> {
    let py = args.py();
    let path: PathBuf = arg(args, 0)?;
    let df = py
        .detach(|| archstudy::store::read_parquet(&path))
        .map_err(|e| crate::runtime_error(format!("{e:#}")))?;
    Table::new(df).into_py(py)
}
