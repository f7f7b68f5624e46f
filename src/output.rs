//! The output layout: the one owner of every path a run writes.
//!
//! A run is written into a hidden staging directory beside its final place and renamed into
//! place only when complete, so a crash or Ctrl-C never leaves a half-written run directory;
//! single files are written to a temporary sibling and renamed.

use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// The files of one run directory.
#[derive(Debug, Clone)]
pub struct RunLayout {
    /// The directory the files are written to (staging during a run, final afterwards).
    pub dir: PathBuf,
}

impl RunLayout {
    /// The layout of an existing run directory.
    pub fn at(dir: impl Into<PathBuf>) -> Self {
        RunLayout { dir: dir.into() }
    }
    /// results.parquet.
    pub fn results(&self) -> PathBuf {
        self.dir.join("results.parquet")
    }
    /// boundaries.parquet.
    pub fn boundaries(&self) -> PathBuf {
        self.dir.join("boundaries.parquet")
    }
    /// bifurcations.parquet.
    pub fn bifurcations(&self) -> PathBuf {
        self.dir.join("bifurcations.parquet")
    }
    /// curves.parquet: the curves of the figures that need the statics (docs/report-files.md).
    pub fn curves(&self) -> PathBuf {
        self.dir.join("curves.parquet")
    }
    /// states.parquet: the states the figures draw (docs/report-files.md).
    pub fn states(&self) -> PathBuf {
        self.dir.join("states.parquet")
    }
    /// reference.parquet: continuum values of discrete cases (docs/report-files.md).
    pub fn reference(&self) -> PathBuf {
        self.dir.join("reference.parquet")
    }
    /// mechanisms.parquet: the mechanisms at each bifurcation (docs/report-files.md).
    pub fn mechanisms(&self) -> PathBuf {
        self.dir.join("mechanisms.parquet")
    }
    /// run.json.
    pub fn run_json(&self) -> PathBuf {
        self.dir.join("run.json")
    }
    /// The manifest as run (a byte copy of the input file).
    pub fn manifest(&self) -> PathBuf {
        self.dir.join("manifest.yaml")
    }
    /// plots/.
    pub fn plots(&self) -> PathBuf {
        self.dir.join("plots")
    }
    /// A figure file in plots/.
    pub fn plot(&self, stem: &str, ext: &str) -> PathBuf {
        self.plots().join(format!("{stem}.{ext}"))
    }
    /// report.html.
    pub fn report_html(&self) -> PathBuf {
        self.dir.join("report.html")
    }
    /// report.md.
    pub fn report_md(&self) -> PathBuf {
        self.dir.join("report.md")
    }

    /// ro-crate-metadata.json: how to cite the run and what it holds.
    pub fn crate_metadata(&self) -> PathBuf {
        self.dir.join(CRATE_METADATA)
    }

    /// Every regular file of the run directory (recursively, hidden files and the crate
    /// metadata itself left out) as `/`-separated relative paths with their sizes in bytes,
    /// sorted by path. Links are not followed.
    pub fn files(&self) -> Result<Vec<(String, u64)>> {
        let mut out = Vec::new();
        list_files(&self.dir, "", &mut out)?;
        out.retain(|(rel, _)| rel != CRATE_METADATA);
        out.sort();
        Ok(out)
    }
}

/// The file name of a run's RO-Crate metadata.
pub const CRATE_METADATA: &str = "ro-crate-metadata.json";

fn list_files(dir: &Path, prefix: &str, out: &mut Vec<(String, u64)>) -> Result<()> {
    let entries =
        std::fs::read_dir(dir).with_context(|| format!("cannot list {}", dir.display()))?;
    for entry in entries {
        let entry = entry.with_context(|| format!("cannot list {}", dir.display()))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let kind = entry
            .file_type()
            .with_context(|| format!("cannot read {}", entry.path().display()))?;
        let rel = format!("{prefix}{name}");
        if kind.is_dir() {
            list_files(&entry.path(), &format!("{rel}/"), out)?;
        } else if kind.is_file() {
            let len = entry.metadata().map(|m| m.len()).unwrap_or(0);
            out.push((rel, len));
        }
    }
    Ok(())
}

/// A run being written: staging directory and final place.
#[derive(Debug)]
pub struct StagedRun {
    /// Where files go while the run is in progress.
    pub layout: RunLayout,
    /// Where the run directory ends up.
    pub target: PathBuf,
    committed: bool,
}

impl StagedRun {
    /// Creates the staging directory `OUT/.NAME.partial-PID` (fails at once on a bad path).
    pub fn create(out: &Path, name: &str) -> Result<Self> {
        std::fs::create_dir_all(out)
            .with_context(|| format!("cannot create the output directory {}", out.display()))?;
        remove_stale_staging(out, name);
        let staging = out.join(format!(".{name}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging)
                .with_context(|| format!("cannot clear {}", staging.display()))?;
        }
        std::fs::create_dir_all(staging.join("plots"))
            .with_context(|| format!("cannot create {}", staging.display()))?;
        Ok(StagedRun {
            layout: RunLayout::at(staging),
            target: out.join(name),
            committed: false,
        })
    }

    /// Moves the complete run into place, replacing an earlier run of the same name.
    pub fn commit(mut self) -> Result<PathBuf> {
        let old = self.target.with_file_name(format!(
            ".{}.old-{}",
            self.target
                .file_name()
                .and_then(|s| s.to_str())
                .unwrap_or("run"),
            std::process::id()
        ));
        let had_old = self.target.exists();
        if had_old {
            std::fs::rename(&self.target, &old).with_context(|| {
                format!(
                    "cannot move the earlier run {} aside",
                    self.target.display()
                )
            })?;
        }
        std::fs::rename(&self.layout.dir, &self.target)
            .with_context(|| format!("cannot move the run into {}", self.target.display()))?;
        if had_old {
            let _ = std::fs::remove_dir_all(&old);
        }
        self.committed = true;
        Ok(self.target.clone())
    }
}

impl Drop for StagedRun {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.layout.dir);
        }
    }
}

/// Removes staging and set-aside directories of `name` left by runs that were killed (their
/// process no longer exists), so an interrupted run leaves nothing behind for long.
fn remove_stale_staging(out: &Path, name: &str) {
    let Ok(entries) = std::fs::read_dir(out) else {
        return;
    };
    for e in entries.flatten() {
        let file = e.file_name();
        let Some(f) = file.to_str() else { continue };
        let pid = f
            .strip_prefix(&format!(".{name}.partial-"))
            .or_else(|| f.strip_prefix(&format!(".{name}.old-")))
            .and_then(|p| p.parse::<u32>().ok());
        if let Some(pid) = pid
            && pid != std::process::id()
            && !Path::new(&format!("/proc/{pid}")).exists()
        {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

/// A temporary sibling of a file, renamed onto it once written.
pub fn temp_sibling(path: &Path) -> PathBuf {
    let name = path.file_name().and_then(|s| s.to_str()).unwrap_or("file");
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

/// Writes bytes to a file atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = temp_sibling(path);
    std::fs::write(&tmp, bytes).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, path)
        .with_context(|| format!("cannot move {} into place", path.display()))?;
    Ok(())
}
