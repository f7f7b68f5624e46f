//! `archstudy merge SHARD_DIR...`: the shard directories of one manifest (src/shard.rs)
//! checked for completeness and joined into the ordinary run directory. The shards' rows are
//! read back into the engine's rows, in plan order, and go through the same stages after the
//! engine as an unsharded run ([`runner::finish_run`]): results.parquet holds the same data
//! (only the solve times, measured where each shard ran, differ from another run's), and the
//! boundaries, bifurcations, figures and reports are those of an unsharded run.

mod recheck;

pub use recheck::{DEFAULT_RECHECK_ROWS, Recheck};

use crate::engine::CaseResult;
use crate::error::UsageError;
use crate::output::StagedRun;
use crate::plan;
use crate::progress::Progress;
use crate::provenance::{ShardBuild, StageTimings, now_rfc3339};
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
    /// How many rows of each shard are analysed again and compared with the shard's.
    pub recheck: Recheck,
}

fn bad_shard(dir: &Path, why: impl ToString) -> anyhow::Error {
    UsageError::new("SHARD_DIR", dir.display(), why).into()
}

/// The shard directories that `from` names: when it is a directory, its subdirectories whose
/// names are those of shard directories (`<name>.shard-I-of-N`), in name order; when it is a
/// file, one directory a line (blank lines and lines starting with `#` skipped, a relative
/// path taken from the current directory, like a `SHARD_DIR` argument). For more shards than
/// a command line holds.
pub fn shards_from(from: &Path) -> Result<Vec<PathBuf>> {
    let bad = |why: String| -> anyhow::Error {
        UsageError::new("--shards-from", from.display(), why).into()
    };
    let meta = std::fs::metadata(from).map_err(|e| {
        bad(format!(
            "a directory of shard directories or a list file ({e})"
        ))
    })?;
    if meta.is_dir() {
        let mut dirs = Vec::new();
        let entries = std::fs::read_dir(from)
            .map_err(|e| bad(format!("a directory that can be listed ({e})")))?;
        for entry in entries {
            let entry = entry.map_err(|e| bad(format!("a directory that can be listed ({e})")))?;
            let name = entry.file_name();
            if name.to_str().is_some_and(is_shard_dir_name) && entry.path().is_dir() {
                dirs.push(entry.path());
            }
        }
        dirs.sort();
        return Ok(dirs);
    }
    if !meta.is_file() {
        return Err(bad(
            "a directory or a regular file (a FIFO or device is not read)".into(),
        ));
    }
    if meta.len() > MAX_LIST_BYTES {
        return Err(bad(format!(
            "a list file of at most {MAX_LIST_BYTES} bytes; this one has {}",
            meta.len()
        )));
    }
    let text = std::fs::read_to_string(from).map_err(|e| {
        bad(format!(
            "a readable UTF-8 text file, one directory a line ({e})"
        ))
    })?;
    Ok(text
        .lines()
        .map(str::trim_end)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(PathBuf::from)
        .collect())
}

/// The largest list file `--shards-from` reads (1 GiB: a million shard paths of 1 KiB).
pub const MAX_LIST_BYTES: u64 = 1 << 30;

