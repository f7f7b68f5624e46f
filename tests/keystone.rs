//! The keystone option (docs/loads-and-geometries.md, *Keystone*): a pointed arch in the
//! continuum with the crown inside one rigid block, checked against fine odd voussoir counts,
//! which put a keystone over the apex, and refused where a form has none.

use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Outcome, Scene};

fn pointed(e: f64, keystone: bool) -> ArchForm {
    ArchForm {
        shape: Shape::Pointed { eccentricity: e },
        joints: JointOrientation::Radial,
        keystone,
    }
}

/// The apex scene of tests/apex.rs: e = 0.1213, α = 45.37°, K = 1.340132, λ = 0.166277.
fn apex_mu(joints: Discretisation, keystone: bool) -> f64 {
    let s = Scene {
        arch: Arch::new(1.340132, 45.37, WeightModel::Annular, joints).unwrap(),
        friction: Friction::new(f64::INFINITY).unwrap(),
        find: Find::Friction,
        form: pointed(0.1213, keystone),
        load: Load::point(0.0),
        lambda: 0.166277,
    };
    let sol = scene::solve(&s);
    assert_eq!(sol.outcome, Some(Outcome::Found), "{joints:?}");
    assert_eq!(
        sol.critical_apex_shared, None,
        "a keystone has no split to choose"
    );
    sol.mu_crit.unwrap()
}

/// With the keystone the continuum has no crown joint: the apex load lies on one block, and
/// μ_c is the keystone value of 2001 and 4001 voussoirs (0.0380245), not the 0.0773289 of a
/// crown joint with the load on one half.
#[test]
fn apex_load_on_the_keystone_equals_odd_voussoirs() {
    let continuum = apex_mu(Discretisation::Continuum, true);
    approx::assert_abs_diff_eq!(continuum, 0.0380245, epsilon = 1e-6);
    for n in [2001, 4001] {
        let discrete = apex_mu(Discretisation::Voussoirs(n), true);
        approx::assert_abs_diff_eq!(discrete, continuum, epsilon = 1e-7);
    }
}

/// λ_max of a point load at `at_deg` on a pointed arch (e = 0.3, α = 90°, K = 1.15, μ = 0.6)
/// with a keystone: ψ₁ = 18.814°, the extrados apex at 16.293°.
fn keystone_lambda(at_deg: f64, joints: Discretisation) -> f64 {
    let s = Scene {
        arch: Arch::new(1.15, 90.0, WeightModel::Annular, joints).unwrap(),
        friction: Friction::new(0.6).unwrap(),
        find: Find::LoadFactor,
        form: pointed(0.3, true),
        load: Load::point(at_deg),
        lambda: 0.0,
    };
    let sol = scene::solve(&s);
    assert_eq!(sol.outcome, Some(Outcome::Found), "{at_deg}° {joints:?}");
    sol.load_factor.unwrap()
}

/// Loads on the keystone off the apex, and one beyond it: the continuum's λ_max against 2001
/// and 4001 voussoirs. The discrete values lie above the continuum and converge to it at
/// first order in 1/N (their gap, about 1.8e-3 and 0.9e-3, halves); the Richardson
/// extrapolation 2λ₄₀₀₁ − λ₂₀₀₁ meets the continuum within 1e-5.
#[test]
fn loads_on_the_keystone_converge_to_the_continuum() {
    for (at_deg, expected) in [
        (0.0, 0.7532291),
        (17.0, 0.6605207),
        (18.0, 0.5616365),
        (-17.5, 0.6073713),
        (25.0, 0.2053250),
    ] {
        let c = keystone_lambda(at_deg, Discretisation::Continuum);
        let a = keystone_lambda(at_deg, Discretisation::Voussoirs(2001));
        let b = keystone_lambda(at_deg, Discretisation::Voussoirs(4001));
        approx::assert_abs_diff_eq!(c, expected, epsilon = 1e-6);
        assert!(a > b && b > c, "{at_deg}°: {a} {b} {c}");
        approx::assert_abs_diff_eq!(2.0 * b - a, c, epsilon = 1e-5);
    }
}

