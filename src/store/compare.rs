//! Comparing a stored table with a recomputed one, column by column.
//!
//! Pure: works on [`Table`]s read by the store (the only polars user) and does no I/O.
//! Rows are compared in order (a run's row order is stable, DESIGN §4).
//! - Float columns and lists of floats agree within a tolerance T when
//!   `|stored − recomputed| ≤ T · (1 + max(|stored|, |recomputed|))` (relative and absolute);
//!   equal values, including equal infinities and NaN against NaN, are identical; null
//!   agrees only with null; lists must have the same length.
//! - Every other column (strings, integers, booleans, lists of strings) must be equal exactly.
//! - Timing columns (`solve_time_us` and any `*_ms` or `*_us` column) are not compared.
//! - A different row count, a column missing from either side, a changed data type or a
//!   changed column order are differences.

use super::{ColumnData, Table, TableColumn};

/// The default tolerance of float comparisons (relative and absolute).
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// How many differing rows a verdict lists.
pub const ROWS_SHOWN: usize = 5;

/// Whether a column holds timings, which differ from run to run and are not compared.
pub fn is_timing_column(name: &str) -> bool {
    name == "solve_time_us" || name.ends_with("_ms") || name.ends_with("_us")
}

/// One row that differs, with both values as text.
#[derive(Debug, Clone, PartialEq)]
pub struct RowDiff {
    /// Row index, counting from 0.
    pub row: usize,
    /// The stored value.
    pub stored: String,
    /// The recomputed value.
    pub recomputed: String,
}

/// The verdict on one column.
#[derive(Debug, Clone, PartialEq)]
pub enum ColumnVerdict {
    /// Every value equal.
    Identical,
    /// Float values not all equal, but all within the tolerance.
    WithinTolerance {
        /// The largest absolute difference.
        max_abs_diff: f64,
    },
    /// Some values differ.
    Different {
        /// How many rows differ.
        rows_differing: usize,
        /// The first rows that differ (at most [`ROWS_SHOWN`]).
        first: Vec<RowDiff>,
        /// The largest absolute difference of float values, when the column is float.
        max_abs_diff: Option<f64>,
    },
    /// A timing column, not compared.
    Ignored,
    /// In the stored table only.
    MissingFromRerun,
    /// In the recomputed table only.
    NotStored,
    /// The data type changed.
    TypeChanged {
        /// Stored type.
        stored: String,
        /// Recomputed type.
        recomputed: String,
    },
}

impl ColumnVerdict {
    /// Whether this verdict counts as agreement.
    pub fn agrees(&self) -> bool {
        matches!(
            self,
            ColumnVerdict::Identical
                | ColumnVerdict::WithinTolerance { .. }
                | ColumnVerdict::Ignored
        )
    }
}

/// The verdict on one column, by name.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnComparison {
    /// Column name.
    pub name: String,
    /// Verdict.
    pub verdict: ColumnVerdict,
}

/// The comparison of two tables.
#[derive(Debug, Clone, PartialEq)]
pub struct TableComparison {
    /// Rows stored.
    pub stored_rows: usize,
    /// Rows recomputed.
    pub recomputed_rows: usize,
    /// Whether the common columns come in the same order.
    pub same_column_order: bool,
    /// One verdict per column: stored columns in file order, then recomputed-only ones.
    pub columns: Vec<ColumnComparison>,
}

impl TableComparison {
    /// Whether the tables agree: same rows, same schema, every column agreeing.
    pub fn agrees(&self) -> bool {
        self.stored_rows == self.recomputed_rows
            && self.same_column_order
            && self.columns.iter().all(|c| c.verdict.agrees())
    }
}

