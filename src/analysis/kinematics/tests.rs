//! The mechanisms of the reference states of docs/mechanics.md §3, their degrees of freedom and the work
//! equation (eqs. 9, 11); the ten families of Figs. 3–5; the associative comparison.

use super::*;
use crate::analysis::MechanismKind;
use crate::analysis::circular::CircularArch;
use crate::analysis::symmetric::{CriticalState, friction, sliding_threshold, thickness};
use crate::model::{Arch, Discretisation, Friction, WeightModel};
use approx::{abs_diff_eq, assert_abs_diff_eq};

const K_C: f64 = 1.113581813339;
const MU_ROT: f64 = 0.395265252140;
const MU_MIN: f64 = 0.309215444330;
const K_BIF: f64 = 1.220507754643;
const HAUNCH_DEG: f64 = 54.48397403;
const SLIDE_DEG: f64 = 28.63619468;

fn semi(k: f64) -> Arch {
    Arch::semicircular(k).unwrap()
}

fn mu(x: f64) -> Friction {
    Friction::new(x).unwrap()
}

fn found(c: crate::analysis::symmetric::Critical) -> CriticalState {
    c.found().expect("a critical state").clone()
}

/// Checks eq. (11) on a field at a state: residual, zero normal work, friction = −loads.
fn assert_work(geom: &CircularArch, state: &CriticalState, f: &VelocityField) -> WorkEquation {
    let w = work_equation(geom, &LimitState::symmetric(state), f);
    assert!(w.work_residual < 1e-9, "{w:?}");
    assert!(
        abs_diff_eq!(w.work_normal, 0.0, epsilon = 1e-9 * w.load_scale),
        "{w:?}"
    );
    match f.kind() {
        Some(MechanismKind::Rotational) => {
            assert!(
                abs_diff_eq!(w.work_friction, 0.0, epsilon = 1e-12 * w.load_scale),
                "{w:?}"
            );
            assert!(
                abs_diff_eq!(w.work_loads, 0.0, epsilon = 1e-9 * w.load_scale),
                "{w:?}"
            );
        }
        _ => {
            assert!(w.work_loads > 0.0 && w.work_friction < 0.0, "{w:?}");
            assert!(
                abs_diff_eq!(w.work_tangential, w.work_friction, epsilon = 1e-9),
                "{w:?}"
            );
        }
    }
    w
}

/// The joints of a field that move, as (angle, rotates, slips).
fn moving(f: &VelocityField) -> Vec<(f64, bool, bool)> {
    f.joints
        .iter()
        .filter(|j| j.rotates() || j.slips())
        .map(|j| (j.angle_deg(), j.rotates(), j.slips()))
        .collect()
}

#[test]
fn rotational_collapse_at_kc_is_the_symmetric_five_hinge_mode() {
    let s = found(thickness(&semi(1.5), Friction::INFINITE));
    assert_abs_diff_eq!(s.k, K_C, epsilon = 1e-9);
    let arch = semi(s.k);
    let m = collapse_mechanism(&arch, &s);
    assert_eq!(m.status, ModeStatus::Admissible);
    assert_eq!(m.mechanism_dof, 2, "symmetric + antisymmetric");
    assert_eq!(m.symmetric_dof, Some(1));
    assert!(m.violations.is_empty() && m.alternatives.is_empty());
    let f = m.field.as_ref().unwrap();
    assert_eq!(f.kind(), Some(MechanismKind::Rotational));
    let angles: Vec<f64> = moving(f).iter().map(|j| j.0).collect();
    let expect = [-90.0, -HAUNCH_DEG, 0.0, HAUNCH_DEG, 90.0];
    assert_eq!(angles.len(), 5, "{angles:?}");
    for (a, e) in angles.iter().zip(expect) {
        assert!(abs_diff_eq!(*a, e, epsilon = 1e-6), "{angles:?}");
    }
    // Normality: the crown and springings open at the intrados, the haunches at the extrados,
    // and eq. (5) holds as an equality: δr_G^n = (h/2)|δα|.
    let h = s.k - 1.0;
    for j in &f.joints {
        let sign = if j.joint.hinge == Some(Face::Intrados) {
            1.0
        } else {
            -1.0
        };
        assert!(sign * j.relative_rotation > 0.1, "{j:?}");
        assert_abs_diff_eq!(
            j.opening,
            0.5 * h * j.relative_rotation.abs(),
            epsilon = 1e-12
        );
        assert!(j.constraint_residual < 1e-12);
    }
    // The crown goes down.
    let crown = f.parts.iter().find(|p| p.theta_to == 0.0).unwrap();
    assert!(crown.velocity.at([0.0, s.k])[1] < 0.0);
    let w = assert_work(&CircularArch::new(arch), &s, f);
    assert_eq!(Some(w), m.work);
}

