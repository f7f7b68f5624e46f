//! Figure 1: the regime map over (μ, K) with a t/R_c axis beside K: coloured regions, the
//! collapse curve from the located boundary points with each segment named by its
//! mechanism, other regime boundaries, and the bifurcation points with their values.

use super::style::{self, LegendItem, Mark, clip_polyline, decimals_for, palette};
use super::{Figure, PlotContext, Window, XyChart as Chart};
use crate::model::{k_from_t_over_r, t_over_r_from_k};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::collections::BTreeMap;

/// A run of the collapse curve with one mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct CollapseSegment {
    /// `rotational`, `mixed` or `sliding`.
    pub mechanism: String,
    /// Points (μ, K) in order along the curve.
    pub points: Vec<(f64, f64)>,
}

/// A bifurcation point with the lines of its annotation.
#[derive(Debug, Clone, PartialEq)]
pub struct BifurcationMark {
    /// μ.
    pub mu: f64,
    /// K.
    pub k: f64,
    /// Annotation, one string per line (already formatted).
    pub lines: Vec<String>,
    /// The point's number, drawn instead of the box where the box finds no free place (a
    /// map at single-column width); the caption lists the numbered values.
    pub compact: String,
}

/// A located regime change on a grid line.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    /// The grid value of the other parameter (K for a change along μ).
    pub fixed: f64,
    /// Where the change is.
    pub at: f64,
    /// Regime on the smaller side.
    pub low: String,
    /// Regime on the larger side.
    pub high: String,
}

/// What the regime map shows.
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeMap {
    /// Title.
    pub title: String,
    /// Grid μ values, increasing, finite.
    pub mu: Vec<f64>,
    /// Grid K values, increasing.
    pub k: Vec<f64>,
    /// Regime names per grid point, K-major: `regimes[ik * mu.len() + imu]` (None: no
    /// value).
    pub regimes: Vec<Option<std::sync::Arc<str>>>,
    /// Located regime changes along μ at a grid K (every boundary point, so that the
    /// coloured regions meet where the boundaries were located, not half-way between grid
    /// points).
    pub crossings_along_mu: Vec<Crossing>,
    /// Located regime changes along K at a grid μ.
    pub crossings_along_k: Vec<Crossing>,
    /// The collapse curve, by mechanism.
    pub collapse: Vec<CollapseSegment>,
    /// Other regime boundaries (not on the collapse curve), as polylines (μ, K).
    pub other_boundaries: Vec<Vec<(f64, f64)>>,
    /// The first complete solution along the study's paths where it differs from the static
    /// limit (a non-associative gap), as polylines (μ, K) (NaN breaks a line): drawn dashed.
    pub gap_collapse: Vec<Vec<(f64, f64)>>,
    /// Bifurcation points.
    pub bifurcations: Vec<BifurcationMark>,
    /// The grid's μ = ∞ column, drawn as its own strip right of the finite axis.
    pub infinite: Option<InfiniteStrip>,
}

/// The μ = ∞ column of the grid: regimes along K, changing at the located boundaries.
#[derive(Debug, Clone, PartialEq)]
pub struct InfiniteStrip {
    /// Regime names at the grid K values (None: no value).
    pub regimes: Vec<Option<std::sync::Arc<str>>>,
    /// Located regime changes along K at μ = ∞ (`fixed` is +∞).
    pub crossings: Vec<Crossing>,
    /// The collapse points at μ = ∞: (K, mechanism).
    pub collapse: Vec<(f64, String)>,
}

impl InfiniteStrip {
    /// The regime at K, from the grid K values `k`: the regime of the grid point below,
    /// changed at every located change between it and K.
    pub fn regime_at<'a>(&'a self, k: &[f64], at: f64) -> Option<&'a str> {
        if k.is_empty() || self.regimes.len() != k.len() {
            return None;
        }
        let j = k.partition_point(|&g| g <= at).clamp(1, k.len()) - 1;
        let mut changes: Vec<&Crossing> = self
            .crossings
            .iter()
            .filter(|c| c.at > k[j] && c.at <= at)
            .collect();
        changes.sort_by(|a, b| a.at.total_cmp(&b.at));
        match changes.last() {
            Some(c) => Some(c.high.as_str()),
            None if at < k[0] => self.regimes[0].as_deref(),
            None => self.regimes[j].as_deref(),
        }
    }
}

mod labels;
mod raster;

impl Figure for RegimeMap {
    fn size(&self) -> (u32, u32) {
        (820, 640)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        self.draw_in(root, root, ctx, true)
    }
}

