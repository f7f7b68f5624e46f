//! Typed rows of the stored tables that figures and reports read back: results.parquet (the
//! columns a report needs), boundaries.parquet and bifurcations.parquet (schemas in the
//! README and docs/report-files.md).

use super::results::filled_by;
use super::{
    bool_column, f64_column, list_f64_column, list_str_column, read_parquet, read_parquet_columns,
    str_column, u64_column,
};
use crate::analysis::windows::Span;
use anyhow::{Context as _, Result};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// The hinges and sliding joints of a stored state (the four list columns).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct JointLists {
    /// Hinge angles from the crown, degrees.
    pub hinge_angles_deg: Vec<f64>,
    /// Hinge faces, `intrados` or `extrados`, one per angle.
    pub hinge_faces: Vec<String>,
    /// Sliding joint angles from the crown, degrees.
    pub sliding_angles_deg: Vec<f64>,
    /// Sliding senses, `outward` or `inward`, one per angle.
    pub sliding_senses: Vec<String>,
}

/// A string column whose values repeat (a load case, a find, a regime): its distinct values,
/// one allocation each, and the index of each row's value.
struct Coded {
    values: Vec<Arc<str>>,
    /// Per row, the index of its value in `values`; [`Coded::NULL`] for a null.
    codes: Vec<u32>,
}

impl Coded {
    const NULL: u32 = u32::MAX;

    /// No rows: a column the table does not store.
    fn absent() -> Self {
        Coded {
            values: Vec::new(),
            codes: Vec::new(),
        }
    }

    fn of(df: &polars::prelude::DataFrame, name: &str) -> Result<Self> {
        let c = df
            .column(name)
            .with_context(|| format!("column `{name}` is missing"))?;
        let ca = c.as_materialized_series().str()?;
        let mut seen: HashMap<&str, u32> = HashMap::new();
        let mut values: Vec<Arc<str>> = Vec::new();
        let mut last: Option<(&str, u32)> = None;
        let codes = ca
            .iter()
            .map(|v| {
                let Some(v) = v else {
                    return Self::NULL;
                };
                if let Some((l, code)) = last
                    && l == v
                {
                    return code;
                }
                let code = *seen.entry(v).or_insert_with(|| {
                    values.push(Arc::from(v));
                    (values.len() - 1) as u32
                });
                last = Some((v, code));
                code
            })
            .collect();
        Ok(Coded { values, codes })
    }

    /// An error unless every row has a value; `path` names the file in it.
    fn require(&self, name: &str, path: &Path) -> Result<()> {
        match self.codes.iter().position(|&c| c == Self::NULL) {
            Some(i) => anyhow::bail!("{}: row {i} has no `{name}`", path.display()),
            None => Ok(()),
        }
    }

    /// Copies of the values for one part of the rows built in parallel: the rows of a part
    /// share them, so that the threads do not all count references on one counter.
    fn local(&self) -> Vec<Arc<str>> {
        self.values.iter().map(|v| Arc::from(&**v)).collect()
    }

    /// The value of row `i` from the part's copies `local` (null past the end).
    fn at(&self, local: &[Arc<str>], i: usize) -> Option<Arc<str>> {
        match self.codes.get(i) {
            Some(&c) if c != Self::NULL => local.get(c as usize).cloned(),
            _ => None,
        }
    }
}

