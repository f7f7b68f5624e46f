//! results.parquet: one row per case (schema in the README).

use super::TableBuilder;
use crate::analysis::{Hinge, SlidingJoint};
use crate::engine::{CaseResult, StateCase};
use crate::manifest::LoadCase;
use crate::plan::Plan;
use crate::scene::Find;
use anyhow::Result;
use polars::prelude::DataFrame;
use rayon::prelude::*;

pub(crate) fn hinge_angles(h: &[Hinge]) -> Vec<f64> {
    h.iter().map(|h| h.angle_deg).collect()
}
pub(crate) fn hinge_faces(h: &[Hinge]) -> Vec<&'static str> {
    h.iter().map(|h| h.face.as_str()).collect()
}
pub(crate) fn sliding_angles(s: &[SlidingJoint]) -> Vec<f64> {
    s.iter().map(|s| s.angle_deg).collect()
}
pub(crate) fn sliding_senses(s: &[SlidingJoint]) -> Vec<&'static str> {
    s.iter().map(|s| s.sense.as_str()).collect()
}

/// The upper ends of a thickness find's windows, the end of the scan standing for a window
/// still open there.
fn window_ends(s: &crate::scene::Solution) -> Vec<f64> {
    let open = s.k_windows_scanned_to.unwrap_or(f64::INFINITY);
    s.k_windows.iter().map(|w| w.1.unwrap_or(open)).collect()
}

/// One column: its name, its values so far and how to read a value from a row.
type Get<'a, R, T> = Box<dyn Fn(&'a R) -> T + Send + Sync + 'a>;

enum Spec<'a, R> {
    U64(&'static str, Vec<u64>, Get<'a, R, u64>),
    F64(&'static str, Vec<f64>, Get<'a, R, f64>),
    OptF64(&'static str, Vec<Option<f64>>, Get<'a, R, Option<f64>>),
    OptU32(&'static str, Vec<Option<u32>>, Get<'a, R, Option<u32>>),
    Bool(&'static str, Vec<bool>, Get<'a, R, bool>),
    OptBool(&'static str, Vec<Option<bool>>, Get<'a, R, Option<bool>>),
    Str(&'static str, Vec<&'a str>, Get<'a, R, &'a str>),
    OptStr(
        &'static str,
        Vec<Option<&'a str>>,
        Get<'a, R, Option<&'a str>>,
    ),
    ListF64(&'static str, Vec<Vec<f64>>, Get<'a, R, Vec<f64>>),
    ListStr(
        &'static str,
        Vec<Vec<&'static str>>,
        Get<'a, R, Vec<&'static str>>,
    ),
}

impl<'a, R> Spec<'a, R> {
    fn name(&self) -> &'static str {
        match self {
            Spec::U64(n, ..)
            | Spec::F64(n, ..)
            | Spec::OptF64(n, ..)
            | Spec::OptU32(n, ..)
            | Spec::Bool(n, ..)
            | Spec::OptBool(n, ..)
            | Spec::Str(n, ..)
            | Spec::OptStr(n, ..)
            | Spec::ListF64(n, ..)
            | Spec::ListStr(n, ..) => n,
        }
    }

    fn reserve(&mut self, n: usize) {
        match self {
            Spec::U64(_, v, _) => v.reserve(n),
            Spec::F64(_, v, _) => v.reserve(n),
            Spec::OptF64(_, v, _) => v.reserve(n),
            Spec::OptU32(_, v, _) => v.reserve(n),
            Spec::Bool(_, v, _) => v.reserve(n),
            Spec::OptBool(_, v, _) => v.reserve(n),
            Spec::Str(_, v, _) => v.reserve(n),
            Spec::OptStr(_, v, _) => v.reserve(n),
            Spec::ListF64(_, v, _) => v.reserve(n),
            Spec::ListStr(_, v, _) => v.reserve(n),
        }
    }

    fn push(&mut self, r: &'a R) {
        match self {
            Spec::U64(_, v, g) => v.push(g(r)),
            Spec::F64(_, v, g) => v.push(g(r)),
            Spec::OptF64(_, v, g) => v.push(g(r)),
            Spec::OptU32(_, v, g) => v.push(g(r)),
            Spec::Bool(_, v, g) => v.push(g(r)),
            Spec::OptBool(_, v, g) => v.push(g(r)),
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
            Spec::OptBool(n, v, _) => t.opt_bool(n, v),
            Spec::Str(n, v, _) => t.str(n, v),
            Spec::OptStr(n, v, _) => t.opt_str(n, v),
            Spec::ListF64(n, v, _) => t.list_f64(n, v),
            Spec::ListStr(n, v, _) => t.list_str(n, v),
        }
    }
}