#[test]
fn mixed_collapse_slides_outward_at_the_springings() {
    let s = found(thickness(&semi(1.5), mu(0.35)));
    assert!(abs_diff_eq!(s.k, 1.16434, epsilon = 1e-5), "K = {}", s.k);
    let arch = semi(s.k);
    let m = collapse_mechanism(&arch, &s);
    assert_eq!(m.status, ModeStatus::Admissible);
    assert_eq!((m.mechanism_dof, m.symmetric_dof), (2, Some(1)));
    let f = m.field.as_ref().unwrap();
    assert_eq!(f.kind(), Some(MechanismKind::Mixed));
    for j in &f.joints {
        if j.joint.slides {
            assert_abs_diff_eq!(j.angle_deg().abs(), 90.0, epsilon = 1e-12);
            assert_eq!(j.slip_sense(), Some(Sense::Outward));
            assert_abs_diff_eq!(j.relative_rotation, 0.0, epsilon = 1e-12);
            assert_abs_diff_eq!(j.dilatancy, 0.0, epsilon = 1e-12);
        } else {
            assert!(j.rotates());
        }
    }
    let w = assert_work(&CircularArch::new(arch), &s, f);
    // R^n = W_half at the springing: dL^(r,t) = −μ (|slip_left| + |slip_right|).
    let slips: f64 = f
        .joints
        .iter()
        .filter(|j| j.joint.slides)
        .map(|j| j.slip.abs())
        .sum();
    assert_abs_diff_eq!(w.work_friction, -0.35 * slips, epsilon = 1e-12);
}

#[test]
fn sliding_collapse_at_mu_min_slides_at_29_and_90_degrees() {
    let s = found(sliding_threshold(&semi(1.3)));
    assert_abs_diff_eq!(s.mu, MU_MIN, epsilon = 1e-9);
    for k in [K_BIF + 0.01, 1.3, 2.0] {
        let arch = semi(k);
        let m = collapse_mechanism(&arch, &s);
        assert_eq!(m.status, ModeStatus::Admissible);
        assert_eq!((m.mechanism_dof, m.symmetric_dof), (2, Some(1)));
        let f = m.field.as_ref().unwrap();
        assert_eq!(f.kind(), Some(MechanismKind::Sliding));
        let js = &f.joints;
        assert_eq!(js.len(), 4);
        for (j, (deg, sense)) in js.iter().zip([
            (-90.0, Sense::Outward),
            (-SLIDE_DEG, Sense::Inward),
            (SLIDE_DEG, Sense::Inward),
            (90.0, Sense::Outward),
        ]) {
            assert!(abs_diff_eq!(j.angle_deg(), deg, epsilon = 1e-6), "{j:?}");
            assert_eq!(j.slip_sense(), Some(sense));
        }
        // Pure translations: no block rotates.
        assert!(f.blocks().all(|b| b.velocity.rotation.abs() < 1e-12));
        assert_work(&CircularArch::new(arch), &s, f);
    }
}

