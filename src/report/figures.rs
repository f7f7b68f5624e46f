//! The figures of a report: what each chart shows, built from the stored data of a run (no
//! analysis), with a filename stem, a title and a caption.

use super::convergence::{ObservedOrder, observed_order};
use super::data::RunData;
use super::format::{given, short};
use super::paper;
use crate::figdata;
use crate::plot::accuracy::{AccuracyChart, AccuracySeries};
use crate::plot::critical::{CriticalChart, CriticalPanel, PointMark};
use crate::plot::domains::{BoundCurve, BoundFamily, DomainsChart};
use crate::plot::mechanisms::{MechanismFigure, MechanismPanels};
use crate::plot::regime_map::{BifurcationMark, CollapseSegment, Crossing, RegimeMap};
use crate::plot::state::StateDrawing;
use crate::plot::{self, Format};
use crate::store::{BoundaryRow, StateRow};
use std::collections::{BTreeMap, HashMap};

/// A chart with its data.
#[derive(Debug, Clone)]
pub enum Chart {
    /// Figure 1.
    RegimeMap(RegimeMap),
    /// Figure 2.
    Domains(DomainsChart),
    /// Figure 3.
    State(StateDrawing),
    /// Figure 4.
    Critical(CriticalChart),
    /// Figure 5.
    Accuracy(AccuracyChart),
    /// Mechanisms at a bifurcation, side by side.
    Mechanisms(MechanismPanels),
}

/// A figure of the report.
#[derive(Debug, Clone)]
pub struct FigureSpec {
    /// File stem in plots/ (filename-safe, unique).
    pub stem: String,
    /// Heading.
    pub title: String,
    /// Caption: what is shown and how to read it.
    pub caption: String,
    /// The chart.
    pub chart: Chart,
}

impl FigureSpec {
    /// The file bytes in a format.
    pub fn render(&self, format: Format) -> Result<Vec<u8>, plot::PlotError> {
        match &self.chart {
            Chart::RegimeMap(c) => plot::render(c, format),
            Chart::Domains(c) => plot::render(c, format),
            Chart::State(c) => plot::render(c, format),
            Chart::Critical(c) => plot::render(c, format),
            Chart::Accuracy(c) => plot::render(c, format),
            Chart::Mechanisms(c) => plot::render(c, format),
        }
    }
}

