//! The output layout: the one owner of every path a run writes.
//!
//! A run is written into a hidden staging directory beside its final place and renamed into
//! place only when complete, so a crash or Ctrl-C never leaves a half-written run directory;
//! single files are written to a temporary sibling and renamed.

use crate::error::UsageError;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Paths this process is writing and would leave half-written if it were stopped: staging
/// directories and temporary files. A signal handler removes them ([`remove_pending`]).
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Records a staging directory or temporary file to remove if the process is interrupted.
pub fn register_pending(path: &Path) {
    if let Ok(mut p) = PENDING.lock() {
        p.push(path.to_path_buf());
    }
}

/// Forgets a path recorded by [`register_pending`] (it was renamed into place or removed).
pub fn unregister_pending(path: &Path) {
    if let Ok(mut p) = PENDING.lock()
        && let Some(i) = p.iter().rposition(|x| x == path)
    {
        p.swap_remove(i);
    }
}

/// Removes every staging directory and temporary file this process is writing; called when
/// the process is interrupted (Ctrl-C, SIGTERM), just before it exits.
pub fn remove_pending() {
    let paths = match PENDING.lock() {
        Ok(p) => p.clone(),
        Err(e) => e.into_inner().clone(),
    };
    for p in paths {
        // The other threads keep writing until the process exits: a file or directory they
        // create while the tree is being removed makes the removal fail, so it is tried
        // again while anything is left.
        for _ in 0..REMOVE_ATTEMPTS {
            let _ = std::fs::remove_dir_all(&p).or_else(|_| std::fs::remove_file(&p));
            if std::fs::symlink_metadata(&p).is_err() {
                break;
            }
        }
    }
}

/// How many times an interrupted run tries to remove a pending path that the still running
/// threads write into.
const REMOVE_ATTEMPTS: usize = 100;

/// Whether `dir` is a run directory `archstudy run` wrote (a directory, not a symbolic link,
/// holding run.json and manifest.yaml), so that a new run of the same name may replace it.
pub fn is_run_dir(dir: &Path) -> bool {
    std::fs::symlink_metadata(dir).is_ok_and(|m| m.is_dir())
        && dir.join("run.json").is_file()
        && dir.join("manifest.yaml").is_file()
}

/// Refuses a run's target `OUT/NAME` when something other than a run directory is there:
/// nothing but an earlier run is ever replaced.
pub fn check_replaceable(target: &Path) -> Result<(), UsageError> {
    if std::fs::symlink_metadata(target).is_err() || is_run_dir(target) {
        return Ok(());
    }
    Err(UsageError::new(
        "--out",
        target.display(),
        "the run directory OUT/NAME exists and is not a run directory (no run.json and \
         manifest.yaml, or a symbolic link); it is never replaced: move it away, or choose \
         another --out or study name",
    ))
}

/// Refuses to write through a symbolic link: `path` (a file or directory a command writes in
/// a run directory) must not be one, so no write leaves the run directory.
pub fn refuse_symlink(path: &Path) -> Result<(), UsageError> {
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(UsageError::new(
            "RUN_DIR",
            path.display(),
            "a file or directory the command writes is a symbolic link, which could lead \
             outside the run directory: remove the link (the command recreates it as a plain \
             file or directory)",
        ));
    }
    Ok(())
}

/// Refuses a run directory whose plots/, tables/, report.html, report.md or any figure or
/// table file is a symbolic link: re-rendering writes only inside the run directory.
pub fn refuse_symlinks_in(layout: &RunLayout) -> Result<(), UsageError> {
    refuse_symlink(&layout.plots())?;
    refuse_symlink(&layout.tables())?;
    refuse_symlink(&layout.report_html())?;
    refuse_symlink(&layout.report_md())?;
    for dir in [layout.plots(), layout.tables()] {
        if let Ok(entries) = std::fs::read_dir(dir) {
            for e in entries.flatten() {
                refuse_symlink(&e.path())?;
            }
        }
    }
    Ok(())
}

/// The process id in a leftover's name `.NAME.partial-PID`, `.NAME.old-PID` or
/// `.NAME.tmp-PID`, when that process no longer runs.
fn dead_owner(file_name: &str, markers: &[&str]) -> Option<u32> {
    let pid = markers.iter().find_map(|m| {
        let i = file_name.rfind(m)?;
        file_name[i + m.len()..].parse::<u32>().ok()
    })?;
    (file_name.starts_with('.')
        && pid != std::process::id()
        && !Path::new(&format!("/proc/{pid}")).exists())
    .then_some(pid)
}