#[test]
fn bifurcation_rotational_mixed_has_both_mechanisms() {
    let s = found(friction(&semi(K_C)));
    assert_abs_diff_eq!(s.mu, MU_ROT, epsilon = 1e-9);
    let arch = semi(K_C);
    let m = collapse_mechanism(&arch, &s);
    assert_eq!(m.status, ModeStatus::Admissible);
    assert_eq!(m.symmetric_dof, Some(2));
    let f = m.field.as_ref().unwrap();
    assert_eq!(f.kind(), Some(MechanismKind::Mixed));
    assert_eq!(m.alternatives.len(), 1);
    let alt = &m.alternatives[0];
    assert_eq!(alt.kind(), Some(MechanismKind::Rotational));
    let geom = CircularArch::new(arch);
    assert_work(&geom, &s, f);
    assert_work(&geom, &s, alt);
    // The mixed mode slides at the springings without rotating there.
    for j in f.joints.iter().filter(|j| j.joint.slides) {
        assert!(j.slips() && !j.rotates(), "{j:?}");
    }
}

#[test]
fn bifurcation_mixed_sliding_has_both_mechanisms() {
    let s = found(thickness(&semi(1.5), mu(MU_MIN)));
    assert_abs_diff_eq!(s.k, K_BIF, epsilon = 1e-8);
    let arch = semi(s.k);
    let m = collapse_mechanism(&arch, &s);
    assert_eq!(m.status, ModeStatus::Admissible);
    assert_eq!(m.symmetric_dof, Some(2));
    let f = m.field.as_ref().unwrap();
    assert_eq!(f.kind(), Some(MechanismKind::Mixed));
    let alt = &m.alternatives[0];
    assert_eq!(alt.kind(), Some(MechanismKind::Sliding));
    let geom = CircularArch::new(arch);
    assert_work(&geom, &s, f);
    assert_work(&geom, &s, alt);
    // The mixed mode slides at the springings only, the sliding one at 28.64° and 90°.
    let slides =
        |f: &VelocityField| -> Vec<f64> { moving(f).iter().filter(|j| j.2).map(|j| j.0).collect() };
    assert_eq!(slides(f), vec![-90.0, 90.0]);
    let sl = slides(alt);
    assert_eq!(sl.len(), 4);
    assert_abs_diff_eq!(sl[2], SLIDE_DEG, epsilon = 1e-6);
}

#[test]
fn discrete_and_centreline_arches_satisfy_the_work_equation() {
    for (weight, joints) in [
        (WeightModel::Annular, Discretisation::Voussoirs(16)),
        (WeightModel::Annular, Discretisation::Voussoirs(15)),
        (WeightModel::Centreline, Discretisation::Continuum),
        (WeightModel::Centreline, Discretisation::Voussoirs(16)),
    ] {
        let base = Arch::new(1.5, 90.0, weight, joints).unwrap();
        for f in [Friction::INFINITE, mu(0.35)] {
            let s = found(thickness(&base, f));
            let arch = base.with_k(s.k);
            let m = collapse_mechanism(&arch, &s);
            assert_eq!(m.status, ModeStatus::Admissible, "{joints} {weight}: {m:?}");
            let field = m.field.as_ref().unwrap();
            assert_eq!(field.kind(), Some(s.mechanism.kind));
            assert!(m.violations.is_empty());
            assert_work(&CircularArch::new(arch), &s, field);
        }
    }
}

#[test]
fn discrete_rotational_collapse_uses_joints_of_the_voussoirs() {
    let base = Arch::new(
        1.5,
        90.0,
        WeightModel::Annular,
        Discretisation::Voussoirs(16),
    )
    .unwrap();
    let s = found(thickness(&base, Friction::INFINITE));
    let m = collapse_mechanism(&base.with_k(s.k), &s);
    assert_eq!(m.mechanism_dof, 2);
    let f = m.field.unwrap();
    for j in &f.joints {
        let steps = j.angle_deg() / (180.0 / 16.0);
        assert!(abs_diff_eq!(steps, steps.round(), epsilon = 1e-9), "{j:?}");
    }
}

