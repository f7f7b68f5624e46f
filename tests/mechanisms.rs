//! The work equation (docs/mechanics.md §1, eq. 11) of every reported mechanism: over
//! randomised scenes of every arch kind (circular or pointed, radial or vertical joints,
//! continuum or voussoirs), every load kind and every find, the mechanism a found collapse
//! reports satisfies dL^(a) + dL^(r,t) = 0 to the documented tolerance
//! (`KinematicsSettings::tol_work`).

use archstudy::analysis::kinematics::KinematicsSettings;
use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Outcome, Scene, Solution};
use proptest::prelude::*;

const TOL_WORK: f64 = KinematicsSettings::DEFAULT.tol_work;

fn form(shape: u8, e: f64, vertical: bool) -> ArchForm {
    ArchForm {
        shape: if shape == 0 {
            Shape::Circular
        } else {
            Shape::Pointed { eccentricity: e }
        },
        joints: if vertical {
            JointOrientation::Vertical
        } else {
            JointOrientation::Radial
        },
        keystone: false,
    }
}

fn load(kind: u8, at_deg: f64) -> Load {
    match kind {
        0 => Load::SelfWeight,
        1 => Load::Horizontal,
        _ => Load::Point { at_deg },
    }
}

fn find(kind: u8) -> Find {
    match kind {
        0 => Find::Thickness,
        1 => Find::Friction,
        _ => Find::LoadFactor,
    }
}

/// A scene from drawn parameters; `None` when the arch cannot be built.
#[derive(Debug, Clone)]
struct Drawn {
    k: f64,
    mu: f64,
    half_angle: f64,
    voussoirs: Option<u32>,
    shape: u8,
    e: f64,
    vertical: bool,
    load: u8,
    at_deg: f64,
    find: u8,
    lambda: f64,
}

impl Drawn {
    fn scene(&self) -> Option<Scene> {
        let joints = self
            .voussoirs
            .map_or(Discretisation::Continuum, Discretisation::Voussoirs);
        let arch = Arch::new(self.k, self.half_angle, WeightModel::Annular, joints).ok()?;
        let load = load(self.load, self.at_deg * self.half_angle / 90.0);
        let find = find(self.find);
        let s = Scene {
            arch,
            friction: Friction::new(self.mu)?,
            find,
            form: form(self.shape, self.e, self.vertical),
            load,
            lambda: if find == Find::LoadFactor || load == Load::SelfWeight {
                0.0
            } else {
                self.lambda
            },
        };
        s.check().ok().map(|()| s)
    }
}

fn drawn() -> impl Strategy<Value = Drawn> {
    (
        (1.08..1.6f64, 0.25..1.0f64, 60.0..90.0f64),
        prop_oneof![Just(None), (3u32..40).prop_map(Some)],
        (0u8..2, 0.02..0.25f64, any::<bool>()),
        (0u8..3, -85.0..85.0f64),
        (0u8..3, 0.0..0.25f64),
    )
        .prop_map(
            |(
                (k, mu, half_angle),
                voussoirs,
                (shape, e, vertical),
                (load, at_deg),
                (find, lambda),
            )| {
                Drawn {
                    k,
                    mu,
                    half_angle,
                    voussoirs,
                    shape,
                    e,
                    vertical,
                    load,
                    at_deg,
                    find,
                    lambda,
                }
            },
        )
}

/// The work residual of a found mechanism that obeys the flow rules, when the scene found
/// one.
fn residual(s: &Solution) -> Option<f64> {
    let found = s.outcome == Some(Outcome::Found) && s.mechanism.is_some();
    (found && s.mechanism_admissible != Some(false)).then(|| s.work_residual.unwrap_or(f64::NAN))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, ..ProptestConfig::default() })]

    #[test]
    fn every_found_mechanism_satisfies_the_work_equation(d in drawn()) {
        let Some(scene) = d.scene() else {
            return Ok(());
        };
        let s = scene::solve(&scene);
        if let Some(r) = residual(&s) {
            prop_assert!(
                r <= TOL_WORK,
                "work residual {r:e} of a {:?} mechanism ({:?}) at λ {:?}, μ {:?}, K {:?}: {:?}",
                s.mechanism, s.hinges, s.load_factor, s.mu_crit, s.k_crit, d
            );
        }
    }
}

