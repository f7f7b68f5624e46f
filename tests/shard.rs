//! Sharded runs (`run --shard I/N`) and their merge: the merged run holds the same data as
//! an unsharded run, and a merge refuses incomplete or mixed shards.

use crate::common::{archstudy, assert_usage_error, bin, manifest, scratch, stderr};
use archstudy::merge::{MergeOptions, merge};
use archstudy::runner::{RunOptions, run_study};
use archstudy::shard::{Shard, run_shard};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

pub(crate) const STATE: &str = "name: state\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 19}\n  mu: {from: 0.2, to: 0.8, steps: 13}\n";
const THICKNESS: &str = "name: thick\nfind: thickness\ngrid:\n  voussoirs: {values: [6, continuum]}\n  mu: {values: [0.3, 0.6, inf]}\n";
const LOAD_FACTOR: &str = "name: lf\nfind: load_factor\nload_cases:\n  - {name: h, kind: horizontal}\n  - {name: p, kind: point, at_deg: 30}\ngrid:\n  k: {values: [1.2, 1.3, 1.4]}\n  mu: {values: [0.4, 0.7]}\n";

fn opts(study: &Path, out: PathBuf) -> RunOptions {
    RunOptions {
        jobs: Some(1),
        ..RunOptions::new(study, out)
    }
}

/// Runs every shard of `count` (in a scrambled order) and returns their directories.
fn shards(study: &Path, out: &Path, count: u64) -> Vec<PathBuf> {
    let mut order: Vec<u64> = (1..=count).collect();
    order.reverse();
    order.rotate_left(1);
    order
        .into_iter()
        .map(|index| {
            run_shard(&opts(study, out.to_path_buf()), Shard { index, count })
                .expect("the shard runs")
                .dir
        })
        .collect()
}

fn merged(dirs: &[PathBuf], out: PathBuf) -> PathBuf {
    merge(&MergeOptions {
        shards: dirs.to_vec(),
        out,
        jobs: Some(1),
        progress: Arc::new(archstudy::progress::Silent),
        command_line: Vec::new(),
        // Every row analysed again: each study here also checks that a case analysed on its
        // own agrees with the same case analysed among its plan.
        recheck: archstudy::merge::Recheck::All,
    })
    .expect("the shards merge")
    .dir
}

fn files(dir: &Path, ext: &str) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(ext))
        .collect();
    v.sort();
    v
}

/// Every Parquet table of two run directories holds the same columns and values (floats to
/// the bit, NaN included), except the timing columns (`solve_time_us`, and
/// `continuum_solve_time_us` of reference.parquet: wall times differ between any two runs);
/// the figures have the same names.
fn assert_same_run(a: &Path, b: &Path) {
    let tables = files(a, ".parquet");
    assert!(tables.len() >= 4, "{tables:?}");
    assert_eq!(tables, files(b, ".parquet"));
    for t in &tables {
        let read = |d: &Path| {
            let mut table = archstudy::store::read_table(&d.join(t)).unwrap();
            table
                .columns
                .retain(|c| !archstudy::verify::compare::is_timing_column(&c.name));
            format!("{table:?}")
        };
        assert!(read(a) == read(b), "{t} differs between {a:?} and {b:?}");
    }
    assert_eq!(files(&a.join("plots"), ""), files(&b.join("plots"), ""));
    assert!(b.join("report.html").is_file() && b.join("report.md").is_file());
}

fn merged_equals_unsharded(name: &str, text: &str, count: u64) {
    let dir = scratch(name);
    let study = manifest(&dir, "s.yaml", text);
    let whole = run_study(&opts(&study, dir.join("whole"))).unwrap().dir;
    let dirs = shards(&study, &dir.join("shards"), count);
    for d in &dirs {
        assert!(!d.join("plots").exists() && !d.join("report.html").exists());
    }
    let run = merged(&dirs, dir.join("merged"));
    assert_same_run(&whole, &run);
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(run.join("run.json")).unwrap()).unwrap();
    let whole_info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(whole.join("run.json")).unwrap()).unwrap();
    assert_eq!(info["cases"], whole_info["cases"]);
    assert_eq!(info["manifest_sha256"], whole_info["manifest_sha256"]);
}