#[test]
fn associative_mechanism_dilates_and_balances_with_zero_work() {
    let s = found(thickness(&semi(1.5), mu(0.35)));
    let arch = semi(s.k);
    let c = compare_flow_rules(&arch, &s);
    assert_eq!(c.associative.status, ModeStatus::Admissible);
    assert_eq!(c.associative.mechanism_dof, c.non_associative.mechanism_dof);
    assert_eq!(c.rows.len(), 2);
    for r in &c.rows {
        assert!(
            abs_diff_eq!(r.dilatancy_non_associative, 0.0, epsilon = 1e-12),
            "{r:?}"
        );
        assert!(r.slip_associative > 0.0 && r.slip_non_associative > 0.0);
        assert_abs_diff_eq!(
            r.dilatancy_associative,
            0.35 * r.slip_associative.abs(),
            epsilon = 1e-12
        );
    }
    // With dilatancy the friction dissipates nothing: dL^(a) = 0 at the same state.
    let w = c.associative.work.unwrap();
    assert!(
        abs_diff_eq!(w.work_loads, 0.0, epsilon = 1e-9 * w.load_scale),
        "{w:?}"
    );
    assert_abs_diff_eq!(
        w.work_normal + w.work_tangential + w.work_loads,
        0.0,
        epsilon = 1e-9
    );
    // The rotational state has nothing to slide: both rules give the same mechanism.
    let r = found(thickness(&semi(1.5), Friction::INFINITE));
    let c = compare_flow_rules(&semi(r.k), &r);
    assert!(c.rows.is_empty());
    assert_eq!(c.associative.field, c.non_associative.field);
}

#[test]
fn associative_sliding_mechanism_at_mu_min() {
    let s = found(sliding_threshold(&semi(1.3)));
    let c = compare_flow_rules(&semi(1.3), &s);
    assert_eq!(c.rows.len(), 4);
    for r in &c.rows {
        assert_eq!(r.slip_associative.signum(), r.slip_non_associative.signum());
        assert_abs_diff_eq!(
            r.dilatancy_associative,
            s.mu * r.slip_associative.abs(),
            epsilon = 1e-12
        );
        assert_abs_diff_eq!(r.dilatancy_non_associative, 0.0, epsilon = 1e-12);
    }
}

#[test]
fn ten_distinct_admissible_families_on_the_semicircle() {
    for k in [1.05, 1.1136, 1.25, 1.5, 2.0, 3.0] {
        let geom = CircularArch::new(semi(k));
        let fams = families(&geom).unwrap();
        assert_eq!(fams.len(), 10);
        let count = |fig| fams.iter().filter(|f| f.template.figure == fig).count();
        assert_eq!((count(3), count(4), count(5)), (2, 6, 2));
        let mut signatures = Vec::new();
        for f in &fams {
            let id = f.template.id;
            assert_eq!(f.modes.dof, 1, "{id} at K = {k}");
            assert_eq!(f.modes.status, ModeStatus::Admissible, "{id} at K = {k}");
            let field = &f.modes.fields[0];
            assert_eq!(field.kind(), Some(f.template.kind), "{id}");
            assert!(field.violations().is_empty(), "{id}");
            assert!(field.constraint_residual() < 1e-12, "{id}");
            assert!(families::margin(f) > 1e-3, "{id} at K = {k}");
            for j in &field.joints {
                // Every joint of a one-dof family moves; pure sliding does not dilate.
                assert!(j.rotates() || j.slips(), "{id}: {j:?}");
                if j.joint.hinge.is_none() {
                    assert_abs_diff_eq!(j.relative_rotation, 0.0, epsilon = 1e-12);
                    assert_abs_diff_eq!(j.dilatancy, 0.0, epsilon = 1e-12);
                }
            }
            let sig: Vec<String> = field
                .joints
                .iter()
                .map(|j| {
                    let face = j.joint.hinge.map_or("-", |f| f.as_str());
                    let slide = j.slip_sense().map_or("-", |s| s.as_str());
                    format!("{face}/{slide}")
                })
                .collect();
            signatures.push(sig);
        }
        for i in 0..signatures.len() {
            for j in 0..i {
                assert_ne!(signatures[i], signatures[j], "K = {k}");
            }
        }
    }
}

