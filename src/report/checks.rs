//! What a report may be drawn from: every stored table is checked against run.json and the
//! value domains of its columns before anything is drawn, so a damaged or edited run
//! directory is refused with the file, column and row at fault instead of giving blank,
//! garbled or silently missing figures.

use super::data::RunData;
use crate::analysis::{MechanismKind, Regime};
use crate::scene::{Find, Outcome};
use crate::store::ResultRow;
use std::path::{Path, PathBuf};

/// A stored table that the report refuses.
#[derive(Debug, thiserror::Error)]
#[error("{}: column `{column}`{}: {problem}; draw the report from the files `archstudy run` wrote, or run the study again", file.display(), row.map(|r| format!(", row {r}")).unwrap_or_default())]
pub struct TableError {
    /// The table.
    pub file: PathBuf,
    /// The column at fault.
    pub column: String,
    /// The first row at fault (from 0), when one row is.
    pub row: Option<usize>,
    /// What is wrong.
    pub problem: String,
}

/// The checks of one table, naming its file.
struct Table<'a> {
    file: &'a Path,
    /// The index in the file of the first row checked.
    offset: usize,
}

impl Table<'_> {
    fn err(&self, column: &str, row: Option<usize>, problem: impl Into<String>) -> TableError {
        TableError {
            file: self.file.to_path_buf(),
            column: column.into(),
            row: row.map(|r| r + self.offset),
            problem: problem.into(),
        }
    }

    /// Every present value satisfies `ok`, described by `domain`.
    fn values(
        &self,
        column: &str,
        values: impl Iterator<Item = Option<f64>>,
        ok: impl Fn(f64) -> bool,
        domain: &str,
    ) -> Result<(), TableError> {
        for (i, v) in values.enumerate() {
            if let Some(v) = v
                && !ok(v)
            {
                return Err(self.err(column, Some(i), format!("value {v} is not {domain}")));
            }
        }
        Ok(())
    }

    /// Every present name is one that `known` accepts. A column holds few distinct names in
    /// long runs: a name equal to the one before it was already accepted.
    fn names<'s>(
        &self,
        column: &str,
        names: impl Iterator<Item = Option<&'s str>>,
        known: impl Fn(&str) -> bool,
    ) -> Result<(), TableError> {
        let mut accepted: Option<&str> = None;
        for (i, n) in names.enumerate() {
            if let Some(n) = n
                && !memo_known(&mut accepted, n, &known)
            {
                return Err(self.err(
                    column,
                    Some(i),
                    format!("{n:?} is not a value archstudy writes"),
                ));
            }
        }
        Ok(())
    }
}

fn is_regime(s: &str) -> bool {
    Regime::ALL.iter().any(|r| r.as_str() == s)
}

fn is_mechanism(s: &str) -> bool {
    [
        MechanismKind::Rotational,
        MechanismKind::Mixed,
        MechanismKind::Sliding,
    ]
    .iter()
    .any(|m| m.as_str() == s)
}

/// Checks the tables a report draws from besides results.parquet (checked as it is read,
/// [`check_result_count`] and [`check_result_rows`]); `data` was read from `dir`.
pub fn check_tables(dir: &Path, data: &RunData) -> Result<(), TableError> {
    check_boundaries(&dir.join("boundaries.parquet"), data)?;
    check_mechanisms(&dir.join("mechanisms.parquet"), data)
}

/// Refuses a results table whose number of rows is not the number of cases run.json records.
pub fn check_result_count(file: &Path, rows: usize, total: u64) -> Result<(), TableError> {
    if rows as u64 != total {
        return Err(Table { file, offset: 0 }.err(
            "case_id",
            None,
            format!("the table has {rows} rows, run.json records {total} cases"),
        ));
    }
    Ok(())
}

/// Checks a block of rows of results.parquet, the first of which is row `offset` of the file:
/// case ids in order and every column in its domain. The rows are read once and each checked
/// whole; only a block with a fault is walked column by column, to name the first fault of
/// the first column that has one.
pub fn check_result_rows(file: &Path, offset: usize, rows: &[ResultRow]) -> Result<(), TableError> {
    let mut names = NameMemo::default();
    let sound = rows
        .iter()
        .enumerate()
        .all(|(i, r)| row_is_sound(r, (offset + i) as u64, &mut names));
    if sound {
        return Ok(());
    }
    locate_row_fault(file, offset, rows)
}

/// The names last accepted in each text column of a results table (a column holds few
/// distinct names, in long runs).
#[derive(Default)]
struct NameMemo<'r> {
    find: Option<&'r str>,
    regime: Option<&'r str>,
    outcome: Option<&'r str>,
}

/// Whether `name` is known, asking `known` only for a name other than the last accepted.
fn memo_known<'r>(last: &mut Option<&'r str>, name: &'r str, known: impl Fn(&str) -> bool) -> bool {
    if *last == Some(name) {
        return true;
    }
    let ok = known(name);
    if ok {
        *last = Some(name);
    }
    ok
}

