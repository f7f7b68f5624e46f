//! results.parquet: one row per case (schema in the README).

use super::TableBuilder;
use crate::engine::CaseResult;
use crate::plan::Plan;
use crate::scene::{HingeRecord, SlidingRecord};
use anyhow::Result;
use polars::prelude::DataFrame;
use rayon::prelude::*;

pub(crate) fn hinge_angles(h: &[HingeRecord]) -> Vec<f64> {
    h.iter().map(|h| h.angle_deg).collect()
}
pub(crate) fn hinge_faces(h: &[HingeRecord]) -> Vec<&'static str> {
    h.iter().map(|h| h.face).collect()
}
pub(crate) fn sliding_angles(s: &[SlidingRecord]) -> Vec<f64> {
    s.iter().map(|s| s.angle_deg).collect()
}
pub(crate) fn sliding_senses(s: &[SlidingRecord]) -> Vec<&'static str> {
    s.iter().map(|s| s.sense).collect()
}

/// One column: its name, its values so far and how to read a value from a row.
type Get<'a, T> = Box<dyn Fn(&'a CaseResult) -> T + 'a>;

enum Spec<'a> {
    U64(&'static str, Vec<u64>, Get<'a, u64>),
    F64(&'static str, Vec<f64>, Get<'a, f64>),
    OptF64(&'static str, Vec<Option<f64>>, Get<'a, Option<f64>>),
    OptU32(&'static str, Vec<Option<u32>>, Get<'a, Option<u32>>),
    Bool(&'static str, Vec<bool>, Get<'a, bool>),
    Str(&'static str, Vec<&'a str>, Get<'a, &'a str>),
    OptStr(&'static str, Vec<Option<&'a str>>, Get<'a, Option<&'a str>>),
    ListF64(&'static str, Vec<Vec<f64>>, Get<'a, Vec<f64>>),
    ListStr(
        &'static str,
        Vec<Vec<&'static str>>,
        Get<'a, Vec<&'static str>>,
    ),
}

impl<'a> Spec<'a> {
    fn push(&mut self, r: &'a CaseResult) {
        match self {
            Spec::U64(_, v, g) => v.push(g(r)),
            Spec::F64(_, v, g) => v.push(g(r)),
            Spec::OptF64(_, v, g) => v.push(g(r)),
            Spec::OptU32(_, v, g) => v.push(g(r)),
            Spec::Bool(_, v, g) => v.push(g(r)),
            Spec::Str(_, v, g) => v.push(g(r)),
            Spec::OptStr(_, v, g) => v.push(g(r)),
            Spec::ListF64(_, v, g) => v.push(g(r)),
            Spec::ListStr(_, v, g) => v.push(g(r)),
        }
    }

    fn add_to(self, t: TableBuilder) -> TableBuilder {
        match self {
            Spec::U64(n, v, _) => t.u64(n, v),
            Spec::F64(n, v, _) => t.f64(n, v),
            Spec::OptF64(n, v, _) => t.opt_f64(n, v),
            Spec::OptU32(n, v, _) => t.opt_u32(n, v),
            Spec::Bool(n, v, _) => t.bool(n, v),
            Spec::Str(n, v, _) => t.str(n, v),
            Spec::OptStr(n, v, _) => t.opt_str(n, v),
            Spec::ListF64(n, v, _) => t.list_f64(n, v),
            Spec::ListStr(n, v, _) => t.list_str(n, v),
        }
    }
}

/// Rows per independently built block of the results table: a fixed size, so that the
/// blocks, and the file written from them, do not depend on the number of threads.
const BLOCK_ROWS: usize = 1 << 18;

/// The results table: one row per case (schema in the README).
///
/// Blocks of [`BLOCK_ROWS`] rows are built in parallel (on the current rayon pool) and
/// stacked; each is built in one pass over its rows (every column of a row is read while the
/// row is in cache): a million-row state grid is read once, not once per column.
pub fn results_frame(plan: &Plan, rows: &[CaseResult]) -> Result<DataFrame> {
    frame_in_blocks(plan, rows, BLOCK_ROWS)
}

fn frame_in_blocks(plan: &Plan, rows: &[CaseResult], block_rows: usize) -> Result<DataFrame> {
    if rows.len() <= block_rows {
        return block_frame(plan, rows);
    }
    let blocks = rows
        .par_chunks(block_rows)
        .map(|b| block_frame(plan, b))
        .collect::<Result<Vec<DataFrame>>>()?;
    let mut blocks = blocks.into_iter();
    let mut df = blocks.next().unwrap_or_default();
    for b in blocks {
        df.vstack_mut_owned(b)?;
    }
    Ok(df)
}

