//! `archstudy run` and `archstudy check`: manifest → plan → engine → store → boundaries →
//! figures and reports, with the provenance of the run in run.json.

use crate::boundaries;
use crate::engine::{self, CaseResult, Status};
use crate::manifest::{self, FigureWidth, Manifest};
use crate::output::{RunLayout, StagedRun, write_atomic};
use crate::plan::{self, Plan};
use crate::progress::{Progress, Silent, Stage};
use crate::provenance::{
    CaseCounts, RunInfo, StageTimings, git_commit, now_rfc3339, rustc_version, sha256_hex, version,
};
use crate::store;
use crate::{citation, figdata, report};
use anyhow::{Context, Result};
use polars::prelude::DataFrame;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// The signal that interrupted the process (0 while none has): set before the partial output
/// is removed, so that work failing because its files vanished exits as interrupted.
static INTERRUPTED: std::sync::atomic::AtomicI32 = std::sync::atomic::AtomicI32::new(0);

/// The signal that interrupted the process, once the interrupt handler has taken one.
pub fn interrupted_by() -> Option<i32> {
    match INTERRUPTED.load(std::sync::atomic::Ordering::SeqCst) {
        0 => None,
        sig => Some(sig),
    }
}
mod memory;
pub use memory::gib;
pub use memory::{
    ARCH_BYTES, BYTES_PER_CASE, CHUNK_BYTES_CRITICAL, CHUNK_BYTES_LOAD_FACTOR, CHUNK_BYTES_STATE,
    LATTICE_BYTES_CRITICAL, LATTICE_BYTES_LOAD_FACTOR, LATTICE_BYTES_PER_CASE, MemoryModel,
    PROGRAM_BYTES, VERIFY_BYTES_PER_CASE, available_memory,
};

/// Installs the handler of Ctrl-C (SIGINT) and SIGTERM: the staging directory and every
/// temporary file this process is writing are removed, then the process exits with status
/// 128 + the signal (130 for Ctrl-C, 143 for SIGTERM). Called once by the command line;
/// later calls do nothing.
pub fn remove_partial_output_on_interrupt() -> Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    static INSTALLED: std::sync::OnceLock<()> = std::sync::OnceLock::new();
    if INSTALLED.get().is_some() {
        return Ok(());
    }
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])
        .context("cannot install the Ctrl-C and SIGTERM handler")?;
    let _ = INSTALLED.set(());
    std::thread::Builder::new()
        .name("interrupt".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                INTERRUPTED.store(sig, std::sync::atomic::Ordering::SeqCst);
                crate::output::remove_pending();
                std::process::exit(128 + sig);
            }
        })
        .context("cannot start the Ctrl-C and SIGTERM handler")?;
    Ok(())
}

pub use crate::manifest::MAX_MANIFEST_BYTES;

/// Reads a manifest file of at most [`MAX_MANIFEST_BYTES`].
fn read_manifest(path: &Path) -> Result<Vec<u8>, manifest::ManifestError> {
    use std::io::Read;
    let err = |message: String| manifest::ManifestError {
        path: path.to_path_buf(),
        position: None,
        key: None,
        message,
    };
    // Checked before opening: opening a FIFO waits for a writer.
    let meta =
        std::fs::metadata(path).map_err(|e| err(format!("cannot read the manifest: {e}")))?;
    if !meta.is_file() {
        return Err(err(
            "not a regular file: a manifest is a YAML file (devices, pipes and directories are not read)".into(),
        ));
    }
    let too_big = || {
        err(format!(
            "the manifest is larger than {MAX_MANIFEST_BYTES} bytes (1 MiB), the limit of a study \
             manifest: describe the grid with {{from, to, steps}} ranges rather than long value lists"
        ))
    };
    if meta.len() > MAX_MANIFEST_BYTES {
        return Err(too_big());
    }
    let file =
        std::fs::File::open(path).map_err(|e| err(format!("cannot read the manifest: {e}")))?;
    let mut bytes = Vec::new();
    file.take(MAX_MANIFEST_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| err(format!("cannot read the manifest: {e}")))?;
    if bytes.len() as u64 > MAX_MANIFEST_BYTES {
        return Err(too_big());
    }
    Ok(bytes)
}

