//! results.parquet read back into the engine's rows ([`CaseResult`]), every column typed into
//! its field of [`Solution`]: how `archstudy merge` gives the stages after the engine the
//! rows of shards analysed elsewhere. A float is stored as its 64 bits, so it reads back
//! exactly; the rows rebuild the same results table.

use super::{bool_column, f64_column, list_f64_column, list_str_column, read_parquet, str_column};
use crate::analysis::gap::GapStatus;
use crate::analysis::windows::Span;
use crate::analysis::{Face, Hinge, MechanismKind, Regime, Sense, SlidingJoint};
use crate::engine::{CaseResult, Status};
use crate::model::WeightModel;
use crate::plan::Plan;
use crate::scene::{Find, Outcome, Solution};
use anyhow::{Context, Result, bail};
use polars::prelude::{DataFrame, SerReader};
use std::path::Path;

/// The columns of one results table, each read once; a column the study's finds do not fill
/// (see [`super::filled_by`]) reads as nulls.
struct Columns<'a> {
    df: &'a DataFrame,
    rows: usize,
}

impl Columns<'_> {
    fn has(&self, name: &str) -> bool {
        self.df.column(name).is_ok()
    }
    fn f64(&self, name: &str) -> Result<Vec<Option<f64>>> {
        if self.has(name) {
            f64_column(self.df, name)
        } else {
            Ok(vec![None; self.rows])
        }
    }
    fn str(&self, name: &str) -> Result<Vec<Option<String>>> {
        if self.has(name) {
            str_column(self.df, name)
        } else {
            Ok(vec![None; self.rows])
        }
    }
    fn list_f64(&self, name: &str) -> Result<Vec<Vec<f64>>> {
        if self.has(name) {
            list_f64_column(self.df, name)
        } else {
            Ok(vec![Vec::new(); self.rows])
        }
    }
    fn list_str(&self, name: &str) -> Result<Vec<Vec<String>>> {
        if self.has(name) {
            list_str_column(self.df, name)
        } else {
            Ok(vec![Vec::new(); self.rows])
        }
    }
}

/// A stored name parsed into one of `all`, or an error naming the column and the value.
fn parse_name<T: Copy>(
    all: &[T],
    name: impl Fn(T) -> &'static str,
    column: &str,
    value: &str,
) -> Result<T> {
    all.iter()
        .copied()
        .find(|v| name(*v) == value)
        .with_context(|| format!("column `{column}`: unknown value `{value}`"))
}

fn opt_name<T: Copy>(
    all: &[T],
    name: impl Fn(T) -> &'static str,
    column: &str,
    value: Option<&String>,
) -> Result<Option<T>> {
    value.map(|v| parse_name(all, name, column, v)).transpose()
}

fn hinges(column: &str, angles: &[f64], faces: &[String]) -> Result<Vec<Hinge>> {
    if angles.len() != faces.len() {
        bail!(
            "column `{column}`: {} angles but {} faces",
            angles.len(),
            faces.len()
        );
    }
    let all = [Face::Intrados, Face::Extrados];
    angles
        .iter()
        .zip(faces)
        .map(|(&angle_deg, f)| {
            Ok(Hinge {
                angle_deg,
                face: parse_name(&all, Face::as_str, column, f)?,
            })
        })
        .collect()
}

fn sliding(angles: &[f64], senses: &[String]) -> Result<Vec<SlidingJoint>> {
    if angles.len() != senses.len() {
        bail!(
            "column `sliding_senses`: {} angles but {} senses",
            angles.len(),
            senses.len()
        );
    }
    let all = [Sense::Outward, Sense::Inward];
    angles
        .iter()
        .zip(senses)
        .map(|(&angle_deg, s)| {
            Ok(SlidingJoint {
                angle_deg,
                sense: parse_name(&all, Sense::as_str, "sliding_senses", s)?,
            })
        })
        .collect()
}

