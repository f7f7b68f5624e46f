//! `archstudy verify`: checks an archive (or a run directory) years later.
//!
//! 1. Integrity: every checksum of SHA256SUMS (missing, extra and corrupt members named),
//!    the required files present, and manifest.yaml the manifest run.json names by hash.
//! 2. Provenance: says when run.json's archstudy version or commit differ from this build.
//! 3. Derived files: run.json's copy of the manifest and its hashes of the tables, the
//!    reports, figures, tables/ and RO-Crate metadata derived again from the hashed manifest
//!    and the stored tables and compared byte for byte, whatever run.json says about the
//!    build (its claims are never the evidence that it is genuine).
//! 4. Unless `--no-rerun`: re-runs the stored manifest with this build into a temporary
//!    directory and compares every column of every stored Parquet file with the recomputed
//!    one ([`compare`]; the rules are stated there and printed).
//!
//! The Parquet files are read by the store; comparison works on the store's plain tables,
//! so this module does not use polars.

pub use crate::store::compare;
mod redraw;

use crate::archive::{self, Provenance, REQUIRED_FILES, SUMS_FILE, check_sums, parse_sums};
use crate::error::UsageError;
use crate::provenance;
use crate::runner::{self, RunOptions};
use crate::store;
use anyhow::{Context, Result};
use compare::{ColumnVerdict, TableComparison, compare_tables};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Options of `verify`, as domain values.
#[derive(Debug, Clone)]
pub struct VerifyOptions {
    /// An archive made by `archstudy archive`, or a run directory.
    pub target: PathBuf,
    /// Whether to re-run the manifest and compare results (false: integrity only).
    pub rerun: bool,
    /// Tolerance T of float comparisons, relative and absolute (see [`compare`]).
    pub tolerance: f64,
}

/// Verifies an archive or a run directory, writing the verdicts to `out`; true when the
/// integrity check passes and (unless not re-running) every stored table agrees.
pub fn verify(opts: &VerifyOptions, out: &mut dyn Write) -> Result<bool> {
    let target = &opts.target;
    if !target.exists() {
        return Err(UsageError::new(
            "ARCHIVE|RUN_DIR",
            target.display(),
            "an archive made by `archstudy archive`, or a run directory (no such file)",
        )
        .into());
    }
    if !target.is_dir() && !target.is_file() {
        return Err(UsageError::new(
            "ARCHIVE|RUN_DIR",
            target.display(),
            "an archive made by `archstudy archive`, or a run directory (a FIFO or device is \
             not read)",
        )
        .into());
    }
    let is_archive = !target.is_dir();
    let unpacked = if is_archive {
        let u = archive::unpack(target)?;
        crate::output::register_pending(u.temp.path());
        Some(u)
    } else {
        None
    };
    let dir = unpacked
        .as_ref()
        .map_or_else(|| target.clone(), |u| u.dir());
    let kind = if is_archive {
        "archive"
    } else {
        "run directory"
    };
    writeln!(out, "verifying {kind} {}", target.display())?;

    let damage = unpacked.as_ref().and_then(|u| u.stream_damage.clone());
    let Some(prov) = integrity(&dir, is_archive, damage.as_deref(), out)? else {
        writeln!(out, "verdict: FAILED (integrity); results not compared")?;
        return Ok(false);
    };
    provenance(&prov, out)?;
    let Some(cases) = redraw::rows_match_plan(&dir, out)? else {
        writeln!(
            out,
            "verdict: DIFFERENT (results.parquet does not hold the manifest's cases); not re-run"
        )?;
        return Ok(false);
    };
    // Re-running needs the memory of a run (the tables are compared a block at a time).
    let model = runner::load_manifest(&dir.join("manifest.yaml"))
        .map_or(runner::MemoryModel::STATE, |(m, _)| {
            runner::MemoryModel::verify_of(&m)
        });
    let needed = model.needed(u64::try_from(cases).unwrap_or(u64::MAX));
    let available = runner::available_memory();
    let too_big = model.check(cases, available).is_err();
    if too_big && opts.rerun {
        return Err(UsageError::new(
            "ARCHIVE|RUN_DIR",
            target.display(),
            format!(
                "a run small enough to re-run here: its {cases} cases need about {} of \
                 memory, {} is available. Check its integrity only with `archstudy \
                 verify --no-rerun`, or verify it on a machine with that memory",
                runner::gib(needed),
                runner::gib(available.unwrap_or(0))
            ),
        )
        .into());
    }
    let reports = if too_big {
        writeln!(
            out,
            "reports: {cases} cases are too many to draw again in the memory available; \
                 checked by checksum only"
        )?;
        true
    } else {
        redraw::derived_match(&dir, &prov, out)?
    };
    if !opts.rerun {
        writeln!(out, "re-run: skipped (--no-rerun)")?;
        if reports {
            writeln!(out, "verdict: OK (integrity only)")?;
        } else {
            writeln!(
                out,
                "verdict: DIFFERENT (derived files are not what the stored tables draw)"
            )?;
        }
        return Ok(reports);
    }
    rerun_and_compare(&dir, opts.tolerance, reports, out)
}