/// One row of results.parquet, with the columns the report and the figure data read back
/// (the inputs, the regime or critical value compared with the continuum, status and time);
/// the rest of a case is in the file.
#[derive(Debug, Clone, PartialEq)]
pub struct ResultRow {
    /// Case id.
    pub case_id: u64,
    /// Load-case name.
    pub load_case: Arc<str>,
    /// `state`, `thickness`, `friction`, `thrust`, `thresholds` or `load_factor`.
    pub find: Arc<str>,
    /// K = R/r given.
    pub k: Option<f64>,
    /// t/R_c given.
    pub t_over_r: Option<f64>,
    /// μ given (+inf for infinite friction).
    pub mu: Option<f64>,
    /// Voussoir count, `None` for the continuum.
    pub voussoirs: Option<u32>,
    /// `found`, `never_stands` or `always_stands` (critical finds).
    pub outcome: Option<Arc<str>>,
    /// Regime (state find).
    pub regime: Option<Arc<str>>,
    /// Lower end of H^r over W_half.
    pub thrust_r_min: Option<f64>,
    /// Collapse thickness ratio.
    pub k_crit: Option<f64>,
    /// Every interval of K on which the arch stands (thickness find): (from, to), `to`
    /// `None` for a window open at the end of the scan.
    pub k_windows: Vec<Span>,
    /// Critical friction.
    pub mu_crit: Option<f64>,
    /// Minimum admissible thrust over W_half (thrust find).
    pub thrust_min: Option<f64>,
    /// Maximum admissible thrust over W_half (thrust find).
    pub thrust_max: Option<f64>,
    /// Collapse thickness at infinite friction (thresholds find).
    pub k_c_rotational: Option<f64>,
    /// μ of the rotational/mixed bifurcation (thresholds find).
    pub mu_rotational_mixed: Option<f64>,
    /// Sliding threshold μ_min (thresholds find).
    pub mu_min: Option<f64>,
    /// K of the mixed/sliding bifurcation (thresholds find).
    pub k_mixed_sliding: Option<f64>,
    /// Largest load factor λ of the live load (load_factor find; null when unbounded).
    pub load_factor: Option<f64>,
    /// `no_gap`, `gap`, `no_complete_solution` or `failed` (critical finds).
    pub gap: Option<Arc<str>>,
    /// The first complete solution along the find's path (critical finds).
    pub collapse_value: Option<f64>,
    /// Its distance to the static limit along the path.
    pub gap_width: Option<f64>,
    /// `ok` or `error`.
    pub status: Arc<str>,
    /// Wall time of the analysis, µs.
    pub solve_time_us: f64,
}

impl ResultRow {
    /// True when a thickness find found that a thicker arch than K_c fails again: more than
    /// one window, or one that closes before the end of the scan.
    pub fn fails_again(&self) -> bool {
        crate::analysis::windows::fails_again(&self.k_windows)
    }

    /// The value of a numeric results column of this row by its name (the critical values
    /// compared with the continuum); `None` when the column is not one of them or is null.
    pub fn value_of(&self, column: &str) -> Option<f64> {
        match column {
            "k_crit" => self.k_crit,
            "mu_crit" => self.mu_crit,
            "thrust_min" => self.thrust_min,
            "thrust_max" => self.thrust_max,
            "thrust_r_min" => self.thrust_r_min,
            "k_c_rotational" => self.k_c_rotational,
            "mu_rotational_mixed" => self.mu_rotational_mixed,
            "mu_min" => self.mu_min,
            "k_mixed_sliding" => self.k_mixed_sliding,
            "load_factor" => self.load_factor,
            _ => None,
        }
    }
}

/// One row of boundaries.parquet: a point where the regime changes along a grid line.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryRow {
    /// Load-case name.
    pub load_case: String,
    /// μ of the point.
    pub mu: f64,
    /// K of the point.
    pub k: f64,
    /// t/R_c of the point.
    pub t_over_r: f64,
    /// Regime on the low side (smaller K or μ).
    pub regime_low: String,
    /// Regime on the high side.
    pub regime_high: String,
    /// The axis along which it was located, `k` or `mu`.
    pub axis: String,
    /// True when the point lies on the boundary of the stable region.
    pub on_collapse_curve: bool,
    /// The collapse mechanism there (collapse-curve points).
    pub mechanism: Option<String>,
    /// Crown thrust over W_half of the limit state.
    pub thrust_over_half_weight: Option<f64>,
    /// Crown moment over W_half·r of the limit state.
    pub crown_moment: Option<f64>,
    /// Hinges and sliding joints of the limit state.
    pub joints: JointLists,
}

/// One row of bifurcations.parquet: a point of the collapse curve where two mechanisms meet.
#[derive(Debug, Clone, PartialEq)]
pub struct BifurcationRow {
    /// Load-case name.
    pub load_case: String,
    /// μ of the point.
    pub mu: f64,
    /// K of the point.
    pub k: f64,
    /// t/R_c of the point.
    pub t_over_r: f64,
    /// One mechanism (the one on the larger-μ side).
    pub mechanism_a: String,
    /// The other mechanism.
    pub mechanism_b: String,
    /// Crown thrust over W_half.
    pub thrust_over_half_weight: Option<f64>,
    /// Crown moment over W_half·r.
    pub crown_moment: Option<f64>,
    /// Hinges and sliding joints of the limit state (both mechanisms together).
    pub joints: JointLists,
}

