//! Helpers shared by the integration tests.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The archstudy binary built for these tests.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_archstudy"))
}

/// Runs the binary with arguments.
pub fn archstudy(args: &[&str]) -> Output {
    bin()
        .args(args)
        .output()
        .expect("the archstudy binary runs")
}

/// A fresh, empty scratch directory for one test, removed when the test passes and kept
/// (with its path printed) when it fails, to be looked at.
pub struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.as_os_str()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("scratch directory kept: {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// The prefix of every scratch directory of this test binary, before the process id.
const SCRATCH_PREFIX: &str = "archstudy-test-";

/// `temp/archstudy-test-{pid}-{name}`, emptied. The first call also removes the directories
/// that earlier runs kept (failed tests, killed runs) once their process has ended.
pub fn scratch(name: &str) -> Scratch {
    static SWEPT: std::sync::Once = std::sync::Once::new();
    SWEPT.call_once(sweep_ended_runs);
    let dir = std::env::temp_dir().join(format!("{SCRATCH_PREFIX}{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    Scratch(dir)
}

/// Removes the scratch directories of test processes that no longer run (Linux, where
/// `/proc/{pid}` says whether a process runs; elsewhere nothing is removed).
fn sweep_ended_runs() {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(std::env::temp_dir()) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(pid) = name
            .to_str()
            .and_then(|n| n.strip_prefix(SCRATCH_PREFIX))
            .and_then(|rest| rest.split('-').next())
            .filter(|pid| !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()))
        else {
            continue;
        };
        if !Path::new("/proc").join(pid).exists() {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

/// Writes a manifest into a directory and returns its path.
pub fn manifest(dir: &Path, file: &str, text: &str) -> PathBuf {
    let p = dir.join(file);
    std::fs::write(&p, text).expect("manifest written");
    p
}

/// `archstudy run MANIFEST --out OUT --quiet`.
pub fn run_quiet(manifest: &Path, out: &Path) -> Output {
    archstudy(&[
        "run",
        manifest.to_str().expect("a UTF-8 path"),
        "--out",
        out.to_str().expect("a UTF-8 path"),
        "--quiet",
    ])
}

/// Waits (without a clock) until `ready()` or the child ends, then sends it SIGTERM: its exit
/// code, or `None` when it had already finished successfully (nothing to check).
pub fn terminate_when(child: &mut std::process::Child, ready: impl Fn() -> bool) -> Option<i32> {
    while !ready() && child.try_wait().expect("the child").is_none() {
        std::thread::yield_now();
    }
    Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("kill runs");
    let status = child.wait().expect("the child ends");
    (!status.success()).then(|| status.code().unwrap_or(-1))
}

/// Standard output as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The JSON printed by `archstudy solve ... --json`.
pub fn solve_json(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["solve"];
    all.extend_from_slice(args);
    all.push("--json");
    let o = archstudy(&all);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).expect("valid JSON")
}

/// Reference values of the semicircular arch (radial joints, annular weight, continuum),
/// computed to 12 digits by two independent routes; the paper prints 4–5 of them.
pub mod reference {
    /// Collapse thickness K_c at large μ (paper 1.1136).
    pub const K_C: f64 = 1.113581813339;
    /// t/R_c at K_c.
    pub const T_OVER_R_C: f64 = 0.107478038107;
    /// μ of the rotational/mixed bifurcation = H/W_half at K_c (paper 0.395).
    pub const MU_ROT: f64 = 0.395265252140;
    /// μ_min: below it no equilibrium (paper 0.309).
    pub const MU_MIN: f64 = 0.309215444330;
    /// K of the mixed/sliding bifurcation (paper 1.2205).
    pub const K_BIF: f64 = 1.220507754643;
    /// Haunch hinge at K_c, degrees from the crown.
    pub const HAUNCH_DEG: f64 = 54.48397403;
    /// Inner sliding joint at μ_min, degrees from the crown (paper 29°).
    pub const SLIDING_DEG: f64 = 28.63619468;
    /// Haunch hinge of the minimum-thrust state at K = 1.35, degrees (paper 63°).
    pub const HAUNCH_MIN_THRUST_DEG: f64 = 63.2903024;
}

/// Runs a manifest text as a study into `dir/out/`, on one thread, and returns the run
/// directory.
pub fn run_study(dir: &Path, file: &str, text: &str) -> PathBuf {
    let study = manifest(dir, file, text);
    let opts = archstudy::runner::RunOptions {
        jobs: Some(1),
        command_line: vec!["archstudy".into(), "run".into(), file.into()],
        ..archstudy::runner::RunOptions::new(study, dir.join("out"))
    };
    archstudy::runner::run_study(&opts)
        .expect("the study runs")
        .dir
}

/// A study run in its own scratch directory (see [`run_study`]), which lives as long as the
/// run: it derefs to the run directory.
pub struct StudyRun {
    dir: PathBuf,
    _scratch: Scratch,
}

impl std::ops::Deref for StudyRun {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.dir
    }
}

impl AsRef<Path> for StudyRun {
    fn as_ref(&self) -> &Path {
        &self.dir
    }
}

impl AsRef<std::ffi::OsStr> for StudyRun {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.dir.as_os_str()
    }
}

impl StudyRun {
    /// The run directory `dir`, inside `scratch`.
    pub fn new(scratch: Scratch, dir: PathBuf) -> Self {
        Self {
            dir,
            _scratch: scratch,
        }
    }
}

/// Runs a manifest text as a study in a fresh scratch directory named `name`.
pub fn study_run(name: &str, file: &str, text: &str) -> StudyRun {
    let scratch = scratch(name);
    let dir = run_study(&scratch, file, text);
    StudyRun::new(scratch, dir)
}

/// Asserts that a command was refused as bad usage or input: exit status 2 and a message on
/// standard error that contains every one of `names` (the option, key or file, the value).
pub fn assert_usage_error(o: &Output, names: &[&str]) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "not a usage error: {e}");
    for n in names {
        assert!(e.contains(n), "the message does not name `{n}`: {e}");
    }
}

/// A 2 × 2 state study named `tiny`: a run of a few files.
pub const TINY: &str = "name: tiny
grid:
  k: {values: [1.2, 1.3]}
  mu: {values: [0.4, 0.6]}
";

/// A 400 × 400 state study named `tiny`: long enough to be caught or to fill a small disk.
pub const LARGER: &str = "name: tiny
grid:
  k: {from: 1.05, to: 1.5, steps: 400}
  mu: {from: 0.2, to: 0.8, steps: 400}
";

/// Every hidden leftover (staging, set-aside run, temporary) under `dir`, recursively; links
/// are not followed.
pub fn leftovers(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let n = e.file_name().to_string_lossy().into_owned();
        if n.contains(".partial-") || n.contains(".old-") || n.contains(".tmp-") {
            out.push(e.path().display().to_string());
        }
        if e.file_type().is_ok_and(|t| t.is_dir()) {
            out.extend(leftovers(&e.path()));
        }
    }
    out
}

/// A small pseudo-random generator of numbers in [0, 1): the random scenes of a test are the
/// same on every run.
pub struct Draw(pub u64);

impl Draw {
    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next number in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}
