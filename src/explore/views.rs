//! What the page shows of one scene, computed by the library and drawn by the report's own
//! chart code: the state (the minimum- and maximum-thrust lines when the arch stands, else
//! the limit state of the find that the scene fails), the paper's Fig. 2, the critical
//! values with their mechanisms, and the frames of the collapse mechanism in motion.

use super::query::QueryError;
use crate::analysis::forms::ArchModel;
use crate::analysis::general;
use crate::analysis::kinematics::drawing;
use crate::analysis::symmetric::{self, ThrustState};
use crate::figdata;
use crate::manifest::{SceneOptionError, SceneOptions};
use crate::model::Load;
use crate::plot::mechanisms::{MechanismFigure, MechanismPanels};
use crate::plot::{self, Format};
use crate::report::charts::{Chart, FigureSpec, solution};
use crate::scene::{self, Find, Outcome, Scene, Solution};
use anyhow::Result;
use rayon::prelude::*;
use serde_json::{Value, json};

/// Frames of the mechanism's motion, from rest to the largest displacement.
pub const MECHANISM_FRAMES: usize = 16;

impl From<SceneOptionError> for QueryError {
    fn from(e: SceneOptionError) -> Self {
        QueryError::new(e.option, &e.value, e.allowed)
    }
}

/// The answers of one scene that the page shows.
#[derive(Debug, Clone)]
pub struct SceneView {
    /// The scene (its `state` question).
    pub scene: Scene,
    /// Its state.
    pub state: Solution,
    /// The critical finds of its arch and load: `thickness`, `friction`, and `thresholds`
    /// (self-weight on a circular arch with radial joints) or `load_factor` (a live load).
    pub finds: Vec<Solution>,
    /// The limit state drawn and set in motion: the find that the scene's own path meets,
    /// K_c(μ) under self-weight, λ_max under a live load (`None` when it has none).
    pub limit: Option<Solution>,
    /// True when the scene stands.
    pub stands: bool,
    /// μ_min at the scene's K on the general route (other forms and live loads, where Hˢ
    /// depends on K): below it the sliding conditions alone fail. `None` on the symmetric
    /// route, whose μ_min (independent of K) is the `thresholds` find's.
    pub mu_min_at_k: Option<f64>,
    /// The minimum- and maximum-thrust states of a standing circular arch with radial joints
    /// under self-weight, drawn in the state figure and marked in Fig. 2 (`None` otherwise,
    /// and in a [`Answers::Limit`] view).
    pub thrust: Option<(ThrustState, ThrustState)>,
}

/// What a view of a scene solves besides its state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Answers {
    /// Every critical find, μ_min at K and the extreme-thrust states: what the page shows.
    All,
    /// Only the finds that give the limit state (its mechanism, its figure).
    Limit,
}

fn with_find(options: &SceneOptions, find: Find) -> Result<Scene, QueryError> {
    let mut o = options.clone();
    o.find = find.as_str().into();
    if find == Find::LoadFactor {
        o.lambda = None;
    }
    if !find.needs_k() {
        // The thickness is what these finds find: K is not an input.
        o.k = None;
        o.t_over_r = None;
    }
    if !find.needs_mu() {
        o.mu = f64::INFINITY;
    }
    Ok(o.scene()?)
}

/// The `state` scene of `options`.
pub fn state_scene(options: &SceneOptions) -> Result<Scene, QueryError> {
    with_find(options, Find::State)
}