/// Reads and validates a manifest without expanding it: the manifest and the file's bytes.
pub fn load_manifest(path: &Path) -> Result<(Manifest, Vec<u8>)> {
    let bytes = read_manifest(path)?;
    let text = String::from_utf8(bytes.clone()).map_err(|_| manifest::ManifestError {
        path: path.to_path_buf(),
        position: None,
        key: None,
        message: "the manifest is not valid UTF-8 text".into(),
    })?;
    Ok((manifest::parse(&text, path)?, bytes))
}

/// Reads and validates a manifest and checks that its run fits (every error here is bad
/// input: exit 2): a plan whose run would not fit in memory, or that has more than
/// [`plan::MAX_CASES`] cases, is refused before anything is expanded, naming `--shard`.
pub fn load_runnable(path: &Path) -> Result<(Manifest, Vec<u8>)> {
    let (m, bytes) = load_manifest(path)?;
    if let Some(message) = unsharded_refusal(&m, available_memory()) {
        return Err(manifest::ManifestError {
            path: path.to_path_buf(),
            position: None,
            key: Some(
                if m.sampling.is_some() {
                    "samples"
                } else {
                    "grid"
                }
                .into(),
            ),
            message,
        }
        .into());
    }
    Ok((m, bytes))
}

/// Why an unsharded run of a manifest is refused, or None when it fits: a plan whose run
/// would need more than `available` bytes (see [`MemoryModel::check`]), or that has more than
/// [`plan::MAX_CASES`] cases. Counted, never expanded. The message names `--shard` and the
/// memory the run would need.
pub fn unsharded_refusal(m: &Manifest, available: Option<u64>) -> Option<String> {
    let requested = plan::case_count(m);
    let model = MemoryModel::of(m);
    if let Err(message) = model.check(requested, available) {
        return Some(message);
    }
    if requested > u128::from(plan::MAX_CASES) {
        let e = plan::PlanTooLarge { requested };
        return Some(format!(
            "{e} (its run would need about {} of memory)",
            gib(model.needed(u64::try_from(e.requested).unwrap_or(u64::MAX)))
        ));
    }
    None
}

/// Reads, validates and expands a manifest, refused as by [`load_runnable`].
pub fn load_plan(path: &Path) -> Result<(Plan, Vec<u8>)> {
    let (m, bytes) = load_runnable(path)?;
    let total = u64::try_from(plan::case_count(&m)).unwrap_or(u64::MAX);
    Ok((plan::build_slice(m, 0..total), bytes))
}

/// What `archstudy check` shows of a manifest.
#[derive(Debug, Clone)]
pub struct CheckSummary {
    /// The plan, described axis by axis (several lines), and how it runs: unsharded with
    /// the memory it needs, or in shards only, with the reason an unsharded run is refused.
    pub plan: String,
    /// Hex SHA-256 of the manifest file.
    pub manifest_sha256: String,
    /// Why an unsharded run is refused (it runs in shards), or None.
    pub unsharded_refusal: Option<String>,
}

/// Validates a manifest and describes its plan without running or expanding it: a plan of
/// 10⁸ cases, which runs in shards only, is checked as quickly as one of ten, and its
/// description says why an unsharded run is refused and how to shard it.
pub fn check(study: &Path) -> Result<CheckSummary> {
    let (m, bytes) = load_manifest(study)?;
    let refusal = unsharded_refusal(&m, available_memory());
    let cases = u64::try_from(plan::case_count(&m)).unwrap_or(u64::MAX);
    let mut plan = plan::describe(&m);
    match &refusal {
        None => {
            let model = MemoryModel::of(&m);
            plan.push_str(&format!(
                "memory: about {} for a run ({} bytes a case and {} besides)\n",
                gib(model.needed(cases)),
                model.per_case,
                gib(model.base_bytes(cases))
            ));
        }
        Some(why) => plan.push_str(&format!(
            "runs in shards only: an unsharded run is refused: {why}\n"
        )),
    }
    Ok(CheckSummary {
        plan,
        manifest_sha256: sha256_hex(&bytes),
        unsharded_refusal: refusal,
    })
}