/// A filename-safe form of a name.
pub fn safe(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn mu_text(mu: f64) -> String {
    if mu.is_infinite() {
        "∞".into()
    } else {
        given(mu)
    }
}

/// All figures of a run, in report order.
pub fn build(data: &RunData) -> Vec<FigureSpec> {
    let mut out = Vec::new();
    let multi = data.manifest.load_cases.len() > 1;
    for lc in &data.manifest.load_cases {
        let sfx = if multi {
            format!("-{}", safe(&lc.name))
        } else {
            String::new()
        };
        let on = if multi {
            format!(" (load case {})", lc.name)
        } else {
            String::new()
        };
        if let Some(map) = regime_map(data, &lc.name, &on) {
            out.push(FigureSpec {
                stem: format!("regime-map{sfx}"),
                title: format!("Regime map{on}"),
                caption: REGIME_CAPTION.into(),
                chart: Chart::RegimeMap(map),
            });
        }
        if let Some(c) = critical(data, &lc.name, &on) {
            out.push(FigureSpec {
                stem: format!("critical-curves{sfx}"),
                title: format!("Critical curves{on}"),
                caption: CRITICAL_CAPTION.into(),
                chart: Chart::Critical(c),
            });
        }
    }
    for s in &data.states {
        if s.source == "scene" {
            out.push(domains(data, s));
        }
    }
    for s in &data.states {
        out.push(state(data, s));
        if let Some(m) = mechanisms(data, s) {
            out.push(m);
        }
    }
    if let Some(a) = accuracy(data) {
        out.push(FigureSpec {
            stem: "speed-accuracy".into(),
            title: "Speed against accuracy".into(),
            caption: ACCURACY_CAPTION.into(),
            chart: Chart::Accuracy(a),
        });
    }
    out
}

const REGIME_CAPTION: &str = "Regimes over the friction coefficient μ (horizontal) and the thickness ratio K = R/r (left axis; t/R_c on the right axis). Stable: an admissible state exists (Hʳ ∩ Hˢ ≠ ∅). Rotational: no line of thrust fits in the arch whatever the friction (Hʳ = ∅). Sliding: no thrust satisfies Coulomb's law at every joint whatever the thickness (Hˢ = ∅). Mixed: both domains exist but are disjoint. The thick line is the collapse curve through the located boundary points, coloured and labelled by the collapse mechanism (hinges only, hinges and sliding joints, sliding joints only); dots mark the bifurcations where two mechanisms coexist, with their values. Dashed lines are the other regime boundaries.";

const CRITICAL_CAPTION: &str = "The collapse thickness K_c(μ) (the smallest K at which the arch stands at friction μ) and the critical friction μ_c(K) (the smallest μ at which an arch of thickness K stands). Dots: bifurcations located in this run; open diamonds: the values printed in the paper, when the study is the paper's case.";

const ACCURACY_CAPTION: &str = "Error of each critical value of a discrete arch of N voussoirs against the continuum value at the same K, μ and load (largest error over the cases with that N), against N (points of one quantity joined in order of N) and against the median solve time per case (one point per N; a thresholds case finds all four quantities in one analysis, so they share its time). The legend gives each quantity's observed order of convergence, the least-squares slope of log|error| against log N over the larger counts. The error need not fall monotonically: it depends on how near a joint of the model lies to the continuum's hinge or sliding section, and a count whose joints include those of a smaller one (512, 1024, 2048, ...) can give the same value. The dashed line marks the median solve time of the continuum analyses (one line per find when the study has several), whose error is zero by definition.";

fn sorted_distinct(v: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = v.filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

fn regime_map(data: &RunData, lc: &str, on: &str) -> Option<RegimeMap> {
    if data.manifest.find_of(lc) != "state" || !single_model(data) {
        return None;
    }
    let rows: Vec<_> = data
        .results
        .iter()
        .filter(|r| &*r.load_case == lc && &*r.find == "state")
        .collect();
    let mu = sorted_distinct(rows.iter().filter_map(|r| r.mu));
    let k = sorted_distinct(rows.iter().filter_map(|r| r.k));
    if mu.len() < 2 || k.len() < 2 {
        return None;
    }
    let mi: HashMap<u64, usize> = mu
        .iter()
        .enumerate()
        .map(|(i, v)| (v.to_bits(), i))
        .collect();
    let ki: HashMap<u64, usize> = k
        .iter()
        .enumerate()
        .map(|(i, v)| (v.to_bits(), i))
        .collect();
    let mut regimes = vec![None; mu.len() * k.len()];
    for r in &rows {
        if let (Some(m), Some(kk)) = (r.mu, r.k)
            && let (Some(&i), Some(&j)) = (mi.get(&m.to_bits()), ki.get(&kk.to_bits()))
        {
            regimes[j * mu.len() + i] = r.regime.clone();
        }
    }
    let bounds = data.boundaries_of(lc);
    let bifs = data.bifurcations_of(lc);
    let span = ((mu[0], mu[mu.len() - 1]), (k[0], k[k.len() - 1]));
    let collapse = collapse_segments(
        &bounds,
        &bifs.iter().map(|b| (b.mu, b.k)).collect::<Vec<_>>(),
        span,
    );
    let other = other_boundaries(&bounds);
    let crossing = |b: &&BoundaryRow, fixed: f64, at: f64| Crossing {
        fixed,
        at,
        low: b.regime_low.clone(),
        high: b.regime_high.clone(),
    };
    let crossings_along_mu = bounds
        .iter()
        .filter(|b| b.axis == "mu")
        .map(|b| crossing(b, b.k, b.mu))
        .collect();
    let crossings_along_k = bounds
        .iter()
        .filter(|b| b.axis == "k")
        .map(|b| crossing(b, b.mu, b.k))
        .collect();
    let bifurcations = bifs
        .iter()
        .map(|b| BifurcationMark {
            mu: b.mu,
            k: b.k,
            lines: vec![
                format!("{} / {}", b.mechanism_a, b.mechanism_b),
                format!("μ = {}", short(b.mu)),
                format!("K = {}  (t/R_c = {})", short(b.k), short(b.t_over_r)),
            ],
        })
        .collect();
    let title = match &data.manifest.title {
        Some(t) => format!("{t}{on}"),
        None => format!("Regimes over μ and K{on}"),
    };
    Some(RegimeMap {
        title,
        mu,
        k,
        regimes,
        crossings_along_mu,
        crossings_along_k,
        collapse,
        other_boundaries: other,
        bifurcations,
    })
}

fn single_model(data: &RunData) -> bool {
    !data
        .manifest
        .grid
        .iter()
        .any(|a| a.name == "voussoirs" || a.name == "half_angle_deg")
}

/// The collapse curve in order along it, split by mechanism. Points are ordered by
/// K/ΔK − μ/Δμ, which increases along a curve on which K grows as μ falls (the collapse
/// curve of a symmetric arch); bifurcations end one segment and start the next.
fn collapse_segments(
    bounds: &[&BoundaryRow],
    bifs: &[(f64, f64)],
    span: ((f64, f64), (f64, f64)),
) -> Vec<CollapseSegment> {
    let dm = (span.0.1 - span.0.0).max(1e-12);
    let dk = (span.1.1 - span.1.0).max(1e-12);
    let key = |mu: f64, k: f64| k / dk - mu / dm;
    let mut pts: Vec<(f64, f64, Option<String>)> = bounds
        .iter()
        .filter(|b| b.on_collapse_curve)
        .map(|b| (b.mu, b.k, Some(b.mechanism.clone().unwrap_or_default())))
        .collect();
    if pts.is_empty() {
        return Vec::new();
    }
    pts.extend(bifs.iter().map(|&(m, k)| (m, k, None)));
    pts.sort_by(|a, b| key(a.0, a.1).total_cmp(&key(b.0, b.1)));
    let mut segs: Vec<CollapseSegment> = Vec::new();
    let mut cur: Option<CollapseSegment> = None;
    let mut pending_bif: Option<(f64, f64)> = None;
    for (m, k, mech) in pts {
        match mech {
            None => {
                if let Some(mut c) = cur.take() {
                    c.points.push((m, k));
                    segs.push(c);
                }
                pending_bif = Some((m, k));
            }
            Some(name) => match cur.as_mut() {
                Some(c) if c.mechanism == name => c.points.push((m, k)),
                _ => {
                    let mut start = Vec::new();
                    if let Some(c) = cur.take() {
                        start.push(*c.points.last().unwrap_or(&(m, k)));
                        segs.push(c);
                    } else if let Some(b) = pending_bif {
                        start.push(b);
                    }
                    start.push((m, k));
                    pending_bif = None;
                    cur = Some(CollapseSegment {
                        mechanism: name,
                        points: start,
                    });
                }
            },
        }
    }
    if let Some(c) = cur {
        segs.push(c);
    }
    segs.retain(|s| s.points.len() >= 2);
    segs
}

/// The boundaries off the collapse curve, one polyline per (low, high, axis) group.
fn other_boundaries(bounds: &[&BoundaryRow]) -> Vec<Vec<(f64, f64)>> {
    let mut groups: BTreeMap<(String, String, String), Vec<(f64, f64)>> = BTreeMap::new();
    for b in bounds.iter().filter(|b| !b.on_collapse_curve) {
        groups
            .entry((b.regime_low.clone(), b.regime_high.clone(), b.axis.clone()))
            .or_default()
            .push((b.mu, b.k));
    }
    groups
        .into_iter()
        .map(|((_, _, axis), mut pts)| {
            if axis == "k" {
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            } else {
                pts.sort_by(|a, b| a.1.total_cmp(&b.1));
            }
            pts
        })
        .filter(|p| p.len() >= 2)
        .collect()
}

fn critical(data: &RunData, lc: &str, on: &str) -> Option<CriticalChart> {
    let paper = data.manifest.is_paper_case();
    let bifs = data.bifurcations_of(lc);
    let paper_pts = [
        (paper::MU_ROTATIONAL_MIXED, paper::K_C),
        (paper::MU_MIN, paper::K_MIXED_SLIDING),
    ];
    // Both panels show the same points, with μ and K on swapped axes.
    let panel = |title: &str, x_desc: &str, y_desc: &str, curve, k_on_x: bool| {
        let xy = |mu: f64, k: f64| if k_on_x { (k, mu) } else { (mu, k) };
        CriticalPanel {
            title: title.into(),
            x_desc: x_desc.into(),
            y_desc: y_desc.into(),
            curve,
            bifurcations: bifs
                .iter()
                .map(|b| {
                    let (x, y) = xy(b.mu, b.k);
                    PointMark {
                        x,
                        y,
                        label: String::new(),
                    }
                })
                .collect(),
            paper: if paper {
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
        }
    };
    let panel_a = |curve: Vec<(f64, f64)>| {
        panel(
            "(a) collapse thickness K_c(μ)",
            "friction coefficient μ",
            "collapse thickness ratio K_c = R/r",
            curve,
            false,
        )
    };
    let panel_b = |curve: Vec<(f64, f64)>| {
        panel(
            "(b) critical friction μ_c(K)",
            "thickness ratio K = R/r",
            "critical friction coefficient μ_c",
            curve,
            true,
        )
    };
    let mut panels = Vec::new();
    match data.manifest.find_of(lc) {
        "state" => {
            let fig = figdata::critical_figure(lc);
            let a = data.curve(&fig, figdata::K_CRIT_OF_MU);
            let b = data.curve(&fig, figdata::MU_CRIT_OF_K);
            if !a.is_empty() {
                panels.push(panel_a(a));
            }
            if !b.is_empty() {
                panels.push(panel_b(b));
            }
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
            if pts.len() >= 2 {
                panels.push(panel_a(pts));
            }
        }
        "friction" if single_model(data) => {
            let mut pts: Vec<(f64, f64)> = data
                .results
                .iter()
                .filter(|r| &*r.load_case == lc)
                .filter_map(|r| Some((r.k?, r.mu_crit.unwrap_or(f64::NAN))))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            if pts.len() >= 2 {
                panels.push(panel_b(pts));
            }
        }
        _ => {}
    }
    if panels.is_empty() {
        return None;
    }
    Some(CriticalChart {
        title: format!("Critical curves{on}"),
        panels,
    })
}

fn domains(data: &RunData, s: &StateRow) -> FigureSpec {
    let fig = figdata::domains_figure(&s.state_id);
    let c = |series: &str| data.curve(&fig, series);
    let curve = |label: &str, series: &str, family, upper| BoundCurve {
        label: label.into(),
        points: c(series),
        family,
        upper,
    };
    let curves = vec![
        curve(
            "min, eq. 2a, thrust at crown extrados",
            "h_min_r_extrados",
            BoundFamily::CrownExtrados,
            false,
        ),
        curve(
            "max, eq. 2b, thrust at crown extrados",
            "h_max_r_extrados",
            BoundFamily::CrownExtrados,
            true,
        ),
        curve(
            "min, eq. 2a, thrust at crown intrados",
            "h_min_r_intrados",
            BoundFamily::CrownIntrados,
            false,
        ),
        curve(
            "max, eq. 2b, thrust at crown intrados",
            "h_max_r_intrados",
            BoundFamily::CrownIntrados,
            true,
        ),
        curve(
            "min, eq. 4a (sliding)",
            "h_min_s",
            BoundFamily::Sliding,
            false,
        ),
        curve(
            "max, eq. 4b (sliding)",
            "h_max_s",
            BoundFamily::Sliding,
            true,
        ),
    ];
    let interval = |lo: Option<f64>, hi: Option<f64>, exists: bool| {
        exists.then(|| (lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY)))
    };
    let regime = s.regime.as_deref().unwrap_or("");
    let r_exists = !matches!(regime, "rotational" | "none");
    let s_exists = !matches!(regime, "sliding" | "none");
    let title = format!(
        "Domains Hʳ and Hˢ, K = {}, μ = {}",
        given(s.scene_k),
        mu_text(s.scene_mu)
    );
    FigureSpec {
        stem: format!("domains-{}", safe(&s.state_id)),
        title: format!(
            "Thrust domains of scene K = {}, μ = {}",
            given(s.scene_k),
            mu_text(s.scene_mu)
        ),
        caption: format!(
            "The paper's Fig. 2 for K = {} (t/R_c = {}) and μ = {}: against the joint angle θ, the crown thrust H/W_half at which the line of thrust through the crown extrados or intrados touches the intrados (eq. 2a, lower bounds) or the extrados (eq. 2b, upper bounds) of joint θ, and the sliding bounds of eqs. 4a/4b. Bands: Hʳ (rotational), Hˢ (sliding) and their intersection, the thrusts of admissible states. Regime: {}.",
            given(s.scene_k),
            short(crate::model::t_over_r_from_k(s.scene_k)),
            mu_text(s.scene_mu),
            if regime.is_empty() { "—" } else { regime }
        ),
        chart: Chart::Domains(DomainsChart {
            title,
            alpha_deg: s.half_angle_deg,
            curves,
            h_r: interval(s.thrust_r_min, s.thrust_r_max, r_exists),
            h_s: interval(s.thrust_s_min, s.thrust_s_max, s_exists),
            discrete: s.voussoirs.is_some(),
        }),
    }
}

fn state(data: &RunData, s: &StateRow) -> FigureSpec {
    let line = data.curve(
        &figdata::line_of_thrust_figure(&s.state_id),
        figdata::LINE_OF_THRUST,
    );
    let joints = match s.voussoirs {
        Some(n) if n > 1 => (1..n)
            .map(|j| -s.half_angle_deg + 2.0 * s.half_angle_deg * f64::from(j) / f64::from(n))
            .collect(),
        _ => Vec::new(),
    };
    let joints_note = if joints.is_empty() {
        ""
    } else {
        " Open circles: the line's points on the joints, the only sections where it must stay within the arch."
    };
    let hinges = s
        .joints
        .hinge_angles_deg
        .iter()
        .copied()
        .zip(s.joints.hinge_faces.iter().cloned())
        .collect();
    let sliding = s
        .joints
        .sliding_angles_deg
        .iter()
        .copied()
        .zip(s.joints.sliding_senses.iter().cloned())
        .collect();
    let mech = s.mechanism.clone().unwrap_or_else(|| "none".into());
    let values = format!(
        "K = {} (t/R_c = {}), μ = {}, H/W_half = {}",
        short(s.k),
        short(s.t_over_r),
        if s.mu.is_infinite() {
            "∞".into()
        } else {
            short(s.mu)
        },
        s.thrust_over_half_weight.map_or("—".into(), short)
    );
    let (title, heading, subtitle, note, caption) = match s.state.as_str() {
        "bifurcation" => (
            format!("Collapse at the {} bifurcation", mech.replace('/', " / ")),
            format!(
                "Collapse state at the {} bifurcation",
                mech.replace('/', " / ")
            ),
            vec![values.clone()],
            None,
            format!(
                "The limit state at the bifurcation where the {} mechanisms coexist ({values}), as in the paper's Figs. 6 and 7: the arch to scale, its line of thrust, hinges on the intrados or extrados and sliding joints with the sense in which the part nearer the crown moves.",
                mech.replace('/', " and ")
            ),
        ),
        "minimum_thrust" => (
            format!(
                "Minimum-thrust state, K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            format!(
                "Minimum-thrust state of scene K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            vec![
                values.clone(),
                format!(
                    "regime {}; limit conditions: {}",
                    s.regime.clone().unwrap_or_default(),
                    mech
                ),
            ],
            None,
            format!(
                "The admissible state of least crown thrust of the scene ({values}): the arch to scale with its line of thrust, the joints where it touches a face (hinges) and the joints at the limit of friction (sliding, with the sense of the crown-side part)."
            ),
        ),
        "collapse" => (
            format!(
                "Scene K = {}, μ = {}: collapse at K_c(μ)",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            format!(
                "Collapse state for scene K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            vec![
                values.clone(),
                format!(
                    "the scene itself ({}) cannot stand; {} mechanism",
                    s.regime.clone().unwrap_or_default(),
                    mech
                ),
            ],
            None,
            format!(
                "The scene K = {}, μ = {} cannot stand (regime {}); drawn is the collapse state at the same friction and the collapse thickness K_c(μ) ({values}).",
                given(s.scene_k),
                mu_text(s.scene_mu),
                s.regime.clone().unwrap_or_default()
            ),
        ),
        _ => (
            format!(
                "Scene K = {}, μ = {}: no equilibrium",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            format!(
                "Scene K = {}, μ = {}",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
            vec![format!("regime {}", s.regime.clone().unwrap_or_default())],
            Some("no admissible state at this friction for any thickness".to_string()),
            format!(
                "The scene K = {}, μ = {} has no admissible state, and none exists at this friction for any thickness.",
                given(s.scene_k),
                mu_text(s.scene_mu)
            ),
        ),
    };
    let note = note.or_else(|| {
        line.is_empty()
            .then(|| "line of thrust not unique: not drawn".to_string())
    });
    let caption = format!("{caption}{joints_note}");
    FigureSpec {
        stem: format!("state-{}", safe(&s.state_id)),
        title: heading,
        caption,
        chart: Chart::State(StateDrawing {
            title,
            subtitle,
            k: s.k,
            alpha_deg: s.half_angle_deg,
            voussoir_joints_deg: joints,
            line_of_thrust: line,
            hinges,
            sliding,
            note,
        }),
    }
}

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

fn mechanisms(data: &RunData, s: &StateRow) -> Option<FigureSpec> {
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
                    super::format::short(m.work_loads)
                ),
                drawing,
            })
        })
        .collect();
    if panels.is_empty() {
        return None;
    }
    let mech = s.mechanism.clone().unwrap_or_default().replace('/', " / ");
    Some(FigureSpec {
        stem: mechanisms_stem(&s.state_id),
        title: format!("Collapse mechanisms at the {mech} bifurcation"),
        caption: format!(
            "The mechanisms admissible at the {mech} bifurcation (K = {}, μ = {}): the arch before the virtual displacement (dashed), fixed parts (grey), the displaced blocks (blue; largest displacement 0.08 r), hinges (red dots; hollow where the joint stays closed in that mechanism) and sliding joints (orange arrows: the sense in which the crown-side part moves). Non-associative panels use the paper's rule (pure sliding, no dilatancy); the associative panels use normality to the Coulomb cone, whose slip opens the joint by tan φ times the slip.",
            short(s.k),
            short(s.mu)
        ),
        chart: Chart::Mechanisms(MechanismPanels { panels }),
    })
}

