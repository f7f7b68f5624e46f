//! `solve` and `solve_many`: keyword values into [`SceneOptions`], checked by the library,
//! solved by [`archstudy::scene::solve`] or, many at once, by
//! [`archstudy::engine::solve_scenes_in_blocks`] with the GIL released.

use crate::arg;
use crate::interrupt::run_stoppable;
use crate::table::Table;
use archstudy::engine;
use archstudy::manifest::{LoadCase, LoadKind, SceneOptions};
use archstudy::model::Load;
use archstudy::scene::{self, Scene};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyCFunction, PyDict, PyTuple};
use rayon::prelude::*;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Solves one scene given by the options of `archstudy solve` (positional, in the order of
/// [`SceneOptions`]' fields): its JSON (the keys of `solve --json`) and a function that draws
/// its state as SVG text.
pub fn solve(args: &Bound<'_, PyTuple>) -> PyResult<Py<PyAny>> {
    let py = args.py();
    let options = SceneOptions {
        k: arg(args, 0)?,
        t_over_r: arg(args, 1)?,
        mu: arg(args, 2)?,
        half_angle_deg: arg(args, 3)?,
        weight: arg(args, 4)?,
        voussoirs: arg(args, 5)?,
        find: arg(args, 6)?,
        shape: arg(args, 7)?,
        eccentricity: arg(args, 8)?,
        joints: arg(args, 9)?,
        keystone: arg(args, 10)?,
        load: arg(args, 11)?,
        at_deg: arg(args, 12)?,
        at_x: arg(args, 13)?,
        lambda: arg(args, 14)?,
        width: arg(args, 15)?,
    };
    let scene = options.scene().map_err(crate::value_error)?;
    let sol = py
        .detach(|| catch_unwind(|| scene::solve(&scene)))
        .map_err(|_| crate::runtime_error("the analysis of the scene failed (a panic)"))?;
    let json = serde_json::to_string_pretty(&sol).map_err(crate::runtime_error)?;
    let svg = PyCFunction::new_closure(
        py,
        Some(c"svg"),
        Some(c"The state drawing of the answer (the report's figure), as SVG text."),
        move |a: &Bound<'_, PyTuple>, _: Option<&Bound<'_, PyDict>>| -> PyResult<String> {
            let sol = &sol;
            a.py()
                .detach(|| {
                    catch_unwind(AssertUnwindSafe(|| {
                        archstudy::report::charts::solution::svg(sol)
                    }))
                })
                .map_err(|_| crate::runtime_error("the drawing of the state failed (a panic)"))?
                .map_err(|e| crate::runtime_error(format!("{e:#}")))
        },
    )?;
    Ok((json, svg).into_pyobject(py)?.into_any().unbind())
}

/// The numeric options of `solve_many`, one float64 array each (NaN: not given).
const NUMBERS: [&str; 10] = [
    "k",
    "t_over_r",
    "mu",
    "half_angle",
    "voussoirs",
    "eccentricity",
    "at",
    "at_x",
    "lambda_",
    "width",
];

/// One value of a numeric column at a row; NaN is "not given".
fn given(col: &Option<Vec<f64>>, i: usize) -> Option<f64> {
    col.as_ref().map(|c| c[i]).filter(|x| !x.is_nan())
}

/// Solves `n` scenes whose numeric options arrive as float64 arrays of length `n` (native
/// byte order; a missing name or NaN: not given), the kinds being one for all: `(n, numbers,
/// find, weight, shape, joints, keystone, load, jobs)` in, a table out ([`Table::into_py`]).
pub fn solve_many(args: &Bound<'_, PyTuple>) -> PyResult<Py<PyAny>> {
    let py = args.py();
    let n: usize = arg(args, 0)?;
    let numbers: Vec<(String, Vec<u8>)> = args
        .get_item(1)?
        .try_iter()?
        .map(|item| {
            let item = item?;
            let name: String = item.get_item(0)?.extract()?;
            let bytes = item.get_item(1)?;
            let bytes = bytes.cast::<PyBytes>().map_err(PyErr::from)?;
            Ok((name, bytes.as_bytes().to_vec()))
        })
        .collect::<PyResult<_>>()?;
    let (find, weight, shape, joints): (String, String, String, String) =
        (arg(args, 2)?, arg(args, 3)?, arg(args, 4)?, arg(args, 5)?);
    let keystone: bool = arg(args, 6)?;
    let load: String = arg(args, 7)?;
    let jobs: Option<usize> = arg(args, 8)?;
    let mut cols: Vec<Option<Vec<f64>>> = vec![None; NUMBERS.len()];
    for (name, b) in &numbers {
        let Some(j) = NUMBERS.iter().position(|x| x == name) else {
            return Err(crate::value_error(format!("unknown option `{name}`")));
        };
        if b.len() != n * 8 {
            return Err(crate::value_error(format!(
                "`{name}` holds {} values, not {n}",
                b.len() / 8
            )));
        }
        cols[j] = Some(
            b.chunks_exact(8)
                .map(|c| f64::from_ne_bytes(c.try_into().unwrap_or_default()))
                .collect(),
        );
    }
    if jobs == Some(0) {
        return Err(crate::value_error(
            "invalid value '0' for 'jobs': the number of threads must be at least 1",
        ));
    }
    let base = SceneOptions {
        find,
        weight,
        shape,
        joints,
        keystone,
        load,
        ..SceneOptions::default()
    };
    let out = run_stoppable(py, true, move |progress| {
        let pool = archstudy::runner::worker_pool(jobs)?.0;
        pool.install(|| {
            let scenes = scenes_of(&base, &cols, n)?;
            let lc = [load_case(&base, scenes.first())];
            // Each block's rows become a frame while they are still in cache; the table
            // reads the frames in turn.
            let blocks = engine::solve_scenes_in_blocks(&scenes, progress.as_ref(), |rows| {
                archstudy::store::scenes_frame(&lc, &rows)
            })?;
            if blocks.is_empty() {
                // No scene: the table's columns all the same.
                return Ok(vec![archstudy::store::scenes_frame(&lc, &[])?]);
            }
            blocks.into_iter().collect::<anyhow::Result<Vec<_>>>()
        })
    })?;
    match out {
        Ok(frames) => Table::of_blocks(frames).into_py(py),
        Err(e) if e.is::<archstudy::manifest::SceneOptionError>() => {
            Err(crate::value_error(format!("{e:#}")))
        }
        Err(e) => Err(crate::runtime_error(format!("{e:#}"))),
    }
}

/// Every scene checked, in parallel; the error of the first row at fault names its row.
fn scenes_of(
    base: &SceneOptions,
    cols: &[Option<Vec<f64>>],
    n: usize,
) -> anyhow::Result<Vec<Scene>> {
    // One copy of the options per worker, its numbers set row by row.
    (0..n)
        .into_par_iter()
        .map_init(
            || base.clone(),
            |o, i| {
                let v = |j: usize| given(&cols[j], i);
                o.k = v(0);
                o.t_over_r = v(1);
                o.mu = v(2).unwrap_or(f64::INFINITY);
                o.half_angle_deg = v(3).unwrap_or(90.0);
                o.voussoirs = v(4).map(|x| x as i64);
                o.eccentricity = v(5);
                o.at_deg = v(6);
                o.at_x = v(7);
                o.lambda = v(8);
                o.width = v(9);
                o.scene()
                    .map_err(|e| anyhow::Error::new(e).context(format!("scene {i}")))
            },
        )
        .collect()
}

/// The one load case of a batch: named by its kind, with the batch's find.
fn load_case(base: &SceneOptions, first: Option<&Scene>) -> LoadCase {
    let kind = match first.map(|s| s.load) {
        Some(Load::Horizontal) => LoadKind::Horizontal,
        Some(Load::Point { .. } | Load::PointX { .. }) => LoadKind::Point,
        _ => LoadKind::SelfWeight,
    };
    LoadCase {
        name: kind.as_str().to_string(),
        kind,
        at_deg: None,
        at_x: None,
        width: None,
        lambda: None,
        find: first.map_or_else(
            || archstudy::scene::Find::parse(&base.find).unwrap_or_default(),
            |s| s.find,
        ),
        sampled: false,
    }
}
