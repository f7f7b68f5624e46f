//! A finished run in the explorer: its regime map (or λ map, or influence line) drawn from
//! its own files by the report's builders, and any case of it, found by a click on that
//! figure, rebuilt from the run's manifest (the plan gives the case's exact scene) and
//! solved again beside the values its results.parquet holds.

use super::query::QueryError;
use crate::manifest::Manifest;
use crate::output::RunLayout;
use crate::plot::frames::{self, PlotFrame};
use crate::report::charts::{self, Chart, FigureSpec};
use crate::report::data::RunData;
use crate::scene::{self, Solution};
use anyhow::Result;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// What the figure of a run shows, and so how a click on it finds a case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum FigureKind {
    /// Regimes over (μ, K): the `state` case nearest the click.
    RegimeMap,
    /// λ_max over (μ, K): the `load_factor` case nearest the click.
    LambdaMap,
    /// λ_max against the load's position (or K, μ), one panel per axis.
    Lines,
}

/// One case a click may pick: its id and its place on a panel of the figure.
#[derive(Debug, Clone, Copy)]
struct Spot {
    case_id: u64,
    panel: usize,
    x: f64,
    y: f64,
}

/// A run directory opened for exploring.
#[derive(Debug)]
pub struct RunView {
    /// The run directory (canonical).
    pub dir: PathBuf,
    manifest: Manifest,
    data: RunData,
    figure: Option<(FigureSpec, FigureKind)>,
    svg: String,
    frames: Vec<PlotFrame>,
    spots: Vec<Spot>,
}

fn pick_figure(data: &RunData) -> Option<(FigureSpec, FigureKind, String)> {
    for lc in charts::load_case_figures(data) {
        if let Some(f) = charts::regime_map::figure(data, &lc) {
            return Some((f, FigureKind::RegimeMap, lc.name.to_string()));
        }
        if let Some(f) = charts::lambda_map::figures(data, &lc).into_iter().next() {
            return Some((f, FigureKind::LambdaMap, lc.name.to_string()));
        }
        let lines = charts::load_factor::figures(data, &lc);
        let influence = lines
            .iter()
            .position(|f| f.stem.starts_with("influence-line"));
        if let Some(f) = influence
            .map(|i| lines[i].clone())
            .or(lines.into_iter().next())
        {
            return Some((f, FigureKind::Lines, lc.name.to_string()));
        }
    }
    None
}

fn spots(data: &RunData, fig: &FigureSpec, kind: FigureKind, lc: &str) -> Vec<Spot> {
    match kind {
        FigureKind::RegimeMap => (data.results.iter())
            .filter(|r| &*r.load_case == lc && &*r.find == "state")
            .filter_map(|r| {
                let (mu, k) = (r.mu?, r.k?);
                (mu.is_finite() && k.is_finite()).then_some(Spot {
                    case_id: r.case_id,
                    panel: 0,
                    x: mu,
                    y: k,
                })
            })
            .collect(),
        FigureKind::LambdaMap => (data.load_factors.iter())
            .filter(|c| c.load_case == lc && c.mu.is_finite())
            .map(|c| Spot {
                case_id: c.row as u64,
                panel: 0,
                x: c.mu,
                y: c.k,
            })
            .collect(),
        FigureKind::Lines => {
            let Chart::Lines(chart) = &fig.chart else {
                return Vec::new();
            };
            let mut out = Vec::new();
            for (i, p) in chart.panels.iter().enumerate() {
                let by_x = p.x_desc.contains("x/L");
                let by_angle = p.x_desc.contains('°') || p.x_desc.contains("angle");
                for c in data.load_factors.iter().filter(|c| c.load_case == lc) {
                    let x = if by_x {
                        c.at_x
                    } else if by_angle {
                        c.at_deg
                    } else if p.x_desc.contains('μ') {
                        Some(c.mu)
                    } else {
                        Some(c.k)
                    };
                    if let (Some(x), Some(y)) = (x, c.load_factor) {
                        let y = if p.log_y { y.log10() } else { y };
                        out.push(Spot {
                            case_id: c.row as u64,
                            panel: i,
                            x,
                            y,
                        });
                    }
                }
            }
            out
        }
    }
}

