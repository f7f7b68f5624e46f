//! The state drawing of one solved scene (`archstudy.solve` in a notebook): the report's own
//! drawing of a state ([`super::state`]), on the scene's arch to scale.
//!
//! A critical find draws its limit state (the arch at K_c, μ_c or λ_max with its hinges and
//! sliding joints); any other find draws the scene's state of largest margin when it stands,
//! else the arch alone with a note that no equilibrium exists.

use super::arch_axis::ArchAxes;
use super::state::figure_with_lines;
use super::{Chart, FigureSpec};
use crate::analysis::MechanismKind;
use crate::analysis::symmetric::ThrustState;
use crate::figdata::{self, general};
use crate::plot::Format;
use crate::scene::{Find, Outcome, Solution};
use crate::store::StateRow;
use anyhow::Result;

/// The state row drawn for a solution: its arch, load and, when known, its crown state.
pub fn state_row(sol: &Solution) -> StateRow {
    let k = sol.k.or(sol.k_crit).or(sol.k_c_rotational).unwrap_or(1.35);
    let mu = if sol.mu_infinite {
        f64::INFINITY
    } else {
        sol.mu.or(sol.mu_crit).unwrap_or(f64::INFINITY)
    };
    let mut row = StateRow {
        state_id: "solution".into(),
        source: "scene".into(),
        state: "no_equilibrium".into(),
        load_case: sol.load.into(),
        scene_k: k,
        scene_mu: mu,
        k,
        t_over_r: crate::model::t_over_r_from_k(k),
        mu,
        half_angle_deg: sol.half_angle_deg,
        weight: sol.weight.as_str().into(),
        voussoirs: sol.voussoirs,
        shape: sol.shape.into(),
        eccentricity: sol.eccentricity.unwrap_or(0.0),
        joint_orientation: sol.joints.into(),
        keystone: sol.keystone && sol.voussoirs.is_none(),
        load: sol.load.into(),
        at_deg: sol.at_deg,
        at_x: sol.at_x,
        load_width: sol.load_width,
        load_factor: sol.lambda.or(sol.load_factor),
        regime: sol.regime.map(|r| r.as_str().to_string()),
        thrust_r_min: sol.thrust_r_min,
        thrust_r_max: sol.thrust_r_max,
        thrust_s_min: sol.thrust_s_min,
        thrust_s_max: sol.thrust_s_max,
        ..StateRow::default()
    };
    let critical = matches!(
        sol.find,
        Find::Thickness | Find::Friction | Find::LoadFactor
    );
    if critical && sol.outcome == Some(Outcome::Found) {
        // λ_max is drawn as a load-factor collapse; K_c and μ_c as the find's limit state.
        row.state = if sol.find == Find::LoadFactor {
            "collapse".into()
        } else {
            "limit".into()
        };
        row.mechanism = sol.mechanism.map(|m| m.as_str().to_string());
        row.thrust_over_half_weight = sol.thrust_over_half_weight;
        row.crown_moment = sol.crown_moment;
        row.crown_shear = sol.crown_shear;
        row.joints = figdata::joint_lists(&sol.hinges, &sol.sliding_joints);
    } else if let Ok(model) = general::model_of_state(&row) {
        let phi = crate::model::Friction::new(mu)
            .unwrap_or(crate::model::Friction::INFINITE)
            .angle();
        let lambda = row.load_factor.unwrap_or(0.0);
        if let Some(c) = general::largest_margin_state(&model, phi, lambda) {
            row.state = "largest_margin".into();
            row.thrust_over_half_weight = finite(c.fx);
            row.crown_moment = finite(-c.m0);
            row.crown_shear = finite(c.fy);
        }
    }
    row
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// The drawing of a solution's state, as the report draws a state.
///
/// A critical find with a gap draws its collapse, the first complete solution (the
/// conservative end, the value archstudy calls the collapse), and names the static limit
/// above it in the subtitle.
pub fn figure(sol: &Solution) -> Result<FigureSpec> {
    if let Some(row) = collapse_row(sol) {
        let (line, on_joints) = figdata::lines_of_state(&row)?.unwrap_or_default();
        let mut spec = figure_with_lines(&row, line, on_joints, false, ArchAxes::default());
        if let Chart::State(d) = &mut spec.chart {
            d.subtitle.push(gap_words(sol));
        }
        return Ok(spec);
    }
    let row = state_row(sol);
    let (line, on_joints) = figdata::lines_of_state(&row)?.unwrap_or_default();
    Ok(figure_with_lines(
        &row,
        line,
        on_joints,
        false,
        ArchAxes::default(),
    ))
}

/// The state row of a critical find's first complete solution when it comes before the
/// static limit (`gap`): the arch at the collapse value with the crown state and the
/// joints of its mechanism.
pub fn collapse_row(sol: &Solution) -> Option<StateRow> {
    let value = drawn_collapse(sol)?;
    let mut row = state_row(sol);
    match sol.find {
        Find::LoadFactor => row.load_factor = Some(value),
        Find::Thickness => {
            row.k = value;
            row.scene_k = value;
            row.t_over_r = crate::model::t_over_r_from_k(value);
        }
        _ => {
            row.mu = value;
            row.scene_mu = value;
        }
    }
    row.state = "first_complete".into();
    row.mechanism = sol.collapse_mechanism.map(|m| m.as_str().to_string());
    row.thrust_over_half_weight = sol.collapse_thrust_over_half_weight;
    row.crown_moment = sol.collapse_crown_moment;
    row.crown_shear = sol.collapse_crown_shear;
    row.joints = figdata::joint_lists(&sol.collapse_hinges, &sol.collapse_sliding_joints);
    Some(row)
}

/// The collapse value of a critical find whose first complete solution comes before its
/// static limit (a gap), the state [`collapse_row`] draws; `None` otherwise.
pub fn drawn_collapse(sol: &Solution) -> Option<f64> {
    use crate::analysis::gap::GapStatus;
    let critical = matches!(
        sol.find,
        Find::LoadFactor | Find::Thickness | Find::Friction
    );
    (critical && sol.gap == Some(GapStatus::Gap) && sol.outcome == Some(Outcome::Found))
        .then_some(sol.collapse_value?)
        .filter(|v| v.is_finite())
}

/// One line on the gap: the collapse value, the static limit above it and the joints that
/// lift off (drawn as neither hinge nor slide).
pub fn gap_words(sol: &Solution) -> String {
    use crate::report::format::short;
    let name = match sol.find {
        Find::LoadFactor => "λ",
        Find::Thickness => "K",
        _ => "μ",
    };
    let limit = match sol.find {
        Find::LoadFactor => sol.load_factor,
        Find::Thickness => sol.k_crit,
        _ => sol.mu_crit,
    };
    let mut s = format!(
        "collapse {name} = {}; static limit {name} = {}; gap {}",
        sol.collapse_value.map_or("—".into(), short),
        limit.map_or("∞".into(), short),
        sol.gap_width.map_or("—".into(), short)
    );
    if !sol.collapse_lifted_joints.is_empty() {
        let at: Vec<String> = sol
            .collapse_lifted_joints
            .iter()
            .map(|a| format!("{}°", crate::report::format::position_deg(*a)))
            .collect();
        s.push_str(&format!("; lift-off at {}", at.join(", ")));
    }
    s
}

/// The drawing of a standing scene of a circular arch with radial joints under self-weight
/// (`sol`, its `state` answer) with the lines of thrust of its minimum-thrust state `lo` and
/// its maximum-thrust state `hi` ([`crate::analysis::symmetric::thrust`]), each with its
/// hinges and sliding joints. A state whose crown moment is not fixed (a thrust set by
/// sliding alone) has no unique line: its line is not drawn and the subtitle says so.
pub fn thrust_states_figure(
    sol: &Solution,
    lo: &ThrustState,
    hi: &ThrustState,
) -> Result<FigureSpec> {
    let row_of = |s: &ThrustState, name: &str| {
        let mut row = state_row(sol);
        row.state = name.into();
        row.thrust_over_half_weight = finite(s.thrust_over_half_weight);
        row.crown_moment = finite(s.crown_moment);
        row.crown_shear = Some(0.0);
        row.joints = figdata::joint_lists(&s.hinges, &s.sliding_joints);
        row.mechanism = MechanismKind::from_counts(s.hinges.len(), s.sliding_joints.len())
            .map(|m| m.as_str().to_string());
        row
    };
    let (row_lo, row_hi) = (row_of(lo, "minimum_thrust"), row_of(hi, "maximum_thrust"));
    let (line_lo, joints_lo) = figdata::lines_of_state(&row_lo)?.unwrap_or_default();
    let (line_hi, _) = figdata::lines_of_state(&row_hi)?.unwrap_or_default();
    let mut spec = figure_with_lines(&row_lo, line_lo, joints_lo, false, ArchAxes::default());
    let h = |s: &ThrustState| crate::report::format::short(s.thrust_over_half_weight);
    if let Chart::State(d) = &mut spec.chart {
        d.title = format!(
            "Minimum- and maximum-thrust states, K = {}, μ = {}",
            crate::report::format::given(row_lo.k),
            super::mu_text(row_lo.mu)
        );
        d.line_label = format!("minimum-thrust line, H/W_half = {}", h(lo));
        d.other_line_label = format!("maximum-thrust line, H/W_half = {}", h(hi));
        if line_hi.is_empty() {
            d.subtitle.push(format!(
                "The maximum thrust H/W_half = {} is set by sliding alone: its line of thrust is not unique and is not drawn.",
                h(hi)
            ));
        }
        d.other_line = line_hi;
        let g = super::state::geometry::of_state(&row_hi);
        d.hinges.extend(g.hinges);
        d.sliding.extend(g.sliding);
    }
    spec.title = "Minimum- and maximum-thrust states".into();
    Ok(spec)
}

/// The drawing of a solution's state as the text of an SVG file.
pub fn svg(sol: &Solution) -> Result<String> {
    let bytes = figure(sol)?.render(Format::Svg)?;
    Ok(String::from_utf8(bytes)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::manifest::SceneOptions;

    #[test]
    fn a_thickness_find_draws_its_limit_state_at_k_crit_with_its_five_hinges() {
        let scene = SceneOptions {
            find: "thickness".into(),
            mu: 0.35,
            ..SceneOptions::default()
        }
        .scene()
        .unwrap();
        let sol = crate::scene::solve_static(&scene);
        let row = state_row(&sol);
        assert_eq!(row.state, "limit");
        assert_eq!(Some(row.k), sol.k_crit);
        let svg = svg(&sol).unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..40]);
        assert!(svg.contains("K = "), "the title names K");
        // Not the words of a study's scene that cannot stand.
        assert!(
            svg.contains("Static limit"),
            "the title names the static limit"
        );
        assert!(!svg.contains("cannot stand"));
    }

    #[test]
    fn a_load_factor_find_with_a_gap_draws_its_collapse_below_the_static_limit() {
        // Twelve voussoirs under a horizontal load: λ_max = 8.518042, but the arch can start
        // to move at λ = 7.383083 (docs/mechanics.md §4).
        let scene = SceneOptions {
            find: "load-factor".into(),
            voussoirs: Some(12),
            k: Some(1.5278),
            mu: 1.0396,
            half_angle_deg: 50.367,
            load: "horizontal".into(),
            ..SceneOptions::default()
        }
        .scene()
        .unwrap();
        let sol = crate::scene::solve(&scene);
        let row = collapse_row(&sol).expect("a gap");
        assert_eq!(row.state, "first_complete");
        assert!(
            (row.load_factor.unwrap() - 7.383083).abs() < 1e-6,
            "{row:?}"
        );
        let spec = figure(&sol).unwrap();
        let Chart::State(d) = &spec.chart else {
            panic!("a state drawing")
        };
        assert!(d.title.contains("first complete solution"), "{}", d.title);
        assert_eq!(d.hinges.len(), sol.collapse_hinges.len());
        assert_eq!(d.sliding.len(), sol.collapse_sliding_joints.len());
        assert_eq!(
            (d.hinges.len(), d.sliding.len()),
            (2, 2),
            "{:?}",
            sol.collapse_hinges
        );
        let words = d.subtitle.join(" | ");
        assert!(
            words.contains("collapse λ = 7.3831") && words.contains("static limit λ = 8.5180"),
            "{words}"
        );
        assert!(
            !d.line_of_thrust.is_empty(),
            "the collapse state's line is drawn"
        );
        // A find without a gap keeps its static limit.
        let no_gap = SceneOptions {
            find: "thickness".into(),
            mu: 0.35,
            ..SceneOptions::default()
        }
        .scene()
        .unwrap();
        assert!(collapse_row(&crate::scene::solve(&no_gap)).is_none());
    }

    #[test]
    fn an_arch_of_more_voussoirs_than_a_figure_can_draw_is_drawn_as_its_outline() {
        let spec = |n: i64| {
            let scene = SceneOptions {
                mu: 0.6,
                voussoirs: Some(n),
                find: "thickness".into(),
                ..SceneOptions::default()
            }
            .scene()
            .unwrap();
            let spec = figure(&crate::scene::solve_static(&scene)).unwrap();
            match spec.chart {
                Chart::State(d) => (d, spec.caption),
                _ => panic!("a state drawing"),
            }
        };
        let (few, few_caption) = spec(1000);
        assert_eq!(few.voussoir_joints.len(), 999);
        assert!(!few.line_on_joints.is_empty());
        let (many, many_caption) = spec(5000);
        assert!(many.voussoir_joints.is_empty() && many.line_on_joints.is_empty());
        assert!(
            many.subtitle
                .iter()
                .any(|l| l.contains("4999 joints are too close to draw")),
            "{:?}",
            many.subtitle
        );
        assert_eq!(
            many.hinges.len(),
            few.hinges.len(),
            "the hinges are still drawn"
        );
        // The caption speaks of the joints' points only where they are drawn.
        assert!(few_caption.contains("Open circles"));
        assert!(!many_caption.contains("Open circles"));
    }

    #[test]
    fn a_state_that_stands_draws_its_state_of_largest_margin() {
        let scene = SceneOptions {
            k: Some(1.3),
            mu: 0.5,
            ..SceneOptions::default()
        }
        .scene()
        .unwrap();
        let row = state_row(&crate::scene::solve(&scene));
        assert_eq!(row.state, "largest_margin");
        assert!(row.thrust_over_half_weight.is_some_and(|h| h > 0.0));
    }
}
