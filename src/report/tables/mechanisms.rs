//! The collapse mechanisms at each bifurcation: kind, flow rule, virtual works and
//! dilatancies.

use super::figures::FigureView;
use crate::report::charts;
use crate::report::data::RunData;
use crate::report::format;
use serde::Serialize;

/// One mechanism at a bifurcation, as a table row.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct MechanismTableRow {
    /// μ of the bifurcation.
    pub mu: String,
    /// K of the bifurcation.
    pub k: String,
    /// Kind of the mechanism.
    pub mechanism: String,
    /// Flow rule at the sliding joints.
    pub flow_rule: String,
    /// dL^(a).
    pub work_loads: String,
    /// dL^(r,n).
    pub work_normal: String,
    /// dL^(r,t).
    pub work_friction: String,
    /// Relative residual of the work equation.
    pub work_residual: String,
    /// Dilatancy at each sliding joint, as `θ: value`.
    pub dilatancy: String,
}

/// The mechanisms at one bifurcation.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct MechanismSection {
    /// Heading.
    pub title: String,
    /// `Figure N`, or empty when the figure is missing.
    pub figure: String,
    /// Anchor of the figure.
    pub anchor: String,
    /// One row per mechanism and flow rule.
    pub rows: Vec<MechanismTableRow>,
}

/// Works, dilatancies and residuals below this are rounding: shown as 0 (or `< 1e-9`), so
/// that the report does not depend on the last bits of the platform's arithmetic.
const WORK_ZERO: f64 = 1e-9;

fn work_text(v: f64) -> String {
    if v.abs() < WORK_ZERO {
        "0".into()
    } else {
        // Six decimals; a value that rounds to zero is 0, never −0.000000.
        crate::report::format::num(Some(v), 6)
    }
}

/// The mechanisms of each bifurcation state, with the number of its figure.
pub fn mechanism_sections(data: &RunData, figures: &[FigureView]) -> Vec<MechanismSection> {
    let mut out: Vec<MechanismSection> = Vec::new();
    for s in data.states.iter().filter(|s| s.source == "bifurcation") {
        let rows: Vec<MechanismTableRow> = data
            .mechanisms
            .iter()
            .filter(|m| m.state_id == s.state_id)
            .map(|m| MechanismTableRow {
                mu: format::value(m.mu),
                k: format::value(m.k),
                mechanism: m.mechanism.clone(),
                flow_rule: charts::flow_rule_text(&m.flow_rule).to_string(),
                work_loads: work_text(m.work_loads),
                work_normal: work_text(m.work_normal),
                work_friction: work_text(m.work_friction),
                work_residual: if m.work_residual < WORK_ZERO {
                    "< 1e-9".into()
                } else {
                    format!("{:.1e}", m.work_residual)
                },
                dilatancy: if m.sliding_angles_deg.is_empty() {
                    "no sliding joint".into()
                } else {
                    m.sliding_angles_deg
                        .iter()
                        .zip(&m.dilatancy)
                        .map(|(a, d)| format!("{a:.2}°: {}", work_text(*d)))
                        .collect::<Vec<_>>()
                        .join("; ")
                },
            })
            .collect();
        if rows.is_empty() {
            continue;
        }
        let stem = charts::mechanisms_stem(&s.state_id);
        let fig = figures.iter().find(|f| f.anchor == format!("fig-{stem}"));
        out.push(MechanismSection {
            title: format!(
                "{} bifurcation, μ = {}, K = {}",
                s.mechanism.clone().unwrap_or_default().replace('/', " / "),
                format::short(s.mu),
                format::short(s.k)
            ),
            figure: fig.map_or(String::new(), |f| format!("Figure {}", f.number)),
            anchor: format!("fig-{stem}"),
            rows,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::work_text;

    #[test]
    fn a_work_that_rounds_to_zero_is_printed_without_a_sign() {
        assert_eq!(work_text(-4e-10), "0");
        assert_eq!(work_text(-4e-7), "0.000000");
        assert_eq!(work_text(-0.25), "-0.250000");
        assert_eq!(work_text(0.125), "0.125000");
    }
}