/// A stored name that must be the one the plan's case has (`shape`, `joints`, `load`).
fn same(column: &str, stored: Option<&String>, planned: &'static str) -> Result<&'static str> {
    match stored {
        Some(s) if s == planned => Ok(planned),
        other => bail!(
            "column `{column}` holds {other:?} where the manifest's case has `{planned}`: the \
             file is not a result of this manifest"
        ),
    }
}

/// The answer columns of results.parquet that hold one float, each with its field.
const ANSWER_F64: [&str; 36] = [
    "collapse_value",
    "gap_width",
    "gap_searched_to",
    "collapse_thrust_over_half_weight",
    "collapse_crown_shear",
    "collapse_crown_moment",
    "collapse_work_loads",
    "collapse_work_friction",
    "collapse_work_residual",
    "collapse_flow_violation",
    "collapse_on_loading",
    "k_windows_scanned_to",
    "k_windows_resolution",
    "thrust_r_min",
    "thrust_r_max",
    "thrust_s_min",
    "thrust_s_max",
    "k_crit",
    "t_over_r_crit",
    "mu_crit",
    "thrust_over_half_weight",
    "crown_moment",
    "crown_shear",
    "load_factor",
    "work_loads",
    "work_friction",
    "work_residual",
    "critical_apex_shared",
    "k_c_rotational",
    "mu_rotational_mixed",
    "mu_min",
    "k_mixed_sliding",
    "thrust_min",
    "thrust_max",
    "k",
    "t_over_r",
];

/// The field of a column of [`ANSWER_F64`].
fn answer_f64<'s>(s: &'s mut Solution, column: &str) -> Option<&'s mut Option<f64>> {
    Some(match column {
        "thrust_r_min" => &mut s.thrust_r_min,
        "thrust_r_max" => &mut s.thrust_r_max,
        "thrust_s_min" => &mut s.thrust_s_min,
        "thrust_s_max" => &mut s.thrust_s_max,
        "k_crit" => &mut s.k_crit,
        "k_windows_scanned_to" => &mut s.k_windows_scanned_to,
        "k_windows_resolution" => &mut s.k_windows_resolution,
        "t_over_r_crit" => &mut s.t_over_r_crit,
        "mu_crit" => &mut s.mu_crit,
        "thrust_over_half_weight" => &mut s.thrust_over_half_weight,
        "crown_moment" => &mut s.crown_moment,
        "crown_shear" => &mut s.crown_shear,
        "load_factor" => &mut s.load_factor,
        "work_loads" => &mut s.work_loads,
        "work_friction" => &mut s.work_friction,
        "work_residual" => &mut s.work_residual,
        "critical_apex_shared" => &mut s.critical_apex_shared,
        "k_c_rotational" => &mut s.k_c_rotational,
        "mu_rotational_mixed" => &mut s.mu_rotational_mixed,
        "mu_min" => &mut s.mu_min,
        "k_mixed_sliding" => &mut s.k_mixed_sliding,
        "thrust_min" => &mut s.thrust_min,
        "thrust_max" => &mut s.thrust_max,
        "k" => &mut s.k,
        "t_over_r" => &mut s.t_over_r,
        "collapse_value" => &mut s.collapse_value,
        "gap_width" => &mut s.gap_width,
        "gap_searched_to" => &mut s.gap_searched_to,
        "collapse_thrust_over_half_weight" => &mut s.collapse_thrust_over_half_weight,
        "collapse_crown_shear" => &mut s.collapse_crown_shear,
        "collapse_crown_moment" => &mut s.collapse_crown_moment,
        "collapse_work_loads" => &mut s.collapse_work_loads,
        "collapse_work_friction" => &mut s.collapse_work_friction,
        "collapse_work_residual" => &mut s.collapse_work_residual,
        "collapse_flow_violation" => &mut s.collapse_flow_violation,
        "collapse_on_loading" => &mut s.collapse_on_loading,
        _ => return None,
    })
}

/// The windows of a thickness find from their stored ends; an upper end at the end of the
/// scan is a window still open there.
pub(super) fn windows(from: &[f64], to: &[f64], scanned_to: Option<f64>) -> Result<Vec<Span>> {
    if from.len() != to.len() {
        bail!(
            "columns `k_windows_from` and `k_windows_to` hold {} and {} values in one row",
            from.len(),
            to.len()
        );
    }
    Ok(from
        .iter()
        .zip(to)
        .map(|(&a, &b)| (a, (Some(b) != scanned_to).then_some(b)))
        .collect())
}

