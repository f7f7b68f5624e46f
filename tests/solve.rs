//! `archstudy solve`: the reference values, the JSON contract and bad input.

use crate::common::reference::{
    HAUNCH_DEG, HAUNCH_MIN_THRUST_DEG, K_BIF, K_C, MU_MIN, MU_ROT, SLIDING_DEG, T_OVER_R_C,
};
use crate::common::{archstudy, assert_usage_error, solve_json, stderr, stdout};
use approx::assert_abs_diff_eq;
use serde_json::Value;

fn f(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number in {v}"))
}

#[test]
fn reference_values_of_the_semicircular_arch() {
    let t = solve_json(&["--find", "thickness"]);
    assert_abs_diff_eq!(f(&t, "k_crit"), K_C, epsilon = 1e-9);
    assert_abs_diff_eq!(f(&t, "t_over_r_crit"), T_OVER_R_C, epsilon = 1e-9);
    assert_abs_diff_eq!(f(&t, "thrust_over_half_weight"), MU_ROT, epsilon = 1e-9);
    assert_eq!(t["mechanism"], "rotational");
    let haunch = t["hinges"]
        .as_array()
        .unwrap()
        .iter()
        .find(|h| h["face"] == "intrados")
        .unwrap();
    assert_abs_diff_eq!(
        haunch["angle_deg"].as_f64().unwrap().abs(),
        HAUNCH_DEG,
        epsilon = 1e-6
    );
    // Eq. (9): the rotational mechanism does no work; its five joints leave two modes.
    assert_eq!(t["mechanism_dof"], 2);
    assert!(f(&t, "work_residual") < 1e-9);
    assert_eq!(f(&t, "work_friction"), 0.0);

    let m = solve_json(&["--find", "friction", "--k", "1.4"]);
    assert_abs_diff_eq!(f(&m, "mu_crit"), MU_MIN, epsilon = 1e-9);
    assert_eq!(m["mechanism"], "sliding");
    let angles: Vec<f64> = m["sliding_joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["angle_deg"].as_f64().unwrap())
        .collect();
    assert!(
        (angles[2] - SLIDING_DEG).abs() < 1e-6 && (angles[3] - 90.0).abs() < 1e-9,
        "{angles:?}"
    );
    // Eq. (11): the loads do positive work, all dissipated by friction.
    assert!(f(&m, "work_loads") > 0.0 && f(&m, "work_residual") < 1e-9);
    assert_abs_diff_eq!(f(&m, "work_loads"), -f(&m, "work_friction"), epsilon = 1e-9);

    let b = solve_json(&["--find", "thickness", "--mu", "0.309215444331"]);
    assert_abs_diff_eq!(f(&b, "k_crit"), K_BIF, epsilon = 1e-8);
    let r = solve_json(&["--find", "friction", "--k", "1.113581813339"]);
    assert_abs_diff_eq!(f(&r, "mu_crit"), MU_ROT, epsilon = 1e-9);
    let th = solve_json(&["--find", "thrust", "--k", "1.35"]);
    let h = th["hinges_min"]
        .as_array()
        .unwrap()
        .iter()
        .find(|h| h["face"] == "intrados")
        .unwrap();
    assert_abs_diff_eq!(
        h["angle_deg"].as_f64().unwrap().abs(),
        HAUNCH_MIN_THRUST_DEG,
        epsilon = 1e-6
    );
}

#[test]
fn the_papers_printed_digits_in_the_summary() {
    let o = archstudy(&["solve", "--find", "thickness"]);
    assert!(stdout(&o).contains("≈ 1.1136"), "{}", stdout(&o));
    assert!(stdout(&o).contains("≈ 0.395"));
    let o = archstudy(&["solve", "--find", "friction", "--k", "1.3"]);
    let s = stdout(&o);
    assert!(
        s.contains("≈ 0.309") && s.contains("28.6362° inward") && s.contains("90.0000° outward"),
        "{s}"
    );
    let o = archstudy(&["solve", "--find", "thickness", "--mu", "0.3092154443303"]);
    assert!(stdout(&o).contains("≈ 1.2205"), "{}", stdout(&o));
    let o = archstudy(&["solve", "--find", "thrust", "--k", "1.35"]);
    assert!(stdout(&o).contains("63.2903° intrados"), "{}", stdout(&o));
}

#[test]
fn json_has_the_documented_keys() {
    let always = [
        "find",
        "k",
        "t_over_r",
        "mu",
        "half_angle_deg",
        "weight",
        "voussoirs",
        "solve_time_us",
    ];
    let per_find: [(&str, &[&str]); 4] = [
        (
            "state",
            &[
                "regime",
                "thrust_r_min",
                "thrust_r_max",
                "thrust_s_min",
                "thrust_s_max",
            ],
        ),
        (
            "thickness",
            &[
                "k_crit",
                "t_over_r_crit",
                "mechanism",
                "thrust_over_half_weight",
                "hinges",
                "sliding_joints",
                "work_loads",
                "work_friction",
                "work_residual",
                "mechanism_dof",
            ],
        ),
        (
            "friction",
            &[
                "mu_crit",
                "mechanism",
                "thrust_over_half_weight",
                "hinges",
                "sliding_joints",
                "work_loads",
                "work_friction",
                "work_residual",
                "mechanism_dof",
            ],
        ),
        (
            "thrust",
            &["thrust_min", "thrust_max", "hinges_min", "hinges_max"],
        ),
    ];
    for (find, keys) in per_find {
        // The friction find computes μ: it is given none.
        let mu: &[&str] = if find == "friction" {
            &[]
        } else {
            &["--mu", "0.4"]
        };
        let v = solve_json(&[&["--find", find], mu].concat());
        for k in always.iter().chain(keys.iter()) {
            assert!(v.get(*k).is_some(), "{find}: key {k} missing in {v}");
        }
    }
    let v = solve_json(&["--find", "state"]);
    assert!(v["mu"].is_null(), "infinite μ is null");
    assert!(v["voussoirs"].is_null(), "continuum is null");
    let v = solve_json(&[
        "--find",
        "state",
        "--voussoirs",
        "12",
        "--t-over-r",
        "0.2",
        "--weight",
        "centreline",
    ]);
    assert_eq!(v["voussoirs"], 12);
    assert_abs_diff_eq!(f(&v, "k"), 1.2222222222222223, epsilon = 1e-15);
    assert_eq!(v["weight"], "centreline");
    let below = solve_json(&["--find", "thickness", "--mu", "0.2"]);
    assert!(below["k_crit"].is_null());
    assert_eq!(below["outcome"], "never_stands");
}

#[test]
fn bad_input_exits_2_naming_option_value_and_allowed() {
    let cases: [(&[&str], &str, &str); 11] = [
        (&["--k", "1"], "--k", "greater than 1"),
        (&["--k", "0.5"], "--k", "greater than 1"),
        (&["--mu", "-0.1"], "--mu", "≥ 0"),
        (&["--mu", "NaN"], "--mu", "≥ 0"),
        (
            &["--half-angle", "180"],
            "--half-angle",
            "between 0 and 180",
        ),
        (&["--half-angle", "0"], "--half-angle", "between 0 and 180"),
        (&["--voussoirs", "0"], "--voussoirs", "≥ 1"),
        (
            &["--k", "1.2", "--t-over-r", "0.2"],
            "--t-over-r",
            "not both",
        ),
        // What the find computes is no input: it would be left out without a word.
        (&["--find", "thickness", "--k", "1.3"], "--k", "computes K"),
        (
            &["--find", "thresholds", "--t-over-r", "0.1"],
            "--t-over-r",
            "computes K",
        ),
        (&["--find", "friction", "--mu", "0.4"], "--mu", "computes μ"),
    ];
    for (args, option, allowed) in cases {
        let mut all = vec!["solve"];
        all.extend_from_slice(args);
        let o = archstudy(&all);
        assert_usage_error(&o, &[option, allowed]);
        let e = stderr(&o);
        assert!(
            e.contains(args[1]) || e.contains(&args[args.len() - 1].to_string()),
            "{args:?}: {e}"
        );
    }
    let o = archstudy(&["solve", "--find", "everything"]);
    assert_usage_error(&o, &["--find", "everything"]);
}

#[test]
fn a_joint_at_the_crown_is_reported_at_zero_degrees_not_a_few_ulps_beside_it() {
    // The load at mid-span splits the crown joint; the family beside it ends one ulp from the
    // crown (−4.9e-324 rad), once reported as a sliding joint at 2.8e-322°.
    let args = "--find load-factor --half-angle 75 --k 1.2 --mu 0.3 --load point --at-x 0.5";
    let j = solve_json(&args.split(' ').collect::<Vec<_>>());
    let mut crown = 0;
    for key in [
        "sliding_joints",
        "collapse_sliding_joints",
        "hinges",
        "collapse_hinges",
    ] {
        for joint in j[key].as_array().into_iter().flatten() {
            let a = joint["angle_deg"].as_f64().expect("an angle");
            assert!(a == 0.0 || a.abs() > 1e-6, "{key}: {a}");
            if a == 0.0 {
                assert!(a.is_sign_positive(), "{key}: −0");
                crown += 1;
            }
        }
    }
    assert!(crown >= 2, "{j}");
}
