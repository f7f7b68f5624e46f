//! The native module `archstudy._archstudy`: a thin layer over the archstudy library. Scenes
//! are checked by [`archstudy::manifest::SceneOptions`], solved by [`archstudy::scene`] and
//! [`archstudy::engine`], drawn by [`archstudy::report`], studies run by
//! [`archstudy::runner`]; tables cross to Python as Arrow through the PyCapsule stream
//! interface ([`table`]). The public, typed Python API is `archstudy/__init__.py`; the
//! functions here take their arguments by position, in the order `__init__.py` passes them.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::ffi;
use pyo3::prelude::*;
use pyo3::types::{PyCFunction, PyDict, PyModule, PyTuple};
use std::ffi::CStr;

mod interrupt;
mod scenes;
mod study;
mod table;

/// A Rust panic or a failed run as a Python exception (never a crash of the interpreter).
pub(crate) fn runtime_error(e: impl std::fmt::Display) -> PyErr {
    PyRuntimeError::new_err(e.to_string())
}

/// A bad keyword value: `ValueError("invalid value 'V' for 'KEY': ALLOWED")`.
pub(crate) fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Argument `i` of a native call, converted.
pub(crate) fn arg<'py, T>(args: &Bound<'py, PyTuple>, i: usize) -> PyResult<T>
where
    T: for<'a> FromPyObject<'a, 'py, Error = PyErr>,
{
    args.get_item(i)?.extract::<T>()
}

/// A native function: its positional arguments in, a Python object out.
type Native = fn(&Bound<'_, PyTuple>) -> PyResult<Py<PyAny>>;

/// The module's functions: name, doc (its first line the text signature that `inspect` and
/// stubtest read), body.
const FUNCTIONS: [(&CStr, &CStr, Native); 4] = [
    (
        c"solve",
        c"solve(k, t_over_r, mu, half_angle, weight, voussoirs, find, shape, eccentricity, joints, keystone, load, at, at_x, lambda_, width, /)\n--\n\nOne scene solved: (json, svg), svg a function that draws it.",
        scenes::solve,
    ),
    (
        c"solve_many",
        c"solve_many(n, numbers, find, weight, shape, joints, keystone, load, jobs, /)\n--\n\nMany scenes solved: (rows, columns, stream).",
        scenes::solve_many,
    ),
    (
        c"run",
        c"run(study, out, jobs, quiet, command_line, /)\n--\n\nA study run: ('ok', dir) or ('manifest', file, line, column, key, (value, allowed, message), text).",
        study::run,
    ),
    (
        c"read_table",
        c"read_table(path, /)\n--\n\nA Parquet table of a run: (rows, columns, stream).",
        study::read_table,
    ),
];

fn add_functions(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    for (name, doc, body) in FUNCTIONS {
        let f = PyCFunction::new_closure(
            py,
            Some(name),
            Some(doc),
            move |args: &Bound<'_, PyTuple>, _kwargs: Option<&Bound<'_, PyDict>>| body(args),
        )?;
        m.add(name.to_str().map_err(runtime_error)?, f)?;
    }
    m.add("__version__", archstudy::provenance::version())?;
    Ok(())
}

static mut MODULE: ffi::PyModuleDef = ffi::PyModuleDef {
    m_base: ffi::PyModuleDef_HEAD_INIT,
    m_name: c"_archstudy".as_ptr(),
    m_doc: c"The native module of archstudy: use the functions of `archstudy`.".as_ptr(),
    m_size: -1,
    m_methods: std::ptr::null_mut(),
    m_slots: std::ptr::null_mut(),
    m_traverse: None,
    m_clear: None,
    m_free: None,
};

/// The module's initialisation, called by the interpreter on `import`.
///
/// # Safety
/// Called by CPython with the GIL held, once per import.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn PyInit__archstudy() -> *mut ffi::PyObject {
    // SAFETY: the interpreter calls this with the GIL held; MODULE lives for the process.
    let m = unsafe { ffi::PyModule_Create2(&raw mut MODULE, ffi::PYTHON_API_VERSION) };
    if m.is_null() {
        return m;
    }
    // SAFETY: the GIL is held (above); `m` is a new reference to a module.
    let py = unsafe { Python::assume_attached() };
    let module = unsafe { Bound::from_owned_ptr(py, m) };
    let added = module
        .cast::<PyModule>()
        .map_err(PyErr::from)
        .and_then(add_functions);
    match added {
        Ok(()) => module.into_ptr(),
        Err(e) => {
            e.restore(py);
            std::ptr::null_mut()
        }
    }
}
