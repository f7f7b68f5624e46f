//! The search for the first complete solution beside the static find it follows
//! (`cargo bench --bench gap`): the load factor of twelve voussoirs and of the continuum under a
//! horizontal load (a gap) and of twelve voussoirs of the semicircle under a point load (none),
//! and the friction and thickness paths of the semicircle under self-weight and of five
//! voussoirs with vertical joints. Each pair compares the static limit alone with the search
//! that `archstudy solve` adds to it; the friction and thickness searches are timed without the
//! static find that gives them the end of their path.

use archstudy::analysis::forms::ArchModel;
use archstudy::analysis::gap::{self, Settings};
use archstudy::analysis::general;
use archstudy::analysis::symmetric;
use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use divan::black_box;

fn main() {
    divan::main();
}

fn model(k: f64, half: f64, joints: Discretisation, form: ArchForm, load: Load) -> ArchModel {
    let arch = Arch::new(k, half, WeightModel::Annular, joints).expect("an arch");
    ArchModel::new(arch, form, load).expect("a form")
}

fn issue_scene(joints: Discretisation) -> ArchModel {
    model(
        1.5278,
        50.367,
        joints,
        ArchForm::default(),
        Load::Horizontal,
    )
}

const MU: f64 = 1.0396;

/// λ_max of twelve voussoirs (the static limit alone).
#[divan::bench]
fn load_factor_static_voussoirs() -> f64 {
    let m = issue_scene(Discretisation::Voussoirs(12));
    general::load_factor(black_box(&m), MU.atan(), &general::Settings::default()).lambda
}

/// The first complete λ of twelve voussoirs.
#[divan::bench]
fn load_factor_first_complete_voussoirs() -> Option<f64> {
    let m = issue_scene(Discretisation::Voussoirs(12));
    gap::first_complete_load_factor(black_box(&m), MU.atan(), &Settings::DEFAULT)
        .first
        .map(|c| c.value)
}

/// λ_max of the continuum (the static limit alone).
#[divan::bench]
fn load_factor_static_continuum() -> f64 {
    let m = issue_scene(Discretisation::Continuum);
    general::load_factor(black_box(&m), MU.atan(), &general::Settings::default()).lambda
}

/// The first complete λ of the continuum.
#[divan::bench]
fn load_factor_first_complete_continuum() -> Option<f64> {
    let m = issue_scene(Discretisation::Continuum);
    gap::first_complete_load_factor(black_box(&m), MU.atan(), &Settings::DEFAULT)
        .first
        .map(|c| c.value)
}

/// Twelve voussoirs of a semicircle (K = 1.5) under a point load at 45° from the crown: the
/// paper's form, no gap.
fn point_load_scene() -> ArchModel {
    model(
        1.5,
        90.0,
        Discretisation::Voussoirs(12),
        ArchForm::default(),
        Load::point(45.0),
    )
}

/// λ_max of twelve voussoirs under a point load (the static limit alone).
#[divan::bench]
fn load_factor_static_point_load() -> f64 {
    let m = point_load_scene();
    general::load_factor(black_box(&m), 0.6_f64.atan(), &general::Settings::default()).lambda
}

/// The first complete λ of twelve voussoirs under a point load (no gap).
#[divan::bench]
fn load_factor_first_complete_point_load() -> Option<f64> {
    let m = point_load_scene();
    gap::first_complete_load_factor(black_box(&m), 0.6_f64.atan(), &Settings::DEFAULT)
        .first
        .map(|c| c.value)
}

fn semicircle(k: f64) -> Arch {
    Arch::new(k, 90.0, WeightModel::Annular, Discretisation::Continuum).expect("an arch")
}

/// Times the first complete μ of `m` under self-weight, its static limit `mu_c` given.
fn bench_friction(bencher: divan::Bencher, m: &ArchModel, mu_c: f64) {
    bencher.bench(|| {
        gap::first_complete_friction(black_box(m), 0.0, mu_c, &Settings::DEFAULT)
            .first
            .map(|c| c.value)
    });
}

/// μ_c of the semicircle at K = 1.3 by its closed forms (the static limit alone).
#[divan::bench]
fn friction_static_semicircle() -> Option<f64> {
    symmetric::friction(black_box(&semicircle(1.3)))
        .found()
        .map(|s| s.mu)
}

/// The first complete μ of the semicircle at K = 1.3 (its static limit found beforehand).
#[divan::bench]
fn friction_first_complete_semicircle(bencher: divan::Bencher) {
    let m = model(
        1.3,
        90.0,
        Discretisation::Continuum,
        ArchForm::default(),
        Load::SelfWeight,
    );
    let mu_c = symmetric::friction(&semicircle(1.3))
        .found()
        .map(|s| s.mu)
        .expect("a critical friction");
    bench_friction(bencher, &m, mu_c);
}

/// K_c of the semicircle at μ = 0.6 by its closed forms (the static limit alone).
#[divan::bench]
fn thickness_static_semicircle() -> Option<f64> {
    let f = Friction::new(0.6).expect("μ ≥ 0");
    symmetric::thickness(black_box(&semicircle(1.3)), f)
        .found()
        .map(|s| s.k)
}

/// The first complete K of the semicircle at μ = 0.6, from K = 3 (its static limit found
/// beforehand).
#[divan::bench]
fn thickness_first_complete_semicircle(bencher: divan::Bencher) {
    let f = Friction::new(0.6).expect("μ ≥ 0");
    let k_c = symmetric::thickness(&semicircle(1.3), f)
        .found()
        .map(|s| s.k)
        .expect("a critical thickness");
    let make = |k: f64| ArchModel::new(semicircle(k), ArchForm::default(), Load::SelfWeight).ok();
    bencher.bench(|| {
        gap::first_complete_thickness(
            black_box(&make),
            f.angle(),
            0.0,
            k_c,
            3.0,
            &Settings::DEFAULT,
        )
        .first
        .map(|c| c.value)
    });
}

fn vertical() -> ArchForm {
    ArchForm {
        shape: Shape::Circular,
        joints: JointOrientation::Vertical,
        keystone: false,
    }
}

/// μ_c of five voussoirs with vertical joints (the static limit alone).
#[divan::bench]
fn friction_static_vertical_joints() -> Option<f64> {
    let m = model(
        1.3,
        90.0,
        Discretisation::Voussoirs(5),
        vertical(),
        Load::SelfWeight,
    );
    general::friction(black_box(&m), &general::Settings::default())
        .found()
        .map(|s| s.mu)
}

/// The first complete μ of five voussoirs with vertical joints (the crown part drops; its
/// static limit found beforehand).
#[divan::bench]
fn friction_first_complete_vertical_joints(bencher: divan::Bencher) {
    let m = model(
        1.3,
        90.0,
        Discretisation::Voussoirs(5),
        vertical(),
        Load::SelfWeight,
    );
    let mu_c = general::friction(&m, &general::Settings::default())
        .found()
        .map(|s| s.mu)
        .expect("a critical friction");
    bench_friction(bencher, &m, mu_c);
}
