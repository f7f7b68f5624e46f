use super::*;
use crate::analysis::forms::ArchModel;
use crate::model::{Arch, ArchForm, Discretisation, JointOrientation, Load, Shape, WeightModel};

fn model(k: f64, half: f64, joints: Discretisation, form: ArchForm, load: Load) -> ArchModel {
    let arch = Arch::new(k, half, WeightModel::Annular, joints).unwrap();
    ArchModel::new(arch, form, load).unwrap()
}

/// What a complete vertex found in a slice is: where, the state, and its moving joints.
fn outcome(f: Option<Found>) -> Option<(f64, [f64; 4], Vec<JointMove>)> {
    f.map(|f| (f.p, f.y, f.moves))
}

/// Along a friction path, testing only the vertices whose rows were not tight together at the
/// step before gives the first complete vertex that testing every vertex gives, at every step
/// after one without a complete vertex; and many vertices were tight together before.
#[test]
fn a_friction_step_that_skips_known_vertices_finds_what_testing_every_vertex_finds() {
    let vertical = ArchForm {
        shape: Shape::Circular,
        joints: JointOrientation::Vertical,
        keystone: false,
    };
    let scenes = [
        // The crown part drops between vertical joints over a range of μ.
        (
            model(
                1.3,
                90.0,
                Discretisation::Voussoirs(5),
                vertical,
                Load::SelfWeight,
            ),
            0.0,
        ),
        // The twelve voussoirs under a horizontal load at a fixed λ.
        (
            model(
                1.5278,
                50.367,
                Discretisation::Voussoirs(12),
                ArchForm::default(),
                Load::Horizontal,
            ),
            7.0,
        ),
    ];
    let settings = Settings::DEFAULT;
    let (mut compared, mut complete, mut shared) = (0, 0, 0);
    for (m, lambda) in scenes {
        let at = move |phi: f64| Some((m, phi));
        let slices = std::cell::Cell::new(0);
        let walker = Walker {
            slices: &slices,
            at: &at,
            thetas: &Joints::Every,
            lambda,
            settings: &settings,
            path: Path::Friction,
            end: f64::NEG_INFINITY,
            frames: std::cell::OnceCell::new(),
        };
        let mut prev: Option<Slice> = None;
        for deg in (10..=89).rev() {
            let (geom, cur) = walker.slice((deg as f64).to_radians()).unwrap();
            let every = outcome(walker.complete_in(&geom, &cur, None, &|_, _| true));
            if let Some(pr) = &prev {
                let known = outcome(walker.complete_in(&geom, &cur, Some(pr), &|_, _| true));
                assert_eq!(known, every, "{deg}°");
                compared += 1;
                complete += usize::from(every.is_some());
                shared += cur
                    .vertices
                    .keys()
                    .filter(|k| pr.vertices.contains_key(*k))
                    .count();
            }
            // The skip holds only after a step without a complete vertex, as the scan takes it.
            prev = every.is_none().then_some(cur);
        }
    }
    assert!(compared > 60, "{compared} steps compared");
    assert!(complete >= 1, "{complete} steps with a complete vertex");
    assert!(shared > 100, "{shared} vertices known from the step before");
}