/// The integrity check; returns run.json's provenance when everything is intact.
fn integrity(
    dir: &Path,
    is_archive: bool,
    stream_damage: Option<&str>,
    out: &mut dyn Write,
) -> Result<Option<Provenance>> {
    let mut ok = true;
    if let Some(d) = stream_damage {
        ok = false;
        writeln!(out, "integrity: {d}")?;
    }
    let (files, skipped) = archive::run_files(dir)?;
    let present: Vec<String> = files.iter().map(|f| f.rel.clone()).collect();
    let sums_path = dir.join(SUMS_FILE);
    if sums_path.is_file() {
        let text = std::fs::read_to_string(&sums_path)
            .with_context(|| format!("cannot read {}", sums_path.display()))?;
        match parse_sums(&text, SUMS_FILE) {
            Err(e) => {
                ok = false;
                writeln!(out, "integrity: {e}")?;
            }
            Ok(listed) => {
                let c = check_sums(dir, &listed, &present)?;
                if c.ok() {
                    writeln!(
                        out,
                        "integrity: all {} files match {SUMS_FILE}",
                        c.matching.len()
                    )?;
                } else {
                    ok = false;
                    writeln!(
                        out,
                        "integrity: {} of {} files listed in {SUMS_FILE} match",
                        c.matching.len(),
                        listed.len()
                    )?;
                    for p in &c.corrupt {
                        writeln!(out, "  corrupt member (checksum differs): {p}")?;
                    }
                    for p in &c.missing {
                        writeln!(out, "  missing member (listed, absent): {p}")?;
                    }
                    for p in &c.extra {
                        writeln!(out, "  extra member (not listed): {p}")?;
                    }
                    for p in &c.duplicated {
                        writeln!(out, "  listed more than once: {p}")?;
                    }
                }
            }
        }
    } else if is_archive {
        ok = false;
        writeln!(out, "integrity: the archive has no {SUMS_FILE}")?;
    } else {
        writeln!(
            out,
            "integrity: no {SUMS_FILE} in this run directory; checking the required files \
             and the manifest hash only"
        )?;
    }
    for s in &skipped {
        writeln!(out, "  note: {s} is not a regular file; not checked")?;
    }
    for f in present.iter().filter(|p| !archive::is_run_file(p)) {
        ok = false;
        writeln!(out, "  not a file a run writes: {f}")?;
    }
    for f in REQUIRED_FILES {
        if !present.iter().any(|p| p == f) {
            ok = false;
            writeln!(out, "  required file missing: {f}")?;
        }
    }
    if !ok {
        return Ok(None);
    }
    match archive::check_run_dir(dir) {
        Ok(p) => {
            writeln!(
                out,
                "integrity: manifest.yaml matches run.json's manifest_sha256"
            )?;
            Ok(Some(p))
        }
        Err(e) => {
            writeln!(out, "integrity: {e:#}")?;
            Ok(None)
        }
    }
}

