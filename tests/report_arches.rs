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
        .filter(|c| c.figure == format!("line_of_thrust/{id}"))
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
    assert!(md.contains("α = 70°"), "the figures name the half-angle");
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
