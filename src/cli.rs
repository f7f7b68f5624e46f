//! The command line: clap arguments as typed, turned into domain values at the edge.

use crate::model::{Arch, Discretisation, Friction, ModelError, WeightModel, k_from_t_over_r};
use crate::scene::{Find, Scene};
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

/// Limit analysis of masonry arches with finite Coulomb friction.
#[derive(Debug, Parser)]
#[command(name = "archstudy", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Analyse one scene and print the answer.
    Solve(SolveArgs),
    /// Run a study manifest: every grid point, Parquet results, boundaries, figures, reports.
    Run(RunArgs),
    /// Validate a study manifest and print its plan without running it.
    Check(CheckArgs),
    /// Re-render the figures and both reports of a run directory from its stored files.
    Report(ReportArgs),
    /// Pack a run directory into one .tar.gz with SHA256SUMS, for deposit with a paper.
    Archive(ArchiveArgs),
    /// Check an archive or run directory: checksums, then re-run and compare every result.
    Verify(VerifyArgs),
}

/// `archstudy report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// The run directory (the `<out>/<name>/` that `archstudy run` wrote).
    #[arg(value_name = "RUN_DIR")]
    pub run_dir: PathBuf,
}

/// `archstudy run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The study manifest (YAML).
    pub study: PathBuf,
    /// Directory under which the run directory `<name>/` is written.
    #[arg(long, default_value = "output")]
    pub out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// `archstudy check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The study manifest (YAML).
    pub study: PathBuf,
}

/// `archstudy archive`.
#[derive(Debug, Args)]
pub struct ArchiveArgs {
    /// The run directory written by `archstudy run`.
    #[arg(value_name = "RUN_DIR")]
    pub run_dir: PathBuf,
    /// The archive to write (default: `<name>-<first 12 hex of the manifest SHA-256>.tar.gz`
    /// in the current directory; in FILE when it is a directory).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: Option<PathBuf>,
}

/// `archstudy verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// An archive made by `archstudy archive`, or a run directory.
    #[arg(value_name = "ARCHIVE|RUN_DIR")]
    pub target: PathBuf,
    /// Check integrity only; do not re-run the manifest.
    #[arg(long)]
    pub no_rerun: bool,
    /// Tolerance T of float columns: |stored - recomputed| <= T * (1 + max(|stored|, |recomputed|)).
    #[arg(long, value_name = "T", default_value_t = crate::verify::compare::DEFAULT_TOLERANCE, allow_hyphen_values = true)]
    pub tolerance: f64,
}

/// `archstudy solve` as typed.
#[derive(Debug, Args)]
pub struct SolveArgs {
    /// Thickness ratio K = R/r (> 1). Default 1.35 when neither --k nor --t-over-r is given.
    #[arg(long = "k", value_name = "K", allow_hyphen_values = true)]
    pub k: Option<f64>,
    /// Thickness over centreline radius t/R_c, in (0, 2), instead of --k.
    #[arg(long = "t-over-r", value_name = "X", allow_hyphen_values = true)]
    pub t_over_r: Option<f64>,
    /// Friction coefficient μ ≥ 0, or `inf`.
    #[arg(
        long,
        value_name = "MU",
        default_value = "inf",
        allow_hyphen_values = true
    )]
    pub mu: String,
    /// Half-embrace angle α in degrees, in (0, 180).
    #[arg(
        long = "half-angle",
        value_name = "DEG",
        default_value_t = 90.0,
        allow_hyphen_values = true
    )]
    pub half_angle: f64,
    /// Weight model.
    #[arg(long, value_name = "MODEL", default_value = "annular", value_parser = ["annular", "centreline"])]
    pub weight: String,
    /// Number of voussoirs N ≥ 1 (omit for the continuum).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub voussoirs: Option<i64>,
    /// What to compute.
    #[arg(long, value_name = "WHAT", default_value = "state", value_parser = ["state", "thickness", "friction", "thrust", "thresholds"])]
    pub find: String,
    /// Print one JSON object instead of a summary.
    #[arg(long)]
    pub json: bool,
}

/// A bad option value: names the option, the value and what is allowed.
#[derive(Debug, thiserror::Error)]
#[error("invalid value '{value}' for '{option}': {allowed}")]
pub struct UsageError {
    /// The option as typed, e.g. `--k`.
    pub option: &'static str,
    /// The value given.
    pub value: String,
    /// What is allowed.
    pub allowed: String,
}

fn usage(option: &'static str, value: impl ToString, allowed: impl ToString) -> UsageError {
    UsageError {
        option,
        value: value.to_string(),
        allowed: allowed.to_string(),
    }
}

/// Parses a friction coefficient: a number ≥ 0 or `inf`.
pub fn parse_mu(s: &str) -> Option<Friction> {
    let t = s.trim();
    if matches!(t, "inf" | "infinity" | "Inf" | "INF" | "∞") {
        return Some(Friction::INFINITE);
    }
    t.parse::<f64>().ok().and_then(Friction::new)
}

impl SolveArgs {
    /// The validated scene.
    pub fn scene(&self) -> Result<Scene, UsageError> {
        let find = Find::parse(&self.find).ok_or_else(|| {
            usage(
                "--find",
                &self.find,
                "one of state, thickness, friction, thrust, thresholds",
            )
        })?;
        let k = match (self.k, self.t_over_r) {
            (Some(_), Some(_)) => {
                return Err(usage(
                    "--t-over-r",
                    self.t_over_r.unwrap_or_default(),
                    "give either --k or --t-over-r, not both",
                ));
            }
            (Some(k), None) => {
                if !(k > 1.0 && k.is_finite()) {
                    return Err(usage(
                        "--k",
                        k,
                        "K = R/r must be a finite number greater than 1",
                    ));
                }
                k
            }
            (None, Some(x)) => {
                if !(x > 0.0 && x < 2.0) {
                    return Err(usage("--t-over-r", x, "t/R_c must be a number in (0, 2)"));
                }
                k_from_t_over_r(x)
            }
            (None, None) => 1.35,
        };
        let friction = parse_mu(&self.mu)
            .ok_or_else(|| usage("--mu", &self.mu, "μ must be a number ≥ 0 or inf"))?;
        let weight = WeightModel::parse(&self.weight)
            .ok_or_else(|| usage("--weight", &self.weight, "annular or centreline"))?;
        let joints = match self.voussoirs {
            None => Discretisation::Continuum,
            Some(n) if n >= 1 && n <= i64::from(u32::MAX) => Discretisation::Voussoirs(n as u32),
            Some(n) => return Err(usage("--voussoirs", n, "N must be an integer ≥ 1")),
        };
        let arch = Arch::new(k, self.half_angle, weight, joints).map_err(|e| match e {
            ModelError::HalfAngle(a) => usage(
                "--half-angle",
                a,
                "α must lie strictly between 0 and 180 degrees",
            ),
            other => usage("--k", k, other.to_string()),
        })?;
        Ok(Scene {
            arch,
            friction,
            find,
        })
    }
}
