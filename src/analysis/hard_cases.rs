//! Numerically hard scenes: limits approached to 1e-12, the singular joints of eqs. (4a, 4b),
//! extreme thickness, friction, embrace and voussoir counts. Each must give finite,
//! consistent answers and never panic.

use super::symmetric::{Critical, friction, sliding_threshold, state, thickness, thrust};
use super::{Face, MechanismKind, Regime};
use crate::model::{Arch, Discretisation, Friction, WeightModel};
use approx::{abs_diff_eq, assert_abs_diff_eq};

const K_C: f64 = 1.113581813339;
const MU_ROT: f64 = 0.395265252140;
const K_BIF: f64 = 1.220507754643;

fn semi(k: f64) -> Arch {
    Arch::semicircular(k).unwrap()
}

fn arch(k: f64, alpha: f64, n: Option<u32>) -> Arch {
    let joints = n.map_or(Discretisation::Continuum, Discretisation::Voussoirs);
    Arch::new(k, alpha, WeightModel::Annular, joints).unwrap()
}

fn mu(x: f64) -> Friction {
    Friction::new(x).unwrap()
}

fn exact_kc() -> f64 {
    thickness(&semi(1.5), Friction::INFINITE).found().unwrap().k
}

fn exact_mu_min() -> f64 {
    sliding_threshold(&semi(1.5)).found().unwrap().mu
}

/// Every number a state report holds is finite or an explicit infinity, never NaN.
fn assert_sane_state(a: &Arch, f: Friction) -> Regime {
    let s = state(a, f);
    for x in [
        s.domains.rotational.interval.lo,
        s.domains.rotational.interval.hi,
        s.domains.sliding.interval.lo,
        s.domains.sliding.interval.hi,
    ] {
        assert!(!x.is_nan(), "NaN in {s:?}");
    }
    s.regime
}

#[test]
fn thickness_within_1e12_of_kc_on_both_sides() {
    let kc = exact_kc();
    assert_abs_diff_eq!(kc, K_C, epsilon = 1e-11);
    let above = assert_sane_state(&semi(kc + 1e-12), Friction::INFINITE);
    let below = assert_sane_state(&semi(kc - 1e-12), Friction::INFINITE);
    assert_eq!(above, Regime::Stable);
    assert!(matches!(below, Regime::Stable | Regime::Rotational));
    // A step of 1e-10 is well outside the tolerance on both sides.
    assert_eq!(
        assert_sane_state(&semi(kc - 1e-10), Friction::INFINITE),
        Regime::Rotational
    );
    assert_eq!(
        assert_sane_state(&semi(kc + 1e-10), Friction::INFINITE),
        Regime::Stable
    );
    // The critical friction just above K_c is the rotational/mixed threshold.
    let f = friction(&semi(kc + 1e-12));
    assert_abs_diff_eq!(f.found().unwrap().mu, MU_ROT, epsilon = 1e-9);
    // Just below, no friction helps (or the state is the limit itself).
    match friction(&semi(kc - 1e-10)) {
        Critical::NeverStands => {}
        other => panic!("expected never_stands, got {other:?}"),
    }
}

#[test]
fn friction_within_1e12_of_mu_min() {
    let m = exact_mu_min();
    let above = thickness(&semi(1.5), mu(m + 1e-12));
    let k = above.found().unwrap().k;
    assert!(abs_diff_eq!(k, K_BIF, epsilon = 1e-8), "K = {k}");
    // Within the tolerance below μ_min the limit state is still the single-valued H^s.
    match thickness(&semi(1.5), mu(m - 1e-12)) {
        Critical::Found(s) => assert_abs_diff_eq!(s.k, K_BIF, epsilon = 1e-8),
        Critical::NeverStands => {}
        Critical::AlwaysStands => panic!("cannot always stand below μ_min"),
    }
    assert_eq!(thickness(&semi(1.5), mu(m - 1e-9)), Critical::NeverStands);
    for x in [m - 1e-12, m + 1e-12] {
        let r = assert_sane_state(&semi(1.3), mu(x));
        assert!(matches!(r, Regime::Stable | Regime::Sliding), "{r:?}");
    }
    assert_eq!(assert_sane_state(&semi(1.3), mu(m - 1e-9)), Regime::Sliding);
    assert_eq!(assert_sane_state(&semi(1.3), mu(m + 1e-9)), Regime::Stable);
}

#[test]
fn friction_within_1e12_of_the_rotational_threshold() {
    let kc = exact_kc();
    let m_rot = friction(&semi(kc)).found().unwrap().mu;
    for x in [m_rot - 1e-12, m_rot, m_rot + 1e-12] {
        let s = thickness(&semi(1.5), mu(x));
        let s = s.found().unwrap();
        assert!(
            abs_diff_eq!(s.k, kc, epsilon = 1e-9),
            "μ = {x}: K = {}",
            s.k
        );
        assert!(matches!(
            s.mechanism.kind,
            MechanismKind::Rotational | MechanismKind::Mixed
        ));
    }
    // Clearly below the threshold the collapse is mixed and thicker.
    let s = thickness(&semi(1.5), mu(m_rot - 1e-6));
    let s = s.found().unwrap();
    assert_eq!(s.mechanism.kind, MechanismKind::Mixed);
    assert!(s.k > kc);
}

