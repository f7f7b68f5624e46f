//! `archstudy archive`: one deterministic `.tar.gz` of a run directory, for deposit with a
//! paper.
//!
//! The archive holds every regular file of the run directory, recursively, under one top
//! directory `<name>-<first 12 hex digits of the manifest's SHA-256>/`, and a `SHA256SUMS`
//! file over all of them (last member). Entries are sorted by path and carry fixed metadata
//! (mode 644/755, uid/gid 0, no owner names, modification time = the run's `finished_at`),
//! and the gzip header has no name or time, so the same run directory always gives the same
//! archive bytes. The archive is written to a temporary sibling and renamed into place.

mod sums;
mod unpack;

pub use sums::{SUMS_FILE, SumEntry, SumsCheck, SumsError, check_sums, format_sums, parse_sums};
pub use unpack::{Unpacked, unpack};

use crate::error::UsageError;
use crate::output::{RunLayout, temp_sibling};
use crate::provenance::sha256_hex;
use anyhow::{Context, Result, bail};
use flate2::Compression;
use flate2::write::GzEncoder;
use std::collections::BTreeSet;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The files every run directory must hold (relative paths).
pub const REQUIRED_FILES: [&str; 3] = ["manifest.yaml", "run.json", "results.parquet"];

/// The files at the top of a run directory that a run writes (besides the figures
/// plots/STEM.{svg,png,pdf} and the tables tables/STEM.{csv,tex}): nothing else is archived, and an archive holding anything else fails
/// `verify`.
pub const RUN_TOP_FILES: [&str; 14] = [
    "manifest.yaml",
    "run.json",
    "results.parquet",
    "boundaries.parquet",
    "bifurcations.parquet",
    "curves.parquet",
    "states.parquet",
    "reference.parquet",
    "mechanisms.parquet",
    "samples.parquet",
    "estimates.parquet",
    "report.html",
    "report.md",
    crate::output::CRATE_METADATA,
];

/// Whether `rel` (relative, `/`-separated) is a file a run writes: one of
/// [`RUN_TOP_FILES`], a figure `plots/STEM.svg`, `.png` or `.pdf`, or a table
/// `tables/STEM.csv` or `.tex` (STEM of letters, digits, `_` and `-`).
pub fn is_run_file(rel: &str) -> bool {
    if RUN_TOP_FILES.contains(&rel) {
        return true;
    }
    let (file, exts): (&str, &[&str]) = if let Some(f) = rel.strip_prefix("plots/") {
        (f, &["svg", "png", "pdf"])
    } else if let Some(t) = rel.strip_prefix("tables/") {
        (t, &["csv", "tex"])
    } else {
        return false;
    };
    let Some((stem, ext)) = file.rsplit_once('.') else {
        return false;
    };
    exts.contains(&ext)
        && !stem.is_empty()
        && stem
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Hex digits of the manifest's SHA-256 in an archive's name.
pub const HASH_PREFIX_LEN: usize = 12;

/// A regular file of a run directory.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct RunFile {
    /// The path relative to the run directory, `/`-separated.
    pub rel: String,
    /// The path on disk.
    pub path: PathBuf,
}

/// Every regular file under `dir`, recursively, sorted by relative path; a `SHA256SUMS` at
/// the top is left out (it is a checksum list, not part of the run). Symbolic links and other
/// special files are returned apart, by relative path.
pub fn run_files(dir: &Path) -> Result<(Vec<RunFile>, Vec<String>)> {
    let mut files = Vec::new();
    let mut skipped = Vec::new();
    walk(dir, "", &mut files, &mut skipped)?;
    files.retain(|f| f.rel != SUMS_FILE);
    files.sort();
    skipped.sort();
    Ok((files, skipped))
}

fn walk(
    dir: &Path,
    prefix: &str,
    files: &mut Vec<RunFile>,
    skipped: &mut Vec<String>,
) -> Result<()> {
    let entries =
        std::fs::read_dir(dir).with_context(|| format!("cannot list {}", dir.display()))?;
    for entry in entries {
        let entry = entry.with_context(|| format!("cannot list {}", dir.display()))?;
        let path = entry.path();
        let name = entry
            .file_name()
            .into_string()
            .map_err(|_| anyhow::anyhow!("{}: the file name is not valid UTF-8", path.display()))?;
        if name.contains(['\n', '\\']) {
            bail!(
                "{}: a file name with a newline or a backslash cannot be listed in {SUMS_FILE}",
                path.display()
            );
        }
        let rel = format!("{prefix}{name}");
        let kind = entry
            .file_type()
            .with_context(|| format!("cannot stat {}", path.display()))?;
        if kind.is_dir() {
            walk(&path, &format!("{rel}/"), files, skipped)?;
        } else if kind.is_file() {
            files.push(RunFile { rel, path });
        } else {
            skipped.push(rel);
        }
    }
    Ok(())
}