#[test]
fn a_state_map_in_uneven_shards_merges_into_the_unsharded_run() {
    // 247 cases in 4 shards: 61, 62, 62, 62.
    merged_equals_unsharded("state", STATE, 4);
}

#[test]
fn a_thickness_study_in_more_shards_than_cases_merges_into_the_unsharded_run() {
    // 6 cases in 8 shards: two shards are empty.
    merged_equals_unsharded("thickness", THICKNESS, 8);
}

#[test]
fn a_load_factor_study_merges_into_the_unsharded_run() {
    merged_equals_unsharded("load-factor", LOAD_FACTOR, 3);
}

#[test]
fn a_sampling_study_in_shards_merges_into_the_unsharded_run() {
    // The samples of a shard are computed from their row alone: the same in any slice.
    merged_equals_unsharded(
        "sampled-shards",
        "name: sampled\ngrid:\n  half_angle_deg: {values: [80, 90]}\nuncertain:\n  k: {distribution: uniform, from: 1.08, to: 1.3}\n  mu: {distribution: lognormal, median: 0.45, cov: 0.2}\nsamples: {n: 100, method: random, seed: 4}\nfind: probability\n",
        3,
    );
}

#[test]
fn a_shard_records_its_slice_and_the_manifest() {
    let dir = scratch("shard-json");
    let study = manifest(&dir, "s.yaml", STATE);
    let d = run_shard(&opts(&study, dir.join("out")), Shard { index: 2, count: 4 })
        .unwrap()
        .dir;
    assert_eq!(d, dir.join("out/state.shard-2-of-4"));
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("run.json")).unwrap()).unwrap();
    let mut shard = info["shard"].clone();
    let rss = shard["peak_rss_bytes"].take();
    assert!(rss.as_u64().is_some_and(|b| b > 1 << 20), "{rss}");
    assert_eq!(
        shard,
        serde_json::json!({"index": 2, "count": 4, "plan_cases": 247, "first_case": 61, "cases": 62, "peak_rss_bytes": null})
    );
    assert_eq!(
        info["manifest_sha256"],
        archstudy::provenance::sha256_hex(STATE.as_bytes())
    );
    let t = archstudy::store::read_table(&d.join("results.parquet")).unwrap();
    assert_eq!(t.rows, 62);
    let ids = format!("{:?}", t.column("case_id").unwrap().data);
    assert!(
        ids.contains("\"61\"") && ids.contains("\"122\"") && !ids.contains("\"123\""),
        "{ids}"
    );
}

/// Three shards of the state study, run by the binary.
pub(crate) fn cli_shards(dir: &Path, text: &str, file: &str, count: u64) -> Vec<PathBuf> {
    let study = manifest(dir, file, text);
    let out = dir.join("out");
    (1..=count)
        .map(|i| {
            let o = archstudy(&[
                "run",
                study.to_str().unwrap(),
                "--shard",
                &format!("{i}/{count}"),
                "--out",
                out.to_str().unwrap(),
                "--quiet",
            ]);
            assert!(o.status.success(), "{}", stderr(&o));
            out.join(Shard { index: i, count }.dir_name(&text[6..text.find('\n').unwrap()]))
        })
        .collect()
}

pub(crate) fn merge_cli(dirs: &[&Path], out: &Path) -> std::process::Output {
    merge_cli_with(dirs, out, &[])
}

