//! The command line as typed (clap), turned into the library's domain values at the edge.

use crate::analysis::forms::FormError;
use crate::error::UsageError;
use crate::manifest::{MAX_GENERAL_VOUSSOIRS, MAX_K};
use crate::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, ModelError, Shape,
    WeightModel, k_from_t_over_r,
};
use crate::scene::{Find, Scene};
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
    /// Eccentricity e ∈ [0, 1) of a pointed arch: its arcs' centres lie at ±e·ρ_c on the
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
    /// The validated scene.
    pub fn scene(&self) -> Result<Scene, UsageError> {
        let find = Find::parse(&self.find).ok_or_else(|| {
            usage(
                "--find",
                &self.find,
                "one of state, thickness, friction, thrust, thresholds, load-factor",
            )
        })?;
        let k = self.k()?;
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
            other if self.t_over_r.is_some() => usage(
                "--t-over-r",
                self.t_over_r.unwrap_or_default(),
                other.to_string(),
            ),
            other => usage("--k", k, other.to_string()),
        })?;
        let form = self.form()?;
        let load = self.load()?;
        if matches!(find, Find::Thrust | Find::Thresholds)
            && !(load == Load::SelfWeight && form.is_circular_radial())
        {
            return Err(usage(
                "--find",
                &self.find,
                format!(
                    "{find} is defined for self-weight on a circular arch with radial joints only"
                ),
            ));
        }
        let lambda = self.lambda(find, load)?;
        if find == Find::LoadFactor && load == Load::SelfWeight {
            return Err(usage(
                "--find",
                &self.find,
                "load-factor needs a live load: give --load horizontal or --load point --at DEG",
            ));
        }
        Self::check_general_voussoirs(joints, load, &form)?;
        let scene = Scene {
            arch,
            friction,
            find,
            form,
            load,
            lambda,
        };
        scene.check().map_err(|e| match e {
            FormError::Eccentricity(v) => usage("--eccentricity", v, e.to_string()),
            FormError::PointedTooThick { k, .. } => usage("--k", k, e.to_string()),
            FormError::VerticalBeyondQuadrant(a) => usage("--half-angle", a, e.to_string()),
            FormError::LoadOutside { at_deg, .. }
            | FormError::LoadInsideKeystone { at_deg, .. }
            | FormError::LoadOffExtrados { at_deg, .. } => usage("--at", at_deg, e.to_string()),
            FormError::NoKeystone(_) => usage("--keystone", "on", e.to_string()),
            FormError::LoadOffSpan { at_x, .. } | FormError::XInsideKeystone { at_x, .. } => {
                usage("--at-x", at_x, e.to_string())
            }
        })?;
        Ok(scene)
    }

    /// K from --k or --t-over-r, within (1, MAX_K].
    fn k(&self) -> Result<f64, UsageError> {
        Ok(match (self.k, self.t_over_r) {
            (Some(_), Some(_)) => {
                return Err(usage(
                    "--t-over-r",
                    self.t_over_r.unwrap_or_default(),
                    "give either --k or --t-over-r, not both",
                ));
            }
            (Some(k), None) => {
                if !(k > 1.0 && k <= MAX_K) {
                    return Err(usage(
                        "--k",
                        crate::manifest::short_number(k),
                        format!(
                            "K = R/r must be a number greater than 1 and at most {MAX_K}: beyond \
                             it the solver's answers are not reliable and no masonry arch is \
                             that thick (README, Limits)"
                        ),
                    ));
                }
                k
            }
            (None, Some(x)) => {
                let x_max = 2.0 * (MAX_K - 1.0) / (MAX_K + 1.0);
                if !(x > 0.0 && x <= x_max && k_from_t_over_r(x) > 1.0) {
                    return Err(usage(
                        "--t-over-r",
                        crate::manifest::short_number(x),
                        format!(
                            "t/R_c must be a number in (0, {x_max:.4}] (K = R/r in (1, {MAX_K}]), \
                             large enough that K differs from 1 (t/R_c ≥ 1e-15)"
                        ),
                    ));
                }
                k_from_t_over_r(x)
            }
            (None, None) => 1.35,
        })
    }

    /// The general solver's voussoir limit (live loads, pointed arches, vertical joints).
    fn check_general_voussoirs(
        joints: Discretisation,
        load: Load,
        form: &ArchForm,
    ) -> Result<(), UsageError> {
        if let Discretisation::Voussoirs(n) = joints
            && n > MAX_GENERAL_VOUSSOIRS
            && (load.is_live() || !form.is_circular_radial())
        {
            Err(usage(
                "--voussoirs",
                n,
                format!(
                    "a live load, a pointed outline or vertical joints are analysed by the \
                     general solver, which answers promptly up to {MAX_GENERAL_VOUSSOIRS} \
                     voussoirs: use at most {MAX_GENERAL_VOUSSOIRS}, or omit --voussoirs for \
                     the continuum"
                ),
            ))
        } else {
            Ok(())
        }
    }

    fn form(&self) -> Result<ArchForm, UsageError> {
        let joints = JointOrientation::parse(&self.joints)
            .ok_or_else(|| usage("--joints", &self.joints, "radial or vertical"))?;
        let shape = match (self.shape.as_str(), self.eccentricity) {
            ("circular", None) => Shape::Circular,
            ("circular", Some(e)) => {
                return Err(usage(
                    "--eccentricity",
                    e,
                    "only a pointed arch has an eccentricity: add --shape pointed",
                ));
            }
            ("pointed", Some(e)) if (0.0..1.0).contains(&e) => Shape::Pointed { eccentricity: e },
            ("pointed", Some(e)) => {
                return Err(usage("--eccentricity", e, "e must lie in [0, 1)"));
            }
            ("pointed", None) => {
                return Err(usage(
                    "--shape",
                    "pointed",
                    "a pointed arch needs --eccentricity E (0 ≤ E < 1; 0.5 is the equilateral arch)",
                ));
            }
            (other, _) => return Err(usage("--shape", other, "circular or pointed")),
        };
        Ok(ArchForm {
            shape,
            joints,
            keystone: self.keystone,
        })
    }

    fn load(&self) -> Result<Load, UsageError> {
        if let Some(x) = self.at_x {
            return match (self.load.as_str(), self.at) {
                (_, Some(a)) => Err(usage(
                    "--at",
                    a,
                    "give the position once: --at DEG or --at-x X/L, not both",
                )),
                ("point", None) if (0.0..=1.0).contains(&x) => Ok(Load::PointX { at_x: x }),
                ("point", None) => Err(usage(
                    "--at-x",
                    x,
                    "x/L must lie in [0, 1] (0 and 1 the extrados springings, 0.5 the crown)",
                )),
                (_, None) => Err(usage(
                    "--at-x",
                    x,
                    "--at-x is the position of a point load: add --load point",
                )),
            };
        }
        let load = match (self.load.as_str(), self.at) {
            ("self-weight" | "self_weight", None) => Load::SelfWeight,
            ("horizontal", None) => Load::Horizontal,
            ("point", Some(a)) if a.is_finite() => Load::Point { at_deg: a },
            ("point", Some(a)) => return Err(usage("--at", a, "a finite angle in degrees")),
            ("point", None) => {
                return Err(usage(
                    "--load",
                    "point",
                    "a point load needs its position: add --at DEG (degrees from the crown) or --at-x X/L",
                ));
            }
            (_, Some(a)) => {
                return Err(usage(
                    "--at",
                    a,
                    "--at is the position of a point load: add --load point",
                ));
            }
            (other, None) => {
                return Err(usage("--load", other, "self-weight, horizontal or point"));
            }
        };
        Ok(load)
    }

    fn lambda(&self, find: Find, load: Load) -> Result<f64, UsageError> {
        match (self.lambda, load.is_live(), find) {
            (None, false, _) | (None, true, Find::LoadFactor) => Ok(0.0),
            (Some(l), _, Find::LoadFactor) => Err(usage(
                "--lambda",
                l,
                "load-factor finds λ itself: remove --lambda",
            )),
            (Some(l), false, _) => Err(usage(
                "--lambda",
                l,
                "self-weight has no live part to scale: add --load horizontal or --load point",
            )),
            (Some(l), true, _) if l >= 0.0 && l.is_finite() => Ok(l),
            (Some(l), true, _) => Err(usage("--lambda", l, "λ must be a finite number ≥ 0")),
            (None, true, _) => Err(usage(
                "--load",
                &self.load,
                format!(
                    "a live load needs its load factor for --find {}: add --lambda L (or use --find load-factor)",
                    find
                ),
            )),
        }
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
