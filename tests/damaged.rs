//! `archstudy report` on damaged tables: each is refused with exit status 2, naming the file,
//! the column and the row, and the report already there is left as it was.

use crate::common::{StudyRun, archstudy, assert_usage_error, study_run};
use archstudy::store;
use polars::prelude::{Column, DataType, NamedFrom, Series};
use std::path::Path;

/// An 11 × 11 grid over the paper's range: both bifurcations, so mechanisms are drawn.
const STUDY: &str = "name: damaged
grid:
  k: {from: 1.05, to: 1.5, steps: 11}
  mu: {from: 0.2, to: 0.8, steps: 11}
";

fn fresh_run(name: &str) -> StudyRun {
    study_run(name, "damaged.yaml", STUDY)
}

fn report_refuses(run: &Path, names: &[&str]) {
    let before = std::fs::read(run.join("report.html")).unwrap();
    let o = archstudy(&["report", run.to_str().unwrap()]);
    assert_usage_error(&o, names);
    assert_eq!(std::fs::read(run.join("report.html")).unwrap(), before);
}

#[test]
fn a_column_of_the_wrong_type_is_refused() {
    let run = fresh_run("damaged-type");
    let path = run.join("results.parquet");
    let mut df = store::read_parquet(&path).unwrap();
    let k = df.column("k").unwrap().cast(&DataType::String).unwrap();
    df.with_column(k).unwrap();
    store::write_parquet(&mut df, &path).unwrap();
    report_refuses(&run, &["results.parquet", "`k`", "not numbers"]);
}

#[test]
fn nan_and_infinite_values_are_refused_with_their_row() {
    for (name, value) in [("damaged-nan", f64::NAN), ("damaged-inf", f64::INFINITY)] {
        let run = fresh_run(name);
        let path = run.join("results.parquet");
        store::rewrite_f64_value(&path, "k", 7, Some(value)).unwrap();
        report_refuses(
            &run,
            &["results.parquet", "column `k`, row 7", "finite K > 1"],
        );
    }
}

#[test]
fn missing_rows_are_refused() {
    let run = fresh_run("damaged-rows");
    let path = run.join("results.parquet");
    let df = store::read_parquet(&path).unwrap();
    let mut short = df.slice(0, 100);
    store::write_parquet(&mut short, &path).unwrap();
    report_refuses(&run, &["results.parquet", "100 rows", "121 cases"]);
}

#[test]
fn a_drawing_that_is_not_json_is_refused() {
    let run = fresh_run("damaged-drawing");
    let path = run.join("mechanisms.parquet");
    let mut df = store::read_parquet(&path).unwrap();
    assert!(df.height() > 0, "the study has mechanisms to draw");
    let bad = vec!["{not json"; df.height()];
    df.with_column(Column::from(Series::new("drawing_json".into(), bad)))
        .unwrap();
    store::write_parquet(&mut df, &path).unwrap();
    report_refuses(
        &run,
        &[
            "mechanisms.parquet",
            "`drawing_json`, row 0",
            "not valid JSON",
        ],
    );
}

#[test]
fn an_unknown_regime_name_is_refused() {
    let run = fresh_run("damaged-regime");
    let path = run.join("results.parquet");
    let mut df = store::read_parquet(&path).unwrap();
    let n = df.height();
    let names: Vec<&str> = (0..n)
        .map(|i| if i == 3 { "wobbly" } else { "stable" })
        .collect();
    df.with_column(Column::from(Series::new("regime".into(), names)))
        .unwrap();
    store::write_parquet(&mut df, &path).unwrap();
    report_refuses(
        &run,
        &["results.parquet", "column `regime`, row 3", "\"wobbly\""],
    );
}

/// Rows are checked whole and a name already accepted is not looked up again, yet a name
/// archstudy never writes is found after a run of accepted ones, and the first fault of the
/// first column that has one is the one named.
#[test]
fn a_late_unknown_name_is_found_and_the_first_faulty_column_named() {
    let run = fresh_run("damaged-late-regime");
    let path = run.join("results.parquet");
    let mut df = store::read_parquet(&path).unwrap();
    let mut bad = store::str_column(&df, "regime").unwrap();
    bad[97] = Some("stabel".to_string());
    bad[98] = Some("stabel".to_string());
    df.with_column(Column::from(Series::new("regime".into(), bad)))
        .unwrap();
    store::write_parquet(&mut df, &path).unwrap();
    report_refuses(
        &run,
        &["results.parquet", "column `regime`, row 97", "\"stabel\""],
    );
    // A fault in an earlier column comes first, though its row is later.
    store::rewrite_f64_value(&path, "mu", 110, Some(-0.5)).unwrap();
    report_refuses(&run, &["results.parquet", "column `mu`, row 110"]);
}