fn provenance(p: &Provenance, out: &mut dyn Write) -> Result<()> {
    let unknown = || "unknown".to_string();
    let stored_version = p.archstudy_version.clone().unwrap_or_else(unknown);
    let stored_commit = p.git_commit.clone().unwrap_or_else(unknown);
    let this_commit = provenance::git_commit().unwrap_or_else(unknown);
    writeln!(
        out,
        "made by: archstudy {stored_version} (commit {stored_commit}); this build: archstudy {} (commit {this_commit})",
        provenance::version()
    )?;
    if stored_version != provenance::version() {
        writeln!(
            out,
            "  note: the archstudy version differs from this build; comparing anyway"
        )?;
    }
    if stored_commit != this_commit {
        writeln!(
            out,
            "  note: the commit differs from this build; comparing anyway"
        )?;
    }
    Ok(())
}

/// Re-runs the stored manifest and compares every stored Parquet table with the recomputed
/// one; the verdict is OK when they agree and `reports_agree` (the stored reports are what
/// the stored tables draw).
fn rerun_and_compare(
    dir: &Path,
    tolerance: f64,
    reports_agree: bool,
    out: &mut dyn Write,
) -> Result<bool> {
    let temp = tempfile::Builder::new()
        .prefix("archstudy-rerun-")
        .tempdir()
        .context("cannot create a temporary directory for the re-run")?;
    crate::output::register_pending(temp.path());
    let opts = RunOptions {
        command_line: std::env::args().collect(),
        ..RunOptions::new(dir.join("manifest.yaml"), temp.path())
    };
    let summary = match runner::run_study(&opts) {
        Ok(s) => s,
        Err(e) => {
            writeln!(out, "re-run: FAILED: {e:#}")?;
            writeln!(
                out,
                "verdict: DIFFERENT (the stored manifest does not run with this build)"
            )?;
            return Ok(false);
        }
    };
    writeln!(
        out,
        "re-run: {} cases in {:.2} s",
        summary.info.cases.total, summary.wall_s
    )?;
    writeln!(
        out,
        "comparing: float columns within |stored - recomputed| <= T * (1 + max(|stored|, |recomputed|)), \
         T = {tolerance:e}; other columns exactly; timing columns (solve_time_us, *_ms, *_us) ignored; \
         rows count from 0"
    )?;

    let (stored_files, _) = archive::run_files(dir)?;
    let (rerun_files, _) = archive::run_files(&summary.dir)?;
    let is_parquet = |rel: &str| rel.ends_with(".parquet");
    let mut compared = 0;
    let mut differing = 0;
    for f in stored_files.iter().filter(|f| is_parquet(&f.rel)) {
        compared += 1;
        let recomputed = summary.dir.join(&f.rel);
        let agrees = compare_file(&f.rel, &f.path, &recomputed, tolerance, out)?;
        if !agrees {
            differing += 1;
        }
    }
    let same_version = archive::read_provenance(&dir.join("run.json"))
        .ok()
        .and_then(|p| p.archstudy_version)
        .is_some_and(|v| v == provenance::version());
    for f in rerun_files.iter().filter(|f| is_parquet(&f.rel)) {
        if !stored_files.iter().any(|s| s.rel == f.rel) {
            if same_version {
                // The same version writes the same tables: a missing one was removed.
                compared += 1;
                differing += 1;
                writeln!(
                    out,
                    "{}: DIFFERENT: written by the re-run of this same version, but missing \
                     from the stored run",
                    f.rel
                )?;
            } else {
                writeln!(
                    out,
                    "{}: written by this build but not stored (another version); not compared",
                    f.rel
                )?;
            }
        }
    }
    if differing == 0 && !reports_agree {
        writeln!(
            out,
            "verdict: DIFFERENT: all {compared} Parquet files agree with the re-run, but \
             derived files are not what they draw"
        )?;
        Ok(false)
    } else if differing == 0 {
        writeln!(
            out,
            "verdict: OK: all {compared} Parquet files agree with the re-run"
        )?;
        Ok(true)
    } else {
        writeln!(
            out,
            "verdict: DIFFERENT: {differing} of {compared} Parquet files differ from the re-run"
        )?;
        Ok(false)
    }
}