/// Constructors of the columns of one type: a name and how to read the value from a row.
macro_rules! column {
    ($fn_name:ident, $variant:ident, $t:ty) => {
        fn $fn_name<'a, R>(
            name: &'static str,
            get: impl Fn(&'a R) -> $t + Send + Sync + 'a,
        ) -> Spec<'a, R> {
            Spec::$variant(name, Vec::new(), Box::new(get))
        }
    };
}
column!(u64_col, U64, u64);
column!(f64_col, F64, f64);
column!(opt_f64, OptF64, Option<f64>);
column!(opt_u32, OptU32, Option<u32>);
column!(bool_col, Bool, bool);
column!(opt_bool, OptBool, Option<bool>);
column!(str_col, Str, &'a str);
column!(opt_str, OptStr, Option<&'a str>);
column!(list_f64, ListF64, Vec<f64>);
column!(list_str, ListStr, Vec<&'static str>);

/// Rows per independently built block of the results table: a fixed size, so that the
/// blocks, and the file written from them, do not depend on the number of threads. (A list
/// column that no row of a block fills is stored as nulls in that block: a table written in
/// chunks holds the data of one pass when its chunks start at multiples of this.)
pub const BLOCK_ROWS: usize = 1 << 18;

/// The results table: one row per case (schema in the README).
///
/// Blocks of [`BLOCK_ROWS`] rows are built in parallel (on the current rayon pool) and
/// stacked; each is built in one pass over its rows (every column of a row is read while the
/// row is in cache): a million-row state grid is read once, not once per column.
///
/// Only the answer columns that the study's finds fill are written ([`filled_by`]): a
/// `state` study has no `k_crit` column, a `thickness` study no `regime` column.
pub fn results_frame(plan: &Plan, rows: &[CaseResult]) -> Result<DataFrame> {
    frame_in_blocks(
        &plan.manifest.load_cases,
        rows,
        BLOCK_ROWS,
        Columns::OfStudy,
    )
}

/// [`results_frame`] of the compact rows of a separable `state` grid: the same table as that
/// of their full rows ([`crate::engine::StateCase::into_result`]).
pub fn state_results_frame(plan: &Plan, rows: &[StateCase]) -> Result<DataFrame> {
    let load_cases = &plan.manifest.load_cases;
    specs_in_blocks(rows, BLOCK_ROWS, || state_columns(load_cases))
}

/// The results table of rows that belong to no study (scenes solved one by one, or many at
/// once from Python): the columns of results.parquet, each row's `load_case` naming one of
/// `load_cases`, the answer columns those load cases' finds fill.
pub fn scenes_frame(load_cases: &[LoadCase], rows: &[CaseResult]) -> Result<DataFrame> {
    frame_in_blocks(load_cases, rows, BLOCK_ROWS, Columns::OfStudy)
}

/// Which answer columns a results table holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Columns {
    /// Those the study's finds fill.
    OfStudy,
    /// Every column (tests compare both).
    #[cfg(test)]
    All,
}

/// The finds whose cases fill an answer column of results.parquet; `None` when every find
/// may fill it (outcome, status, message, solve time).
pub fn filled_by(column: &str) -> Option<&'static [Find]> {
    use Find::{Friction, LoadFactor, State, Thickness, Thresholds, Thrust};
    Some(match column {
        "regime" | "thrust_r_min" | "thrust_r_max" | "thrust_s_min" | "thrust_s_max" => &[State],
        "k_crit"
        | "t_over_r_crit"
        | "k_windows_from"
        | "k_windows_to"
        | "k_windows_scanned_to"
        | "k_windows_resolution" => &[Thickness],
        "mu_crit" => &[Friction],
        "load_factor" | "load_factor_unbounded" => &[LoadFactor],
        "mechanism"
        | "thrust_over_half_weight"
        | "crown_moment"
        | "crown_shear"
        | "hinge_angles_deg"
        | "hinge_faces"
        | "sliding_angles_deg"
        | "sliding_senses"
        | "work_loads"
        | "work_friction"
        | "work_residual"
        | "mechanism_dof"
        | "mechanism_admissible"
        | "critical_apex_shared"
        | "gap"
        | "collapse_value"
        | "gap_width"
        | "gap_searched_to"
        | "collapse_mechanism"
        | "collapse_hinge_angles_deg"
        | "collapse_hinge_faces"
        | "collapse_sliding_angles_deg"
        | "collapse_sliding_senses"
        | "collapse_lifted_angles_deg"
        | "collapse_thrust_over_half_weight"
        | "collapse_crown_shear"
        | "collapse_crown_moment"
        | "collapse_work_loads"
        | "collapse_work_friction"
        | "collapse_work_residual"
        | "collapse_flow_violation" => &[Thickness, Friction, LoadFactor],
        "collapse_on_loading" => &[Thickness, Friction],
        "k_c_rotational" | "mu_rotational_mixed" | "mu_min" | "k_mixed_sliding" => &[Thresholds],
        "thrust_min"
        | "thrust_max"
        | "hinges_min_angles_deg"
        | "hinges_min_faces"
        | "hinges_max_angles_deg"
        | "hinges_max_faces" => &[Thrust],
        _ => return None,
    })
}

/// The finds of a plan's load cases.
fn study_finds(load_cases: &[LoadCase]) -> Vec<Find> {
    let mut finds: Vec<Find> = load_cases.iter().map(|l| l.find).collect();
    finds.sort_by_key(|f| f.as_str());
    finds.dedup();
    finds
}

fn frame_in_blocks(
    load_cases: &[LoadCase],
    rows: &[CaseResult],
    block_rows: usize,
    columns: Columns,
) -> Result<DataFrame> {
    let finds = study_finds(load_cases);
    let specs = || {
        let mut specs = input_columns(load_cases);
        specs.extend(answer_columns().into_iter().filter(|s| {
            columns != Columns::OfStudy
                || filled_by(s.name()).is_none_or(|by| by.iter().any(|f| finds.contains(f)))
        }));
        specs
    };
    specs_in_blocks(rows, block_rows, specs)
}

/// The table of rows of any type, in blocks of `block_rows` built in parallel, each with the
/// columns `specs` gives.
fn specs_in_blocks<'a, R: Sync>(
    rows: &'a [R],
    block_rows: usize,
    specs: impl Fn() -> Vec<Spec<'a, R>> + Sync,
) -> Result<DataFrame> {
    if rows.len() <= block_rows {
        return block_frame(rows, specs());
    }
    let blocks = rows
        .par_chunks(block_rows)
        .map(|b| block_frame(b, specs()))
        .collect::<Result<Vec<DataFrame>>>()?;
    stacked(blocks)
}

