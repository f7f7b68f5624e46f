//! Unpacking an archive into a temporary directory, checking its shape as it goes: one top
//! directory, only regular files and directories, no path that leaves the top directory.
//! A corrupt or truncated file is an error that says so, never a panic.

use anyhow::{Context, Result, anyhow, bail};
use flate2::read::GzDecoder;
use std::collections::BTreeSet;
use std::fs::File;
use std::io::BufReader;
use std::path::{Component, Path, PathBuf};

/// The most an archive may unpack to: 50 times its own size plus 16 MiB. A run's Parquet
/// files barely compress and its SVG figures compress about tenfold, so real archives stay
/// far below; a small archive of one huge zero-filled member (a "zip bomb") is refused
/// before it fills the disk.
pub fn unpack_limit(archive_bytes: u64) -> u64 {
    archive_bytes.saturating_mul(50).saturating_add(16 << 20)
}

/// An archive unpacked into a temporary directory (removed when dropped).
#[derive(Debug)]
pub struct Unpacked {
    /// The temporary directory holding the top directory.
    pub temp: tempfile::TempDir,
    /// The name of the archive's top directory.
    pub top: String,
    /// Set when every member was read but the gzip stream failed its final check (CRC or
    /// length): the bytes of some member are wrong, and the checksums will say which.
    pub stream_damage: Option<String>,
}

impl Unpacked {
    /// The unpacked top directory: the run directory as archived, with SHA256SUMS.
    pub fn dir(&self) -> PathBuf {
        self.temp.path().join(&self.top)
    }
}

/// Unpacks a `.tar.gz` made by `archstudy archive` into a new temporary directory.
pub fn unpack(archive: &Path) -> Result<Unpacked> {
    let file = File::open(archive).with_context(|| format!("cannot open {}", archive.display()))?;
    let temp = tempfile::Builder::new()
        .prefix("archstudy-verify-")
        .tempdir()
        .context("cannot create a temporary directory to unpack into")?;
    let limit = unpack_limit(file.metadata().map_or(0, |m| m.len()));
    let (top, stream_damage) = unpack_into(file, temp.path(), limit).with_context(|| {
        format!(
            "cannot read {} as an archive made by `archstudy archive` (is it corrupt or truncated?)",
            archive.display()
        )
    })?;
    Ok(Unpacked {
        temp,
        top,
        stream_damage,
    })
}

fn unpack_into(file: File, dest: &Path, limit: u64) -> Result<(String, Option<String>)> {
    use std::io::Read;
    let mut budget = limit;
    let mut tar = tar::Archive::new(GzDecoder::new(BufReader::new(file)));
    let mut top: Option<String> = None;
    let mut seen = BTreeSet::new();
    let entries = tar.entries().context("cannot read the tar stream")?;
    for entry in entries {
        let mut entry = entry.context("cannot read the next member")?;
        let kind = entry.header().entry_type();
        let raw = entry
            .path()
            .context("a member has an unreadable path")?
            .into_owned();
        let shown = raw.display().to_string();
        let mut parts = Vec::new();
        for c in raw.components() {
            match c {
                Component::Normal(p) => parts.push(
                    p.to_str()
                        .ok_or_else(|| anyhow!("member `{shown}`: the path is not UTF-8"))?
                        .to_string(),
                ),
                Component::CurDir => {}
                _ => bail!("member `{shown}`: the path leaves the archive's top directory"),
            }
        }
        let Some(first) = parts.first() else {
            bail!("a member has an empty path");
        };
        match &top {
            None => top = Some(first.clone()),
            Some(t) if t != first => {
                bail!("member `{shown}` is outside the top directory `{t}/`")
            }
            Some(_) => {}
        }
        let target = parts.iter().fold(dest.to_path_buf(), |p, c| p.join(c));
        match kind {
            tar::EntryType::Directory => {
                std::fs::create_dir_all(&target)
                    .with_context(|| format!("cannot create {}", target.display()))?;
            }
            tar::EntryType::Regular | tar::EntryType::Continuous => {
                if parts.len() < 2 {
                    bail!("member `{shown}` is a file where the top directory should be");
                }
                if !seen.insert(parts.join("/")) {
                    bail!("member `{shown}` appears twice");
                }
                if let Some(parent) = target.parent() {
                    std::fs::create_dir_all(parent)
                        .with_context(|| format!("cannot create {}", parent.display()))?;
                }
                let too_big = || {
                    anyhow!(
                        "member `{shown}` would unpack the archive past {limit} bytes (50 times \
                         its size plus 16 MiB); an archive of a run is never that compressible"
                    )
                };
                if entry.header().size().unwrap_or(u64::MAX) > budget {
                    return Err(too_big());
                }
                let mut out = File::create(&target)
                    .with_context(|| format!("cannot create {}", target.display()))?;
                let written = std::io::copy(&mut (&mut entry).take(budget + 1), &mut out)
                    .with_context(|| format!("cannot read member `{shown}`"))?;
                if written > budget {
                    return Err(too_big());
                }
                budget -= written;
            }
            tar::EntryType::XGlobalHeader
            | tar::EntryType::XHeader
            | tar::EntryType::GNULongName
            | tar::EntryType::GNULongLink => {}
            other => bail!("member `{shown}` is a {other:?} entry, not a file or a directory"),
        }
    }
    let top = top.ok_or_else(|| anyhow!("the archive is empty"))?;
    if !dest.join(&top).is_dir() {
        bail!("the archive has no top directory `{top}/`");
    }
    // Read to the end of the gzip stream so a damaged trailer (CRC, length) is noticed too.
    let mut rest = tar.into_inner();
    let damage = std::io::copy(&mut rest, &mut std::io::sink())
        .err()
        .map(|e| format!("the gzip stream is damaged: {e}"));
    Ok((top, damage))
}