/// `archstudy merge` of `dirs` into `out` with further options.
pub(crate) fn merge_cli_with(dirs: &[&Path], out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["merge".to_string()];
    args.extend(extra.iter().map(|s| s.to_string()));
    args.extend(dirs.iter().map(|d| d.display().to_string()));
    args.extend(["--out".into(), out.display().to_string(), "--quiet".into()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    archstudy(&args)
}

#[test]
fn a_merge_refuses_a_missing_a_duplicated_and_a_foreign_shard() {
    let dir = scratch("merge-refusals");
    let d = cli_shards(&dir, STATE, "s.yaml", 3);
    let out = dir.join("merged");
    // Missing: shard 2 of 3.
    let o = merge_cli(&[&d[0], &d[2]], &out);
    assert_usage_error(
        &o,
        &["SHARD_DIR", "shard 2 of 3", "state.shard-2-of-3", "missing"],
    );
    // Duplicated: shard 3 twice, once through a copy.
    let copy = dir.join("copy-of-3");
    std::fs::create_dir(&copy).unwrap();
    for f in ["run.json", "manifest.yaml", "results.parquet"] {
        std::fs::copy(d[2].join(f), copy.join(f)).unwrap();
    }
    let o = merge_cli(&[&d[0], &d[1], &d[2], &copy], &out);
    assert_usage_error(
        &o,
        &["SHARD_DIR", "shard 3 of 3 is given twice", "copy-of-3"],
    );
    // Foreign: shard 2 of a study that differs only in its grid.
    let other = scratch("merge-refusals-other");
    let foreign = cli_shards(
        &other,
        &STATE.replace("steps: 13", "steps: 14"),
        "s.yaml",
        3,
    );
    let o = merge_cli(&[&d[0], &foreign[1], &d[2]], &out);
    assert_usage_error(
        &o,
        &[
            "SHARD_DIR",
            "another manifest",
            foreign[1].to_str().unwrap(),
        ],
    );
    // Not a shard: an unsharded run directory.
    let run = crate::common::run_study(&dir, "s.yaml", STATE);
    let o = merge_cli(&[&d[0], &run], &out);
    assert_usage_error(&o, &["SHARD_DIR", "shard"]);
    // Incomplete: results.parquet removed.
    std::fs::remove_file(d[1].join("results.parquet")).unwrap();
    let o = merge_cli(&[&d[0], &d[1], &d[2]], &out);
    assert_usage_error(&o, &["SHARD_DIR", "state.shard-2-of-3", "results.parquet"]);
    assert!(!out.join("state").exists());
    // Nothing half-written was left by the refusals.
    if out.exists() {
        assert_eq!(files(&out, ""), Vec::<String>::new());
    }
}

#[test]
fn a_bad_shard_flag_is_a_usage_error() {
    let dir = scratch("shard-flag");
    let study = manifest(&dir, "s.yaml", STATE);
    for bad in ["0/3", "4/3", "x", "1/0"] {
        let o = archstudy(&[
            "run",
            study.to_str().unwrap(),
            "--shard",
            bad,
            "--out",
            dir.join("o").to_str().unwrap(),
        ]);
        assert_usage_error(&o, &["--shard", bad, "I/N"]);
    }
}

#[test]
fn an_interrupted_shard_leaves_no_files_and_the_merge_names_it() {
    let dir = scratch("shard-interrupt");
    let big = "name: big\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 400}\n  mu: {from: 0.2, to: 0.8, steps: 400}\n";
    let study = manifest(&dir, "big.yaml", big);
    let out = dir.join("out");
    let o = archstudy(&[
        "run",
        study.to_str().unwrap(),
        "--shard",
        "2/2",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut child = bin()
        .args([
            "run",
            study.to_str().unwrap(),
            "--shard",
            "1/2",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ])
        .spawn()
        .unwrap();
    // Interrupted once the staging directory exists.
    let staging = out.join(format!(".big.shard-1-of-2.partial-{}", child.id()));
    let Some(code) = crate::common::terminate_when(&mut child, || staging.exists()) else {
        // The shard finished before the signal: nothing to check.
        return;
    };
    assert_eq!(code, 143);
    assert_eq!(files(&out, ""), vec!["big.shard-2-of-2".to_string()]);
    let o = merge_cli(&[&out.join("big.shard-2-of-2")], &dir.join("merged"));
    assert_usage_error(&o, &["shard 1 of 2", "big.shard-1-of-2", "missing"]);
}

#[test]
fn a_plan_of_a_hundred_million_cases_is_refused_whole_and_runs_in_shards() {
    let dir = scratch("hundred-million");
    let study = manifest(
        &dir,
        "huge.yaml",
        "name: huge\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 10000}\n  mu: {from: 0.2, to: 0.8, steps: 10000}\n",
    );
    let (s, out) = (study.to_str().unwrap(), dir.join("out"));
    // `check` describes the plan without expanding it, and says it runs in shards only.
    let o = archstudy(&["check", s]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    for needle in [
        "axis k: 10000 values from 1.05 to 1.5",
        "axis mu: 10000 values from 0.2 to 0.8",
        "cases: 100000000\nruns in shards only",
        "--shard I/N",
        "GiB of memory",
    ] {
        assert!(text.contains(needle), "{needle}: {text}");
    }
    // An unsharded run is refused up front, naming --shard and the memory it would need.
    let o = archstudy(&["run", s, "--out", out.to_str().unwrap(), "--quiet"]);
    assert_usage_error(
        &o,
        &[
            "huge.yaml",
            "100000000 cases",
            "--shard I/N",
            "N ≥",
            "GiB of memory",
        ],
    );
    assert!(!out.join("huge").exists());
    let o = archstudy(&[
        "run",
        s,
        "--shard",
        "10000/10000",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let d = out.join("huge.shard-10000-of-10000");
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("run.json")).unwrap()).unwrap();
    assert_eq!(info["shard"]["plan_cases"], 100_000_000);
    assert_eq!(info["shard"]["first_case"], 99_990_000);
    assert_eq!(info["cases"]["total"], 10_000);
    // The shard expands its own cases only: far below the 6 GiB of the whole plan.
    let rss = info["shard"]["peak_rss_bytes"].as_u64().unwrap();
    assert!(
        rss < 1 << 30,
        "a shard of 10,000 cases peaked at {rss} bytes"
    );
    let t = archstudy::store::read_table(&d.join("results.parquet")).unwrap();
    assert_eq!(t.rows, 10_000);
}

#[test]
fn slurm_writes_an_array_and_a_merge_that_run_as_the_scheduler_would() {
    let dir = scratch("slurm");
    let study = manifest(&dir, "s.yaml", STATE);
    let out = dir.join("out");
    let o = slurm_cli(
        &study,
        "4",
        &["--partition", "short", "--time", "00:10:00"],
        &out,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let commands = crate::common::stdout(&o);
    assert!(
        commands.contains("sbatch --parsable") && commands.contains("--dependency=afterok:"),
        "{commands}"
    );
    let scripts = out.join("state.slurm");
    let array = std::fs::read_to_string(scripts.join("array.sh")).unwrap();
    for line in [
        "#SBATCH --array=0-3",
        "#SBATCH --partition=short",
        "#SBATCH --time=00:10:00",
        "#SBATCH --mem=",
        "--shard \"$((SLURM_ARRAY_TASK_ID + 1))/4\"",
    ] {
        assert!(array.contains(line), "{line}: {array}");
    }
    let merge_sh = std::fs::read_to_string(scripts.join("merge.sh")).unwrap();
    assert!(
        merge_sh.contains("printf '%s\\n' ./state.shard-*-of-4 > ")
            && merge_sh.contains(" merge --shards-from "),
        "{merge_sh}"
    );
    // Run the scripts as Slurm would: each task with its SLURM_ARRAY_TASK_ID, then the merge.
    run_scripts(&scripts, 4);
    let whole = run_study(&opts(&study, dir.join("whole"))).unwrap().dir;
    assert_same_run(&whole, &out.join("state"));
    // Values that would not survive a #SBATCH line are refused.
    for (flag, bad) in [
        ("--partition", "a b"),
        ("--time", "1\n#SBATCH --x"),
        ("--mem", ""),
    ] {
        let o = slurm_cli(&study, "2", &[flag, bad], &out);
        assert_usage_error(&o, &[flag]);
    }
    let o = slurm_cli(&study, "0", &[], &out);
    assert_usage_error(&o, &["--shards", "0"]);
}

/// `archstudy slurm STUDY --shards N ... --out OUT` with further options before `--out`.
fn slurm_cli(study: &Path, shards: &str, extra: &[&str], out: &Path) -> std::process::Output {
    let (study, out) = (study.to_str().unwrap(), out.to_str().unwrap());
    let mut args = vec!["slurm", study, "--shards", shards];
    args.extend_from_slice(extra);
    args.extend(["--out", out]);
    archstudy(&args)
}

/// Runs the scripts of `slurm` as the scheduler would: each of the `tasks` array tasks with
/// its SLURM_ARRAY_TASK_ID, then the merge; each must succeed.
fn run_scripts(scripts: &std::path::Path, tasks: usize) {
    for task in 0..tasks {
        let o = Command::new("bash")
            .arg(scripts.join("array.sh"))
            .env("SLURM_ARRAY_TASK_ID", task.to_string())
            .output()
            .unwrap();
        assert!(o.status.success(), "task {task}: {}", stderr(&o));
    }
    let o = Command::new("bash")
        .arg(scripts.join("merge.sh"))
        .output()
        .unwrap();
    assert!(o.status.success(), "merge: {}", stderr(&o));
}

/// Every value a Slurm script interpolates is quoted for its reader or refused: an --out with
/// a space and a `%` (quoted in `#SBATCH --output`, `%` doubled), a study name starting with
/// `-`; a newline in --out is refused before anything is written.
#[test]
fn slurm_scripts_quote_or_refuse_every_value() {
    let dir = scratch("slurm-quoting");
    let study = manifest(&dir, "s.yaml", &STATE.replace("name: state", "name: -dash"));
    let out = dir.join("out 50%");
    let o = slurm_cli(&study, "2", &[], &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let scripts = out.join("-dash.slurm");
    let array = std::fs::read_to_string(scripts.join("array.sh")).unwrap();
    let logs = format!("{}/-dash.slurm/logs", out.display()).replace('%', "%%");
    assert!(
        array.contains(&format!("#SBATCH --output=\"{logs}/shard-%a.out\"\n")),
        "{array}"
    );
    run_scripts(&scripts, 2);
    assert!(out.join("-dash/report.html").is_file());
    // A newline would end a comment or a #SBATCH line: refused, nothing written.
    let bad = dir.join("a\nrm -rf x");
    let o = slurm_cli(&study, "2", &[], &bad);
    assert_usage_error(&o, &["--out", "control characters"]);
    assert!(!bad.exists());
}

#[test]
fn a_merge_job_that_cannot_be_submitted_names_the_queued_array() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch("slurm-submit-merge-fails");
    let study = manifest(&dir, "s.yaml", STATE);
    // An sbatch that queues the array (job 4242) and refuses the merge.
    let fake = dir.join("bin");
    std::fs::create_dir_all(&fake).unwrap();
    let sbatch = fake.join("sbatch");
    std::fs::write(
        &sbatch,
        "#!/bin/sh\ncase \"$*\" in *dependency*) echo 'sbatch: error: QOS limit' >&2; exit 1;; esac\necho 4242\n",
    )
    .unwrap();
    std::fs::set_permissions(&sbatch, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!(
        "{}:{}",
        fake.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let o = bin()
        .args([
            "slurm",
            study.to_str().unwrap(),
            "--shards",
            "2",
            "--out",
            dir.join("out").to_str().unwrap(),
            "--submit",
        ])
        .env("PATH", path)
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = stderr(&o);
    for want in [
        "array job 4242 is queued",
        "sbatch --dependency=afterok:4242",
        "scancel 4242",
        "QOS limit",
    ] {
        assert!(err.contains(want), "{want}: {err}");
    }
}