/// Frames of the same columns one under the other, each block kept as one chunk of every
/// column (the chunks stay aligned: one Arrow record batch per block); none gives an empty
/// frame.
fn stacked(blocks: Vec<DataFrame>) -> Result<DataFrame> {
    let mut blocks = blocks.into_iter();
    let mut df = blocks.next().unwrap_or_default();
    for b in blocks {
        df.vstack_mut_owned(b)?;
    }
    Ok(df)
}

/// The columns of results.parquet that echo the case's inputs, in order, for rows of type
/// `$row` whose field `$echo` holds the inputs' fields ([`crate::scene::Inputs`]).
macro_rules! input_columns {
    ($load_cases:expr, $row:ty, $echo:ident) => {{
        let load_cases: &'a [LoadCase] = $load_cases;
        vec![
            u64_col("case_id", |r: &$row| r.case_id),
            str_col("load_case", |r: &$row| {
                load_cases[r.load_case].name.as_str()
            }),
            str_col("load_kind", |r: &$row| {
                load_cases[r.load_case].kind.as_str()
            }),
            str_col("find", |r: &$row| r.$echo.find.as_str()),
            opt_f64("k", |r: &$row| r.$echo.k),
            opt_f64("t_over_r", |r: &$row| r.$echo.t_over_r),
            opt_f64("mu", |r: &$row| {
                if r.$echo.mu_infinite {
                    Some(f64::INFINITY)
                } else {
                    r.$echo.mu
                }
            }),
            f64_col("half_angle_deg", |r: &$row| r.$echo.half_angle_deg),
            str_col("weight", |r: &$row| r.$echo.weight.as_str()),
            opt_u32("voussoirs", |r: &$row| r.$echo.voussoirs),
            // Form and load case (docs/loads-and-geometries.md).
            str_col("shape", |r: &$row| r.$echo.shape),
            opt_f64("eccentricity", |r: &$row| r.$echo.eccentricity),
            str_col("joints", |r: &$row| r.$echo.joints),
            bool_col("keystone", |r: &$row| r.$echo.keystone),
            str_col("load", |r: &$row| r.$echo.load),
            opt_f64("at_deg", |r: &$row| r.$echo.at_deg),
            opt_f64("at_x", |r: &$row| r.$echo.at_x),
            opt_f64("load_width", |r: &$row| r.$echo.load_width),
            opt_f64("lambda", |r: &$row| r.$echo.lambda),
        ]
    }};
}

