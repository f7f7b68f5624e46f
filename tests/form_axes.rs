//! `eccentricity` and `joints` as grid axes: forms side by side in one study, each case,
//! boundary, bifurcation and drawn state on its own form, with the values the same forms give
//! in studies of their own.

use crate::common::{archstudy, assert_usage_error, manifest, run_study, scratch, stderr};
use archstudy::store;
use std::path::Path;

const FORMS: &str = "name: forms
arch: {shape: pointed}
grid:
  eccentricity: {values: [0, 0.2]}
  k: {from: 1.05, to: 1.3, steps: 11}
  mu: {from: 0.2, to: 0.6, steps: 9}
scenes:
  - {k: 1.2, mu: 0.4}
";

/// The bifurcations of a run as (e, μ, K), e being None for a circular arch.
fn bifurcations(run: &Path) -> Vec<(Option<f64>, f64, f64)> {
    let rows = store::read_bifurcations(&run.join("bifurcations.parquet")).unwrap();
    let groups = store::read_bifurcation_groups(&run.join("bifurcations.parquet")).unwrap();
    rows.iter()
        .zip(&groups)
        .map(|(b, g)| (g.eccentricity, b.mu, b.k))
        .collect()
}

#[test]
fn an_eccentricity_axis_puts_the_semicircle_and_a_pointed_arch_side_by_side() {
    let dir = scratch("form-axes-e");
    let run = run_study(&dir, "forms.yaml", FORMS);
    let b = bifurcations(&run);
    assert_eq!(b.len(), 4, "{b:?}");
    // e = 0 is the semicircle: the paper's bifurcations (closed forms, DESIGN values
    // μ 0.3952652519 at K 1.1135818136 and μ 0.3092154443 at K 1.2205077547).
    let e0: Vec<_> = b.iter().filter(|x| x.0 == Some(0.0)).collect();
    assert_eq!(e0.len(), 2, "{b:?}");
    assert!((e0[0].1 - 0.395_265_251_9).abs() < 1e-8 && (e0[0].2 - 1.113_581_813_6).abs() < 1e-8);
    assert!((e0[1].1 - 0.309_215_444_3).abs() < 1e-8 && (e0[1].2 - 1.220_507_754_7).abs() < 1e-8);
    // e = 0.2: those of a study of that arch alone.
    let alone = run_study(
        &dir,
        "alone.yaml",
        &FORMS
            .replace("name: forms", "name: alone")
            .replace("{shape: pointed}", "{shape: pointed, eccentricity: 0.2}")
            .replace("  eccentricity: {values: [0, 0.2]}\n", ""),
    );
    let own = bifurcations(&alone);
    let e2: Vec<_> = b.iter().filter(|x| x.0 == Some(0.2)).collect();
    assert_eq!(e2.len(), own.len());
    for (x, y) in e2.iter().zip(&own) {
        assert!(
            (x.1 - y.1).abs() < 1e-12 && (x.2 - y.2).abs() < 1e-12,
            "{x:?} {y:?}"
        );
    }
    // Every row of results.parquet of e = 0.2 is the single study's row.
    let all = store::read_table(&run.join("results.parquet")).unwrap();
    let one = store::read_table(&alone.join("results.parquet")).unwrap();
    let col = |t: &store::Table, n: &str| match &t.column(n).unwrap().data {
        store::ColumnData::Float(v) => v.clone(),
        other => panic!("{n}: {other:?}"),
    };
    let e = col(&all, "eccentricity");
    let regimes = |t: &store::Table| match &t.column("regime").unwrap().data {
        store::ColumnData::Exact(v) => v.clone(),
        other => panic!("{other:?}"),
    };
    let (ra, ro) = (regimes(&all), regimes(&one));
    let pointed: Vec<_> = (0..all.rows).filter(|&i| e[i] == Some(0.2)).collect();
    assert_eq!(pointed.len(), one.rows);
    for (j, &i) in pointed.iter().enumerate() {
        assert_eq!(ra[i], ro[j], "row {i}");
    }
    // The scene is drawn once per form, each on its own outline.
    let states = store::read_states(&run.join("states.parquet")).unwrap();
    let scenes: Vec<(String, f64)> = states
        .iter()
        .filter(|s| s.source == "scene")
        .map(|s| (s.shape.clone(), s.eccentricity))
        .collect();
    assert_eq!(
        scenes,
        vec![("pointed".to_string(), 0.0), ("pointed".to_string(), 0.2)]
    );
    // The figures of an arch axis: a regime map per form, their collapse curves, the
    // bifurcations against e.
    for f in ["regime-maps", "collapse-curves", "bifurcations-by-arch"] {
        assert!(run.join(format!("plots/{f}.svg")).is_file(), "{f}");
    }
    let md = std::fs::read_to_string(run.join("report.md")).unwrap();
    assert!(
        md.contains("(e = 0.2)") && md.contains("eccentricity e: grid axis"),
        "{md}"
    );
    // Captions print the eccentricity as given, not padded to four decimals.
    assert!(
        md.contains("pointed, e = 0.2") && !md.contains("e = 0.2000"),
        "{md}"
    );
    // run.json keeps the axis as given.
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(run.join("run.json")).unwrap()).unwrap();
    let axis = &info["manifest"]["grid"][0];
    assert_eq!(axis["name"], "eccentricity");
    assert_eq!(axis["values"], serde_json::json!([0.0, 0.2]));
}

