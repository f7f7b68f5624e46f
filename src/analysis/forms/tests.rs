//! Checks of the forms: Green's moments against quadrature, the circular closed forms,
//! loads, refusals and the load-factor programme against clarabel.

use super::*;
use crate::analysis::circular::CircularArch;
use crate::analysis::statics::{ArchGeometry, joint_rows};
use crate::model::Shape;
use approx::{abs_diff_eq, assert_abs_diff_eq};

fn arch(k: f64, alpha: f64, weight: WeightModel, joints: Discretisation) -> Arch {
    Arch::new(k, alpha, weight, joints).unwrap()
}

fn form(e: f64, joints: JointOrientation) -> ArchForm {
    ArchForm {
        shape: if e == 0.0 {
            Shape::Circular
        } else {
            Shape::Pointed { eccentricity: e }
        },
        joints,
        keystone: false,
    }
}

/// Area and first moments of the right half region up to joint θ by brute-force
/// quadrature over a fine polar grid about C (midpoint rule in ρ, Gauss–Legendre would
/// be overkill): a check of the Green's-theorem closed forms.
fn quadrature(m: &ArchModel, theta: f64) -> [f64; 3] {
    let (k, d) = (m.arch.k, m.d);
    let j = m.joint_at(theta);
    let (i, e) = (j.intrados, j.extrados);
    let inside = |x: f64, y: f64| {
        // Right of the crown plane, left of the joint line I→E (crossing z ≥ 0).
        let z = (e[0] - i[0]) * (y - i[1]) - (e[1] - i[1]) * (x - i[0]);
        x >= 0.0 && z >= 0.0
    };
    let (nr, np) = (400, 4000);
    let mut s = [0.0; 3];
    for a in 0..nr {
        let rho = 1.0 + (k - 1.0) * (a as f64 + 0.5) / nr as f64;
        for b in 0..np {
            let psi = std::f64::consts::FRAC_PI_2 * (b as f64 + 0.5) / np as f64;
            let (x, y) = (-d + rho * psi.sin(), rho * psi.cos());
            if inside(x, y) {
                let da = rho * (k - 1.0) / nr as f64 * std::f64::consts::FRAC_PI_2 / np as f64;
                s[0] += da;
                s[1] += x * da;
                s[2] += y * da;
            }
        }
    }
    s
}

#[test]
fn green_moments_match_quadrature() {
    for (e, joints, theta) in [
        (0.3, JointOrientation::Radial, 1.0),
        (0.3, JointOrientation::Vertical, 1.2),
        (0.0, JointOrientation::Vertical, 0.7),
    ] {
        let a = arch(1.2, 90.0, WeightModel::Annular, Discretisation::Continuum);
        let m = ArchModel::new(a, form(e, joints), Load::SelfWeight).unwrap();
        let exact = m.region(&m.half_joint(theta)).0;
        let q = quadrature(&m, theta);
        for c in 0..3 {
            assert!(
                abs_diff_eq!(exact[c], q[c], epsilon = 2e-3 * exact[0]),
                "e = {e}, {joints:?}: {exact:?} vs {q:?}"
            );
        }
    }
}

#[test]
fn semicircle_by_green_equals_the_closed_forms() {
    // Force the Green route on the circular radial arch by asking for the region.
    for weight in [WeightModel::Annular] {
        let a = arch(1.3, 90.0, weight, Discretisation::Continuum);
        let m = ArchModel::new(a, ArchForm::default(), Load::SelfWeight).unwrap();
        for theta in [0.0, 0.1, 0.7, 1.5, FRAC_PI_2] {
            let raw = m.region(&m.half_joint(theta)).0.map(|v| v / m.w_half);
            let cf = m.weight_moments(theta);
            for c in 0..3 {
                assert!(
                    abs_diff_eq!(raw[c], cf[c], epsilon = 1e-14),
                    "{theta}: {raw:?} vs {cf:?}"
                );
            }
        }
    }
}

#[test]
fn circular_radial_rows_equal_circular_arch_rows() {
    for weight in [WeightModel::Annular, WeightModel::Centreline] {
        let a = arch(1.25, 75.0, weight, Discretisation::Continuum);
        let m = ArchModel::new(a, ArchForm::default(), Load::SelfWeight).unwrap();
        let c = CircularArch::new(a);
        for theta in [-1.3, -0.4, 0.0, 0.2, 1.3] {
            let (r1, r2) = (joint_rows(&m, theta, 0.4), joint_rows(&c, theta, 0.4));
            for (x, y) in r1.iter().zip(&r2) {
                assert_eq!(x.condition, y.condition);
                assert_abs_diff_eq!(x.b, y.b, epsilon = 1e-15);
                assert_abs_diff_eq!(x.a_lambda, y.a_lambda, epsilon = 1e-15);
                for i in 0..3 {
                    assert_abs_diff_eq!(x.a[i], y.a[i], epsilon = 1e-15);
                }
            }
        }
    }
}