/// Compares a stored table with a recomputed one (rows up to the shorter height).
pub fn compare_tables(stored: &Table, recomputed: &Table, tolerance: f64) -> TableComparison {
    let mut columns = Vec::with_capacity(stored.columns.len());
    for s in &stored.columns {
        let verdict = match recomputed.column(&s.name) {
            _ if is_timing_column(&s.name) => ColumnVerdict::Ignored,
            None => ColumnVerdict::MissingFromRerun,
            Some(r) => compare_columns(s, r, tolerance),
        };
        columns.push(ColumnComparison {
            name: s.name.clone(),
            verdict,
        });
    }
    for r in &recomputed.columns {
        if stored.column(&r.name).is_none() {
            columns.push(ColumnComparison {
                name: r.name.clone(),
                verdict: if is_timing_column(&r.name) {
                    ColumnVerdict::Ignored
                } else {
                    ColumnVerdict::NotStored
                },
            });
        }
    }
    let order = |t: &Table, other: &Table| -> Vec<String> {
        t.columns
            .iter()
            .filter(|c| other.column(&c.name).is_some())
            .map(|c| c.name.clone())
            .collect()
    };
    TableComparison {
        stored_rows: stored.rows,
        recomputed_rows: recomputed.rows,
        same_column_order: order(stored, recomputed) == order(recomputed, stored),
        columns,
    }
}

/// Folds the comparison of a block of rows, the block starting at row `offset` of both
/// tables, into the comparison of the rows before it (`earlier`, None for the first block).
/// Comparing two tables block by block and folding gives the verdicts of [`compare_tables`]
/// on the whole tables (row counts aside, which the caller sets from the files): so a table
/// larger than memory is compared a block at a time.
pub fn fold_block(
    earlier: Option<TableComparison>,
    mut block: TableComparison,
    offset: usize,
) -> TableComparison {
    for c in &mut block.columns {
        if let ColumnVerdict::Different { first, .. } = &mut c.verdict {
            for d in first {
                d.row += offset;
            }
        }
    }
    let Some(mut acc) = earlier else {
        return block;
    };
    for (a, b) in acc.columns.iter_mut().zip(block.columns) {
        a.verdict = fold_verdict(
            std::mem::replace(&mut a.verdict, ColumnVerdict::Ignored),
            b.verdict,
        );
    }
    acc.stored_rows += block.stored_rows;
    acc.recomputed_rows += block.recomputed_rows;
    acc
}

/// One column's verdict on the rows so far and on the next block, as one verdict.
fn fold_verdict(a: ColumnVerdict, b: ColumnVerdict) -> ColumnVerdict {
    use ColumnVerdict::{Different, Identical, WithinTolerance};
    // The largest float difference of a verdict on values, None for an exact column.
    let max = |v: &ColumnVerdict| match v {
        Identical => Some(0.0),
        WithinTolerance { max_abs_diff } => Some(*max_abs_diff),
        Different { max_abs_diff, .. } => *max_abs_diff,
        _ => None,
    };
    match (&a, &b) {
        (Identical, Identical) => Identical,
        (Identical | WithinTolerance { .. }, Identical | WithinTolerance { .. }) => {
            WithinTolerance {
                max_abs_diff: max(&a).unwrap_or(0.0).max(max(&b).unwrap_or(0.0)),
            }
        }
        (Identical | WithinTolerance { .. } | Different { .. }, Different { .. })
        | (Different { .. }, Identical | WithinTolerance { .. }) => {
            let (ma, mb) = (max(&a), max(&b));
            // An exact column's Different carries no difference; a float column's always does.
            let exact = matches!(
                &a,
                Different {
                    max_abs_diff: None,
                    ..
                }
            ) || matches!(
                &b,
                Different {
                    max_abs_diff: None,
                    ..
                }
            );
            let parts = |v: ColumnVerdict| match v {
                Different {
                    rows_differing,
                    first,
                    ..
                } => (rows_differing, first),
                _ => (0, Vec::new()),
            };
            let ((na, mut first), (nb, more)) = (parts(a), parts(b));
            first.extend(more);
            first.truncate(ROWS_SHOWN);
            Different {
                rows_differing: na + nb,
                first,
                max_abs_diff: if exact {
                    None
                } else {
                    Some(ma.unwrap_or(0.0).max(mb.unwrap_or(0.0)))
                },
            }
        }
        // Verdicts on the schema (ignored, missing, type changed) are the same in every block.
        _ => a,
    }
}

