//! Reproducibility facts, stage timings and the files of the run directory.

use super::{Item, item};
use crate::report::data::RunData;
use crate::report::format::millis;

/// Where the run came from: manifest, versions, command line, threads, date.
pub fn reproducibility(data: &RunData) -> Vec<Item> {
    let i = &data.info;
    vec![
        item("manifest", i.manifest_path.clone()),
        item("manifest SHA-256", i.manifest_sha256.clone()),
        item("archstudy version", i.archstudy_version.clone()),
        item(
            "archstudy commit",
            i.git_commit.clone().unwrap_or_else(|| "unknown".into()),
        ),
        item("rustc", i.rustc_version.clone()),
        item("command line", i.command_line.join(" ")),
        item("threads", i.threads.to_string()),
        item("date", i.started_at.clone()),
        item("grid path", grid_path(i)),
    ]
}

/// How the engine went through the plan, in words.
fn grid_path(i: &crate::provenance::RunInfo) -> String {
    match i.grid_path.as_str() {
        "separable" => "separable: one H^r per K, one H^s per μ".into(),
        "k_lines" => "per K line: thresholds in μ by bisection".into(),
        "case_by_case" => "case by case".into(),
        _ if i.separable => "separable".into(),
        _ => "not recorded".into(),
    }
}

/// Wall time of each stage of the run.
pub fn stages(data: &RunData) -> Vec<Item> {
    let s = &data.info.stages;
    vec![
        item("plan", millis(s.plan_ms)),
        item("engine", millis(s.engine_ms)),
        item("store", millis(s.store_ms)),
        item("boundaries", millis(s.boundaries_ms)),
        item("figures", millis(s.plots_ms)),
    ]
}

/// The files of the run directory and what each holds.
pub fn files(data: &RunData) -> Vec<Item> {
    let mut v = vec![item(
        "results.parquet",
        "one row per case: inputs, regime or critical value, mechanism, solve time",
    )];
    if data.boundaries.is_some() {
        v.push(item(
            "boundaries.parquet",
            "regime boundaries located along the grid lines",
        ));
    }
    if data.bifurcations.is_some() {
        v.push(item(
            "bifurcations.parquet",
            "points where two collapse mechanisms coexist",
        ));
    }
    if data.manifest.sampling.is_some() {
        v.push(item(
            "samples.parquet",
            "one row per sample: the values of the uncertain parameters and the answer",
        ));
        v.push(item(
            "estimates.parquet",
            "probabilities, fragility curves, quantiles and Sobol indices with their intervals; \
             the exact probability and the convergence study",
        ));
        v.push(item(
            "curves.parquet",
            "figure data: the collapse curve drawn under the samples",
        ));
    } else {
        v.push(item(
            "curves.parquet, states.parquet, reference.parquet, mechanisms.parquet",
            "figure data: curves from the statics, drawn states, continuum references, \
             mechanisms at the bifurcations",
        ));
    }
    v.push(item(
        "run.json, manifest.yaml",
        "provenance: the resolved manifest, versions, timings; the manifest as given",
    ));
    v.push(item(
        "plots/",
        "every figure for print at the column width: PDF (fonts embedded), SVG and PNG (300 dpi)",
    ));
    v.push(item(
        "tables/",
        "every table of this report as CSV and as a LaTeX booktabs table",
    ));
    v
}