impl RunView {
    /// Opens a run directory: its stored tables, manifest and figure.
    pub fn open(dir: &Path) -> Result<Self> {
        let dir = dir
            .canonicalize()
            .map_err(|e| crate::report::data::RunDirError {
                path: dir.to_path_buf(),
                reason: format!("cannot open it: {e}"),
            })?;
        let layout = RunLayout::at(&dir);
        let data = crate::report::data::load(&layout)?;
        let (manifest, _) = crate::runner::load_manifest(&layout.manifest())?;
        let (figure, svg, frames, spots) = match pick_figure(&data) {
            Some((f, kind, lc)) => {
                let (svg, frames) = frames::capture(|| super::views::screen_svg(&f));
                let spots = spots(&data, &f, kind, &lc);
                (Some((f, kind)), svg?, frames, spots)
            }
            None => (None, String::new(), Vec::new(), Vec::new()),
        };
        Ok(RunView {
            dir,
            manifest,
            data,
            figure,
            svg,
            frames,
            spots,
        })
    }

    /// The figure of the run, when it has one of the kinds the explorer reads.
    pub fn figure(&self) -> Option<&FigureSpec> {
        self.figure.as_ref().map(|(f, _)| f)
    }

    /// The run as JSON: its name, title, case count, figure (SVG and frames) and the
    /// figure's kind.
    pub fn json(&self) -> Value {
        json!({
            "open": true,
            "name": self.data.manifest.name,
            "title": self.data.manifest.title,
            "cases": self.data.info.cases.total,
            "figure": self.figure.as_ref().map(|(f, kind)| json!({
                "title": f.title,
                "caption": f.caption,
                "kind": match kind {
                    FigureKind::RegimeMap => "regime_map",
                    FigureKind::LambdaMap => "lambda_map",
                    FigureKind::Lines => "lines",
                },
                "svg": self.svg,
                "frames": self.frames,
            })),
        })
    }

    /// The case nearest the point (x, y) of panel `panel` of the figure, in its frame's
    /// units, measured in fractions of the frame.
    pub fn case_at(&self, panel: usize, x: f64, y: f64) -> Result<u64, QueryError> {
        let frame = self.frames.get(panel).ok_or_else(|| {
            QueryError::new(
                "panel",
                &panel.to_string(),
                format!(
                    "a panel of the run's figure, 0 to {}",
                    self.frames.len().max(1) - 1
                ),
            )
        })?;
        let (sx, sy) = ((frame.x.1 - frame.x.0).abs(), (frame.y.1 - frame.y.0).abs());
        let d = |s: &Spot| ((s.x - x) / sx).powi(2) + ((s.y - y) / sy).powi(2);
        self.spots
            .iter()
            .filter(|s| s.panel == panel)
            .min_by(|a, b| d(a).total_cmp(&d(b)))
            .map(|s| s.case_id)
            .ok_or_else(|| QueryError::new("panel", &panel.to_string(), "a panel with cases"))
    }

    /// One case: its stored row and its scene solved again (the scene the run's plan gives
    /// the case id).
    pub fn case(&self, id: u64) -> Result<(Value, Solution), QueryError> {
        let total = self.data.info.cases.total;
        if id >= total {
            return Err(QueryError::new(
                "case",
                &id.to_string(),
                format!("a case id of the run, 0 to {}", total.saturating_sub(1)),
            ));
        }
        let plan = crate::plan::build_slice(self.manifest.clone(), id..id + 1);
        let case = plan
            .cases
            .first()
            .ok_or_else(|| QueryError::new("case", &id.to_string(), "a case of the run's plan"))?;
        let sol = scene::solve(&case.scene);
        let stored =
            crate::store::read_results_rows(&RunLayout::at(&self.dir).results(), (id as usize, 1))
                .ok()
                .and_then(|rows| rows.into_iter().next());
        let row = stored.map(|r| {
            json!({
                "case_id": r.case_id,
                "load_case": &*r.load_case,
                "find": &*r.find,
                "k": r.k,
                "mu": r.mu.map(|m| if m.is_finite() { json!(m) } else { json!("inf") }),
                "voussoirs": r.voussoirs,
                "regime": r.regime.as_deref(),
                "outcome": r.outcome.as_deref(),
                "k_crit": r.k_crit,
                "mu_crit": r.mu_crit,
                "load_factor": r.load_factor,
                "gap": r.gap.as_deref(),
                "collapse_value": r.collapse_value,
                "status": &*r.status,
            })
        });
        Ok((json!({"case_id": id, "stored": row}), sol))
    }
}
