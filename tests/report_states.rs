//! Every drawn state is drawn on its own arch and under its own load: on a pointed arch,
//! with vertical joints, under a point load and under a horizontal load, each row of
//! states.parquet carries the parameters of its case, its outline is that arch's, and its
//! line of thrust passes through its hinges (a limit state) or stays inside the masonry (a
//! state that stands).

use crate::common::{run_study, scratch, study_run};
use archstudy::output::RunLayout;
use archstudy::report::charts::state::geometry::of_state;
use archstudy::store::{self, LoadFactorCase, StateRow};
use std::path::Path;

const POINTED_POINT_LOAD: &str = "\
name: pointed-point
arch: {shape: pointed, eccentricity: 0.2}
grid:
  at_deg: {values: [-60, -40, -20, 20, 40, 60]}
  k: {values: [1.15, 1.3]}
  mu: {values: [0.5, inf]}
load_cases:
  - {name: point, kind: point}
find: load_factor
";

const VERTICAL_HORIZONTAL: &str = "\
name: vertical-horizontal
arch: {joints: vertical, voussoirs: 12}
grid:
  k: {values: [1.15, 1.3, 1.45]}
  mu: {values: [0.6, 1.0, inf]}
load_cases:
  - {name: wind, kind: horizontal}
find: load_factor
";

const POINTED_VERTICAL_STATE: &str = "\
name: pointed-vertical
arch: {shape: pointed, eccentricity: 0.2, joints: vertical}
grid:
  k: {values: [1.1, 1.3]}
  mu: {values: [0.7, 1.6]}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
scenes:
  - {k: 1.3, mu: 1.6}
  - {k: 1.1, mu: 0.7}
";

fn states(run: &Path) -> Vec<StateRow> {
    store::read_states(&RunLayout::at(run).states()).expect("states.parquet")
}

fn cases(run: &Path) -> Vec<LoadFactorCase> {
    store::read_load_factor_cases(&RunLayout::at(run).results()).expect("results.parquet")
}

fn line(run: &Path, id: &str) -> Vec<(f64, f64)> {
    let curves = store::read_curves(&RunLayout::at(run).curves()).expect("curves.parquet");
    curves
        .iter()
        .filter(|c| c.figure == format!("line_of_thrust/{id}") && c.series == "line_of_thrust")
        .map(|c| (c.x, c.y))
        .collect()
}

/// The offset d = e(1 + K)/2 of each half's centre from the axis.
fn offset(s: &StateRow) -> f64 {
    s.eccentricity * 0.5 * (1.0 + s.k)
}

