//! `archstudy merge` against shards that are not what they claim: tables edited after the
//! shard wrote them, rows that contradict the plan, impossible timings, and a merge that would
//! replace one of its own inputs; and the ways of naming many shards.

use crate::common::{archstudy, assert_usage_error, scratch, stderr};
use crate::shard::{STATE, cli_shards, merge_cli, merge_cli_with};
use archstudy::provenance::sha256_hex;
use archstudy::store;
use std::path::{Path, PathBuf};

/// Copies a shard directory (its files only) to `to`.
fn copy_shard(from: &Path, to: &Path) -> PathBuf {
    std::fs::create_dir_all(to).unwrap();
    for f in ["run.json", "manifest.yaml", "results.parquet"] {
        std::fs::copy(from.join(f), to.join(f)).unwrap();
    }
    to.to_path_buf()
}

fn edit_run_json(dir: &Path, f: impl FnOnce(&mut serde_json::Value)) {
    let path = dir.join("run.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    f(&mut v);
    std::fs::write(&path, serde_json::to_string_pretty(&v).unwrap()).unwrap();
}

/// Records the present hash of results.parquet in the shard's run.json, as a careful forger
/// would.
fn rehash(dir: &Path) {
    let hash = sha256_hex(&std::fs::read(dir.join("results.parquet")).unwrap());
    edit_run_json(dir, |v| v["table_sha256"]["results.parquet"] = hash.into());
}

#[test]
fn a_merge_refuses_shard_tables_that_are_not_what_the_shard_wrote_or_the_plan_holds() {
    let dir = scratch("merge-forged");
    let d = cli_shards(&dir, STATE, "s.yaml", 2);
    let out = dir.join("merged");
    type Forge = fn(&Path);
    let forgeries: Vec<(&str, Forge, Vec<&str>)> = vec![
        (
            "thrust edited",
            |s| {
                store::rewrite_f64_value(&s.join("results.parquet"), "thrust_r_min", 0, Some(9.0))
                    .unwrap();
            },
            vec!["not the table the shard wrote"],
        ),
        (
            "a grid value edited, hash recomputed",
            |s| {
                store::rewrite_f64_value(&s.join("results.parquet"), "k", 0, Some(7.7)).unwrap();
                rehash(s);
            },
            vec!["row 0 (case 0)", "`k` is not the plan's value"],
        ),
        (
            "rows swapped keeping their ids",
            |s| {
                let p = s.join("results.parquet");
                let df = store::read_parquet(&p).unwrap();
                let mut swapped = df.slice(1, 1).vstack(&df.slice(0, 1)).unwrap();
                swapped = swapped.vstack(&df.slice(2, df.height() - 2)).unwrap();
                let ids: Vec<u64> = (0..df.height() as u64).collect();
                swapped
                    .with_column(polars::prelude::Column::new("case_id".into(), ids))
                    .unwrap();
                store::write_parquet(&mut swapped, &p).unwrap();
            },
            vec!["not the table the shard wrote"],
        ),
        (
            "column dropped, hash recomputed",
            |s| {
                let p = s.join("results.parquet");
                let mut df = store::read_parquet(&p).unwrap().drop("regime").unwrap();
                store::write_parquet(&mut df, &p).unwrap();
                rehash(s);
            },
            vec!["regime", "missing"],
        ),
        (
            "no hash",
            |s| edit_run_json(s, |v| v["table_sha256"] = serde_json::json!({})),
            vec!["records no hash of results.parquet"],
        ),
        (
            "negative timing",
            |s| edit_run_json(s, |v| v["stages"]["engine_ms"] = (-5.0).into()),
            vec!["stages.engine_ms = -5"],
        ),
        (
            "huge timing",
            |s| edit_run_json(s, |v| v["stages"]["store_ms"] = 1e308.into()),
            vec!["stages.store_ms = 1000000"],
        ),
    ];
    for (i, (name, forge, said)) in forgeries.into_iter().enumerate() {
        let forged = copy_shard(&d[0], &dir.join(format!("f{i}")).join("state.shard-1-of-2"));
        forge(&forged);
        let o = merge_cli(&[&forged, &d[1]], &out);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {e}");
        assert!(e.contains(forged.to_str().unwrap()), "{name}: {e}");
        for s in said {
            assert!(e.contains(s), "{name}: `{s}` not said: {e}");
        }
        assert!(!out.join("state").exists(), "{name}");
    }
}

/// Rewrites a float column of a shard's table through `f` and records the new hash, as a
/// careful forger would.
fn forge_column(dir: &Path, column: &str, f: impl Fn(f64) -> f64) {
    let p = dir.join("results.parquet");
    let mut df = store::read_parquet(&p).unwrap();
    let c = df.column(column).unwrap().f64().unwrap().clone();
    let v: Vec<Option<f64>> = (0..c.len()).map(|i| c.get(i).map(&f)).collect();
    df.with_column(polars::prelude::Column::new(column.into(), v))
        .unwrap();
    store::write_parquet(&mut df, &p).unwrap();
    rehash(dir);
}

#[test]
fn a_merge_analyses_shard_rows_again_and_refuses_values_the_plan_does_not_give() {
    let dir = scratch("merge-recheck");
    let d = cli_shards(&dir, STATE, "s.yaml", 2);
    let out = dir.join("merged");
    // Every thrust scaled by 1.5, the hash recomputed: the plan checks pass, the values do
    // not; any of the 64 rows drawn shows it.
    let scaled = copy_shard(&d[0], &dir.join("scaled/state.shard-1-of-2"));
    forge_column(&scaled, "thrust_r_max", |h| 1.5 * h);
    let o = merge_cli(&[&scaled, &d[1]], &out);
    assert_usage_error(
        &o,
        &[
            scaled.to_str().unwrap(),
            "analysed again gives `thrust_r_max`",
            "analysed by this build",
            "re-run the shard",
        ],
    );
    assert!(!out.join("state").exists());
    // One regime flipped: a random draw of 64 of 124 rows may miss it, `--recheck all`
    // cannot, and names the case.
    let flipped = copy_shard(&d[1], &dir.join("flipped/state.shard-2-of-2"));
    let p = flipped.join("results.parquet");
    let mut df = store::read_parquet(&p).unwrap();
    let row = 40;
    let c = df.column("regime").unwrap().str().unwrap().clone();
    let mut regimes: Vec<Option<String>> =
        (0..c.len()).map(|i| c.get(i).map(str::to_string)).collect();
    let was = regimes[row].clone().unwrap();
    regimes[row] = Some(if was == "stable" { "sliding" } else { "stable" }.to_string());
    let case: u64 = df
        .column("case_id")
        .unwrap()
        .u64()
        .unwrap()
        .get(row)
        .unwrap();
    df.with_column(polars::prelude::Column::new("regime".into(), regimes))
        .unwrap();
    store::write_parquet(&mut df, &p).unwrap();
    rehash(&flipped);
    let o = merge_cli_with(&[&d[0], &flipped], &out, &["--recheck", "all"]);
    assert_usage_error(
        &o,
        &[&format!(
            "case {case} analysed again gives `regime` = \"{was}\""
        )],
    );
    // `--recheck 0` takes the values on trust once the rows match the plan, and says so in
    // run.json: no row analysed again.
    let o = merge_cli_with(&[&d[0], &flipped], &out, &["--recheck", "0"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("state/run.json")).unwrap()).unwrap();
    assert_eq!(info["shard_builds"][0]["rows_rechecked"], 0);
    // The genuine shards merge, with the rows analysed again counted: 64 of each shard.
    let o = merge_cli(&[&d[0], &d[1]], &dir.join("genuine"));
    assert!(o.status.success(), "{}", stderr(&o));
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("genuine/state/run.json")).unwrap())
            .unwrap();
    assert_eq!(info["shard_builds"][0]["rows_rechecked"], 128);
    let o = merge_cli_with(&[&d[0], &d[1]], &out, &["--recheck", "some"]);
    assert_usage_error(&o, &["--recheck", "some", "`all`"]);
}