#[test]
fn families_exist_on_horseshoe_and_moderate_segmental_arches() {
    for (alpha, k) in [(60.0, 1.2), (120.0, 1.5), (150.0, 2.0)] {
        let arch = Arch::new(k, alpha, WeightModel::Annular, Discretisation::Continuum).unwrap();
        let fams = families(&CircularArch::new(arch)).unwrap();
        for f in &fams {
            assert_eq!(
                f.modes.status,
                ModeStatus::Admissible,
                "{} α {alpha}",
                f.template.id
            );
            assert_eq!(f.modes.dof, 1);
        }
    }
}

#[test]
fn opposite_families_move_in_opposite_senses() {
    let geom = CircularArch::new(semi(1.2));
    let fams = families(&geom).unwrap();
    let by = |id: &str| fams.iter().find(|f| f.template.id == id).unwrap();
    for (a, b) in [
        ("rotational-a", "rotational-b"),
        ("mixed-springing-a", "mixed-springing-b"),
        ("mixed-inner-a", "mixed-inner-b"),
        ("mixed-la-hire-a", "mixed-la-hire-b"),
        ("sliding-a", "sliding-b"),
    ] {
        let (fa, fb) = (&by(a).modes.fields[0], &by(b).modes.fields[0]);
        for (ja, jb) in fa.joints.iter().zip(&fb.joints) {
            assert_eq!(ja.rotates(), jb.rotates());
            assert!(
                ja.relative_rotation * jb.relative_rotation <= 1e-20,
                "{a}/{b}"
            );
            assert_eq!(
                ja.slip_sense().map(|s| s == Sense::Outward),
                jb.slip_sense().map(|s| s == Sense::Inward),
                "{a}/{b}"
            );
        }
    }
}

#[test]
fn displaced_blocks_keep_their_shape_and_meet_at_hinges() {
    let geom = CircularArch::new(semi(1.25));
    for f in families(&geom).unwrap() {
        let field = &f.modes.fields[0];
        let eps = 1e-3;
        let d = drawing(&geom, field, eps);
        assert_eq!(
            d.outlines.len(),
            field
                .parts
                .iter()
                .filter(|p| p.theta_to > p.theta_from)
                .count()
        );
        for o in &d.outlines {
            // Rigid motion: distances between polygon vertices are kept.
            let (p, q) = (o.original[0], o.original[o.original.len() / 2]);
            let (pd, qd) = (o.displaced[0], o.displaced[o.original.len() / 2]);
            let l0 = (p[0] - q[0]).hypot(p[1] - q[1]);
            let l1 = (pd[0] - qd[0]).hypot(pd[1] - qd[1]);
            assert_abs_diff_eq!(l0, l1, epsilon = 1e-12);
            // Corner displacements are at most ε (field normalised to corner speed 1).
            for (a, b) in o.original.iter().zip(&o.displaced) {
                assert!((a[0] - b[0]).hypot(a[1] - b[1]) <= eps * (1.0 + 1e-6));
            }
        }
        // A pure hinge point is carried to the same place by both blocks, to O(ε²).
        for (k, m) in field.joints.iter().enumerate() {
            if let (Some(face), false) = (m.joint.hinge, m.joint.slides) {
                let j = crate::analysis::statics::ArchGeometry::joint(&geom, m.joint.theta);
                let p = if face == Face::Intrados {
                    j.intrados
                } else {
                    j.extrados
                };
                let a = outline::displace(
                    &field.parts[k].velocity,
                    p,
                    eps,
                    &KinematicsSettings::DEFAULT,
                );
                let b = outline::displace(
                    &field.parts[k + 1].velocity,
                    p,
                    eps,
                    &KinematicsSettings::DEFAULT,
                );
                assert!(
                    (a[0] - b[0]).hypot(a[1] - b[1]) < 10.0 * eps * eps,
                    "{}",
                    f.template.id
                );
            }
        }
    }
}

