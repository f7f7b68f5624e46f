//! The report says in words what a reader would otherwise take for a defect: cases where no
//! requested μ lets the arch stand, load positions with an unbounded λ, and the sliver a
//! point load punches through the continuum, and sliding on the edges of a pointed arch's crown
//! wedge.

use crate::common::{run_study, scratch};
use std::path::Path;

fn report(run: &Path) -> String {
    std::fs::read_to_string(run.join("report.md")).expect("report.md")
}

#[test]
fn cases_where_no_requested_mu_stands_are_named() {
    let dir = scratch("notes-never-stands");
    let run = run_study(
        &dir,
        "vj.yaml",
        "name: vj\narch:\n  joints: vertical\n  voussoirs: 7\nfind: load_factor\nload_cases:\n  - {name: h, kind: horizontal}\ngrid:\n  k: {from: 1.1, to: 1.5, steps: 5}\n  mu: {values: [0.3, 0.5, 0.7, 0.9]}\n",
    );
    let md = report(&run);
    // Vertical joints need far more friction: at K = 1.4 and 1.5 only μ = 0.9 stands.
    assert!(
        md.contains("No requested μ stands in 18 of 20 cases"),
        "{md}"
    );
    assert!(
        md.contains("At K = 1.1, 1.2, 1.3 not one of the requested μ (up to 0.9) stands"),
        "{md}"
    );
    // And the friction it would need (the friction find of seven voussoirs with vertical
    // joints under self-weight): none at K = 1.1, μ_c = 1.2564266 at 1.2, 1.0229946 at 1.3.
    assert!(md.contains("K = 1.1: no μ lets it stand"), "{md}");
    assert!(md.contains("K = 1.2: μ_c = 1.256"), "{md}");
    assert!(md.contains("K = 1.3: μ_c = 1.023"), "{md}");
}

#[test]
fn a_friction_study_says_which_thicknesses_stand_at_no_mu() {
    let dir = scratch("notes-never-stands-friction");
    let run = run_study(
        &dir,
        "fr.yaml",
        "name: fr\nfind: friction\ngrid:\n  k: {values: [1.05, 1.1, 1.2, 1.3]}\n",
    );
    let md = report(&run);
    // K_c = 1.1136 at μ = ∞: the two thinner arches stand at no μ; a friction find has no μ
    // of its own to blame.
    assert!(md.contains("The arch never stands in 2 of 4 cases"), "{md}");
    assert!(
        md.contains("a friction case stands at no μ, however large"),
        "{md}"
    );
    assert!(!md.contains("No requested μ"), "{md}");
}

#[test]
fn positions_with_an_unbounded_lambda_are_named() {
    let dir = scratch("notes-unbounded");
    let run = run_study(
        &dir,
        "unb.yaml",
        "name: unb\nfind: load_factor\nload_cases:\n  - {name: p, kind: point}\ngrid:\n  at_deg: {values: [-90, -60, -30]}\n  k: {values: [1.2, 1.3]}\n  mu: {values: [0.5, inf]}\n",
    );
    let md = report(&run);
    // Over the springing at every K and μ, and at −60° without sliding (μ = ∞).
    assert!(md.contains("λ is unbounded in 6 cases"), "{md}");
    assert!(
        md.contains("Point load positions with an unbounded λ: -90°, -60°."),
        "{md}"
    );
}

#[test]
fn a_sliver_punched_by_a_point_load_on_the_continuum_is_named() {
    let dir = scratch("notes-sliver");
    let run = run_study(
        &dir,
        "sliver.yaml",
        "name: sliver\narch:\n  half_angle_deg: 60\nfind: load_factor\nload_cases:\n  - {name: p, kind: point, at_x: 0.25}\ngrid:\n  k: {values: [1.1, 1.2, 1.3]}\n  mu: {values: [0.3, 0.5, inf]}\n",
    );
    let md = report(&run);
    // K = 1.2 and 1.3 at μ = 0.3, and K = 1.3 at μ = 0.5, slide on both sides of the load;
    // λ_max = 0.4894 at μ = 0.3 whatever K.
    assert!(
        md.contains(
            "punches a sliver of zero width through the arch in 3 of the cases drawn \
             (results.parquet row 3 first: K = 1.2, μ = 0.3, load at x/L = 0.25, \
             λ_max = 0.4894)"
        ),
        "{md}"
    );
}

#[test]
fn sliding_on_the_edges_of_a_pointed_arch_s_crown_wedge_is_named() {
    let dir = scratch("notes-crown-wedge");
    let run = run_study(
        &dir,
        "p5.yaml",
        "name: p5\narch: {shape: pointed, eccentricity: 0.5}\ngrid:\n  k: {from: 1.05, to: 1.3, steps: 26}\n  mu: {from: 0.1, to: 0.6, steps: 26}\n",
    );
    let md = report(&run);
    // The mixed/sliding bifurcation of the equilateral arch lies at K = 1.1420: ψ₁ =
    // asin(0.5 · 2.1420 / 2) = 32.378°, where its mechanism slides.
    let psi1 = (0.5f64 * (1.0 + 1.142) / 2.0).asin().to_degrees();
    assert!((psi1 - 32.378).abs() < 0.01);
    assert!(
        md.contains("In 2 of the 2 mechanisms drawn the arch slides at ±ψ₁")
            && md.contains("ψ₁ = 32.378")
            && md.contains("edges of the crown wedge"),
        "{md}"
    );
    // The friction find at K = 1.2 slides outward at ±ψ₁ = asin(0.55) = 33.367°.
    let v = crate::common::solve_json(&[
        "--find",
        "friction",
        "--shape",
        "pointed",
        "--eccentricity",
        "0.5",
        "--k",
        "1.2",
    ]);
    let angles: Vec<f64> = v["sliding_joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["angle_deg"].as_f64().unwrap())
        .collect();
    let edge = 0.55f64.asin().to_degrees();
    assert!(
        angles.iter().any(|a| (a - edge).abs() < 1e-9),
        "{angles:?} against ψ₁ = {edge}"
    );
    // A pointed arch whose mechanisms slide elsewhere says nothing of the kind.
    let run = run_study(
        &dir,
        "p2.yaml",
        "name: p2\narch: {shape: pointed, eccentricity: 0.2}\ngrid:\n  k: {from: 1.05, to: 1.4, steps: 15}\n  mu: {from: 0.15, to: 0.6, steps: 10}\n",
    );
    assert!(!report(&run).contains("crown wedge"));
}
