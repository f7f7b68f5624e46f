//! The collapse mechanisms at a bifurcation, side by side.

use super::{Chart, FigureSpec, safe};
use crate::plot::mechanisms::{MechanismFigure, MechanismPanels};
use crate::report::data::RunData;
use crate::report::format::short;
use crate::store::StateRow;

/// File stem of the mechanisms figure of a bifurcation state.
pub fn mechanisms_stem(state_id: &str) -> String {
    format!("mechanisms-{}", safe(state_id))
}

/// Text of a flow rule column value.
pub fn flow_rule_text(rule: &str) -> &str {
    match rule {
        "non_associative" => "non-associative (pure sliding)",
        "associative" => "associative (dilatancy tan φ)",
        other => other,
    }
}

/// The mechanisms figure of a bifurcation state, when its mechanisms were stored.
pub fn figure(data: &RunData, s: &StateRow) -> Option<FigureSpec> {
    let rows: Vec<_> = data
        .mechanisms
        .iter()
        .filter(|m| m.state_id == s.state_id)
        .collect();
    let panels: Vec<MechanismFigure> = rows
        .iter()
        .filter_map(|m| {
            let drawing = serde_json::from_str(&m.drawing_json).ok()?;
            Some(MechanismFigure {
                title: format!("{} mechanism", m.mechanism),
                subtitle: format!(
                    "{}; dL(a) = {}",
                    flow_rule_text(&m.flow_rule),
                    short(m.work_loads)
                ),
                drawing,
                window: None,
            })
        })
        .collect();
    if panels.is_empty() {
        return None;
    }
    let mech = s.mechanism.clone().unwrap_or_default().replace('/', " / ");
    let arch = super::state::arch_text(s, super::arch_axis::axes(data));
    let on = if arch.is_empty() {
        String::new()
    } else {
        format!(" ({arch})")
    };
    if s.source == "case" {
        return Some(FigureSpec {
            stem: mechanisms_stem(&s.state_id),
            title: format!(
                "Collapse mechanism of case {}{on}",
                s.case_id.map_or("—".into(), |c| c.to_string())
            ),
            caption: format!(
                "The {mech} collapse mechanism of the state at λ_max (K = {}, μ = {}{on}), from the joints at the limit there: the arch before the virtual displacement (dashed), fixed parts (grey), the displaced blocks (blue; largest displacement 0.08 r), hinges (red dots) and sliding joints (an orange dot at the middle of the joint, with an orange arrow beside it on the crown side for the sense in which the crown-side part moves), under the paper's rule (pure sliding, no dilatancy).",
                short(s.k),
                short(s.mu)
            ),
            chart: Chart::Mechanisms(MechanismPanels { panels }),
        });
    }
    Some(FigureSpec {
        stem: mechanisms_stem(&s.state_id),
        title: format!("Collapse mechanisms at the {mech} bifurcation{on}"),
        caption: format!(
            "The mechanisms admissible at the {mech} bifurcation (K = {}, μ = {}{on}): the arch before the virtual displacement (dashed), fixed parts (grey), the displaced blocks (blue; largest displacement 0.08 r), hinges (red dots; hollow where the joint stays closed in that mechanism) and the sliding joints of the limit state (an orange dot at the middle of the joint, with an orange arrow beside it on the crown side for the sense in which the crown-side part moves; a dot without an arrow is a joint at the Coulomb limit that does not slip in that mechanism). Non-associative panels use the paper's rule (pure sliding, no dilatancy); the associative panels use normality to the Coulomb cone, whose slip opens the joint by tan φ times the slip.",
            short(s.k),
            short(s.mu)
        ),
        chart: Chart::Mechanisms(MechanismPanels { panels }),
    })
}
