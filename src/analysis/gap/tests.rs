use super::*;
use crate::analysis::forms::ArchModel;
use crate::model::{Arch, ArchForm, Discretisation, Load, WeightModel};

fn model(k: f64, half_deg: f64, joints: Discretisation, load: Load) -> ArchModel {
    let arch = Arch::new(k, half_deg, WeightModel::Annular, joints).unwrap();
    ArchModel::new(arch, ArchForm::default(), load).unwrap()
}

#[test]
fn twelve_voussoirs_under_horizontal_load_collapse_below_the_static_limit() {
    let m = model(
        1.5278,
        50.367,
        Discretisation::Voussoirs(12),
        Load::Horizontal,
    );
    let s = first_complete_load_factor(&m, 1.0396_f64.atan(), &Settings::DEFAULT);
    assert_eq!(s.status, GapStatus::Gap);
    let c = s.first.unwrap();
    assert!((c.state.y[3] - 7.383083).abs() < 5e-7, "{}", c.state.y[3]);
    assert!((s.static_limit.unwrap() - 8.518042010861949).abs() < 1e-9);
}

#[test]
fn the_continuum_solved_on_its_own_joints_agrees_with_fine_voussoirs() {
    // The continuum's lowest complete vertex on sampled joints is solved on the continuum
    // (hinges where their rows are tangent). Voussoirs approach it from above as their joints
    // near the tangency: 250, 500 and 1000 voussoirs share the joint nearest to it.
    let phi = 1.0396_f64.atan();
    let first = |joints| {
        let s = first_complete_load_factor(
            &model(1.5278, 50.367, joints, Load::Horizontal),
            phi,
            &Settings::DEFAULT,
        );
        assert_eq!(s.status, GapStatus::Gap);
        s.first.unwrap().value
    };
    let continuum = first(Discretisation::Continuum);
    assert!((continuum - 7.2845223058).abs() < 1e-9, "{continuum}");
    let coarse = first(Discretisation::Voussoirs(500));
    assert!((coarse - 7.2845643074).abs() < 1e-9, "{coarse}");
    let fine = first(Discretisation::Voussoirs(2000));
    assert!(fine > continuum && fine - continuum < 5e-8, "{fine}");
}