/// Each case state equals its case of results.parquet: K, μ, position, λ and mechanism.
fn assert_case_states(run: &Path, form: (&str, f64, &str), load: &str) {
    let all = cases(run);
    let drawn = states(run);
    let case_states: Vec<&StateRow> = drawn.iter().filter(|s| s.source == "case").collect();
    assert!(case_states.len() >= 2, "{drawn:#?}");
    let weakest = all
        .iter()
        .filter_map(|c| c.load_factor)
        .fold(f64::INFINITY, f64::min);
    let mut hinges_checked = 0;
    for s in case_states {
        let c = &all[s.case_id.expect("case id") as usize];
        assert_eq!((s.shape.as_str(), s.eccentricity), (form.0, form.1));
        assert_eq!(s.joint_orientation, form.2);
        assert_eq!(s.load, load);
        let (l, lc) = (s.load_factor.expect("λ"), c.load_factor.expect("λ"));
        // The weakest position of a moving point load is refined between the grid positions
        // either side of its case (20° apart here): below the case's λ, within 20° of it.
        if s.state == "weakest" && load == "point" && s.at_deg != c.at_deg {
            assert_eq!((s.k, s.mu), (c.k, c.mu), "{}", s.state_id);
            let (a, ac) = (s.at_deg.unwrap(), c.at_deg.unwrap());
            assert!((a - ac).abs() < 20.0, "{}: {a} from {ac}", s.state_id);
            assert!(l < lc, "{}: λ {l} vs {lc}", s.state_id);
        } else {
            assert_eq!(
                (s.k, s.mu, s.at_deg),
                (c.k, c.mu, c.at_deg),
                "{}",
                s.state_id
            );
            assert!(
                (l - lc).abs() < 1e-9 * (1.0 + lc),
                "{}: λ {l} vs {lc}",
                s.state_id
            );
            assert_eq!(s.mechanism, c.mechanism, "{}", s.state_id);
        }
        // Its collapse mechanism is stored and drawn, of the same kind, meeting eq. (11).
        let mechs = store::read_mechanisms(&RunLayout::at(run).mechanisms()).expect("mechanisms");
        let m = mechs
            .iter()
            .find(|m| m.state_id == s.state_id)
            .expect("a mechanism of the state");
        assert_eq!(Some(&m.mechanism), s.mechanism.as_ref(), "{}", s.state_id);
        assert!(
            m.work_residual < 1e-6,
            "{}: {}",
            s.state_id,
            m.work_residual
        );
        // Drawn for radial and vertical joints alike.
        assert!(
            run.join(format!("plots/mechanisms-{}.png", s.state_id))
                .is_file(),
            "{}",
            s.state_id
        );
        if s.state == "weakest" {
            assert!((lc - weakest).abs() < 1e-15, "{lc} vs {weakest}");
        }
        // The line of thrust passes through every hinge of the drawn arch.
        let g = of_state(s);
        let pts = line(run, &s.state_id);
        for h in &g.hinges {
            let p = h.point();
            let gap = pts
                .iter()
                .map(|q| (q.0 - p.0).hypot(q.1 - p.1))
                .fold(f64::INFINITY, f64::min);
            assert!(gap < 1e-7, "{}: hinge {:?} {gap}", s.state_id, h.joint);
            hinges_checked += 1;
        }
    }
    assert!(hinges_checked >= 3, "{hinges_checked} hinges");
    // One state per mechanism found among the cases.
    let mut kinds: Vec<&str> = all.iter().filter_map(|c| c.mechanism.as_deref()).collect();
    kinds.sort_unstable();
    kinds.dedup();
    // Of the cases drawn (a refined weakest state may collapse otherwise than its case).
    let mut drawn_kinds: Vec<&str> = drawn
        .iter()
        .filter(|s| s.source == "case")
        .filter_map(|s| all[s.case_id? as usize].mechanism.as_deref())
        .collect();
    drawn_kinds.sort_unstable();
    assert_eq!(drawn_kinds, kinds);
}

#[test]
fn pointed_arch_under_a_point_load_draws_its_weakest_case_on_the_pointed_arch() {
    let dir = scratch("states-pointed-point");
    let run = run_study(&dir, "pointed-point.yaml", POINTED_POINT_LOAD);
    assert_case_states(&run, ("pointed", 0.2, "radial"), "point");
    for s in states(&run) {
        // The load is drawn at the extrados end of its radial joint about its half's centre.
        let g = of_state(&s);
        let d = offset(&s);
        let t = s.at_deg.expect("position").to_radians();
        let Some(archstudy::plot::state::DrawnLoad::Point { at, .. }) = g.load else {
            panic!("{}: no point load drawn", s.state_id);
        };
        let want = (-d.copysign(t) + s.k * t.sin(), s.k * t.cos());
        assert!((at.0 - want.0).abs() < 1e-12 && (at.1 - want.1).abs() < 1e-12);
        assert!(std::fs::metadata(run.join(format!("plots/state-{}.svg", s.state_id))).is_ok());
    }
}

