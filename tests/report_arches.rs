//! Every drawn state is drawn on the arch of its own case: with a `half_angle_deg` or a
//! `voussoirs` axis, each bifurcation and scene of states.parquet carries the half-angle and
//! voussoir count of its group, its line of thrust ends at that arch's springings, and its
//! figure names them.

use crate::common::{run_study, scratch};
use archstudy::output::RunLayout;
use archstudy::store::{self, StateRow};
use std::path::Path;

const HALF_ANGLE_STUDY: &str = "\
name: segmental
grid:
  half_angle_deg: {values: [70, 90]}
  k: {from: 1.02, to: 1.3, steps: 8}
  mu: {from: 0.2, to: 0.8, steps: 7}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
scenes:
  - {k: 1.2, mu: 0.5}
";

const VOUSSOIRS_STUDY: &str = "\
name: discrete
grid:
  voussoirs: {values: [7, 12]}
  k: {from: 1.05, to: 1.4, steps: 8}
  mu: {from: 0.2, to: 0.8, steps: 7}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
scenes:
  - {k: 1.3, mu: 0.6}
";

/// The angle from the crown, degrees, of a point (x, y) over r of a circular arch.
fn angle_deg((x, y): (f64, f64)) -> f64 {
    x.atan2(y).to_degrees()
}

/// The states of a run, with its bifurcations and their arch groups.
fn stored(run: &Path) -> (Vec<StateRow>, Vec<store::BifurcationGroup>) {
    let layout = RunLayout::at(run);
    let states = store::read_states(&layout.states()).expect("states.parquet");
    let groups = store::read_bifurcation_groups(&layout.bifurcations()).expect("bifurcations");
    (states, groups)
}

/// The line of thrust of a state, from curves.parquet.
fn line_of_thrust(run: &Path, id: &str) -> Vec<(f64, f64)> {
    let curves = store::read_curves(&RunLayout::at(run).curves()).expect("curves.parquet");
    curves
        .iter()
        .filter(|c| c.figure == format!("line_of_thrust/{id}") && c.series == "line_of_thrust")
        .map(|c| (c.x, c.y))
        .collect()
}

#[test]
fn bifurcation_and_scene_states_carry_their_own_half_angle() {
    let dir = scratch("arches-half-angle");
    let run = run_study(&dir, "segmental.yaml", HALF_ANGLE_STUDY);
    let (states, groups) = stored(&run);
    let bifs: Vec<&StateRow> = states
        .iter()
        .filter(|s| s.source == "bifurcation")
        .collect();
    assert_eq!(bifs.len(), groups.len(), "one drawn state per bifurcation");
    let alphas: Vec<f64> = groups.iter().filter_map(|g| g.half_angle_deg).collect();
    assert!(
        alphas.contains(&70.0) && alphas.contains(&90.0),
        "{alphas:?}"
    );
    for (s, g) in bifs.iter().zip(&groups) {
        let alpha = g.half_angle_deg.expect("half_angle_deg stored");
        assert_eq!(s.half_angle_deg, alpha, "{}", s.state_id);
        assert_eq!(s.voussoirs, None);
        assert_eq!(
            (s.shape.as_str(), s.load.as_str()),
            ("circular", "self_weight")
        );
        let line = line_of_thrust(&run, &s.state_id);
        let (first, last) = (line.first().copied(), line.last().copied());
        let (first, last) = (first.expect("a line"), last.expect("a line"));
        approx::assert_abs_diff_eq!(angle_deg(first), -alpha, epsilon = 1e-6);
        approx::assert_abs_diff_eq!(angle_deg(last), alpha, epsilon = 1e-6);
    }
    for (suffix, alpha) in [("-a70", 70.0), ("-a90", 90.0)] {
        let s = states
            .iter()
            .find(|s| s.state_id == format!("scene-1{suffix}"))
            .expect("one scene state per half-angle");
        assert_eq!(s.half_angle_deg, alpha);
        let line = line_of_thrust(&run, &s.state_id);
        approx::assert_abs_diff_eq!(angle_deg(line[0]), -alpha, epsilon = 1e-6);
    }
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    // Every figure of one arch names it, the semicircle (α = 90°, the default) included.
    let one_arch: Vec<&str> = md
        .lines()
        .filter(|l| l.starts_with("### Figure") && !l.contains("by half-angle"))
        .filter(|l| l.contains("bifurcation (") || l.contains("bifurcation") || l.contains("scene"))
        .filter(|l| !l.contains("against the half-angle"))
        .collect();
    assert!(one_arch.len() >= 8, "{one_arch:#?}");
    for l in &one_arch {
        assert!(l.contains("(α = 70°)") || l.contains("(α = 90°)"), "{l}");
    }
    assert!(one_arch.iter().filter(|l| l.contains("α = 90°")).count() >= 4);
}