#[test]
fn singular_joints_of_the_sliding_bounds() {
    // N = 6: half joints at 0°, 30°, 60°, 90°. μ = tan 30° puts θ = φ at 30° and
    // θ + φ = 90° at 60°: the bounds of eqs. (4a, 4b) divide by zero there.
    let n6 = arch(1.3, 90.0, Some(6));
    let phi = 30f64.to_radians();
    let at = mu(phi.tan());
    let r = assert_sane_state(&n6, at);
    let s = state(&n6, at).domains.sliding.interval;
    // The limits of the interval are continuous through the singular value.
    for dx in [1e-9, -1e-9] {
        let t = state(&n6, mu(phi.tan() + dx)).domains.sliding.interval;
        assert!(abs_diff_eq!(t.lo, s.lo, epsilon = 1e-7), "{s:?} vs {t:?}");
        assert!(abs_diff_eq!(t.hi, s.hi, epsilon = 1e-7), "{s:?} vs {t:?}");
        assert_eq!(assert_sane_state(&n6, mu(phi.tan() + dx)), r);
    }
    let t = thickness(&n6, at);
    assert!(t.found().is_some_and(|s| s.k.is_finite()));
    // Continuum at the same μ: θ = φ and θ + φ = 90° are interior joints.
    let c = thickness(&semi(1.5), at);
    assert!(
        c.found()
            .is_some_and(|s| s.k.is_finite() && s.k >= K_C - 1e-9)
    );
}

#[test]
fn nearly_zero_thickness() {
    let a = semi(1.0 + 1e-9);
    assert_eq!(
        assert_sane_state(&a, Friction::INFINITE),
        Regime::Rotational
    );
    assert_eq!(friction(&a), Critical::NeverStands);
    assert!(thrust(&a, Friction::INFINITE).is_none());
    assert_abs_diff_eq!(
        thickness(&a, Friction::INFINITE).found().unwrap().k,
        K_C,
        epsilon = 1e-9
    );
}

#[test]
fn very_thick_arch() {
    let a = semi(100.0);
    assert_eq!(assert_sane_state(&a, Friction::INFINITE), Regime::Stable);
    let (lo, hi) = thrust(&a, Friction::INFINITE).unwrap();
    assert!(
        abs_diff_eq!(lo.thrust_over_half_weight, 0.0, epsilon = 1e-12),
        "{lo:?}"
    );
    assert!(hi.thrust_over_half_weight.is_finite() && hi.thrust_over_half_weight > 10.0);
    // Thick enough for the halves to stand alone: friction only has to stop sliding.
    let f = friction(&a);
    let s = f.found().unwrap();
    assert_abs_diff_eq!(s.mu, exact_mu_min(), epsilon = 1e-9);
    assert_eq!(s.mechanism.kind, MechanismKind::Sliding);
}

#[test]
fn zero_and_huge_friction() {
    assert_eq!(assert_sane_state(&semi(1.3), mu(0.0)), Regime::Sliding);
    assert_eq!(thickness(&semi(1.3), mu(0.0)), Critical::NeverStands);
    let big = thickness(&semi(1.3), mu(1e9)).found().unwrap().k;
    assert_abs_diff_eq!(big, K_C, epsilon = 1e-9);
    assert_eq!(assert_sane_state(&semi(1.3), mu(1e9)), Regime::Stable);
}

#[test]
fn extreme_embrace_angles() {
    // A 2° segment: a nearly straight flat arch, thrust far above the weight.
    let flat = arch(1.35, 1.0, None);
    assert_eq!(assert_sane_state(&flat, Friction::INFINITE), Regime::Stable);
    let kc = thickness(&flat, Friction::INFINITE).found().unwrap().k;
    assert!(kc > 1.0 && kc < 1.0 + 1e-6, "{kc}");
    // A 300° horseshoe: much thicker than the semicircle at collapse.
    let horseshoe = arch(1.35, 150.0, None);
    assert_sane_state(&horseshoe, Friction::INFINITE);
    let s = thickness(&horseshoe, Friction::INFINITE);
    let s = s.found().unwrap();
    assert!(s.k > 2.0 && s.k.is_finite());
    assert_eq!(s.mechanism.kind, MechanismKind::Rotational);
}

