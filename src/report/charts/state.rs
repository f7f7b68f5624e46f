//! Figure 3: a state of the arch drawn to scale with its line of thrust, hinges and sliding
//! joints.

use super::arch_axis::ArchAxes;
use super::{Chart, FigureSpec, mu_text, safe};
use crate::figdata;
use crate::plot::state::{StateDrawing, Xy};
use crate::report::data::RunData;
use crate::report::format::{compact, given, position_deg, short};
use crate::store::StateRow;

pub mod geometry;

/// The drawing of a state, to scale, on its own arch: outline, joints and supports from the
/// general statics of the state's arch, form and load ([`figdata::general::model_of_state`]).
pub fn figure(data: &RunData, s: &StateRow) -> FigureSpec {
    let fig = figdata::line_of_thrust_figure(&s.state_id);
    let line = data.curve(&fig, figdata::LINE_OF_THRUST);
    let on_joints = data.curve(&fig, figdata::LINE_ON_JOINTS);
    let moving = data.manifest.axis("at_deg").is_some() || data.manifest.axis("at_x").is_some();
    figure_with_lines(s, line, on_joints, moving, super::arch_axis::axes(data))
}

/// The drawing of a state from its line of thrust and the line's points on the voussoir
/// joints (empty for the continuum); `moving` when the study moves its point load (the
/// caption then names the weakest position); `varied` the arch axes of the study, whose
/// values every title names.
pub fn figure_with_lines(
    s: &StateRow,
    line: Vec<Xy>,
    on_joints: Vec<Xy>,
    moving: bool,
    varied: ArchAxes,
) -> FigureSpec {
    let mut geometry = geometry::of_state(s);
    let mut on_joints = on_joints;
    let too_many = geometry.voussoir_joints.len() > crate::plot::MAX_DRAWN_JOINTS;
    let line = crate::plot::thinned(line);
    let n_joints = geometry.voussoir_joints.len();
    if too_many {
        geometry.voussoir_joints.clear();
        on_joints.clear();
    }
    let joints_note = if on_joints.is_empty() {
        ""
    } else {
        " Open circles: the line's points on the joints, the only sections where it must stay within the arch."
    };
    let mut texts = StateTexts::of(s, moving);
    let arch = arch_text(s, varied);
    if !arch.is_empty() {
        texts.title = format!("{} ({arch})", texts.title);
        texts.heading = format!("{} ({arch})", texts.heading);
        texts.caption = format!("{} Arch: {arch}.", texts.caption);
    }
    let note = texts.note.or_else(|| {
        line.is_empty()
            .then(|| "line of thrust not unique: not drawn".to_string())
    });
    let vertical_note = if s.joint_orientation == "vertical" {
        " The joints are vertical planes through the intrados and the supports the radial springing joints; between the last vertical section and a support the model has no section, and the line of thrust is drawn straight there."
    } else {
        ""
    };
    let caption = format!("{}{joints_note}{vertical_note}", texts.caption);
    let mut subtitle = texts.subtitle;
    if too_many {
        subtitle.push(format!(
            "the {n_joints} joints are too close to draw: the arch is drawn as its outline"
        ));
    }
    FigureSpec {
        stem: format!("state-{}", safe(&s.state_id)),
        title: texts.heading,
        caption,
        chart: Chart::State(StateDrawing {
            title: texts.title,
            subtitle,
            outline: geometry.outline,
            voussoir_joints: geometry.voussoir_joints,
            supports: geometry.supports,
            line_of_thrust: line,
            line_on_joints: on_joints,
            line_label: String::new(),
            other_line: Vec::new(),
            other_line_label: String::new(),
            hinges: geometry.hinges,
            sliding: geometry.sliding,
            load: geometry.load,
            note: geometry.note.or(note),
        }),
    }
}

