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
    eprintln!("{s:#?}");
    assert_eq!(s.status, GapStatus::Gap);
    let c = s.first.unwrap();
    assert!((c.state.y[3] - 7.383083).abs() < 5e-7, "{}", c.state.y[3]);
    assert!((s.static_limit.unwrap() - 8.518042010861949).abs() < 1e-9);
}

#[test]
fn probe_continuum_sampling() {
    for load in [Load::Horizontal, Load::Point { at_deg: 30.0 }] {
        for (k, half, mu) in [(1.5278, 50.367, 1.0396), (1.3, 90.0, 0.6), (1.2, 60.0, 0.8)] {
            let m = model(k, half, Discretisation::Continuum, load);
            for n in [9, 17, 33] {
                let st = Settings {
                    continuum_joints: n,
                    ..Settings::DEFAULT
                };
                let t = std::time::Instant::now();
                let s = first_complete_load_factor(&m, f64::atan(mu), &st);
                let el = t.elapsed();
                eprintln!(
                    "{load:?} k={k} n={n} status={:?} first={:?} static={:?} verts={} {:?} mech={:?}",
                    s.status,
                    s.first.as_ref().map(|c| c.state.y[3]),
                    s.static_limit,
                    s.vertices,
                    el,
                    s.first
                        .as_ref()
                        .map(|c| (&c.mechanism.mechanism, &c.mechanism.lifted_deg))
                );
            }
        }
    }
}

#[test]
fn probe_friction_path() {
    let m = model(
        1.5278,
        50.367,
        Discretisation::Voussoirs(12),
        Load::Horizontal,
    );
    let s = first_complete_friction(&m, 5.0, 0.842831173042, &Settings::DEFAULT);
    eprintln!(
        "{:?} {:?} {}",
        s.status,
        s.first.as_ref().map(|c| c.value),
        s.vertices
    );
    let g = m;
    let at = move |phi: f64| Some((g, phi));
    let w = path::Walker {
        at: &at,
        thetas: None,
        lambda: 5.0,
        settings: &Settings::DEFAULT,
    };
    for mu in [1000.0, 10.0, 1.0, 0.9, 0.85, 0.8429] {
        let sl = w.slice(f64::atan(mu));
        eprintln!("mu {mu}: {:?}", sl.map(|(_, s)| s.vertices.len()));
    }
}