/// Label of a compared quantity.
pub fn quantity_label(q: &str) -> &'static str {
    match q {
        "k_crit" => "K_c",
        "mu_crit" => "μ_c",
        "thrust_min" => "H_min/W_half",
        "thrust_r_min" => "min Hʳ/W_half",
        "k_c_rotational" => "K_c (μ = ∞)",
        "mu_rotational_mixed" => "μ, rotational/mixed",
        "mu_min" => "μ_min",
        "k_mixed_sliding" => "K, mixed/sliding",
        "load_factor" => "λ (load factor)",
        _ => "value",
    }
}

/// One row of the accuracy data: quantity, N, largest |error|, largest relative error,
/// median solve time of the discrete cases and of their continuum references (µs).
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyRow {
    /// Results column compared.
    pub quantity: String,
    /// Voussoir count.
    pub voussoirs: u32,
    /// Cases compared.
    pub cases: usize,
    /// Largest |discrete − continuum|.
    pub max_abs_error: f64,
    /// Largest |discrete − continuum| / |continuum|.
    pub max_rel_error: f64,
    /// The discrete value when one case has this N (NaN otherwise).
    pub value: f64,
    /// The continuum value when one case has this N (NaN otherwise).
    pub continuum_value: f64,
    /// Median solve time of the discrete cases, µs.
    pub median_time_us: f64,
    /// Median solve time of the continuum references, µs.
    pub continuum_median_time_us: f64,
}