/// Compares two columns of the same name.
pub fn compare_columns(s: &TableColumn, r: &TableColumn, tolerance: f64) -> ColumnVerdict {
    match (&s.data, &r.data) {
        _ if s.dtype != r.dtype => ColumnVerdict::TypeChanged {
            stored: s.dtype.clone(),
            recomputed: r.dtype.clone(),
        },
        (ColumnData::Float(a), ColumnData::Float(b)) => {
            float_verdict(a, b, tolerance, |x, y| float_diff(*x, *y), fmt_opt_f64)
        }
        (ColumnData::FloatList(a), ColumnData::FloatList(b)) => {
            float_verdict(a, b, tolerance, list_diff, fmt_list)
        }
        (ColumnData::Exact(a), ColumnData::Exact(b)) => {
            let mut rows_differing = 0;
            let mut first = Vec::new();
            for (row, (x, y)) in a.iter().zip(b).enumerate() {
                if x != y {
                    rows_differing += 1;
                    if first.len() < ROWS_SHOWN {
                        first.push(RowDiff {
                            row,
                            stored: fmt_opt_str(x),
                            recomputed: fmt_opt_str(y),
                        });
                    }
                }
            }
            if rows_differing == 0 {
                ColumnVerdict::Identical
            } else {
                ColumnVerdict::Different {
                    rows_differing,
                    first,
                    max_abs_diff: None,
                }
            }
        }
        // Same dtype always gives the same kind; kept total for safety.
        _ => ColumnVerdict::TypeChanged {
            stored: s.dtype.clone(),
            recomputed: r.dtype.clone(),
        },
    }
}

/// How two float values (or lists) compare: `None` when they cannot agree (null against a
/// value, lists of different lengths, an infinity against a finite value), else the largest
/// absolute difference and the largest scale `max(|a|, |b|)` of the pair that has it.
type Diff = Option<(f64, f64)>;

fn float_diff(a: Option<f64>, b: Option<f64>) -> Diff {
    match (a, b) {
        (None, None) => Some((0.0, 0.0)),
        (Some(x), Some(y)) if x == y || (x.is_nan() && y.is_nan()) => Some((0.0, 0.0)),
        (Some(x), Some(y)) if x.is_finite() && y.is_finite() => {
            Some(((x - y).abs(), x.abs().max(y.abs())))
        }
        _ => None,
    }
}

fn list_diff(a: &Option<Vec<Option<f64>>>, b: &Option<Vec<Option<f64>>>) -> Diff {
    match (a, b) {
        (None, None) => Some((0.0, 0.0)),
        (Some(x), Some(y)) if x.len() == y.len() => {
            let mut worst = (0.0, 0.0);
            for (u, v) in x.iter().zip(y) {
                let (d, scale) = float_diff(*u, *v)?;
                if d > worst.0 {
                    worst = (d, scale);
                }
            }
            Some(worst)
        }
        _ => None,
    }
}

fn within(d: f64, scale: f64, tolerance: f64) -> bool {
    d <= tolerance * (1.0 + scale)
}

fn float_verdict<T>(
    a: &[T],
    b: &[T],
    tolerance: f64,
    diff: impl Fn(&T, &T) -> Diff,
    fmt: impl Fn(&T) -> String,
) -> ColumnVerdict {
    let mut max_abs_diff: f64 = 0.0;
    let mut rows_differing = 0;
    // Whether a differing row differs by a number (not a null or infinity against a value).
    let mut numeric_difference = false;
    let mut first = Vec::new();
    for (row, (x, y)) in a.iter().zip(b).enumerate() {
        let d = diff(x, y);
        if let Some((d, _)) = d {
            max_abs_diff = max_abs_diff.max(d);
        }
        let ok = matches!(d, Some((d, scale)) if within(d, scale, tolerance));
        if !ok {
            numeric_difference |= d.is_some();
            rows_differing += 1;
            if first.len() < ROWS_SHOWN {
                first.push(RowDiff {
                    row,
                    stored: fmt(x),
                    recomputed: fmt(y),
                });
            }
        }
    }
    if rows_differing > 0 {
        // Rows that differ only by nulls or infinities against values have no numeric
        // difference to show ("max difference 0" would say they agree).
        ColumnVerdict::Different {
            rows_differing,
            first,
            max_abs_diff: numeric_difference.then_some(max_abs_diff),
        }
    } else if max_abs_diff > 0.0 {
        ColumnVerdict::WithinTolerance { max_abs_diff }
    } else {
        ColumnVerdict::Identical
    }
}