#[test]
fn vertical_joints_under_a_horizontal_load_draw_vertical_joints_and_the_load() {
    let dir = scratch("states-vertical-horizontal");
    let run = run_study(&dir, "vertical-horizontal.yaml", VERTICAL_HORIZONTAL);
    assert_case_states(&run, ("circular", 0.0, "vertical"), "horizontal");
    for s in states(&run) {
        let g = of_state(&s);
        assert_eq!(g.voussoir_joints.len(), 11, "{}", s.state_id);
        for j in &g.voussoir_joints {
            assert!((j.intrados.0 - j.extrados.0).abs() < 1e-12, "{j:?}");
        }
        assert!(matches!(
            g.load,
            Some(archstudy::plot::state::DrawnLoad::Horizontal { .. })
        ));
        // The line's points on the joints are stored, one per joint between voussoirs.
        let curves = store::read_curves(&RunLayout::at(&run).curves()).expect("curves");
        let on_joints = curves
            .iter()
            .filter(|c| {
                c.figure == format!("line_of_thrust/{}", s.state_id) && c.series == "line_on_joints"
            })
            .count();
        assert_eq!(on_joints, 11, "{}", s.state_id);
    }
    // Their states and mechanisms are drawn.
    let plots: Vec<String> = std::fs::read_dir(run.join("plots"))
        .expect("plots")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        plots.iter().any(|p| p.starts_with("state-case-")),
        "{plots:?}"
    );
    assert!(
        plots.iter().any(|p| p.starts_with("mechanisms-")),
        "{plots:?}"
    );
}

#[test]
fn a_standing_pointed_arch_with_vertical_joints_has_its_line_inside_the_masonry() {
    let dir = scratch("states-pointed-vertical");
    let run = run_study(&dir, "pointed-vertical.yaml", POINTED_VERTICAL_STATE);
    let drawn = states(&run);
    let standing = drawn
        .iter()
        .find(|s| s.state == "largest_margin")
        .expect("the scene K = 1.3, μ = 1.6 stands");
    assert_eq!((standing.k, standing.mu), (1.3, 1.6));
    assert_eq!(standing.regime.as_deref(), Some("stable"));
    let d = offset(standing);
    let pts = line(&run, &standing.state_id);
    assert!(pts.len() > 300);
    for (x, y) in pts {
        // Inside the annulus of its own half, strictly.
        let r = (x.abs() + d).hypot(y);
        assert!(
            r > 1.0 + 1e-3 && r < standing.k - 1e-3,
            "({x}, {y}): r = {r}"
        );
    }
    let collapse = drawn
        .iter()
        .find(|s| s.scene_k == 1.1)
        .expect("the scene K = 1.1, μ = 0.7");
    assert_eq!(collapse.state, "collapse");
    assert!(collapse.k > 1.1, "K_c = {}", collapse.k);
    assert_eq!(collapse.joint_orientation, "vertical");
    assert!(!collapse.joints.sliding_angles_deg.is_empty());
}

/// A pointed arch (e = 0.2) under self-weight over a grid that holds both its bifurcations
/// (rotational / mixed at μ ≈ 0.319, mixed / sliding at μ ≈ 0.259).
const POINTED_STATE: &str = "\
name: pointed-state
arch: {shape: pointed, eccentricity: 0.2}
grid:
  k: {from: 1.05, to: 1.2, steps: 16}
  mu: {values: [0.22, 0.25, 0.28, 0.31, 0.34, inf]}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

/// The semicircle with vertical joints under self-weight over a grid that holds its
/// rotational / mixed bifurcation (μ ≈ 2.02, K ≈ 1.116).
const VERTICAL_STATE: &str = "\
name: vertical-state
arch: {joints: vertical}
grid:
  k: {from: 1.08, to: 1.2, steps: 13}
  mu: {values: [1.8, 1.9, 2.0, 2.1, 2.2, inf]}
load_cases:
  - {name: gravity, kind: self_weight}
find: state
";