fn block_frame<'a>(plan: &'a Plan, rows: &'a [CaseResult]) -> Result<DataFrame> {
    let m = &plan.manifest;
    let n = rows.len();
    let mut specs: Vec<Spec<'a>> = vec![
        Spec::U64(
            "case_id",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.case_id),
        ),
        Spec::Str(
            "load_case",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| m.load_cases[r.load_case].name.as_str()),
        ),
        Spec::Str(
            "load_kind",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| m.load_cases[r.load_case].kind.as_str()),
        ),
        Spec::Str(
            "find",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.find),
        ),
        Spec::OptF64(
            "k",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.k),
        ),
        Spec::OptF64(
            "t_over_r",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.t_over_r),
        ),
        Spec::OptF64(
            "mu",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| {
                if r.solution.mu_infinite {
                    Some(f64::INFINITY)
                } else {
                    r.solution.mu
                }
            }),
        ),
        Spec::F64(
            "half_angle_deg",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.half_angle_deg),
        ),
        Spec::Str(
            "weight",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.weight),
        ),
        Spec::OptU32(
            "voussoirs",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.voussoirs),
        ),
        // Form and load case (docs/loads-and-geometries.md).
        Spec::Str(
            "shape",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.shape),
        ),
        Spec::OptF64(
            "eccentricity",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.eccentricity),
        ),
        Spec::Str(
            "joints",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.joints),
        ),
        Spec::Str(
            "load",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.load),
        ),
        Spec::OptF64(
            "at_deg",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.at_deg),
        ),
        Spec::OptF64(
            "lambda",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.lambda),
        ),
        Spec::OptStr(
            "outcome",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.outcome),
        ),
        Spec::OptStr(
            "regime",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.regime),
        ),
        Spec::OptF64(
            "thrust_r_min",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.thrust_r_min),
        ),
        Spec::OptF64(
            "thrust_r_max",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.thrust_r_max),
        ),
        Spec::OptF64(
            "thrust_s_min",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.thrust_s_min),
        ),
        Spec::OptF64(
            "thrust_s_max",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.thrust_s_max),
        ),
        Spec::OptF64(
            "k_crit",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.k_crit),
        ),
        Spec::OptF64(
            "t_over_r_crit",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.t_over_r_crit),
        ),
        Spec::OptF64(
            "mu_crit",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.mu_crit),
        ),
        Spec::OptStr(
            "mechanism",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.mechanism),
        ),
        Spec::OptF64(
            "thrust_over_half_weight",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.thrust_over_half_weight),
        ),
        Spec::OptF64(
            "crown_moment",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.crown_moment),
        ),
        Spec::OptF64(
            "crown_shear",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.crown_shear),
        ),
        Spec::OptF64(
            "load_factor",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.load_factor),
        ),
        Spec::Bool(
            "load_factor_unbounded",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.load_factor_unbounded),
        ),
        Spec::ListF64(
            "hinge_angles_deg",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| hinge_angles(&r.solution.hinges)),
        ),
        Spec::ListStr(
            "hinge_faces",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| hinge_faces(&r.solution.hinges)),
        ),
        Spec::ListF64(
            "sliding_angles_deg",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| sliding_angles(&r.solution.sliding_joints)),
        ),
        Spec::ListStr(
            "sliding_senses",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| sliding_senses(&r.solution.sliding_joints)),
        ),
        Spec::OptF64(
            "work_loads",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.work_loads),
        ),
        Spec::OptF64(
            "work_friction",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.work_friction),
        ),
        Spec::OptF64(
            "work_residual",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.work_residual),
        ),
        Spec::OptU32(
            "mechanism_dof",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.mechanism_dof),
        ),
        Spec::OptF64(
            "k_c_rotational",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.k_c_rotational),
        ),
        Spec::OptF64(
            "mu_rotational_mixed",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.mu_rotational_mixed),
        ),
        Spec::OptF64(
            "mu_min",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.mu_min),
        ),
        Spec::OptF64(
            "k_mixed_sliding",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.k_mixed_sliding),
        ),
        Spec::OptF64(
            "thrust_min",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.thrust_min),
        ),
        Spec::OptF64(
            "thrust_max",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.thrust_max),
        ),
        Spec::ListF64(
            "hinges_min_angles_deg",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| hinge_angles(&r.solution.hinges_min)),
        ),
        Spec::ListStr(
            "hinges_min_faces",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| hinge_faces(&r.solution.hinges_min)),
        ),
        Spec::ListF64(
            "hinges_max_angles_deg",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| hinge_angles(&r.solution.hinges_max)),
        ),
        Spec::ListStr(
            "hinges_max_faces",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| hinge_faces(&r.solution.hinges_max)),
        ),
        Spec::Str(
            "status",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.status.as_str()),
        ),
        Spec::OptStr(
            "message",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.message.as_deref()),
        ),
        Spec::F64(
            "solve_time_us",
            Vec::with_capacity(n),
            Box::new(|r: &'a CaseResult| r.solution.solve_time_us),
        ),
    ];
    for r in rows {
        for s in specs.iter_mut() {
            s.push(r);
        }
    }
    specs
        .into_iter()
        .fold(TableBuilder::new(), |t, s| s.add_to(t))
        .finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine;
    use std::path::Path;

    #[test]
    fn blocks_stack_to_the_table_of_one_pass() {
        // Blocks of 7 rows split a 13 × 11 state grid unevenly; the stacked table has the
        // same columns, values and nulls as the one built in a single pass.
        let m = crate::manifest::parse(
            "name: a\ngrid:\n  k: {from: 1.05, to: 1.4, steps: 13}\n  mu: {from: 0.2, to: 0.7, steps: 11}\n",
            Path::new("a.yaml"),
        )
        .unwrap();
        let plan = crate::plan::build(m).unwrap();
        let rows = engine::run(&plan, &crate::progress::Silent);
        let whole = frame_in_blocks(&plan, &rows, usize::MAX).unwrap();
        let blocks = frame_in_blocks(&plan, &rows, 7).unwrap();
        assert_eq!(whole.height(), 143);
        assert_eq!(whole.get_column_names(), blocks.get_column_names());
        // Solve times differ between runs of a case but not between two tables of one run.
        assert!(whole.equals_missing(&blocks));
    }
}
