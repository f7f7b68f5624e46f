//! `archstudy archive` and `archstudy verify` end to end, on a tiny study.

use crate::common::run_study;
use archstudy::provenance::sha256_hex;
use archstudy::store::{self, ColumnData};
use flate2::Compression;
use flate2::read::GzDecoder;
use flate2::write::GzEncoder;
use std::io::{Cursor, Read, Write};
use std::path::{Path, PathBuf};
use std::process::Command;

const TINY: &str = "\
name: tiny
arch:
  shape: circular
  half_angle_deg: 90
  joints: radial
  weight: annular
  voussoirs: continuum
grid:
  k: {from: 1.05, to: 1.5, steps: 6}
  mu: {values: [0.3, 0.4, inf]}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

/// Runs the tiny study under `root/out/tiny` (its figures are nested files, in plots/).
fn tiny_run(root: &Path) -> PathBuf {
    let dir = run_study(root, "tiny.yaml", TINY);
    assert!(dir.join("plots/regime-map.svg").is_file());
    dir
}

/// The files of a run directory, relative, sorted bytewise (the archive's order).
fn run_files(dir: &Path) -> Vec<String> {
    fn walk(base: &Path, dir: &Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(base, &p, out);
            } else {
                out.push(p.strip_prefix(base).unwrap().display().to_string());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

struct Output {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn archstudy(args: &[&str], cwd: &Path) -> Output {
    let o = Command::new(env!("CARGO_BIN_EXE_archstudy"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap();
    let out = Output {
        code: o.status.code(),
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
    };
    assert!(
        !out.stderr.contains("panicked"),
        "archstudy {args:?} panicked:\n{}",
        out.stderr
    );
    out
}

fn archive(run: &Path, to: &Path) {
    let o = archstudy(
        &["archive", run.to_str().unwrap(), "-o", to.to_str().unwrap()],
        run,
    );
    assert_eq!(o.code, Some(0), "{}", o.stderr);
}

fn gunzip(bytes: &[u8]) -> Vec<u8> {
    let mut v = Vec::new();
    GzDecoder::new(bytes).read_to_end(&mut v).unwrap();
    v
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut e = GzEncoder::new(Vec::new(), Compression::default());
    e.write_all(bytes).unwrap();
    e.finish().unwrap()
}

/// The regular-file members of a tar: path, offset of the data, size.
fn members(tar_bytes: &[u8]) -> Vec<(String, u64, u64)> {
    let mut a = tar::Archive::new(Cursor::new(tar_bytes));
    a.entries()
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.header().entry_type() == tar::EntryType::Regular)
        .map(|e| {
            (
                e.path().unwrap().display().to_string(),
                e.raw_file_position(),
                e.size(),
            )
        })
        .collect()
}

#[test]
fn archive_then_verify_passes() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let file = tmp.path().join("tiny.tar.gz");
    archive(&run, &file);
    let o = archstudy(&["verify", file.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(0), "{}\n{}", o.stdout, o.stderr);
    assert!(
        o.stdout.contains(&format!(
            "integrity: all {} files match SHA256SUMS",
            run_files(&run).len()
        )),
        "{}",
        o.stdout
    );
    assert!(
        o.stdout.contains("results.parquet: agrees (18 rows)"),
        "{}",
        o.stdout
    );
    assert!(o.stdout.contains("solve_time_us"), "{}", o.stdout);
    assert!(o.stdout.contains("verdict: OK"), "{}", o.stdout);
    // The run directory itself verifies too.
    let o = archstudy(&["verify", run.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(0), "{}\n{}", o.stdout, o.stderr);
}

#[test]
fn archive_holds_every_file_under_one_named_top_directory() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let o = archstudy(&["archive", run.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(0), "{}", o.stderr);
    let hash = sha256_hex(TINY.as_bytes());
    let top = format!("tiny-{}", &hash[..12]);
    let file = tmp.path().join(format!("{top}.tar.gz"));
    let bytes = std::fs::read(&file).unwrap();
    let names: Vec<String> = members(&gunzip(&bytes)).into_iter().map(|m| m.0).collect();
    let mut expected: Vec<String> = run_files(&run)
        .iter()
        .map(|n| format!("{top}/{n}"))
        .collect();
    expected.push(format!("{top}/SHA256SUMS"));
    for required in [
        "manifest.yaml",
        "results.parquet",
        "run.json",
        "plots/regime-map.svg",
    ] {
        assert!(
            expected.contains(&format!("{top}/{required}")),
            "{required} missing"
        );
    }
    assert_eq!(names, expected);
    // No temporary file is left beside it.
    let leftovers: Vec<_> = std::fs::read_dir(tmp.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn archive_is_byte_identical_when_made_twice() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let a = tmp.path().join("a.tar.gz");
    let b = tmp.path().join("b.tar.gz");
    archive(&run, &a);
    // Touch a file: modification times on disk must not reach the archive.
    let f = run.join("plots/regime-map.svg");
    std::fs::write(&f, std::fs::read(&f).unwrap()).unwrap();
    archive(&run, &b);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}

#[test]
fn flipping_one_byte_of_any_member_fails_with_that_member_named() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let file = tmp.path().join("tiny.tar.gz");
    archive(&run, &file);
    let tar_bytes = gunzip(&std::fs::read(&file).unwrap());
    let data_members: Vec<_> = members(&tar_bytes)
        .into_iter()
        .filter(|m| !m.0.ends_with("SHA256SUMS"))
        .collect();
    assert_eq!(data_members.len(), run_files(&run).len());
    for (path, pos, size) in data_members {
        let mut t = tar_bytes.clone();
        t[(pos + size / 2) as usize] ^= 0x01;
        let bad = tmp.path().join("bad.tar.gz");
        std::fs::write(&bad, gzip(&t)).unwrap();
        let o = archstudy(&["verify", bad.to_str().unwrap()], tmp.path());
        assert_eq!(o.code, Some(1), "{path}: {}", o.stdout);
        let rel = path.split_once('/').unwrap().1;
        assert!(
            o.stdout
                .contains(&format!("corrupt member (checksum differs): {rel}")),
            "{path}: {}",
            o.stdout
        );
        assert!(
            o.stdout.contains("verdict: FAILED (integrity)"),
            "{}",
            o.stdout
        );
    }
}

#[test]
fn a_damaged_member_in_an_unpacked_archive_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let file = tmp.path().join("tiny.tar.gz");
    archive(&run, &file);
    let unpacked = archstudy::archive::unpack(&file).unwrap();
    let dir = unpacked.dir();
    std::fs::write(dir.join("plots/regime-map.svg"), "<svg />\n").unwrap();
    std::fs::remove_file(dir.join("run.json")).unwrap();
    std::fs::write(dir.join("notes.txt"), "added later\n").unwrap();
    let o = archstudy(&["verify", "--no-rerun", dir.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(1), "{}", o.stdout);
    assert!(
        o.stdout
            .contains("corrupt member (checksum differs): plots/regime-map.svg")
    );
    assert!(
        o.stdout
            .contains("missing member (listed, absent): run.json")
    );
    assert!(o.stdout.contains("extra member (not listed): notes.txt"));
}

/// The first row of a float column of results.parquet with a finite, non-zero value.
fn finite_row(results: &Path, column: &str) -> (usize, f64) {
    let t = store::read_table(results).unwrap();
    let ColumnData::Float(v) = &t.column(column).unwrap().data else {
        panic!("{column} is not a float column");
    };
    v.iter()
        .enumerate()
        .find_map(|(i, x)| x.filter(|x| x.is_finite() && *x != 0.0).map(|x| (i, x)))
        .unwrap()
}

#[test]
fn a_changed_result_value_is_reported_as_its_column_and_row() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let results = run.join("results.parquet");
    let (row, value) = finite_row(&results, "thrust_r_min");
    let changed = value + 0.25;
    store::rewrite_f64_value(&results, "thrust_r_min", row, Some(changed)).unwrap();

    let o = archstudy(&["verify", run.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(1), "{}\n{}", o.stdout, o.stderr);
    let line = o
        .stdout
        .lines()
        .find(|l| l.trim_start().starts_with("thrust_r_min "))
        .unwrap_or_else(|| panic!("{}", o.stdout));
    assert!(line.contains("different in 1 of 18 rows"), "{line}");
    assert!(
        o.stdout.contains(&format!(
            "row {row}: stored {changed:?}, recomputed {value:?}"
        )),
        "{}",
        o.stdout
    );
    // Every other column still agrees.
    assert_eq!(o.stdout.matches("different").count(), 1, "{}", o.stdout);
    assert!(o.stdout.contains("verdict: DIFFERENT: 1 of"));

    // Archived, the changed run still fails the same way (checksums are of the changed file).
    let file = tmp.path().join("changed.tar.gz");
    archive(&run, &file);
    let o = archstudy(&["verify", file.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(1));
    assert!(o.stdout.contains(&format!("row {row}: stored {changed:?}")));

    // --no-rerun compares no values, but the table is not the one run.json records.
    let o = archstudy(
        &["verify", "--no-rerun", file.to_str().unwrap()],
        tmp.path(),
    );
    assert_eq!(o.code, Some(1), "{}", o.stdout);
    assert!(o.stdout.contains("re-run: skipped (--no-rerun)"));
    assert!(
        o.stdout
            .contains("tables: DIFFERENT: results.parquet is not the table run.json records"),
        "{}",
        o.stdout
    );
}

#[test]
fn a_difference_within_the_tolerance_is_reported_as_such() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let results = run.join("results.parquet");
    let (row, value) = finite_row(&results, "k");
    store::rewrite_f64_value(&results, "k", row, Some(value * (1.0 + 1e-12))).unwrap();
    // As on another machine: the reports are drawn from the tables as stored.
    let o = archstudy(&["report", run.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(0), "{}", o.stderr);
    // The comparison finds the difference within the tolerance; the verdict still names
    // the table as not the one run.json records.
    let o = archstudy(&["verify", run.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(1), "{}", o.stdout);
    assert!(o.stdout.contains("tables: DIFFERENT: results.parquet"));
    assert!(
        o.stdout.contains("within tolerance (max difference"),
        "{}",
        o.stdout
    );
    // A tighter tolerance turns it into a difference.
    let o = archstudy(
        &["verify", "--tolerance", "0", run.to_str().unwrap()],
        tmp.path(),
    );
    assert_eq!(o.code, Some(1), "{}", o.stdout);
    assert!(o.stdout.contains(&format!("row {row}: stored")));
}

#[test]
fn a_different_version_is_noted_and_still_compared_but_turns_no_check_off() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let path = run.join("run.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["archstudy_version"] = "0.0.1".into();
    v["git_commit"] = "0123456789abcdef".into();
    std::fs::write(&path, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    let o = archstudy(&["verify", run.to_str().unwrap()], tmp.path());
    assert!(
        o.stdout
            .contains("archstudy 0.0.1 (commit 0123456789abcdef)")
    );
    assert!(
        o.stdout
            .contains("the archstudy version differs from this build; comparing anyway")
    );
    assert!(
        o.stdout
            .contains("the commit differs from this build; comparing anyway")
    );
    assert!(o.stdout.contains("results.parquet: agrees"));
    // The reports and the RO-Crate were drawn from the unedited run.json: the edited claim
    // is named, not taken as a reason to skip drawing them again.
    assert_eq!(o.code, Some(1), "{}", o.stdout);
    assert!(
        o.stdout.contains(
            "reports: DIFFERENT: ro-crate-metadata.json is not what this build draws from the \
             stored tables; run.json names another build (archstudy 0.0.1, commit \
             0123456789abcdef)"
        ),
        "{}",
        o.stdout
    );
}

#[test]
fn corrupt_and_truncated_archives_give_a_clear_error() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    let file = tmp.path().join("tiny.tar.gz");
    archive(&run, &file);
    let good = std::fs::read(&file).unwrap();
    let mut flipped = good.clone();
    flipped[good.len() / 2] ^= 0xff;
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("truncated", good[..good.len() / 2].to_vec()),
        ("truncated-trailer", good[..good.len() - 4].to_vec()),
        ("empty", Vec::new()),
        ("not-gzip", b"this is not an archive\n".to_vec()),
        ("flipped", flipped),
        ("plain-tar", gunzip(&good)),
    ];
    for (name, bytes) in cases {
        let bad = tmp.path().join(format!("{name}.tar.gz"));
        std::fs::write(&bad, bytes).unwrap();
        let o = archstudy(&["verify", bad.to_str().unwrap()], tmp.path());
        assert_eq!(o.code, Some(1), "{name}: {}\n{}", o.stdout, o.stderr);
        let said = format!("{}{}", o.stdout, o.stderr);
        assert!(
            said.contains("corrupt or truncated") || said.contains("gzip stream is damaged"),
            "{name}: {said}"
        );
    }
}

#[test]
fn bad_usage_exits_2() {
    let tmp = tempfile::tempdir().unwrap();
    let o = archstudy(&["verify", "no-such-archive.tar.gz"], tmp.path());
    assert_eq!(o.code, Some(2), "{}", o.stderr);
    assert!(o.stderr.contains("no-such-archive.tar.gz"));
    let o = archstudy(&["verify", "--tolerance", "-1", "."], tmp.path());
    assert_eq!(o.code, Some(2), "{}", o.stderr);
    assert!(o.stderr.contains("--tolerance"));
    let o = archstudy(&["archive", "no-such-run"], tmp.path());
    assert_eq!(o.code, Some(2), "{}", o.stderr);
    // A directory that is not a run is a failure that names what is missing.
    let o = archstudy(&["archive", "."], tmp.path());
    assert_eq!(o.code, Some(1), "{}", o.stderr);
    assert!(
        o.stderr
            .contains("manifest.yaml, run.json, results.parquet missing")
    );
}

#[test]
fn a_rewritten_report_or_a_short_table_fails_even_with_recomputed_checksums() {
    let tmp = tempfile::tempdir().unwrap();
    let run = tiny_run(tmp.path());
    // A report edited by hand, archived with fresh checksums: integrity passes, the report
    // is not what the stored tables draw.
    let md = run.join("report.md");
    let text = std::fs::read_to_string(&md).unwrap();
    std::fs::write(&md, text.replacen("stable", "STABLE", 1)).unwrap();
    let file = tmp.path().join("forged.tar.gz");
    archive(&run, &file);
    let o = archstudy(
        &["verify", "--no-rerun", file.to_str().unwrap()],
        tmp.path(),
    );
    assert_eq!(o.code, Some(1), "{}", o.stdout);
    assert!(o.stdout.contains("integrity: all"), "{}", o.stdout);
    assert!(
        o.stdout
            .contains("reports: DIFFERENT: report.md is not what the stored tables draw"),
        "{}",
        o.stdout
    );
    // Drawn again, the run is consistent and passes.
    let o = archstudy(&["report", run.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(0), "{}", o.stderr);
    let o = archstudy(&["verify", "--no-rerun", run.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(0), "{}", o.stdout);
    assert!(
        o.stdout
            .contains("drawn again from the stored tables are identical")
    );

    // A results table cut to fewer rows than the manifest's plan.
    let results = run.join("results.parquet");
    let df = store::read_parquet(&results).unwrap();
    let mut short = df.slice(0, df.height() - 3);
    store::write_parquet(&mut short, &results).unwrap();
    let o = archstudy(&["verify", run.to_str().unwrap()], tmp.path());
    assert_eq!(o.code, Some(1), "{}", o.stdout);
    assert!(
        o.stdout
            .contains("rows: DIFFERENT: results.parquet has 15 rows, the manifest's plan 18 cases"),
        "{}",
        o.stdout
    );
    assert!(!o.stdout.contains("re-run:"), "{}", o.stdout);
}
