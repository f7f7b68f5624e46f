//! `archstudy merge SHARD_DIR...`: the shard directories of one manifest (src/shard.rs)
//! checked for completeness and joined into the ordinary run directory. The shards' rows are
//! read back into the engine's rows, in plan order, and go through the same stages after the
//! engine as an unsharded run ([`runner::finish_run`]): results.parquet holds the same data
//! (only the solve times, measured where each shard ran, differ from another run's), and the
//! boundaries, bifurcations, figures and reports are those of an unsharded run.

use crate::engine::CaseResult;
use crate::error::UsageError;
use crate::output::StagedRun;
use crate::plan;
use crate::progress::Progress;
use crate::provenance::{StageTimings, now_rfc3339};
use crate::runner::{self, Analysed, RunOptions, RunSummary, ms, worker_pool};
use crate::shard::{Shard, ShardRunInfo};
use crate::store;
use anyhow::Result;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// Options of a merge, as domain values.
#[derive(Clone)]
pub struct MergeOptions {
    /// The shard directories, in any order.
    pub shards: Vec<PathBuf>,
    /// Directory under which the run directory `<name>/` is written.
    pub out: PathBuf,
    /// Worker threads (None: all cores).
    pub jobs: Option<usize>,
    /// Where the stages report their progress.
    pub progress: Arc<dyn Progress>,
    /// The command line recorded in run.json.
    pub command_line: Vec<String>,
}

fn bad_shard(dir: &Path, why: impl ToString) -> anyhow::Error {
    UsageError::new("SHARD_DIR", dir.display(), why).into()
}

/// Reads a shard directory's run.json.
fn read_record(dir: &Path) -> Result<ShardRunInfo> {
    let path = dir.join("run.json");
    let text = std::fs::read_to_string(&path).map_err(|e| {
        bad_shard(
            dir,
            format!(
                "not a shard directory: cannot read {} ({e}); give the directories \
                 `OUT/<name>.shard-I-of-N` that `archstudy run STUDY --shard I/N` wrote",
                path.display()
            ),
        )
    })?;
    serde_json::from_str(&text).map_err(|e| {
        bad_shard(
            dir,
            format!(
                "{} is not the run.json of a shard ({e}): a shard's run.json has a `shard` \
                 entry; give the directories `archstudy run STUDY --shard I/N` wrote",
                path.display()
            ),
        )
    })
}

/// The shards' records in shard order, after checking that they are shards 1..N of one
/// manifest, each exactly once.
fn check_complete(dirs: &[PathBuf]) -> Result<Vec<(PathBuf, ShardRunInfo)>> {
    if dirs.is_empty() {
        return Err(UsageError::new(
            "SHARD_DIR",
            "(none)",
            "give the shard directories to merge, e.g. `archstudy merge output/seed.shard-*`",
        )
        .into());
    }
    let mut records = Vec::with_capacity(dirs.len());
    for d in dirs {
        records.push((d.clone(), read_record(d)?));
    }
    // The manifest most shards have is the study's; the others are foreign.
    let sha_of = |i: usize| &records[i].1.info.manifest_sha256;
    let majority = (0..records.len())
        .max_by_key(|&i| {
            let n = records
                .iter()
                .filter(|(_, r)| &r.info.manifest_sha256 == sha_of(i))
                .count();
            (n, std::cmp::Reverse(i))
        })
        .unwrap_or(0);
    let first_dir = &records[majority].0;
    let (sha, count) = (
        records[majority].1.info.manifest_sha256.clone(),
        records[majority].1.shard.count,
    );
    for (d, r) in &records {
        if r.info.manifest_sha256 != sha {
            return Err(bad_shard(
                d,
                format!(
                    "a shard of another manifest (SHA-256 {}…, while {} is of {}…): merge only \
                     the shards of one manifest",
                    &r.info.manifest_sha256[..12.min(r.info.manifest_sha256.len())],
                    first_dir.display(),
                    &sha[..12.min(sha.len())]
                ),
            ));
        }
        if r.shard.count != count {
            return Err(bad_shard(
                d,
                format!(
                    "shard {} of {}, while {} is of {count} shards: merge the shards of one split",
                    r.shard.index,
                    r.shard.count,
                    first_dir.display()
                ),
            ));
        }
    }
    records.sort_by_key(|(_, r)| r.shard.index);
    for w in records.windows(2) {
        if w[0].1.shard.index == w[1].1.shard.index {
            return Err(bad_shard(
                &w[1].0,
                format!(
                    "shard {} of {count} is given twice (also as {}): give each shard once",
                    w[1].1.shard.index,
                    w[0].0.display()
                ),
            ));
        }
    }
    let have: Vec<u64> = records.iter().map(|(_, r)| r.shard.index).collect();
    let missing: Vec<u64> = (1..=count).filter(|i| !have.contains(i)).collect();
    if let Some(&i) = missing.first() {
        let name = Shard { index: i, count }.dir_name(&records[0].1.info.name);
        let list: Vec<String> = missing.iter().take(10).map(u64::to_string).collect();
        return Err(UsageError::new(
            "SHARD_DIR",
            format!("{} directories", dirs.len()),
            format!(
                "shard {i} of {count} (`{name}`) is missing: shards {}{} of {count} are not \
                 among the directories given; run them (`archstudy run STUDY --shard {i}/{count}`) \
                 and merge all {count}",
                list.join(", "),
                if missing.len() > 10 { ", …" } else { "" }
            ),
        )
        .into());
    }
    Ok(records)
}