fn fmt_opt_f64(v: &Option<f64>) -> String {
    v.map_or_else(|| "null".to_string(), |x| format!("{x:?}"))
}

fn fmt_list(v: &Option<Vec<Option<f64>>>) -> String {
    match v {
        None => "null".to_string(),
        Some(xs) => format!(
            "[{}]",
            xs.iter().map(fmt_opt_f64).collect::<Vec<_>>().join(", ")
        ),
    }
}

fn fmt_opt_str(v: &Option<String>) -> String {
    v.clone().unwrap_or_else(|| "null".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn col(name: &str, dtype: &str, data: ColumnData) -> TableColumn {
        TableColumn {
            name: name.into(),
            dtype: dtype.into(),
            data,
        }
    }

    fn table(columns: Vec<TableColumn>) -> Table {
        Table {
            rows: columns.first().map_or(0, |c| c.data.len()),
            columns,
        }
    }

    fn floats(v: &[f64]) -> ColumnData {
        ColumnData::Float(v.iter().map(|x| Some(*x)).collect())
    }

    /// Tables compared in blocks of `n` rows and folded: the verdicts of the whole.
    fn in_blocks(s: &Table, r: &Table, tolerance: f64, n: usize) -> TableComparison {
        let slice = |t: &Table, at: usize, len: usize| Table {
            rows: len,
            columns: t
                .columns
                .iter()
                .map(|c| {
                    let data = match &c.data {
                        ColumnData::Float(v) => ColumnData::Float(v[at..at + len].to_vec()),
                        ColumnData::FloatList(v) => ColumnData::FloatList(v[at..at + len].to_vec()),
                        ColumnData::Exact(v) => ColumnData::Exact(v[at..at + len].to_vec()),
                    };
                    TableColumn { data, ..c.clone() }
                })
                .collect(),
        };
        let rows = s.rows.min(r.rows);
        let mut acc = None;
        let mut at = 0;
        loop {
            let len = n.min(rows - at);
            acc = Some(fold_block(
                acc,
                compare_tables(&slice(s, at, len), &slice(r, at, len), tolerance),
                at,
            ));
            at += len;
            if at >= rows {
                break;
            }
        }
        let mut c = acc.unwrap();
        (c.stored_rows, c.recomputed_rows) = (s.rows, r.rows);
        c
    }

    #[test]
    fn tables_compared_in_blocks_have_the_verdicts_of_the_whole() {
        let xs: Vec<f64> = (0..23).map(|i| f64::from(i) * 0.5).collect();
        let mut near = xs.clone();
        near[4] += 1e-12;
        near[17] += 2e-12;
        let mut far = xs.clone();
        for i in [1, 6, 7, 12, 13, 19, 22] {
            far[i] += 0.25 * f64::from(i as u32);
        }
        let names: Vec<Option<String>> = (0..23).map(|i| Some(format!("r{i}"))).collect();
        let mut other_names = names.clone();
        other_names[9] = None;
        other_names[21] = Some("x".into());
        let lists = |v: &[f64]| {
            ColumnData::FloatList(v.iter().map(|x| Some(vec![Some(*x), Some(1.0)])).collect())
        };
        let s = table(vec![
            col("same", "f64", floats(&xs)),
            col("near", "f64", floats(&xs)),
            col("far", "f64", floats(&xs)),
            col("list", "list[f64]", lists(&xs)),
            col("name", "str", ColumnData::Exact(names.clone())),
            col("solve_time_us", "f64", floats(&xs)),
            col("gone", "f64", floats(&xs)),
            col("typed", "f64", floats(&xs)),
        ]);
        let r = table(vec![
            col("same", "f64", floats(&xs)),
            col("near", "f64", floats(&near)),
            col("far", "f64", floats(&far)),
            col("list", "list[f64]", lists(&far)),
            col("name", "str", ColumnData::Exact(other_names)),
            col("solve_time_us", "f64", floats(&far)),
            col("typed", "str", ColumnData::Exact(names)),
            col("new", "f64", floats(&xs)),
        ]);
        let whole = compare_tables(&s, &r, 1e-9);
        assert!(matches!(
            &whole.columns[2].verdict,
            ColumnVerdict::Different { rows_differing: 7, first, .. } if first.len() == ROWS_SHOWN
        ));
        for n in [1, 2, 3, 5, 7, 22, 23, 100] {
            assert_eq!(in_blocks(&s, &r, 1e-9, n), whole, "blocks of {n} rows");
        }
        // Tables of different heights: compared over the shorter one, heights kept.
        let mut r_short = r.clone();
        for c in &mut r_short.columns {
            if let ColumnData::Float(v) = &mut c.data {
                v.truncate(20);
            } else if let ColumnData::FloatList(v) = &mut c.data {
                v.truncate(20);
            } else if let ColumnData::Exact(v) = &mut c.data {
                v.truncate(20);
            }
        }
        r_short.rows = 20;
        let whole = compare_tables(&s, &r_short, 1e-9);
        assert_eq!((whole.stored_rows, whole.recomputed_rows), (23, 20));
        for n in [1, 4, 20, 64] {
            assert_eq!(
                in_blocks(&s, &r_short, 1e-9, n),
                whole,
                "blocks of {n} rows"
            );
        }
        // No rows: the schema's verdicts.
        let (s0, r0) = (
            Table {
                rows: 0,
                ..s.clone()
            },
            Table {
                rows: 0,
                ..r.clone()
            },
        );
        let empty = |t: &Table| Table {
            rows: 0,
            columns: t
                .columns
                .iter()
                .map(|c| TableColumn {
                    data: match c.data {
                        ColumnData::Float(_) => ColumnData::Float(vec![]),
                        ColumnData::FloatList(_) => ColumnData::FloatList(vec![]),
                        ColumnData::Exact(_) => ColumnData::Exact(vec![]),
                    },
                    ..c.clone()
                })
                .collect(),
        };
        let (s0, r0) = (empty(&s0), empty(&r0));
        assert_eq!(in_blocks(&s0, &r0, 1e-9, 8), compare_tables(&s0, &r0, 1e-9));
    }

    #[test]
    fn floats_are_identical_within_tolerance_or_different() {
        let s = col("x", "f64", floats(&[1.0, f64::INFINITY, f64::NAN, 1e6]));
        let same = compare_columns(&s, &s.clone(), 1e-9);
        assert_eq!(same, ColumnVerdict::Identical);

        let near = col(
            "x",
            "f64",
            floats(&[1.0 + 1e-12, f64::INFINITY, f64::NAN, 1e6 + 1e-4]),
        );
        match compare_columns(&s, &near, 1e-9) {
            ColumnVerdict::WithinTolerance { max_abs_diff } => {
                assert!((max_abs_diff - 1e-4).abs() < 1e-9)
            }
            v => panic!("{v:?}"),
        }

        let far = col("x", "f64", floats(&[1.0, 1.0, f64::NAN, 1e6]));
        match compare_columns(&s, &far, 1e-9) {
            ColumnVerdict::Different {
                rows_differing,
                first,
                ..
            } => {
                assert_eq!(rows_differing, 1);
                assert_eq!(first[0].row, 1);
                assert_eq!(first[0].stored, "inf");
                assert_eq!(first[0].recomputed, "1.0");
            }
            v => panic!("{v:?}"),
        }
    }

    #[test]
    fn null_agrees_only_with_null() {
        let a = col("x", "f64", ColumnData::Float(vec![None, Some(1.0)]));
        let b = col("x", "f64", ColumnData::Float(vec![Some(0.0), Some(1.0)]));
        assert!(!compare_columns(&a, &b, 1.0).agrees());
        assert_eq!(compare_columns(&a, &a, 0.0), ColumnVerdict::Identical);
        // A value against a null has no numeric difference: none is claimed (not "0").
        match compare_columns(&a, &b, 0.0) {
            ColumnVerdict::Different { max_abs_diff, .. } => assert_eq!(max_abs_diff, None),
            v => panic!("{v:?}"),
        }
        let c = col("x", "f64", ColumnData::Float(vec![Some(0.0), Some(3.0)]));
        match compare_columns(&a, &c, 0.0) {
            ColumnVerdict::Different { max_abs_diff, .. } => assert_eq!(max_abs_diff, Some(2.0)),
            v => panic!("{v:?}"),
        }
    }

    #[test]
    fn float_lists_compare_by_element_and_length() {
        let l = |v: Vec<Option<Vec<Option<f64>>>>| col("h", "list[f64]", ColumnData::FloatList(v));
        let a = l(vec![Some(vec![Some(54.0)]), Some(vec![])]);
        let b = l(vec![Some(vec![Some(54.0 + 1e-12)]), Some(vec![])]);
        let c = l(vec![Some(vec![Some(54.0)]), Some(vec![Some(1.0)])]);
        assert!(matches!(
            compare_columns(&a, &b, 1e-9),
            ColumnVerdict::WithinTolerance { .. }
        ));
        match compare_columns(&a, &c, 1e-9) {
            ColumnVerdict::Different { first, .. } => {
                assert_eq!(first[0].row, 1);
                assert_eq!(first[0].stored, "[]");
                assert_eq!(first[0].recomputed, "[1.0]");
            }
            v => panic!("{v:?}"),
        }
    }

    #[test]
    fn exact_columns_timings_and_schema() {
        let s = table(vec![
            col(
                "regime",
                "str",
                ColumnData::Exact(vec![Some("\"stable\"".into())]),
            ),
            col("solve_time_us", "f64", floats(&[3.0])),
            col("gone", "u64", ColumnData::Exact(vec![Some("1".into())])),
        ]);
        let r = table(vec![
            col(
                "regime",
                "str",
                ColumnData::Exact(vec![Some("\"sliding\"".into())]),
            ),
            col("solve_time_us", "f64", floats(&[5.0])),
            col("new", "u64", ColumnData::Exact(vec![Some("1".into())])),
        ]);
        let c = compare_tables(&s, &r, 1e-9);
        let v: Vec<_> = c
            .columns
            .iter()
            .map(|c| (c.name.as_str(), &c.verdict))
            .collect();
        assert!(matches!(v[0], ("regime", ColumnVerdict::Different { .. })));
        assert_eq!(v[1], ("solve_time_us", &ColumnVerdict::Ignored));
        assert_eq!(v[2], ("gone", &ColumnVerdict::MissingFromRerun));
        assert_eq!(v[3], ("new", &ColumnVerdict::NotStored));
        assert!(!c.agrees());
        assert!(compare_tables(&s, &s, 0.0).agrees());
    }

    #[test]
    fn row_count_and_type_changes_are_differences() {
        let s = table(vec![col("x", "f64", floats(&[1.0, 2.0]))]);
        let r = table(vec![col("x", "f64", floats(&[1.0]))]);
        assert!(!compare_tables(&s, &r, 1e-9).agrees());
        let t = table(vec![col("x", "f32", floats(&[1.0, 2.0]))]);
        assert!(matches!(
            compare_tables(&s, &t, 1e-9).columns[0].verdict,
            ColumnVerdict::TypeChanged { .. }
        ));
    }

    #[test]
    fn timing_columns_are_recognised() {
        assert!(is_timing_column("solve_time_us"));
        assert!(is_timing_column("engine_ms"));
        assert!(!is_timing_column("mu"));
        assert!(!is_timing_column("status"));
    }
}