#[test]
fn a_joints_axis_runs_radial_and_vertical_joints_as_their_own_studies_do() {
    let dir = scratch("form-axes-joints");
    let text = "name: j\narch: {voussoirs: 9}\ngrid:\n  joints: {values: [radial, vertical]}\n  k: {from: 1.1, to: 1.5, steps: 5}\n  mu: {from: 0.3, to: 1.2, steps: 4}\nload_cases:\n  - {name: h, kind: horizontal}\nfind: load_factor\n";
    let run = run_study(&dir, "j.yaml", text);
    let vertical = run_study(
        &dir,
        "v.yaml",
        &text
            .replace("name: j", "name: v")
            .replace("{voussoirs: 9}", "{voussoirs: 9, joints: vertical}")
            .replace("  joints: {values: [radial, vertical]}\n", ""),
    );
    let both = store::read_load_factor_cases(&run.join("results.parquet")).unwrap();
    let own = store::read_load_factor_cases(&vertical.join("results.parquet")).unwrap();
    let v: Vec<_> = both
        .iter()
        .filter(|c| c.joints == archstudy::model::JointOrientation::Vertical)
        .collect();
    assert_eq!(v.len(), own.len());
    assert!(own.iter().any(|c| c.load_factor.is_some()));
    for (a, b) in v.iter().zip(&own) {
        assert_eq!((a.k, a.mu, a.load_factor), (b.k, b.mu, b.load_factor));
    }
    // A λ map per form (the study's two arches), named by its joints.
    assert!(run.join("plots/lambda-map-a90-vertical-n9.svg").is_file());
    assert!(run.join("plots/lambda-map-a90-n9.svg").is_file());
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(run.join("run.json")).unwrap()).unwrap();
    assert_eq!(
        info["manifest"]["grid"][0]["values"],
        serde_json::json!(["radial", "vertical"])
    );
    let o = archstudy(&["check", dir.join("j.yaml").to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("joints: grid axis")
            && out.contains("axis joints: 2 values from radial to vertical"),
        "{out}"
    );
}

#[test]
fn form_axes_refuse_what_they_cannot_span() {
    let dir = scratch("form-axes-refused");
    let cases: [(&str, &[&str]); 5] = [
        (
            "name: a\ngrid:\n  eccentricity: {values: [0, 0.2]}\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            &["arch.shape", "shape: pointed"],
        ),
        (
            "name: a\narch: {shape: pointed}\ngrid:\n  eccentricity: {values: [0.2, 0.99999]}\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            &["grid.eccentricity.values", "0.99999", "[0, 0.9999]"],
        ),
        (
            "name: a\ngrid:\n  joints: {values: [radial, diagonal]}\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            &["grid.joints.values", "diagonal", "radial or vertical"],
        ),
        (
            "name: a\ngrid:\n  joints: {values: [vertical, vertical]}\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            &["grid.joints.values", "repeated"],
        ),
        // Vertical joints need α ≤ 90°, whichever axis brings them.
        (
            "name: a\narch: {half_angle_deg: 120}\ngrid:\n  joints: {values: [radial, vertical]}\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            &["vertical", "α ≤ 90°"],
        ),
    ];
    for (i, (text, said)) in cases.iter().enumerate() {
        let m = manifest(&dir, &format!("m{i}.yaml"), text);
        let o = archstudy(&["check", m.to_str().unwrap()]);
        assert_usage_error(&o, said);
        assert!(!stderr(&o).is_empty());
    }
}
