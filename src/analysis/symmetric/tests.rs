//! Tests of the symmetric route against the paper's reference values.

use super::domains::{concave_peak, discrete_rotational_peak};
use super::*;
use crate::analysis::types::Face;
use crate::model::{Discretisation, WeightModel};
use approx::{abs_diff_eq, assert_abs_diff_eq};

const K_C: f64 = 1.113581813339;
const MU_ROT: f64 = 0.395265252140;
const MU_MIN: f64 = 0.309215444330;
const K_BIF: f64 = 1.220507754643;

fn semi(k: f64) -> Arch {
    Arch::semicircular(k).unwrap()
}

#[test]
fn rotational_collapse_thickness_matches_reference() {
    let c = thickness(&semi(1.5), Friction::INFINITE);
    let s = c.found().expect("K_c exists");
    assert!(abs_diff_eq!(s.k, K_C, epsilon = 1e-9), "K_c = {}", s.k);
    assert_abs_diff_eq!(
        crate::model::t_over_r_from_k(s.k),
        0.107478038107,
        epsilon = 1e-9
    );
    assert_abs_diff_eq!(s.thrust_over_half_weight, MU_ROT, epsilon = 1e-9);
    assert_eq!(s.mechanism.kind, crate::analysis::MechanismKind::Rotational);
    let haunch = s
        .mechanism
        .hinges
        .iter()
        .find(|h| h.face == Face::Intrados)
        .unwrap();
    assert!(
        abs_diff_eq!(haunch.angle_deg.abs(), 54.48397403, epsilon = 1e-6),
        "{haunch:?}"
    );
    // Crown extrados, two haunches, two springings.
    assert_eq!(s.mechanism.hinges.len(), 5, "{:?}", s.mechanism.hinges);
}

#[test]
fn sliding_threshold_matches_reference() {
    let c = sliding_threshold(&semi(1.3));
    let s = c.found().unwrap();
    assert!(
        abs_diff_eq!(s.mu, MU_MIN, epsilon = 1e-9),
        "μ_min = {}",
        s.mu
    );
    let angles: Vec<f64> = s
        .mechanism
        .sliding_joints
        .iter()
        .map(|j| j.angle_deg)
        .collect();
    assert_eq!(angles.len(), 4);
    assert!(
        abs_diff_eq!(angles[2], 28.63619468, epsilon = 1e-6),
        "{angles:?}"
    );
    assert_abs_diff_eq!(angles[3], 90.0, epsilon = 1e-9);
}

#[test]
fn bifurcations_match_reference() {
    // Rotational/mixed: μ_c at K_c equals the thrust there.
    let kc = thickness(&semi(1.5), Friction::INFINITE).found().unwrap().k;
    let f = friction(&semi(kc));
    let s = f.found().unwrap();
    assert!(abs_diff_eq!(s.mu, MU_ROT, epsilon = 1e-9), "μ = {}", s.mu);
    // Mixed/sliding: K_c at μ_min.
    let mu_min = sliding_threshold(&semi(1.3)).found().unwrap().mu;
    let t = thickness(&semi(1.5), Friction::new(mu_min).unwrap());
    let s = t.found().unwrap();
    assert!(abs_diff_eq!(s.k, K_BIF, epsilon = 1e-8), "K = {}", s.k);
}

#[test]
fn friction_on_the_sliding_segment_is_the_sliding_mechanism() {
    // Beyond the mixed/sliding bifurcation μ_c = μ_min, where H^s is a single thrust
    // (μ_min·W_half at the springings) inside H^r: no hinge, four sliding joints.
    let s = friction(&semi(1.3)).found().cloned().unwrap();
    assert!(abs_diff_eq!(s.mu, MU_MIN, epsilon = 1e-9), "μ = {}", s.mu);
    assert_eq!(s.mechanism.kind, crate::analysis::MechanismKind::Sliding);
    assert_abs_diff_eq!(s.thrust_over_half_weight, MU_MIN, epsilon = 1e-9);
    assert!(s.mechanism.hinges.is_empty(), "{:?}", s.mechanism.hinges);
    let angles: Vec<f64> = s
        .mechanism
        .sliding_joints
        .iter()
        .map(|j| j.angle_deg)
        .collect();
    assert_eq!(angles.len(), 4, "{angles:?}");
    assert_abs_diff_eq!(angles[2], 28.63619468, epsilon = 1e-6);
    assert_abs_diff_eq!(angles[3], 90.0, epsilon = 1e-9);
}