/// Options of a run, as domain values.
#[derive(Clone)]
pub struct RunOptions {
    /// The manifest.
    pub study: PathBuf,
    /// Directory under which `<name>/` is written.
    pub out: PathBuf,
    /// Worker threads (None: all cores; Some(0) is refused).
    pub jobs: Option<usize>,
    /// Where the stages report their progress.
    pub progress: Arc<dyn Progress>,
    /// The command line recorded in run.json.
    pub command_line: Vec<String>,
    /// The column width of the paper figures, replacing the manifest's `figures.width`
    /// (recorded in run.json's resolved manifest, so `report` re-draws the same).
    pub figure_width: Option<FigureWidth>,
}

impl RunOptions {
    /// Runs `study` into `out/<name>/` on every core, silently, recording no command line.
    pub fn new(study: impl Into<PathBuf>, out: impl Into<PathBuf>) -> Self {
        RunOptions {
            study: study.into(),
            out: out.into(),
            jobs: None,
            progress: Arc::new(Silent),
            command_line: Vec::new(),
            figure_width: None,
        }
    }
}

impl std::fmt::Debug for RunOptions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RunOptions")
            .field("study", &self.study)
            .field("out", &self.out)
            .field("jobs", &self.jobs)
            .field("command_line", &self.command_line)
            .finish_non_exhaustive()
    }
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

pub(crate) fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn write_run_json(layout: &RunLayout, info: &RunInfo) -> Result<()> {
    write_atomic(
        &layout.run_json(),
        serde_json::to_string_pretty(info)?.as_bytes(),
    )
}

/// Runs `work` as one stage of the run, reported to `progress` and timed in milliseconds.
pub(crate) fn stage<T>(
    progress: &dyn Progress,
    stage: Stage,
    work: impl FnOnce() -> Result<T>,
) -> Result<(T, f64)> {
    let t = Instant::now();
    if progress.stopped() {
        return Err(crate::progress::Stopped.into());
    }
    progress.begin(stage, None);
    let out = work();
    progress.end(stage);
    if progress.stopped() {
        return Err(crate::progress::Stopped.into());
    }
    Ok((out?, ms(t)))
}

/// Figure data, figures and both reports, from the stored files of the run (`results`:
/// results.parquet as read back for the report); run.json is written first (the reports
/// read it) and again with the figure and report timings.
fn publish(
    m: &Manifest,
    layout: &RunLayout,
    info: &mut RunInfo,
    progress: &dyn Progress,
    results: report::data::ResultsRead,
) -> Result<()> {
    write_run_json(layout, info)?;
    let t = Instant::now();
    stage(progress, Stage::FigureData, || figdata::run(m, layout))?;
    // Every table is written: run.json records their hashes before the reports show it.
    info.table_sha256 = layout.table_sha256()?;
    let mut data = report::data::load_with(layout, Some(results))?;
    let (figs, _) = stage(progress, Stage::Figures, || {
        report::draw_figures(&data, layout)
    })?;
    info.stages.plots_ms = ms(t);
    write_run_json(layout, info)?;
    let ((), report_ms) = stage(progress, Stage::Reports, || {
        data.info = report::data::load_info(layout)?;
        report::write_reports(&data, &figs, layout)
    })?;
    info.stages.report_ms = report_ms;
    // A million rows take tens of milliseconds to free, and nothing waits for them: they are
    // freed on a thread of their own while the run is finished (or the process ends).
    // (Where no thread can be started, the closure and its rows are dropped here.)
    let rows = std::mem::take(&mut data.results);
    let _ = std::thread::Builder::new().spawn(move || drop(rows));
    info.finished_at = now_rfc3339();
    write_run_json(layout, info)?;
    citation::write_crate_metadata(layout, m, info)
}

