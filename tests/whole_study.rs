//! Key results range over the whole study: the smallest and largest λ_max over every arch of
//! a `half_angle_deg` axis, and a sweep over μ at one K reports the μ_c it located.

use crate::common::{run_study, scratch, solve_json};
use approx::assert_relative_eq;
use archstudy::output::RunLayout;
use archstudy::store;
use std::path::Path;

/// The value of the key-results row whose quantity starts with `label`, from report.md.
fn key_result(run: &Path, label: &str) -> Option<(String, f64)> {
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    md.lines().find_map(|l| {
        let cells: Vec<&str> = l.split('|').map(str::trim).collect();
        let q = cells.get(1)?;
        if !q.starts_with(label) {
            return None;
        }
        Some((q.to_string(), cells.get(2)?.parse().ok()?))
    })
}

/// A horizontal load on two arches: the shallower one first in plan order.
const ARCHES_STUDY: &str = "\
name: arches
find: load_factor
load_cases:
  - {name: h, kind: horizontal}
grid:
  half_angle_deg: {values: [60, 90]}
  k: {values: [1.1, 1.2, 1.3]}
  mu: {values: [0.5, inf]}
";

#[test]
fn the_extremes_of_lambda_range_over_every_arch_of_the_study() {
    let dir = scratch("whole-arches");
    let run = run_study(&dir, "arches.yaml", ARCHES_STUDY);
    let cases = store::read_load_factor_cases(&RunLayout::at(&run).results()).expect("results");
    let lambdas: Vec<(f64, f64)> = cases
        .iter()
        .filter_map(|c| Some((c.load_factor?, c.half_angle_deg)))
        .collect();
    let (lo, lo_alpha) = lambdas
        .iter()
        .copied()
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("a bounded case");
    let (hi, hi_alpha) = lambdas
        .iter()
        .copied()
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .expect("a bounded case");
    // The two ends lie on different arches, so a summary of one arch misses one of them.
    assert_ne!(lo_alpha, hi_alpha, "{lambdas:?}");
    let (q, v) = key_result(&run, "smallest λ_max of the study").expect("smallest row");
    assert_relative_eq!(v, lo, max_relative = 1e-9);
    assert!(q.contains(&format!("α = {lo_alpha}°")), "{q}");
    let (q, v) = key_result(&run, "largest λ_max of the study").expect("largest row");
    assert_relative_eq!(v, hi, max_relative = 1e-9);
    assert!(q.contains(&format!("α = {hi_alpha}°")), "{q}");
}

/// A sweep over μ at one K: the circular arch at K = 1.2 collapses by a mixed mechanism.
const MU_SWEEP_STUDY: &str = "\
name: mu-sweep
grid:
  k: {values: [1.2]}
  mu: {from: 0.2, to: 0.6, steps: 9}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

#[test]
fn a_sweep_over_mu_at_one_k_reports_the_mu_c_it_located() {
    let dir = scratch("whole-mu-sweep");
    let run = run_study(&dir, "mu-sweep.yaml", MU_SWEEP_STUDY);
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    assert!(!md.contains("located no collapse curve"), "{md}");
    let (q, v) = key_result(&run, "μ_c at K = 1.2").expect("the located μ_c");
    let solved = solve_json(&["--find", "friction", "--k", "1.2"]);
    let mu_c = solved["mu_crit"].as_f64().expect("mu_crit");
    // μ_c(1.2) = 0.3232251…, located to the study's boundary tolerance (1e-9).
    assert_relative_eq!(v, mu_c, max_relative = 1e-8);
    assert_relative_eq!(v, 0.3232251, max_relative = 1e-6);
    assert!(q.contains("mixed collapse"), "{q}");
}

/// A thickness study over μ (a range that also holds ∞) for 6 voussoirs and the continuum.
const VOUSSOIRS_THICKNESS_STUDY: &str = "\
name: voussoirs-thickness
find: thickness
grid:
  voussoirs: {values: [6, continuum]}
  mu: {from: 0.4, to: 0.6, steps: 3, also: [inf]}
";

#[test]
fn a_thickness_study_with_a_voussoir_axis_draws_k_c_of_every_arch() {
    use archstudy::plot::lines::LinePoint;
    use archstudy::report::charts::{self, Chart};
    let dir = scratch("whole-voussoirs-thickness");
    let run = run_study(&dir, "v.yaml", VOUSSOIRS_THICKNESS_STUDY);
    assert!(run.join("plots/critical-arches.png").is_file());
    let data = archstudy::report::data::load(&RunLayout::at(&run)).expect("run data");
    let figs = charts::build(&data);
    let fig = figs
        .iter()
        .find(|f| f.stem == "critical-arches")
        .expect("the per-arch figure");
    let Chart::Lines(chart) = &fig.chart else {
        panic!("not a lines chart");
    };
    let lines = &chart.panels[0].lines;
    let labels: Vec<&str> = lines.iter().map(|l| l.label.as_str()).collect();
    assert_eq!(labels, ["N = 6", "continuum"]);
    // The lines hold the finite μ of the range; at μ = 0.6 the continuum's K_c is the
    // rotational K_c of the semicircle (the rotational/mixed bifurcation is at μ = 0.395).
    let at = |pts: &[LinePoint], x: f64| pts.iter().find(|p| p.x == x).map(|p| p.y);
    let continuum = at(&lines[1].points, 0.6).expect("μ = 0.6");
    assert_relative_eq!(
        continuum,
        crate::common::reference::K_C,
        max_relative = 1e-9
    );
    // Six voussoirs stand thinner than the continuum (K_c(N) ≤ K_c of the continuum).
    let six = at(&lines[0].points, 0.6).expect("μ = 0.6");
    assert!(six < continuum, "{six} {continuum}");
    let mus: Vec<f64> = lines[1].points.iter().map(|p| p.x).collect();
    assert_eq!(mus, [0.4, 0.5, 0.6]);
}
