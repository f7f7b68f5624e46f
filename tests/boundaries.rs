//! `archstudy run` writes boundaries.parquet and bifurcations.parquet (schema in
//! docs/boundaries-schema.md) and records the refinement cost in run.json.

use approx::abs_diff_eq;
use archstudy::store::{f64_column, list_f64_column, read_parquet, str_column};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A scratch directory removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let p = std::env::temp_dir().join(format!("archstudy-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(&p).unwrap();
        Scratch(p)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn run_study(dir: &Path, yaml: &str) -> PathBuf {
    let study = dir.join("study.yaml");
    std::fs::write(&study, yaml).unwrap();
    let out = dir.join("out");
    let status = Command::new(env!("CARGO_BIN_EXE_archstudy"))
        .arg("run")
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .arg("--quiet")
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    out.join("t")
}

fn columns(path: &Path) -> Vec<String> {
    let df = read_parquet(path).unwrap();
    df.get_column_names()
        .iter()
        .map(|s| s.to_string())
        .collect()
}

#[test]
fn run_writes_boundaries_bifurcations_and_their_cost() {
    let s = Scratch::new("boundaries-run");
    let dir = run_study(
        &s.0,
        "name: t\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 31}\n  mu: {from: 0.2, to: 0.8, steps: 41}\nboundaries: {tolerance: 1.0e-10}\n",
    );
    let b = read_parquet(&dir.join("boundaries.parquet")).unwrap();
    assert!(b.height() > 50);
    let axis = str_column(&b, "axis").unwrap();
    assert!(
        axis.iter()
            .all(|a| matches!(a.as_deref(), Some("k" | "mu")))
    );
    let f = read_parquet(&dir.join("bifurcations.parquet")).unwrap();
    assert_eq!(f.height(), 2);
    let (mu, k) = (f64_column(&f, "mu").unwrap(), f64_column(&f, "k").unwrap());
    let a = str_column(&f, "mechanism_a").unwrap();
    let bm = str_column(&f, "mechanism_b").unwrap();
    let expected = [
        (0.395265252140, 1.113581813339, "mixed", "rotational"),
        (0.309215444330, 1.220507754643, "sliding", "mixed"),
    ];
    for (i, (m, kk, ma, mb)) in expected.into_iter().enumerate() {
        assert!(abs_diff_eq!(mu[i].unwrap(), m, epsilon = 1e-8), "{mu:?}");
        assert!(abs_diff_eq!(k[i].unwrap(), kk, epsilon = 1e-8), "{k:?}");
        assert_eq!((a[i].as_deref(), bm[i].as_deref()), (Some(ma), Some(mb)));
    }
    let sliding = list_f64_column(&f, "sliding_angles_deg").unwrap();
    assert_eq!(sliding[1].len(), 4);

    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("run.json")).unwrap()).unwrap();
    assert!(info["boundary_refinement_analyses"].as_u64().unwrap() > 0);
    assert!(info["stages"]["boundaries_ms"].as_f64().unwrap() > 0.0);
}

#[test]
fn run_writes_empty_tables_with_the_full_schema() {
    let s = Scratch::new("boundaries-empty");
    let dir = run_study(
        &s.0,
        "name: t\nfind: thrust\ngrid:\n  k: {values: [1.2, 1.3]}\n  mu: {values: [0.4]}\n",
    );
    let b = columns(&dir.join("boundaries.parquet"));
    assert_eq!(&b[..4], ["load_case", "mu", "k", "t_over_r"]);
    assert!(b.iter().any(|c| c == "sliding_senses"));
    assert_eq!(
        read_parquet(&dir.join("boundaries.parquet"))
            .unwrap()
            .height(),
        0
    );
    let f = columns(&dir.join("bifurcations.parquet"));
    assert!(f.iter().any(|c| c == "mechanism_a") && f.iter().any(|c| c == "mechanism_b"));
}