/// Rows of a stored table and of its recomputed counterpart compared at a time: the two
/// tables are read in blocks ([`store::TableReader`]), so that verify's memory does not grow
/// with the number of rows.
pub const COMPARE_BLOCK_ROWS: usize = 1 << 14;

/// Compares one stored Parquet file with its recomputed counterpart and prints the verdicts.
fn compare_file(
    rel: &str,
    stored: &Path,
    recomputed: &Path,
    tolerance: f64,
    out: &mut dyn Write,
) -> Result<bool> {
    if !recomputed.is_file() {
        writeln!(out, "{rel}: different: not written by the re-run")?;
        return Ok(false);
    }
    match compare_in_blocks(stored, recomputed, tolerance, BLOCKS)? {
        Err(e) => {
            writeln!(
                out,
                "{rel}: different: the stored file cannot be read: {e:#}"
            )?;
            Ok(false)
        }
        Ok((c, _)) => {
            print_comparison(rel, &c, out)?;
            Ok(c.agrees())
        }
    }
}

/// How many rows [`compare_in_blocks`] compares and decodes at a time.
#[derive(Debug, Clone, Copy)]
pub struct Blocks {
    /// Rows converted and compared at a time.
    pub compare: usize,
    /// Rows of each file decoded at a time (a multiple of `compare`).
    pub decode: usize,
}

/// The blocks of `archstudy verify`: [`COMPARE_BLOCK_ROWS`] and [`store::TABLE_FRAME_ROWS`].
pub const BLOCKS: Blocks = Blocks {
    compare: COMPARE_BLOCK_ROWS,
    decode: store::TABLE_FRAME_ROWS,
};

/// Compares two Parquet tables a block of rows at a time ([`compare::fold_block`]): the
/// comparison and the most rows held decoded from either file, or the error that makes the
/// stored file unreadable (a recomputed file that cannot be read is an error).
pub fn compare_in_blocks(
    stored: &Path,
    recomputed: &Path,
    tolerance: f64,
    blocks: Blocks,
) -> Result<Result<(TableComparison, usize), anyhow::Error>> {
    let mut s = match store::TableReader::with_frame_rows(stored, blocks.decode) {
        Ok(s) => s,
        Err(e) => return Ok(Err(e)),
    };
    let mut r = store::TableReader::with_frame_rows(recomputed, blocks.decode)
        .with_context(|| format!("cannot read the recomputed {}", recomputed.display()))?;
    let rows = s.rows().min(r.rows());
    let block = blocks.compare.clamp(1, blocks.decode.max(1));
    let mut acc = None;
    let mut at = 0;
    loop {
        let len = block.min(rows - at);
        let st = match s.read(at, len) {
            Ok(t) => t,
            Err(e) => return Ok(Err(e)),
        };
        let rt = r
            .read(at, len)
            .with_context(|| format!("cannot read the recomputed {}", recomputed.display()))?;
        acc = Some(compare::fold_block(
            acc,
            compare_tables(&st, &rt, tolerance),
            at,
        ));
        at += len;
        if at >= rows {
            break;
        }
    }
    let Some(mut c) = acc else {
        anyhow::bail!("no rows compared");
    };
    (c.stored_rows, c.recomputed_rows) = (s.rows(), r.rows());
    Ok(Ok((c, s.largest_frame().max(r.largest_frame()))))
}