/// Every bifurcation of a state study on the general route has its collapse mechanisms in
/// mechanisms.parquet, as the semicircle's do: rows numbered by the bifurcation, at its K and
/// μ (to 1e-9), under both flow rules, of both its mechanisms among them, each meeting the
/// work equation (eq. 11; the whole balance under the associative rule) to
/// `KinematicsSettings::tol_work`, and drawn as `plots/mechanisms-bifurcation-<i>.png`.
/// Returns each bifurcation's K with the drawings of its mechanisms.
fn assert_bifurcation_mechanisms(
    run: &Path,
    at_least: usize,
) -> Vec<(f64, Vec<archstudy::analysis::kinematics::MechanismDrawing>)> {
    use archstudy::analysis::kinematics::KinematicsSettings;
    let layout = RunLayout::at(run);
    let bifs = store::read_bifurcations(&layout.bifurcations()).expect("bifurcations");
    let mechs = store::read_mechanisms(&layout.mechanisms()).expect("mechanisms");
    assert!(bifs.len() >= at_least, "{} bifurcations", bifs.len());
    let mut out = Vec::new();
    for (i, b) in bifs.iter().enumerate() {
        let id = format!("bifurcation-{}", i + 1);
        let own: Vec<&store::MechanismRow> = mechs
            .iter()
            .filter(|m| m.bifurcation as usize == i + 1 && m.load_case == b.load_case)
            .collect();
        for rule in ["non_associative", "associative"] {
            let n = own.iter().filter(|m| m.flow_rule == rule).count();
            assert!(n >= 2, "{id}: {n} {rule} mechanisms");
        }
        let mut kinds: Vec<&str> = own.iter().map(|m| m.mechanism.as_str()).collect();
        kinds.sort_unstable();
        kinds.dedup();
        for kind in [&b.mechanism_a, &b.mechanism_b] {
            assert!(
                kinds.contains(&kind.as_str()),
                "{id}: {kinds:?}, not {kind}"
            );
        }
        let mut drawings = Vec::new();
        for m in &own {
            assert_eq!(m.state_id, id);
            assert!((m.k - b.k).abs() <= 1e-9, "{id}: K {} vs {}", m.k, b.k);
            assert!((m.mu - b.mu).abs() <= 1e-9, "{id}: μ {} vs {}", m.mu, b.mu);
            assert!(
                m.work_residual <= KinematicsSettings::DEFAULT.tol_work,
                "{id} {} {}: work residual {}",
                m.mechanism,
                m.flow_rule,
                m.work_residual
            );
            drawings.push(serde_json::from_str(&m.drawing_json).expect("a drawing"));
        }
        assert!(
            run.join(format!("plots/mechanisms-{id}.png")).is_file(),
            "{id}: no figure"
        );
        out.push((b.k, drawings));
    }
    out
}

/// The drawing stands on horizontal springing beds from (±`intrados_x`, 0) to
/// (±`extrados_x`, 0), to 1e-12 (`k`, the arch's K, names it in a failure).
fn assert_supports(
    g: &archstudy::analysis::kinematics::MechanismDrawing,
    intrados_x: f64,
    extrados_x: f64,
    k: f64,
) {
    for (s, side) in g.supports.iter().zip([-1.0, 1.0]) {
        for (p, x) in [
            (s.intrados, side * intrados_x),
            (s.extrados, side * extrados_x),
        ] {
            assert!(
                (p[0] - x).abs() < 1e-12 && p[1].abs() < 1e-12,
                "{p:?} against ({x}, 0) at K {k}"
            );
        }
    }
}

