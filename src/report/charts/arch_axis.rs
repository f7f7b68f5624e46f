//! State studies with a `half_angle_deg` or `voussoirs` axis: the regime map of every arch
//! as small multiples sharing axes and colours, the collapse curves K_c(μ) of every arch on
//! one chart, and the bifurcation values against the axis.

use super::regime_map::{ArchKey, regime_map_of};
use super::{Chart, FigureSpec, LoadCaseFigure, single_model};
use crate::plot::lines::{Line, LinePanel, LinePoint, LinesChart};
use crate::plot::regime_map::{RegimeMap, RegimeMapPanels};
use crate::report::data::RunData;

/// The arches of a load case's state cases, by α, e (circular first), joints (radial first)
/// then N (the continuum last).
pub fn arches_of(data: &RunData, lc: &str) -> Vec<ArchKey> {
    let mut v: Vec<ArchKey> = data
        .results
        .iter()
        .zip(&data.result_arches)
        .filter(|(r, _)| &*r.load_case == lc && &*r.find == "state")
        .map(|(_, a)| *a)
        .collect();
    v.sort_by(|a, b| {
        (a.half_angle_deg.total_cmp(&b.half_angle_deg))
            .then((a.eccentricity.unwrap_or(-1.0)).total_cmp(&b.eccentricity.unwrap_or(-1.0)))
            .then((a.joints as u8).cmp(&(b.joints as u8)))
            .then((a.voussoirs.unwrap_or(u32::MAX)).cmp(&b.voussoirs.unwrap_or(u32::MAX)))
    });
    v.dedup();
    v
}

/// Which arch axes a study has (none: a single arch, as `solve` draws it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ArchAxes {
    /// A `half_angle_deg` axis.
    pub alpha: bool,
    /// An `eccentricity` axis.
    pub e: bool,
    /// A `joints` axis.
    pub joints: bool,
    /// A `voussoirs` axis.
    pub n: bool,
}

/// Which arch axes the study has.
pub fn axes(data: &RunData) -> ArchAxes {
    let has = |n: &str| data.manifest.grid.iter().any(|a| a.name == n);
    ArchAxes {
        alpha: has("half_angle_deg"),
        e: has("eccentricity"),
        joints: has("joints"),
        n: has("voussoirs"),
    }
}