fn print_comparison(rel: &str, c: &TableComparison, out: &mut dyn Write) -> Result<()> {
    let verdict = if c.agrees() { "agrees" } else { "DIFFERENT" };
    if c.stored_rows == c.recomputed_rows {
        writeln!(out, "{rel}: {verdict} ({} rows)", c.stored_rows)?;
    } else {
        writeln!(
            out,
            "{rel}: {verdict}: row count differs: stored {}, recomputed {} (columns compared over the first {})",
            c.stored_rows,
            c.recomputed_rows,
            c.stored_rows.min(c.recomputed_rows)
        )?;
    }
    if !c.same_column_order {
        writeln!(out, "  the column order differs")?;
    }
    let width = c.columns.iter().map(|x| x.name.len()).max().unwrap_or(0);
    for col in &c.columns {
        let text = match &col.verdict {
            ColumnVerdict::Identical => "identical".to_string(),
            ColumnVerdict::WithinTolerance { max_abs_diff } => {
                format!("within tolerance (max difference {max_abs_diff:.3e})")
            }
            ColumnVerdict::Ignored => "ignored (timing)".to_string(),
            ColumnVerdict::MissingFromRerun => "different: missing from the re-run".to_string(),
            ColumnVerdict::NotStored => "different: not in the stored table".to_string(),
            ColumnVerdict::TypeChanged { stored, recomputed } => {
                format!("different: type stored {stored}, recomputed {recomputed}")
            }
            ColumnVerdict::Different {
                rows_differing,
                max_abs_diff,
                ..
            } => {
                let n = c.stored_rows.min(c.recomputed_rows);
                match max_abs_diff {
                    Some(d) => format!(
                        "different in {rows_differing} of {n} rows (max difference {d:.3e})"
                    ),
                    None => format!("different in {rows_differing} of {n} rows"),
                }
            }
        };
        writeln!(out, "  {:width$}  {text}", col.name)?;
        if let ColumnVerdict::Different { first, .. } = &col.verdict {
            for d in first {
                writeln!(
                    out,
                    "      row {}: stored {}, recomputed {}",
                    d.row, d.stored, d.recomputed
                )?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::{TableBuilder, read_table, write_parquet};

    /// Two tables of 1000 rows compared in blocks of 64 rows, decoded 256 at a time: the
    /// verdicts of the whole tables, with never more than 256 rows decoded at once.
    #[test]
    fn tables_are_compared_a_block_at_a_time_with_the_verdicts_of_the_whole() {
        let dir = tempfile::tempdir().unwrap();
        let n = 1000;
        let xs: Vec<f64> = (0..n).map(|i| f64::from(i) / 7.0).collect();
        let mut ys = xs.clone();
        for i in [3usize, 255, 256, 700, 999] {
            ys[i] += 1.0;
        }
        ys[500] += 1e-12;
        let names = |k: u32| -> Vec<String> { (0..n).map(|i| format!("c{}", i / k)).collect() };
        let write = |file: &str, x: Vec<f64>, s: Vec<String>, rows: usize| {
            let path = dir.path().join(file);
            let mut df = TableBuilder::new()
                .f64("x", x[..rows].to_vec())
                .str("name", s[..rows].to_vec())
                .f64("solve_time_us", vec![1.0; rows])
                .finish()
                .unwrap();
            write_parquet(&mut df, &path).unwrap();
            path
        };
        let a = write("a.parquet", xs.clone(), names(10), 1000);
        let b = write("b.parquet", ys, names(9), 1000);
        let short = write("c.parquet", xs, names(10), 900);
        let blocks = Blocks {
            compare: 64,
            decode: 256,
        };
        for (s, r) in [(&a, &b), (&b, &a), (&a, &a), (&a, &short)] {
            let whole = compare_tables(&read_table(s).unwrap(), &read_table(r).unwrap(), 1e-9);
            let (c, held) = compare_in_blocks(s, r, 1e-9, blocks).unwrap().unwrap();
            assert_eq!(c, whole);
            assert_eq!(held, 256);
        }
        let (c, _) = compare_in_blocks(&a, &b, 1e-9, blocks).unwrap().unwrap();
        match &c.columns[0].verdict {
            ColumnVerdict::Different {
                rows_differing,
                first,
                max_abs_diff,
            } => {
                assert_eq!(*rows_differing, 5);
                let rows: Vec<usize> = first.iter().map(|d| d.row).collect();
                assert_eq!(rows, vec![3, 255, 256, 700, 999]);
                assert!(max_abs_diff.is_some_and(|d| (d - 1.0).abs() < 1e-12));
            }
            other => panic!("{other:?}"),
        }
        // A stored file that is not Parquet is unreadable, not an error of the comparison.
        let junk = dir.path().join("junk.parquet");
        std::fs::write(&junk, b"not parquet").unwrap();
        assert!(compare_in_blocks(&junk, &a, 1e-9, blocks).unwrap().is_err());
    }
}