/// Whether one row of results.parquet passes every check of [`check_result_rows`].
fn row_is_sound<'r>(r: &'r ResultRow, id: u64, names: &mut NameMemo<'r>) -> bool {
    let finite = |v: Option<f64>| v.is_none_or(f64::is_finite);
    r.case_id == id
        && r.k.is_none_or(k_in_domain)
        && r.t_over_r.is_none_or(t_over_r_in_domain)
        && r.mu.is_none_or(mu_in_domain)
        && finite(r.k_crit)
        && finite(r.mu_crit)
        && finite(r.thrust_r_min)
        && finite(r.load_factor)
        && memo_known(&mut names.find, &r.find, is_find)
        && r.regime
            .as_deref()
            .is_none_or(|g| memo_known(&mut names.regime, g, is_regime))
        && r.outcome
            .as_deref()
            .is_none_or(|o| memo_known(&mut names.outcome, o, is_outcome))
        && is_status(&r.status)
}

fn k_in_domain(k: f64) -> bool {
    k.is_finite() && k > 1.0
}

fn t_over_r_in_domain(x: f64) -> bool {
    x.is_finite() && x > 0.0 && x < 2.0
}

fn mu_in_domain(m: f64) -> bool {
    m >= 0.0
}

fn is_find(s: &str) -> bool {
    Find::parse(s).is_some()
}

fn is_outcome(s: &str) -> bool {
    Outcome::parse(s).is_some()
}

fn is_status(s: &str) -> bool {
    s == "ok" || s == "error"
}

/// The first fault of a block that [`row_is_sound`] refused, column by column.
fn locate_row_fault(file: &Path, offset: usize, rows: &[ResultRow]) -> Result<(), TableError> {
    let t = Table { file, offset };
    if let Some(i) = rows
        .iter()
        .enumerate()
        .position(|(i, r)| r.case_id != (offset + i) as u64)
    {
        return Err(t.err("case_id", Some(i), "case ids are not 0, 1, 2, … in order"));
    }
    t.values("k", rows.iter().map(|r| r.k), k_in_domain, "a finite K > 1")?;
    t.values(
        "t_over_r",
        rows.iter().map(|r| r.t_over_r),
        t_over_r_in_domain,
        "a t/R_c in (0, 2)",
    )?;
    t.values(
        "mu",
        rows.iter().map(|r| r.mu),
        mu_in_domain,
        "μ ≥ 0 or inf",
    )?;
    let finite = |x: f64| x.is_finite();
    for (column, get) in [
        ("k_crit", (|r: &ResultRow| r.k_crit) as fn(&_) -> _),
        ("mu_crit", |r| r.mu_crit),
        ("thrust_r_min", |r| r.thrust_r_min),
        ("load_factor", |r| r.load_factor),
    ] {
        t.values(column, rows.iter().map(get), finite, "a finite number")?;
    }
    t.names("find", rows.iter().map(|r| Some(&*r.find)), is_find)?;
    t.names(
        "regime",
        rows.iter().map(|r| r.regime.as_deref()),
        is_regime,
    )?;
    t.names(
        "outcome",
        rows.iter().map(|r| r.outcome.as_deref()),
        is_outcome,
    )?;
    t.names("status", rows.iter().map(|r| Some(&*r.status)), is_status)
}

fn check_boundaries(file: &Path, data: &RunData) -> Result<(), TableError> {
    let Some(rows) = &data.boundaries else {
        return Ok(());
    };
    let t = Table { file, offset: 0 };
    t.values(
        "k",
        rows.iter().map(|r| Some(r.k)),
        |k| k.is_finite() && k > 1.0,
        "a finite K > 1",
    )?;
    t.values(
        "mu",
        rows.iter().map(|r| Some(r.mu)),
        |m| m >= 0.0,
        "μ ≥ 0 or inf",
    )?;
    t.names(
        "regime_low",
        rows.iter().map(|r| Some(r.regime_low.as_str())),
        is_regime,
    )?;
    t.names(
        "regime_high",
        rows.iter().map(|r| Some(r.regime_high.as_str())),
        is_regime,
    )?;
    t.names(
        "mechanism",
        rows.iter().map(|r| r.mechanism.as_deref()),
        is_mechanism,
    )
}

fn check_mechanisms(file: &Path, data: &RunData) -> Result<(), TableError> {
    let t = Table { file, offset: 0 };
    for (i, m) in data.mechanisms.iter().enumerate() {
        if serde_json::from_str::<serde_json::Value>(&m.drawing_json).is_err() {
            return Err(t.err("drawing_json", Some(i), "the drawing is not valid JSON"));
        }
    }
    t.values(
        "k",
        data.mechanisms.iter().map(|m| Some(m.k)),
        |k| k.is_finite() && k > 1.0,
        "a finite K > 1",
    )
}
