//! Point-load positions as x/L of the extrados span (docs/loads-and-geometries.md, *Point
//! loads as x/L*): the conversion to the joint angle checked against closed forms and the
//! angle route, loads on a keystone against fine voussoir models, and a study grouped by x/L.

use archstudy::model::{
    Arch, ArchForm, Discretisation, Friction, JointOrientation, Load, Shape, WeightModel,
};
use archstudy::scene::{self, Find, Outcome, Scene, Solution};

fn load_factor(arch: Arch, form: ArchForm, load: Load, mu: f64) -> Solution {
    let s = Scene {
        arch,
        friction: Friction::new(mu).unwrap(),
        find: Find::LoadFactor,
        form,
        load,
        lambda: 0.0,
    };
    scene::solve(&s)
}

/// On the semicircle x/L = (1 + sin ψ)/2: x/L = 0.75 is the load at 30°, whose λ_max at
/// K = 1.3, μ = ∞ is 0.927921894 (docs reference table); each route reports the other's
/// position.
#[test]
fn x_over_l_on_the_semicircle_is_the_angle_of_the_closed_form() {
    let arch = Arch::semicircular(1.3).unwrap();
    let by_x = load_factor(
        arch,
        ArchForm::default(),
        Load::point_x(0.75),
        f64::INFINITY,
    );
    let by_deg = load_factor(arch, ArchForm::default(), Load::point(30.0), f64::INFINITY);
    approx::assert_abs_diff_eq!(by_x.load_factor.unwrap(), 0.927921894, epsilon = 1e-9);
    approx::assert_abs_diff_eq!(
        by_x.load_factor.unwrap(),
        by_deg.load_factor.unwrap(),
        epsilon = 1e-12
    );
    approx::assert_abs_diff_eq!(by_x.at_deg.unwrap(), 30.0, epsilon = 1e-12);
    approx::assert_abs_diff_eq!(by_deg.at_x.unwrap(), 0.75, epsilon = 1e-15);
    // The left half mirrors the right.
    let left = load_factor(
        arch,
        ArchForm::default(),
        Load::point_x(0.25),
        f64::INFINITY,
    );
    approx::assert_abs_diff_eq!(left.at_deg.unwrap(), -30.0, epsilon = 1e-12);
    approx::assert_abs_diff_eq!(
        left.load_factor.unwrap(),
        by_x.load_factor.unwrap(),
        epsilon = 1e-9
    );
}

/// Vertical joints: the joint through the point at x has its intrados end at x too, so
/// sin θ = x + d; on the semicircle at K = 1.3, x/L = 0.75 is x = 0.65, θ = asin 0.65.
#[test]
fn x_over_l_with_vertical_joints_takes_the_vertical_joint_through_the_point() {
    let arch = Arch::semicircular(1.3).unwrap();
    let vertical = ArchForm {
        joints: JointOrientation::Vertical,
        ..ArchForm::default()
    };
    let by_x = load_factor(arch, vertical, Load::point_x(0.75), f64::INFINITY);
    let theta = 0.65f64.asin().to_degrees();
    approx::assert_abs_diff_eq!(by_x.at_deg.unwrap(), theta, epsilon = 1e-12);
    let by_deg = load_factor(arch, vertical, Load::point(theta), f64::INFINITY);
    assert_eq!(by_x.outcome, Some(Outcome::Found));
    approx::assert_abs_diff_eq!(
        by_x.load_factor.unwrap(),
        by_deg.load_factor.unwrap(),
        epsilon = 1e-9
    );
}