/// The point load of the example: a mixed mechanism whose hinge and sliding joint both
/// sit at the load (a La Hire joint with the load on its hinged side), λ as with 2049 voussoirs.
#[test]
fn point_load_la_hire_mechanism_satisfies_the_work_equation() {
    let arch = Arch::new(1.3, 90.0, WeightModel::Annular, Discretisation::Continuum).unwrap();
    let mut s = Scene::new(arch, Friction::new(0.5).unwrap(), Find::LoadFactor);
    s.load = Load::Point { at_deg: 30.0 };
    let c = scene::solve(&s);
    assert!(
        c.work_residual.unwrap() <= TOL_WORK,
        "{:?}",
        c.work_residual
    );
    // dL(a) > 0 is dissipated by friction: dL(r,t) = −dL(a) < 0.
    assert!(c.work_loads.unwrap() > 0.1);
    s.arch = Arch::new(
        1.3,
        90.0,
        WeightModel::Annular,
        Discretisation::Voussoirs(2049),
    )
    .unwrap();
    let v = scene::solve(&s);
    approx::assert_relative_eq!(
        c.load_factor.unwrap(),
        v.load_factor.unwrap(),
        max_relative = 1e-3
    );
    assert!(
        v.work_residual.unwrap() <= TOL_WORK,
        "{:?}",
        v.work_residual
    );
}

fn pointed_voussoirs(k: f64, n: u32, mu: f64, find: Find) -> Scene {
    let arch = Arch::new(k, 90.0, WeightModel::Annular, Discretisation::Voussoirs(n)).unwrap();
    let mut s = Scene::new(arch, Friction::new(mu).unwrap(), find);
    s.form = form(1, 0.2, false);
    s
}

/// Three voussoirs of a pointed arch (e = 0.2, μ = ∞): the keystone spans the apex, and a
/// thrust line through the four joint points stands at zero thickness, so the arch stands at
/// every thickness: `always_stands`, not a critical K a hair above 1. Checked two ways: the
/// state find says `stable` from K = 1.0001 to K = 2.
#[test]
fn three_voussoir_pointed_arch_stands_at_every_thickness() {
    for mu in [f64::INFINITY, 0.6] {
        let s = scene::solve(&pointed_voussoirs(1.5, 3, mu, Find::Thickness));
        assert_eq!(s.outcome, Some(Outcome::AlwaysStands), "μ {mu}: {s:?}");
        assert_eq!(s.k_crit, None);
        for k in [1.0001, 1.01, 1.2, 2.0] {
            let st = scene::solve(&pointed_voussoirs(k, 3, mu, Find::State));
            assert_eq!(
                st.regime,
                Some(archstudy::analysis::Regime::Stable),
                "K {k}, μ {mu}"
            );
        }
    }
    // Five voussoirs have a genuine collapse thickness (K ≈ 1.0700), with its mechanism.
    let s = scene::solve(&pointed_voussoirs(1.5, 5, f64::INFINITY, Find::Thickness));
    assert_eq!(s.outcome, Some(Outcome::Found));
    approx::assert_abs_diff_eq!(s.k_crit.unwrap(), 1.0699647, epsilon = 1e-6);
    let below = scene::solve(&pointed_voussoirs(1.069, 5, f64::INFINITY, Find::State));
    assert_eq!(below.regime, Some(archstudy::analysis::Regime::Rotational));
}

/// A very thick semicircle (K = 10⁶): μ_c is μ_min, and its four-joint sliding mechanism is
/// the one of K = 1.5 (sliding rows over W_half do not depend on K): the same dof and the same
/// work of the loads, with the work equation satisfied. The rank test of the compatibility
/// system is scale-free, so lengths of 10⁶ r do not drop constraints.
#[test]
fn very_thick_arch_reports_an_exact_sliding_mechanism() {
    let at = |k: f64| {
        let arch = Arch::new(k, 90.0, WeightModel::Annular, Discretisation::Continuum).unwrap();
        scene::solve(&Scene::new(
            arch,
            Friction::new(0.4).unwrap(),
            Find::Friction,
        ))
    };
    let (thick, thin) = (at(1e6), at(1.5));
    approx::assert_relative_eq!(
        thick.mu_crit.unwrap(),
        crate::common::reference::MU_MIN,
        max_relative = 1e-9
    );
    assert_eq!(thick.mechanism_dof, thin.mechanism_dof);
    assert!(thick.work_residual.unwrap() <= TOL_WORK, "{thick:?}");
    approx::assert_relative_eq!(
        thick.work_loads.unwrap(),
        thin.work_loads.unwrap(),
        max_relative = 1e-9
    );
}
