//! Checks of a stored run that need no re-run: every derived file (reports, figures,
//! tables/, RO-Crate metadata, run.json's copy of the manifest and its hashes of the tables)
//! derived again from the hashed manifest and the stored tables, whatever run.json says about
//! the build that made it; and the number of rows of its results against the plan of its
//! manifest (a table cut short or padded).

use crate::archive::{self, Provenance};
use crate::citation;
use crate::manifest::{FigureWidth, Manifest};
use crate::output::{CRATE_METADATA, RunLayout};
use crate::provenance::{self, RunInfo};
use crate::report;
use crate::runner;
use crate::store;
use anyhow::{Context, Result};
use std::io::Write;
use std::path::Path;

/// True when run.json says the run was made by this very build (same version and commit).
/// A claim of the file itself: it decides how a difference is worded, never whether a
/// derived file is checked.
fn claims_this_build(p: &Provenance) -> bool {
    p.archstudy_version.as_deref() == Some(provenance::version())
        && p.git_commit.is_some()
        && p.git_commit == provenance::git_commit()
}

/// Copies the regular files of a run directory that are not drawn ([`is_drawn`]) into `to`:
/// what is drawn there again is then only what the stored tables draw.
fn copy_run(dir: &Path, to: &Path) -> Result<()> {
    let (files, _) = archive::run_files(dir)?;
    for f in files.into_iter().filter(|f| !is_drawn(&f.rel)) {
        let target = to.join(&f.rel);
        if let Some(parent) = target.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create {}", parent.display()))?;
        }
        std::fs::copy(&f.path, &target)
            .with_context(|| format!("cannot copy {}", f.path.display()))?;
    }
    Ok(())
}

/// Whether a file of a run directory is derived from its manifest and tables by drawing:
/// the reports, the figures, the tables of the reports and the RO-Crate metadata.
fn is_drawn(rel: &str) -> bool {
    rel == "report.html"
        || rel == "report.md"
        || rel == CRATE_METADATA
        || rel.starts_with("plots/")
        || rel.starts_with("tables/")
}

/// The hashed manifest (manifest.yaml) as the run resolved it: the figure width of
/// run.json's copy is the one setting a run may take from its command line (`--figure-width`).
fn resolved_manifest(dir: &Path, info: &RunInfo) -> Result<Manifest> {
    let (mut m, _) = runner::load_manifest(&dir.join("manifest.yaml"))?;
    if let Some(w) = info
        .manifest
        .get("figure_width")
        .and_then(serde_json::Value::as_str)
        .and_then(FigureWidth::parse)
    {
        m.figure_width = w;
    }
    Ok(m)
}

/// Checks every file of a stored run that is derived rather than computed, whatever run.json
/// says about the build that made it: run.json's copy of the manifest against the hashed
/// manifest.yaml, run.json's hashes of the tables against the tables, and the reports,
/// figures, tables/ and RO-Crate metadata drawn again from the stored tables, byte for byte.
/// True when all agree.
pub(super) fn derived_match(dir: &Path, prov: &Provenance, out: &mut dyn Write) -> Result<bool> {
    let info = match report::data::load_info(&RunLayout::at(dir)) {
        Ok(i) => i,
        Err(e) => {
            writeln!(
                out,
                "run.json: DIFFERENT: cannot be read as a run's record: {e:#}"
            )?;
            return Ok(false);
        }
    };
    let m = resolved_manifest(dir, &info)?;
    let copy_ok = manifest_copy_matches(&m, &info, out)?;
    let hashes_ok = table_hashes_match(dir, &info, out)?;
    let drawn_ok = drawn_match(dir, &m, &info, prov, out)?;
    Ok(copy_ok && hashes_ok && drawn_ok)
}

/// run.json's copy of the manifest (which the reports are drawn from) against the hashed
/// manifest.yaml, resolved by this build.
fn manifest_copy_matches(m: &Manifest, info: &RunInfo, out: &mut dyn Write) -> Result<bool> {
    let expected = serde_json::to_value(m)?;
    if expected == info.manifest {
        writeln!(
            out,
            "run.json: its copy of the manifest is manifest.yaml as resolved by this build"
        )?;
        return Ok(true);
    }
    let keys = differing_keys(&expected, &info.manifest);
    writeln!(
        out,
        "run.json: DIFFERENT: its copy of the manifest is not manifest.yaml as resolved by \
         this build (differing keys: {})",
        keys.join(", ")
    )?;
    Ok(false)
}

/// The top-level keys in which two JSON objects differ (`manifest` when either is not one).
fn differing_keys(a: &serde_json::Value, b: &serde_json::Value) -> Vec<String> {
    let (Some(a), Some(b)) = (a.as_object(), b.as_object()) else {
        return vec!["manifest".into()];
    };
    let mut keys: Vec<String> = a
        .keys()
        .chain(b.keys())
        .filter(|k| a.get(*k) != b.get(*k))
        .map(|k| shown(k))
        .collect();
    keys.sort();
    keys.dedup();
    keys
}

/// Characters shown of a key or file name read from run.json.
const KEY_SHOWN: usize = 40;

/// A key or name read from a file, as verify prints it: at most [`KEY_SHOWN`] characters,
/// control and format characters escaped.
fn shown(s: &str) -> String {
    s.chars()
        .take(KEY_SHOWN)
        .flat_map(char::escape_debug)
        .collect()
}