fn joint_lists(df: &polars::prelude::DataFrame) -> Result<Vec<JointLists>> {
    let ha = list_f64_column(df, "hinge_angles_deg")?;
    let hf = list_str_column(df, "hinge_faces")?;
    let sa = list_f64_column(df, "sliding_angles_deg")?;
    let ss = list_str_column(df, "sliding_senses")?;
    Ok(ha
        .into_iter()
        .zip(hf)
        .zip(sa.into_iter().zip(ss))
        .map(|((ha, hf), (sa, ss))| JointLists {
            hinge_angles_deg: ha,
            hinge_faces: hf,
            sliding_angles_deg: sa,
            sliding_senses: ss,
        })
        .collect())
}

fn required<T>(v: Vec<Option<T>>, name: &str, path: &Path) -> Result<Vec<T>> {
    v.into_iter()
        .enumerate()
        .map(|(i, s)| s.with_context(|| format!("{}: row {i} has no `{name}`", path.display())))
        .collect()
}

/// The columns of results.parquet that make a [`ResultRow`].
const RESULT_ROW_COLUMNS: [&str; 27] = [
    "case_id",
    "load_case",
    "find",
    "k",
    "t_over_r",
    "mu",
    "voussoirs",
    "outcome",
    "regime",
    "thrust_r_min",
    "k_crit",
    "k_windows_from",
    "k_windows_to",
    "k_windows_scanned_to",
    "mu_crit",
    "thrust_min",
    "thrust_max",
    "k_c_rotational",
    "mu_rotational_mixed",
    "mu_min",
    "k_mixed_sliding",
    "load_factor",
    "gap",
    "collapse_value",
    "gap_width",
    "status",
    "solve_time_us",
];

/// Reads results.parquet (the columns of [`ResultRow`] only).
pub fn read_results(path: &Path) -> Result<Vec<ResultRow>> {
    let df = read_parquet_columns(path, &RESULT_ROW_COLUMNS)?;
    results_of_frame(&df, path)
}

/// Reads the rows `offset .. offset + len` of results.parquet (the columns of [`ResultRow`]
/// only; only the row groups that hold them are decoded).
pub fn read_results_rows(path: &Path, (offset, len): (usize, usize)) -> Result<Vec<ResultRow>> {
    let df = super::read_parquet_rows(path, &RESULT_ROW_COLUMNS, Some((offset, len)))?;
    results_of_frame(&df, path)
}

/// Reads results.parquet (the columns of [`ResultRow`] only) `block` rows at a time, in
/// order, handing each block and the index of its first row to `each`: the rows of a large
/// run need not be in memory at once.
pub fn read_results_in_blocks(
    path: &Path,
    block: usize,
    mut each: impl FnMut(usize, Vec<ResultRow>) -> Result<()>,
) -> Result<()> {
    super::read_parquet_in_blocks(path, &RESULT_ROW_COLUMNS, block, |offset, df| {
        each(offset, results_of_frame(df, path)?)
    })
}

/// Reads results.parquet (the columns of [`ResultRow`] only) `block` rows at a time, in
/// order, appending each block's rows to `out` ([`extend_results_of_frame`]) and handing
/// `each` the index of the block's first row in the file, `out` and the index of the block's
/// first row there: a reader that keeps some rows of every block cuts `out` back to them, and
/// the rows it keeps are written once.
pub fn append_results_in_blocks(
    path: &Path,
    block: usize,
    out: &mut Vec<ResultRow>,
    mut each: impl FnMut(usize, &mut Vec<ResultRow>, usize) -> Result<()>,
) -> Result<()> {
    super::read_parquet_in_blocks(path, &RESULT_ROW_COLUMNS, block, |offset, df| {
        let start = out.len();
        extend_results_of_frame(df, path, out)?;
        each(offset, out, start)
    })
}

/// The result rows of a results frame (its columns of [`ResultRow`]); `path` names where it
/// came from in errors.
pub fn results_of_frame(df: &polars::prelude::DataFrame, path: &Path) -> Result<Vec<ResultRow>> {
    let mut out = Vec::new();
    extend_results_of_frame(df, path, &mut out)?;
    Ok(out)
}

