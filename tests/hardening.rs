//! The attack catalogue: bad input, full disks, interruptions, links out of the
//! run directory. Each test asserts the refusal (exit 2, the key or option named) or that the
//! earlier run is intact and no temporary is left.

use crate::common::{
    LARGER, TINY, archstudy, assert_usage_error, bin, leftovers, manifest, run_quiet, scratch,
    stderr,
};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::process::Command;

fn corpus() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "yaml"))
        .collect();
    v.sort();
    v
}

/// Runs the binary under `sh -c` with a shell limit such as `ulimit -v 4000000`.
fn limited(limit: &str, args: &[&str]) -> std::process::Output {
    let exe = env!("CARGO_BIN_EXE_archstudy");
    Command::new("sh")
        .arg("-c")
        .arg(format!("{limit}; exec \"$0\" \"$@\""))
        .arg(exe)
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn every_manifest_of_the_corpus_is_refused_naming_its_key() {
    let out = scratch("corpus-runs");
    let o = out.to_str().unwrap();
    for m in corpus() {
        let p = m.to_str().unwrap();
        // The 5001² grid is beyond the unsharded cap; limit memory all the same, so that a
        // regression that runs it fails quickly.
        let limit = if p.ends_with("grid-5001-squared.yaml") {
            "ulimit -v 4000000"
        } else {
            "true"
        };
        let o_run = limited(limit, &["run", p, "--out", o, "--quiet"]);
        let o = limited(limit, &["check", p]);
        assert_eq!(o_run.status.code(), Some(2), "{p}: {}", stderr(&o_run));
        if p.ends_with("grid-5001-squared.yaml") {
            // A valid manifest too large for one run: `check` describes it and says, as
            // `run` refuses, that it runs in shards only.
            assert_usage_error(&o_run, &[p, "key `grid`", "--shard", "GiB of memory"]);
            let s = String::from_utf8_lossy(&o.stdout);
            assert!(o.status.success(), "{p}: {}", stderr(&o));
            let why = stderr(&o_run);
            let why = why.split("25010001 cases").nth(1).unwrap().trim();
            assert!(s.contains("cases: 25010001\nruns in shards only"), "{s}");
            assert!(s.contains(why), "{p}: check says {s}, run says {why}");
            continue;
        }
        let e = stderr(&o);
        assert_usage_error(&o, &[p, "key `"]);
        // `check` refuses what `run` would, with the same message, before anything is run.
        assert_eq!(stderr(&o_run), e, "{p}");
        for parser in [
            "invalid i64",
            "DuplicateKeyPolicy",
            "budget breached",
            "Nodes {",
        ] {
            assert!(!e.contains(parser), "{p}: parser wording: {e}");
        }
    }
    assert_eq!(
        std::fs::read_dir(&out).unwrap().count(),
        0,
        "a refused run wrote"
    );
}

#[test]
fn a_device_or_an_oversized_manifest_is_refused_unread() {
    let o = archstudy(&["check", "/dev/zero"]);
    assert_usage_error(&o, &["/dev/zero", "not a regular file"]);
    let dir = scratch("oversized");
    let big = manifest(&dir, "big.yaml", &"#".repeat(2 << 20));
    let o = archstudy(&["check", big.to_str().unwrap()]);
    assert_usage_error(&o, &["big.yaml", "1 MiB"]);
}

#[test]
fn solve_refuses_what_it_cannot_answer_naming_the_option() {
    assert_usage_error(
        &archstudy(&["solve", "--t-over-r", "1e-300"]),
        &["--t-over-r"],
    );
    assert_usage_error(
        &archstudy(&["solve", "--k", "1e300", "--mu", "0.4"]),
        &["--k", "1e300", "at most 100"],
    );
    assert_usage_error(
        &archstudy(&[
            "solve",
            "--load",
            "horizontal",
            "--find",
            "load-factor",
            "--voussoirs",
            "1000000",
        ]),
        &["--voussoirs", "100000"],
    );
}

#[test]
fn a_plan_too_big_for_the_memory_limit_exits_2_naming_the_memory() {
    let dir = scratch("ulimit-v");
    let m = manifest(
        &dir,
        "big.yaml",
        "name: big\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 2000}\n  mu: {from: 0.2, to: 0.8, steps: 2000}\n",
    );
    let out = dir.join("out");
    let o = limited(
        // 4,000,000 cases need about 1 GiB (0.8 GiB besides 64 bytes a case): refused in 0.76.
        "ulimit -v 800000",
        &[
            "run",
            m.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ],
    );
    assert_usage_error(&o, &["grid", "GiB of memory", "ulimit -v"]);
    assert!(leftovers(&dir).is_empty());
}

#[test]
fn run_never_replaces_a_users_directory_of_the_same_name() {
    let dir = scratch("user-dir");
    let m = manifest(&dir, "tiny.yaml", TINY);
    let out = dir.join("out");
    std::fs::create_dir_all(out.join("tiny")).unwrap();
    std::fs::write(out.join("tiny/thesis.tex"), "mine").unwrap();
    let o = run_quiet(&m, &out);
    assert_usage_error(&o, &["--out", "not a run directory"]);
    assert_eq!(
        std::fs::read_to_string(out.join("tiny/thesis.tex")).unwrap(),
        "mine"
    );
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
}

fn tiny_run(dir: &Path) -> PathBuf {
    let m = manifest(dir, "tiny.yaml", TINY);
    let out = dir.join("out");
    let o = run_quiet(&m, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    out.join("tiny")
}

#[test]
fn archive_does_not_overwrite_a_file_without_force() {
    let dir = scratch("archive-force");
    let run = tiny_run(&dir);
    let target = dir.join("precious.tar.gz");
    std::fs::write(&target, "keep").unwrap();
    let t = target.to_str().unwrap();
    let o = archstudy(&["archive", run.to_str().unwrap(), "-o", t]);
    assert_usage_error(&o, &["--output", "--force"]);
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
    let o = archstudy(&["archive", run.to_str().unwrap(), "-o", t, "--force"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_ne!(std::fs::read(&target).unwrap(), b"keep");
}

#[test]
fn report_does_not_write_through_a_symlink_out_of_the_run() {
    let dir = scratch("symlink");
    let run = tiny_run(&dir);
    let outside = dir.join("outside");
    std::fs::create_dir(&outside).unwrap();
    std::fs::remove_dir_all(run.join("plots")).unwrap();
    std::os::unix::fs::symlink(&outside, run.join("plots")).unwrap();
    let o = archstudy(&["report", run.to_str().unwrap()]);
    assert_usage_error(&o, &["plots", "symbolic link"]);
    assert_eq!(std::fs::read_dir(&outside).unwrap().count(), 0);
}

#[test]
fn a_full_disk_during_run_keeps_the_earlier_run_and_leaves_no_temporary() {
    let dir = scratch("ulimit-f");
    let run = tiny_run(&dir);
    let before = std::fs::read(run.join("results.parquet")).unwrap();
    let m = dir.join("tiny.yaml");
    let out = dir.join("out");
    // 20 blocks of 512 bytes: the figures cannot be written (SIGXFSZ or EFBIG).
    let o = limited(
        "ulimit -f 20",
        &[
            "run",
            m.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ],
    );
    assert!(!o.status.success(), "the run fitted in 10 kB");
    assert_eq!(std::fs::read(run.join("results.parquet")).unwrap(), before);
    // A process killed by the limit cannot clean up; the next run sweeps what it left.
    let o = run_quiet(&m, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
    // report and archive under the same limit leave nothing either once rerun.
    let _ = limited("ulimit -f 20", &["report", run.to_str().unwrap()]);
    let a = dir.join("a.tar.gz");
    let _ = limited(
        "ulimit -f 20",
        &["archive", run.to_str().unwrap(), "-o", a.to_str().unwrap()],
    );
    let o = archstudy(&[
        "archive",
        run.to_str().unwrap(),
        "-o",
        a.to_str().unwrap(),
        "--force",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = archstudy(&["verify", a.to_str().unwrap(), "--no-rerun"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!crate::common::stdout(&o).contains(".tmp-"));
}

#[test]
fn sigint_and_sigterm_mid_run_remove_the_staging_directory() {
    let dir = scratch("sigint");
    let run = tiny_run(&dir);
    let before = std::fs::read(run.join("results.parquet")).unwrap();
    let m = manifest(
        &dir,
        "tiny.yaml",
        "name: tiny\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 400}\n  mu: {from: 0.2, to: 0.8, steps: 400}\n",
    );
    let out = dir.join("out");
    let mut interrupted = 0;
    for (sig, code) in [("INT", 130), ("TERM", 143)] {
        let mut child = bin()
            .args([
                "run",
                m.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--quiet",
            ])
            .spawn()
            .unwrap();
        // Wait (without a clock) until the staging directory exists, then interrupt.
        let staging = out.join(format!(".tiny.partial-{}", child.id()));
        while !staging.exists() {
            if child.try_wait().unwrap().is_some() {
                break;
            }
            std::thread::yield_now();
        }
        Command::new("kill")
            .args([format!("-{sig}"), child.id().to_string()])
            .status()
            .unwrap();
        let status = child.wait().unwrap();
        if status.success() {
            // The run finished before the signal; nothing to check for this signal.
            continue;
        }
        interrupted += 1;
        assert_eq!(status.code(), Some(code), "SIG{sig}");
        assert!(
            leftovers(&dir).is_empty(),
            "SIG{sig}: {:?}",
            leftovers(&dir)
        );
        assert_eq!(std::fs::read(run.join("results.parquet")).unwrap(), before);
    }
    assert!(interrupted > 0, "both runs finished before their signal");
}

prop_compose! {
    /// A corpus manifest with a few bytes replaced, inserted or removed.
    fn mutated()(seed in 0usize..64, edits in prop::collection::vec((any::<u16>(), any::<u8>(), 0u8..3), 1..6)) -> String {
        let files = corpus();
        let mut extra = vec![TINY.to_string(), std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/seed.yaml")).unwrap()];
        extra.extend(files.iter().filter(|f| std::fs::metadata(f).unwrap().len() < 10_000).map(|f| std::fs::read_to_string(f).unwrap()));
        let mut bytes = extra[seed % extra.len()].clone().into_bytes();
        for (at, b, op) in edits {
            let i = usize::from(at) % (bytes.len() + 1);
            match op {
                0 if i < bytes.len() => bytes[i] = b,
                1 => bytes.insert(i, b),
                _ if i < bytes.len() => { bytes.remove(i); }
                _ => {}
            }
        }
        String::from_utf8_lossy(&bytes).into_owned()
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// Manifest text never panics the parser: it is a plan, or an error naming the file and
    /// a key or position, in the manifest's words.
    #[test]
    fn mutated_manifests_parse_or_are_refused_by_key(text in mutated()) {
        let path = Path::new("fuzz.yaml");
        match archstudy::manifest::parse(&text, path) {
            Ok(m) => prop_assert!(archstudy::plan::case_count(&m) > 0),
            Err(e) => {
                prop_assert!(e.key.is_some() || e.position.is_some(), "{e}");
                let s = e.to_string();
                prop_assert!(s.starts_with("fuzz.yaml"), "{s}");
                prop_assert!(!s.contains("invalid i64") && !s.contains("DuplicateKeyPolicy"), "{s}");
            }
        }
    }

    /// `solve` arguments: a scene, or a usage error naming an option; never a panic.
    #[test]
    fn solve_arguments_give_a_scene_or_name_an_option(
        k in prop_oneof![Just(None), (-1e300f64..1e300).prop_map(Some), (0.9f64..200.0).prop_map(Some)],
        t in prop_oneof![Just(None), (-1.0f64..3.0).prop_map(Some), Just(Some(1e-300))],
        n in prop_oneof![Just(None), (-5i64..2_000_000).prop_map(Some)],
        load in prop_oneof![Just("self-weight"), Just("horizontal"), Just("point")],
        find in prop_oneof![Just("state"), Just("load-factor"), Just("friction"), Just("thickness")],
    ) {
        use clap::Parser;
        let mut args = vec!["archstudy".to_string(), "solve".into(), "--load".into(), load.into(), "--find".into(), find.into()];
        if let Some(k) = k { args.extend(["--k".into(), k.to_string()]); }
        if let Some(t) = t { args.extend(["--t-over-r".into(), t.to_string()]); }
        if let Some(n) = n { args.extend(["--voussoirs".into(), n.to_string()]); }
        let Ok(cli) = archstudy::app::Cli::try_parse_from(&args) else { return Ok(()); };
        let archstudy::app::Command::Solve(s) = cli.command else { unreachable!() };
        if let Err(e) = s.scene() {
            prop_assert!(e.option.starts_with("--"), "{e}");
        }
    }
}

/// Spawns archstudy with `args` and kills it with SIGKILL (which no handler sees) as soon as
/// `leftover` exists; false when the command finished first.
fn killed_when_it_writes(args: &[&str], leftover: impl Fn(u32) -> PathBuf) -> bool {
    let mut child = bin().args(args).spawn().unwrap();
    let path = leftover(child.id());
    while !path.exists() {
        if child.try_wait().unwrap().is_some() {
            return false;
        }
        std::thread::yield_now();
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        path.exists(),
        "{} vanished with its process",
        path.display()
    );
    true
}

#[test]
fn kill_9_mid_run_keeps_the_earlier_run_and_the_next_run_sweeps_the_staging() {
    let dir = scratch("kill9-run");
    let run = tiny_run(&dir);
    let before = std::fs::read(run.join("results.parquet")).unwrap();
    let out = dir.join("out");
    let larger = manifest(&dir, "larger.yaml", LARGER);
    let args = [
        "run",
        larger.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    let killed = (0..5)
        .any(|_| killed_when_it_writes(&args, |pid| out.join(format!(".tiny.partial-{pid}"))));
    assert!(killed, "every run finished before it could be killed");
    // The killed run could not clean up: its staging directory is the only leftover (with,
    // when the kill came mid-write, a temporary file inside it).
    let left = leftovers(&dir);
    let outermost: Vec<&String> = (left.iter())
        .filter(|p| !left.iter().any(|q| p.starts_with(&format!("{q}/"))))
        .collect();
    assert_eq!(outermost.len(), 1, "{left:?}");
    assert!(outermost[0].contains(".tiny.partial-"), "{left:?}");
    assert!(std::fs::read(run.join("results.parquet")).unwrap() == before);
    let again = manifest(&dir, "tiny.yaml", TINY);
    let o = run_quiet(&again, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
    assert!(run.join("run.json").is_file());
}

#[test]
fn kill_9_mid_archive_leaves_no_archive_and_the_next_archive_sweeps_its_temporary() {
    let dir = scratch("kill9-archive");
    let larger = manifest(&dir, "larger.yaml", LARGER);
    let out = dir.join("out");
    let o = run_quiet(&larger, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let run = out.join("tiny");
    let target = dir.join("run.tar.gz");
    let args = [
        "archive",
        run.to_str().unwrap(),
        "-o",
        target.to_str().unwrap(),
    ];
    let killed = (0..5).any(|_| {
        let _ = std::fs::remove_file(&target);
        killed_when_it_writes(&args, |pid| dir.join(format!(".run.tar.gz.tmp-{pid}")))
    });
    assert!(killed, "every archive finished before it could be killed");
    assert!(
        !target.exists(),
        "a killed archive must not leave a complete-looking file"
    );
    assert_eq!(leftovers(&dir).len(), 1, "{:?}", leftovers(&dir));
    let o = archstudy(&[
        "archive",
        run.to_str().unwrap(),
        "-o",
        target.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
    let o = archstudy(&["verify", target.to_str().unwrap(), "--no-rerun"]);
    assert!(o.status.success(), "{}", crate::common::stdout(&o));
}

#[test]
fn an_out_directory_that_is_a_link_is_followed_but_a_linked_run_directory_is_not_replaced() {
    let dir = scratch("linked-out");
    let m = manifest(&dir, "tiny.yaml", TINY);
    // OUT itself a link (scratch storage on a cluster): the user chose it, so it is used.
    let storage = dir.join("storage");
    std::fs::create_dir(&storage).unwrap();
    let out = dir.join("out");
    std::os::unix::fs::symlink(&storage, &out).unwrap();
    let args = |o: &Path| run_quiet(&m, o);
    let o = args(&out);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(storage.join("tiny/results.parquet").is_file());
    // OUT/NAME a link to a run elsewhere: never replaced, the run it points to untouched.
    let other = dir.join("other");
    std::fs::create_dir(&other).unwrap();
    std::os::unix::fs::symlink(storage.join("tiny"), other.join("tiny")).unwrap();
    let before = std::fs::read(storage.join("tiny/results.parquet")).unwrap();
    let o = args(&other);
    assert_usage_error(&o, &["--out", "symbolic link"]);
    assert!(
        std::fs::symlink_metadata(other.join("tiny"))
            .unwrap()
            .is_symlink()
    );
    assert_eq!(
        std::fs::read(storage.join("tiny/results.parquet")).unwrap(),
        before
    );
    assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
}

#[test]
fn an_unknown_key_in_a_flow_mapping_is_named() {
    let dir = scratch("flow-key");
    let m = manifest(
        &dir,
        "flow.yaml",
        "name: t\ngrid:\n  k: {values: [1.1, 1.2]}\n  mu: {values: [0.4, 0.5]}\nscenes: [{k: 1.2, mu: 0.4, note: x}]\n",
    );
    let o = archstudy(&["check", m.to_str().unwrap()]);
    assert_usage_error(&o, &["key `note`", "unknown field `note`"]);
    assert!(!stderr(&o).contains("key `mu`"), "{}", stderr(&o));
}

#[test]
fn a_small_study_runs_under_a_tight_address_space_limit() {
    // 37 load-factor cases need 128 MiB and 37 × 2624 bytes: far below 600,000 KiB, which the
    // estimate of a 1001² map (0.75 GiB besides its cases) once refused with advice to run 37
    // shards that were refused in turn.
    let dir = scratch("ulimit-small");
    let m = manifest(
        &dir,
        "small.yaml",
        "name: small\nfind: load_factor\nload_cases:\n  - {name: h, kind: horizontal}\ngrid:\n  k: {from: 1.1, to: 1.46, steps: 37}\n  mu: {values: [0.6]}\n",
    );
    let out = dir.join("out");
    let o = limited(
        "ulimit -v 600000",
        &[
            "run",
            m.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
            "--jobs",
            "2",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("small/results.parquet").is_file());
}

#[test]
fn verify_of_a_run_too_large_to_redo_here_checks_integrity_within_the_memory_limit() {
    use polars::prelude::{DataFrame, IntoColumn, NamedFrom, ParquetWriter, Series};
    let dir = scratch("verify-large");
    let run = tiny_run(&dir);
    // The run of a 4000 × 3500 grid: 14,000,000 rows, more than 4 GB of memory can re-run
    // (3.3 GiB at 256 bytes a case and 0.8 GiB besides).
    let text = "name: tiny\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 4000}\n  mu: {from: 0.2, to: 0.8, steps: 3500}\n";
    let old = archstudy::provenance::sha256_hex(&std::fs::read(run.join("manifest.yaml")).unwrap());
    std::fs::write(run.join("manifest.yaml"), text).unwrap();
    let new = archstudy::provenance::sha256_hex(text.as_bytes());
    let info = std::fs::read_to_string(run.join("run.json")).unwrap();
    std::fs::write(run.join("run.json"), info.replace(&old, &new)).unwrap();
    let ids = Series::new("case_id".into(), vec![0u32; 14_000_000]).into_column();
    let mut frame = DataFrame::new(14_000_000, vec![ids]).unwrap();
    let file = std::fs::File::create(run.join("results.parquet")).unwrap();
    ParquetWriter::new(file).finish(&mut frame).unwrap();
    let r = run.to_str().unwrap();

    let o = limited("ulimit -v 4000000", &["verify", r]);
    assert_usage_error(&o, &["14000000 cases", "GiB", "--no-rerun"]);
    let o = limited("ulimit -v 4000000", &["verify", r, "--no-rerun"]);
    let text = crate::common::stdout(&o);
    assert!(o.status.success(), "{text}{}", stderr(&o));
    assert!(
        text.contains("results.parquet has the 14000000 rows of the plan"),
        "{text}"
    );
    assert!(text.contains("too many to draw again"), "{text}");
    assert!(text.contains("verdict: OK (integrity only)"), "{text}");
}

#[test]
fn archive_never_packs_what_a_link_in_the_run_points_to() {
    let dir = scratch("archive-link");
    let run = tiny_run(&dir);
    let secret = dir.join("secret.txt");
    std::fs::write(&secret, "not part of any run").unwrap();
    std::os::unix::fs::symlink(&secret, run.join("plots/extra.svg")).unwrap();
    let a = dir.join("a.tar.gz");
    let o = archstudy(&["archive", run.to_str().unwrap(), "-o", a.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("plots/extra.svg was left out"),
        "{}",
        stderr(&o)
    );
    let listing = Command::new("tar").arg("tzvf").arg(&a).output().unwrap();
    let listing = String::from_utf8_lossy(&listing.stdout);
    assert!(!listing.contains("extra.svg"), "{listing}");
    let bytes = Command::new("tar")
        .arg("xzOf")
        .arg(&a)
        .output()
        .unwrap()
        .stdout;
    let text = String::from_utf8_lossy(&bytes);
    assert!(!text.contains("not part of any run"));
}