/// The accuracy rows of a run (empty without references).
pub fn accuracy_rows(data: &RunData) -> Vec<AccuracyRow> {
    if data.reference.is_empty() {
        return Vec::new();
    }
    let by_id: HashMap<u64, &crate::store::ResultRow> =
        data.results.iter().map(|r| (r.case_id, r)).collect();
    // Per (quantity, N): value, continuum value, solve time, continuum solve time.
    type Sample = (f64, f64, f64, f64);
    let mut groups: BTreeMap<(String, u32), Vec<Sample>> = BTreeMap::new();
    for rf in &data.reference {
        let Some(r) = by_id.get(&rf.case_id) else {
            continue;
        };
        let (Some(n), Some(cont)) = (r.voussoirs, rf.continuum_value) else {
            continue;
        };
        let Some(v) = r.value_of(&rf.quantity) else {
            continue;
        };
        groups.entry((rf.quantity.clone(), n)).or_default().push((
            v,
            cont,
            r.solve_time_us,
            rf.continuum_solve_time_us,
        ));
    }
    groups
        .into_iter()
        .map(|((q, n), v)| {
            let max_abs = v.iter().map(|x| (x.0 - x.1).abs()).fold(0.0, f64::max);
            let max_rel = v
                .iter()
                .map(|x| (x.0 - x.1).abs() / x.1.abs())
                .fold(0.0, f64::max);
            let (value, continuum_value) = match v.as_slice() {
                [one] => (one.0, one.1),
                _ => (f64::NAN, f64::NAN),
            };
            let mut t: Vec<f64> = v.iter().map(|x| x.2).collect();
            let mut tc: Vec<f64> = v.iter().map(|x| x.3).collect();
            t.sort_by(f64::total_cmp);
            tc.sort_by(f64::total_cmp);
            AccuracyRow {
                quantity: q,
                voussoirs: n,
                cases: v.len(),
                max_abs_error: max_abs,
                max_rel_error: max_rel,
                value,
                continuum_value,
                median_time_us: super::format::quantile(&t, 0.5),
                continuum_median_time_us: super::format::quantile(&tc, 0.5),
            }
        })
        .collect()
}