/// Solves the scene of `options` and what `answers` asks of it.
pub fn scene_view(options: &SceneOptions, answers: Answers) -> Result<SceneView, QueryError> {
    let scene = with_find(options, Find::State)?;
    let state = scene::solve(&scene);
    let stands = state.regime.is_some_and(|r| r.as_str() == "stable");
    let live = scene.load != Load::SelfWeight;
    let symmetric_route = !live && scene.form.is_circular_radial();
    let all = answers == Answers::All;
    let mut finds = vec![Find::Thickness];
    if all {
        finds.push(Find::Friction);
    }
    if live {
        finds.push(Find::LoadFactor);
    } else if all && symmetric_route {
        finds.push(Find::Thresholds);
    }
    // The finds are independent: solved on all cores, in order.
    let finds: Vec<Solution> = finds
        .into_par_iter()
        .filter_map(|f| with_find(options, f).ok())
        .map(|s| scene::solve(&s))
        .collect();
    let limit_find = if live {
        Find::LoadFactor
    } else {
        Find::Thickness
    };
    // Under a live load that no λ ≥ 0 lets stand, the limit on the scene's path is the
    // thickness at the scene's λ.
    let found = |f: Find| {
        finds
            .iter()
            .find(|s| s.find == f && s.outcome == Some(Outcome::Found))
            .cloned()
    };
    let limit = found(limit_find).or_else(|| found(Find::Thickness));
    let mu_min_at_k = if all && !symmetric_route {
        let settings = general::Settings {
            lambda: scene.lambda,
            ..general::Settings::default()
        };
        ArchModel::new(scene.arch, scene.form, scene.load)
            .ok()
            .and_then(|m| {
                general::sliding_threshold(&m, &settings)
                    .found()
                    .map(|s| s.mu)
            })
    } else {
        None
    };
    let thrust = if all && stands && symmetric_route {
        symmetric::thrust(&scene.arch, scene.friction)
    } else {
        None
    };
    Ok(SceneView {
        scene,
        state,
        finds,
        limit,
        stands,
        mu_min_at_k,
        thrust,
    })
}

impl SceneView {
    /// The state figure: the minimum- and maximum-thrust lines of a standing circular arch
    /// with radial joints under self-weight; the state of largest margin of another
    /// standing scene; else the limit state.
    pub fn state_figure(&self) -> Result<FigureSpec> {
        if let Some((lo, hi)) = &self.thrust {
            return solution::thrust_states_figure(&self.state, lo, hi);
        }
        if self.stands {
            return solution::figure(&self.state);
        }
        match &self.limit {
            Some(l) => solution::figure(l),
            None => solution::figure(&self.state),
        }
    }

    /// The hinges and sliding joints drawn in the state figure (those of its states).
    pub fn drawn_joints(&self) -> Value {
        if let Some((lo, hi)) = &self.thrust {
            return json!({
                "hinges": lo.hinges.iter().chain(&hi.hinges).collect::<Vec<_>>(),
                "sliding_joints": lo.sliding_joints.iter().chain(&hi.sliding_joints).collect::<Vec<_>>(),
            });
        }
        match (&self.limit, self.stands) {
            // A gap: the collapse, the first complete solution, is drawn.
            (Some(l), false) if solution::drawn_collapse(l).is_some() => json!({
                "hinges": l.collapse_hinges,
                "sliding_joints": l.collapse_sliding_joints,
            }),
            (Some(l), false) => json!({"hinges": l.hinges, "sliding_joints": l.sliding_joints}),
            _ => json!({"hinges": [], "sliding_joints": []}),
        }
    }

    /// True when the scene stands but lies between the collapse (the first complete
    /// solution of its limit find) and the static limit: λ at or above the collapse λ, or K
    /// at or below the collapse K.
    fn inside_gap(&self, limit: &Solution) -> bool {
        let Some(collapse) = solution::drawn_collapse(limit) else {
            return false;
        };
        match limit.find {
            Find::LoadFactor => self.scene.lambda >= collapse,
            Find::Thickness => self.scene.arch.k <= collapse,
            _ => false,
        }
    }

    /// What the state figure draws, in words.
    pub fn drawn_text(&self) -> String {
        match (&self.limit, self.stands) {
            (_, true) if self.thrust.is_some() => {
                "the minimum- and maximum-thrust states of the scene".into()
            }
            (Some(l), true) if self.inside_gap(l) => format!(
                "the scene's state of largest margin, inside the gap: an equilibrium exists up \
                 to the static limit, but the arch can start to move from its collapse ({})",
                solution::gap_words(l)
            ),
            (_, true) => "the scene's state of largest margin".into(),
            (Some(l), false) if solution::drawn_collapse(l).is_some() => format!(
                "the scene does not stand: its collapse, the first complete solution, below \
                 the static limit ({})",
                solution::gap_words(l)
            ),
            (Some(l), false) if l.find == Find::LoadFactor => format!(
                "the scene does not stand: its collapse state at λ_max = {}",
                fmt(l.load_factor)
            ),
            (Some(l), false) => format!(
                "the scene does not stand: its limit state at K_c(μ) = {}",
                fmt(l.k_crit)
            ),
            (None, false) => "the scene does not stand, and no limit state was found".into(),
        }
    }

