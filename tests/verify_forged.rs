//! `archstudy verify` against forgeries: a real run, each kind of derived file forged in turn
//! and archived with its checksums recomputed; verify fails and names the forged file.

use crate::common::{TINY, archstudy, run_study, stdout};
use std::path::{Path, PathBuf};

/// Copies a directory tree.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let target = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy_tree(&p, &target);
        } else {
            std::fs::copy(&p, &target).unwrap();
        }
    }
}

fn edit(path: &Path, f: impl FnOnce(String) -> String) {
    let text = std::fs::read_to_string(path).unwrap();
    std::fs::write(path, f(text)).unwrap();
}

fn edit_json(path: &Path, f: impl FnOnce(&mut serde_json::Value)) {
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    f(&mut v);
    std::fs::write(path, serde_json::to_string_pretty(&v).unwrap()).unwrap();
}

/// The first table of tables/ with the extension `ext`.
fn first_table(run: &Path, ext: &str) -> PathBuf {
    let mut t: Vec<PathBuf> = std::fs::read_dir(run.join("tables"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == ext))
        .collect();
    t.sort();
    t.remove(0)
}

type Forge = fn(&Path);

/// Each forgery, with the text verify must print for it.
fn forgeries() -> Vec<(&'static str, Forge, &'static str)> {
    vec![
        (
            "csv numbers",
            |r| edit(&r.join("tables/study.csv"), |t| t.replace('1', "7")),
            "tables/study.csv",
        ),
        (
            "tex input line",
            |r| {
                edit(&r.join("tables/study.tex"), |t| {
                    t + "\\input{/etc/passwd}\n"
                })
            },
            "tables/study.tex",
        ),
        (
            "table added",
            |r| std::fs::write(r.join("tables/extra.csv"), "a,b\n1,2\n").unwrap(),
            "tables/extra.csv",
        ),
        (
            "every table removed",
            |r| std::fs::remove_dir_all(r.join("tables")).unwrap(),
            "tables/study.csv (missing)",
        ),
        (
            "another table's csv",
            |r| {
                let csv = first_table(r, "csv");
                edit(&csv, |t| t.replacen(',', ";", 1));
            },
            "tables/",
        ),
        (
            "report.html",
            |r| edit(&r.join("report.html"), |t| t.replacen("<h1>", "<h1>X", 1)),
            "report.html",
        ),
        (
            "report.md",
            |r| edit(&r.join("report.md"), |t| t + "\nForged line.\n"),
            "report.md",
        ),
        (
            "figure",
            |r| {
                edit(&r.join("plots/regime-map.svg"), |t| {
                    t.replacen("<svg", "<svg data-x=\"1\"", 1)
                })
            },
            "plots/regime-map.svg",
        ),
        (
            "crate title",
            |r| {
                edit_json(&r.join("ro-crate-metadata.json"), |v| {
                    v["@graph"][1]["name"] = "FORGED TITLE".into();
                });
            },
            "ro-crate-metadata.json",
        ),
        (
            "crate licence",
            |r| {
                edit_json(&r.join("ro-crate-metadata.json"), |v| {
                    v["@graph"][2]["license"] = "Proprietary".into();
                });
            },
            "ro-crate-metadata.json",
        ),
        (
            "crate removed",
            |r| std::fs::remove_file(r.join("ro-crate-metadata.json")).unwrap(),
            "ro-crate-metadata.json (missing)",
        ),
        (
            "crate nested deep",
            |r| {
                let deep = "[".repeat(200_000) + &"]".repeat(200_000);
                std::fs::write(r.join("ro-crate-metadata.json"), deep).unwrap();
            },
            "ro-crate-metadata.json",
        ),
        (
            "manifest copy, report drawn again",
            |r| {
                edit_json(&r.join("run.json"), |v| {
                    v["manifest"]["title"] = "FORGED TITLE".into();
                    v["manifest"]["description"] = "forged".into();
                });
                let o = archstudy(&["report", r.to_str().unwrap()]);
                assert!(o.status.success());
            },
            "run.json: DIFFERENT: its copy of the manifest is not manifest.yaml",
        ),
        (
            "git commit",
            |r| edit_json(&r.join("run.json"), |v| v["git_commit"] = "0123abcd".into()),
            "run.json names another build (archstudy",
        ),
        (
            // The version is a claim no stored value depends on: `report` draws every file
            // again from it, crate included, and verify notes the other version. Editing it
            // must not turn a check off: a report forged afterwards is still named.
            "version, report drawn again, then forged",
            |r| {
                edit_json(&r.join("run.json"), |v| {
                    v["archstudy_version"] = "0.0.1".into()
                });
                let o = archstudy(&["report", r.to_str().unwrap()]);
                assert!(o.status.success());
                edit(&r.join("report.html"), |t| t.replacen("<h1>", "<h1>X", 1));
            },
            "report.html",
        ),
        (
            "table hash",
            |r| {
                edit_json(&r.join("run.json"), |v| {
                    v["table_sha256"]["results.parquet"] = "00".repeat(32).into();
                });
            },
            "tables: DIFFERENT: results.parquet is not the table run.json records",
        ),
    ]
}

