//! The regime map around a scene: the K × μ `state` study of [`super::study`], planned,
//! analysed, its boundaries and bifurcations located as a run locates them, held in memory
//! and drawn by the report's own regime-map builder. Nothing is written.

use super::query::QueryError;
use super::study::{MapWindow, manifest_text};
use crate::boundaries;
use crate::manifest::{self, SceneOptions};
use crate::plan;
use crate::plot::frames::{self, PlotFrame};
use crate::progress::Silent;
use crate::report::charts::{FigureSpec, LoadCaseFigure, regime_map};
use crate::report::live;
use crate::scene::Scene;
use anyhow::{Context, Result, anyhow};
use serde::Serialize;
use std::path::Path;

/// A drawn regime map with what the page needs to read it.
#[derive(Debug, Clone, Serialize)]
pub struct MapView {
    /// The screen SVG.
    pub svg: String,
    /// Where its plotting area lies (μ across, K up).
    pub frame: Option<PlotFrame>,
    /// The bifurcations located: (μ, K, mechanisms).
    pub bifurcations: Vec<(f64, f64, String)>,
    /// The located points on the collapse curve: (μ, K).
    pub collapse: Vec<(f64, f64)>,
    /// Grid points analysed.
    pub points: u64,
    /// Analyses spent locating the boundaries beyond the grid.
    pub refinement_analyses: u64,
    /// The window drawn.
    pub window: MapWindow,
    /// The manifest of the study drawn.
    pub manifest: String,
}

/// The regime map of `window` on the arch and load of `options` (checked into `scene`) and
/// its figure.
pub fn regime_map(
    options: &SceneOptions,
    scene: &Scene,
    window: &MapWindow,
) -> Result<(MapView, FigureSpec)> {
    let text = manifest_text(options, scene, window);
    let m = manifest::parse(&text, Path::new("explore-around-scene.yaml"))
        .map_err(|e| anyhow!(QueryError::new("k_from", &window.query(), e.to_string())))?;
    let plan = plan::build(m.clone())?;
    let results = crate::engine::analyse(&plan, &Silent);
    let located = boundaries::locate(&plan, &results);
    let data = live::run_data(&m, &plan, &results, &located)?;
    let lc_name = m
        .load_cases
        .first()
        .map(|l| l.name.clone())
        .context("the map's study has no load case")?;
    let lc = LoadCaseFigure {
        name: &lc_name,
        stem_suffix: String::new(),
        title_suffix: String::new(),
    };
    let spec = regime_map::figure(&data, &lc).context("the map's study draws no regime map")?;
    let (svg, frames) = frames::capture(|| super::views::screen_svg(&spec));
    let collapse = data
        .boundaries
        .iter()
        .flatten()
        .filter(|b| b.on_collapse_curve)
        .map(|b| (b.mu, b.k))
        .collect();
    let bifurcations = data
        .bifurcations
        .iter()
        .flatten()
        .map(|b| {
            let label = crate::figdata::bifurcation_label(&b.mechanism_a, &b.mechanism_b);
            (b.mu, b.k, label)
        })
        .collect();
    Ok((
        MapView {
            svg: svg?,
            frame: frames.first().copied(),
            bifurcations,
            collapse,
            points: plan.cases.len() as u64,
            refinement_analyses: located.refinement_analyses,
            window: *window,
            manifest: text,
        },
        spec,
    ))
}