#[test]
fn closed_form_peak_matches_bisection_on_the_supergradient() {
    for alpha in [20.0, 45.0, 90.0, 120.0, 160.0] {
        for k in [1.05, 1.2, 1.6, 3.0] {
            for w in [WeightModel::Annular, WeightModel::Centreline] {
                let a = Arch::new(k, alpha, w, Discretisation::Continuum).unwrap();
                let sym = SymmetricCircular::new(&a);
                let (h1, g1) = rotational_peak(&sym);
                let (h2, g2) = concave_peak(
                    |h| sym.rotational_margin(h),
                    |h| sym.rotational_slope(h),
                    &Settings::DEFAULT,
                );
                if h1.is_infinite() || h2.is_infinite() {
                    assert_eq!(h1.is_infinite(), h2.is_infinite(), "α = {alpha}, K = {k}");
                    continue;
                }
                assert!(
                    abs_diff_eq!(g1, g2, epsilon = 1e-13),
                    "α = {alpha}, K = {k}: {g1} vs {g2}"
                );
                assert!(g1 >= g2 - 1e-15, "the closed form is the true maximum");
                assert!(
                    abs_diff_eq!(h1, h2, epsilon = 1e-6 * (1.0 + h1.abs())),
                    "α = {alpha}, K = {k}: {h1} vs {h2}"
                );
            }
        }
    }
}

#[test]
fn discrete_peak_matches_bisection_on_the_supergradient() {
    for n in [2u32, 3, 4, 5, 7, 8, 16, 33, 64, 101, 512] {
        for alpha in [30.0, 90.0, 140.0] {
            for k in [1.02, 1.1, 1.3, 2.0] {
                let a = Arch::new(k, alpha, WeightModel::Annular, Discretisation::Voussoirs(n))
                    .unwrap();
                let sym = SymmetricCircular::new(&a);
                let Some((h1, g1)) = discrete_rotational_peak(&sym, n, &Settings::DEFAULT) else {
                    continue;
                };
                let (h2, g2) = concave_peak(
                    |h| sym.rotational_margin(h),
                    |h| sym.rotational_slope(h),
                    &Settings::DEFAULT,
                );
                if h1.is_infinite() || h2.is_infinite() {
                    assert_eq!(
                        h1.is_infinite(),
                        h2.is_infinite(),
                        "N = {n}, α = {alpha}, K = {k}"
                    );
                    continue;
                }
                assert!(
                    abs_diff_eq!(g1, g2, epsilon = 1e-12),
                    "N = {n}, α = {alpha}, K = {k}: {g1} vs {g2} at {h1} / {h2}"
                );
            }
        }
    }
}

#[test]
fn min_thrust_hinge_at_k_1_35() {
    let (lo, _) = thrust(&semi(1.35), Friction::INFINITE).unwrap();
    let haunch = lo.hinges.iter().find(|h| h.face == Face::Intrados).unwrap();
    assert!(
        abs_diff_eq!(haunch.angle_deg.abs(), 63.2903024, epsilon = 1e-6),
        "{:?}",
        lo.hinges
    );
}

#[test]
fn discrete_approaches_continuum_from_below() {
    let mut prev = 1.0;
    for n in [8u32, 16, 64, 512, 4096] {
        let a = Arch::new(
            1.5,
            90.0,
            WeightModel::Annular,
            Discretisation::Voussoirs(n),
        )
        .unwrap();
        let k = thickness(&a, Friction::INFINITE).found().unwrap().k;
        assert!(k <= K_C + 1e-12, "N = {n}: {k}");
        assert!(k >= prev - 1e-4, "N = {n}: {k} < {prev}");
        prev = k;
        if n >= 512 {
            assert!(K_C - k < 1e-6, "N = {n}: {k}");
        }
    }
}
