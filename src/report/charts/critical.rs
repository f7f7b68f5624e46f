//! Figure 4: the critical curves K_c(μ) and μ_c(K) with the bifurcations and, for the
//! paper's case, the paper's printed values.

use super::{Chart, FigureSpec, LoadCaseFigure, single_model};
use crate::figdata;
use crate::plot::critical::{CriticalChart, CriticalPanel, PointMark};
use crate::report::data::RunData;
use crate::report::paper;

const CRITICAL_CAPTION: &str = "The collapse thickness K_c(μ) (the smallest K at which the arch stands at friction μ) and the critical friction μ_c(K) (the smallest μ at which an arch of thickness K stands). Dots: bifurcations located in this run; open diamonds: the values printed in the paper, when the study is the paper's case.";

/// Added to the caption of a thickness study's figure, whose panel (a) shades the windows.
const WINDOWS_CAPTION: &str = "Shaded: every interval of K in which the arch stands at that μ (the windows of the thickness find, scanned to the larger of K = 3 and 1 + 2 (K_c − 1)); a gap above K_c is a range of thicker arches that fail again.";

/// The critical-curves figure of a load case, when it has a critical curve.
pub fn figure(data: &RunData, lc: &LoadCaseFigure) -> Option<FigureSpec> {
    let on = &lc.title_suffix;
    let c = critical(data, lc.name, on)?;
    let mut caption = CRITICAL_CAPTION.to_string();
    if c.panels.iter().any(|p| !p.windows.is_empty()) {
        caption.push(' ');
        caption.push_str(WINDOWS_CAPTION);
    }
    if let Some(note) = gap_note(data, lc.name) {
        caption.push(' ');
        caption.push_str(&note);
    }
    if let Some(note) = c.panels.first().and_then(off_the_top) {
        caption.push(' ');
        caption.push_str(&note);
    }
    Some(FigureSpec {
        stem: format!("critical-curves{}", lc.stem_suffix),
        title: format!("Critical curves{on}"),
        caption,
        chart: Chart::Critical(c),
    })
}

/// Where panel (a)'s K_c(μ) leaves the top of its axis (the study's largest K), in words.
fn off_the_top(p: &CriticalPanel) -> Option<String> {
    let top = p.y_max?;
    let beyond: Vec<f64> = (p.curve.iter())
        .filter(|q| q.1.is_finite() && q.1 > top)
        .map(|q| q.0)
        .collect();
    let (lo, hi) = (beyond.first()?, beyond.last()?);
    let highest = (p.curve.iter())
        .map(|q| q.1)
        .filter(|y| y.is_finite())
        .fold(f64::NEG_INFINITY, f64::max);
    Some(format!(
        "Panel (a) stops at the study's largest K, {top:.3}: K_c(μ) rises beyond it for μ from \
         {lo:.3} to {hi:.3}, up to {highest:.3}."
    ))
}

fn critical(data: &RunData, lc: &str, on: &str) -> Option<CriticalChart> {
    let marks = Marks {
        bifurcations: data
            .bifurcations_of(lc)
            .iter()
            .map(|b| (b.mu, b.k))
            .collect(),
        paper: data.manifest.is_paper_case(),
    };
    let (a, b) = curves(data, lc);
    let mut panels = Vec::new();
    if let Some(a) = a {
        let mut panel = marks.panel(Axes::COLLAPSE_THICKNESS, a);
        if data.manifest.find_of(lc) == "thickness" {
            panel.windows = windows(data, lc);
            panel.collapse = collapse(data, lc);
        }
        // A state study covers a range of K: K_c(μ) above it is off the map too.
        if data.manifest.find_of(lc) == "state" {
            panel.y_max = data.totals.k_max.get(lc).copied();
            panel.collapse = data.curve(&figdata::critical_figure(lc), figdata::K_COLLAPSE_OF_MU);
        }
        panels.push(panel);
    }
    if let Some(b) = b {
        let mut panel = marks.panel(Axes::CRITICAL_FRICTION, b);
        match data.manifest.find_of(lc) {
            "friction" => panel.collapse = collapse(data, lc),
            "state" => {
                panel.collapse =
                    data.curve(&figdata::critical_figure(lc), figdata::MU_COLLAPSE_OF_K);
            }
            _ => {}
        }
        panels.push(panel);
    }
    if panels.is_empty() {
        return None;
    }
    Some(CriticalChart {
        title: format!("Critical curves{on}"),
        panels,
    })
}

/// A curve (x, y); NaN breaks it.
type Curve = Vec<(f64, f64)>;