/// A point of a pointed arch's keystone (e = 0.3, K = 1.15, μ = 0.6, keystone from x/L
/// 0.4708 to 0.5292): x/L = 0.505 lies at 16.716° from its arc's centre. The continuum's
/// λ_max is that of the angle route, and of 2001 and 4001 voussoirs by Richardson
/// extrapolation (their own gaps about 2e-3 and 1e-3).
#[test]
fn x_over_l_on_a_keystone_matches_fine_voussoirs() {
    let form = ArchForm {
        shape: Shape::Pointed { eccentricity: 0.3 },
        joints: JointOrientation::Radial,
        keystone: true,
    };
    let solve = |joints, load| {
        let arch = Arch::new(1.15, 90.0, WeightModel::Annular, joints).unwrap();
        let s = load_factor(arch, form, load, 0.6);
        assert_eq!(s.outcome, Some(Outcome::Found), "{joints:?}");
        s
    };
    let at = Load::point_x(0.505);
    let c = solve(Discretisation::Continuum, at);
    approx::assert_abs_diff_eq!(c.at_deg.unwrap(), 16.716146667, epsilon = 1e-8);
    let lc = c.load_factor.unwrap();
    approx::assert_abs_diff_eq!(lc, 0.6947039, epsilon = 1e-6);
    let by_deg = solve(Discretisation::Continuum, Load::point(c.at_deg.unwrap()));
    approx::assert_abs_diff_eq!(by_deg.load_factor.unwrap(), lc, epsilon = 1e-9);
    approx::assert_abs_diff_eq!(by_deg.at_x.unwrap(), 0.505, epsilon = 1e-12);
    let a = solve(Discretisation::Voussoirs(2001), at)
        .load_factor
        .unwrap();
    let b = solve(Discretisation::Voussoirs(4001), at)
        .load_factor
        .unwrap();
    assert!(a > b && b > lc, "{a} {b} {lc}");
    approx::assert_abs_diff_eq!(2.0 * b - a, lc, epsilon = 1e-5);
}

/// A load-factor study over an x/L axis at two thicknesses: every row stores both positions,
/// the angle of one x/L moves with K, and the boundaries and bifurcations are grouped by
/// x/L (their at_x is a value of the axis, their at_deg null).
#[test]
fn x_over_l_study_stores_both_positions_and_groups_by_x() {
    use crate::common::{run_study, scratch};
    use archstudy::store;
    let dir = scratch("span-positions");
    let text = "name: span
arch: {shape: pointed, eccentricity: 0.3}
grid:
  at_x: {values: [0.6, 0.7, 0.8]}
  k: {values: [1.12, 1.16, 1.2, 1.24]}
  mu: {values: [0.3, 0.45, 0.6, inf]}
load_cases:
  - {name: p, kind: point}
find: load_factor
";
    let run = run_study(&dir, "span.yaml", text);
    let df = store::read_parquet(&run.join("results.parquet")).unwrap();
    let at_x = store::f64_column(&df, "at_x").unwrap();
    let at_deg = store::f64_column(&df, "at_deg").unwrap();
    let k = store::f64_column(&df, "k").unwrap();
    assert_eq!(df.height(), 3 * 4 * 4);
    // Rows 0 and 4 share x/L = 0.6 at K = 1.12 and 1.16.
    assert_eq!((at_x[0], at_x[4]), (Some(0.6), Some(0.6)));
    assert_eq!((k[0], k[4]), (Some(1.12), Some(1.16)));
    let angle = |k: f64| {
        let d = 0.3 * 0.5 * (1.0 + k);
        ((0.2 * (k - d) + d) / k).asin().to_degrees()
    };
    approx::assert_abs_diff_eq!(at_deg[0].unwrap(), angle(1.12), epsilon = 1e-12);
    approx::assert_abs_diff_eq!(at_deg[4].unwrap(), angle(1.16), epsilon = 1e-12);
    assert!((at_deg[0].unwrap() - at_deg[4].unwrap()).abs() > 0.1);
    let bif = store::read_parquet(&run.join("bifurcations.parquet")).unwrap();
    assert!(bif.height() > 0, "no change of mechanism located");
    let bx = store::f64_column(&bif, "at_x").unwrap();
    let bd = store::f64_column(&bif, "at_deg").unwrap();
    for (x, d) in bx.iter().zip(&bd) {
        assert!(matches!(x, Some(v) if [0.6, 0.7, 0.8].contains(v)), "{x:?}");
        assert_eq!(*d, None);
    }
}