/// Every kind of derived file forged in turn, archived with fresh checksums: integrity holds,
/// verify (with and without re-run) fails and names the file; the unforged run passes.
#[test]
fn verify_names_every_forged_derived_file_even_with_recomputed_checksums() {
    let tmp = tempfile::tempdir().unwrap();
    let run = run_study(tmp.path(), "tiny.yaml", TINY);
    let verify = |target: &Path, rerun: bool| {
        let t = target.to_str().unwrap();
        let args = if rerun {
            vec!["verify", t]
        } else {
            vec!["verify", "--no-rerun", t]
        };
        archstudy(&args)
    };
    let o = verify(&run, false);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert!(stdout(&o).contains("tables: all 7 Parquet tables have the hashes run.json records"));
    for (i, (name, forge, said)) in forgeries().into_iter().enumerate() {
        let dir = tmp.path().join(format!("forged-{i}")).join("tiny");
        copy_tree(&run, &dir);
        forge(&dir);
        let file = tmp.path().join(format!("forged-{i}.tar.gz"));
        let o = archstudy(&[
            "archive",
            dir.to_str().unwrap(),
            "-o",
            file.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{name}: {}", crate::common::stderr(&o));
        // The full re-run once, on the first forgery; --no-rerun (which draws again too)
        // for the others.
        let o = verify(&file, i == 0);
        let out = stdout(&o);
        assert_eq!(o.status.code(), Some(1), "{name}: {out}");
        assert!(out.contains("integrity: all"), "{name}: {out}");
        assert!(out.contains(said), "{name}: `{said}` not said: {out}");
        assert!(!out.contains("verdict: OK"), "{name}: {out}");
    }
}

#[test]
fn verify_stopped_by_sigterm_leaves_no_temporary_re_run() {
    use crate::common::{bin, scratch};
    let dir = scratch("verify-sigterm");
    let run = run_study(
        &dir,
        "big.yaml",
        "name: big\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 400}\n  mu: {from: 0.2, to: 0.8, steps: 400}\n",
    );
    let tmp = dir.join("tmp");
    std::fs::create_dir_all(&tmp).unwrap();
    let mut child = bin()
        .args(["verify", run.to_str().unwrap()])
        .env("TMPDIR", &tmp)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Stopped once the re-run's temporary directory exists.
    let rerun = || {
        std::fs::read_dir(&tmp).unwrap().flatten().any(|e| {
            e.file_name()
                .to_string_lossy()
                .starts_with("archstudy-rerun-")
        })
    };
    let Some(code) = crate::common::terminate_when(&mut child, rerun) else {
        // Verify finished before the signal: nothing to check.
        return;
    };
    assert_eq!(code, 143);
    let left: Vec<_> = std::fs::read_dir(&tmp).unwrap().flatten().collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}