/// Appends the result rows of a results frame to `out`, built in parallel (on the current
/// rayon pool) in place: a reader that keeps the rows of many blocks writes them once, into
/// one vector, rather than into a vector per block and then again into the whole.
pub fn extend_results_of_frame(
    df: &polars::prelude::DataFrame,
    path: &Path,
    out: &mut Vec<ResultRow>,
) -> Result<()> {
    use rayon::prelude::*;
    let cx = || format!("in {}", path.display());
    // An answer column the study's finds do not fill is not stored: all null, and held as
    // nothing rather than as a vector of nulls.
    let absent = |name: &str| df.column(name).is_err() && filled_by(name).is_some();
    let f = |name: &str| -> Result<Nullable<f64>> {
        if absent(name) {
            return Ok(Nullable(None));
        }
        Ok(Nullable(Some(f64_column(df, name).with_context(cx)?)))
    };
    let s = |name: &str| -> Result<Coded> {
        if absent(name) {
            return Ok(Coded::absent());
        }
        Coded::of(df, name).with_context(cx)
    };
    let req = |name: &str| -> Result<Coded> {
        let c = Coded::of(df, name).with_context(cx)?;
        c.require(name, path)?;
        Ok(c)
    };
    let case_id = u64_column(df, "case_id").with_context(cx)?;
    let (load_case, find) = (req("load_case")?, req("find")?);
    let (k, t_over_r, mu) = (f("k")?, f("t_over_r")?, f("mu")?);
    let voussoirs = f("voussoirs")?;
    let (outcome, regime) = (s("outcome")?, s("regime")?);
    let rmin = f("thrust_r_min")?;
    let (k_crit, mu_crit) = (f("k_crit")?, f("mu_crit")?);
    let windows = window_lists(df, f("k_windows_scanned_to")?).with_context(cx)?;
    let (tmin, tmax) = (f("thrust_min")?, f("thrust_max")?);
    let (kcr, murm) = (f("k_c_rotational")?, f("mu_rotational_mixed")?);
    let (mumin, kms) = (f("mu_min")?, f("k_mixed_sliding")?);
    let load_factor = f("load_factor")?;
    let gap = s("gap")?;
    let (collapse, width) = (f("collapse_value")?, f("gap_width")?);
    let status = req("status")?;
    let time = f("solve_time_us")?;
    let strings = [&load_case, &find, &outcome, &regime, &gap, &status];
    out.par_extend(case_id.par_iter().enumerate().map_init(
        || strings.map(Coded::local),
        |local, (i, &case_id)| ResultRow {
            case_id,
            load_case: load_case.at(&local[0], i).unwrap_or_default(),
            find: find.at(&local[1], i).unwrap_or_default(),
            k: k.at(i),
            t_over_r: t_over_r.at(i),
            mu: mu.at(i),
            voussoirs: voussoirs.at(i).map(|v| v as u32),
            outcome: outcome.at(&local[2], i),
            regime: regime.at(&local[3], i),
            thrust_r_min: rmin.at(i),
            k_crit: k_crit.at(i),
            k_windows: windows.get(i).cloned().unwrap_or_default(),
            mu_crit: mu_crit.at(i),
            thrust_min: tmin.at(i),
            thrust_max: tmax.at(i),
            k_c_rotational: kcr.at(i),
            mu_rotational_mixed: murm.at(i),
            mu_min: mumin.at(i),
            k_mixed_sliding: kms.at(i),
            load_factor: load_factor.at(i),
            gap: gap.at(&local[4], i),
            collapse_value: collapse.at(i),
            gap_width: width.at(i),
            status: status.at(&local[5], i).unwrap_or_default(),
            solve_time_us: time.at(i).unwrap_or(f64::NAN),
        },
    ));
    Ok(())
}

/// A nullable column read back: its values, or `None` when the table does not store it (a
/// column the study's finds do not fill), where every row is null.
struct Nullable<T>(Option<Vec<Option<T>>>);

impl<T: Clone> Nullable<T> {
    /// The value of row `i` (null past the end or when the column is not stored).
    fn at(&self, i: usize) -> Option<T> {
        self.0.as_ref().and_then(|v| v.get(i).cloned().flatten())
    }
}

