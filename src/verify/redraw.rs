//! Checks of a stored run that need no re-run: its reports and figures drawn again from its
//! own tables (a report rewritten by hand no longer matches them), and the number of rows of
//! its results against the plan of its manifest (a table cut short or padded).

use crate::archive::{self, Provenance};
use crate::provenance;
use crate::runner;
use crate::store;
use anyhow::{Context, Result};
use std::io::Write;
use std::path::Path;

/// True when the run was made by this very build (same version and commit), whose reports
/// drawn from the same tables are the same bytes.
fn made_by_this_build(p: &Provenance) -> bool {
    p.archstudy_version.as_deref() == Some(provenance::version())
        && p.git_commit.is_some()
        && p.git_commit == provenance::git_commit()
}

/// Copies the regular files of a run directory into `to`.
fn copy_run(dir: &Path, to: &Path) -> Result<()> {
    let (files, _) = archive::run_files(dir)?;
    for f in files {
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

/// Draws the reports and figures of the stored run again, from its stored tables, and
/// compares them byte for byte with the stored ones. Runs made by another build are not
/// compared (its drawing may differ): a note says so.
pub(super) fn reports_match(dir: &Path, prov: &Provenance, out: &mut dyn Write) -> Result<bool> {
    if !made_by_this_build(prov) {
        writeln!(
            out,
            "reports: made by another build; not drawn again (checked by checksum only)"
        )?;
        return Ok(true);
    }
    let temp = tempfile::Builder::new()
        .prefix("archstudy-redraw-")
        .tempdir()
        .context("cannot create a temporary directory to draw the reports")?;
    crate::output::register_pending(temp.path());
    let again = temp.path().join("run");
    copy_run(dir, &again)?;
    let drawn = crate::report::render_run(&again);
    let result = match drawn {
        Err(e) => {
            writeln!(
                out,
                "reports: cannot be drawn from the stored tables: {e:#}"
            )?;
            Ok(false)
        }
        Ok(_) => compare_drawn(dir, &again, out),
    };
    crate::output::unregister_pending(temp.path());
    result
}

/// Compares report.html, report.md and every figure of two run directories.
fn compare_drawn(stored: &Path, again: &Path, out: &mut dyn Write) -> Result<bool> {
    let (files, _) = archive::run_files(again)?;
    let drawn: Vec<String> = files
        .into_iter()
        .map(|f| f.rel)
        .filter(|r| r == "report.html" || r == "report.md" || r.starts_with("plots/"))
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
    // A stored figure that the tables do not produce was added by hand.
    differing.extend(
        stored_files
            .into_iter()
            .map(|f| f.rel)
            .filter(|r| r.starts_with("plots/") && !drawn.contains(r)),
    );
    if differing.is_empty() {
        writeln!(
            out,
            "reports: report.html, report.md and {} figure files drawn again from the stored \
             tables are identical",
            drawn.len().saturating_sub(2)
        )?;
        return Ok(true);
    }
    for rel in &differing {
        writeln!(
            out,
            "reports: DIFFERENT: {rel} is not what the stored tables draw"
        )?;
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