/// Regime maps of the values of an arch axis side by side (small multiples): the same grid,
/// axes and colours in every panel.
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeMapPanels {
    /// The maps, one per value, each titled by its value.
    pub maps: Vec<RegimeMap>,
}

impl RegimeMapPanels {
    fn columns(&self) -> usize {
        match self.maps.len() {
            0 | 1 => 1,
            2 | 4 => 2,
            _ => 3,
        }
    }
}

impl Figure for RegimeMapPanels {
    fn size(&self) -> (u32, u32) {
        let cols = self.columns();
        let rows = self.maps.len().div_ceil(cols).max(1);
        (680 * cols as u32, 560 * rows as u32)
    }

    fn panel_grid(&self) -> (usize, usize) {
        let cols = self.columns();
        (self.maps.len().div_ceil(cols).max(1), cols)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let cols = self.columns();
        let rows = self.maps.len().div_ceil(cols).max(1);
        // One legend for all panels, in the order of the first map that has each item.
        let mut legend: Vec<LegendItem> = Vec::new();
        for item in self.maps.iter().flat_map(RegimeMap::legend) {
            if !legend.iter().any(|l| l.label == item.label) {
                legend.push(item);
            }
        }
        let upper = style::above_legend(root, ctx, &legend)?;
        let grid = ctx.panel_grid((rows, cols));
        for (area, map) in upper.split_evenly(grid).iter().zip(&self.maps) {
            map.draw_in(root, area, ctx, false)?;
        }
        Ok(())
    }
}

impl RegimeMap {
    /// Draws the map in `area`, a part of `root` (the whole canvas, on which the pieces
    /// placed in absolute pixels are drawn), with its legend below it when `with_legend`.
    fn draw_in<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        area: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
        with_legend: bool,
    ) -> DrawResult<(), DB> {
        let upper = if with_legend {
            style::above_legend(area, ctx, &self.legend())?
        } else {
            area.clone()
        };
        if self.mu.len() < 2 || self.k.len() < 2 {
            upper.draw(&Text::new(
                "The regime map needs at least two values of μ and of K.".to_string(),
                (ctx.px(20.0), ctx.px(60.0)),
                ctx.font(15.0),
            ))?;
            return Ok(());
        }
        let window = (
            (self.mu[0], self.mu[self.mu.len() - 1]),
            (self.k[0], self.k[self.k.len() - 1]),
        );
        let ((mu0, mu1), (k0, k1)) = window;
        let strip = if self.infinite.is_some() {
            STRIP_GAP + STRIP_WIDTH
        } else {
            0.0
        };
        let mut builder = ChartBuilder::on(&upper);
        if !with_legend {
            // A panel of small multiples is named by its arch in every format: the caption
            // of a paper figure cannot say which panel is which.
            builder.caption(&self.title, ctx.font(15.0));
        } else if ctx.titles {
            builder.caption(&self.title, ctx.font(17.0));
        }
        let mut chart = builder
            .margin(ctx.px(10.0))
            .margin_right(ctx.px(86.0 + strip))
            .x_label_area_size(ctx.px(50.0))
            .y_label_area_size(ctx.px(72.0))
            .build_cartesian_2d(mu0..mu1, k0..k1)?;
        super::frames::record(&chart, (mu0, mu1), (k0, k1), false);
        self.draw_regions(&mut chart, ctx, window)?;
        super::draw_mu_k_mesh(&mut chart, ctx, window, true)?;
        self.draw_strip(root, &chart, ctx, window)?;
        draw_t_axis(root, &chart, ctx, window, ctx.px(strip))?;
        self.draw_curves(&mut chart, ctx, window)?;
        let mut labels = labels::Labels::new(self, &chart, ctx, window);
        labels.draw_bifurcations(root)?;
        labels.draw_segments(root)?;
        labels.draw_regions(root)?;
        Ok(())
    }
}