/// The worker pool of a run: `jobs` threads, or one per core.
pub fn worker_pool(jobs: Option<usize>) -> Result<(rayon::ThreadPool, usize)> {
    let threads = match jobs {
        Some(0) => anyhow::bail!("a run needs at least one worker thread"),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("cannot start the worker threads")?;
    Ok((pool, threads))
}

/// Cases analysed and stored at a time: the engine's rows of one chunk are appended to
/// results.parquet as row groups and dropped, so that the memory of a run does not grow with
/// its number of cases. The rows are those of one pass (the engine's answer for a case does
/// not depend on the other cases it runs with), and a chunk is a block of the results table
/// ([`store::BLOCK_ROWS`]), so the file holds the data of one pass too.
pub const CHUNK_CASES: u64 = memory::CHUNK_CASES;

/// results.parquet written chunk by chunk in plan order, with the count of the rows and the
/// cell code ([`boundaries::cell_code`]) of each, all the boundaries stage reads of a row.
pub(crate) struct ResultsWriter {
    path: PathBuf,
    appender: Option<store::ParquetAppender>,
    /// One cell code per row written, in order.
    pub codes: Vec<u8>,
    /// Rows whose analysis ran.
    pub ok: u64,
    /// Rows written.
    pub total: u64,
}

impl ResultsWriter {
    /// A writer of `path` (nothing is written until the first chunk).
    pub fn new(path: &Path) -> Self {
        ResultsWriter {
            path: path.to_path_buf(),
            appender: None,
            codes: Vec::new(),
            ok: 0,
            total: 0,
        }
    }

    /// Appends the rows of the cases of `plan` (a slice), in its order.
    pub fn push(
        &mut self,
        plan: &Plan,
        rows: &[CaseResult],
        pool: &rayon::ThreadPool,
    ) -> Result<()> {
        let mut df = self.table(plan, rows, pool)?;
        store::ParquetAppender::append_or_create(&mut self.appender, &self.path, &mut df)
    }

    /// The table of the rows of the cases of `plan` (a slice), their codes and counts taken:
    /// what [`store::ParquetAppender::append_or_create`] writes next.
    fn table(
        &mut self,
        plan: &Plan,
        rows: &[CaseResult],
        pool: &rayon::ThreadPool,
    ) -> Result<DataFrame> {
        let df = pool.install(|| store::results_frame(plan, rows))?;
        self.codes.extend(rows.iter().map(boundaries::cell_code));
        self.count(
            rows.len(),
            rows.iter().filter(|r| r.status == Status::Ok).count(),
        );
        Ok(df)
    }

    /// [`table`](Self::table) of the rows of a chunk, compact or full.
    fn table_of(
        &mut self,
        plan: &Plan,
        rows: &engine::Rows,
        pool: &rayon::ThreadPool,
    ) -> Result<DataFrame> {
        match rows {
            engine::Rows::Cases(rows) => self.table(plan, rows, pool),
            engine::Rows::States(states) => {
                let df = pool.install(|| store::state_results_frame(plan, states))?;
                self.codes
                    .extend(states.iter().map(boundaries::state_cell_code));
                let ok = states.iter().filter(|r| r.answer.is_some()).count();
                self.count(states.len(), ok);
                Ok(df)
            }
        }
    }

    fn count(&mut self, rows: usize, ok: usize) {
        self.ok += ok as u64;
        self.total += rows as u64;
    }

    /// Writes the footer and moves the file into place.
    pub fn finish(&mut self) -> Result<()> {
        match self.appender.take() {
            Some(a) => a.finish(),
            None => Ok(()),
        }
    }
}

/// A chunk's table being appended on its own thread; it gives the appender back.
type Writing<'scope> =
    std::thread::ScopedJoinHandle<'scope, Result<Option<store::ParquetAppender>>>;

/// What a scoped thread doing `what` gave, its error, or the panic that stopped it.
fn joined<T>(h: std::thread::ScopedJoinHandle<'_, Result<T>>, what: &str) -> Result<T> {
    h.join()
        .map_err(|p| anyhow::anyhow!("{what} stopped unexpectedly: {}", engine::panic_message(p)))?
}

/// What analysing a slice of a plan in chunks produced.
pub(crate) struct Chunked {
    /// The rows written, their codes and counts.
    pub written: ResultsWriter,
    /// Time in the engine, ms.
    pub engine_ms: f64,
    /// Time writing results.parquet, ms.
    pub store_ms: f64,
}

/// Analyses the cases `ids` of a manifest's plan chunk by chunk (`chunk` cases, the plan
/// expanded one chunk at a time), appending each chunk's rows to `results` in plan order.
pub(crate) fn analyse_in_chunks(
    m: &Manifest,
    ids: std::ops::Range<u64>,
    pool: &rayon::ThreadPool,
    progress: &dyn Progress,
    (results, chunk): (&Path, u64),
) -> Result<Chunked> {
    let mut starts: Vec<u64> = ids.clone().step_by(chunk.max(1) as usize).collect();
    if starts.is_empty() {
        // An empty slice still writes its (empty) table.
        starts.push(ids.start);
    }
    let mut out = Chunked {
        written: ResultsWriter::new(results),
        engine_ms: 0.0,
        store_ms: 0.0,
    };
    // One progress stage over all chunks, so the bar and the rate do not restart.
    progress.begin(Stage::Analyse, Some(ids.end - ids.start));
    // One buffer of rows for every chunk: its pages are cleared by the kernel once. A chunk's
    // table is written on its own thread while the next chunk is analysed (one at a time,
    // so that at most two chunks' tables are held).
    let mut rows = engine::Rows::default();
    let path = results.to_path_buf();
    std::thread::scope(|scope| -> Result<()> {
        let mut writing: Option<Writing<'_>> = None;
        let mut chunks = || -> Result<()> {
            for &start in &starts {
                let plan = plan::build_slice(m.clone(), start..(start + chunk).min(ids.end));
                let t = Instant::now();
                pool.install(|| engine::analyse_rows(&plan, progress, &mut rows));
                if progress.stopped() {
                    return Err(crate::progress::Stopped.into());
                }
                out.engine_ms += ms(t);
                let t = Instant::now();
                let mut df = out.written.table_of(&plan, &rows, pool)?;
                // The rows' own allocations (hinges, messages) are freed; the buffer is kept.
                rows.clear();
                memory::release_freed_memory();
                let mut appender = match writing.take() {
                    Some(w) => joined(w, "writing results.parquet")?,
                    None => out.written.appender.take(),
                };
                let path = &path;
                writing = Some(scope.spawn(move || {
                    store::ParquetAppender::append_or_create(&mut appender, path, &mut df)?;
                    Ok(appender)
                }));
                out.store_ms += ms(t);
            }
            Ok(())
        };
        let analysed = chunks();
        // The last write is waited for whatever stopped the loop: its error (or panic) is
        // reported after the loop's own.
        let t = Instant::now();
        let last = writing.take().map(|w| joined(w, "writing results.parquet"));
        analysed?;
        if let Some(appender) = last {
            out.written.appender = appender?;
        }
        out.store_ms += ms(t);
        Ok(())
    })?;
    progress.end(Stage::Analyse);
    let t = Instant::now();
    out.written.finish()?;
    out.store_ms += ms(t);
    Ok(out)
}

/// What the stages after the engine start from: the manifest, and results.parquet written
/// with the cell code of every case (by the engine, or from the shards of a sharded run).
pub(crate) struct Analysed {
    /// The manifest of the plan.
    pub manifest: Manifest,
    /// The manifest file's bytes.
    pub bytes: Vec<u8>,
    /// The manifest's path as given, recorded in run.json.
    pub manifest_path: String,
    /// The cell code of every case, in plan order, and the counts of results.parquet.
    pub written: ResultsWriter,
    /// Timings so far (plan, engine, store).
    pub stages: StageTimings,
    /// When the run started (RFC 3339).
    pub started_at: String,
    /// The builds that analysed the rows, for a merged run (empty otherwise).
    pub shard_builds: Vec<crate::provenance::ShardBuild>,
}

/// Runs a study end to end and moves the complete run directory into place. The plan is
/// analysed and stored chunk by chunk ([`CHUNK_CASES`]): no stage holds every row.
pub fn run_study(opts: &RunOptions) -> Result<RunSummary> {
    let t0 = Instant::now();
    let started_at = now_rfc3339();
    let progress = opts.progress.as_ref();
    let (mut m, bytes) = load_runnable(&opts.study)?;
    if let Some(w) = opts.figure_width {
        m.figure_width = w;
    }
    let total = u64::try_from(plan::case_count(&m)).unwrap_or(u64::MAX);
    let mut stages = StageTimings {
        plan_ms: ms(t0),
        ..Default::default()
    };
    let (pool, threads) = worker_pool(opts.jobs)?;
    // Output is staged first: a bad output path fails before any work.
    let staged = StagedRun::create(&opts.out, &m.name)?;
    write_atomic(&staged.layout.manifest(), &bytes)?;
    let done = analyse_in_chunks(
        &m,
        0..total,
        &pool,
        progress,
        (&staged.layout.results(), CHUNK_CASES),
    )?;
    (stages.engine_ms, stages.store_ms) = (done.engine_ms, done.store_ms);
    let analysed = Analysed {
        manifest: m,
        bytes,
        manifest_path: opts.study.display().to_string(),
        written: done.written,
        stages,
        started_at,
        shard_builds: Vec::new(),
    };
    finish_run(analysed, staged, (&pool, threads), opts, t0)
}

/// The stages after the engine and the store, shared by `archstudy run` and `archstudy
/// merge`: boundaries and bifurcations located from the cell codes and stored, run.json,
/// figure data, figures and reports; then the staged run directory is moved into place.
pub(crate) fn finish_run(
    a: Analysed,
    staged: StagedRun,
    (pool, threads): (&rayon::ThreadPool, usize),
    opts: &RunOptions,
    t0: Instant,
) -> Result<RunSummary> {
    let progress = opts.progress.as_ref();
    let Analysed {
        manifest: m,
        bytes,
        manifest_path,
        written,
        stages,
        started_at,
        shard_builds,
    } = a;
    let layout = staged.layout.clone();
    // The plan's description without its cases: they are expanded a chunk at a time.
    let empty = plan::build_slice(m.clone(), 0..0);
    // The report's rows come from results.parquet alone: they are read while the boundaries
    // are located, which leaves a core idle for much of its time; the stage ends when both
    // are done. A stop ends the read at its next block.
    let stop = || progress.stopped();
    let ((located, boundaries_ms), results) = std::thread::scope(|scope| {
        let reader = scope
            .spawn(|| pool.install(|| report::data::read_results(&layout, written.total, &stop)));
        let located = stage(progress, Stage::Boundaries, || {
            let located = pool.install(|| boundaries::locate_codes(&m, &written.codes, progress));
            store::write_parquet(
                &mut store::boundaries_frame(&empty, &located)?,
                &layout.boundaries(),
            )?;
            store::write_parquet(
                &mut store::bifurcations_frame(&empty, &located)?,
                &layout.bifurcations(),
            )?;
            Ok(located)
        });
        let t = Instant::now();
        let results = joined(reader, "reading results.parquet back");
        let (located, located_ms) = located?;
        anyhow::Ok(((located, located_ms + ms(t)), results?))
    })?;
    let (ok, total) = (written.ok, written.total);
    drop(written);
    let mut info = RunInfo {
        name: m.name.clone(),
        manifest: serde_json::to_value(&m)?,
        manifest_sha256: sha256_hex(&bytes),
        manifest_path,
        archstudy_version: version().to_string(),
        git_commit: git_commit(),
        rustc_version: rustc_version().to_string(),
        command_line: opts.command_line.clone(),
        threads,
        started_at,
        finished_at: String::new(),
        cases: CaseCounts {
            total,
            ok,
            error: total - ok,
        },
        separable: empty.is_separable_state_grid(),
        grid_path: engine::GridPath::of(&empty).as_str().to_string(),
        stages: StageTimings {
            boundaries_ms,
            ..stages
        },
        boundary_refinement_analyses: located.refinement_analyses,
        table_sha256: std::collections::BTreeMap::new(),
        shard_builds,
    };
    // Figure data, figures and reports, from the stored files.
    publish(&m, &layout, &mut info, progress, results)?;
    let dir = staged.commit()?;
    Ok(RunSummary {
        dir,
        info,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}