/// The curves K_c(μ) and μ_c(K) of a load case, when its find gives them: a state study's
/// stored critical curves, or the critical values of a thickness or friction study over one
/// model (at least two points).
fn curves(data: &RunData, lc: &str) -> (Option<Curve>, Option<Curve>) {
    match data.manifest.find_of(lc) {
        "state" => {
            let fig = figdata::critical_figure(lc);
            let a = data.curve(&fig, figdata::K_CRIT_OF_MU);
            let b = data.curve(&fig, figdata::MU_CRIT_OF_K);
            ((!a.is_empty()).then_some(a), (!b.is_empty()).then_some(b))
        }
        "thickness" if single_model(data) => {
            let mut pts: Vec<(f64, f64)> = data
                .results
                .iter()
                .filter(|r| &*r.load_case == lc)
                .filter_map(|r| {
                    Some((
                        r.mu.filter(|m| m.is_finite())?,
                        r.k_crit.unwrap_or(f64::NAN),
                    ))
                })
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            ((pts.len() >= 2).then_some(pts), None)
        }
        "friction" if single_model(data) => {
            let mut pts: Vec<(f64, f64)> = data
                .results
                .iter()
                .filter(|r| &*r.load_case == lc)
                .filter_map(|r| Some((r.k?, r.mu_crit.unwrap_or(f64::NAN))))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            (None, (pts.len() >= 2).then_some(pts))
        }
        _ => (None, None),
    }
}