impl RegimeMap {
    /// The regions, on a raster of about 2 design pixels, as runs of equal regime along each
    /// row merged with identical runs of the rows above into one rectangle (few elements, no
    /// seams between rows).
    fn draw_regions<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<DB>,
        ctx: &PlotContext,
        ((mu0, mu1), (k0, k1)): Window,
    ) -> DrawResult<(), DB> {
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let nxr = ((f64::from(xr.end - xr.start) / ctx.scale / 2.0).ceil() as usize).max(2);
        let nyr = ((f64::from(yr.end - yr.start) / ctx.scale / 2.0).ceil() as usize).max(2);
        let raster = self.raster(nxr, nyr);
        let me: Vec<f64> = (0..=nxr)
            .map(|i| mu0 + (mu1 - mu0) * i as f64 / nxr as f64)
            .collect();
        let ke: Vec<f64> = (0..=nyr)
            .map(|j| k0 + (k1 - k0) * j as f64 / nyr as f64)
            .collect();
        let px_mu = (mu1 - mu0) / f64::from((xr.end - xr.start).max(1));
        let px_k = (k1 - k0) / f64::from((yr.end - yr.start).max(1));
        let nx = nxr;
        let mut open: BTreeMap<(usize, usize, &str), usize> = BTreeMap::new();
        let mut rects = Vec::new();
        let mut close = |(i0, i1, name): (usize, usize, &str), j0: usize, j1: usize| {
            let x1 = (me[i1] + px_mu).min(mu1);
            let y1 = (ke[j1] + px_k).min(k1);
            rects.push(Rectangle::new(
                [(me[i0], ke[j0]), (x1, y1)],
                palette::regime(name).filled(),
            ));
        };
        for j in 0..=nyr {
            let mut runs = Vec::new();
            let mut i = 0;
            while j < nyr && i < nx {
                let r = raster[j * nx + i];
                let start = i;
                while i < nx && raster[j * nx + i] == r {
                    i += 1;
                }
                if let Some(name) = r {
                    runs.push((start, i, name));
                }
            }
            let ended: Vec<_> = open.keys().filter(|k| !runs.contains(k)).cloned().collect();
            for key in ended {
                if let Some(j0) = open.remove(&key) {
                    close(key, j0, j);
                }
            }
            for run in runs {
                open.entry(run).or_insert(j);
            }
        }
        chart.draw_series(rects)?;
        Ok(())
    }

    /// The other regime boundaries (thin dashed lines), then the collapse curve.
    fn draw_curves<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<DB>,
        ctx: &PlotContext,
        window: Window,
    ) -> DrawResult<(), DB> {
        for line in &self.other_boundaries {
            for piece in clip_polyline(line, window.0, window.1) {
                chart.draw_series(DashedLineSeries::new(
                    piece,
                    ctx.upx(6.0),
                    ctx.upx(4.0),
                    palette::INK.mix(0.75).stroke_width(ctx.upx(1.2).max(1)),
                ))?;
            }
        }
        for seg in &self.collapse {
            let color = palette::mechanism(&seg.mechanism);
            for piece in clip_polyline(&seg.points, window.0, window.1) {
                chart.draw_series(LineSeries::new(piece, color.stroke_width(ctx.upx(3.2))))?;
            }
        }
        for line in &self.gap_collapse {
            for piece in clip_polyline(line, window.0, window.1) {
                chart.draw_series(DashedLineSeries::new(
                    piece,
                    ctx.upx(8.0),
                    ctx.upx(5.0),
                    palette::GAP.stroke_width(ctx.upx(2.4)),
                ))?;
            }
        }
        Ok(())
    }
}

/// The t/R_c axis at the right edge, ticks at round values of t/R_c.
fn draw_t_axis<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &Chart<DB>,
    ctx: &PlotContext,
    ((_, mu1), (k0, k1)): Window,
    offset: i32,
) -> DrawResult<(), DB> {
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let (t0, t1) = (t_over_r_from_k(k0), t_over_r_from_k(k1));
    let (ticks, dec) = t_ticks(t0, t1);
    let x_axis = xr.end + offset;
    let tick_font = ctx.font(13.0).pos(Pos::new(HPos::Left, VPos::Center));
    root.draw(&PathElement::new(
        vec![(x_axis, yr.start), (x_axis, yr.end)],
        BLACK.stroke_width(ctx.upx(1.0).max(1)),
    ))?;
    for t in &ticks {
        let (_, py) = chart.backend_coord(&(mu1, k_from_t_over_r(*t)));
        root.draw(&PathElement::new(
            vec![(x_axis, py), (x_axis + ctx.px(5.0), py)],
            BLACK.stroke_width(ctx.upx(1.0).max(1)),
        ))?;
        root.draw(&Text::new(
            format!("{t:.dec$}"),
            (x_axis + ctx.px(8.0), py),
            tick_font.clone(),
        ))?;
    }
    let desc = ctx
        .font(14.0)
        .transform(FontTransform::Rotate90)
        .pos(Pos::new(HPos::Center, VPos::Bottom));
    root.draw(&Text::new(
        "thickness t/R_c".to_string(),
        (x_axis + ctx.px(72.0), (yr.start + yr.end) / 2),
        desc,
    ))
}