/// Refusals: both position keys, x/L outside [0, 1] or beyond a semicircle, and a point
/// above a pointed arch's keystone wedge without `keystone: true`.
#[test]
fn x_over_l_usage_errors() {
    use crate::common::{archstudy, assert_usage_error, manifest, scratch};
    let dir = scratch("span-refusals");
    let case = |arch: &str, lc: &str| {
        format!(
            "name: bad\narch: {arch}\ngrid:\n  k: {{values: [1.15, 1.2]}}\n  mu: {{values: [0.6]}}\nload_cases:\n  - {lc}\nfind: load_factor\n"
        )
    };
    for (text, names) in [
        (
            case("{}", "{name: p, kind: point, at_deg: 10, at_x: 0.6}"),
            &["load_cases.at_x", "once"][..],
        ),
        (
            case("{}", "{name: p, kind: point, at_x: 1.2}"),
            &["load_cases.at_x", "1.2", "[0, 1]"][..],
        ),
        (
            case("{half_angle_deg: 120}", "{name: p, kind: point, at_x: 0.6}"),
            &["load_cases.at_x", "α ≤ 90°"][..],
        ),
        (
            case(
                "{shape: pointed, eccentricity: 0.3}",
                "{name: p, kind: point, at_x: 0.51}",
            ),
            &["load_cases.at_x", "0.51", "keystone: true"][..],
        ),
    ] {
        let m = manifest(&dir, "bad.yaml", &text);
        assert_usage_error(&archstudy(&["check", m.to_str().unwrap()]), names);
    }
    let o = archstudy(&[
        "solve",
        "--find",
        "load-factor",
        "--load",
        "point",
        "--at",
        "10",
        "--at-x",
        "0.6",
    ]);
    assert_usage_error(&o, &["--at", "--at-x"]);
}

/// Without a keystone, the thickest pointed arch on which a load at x/L still sits at a
/// joint is the K where its extrados point reaches the first joint ψ₁ = asin d: there
/// asin((|x| + d)/K) = asin d, which a thickness search must not pass.
#[test]
fn x_over_l_bounds_the_thickness_where_the_point_meets_the_first_joint() {
    let form = ArchForm {
        shape: Shape::Pointed { eccentricity: 0.3 },
        joints: JointOrientation::Radial,
        keystone: false,
    };
    let half = std::f64::consts::FRAC_PI_2;
    let k = form.max_k_with_load(half, Load::point_x(0.52));
    assert!(k > 1.0 && k < form.max_k(half), "{k}");
    let (_, _, psi) = form.extrados_at_x(k, half, 0.52).unwrap();
    approx::assert_abs_diff_eq!(psi, form.centre_offset(k).asin(), epsilon = 1e-12);
    // Closed form: u(K − d) = (K − 1)d with u = 0.04, d = 0.15(1 + K), i.e.
    // 0.15K² − 0.034K − 0.144 = 0: K = 1.0996621043.
    let root = (0.034 + (0.034f64.powi(2) + 4.0 * 0.15 * 0.144).sqrt()) / 0.3;
    approx::assert_abs_diff_eq!(k, root, epsilon = 1e-12);
    approx::assert_abs_diff_eq!(k, 1.0996621043, epsilon = 1e-10);
    let keystone = ArchForm {
        keystone: true,
        ..form
    };
    assert_eq!(
        keystone.max_k_with_load(half, Load::point_x(0.52)),
        keystone.max_k(half)
    );
}

/// `solve` names an x/L position as given, with its computed angle rounded: on the
/// semicircle x/L = 0.75 is the extrados point at 30° (sin θ = 2·0.75 − 1 = 0.5), and its
/// λ_max is that of the load given as 30°.
#[test]
fn solve_names_an_x_over_l_position_and_its_angle() {
    use crate::common::{archstudy, stdout};
    let solve = |at: &[&str]| {
        let mut args = vec![
            "solve",
            "--find",
            "load-factor",
            "--k",
            "1.3",
            "--mu",
            "0.5",
        ];
        args.extend_from_slice(&["--load", "point"]);
        args.extend_from_slice(at);
        let o = archstudy(&args);
        let text = stdout(&o);
        assert!(o.status.success(), "{text}");
        text
    };
    let by_x = solve(&["--at-x", "0.75"]);
    assert!(
        by_x.contains("a point load at x/L = 0.75 (30.000000°)"),
        "{by_x}"
    );
    let lambda = |t: &str| {
        t.lines()
            .find(|l| l.starts_with("λ_max = "))
            .map(str::to_string)
            .unwrap()
    };
    assert_eq!(lambda(&by_x), lambda(&solve(&["--at", "30"])));
}