/// The mechanisms at the bifurcations of a pointed arch are drawn on the pointed arch: its
/// springings at x = ±(1 − d) and ±(K − d), d = e(1 + K)/2 the offset of each half's centre,
/// not at ±1 and ±K as on the semicircle, and its highest point the extrados apex at x = 0,
/// y = √(K² − d²).
#[test]
fn pointed_arch_bifurcations_have_their_mechanisms_drawn_on_the_pointed_arch() {
    let run = study_run("states-pointed-state", "pointed.yaml", POINTED_STATE);
    let all = assert_bifurcation_mechanisms(&run, 2);
    let mut drawn = 0;
    for (k, drawings) in all {
        let d = 0.2 * 0.5 * (1.0 + k);
        let apex = (k * k - d * d).sqrt();
        for g in drawings {
            assert_supports(&g, 1.0 - d, k - d, k);
            let top = g
                .outlines
                .iter()
                .flat_map(|o| o.original.iter())
                .max_by(|a, b| a[1].total_cmp(&b[1]))
                .expect("an outline");
            assert!(
                top[0].abs() < 1e-9 && (top[1] - apex).abs() < 1e-9,
                "highest point {top:?}, apex (0, {apex}) at K {k}"
            );
            drawn += 1;
        }
    }
    assert!(drawn >= 8, "{drawn} drawings");
}

/// The mechanisms at the bifurcation of the semicircle with vertical joints are drawn on
/// that arch: it stands on its radial springings (from (±1, 0) to (±K, 0)), and its sliding
/// joints at ±90° are the vertical sections through the intrados springings: centred at
/// (±1, √(K² − 1)/2) and running straight up.
#[test]
fn vertical_joint_bifurcations_have_their_mechanisms_drawn_on_vertical_joints() {
    let run = study_run("states-vertical-state", "vertical.yaml", VERTICAL_STATE);
    let all = assert_bifurcation_mechanisms(&run, 1);
    let mut sections = 0;
    for (k, drawings) in all {
        for g in drawings {
            assert_supports(&g, 1.0, k, k);
            for s in g.slides.iter().filter(|s| s.centre[1] > 1e-9) {
                let side = s.centre[0].signum();
                assert!(
                    (s.centre[0] - side).abs() < 1e-12
                        && (s.centre[1] - 0.5 * (k * k - 1.0).sqrt()).abs() < 1e-12,
                    "{s:?} at K {k}"
                );
                assert!(
                    s.along[0].abs() < 1e-12 && (s.along[1] - 1.0).abs() < 1e-12,
                    "{s:?}"
                );
                sections += 1;
            }
        }
    }
    assert!(sections >= 8, "{sections} vertical sections drawn");
}

const VERTICAL_WEDGE_LOAD: &str = "\
name: vertical-wedge
arch: {joints: vertical, half_angle_deg: 60}
grid:
  at_x: {values: [0.03, 0.97]}
  k: {values: [1.35, 1.5]}
  mu: {values: [0.5, 0.55]}
load_cases:
  - {name: point, kind: point}
find: load_factor
scenes:
  - {k: 1.5, mu: 0.55}
";

