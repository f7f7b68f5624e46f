//! The command line as typed (clap), turned into the library's domain values at the edge.

use crate::error::UsageError;
use crate::manifest::SceneOptions;
use crate::model::Friction;
use crate::scene::Scene;
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;
use std::sync::Arc;

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
    /// Join the shard directories of a sharded run (`run --shard I/N`) into one run directory.
    Merge(MergeArgs),
    /// Write Slurm batch scripts for a sharded run: a job array and a merge job after it.
    Slurm(SlurmArgs),
    /// Serve a page on this machine to explore one arch live (and a finished run's cases).
    Explore(ExploreArgs),
}

/// `archstudy explore`.
#[derive(Debug, Args)]
pub struct ExploreArgs {
    /// A run directory: the page opens on its regime map (or λ map, or influence line), and a
    /// click on it shows that case.
    pub run_dir: Option<PathBuf>,
    /// The port to listen on (0: any free port; the address is printed).
    #[arg(long, default_value_t = 8000)]
    pub port: u16,
    /// The address to listen on. Anything but a loopback address lets other machines use the
    /// server, with a warning.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: String,
    /// Open the page in the default browser.
    #[arg(long)]
    pub open: bool,
}

/// `archstudy merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The shard directories `OUT/<name>.shard-I-of-N` of one manifest, every shard once.
    #[arg(value_name = "SHARD_DIR", required_unless_present = "shards_from")]
    pub shards: Vec<PathBuf>,
    /// Takes the shard directories from a directory (its subdirectories named
    /// `<name>.shard-I-of-N`) or a list file (one directory a line), besides any SHARD_DIR.
    #[arg(long, value_name = "DIR|FILE")]
    pub shards_from: Option<PathBuf>,
    /// Directory under which the run directory `<name>/` is written.
    #[arg(long, default_value = "output")]
    pub out: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Rows of each shard analysed again and compared with the shard's (drawn at random in
    /// each merge): a count, or `all`; 0 takes the shards' values on trust once their rows
    /// match the plan.
    #[arg(long, value_name = "N|all", default_value = "64")]
    pub recheck: String,
}

/// `archstudy slurm`.
#[derive(Debug, Args)]
pub struct SlurmArgs {
    /// The study manifest (YAML).
    pub study: PathBuf,
    /// Number of shards: one array task each.
    #[arg(long, value_name = "N")]
    pub shards: u64,
    /// Slurm partition of both jobs.
    #[arg(long, value_name = "P")]
    pub partition: Option<String>,
    /// Time limit of each job, e.g. 02:00:00.
    #[arg(long, value_name = "T")]
    pub time: Option<String>,
    /// Memory of each array task, e.g. 4G (default: the run's estimate for one shard).
    #[arg(long, value_name = "M")]
    pub mem: Option<String>,
    /// Directory of the shards, the merged run and the scripts (`<name>.slurm/`).
    #[arg(long, default_value = "output")]
    pub out: PathBuf,
    /// Submit both jobs with sbatch (default: only print the commands).
    #[arg(long)]
    pub submit: bool,
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
    /// Run only shard I of N (1 ≤ I ≤ N), a contiguous slice of the plan, into
    /// `<out>/<name>.shard-I-of-N/`; join the shards with `archstudy merge`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Column width of the paper figures in plots/ (PDF, SVG, PNG): `single` (3.5 in) or
    /// `double` (7.2 in); replaces the manifest's `figures.width` (default double).
    #[arg(long, value_name = "single|double")]
    pub figure_width: Option<String>,
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
    /// Replace the archive file if it exists (without it, an existing file is refused).
    #[arg(long)]
    pub force: bool,
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
    #[arg(long, value_name = "WHAT", default_value = "state", value_parser = ["state", "thickness", "friction", "thrust", "thresholds", "load-factor", "load_factor"])]
    pub find: String,
    /// Outline: circular, or pointed (two arcs meeting at the crown; needs --eccentricity).
    #[arg(long, value_name = "SHAPE", default_value = "circular", value_parser = ["circular", "pointed"])]
    pub shape: String,
    /// Eccentricity e ∈ [0, 0.9999] of a pointed arch: its arcs' centres lie at ±e·ρ_c on the
    /// springing line (0: semicircle, 0.5: equilateral).
    #[arg(long, value_name = "E", allow_hyphen_values = true)]
    pub eccentricity: Option<f64>,
    /// Joint planes: radial, or vertical through the intrados points (α ≤ 90°).
    #[arg(long, value_name = "PLANES", default_value = "radial", value_parser = ["radial", "vertical"])]
    pub joints: String,
    /// The crown inside one rigid block, the keystone: a pointed arch with radial joints in
    /// the continuum (the wedge between the first joints ±ψ₁), or an odd voussoir count.
    /// A point load may then sit on the keystone.
    #[arg(long)]
    pub keystone: bool,
    /// Load case: self-weight only, or self-weight plus a live load scaled by λ: a horizontal
    /// body force λ·(weight), or a vertical point load λ·W_total on the extrados (--at).
    #[arg(long, value_name = "LOAD", default_value = "self-weight", value_parser = ["self-weight", "self_weight", "horizontal", "point"])]
    pub load: String,
    /// Position of the point load, degrees from the crown (positive to the right).
    #[arg(long = "at", value_name = "DEG", allow_hyphen_values = true)]
    pub at: Option<f64>,
    /// Position of the point load as x/L ∈ [0, 1]: horizontally from the left extrados
    /// springing over the extrados span (0.5 is the crown; α ≤ 90°). Instead of --at.
    #[arg(long = "at-x", value_name = "X/L", allow_hyphen_values = true)]
    pub at_x: Option<f64>,
    /// Spread the point load uniformly over this width of the extrados, as a fraction of
    /// the extrados span measured horizontally (a patch load centred on its position;
    /// α ≤ 90°). Without it the load is concentrated.
    #[arg(long, value_name = "W/L")]
    pub width: Option<f64>,
    /// Load factor λ ≥ 0 of the live load (multiples of the total weight), for every find
    /// but load-factor.
    #[arg(long, value_name = "L", allow_hyphen_values = true)]
    pub lambda: Option<f64>,
    /// Print one JSON object instead of a summary.
    #[arg(long)]
    pub json: bool,
}

