//! The figures of a load_factor study, from the λ_max and mechanism of every stored case:
//! λ against K for a few μ and against μ for a few K, and, for a point load at several
//! positions, the influence line λ against the load's position (angle and x/L).

use super::regime_map::ArchKey;
use super::{Chart, FigureSpec, LoadCaseFigure};
use crate::plot::lines::{Line, LinePanel, LinePoint, LinesChart};
use crate::report::data::{ArchView, RunData, given_position};
use crate::report::format::{compact, given, position_deg, short};
use crate::store::LoadFactorCase;

/// How the line figures mark the gap.
const BARS: &str = "Green bars, from the collapse up to λ_max";

/// At most this many lines per panel.
const MAX_LINES: usize = 4;

/// Distinct finite-or-infinite values, sorted.
pub(super) fn distinct(vals: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = vals.filter(|x| !x.is_nan()).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// Up to `n` values spread over a sorted list, always with its ends.
pub fn spread(values: &[f64], n: usize) -> Vec<f64> {
    if values.len() <= n {
        return values.to_vec();
    }
    let mut out: Vec<f64> = (0..n)
        .map(|i| values[(i * (values.len() - 1)) / (n - 1).max(1)])
        .collect();
    out.dedup();
    out
}

/// True when the positive values of the lines span more than a factor of 30: drawn on a
/// logarithmic axis, so that the small values are not flattened against zero.
fn wide(lines: &[Line]) -> bool {
    let ys = lines
        .iter()
        .flat_map(|l| &l.points)
        .map(|q| q.y)
        .filter(|y| y.is_finite() && *y > 0.0);
    let (lo, hi) = ys.fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    hi > 30.0 * lo
}

/// The point of a case on a line.
fn point(x: f64, c: &LoadFactorCase) -> LinePoint {
    LinePoint {
        x,
        y: c.load_factor.unwrap_or(f64::NAN),
        mechanism: c.mechanism.clone().unwrap_or_default(),
        collapse: c.collapse_below.unwrap_or(f64::NAN),
    }
}

/// The horizontal position of a point load over the span, x/L: x from the left springing of
/// the extrados to the load's point on the extrados (the extrados end of its joint), L the
/// distance between the extrados springings. Computed from the arch's form.
pub fn x_over_l(arch: &ArchView, k: f64, half_angle_deg: f64, at_deg: f64) -> f64 {
    let e = if arch.shape == "pointed" {
        arch.eccentricity.unwrap_or(0.0)
    } else {
        0.0
    };
    let offset = e * 0.5 * (1.0 + k);
    let reach = if arch.joints == "vertical" { 1.0 } else { k };
    let spring = k * half_angle_deg.to_radians().sin() - offset;
    let x = if at_deg == 0.0 {
        0.0
    } else {
        at_deg.signum() * (reach * at_deg.abs().to_radians().sin() - offset)
    };
    0.5 * (1.0 + x / spring)
}

/// The distinct positions of the point load among `own`, as the manifest gave them (x/L
/// when `by_x`, else degrees).
pub(super) fn positions(own: &[&LoadFactorCase], by_x: bool) -> Vec<f64> {
    distinct(own.iter().filter_map(|c| given_position(c, by_x)))
}

/// ", load at …" naming the position of the point load of `own` as given (x/L or degrees),
/// empty for other loads.
pub(super) fn load_at_text(own: &[&LoadFactorCase], by_x: bool) -> String {
    let Some(c) = own.iter().find(|c| c.at_deg.is_some() || c.at_x.is_some()) else {
        return String::new();
    };
    match (by_x, c.at_x, c.at_deg) {
        (true, Some(x), _) => format!(", load at x/L = {}", given(x)),
        (_, _, Some(a)) => format!(", load at {}°", position_deg(a)),
        _ => String::new(),
    }
}

/// The cases of one load case, and the arch group to draw (the first half-angle and voussoir
/// count of the study: a study with arch axes gets one figure per group).
pub(super) struct Cases<'a> {
    all: Vec<&'a LoadFactorCase>,
}

impl<'a> Cases<'a> {
    pub(super) fn of(data: &'a RunData, lc: &str) -> Self {
        Cases {
            all: data
                .load_factors
                .iter()
                .filter(|c| c.load_case == lc)
                .collect(),
        }
    }