/// A point load by x/L on the springing wedge of a vertical-joint arch (α = 60°: x/L = 0.03
/// and 0.97 lie beyond the vertical sections through the intrados springings, x = ±sin α):
/// each state is drawn with the load at its own extrados point, the closed form
/// x = (2x/L − 1)·K sin α, y = √(K² − x²), to 1e-9, not at the top of the vertical joint at
/// ±α; its λ is the case's (the state is solved again with the load there), and its line of
/// thrust turns on the load's vertical.
#[test]
fn a_load_on_the_springing_wedge_is_drawn_at_its_own_extrados_point() {
    let dir = scratch("states-vertical-wedge");
    let run = run_study(&dir, "vertical-wedge.yaml", VERTICAL_WEDGE_LOAD);
    let (all, drawn) = (cases(&run), states(&run));
    assert!(drawn.len() >= 3, "{drawn:#?}");
    // The case states: the weakest (sliding at both springings, λ ≈ 13.19) and the weakest
    // mixed one (λ ≈ 55.65), each with the λ and mechanism of its case.
    for s in drawn.iter().filter(|s| s.source == "case") {
        let c = &all[s.case_id.expect("case id") as usize];
        assert_eq!((s.k, s.mu, s.at_x), (c.k, c.mu, c.at_x), "{}", s.state_id);
        let (l, lc) = (s.load_factor.expect("λ"), c.load_factor.expect("λ"));
        assert!(
            (l - lc).abs() < 1e-9 * (1.0 + lc),
            "{}: λ {l} vs {lc}",
            s.state_id
        );
        assert_eq!(s.mechanism, c.mechanism, "{}", s.state_id);
    }
    let kinds: Vec<_> = (drawn.iter())
        .filter(|s| s.source == "case")
        .map(|s| (s.mechanism.clone().unwrap_or_default(), s.load_factor))
        .collect();
    assert_eq!(kinds.len(), 2, "{kinds:?}");
    approx::assert_abs_diff_eq!(kinds[0].1.unwrap(), 13.1900814, epsilon = 1e-6);
    approx::assert_abs_diff_eq!(kinds[1].1.unwrap(), 55.6503316, epsilon = 1e-6);
    let alpha = 60f64.to_radians();
    for s in &drawn {
        let at_x = s
            .at_x
            .unwrap_or_else(|| panic!("{}: no x/L: {s:?}", s.state_id));
        assert!(at_x == 0.03 || at_x == 0.97, "{}: {at_x}", s.state_id);
        let x = (2.0 * at_x - 1.0) * s.k * alpha.sin();
        let want = (x, (s.k * s.k - x * x).sqrt());
        assert!(x.abs() > alpha.sin(), "{}: not on the wedge", s.state_id);
        let g = of_state(s);
        let Some(archstudy::plot::state::DrawnLoad::Point { at, .. }) = g.load else {
            panic!("{}: no point load drawn", s.state_id);
        };
        assert!(
            (at.0 - want.0).abs() < 1e-9 && (at.1 - want.1).abs() < 1e-9,
            "{}: arrow at {at:?}, the load at {want:?}",
            s.state_id
        );
        let pts = line(&run, &s.state_id);
        assert!(
            pts.iter().any(|p| (p.0 - want.0).abs() < 1e-12),
            "{}: the line does not turn on the load's vertical",
            s.state_id
        );
    }
}

/// A scene of a load_factor study names where its point load stands: the weakest position
/// of its arch here (the study moves the load), in the figure's subtitle as in its caption.
#[test]
fn a_load_factor_scene_names_its_load_position() {
    let manifest = "\
name: scene-position
arch: {shape: pointed, eccentricity: 0.2}
grid:
  at_deg: {values: [-45, -15, 30]}
  k: {values: [1.3]}
  mu: {values: [0.5, 0.6]}
load_cases:
  - {name: point, kind: point}
find: load_factor
scenes:
  - {k: 1.3, mu: 0.5}
";
    let run = study_run("scene-position", "scene.yaml", manifest);
    let states = store::read_states(&RunLayout::at(&run).states()).expect("states.parquet");
    let scene = states
        .iter()
        .find(|s| s.state_id == "scene-1")
        .expect("the scene's state");
    let cases = store::read_load_factor_cases(&run.join("results.parquet")).expect("results");
    // The weakest of the three positions at K = 1.3, μ = 0.5.
    let weakest = cases
        .iter()
        .filter(|c| c.mu == 0.5)
        .min_by(|a, b| a.load_factor.unwrap().total_cmp(&b.load_factor.unwrap()))
        .expect("cases at μ = 0.5");
    assert_eq!(scene.at_deg, weakest.at_deg);
    let at = scene.at_deg.expect("a point load position");
    let named = format!("load at {}°", archstudy::report::format::position_deg(at));
    // Figures set a minus sign where the report's text has a hyphen-minus.
    let drawn = named.replace('-', "\u{2212}");
    let svg = std::fs::read_to_string(run.join("plots/state-scene-1.svg")).expect("the figure");
    assert!(svg.contains(&drawn), "the subtitle does not name {drawn}");
    let md = std::fs::read_to_string(run.join("report.md")).expect("report.md");
    let caption = md
        .lines()
        .find(|l| l.contains("The collapse state of the scene"))
        .expect("the scene's caption");
    assert!(
        caption.contains(&named),
        "the caption does not name {named}: {caption}"
    );
}