#[test]
fn centreline_pointed_weight_is_the_centreline_length() {
    // Half the centreline of a pointed arch runs from ψ_c0 = asin e to α.
    let a = arch(
        1.2,
        90.0,
        WeightModel::Centreline,
        Discretisation::Continuum,
    );
    let m = ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::SelfWeight).unwrap();
    assert_abs_diff_eq!(
        m.w_half,
        0.2 * 1.1 * (FRAC_PI_2 - 0.5f64.asin()),
        epsilon = 1e-15
    );
    assert_abs_diff_eq!(m.weight_moments(FRAC_PI_2)[0], 1.0, epsilon = 1e-15);
    assert_eq!(m.weight_moments(0.0), [0.0, 0.0, 0.0]);
}

#[test]
fn total_weight_and_continuity() {
    for (e, joints) in [
        (0.0, JointOrientation::Vertical),
        (0.4, JointOrientation::Radial),
        (0.4, JointOrientation::Vertical),
    ] {
        let a = arch(1.15, 90.0, WeightModel::Annular, Discretisation::Continuum);
        let m = ArchModel::new(a, form(e, joints), Load::SelfWeight).unwrap();
        // The support carries the whole half weight; the crown nothing.
        let s = m.support_param(1.0);
        assert_abs_diff_eq!(m.weight_moments(s)[0], 1.0, epsilon = 1e-14);
        assert_abs_diff_eq!(m.weight_moments(-s)[0], -1.0, epsilon = 1e-14);
        assert!(m.weight_moments(0.0).iter().all(|v| v.abs() < 1e-15));
        // The first joint of the family next to the crown: a vertical one is the crown
        // joint itself; a radial one of a pointed arch encloses the keystone wedge.
        let w1 = m.weight_moments(m.psi_1.max(1e-300))[0];
        if joints == JointOrientation::Vertical {
            assert!(abs_diff_eq!(w1, 0.0, epsilon = 1e-14), "{w1}");
        } else {
            assert!(w1 > 0.0);
        }
    }
}

#[test]
fn point_load_belongs_to_the_crown_side_of_its_joint() {
    let a = arch(1.3, 90.0, WeightModel::Annular, Discretisation::Continuum);
    let m = ArchModel::new(a, ArchForm::default(), Load::point(30.0)).unwrap();
    let at = 30f64.to_radians();
    assert_eq!(m.live_load(at).fy, -2.0);
    assert_eq!(m.live_load(at.next_down()).fy, 0.0);
    assert_eq!(
        m.families(),
        vec![[-FRAC_PI_2, at.next_down()], [at, FRAC_PI_2]]
    );
    let m = ArchModel::new(a, ArchForm::default(), Load::point(-30.0)).unwrap();
    assert_eq!(m.live_load(-at).fy, 2.0);
    assert_eq!(m.live_load((-at).next_up()).fy, 0.0);
    let m = ArchModel::new(a, ArchForm::default(), Load::point(0.0)).unwrap();
    assert_eq!(m.live_load(0.0).fy, 0.0);
    assert_eq!(m.live_load(1e-300).fy, -2.0);
    assert_eq!(m.live_load(-1e-300).fy, 0.0);
    // Its moment is that of P at the extrados point.
    let x = 1.3 * at.sin();
    let m = ArchModel::new(a, ArchForm::default(), Load::point(30.0)).unwrap();
    assert_abs_diff_eq!(m.live_load(1.0).m, -2.0 * x, epsilon = 1e-15);
}

#[test]
fn invalid_forms_are_refused() {
    let a = arch(3.2, 90.0, WeightModel::Annular, Discretisation::Continuum);
    assert!(matches!(
        ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::SelfWeight),
        Err(FormError::PointedTooThick { .. })
    ));
    let a = arch(1.2, 120.0, WeightModel::Annular, Discretisation::Continuum);
    assert!(matches!(
        ArchModel::new(a, form(0.0, JointOrientation::Vertical), Load::SelfWeight),
        Err(FormError::VerticalBeyondQuadrant(_))
    ));
    let a = arch(1.2, 60.0, WeightModel::Annular, Discretisation::Continuum);
    assert!(matches!(
        ArchModel::new(a, ArchForm::default(), Load::point(61.0)),
        Err(FormError::LoadOutside { .. })
    ));
    let a = arch(1.2, 90.0, WeightModel::Annular, Discretisation::Continuum);
    assert!(matches!(
        ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::point(10.0)),
        Err(FormError::LoadInsideKeystone { .. })
    ));
}