/// Removes the temporary files `.FILE.tmp-PID` that processes which no longer run left in
/// `dir` (and, for a run directory, in its plots/ and tables/), e.g. after kill -9 or a full
/// disk.
pub fn sweep_temporaries(dir: &Path) {
    for d in [dir.to_path_buf(), dir.join("plots"), dir.join("tables")] {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name();
            if let Some(f) = name.to_str()
                && dead_owner(f, &[".tmp-"]).is_some()
                && e.file_type().is_ok_and(|t| t.is_file())
            {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}

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
    /// samples.parquet: every sample of a sampling study with its values and answer
    /// (docs/report-files.md).
    pub fn samples(&self) -> PathBuf {
        self.dir.join("samples.parquet")
    }
    /// estimates.parquet: the estimates of a sampling study (docs/report-files.md).
    pub fn estimates(&self) -> PathBuf {
        self.dir.join("estimates.parquet")
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
    /// tables/: every table of the reports as CSV and LaTeX.
    pub fn tables(&self) -> PathBuf {
        self.dir.join("tables")
    }
    /// A table file in tables/.
    pub fn table(&self, stem: &str, ext: &str) -> PathBuf {
        self.tables().join(format!("{stem}.{ext}"))
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

    /// Hex SHA-256 of every Parquet table at the top of the run directory, by file name
    /// (run.json's `table_sha256`).
    pub fn table_sha256(&self) -> Result<std::collections::BTreeMap<String, String>> {
        let mut out = std::collections::BTreeMap::new();
        for (rel, _) in self.files()? {
            if rel.contains('/') || !rel.ends_with(".parquet") {
                continue;
            }
            let path = self.dir.join(&rel);
            let file = std::fs::File::open(&path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            let hash = crate::provenance::sha256_reader(std::io::BufReader::new(file))
                .with_context(|| format!("cannot read {}", path.display()))?;
            out.insert(rel, hash);
        }
        Ok(out)
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

/// The largest run.json read (64 MiB; a run's is a few kilobytes): a larger file is refused
/// rather than read into memory.
pub const MAX_RUN_JSON_BYTES: u64 = 64 << 20;

/// Reads a file that must be a regular file of at most `max_bytes` bytes, as text. A FIFO, a
/// device (/dev/zero) or a directory is refused before it is opened (opening a FIFO waits for
/// a writer; a device never ends), a larger file before it is read.
pub fn read_regular_text(path: &Path, max_bytes: u64) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind, Read};
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            "not a regular file (devices, pipes and directories are not read)",
        ));
    }
    if meta.len() > max_bytes {
        return Err(Error::new(
            ErrorKind::InvalidData,
            format!("larger than {max_bytes} bytes, the most that is read of it"),
        ));
    }
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(max_bytes + 1)
        .read_to_string(&mut text)?;
    if text.len() as u64 > max_bytes {
        return Err(Error::new(
            ErrorKind::InvalidData,
            format!("larger than {max_bytes} bytes, the most that is read of it"),
        ));
    }
    Ok(text)
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
        sweep_temporaries(out);
        check_replaceable(&out.join(name))?;
        let staging = out.join(format!(".{name}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging)
                .with_context(|| format!("cannot clear {}", staging.display()))?;
        }
        register_pending(&staging);
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
        check_replaceable(&self.target)?;
        let had_old = is_run_dir(&self.target);
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
        unregister_pending(&self.layout.dir);
        Ok(self.target.clone())
    }
}

impl Drop for StagedRun {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.layout.dir);
            unregister_pending(&self.layout.dir);
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
        let ours =
            f.starts_with(&format!(".{name}.partial-")) || f.starts_with(&format!(".{name}.old-"));
        if ours
            && dead_owner(f, &[".partial-", ".old-"]).is_some()
            && e.file_type().is_ok_and(|t| t.is_dir())
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

/// Writes bytes to a file atomically: to a temporary sibling, renamed onto the file once
/// complete; the temporary is removed on any error (a full disk leaves nothing behind).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = temp_sibling(path);
    register_pending(&tmp);
    let result = std::fs::write(&tmp, bytes)
        .with_context(|| format!("cannot write {}", tmp.display()))
        .and_then(|()| {
            std::fs::rename(&tmp, path)
                .with_context(|| format!("cannot move {} into place", path.display()))
        });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    unregister_pending(&tmp);
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A process id no process has (Linux pids stay below 2^22).
    const DEAD: u32 = 4_000_000_000;

    #[test]
    fn only_an_absent_target_or_an_earlier_run_may_be_replaced() {
        let t = tempfile::tempdir().unwrap();
        let out = t.path();
        assert!(check_replaceable(&out.join("absent")).is_ok());
        std::fs::write(out.join("file"), "mine").unwrap();
        assert!(check_replaceable(&out.join("file")).is_err());
        std::fs::create_dir(out.join("dir")).unwrap();
        std::fs::write(out.join("dir/notes.txt"), "mine").unwrap();
        assert!(check_replaceable(&out.join("dir")).is_err());
        std::fs::create_dir(out.join("run")).unwrap();
        std::fs::write(out.join("run/run.json"), "{}").unwrap();
        std::fs::write(out.join("run/manifest.yaml"), "name: run").unwrap();
        assert!(check_replaceable(&out.join("run")).is_ok());
        std::os::unix::fs::symlink(out.join("run"), out.join("link")).unwrap();
        assert!(check_replaceable(&out.join("link")).is_err());
    }

    #[test]
    fn a_staged_run_never_replaces_a_users_directory() {
        let t = tempfile::tempdir().unwrap();
        let out = t.path();
        std::fs::create_dir(out.join("study")).unwrap();
        std::fs::write(out.join("study/thesis.tex"), "years of work").unwrap();
        let e = StagedRun::create(out, "study").unwrap_err();
        assert!(e.is::<UsageError>(), "{e:#}");
        assert!(e.to_string().contains("not a run directory"), "{e}");
        let names: Vec<String> = std::fs::read_dir(out)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(names, ["study"]);
        assert_eq!(
            std::fs::read_to_string(out.join("study/thesis.tex")).unwrap(),
            "years of work"
        );
    }

    #[test]
    fn a_failed_atomic_write_leaves_no_temporary() {
        let t = tempfile::tempdir().unwrap();
        // The rename fails: a non-empty directory is where the file should go.
        let target = t.path().join("report.html");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("x"), "x").unwrap();
        assert!(write_atomic(&target, b"<html>").is_err());
        assert!(!temp_sibling(&target).exists());
        assert_eq!(std::fs::read_dir(t.path()).unwrap().count(), 1);
        assert!(!PENDING.lock().unwrap().contains(&temp_sibling(&target)));
    }

    #[test]
    fn leftovers_of_dead_processes_are_swept_and_others_kept() {
        let t = tempfile::tempdir().unwrap();
        let d = t.path();
        std::fs::create_dir(d.join("plots")).unwrap();
        let dead = [
            format!(".report.html.tmp-{DEAD}"),
            format!("plots/.a.svg.tmp-{DEAD}"),
        ];
        let kept = [
            format!(".report.html.tmp-{}", std::process::id()),
            "notes.tmp-12".to_string(),
            "report.md".to_string(),
        ];
        for f in dead.iter().chain(&kept) {
            std::fs::write(d.join(f), "x").unwrap();
        }
        sweep_temporaries(d);
        for f in &dead {
            assert!(!d.join(f).exists(), "{f} left");
        }
        for f in &kept {
            assert!(d.join(f).exists(), "{f} removed");
        }
        std::fs::create_dir(d.join(format!(".s.partial-{DEAD}"))).unwrap();
        std::fs::create_dir(d.join(format!(".s.old-{DEAD}"))).unwrap();
        std::fs::create_dir(d.join(format!(".other.partial-{DEAD}"))).unwrap();
        remove_stale_staging(d, "s");
        assert!(!d.join(format!(".s.partial-{DEAD}")).exists());
        assert!(!d.join(format!(".s.old-{DEAD}")).exists());
        assert!(d.join(format!(".other.partial-{DEAD}")).exists());
    }

    #[test]
    fn pending_paths_are_removed_on_interrupt() {
        let t = tempfile::tempdir().unwrap();
        let staging = t.path().join(".s.partial-1");
        std::fs::create_dir_all(staging.join("plots")).unwrap();
        std::fs::write(staging.join("plots/a.svg"), "x").unwrap();
        let tmp = t.path().join(".f.tmp-1");
        std::fs::write(&tmp, "x").unwrap();
        register_pending(&staging);
        register_pending(&tmp);
        remove_pending();
        unregister_pending(&staging);
        unregister_pending(&tmp);
        assert!(!staging.exists() && !tmp.exists());
    }
}