    /// The arch groups (half-angle, voussoirs, eccentricity, joints), in the order of the
    /// arch axes.
    pub(super) fn groups(&self) -> Vec<ArchKey> {
        let mut g: Vec<ArchKey> = Vec::new();
        for c in &self.all {
            if !g.contains(&c.arch()) {
                g.push(c.arch());
            }
        }
        g.sort_by(|a, b| {
            (a.half_angle_deg.total_cmp(&b.half_angle_deg))
                .then((a.eccentricity.unwrap_or(-1.0)).total_cmp(&b.eccentricity.unwrap_or(-1.0)))
                .then((a.joints as u8).cmp(&(b.joints as u8)))
                .then(a.voussoirs.cmp(&b.voussoirs))
        });
        g
    }

    pub(super) fn of_group(&self, g: ArchKey) -> Vec<&'a LoadFactorCase> {
        self.all.iter().copied().filter(|c| c.arch() == g).collect()
    }
}

/// The words naming an arch group when the study has more than one.
pub(super) fn group_text(g: ArchKey, several: bool) -> String {
    if !several {
        return String::new();
    }
    let n = g
        .voussoirs
        .map_or("continuum".to_string(), |n| format!("N = {n}"));
    let form = match g.eccentricity {
        Some(e) => format!(", e = {}", given(e)),
        None => String::new(),
    };
    let joints = if g.joints == crate::model::JointOrientation::Vertical {
        ", vertical joints"
    } else {
        ""
    };
    format!(", α = {}°{form}{joints}, {n}", given(g.half_angle_deg))
}

pub(super) fn group_stem(g: ArchKey, several: bool) -> String {
    if !several {
        return String::new();
    }
    let n = g
        .voussoirs
        .map_or("continuum".to_string(), |n| format!("n{n}"));
    let form = match g.eccentricity {
        Some(e) => format!("-e{}", given(e)),
        None => String::new(),
    };
    let joints = if g.joints == crate::model::JointOrientation::Vertical {
        "-vertical"
    } else {
        ""
    };
    format!("-a{}{form}{joints}-{n}", given(g.half_angle_deg))
}

/// The load-factor figures of a load case.
pub fn figures(data: &RunData, lc: &LoadCaseFigure) -> Vec<FigureSpec> {
    if data.manifest.find_of(lc.name) != "load_factor" {
        return Vec::new();
    }
    let cases = Cases::of(data, lc.name);
    let groups = cases.groups();
    let several = groups.len() > 1;
    let by_x = data.manifest.positions_by_x(lc.name);
    let mut out = Vec::new();
    for g in groups {
        let own = cases.of_group(g);
        let on = group_text(g, several);
        let stem = format!("{}{}", lc.stem_suffix, group_stem(g, several));
        if positions(&own, by_x).len() > 2 {
            out.extend(influence_line(data, lc, &own, (&on, &stem)));
        } else {
            let at = load_at_text(&own, by_x);
            out.extend(lambda_curves(lc, &own, (&on, &stem), &at));
        }
    }
    out
}

/// λ against K for a few μ, and against μ for a few K.
fn lambda_curves(
    lc: &LoadCaseFigure,
    own: &[&LoadFactorCase],
    (on, stem): (&str, &str),
    at: &str,
) -> Option<FigureSpec> {
    // Lines only for values at which some case has a finite λ (an arch that never stands
    // at that μ or K would be an empty line with a label).
    let bounded = || own.iter().filter(|c| c.load_factor.is_some());
    let ks = distinct(bounded().map(|c| c.k));
    let mus = distinct(bounded().map(|c| c.mu));
    let finite_mus: Vec<f64> = mus.iter().copied().filter(|m| m.is_finite()).collect();
    let mut panels = Vec::new();
    if ks.len() > 1 {
        let lines: Vec<Line> = spread(&mus, MAX_LINES)
            .into_iter()
            .map(|mu| Line {
                label: format!("μ = {}", compact(mu)),
                points: own
                    .iter()
                    .filter(|c| c.mu == mu)
                    .map(|c| point(c.k, c))
                    .collect(),
            })
            .collect();
        panels.push(LinePanel {
            title: "λ against K".into(),
            x_desc: "K = R/r".into(),
            y_desc: "λ_max (multiples of the weight)".into(),
            log_y: wide(&lines),
            marks: Vec::new(),
            lines,
        });
    }
    if finite_mus.len() > 1 {
        let lines: Vec<Line> = spread(&ks, MAX_LINES)
            .into_iter()
            .map(|k| Line {
                label: format!("K = {}", compact(k)),
                points: own
                    .iter()
                    .filter(|c| c.k == k && c.mu.is_finite())
                    .map(|c| point(c.mu, c))
                    .collect(),
            })
            .collect();
        panels.push(LinePanel {
            title: "λ against μ".into(),
            x_desc: "friction coefficient μ".into(),
            y_desc: "λ_max (multiples of the weight)".into(),
            log_y: wide(&lines),
            marks: Vec::new(),
            lines,
        });
    }
    if panels.is_empty() {
        return None;
    }
    Some(FigureSpec {
        stem: format!("load-factor{stem}"),
        title: format!("Collapse load factor λ{}{on}{at}", lc.title_suffix),
        caption: format!(
            "The largest load factor λ of the live load at which the arch still stands (λ_max, from results.parquet), {}. Each point is one case, coloured by its collapse mechanism at λ_max; a break in a line is a case where λ is unbounded or the arch does not stand under its own weight. λ_max is the static limit; where a complete solution comes first (key results), the arch can start to move below it.{}",
            match (ks.len() > 1, finite_mus.len() > 1) {
                (true, true) => format!(
                    "against the thickness K for up to {MAX_LINES} values of μ (left) and against the friction coefficient for up to {MAX_LINES} values of K (right; μ = ∞ is the left panel's line of that name)"
                ),
                (true, false) => format!(
                    "against the thickness K for up to {MAX_LINES} values of μ (the study has λ at fewer than two finite μ, so no panel against μ)"
                ),
                _ => format!(
                    "against the friction coefficient for up to {MAX_LINES} values of K (the study has λ at a single K, so no panel against K)"
                ),
            },
            gap_sentence(own, BARS)
        ),
        chart: Chart::Lines(LinesChart {
            title: format!("Collapse load factor λ{on}{at}"),
            panels,
        }),
    })
}