#[test]
fn pointed_margins_converge_even_without_friction() {
    // At φ = 0 the sliding rows pin the tangential force to zero; the programme solver's
    // residual on rows it already holds must not read as a missing joint.
    use crate::analysis::general::{self, Outcome, RowSet, Settings};
    let a = arch(1.3, 90.0, WeightModel::Annular, Discretisation::Continuum);
    let m = ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::SelfWeight).unwrap();
    for phi in [0.0, 0.1, 0.6, FRAC_PI_2] {
        for set in [RowSet::Rotational, RowSet::Sliding, RowSet::All] {
            let r = general::margin(&m, phi, set, &Settings::default());
            assert_eq!(r.outcome, Outcome::Solved, "φ = {phi}, {set:?}");
        }
    }
}

#[test]
fn load_factor_programmes_agree_with_clarabel() {
    use crate::analysis::general::{self, LinearRows, OBJECTIVE, RowSet, Settings};
    use crate::analysis::lp;
    use clarabel::algebra::CscMatrix;
    use clarabel::solver::{
        DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    };
    let voussoirs = |k, n| arch(k, 90.0, WeightModel::Annular, Discretisation::Voussoirs(n));
    let a = voussoirs(1.3, 64);
    for (a, f, load, phi) in [
        (a, ArchForm::default(), Load::Horizontal, 0.6f64.atan()),
        (a, ArchForm::default(), Load::point(22.5), FRAC_PI_2),
        (
            a,
            form(0.3, JointOrientation::Vertical),
            Load::Horizontal,
            1.4,
        ),
        (
            a,
            form(0.3, JointOrientation::Radial),
            Load::point(-45.0),
            0.7,
        ),
        // On the keystone of 65 voussoirs (ψ₁ = 18.8°, extrados apex 16.3°).
        (
            voussoirs(1.15, 65),
            ArchForm {
                keystone: true,
                ..form(0.3, JointOrientation::Radial)
            },
            Load::point(18.5),
            0.7,
        ),
    ] {
        let g = ArchModel::new(a, f, load).unwrap();
        let thetas = g.discrete_joints().unwrap();
        let rows = LinearRows::load_factor(&g, &thetas, phi, RowSet::All);
        let ours = lp::maximise(&OBJECTIVE, &rows.a, &rows.b, &lp::Settings::default()).unwrap();
        assert_eq!(ours.status, lp::Status::Optimal, "{f:?} {load:?}");
        let p = CscMatrix::<f64>::zeros((4, 4));
        let q = OBJECTIVE.map(|c| -c);
        let am = CscMatrix::from(rows.a.iter());
        let cones = [NonnegativeConeT(rows.b.len())];
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_gap_abs(1e-11)
            .tol_gap_rel(1e-11)
            .tol_feas(1e-11)
            .build()
            .unwrap();
        let mut solver = DefaultSolver::new(&p, &q, &am, &rows.b, &cones, settings).unwrap();
        solver.solve();
        assert_eq!(solver.solution.status, SolverStatus::Solved);
        let oracle = solver.solution.x[3];
        assert!(
            abs_diff_eq!(ours.x[3], oracle, epsilon = 1e-7 * (1.0 + oracle.abs())),
            "{f:?} {load:?}: {} vs {oracle}",
            ours.x[3]
        );
        // The analysis solves the same programme.
        let lf = general::load_factor(&g, phi, &Settings::default());
        assert!(
            abs_diff_eq!(lf.lambda, ours.x[3], epsilon = 1e-12),
            "{} vs {}",
            lf.lambda,
            ours.x[3]
        );
    }
}

#[test]
fn discrete_joints_of_each_form() {
    let a = arch(
        1.2,
        90.0,
        WeightModel::Annular,
        Discretisation::Voussoirs(4),
    );
    let radial = ArchModel::new(a, ArchForm::default(), Load::SelfWeight).unwrap();
    let j = radial.discrete_joints().unwrap();
    assert_eq!(j, CircularArch::new(a).discrete_joints().unwrap());
    let v = ArchModel::new(a, form(0.0, JointOrientation::Vertical), Load::SelfWeight).unwrap();
    let jv = v.discrete_joints().unwrap();
    assert!(jv[0] < -FRAC_PI_2 && jv[4] > FRAC_PI_2 && jv[2] == 0.0);
    assert_eq!(v.angle_deg(jv[4]), 90.0);
    let p = ArchModel::new(a, form(0.5, JointOrientation::Radial), Load::SelfWeight).unwrap();
    let jp = p.discrete_joints().unwrap();
    let psi1 = p.first_joint();
    assert_abs_diff_eq!(jp[3], psi1 + 0.5 * (FRAC_PI_2 - psi1), epsilon = 1e-15);
    assert_eq!(jp[2], 0.0);
}