/// Position of a quantity in tables and legends: the order of the find's columns.
pub fn quantity_rank(q: &str) -> usize {
    [
        "k_crit",
        "mu_crit",
        "thrust_min",
        "thrust_r_min",
        "k_c_rotational",
        "mu_rotational_mixed",
        "mu_min",
        "k_mixed_sliding",
        "load_factor",
    ]
    .iter()
    .position(|c| *c == q)
    .unwrap_or(usize::MAX)
}

/// The observed order of convergence of each quantity, from its largest error per N.
pub fn orders(rows: &[AccuracyRow]) -> BTreeMap<String, Option<ObservedOrder>> {
    let mut pts: BTreeMap<String, Vec<(u32, f64)>> = BTreeMap::new();
    for r in rows {
        pts.entry(r.quantity.clone())
            .or_default()
            .push((r.voussoirs, r.max_abs_error));
    }
    pts.into_iter()
        .map(|(q, p)| (q, observed_order(&p)))
        .collect()
}

fn accuracy(data: &RunData) -> Option<AccuracyChart> {
    let rows = accuracy_rows(data);
    if rows.is_empty() {
        return None;
    }
    let orders = orders(&rows);
    let mut by_q: BTreeMap<(usize, String), AccuracySeries> = BTreeMap::new();
    // Continuum solve times by find: one find's quantities come from one analysis.
    let mut cont_times: BTreeMap<&str, Vec<f64>> = BTreeMap::new();
    for r in &rows {
        let s = by_q
            .entry((quantity_rank(&r.quantity), r.quantity.clone()))
            .or_insert_with(|| AccuracySeries {
                label: match orders.get(&r.quantity).and_then(Option::as_ref) {
                    Some(o) => format!(
                        "{}: order {:.2} (N = {}–{})",
                        quantity_label(&r.quantity),
                        o.order,
                        o.n_from,
                        o.n_to
                    ),
                    None => quantity_label(&r.quantity).to_string(),
                },
                by_count: Vec::new(),
                by_time: Vec::new(),
            });
        if r.max_abs_error > 0.0 {
            s.by_count.push((f64::from(r.voussoirs), r.max_abs_error));
            s.by_time.push((r.median_time_us, r.max_abs_error));
        }
        let find = figdata::find_of_quantity(&r.quantity).unwrap_or("");
        cont_times
            .entry(find)
            .or_default()
            .push(r.continuum_median_time_us);
    }
    let several = cont_times.len() > 1;
    let continuum_times = cont_times
        .into_iter()
        .filter_map(|(find, mut t)| {
            t.sort_by(f64::total_cmp);
            let median = super::format::quantile(&t, 0.5);
            let label = if several {
                format!("continuum, {}", find.replace('_', " "))
            } else {
                "continuum".to_string()
            };
            median.is_finite().then_some((median, label))
        })
        .collect();
    Some(AccuracyChart {
        title: "Discrete arch against the continuum".into(),
        series: by_q.into_values().collect(),
        continuum_times,
    })
}