#[test]
fn bad_patterns_are_errors_and_rigid_patterns_a_status() {
    let geom = CircularArch::new(semi(1.2));
    let outside = [ActiveJoint::hinge(2.0, Face::Intrados)];
    assert!(matches!(
        mechanism_modes(&geom, &outside, FlowRule::NonAssociative, false),
        Err(KinematicsError::Outside { .. })
    ));
    let nan = [ActiveJoint::hinge(f64::NAN, Face::Intrados)];
    assert!(mechanism_modes(&geom, &nan, FlowRule::NonAssociative, false).is_err());
    let both = [
        ActiveJoint::hinge(0.1, Face::Intrados),
        ActiveJoint::hinge(0.1, Face::Extrados),
    ];
    assert!(matches!(
        mechanism_modes(&geom, &both, FlowRule::NonAssociative, false),
        Err(KinematicsError::BothFaces(_))
    ));
    // Three hinges: a three-hinged arch does not move.
    let three = [
        ActiveJoint::hinge(-1.0, Face::Extrados),
        ActiveJoint::hinge(0.0, Face::Intrados),
        ActiveJoint::hinge(1.0, Face::Extrados),
    ];
    let m = mechanism_modes(&geom, &three, FlowRule::NonAssociative, false).unwrap();
    assert_eq!((m.status, m.dof), (ModeStatus::Rigid, 0));
    // No joint at all: nothing moves.
    let m = mechanism_modes(&geom, &[], FlowRule::NonAssociative, false).unwrap();
    assert_eq!((m.status, m.dof), (ModeStatus::Rigid, 0));
}

#[test]
fn la_hire_joint_is_merged_from_a_state_pattern() {
    let s = found(friction(&semi(K_C)));
    let joints = pattern_of(&s.mechanism);
    let geom = CircularArch::new(semi(K_C));
    let merged = normalise_pattern(&geom, &joints, &KinematicsSettings::DEFAULT).unwrap();
    assert_eq!(merged.len(), 5);
    let spr = merged.last().unwrap();
    assert_eq!(
        (spr.hinge, spr.slides, spr.sense),
        (Some(Face::Extrados), true, Some(Sense::Outward))
    );
}

#[test]
fn every_critical_state_of_a_sweep_gets_a_status_and_admissible_ones_balance() {
    let (mut admissible, mut total) = (0, 0);
    for alpha in [10.0, 45.0, 90.0, 150.0, 179.0] {
        for joints in [None, Some(1), Some(2), Some(3), Some(16), Some(101)] {
            for weight in [WeightModel::Annular, WeightModel::Centreline] {
                let d = joints.map_or(Discretisation::Continuum, Discretisation::Voussoirs);
                let base = Arch::new(1.5, alpha, weight, d).unwrap();
                let mut states = Vec::new();
                for f in [Friction::INFINITE, mu(0.0), mu(0.2), mu(0.35), mu(1.5)] {
                    states.push(thickness(&base, f));
                }
                for k in [1.01, 1.2, 3.0] {
                    states.push(friction(&base.with_k(k)));
                }
                for c in states {
                    let Some(s) = c.found() else { continue };
                    let m = collapse_mechanism(&base, s);
                    total += 1;
                    assert_ne!(m.status, ModeStatus::Failed, "α {alpha} {d}: {s:?}");
                    if let Some(w) = m.work {
                        // Eq. (11) holds for any field of the state's pattern, even a
                        // degenerate one (μ = 0, zero thrust).
                        assert!(w.work_residual < 1e-9, "α {alpha} {d}: {s:?} {w:?}");
                    }
                    if m.status == ModeStatus::Admissible {
                        admissible += 1;
                    }
                }
            }
        }
    }
    // The exceptions are degenerate: zero thrust at μ = 0 on two voussoirs, and the thick
    // horseshoe whose crown tangency is a double hinge of zero length (three hinges: rigid).
    assert!(admissible + 12 >= total, "{admissible} of {total}");
}