/// An angle in degrees to at most four decimals, without trailing zeros (α = 60°, not
/// 59.99999999999999° as stored after a round trip through radians).
pub fn degrees(v: f64) -> String {
    let s = format!("{v:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The arch's values on the study's arch axes, e.g. `α = 60°`, `e = 0.2`, `vertical joints`,
/// `N = 9`, `continuum`.
pub fn arch_label(data: &RunData, a: ArchKey) -> String {
    let by = axes(data);
    let mut parts = Vec::new();
    if by.alpha {
        parts.push(format!("α = {}°", degrees(a.half_angle_deg)));
    }
    if by.e {
        parts.push(format!(
            "e = {}",
            crate::report::format::given(a.eccentricity.unwrap_or(0.0))
        ));
    }
    if by.joints {
        parts.push(format!("{} joints", a.joints.as_str()));
    }
    if by.n {
        parts.push(
            a.voussoirs
                .map_or("continuum".to_string(), |n| format!("N = {n}")),
        );
    }
    parts.join(", ")
}

/// The regime maps, the collapse curves and the bifurcations against the axis of a state
/// load case with an arch axis.
pub fn figures(data: &RunData, lc: &LoadCaseFigure) -> Vec<FigureSpec> {
    if data.manifest.find_of(lc.name) != "state" || single_model(data) {
        return Vec::new();
    }
    let on = &lc.title_suffix;
    let maps: Vec<(ArchKey, RegimeMap)> = arches_of(data, lc.name)
        .into_iter()
        .filter_map(|a| regime_map_of(data, lc.name, arch_label(data, a), Some(a)).map(|m| (a, m)))
        .collect();
    if maps.is_empty() {
        return Vec::new();
    }
    let axis_name = axis_words(data);
    let mut caption = format!(
        "The regime map of every {axis_name} of the study, one panel each, named above it, over the same μ and K axes and in the same colours (read each panel as the regime map of a single arch: regions from results.parquet and the located boundaries of that arch in boundaries.parquet, its collapse curve coloured by mechanism, its bifurcations marked with their values, or with their number where the values find no free place)."
    );
    caption.push_str(&numbered_bifurcations(&maps));
    let mut out = vec![FigureSpec {
        stem: format!("regime-maps{}", lc.stem_suffix),
        title: format!("Regime maps by {axis_name}{on}"),
        caption,
        chart: Chart::RegimeMapPanels(RegimeMapPanels {
            maps: maps.iter().map(|(_, m)| m.clone()).collect(),
        }),
    }];
    if maps.len() > 1 {
        out.push(collapse_overlay(&maps, lc, &axis_name));
    }
    out.extend(bifurcations_against_axis(data, &maps, lc));
    out
}

/// The bifurcations of every panel with their numbers, for the caption: a panel too small
/// for a bifurcation's values shows its number only.
fn numbered_bifurcations(maps: &[(ArchKey, RegimeMap)]) -> String {
    let panels: Vec<String> = maps
        .iter()
        .filter(|(_, m)| !m.bifurcations.is_empty())
        .map(|(_, m)| {
            let listed: Vec<String> = (m.bifurcations.iter())
                .map(|b| format!("{}, {}: {}", b.compact, b.lines[0], b.lines[1..].join(", ")))
                .collect();
            format!("{}: {}", m.title, listed.join("; "))
        })
        .collect();
    if panels.is_empty() {
        String::new()
    } else {
        format!(" Bifurcations by panel: {}.", panels.join(". "))
    }
}

/// `half-angle`, `voussoir count` or `arch`.
fn axis_words(data: &RunData) -> String {
    let by = axes(data);
    match (by.alpha, by.e, by.joints, by.n) {
        (true, false, false, false) => "half-angle".into(),
        (false, true, false, false) => "eccentricity".into(),
        (false, false, true, false) => "joint orientation".into(),
        (false, false, false, true) => "voussoir count".into(),
        _ => "arch".into(),
    }
}

/// The collapse curve of every arch on one chart: K_c against μ, one line per arch.
fn collapse_overlay(
    maps: &[(ArchKey, RegimeMap)],
    lc: &LoadCaseFigure,
    axis_name: &str,
) -> FigureSpec {
    let lines = maps
        .iter()
        .map(|(_, m)| {
            let mut points: Vec<LinePoint> = Vec::new();
            for seg in &m.collapse {
                for &(mu, k) in &seg.points {
                    if points.last().is_some_and(|p| p.x == mu && p.y == k) {
                        continue;
                    }
                    points.push(LinePoint {
                        x: mu,
                        y: k,
                        mechanism: seg.mechanism.clone(),
                        collapse: f64::NAN,
                    });
                }
            }
            Line {
                label: m.title.clone(),
                points,
            }
        })
        .collect();
    let on = &lc.title_suffix;
    FigureSpec {
        stem: format!("collapse-curves{}", lc.stem_suffix),
        title: format!("Collapse curves by {axis_name}{on}"),
        caption: format!(
            "The collapse curve K_c(μ) of every {axis_name} (the located collapse points of boundaries.parquet joined in order along the curve), one grey line each, named in the legend and, where every end has room, labelled at its end; each point is coloured by its collapse mechanism (rotational, mixed, sliding). Below its curve an arch does not stand."
        ),
        chart: Chart::Lines(LinesChart {
            title: format!("Collapse thickness K_c against μ{on}"),
            panels: vec![LinePanel {
                title: String::new(),
                x_desc: "friction coefficient μ".into(),
                y_desc: "collapse thickness ratio K_c = R/r".into(),
                lines,
                log_y: false,
                marks: Vec::new(),
            }],
        }),
    }
}

/// The bifurcation points of every arch against the axis: μ (left) and K (right), one
/// line per pair of mechanisms. None unless the study has one arch axis with at least two
/// numeric values with bifurcations.
fn bifurcations_against_axis(
    data: &RunData,
    maps: &[(ArchKey, RegimeMap)],
    lc: &LoadCaseFigure,
) -> Option<FigureSpec> {
    let by = axes(data);
    if usize::from(by.alpha) + usize::from(by.e) + usize::from(by.n) != 1 || by.joints {
        // Two arch axes (or joint planes, which have no scale): one line per pair of
        // mechanisms would mix the arches; the table under "Values" lists them by arch.
        return None;
    }
    let (by_alpha, by_e) = (by.alpha, by.e);
    let x_of = |a: ArchKey| {
        if by_alpha {
            Some(a.half_angle_deg)
        } else if by_e {
            Some(a.eccentricity.unwrap_or(0.0))
        } else {
            a.voussoirs.map(f64::from)
        }
    };
    let mut kinds: Vec<String> = maps
        .iter()
        .flat_map(|(_, m)| {
            m.bifurcations
                .iter()
                .filter_map(|b| b.lines.first().cloned())
        })
        .collect();
    kinds.sort();
    kinds.dedup();
    let panel = |value: &dyn Fn(f64, f64) -> f64, y_desc: &str| LinePanel {
        title: String::new(),
        x_desc: if by_alpha {
            "half-angle α (°)".into()
        } else if by_e {
            "eccentricity e".into()
        } else {
            "voussoirs N".into()
        },
        y_desc: y_desc.into(),
        lines: kinds
            .iter()
            .map(|kind| Line {
                label: kind.clone(),
                points: maps
                    .iter()
                    .filter_map(|(a, m)| {
                        let x = x_of(*a)?;
                        let b = m
                            .bifurcations
                            .iter()
                            .find(|b| b.lines.first() == Some(kind))?;
                        // Coloured by the mechanism on its lower-μ side, the one that takes
                        // over below the bifurcation.
                        let below = kind.split(" / ").next().unwrap_or_default();
                        Some(LinePoint {
                            x,
                            y: value(b.mu, b.k),
                            mechanism: below.to_string(),
                            collapse: f64::NAN,
                        })
                    })
                    .collect(),
            })
            .collect(),
        log_y: false,
        marks: Vec::new(),
    };
    let left = panel(&|mu, _| mu, "friction coefficient μ at the bifurcation");
    let right = panel(&|_, k| k, "thickness ratio K at the bifurcation");
    if left.lines.iter().all(|l| l.points.len() < 2) {
        return None;
    }
    let on = &lc.title_suffix;
    let axis = if by_alpha {
        "half-angle α"
    } else if by_e {
        "eccentricity e"
    } else {
        "voussoir count N"
    };
    Some(FigureSpec {
        stem: format!("bifurcations-by-arch{}", lc.stem_suffix),
        title: format!("Bifurcations against the {axis}{on}"),
        caption: format!(
            "Where two collapse mechanisms meet on the collapse curve of each arch (bifurcations.parquet), against the {axis}: the friction coefficient μ (left) and the thickness ratio K (right) of each bifurcation, one line per pair of mechanisms, each point coloured by the mechanism on its lower-μ side (the one that takes over below it: mixed below the rotational/mixed bifurcation, sliding below the mixed/sliding one)."
        ),
        chart: Chart::Lines(LinesChart {
            title: format!("Bifurcations against the {axis}{on}"),
            panels: vec![left, right],
        }),
    })
}
