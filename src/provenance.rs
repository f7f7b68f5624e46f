//! Provenance of a run: what was run, with which build, when, and how long each stage took.
//! Written to run.json by the runner and read back by the report, archive and verify, so it
//! sits below all of them.

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

/// Wall time of each stage of a run, in milliseconds.
#[derive(Debug, Clone, Default, Serialize, Deserialize, PartialEq)]
pub struct StageTimings {
    /// Reading the manifest and building the plan.
    pub plan_ms: f64,
    /// Analysing every case.
    pub engine_ms: f64,
    /// Writing results.parquet.
    pub store_ms: f64,
    /// Locating boundaries and bifurcations and writing their tables.
    pub boundaries_ms: f64,
    /// Rendering the figures.
    pub plots_ms: f64,
    /// Rendering both reports.
    pub report_ms: f64,
}

/// Cases by status.
#[derive(Debug, Clone, Default, Serialize, Deserialize, PartialEq)]
pub struct CaseCounts {
    /// All cases.
    pub total: u64,
    /// Cases that produced an answer.
    pub ok: u64,
    /// Cases that failed (see their `message`).
    pub error: u64,
}

/// Provenance of a run: what was run, with what, when, and how long it took.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct RunInfo {
    /// The study name.
    pub name: String,
    /// The resolved manifest (defaults filled in).
    pub manifest: serde_json::Value,
    /// SHA-256 of the manifest file as read.
    pub manifest_sha256: String,
    /// The manifest path as given.
    pub manifest_path: String,
    /// archstudy version.
    pub archstudy_version: String,
    /// Git commit of the build, when known (`-dirty` when built from a modified tree).
    pub git_commit: Option<String>,
    /// rustc that built archstudy.
    pub rustc_version: String,
    /// The command line.
    pub command_line: Vec<String>,
    /// Worker threads.
    pub threads: usize,
    /// Start time (RFC 3339, UTC).
    pub started_at: String,
    /// End time (RFC 3339, UTC).
    pub finished_at: String,
    /// Cases by status.
    pub cases: CaseCounts,
    /// Whether the separable fast path was used (symmetric `state` grid of a circular arch
    /// with radial joints).
    pub separable: bool,
    /// How the engine went through the plan: `separable`, `k_lines` (symmetric `state` grid
    /// of another form, per K line) or `case_by_case`; empty in runs made before it was
    /// recorded.
    #[serde(default)]
    pub grid_path: String,
    /// Wall time of each stage.
    pub stages: StageTimings,
    /// Extra analyses spent locating boundaries and bifurcations.
    pub boundary_refinement_analyses: u64,
    /// Hex SHA-256 of every Parquet table of the run directory, by file name, as written
    /// (a shard's: its results.parquet; empty in runs made before it was recorded).
    #[serde(default)]
    pub table_sha256: std::collections::BTreeMap<String, String>,
    /// For a merged run: the builds that analysed its shards, each with the shards it ran
    /// (empty, and not written, for a run that was not merged).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub shard_builds: Vec<ShardBuild>,
}

/// A build that analysed shards of a merged run, as the shards' run.json record it.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, Eq)]
pub struct ShardBuild {
    /// archstudy version.
    pub archstudy_version: String,
    /// Git commit of the build, when known.
    pub git_commit: Option<String>,
    /// rustc that built it.
    pub rustc_version: String,
    /// The shards it ran, as ranges of shard numbers (`1-37, 40`).
    pub shards: String,
    /// Rows of those shards the merge analysed again, each agreeing with the shard's row.
    #[serde(default)]
    pub rows_rechecked: u64,
}

/// The version of archstudy.
pub fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

/// The git commit archstudy was built from, when known.
pub fn git_commit() -> Option<String> {
    let c = env!("ARCHSTUDY_GIT_COMMIT");
    (!c.is_empty()).then(|| c.to_string())
}

/// The rustc that built archstudy.
pub fn rustc_version() -> &'static str {
    env!("ARCHSTUDY_RUSTC_VERSION")
}

/// The current time, RFC 3339 in UTC with milliseconds, as run.json records it.
pub fn now_rfc3339() -> String {
    chrono::Utc::now().to_rfc3339_opts(chrono::SecondsFormat::Millis, true)
}

/// Hex SHA-256 of everything `reader` yields, read a block at a time.
pub fn sha256_reader(mut reader: impl std::io::Read) -> std::io::Result<String> {
    let mut hasher = Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    loop {
        let n = reader.read(&mut buf)?;
        if n == 0 {
            break;
        }
        hasher.update(&buf[..n]);
    }
    Ok(hasher
        .finalize()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect())
}

/// Hex SHA-256 of some bytes.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}