    /// Fig. 2 of the scene: a circular arch with radial joints under self-weight only.
    pub fn domains_figure(&self) -> Option<FigureSpec> {
        if self.scene.load != Load::SelfWeight || !self.scene.form.is_circular_radial() {
            return None;
        }
        let row = solution::state_row(&self.state);
        let curves = figdata::curves::domain_curves(&self.scene.arch, self.scene.friction);
        let mut spec = crate::report::charts::domains::figure_of(&row, Default::default(), |s| {
            curves.series(s)
        });
        // The thrusts of the states drawn beside it: the least and the largest admissible.
        if let Some((lo, hi)) = &self.thrust
            && let Chart::Domains(d) = &mut spec.chart
        {
            d.marks = vec![
                (lo.thrust_over_half_weight, "minimum-thrust state".into()),
                (hi.thrust_over_half_weight, "maximum-thrust state".into()),
            ];
        }
        Some(spec)
    }

    /// The frames of the collapse mechanism of the limit state, from rest to the drawing's
    /// amplitude, on one window; empty when there is no limit state or its pattern has no
    /// mechanism.
    pub fn mechanism_frames(&self) -> Vec<FigureSpec> {
        let Some(limit) = &self.limit else {
            return Vec::new();
        };
        // With a gap, the mechanism that starts at the collapse (the first complete
        // solution), else that of the static limit.
        let collapse = solution::collapse_row(limit);
        let row = collapse
            .clone()
            .unwrap_or_else(|| solution::state_row(limit));
        let Some((model, field)) = figdata::mechanism_of_state(&row) else {
            return Vec::new();
        };
        let full = figdata::mechanisms::DRAWING_AMPLITUDE;
        let window = drawing(&model, &field, full).bounds();
        let kind = field.kind().map_or("collapse", |k| k.as_str());
        let title = match limit.find {
            _ if collapse.is_some() => format!(
                "{kind} mechanism at the collapse ({})",
                solution::gap_words(limit)
            ),
            Find::LoadFactor => format!("{kind} mechanism at λ_max = {}", fmt(limit.load_factor)),
            _ if limit.lambda.is_some() => format!(
                "{kind} mechanism at K_c = {} (λ = {})",
                fmt(limit.k_crit),
                fmt(limit.lambda)
            ),
            _ => format!("{kind} mechanism at K_c = {}", fmt(limit.k_crit)),
        };
        let subtitle = if collapse.is_some() {
            "the first complete solution: its mechanism obeys the flow rules".to_string()
        } else {
            format!(
                "non-associative (pure sliding); admissible: {}",
                match limit.mechanism_admissible {
                    Some(true) => "yes",
                    Some(false) => "no",
                    None => "—",
                }
            )
        };
        (0..MECHANISM_FRAMES)
            .map(|i| {
                let a = full * i as f64 / (MECHANISM_FRAMES - 1) as f64;
                FigureSpec {
                    stem: format!("mechanism-{i}"),
                    title: title.clone(),
                    caption: String::new(),
                    chart: Chart::Mechanisms(MechanismPanels {
                        panels: vec![MechanismFigure {
                            title: title.clone(),
                            subtitle: subtitle.clone(),
                            drawing: drawing(&model, &field, a),
                            window: Some(window),
                        }],
                    }),
                }
            })
            .collect()
    }

    /// The answers as JSON: the state, the critical finds, what is drawn and its joints.
    pub fn json(&self) -> Value {
        let mut finds = serde_json::Map::new();
        for s in &self.finds {
            finds.insert(s.find.as_str().into(), json!(s));
        }
        json!({
            "state": self.state,
            "stands": self.stands,
            "finds": finds,
            "limit": self.limit,
            "drawn": self.drawn_text(),
            "drawn_joints": self.drawn_joints(),
            "mu_min_at_k": self.mu_min_at_k,
        })
    }
}

fn fmt(x: Option<f64>) -> String {
    x.map_or("—".into(), crate::report::format::short)
}

/// The screen SVG of a figure.
pub fn screen_svg(f: &FigureSpec) -> Result<String> {
    Ok(String::from_utf8(f.render(Format::Svg)?)?)
}

/// The file of a figure to download: its paper SVG (both columns wide) or the PDF made
/// from it, as the report writes plots/STEM.svg and .pdf.
pub fn download(f: &FigureSpec, pdf: bool) -> Result<Vec<u8>> {
    let svg = f.render(Format::Paper(crate::manifest::FigureWidth::Double))?;
    if pdf {
        Ok(plot::paper::svg_to_pdf(&String::from_utf8_lossy(&svg))?)
    } else {
        Ok(svg)
    }
}