/// A list column of angles and its list column of faces or senses.
type AnglesAndNames = (Vec<Vec<f64>>, Vec<Vec<String>>);

/// Every column of a results table, read once into typed vectors.
struct Stored {
    ids: Vec<u64>,
    floats: Vec<(&'static str, Vec<Option<f64>>)>,
    strs: std::collections::HashMap<&'static str, Vec<Option<String>>>,
    num: std::collections::HashMap<&'static str, Vec<Option<f64>>>,
    lists: std::collections::HashMap<&'static str, AnglesAndNames>,
    unbounded: Vec<Option<bool>>,
    admissible: Vec<Option<bool>>,
    /// The windows of a thickness find: lower and upper ends.
    windows: (Vec<Vec<f64>>, Vec<Vec<f64>>),
    /// The joints that lift off in the mechanism of the first complete solution.
    lifted: Vec<Vec<f64>>,
}

/// The string columns read into a [`Stored`].
const STRS: [&str; 13] = [
    "gap",
    "collapse_mechanism",
    "load_case",
    "find",
    "weight",
    "shape",
    "joints",
    "load",
    "outcome",
    "regime",
    "mechanism",
    "status",
    "message",
];
/// The other numeric input columns, and `mechanism_dof` and `solve_time_us`.
const NUMS: [&str; 10] = [
    "mu",
    "half_angle_deg",
    "voussoirs",
    "eccentricity",
    "at_deg",
    "at_x",
    "load_width",
    "lambda",
    "mechanism_dof",
    "solve_time_us",
];
/// The list columns: angles and their faces or senses.
const LISTS: [(&str, &str); 6] = [
    ("collapse_hinge_angles_deg", "collapse_hinge_faces"),
    ("collapse_sliding_angles_deg", "collapse_sliding_senses"),
    ("hinge_angles_deg", "hinge_faces"),
    ("sliding_angles_deg", "sliding_senses"),
    ("hinges_min_angles_deg", "hinges_min_faces"),
    ("hinges_max_angles_deg", "hinges_max_faces"),
];

impl Stored {
    fn read(df: &DataFrame) -> Result<Self> {
        let c = Columns {
            df,
            rows: df.height(),
        };
        let mut strs = std::collections::HashMap::new();
        for n in STRS {
            strs.insert(n, c.str(n)?);
        }
        let mut num = std::collections::HashMap::new();
        for n in NUMS {
            num.insert(n, c.f64(n)?);
        }
        let mut lists = std::collections::HashMap::new();
        for (a, b) in LISTS {
            lists.insert(a, (c.list_f64(a)?, c.list_str(b)?));
        }
        Ok(Stored {
            ids: super::u64_column(df, "case_id")?,
            floats: ANSWER_F64
                .iter()
                .map(|n| Ok((*n, c.f64(n)?)))
                .collect::<Result<_>>()?,
            strs,
            num,
            lists,
            unbounded: if c.has("load_factor_unbounded") {
                bool_column(df, "load_factor_unbounded")?
            } else {
                vec![None; c.rows]
            },
            admissible: if c.has("mechanism_admissible") {
                bool_column(df, "mechanism_admissible")?
            } else {
                vec![None; c.rows]
            },
            windows: (c.list_f64("k_windows_from")?, c.list_f64("k_windows_to")?),
            lifted: c.list_f64("collapse_lifted_angles_deg")?,
        })
    }

    fn s(&self, column: &str, i: usize) -> Option<&String> {
        self.strs.get(column).and_then(|v| v[i].as_ref())
    }

    fn n(&self, column: &str, i: usize) -> Option<f64> {
        self.num.get(column).and_then(|v| v[i])
    }

    fn hinges(&self, angles: &'static str, faces: &str, i: usize) -> Result<Vec<Hinge>> {
        let (a, f) = self
            .lists
            .get(angles)
            .map_or((&[][..], &[][..]), |(a, f)| (&a[i][..], &f[i][..]));
        hinges(faces, a, f)
    }

