//! `archstudy run` and `archstudy check`: results agree with `solve`, determinism across
//! thread counts, the Parquet schema, and bad manifests.

use crate::common::reference::{K_BIF, K_C, MU_MIN, MU_ROT};
use crate::common::{archstudy, assert_usage_error, manifest, scratch, solve_json, stderr, stdout};
use approx::{abs_diff_eq, assert_abs_diff_eq};
use archstudy::scene::Find;
use archstudy::store;
use std::path::Path;

const SMALL: &str = "name: small
grid:
  k: {from: 1.05, to: 1.5, steps: 19}
  mu: {values: [0.2, 0.3, 0.309215444331, 0.35, 0.395265252140, 0.5, inf]}
";

fn run(dir: &Path, manifest_path: &Path, extra: &[&str]) -> std::process::Output {
    let out = dir.join("out");
    let mut args = vec![
        "run",
        manifest_path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    args.extend_from_slice(extra);
    archstudy(&args)
}

#[test]
fn regimes_agree_with_solve_and_the_exact_boundaries() {
    let dir = scratch("agree");
    let m = manifest(&dir, "small.yaml", SMALL);
    let o = run(&dir, &m, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let df = store::read_parquet(&dir.join("out/small/results.parquet")).unwrap();
    assert_eq!(df.height(), 19 * 7);
    let k = store::f64_column(&df, "k").unwrap();
    let mu = store::f64_column(&df, "mu").unwrap();
    let regime = store::str_column(&df, "regime").unwrap();
    let lo = store::f64_column(&df, "thrust_r_min").unwrap();
    for i in (0..df.height()).step_by(5) {
        let (k, mu) = (k[i].unwrap(), mu[i].unwrap());
        let mu_arg = if mu.is_infinite() {
            "inf".to_string()
        } else {
            format!("{mu:?}")
        };
        let v = solve_json(&["--k", &format!("{k:?}"), "--mu", &mu_arg]);
        assert_eq!(
            v["regime"].as_str(),
            regime[i].as_deref(),
            "K = {k}, μ = {mu}"
        );
        assert_eq!(v["thrust_r_min"].as_f64(), lo[i], "K = {k}, μ = {mu}");
    }
    // The exact regime boundaries of the paper's case.
    let (kc, mu_min, mu_rot) = (K_C, MU_MIN, MU_ROT);
    for i in 0..df.height() {
        let (k, mu) = (k[i].unwrap(), mu[i].unwrap());
        let expected = if mu < mu_min - 1e-12 {
            if k < kc { "none" } else { "sliding" }
        } else if k < kc {
            "rotational"
        } else if mu >= mu_rot || k >= 1.220507754643 {
            "stable"
        } else {
            // Between the bifurcations: stable iff above the mixed collapse curve.
            let v = solve_json(&["--find", "thickness", "--mu", &format!("{mu:?}")]);
            if k >= v["k_crit"].as_f64().unwrap() {
                "stable"
            } else {
                "mixed"
            }
        };
        assert_eq!(regime[i].as_deref(), Some(expected), "K = {k}, μ = {mu}");
    }
}

#[test]
fn one_and_two_threads_give_identical_results() {
    let dir = scratch("jobs");
    let text = "name: jobs\nfind: thickness\narch: {voussoirs: 24}\ngrid:\n  mu: {from: 0.3, to: 0.5, steps: 9}\n  half_angle_deg: {values: [60, 90, 120]}\n";
    let m = manifest(&dir, "jobs.yaml", text);
    let a = dir.join("a");
    let b = dir.join("b");
    for (out, jobs) in [(&a, "1"), (&b, "2")] {
        let o = archstudy(&[
            "run",
            m.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--jobs",
            jobs,
            "--quiet",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let mut da = store::read_parquet(&a.join("jobs/results.parquet")).unwrap();
    let mut db = store::read_parquet(&b.join("jobs/results.parquet")).unwrap();
    let _ = da.drop_in_place("solve_time_us");
    let _ = db.drop_in_place("solve_time_us");
    assert!(
        da.equals_missing(&db),
        "results differ between --jobs 1 and --jobs 2"
    );
    assert_eq!(da.height(), 27);
}

#[test]
fn parquet_schema_reads_back_with_documented_names_and_types() {
    use polars::prelude::DataType;
    let dir = scratch("schema");
    let text = "name: schema\nfind: thickness\ngrid:\n  mu: {values: [0.25, 0.35, inf]}\n";
    let m = manifest(&dir, "schema.yaml", text);
    let o = run(&dir, &m, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let df = store::read_parquet(&dir.join("out/schema/results.parquet")).unwrap();
    let expect = [
        ("case_id", DataType::UInt64),
        ("load_case", DataType::String),
        ("load_kind", DataType::String),
        ("find", DataType::String),
        ("k", DataType::Float64),
        ("t_over_r", DataType::Float64),
        ("mu", DataType::Float64),
        ("half_angle_deg", DataType::Float64),
        ("weight", DataType::String),
        ("voussoirs", DataType::UInt32),
        ("outcome", DataType::String),
        ("regime", DataType::String),
        ("thrust_r_min", DataType::Float64),
        ("thrust_r_max", DataType::Float64),
        ("thrust_s_min", DataType::Float64),
        ("thrust_s_max", DataType::Float64),
        ("k_crit", DataType::Float64),
        ("t_over_r_crit", DataType::Float64),
        ("mu_crit", DataType::Float64),
        ("mechanism", DataType::String),
        ("thrust_over_half_weight", DataType::Float64),
        ("crown_moment", DataType::Float64),
        (
            "hinge_angles_deg",
            DataType::List(Box::new(DataType::Float64)),
        ),
        ("hinge_faces", DataType::List(Box::new(DataType::String))),
        (
            "sliding_angles_deg",
            DataType::List(Box::new(DataType::Float64)),
        ),
        ("sliding_senses", DataType::List(Box::new(DataType::String))),
        ("work_loads", DataType::Float64),
        ("work_friction", DataType::Float64),
        ("work_residual", DataType::Float64),
        ("mechanism_dof", DataType::UInt32),
        ("thrust_min", DataType::Float64),
        ("thrust_max", DataType::Float64),
        (
            "hinges_min_angles_deg",
            DataType::List(Box::new(DataType::Float64)),
        ),
        (
            "hinges_min_faces",
            DataType::List(Box::new(DataType::String)),
        ),
        (
            "hinges_max_angles_deg",
            DataType::List(Box::new(DataType::Float64)),
        ),
        (
            "hinges_max_faces",
            DataType::List(Box::new(DataType::String)),
        ),
        ("status", DataType::String),
        ("message", DataType::String),
        ("solve_time_us", DataType::Float64),
    ];
    // A thickness study stores the columns a thickness find fills, and only those.
    for (name, dtype) in &expect {
        let filled = store::filled_by(name).is_none_or(|by| by.contains(&Find::Thickness));
        match df.column(name) {
            Ok(c) => {
                assert!(
                    filled,
                    "column {name} stored though a thickness study leaves it empty"
                );
                assert_eq!(c.dtype(), dtype, "column {name}");
            }
            Err(_) => assert!(!filled, "column {name} missing"),
        }
    }
    for absent in [
        "regime",
        "thrust_r_min",
        "mu_crit",
        "thrust_min",
        "k_c_rotational",
    ] {
        assert!(df.column(absent).is_err(), "{absent}");
    }
    let k = store::f64_column(&df, "k_crit").unwrap();
    assert!(k[0].is_none(), "μ = 0.25 < μ_min: no collapse thickness");
    assert_abs_diff_eq!(k[2].unwrap(), K_C, epsilon = 1e-9);
    let mech = store::str_column(&df, "mechanism").unwrap();
    assert_eq!(mech[1].as_deref(), Some("mixed"));
    let hinges = store::list_f64_column(&df, "hinge_angles_deg").unwrap();
    assert_eq!(hinges[2].len(), 5);
    let mu = store::f64_column(&df, "mu").unwrap();
    assert!(mu[2].unwrap().is_infinite());
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out/schema/run.json")).unwrap()).unwrap();
    for key in [
        "manifest",
        "manifest_sha256",
        "archstudy_version",
        "rustc_version",
        "command_line",
        "threads",
        "started_at",
        "finished_at",
        "cases",
        "stages",
    ] {
        assert!(info.get(key).is_some(), "run.json lacks {key}");
    }
    assert_eq!(info["cases"]["total"], 3);
}

#[test]
fn bad_manifests_exit_2_with_a_located_message_and_write_nothing() {
    let dir = scratch("bad");
    let good_grid = "grid:\n  k: {from: 1.05, to: 1.5, steps: 5}\n  mu: {values: [0.3, inf]}\n";
    let cases: Vec<(&str, String, &[&str])> = vec![
        ("malformed", "name: x\ngrid: [unclosed\n".to_string(), &["malformed.yaml:"]),
        ("unknown-key", format!("name: x\ncolour: red\n{good_grid}"), &["colour", ":2:"]),
        ("wrong-type", "name: x\ngrid:\n  k: {from: one, to: 1.5, steps: 5}\n  mu: {values: [0.3]}\n".to_string(), &[":3:", "one"]),
        ("empty-range", "name: x\ngrid:\n  k: {from: 1.2, to: 1.2, steps: 5}\n  mu: {values: [0.3]}\n".to_string(), &["grid.k", "empty", ":3:"]),
        ("reversed-range", "name: x\ngrid:\n  k: {from: 1.5, to: 1.2, steps: 5}\n  mu: {values: [0.3]}\n".to_string(), &["grid.k.to", "reversed", ":3:"]),
        ("zero-steps", "name: x\ngrid:\n  k: {from: 1.1, to: 1.2, steps: 0}\n  mu: {values: [0.3]}\n".to_string(), &["grid.k.steps", "value 0", ":3:"]),
        ("dup-load-case", format!("name: x\n{good_grid}load_cases:\n  - {{name: g, kind: self_weight}}\n  - {{name: g, kind: self_weight}}\n"), &["load_cases.name", "duplicate", ":7:"]),
        ("k-le-1", "name: x\ngrid:\n  k: {values: [1.2, 1.0]}\n  mu: {values: [0.3]}\n".to_string(), &["grid.k.values", "value 1", "greater than 1", ":3:"]),
        ("negative-mu", "name: x\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.3, -0.2]}\n".to_string(), &["grid.mu.values", "value -0.2", "≥ 0", ":4:"]),
        ("nan-mu", "name: x\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [.nan]}\n".to_string(), &["grid.mu.values", "NaN", ":4:"]),
        ("thickness-with-k", "name: x\nfind: thickness\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.3]}\n".to_string(), &["grid.k", "thickness"]),
        ("friction-with-mu", "name: x\nfind: friction\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.3]}\n".to_string(), &["grid.mu", "friction"]),
        ("absurd-size", "name: x\ngrid:\n  k: {from: 1.1, to: 1.5, steps: 100000}\n  mu: {from: 0.1, to: 0.9, steps: 100000}\n".to_string(), &["10000000000 cases"]),
    ];
    for (name, text, needles) in cases {
        let m = manifest(&dir, &format!("{name}.yaml"), &text);
        let out = dir.join(format!("out-{name}"));
        let o = archstudy(&[
            "run",
            m.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]);
        let file = format!("{name}.yaml");
        let mut names = vec![file.as_str()];
        names.extend_from_slice(needles);
        assert_usage_error(&o, &names);
        assert!(!out.exists(), "{name}: output written");
        let c = archstudy(&["check", m.to_str().unwrap()]);
        if name == "absurd-size" {
            // Valid, but too large for one run: `check` describes it, in shards only.
            let s = stdout(&c);
            assert!(c.status.success(), "{name}: check: {}", stderr(&c));
            assert!(s.contains("cases: 10000000000\nruns in shards only"), "{s}");
            assert!(s.contains("--shard I/N"), "{s}");
        } else {
            assert_eq!(c.status.code(), Some(2), "{name}: check");
        }
    }
    let missing = archstudy(&[
        "run",
        dir.join("nope.yaml").to_str().unwrap(),
        "--out",
        dir.join("o").to_str().unwrap(),
    ]);
    assert_usage_error(&missing, &["nope.yaml"]);
    assert!(!dir.join("o").exists());
}

#[test]
fn check_prints_the_plan() {
    let dir = scratch("check");
    let m = manifest(&dir, "small.yaml", SMALL);
    let o = archstudy(&["check", m.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    assert!(
        s.contains("cases: 133")
            && s.contains("axis k: 19 values")
            && s.contains("axis mu: 7 values"),
        "{s}"
    );
}

#[test]
fn the_closing_line_counts_one_case_as_one_case() {
    let dir = scratch("one-case");
    let m = manifest(
        &dir,
        "one.yaml",
        "name: one\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
    );
    let o = run(&dir, &m, &[]);
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(e.contains("1 case (1 ok, 0 failed) in "), "{e}");
    let o = run(&dir, &manifest(&dir, "small.yaml", SMALL), &[]);
    assert!(
        stderr(&o).contains("133 cases (133 ok, 0 failed) in "),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_rerun_replaces_the_earlier_run_and_leaves_no_staging_directory() {
    let dir = scratch("rerun");
    let m = manifest(&dir, "small.yaml", SMALL);
    for _ in 0..2 {
        let o = run(&dir, &m, &[]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let entries: Vec<String> = std::fs::read_dir(dir.join("out"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(entries, vec!["small".to_string()]);
}

#[test]
fn convergence_study_thresholds_approach_the_continuum() {
    let dir = scratch("convergence");
    let out = dir.join("out");
    let o = archstudy(&[
        "run",
        "studies/convergence.yaml",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let df = store::read_parquet(&out.join("convergence/results.parquet")).unwrap();
    let n = store::f64_column(&df, "voussoirs").unwrap();
    let kc = store::f64_column(&df, "k_c_rotational").unwrap();
    let mu_rm = store::f64_column(&df, "mu_rotational_mixed").unwrap();
    let mu_min = store::f64_column(&df, "mu_min").unwrap();
    let k_ms = store::f64_column(&df, "k_mixed_sliding").unwrap();
    let lf = store::f64_column(&df, "load_factor").unwrap();
    let lc = store::str_column(&df, "load_case").unwrap();
    // The self-weight thresholds first (25 models, continuum last), then the horizontal
    // load factor of the same 25 models.
    assert_eq!(df.height(), 50);
    let last = 24;
    assert!(lc[..25].iter().all(|l| l.as_deref() == Some("self_weight")));
    assert!(lc[25..].iter().all(|l| l.as_deref() == Some("horizontal")));
    assert!(
        n[last].is_none() && n[49].is_none(),
        "the continuum is the last row"
    );
    assert_abs_diff_eq!(kc[last].unwrap(), K_C, epsilon = 1e-9);
    assert_abs_diff_eq!(mu_rm[last].unwrap(), MU_ROT, epsilon = 1e-9);
    assert_abs_diff_eq!(mu_min[last].unwrap(), MU_MIN, epsilon = 1e-9);
    assert_abs_diff_eq!(k_ms[last].unwrap(), K_BIF, epsilon = 1e-8);
    // Every discrete arch collapses no later than the continuum, and 4096 voussoirs are
    // within 1e-6 of it.
    for i in 0..last {
        if let Some(k) = kc[i] {
            assert!(k <= kc[last].unwrap() + 1e-12, "N = {:?}: {k}", n[i]);
        }
    }
    let i4096 = n.iter().position(|x| *x == Some(4096.0)).unwrap();
    for (col, name) in [
        (&kc, "K_c"),
        (&mu_rm, "μ rot/mixed"),
        (&mu_min, "μ_min"),
        (&k_ms, "K mixed/sliding"),
    ] {
        let e = (col[i4096].unwrap() - col[last].unwrap()).abs();
        assert!(e < 1e-6, "{name}: error {e} at N = 4096");
    }
    // The horizontal load factor: every discrete arch carries more than the continuum, and
    // 4096 voussoirs are within 1e-7 of it.
    let lambda_c = lf[49].unwrap();
    assert!(
        abs_diff_eq!(lambda_c, 0.05246891, epsilon = 1e-8),
        "{lambda_c}"
    );
    for i in 25..49 {
        let l = lf[i].unwrap();
        assert!(l > lambda_c, "N = {:?}: {l}", n[i]);
    }
    let e = lf[25 + i4096].unwrap() - lambda_c;
    assert!(e < 1e-7, "λ: error {e} at N = 4096");
}

#[test]
fn a_batch_log_names_every_stage_and_counts_the_boundary_analyses() {
    let dir = scratch("batch-log");
    let m = manifest(
        &dir,
        "lf.yaml",
        "name: lf
grid:
  k: {from: 1.15, to: 1.45, steps: 4}
  mu: {values: [0.35, 0.5, inf]}
load_cases:
  - {name: wind, kind: horizontal, find: load_factor}
",
    );
    let out = dir.join("out");
    // Standard error is a pipe here, as in a batch job: plain lines, no bar.
    let o = archstudy(&["run", m.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let log = stderr(&o);
    for line in [
        "analysing: 12 cases",
        "analysing: done, 12/12 cases in",
        "figure data: done in",
        "drawing figures: done",
        "writing reports: done in",
    ] {
        assert!(log.contains(line), "no `{line}` in:\n{log}");
    }
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("lf/run.json")).unwrap()).unwrap();
    let analyses = info["boundary_refinement_analyses"].as_u64().unwrap();
    assert!(analyses > 0, "{info}");
    assert!(
        log.contains(&format!(
            "locating boundaries: done, {analyses} analyses in"
        )),
        "{log}"
    );
    assert!(!log.contains('\r'), "a bar was drawn into a log: {log:?}");
}