/// What run.json says about where a run came from (read leniently, so that run.json files of
/// other versions still read).
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// The study name.
    pub name: String,
    /// SHA-256 of the manifest as run (hex).
    pub manifest_sha256: String,
    /// The archstudy version that made the run.
    pub archstudy_version: Option<String>,
    /// The git commit of that build, when recorded.
    pub git_commit: Option<String>,
    /// When the run finished (RFC 3339), when recorded.
    pub finished_at: Option<String>,
}

/// Reads the provenance fields of a run.json.
pub fn read_provenance(run_json: &Path) -> Result<Provenance> {
    let text = crate::output::read_regular_text(run_json, crate::output::MAX_RUN_JSON_BYTES)
        .with_context(|| format!("cannot read {}", run_json.display()))?;
    let v: serde_json::Value = serde_json::from_str(&text)
        .with_context(|| format!("{} is not valid JSON", run_json.display()))?;
    let field = |k: &str| v.get(k).and_then(|x| x.as_str()).map(str::to_string);
    let name = field("name")
        .with_context(|| format!("{} has no string field `name`", run_json.display()))?;
    let manifest_sha256 = field("manifest_sha256").with_context(|| {
        format!(
            "{} has no string field `manifest_sha256`",
            run_json.display()
        )
    })?;
    if manifest_sha256.len() != 64 || !manifest_sha256.bytes().all(|b| b.is_ascii_hexdigit()) {
        bail!(
            "{}: `manifest_sha256` is `{manifest_sha256}`, not 64 hex digits",
            run_json.display()
        );
    }
    Ok(Provenance {
        name,
        manifest_sha256: manifest_sha256.to_ascii_lowercase(),
        archstudy_version: field("archstudy_version"),
        git_commit: field("git_commit"),
        finished_at: field("finished_at"),
    })
}

/// The archive's top directory (and file stem): `<name>-<first 12 hex of the manifest hash>`,
/// with any character other than ASCII letters, digits, `-` and `_` in the name replaced.
pub fn archive_stem(p: &Provenance) -> String {
    let name: String = p
        .name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("{name}-{}", &p.manifest_sha256[..HASH_PREFIX_LEN])
}

/// Checks that a run directory is complete and consistent: the required files are there and
/// manifest.yaml is the manifest run.json names by hash. Returns run.json's provenance.
pub fn check_run_dir(dir: &Path) -> Result<Provenance> {
    let missing: Vec<&str> = REQUIRED_FILES
        .iter()
        .copied()
        .filter(|f| !dir.join(f).is_file())
        .collect();
    if !missing.is_empty() {
        bail!(
            "{} is not a complete run directory: {} missing",
            dir.display(),
            missing.join(", ")
        );
    }
    let layout = RunLayout::at(dir);
    let p = read_provenance(&layout.run_json())?;
    let manifest = layout.manifest();
    let bytes =
        std::fs::read(&manifest).with_context(|| format!("cannot read {}", manifest.display()))?;
    let actual = sha256_hex(&bytes);
    if actual != p.manifest_sha256 {
        bail!(
            "{} has SHA-256 {actual}, but {} says the manifest run had {}",
            manifest.display(),
            layout.run_json().display(),
            p.manifest_sha256
        );
    }
    Ok(p)
}

/// What `archive` wrote.
#[derive(Debug, Clone)]
pub struct ArchiveSummary {
    /// The archive file.
    pub path: PathBuf,
    /// Its top directory.
    pub top: String,
    /// Files archived (not counting SHA256SUMS).
    pub files: usize,
    /// Size of the archive, in bytes.
    pub bytes: u64,
    /// Entries of the run directory left out (not regular files).
    pub skipped: Vec<String>,
}

/// Writes the archive of a run directory to `out`, or to `<stem>.tar.gz` in the current
/// directory (in `out` when it is a directory); an existing archive file is replaced.
pub fn write_archive(run_dir: &Path, out: Option<&Path>) -> Result<ArchiveSummary> {
    write_archive_with(run_dir, out, true)
}