#[test]
fn a_merge_never_replaces_its_inputs_and_records_every_shards_build() {
    let dir = scratch("merge-inputs");
    let d = cli_shards(&dir, STATE, "s.yaml", 2);
    // A shard directory that is OUT/<name>: the merge would replace it.
    let trap = dir.join("trap");
    let inside = copy_shard(&d[0], &trap.join("state"));
    let o = merge_cli(&[&inside, &d[1]], &trap);
    assert_usage_error(&o, &["--out", "shard directory"]);
    assert!(inside.join("run.json").is_file() && inside.join("results.parquet").is_file());
    // One held inside OUT/<name>.
    let nested = copy_shard(&d[0], &trap.join("state/sub"));
    let o = merge_cli(&[&nested, &d[1]], &trap);
    assert_usage_error(&o, &["--out"]);
    // Shards of another build: the merged run.json names each build and its shards.
    edit_run_json(&d[1], |v| {
        v["archstudy_version"] = "0.0.9".into();
        v["git_commit"] = "feedbeef".into();
    });
    let out = dir.join("merged");
    let o = merge_cli(&[&d[0], &d[1]], &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("state/run.json")).unwrap()).unwrap();
    let builds = info["shard_builds"].as_array().unwrap();
    assert_eq!(builds.len(), 2, "{builds:?}");
    assert_eq!(builds[0]["shards"], "1");
    assert_eq!(builds[0]["archstudy_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(builds[1]["shards"], "2");
    assert_eq!(builds[1]["archstudy_version"], "0.0.9");
    assert_eq!(builds[1]["git_commit"], "feedbeef");
}

#[test]
fn a_merge_takes_its_shards_from_a_directory_or_a_list_file() {
    let dir = scratch("merge-from");
    let d = cli_shards(&dir, STATE, "s.yaml", 3);
    let shards_dir = d[0].parent().unwrap();
    let o = archstudy(&[
        "merge",
        "--shards-from",
        shards_dir.to_str().unwrap(),
        "--out",
        dir.join("a").to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.join("a/state/report.html").is_file());
    let list = dir.join("shards.list");
    let text: String = std::iter::once("# the shards\n".to_string())
        .chain(d.iter().rev().map(|p| format!("{}\n\n", p.display())))
        .collect();
    std::fs::write(&list, text).unwrap();
    let o = archstudy(&[
        "merge",
        "--shards-from",
        list.to_str().unwrap(),
        "--out",
        dir.join("b").to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.join("b/state/report.html").is_file());
    // A FIFO is not read.
    let fifo = dir.join("fifo");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let o = archstudy(&["merge", "--shards-from", fifo.to_str().unwrap()]);
    assert_usage_error(&o, &["--shards-from", "regular file"]);
}