    /// The solution of row `i`: the inputs of `planned` (the manifest's case), checked
    /// against the stored ones, and the stored answer.
    fn solution(&self, i: usize, planned: Solution) -> Result<Solution> {
        let name = |column: &str| self.s(column, i).map_or("", String::as_str);
        let mu = self.n("mu", i);
        let slides = |column: &str| {
            self.lists
                .get(column)
                .map_or((&[][..], &[][..]), |(a, s)| (&a[i][..], &s[i][..]))
        };
        let (sa, ss) = slides("sliding_angles_deg");
        let (ca, cs) = slides("collapse_sliding_angles_deg");
        let mut s = Solution {
            find: parse_name(&Find::ALL, Find::as_str, "find", name("find"))?,
            mu: mu.filter(|m| !m.is_infinite()),
            mu_infinite: mu.is_some_and(f64::is_infinite),
            half_angle_deg: self.n("half_angle_deg", i).context("no half_angle_deg")?,
            weight: parse_name(
                &[WeightModel::Annular, WeightModel::Centreline],
                WeightModel::as_str,
                "weight",
                name("weight"),
            )?,
            voussoirs: self.n("voussoirs", i).map(|v| v as u32),
            shape: same("shape", self.s("shape", i), planned.shape)?,
            eccentricity: self.n("eccentricity", i),
            joints: same("joints", self.s("joints", i), planned.joints)?,
            keystone: planned.keystone,
            load: same("load", self.s("load", i), planned.load)?,
            at_deg: self.n("at_deg", i),
            at_x: self.n("at_x", i),
            load_width: self.n("load_width", i),
            lambda: self.n("lambda", i),
            outcome: opt_name(
                &Outcome::ALL,
                Outcome::as_str,
                "outcome",
                self.s("outcome", i),
            )?,
            regime: opt_name(&Regime::ALL, Regime::as_str, "regime", self.s("regime", i))?,
            mechanism: opt_name(
                &[
                    MechanismKind::Rotational,
                    MechanismKind::Mixed,
                    MechanismKind::Sliding,
                ],
                MechanismKind::as_str,
                "mechanism",
                self.s("mechanism", i),
            )?,
            hinges: self.hinges("hinge_angles_deg", "hinge_faces", i)?,
            sliding_joints: sliding(sa, ss)?,
            gap: opt_name(&GapStatus::ALL, GapStatus::as_str, "gap", self.s("gap", i))?,
            collapse_mechanism: opt_name(
                &[
                    MechanismKind::Rotational,
                    MechanismKind::Mixed,
                    MechanismKind::Sliding,
                ],
                MechanismKind::as_str,
                "collapse_mechanism",
                self.s("collapse_mechanism", i),
            )?,
            collapse_hinges: self.hinges("collapse_hinge_angles_deg", "collapse_hinge_faces", i)?,
            collapse_sliding_joints: sliding(ca, cs)?,
            collapse_lifted_joints: self.lifted[i].clone(),
            hinges_min: self.hinges("hinges_min_angles_deg", "hinges_min_faces", i)?,
            hinges_max: self.hinges("hinges_max_angles_deg", "hinges_max_faces", i)?,
            load_factor_unbounded: self.unbounded[i].unwrap_or(false),
            mechanism_dof: self.n("mechanism_dof", i).map(|v| v as u32),
            mechanism_admissible: self.admissible[i],
            solve_time_us: self.n("solve_time_us", i).unwrap_or(0.0),
            ..planned
        };
        for (column, values) in &self.floats {
            if let Some(field) = answer_f64(&mut s, column) {
                *field = values[i];
            }
        }
        s.k_windows = windows(
            &self.windows.0[i],
            &self.windows.1[i],
            s.k_windows_scanned_to,
        )?;
        Ok(s)
    }
}

/// Reads the rows of results.parquet written for (a slice of) `plan` back into the engine's
/// rows, in file order. Every row's case id must be a case of `plan` (of the slice), and its load case and
/// form must be that case's.
pub fn read_case_results(plan: &Plan, path: &Path) -> Result<Vec<CaseResult>> {
    let df = read_parquet(path)?;
    let mut out = Vec::with_capacity(df.height());
    // Blocks of rows: the typed columns of one block are dropped before the next is read.
    for offset in (0..df.height()).step_by(READ_BLOCK_ROWS) {
        let block = df.slice(offset as i64, READ_BLOCK_ROWS);
        let rows = read_frame(plan, &block)
            .with_context(|| format!("in {} (rows from {offset})", path.display()))?;
        out.extend(rows);
    }
    Ok(out)
}

/// [`read_case_results`] of the rows `offset .. offset + len` of the file only (the row
/// groups that hold them are decoded); `plan` holds (at least) their cases.
pub fn read_case_results_rows(
    plan: &Plan,
    path: &Path,
    (offset, len): (usize, usize),
) -> Result<Vec<CaseResult>> {
    let df = read_slice(path, (offset, len))?;
    read_frame(plan, &df).with_context(|| format!("in {} (rows from {offset})", path.display()))
}

/// Every column of the rows `offset .. offset + len` of a Parquet file.
fn read_slice(path: &Path, (offset, len): (usize, usize)) -> Result<polars::prelude::DataFrame> {
    let file =
        std::fs::File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    polars::prelude::ParquetReader::new(file)
        .with_slice(Some((offset, len)))
        .finish()
        .with_context(|| format!("cannot read {} as Parquet", path.display()))
}

/// [`read_case_results_rows`] of a table written elsewhere (a shard's), checked to be the
/// table this build writes for the rows it reads back as: the same columns in the same order,
/// of the same types, with the same values. A value the rows do not carry (a grid value or load case other than
/// the plan's) or a column dropped, renamed or retyped is an error naming the column. `plan`
/// holds exactly the cases of the rows, in order.
pub fn read_foreign_case_results_rows(
    plan: &Plan,
    path: &Path,
    (offset, len): (usize, usize),
) -> Result<Vec<CaseResult>> {
    let df = read_slice(path, (offset, len))?;
    let rows = read_frame(plan, &df)
        .with_context(|| format!("in {} (rows from {offset})", path.display()))?;
    for (i, (case, r)) in plan.cases.iter().zip(&rows).enumerate() {
        if let Some(name) = differs_from_plan(&case.scene, &r.solution) {
            bail!(
                "row {} (case {}): `{name}` is not the plan's value for that case",
                offset + i,
                case.id
            );
        }
    }
    same_as_written(plan, &df, &rows)
        .with_context(|| format!("in {} (rows from {offset})", path.display()))?;
    Ok(rows)
}

/// The stored frame against the frame this build writes for `rows` of `plan`; Err names the
/// first column that differs.
/// The first input column of a stored answer that is not the value its case's scene gives
/// (K, μ, the arch): a row carries its inputs back, so a forged grid value would otherwise
/// be read and written again as if it were the plan's.
fn differs_from_plan(
    scene: &crate::scene::Scene,
    stored: &crate::scene::Solution,
) -> Option<&'static str> {
    let want = crate::scene::Solution::empty(scene);
    let same = |a: Option<f64>, b: Option<f64>| a.map(f64::to_bits) == b.map(f64::to_bits);
    [
        ("k", same(want.k, stored.k)),
        ("t_over_r", same(want.t_over_r, stored.t_over_r)),
        (
            "mu",
            same(want.mu, stored.mu) && want.mu_infinite == stored.mu_infinite,
        ),
        (
            "half_angle_deg",
            want.half_angle_deg.to_bits() == stored.half_angle_deg.to_bits(),
        ),
        ("voussoirs", want.voussoirs == stored.voussoirs),
        ("weight", want.weight == stored.weight),
        ("shape", want.shape == stored.shape),
        ("eccentricity", same(want.eccentricity, stored.eccentricity)),
        ("joints", want.joints == stored.joints),
        ("lambda", same(want.lambda, stored.lambda)),
    ]
    .into_iter()
    .find(|(_, ok)| !ok)
    .map(|(name, _)| name)
}

