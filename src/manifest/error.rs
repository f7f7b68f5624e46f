//! The error of a manifest that cannot be read or is not valid: the file, the line and
//! column, the key at fault and what is wrong, on one line.

use std::path::PathBuf;

/// A manifest that could not be read or is not valid.
#[derive(Debug, thiserror::Error)]
#[error("{}", self.render())]
pub struct ManifestError {
    /// The manifest file.
    pub path: PathBuf,
    /// 1-based line and column, when known.
    pub position: Option<(u64, u64)>,
    /// The key at fault (dotted path), when known.
    pub key: Option<String>,
    /// What is wrong, with the value given and what is allowed.
    pub message: String,
}

impl ManifestError {
    fn render(&self) -> String {
        let mut s = self.path.display().to_string();
        if let Some((l, c)) = self.position {
            s.push_str(&format!(":{l}:{c}"));
        }
        s.push_str(": ");
        if let Some(k) = &self.key {
            s.push_str(&format!("key `{k}`: "));
        }
        s.push_str(&self.message);
        s
    }
}
