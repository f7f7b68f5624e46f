//! Load cases and arch forms: the general three-unknown route against the reference values,
//! horizontal and point loads, continuum against fine voussoirs, a hand-checked load factor,
//! the manifest keys, the command-line options and the stored columns.

use crate::common::reference::{
    HAUNCH_DEG as HAUNCH, K_BIF, K_C, MU_MIN, MU_ROT, SLIDING_DEG, T_OVER_R_C,
};
use crate::common::{archstudy, assert_usage_error, manifest, scratch, solve_json, stderr};
use archstudy::analysis::forms::ArchModel;
use archstudy::analysis::{Face, MechanismKind, Regime};
use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Outcome, Scene, Solution};
use archstudy::store;
use std::path::Path;

fn arch(k: f64, joints: Discretisation) -> Arch {
    Arch::new(k, 90.0, WeightModel::Annular, joints).unwrap()
}

fn mu(m: f64) -> Friction {
    Friction::new(m).unwrap()
}

fn pointed(e: f64) -> ArchForm {
    ArchForm {
        shape: Shape::Pointed { eccentricity: e },
        joints: JointOrientation::Radial,
        keystone: false,
    }
}

fn vertical() -> ArchForm {
    ArchForm {
        shape: Shape::Circular,
        joints: JointOrientation::Vertical,
        keystone: false,
    }
}

fn scene(arch: Arch, friction: Friction, find: Find, form: ArchForm, load: Load) -> Scene {
    Scene {
        arch,
        friction,
        find,
        form,
        load,
        lambda: 0.0,
    }
}