#[test]
fn bifurcation_and_scene_states_carry_their_own_voussoir_count() {
    let dir = scratch("arches-voussoirs");
    let run = run_study(&dir, "discrete.yaml", VOUSSOIRS_STUDY);
    let (states, groups) = stored(&run);
    let bifs: Vec<&StateRow> = states
        .iter()
        .filter(|s| s.source == "bifurcation")
        .collect();
    assert_eq!(bifs.len(), groups.len(), "one drawn state per bifurcation");
    assert!(!bifs.is_empty(), "the grid crosses a bifurcation");
    for (s, g) in bifs.iter().zip(&groups) {
        let n = g.voussoirs.expect("voussoirs stored");
        assert!(n.is_some(), "discrete arches only");
        assert_eq!(s.voussoirs, n, "{}", s.state_id);
        assert_eq!(s.half_angle_deg, 90.0);
    }
    for (suffix, n) in [("-n7", 7), ("-n12", 12)] {
        let s = states
            .iter()
            .find(|s| s.state_id == format!("scene-1{suffix}"))
            .expect("one scene state per voussoir count");
        assert_eq!(s.voussoirs, Some(n));
    }
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    assert!(md.contains("N = 7 voussoirs") && md.contains("N = 12 voussoirs"));
}

/// A horizontal-load map of `nk` × `nmu` points.
fn load_factor_map(nk: usize, nmu: usize) -> String {
    format!(
        "name: lambda-map
grid:
  k: {{from: 1.1, to: 1.6, steps: {nk}}}
  mu: {{from: 0.3, to: 1.0, steps: {nmu}}}
load_cases:
  - {{name: horizontal, kind: horizontal}}
find: load_factor
"
    )
}

/// The rows of the key-results table of report.md.
fn key_result_rows(md: &str) -> Vec<String> {
    md.split("## Key results")
        .nth(1)
        .and_then(|s| s.split("\n## ").next())
        .map(|s| {
            s.lines()
                .filter(|l| l.starts_with("| ") && !l.starts_with("| quantity"))
                .map(str::to_string)
                .collect()
        })
        .unwrap_or_default()
}

fn assert_short_load_factor_report(nk: usize, nmu: usize) {
    let dir = scratch(&format!("arches-lambda-{nk}x{nmu}"));
    let run = run_study(&dir, "lambda.yaml", &load_factor_map(nk, nmu));
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    let rows = key_result_rows(&md);
    assert!(
        (8..=40).contains(&rows.len()),
        "{} key-result rows",
        rows.len()
    );
    assert!(rows[0].contains("smallest λ_max"), "{}", rows[0]);
    // Every λ row names K and μ; every change of mechanism names where it was located.
    for r in &rows {
        assert!(r.contains("K") && r.contains("μ"), "{r}");
    }
    let bifurcations = store::read_bifurcations(&RunLayout::at(&run).bifurcations())
        .expect("bifurcations.parquet");
    assert!(
        bifurcations.len() > 6,
        "the map crosses several mechanism changes"
    );
    let lines = md.lines().count();
    assert!(lines < 300, "report.md has {lines} lines");
    assert!(
        std::fs::metadata(run.join("plots/load-factor.png")).is_ok(),
        "a load_factor study draws λ against K and μ"
    );
}

#[test]
fn key_results_stay_short_on_a_load_factor_map() {
    assert_short_load_factor_report(41, 29);
}

/// The size the report must stay short at: 26,931 cases, about half a minute of one core in
/// the test build.
#[test]
fn key_results_stay_short_on_a_191_by_141_load_factor_map() {
    assert_short_load_factor_report(191, 141);
}