/// Whether a directory name is that of a shard directory, `<name>.shard-I-of-N`.
fn is_shard_dir_name(name: &str) -> bool {
    let Some((_, tail)) = name.rsplit_once(".shard-") else {
        return false;
    };
    let Some((i, n)) = tail.split_once("-of-") else {
        return false;
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    digits(i) && digits(n)
}

/// Reads a shard directory's run.json.
fn read_record(dir: &Path) -> Result<ShardRunInfo> {
    let path = dir.join("run.json");
    let text = crate::output::read_regular_text(&path, crate::output::MAX_RUN_JSON_BYTES).map_err(
        |e| {
            bad_shard(
                dir,
                format!(
                    "not a shard directory: cannot read {} ({e}); give the directories \
                 `OUT/<name>.shard-I-of-N` that `archstudy run STUDY --shard I/N` wrote",
                    path.display()
                ),
            )
        },
    )?;
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

/// The rows of one shard, checked against the slice of the plan it must hold and some of them
/// analysed again ([`Recheck`]), handed to `each` a chunk of [`runner::CHUNK_CASES`] rows at
/// a time (only those rows are decoded). Returns the number of rows analysed again.
fn shard_rows(
    (m, total, again): (&crate::manifest::Manifest, u64, Recheck),
    dir: &Path,
    r: &ShardRunInfo,
    mut each: impl FnMut(Vec<CaseResult>) -> Result<()>,
) -> Result<u64> {
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
    check_recorded_hash(dir, r, &path)?;
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
    let picked = again.offsets(n);
    let mut offset = 0u64;
    while offset < n {
        let len = runner::CHUNK_CASES.min(n - offset);
        let first = ids.start + offset;
        let slice = plan::build_slice(m.clone(), first..first + len);
        let rows =
            store::read_foreign_case_results_rows(&slice, &path, (offset as usize, len as usize))
                .map_err(unreadable)?;
        let picks: Vec<usize> = picked
            .range(offset..offset + len)
            .map(|&i| (i - offset) as usize)
            .collect();
        if let Some(d) = recheck::recheck(&slice, &rows, &picks)? {
            return Err(disagreeing_shard(dir, r, &d));
        }
        each(rows)?;
        offset += len;
    }
    Ok(picked.len() as u64)
}

/// A shard whose row this build analyses otherwise, named with the case, the column, both
/// values and the build that wrote the shard.
fn disagreeing_shard(dir: &Path, r: &ShardRunInfo, d: &recheck::Disagreement) -> anyhow::Error {
    let ours = crate::provenance::git_commit();
    let build =
        if r.info.archstudy_version == crate::provenance::version() && r.info.git_commit == ours {
            "this build".to_string()
        } else {
            format!(
                "archstudy {} ({}), this build being {} ({})",
                r.info.archstudy_version,
                r.info.git_commit.as_deref().unwrap_or("commit unknown"),
                crate::provenance::version(),
                ours.as_deref().unwrap_or("commit unknown")
            )
        };
    bad_shard(
        dir,
        format!(
            "case {} analysed again gives `{}` = {} where the shard's results.parquet holds {} \
             (the shard says it was analysed by {build}): its table is not the analysis of its \
             plan; re-run the shard",
            d.case_id, d.column, d.recomputed, d.stored
        ),
    )
}

/// results.parquet of a shard against the hash its run.json records: a table edited after
/// the shard wrote it is refused.
fn check_recorded_hash(dir: &Path, r: &ShardRunInfo, path: &Path) -> Result<()> {
    let Some(recorded) = r.info.table_sha256.get("results.parquet") else {
        return Err(bad_shard(
            dir,
            "its run.json records no hash of results.parquet (a shard of an older version, or \
             an edited run.json): re-run the shard",
        ));
    };
    let file = std::fs::File::open(path)
        .map_err(|e| bad_shard(dir, format!("cannot read {} ({e})", path.display())))?;
    let actual = crate::provenance::sha256_reader(std::io::BufReader::new(file))
        .map_err(|e| bad_shard(dir, format!("cannot read {} ({e})", path.display())))?;
    if !recorded.eq_ignore_ascii_case(&actual) {
        return Err(bad_shard(
            dir,
            "its results.parquet is not the table the shard wrote (its SHA-256 is not the one \
             its run.json records): re-run the shard",
        ));
    }
    Ok(())
}

/// Refuses a merge whose run directory `target` (`OUT/<name>`), which the merge replaces,
/// is or holds one of the shard directories it reads.
fn refuse_replacing_an_input(target: &Path, records: &[(PathBuf, ShardRunInfo)]) -> Result<()> {
    let Ok(target) = target.canonicalize() else {
        return Ok(());
    };
    for (d, _) in records {
        let shard = d.canonicalize().unwrap_or_else(|_| d.clone());
        if shard.starts_with(&target) {
            return Err(UsageError::new(
                "--out",
                target.display(),
                format!(
                    "a directory other than the shard directory {} or one that holds it: \
                     the merged run replaces OUT/<name>; give another --out, or move the shards",
                    d.display()
                ),
            )
            .into());
        }
    }
    Ok(())
}

/// A shard's stage timings, each finite and ≥ 0 (they are summed into the merged run's).
fn check_timings(dir: &Path, r: &ShardRunInfo) -> Result<()> {
    let s = &r.info.stages;
    for (name, v) in [
        ("plan_ms", s.plan_ms),
        ("engine_ms", s.engine_ms),
        ("store_ms", s.store_ms),
        ("boundaries_ms", s.boundaries_ms),
        ("plots_ms", s.plots_ms),
        ("report_ms", s.report_ms),
    ] {
        if !(v.is_finite() && (0.0..=MAX_SHARD_MS).contains(&v)) {
            return Err(bad_shard(
                dir,
                format!(
                    "its run.json records the timing stages.{name} = {v}, not a time in \
                     milliseconds from 0 to {MAX_SHARD_MS:e}: re-run the shard"
                ),
            ));
        }
    }
    Ok(())
}

/// The longest stage time a shard may record, in milliseconds (about 31,700 years): the sum
/// over a million shards stays finite.
pub const MAX_SHARD_MS: f64 = 1e15;

/// The builds that analysed the shards (version, commit, rustc), each with the shards it ran,
/// in the order first seen.
fn shard_builds(records: &[(PathBuf, ShardRunInfo)], rechecked: &[u64]) -> Vec<ShardBuild> {
    let mut builds: Vec<(ShardBuild, Vec<u64>)> = Vec::new();
    for ((_, r), &again) in records.iter().zip(rechecked) {
        let b = ShardBuild {
            archstudy_version: r.info.archstudy_version.clone(),
            git_commit: r.info.git_commit.clone(),
            rustc_version: r.info.rustc_version.clone(),
            shards: String::new(),
            rows_rechecked: 0,
        };
        let same = |x: &ShardBuild| {
            (&x.archstudy_version, &x.git_commit, &x.rustc_version)
                == (&b.archstudy_version, &b.git_commit, &b.rustc_version)
        };
        match builds.iter_mut().find(|(x, _)| same(x)) {
            Some((x, list)) => {
                list.push(r.shard.index);
                x.rows_rechecked += again;
            }
            None => builds.push((
                ShardBuild {
                    rows_rechecked: again,
                    ..b
                },
                vec![r.shard.index],
            )),
        }
    }
    builds
        .into_iter()
        .map(|(b, list)| ShardBuild {
            shards: ranges(&list),
            ..b
        })
        .collect()
}

/// Sorted shard numbers as ranges: `1-3, 5`.
fn ranges(sorted: &[u64]) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut i = 0;
    while i < sorted.len() {
        let mut j = i;
        while j + 1 < sorted.len() && sorted[j + 1] == sorted[j] + 1 {
            j += 1;
        }
        out.push(if i == j {
            sorted[i].to_string()
        } else {
            format!("{}-{}", sorted[i], sorted[j])
        });
        i = j + 1;
    }
    out.join(", ")
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
    for (d, r) in &records {
        check_timings(d, r)?;
    }
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
    refuse_replacing_an_input(&opts.out.join(&m.name), &records)?;
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
    let mut rechecked = Vec::with_capacity(records.len());
    for (dir, r) in &records {
        let again = shard_rows((&m, total, opts.recheck), dir, r, |rows| {
            pending.extend(rows);
            while pending.len() >= chunk {
                let rest = pending.split_off(chunk);
                store_chunk(std::mem::replace(&mut pending, rest), &mut stored)?;
            }
            Ok(())
        })?;
        rechecked.push(again);
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
        shard_builds: shard_builds(&records, &rechecked),
    };
    runner::finish_run(analysed, staged, (&pool, threads), &run_opts, t0)
}
