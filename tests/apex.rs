//! A point load at the apex of a pointed arch (docs/loads-and-geometries.md, *A point load
//! at the apex*): the values of the two modelling choices the model makes today, each shown
//! two ways.

use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Outcome, Scene};

/// The scene of the issue: e = 0.1213, α = 45.37°, K = 1.340132, P = 0.166277·W at the apex.
fn apex(joints: Discretisation) -> f64 {
    apex_both(joints).0
}

/// The find's μ (the whole load on the right half) and μ with the load shared freely.
fn apex_both(joints: Discretisation) -> (f64, Option<f64>) {
    let arch = Arch::new(1.340132, 45.37, WeightModel::Annular, joints).unwrap();
    let s = Scene {
        arch,
        friction: Friction::new(f64::INFINITY).unwrap(),
        find: Find::Friction,
        form: ArchForm {
            shape: Shape::Pointed {
                eccentricity: 0.1213,
            },
            joints: JointOrientation::Radial,
            keystone: false,
        },
        load: Load::point(0.0),
        lambda: 0.166277,
    };
    let sol = scene::solve(&s);
    assert_eq!(sol.outcome, Some(Outcome::Found), "{joints:?}");
    (sol.mu_crit.unwrap(), sol.critical_apex_shared)
}

/// The crown joint between the halves with the load on the right half (the continuum, and
/// every even voussoir count, whose middle joint is the crown joint): μ = 0.077329, the same
/// on the continuum and on 2000 and 4000 voussoirs.
#[test]
fn apex_load_on_one_half_continuum_and_voussoirs_agree() {
    let continuum = apex(Discretisation::Continuum);
    approx::assert_abs_diff_eq!(continuum, 0.0773289, epsilon = 1e-6);
    for n in [2000, 4000] {
        approx::assert_abs_diff_eq!(
            apex(Discretisation::Voussoirs(n)),
            continuum,
            epsilon = 1e-6
        );
    }
}

/// An odd voussoir count puts a keystone over the apex: the load sits on the keystone, whose
/// two joints share it symmetrically, and the arch needs half the friction: μ = 0.038024 on
/// 2001 and 4001 voussoirs alike.
#[test]
fn apex_load_on_a_keystone_fine_models_agree() {
    let a = apex(Discretisation::Voussoirs(2001));
    let b = apex(Discretisation::Voussoirs(4001));
    approx::assert_abs_diff_eq!(a, 0.0380245, epsilon = 1e-6);
    approx::assert_abs_diff_eq!(a, b, epsilon = 1e-6);
}

/// The split of the apex load between the halves is statically indeterminate: the find's μ
/// (whole load on one half, the least favourable split) and `critical_apex_shared` (free
/// split, the most favourable) bound every split. The free split equals the keystone value of
/// the odd counts (0.038024) on the continuum and on 2000 and 4000 voussoirs; a keystone
/// model has no split to choose and reports none.
#[test]
fn apex_load_split_is_bounded_by_one_half_and_the_free_split() {
    for joints in [
        Discretisation::Continuum,
        Discretisation::Voussoirs(2000),
        Discretisation::Voussoirs(4000),
    ] {
        let (one_half, shared) = apex_both(joints);
        let shared = shared.unwrap();
        approx::assert_abs_diff_eq!(one_half, 0.0773289, epsilon = 1e-6);
        approx::assert_abs_diff_eq!(shared, 0.0380245, epsilon = 1e-6);
    }
    let keystone = apex_both(Discretisation::Voussoirs(2001));
    assert_eq!(keystone.1, None);
    let continuum = apex_both(Discretisation::Continuum).1.unwrap();
    approx::assert_relative_eq!(continuum, keystone.0, max_relative = 1e-6);
}

/// A load off the apex, and an apex load on a circular arch (whose continuum has both sides
/// of the load as joints), have no split to bound.
#[test]
fn only_an_apex_load_on_a_pointed_arch_reports_the_free_split() {
    let arch = Arch::new(1.3, 90.0, WeightModel::Annular, Discretisation::Continuum).unwrap();
    let mut s = Scene::new(arch, Friction::new(0.5).unwrap(), Find::LoadFactor);
    s.load = Load::point(0.0);
    assert_eq!(scene::solve(&s).critical_apex_shared, None);
    s.form.shape = Shape::Pointed { eccentricity: 0.1 };
    let at_apex = scene::solve(&s);
    let (lambda, shared) = (
        at_apex.load_factor.unwrap(),
        at_apex.critical_apex_shared.unwrap(),
    );
    // A free split can only help: λ_max with it is at least the one-half value.
    assert!(shared >= lambda - 1e-9, "{shared} < {lambda}");
    s.load = Load::point(30.0);
    assert_eq!(scene::solve(&s).critical_apex_shared, None);
}

/// results.parquet stores `mechanism_admissible` and `critical_apex_shared` where the route
/// computes them, null otherwise: a friction study with the apex scene (both filled; the free
/// split 0.0380245 beside μ_c = 0.0773289) and a load 20° off the apex (no split: null), and
/// a state study, whose find computes neither (the columns are left out). The merge path reads
/// both back.
#[test]
fn results_parquet_stores_admissibility_and_the_free_split() {
    use archstudy::{engine, manifest, plan, progress, store};
    use std::path::Path;
    let studies = [
        "name: apex
arch: {shape: pointed, eccentricity: 0.1213, half_angle_deg: 45.37}
grid:
  k: {values: [1.340132]}
load_cases:
  - {name: apex, kind: point, at_deg: 0, lambda: 0.166277}
  - {name: off, kind: point, at_deg: 20, lambda: 0.166277}
find: friction
",
        "name: plain
grid:
  k: {values: [1.2]}
  mu: {values: [0.4]}
",
    ];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("results.parquet");
    for (i, text) in studies.into_iter().enumerate() {
        let m = manifest::parse(text, Path::new("s.yaml")).unwrap();
        let plan = plan::build(m).unwrap();
        let rows = engine::run(&plan, &progress::Silent);
        store::write_parquet(&mut store::results_frame(&plan, &rows).unwrap(), &path).unwrap();
        let df = store::read_parquet(&path).unwrap();
        if i == 1 {
            for name in ["mechanism_admissible", "critical_apex_shared"] {
                assert!(df.column(name).is_err(), "a state study stores {name}");
            }
            continue;
        }
        let admissible = df.column("mechanism_admissible").unwrap();
        let admissible: Vec<Option<bool>> = admissible.bool().unwrap().iter().collect();
        let shared = store::f64_column(&df, "critical_apex_shared").unwrap();
        let mu = store::f64_column(&df, "mu_crit").unwrap();
        assert_eq!(admissible, vec![Some(true), Some(true)]);
        approx::assert_abs_diff_eq!(mu[0].unwrap(), 0.0773289, epsilon = 1e-6);
        approx::assert_abs_diff_eq!(shared[0].unwrap(), 0.0380245, epsilon = 1e-6);
        assert_eq!(shared[1], None);
        // Read back into the engine's rows (a merge): both fields as solved.
        let back = store::read_case_results(&plan, &path).unwrap();
        for (a, b) in rows.iter().zip(&back) {
            assert_eq!(
                (
                    a.solution.mechanism_admissible,
                    a.solution.critical_apex_shared
                ),
                (
                    b.solution.mechanism_admissible,
                    b.solution.critical_apex_shared
                )
            );
        }
        for name in ["mechanism_admissible", "critical_apex_shared"] {
            let (_, meaning) = store::column_doc(name).unwrap();
            assert!(!meaning.is_empty(), "{name}");
        }
    }
}