/// The drawn state of the weakest case of a moving point load on the arch of `own`, its
/// position refined between grid positions (with arch axes the weakest case may lie on
/// another arch's figure).
fn refined_weakest<'a>(
    data: &'a RunData,
    lc: &str,
    own: &[&LoadFactorCase],
) -> Option<&'a crate::store::StateRow> {
    let arch = own.first().map(|c| c.arch())?;
    data.states.iter().find(|s| {
        s.load_case == lc
            && s.state == "weakest"
            && s.source == "case"
            && s.load == "point"
            && arch.half_angle_deg == s.half_angle_deg
            && arch.voussoirs == s.voussoirs
            && arch.joints.as_str() == s.joint_orientation
            && arch.eccentricity.unwrap_or(0.0) == s.eccentricity
    })
}

/// The refined weakest point of an influence line, (position, λ_max), against the angle or
/// x/L; empty without one.
fn refined_mark(
    data: &RunData,
    refined: Option<&crate::store::StateRow>,
    as_xl: bool,
) -> Vec<(f64, f64)> {
    refined
        .and_then(|s| {
            let (lambda, at) = (s.load_factor?, s.at_deg?);
            let x = if as_xl {
                s.at_x.unwrap_or_else(|| {
                    let e = (s.shape == "pointed").then_some(s.eccentricity);
                    let arch = data.manifest.arch.with_form(e, &s.joint_orientation);
                    x_over_l(&arch, s.k, s.half_angle_deg, at)
                })
            } else {
                at
            };
            Some(vec![(x, lambda)])
        })
        .unwrap_or_default()
}

/// The refined weakest position in words, for the influence line's caption.
fn refined_sentence(refined: Option<&crate::store::StateRow>) -> String {
    let Some((s, lambda, at)) = refined.and_then(|s| Some((s, s.load_factor?, s.at_deg?))) else {
        return String::new();
    };
    let at_x = s.at_x.map_or(String::new(), |x| format!(", x/L = {x:.6}"));
    format!(
        " The open diamond is the least λ_max of the weakest line (K = {}, μ = {}) refined between the grid positions either side of its weakest one: λ_max = {} with the load at {at:.4}°{at_x} (states.parquet).",
        compact(s.k),
        compact(s.mu),
        short(lambda),
    )
}

/// The cases with a non-associative gap in words, after `marks` (how the figure shows them);
/// empty when none has one.
pub(super) fn gap_sentence(own: &[&LoadFactorCase], marks: &str) -> String {
    let gaps: Vec<(&LoadFactorCase, f64)> = (own.iter())
        .filter_map(|c| Some((*c, c.collapse_below?)))
        .collect();
    let widest = gaps
        .iter()
        .filter_map(|(c, v)| Some((*c, c.load_factor? - v)))
        .max_by(|a, b| a.1.total_cmp(&b.1));
    let Some((c, w)) = widest else {
        return String::new();
    };
    let at = c
        .at_deg
        .map_or(String::new(), |a| format!(", load at {}°", position_deg(a)));
    format!(
        " {marks}: the non-associative gap, where the collapse (the first complete solution, \
         from which a mechanism obeying the flow rules can start) comes before λ_max, in {} of \
         the {} cases; the widest is {w:.4} (λ = {:.4} against λ_max = {:.4}) at K = {}, μ = {}{at}. \
         Inside the gap the outcome depends on contact stiffness and initial stress.",
        gaps.len(),
        own.len(),
        c.load_factor.unwrap_or(f64::NAN) - w,
        c.load_factor.unwrap_or(f64::NAN),
        compact(c.k),
        compact(c.mu),
    )
}