/// λ_max of the live load (None when unbounded or when the arch never stands).
fn lambda_max(arch: Arch, m: Friction, form: ArchForm, load: Load) -> Solution {
    scene::solve(&scene(arch, m, Find::LoadFactor, form, load))
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn general_route_reproduces_the_reference_values() {
    // A pointed arch with e = 0 is the semicircle, analysed by the general formulation
    // (the path of every pointed arch); so is the circular arch under a live load at λ = 0.
    let forms = [
        (pointed(0.0), Load::SelfWeight),
        (ArchForm::default(), Load::Horizontal),
    ];
    for (form, load) in forms {
        let a = arch(1.35, Discretisation::Continuum);
        let what = format!("{form:?} {load:?}");
        let s = |find: Find, a: Arch, m: Friction| scene::solve(&scene(a, m, find, form, load));
        let t = s(Find::Thickness, a, Friction::INFINITE);
        assert_eq!(t.outcome, Some(Outcome::Found), "{what}");
        let kc = t.k_crit.unwrap();
        assert!(close(kc, K_C, 1e-9), "{what}: K_c = {kc}");
        assert!(close(t.t_over_r_crit.unwrap(), T_OVER_R_C, 1e-9));
        assert!(close(t.thrust_over_half_weight.unwrap(), MU_ROT, 1e-9));
        assert_eq!(t.mechanism, Some(MechanismKind::Rotational));
        let haunch = t.hinges.iter().find(|h| h.face == Face::Intrados).unwrap();
        assert!(
            close(haunch.angle_deg.abs(), HAUNCH, 1e-6),
            "{:?}",
            t.hinges
        );
        // μ at the rotational/mixed bifurcation: the critical friction at K_c.
        let f = s(Find::Friction, a.with_k(kc), Friction::INFINITE);
        assert!(close(f.mu_crit.unwrap(), MU_ROT, 1e-9), "{what}: {f:?}");
        // μ_min: the critical friction of any K above the mixed/sliding bifurcation.
        let f = s(Find::Friction, a.with_k(1.4), Friction::INFINITE);
        let mu_min = f.mu_crit.unwrap();
        assert!(close(mu_min, MU_MIN, 1e-9), "{what}: μ_min = {mu_min}");
        assert_eq!(f.mechanism, Some(MechanismKind::Sliding));
        let angles: Vec<f64> = f.sliding_joints.iter().map(|j| j.angle_deg).collect();
        assert!(close(angles[2], SLIDING_DEG, 1e-6) && close(angles[3], 90.0, 1e-9));
        // K at the mixed/sliding bifurcation: the collapse thickness at μ_min, taken a hair
        // above it (1e-13 relative, far below the 1e-9 asserted): μ_min was found at K = 1.4
        // at the edge of the feasibility tolerance, and the sliding margin at another K
        // differs from it by rounding, which must not decide whether the arch can stand.
        let b = s(Find::Thickness, a, mu(mu_min * (1.0 + 1e-13)));
        assert!(close(b.k_crit.unwrap(), K_BIF, 1e-9), "{what}: {b:?}");
        // Between the bifurcations the collapse is mixed, with the symmetric value.
        let sym = scene::solve(&Scene::new(a, mu(0.35), Find::Thickness));
        let general = s(Find::Thickness, a, mu(0.35));
        assert!(close(general.k_crit.unwrap(), sym.k_crit.unwrap(), 1e-9));
        assert_eq!(general.mechanism, Some(MechanismKind::Mixed));
    }
}

#[test]
fn general_route_reproduces_discrete_and_segmental_values() {
    for (alpha, n) in [(90.0, Some(16)), (60.0, None), (120.0, Some(9))] {
        let joints = n.map_or(Discretisation::Continuum, Discretisation::Voussoirs);
        let a = Arch::new(1.4, alpha, WeightModel::Annular, joints).unwrap();
        for m in [Friction::INFINITE, mu(0.9)] {
            let sym = scene::solve(&Scene::new(a, m, Find::Thickness));
            let general = scene::solve(&scene(
                a,
                m,
                Find::Thickness,
                pointed(0.0),
                Load::SelfWeight,
            ));
            assert_eq!(sym.outcome, general.outcome, "α = {alpha}, N = {n:?}");
            if let (Some(x), Some(y)) = (sym.k_crit, general.k_crit) {
                assert!(close(x, y, 1e-9), "α = {alpha}, N = {n:?}: {x} vs {y}");
            }
        }
    }
}

#[test]
fn vertical_and_radial_joints_agree_where_the_joints_coincide() {
    // With one or two voussoirs the joints are the springings (and the crown), the same
    // planes whatever the joint orientation: every answer must agree.
    for n in [1, 2] {
        let a = arch(1.2, Discretisation::Voussoirs(n));
        for (find, m, load) in [
            (Find::Friction, Friction::INFINITE, Load::SelfWeight),
            (Find::LoadFactor, Friction::INFINITE, Load::Horizontal),
            (Find::LoadFactor, mu(0.3), Load::Horizontal),
            (Find::LoadFactor, Friction::INFINITE, Load::point(0.0)),
        ] {
            let r = scene::solve(&scene(a, m, find, ArchForm::default(), load));
            let v = scene::solve(&scene(a, m, find, vertical(), load));
            assert_eq!(r.outcome, v.outcome, "N = {n}, {find} {load:?}");
            assert_eq!(r.mechanism, v.mechanism, "N = {n}, {find} {load:?}");
            for (x, y) in [(r.load_factor, v.load_factor), (r.mu_crit, v.mu_crit)] {
                assert_eq!(x.is_some(), y.is_some());
                if let (Some(x), Some(y)) = (x, y) {
                    assert!(close(x, y, 1e-10), "N = {n}, {find} {load:?}: {x} vs {y}");
                }
            }
        }
    }
    // With more joints they differ: vertical haunch joints need a thicker arch.
    let a = arch(1.3, Discretisation::Continuum);
    let r = scene::solve(&scene(
        a,
        Friction::INFINITE,
        Find::Thickness,
        ArchForm::default(),
        Load::SelfWeight,
    ));
    let v = scene::solve(&scene(
        a,
        Friction::INFINITE,
        Find::Thickness,
        vertical(),
        Load::SelfWeight,
    ));
    assert!(v.k_crit.unwrap() > r.k_crit.unwrap() + 1e-4, "{v:?}");
}

#[test]
fn one_voussoir_under_a_horizontal_load_by_hand() {
    // A single block on two horizontal supports [−K, −1] and [1, K]: it overturns when the
    // resultant of its weight (2 W_half at the centroid height y_G) and of the horizontal
    // load 2λ W_half leaves the base [−K, K], at λ = K/y_G, y_G = 4(K³ − 1)/(3π(K² − 1));
    // it slides when the horizontal load exceeds μ times the weight, at λ = μ.
    for k in [1.2, 1.5, 2.0] {
        let y_g = 4.0 * (k * k * k - 1.0) / (3.0 * std::f64::consts::PI * (k * k - 1.0));
        let overturn = k / y_g;
        for form in [ArchForm::default(), vertical()] {
            let a = arch(k, Discretisation::Voussoirs(1));
            let s = lambda_max(a, Friction::INFINITE, form, Load::Horizontal);
            assert!(
                close(s.load_factor.unwrap(), overturn, 1e-12),
                "K = {k}: {s:?}"
            );
            assert_eq!(s.mechanism, Some(MechanismKind::Rotational));
            let hinges: Vec<(f64, &str)> = s
                .hinges
                .iter()
                .map(|h| (h.angle_deg, h.face.as_str()))
                .collect();
            assert_eq!(hinges, vec![(90.0, "extrados")], "K = {k}");
            let m = 0.5 * overturn;
            let s = lambda_max(a, mu(m), form, Load::Horizontal);
            assert!(close(s.load_factor.unwrap(), m, 1e-12), "K = {k}: {s:?}");
            assert_eq!(s.mechanism, Some(MechanismKind::Sliding));
        }
    }
}

#[test]
fn horizontal_load_factor_vanishes_at_k_c_and_grows_with_k() {
    let h = |k: f64, m: Friction| {
        lambda_max(
            arch(k, Discretisation::Continuum),
            m,
            ArchForm::default(),
            Load::Horizontal,
        )
    };
    let below = h(K_C - 1e-7, Friction::INFINITE);
    assert_eq!(below.outcome, Some(Outcome::NeverStands));
    assert!(below.load_factor.is_none() && !below.load_factor_unbounded);
    let at = h(K_C + 1e-9, Friction::INFINITE).load_factor.unwrap();
    assert!(at > 0.0 && at < 1e-8, "λ = {at}");
    let mut last = at;
    for k in [1.12, 1.15, 1.2, 1.3, 1.4, 1.5] {
        let l = h(k, Friction::INFINITE).load_factor.unwrap();
        assert!(l > last, "K = {k}: {l} after {last}");
        last = l;
    }
    // A thick arch with ample friction: four hinges, alternating faces.
    let thick = h(1.5, Friction::INFINITE);
    assert_eq!(thick.mechanism, Some(MechanismKind::Rotational));
    let faces: Vec<&str> = thick.hinges.iter().map(|h| h.face.as_str()).collect();
    assert_eq!(faces.len(), 4, "{:?}", thick.hinges);
    assert!(faces.windows(2).all(|w| w[0] != w[1]), "{faces:?}");
    // Low friction: the same arch slides at a springing.
    let low = h(1.5, mu(0.4));
    assert!(low.load_factor.unwrap() < thick.load_factor.unwrap());
    assert!(
        matches!(
            low.mechanism,
            Some(MechanismKind::Mixed | MechanismKind::Sliding)
        ),
        "{low:?}"
    );
    assert!(
        low.sliding_joints
            .iter()
            .any(|j| close(j.angle_deg.abs(), 90.0, 1e-9)),
        "{:?}",
        low.sliding_joints
    );
}

#[test]
fn point_load_goes_straight_into_the_support_near_the_springings() {
    // μ = ∞: a large point load at the extrados point at angle a can be carried by the
    // vertical through it alone iff that vertical crosses every joint beyond a inside the
    // arch, i.e. iff K sin a ≥ 1; otherwise λ is finite.
    let k = 1.3;
    let a = arch(k, Discretisation::Continuum);
    let p = |at: f64| lambda_max(a, Friction::INFINITE, ArchForm::default(), Load::point(at));
    let edge = (1.0 / k).asin().to_degrees();
    for at in [90.0, -90.0, edge + 0.5, -(edge + 0.5)] {
        let s = p(at);
        assert_eq!(s.outcome, Some(Outcome::Unbounded), "at {at}°");
        assert!(s.load_factor.is_none() && s.load_factor_unbounded);
    }
    for at in [0.0, 30.0, -30.0, edge - 0.5] {
        let s = p(at);
        assert_eq!(s.outcome, Some(Outcome::Found), "at {at}°");
        assert!(s.load_factor.unwrap() > 0.0 && !s.load_factor_unbounded);
    }
    // Symmetric positions give the same λ; the load's joint is a hinge of the mechanism.
    let (l, r) = (p(30.0), p(-30.0));
    assert!(close(l.load_factor.unwrap(), r.load_factor.unwrap(), 1e-9));
    assert!(
        l.hinges
            .iter()
            .any(|h| close(h.angle_deg, 30.0, 1e-9) && h.face == Face::Extrados)
    );
    // The command line says so in JSON.
    let v = solve_json(&[
        "--find",
        "load-factor",
        "--load",
        "point",
        "--at",
        "90",
        "--k",
        "1.3",
    ]);
    assert!(v["load_factor"].is_null());
    assert_eq!(v["load_factor_unbounded"], true);
    assert_eq!(v["outcome"], "unbounded");
    assert_eq!(v["at_deg"], 90.0);
    assert_eq!(v["load"], "point");
}

#[test]
fn continuum_and_fine_voussoirs_agree() {
    let cases = [
        (1.3, Friction::INFINITE, Load::Horizontal),
        (1.3, mu(0.6), Load::Horizontal),
        (1.3, Friction::INFINITE, Load::point(22.5)),
        (1.25, mu(0.5), Load::point(-22.5)),
    ];
    for (k, m, load) in cases {
        let at = |joints| {
            lambda_max(arch(k, joints), m, ArchForm::default(), load)
                .load_factor
                .unwrap()
        };
        let c = at(Discretisation::Continuum);
        let coarse = at(Discretisation::Voussoirs(128));
        let fine = at(Discretisation::Voussoirs(512));
        // Fewer potential joints: a discrete arch carries at least as much, and tends to the
        // continuum.
        assert!(
            fine >= c - 1e-12 && coarse >= c - 1e-12,
            "{load:?}: {c} {coarse} {fine}"
        );
        assert!(fine - c < 1e-5, "{load:?}: {c} vs {fine}");
        assert!(fine - c <= coarse - c, "{load:?}: {c} {coarse} {fine}");
    }
}

/// At 10⁵ voussoirs the thrust line comes within the active tolerance of the boundary at
/// several neighbouring joints (their slack grows as the square of the spacing, 10⁻⁹ here):
/// each band is one hinge, and the mechanism is the continuum's, with one degree of freedom
/// and its work equation met.
#[test]
fn the_finest_voussoir_arches_name_the_continuums_mechanism() {
    let m = mu(0.6);
    let c = lambda_max(
        arch(1.3, Discretisation::Continuum),
        m,
        ArchForm::default(),
        Load::Horizontal,
    );
    for n in [70_000, 100_000] {
        let s = lambda_max(
            arch(1.3, Discretisation::Voussoirs(n)),
            m,
            ArchForm::default(),
            Load::Horizontal,
        );
        let (l, lc) = (s.load_factor.unwrap(), c.load_factor.unwrap());
        assert!(l >= lc - 1e-12 && l - lc < 1e-9, "{n}: {l} against {lc}");
        assert_eq!(s.mechanism_dof, Some(1), "{n}: {:?}", s.hinges);
        assert_eq!(s.mechanism_admissible, Some(true), "{n}");
        assert!(
            s.work_residual.unwrap() < 1e-12,
            "{n}: {:?}",
            s.work_residual
        );
        assert_eq!(s.hinges.len(), 3, "{n}: {:?}", s.hinges);
        for (h, hc) in s.hinges.iter().zip(&c.hinges) {
            assert_eq!(h.face, hc.face);
            // Within two joint spacings (180°/n) of the continuum's hinge.
            assert!(
                (h.angle_deg - hc.angle_deg).abs() < 2.0 * 180.0 / f64::from(n),
                "{n}: {h:?} against {hc:?}"
            );
        }
    }
}

/// The critical thickness of a pointed arch falls as t/R_c ≈ 0.175 (1 − e): up to the largest
/// eccentricity allowed (0.9999) it follows that law and friction only raises it; beyond,
/// the margins no longer resolve the thrust line, and the eccentricity is refused.
#[test]
fn the_most_pointed_arches_keep_their_critical_thickness_law_and_beyond_are_refused() {
    let k_c = |e: f64, m: Friction| {
        let s = scene::solve(&scene(
            arch(1.2, Discretisation::Continuum),
            m,
            Find::Thickness,
            pointed(e),
            Load::SelfWeight,
        ));
        s.k_crit.unwrap()
    };
    for e in [0.99, 0.999, 0.9999] {
        let (inf, finite) = (k_c(e, Friction::INFINITE), k_c(e, mu(0.6)));
        let t = archstudy::model::t_over_r_from_k(inf);
        assert!(
            (t / (1.0 - e) - 0.175).abs() < 0.004,
            "e = {e}: t/R_c = {t}"
        );
        // Within 10⁻⁹ of K_c − 1 (at e = 0.99999 the two were 2 % apart).
        assert!(
            finite >= inf - 1e-9 * (inf - 1.0),
            "e = {e}: {finite} < {inf}"
        );
    }
    let e = ArchModel::new(
        arch(1.0000005, Discretisation::Continuum),
        pointed(0.99999),
        Load::SelfWeight,
    )
    .unwrap_err();
    assert!(e.to_string().contains("[0, 0.9999]"), "{e}");
    let o = archstudy(&[
        "solve",
        "--shape",
        "pointed",
        "--eccentricity",
        "0.99999",
        "--mu",
        "0.6",
    ]);
    assert_usage_error(&o, &["--eccentricity", "0.99999", "[0, 0.9999]"]);
    let dir = scratch("eccentricity-bound");
    let study = manifest(
        &dir,
        "e.yaml",
        "name: e\narch: {shape: pointed, eccentricity: 0.999999}\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.6]}\n",
    );
    let o = archstudy(&["check", study.to_str().unwrap()]);
    assert_usage_error(&o, &["arch.eccentricity", "0.999999", "[0, 0.9999]"]);
}

#[test]
fn pointed_arch_collapses_with_the_crown_rising() {
    // Under self-weight an equilateral arch is much thinner at collapse than the semicircle,
    // and its mechanism opens the crown at the intrados.
    let a = arch(1.2, Discretisation::Continuum);
    let t = scene::solve(&scene(
        a,
        Friction::INFINITE,
        Find::Thickness,
        pointed(0.5),
        Load::SelfWeight,
    ));
    let k = t.k_crit.unwrap();
    assert!(k > 1.0 && k < K_C, "{t:?}");
    assert!(
        t.hinges
            .iter()
            .any(|h| h.angle_deg == 0.0 && h.face == Face::Intrados),
        "{t:?}"
    );
    // Thicker than that it stands, thinner it does not.
    let state = |k: f64| {
        scene::solve(&scene(
            a.with_k(k),
            Friction::INFINITE,
            Find::State,
            pointed(0.5),
            Load::SelfWeight,
        ))
        .regime
    };
    assert_eq!(state(k + 1e-6), Some(Regime::Stable));
    assert_eq!(state(k - 1e-6), Some(Regime::Rotational));
    // Continuum and voussoirs again.
    let fine = scene::solve(&scene(
        arch(1.2, Discretisation::Voussoirs(512)),
        Friction::INFINITE,
        Find::Thickness,
        pointed(0.5),
        Load::SelfWeight,
    ));
    let kf = fine.k_crit.unwrap();
    assert!(kf <= k + 1e-12 && k - kf < 1e-5, "{k} vs {kf}");
}

fn run_study(dir: &Path, name: &str, text: &str) -> std::process::Output {
    let m = manifest(dir, &format!("{name}.yaml"), text);
    let out = dir.join("out");
    archstudy(&[
        "run",
        m.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ])
}

#[test]
fn load_factor_study_stores_its_columns_and_locates_mechanism_changes() {
    use polars::prelude::DataType;
    let dir = scratch("loads-lf");
    let text = "name: lf
grid:
  k: {from: 1.15, to: 1.45, steps: 4}
  mu: {values: [0.35, 0.5, 0.7, inf]}
load_cases:
  - {name: seismic, kind: horizontal}
  - {name: quarter, kind: point, at_deg: -45}
find: load_factor
boundaries: {tolerance: 1.0e-8}
";
    let o = run_study(&dir, "lf", text);
    assert!(o.status.success(), "{}", stderr(&o));
    let df = store::read_parquet(&dir.join("out/lf/results.parquet")).unwrap();
    assert_eq!(df.height(), 2 * 4 * 4);
    for (name, dtype) in [
        ("shape", DataType::String),
        ("eccentricity", DataType::Float64),
        ("joints", DataType::String),
        ("load", DataType::String),
        ("at_deg", DataType::Float64),
        ("lambda", DataType::Float64),
        ("crown_shear", DataType::Float64),
        ("load_factor", DataType::Float64),
        ("load_factor_unbounded", DataType::Boolean),
    ] {
        let c = df
            .column(name)
            .unwrap_or_else(|_| panic!("column {name} missing"));
        assert_eq!(c.dtype(), &dtype, "column {name}");
    }
    let load = store::str_column(&df, "load").unwrap();
    let at = store::f64_column(&df, "at_deg").unwrap();
    let lf = store::f64_column(&df, "load_factor").unwrap();
    let k = store::f64_column(&df, "k").unwrap();
    let mus = store::f64_column(&df, "mu").unwrap();
    assert_eq!(load[0].as_deref(), Some("horizontal"));
    assert_eq!((at[0], at[16]), (None, Some(-45.0)));
    // Every stored value is what `solve` gives.
    for i in [0, 5, 10, 21, 31] {
        let m = mus[i].unwrap();
        let l = if i < 16 {
            Load::Horizontal
        } else {
            Load::point(-45.0)
        };
        let f = if m.is_infinite() {
            Friction::INFINITE
        } else {
            mu(m)
        };
        let s = lambda_max(
            arch(k[i].unwrap(), Discretisation::Continuum),
            f,
            ArchForm::default(),
            l,
        );
        assert_eq!(s.load_factor, lf[i], "row {i}");
    }
    // Mechanism changes over (K, μ) are bifurcations: on either side of each located point
    // the mechanisms differ, as recorded.
    let b = store::read_parquet(&dir.join("out/lf/bifurcations.parquet")).unwrap();
    assert!(b.height() >= 2, "{b}");
    let bk = store::f64_column(&b, "k").unwrap();
    let bmu = store::f64_column(&b, "mu").unwrap();
    let axis = store::str_column(&b, "axis").unwrap();
    let ma = store::str_column(&b, "mechanism_a").unwrap();
    let mb = store::str_column(&b, "mechanism_b").unwrap();
    let case = store::str_column(&b, "load_case").unwrap();
    let blf = store::f64_column(&b, "load_factor").unwrap();
    for i in 0..b.height() {
        let (k, m) = (bk[i].unwrap(), bmu[i].unwrap());
        let l = if case[i].as_deref() == Some("seismic") {
            Load::Horizontal
        } else {
            Load::point(-45.0)
        };
        let at = |k: f64, m: f64| {
            lambda_max(
                arch(k, Discretisation::Continuum),
                mu(m),
                ArchForm::default(),
                l,
            )
        };
        let step = 2e-8;
        let (lo, hi) = match axis[i].as_deref() {
            Some("k") => (at(k - step, m), at(k + step, m)),
            Some("mu") => (at(k, m - step), at(k, m + step)),
            other => panic!("axis {other:?}"),
        };
        assert_eq!(
            lo.mechanism.map(|m| m.as_str()),
            ma[i].as_deref(),
            "row {i}"
        );
        assert_eq!(
            hi.mechanism.map(|m| m.as_str()),
            mb[i].as_deref(),
            "row {i}"
        );
        assert!(
            close(
                blf[i].unwrap(),
                lo.load_factor.unwrap(),
                1e-5 * (1.0 + blf[i].unwrap())
            ),
            "row {i}: {:?} vs {:?} at K = {k}, μ = {m}, {:?}",
            blf[i],
            lo.load_factor,
            axis[i]
        );
    }
}

#[test]
fn influence_line_of_a_point_load() {
    let dir = scratch("loads-influence");
    let text = "name: infl
grid:
  at_deg: {from: -90, to: 90, steps: 13}
  k: {values: [1.3]}
  mu: {values: [inf]}
load_cases:
  - {name: p, kind: point}
find: load_factor
";
    let o = run_study(&dir, "infl", text);
    assert!(o.status.success(), "{}", stderr(&o));
    let df = store::read_parquet(&dir.join("out/infl/results.parquet")).unwrap();
    let at = store::f64_column(&df, "at_deg").unwrap();
    let lf = store::f64_column(&df, "load_factor").unwrap();
    let unb = df
        .column("load_factor_unbounded")
        .unwrap()
        .bool()
        .unwrap()
        .clone();
    assert_eq!(df.height(), 13);
    for i in 0..13 {
        let a = at[i].unwrap();
        let expect_unbounded = 1.3 * a.to_radians().sin().abs() >= 1.0;
        assert_eq!(unb.get(i), Some(expect_unbounded), "at {a}°");
        assert_eq!(lf[i].is_none(), expect_unbounded, "at {a}°");
        // Mirror symmetry of the influence line.
        if let (Some(x), Some(y)) = (lf[i], lf[12 - i]) {
            assert!(close(x, y, 1e-9), "at ±{a}°: {x} vs {y}");
        }
    }
}

/// The weakest position of a moving point load is refined between the grid positions either
/// side of the grid's weakest: on the pointed arch (e = 0.2, K = 1.15, μ = 0.5) λ_max falls
/// towards the keystone's edge ψ₁ = asin(e (1 + K)/2) = 12.4155°, below the grid's least
/// (0.1703 at ±15°), to 0.15721 there.
#[test]
fn the_weakest_load_position_is_refined_between_grid_positions() {
    let dir = scratch("refined-position");
    let text = "name: r\narch: {shape: pointed, eccentricity: 0.2}\nfind: load_factor\nload_cases:\n  - {name: p, kind: point}\ngrid:\n  at_deg: {values: [-30, -25, -20, -15, 0, 15, 20, 25, 30]}\n  k: {values: [1.15]}\n  mu: {values: [0.5]}\n";
    let o = run_study(&dir, "r", text);
    assert!(o.status.success(), "{}", stderr(&o));
    let run = dir.join("out/r");
    let states = store::read_states(&run.join("states.parquet")).unwrap();
    let w = states.iter().find(|s| s.state == "weakest").unwrap();
    let psi1 = (0.2f64 * 2.15 / 2.0).asin().to_degrees();
    let at = w.at_deg.unwrap();
    assert!(
        (at.abs() - psi1).abs() < 1e-7 && at.abs() >= psi1,
        "{at} against ψ₁ = {psi1}"
    );
    let refined = w.load_factor.unwrap();
    // The grid's weakest, and λ_max at the refined position solved on its own.
    let grid = lambda_max(
        arch(1.15, Discretisation::Continuum),
        mu(0.5),
        pointed(0.2),
        Load::point(-15.0),
    )
    .load_factor
    .unwrap();
    let again = lambda_max(
        arch(1.15, Discretisation::Continuum),
        mu(0.5),
        pointed(0.2),
        Load::point(at),
    )
    .load_factor
    .unwrap();
    assert!((grid - 0.170251).abs() < 1e-6, "{grid}");
    assert!((refined - 0.157210).abs() < 1e-6, "{refined}");
    assert!((again - refined).abs() < 1e-9, "{again} against {refined}");
    let md = std::fs::read_to_string(run.join("report.md")).unwrap();
    assert!(
        md.contains("λ_max at the weakest load position refined between grid points (K = 1.15, μ = 0.5, load at -12.4155°; the grid's weakest: 0.1703 at -15°) | 0.1572102"),
        "{md}"
    );
    assert!(md.contains("The open diamond is the least λ_max of the weakest line"));
}

#[test]
fn live_load_state_study_uses_the_general_route() {
    let dir = scratch("loads-state");
    let text = "name: st
arch: {shape: pointed, eccentricity: 0.5}
grid:
  k: {from: 1.02, to: 1.1, steps: 3}
  mu: {values: [0.2, 0.6]}
load_cases:
  - {name: seismic, kind: horizontal, lambda: 0.02}
scenes:
  - {k: 1.06, mu: 0.6}
";
    let o = run_study(&dir, "st", text);
    assert!(o.status.success(), "{}", stderr(&o));
    // The scene's caption gives λ and e as the study gave them.
    let md = std::fs::read_to_string(dir.join("out/st/report.md")).unwrap();
    assert!(
        md.contains("pointed, e = 0.5, horizontal load, λ = 0.02") && !md.contains("λ = 0.0200"),
        "{md}"
    );
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out/st/run.json")).unwrap()).unwrap();
    assert_eq!(info["separable"], false);
    assert_eq!(info["grid_path"], "case_by_case");
    let df = store::read_parquet(&dir.join("out/st/results.parquet")).unwrap();
    let regime = store::str_column(&df, "regime").unwrap();
    let lambda = store::f64_column(&df, "lambda").unwrap();
    let k = store::f64_column(&df, "k").unwrap();
    let m = store::f64_column(&df, "mu").unwrap();
    for i in 0..df.height() {
        assert_eq!(lambda[i], Some(0.02));
        let s = scene::solve(&Scene {
            lambda: 0.02,
            ..scene(
                arch(k[i].unwrap(), Discretisation::Continuum),
                mu(m[i].unwrap()),
                Find::State,
                pointed(0.5),
                Load::Horizontal,
            )
        });
        assert_eq!(
            s.regime.map(|r| r.as_str()),
            regime[i].as_deref(),
            "row {i}"
        );
    }
    // Boundaries are located on the general route too, each between its two regimes.
    let b = store::read_parquet(&dir.join("out/st/boundaries.parquet")).unwrap();
    assert!(b.height() >= 1, "{b}");
}

#[test]
fn bad_load_manifests_are_refused_with_a_located_message() {
    let dir = scratch("loads-bad");
    let base = "name: bad\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [inf]}\n";
    let cases: [(&str, &str, &[&str]); 12] = [
        (
            "load_cases:\n  - {name: a, kind: wind}\n",
            "",
            &["load_cases.kind", "\"wind\"", "horizontal or point", ":6:"],
        ),
        (
            "load_cases:\n  - {name: a, kind: point, at_deg: 100}\n",
            "find: load_factor\n",
            &["load_cases.at_deg", "value 100", "[−90, 90]", ":6:"],
        ),
        (
            "load_cases:\n  - {name: a, kind: point}\n",
            "find: load_factor\n",
            &["load_cases.at_deg", "needs its position", ":6:"],
        ),
        (
            "load_cases:\n  - {name: a, kind: horizontal}\n",
            "",
            &["load_cases.lambda", "needs its load factor", ":6:"],
        ),
        (
            "load_cases:\n  - {name: a, kind: horizontal, lambda: 0.1}\n",
            "find: load_factor\n",
            &["load_cases.lambda", "value 0.1", "finds λ itself"],
        ),
        (
            "load_cases:\n  - {name: a, kind: self_weight}\n",
            "find: load_factor\n",
            &["load_cases.kind", "needs a live load", ":6:"],
        ),
        (
            "load_cases:\n  - {name: a, kind: horizontal, lambda: -1}\n",
            "",
            &["load_cases.lambda", "value -1", "≥ 0"],
        ),
        (
            "load_cases:\n  - {name: a, kind: horizontal, at_deg: 10}\n",
            "find: load_factor\n",
            &["load_cases.at_deg", "value 10", "only a `point`"],
        ),
        (
            "arch: {eccentricity: 0.5}\n",
            "",
            &["arch.eccentricity", "value 0.5", "shape: pointed"],
        ),
        (
            "arch: {shape: pointed, eccentricity: 0.5}\ngrid2: 1\n",
            "",
            &["grid2"],
        ),
        (
            "arch: {joints: vertical, half_angle_deg: 120}\n",
            "",
            &["arch.joints", "\"vertical\"", "α ≤ 90°"],
        ),
        (
            "arch: {shape: pointed}\n",
            "",
            &["arch.eccentricity", "needs `eccentricity: e`"],
        ),
    ];
    for (i, (extra, find, wanted)) in cases.iter().enumerate() {
        let text = format!("{base}{extra}{find}");
        let o = run_study(&dir, &format!("bad{i}"), &text);
        let file = format!("bad{i}.yaml");
        let mut names = vec![file.as_str()];
        names.extend_from_slice(wanted);
        assert_usage_error(&o, &names);
        assert!(!dir.join("out/bad").exists(), "case {i} left output behind");
    }
    // A pointed arch too thick for its eccentricity, and an at_deg axis with another load.
    let o = run_study(
        &dir,
        "thick",
        "name: bad\narch: {shape: pointed, eccentricity: 0.5}\ngrid:\n  k: {values: [1.2, 3.5]}\n  mu: {values: [inf]}\n",
    );
    assert_usage_error(&o, &["grid.k", "K < 3"]);
    let o = run_study(
        &dir,
        "axis",
        "name: bad\ngrid:\n  at_deg: {values: [0, 30]}\n  k: {values: [1.2]}\n  mu: {values: [inf]}\nload_cases:\n  - {name: h, kind: horizontal}\nfind: load_factor\n",
    );
    assert_usage_error(&o, &["grid.at_deg", "\"h\""]);
}

#[test]
fn command_line_options_and_json_keys() {
    let v = solve_json(&[
        "--find",
        "load-factor",
        "--load",
        "horizontal",
        "--k",
        "1.3",
        "--mu",
        "0.6",
    ]);
    for key in [
        "find",
        "k",
        "mu",
        "outcome",
        "mechanism",
        "hinges",
        "sliding_joints",
        "load",
        "at_deg",
        "lambda",
        "load_factor",
        "load_factor_unbounded",
        "shape",
        "eccentricity",
        "joints",
        "crown_shear",
        "thrust_over_half_weight",
        "crown_moment",
        "regime",
        "thrust_r_min",
    ] {
        assert!(v.get(key).is_some(), "key {key} missing in {v}");
    }
    assert_eq!(v["find"], "load_factor");
    assert!(v["load_factor"].as_f64().unwrap() > 0.0);
    assert_eq!(v["load_factor_unbounded"], false);
    assert!(v["lambda"].is_null() && v["at_deg"].is_null());
    let v = solve_json(&[
        "--find",
        "state",
        "--load",
        "point",
        "--at",
        "-30",
        "--lambda",
        "0.2",
        "--k",
        "1.3",
        "--shape",
        "pointed",
        "--eccentricity",
        "0.2",
        "--joints",
        "vertical",
    ]);
    assert_eq!(v["lambda"], 0.2);
    assert_eq!(v["shape"], "pointed");
    assert_eq!(v["eccentricity"], 0.2);
    assert_eq!(v["joints"], "vertical");
    assert!(v["regime"].is_string());
    let bad: [(&[&str], &str, &str); 8] = [
        (&["--at", "30"], "--at", "--load point"),
        (&["--load", "point"], "--load", "--at DEG"),
        (&["--lambda", "0.1"], "--lambda", "no live part"),
        (&["--find", "load-factor"], "--find", "needs a live load"),
        (&["--shape", "pointed"], "--shape", "--eccentricity"),
        (
            &["--eccentricity", "0.3"],
            "--eccentricity",
            "--shape pointed",
        ),
        (
            &["--find", "thrust", "--joints", "vertical"],
            "--find",
            "radial joints",
        ),
        (
            &["--load", "point", "--at", "95", "--find", "load-factor"],
            "--at",
            "not on the arch",
        ),
    ];
    for (args, option, allowed) in bad {
        let mut all = vec!["solve"];
        all.extend_from_slice(args);
        let o = archstudy(&all);
        assert_usage_error(&o, &[option, allowed]);
    }
}

#[test]
fn load_factor_agrees_with_the_work_equation_of_its_mechanism() {
    use archstudy::analysis::forms::ArchModel;
    use archstudy::analysis::general::{self, Settings};
    use archstudy::analysis::kinematics::{
        FlowRule, LimitState, mechanism_modes, pattern_of, work_equation,
    };
    // Rotational mechanisms: the virtual work of the loads vanishes (eq. 9), so the load
    // factor is −(work of the dead load)/(work of the live load) on the mechanism's velocity
    // field, a kinematic route independent of the programme that found λ.
    let cases = [
        (
            1.3,
            Discretisation::Continuum,
            ArchForm::default(),
            Load::Horizontal,
        ),
        (
            1.3,
            Discretisation::Voussoirs(64),
            ArchForm::default(),
            Load::Horizontal,
        ),
        (
            1.3,
            Discretisation::Continuum,
            ArchForm::default(),
            Load::point(30.0),
        ),
        (
            1.25,
            Discretisation::Continuum,
            ArchForm::default(),
            Load::point(-22.5),
        ),
        (
            1.2,
            Discretisation::Continuum,
            pointed(0.3),
            Load::Horizontal,
        ),
    ];
    for (k, joints, form, load) in cases {
        let model = ArchModel::new(arch(k, joints), form, load).unwrap();
        let lf = general::load_factor(&model, std::f64::consts::FRAC_PI_2, &Settings::default());
        let m = lf.mechanism.clone().unwrap();
        assert_eq!(
            m.kind,
            archstudy::analysis::MechanismKind::Rotational,
            "{load:?}"
        );
        let modes =
            mechanism_modes(&model, &pattern_of(&m), FlowRule::NonAssociative, true).unwrap();
        assert_eq!(modes.dof, 1, "{load:?}: {m:?}");
        let field = &modes.fields[0];
        let work = |lambda: f64| {
            let state = LimitState {
                crown_force: [0.0, 0.0],
                crown_moment_origin: 0.0,
                load_factor: lambda,
                mu: f64::INFINITY,
            };
            work_equation(&model, &state, field).work_loads
        };
        let (dead, live) = (work(0.0), work(1.0) - work(0.0));
        let lambda_work = -dead / live;
        assert!(
            close(lambda_work, lf.lambda, 1e-9 * (1.0 + lf.lambda)),
            "{k} {joints} {load:?}: work {lambda_work} vs LP {}",
            lf.lambda
        );
    }
    // Mixed mechanisms: the loads' work balances the friction dissipated at the sliding
    // joints (eq. 11) for the state the programme found.
    for (m, load) in [(0.6, Load::Horizontal), (0.5, Load::point(-22.5))] {
        let s = lambda_max(
            arch(1.3, Discretisation::Continuum),
            mu(m),
            ArchForm::default(),
            load,
        );
        assert_eq!(s.mechanism, Some(MechanismKind::Mixed), "{load:?}");
        assert_eq!(s.mechanism_dof, Some(1));
        assert!(s.work_loads.unwrap() > 0.0);
        assert!(s.work_residual.unwrap() < 1e-9, "{load:?}: {s:?}");
    }
}

#[test]
fn one_study_converges_thresholds_and_a_horizontal_load_factor() {
    // The shape of studies/convergence.yaml on a few counts: the self-weight load case finds
    // the thresholds, the horizontal one its load factor at t/R_c = 0.15, μ = 0.4.
    let dir = scratch("loads-two-finds");
    let text = "name: conv
grid:
  voussoirs: {values: [8, 64, 512, continuum]}
  t_over_r: {values: [0.15]}
  mu: {values: [0.4]}
load_cases:
  - {name: gravity, kind: self_weight}
  - {name: wind, kind: horizontal, find: load_factor}
find: thresholds
";
    let o = run_study(&dir, "conv", text);
    assert!(o.status.success(), "{}", stderr(&o));
    let run = dir.join("out/conv");
    let rows = store::read_results(&run.join("results.parquet")).unwrap();
    assert_eq!(rows.len(), 8);
    let (gravity, wind): (Vec<_>, Vec<_>) = rows.iter().partition(|r| &*r.load_case == "gravity");
    assert!(
        gravity
            .iter()
            .all(|r| &*r.find == "thresholds" && r.k.is_none())
    );
    assert!(
        wind.iter()
            .all(|r| &*r.find == "load_factor" && r.mu == Some(0.4))
    );
    // The continuum thresholds of the paper, in the same run as the load factor.
    let cont = gravity.iter().find(|r| r.voussoirs.is_none()).unwrap();
    assert!(close(cont.k_c_rotational.unwrap(), K_C, 1e-9));
    assert!(close(cont.mu_min.unwrap(), MU_MIN, 1e-9));
    // The continuum load factor, checked against a model of 4096 voussoirs solved apart:
    // a discrete arch has fewer potential joints, so it carries at least as much.
    let lambda = |n: Option<u32>| {
        wind.iter()
            .find(|r| r.voussoirs == n)
            .and_then(|r| r.load_factor)
            .unwrap()
    };
    let lc = lambda(None);
    let k = archstudy::model::k_from_t_over_r(0.15);
    let fine = lambda_max(
        arch(k, Discretisation::Voussoirs(4096)),
        mu(0.4),
        ArchForm::default(),
        Load::Horizontal,
    )
    .load_factor
    .unwrap();
    assert!(
        fine >= lc && fine - lc < 1e-7,
        "{lc} against N = 4096: {fine}"
    );
    assert!(close(lc, 0.05246891, 1e-8), "{lc}");
    for n in [8, 64, 512] {
        assert!(lambda(Some(n)) > lc, "N = {n}");
    }
    // The same λ from the other side: the state at a given λ (feasibility of all rows, not
    // the largest λ) is stable just below it and collapses by a mixed mechanism just above.
    let regime_at = |l: f64| {
        let mut s = scene(
            arch(k, Discretisation::Continuum),
            mu(0.4),
            Find::State,
            ArchForm::default(),
            Load::Horizontal,
        );
        s.lambda = l;
        scene::solve(&s).regime
    };
    assert_eq!(regime_at(lc * (1.0 - 1e-7)), Some(Regime::Stable));
    assert_eq!(regime_at(lc * (1.0 + 1e-7)), Some(Regime::Mixed));
    assert!(lambda(Some(512)) - lc < 1e-5 && lambda(Some(8)) - lc > 1e-3);
    // Each discrete case's reference is the continuum case of its own load case.
    let refs = store::read_reference(&run.join("reference.parquet")).unwrap();
    let lf: Vec<_> = refs
        .iter()
        .filter(|r| r.quantity == "load_factor")
        .collect();
    assert_eq!(lf.len(), 3);
    assert!(lf.iter().all(|r| r.continuum_value == Some(lc)));
    assert_eq!(refs.iter().filter(|r| r.quantity == "mu_min").count(), 3);
    // The report tabulates the load factor's convergence beside the thresholds'.
    let md = std::fs::read_to_string(run.join("report.md")).unwrap();
    assert!(md.contains("### λ (load factor) (`load_factor`)"), "{md}");
    let row = format!(
        "| 512 | {:.10} | {:.3e} |",
        lambda(Some(512)),
        lambda(Some(512)) - lc
    );
    assert!(md.contains(&row), "{row} not in the report");
    assert!(md.contains("load case wind: load_factor"), "{md}");
    // Key results: the extremes of λ_max over every voussoir count, each named by its
    // stored cell and its axes (the continuum is the weakest, 8 voussoirs the strongest).
    let key = format!(
        "| smallest λ_max of the study (wind) (K = 1.1622, μ = 0.4, continuum, mixed collapse) | {lc:.10} | — | — | `results.parquet row 7 load_factor` |"
    );
    assert!(md.contains(&key), "{key} not in the report");
    let key = format!(
        "| largest λ_max of the study (wind) (K = 1.1622, μ = 0.4, N = 8, mixed collapse) | {:.10} | — | — | `results.parquet row 4 load_factor` |",
        lambda(Some(8))
    );
    assert!(md.contains(&key), "{key} not in the report");
    assert!(
        md.contains("| μ_min, sliding threshold, continuum (gravity) | 0.3092154443 | 0.309 |"),
        "{md}"
    );
}

#[test]
fn a_self_weight_state_study_of_a_pointed_arch_goes_per_k_line() {
    let dir = scratch("loads-k-lines");
    let text = "name: kl
arch: {shape: pointed, eccentricity: 0.2}
grid:
  k: {from: 1.05, to: 1.2, steps: 3}
  mu: {values: [0.25, 0.4, inf]}
";
    let o = run_study(&dir, "kl", text);
    assert!(o.status.success(), "{}", stderr(&o));
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out/kl/run.json")).unwrap()).unwrap();
    assert_eq!(info["separable"], false);
    assert_eq!(info["grid_path"], "k_lines");
    let md = std::fs::read_to_string(dir.join("out/kl/report.md")).unwrap();
    assert!(md.contains("per K line"), "{md}");
}