/// Without the keystone a load between the crown joint and ψ₁ is refused; with it, a load
/// nearer the crown than the extrados apex is refused (no extrados point is at that angle),
/// as are the forms without a keystone.
#[test]
fn keystone_refusals() {
    use archstudy::analysis::forms::{ArchModel, FormError};
    use archstudy::model::KeystoneRefusal;
    let arch = |joints| Arch::new(1.15, 90.0, WeightModel::Annular, joints).unwrap();
    let c = Discretisation::Continuum;
    let at = Load::point;
    assert!(matches!(
        ArchModel::new(arch(c), pointed(0.3, false), at(17.0)),
        Err(FormError::LoadInsideKeystone { .. })
    ));
    assert!(matches!(
        ArchModel::new(arch(c), pointed(0.3, true), at(16.0)),
        Err(FormError::LoadOffExtrados { .. })
    ));
    let circular = ArchForm {
        keystone: true,
        ..ArchForm::default()
    };
    let vertical = ArchForm {
        joints: JointOrientation::Vertical,
        ..pointed(0.3, true)
    };
    for (form, joints, why) in [
        (circular, c, KeystoneRefusal::Circular),
        (vertical, c, KeystoneRefusal::Vertical),
        (
            pointed(0.3, true),
            Discretisation::Voussoirs(20),
            KeystoneRefusal::EvenVoussoirs(20),
        ),
    ] {
        assert_eq!(
            ArchModel::new(arch(joints), form, Load::SelfWeight).err(),
            Some(FormError::NoKeystone(why))
        );
    }
    // An odd count has a keystone whatever the form; loads between the vertical joints at
    // ±ψ₁ (the crown plane) do not exist.
    let odd = arch(Discretisation::Voussoirs(21));
    assert!(ArchModel::new(odd, circular, Load::SelfWeight).is_ok());
    assert!(matches!(
        ArchModel::new(odd, vertical, at(10.0)),
        Err(FormError::LoadInsideKeystone { .. })
    ));
}

/// A load-factor study with `keystone: true`: every row says so in results.parquet, and the
/// loads on the keystone (17° and 18°, inside ψ₁ = 18.814°) get the continuum's λ_max above.
#[test]
fn keystone_study_stores_its_column() {
    use crate::common::{run_study, scratch};
    use archstudy::store;
    let dir = scratch("keystone-study");
    let text = "name: ks
arch: {shape: pointed, eccentricity: 0.3, keystone: true}
grid:
  at_deg: {values: [0, 17, 18]}
  k: {values: [1.15]}
  mu: {values: [0.6]}
load_cases:
  - {name: p, kind: point}
find: load_factor
";
    let run = run_study(&dir, "ks.yaml", text);
    let df = store::read_parquet(&run.join("results.parquet")).unwrap();
    let keystone = store::bool_column(&df, "keystone").unwrap();
    assert_eq!(keystone, vec![Some(true); 3]);
    let lf = store::f64_column(&df, "load_factor").unwrap();
    for (got, want) in lf.iter().zip([0.7532291, 0.6605207, 0.5616365]) {
        approx::assert_abs_diff_eq!(got.unwrap(), want, epsilon = 1e-6);
    }
}

