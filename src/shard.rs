//! Sharded runs: `archstudy run STUDY --shard I/N` analyses shard I of N, a contiguous slice
//! of the plan in case-id order (sizes differ by at most one case; a shard may be empty when
//! N exceeds the number of cases), into its own directory `OUT/<name>.shard-I-of-N/`:
//! manifest.yaml, results.parquet (the slice's rows, schema of a whole run's) and run.json
//! with the manifest's SHA-256 and a `shard` entry. No boundaries, figures or reports: those
//! come from `archstudy merge` over the N directories (src/merge.rs). A shard directory is
//! staged and renamed like a run: an interrupted shard leaves nothing behind.

use crate::engine;
use crate::error::UsageError;
use crate::output::{StagedRun, write_atomic};
use crate::plan;
use crate::provenance::{
    CaseCounts, RunInfo, StageTimings, git_commit, now_rfc3339, rustc_version, sha256_hex, version,
};
use crate::runner::{self, RunOptions, RunSummary, analyse_in_chunks, ms, worker_pool};
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Shard `index` (1-based) of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, from 1 to `count`.
    pub index: u64,
    /// How many shards the plan is split into.
    pub count: u64,
}

/// Largest number of shards a plan may be split into.
pub const MAX_SHARDS: u64 = 1_000_000;

impl Shard {
    /// Parses `I/N` (1 ≤ I ≤ N ≤ [`MAX_SHARDS`]); `option` names the flag in the error.
    pub fn parse(option: &'static str, text: &str) -> Result<Shard, UsageError> {
        let bad = || {
            UsageError::new(
                option,
                text,
                format!(
                    "a shard is I/N with whole numbers 1 ≤ I ≤ N ≤ {MAX_SHARDS}, e.g. 3/8 for \
                     the third of eight shards (a Slurm array task runs \
                     --shard $((SLURM_ARRAY_TASK_ID+1))/N)"
                ),
            )
        };
        let (i, n) = text.trim().split_once('/').ok_or_else(bad)?;
        let index: u64 = i.trim().parse().map_err(|_| bad())?;
        let count: u64 = n.trim().parse().map_err(|_| bad())?;
        if index == 0 || index > count || count > MAX_SHARDS {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// The shard directory's name for a study, e.g. `seed.shard-03-of-16`: the index is
    /// padded to the width of the count, so the directories sort in shard order.
    pub fn dir_name(&self, study: &str) -> String {
        let width = self.count.to_string().len();
        format!(
            "{study}.shard-{:0width$}-of-{}",
            self.index,
            self.count,
            width = width
        )
    }
}

/// The `shard` entry of a shard's run.json.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardInfo {
    /// Which shard, from 1 to `count`.
    pub index: u64,
    /// How many shards the plan is split into.
    pub count: u64,
    /// Cases in the whole plan.
    pub plan_cases: u64,
    /// Id of the shard's first case.
    pub first_case: u64,
    /// Cases in the shard (ids `first_case ..< first_case + cases`).
    pub cases: u64,
    /// Peak resident memory of the shard's process, in bytes, when known.
    #[serde(default)]
    pub peak_rss_bytes: Option<u64>,
}

/// A shard's run.json: a run's provenance and the `shard` entry.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ShardRunInfo {
    /// Provenance, as in a run's run.json (`cases` counts the shard's cases).
    #[serde(flatten)]
    pub info: RunInfo,
    /// Which slice of the plan.
    pub shard: ShardInfo,
}

/// The number of cases of a manifest's plan, refused when it does not fit in 64 bits.
fn plan_cases(m: &crate::manifest::Manifest) -> Result<u64, UsageError> {
    let n = plan::case_count(m);
    u64::try_from(n).map_err(|_| {
        UsageError::new(
            "STUDY",
            &m.name,
            format!("the plan has {n} cases, more than any run can hold: reduce the grid"),
        )
    })
}

/// Cases a shard analyses and stores at a time ([`runner::CHUNK_CASES`]): a shard's memory
/// does not grow with its size.
pub const CHUNK_CASES: u64 = runner::CHUNK_CASES;

