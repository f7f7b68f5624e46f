//! SHA256SUMS: the checksum list of an archive, in the format of `sha256sum` (one
//! `<64 hex digits>  <path>` line per file, paths relative to the archive's top directory,
//! `/`-separated, sorted), so `sha256sum -c SHA256SUMS` checks an unpacked archive too.

use crate::provenance::sha256_hex;
use anyhow::{Context, Result};
use std::collections::BTreeMap;
use std::path::Path;

/// The name of the checksum file at the top of an archive.
pub const SUMS_FILE: &str = "SHA256SUMS";

/// One line of a SHA256SUMS file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SumEntry {
    /// Lower-case hex SHA-256 of the file's bytes (64 characters).
    pub sha256: String,
    /// The path relative to the top directory, `/`-separated.
    pub path: String,
}

/// Formats checksum lines as `sha256sum` writes them (text mode: two spaces).
pub fn format_sums(entries: &[SumEntry]) -> String {
    entries
        .iter()
        .map(|e| format!("{}  {}\n", e.sha256, e.path))
        .collect()
}

/// A malformed SHA256SUMS line.
#[derive(Debug, thiserror::Error)]
#[error("{file} line {line}: {message}")]
pub struct SumsError {
    /// The checksum file.
    pub file: String,
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// Parses a SHA256SUMS file (text or binary mode markers, `*` or space, both accepted).
pub fn parse_sums(text: &str, file: &str) -> Result<Vec<SumEntry>, SumsError> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let err = |message: String| SumsError {
            file: file.to_string(),
            line: i + 1,
            message,
        };
        if line.trim().is_empty() {
            continue;
        }
        let (hash, rest) = line
            .split_once(' ')
            .ok_or_else(|| err(format!("expected `<sha256>  <path>`, found `{line}`")))?;
        if hash.len() != 64 || !hash.bytes().all(|b| b.is_ascii_hexdigit()) {
            return Err(err(format!("`{hash}` is not a SHA-256 (64 hex digits)")));
        }
        let path = rest
            .strip_prefix(' ')
            .or_else(|| rest.strip_prefix('*'))
            .ok_or_else(|| {
                err(format!(
                    "expected two spaces after the checksum in `{line}`"
                ))
            })?;
        if path.is_empty() {
            return Err(err("the path is empty".into()));
        }
        out.push(SumEntry {
            sha256: hash.to_ascii_lowercase(),
            path: path.to_string(),
        });
    }
    Ok(out)
}

/// The outcome of checking files against a checksum list.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SumsCheck {
    /// Files listed and found with the right checksum.
    pub matching: Vec<String>,
    /// Files listed but absent.
    pub missing: Vec<String>,
    /// Files present but not listed.
    pub extra: Vec<String>,
    /// Files listed and present whose bytes do not match their checksum.
    pub corrupt: Vec<String>,
    /// Paths listed more than once.
    pub duplicated: Vec<String>,
}

impl SumsCheck {
    /// Whether every listed file is present and intact and nothing else is there.
    pub fn ok(&self) -> bool {
        self.missing.is_empty()
            && self.extra.is_empty()
            && self.corrupt.is_empty()
            && self.duplicated.is_empty()
    }
}

/// Checks the files under `dir` (given by their relative `/`-separated paths) against a
/// checksum list: every listed file must be present and match, and no other file be there.
pub fn check_sums(dir: &Path, listed: &[SumEntry], present: &[String]) -> Result<SumsCheck> {
    let mut check = SumsCheck::default();
    let mut expected: BTreeMap<&str, &str> = BTreeMap::new();
    for e in listed {
        if expected.insert(&e.path, &e.sha256).is_some() {
            check.duplicated.push(e.path.clone());
        }
    }
    let present_set: std::collections::BTreeSet<&str> =
        present.iter().map(String::as_str).collect();
    for (path, sha) in &expected {
        if !present_set.contains(path) {
            check.missing.push(path.to_string());
            continue;
        }
        let file = dir.join(path);
        let bytes =
            std::fs::read(&file).with_context(|| format!("cannot read {}", file.display()))?;
        if sha256_hex(&bytes) == *sha {
            check.matching.push(path.to_string());
        } else {
            check.corrupt.push(path.to_string());
        }
    }
    check.extra = present_set
        .iter()
        .filter(|p| !expected.contains_key(*p))
        .map(|p| p.to_string())
        .collect();
    Ok(check)
}

#[cfg(test)]
mod tests {
    use super::*;

    const H: &str = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855";

    #[test]
    fn format_and_parse_round_trip() {
        let entries = vec![
            SumEntry {
                sha256: H.into(),
                path: "plots/a b.svg".into(),
            },
            SumEntry {
                sha256: H.into(),
                path: "run.json".into(),
            },
        ];
        let text = format_sums(&entries);
        assert_eq!(text.lines().next(), Some(&*format!("{H}  plots/a b.svg")));
        assert_eq!(parse_sums(&text, "SHA256SUMS").unwrap(), entries);
    }

    #[test]
    fn malformed_lines_are_named() {
        let e = parse_sums(&format!("{H}  ok\nnot a checksum line\n"), "S").unwrap_err();
        assert_eq!(e.line, 2);
        assert!(e.to_string().starts_with("S line 2:"), "{e}");
        assert!(parse_sums("abc  x\n", "S").is_err());
        assert!(parse_sums(&format!("{H}x\n"), "S").is_err());
    }

    #[test]
    fn missing_extra_and_corrupt_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("a"), b"").unwrap();
        std::fs::write(dir.path().join("b"), b"x").unwrap();
        std::fs::write(dir.path().join("c"), b"").unwrap();
        let listed = vec![
            SumEntry {
                sha256: H.into(),
                path: "a".into(),
            },
            SumEntry {
                sha256: H.into(),
                path: "b".into(),
            },
            SumEntry {
                sha256: H.into(),
                path: "gone".into(),
            },
        ];
        let present = vec!["a".to_string(), "b".to_string(), "c".to_string()];
        let c = check_sums(dir.path(), &listed, &present).unwrap();
        assert_eq!(c.matching, vec!["a"]);
        assert_eq!(c.corrupt, vec!["b"]);
        assert_eq!(c.missing, vec!["gone"]);
        assert_eq!(c.extra, vec!["c"]);
        assert!(!c.ok());
    }
}
