//! `archstudy run` and `archstudy check`: manifest → plan → engine → store → boundaries →
//! figures and reports, with the provenance of the run in run.json.

use crate::boundaries;
use crate::cli::{CheckArgs, RunArgs, UsageError};
use crate::engine::{self, CaseResult, Progress, Status};
use crate::manifest::{self, Manifest};
use crate::output::{RunLayout, StagedRun, write_atomic};
use crate::plan::{self, Plan};
use crate::store;
use crate::{figdata, report};
use anyhow::{Context, Result};
use serde::Serialize;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Wall time of each stage of a run, in milliseconds.
#[derive(Debug, Clone, Default, Serialize, serde::Deserialize, PartialEq)]
pub struct StageTimings {
    /// Reading the manifest and building the plan.
    pub plan_ms: f64,
    /// Analysing every case.
    pub engine_ms: f64,
    /// Writing results.parquet.
    pub store_ms: f64,
    /// Locating boundaries and bifurcations and writing their tables.
    pub boundaries_ms: f64,
    /// Rendering the figures.
    pub plots_ms: f64,
    /// Rendering both reports.
    pub report_ms: f64,
}

/// Cases by status.
#[derive(Debug, Clone, Default, Serialize, serde::Deserialize, PartialEq)]
pub struct CaseCounts {
    /// All cases.
    pub total: u64,
    /// Cases that produced an answer.
    pub ok: u64,
    /// Cases that failed (see their `message`).
    pub error: u64,
}

/// Provenance of a run: what was run, with what, when, and how long it took.
#[derive(Debug, Clone, Serialize, serde::Deserialize, PartialEq)]
pub struct RunInfo {
    /// The study name.
    pub name: String,
    /// The resolved manifest (defaults filled in).
    pub manifest: serde_json::Value,
    /// SHA-256 of the manifest file as read.
    pub manifest_sha256: String,
    /// The manifest path as given.
    pub manifest_path: String,
    /// archstudy version.
    pub archstudy_version: String,
    /// Git commit of the build, when known (`-dirty` when built from a modified tree).
    pub git_commit: Option<String>,
    /// rustc that built archstudy.
    pub rustc_version: String,
    /// The command line.
    pub command_line: Vec<String>,
    /// Worker threads.
    pub threads: usize,
    /// Start time (RFC 3339, UTC).
    pub started_at: String,
    /// End time (RFC 3339, UTC).
    pub finished_at: String,
    /// Cases by status.
    pub cases: CaseCounts,
    /// Whether the separable fast path was used (symmetric `state` grid).
    pub separable: bool,
    /// Wall time of each stage.
    pub stages: StageTimings,
    /// Extra analyses spent locating boundaries and bifurcations.
    pub boundary_refinement_analyses: u64,
}

/// The version of archstudy.
pub fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

/// The git commit archstudy was built from, when known.
pub fn git_commit() -> Option<String> {
    let c = env!("ARCHSTUDY_GIT_COMMIT");
    (!c.is_empty()).then(|| c.to_string())
}

/// Hex SHA-256 of some bytes.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Reads, validates and expands a manifest (every error here is bad input: exit 2).
pub fn load_plan(path: &Path) -> Result<(Plan, Vec<u8>)> {
    let bytes = std::fs::read(path).map_err(|e| manifest::ManifestError {
        path: path.to_path_buf(),
        position: None,
        key: None,
        message: format!("cannot read the manifest: {e}"),
    })?;
    let text = String::from_utf8(bytes.clone()).map_err(|_| manifest::ManifestError {
        path: path.to_path_buf(),
        position: None,
        key: None,
        message: "the manifest is not valid UTF-8 text".into(),
    })?;
    let m: Manifest = manifest::parse(&text, path)?;
    let plan = plan::build(m).map_err(|e| manifest::ManifestError {
        path: path.to_path_buf(),
        position: None,
        key: Some("grid".into()),
        message: e.to_string(),
    })?;
    Ok((plan, bytes))
}

/// `archstudy check`: validate and print the plan.
pub fn check_command(args: &CheckArgs) -> Result<ExitCode> {
    let (plan, bytes) = load_plan(&args.study)?;
    print!("{}", plan.describe());
    println!("manifest sha256: {}", sha256_hex(&bytes));
    Ok(ExitCode::SUCCESS)
}

/// Options of a run, as domain values.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// The manifest.
    pub study: PathBuf,
    /// Directory under which `<name>/` is written.
    pub out: PathBuf,
    /// Worker threads (None: all cores).
    pub jobs: Option<usize>,
    /// Progress bar or not.
    pub progress: Progress,
    /// The command line recorded in run.json.
    pub command_line: Vec<String>,
}