/// The arch and load of a state where they differ from the paper's semicircle under its own
/// weight: half-angle, voussoir count, shape, joints, load, its position and λ (empty for the
/// paper's arch).
pub fn arch_text(s: &StateRow, varied: ArchAxes) -> String {
    let mut parts = Vec::new();
    if s.shape == "pointed" {
        parts.push(format!("pointed, e = {}", given(s.eccentricity)));
    } else if varied.e {
        parts.push("e = 0".into());
    }
    if varied.alpha || (s.half_angle_deg - 90.0).abs() > 1e-9 {
        parts.push(format!("α = {}°", given(s.half_angle_deg)));
    }
    match s.voussoirs {
        Some(n) => parts.push(format!("N = {n} voussoirs")),
        None if varied.n => parts.push("continuum".into()),
        None => {}
    }
    if varied.joints || s.joint_orientation == "vertical" {
        parts.push(format!("{} joints", s.joint_orientation));
    }
    if s.weight != "annular" {
        parts.push(format!("{} weight", s.weight));
    }
    if s.load != "self_weight" {
        let at = match (s.at_x, s.at_deg) {
            // x/L as given; one computed from the angle (every digit of a float) yields to it.
            (Some(x), None) => format!(" at x/L = {}", given(x)),
            (Some(x), Some(_)) if given(x).len() <= 8 => format!(" at x/L = {}", given(x)),
            (_, Some(a)) => format!(" at {}°", position_deg(a)),
            (None, None) => String::new(),
        };
        let lambda = s
            .load_factor
            .map_or(String::new(), |l| format!(", λ = {}", compact(l)));
        let spread = s
            .load_width
            .filter(|&w| w > 0.0)
            .map_or(String::new(), |w| format!(" spread over {} L", given(w)));
        parts.push(format!(
            "{} load{spread}{at}{lambda}",
            s.load.replace('_', " ")
        ));
    }
    parts.join(", ")
}

/// The words of a state figure, which depend on the kind of state drawn.
struct StateTexts {
    /// Title inside the figure.
    title: String,
    /// Heading of the figure in the report.
    heading: String,
    /// Lines under the title.
    subtitle: Vec<String>,
    /// A note drawn in the middle, if any.
    note: Option<String>,
    /// Caption, before the note on the joints.
    caption: String,
}

impl StateTexts {
    /// The words of state `s`; `moving` when the study moves its point load over positions.
    fn of(s: &StateRow, moving: bool) -> Self {
        let mech = s.mechanism.clone().unwrap_or_else(|| "none".into());
        // K and μ as given when they are a study's values (1.35, 0.4), to four decimals when
        // computed (a bifurcation's); t/R_c and the thrust are always computed.
        let values = format!(
            "K = {} (t/R_c = {}), μ = {}, H/W_half = {}",
            compact(s.k),
            short(s.t_over_r),
            compact(s.mu),
            s.thrust_over_half_weight.map_or("—".into(), short)
        );
        match s.state.as_str() {
            "bifurcation" => Self::bifurcation(&mech, values),
            "minimum_thrust" => Self::minimum_thrust(s, &mech, values),
            "largest_margin" => Self::largest_margin(s, values),
            "weakest" | "weakest_of_mechanism" => Self::weakest_case(s, &mech, values, moving),
            "collapse" if s.load_factor.is_some() && s.load != "self_weight" => {
                Self::load_factor_collapse(s, &mech, values)
            }
            "collapse" => Self::collapse(s, &mech, values),
            "limit" => Self::limit(&mech, values),
            "first_complete" => Self::first_complete(&mech, values),
            "no_load_factor" => Self::no_load_factor(s),
            _ => Self::no_equilibrium(s),
        }
    }