fn usage(option: &'static str, value: impl ToString, allowed: impl ToString) -> UsageError {
    UsageError::new(option, value, allowed)
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
    /// The validated scene: the options as [`SceneOptions`], checked there, an error naming
    /// the option as typed (`--t-over-r`).
    pub fn scene(&self) -> Result<Scene, UsageError> {
        let mu = parse_mu(&self.mu)
            .ok_or_else(|| usage("--mu", &self.mu, "μ must be a number ≥ 0 or inf"))?;
        let options = SceneOptions {
            k: self.k,
            t_over_r: self.t_over_r,
            mu: mu.mu(),
            half_angle_deg: self.half_angle,
            weight: self.weight.clone(),
            voussoirs: self.voussoirs,
            find: self.find.clone(),
            shape: self.shape.clone(),
            eccentricity: self.eccentricity,
            joints: self.joints.clone(),
            keystone: self.keystone,
            load: self.load.clone(),
            at_deg: self.at,
            at_x: self.at_x,
            width: self.width,
            lambda: self.lambda,
        };
        options
            .scene()
            .map_err(|e| usage(flag(e.option), e.value, e.allowed))
    }
}

/// The command-line flag of a scene option's keyword.
fn flag(option: &'static str) -> &'static str {
    match option {
        "k" => "--k",
        "t_over_r" => "--t-over-r",
        "mu" => "--mu",
        "half_angle" => "--half-angle",
        "weight" => "--weight",
        "voussoirs" => "--voussoirs",
        "find" => "--find",
        "shape" => "--shape",
        "eccentricity" => "--eccentricity",
        "joints" => "--joints",
        "keystone" => "--keystone",
        "load" => "--load",
        "at" => "--at",
        "at_x" => "--at-x",
        "width" => "--width",
        "lambda" => "--lambda",
        other => other,
    }
}

impl RunArgs {
    /// The validated options of the run, reporting progress to `progress`.
    pub fn options(
        &self,
        progress: Arc<dyn crate::progress::Progress>,
    ) -> Result<crate::runner::RunOptions, UsageError> {
        if let Some(0) = self.jobs {
            return Err(usage(
                "--jobs",
                0,
                "the number of threads must be at least 1",
            ));
        }
        let figure_width = match &self.figure_width {
            None => None,
            Some(w) => Some(crate::manifest::FigureWidth::parse(w).ok_or_else(|| {
                usage(
                    "--figure-width",
                    w,
                    format!(
                        "the column width must be {}",
                        crate::manifest::FigureWidth::NAMES
                    ),
                )
            })?),
        };
        Ok(crate::runner::RunOptions {
            study: self.study.clone(),
            out: self.out.clone(),
            jobs: self.jobs,
            progress,
            command_line: std::env::args().collect(),
            figure_width,
        })
    }
}

impl VerifyArgs {
    /// The validated options.
    pub fn options(&self) -> Result<crate::verify::VerifyOptions, UsageError> {
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            return Err(usage(
                "--tolerance",
                self.tolerance,
                "the tolerance must be a finite number ≥ 0",
            ));
        }
        Ok(crate::verify::VerifyOptions {
            target: self.target.clone(),
            rerun: !self.no_rerun,
            tolerance: self.tolerance,
        })
    }
}
