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