/// The rows of one shard, checked against the slice of the plan it must hold, handed to
/// `each` a chunk of [`runner::CHUNK_CASES`] rows at a time (only those rows are decoded).
fn shard_rows(
    (m, total): (&crate::manifest::Manifest, u64),
    dir: &Path,
    r: &ShardRunInfo,
    mut each: impl FnMut(Vec<CaseResult>) -> Result<()>,
) -> Result<()> {
    let ids = plan::shard_ids(total, r.shard.index, r.shard.count);
    let recorded = r.shard.first_case..r.shard.first_case + r.shard.cases;
    if r.shard.plan_cases != total || recorded != ids {
        return Err(bad_shard(
            dir,
            format!(
                "its run.json records cases {recorded:?} of {}, but shard {} of {} of this \
                 manifest's {total} cases is {ids:?}: re-run the shard",
                r.shard.plan_cases, r.shard.index, r.shard.count
            ),
        ));
    }
    let path = dir.join("results.parquet");
    if !path.is_file() {
        return Err(bad_shard(
            dir,
            "incomplete shard: results.parquet is missing; re-run the shard",
        ));
    }
    let unreadable =
        |e: anyhow::Error| bad_shard(dir, format!("unreadable shard: {e:#}; re-run the shard"));
    let got = store::read_case_ids(&path).map_err(unreadable)?;
    if !got.iter().copied().eq(ids.clone()) {
        return Err(bad_shard(
            dir,
            format!(
                "incomplete shard: results.parquet holds {} rows where shard {} of {} holds \
                 cases {ids:?} in order; re-run the shard",
                got.len(),
                r.shard.index,
                r.shard.count
            ),
        ));
    }
    drop(got);
    let n = ids.end - ids.start;
    let mut offset = 0u64;
    while offset < n {
        let len = runner::CHUNK_CASES.min(n - offset);
        let first = ids.start + offset;
        let slice = plan::build_slice(m.clone(), first..first + len);
        let rows = store::read_case_results_rows(&slice, &path, (offset as usize, len as usize))
            .map_err(unreadable)?;
        each(rows)?;
        offset += len;
    }
    Ok(())
}

/// Merges the shards of one manifest into `OUT/<name>/`, the run directory an unsharded run
/// writes. Missing, duplicated or foreign shards are refused (exit 2), naming the shard. The
/// shards are read a chunk of [`runner::CHUNK_CASES`] rows at a time, appended to
/// results.parquet in the chunks of an unsharded run and dropped: the merge holds two chunks
/// of rows, one shard's case ids and one byte a case.
pub fn merge(opts: &MergeOptions) -> Result<RunSummary> {
    let t0 = Instant::now();
    let started_at = now_rfc3339();
    let records = check_complete(&opts.shards)?;
    let (first_dir, first) = &records[0];
    let manifest_file = first_dir.join("manifest.yaml");
    let (m, bytes) = runner::load_runnable(&manifest_file)?;
    if crate::provenance::sha256_hex(&bytes) != first.info.manifest_sha256 {
        return Err(bad_shard(
            first_dir,
            "its manifest.yaml is not the manifest its run.json records (SHA-256 differs): \
             re-run the shard",
        ));
    }
    let total = u64::try_from(plan::case_count(&m)).unwrap_or(u64::MAX);
    let mut stages = StageTimings {
        plan_ms: ms(t0),
        ..Default::default()
    };
    let (pool, threads) = worker_pool(opts.jobs)?;
    let staged = StagedRun::create(&opts.out, &m.name)?;
    crate::output::write_atomic(&staged.layout.manifest(), &bytes)?;
    let t = Instant::now();
    let mut written = runner::ResultsWriter::new(&staged.layout.results());
    // The shards' rows are stored in the chunks of an unsharded run, so that the table is
    // that run's to the byte of every value.
    let mut pending: Vec<CaseResult> = Vec::new();
    let mut stored = 0u64;
    let mut store_chunk = |rows: Vec<CaseResult>, stored: &mut u64| -> Result<()> {
        let ids = *stored..*stored + rows.len() as u64;
        written.push(&plan::build_slice(m.clone(), ids), &rows, &pool)?;
        *stored += rows.len() as u64;
        Ok(())
    };
    let chunk = runner::CHUNK_CASES as usize;
    for (dir, r) in &records {
        shard_rows((&m, total), dir, r, |rows| {
            pending.extend(rows);
            while pending.len() >= chunk {
                let rest = pending.split_off(chunk);
                store_chunk(std::mem::replace(&mut pending, rest), &mut stored)?;
            }
            Ok(())
        })?;
        stages.engine_ms += r.info.stages.engine_ms;
    }
    if !pending.is_empty() || stored == 0 {
        store_chunk(pending, &mut stored)?;
    }
    written.finish()?;
    stages.store_ms = ms(t);
    let run_opts = RunOptions {
        study: manifest_file.clone(),
        out: opts.out.clone(),
        jobs: opts.jobs,
        progress: opts.progress.clone(),
        command_line: opts.command_line.clone(),
        figure_width: None,
    };
    let analysed = Analysed {
        manifest: m,
        bytes,
        manifest_path: first.info.manifest_path.clone(),
        written,
        stages,
        started_at,
    };
    runner::finish_run(analysed, staged, (&pool, threads), &run_opts, t0)
}
