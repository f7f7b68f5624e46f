//! Boundary location on whole grids: manifest → plan → engine → locate, checked against the
//! reference values of docs/mechanics.md §3 and against the critical-value analyses.

use super::*;
use crate::analysis::symmetric;
use crate::analysis::{Face, MechanismKind as M, Regime as R};
use crate::engine;
use crate::manifest;
use crate::model::{Arch, Friction};
use std::path::Path;

const K_C: f64 = 1.113581813339;
const MU_ROT: f64 = 0.395265252140;
const MU_MIN: f64 = 0.309215444330;
const K_BIF: f64 = 1.220507754643;

fn run(yaml: &str) -> (Plan, Located) {
    let m = manifest::parse(yaml, Path::new("test.yaml")).expect("valid manifest");
    let plan = crate::plan::build(m).expect("small plan");
    let results = engine::run(&plan, &crate::progress::Silent);
    let located = locate(&plan, &results);
    (plan, located)
}

/// The seed study's ranges with n × n points.
fn seed_like(n: usize) -> String {
    format!(
        "name: t\ngrid:\n  k: {{from: 1.05, to: 1.5, steps: {n}}}\n  mu: {{from: 0.2, to: 0.8, steps: {n}}}\n"
    )
}

fn semi(k: f64) -> Arch {
    Arch::semicircular(k).unwrap()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

/// The two bifurcations of the paper (Figs. 6, 7), with their coexisting mechanisms.
fn assert_paper_bifurcations(l: &Located) {
    let b = &l.bifurcations;
    assert_eq!(b.len(), 2, "{b:#?}");
    let (rm, ms) = (&b[0], &b[1]);
    assert_eq!((rm.mechanism_a, rm.mechanism_b), (M::Mixed, M::Rotational));
    assert!(
        close(rm.k, K_C, 1e-8) && close(rm.mu, MU_ROT, 1e-8),
        "{rm:?}"
    );
    assert!(close(rm.state.thrust_over_half_weight, MU_ROT, 1e-8));
    // Crown extrados, haunches (54.48°) at the intrados, springings at the extrados; the
    // springings also slide.
    let h = &rm.state.mechanism.hinges;
    assert_eq!(h.len(), 5, "{h:?}");
    assert!(
        h.iter()
            .any(|h| h.angle_deg == 0.0 && h.face == Face::Extrados)
    );
    assert!(
        h.iter()
            .any(|h| close(h.angle_deg, 54.48397403, 1e-6) && h.face == Face::Intrados)
    );
    let s: Vec<f64> = rm
        .state
        .mechanism
        .sliding_joints
        .iter()
        .map(|j| j.angle_deg)
        .collect();
    assert_eq!(s, vec![-90.0, 90.0]);

    assert_eq!((ms.mechanism_a, ms.mechanism_b), (M::Sliding, M::Mixed));
    assert!(
        close(ms.k, K_BIF, 1e-8) && close(ms.mu, MU_MIN, 1e-8),
        "{ms:?}"
    );
    // Sliding at 29° and 90° (paper §5) with the hinges of the mixed mechanism.
    let s: Vec<f64> = ms
        .state
        .mechanism
        .sliding_joints
        .iter()
        .map(|j| j.angle_deg)
        .collect();
    assert_eq!(s.len(), 4, "{s:?}");
    assert!(
        close(s[2], 28.63619468, 1e-6) && close(s[3], 90.0, 1e-9),
        "{s:?}"
    );
    assert!(!ms.state.mechanism.hinges.is_empty());
}

#[test]
fn seed_style_grid_has_the_two_bifurcations_of_the_paper() {
    let (_, l) = run(&seed_like(101));
    assert_paper_bifurcations(&l);
}

#[test]
fn collapse_curve_points_lie_on_the_exact_curve() {
    let (_, l) = run(&seed_like(101));
    let curve: Vec<&BoundaryPoint> = l
        .boundaries
        .iter()
        .filter(|p| p.on_collapse_curve)
        .collect();
    assert!(curve.len() > 150, "{}", curve.len());
    let mut seen = [0usize; 3];
    for p in curve {
        let m = p
            .mechanism
            .unwrap_or_else(|| panic!("no mechanism at {p:?}"));
        assert!(p.regime_low == R::Stable || p.regime_high == R::Stable);
        match m {
            M::Rotational => {
                seen[0] += 1;
                assert_eq!(p.axis, EdgeAxis::K);
                assert!(close(p.k, K_C, 1e-9), "{p:?}");
            }
            M::Mixed => {
                seen[1] += 1;
                // K_c(μ) at the located μ is the grid K of a μ-edge, the located K of a K-edge.
                let kc = symmetric::thickness(&semi(1.3), Friction::new(p.mu).unwrap());
                let kc = kc.found().unwrap().k;
                match p.axis {
                    EdgeAxis::K => assert!(close(p.k, kc, 1e-9), "{p:?}: K_c {kc}"),
                    EdgeAxis::Mu => {
                        let mc = symmetric::friction(&semi(p.k)).found().unwrap().mu;
                        assert!(close(p.mu, mc, 1e-9), "{p:?}: μ_c {mc}");
                        assert!(close(p.k, kc, 1e-9), "{p:?}: K_c {kc}");
                    }
                }
                assert!(p.mu > MU_MIN && p.mu < MU_ROT && p.k > K_C && p.k < K_BIF);
            }
            M::Sliding => {
                seen[2] += 1;
                // The sliding segment: the line μ = μ_min for K ≥ 1.2205, H^s a single thrust.
                assert_eq!(p.axis, EdgeAxis::Mu);
                assert!(close(p.mu, MU_MIN, 1e-9) && p.k >= K_BIF, "{p:?}");
                assert_eq!((p.regime_low, p.regime_high), (R::Sliding, R::Stable));
                let s = p.state.as_ref().unwrap();
                assert!(s.mechanism.hinges.is_empty());
                assert_eq!(s.mechanism.sliding_joints.len(), 4);
                assert!(close(s.thrust_over_half_weight, MU_MIN, 1e-9));
            }
        }
    }
    assert!(seen.iter().all(|&n| n > 10), "{seen:?}");
}

#[test]
fn coarse_and_fine_grids_agree_and_cost_grows_with_the_side() {
    let mut counts = Vec::new();
    let mut found = Vec::new();
    for n in [11, 41, 101, 401] {
        let (_, l) = run(&seed_like(n));
        assert_paper_bifurcations(&l);
        counts.push((n, l.refinement_analyses));
        found.push(l.bifurcations);
    }
    for f in &found[1..] {
        for (a, b) in f.iter().zip(&found[0]) {
            assert!(close(a.k, b.k, 1e-8) && close(a.mu, b.mu, 1e-8));
        }
    }
    // Measured (debug and release alike): 11 → 87, 41 → 239, 101 → 530, 401 → 2026.
    eprintln!("refinement analyses by grid side: {counts:?}");
    let per_side = |i: usize| counts[i].1 as f64 / counts[i].0 as f64;
    assert!(per_side(3) < 1.2 * per_side(2), "{counts:?}");
    assert!(counts[3].1 < 3000, "{counts:?}");
}

fn yaml_values(name: &str, v: &[f64]) -> String {
    let list: Vec<String> = v
        .iter()
        .map(|x| {
            if x.is_infinite() {
                "inf".into()
            } else {
                format!("{x:?}")
            }
        })
        .collect();
    format!("  {name}: {{values: [{}]}}\n", list.join(", "))
}

#[test]
fn grid_points_on_a_boundary_are_reported_once() {
    // K_c and μ_min exactly on the grid: the regime there is the limit (admissible) one.
    let kc = symmetric::thickness(&semi(1.3), Friction::INFINITE)
        .found()
        .unwrap()
        .k;
    let mu_min = symmetric::sliding_threshold(&semi(1.3)).found().unwrap().mu;
    let yaml = format!(
        "name: t\ngrid:\n{}{}",
        yaml_values("k", &[1.05, kc, 1.3]),
        yaml_values("mu", &[0.2, mu_min, 0.5])
    );
    let (_, l) = run(&yaml);
    let got: Vec<(EdgeAxis, R, R)> = l
        .boundaries
        .iter()
        .map(|p| (p.axis, p.regime_low, p.regime_high))
        .collect();
    use EdgeAxis::{K, Mu};
    assert_eq!(
        got,
        vec![
            (K, R::None, R::Sliding),
            (K, R::Rotational, R::Mixed),
            (K, R::Mixed, R::Stable),
            (K, R::Rotational, R::Stable),
            (Mu, R::None, R::Rotational),
            (Mu, R::Sliding, R::Mixed),
            (Mu, R::Mixed, R::Stable),
            (Mu, R::Sliding, R::Stable),
        ],
        "{:#?}",
        l.boundaries
    );
    let b = &l.boundaries;
    for p in [&b[0], &b[1], &b[3]] {
        assert!(close(p.k, kc, 1e-9), "{p:?}");
    }
    for p in [&b[4], &b[5], &b[7]] {
        assert!(close(p.mu, mu_min, 1e-9), "{p:?}");
    }
    // The mixed/stable crossing of the μ_min row is the mixed/sliding bifurcation's K; that
    // of the K_c column is the rotational/mixed bifurcation's μ.
    assert!(close(b[2].k, K_BIF, 1e-8) && close(b[6].mu, MU_ROT, 1e-8));
    assert_eq!(b[7].mechanism, Some(M::Sliding));
}

#[test]
fn boundaries_meeting_the_grid_edge_keep_only_the_bifurcations_inside() {
    // The collapse curve leaves through K = 1.2 before the sliding segment starts.
    let (_, l) = run(
        "name: t\ngrid:\n  k: {from: 1.05, to: 1.2, steps: 16}\n  mu: {from: 0.2, to: 0.8, steps: 25}\n",
    );
    assert_eq!(l.bifurcations.len(), 1);
    assert_eq!(l.bifurcations[0].mechanism_b, M::Rotational);
    assert!(close(l.bifurcations[0].mu, MU_ROT, 1e-8));
    // ... and through μ = 0.39 below the rotational segment.
    let (_, l) = run(
        "name: t\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 16}\n  mu: {from: 0.25, to: 0.39, steps: 15}\n",
    );
    assert_eq!(l.bifurcations.len(), 1);
    assert_eq!(l.bifurcations[0].mechanism_a, M::Sliding);
    assert!(close(l.bifurcations[0].k, K_BIF, 1e-8));
    // Only the rotational segment: boundary points, no bifurcation.
    let (_, l) = run(
        "name: t\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 10}\n  mu: {from: 0.5, to: 0.8, steps: 4}\n",
    );
    assert!(l.bifurcations.is_empty());
    assert_eq!(l.boundaries.len(), 4);
    assert!(
        l.boundaries
            .iter()
            .all(|p| p.mechanism == Some(M::Rotational))
    );
}

#[test]
fn a_single_k_or_mu_value_gives_one_sided_boundaries() {
    let (_, l) =
        run("name: t\ngrid:\n  k: {values: [1.15]}\n  mu: {from: 0.2, to: 0.8, steps: 7}\n");
    let got: Vec<_> = l
        .boundaries
        .iter()
        .map(|p| (p.axis, p.regime_low, p.regime_high))
        .collect();
    assert_eq!(
        got,
        vec![
            (EdgeAxis::Mu, R::Sliding, R::Mixed),
            (EdgeAxis::Mu, R::Mixed, R::Stable)
        ]
    );
    let mc = symmetric::friction(&semi(1.15)).found().unwrap().mu;
    assert!(close(l.boundaries[1].mu, mc, 1e-9));
    assert!(l.bifurcations.is_empty());

    let (_, l) =
        run("name: t\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 7}\n  mu: {values: [0.35]}\n");
    let got: Vec<_> = l
        .boundaries
        .iter()
        .map(|p| (p.axis, p.regime_low, p.regime_high))
        .collect();
    assert_eq!(
        got,
        vec![
            (EdgeAxis::K, R::Rotational, R::Mixed),
            (EdgeAxis::K, R::Mixed, R::Stable)
        ]
    );
    let kc = symmetric::thickness(&semi(1.3), Friction::new(0.35).unwrap());
    assert!(close(l.boundaries[1].k, kc.found().unwrap().k, 1e-9));
    assert!(l.bifurcations.is_empty());

    let (_, l) = run("name: t\ngrid:\n  k: {values: [1.15]}\n  mu: {values: [0.35]}\n");
    assert_eq!(l, Located::default());
}

#[test]
fn infinite_friction_rows_and_edges_are_refined() {
    let (_, l) = run(
        "name: t\ngrid:\n  k: {from: 1.05, to: 1.3, steps: 11}\n  mu: {values: [0.3, 0.35, inf]}\n",
    );
    let inf_row: Vec<_> = l.boundaries.iter().filter(|p| p.mu.is_infinite()).collect();
    assert_eq!(inf_row.len(), 1);
    assert!(close(inf_row[0].k, K_C, 1e-9) && inf_row[0].mechanism == Some(M::Rotational));
    // μ-edges from 0.35 to ∞ cross the mixed part of the curve at μ_c(K).
    let to_inf: Vec<_> = l
        .boundaries
        .iter()
        .filter(|p| p.axis == EdgeAxis::Mu && p.mu > 0.35)
        .collect();
    assert!(!to_inf.is_empty());
    for p in to_inf {
        let mc = symmetric::friction(&semi(p.k)).found().unwrap().mu;
        assert!(close(p.mu, mc, 1e-9), "{p:?}: μ_c {mc}");
    }
    assert_eq!(l.bifurcations.len(), 2);
}

/// An arch other than the paper's gets its own bifurcations: the rotational/mixed one where
/// the thrust of the rotational collapse state, h_r, reaches the upper end of H^s, which is
/// W_half/tan(α − φ) at the springing (eq. 4b is decreasing in θ), and the mixed/sliding one
/// at the collapse thickness for μ_min.
fn assert_own_bifurcations(arch_yaml: &str, arch: Arch, k_range: (f64, f64), mu_range: (f64, f64)) {
    let rot = symmetric::thickness(&arch, Friction::INFINITE);
    let rot = rot.found().unwrap();
    let mu_rm = (arch.half_angle - (1.0 / rot.thrust_over_half_weight).atan()).tan();
    let mu_min = symmetric::sliding_threshold(&arch).found().unwrap().mu;
    let k_ms = symmetric::thickness(&arch, Friction::new(mu_min).unwrap());
    let k_ms = k_ms.found().unwrap().k;
    let yaml = format!(
        "name: t\narch:\n{arch_yaml}grid:\n  k: {{from: {}, to: {}, steps: 21}}\n  mu: {{from: {}, to: {}, steps: 21}}\n",
        k_range.0, k_range.1, mu_range.0, mu_range.1
    );
    let (_, l) = run(&yaml);
    let b = &l.bifurcations;
    assert_eq!(b.len(), 2, "{arch_yaml}: {b:#?}");
    assert!(
        close(b[0].k, rot.k, 1e-8) && close(b[0].mu, mu_rm, 1e-8),
        "{arch_yaml}: {:?} vs μ {mu_rm}",
        b[0]
    );
    assert_eq!(b[0].mechanism_b, M::Rotational);
    assert!(
        close(b[1].k, k_ms, 1e-8) && close(b[1].mu, mu_min, 1e-8),
        "{arch_yaml}: {:?}",
        b[1]
    );
    assert_eq!(b[1].mechanism_a, M::Sliding);
    // Not the paper's numbers (μ_min depends on α and the joints only, not on the weight).
    assert!(!close(b[0].k, K_C, 1e-6) && !close(b[1].k, K_BIF, 1e-6));
    for p in l.boundaries.iter().filter(|p| p.on_collapse_curve) {
        assert!(p.mechanism.is_some(), "{p:?}");
    }
}

#[test]
fn other_arches_get_their_own_bifurcations() {
    use crate::model::{Discretisation, WeightModel};
    // Segmental, α = 60°: K_c = 1.0231, μ = 0.1447; μ_min = 0.0944, K = 1.0502.
    let a = Arch::new(1.1, 60.0, WeightModel::Annular, Discretisation::Continuum).unwrap();
    assert_own_bifurcations("  half_angle_deg: 60\n", a, (1.005, 1.1), (0.05, 0.3));
    // 16 voussoirs (a joint at the crown): slightly below the continuum values.
    let a = Arch::new(
        1.3,
        90.0,
        WeightModel::Annular,
        Discretisation::Voussoirs(16),
    )
    .unwrap();
    assert_own_bifurcations("  voussoirs: 16\n", a, (1.05, 1.5), (0.2, 0.8));
    // Centreline weight.
    let a = Arch::new(
        1.3,
        90.0,
        WeightModel::Centreline,
        Discretisation::Continuum,
    )
    .unwrap();
    assert_own_bifurcations("  weight: centreline\n", a, (1.05, 1.5), (0.2, 0.8));
}

#[test]
fn every_value_of_another_axis_is_its_own_grid() {
    let (_, l) = run(
        "name: t\ngrid:\n  half_angle_deg: {values: [60, 90]}\n  k: {from: 1.005, to: 1.5, steps: 31}\n  mu: {from: 0.05, to: 0.8, steps: 31}\n",
    );
    let angles: Vec<f64> = l
        .bifurcations
        .iter()
        .map(|b| b.half_angle_deg.round())
        .collect();
    assert_eq!(angles, vec![60.0, 60.0, 90.0, 90.0]);
    assert!(close(l.bifurcations[2].k, K_C, 1e-8));
}

#[test]
fn thickness_and_friction_sweeps_report_their_bifurcations() {
    for yaml in [
        "name: t\nfind: thickness\ngrid:\n  mu: {from: 0.2, to: 0.8, steps: 13}\n",
        "name: t\nfind: friction\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 13}\n",
    ] {
        let (_, l) = run(yaml);
        assert!(l.boundaries.is_empty());
        assert_paper_bifurcations(&l);
        assert!(l.refinement_analyses > 0);
    }
    // A μ sweep above μ_min sees only the rotational/mixed change.
    let (_, l) = run("name: t\nfind: thickness\ngrid:\n  mu: {values: [0.35, 0.45, inf]}\n");
    assert_eq!(l.bifurcations.len(), 1);
    assert!(close(l.bifurcations[0].mu, MU_ROT, 1e-8));
    let (_, l) = run("name: t\nfind: thrust\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n");
    assert_eq!(l, Located::default());
}