    /// The state of largest margin of a scene that stands (general route).
    fn largest_margin(s: &StateRow, values: String) -> Self {
        StateTexts {
            title: format!(
                "Scene K = {}, μ = {}: state of largest margin",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            heading: format!(
                "State of largest margin of scene K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            subtitle: vec![
                values.clone(),
                format!("regime {}", s.regime.clone().unwrap_or_default()),
            ],
            note: None,
            caption: format!(
                "The scene stands ({values}); drawn is its admissible state farthest from every limit condition (the largest common margin of the no-tension and friction conditions of all joints), so its line of thrust lies inside the masonry and no joint is at a limit. This is another kind of state than the minimum-thrust state drawn for a circular arch with radial joints under its own weight: compare forms by their collapse states, not by these scenes."
            ),
        }
    }

    /// The collapse state at λ_max of a stored load_factor case.
    fn weakest_case(s: &StateRow, mech: &str, values: String, moving: bool) -> Self {
        let lambda = s.load_factor.map_or("—".into(), short);
        let refined = s.state == "weakest" && s.load == "point" && moving;
        let which = if s.state == "weakest" {
            if refined {
                "the weakest load position of the study, refined between the grid positions either side of it".to_string()
            } else {
                "the weakest case of the study".to_string()
            }
        } else {
            format!("the weakest case collapsing by a {mech} mechanism")
        };
        let at = load_position(s);
        StateTexts {
            title: format!("Collapse at λ_max: {mech} mechanism"),
            heading: format!(
                "Collapse state of case {} ({which})",
                s.case_id.map_or("—".into(), |c| c.to_string())
            ),
            subtitle: vec![values.clone(), format!("λ_max = {lambda}{at}; {which}")],
            note: None,
            caption: format!(
                "The collapse state of case {} of results.parquet, {which}, at its largest load factor λ_max = {lambda} ({values}{at}): the arch to scale with the load drawn where it acts, the line of thrust, hinges on the intrados or extrados and sliding joints with the sense in which the part nearer the crown moves.{}",
                s.case_id.map_or("—".into(), |c| c.to_string()),
                if refined {
                    " The position and λ_max are those refined between the grid positions either side of the case (the least λ_max over them, to the study's boundary tolerance); the case holds the grid's."
                } else {
                    ""
                }
            ),
        }
    }

    /// The collapse state at λ_max of a scene of a load_factor study.
    fn load_factor_collapse(s: &StateRow, mech: &str, values: String) -> Self {
        let lambda = s.load_factor.map_or("—".into(), short);
        let at = load_position(s);
        StateTexts {
            title: format!(
                "Scene K = {}, μ = {}: collapse at λ_max",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            heading: format!(
                "Collapse state of scene K = {}, μ = {} at λ_max",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            subtitle: vec![
                values.clone(),
                format!("λ_max = {lambda}{at}; {mech} mechanism"),
            ],
            note: None,
            caption: format!(
                "The collapse state of the scene at its largest load factor λ_max = {lambda} ({values}{at}), with the load drawn where it acts."
            ),
        }
    }

    /// A scene of a load_factor study with no finite load factor.
    fn no_load_factor(s: &StateRow) -> Self {
        StateTexts {
            title: format!(
                "Scene K = {}, μ = {}: no finite load factor",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            heading: format!(
                "Scene K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            subtitle: Vec::new(),
            note: Some("no finite collapse load factor at this scene".to_string()),
            caption: format!(
                "The scene K = {}, μ = {} has no finite collapse load factor: it stands under every λ, or under none.",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
        }
    }

    /// The limit state at a bifurcation.
    fn bifurcation(mech: &str, values: String) -> Self {
        StateTexts {
            title: format!("Collapse at the {} bifurcation", mech.replace('/', " / ")),
            heading: format!(
                "Collapse state at the {} bifurcation",
                mech.replace('/', " / ")
            ),
            subtitle: vec![values.clone()],
            note: None,
            caption: format!(
                "The limit state at the bifurcation where the {} mechanisms coexist ({values}), as in the paper's Figs. 6 and 7: the arch to scale, its line of thrust, hinges on the intrados or extrados and sliding joints with the sense in which the part nearer the crown moves.",
                mech.replace('/', " and ")
            ),
        }
    }

    /// The admissible state of least thrust of a scene that stands.
    fn minimum_thrust(s: &StateRow, mech: &str, values: String) -> Self {
        StateTexts {
            title: format!(
                "Minimum-thrust state, K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            heading: format!(
                "Minimum-thrust state of scene K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            subtitle: vec![
                values.clone(),
                format!(
                    "regime {}; limit conditions: {}",
                    s.regime.clone().unwrap_or_default(),
                    mech
                ),
            ],
            note: None,
            caption: format!(
                "The admissible state of least crown thrust of the scene ({values}): the arch to scale with its line of thrust, the joints where it touches a face (hinges) and the joints at the limit of friction (sliding, with the sense of the crown-side part)."
            ),
        }
    }

    /// The limit state of a thickness or friction find solved on its own (a notebook's
    /// `solve`): the arch at K_c or μ_c.
    fn limit(mech: &str, values: String) -> Self {
        StateTexts {
            title: format!("Static limit: {mech} collapse"),
            heading: format!("Static limit state, {mech} collapse"),
            subtitle: vec![values.clone(), format!("{mech} mechanism")],
            note: None,
            caption: format!(
                "The limit state of the find ({values}): the arch to scale at its critical value with its line of thrust, hinges and sliding joints (with the sense of the crown-side part)."
            ),
        }
    }

    /// The first complete solution of a critical find solved on its own, where it comes
    /// before the static limit (the non-associative gap): the state from which the arch can
    /// start to move, with the mechanism that obeys the flow rules there.
    fn first_complete(mech: &str, values: String) -> Self {
        StateTexts {
            title: format!("Collapse: first complete solution, {mech} mechanism"),
            heading: format!("Collapse state (first complete solution), {mech} mechanism"),
            subtitle: vec![
                values.clone(),
                format!("{mech} mechanism obeying the flow rules"),
            ],
            note: None,
            caption: format!(
                "The first complete solution met along the find's path ({values}): an admissible state with a mechanism whose hinges turn about the faces the line of thrust touches and whose sliding joints slip against the full friction force. The arch can start to move here, before the static limit."
            ),
        }
    }

    /// The collapse state at K_c(μ) of a scene that cannot stand.
    fn collapse(s: &StateRow, mech: &str, values: String) -> Self {
        StateTexts {
            title: format!(
                "Scene K = {}, μ = {}: collapse at K_c(μ)",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            heading: format!(
                "Collapse state for scene K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            subtitle: vec![
                values.clone(),
                format!(
                    "the scene itself ({}) cannot stand; {} mechanism",
                    s.regime.clone().unwrap_or_default(),
                    mech
                ),
            ],
            note: None,
            caption: format!(
                "The scene K = {}, μ = {} cannot stand (regime {}); drawn is the collapse state at the same friction and the collapse thickness K_c(μ) ({values}).",
                given(s.scene_k),
                mu_text(s.scene_mu),
                s.regime.clone().unwrap_or_default()
            ),
        }
    }

    /// A scene with no admissible state at its friction for any thickness.
    fn no_equilibrium(s: &StateRow) -> Self {
        StateTexts {
            title: format!(
                "Scene K = {}, μ = {}: no equilibrium",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            heading: format!(
                "Scene K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            subtitle: vec![format!("regime {}", s.regime.clone().unwrap_or_default())],
            note: Some("no admissible state at this friction for any thickness".to_string()),
            caption: format!(
                "The scene K = {}, μ = {} has no admissible state, and none exists at this friction for any thickness.",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
        }
    }
}

/// ", load at …" naming a point load's position, empty for other loads. A position given as
/// x/L is named so: on the springing wedge of a vertical-joint arch its angle is ±α, which
/// names the vertical joint, not the load's point.
fn load_position(s: &StateRow) -> String {
    match (s.at_x, s.at_deg) {
        (Some(x), _) => format!(", load at x/L = {}", compact(x)),
        (None, Some(a)) => format!(", load at {}°", position_deg(a)),
        (None, None) => String::new(),
    }
}