/// The windows of K of each row ([`super::cases::windows`]); empty lists where the table has
/// no window columns (a study without thickness finds).
fn window_lists(
    df: &polars::prelude::DataFrame,
    scanned_to: Nullable<f64>,
) -> Result<Vec<Vec<Span>>> {
    if df.column("k_windows_from").is_err() {
        return Ok(Vec::new());
    }
    let from = list_f64_column(df, "k_windows_from")?;
    let to = list_f64_column(df, "k_windows_to")?;
    from.iter()
        .zip(&to)
        .enumerate()
        .map(|(i, (a, b))| super::cases::windows(a, b, scanned_to.at(i)))
        .collect()
}

/// Reads boundaries.parquet.
pub fn read_boundaries(path: &Path) -> Result<Vec<BoundaryRow>> {
    boundaries_of_frame(&read_parquet(path)?, path)
}

/// The rows of a boundaries frame; `path` names where it came from in errors.
pub fn boundaries_of_frame(
    df: &polars::prelude::DataFrame,
    path: &Path,
) -> Result<Vec<BoundaryRow>> {
    let cx = || format!("in {}", path.display());
    let f = |name: &str| f64_column(df, name).with_context(cx);
    let s = |name: &str| str_column(df, name).with_context(cx);
    let load_case = required(s("load_case")?, "load_case", path)?;
    let mu = required(f("mu")?, "mu", path)?;
    let k = required(f("k")?, "k", path)?;
    let t = required(f("t_over_r")?, "t_over_r", path)?;
    let low = required(s("regime_low")?, "regime_low", path)?;
    let high = required(s("regime_high")?, "regime_high", path)?;
    let axis = required(s("axis")?, "axis", path)?;
    let on = bool_column(df, "on_collapse_curve").with_context(cx)?;
    let mech = s("mechanism")?;
    let (thrust, moment) = (f("thrust_over_half_weight")?, f("crown_moment")?);
    let joints = joint_lists(df).with_context(cx)?;
    Ok(joints
        .into_iter()
        .enumerate()
        .map(|(i, joints)| BoundaryRow {
            load_case: load_case[i].clone(),
            mu: mu[i],
            k: k[i],
            t_over_r: t[i],
            regime_low: low[i].clone(),
            regime_high: high[i].clone(),
            axis: axis[i].clone(),
            on_collapse_curve: on[i].unwrap_or(false),
            mechanism: mech[i].clone(),
            thrust_over_half_weight: thrust[i],
            crown_moment: moment[i],
            joints,
        })
        .collect())
}

/// Reads bifurcations.parquet.
pub fn read_bifurcations(path: &Path) -> Result<Vec<BifurcationRow>> {
    bifurcations_of_frame(&read_parquet(path)?, path)
}

/// The rows of a bifurcations frame; `path` names where it came from in errors.
pub fn bifurcations_of_frame(
    df: &polars::prelude::DataFrame,
    path: &Path,
) -> Result<Vec<BifurcationRow>> {
    let cx = || format!("in {}", path.display());
    let f = |name: &str| f64_column(df, name).with_context(cx);
    let s = |name: &str| str_column(df, name).with_context(cx);
    let load_case = required(s("load_case")?, "load_case", path)?;
    let mu = required(f("mu")?, "mu", path)?;
    let k = required(f("k")?, "k", path)?;
    let t = required(f("t_over_r")?, "t_over_r", path)?;
    let a = required(s("mechanism_a")?, "mechanism_a", path)?;
    let b = required(s("mechanism_b")?, "mechanism_b", path)?;
    let (thrust, moment) = (f("thrust_over_half_weight")?, f("crown_moment")?);
    let joints = joint_lists(df).with_context(cx)?;
    Ok(joints
        .into_iter()
        .enumerate()
        .map(|(i, joints)| BifurcationRow {
            load_case: load_case[i].clone(),
            mu: mu[i],
            k: k[i],
            t_over_r: t[i],
            mechanism_a: a[i].clone(),
            mechanism_b: b[i].clone(),
            thrust_over_half_weight: thrust[i],
            crown_moment: moment[i],
            joints,
        })
        .collect())
}