/// The manifest refuses a keystone where the form has none, and a load on the keystone
/// nearer the crown than the extrados apex; `solve --keystone` likewise.
#[test]
fn keystone_usage_errors() {
    use crate::common::{archstudy, assert_usage_error, manifest, scratch};
    let dir = scratch("keystone-refusals");
    for (arch, at, names) in [
        (
            "{keystone: true}",
            "30",
            &["arch.keystone", "circular arch has no keystone"][..],
        ),
        (
            "{shape: pointed, eccentricity: 0.3, keystone: true, voussoirs: 40}",
            "30",
            &["arch.keystone", "40 voussoirs"][..],
        ),
        (
            "{shape: pointed, eccentricity: 0.3, keystone: true}",
            "16",
            &["grid.at_deg", "16", "extrados"][..],
        ),
        (
            "{shape: pointed, eccentricity: 0.3}",
            "17",
            &["grid.at_deg", "17", "keystone: true"][..],
        ),
    ] {
        let text = format!(
            "name: bad\narch: {arch}\ngrid:\n  at_deg: {{values: [{at}]}}\n  k: {{values: [1.15]}}\n  mu: {{values: [0.6]}}\nload_cases:\n  - {{name: p, kind: point}}\nfind: load_factor\n"
        );
        let m = manifest(&dir, "bad.yaml", &text);
        assert_usage_error(&archstudy(&["check", m.to_str().unwrap()]), names);
    }
    // A thickness find has no K axis: its path runs down towards K = 1, where the keystone's
    // extrados starts at asin 0.3 = 17.4576°; `solve` refuses 10° there, and so does a manifest.
    let text = "name: bad\narch: {shape: pointed, eccentricity: 0.3, keystone: true}\ngrid:\n  mu: {values: [0.6]}\nload_cases:\n  - {name: p, kind: point, at_deg: 10, lambda: 0.2}\nfind: thickness\n";
    let m = manifest(&dir, "thickness.yaml", text);
    assert_usage_error(
        &archstudy(&["check", m.to_str().unwrap()]),
        &["at_deg", "10", "17.457603", "x/L"],
    );
    // Without a keystone no joint lies there on any arch of the path: `solve` refuses it, and
    // so does a manifest.
    let m = manifest(
        &dir,
        "no-keystone.yaml",
        &text.replace(", keystone: true", ""),
    );
    assert_usage_error(
        &archstudy(&["check", m.to_str().unwrap()]),
        &["at_deg", "10", "17.457603", "thickness find"],
    );
    let o = archstudy(&[
        "solve",
        "--find",
        "load-factor",
        "--load",
        "point",
        "--at",
        "10",
        "--keystone",
    ]);
    assert_usage_error(&o, &["--keystone", "circular arch"]);
}

/// A thickness find whose load passes onto the keystone (e = 0.25, α = 82°, μ = 0.25, the
/// load by angle at 17.4°, λ = 0.2): the keystone's edge ψ₁ = asin(e(1 + K)/2) reaches the
/// load at K* = 2 sin 17.4°/e − 1. Below K* the load sits beyond the edge joint, on a sliver
/// that slides off (λ_max ≈ 0.094); from K* on it lies on the keystone (λ_max ≈ 0.256). The
/// margin jumps across zero there, so K_c = K* is a threshold, not a limit state: no
/// mechanism and no work equation are reported (the state there has a margin of about 0.014,
/// and its active rows are those of the largest margin).
#[test]
fn thickness_at_the_keystone_edge_is_a_threshold_without_a_mechanism() {
    let (e, at_deg) = (0.25, 17.4f64);
    let scene = |k: f64, find: Find| Scene {
        arch: Arch::new(k, 82.0, WeightModel::Annular, Discretisation::Continuum).unwrap(),
        friction: Friction::new(0.25).unwrap(),
        find,
        form: pointed(e, true),
        load: Load::point(at_deg),
        lambda: if find == Find::LoadFactor { 0.0 } else { 0.2 },
    };
    let k_star = 2.0 * at_deg.to_radians().sin() / e - 1.0;
    let s = scene::solve(&scene(1.5, Find::Thickness));
    assert_eq!(s.outcome, Some(Outcome::Found), "{s:?}");
    approx::assert_abs_diff_eq!(s.k_crit.unwrap(), k_star, epsilon = 1e-12);
    assert_eq!(s.mechanism, None, "{s:?}");
    assert!(s.hinges.is_empty() && s.sliding_joints.is_empty(), "{s:?}");
    assert_eq!(
        (s.work_residual, s.mechanism_dof, s.mechanism_admissible),
        (None, None, None)
    );
    let lambda = |k: f64| {
        let l = scene::solve(&scene(k, Find::LoadFactor));
        assert_eq!(l.outcome, Some(Outcome::Found), "K {k}");
        l.load_factor.unwrap()
    };
    let (below, above) = (lambda(k_star - 1e-9), lambda(k_star + 1e-9));
    assert!(
        below < 0.15 && above > 0.25,
        "λ_max {below} below K*, {above} above"
    );
}