/// " spread over w of the span …" for a patch load case, empty for a concentrated load.
fn spread_phrase(data: &RunData, lc: &str) -> String {
    data.manifest
        .load_cases
        .iter()
        .find(|l| l.name == lc)
        .and_then(|l| l.width)
        .filter(|&w| w > 0.0)
        .map_or(String::new(), |w| {
            format!(
                ", spread uniformly over {} of the extrados span (measured horizontally) centred on its position",
                given(w)
            )
        })
}

/// The influence line: λ against the position of the point load, for a few (K, μ).
fn influence_line(
    data: &RunData,
    lc: &LoadCaseFigure,
    own: &[&LoadFactorCase],
    (on, stem): (&str, &str),
) -> Option<FigureSpec> {
    let mut combos: Vec<(f64, f64)> = own
        .iter()
        .filter(|c| c.load_factor.is_some())
        .map(|c| (c.k, c.mu))
        .collect();
    combos.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    combos.dedup();
    let idx: Vec<f64> = (0..combos.len()).map(|i| i as f64).collect();
    let mut chosen: Vec<(f64, f64)> = spread(&idx, MAX_LINES)
        .into_iter()
        .map(|i| combos[i as usize])
        .collect();
    // The weakest position refined between grid positions (the drawn state of the weakest
    // case), on the line of its (K, μ), which is always drawn.
    let refined = refined_weakest(data, lc.name, own);
    if let Some(s) = refined
        && !chosen.contains(&(s.k, s.mu))
        && combos.contains(&(s.k, s.mu))
    {
        chosen.push((s.k, s.mu));
        chosen.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    }
    let mark = |as_xl: bool| refined_mark(data, refined, as_xl);
    let line = |(k, mu): (f64, f64), as_xl: bool| {
        let mut pts: Vec<LinePoint> = own
            .iter()
            .filter(|c| c.k == k && c.mu == mu)
            .filter_map(|c| {
                let at = c.at_deg?;
                // The stored x/L is exact on every form (keystones, springing wedges);
                // runs written before it was stored get it from the angle.
                let x = if as_xl {
                    c.at_x.unwrap_or_else(|| {
                        let arch =
                            (data.manifest.arch).with_form(c.eccentricity, c.joints.as_str());
                        x_over_l(&arch, c.k, c.half_angle_deg, at)
                    })
                } else {
                    at
                };
                Some(point(x, c))
            })
            .collect();
        pts.sort_by(|a, b| a.x.total_cmp(&b.x));
        Line {
            label: format!("K = {}, μ = {}", compact(k), compact(mu)),
            points: pts,
        }
    };
    let panel = |as_xl: bool| LinePanel {
        title: if as_xl {
            "against x/L along the span".into()
        } else {
            "against the angle from the crown".into()
        },
        x_desc: if as_xl {
            "x/L of the load (extrados, from the left springing)".into()
        } else {
            "load position θ from the crown, degrees".into()
        },
        y_desc: "λ_max (multiples of the weight)".into(),
        log_y: wide(&chosen.iter().map(|&c| line(c, as_xl)).collect::<Vec<_>>()),
        marks: mark(as_xl),
        lines: chosen.iter().map(|&c| line(c, as_xl)).collect(),
    };
    Some(FigureSpec {
        stem: format!("influence-line{stem}"),
        title: format!("Influence line of the point load{}{on}", lc.title_suffix),
        caption: format!(
            "The collapse load factor λ_max of a point load λ·W_total on the extrados{} (results.parquet) against its position: left, the angle θ of its joint from the crown (negative to the left); right, the horizontal position x/L of the load's point from the left springing of the extrados over the distance between the extrados springings. One line per (K, μ), for up to four of the study's (and the line of the weakest case); each point coloured by the collapse mechanism at λ_max; a break in a line is a position where λ is unbounded or no state stands.{}{}",
            spread_phrase(data, lc.name),
            refined_sentence(refined),
            gap_sentence(own, BARS)
        ),
        chart: Chart::Lines(LinesChart {
            title: format!("Influence line of the point load{on}"),
            panels: vec![panel(false), panel(true)],
        }),
    })
}