#[test]
fn extreme_voussoir_counts() {
    // One block spans the opening: it stands for every thickness and friction.
    let one = arch(1.01, 90.0, Some(1));
    assert_eq!(assert_sane_state(&one, mu(0.0)), Regime::Stable);
    assert_eq!(thickness(&one, Friction::INFINITE), Critical::AlwaysStands);
    // Two blocks: a three-hinge arch, stands for every thickness.
    assert_eq!(
        thickness(&arch(1.5, 90.0, Some(2)), Friction::INFINITE),
        Critical::AlwaysStands
    );
    // Three blocks: the keystone wedges between the two side blocks.
    let three = arch(1.3, 90.0, Some(3));
    assert_sane_state(&three, mu(0.3));
    let f = friction(&three);
    assert!(f.found().is_some_and(|s| s.mu > 0.0 && s.mu < 1.0));
    // 100000 voussoirs: the continuum from below, to 1e-9.
    let many = thickness(&arch(1.5, 90.0, Some(100_000)), Friction::INFINITE);
    let k = many.found().unwrap().k;
    assert!(k <= exact_kc() + 1e-13 && exact_kc() - k < 1e-9, "{k}");
}

#[test]
fn weight_models_agree_as_the_arch_gets_thin() {
    // The first moments differ by t²/12 per unit weight: relative thrust differences shrink
    // like (K − 1)².
    // A 60° segmental arch stands down to small thicknesses.
    let mut last = f64::INFINITY;
    let mut compared = 0;
    for k in [1.2, 1.1, 1.05, 1.02, 1.01] {
        let a = arch(k, 30.0, None);
        let c = a.with_weight(WeightModel::Centreline);
        let (la, ha) = thrust(&a, Friction::INFINITE).map_or((f64::NAN, f64::NAN), |(l, h)| {
            (l.thrust_over_half_weight, h.thrust_over_half_weight)
        });
        let (lc, hc) = thrust(&c, Friction::INFINITE).map_or((f64::NAN, f64::NAN), |(l, h)| {
            (l.thrust_over_half_weight, h.thrust_over_half_weight)
        });
        if la.is_nan() || lc.is_nan() {
            continue;
        }
        let d = ((la - lc).abs() / la).max((ha - hc).abs() / ha);
        assert!(d < last, "K = {k}: {d} ≥ {last}");
        last = d;
        compared += 1;
    }
    assert!(compared >= 4, "only {compared} thicknesses stand");
    assert!(last < 1e-4, "{last}");
    let kc_a = thickness(&arch(1.5, 90.0, None), Friction::INFINITE)
        .found()
        .unwrap()
        .k;
    let kc_c = thickness(
        &arch(1.5, 90.0, None).with_weight(WeightModel::Centreline),
        Friction::INFINITE,
    )
    .found()
    .unwrap()
    .k;
    assert!(abs_diff_eq!(kc_a, kc_c, epsilon = 5e-3), "{kc_a} vs {kc_c}");
}

#[test]
fn hinges_of_the_maximum_thrust_state() {
    // Crown intrados and springing extrados (paper §2.1).
    let (_, hi) = thrust(&semi(1.35), Friction::INFINITE).unwrap();
    let faces: Vec<(i64, Face)> = hi
        .hinges
        .iter()
        .map(|h| (h.angle_deg.round() as i64, h.face))
        .collect();
    assert_eq!(
        faces,
        vec![
            (-90, Face::Extrados),
            (0, Face::Intrados),
            (90, Face::Extrados)
        ]
    );
}

#[test]
fn critical_friction_exactly_at_the_collapse_thickness() {
    // At K = K_c the rotational margin is zero for every μ above the threshold: the search
    // must not chase rounding noise on that plateau (64 voussoirs used to give 0.418).
    let cases = [
        arch(1.5, 90.0, Some(64)),
        arch(1.5, 90.0, Some(16)).with_weight(WeightModel::Centreline),
        arch(1.5, 90.0, Some(16)),
        arch(1.5, 90.0, None),
        arch(1.5, 60.0, None),
        arch(1.5, 120.0, None),
    ];
    for a in cases {
        let kc = thickness(&a, Friction::INFINITE).found().unwrap().clone();
        let at = a.with_k(kc.k);
        let f = friction(&at);
        let m = f.found().unwrap_or_else(|| panic!("{a:?}: {f:?}")).mu;
        // Stands at μ_c, not clearly below it.
        assert_eq!(state(&at, mu(m)).regime, Regime::Stable, "{a:?}");
        assert_ne!(
            state(&at, mu(m * (1.0 - 1e-7))).regime,
            Regime::Stable,
            "{a:?}: μ_c = {m}"
        );
        if a.half_angle_deg() == 90.0 {
            // Semicircle: H_max^s = μ W_half at the springing, so μ_c is the thrust at K_c.
            assert!(
                abs_diff_eq!(m, kc.thrust_over_half_weight, epsilon = 1e-9),
                "{a:?}: {m} vs {}",
                kc.thrust_over_half_weight
            );
        }
    }
}
