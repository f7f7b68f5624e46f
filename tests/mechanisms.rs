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
