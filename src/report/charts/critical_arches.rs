//! The critical values of a thickness or friction study with a half-angle or voussoir axis,
//! one line per arch on one chart: K_c(μ) of a thickness study, μ_c(K) of a friction study.
//! The continuum, when the study has it, is one of the lines, the reference the voussoir
//! counts tend to.

use super::arch_axis::arch_label;
use super::regime_map::ArchKey;
use super::{Chart, FigureSpec, LoadCaseFigure, single_model};
use crate::plot::lines::{Line, LinePanel, LinePoint, LinesChart};
use crate::report::data::RunData;

/// The critical curve of every arch of a load case, when its find is `thickness` or
/// `friction` and the study has an arch axis.
pub fn figure(data: &RunData, lc: &LoadCaseFigure) -> Option<FigureSpec> {
    let find = data.manifest.find_of(lc.name);
    let thickness = match find {
        "thickness" => true,
        "friction" => false,
        _ => return None,
    };
    if single_model(data) || data.result_arches.len() != data.results.len() {
        return None;
    }
    let mut arches: Vec<(ArchKey, Vec<LinePoint>)> = Vec::new();
    for (r, a) in data.results.iter().zip(&data.result_arches) {
        if &*r.load_case != lc.name {
            continue;
        }
        let (x, y) = if thickness {
            (r.mu, r.k_crit)
        } else {
            (r.k, r.mu_crit)
        };
        let Some(x) = x.filter(|x| x.is_finite()) else {
            continue;
        };
        let key = *a;
        let point = LinePoint {
            x,
            y: y.unwrap_or(f64::NAN),
            mechanism: String::new(),
            collapse: (r.collapse_value)
                .filter(|_| r.gap.as_deref() == Some("gap"))
                .unwrap_or(f64::NAN),
        };
        match arches.iter_mut().find(|(k, _)| *k == key) {
            Some((_, pts)) => pts.push(point),
            None => arches.push((key, vec![point])),
        }
    }
    let lines: Vec<Line> = arches
        .into_iter()
        .filter(|(_, pts)| pts.iter().filter(|p| p.y.is_finite()).count() >= 2)
        .map(|(key, mut points)| {
            points.sort_by(|a, b| a.x.total_cmp(&b.x));
            Line {
                label: arch_label(data, key),
                points,
            }
        })
        .collect();
    if lines.is_empty() {
        return None;
    }
    let on = &lc.title_suffix;
    let (title, x_desc, y_desc, what) = if thickness {
        (
            format!("Collapse thickness K_c(μ) of every arch{on}"),
            "friction coefficient μ",
            "collapse thickness ratio K_c = R/r",
            "the collapse thickness K_c (the smallest K at which the arch stands) against the friction coefficient μ",
        )
    } else {
        (
            format!("Critical friction μ_c(K) of every arch{on}"),
            "thickness ratio K = R/r",
            "critical friction coefficient μ_c",
            "the critical friction μ_c (the smallest μ at which the arch stands) against the thickness K",
        )
    };
    let gaps = (lines.iter())
        .flat_map(|l| &l.points)
        .filter(|p| p.collapse.is_finite())
        .count();
    let gap_note = if gaps > 0 {
        format!(
            " Green bars, in {gaps} case(s): the non-associative gap, from the collapse (the first complete solution along decreasing {}, crossbar) to the static limit; inside it the outcome depends on contact stiffness and initial stress.",
            if thickness { "K" } else { "μ" }
        )
    } else {
        String::new()
    };
    Some(FigureSpec {
        stem: format!("critical-arches{}", lc.stem_suffix),
        title: title.clone(),
        caption: format!(
            "For every arch of the study (results.parquet), {what}: one line per arch, named at its end, the continuum among them when the study has it. A break in a line is a case with no critical value (the arch never or always stands there).{gap_note}"
        ),
        chart: Chart::Lines(LinesChart {
            title,
            panels: vec![LinePanel {
                title: String::new(),
                x_desc: x_desc.into(),
                y_desc: y_desc.into(),
                lines,
                log_y: false,
                marks: Vec::new(),
            }],
        }),
    })
}