/// The collapse of a thickness or friction study over one model, (μ, K_col) or (K, μ_col):
/// the first complete solution along the find's path, NaN where none was found. Empty when no
/// case has a gap (the curve is then the critical curve itself).
fn collapse(data: &RunData, lc: &str) -> Curve {
    let rows = || data.results.iter().filter(|r| &*r.load_case == lc);
    if !single_model(data) || !rows().any(|r| r.gap.as_deref() == Some("gap")) {
        return Vec::new();
    }
    let thickness = data.manifest.find_of(lc) == "thickness";
    let mut pts: Curve = rows()
        .filter_map(|r| {
            let x = if thickness { r.mu } else { r.k };
            Some((
                x.filter(|v| v.is_finite())?,
                r.collapse_value.unwrap_or(f64::NAN),
            ))
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts
}

/// The gap of a thickness or friction study in words: how many cases have one and the
/// widest, or `None` when none has.
fn gap_note(data: &RunData, lc: &str) -> Option<String> {
    let find = data.manifest.find_of(lc);
    if find == "state" {
        return state_gap_note(data, lc);
    }
    let (name, path, at) = match find {
        "thickness" => ("K", "decreasing K", "μ"),
        "friction" => ("μ", "decreasing μ", "K"),
        _ => return None,
    };
    let rows: Vec<_> = (data.results.iter())
        .filter(|r| &*r.load_case == lc && r.gap.as_deref() == Some("gap"))
        .collect();
    let widest = rows
        .iter()
        .filter_map(|r| Some((r.gap_width?, r)))
        .max_by(|a, b| a.0.total_cmp(&b.0))?;
    let x = if find == "thickness" {
        widest.1.mu
    } else {
        widest.1.k
    };
    Some(format!(
        "Dashed: the collapse, the first complete solution along {path}, from which a mechanism \
         obeying the flow rules can start. In {} case(s) it comes before the static limit: the \
         non-associative gap, in which the outcome depends on contact stiffness and initial \
         stress; the widest is {:.4} in {name} at {at} = {}.",
        rows.len(),
        widest.0,
        x.map_or("?".into(), |v| format!("{v:.4}"))
    ))
}

/// The gap of a state study's critical curves in words: where the collapse curves stored
/// beside K_c(μ) and μ_c(K) (figure data, self-weight on forms other than the circular arch
/// with radial joints) lie above them, and by how much at most.
fn state_gap_note(data: &RunData, lc: &str) -> Option<String> {
    let fig = figdata::critical_figure(lc);
    let widest = |col: &str, crit: &str| {
        let (c, s) = (data.curve(&fig, col), data.curve(&fig, crit));
        c.iter()
            .zip(&s)
            .filter(|(a, b)| a.1.is_finite() && b.1.is_finite() && a.1 > b.1)
            .map(|(a, b)| (a.1 - b.1, a.0, a.1))
            .max_by(|x, y| x.0.total_cmp(&y.0))
    };
    // Samples whose first complete solution is the start of the path: x from, to, and the
    // largest start.
    let at_start = |series: &str| {
        let s = data.curve(&fig, series);
        let top = s.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        Some((s.first()?.0, s.last()?.0, top, s.len()))
    };
    let k = widest(figdata::K_COLLAPSE_OF_MU, figdata::K_CRIT_OF_MU);
    let mu = widest(figdata::MU_COLLAPSE_OF_K, figdata::MU_CRIT_OF_K);
    let k_start = at_start(figdata::K_COLLAPSE_AT_START);
    let mu_start = at_start(figdata::MU_COLLAPSE_AT_START);
    if k.is_none() && mu.is_none() && k_start.is_none() && mu_start.is_none() {
        return None;
    }
    let mut parts = Vec::new();
    if let Some((w, at, to)) = k {
        parts.push(format!(
            "along decreasing K it lies up to {w:.4} above K_c (at μ = {at:.4}, K = {to:.4})"
        ));
    }
    let from_start = |s: Option<(f64, f64, f64, usize)>, (x, y, what): (&str, &str, &str)| {
        s.map(|(a, b, top, n)| {
            format!(
                "at {n} of the samples of {x} from {a:.4} to {b:.4} it is the start of the \
                 search itself ({y} up to {top:.4}): there the arch can move at every {what} \
                 searched, and no dashed line is drawn"
            )
        })
    };
    parts.extend(from_start(k_start, ("μ", "K", "thickness")));
    if let Some((w, at, to)) = mu {
        parts.push(format!(
            "along decreasing μ it lies up to {w:.4} above μ_c (at K = {at:.4}, μ = {to:.4})"
        ));
    }
    parts.extend(from_start(mu_start, ("K", "μ", "friction")));
    Some(format!(
        "Dashed: the collapse, the first complete solution from which a mechanism obeying the \
         flow rules can start, found at the curves' samples; {}. Between the two lies the \
         non-associative gap, in which the outcome depends on contact stiffness and initial \
         stress: the arches of the regime map that stand there may also move.",
        parts.join("; ")
    ))
}

/// The windows of K of a thickness study over one model, (μ, from, to), shaded on panel (a).
fn windows(data: &RunData, lc: &str) -> Vec<(f64, f64, f64)> {
    data.results
        .iter()
        .filter(|r| &*r.load_case == lc)
        .filter_map(|r| Some((r.mu.filter(|m| m.is_finite())?, &r.k_windows)))
        .flat_map(|(mu, w)| {
            w.iter()
                .map(move |&(a, b)| (mu, a, b.unwrap_or(f64::INFINITY)))
        })
        .collect()
}

/// The words and axes of one panel.
struct Axes {
    title: &'static str,
    x_desc: &'static str,
    y_desc: &'static str,
    /// K on the x axis (panel b), μ on it otherwise.
    k_on_x: bool,
}

impl Axes {
    /// Panel (a): K_c against μ.
    const COLLAPSE_THICKNESS: Axes = Axes {
        title: "(a) collapse thickness K_c(μ)",
        x_desc: "friction coefficient μ",
        y_desc: "collapse thickness ratio K_c = R/r",
        k_on_x: false,
    };
    /// Panel (b): μ_c against K.
    const CRITICAL_FRICTION: Axes = Axes {
        title: "(b) critical friction μ_c(K)",
        x_desc: "thickness ratio K = R/r",
        y_desc: "critical friction coefficient μ_c",
        k_on_x: true,
    };
}

/// The points both panels mark, with μ and K on swapped axes.
struct Marks {
    /// Bifurcations of this run, (μ, K).
    bifurcations: Vec<(f64, f64)>,
    /// Whether the paper's printed values are marked too.
    paper: bool,
}

impl Marks {
    fn panel(&self, axes: Axes, curve: Curve) -> CriticalPanel {
        let k_on_x = axes.k_on_x;
        let xy = |mu: f64, k: f64| if k_on_x { (k, mu) } else { (mu, k) };
        let paper_pts = [
            (paper::MU_ROTATIONAL_MIXED, paper::K_C),
            (paper::MU_MIN, paper::K_MIXED_SLIDING),
        ];
        CriticalPanel {
            title: axes.title.into(),
            x_desc: axes.x_desc.into(),
            y_desc: axes.y_desc.into(),
            curve,
            bifurcations: self
                .bifurcations
                .iter()
                .map(|&(mu, k)| {
                    let (x, y) = xy(mu, k);
                    PointMark {
                        x,
                        y,
                        label: String::new(),
                    }
                })
                .collect(),
            paper: if self.paper {
                paper_pts
                    .iter()
                    .map(|(m, k)| {
                        let (x, y) = xy(m.value, k.value);
                        let label = if k_on_x {
                            format!("paper: K = {}, μ = {}", k.text, m.text)
                        } else {
                            format!("paper: μ = {}, K = {}", m.text, k.text)
                        };
                        PointMark { x, y, label }
                    })
                    .collect()
            } else {
                Vec::new()
            },
            y_max: None,
            windows: Vec::new(),
            collapse: Vec::new(),
        }
    }
}