fn same_as_written(plan: &Plan, stored: &DataFrame, rows: &[CaseResult]) -> Result<()> {
    let again = super::results_frame(plan, rows)?;
    let names = |df: &DataFrame| -> Vec<String> {
        df.get_column_names()
            .iter()
            .map(|n| n.to_string())
            .collect()
    };
    let (have, want) = (names(stored), names(&again));
    if have != want {
        let missing: Vec<&String> = want.iter().filter(|n| !have.contains(n)).collect();
        let extra: Vec<&String> = have.iter().filter(|n| !want.contains(n)).collect();
        bail!(
            "the columns are not those of a results table of this manifest (missing: \
             {missing:?}; not expected: {extra:?}; or in another order)"
        );
    }
    for col in again.columns() {
        let name = col.name().as_str();
        let s = stored.column(name)?;
        if s.dtype() != col.dtype() {
            bail!(
                "column `{name}` is of type {}, a results table's is {}",
                s.dtype(),
                col.dtype()
            );
        }
        if !s
            .as_materialized_series()
            .equals_missing(col.as_materialized_series())
        {
            bail!(
                "column `{name}` holds values that its rows do not give (a value the plan \
                 fixes, such as a grid value or load case, or one that contradicts the \
                 other columns of its row)"
            );
        }
    }
    Ok(())
}

