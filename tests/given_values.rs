//! Values a researcher gives come back as given: a half-angle of 60° is 60 in `solve --json`,
//! results.parquet, headings, captions and figure file names (not the 59.99999999999999 of
//! a round trip through radians); a point load fixed at x/L is one position at every K.

use crate::common::{run_study, scratch, solve_json};
use archstudy::output::RunLayout;
use archstudy::store;
use std::path::Path;

/// Half-angles whose round trip through radians is not exact.
const ANGLES: [f64; 3] = [30.0, 60.0, 120.0];

#[test]
fn solve_json_keeps_the_half_angle_as_given() {
    for a in ANGLES {
        let text = a.to_string();
        let v = solve_json(&["--half-angle", &text]);
        assert_eq!(v["half_angle_deg"].as_f64(), Some(a), "{v}");
    }
    // A springing joint of the mechanism is named by α as given.
    let v = solve_json(&[
        "--find",
        "load-factor",
        "--half-angle",
        "60",
        "--k",
        "1.2",
        "--mu",
        "0.3",
        "--load",
        "point",
        "--at-x",
        "0.25",
    ]);
    let angles: Vec<f64> = v["sliding_joints"]
        .as_array()
        .expect("sliding_joints")
        .iter()
        .filter_map(|j| j["angle_deg"].as_f64())
        .collect();
    assert!(angles.contains(&60.0), "{angles:?}");
    assert!(
        angles.iter().all(|a| a.abs() == 60.0 || a.abs() < 59.0),
        "{angles:?}"
    );
}

const HALF_ANGLE_STUDY: &str = "\
name: given-angles
grid:
  half_angle_deg: {values: [30, 60, 120]}
  k: {values: [1.05, 1.2]}
  mu: {values: [0.4, inf]}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
scenes:
  - {k: 1.2, mu: 0.4}
";

/// Every file name under `plots/`.
fn plot_names(run: &Path) -> Vec<String> {
    std::fs::read_dir(run.join("plots"))
        .expect("plots/")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect()
}

/// Decimals of 13 digits or more after a decimal point (a round trip's last bits, or an
/// angle printed to 15 digits), with the text before them.
fn long_decimals(text: &str) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 1;
    while i + 1 < chars.len() {
        if chars[i] == '.' && chars[i - 1].is_ascii_digit() {
            let run = chars[i + 1..]
                .iter()
                .take_while(|c| c.is_ascii_digit())
                .count();
            if run >= 13 {
                let from = i.saturating_sub(12);
                out.push(chars[from..i + 1 + run].iter().collect());
            }
            i += run;
        }
        i += 1;
    }
    out
}

#[test]
fn a_half_angle_axis_is_stored_and_printed_as_given() {
    let dir = scratch("given-angles");
    let run = run_study(&dir, "given-angles.yaml", HALF_ANGLE_STUDY);
    let arches = store::read_row_arches(&RunLayout::at(&run).results()).expect("results");
    let mut seen: Vec<f64> = arches.iter().map(|a| a.half_angle_deg).collect();
    seen.sort_by(f64::total_cmp);
    seen.dedup();
    assert_eq!(seen, ANGLES.to_vec());
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    assert!(!md.contains("59.9999"), "{md}");
    assert!(!md.contains("29.9999") && !md.contains("119.9999"));
    assert_eq!(long_decimals(&md), Vec::<String>::new());
    for name in plot_names(&run) {
        assert!(!name.contains("9999"), "{name}");
    }
    let json = std::fs::read_to_string(run.join("run.json")).expect("run.json");
    assert!(!json.contains("59.9999"));
}

/// A point load fixed at x/L = 0.25 on a segmental arch, over K and μ.
const SPAN_POINT_STUDY: &str = "\
name: span-point
arch:
  half_angle_deg: 60
grid:
  k: {values: [1.1, 1.2, 1.3]}
  mu: {values: [0.3, 0.5, inf]}
load_cases:
  - {name: quarter, kind: point, at_x: 0.25}
find: load_factor
";

#[test]
fn a_point_load_fixed_at_x_over_l_is_one_position_at_every_k() {
    let dir = scratch("span-point");
    let run = run_study(&dir, "span-point.yaml", SPAN_POINT_STUDY);
    let cases = store::read_load_factor_cases(&RunLayout::at(&run).results()).expect("results");
    assert_eq!(cases.len(), 9);
    assert!(
        cases
            .iter()
            .all(|c| c.at_x == Some(0.25) && c.half_angle_deg == 60.0)
    );
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    // One position: no "weakest load position" among positions that are one, no influence
    // line, and the λ-against-K/μ figure of the load case.
    assert!(!md.contains("weakest load position"), "{md}");
    let plots = plot_names(&run);
    assert!(plots.iter().any(|p| p == "load-factor.png"), "{plots:?}");
    assert!(!plots.iter().any(|p| p.starts_with("influence-line")));
    assert!(md.contains("x/L = 0.25"), "{md}");
    // Angles in text to the digits that mean something.
    assert_eq!(long_decimals(&md), Vec::<String>::new());
}