/// [`write_archive`], refusing to replace an existing file unless `force`.
pub fn write_archive_with(
    run_dir: &Path,
    out: Option<&Path>,
    force: bool,
) -> Result<ArchiveSummary> {
    if !run_dir.is_dir() {
        return Err(UsageError::new(
            "RUN_DIR",
            run_dir.display(),
            "a run directory written by `archstudy run`",
        )
        .into());
    }
    let prov = check_run_dir(run_dir)?;
    let top = archive_stem(&prov);
    let file_name = format!("{top}.tar.gz");
    let path = match out {
        None => PathBuf::from(&file_name),
        Some(o) if o.is_dir() => o.join(&file_name),
        Some(o) => o.to_path_buf(),
    };
    if std::fs::symlink_metadata(&path).is_ok() && !force {
        return Err(UsageError::new(
            "--output",
            path.display(),
            "the archive file exists and is not replaced: give --force to replace it, or \
             another -o FILE",
        )
        .into());
    }
    if let Some(parent) = path.parent() {
        let parent = if parent.as_os_str().is_empty() {
            Path::new(".")
        } else {
            parent
        };
        crate::output::sweep_temporaries(parent);
    }
    crate::output::sweep_temporaries(run_dir);
    let (mut files, mut skipped) = run_files(run_dir)?;
    // Only the files a run writes are packed: a leftover temporary or a stray file is not.
    skipped.extend(
        files
            .iter()
            .filter(|f| !is_run_file(&f.rel))
            .map(|f| f.rel.clone()),
    );
    files.retain(|f| is_run_file(&f.rel));
    let mtime = prov
        .finished_at
        .as_deref()
        .and_then(|t| chrono::DateTime::parse_from_rfc3339(t).ok())
        .map_or(0, |t| u64::try_from(t.timestamp()).unwrap_or(0));

    let tmp = temp_sibling(&path);
    crate::output::register_pending(&tmp);
    let result = (|| -> Result<u64> {
        let file =
            File::create(&tmp).with_context(|| format!("cannot create {}", tmp.display()))?;
        let gz = GzEncoder::new(BufWriter::new(file), Compression::default());
        let mut tar = tar::Builder::new(gz);
        write_members(&mut tar, &top, &files, mtime)
            .with_context(|| format!("cannot write {}", tmp.display()))?;
        let file = tar
            .into_inner()
            .and_then(|gz| gz.finish())
            .and_then(|w| w.into_inner().map_err(|e| e.into_error()))
            .with_context(|| format!("cannot write {}", tmp.display()))?;
        file.sync_all()
            .with_context(|| format!("cannot write {}", tmp.display()))?;
        let bytes = file.metadata().map(|m| m.len()).unwrap_or(0);
        std::fs::rename(&tmp, &path)
            .with_context(|| format!("cannot move {} into place", path.display()))?;
        Ok(bytes)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    crate::output::unregister_pending(&tmp);
    Ok(ArchiveSummary {
        path,
        top,
        files: files.len(),
        bytes: result?,
        skipped,
    })
}

/// Appends the directories, the files (sorted) and SHA256SUMS (last).
fn write_members<W: Write>(
    tar: &mut tar::Builder<W>,
    top: &str,
    files: &[RunFile],
    mtime: u64,
) -> Result<()> {
    let mut dirs_done = BTreeSet::new();
    append_dir(tar, &format!("{top}/"), mtime)?;
    let mut sums = Vec::with_capacity(files.len());
    for f in files {
        // Parent directories first, each once.
        let parts: Vec<&str> = f.rel.split('/').collect();
        for i in 1..parts.len() {
            let d = parts[..i].join("/");
            if dirs_done.insert(d.clone()) {
                append_dir(tar, &format!("{top}/{d}/"), mtime)?;
            }
        }
        let bytes =
            std::fs::read(&f.path).with_context(|| format!("cannot read {}", f.path.display()))?;
        sums.push(SumEntry {
            sha256: sha256_hex(&bytes),
            path: f.rel.clone(),
        });
        append_file(tar, &format!("{top}/{}", f.rel), &bytes, mtime)?;
    }
    append_file(
        tar,
        &format!("{top}/{SUMS_FILE}"),
        format_sums(&sums).as_bytes(),
        mtime,
    )
}

fn header(kind: tar::EntryType, mode: u32, size: u64, mtime: u64) -> tar::Header {
    let mut h = tar::Header::new_gnu();
    h.set_entry_type(kind);
    h.set_mode(mode);
    h.set_size(size);
    h.set_mtime(mtime);
    h.set_uid(0);
    h.set_gid(0);
    h
}

fn append_dir<W: Write>(tar: &mut tar::Builder<W>, path: &str, mtime: u64) -> Result<()> {
    let mut h = header(tar::EntryType::Directory, 0o755, 0, mtime);
    tar.append_data(&mut h, path, std::io::empty())
        .with_context(|| format!("cannot add the directory {path}"))
}

fn append_file<W: Write>(
    tar: &mut tar::Builder<W>,
    path: &str,
    bytes: &[u8],
    mtime: u64,
) -> Result<()> {
    let mut h = header(tar::EntryType::Regular, 0o644, bytes.len() as u64, mtime);
    tar.append_data(&mut h, path, bytes)
        .with_context(|| format!("cannot add {path}"))
}