/// λ_max of a point load at x/L on the continuum and on N = 2001, 4001 and 8001 voussoirs
/// (odd counts, so with a keystone; `even` takes 2000, 4000 and 8000): the discrete values lie
/// above the continuum, fall with N, and their extrapolation to 1/N = 0 through
/// λ = c + A/N + B/N² (first-order convergence, with the second-order term that two counts
/// leave at 1e-4 on these scenes) meets the continuum to 1e-6 of λ. Returns the continuum's
/// λ_max.
fn x_over_l_converges(
    arch_at: impl Fn(Discretisation) -> Arch,
    form: ArchForm,
    at_x: f64,
    mu: f64,
    even: bool,
) -> f64 {
    let lambda = |joints| {
        let s = scene::solve(&Scene {
            arch: arch_at(joints),
            friction: Friction::new(mu).unwrap(),
            find: Find::LoadFactor,
            form,
            load: Load::point_x(at_x),
            lambda: 0.0,
        });
        assert_eq!(
            s.outcome,
            Some(Outcome::Found),
            "x/L {at_x} {joints:?}: {s:?}"
        );
        assert_eq!(s.at_x, Some(at_x));
        s.load_factor.unwrap()
    };
    let c = lambda(Discretisation::Continuum);
    let ns: [u32; 3] = if even {
        [2000, 4000, 8000]
    } else {
        [2001, 4001, 8001]
    };
    let l = ns.map(|n| lambda(Discretisation::Voussoirs(n)));
    assert!(
        l[0] > l[1] && l[1] > l[2] && l[2] > c,
        "x/L {at_x}: {l:?} {c}"
    );
    // Lagrange's polynomial through (1/N, λ_N), evaluated at 1/N = 0.
    let h = ns.map(|n| 1.0 / f64::from(n));
    let extrapolated: f64 = (0..3)
        .map(|i| {
            let w: f64 = (0..3)
                .filter(|&j| j != i)
                .map(|j| h[j] / (h[j] - h[i]))
                .product();
            w * l[i]
        })
        .sum();
    approx::assert_abs_diff_eq!(extrapolated, c, epsilon = 1e-6 * c.max(1.0));
    c
}

/// Keystone and x/L scenes beyond the one of tests/span_positions.rs: a load left of the apex
/// on the keystone of another pointed arch (e = 0.2, α = 80°, K = 1.25: the keystone's
/// extrados spans x/L 0.4720 to 0.5280) at μ = 0.6 and 0.4, and a load on the springing wedge
/// of a vertical-joint arch (α = 60°, K = 1.5, μ = 0.5, x/L = 0.03, beyond the vertical joint
/// at −60°), against fine voussoirs.
#[test]
fn keystone_and_wedge_loads_by_x_over_l_converge_to_the_continuum() {
    let keystone_arch = |joints| Arch::new(1.25, 80.0, WeightModel::Annular, joints).unwrap();
    for (mu, expected) in [(0.6, 5.0189137), (0.4, 0.7199306)] {
        let c = x_over_l_converges(keystone_arch, pointed(0.2, true), 0.48, mu, false);
        approx::assert_abs_diff_eq!(c, expected, epsilon = 1e-6);
    }
    let wedge_arch = |joints| Arch::new(1.5, 60.0, WeightModel::Annular, joints).unwrap();
    let vertical = ArchForm {
        joints: JointOrientation::Vertical,
        ..ArchForm::default()
    };
    let c = x_over_l_converges(wedge_arch, vertical, 0.03, 0.5, true);
    approx::assert_abs_diff_eq!(c, 13.1900814, epsilon = 1e-6);
}