/// Width of the μ = ∞ strip and of the gap that separates it from the finite axis, design
/// pixels.
const STRIP_WIDTH: f64 = 30.0;
const STRIP_GAP: f64 = 16.0;

impl RegimeMap {
    /// The μ = ∞ column as a strip right of the plot, separated from the finite μ axis by a
    /// gap: its regimes along K (the raster's rows), its collapse points as thick ticks in
    /// the mechanism's colour, a frame and the label ∞ under it.
    fn draw_strip<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
        ((_, mu1), (k0, k1)): Window,
    ) -> DrawResult<(), DB> {
        let Some(strip) = &self.infinite else {
            return Ok(());
        };
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let (x0, x1) = (
            xr.end + ctx.px(STRIP_GAP),
            xr.end + ctx.px(STRIP_GAP + STRIP_WIDTH),
        );
        let y = |k: f64| chart.backend_coord(&(mu1, k)).1;
        let ny = ((f64::from(yr.end - yr.start) / ctx.scale / 2.0).ceil() as usize).max(2);
        let edge = |r: usize| k0 + (k1 - k0) * r as f64 / ny as f64;
        let mut r = 0;
        while r < ny {
            let name = strip.regime_at(&self.k, 0.5 * (edge(r) + edge(r + 1)));
            let start = r;
            while r < ny && strip.regime_at(&self.k, 0.5 * (edge(r) + edge(r + 1))) == name {
                r += 1;
            }
            if let Some(name) = name {
                root.draw(&Rectangle::new(
                    [(x0, y(edge(r))), (x1, y(edge(start)))],
                    palette::regime(name).filled(),
                ))?;
            }
        }
        for (k, mech) in strip.collapse.iter().filter(|c| c.0 >= k0 && c.0 <= k1) {
            root.draw(&PathElement::new(
                vec![(x0, y(*k)), (x1, y(*k))],
                palette::mechanism(mech).stroke_width(ctx.upx(3.2)),
            ))?;
        }
        let frame = BLACK.stroke_width(ctx.upx(1.0).max(1));
        root.draw(&Rectangle::new([(x0, yr.start), (x1, yr.end)], frame))?;
        root.draw(&Text::new(
            "∞".to_string(),
            ((x0 + x1) / 2, yr.end + ctx.px(8.0)),
            ctx.font(13.0).pos(Pos::new(HPos::Center, VPos::Top)),
        ))
    }
}

const REGIME_ORDER: [&str; 5] = ["stable", "rotational", "mixed", "sliding", "none"];

/// Ticks of t/R_c inside [t0, t1] at a nice step.
fn t_ticks(t0: f64, t1: f64) -> (Vec<f64>, usize) {
    let step = style::nice_step(t1 - t0, 6);
    let mut v = Vec::new();
    let mut t = (t0 / step).ceil() * step;
    while t <= t1 + 1e-12 {
        v.push(t);
        t += step;
    }
    (v, decimals_for(t1 - t0))
}

impl RegimeMap {
    fn legend(&self) -> Vec<LegendItem> {
        let mut items = Vec::new();
        for name in REGIME_ORDER {
            let strip = self.infinite.iter().flat_map(|s| s.regimes.iter());
            if self
                .regimes
                .iter()
                .chain(strip)
                .any(|r| r.as_deref() == Some(name))
            {
                let label = match name {
                    "none" => "none (no equilibrium)",
                    other => other,
                };
                items.push(LegendItem::new(label, Mark::Swatch(palette::regime(name))));
            }
        }
        for m in ["rotational", "mixed", "sliding"] {
            if self.collapse.iter().any(|s| s.mechanism == m) {
                items.push(LegendItem::new(
                    format!("{m} collapse"),
                    Mark::Line {
                        color: palette::mechanism(m),
                        width: 3.2,
                        dashed: false,
                    },
                ));
            }
        }
        if !self.gap_collapse.is_empty() {
            items.push(LegendItem::new(
                "collapse: first complete solution",
                Mark::Line {
                    color: palette::GAP,
                    width: 2.4,
                    dashed: true,
                },
            ));
        }
        if !self.other_boundaries.is_empty() {
            items.push(LegendItem::new(
                "other regime boundary",
                Mark::Line {
                    color: palette::INK,
                    width: 1.2,
                    dashed: true,
                },
            ));
        }
        if !self.bifurcations.is_empty() {
            items.push(LegendItem::new("bifurcation", Mark::Dot(palette::INK)));
        }
        items
    }
}