/// The input columns of full rows.
fn input_columns<'a>(load_cases: &'a [LoadCase]) -> Vec<Spec<'a, CaseResult>> {
    input_columns!(load_cases, CaseResult, solution)
}

/// Every column of compact `state` rows, in the order of [`input_columns`] followed by the
/// answer columns a `state` study holds ([`answer_columns`] filtered by [`filled_by`]).
fn state_columns<'a>(load_cases: &'a [LoadCase]) -> Vec<Spec<'a, StateCase>> {
    let mut specs = input_columns!(load_cases, StateCase, inputs);
    let a = |r: &'a StateCase| r.answer.as_ref();
    specs.extend([
        opt_str("outcome", |_: &StateCase| None),
        opt_str("regime", move |r| a(r).map(|a| a.regime.as_str())),
        opt_f64("thrust_r_min", move |r| a(r).and_then(|a| a.thrust_r_min)),
        opt_f64("thrust_r_max", move |r| a(r).and_then(|a| a.thrust_r_max)),
        opt_f64("thrust_s_min", move |r| a(r).and_then(|a| a.thrust_s_min)),
        opt_f64("thrust_s_max", move |r| a(r).and_then(|a| a.thrust_s_max)),
        str_col("status", |r: &StateCase| r.status().as_str()),
        opt_str("message", |r: &'a StateCase| r.message.as_deref()),
        f64_col("solve_time_us", |r: &StateCase| r.solve_time_us),
    ]);
    specs
}