/// The case ids of results.parquet, in file order (no other column is decoded).
pub fn read_case_ids(path: &Path) -> Result<Vec<u64>> {
    let df = super::read_parquet_columns(path, &["case_id"])?;
    super::u64_column(&df, "case_id").with_context(|| format!("in {}", path.display()))
}

/// Rows of results.parquet typed at a time by [`read_case_results`].
const READ_BLOCK_ROWS: usize = 1 << 16;

fn read_frame(plan: &Plan, df: &DataFrame) -> Result<Vec<CaseResult>> {
    let stored = Stored::read(df)?;
    let mut out = Vec::with_capacity(stored.ids.len());
    // A slice of a plan holds the cases from its first id on.
    let first = plan.cases.first().map_or(0, |c| c.id);
    for (i, &id) in stored.ids.iter().enumerate() {
        let row = || format!("row {i} (case {id})");
        let case = id
            .checked_sub(first)
            .and_then(|n| usize::try_from(n).ok())
            .and_then(|n| plan.cases.get(n))
            .filter(|case| case.id == id)
            .with_context(|| format!("{}: the manifest's plan has no such case", row()))?;
        let lc_name = &plan.manifest.load_cases[case.load_case].name;
        let stored_lc = stored.s("load_case", i);
        if stored_lc != Some(lc_name) {
            bail!(
                "{}: load case {stored_lc:?}, the manifest's is `{lc_name}`",
                row()
            );
        }
        let solution = stored
            .solution(i, Solution::empty(&case.scene))
            .with_context(row)?;
        let status = match stored.s("status", i).map(String::as_str) {
            Some("ok") => Status::Ok,
            Some("error") => Status::Error,
            other => bail!(
                "{}: column `status` holds {other:?}, not ok or error",
                row()
            ),
        };
        out.push(CaseResult {
            case_id: id,
            load_case: case.load_case,
            solution,
            status,
            message: stored.s("message", i).cloned(),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine;
    use std::path::Path;

    /// Every find's rows, written and read back, rebuild the same table and the same rows.
    #[test]
    fn rows_read_back_rebuild_the_same_table() {
        let studies = [
            "name: a\ngrid:\n  k: {from: 1.05, to: 1.4, steps: 5}\n  mu: {values: [0.2, 0.5, inf]}\n",
            "name: b\nfind: thickness\ngrid:\n  voussoirs: {values: [6, continuum]}\n  mu: {values: [0.3, 0.6, inf]}\n",
            "name: c\nfind: load_factor\nload_cases:\n  - {name: h, kind: horizontal}\n  - {name: p, kind: point, at_deg: 30}\ngrid:\n  k: {values: [1.2, 1.4]}\n  mu: {values: [0.3, 0.6]}\n",
            "name: d\nfind: thrust\ngrid:\n  k: {values: [1.2, 1.35]}\n  mu: {values: [0.5, inf]}\n",
            "name: e\nfind: thresholds\ngrid:\n  half_angle_deg: {values: [60, 90]}\n",
            "name: f\nfind: friction\ngrid:\n  k: {values: [1.15, 1.3]}\n",
        ];
        let dir = std::env::temp_dir().join(format!("archstudy-cases-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for text in studies {
            let plan =
                crate::plan::build(crate::manifest::parse(text, Path::new("s.yaml")).unwrap())
                    .unwrap();
            let rows = engine::run(&plan, &crate::progress::Silent);
            let path = dir.join("results.parquet");
            super::super::write_parquet(
                &mut super::super::results_frame(&plan, &rows).unwrap(),
                &path,
            )
            .unwrap();
            let back = read_case_results(&plan, &path).unwrap();
            assert_eq!(back.len(), rows.len(), "{text}");
            for (a, b) in rows.iter().zip(&back) {
                let mut a_sol = a.solution.clone();
                // Not stored: the sliding joints of the thrust find's extreme states.
                a_sol.sliding_joints_min.clear();
                a_sol.sliding_joints_max.clear();
                assert_eq!(format!("{a_sol:?}"), format!("{:?}", b.solution), "{text}");
                assert_eq!(
                    (a.case_id, a.load_case, a.status, &a.message),
                    (b.case_id, b.load_case, b.status, &b.message)
                );
            }
            let again = super::super::results_frame(&plan, &back).unwrap();
            assert!(
                again.equals_missing(&super::super::results_frame(&plan, &rows).unwrap()),
                "{text}"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_row_of_another_manifest_is_refused() {
        let p = |t: &str| {
            crate::plan::build(crate::manifest::parse(t, Path::new("s.yaml")).unwrap()).unwrap()
        };
        let plan = p("name: a\ngrid:\n  k: {values: [1.2, 1.3]}\n  mu: {values: [0.4]}\n");
        let other = p(
            "name: a\nload_cases: [{name: wind, kind: horizontal, lambda: 0.01}]\ngrid:\n  k: {values: [1.2, 1.3]}\n  mu: {values: [0.4]}\n",
        );
        let rows = engine::run(&other, &crate::progress::Silent);
        let df = super::super::results_frame(&other, &rows).unwrap();
        let e = format!("{:#}", read_frame(&plan, &df).unwrap_err());
        assert!(
            e.contains("row 0 (case 0)") && e.contains("load case"),
            "{e}"
        );
    }

    /// A merge reads a shard a chunk at a time: a read of one chunk's rows decodes only the
    /// row groups that hold them. The row groups of the other chunks are overwritten with
    /// garbage: a reader that decoded them would fail.
    #[test]
    fn a_chunk_read_decodes_only_its_own_row_groups() {
        use polars_parquet::read::read_metadata;
        use std::io::{Seek, SeekFrom, Write};
        let text = "name: a\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 6}\n  mu: {from: 0.2, to: 0.8, steps: 5}\n";
        let plan =
            crate::plan::build(crate::manifest::parse(text, Path::new("s.yaml")).unwrap()).unwrap();
        let rows = engine::run(&plan, &crate::progress::Silent);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("results.parquet");
        // Three chunks of 10 rows, each appended as its own row group.
        let chunk = |i: u64| crate::plan::build_slice(plan.manifest.clone(), i * 10..i * 10 + 10);
        let frame = |i: u64| {
            let at = (i * 10) as usize..(i * 10 + 10) as usize;
            super::super::results_frame(&chunk(i), &rows[at]).unwrap()
        };
        let mut w = super::super::ParquetAppender::create(&path, &mut frame(0)).unwrap();
        w.append(&mut frame(1)).unwrap();
        w.append(&mut frame(2)).unwrap();
        w.finish().unwrap();
        let meta = read_metadata(&mut std::fs::File::open(&path).unwrap()).unwrap();
        assert_eq!(meta.row_groups.len(), 3);
        let mut file = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        for g in [0, 2] {
            let r = meta.row_groups[g].full_byte_range();
            file.seek(SeekFrom::Start(r.start)).unwrap();
            file.write_all(&vec![0xff; (r.end - r.start) as usize])
                .unwrap();
        }
        drop(file);
        assert!(
            read_case_results(&plan, &path).is_err(),
            "the garbage is read as rows"
        );
        let back = read_case_results_rows(&chunk(1), &path, (10, 10)).unwrap();
        let ids: Vec<u64> = back.iter().map(|r| r.case_id).collect();
        assert_eq!(ids, (10..20).collect::<Vec<u64>>());
        for (a, b) in rows[10..20].iter().zip(&back) {
            assert_eq!(format!("{:?}", a.solution), format!("{:?}", b.solution));
        }
    }
}