/// `archstudy run` from the command line.
pub fn run_command(args: &RunArgs) -> Result<ExitCode> {
    if let Some(0) = args.jobs {
        return Err(UsageError {
            option: "--jobs",
            value: "0".into(),
            allowed: "the number of threads must be at least 1".into(),
        }
        .into());
    }
    let opts = RunOptions {
        study: args.study.clone(),
        out: args.out.clone(),
        jobs: args.jobs,
        progress: if args.quiet {
            Progress::Hidden
        } else {
            Progress::Auto
        },
        command_line: std::env::args().collect(),
    };
    let summary = run_study(&opts)?;
    eprintln!(
        "{} cases ({} ok, {} failed) in {:.2} s; written to {}",
        summary.info.cases.total,
        summary.info.cases.ok,
        summary.info.cases.error,
        summary.wall_s,
        summary.dir.display()
    );
    if summary.info.cases.error > 0 {
        eprintln!(
            "warning: {} cases failed; their rows carry status `error` and a message",
            summary.info.cases.error
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// What a finished run reports.
#[derive(Debug)]
pub struct RunSummary {
    /// The run directory.
    pub dir: PathBuf,
    /// Its run.json.
    pub info: RunInfo,
    /// Total wall time in seconds.
    pub wall_s: f64,
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn write_run_json(layout: &RunLayout, info: &RunInfo) -> Result<()> {
    write_atomic(
        &layout.run_json(),
        serde_json::to_string_pretty(info)?.as_bytes(),
    )
}

/// Figure data, figures and both reports, from the stored files of the run; run.json is
/// written first (the reports read it) and again with the figure and report timings.
fn publish(plan: &Plan, layout: &RunLayout, info: &mut RunInfo) -> Result<()> {
    write_run_json(layout, info)?;
    let t = Instant::now();
    figdata::run(plan, layout)?;
    let mut data = report::data::load(layout)?;
    let figs = report::draw_figures(&data, layout)?;
    info.stages.plots_ms = ms(t);
    write_run_json(layout, info)?;
    let t = Instant::now();
    data.info = report::data::load_info(layout)?;
    report::write_reports(&data, &figs, layout)?;
    info.stages.report_ms = ms(t);
    info.finished_at = chrono::Utc::now().to_rfc3339_opts(chrono::SecondsFormat::Millis, true);
    write_run_json(layout, info)
}

/// Runs a study end to end and moves the complete run directory into place.
pub fn run_study(opts: &RunOptions) -> Result<RunSummary> {
    let t0 = Instant::now();
    let started_at = chrono::Utc::now().to_rfc3339_opts(chrono::SecondsFormat::Millis, true);
    let (plan, bytes) = load_plan(&opts.study)?;
    let mut stages = StageTimings {
        plan_ms: ms(t0),
        ..Default::default()
    };
    let threads = opts
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("cannot start the worker threads")?;
    // Output is staged first: a bad output path fails before any work.
    let staged = StagedRun::create(&opts.out, &plan.manifest.name)?;
    let layout = staged.layout.clone();
    std::fs::write(layout.manifest(), &bytes)
        .with_context(|| format!("cannot write {}", layout.manifest().display()))?;

    let t = Instant::now();
    let results: Vec<CaseResult> = pool.install(|| engine::run(&plan, opts.progress));
    stages.engine_ms = ms(t);

    let t = Instant::now();
    let mut df = pool.install(|| store::results_frame(&plan, &results))?;
    store::write_parquet(&mut df, &layout.results())?;
    drop(df);
    stages.store_ms = ms(t);

    let t = Instant::now();
    let located = pool.install(|| boundaries::locate(&plan, &results));
    store::write_parquet(
        &mut store::boundaries_frame(&plan, &located)?,
        &layout.boundaries(),
    )?;
    store::write_parquet(
        &mut store::bifurcations_frame(&plan, &located)?,
        &layout.bifurcations(),
    )?;
    stages.boundaries_ms = ms(t);

    let ok = results.iter().filter(|r| r.status == Status::Ok).count() as u64;
    let total = results.len() as u64;
    // Figures and reports read the stored files: the engine's rows (hundreds of bytes a case)
    // are not needed past this point.
    drop(results);
    let mut info = RunInfo {
        name: plan.manifest.name.clone(),
        manifest: serde_json::to_value(&plan.manifest)?,
        manifest_sha256: sha256_hex(&bytes),
        manifest_path: opts.study.display().to_string(),
        archstudy_version: version().to_string(),
        git_commit: git_commit(),
        rustc_version: env!("ARCHSTUDY_RUSTC_VERSION").to_string(),
        command_line: opts.command_line.clone(),
        threads,
        started_at,
        finished_at: String::new(),
        cases: CaseCounts {
            total,
            ok,
            error: total - ok,
        },
        separable: plan.is_separable_state_grid(),
        stages,
        boundary_refinement_analyses: located.refinement_analyses,
    };
    // Figure data, figures and reports, from the stored files.
    publish(&plan, &layout, &mut info)?;
    let dir = staged.commit()?;
    Ok(RunSummary {
        dir,
        info,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}