/// run.json's `table_sha256` against the Parquet tables of the run directory: every table
/// listed and every listed hash that of the file.
fn table_hashes_match(dir: &Path, info: &RunInfo, out: &mut dyn Write) -> Result<bool> {
    if info.table_sha256.is_empty() {
        writeln!(
            out,
            "tables: run.json records no hashes of its tables (a run of an older version); \
             the tables are checked by the re-run only"
        )?;
        return Ok(true);
    }
    let actual = RunLayout::at(dir).table_sha256()?;
    let mut ok = true;
    for (name, hash) in &actual {
        match info.table_sha256.get(name) {
            Some(h) if h.eq_ignore_ascii_case(hash) => {}
            Some(_) => {
                ok = false;
                writeln!(
                    out,
                    "tables: DIFFERENT: {name} is not the table run.json records"
                )?;
            }
            None => {
                ok = false;
                writeln!(out, "tables: DIFFERENT: {name} is not recorded in run.json")?;
            }
        }
    }
    for name in info
        .table_sha256
        .keys()
        .filter(|n| !actual.contains_key(*n))
    {
        ok = false;
        let shown = shown(name);
        writeln!(
            out,
            "tables: DIFFERENT: {shown} is recorded in run.json but missing"
        )?;
    }
    if ok {
        writeln!(
            out,
            "tables: all {} Parquet tables have the hashes run.json records",
            actual.len()
        )?;
    }
    Ok(ok)
}

/// Draws the reports, figures, tables/ and RO-Crate metadata of the stored run again, from
/// its stored tables, and compares them byte for byte with the stored ones.
fn drawn_match(
    dir: &Path,
    m: &Manifest,
    info: &RunInfo,
    prov: &Provenance,
    out: &mut dyn Write,
) -> Result<bool> {
    let temp = tempfile::Builder::new()
        .prefix("archstudy-redraw-")
        .tempdir()
        .context("cannot create a temporary directory to draw the reports")?;
    crate::output::register_pending(temp.path());
    let again = temp.path().join("run");
    copy_run(dir, &again)?;
    let drawn = report::render_run(&again).and_then(|_| {
        let layout = RunLayout::at(&again);
        std::fs::remove_file(layout.crate_metadata()).ok();
        citation::write_crate_metadata(&layout, m, info)
    });
    let result = match drawn {
        Err(e) => {
            writeln!(
                out,
                "reports: DIFFERENT: cannot be drawn from the stored tables: {e:#}"
            )?;
            Ok(false)
        }
        Ok(()) => compare_drawn(dir, &again, prov, out),
    };
    crate::output::unregister_pending(temp.path());
    result
}

/// Compares every drawn file ([`is_drawn`]) of two run directories.
fn compare_drawn(
    stored: &Path,
    again: &Path,
    prov: &Provenance,
    out: &mut dyn Write,
) -> Result<bool> {
    let (files, _) = archive::run_files(again)?;
    let drawn: Vec<String> = files
        .into_iter()
        .map(|f| f.rel)
        .filter(|r| is_drawn(r))
        .collect();
    let (stored_files, _) = archive::run_files(stored)?;
    let mut differing: Vec<String> = drawn
        .iter()
        .filter(|rel| {
            let a = std::fs::read(stored.join(rel)).ok();
            let b = std::fs::read(again.join(rel)).ok();
            a.is_none() || a != b
        })
        .cloned()
        .collect();
    // A stored figure or table that the stored tables do not produce was added by hand.
    differing.extend(
        stored_files
            .into_iter()
            .map(|f| f.rel)
            .filter(|r| is_drawn(r) && !drawn.contains(r)),
    );
    if differing.is_empty() {
        let figures = drawn.iter().filter(|r| r.starts_with("plots/")).count();
        let tables = drawn.iter().filter(|r| r.starts_with("tables/")).count();
        writeln!(
            out,
            "reports: report.html, report.md, {figures} figure files, {tables} table files and \
             {CRATE_METADATA} drawn again from the stored tables are identical"
        )?;
        return Ok(true);
    }
    let why = if claims_this_build(prov) {
        "is not what the stored tables draw".to_string()
    } else {
        format!(
            "is not what this build draws from the stored tables; run.json names another \
             build (archstudy {}, commit {}), whose drawing this build cannot re-derive",
            prov.archstudy_version.as_deref().unwrap_or("unknown"),
            prov.git_commit.as_deref().unwrap_or("unknown")
        )
    };
    for rel in &differing {
        let state = if stored.join(rel).is_file() {
            ""
        } else {
            " (missing)"
        };
        writeln!(out, "reports: DIFFERENT: {rel}{state} {why}")?;
    }
    Ok(false)
}

/// The number of rows of results.parquet against the number of cases of the manifest's
/// plan, counted from the manifest without expanding the plan; the number of cases when they
/// agree.
pub(super) fn rows_match_plan(dir: &Path, out: &mut dyn Write) -> Result<Option<u128>> {
    let cases = match runner::load_manifest(&dir.join("manifest.yaml")) {
        Ok((manifest, _)) => crate::plan::case_count(&manifest),
        Err(e) => {
            writeln!(
                out,
                "rows: the stored manifest is refused by this build: {e:#}"
            )?;
            return Ok(None);
        }
    };
    let rows = store::parquet_rows(&dir.join("results.parquet"))?;
    if rows as u128 == cases {
        writeln!(
            out,
            "rows: results.parquet has the {cases} rows of the plan"
        )?;
        Ok(Some(cases))
    } else {
        writeln!(
            out,
            "rows: DIFFERENT: results.parquet has {rows} rows, the manifest's plan {cases} cases"
        )?;
        Ok(None)
    }
}