/// The columns of results.parquet that hold the answer, in order.
fn answer_columns<'a>() -> Vec<Spec<'a, CaseResult>> {
    let s = |r: &'a CaseResult| &r.solution;
    vec![
        opt_str("outcome", move |r| s(r).outcome.map(|o| o.as_str())),
        opt_str("regime", move |r| s(r).regime.map(|g| g.as_str())),
        opt_f64("thrust_r_min", move |r| s(r).thrust_r_min),
        opt_f64("thrust_r_max", move |r| s(r).thrust_r_max),
        opt_f64("thrust_s_min", move |r| s(r).thrust_s_min),
        opt_f64("thrust_s_max", move |r| s(r).thrust_s_max),
        opt_f64("k_crit", move |r| s(r).k_crit),
        opt_f64("t_over_r_crit", move |r| s(r).t_over_r_crit),
        list_f64("k_windows_from", move |r| {
            s(r).k_windows.iter().map(|w| w.0).collect()
        }),
        list_f64("k_windows_to", move |r| window_ends(s(r))),
        opt_f64("k_windows_scanned_to", move |r| s(r).k_windows_scanned_to),
        opt_f64("k_windows_resolution", move |r| s(r).k_windows_resolution),
        opt_f64("mu_crit", move |r| s(r).mu_crit),
        opt_str("mechanism", move |r| s(r).mechanism.map(|m| m.as_str())),
        opt_f64("thrust_over_half_weight", move |r| {
            s(r).thrust_over_half_weight
        }),
        opt_f64("crown_moment", move |r| s(r).crown_moment),
        opt_f64("crown_shear", move |r| s(r).crown_shear),
        opt_f64("load_factor", move |r| s(r).load_factor),
        bool_col("load_factor_unbounded", move |r| s(r).load_factor_unbounded),
        list_f64("hinge_angles_deg", move |r| hinge_angles(&s(r).hinges)),
        list_str("hinge_faces", move |r| hinge_faces(&s(r).hinges)),
        list_f64("sliding_angles_deg", move |r| {
            sliding_angles(&s(r).sliding_joints)
        }),
        list_str("sliding_senses", move |r| {
            sliding_senses(&s(r).sliding_joints)
        }),
        opt_f64("work_loads", move |r| s(r).work_loads),
        opt_f64("work_friction", move |r| s(r).work_friction),
        opt_f64("work_residual", move |r| s(r).work_residual),
        opt_u32("mechanism_dof", move |r| s(r).mechanism_dof),
        opt_bool("mechanism_admissible", move |r| s(r).mechanism_admissible),
        opt_f64("critical_apex_shared", move |r| s(r).critical_apex_shared),
        opt_str("gap", move |r| s(r).gap.map(|g| g.as_str())),
        opt_f64("collapse_value", move |r| s(r).collapse_value),
        opt_f64("gap_width", move |r| s(r).gap_width),
        opt_f64("gap_searched_to", move |r| s(r).gap_searched_to),
        opt_str("collapse_mechanism", move |r| {
            s(r).collapse_mechanism.map(|m| m.as_str())
        }),
        list_f64("collapse_hinge_angles_deg", move |r| {
            hinge_angles(&s(r).collapse_hinges)
        }),
        list_str("collapse_hinge_faces", move |r| {
            hinge_faces(&s(r).collapse_hinges)
        }),
        list_f64("collapse_sliding_angles_deg", move |r| {
            sliding_angles(&s(r).collapse_sliding_joints)
        }),
        list_str("collapse_sliding_senses", move |r| {
            sliding_senses(&s(r).collapse_sliding_joints)
        }),
        list_f64("collapse_lifted_angles_deg", move |r| {
            s(r).collapse_lifted_joints.clone()
        }),
        opt_f64("collapse_thrust_over_half_weight", move |r| {
            s(r).collapse_thrust_over_half_weight
        }),
        opt_f64("collapse_crown_shear", move |r| s(r).collapse_crown_shear),
        opt_f64("collapse_crown_moment", move |r| s(r).collapse_crown_moment),
        opt_f64("collapse_work_loads", move |r| s(r).collapse_work_loads),
        opt_f64("collapse_work_friction", move |r| {
            s(r).collapse_work_friction
        }),
        opt_f64("collapse_work_residual", move |r| {
            s(r).collapse_work_residual
        }),
        opt_f64("collapse_flow_violation", move |r| {
            s(r).collapse_flow_violation
        }),
        opt_f64("collapse_on_loading", move |r| s(r).collapse_on_loading),
        opt_f64("k_c_rotational", move |r| s(r).k_c_rotational),
        opt_f64("mu_rotational_mixed", move |r| s(r).mu_rotational_mixed),
        opt_f64("mu_min", move |r| s(r).mu_min),
        opt_f64("k_mixed_sliding", move |r| s(r).k_mixed_sliding),
        opt_f64("thrust_min", move |r| s(r).thrust_min),
        opt_f64("thrust_max", move |r| s(r).thrust_max),
        list_f64("hinges_min_angles_deg", move |r| {
            hinge_angles(&s(r).hinges_min)
        }),
        list_str("hinges_min_faces", move |r| hinge_faces(&s(r).hinges_min)),
        list_f64("hinges_max_angles_deg", move |r| {
            hinge_angles(&s(r).hinges_max)
        }),
        list_str("hinges_max_faces", move |r| hinge_faces(&s(r).hinges_max)),
        str_col("status", |r: &CaseResult| r.status.as_str()),
        opt_str("message", |r: &'a CaseResult| r.message.as_deref()),
        f64_col("solve_time_us", move |r| s(r).solve_time_us),
    ]
}

/// Groups of columns of a block built side by side (on the current rayon pool), each in one
/// pass over the block's rows: a fixed number, so that the work, not the table, depends on
/// the threads. Every column is the same whatever the grouping.
const COLUMN_GROUPS: usize = 4;

/// One block of the results table: its columns dealt round-robin into [`COLUMN_GROUPS`]
/// groups built in parallel, each group in one pass over the rows (every column of the
/// group read while the row is in cache), then put back in order.
fn block_frame<'a, R: Sync>(rows: &'a [R], specs: Vec<Spec<'a, R>>) -> Result<DataFrame> {
    let mut groups: Vec<Vec<(usize, Spec<'a, R>)>> =
        (0..COLUMN_GROUPS).map(|_| Vec::new()).collect();
    for (i, s) in specs.into_iter().enumerate() {
        groups[i % COLUMN_GROUPS].push((i, s));
    }
    let built = groups
        .into_par_iter()
        .map(|mut group| {
            for (_, s) in group.iter_mut() {
                s.reserve(rows.len());
            }
            for r in rows {
                for (_, s) in group.iter_mut() {
                    s.push(r);
                }
            }
            group
                .into_iter()
                .map(|(i, s)| (i, s.add_to(TableBuilder::new()).columns))
                .collect::<Vec<_>>()
        })
        .collect::<Vec<_>>();
    let mut built: Vec<(usize, Vec<polars::prelude::Column>)> =
        built.into_iter().flatten().collect();
    built.sort_by_key(|(i, _)| *i);
    Ok(DataFrame::new_infer_height(
        built.into_iter().flat_map(|(_, c)| c).collect(),
    )?)
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
        let whole = frame_in_blocks(
            &plan.manifest.load_cases,
            &rows,
            usize::MAX,
            Columns::OfStudy,
        )
        .unwrap();
        let blocks =
            frame_in_blocks(&plan.manifest.load_cases, &rows, 7, Columns::OfStudy).unwrap();
        assert_eq!(whole.height(), 143);
        assert_eq!(whole.get_column_names(), blocks.get_column_names());
        // Solve times differ between runs of a case but not between two tables of one run.
        assert!(whole.equals_missing(&blocks));
    }

    /// The compact rows of separable `state` grids (several arches, two load cases, infinite
    /// friction, centreline weights, and a run stopped before it began, whose every row is
    /// an error) give the table of their full rows.
    #[test]
    fn compact_state_rows_give_the_table_of_their_full_rows() {
        let studies = [
            "grid:\n  k: {from: 1.05, to: 1.4, steps: 9}\n  mu: {values: [0.2, 0.35, 0.6, inf]}\n  half_angle_deg: {values: [60, 90, 120]}\n",
            "arch:\n  weight: centreline\ngrid:\n  k: {values: [1.1, 1.3]}\n  mu: {values: [0.3, 0.5]}\n  voussoirs: {values: [5, 8, continuum]}\nload_cases:\n  - {name: a, kind: self_weight}\n  - {name: b, kind: self_weight}\n",
        ];
        let silent: &dyn crate::progress::Progress = &crate::progress::Silent;
        for text in studies {
            let m =
                crate::manifest::parse(&format!("name: a\n{text}"), Path::new("a.yaml")).unwrap();
            let plan = crate::plan::build(m).unwrap();
            assert_eq!(engine::GridPath::of(&plan), engine::GridPath::Separable);
            for progress in [silent, &crate::progress::StopNow] {
                let mut rows = engine::Rows::default();
                engine::analyse_rows(&plan, progress, &mut rows);
                let engine::Rows::States(states) = &rows else {
                    panic!("a separable grid gives compact rows");
                };
                assert_eq!(states.len(), plan.cases.len());
                let compact = state_results_frame(&plan, states).unwrap();
                let full = rows.into_results();
                let expected = results_frame(&plan, &full).unwrap();
                assert_eq!(compact.schema(), expected.schema());
                assert!(compact.equals_missing(&expected), "{compact}\n{expected}");
                let ok = full
                    .iter()
                    .filter(|r| r.status == engine::Status::Ok)
                    .count();
                assert_eq!(
                    ok,
                    if progress.stopped() {
                        0
                    } else {
                        plan.cases.len()
                    }
                );
                // The regimes are those of the scenes solved one by one.
                for r in full.iter().filter(|r| r.status == engine::Status::Ok) {
                    let alone = crate::scene::solve(&plan.cases[r.case_id as usize].scene);
                    assert_eq!(r.solution.regime, alone.regime);
                    assert_eq!(r.solution.thrust_s_max, alone.thrust_s_max);
                }
            }
        }
    }

    /// Every find of a small study: the columns a study leaves out are null in every row
    /// of the full table, and the ones it keeps are exactly those its finds fill.
    #[test]
    fn a_study_writes_the_columns_its_finds_fill() {
        let cases = [
            (
                "state",
                "grid:\n  k: {values: [1.05, 1.12, 1.3]}\n  mu: {values: [0.3, 0.5, inf]}\n",
            ),
            (
                "thickness",
                "find: thickness\ngrid:\n  mu: {values: [0.2, 0.35, 0.5]}\n",
            ),
            (
                "friction",
                "find: friction\ngrid:\n  k: {values: [1.1, 1.2, 1.4]}\n",
            ),
            (
                "thrust",
                "find: thrust\ngrid:\n  k: {values: [1.2, 1.4]}\n  mu: {values: [0.3, inf]}\n",
            ),
            (
                "thresholds",
                "find: thresholds\ngrid:\n  half_angle_deg: {values: [60, 90]}\n",
            ),
            (
                "load_factor",
                "find: load_factor\nload_cases:\n  - {name: h, kind: horizontal}\n  - {name: p, kind: point, at_deg: 30}\ngrid:\n  k: {values: [1.2, 1.4]}\n  mu: {values: [0.3, 0.6]}\n",
            ),
            (
                "state and horizontal",
                "grid:\n  k: {values: [1.2, 1.4]}\n  mu: {values: [0.3, 0.6]}\nload_cases:\n  - {name: g, kind: self_weight}\n  - {name: h, kind: horizontal, lambda: 0.05}\n",
            ),
        ];
        for (what, text) in cases {
            let m =
                crate::manifest::parse(&format!("name: a\n{text}"), Path::new("a.yaml")).unwrap();
            let plan = crate::plan::build(m).unwrap();
            let rows = engine::run(&plan, &crate::progress::Silent);
            let all = frame_in_blocks(&plan.manifest.load_cases, &rows, BLOCK_ROWS, Columns::All)
                .unwrap();
            let kept = results_frame(&plan, &rows).unwrap();
            for c in all.columns() {
                let name = c.name().as_str();
                let filled = c.null_count() < c.len()
                    && !(c.dtype().is_list()
                        && c.list()
                            .unwrap()
                            .iter()
                            .all(|l| l.is_none_or(|s| s.is_empty())))
                    && !(name == "load_factor_unbounded"
                        && c.bool().unwrap().iter().all(|b| b != Some(true)));
                let is_kept = kept.column(name).is_ok();
                assert!(
                    !filled || is_kept,
                    "{what}: `{name}` is filled but left out"
                );
            }
            let finds = study_finds(&plan.manifest.load_cases);
            for c in kept.columns() {
                let name = c.name().as_str();
                assert!(
                    filled_by(name).is_none_or(|by| by.iter().any(|f| finds.contains(f))),
                    "{what}: `{name}` kept though no find fills it"
                );
            }
            assert!(kept.width() < all.width(), "{what}: nothing left out");
        }
    }
}