/// Refuses a shard of a study of `model` that would not fit in memory: it analyses and stores
/// a chunk at a time and draws nothing.
fn check_chunk(shard: Shard, model: &runner::MemoryModel, cases: u64) -> Result<()> {
    let needed = model.shard_needed(cases);
    let fits = runner::available_memory().is_none_or(|a| needed <= a);
    fits.then_some(()).ok_or_else(|| {
        let message = format!(
            "its {cases} cases need about {} of memory (a chunk of at most {CHUNK_CASES} \
             analysed at a time), more than is available (the smaller of the free memory and \
             `ulimit -v`); raise `ulimit -v`, free memory or run more shards",
            runner::gib(needed)
        );
        UsageError::new(
            "--shard",
            format!("{}/{}", shard.index, shard.count),
            format!("this shard does not fit in memory: {message}"),
        )
        .into()
    })
}

/// The peak resident memory of this process so far, in bytes (VmHWM of /proc/self/status),
/// when known.
pub fn peak_rss_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = text.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line["VmHWM:".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    Some(kb.saturating_mul(1024))
}

/// Runs one shard of a study into `OUT/<name>.shard-I-of-N/` (staged, then renamed).
pub fn run_shard(opts: &RunOptions, shard: Shard) -> Result<RunSummary> {
    let t0 = Instant::now();
    let started_at = now_rfc3339();
    let progress = opts.progress.as_ref();
    let (m, bytes) = runner::load_manifest(&opts.study)?;
    let total = plan_cases(&m)?;
    let ids = plan::shard_ids(total, shard.index, shard.count);
    check_chunk(shard, &runner::MemoryModel::of(&m), ids.end - ids.start)?;
    let empty = plan::build_slice(m.clone(), 0..0);
    let separable = empty.is_separable_state_grid();
    let grid_path = engine::GridPath::of(&empty).as_str().to_string();
    let mut stages = StageTimings {
        plan_ms: ms(t0),
        ..Default::default()
    };
    let (pool, threads) = worker_pool(opts.jobs)?;
    let staged = StagedRun::create(&opts.out, &shard.dir_name(&m.name))?;
    let layout = staged.layout.clone();
    // A shard has no figures.
    std::fs::remove_dir(layout.plots()).context("cannot clear the staged plots directory")?;
    write_atomic(&layout.manifest(), &bytes)?;
    let done = analyse_in_chunks(
        &m,
        ids.clone(),
        &pool,
        progress,
        (&layout.results(), CHUNK_CASES),
    )?;
    (stages.engine_ms, stages.store_ms) = (done.engine_ms, done.store_ms);
    let (ok, count) = (done.written.ok, done.written.total);
    let info = RunInfo {
        name: m.name.clone(),
        manifest: serde_json::to_value(&m)?,
        manifest_sha256: sha256_hex(&bytes),
        manifest_path: opts.study.display().to_string(),
        archstudy_version: version().to_string(),
        git_commit: git_commit(),
        rustc_version: rustc_version().to_string(),
        command_line: opts.command_line.clone(),
        threads,
        started_at,
        finished_at: now_rfc3339(),
        cases: CaseCounts {
            total: count,
            ok,
            error: count - ok,
        },
        separable,
        grid_path,
        stages,
        boundary_refinement_analyses: 0,
        table_sha256: layout.table_sha256()?,
        shard_builds: Vec::new(),
    };
    let record = ShardRunInfo {
        info: info.clone(),
        shard: ShardInfo {
            index: shard.index,
            count: shard.count,
            plan_cases: total,
            first_case: ids.start,
            cases: ids.end - ids.start,
            peak_rss_bytes: peak_rss_bytes(),
        },
    };
    write_atomic(
        &layout.run_json(),
        serde_json::to_string_pretty(&record)?.as_bytes(),
    )?;
    let dir = staged.commit()?;
    Ok(RunSummary {
        dir,
        info,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::progress::Stage;
    use crate::store;

    #[test]
    fn a_shard_is_i_of_n_with_one_based_index() {
        assert_eq!(
            Shard::parse("--shard", "3/8").unwrap(),
            Shard { index: 3, count: 8 }
        );
        assert_eq!(
            Shard::parse("--shard", " 1 / 1 ").unwrap(),
            Shard { index: 1, count: 1 }
        );
        for bad in [
            "0/4",
            "5/4",
            "4",
            "a/4",
            "1/0",
            "-1/4",
            "1/2000000",
            "1/2/3",
            "",
        ] {
            let e = Shard::parse("--shard", bad).unwrap_err().to_string();
            assert!(e.contains("--shard") && e.contains("I/N"), "{bad}: {e}");
        }
    }

    #[test]
    fn shard_directories_sort_in_shard_order() {
        let names: Vec<String> = (1..=12)
            .map(|i| {
                Shard {
                    index: i,
                    count: 12,
                }
                .dir_name("seed")
            })
            .collect();
        assert_eq!(names[0], "seed.shard-01-of-12");
        assert_eq!(names[11], "seed.shard-12-of-12");
        let mut sorted = names.clone();
        sorted.sort();
        assert_eq!(sorted, names);
    }

    /// Progress events as they arrive: begins (with their totals), ends, and the count.
    #[derive(Default)]
    struct Recorded {
        events: std::sync::Mutex<Vec<(Stage, Option<u64>)>>,
        advanced: std::sync::atomic::AtomicU64,
    }

    impl crate::progress::Progress for Recorded {
        fn begin(&self, stage: Stage, total: Option<u64>) {
            self.events.lock().unwrap().push((stage, total));
        }
        fn advance(&self, n: u64) {
            self.advanced
                .fetch_add(n, std::sync::atomic::Ordering::Relaxed);
        }
        fn end(&self, stage: Stage) {
            self.events.lock().unwrap().push((stage, None));
        }
    }

    #[test]
    fn rows_stored_in_chunks_are_those_of_one_pass() {
        // 13 × 11 cases of a state map, a slice of 100 of them in chunks of 7 (the last one
        // short), against the same slice analysed and stored at once.
        let m = crate::manifest::parse(
            "name: a\ngrid:\n  k: {from: 1.05, to: 1.4, steps: 13}\n  mu: {from: 0.2, to: 0.7, steps: 11}\n",
            std::path::Path::new("a.yaml"),
        )
        .unwrap();
        let dir = std::env::temp_dir().join(format!("archstudy-chunks-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let silent = crate::progress::Silent;
        let (chunked, whole) = (dir.join("chunked.parquet"), dir.join("whole.parquet"));
        let seen = Recorded::default();
        let done = analyse_in_chunks(&m, 20..120, &pool, &seen, (&chunked, 7)).unwrap();
        assert_eq!((done.written.total, done.written.ok), (100, 100));
        // One stage over the 15 chunks: the bar neither restarts nor loses its total.
        assert_eq!(
            *seen.events.lock().unwrap(),
            vec![(Stage::Analyse, Some(100)), (Stage::Analyse, None)]
        );
        assert_eq!(
            seen.advanced.load(std::sync::atomic::Ordering::Relaxed),
            100
        );
        analyse_in_chunks(&m, 20..120, &pool, &silent, (&whole, 1000)).unwrap();
        let read = |p: &std::path::Path| {
            let mut t = store::read_table(p).unwrap();
            t.columns.retain(|c| c.name != "solve_time_us");
            t
        };
        assert_eq!(read(&chunked).rows, 100);
        assert_eq!(read(&chunked), read(&whole));
        let plan = plan::build(m.clone()).unwrap();
        let ids: Vec<u64> = store::read_case_results(&plan, &chunked)
            .unwrap()
            .iter()
            .map(|r| r.case_id)
            .collect();
        assert_eq!(ids, (20..120).collect::<Vec<u64>>());
        // An empty slice writes an empty table with the columns of the study.
        let empty = dir.join("empty.parquet");
        analyse_in_chunks(&m, 5..5, &pool, &silent, (&empty, 7)).unwrap();
        let t = store::read_table(&empty).unwrap();
        assert_eq!(t.rows, 0);
        assert_eq!(t.columns.len(), read(&whole).columns.len() + 1);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_chunk_that_cannot_be_written_fails_the_slice_with_its_cause() {
        // Chunks are written on their own thread while the next is analysed: a write that
        // fails (here the first, into a directory that does not exist) still fails the slice,
        // naming the file, and creates nothing.
        let m = crate::manifest::parse(
            "name: a\ngrid:\n  k: {from: 1.05, to: 1.4, steps: 5}\n  mu: {from: 0.2, to: 0.7, steps: 6}\n",
            std::path::Path::new("a.yaml"),
        )
        .unwrap();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let dir = std::env::temp_dir().join(format!("archstudy-no-dir-{}", std::process::id()));
        let results = dir.join("results.parquet");
        let e = analyse_in_chunks(&m, 0..30, &pool, &crate::progress::Silent, (&results, 7))
            .err()
            .expect("the first chunk cannot be written");
        let text = format!("{e:#}");
        assert!(text.contains("cannot create"), "{text}");
        assert!(text.contains("results.parquet"), "{text}");
        assert!(!dir.exists());
    }
}
