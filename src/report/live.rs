//! The data of a run held in memory: a plan just analysed, with its located boundaries,
//! put in the same rows a report reads from a run directory, so that a figure of a study
//! that was never written (the regime map around a scene in `archstudy explore`) is drawn
//! by the report's own chart builders. The rows pass through the same frames as the stored
//! tables; nothing touches the disk.

use super::data::{ManifestView, RunData};
use crate::boundaries::Located;
use crate::engine::CaseResult;
use crate::manifest::Manifest;
use crate::plan::Plan;
use crate::provenance::{self, CaseCounts, RunInfo};
use crate::store;
use anyhow::Result;
use std::path::Path;

/// Where in-memory rows come from, as errors name it.
const ORIGIN: &str = "(rows held in memory)";

/// The run data of `results` (every case of `plan`, in plan order) and `located`.
pub fn run_data(
    manifest: &Manifest,
    plan: &Plan,
    results: &[CaseResult],
    located: &Located,
) -> Result<RunData> {
    let origin = Path::new(ORIGIN);
    let rows = store::results_of_frame(&store::results_frame(plan, results)?, origin)?;
    let bifurcations_frame = store::bifurcations_frame(plan, located)?;
    let ok = rows.iter().filter(|r| &*r.status == "ok").count() as u64;
    let total = rows.len() as u64;
    let manifest_json = serde_json::to_value(manifest)?;
    let view: ManifestView = serde_json::from_value(manifest_json.clone())?;
    let info = RunInfo {
        name: manifest.name.clone(),
        manifest: manifest_json,
        manifest_sha256: String::new(),
        manifest_path: String::new(),
        archstudy_version: provenance::version().to_string(),
        git_commit: provenance::git_commit(),
        rustc_version: provenance::rustc_version().to_string(),
        command_line: Vec::new(),
        threads: rayon::current_num_threads(),
        started_at: String::new(),
        finished_at: String::new(),
        cases: CaseCounts {
            total,
            ok,
            error: total - ok,
        },
        separable: false,
        grid_path: String::new(),
        stages: Default::default(),
        boundary_refinement_analyses: located.refinement_analyses,
        table_sha256: Default::default(),
        shard_builds: Vec::new(),
    };
    let mut totals = super::reduce::ResultTotals::default();
    totals.add(&rows);
    totals.finish();
    Ok(RunData {
        info,
        manifest: view,
        results: rows,
        totals,
        boundaries: Some(store::boundaries_of_frame(
            &store::boundaries_frame(plan, located)?,
            origin,
        )?),
        bifurcations: Some(store::bifurcations_of_frame(&bifurcations_frame, origin)?),
        curves: Vec::new(),
        states: Vec::new(),
        reference: Vec::new(),
        mechanisms: Vec::new(),
        load_factors: Vec::new(),
        load_factor_singled: Vec::new(),
        bifurcation_groups: store::bifurcation_groups_of_frame(&bifurcations_frame),
        result_arches: Vec::new(),
        boundary_arches: Vec::new(),
        estimates: Vec::new(),
        samples: Vec::new(),
    })
}
