//! The figures of a sampling study: curves with a confidence band (a fragility curve, a
//! probability against a grid axis, the error of an estimate against n on log axes), bars
//! with their intervals (the probability of each mechanism, Sobol indices), and the samples
//! over the (μ, K) plane with the collapse curve they are judged against.

use super::style::{self, LegendItem, Mark, above_legend, clip_polyline, decimals_for, palette};
use super::{Figure, PlotContext};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One curve of a panel, with an optional band.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// (x, y) points by increasing x (NaN breaks the line).
    pub points: Vec<(f64, f64)>,
    /// (x, lo, hi) of its band, by increasing x (empty: none).
    pub band: Vec<(f64, f64, f64)>,
    /// Colour.
    pub color: RGBColor,
    /// Dashed (a reference line) or solid.
    pub dashed: bool,
    /// Points joined by a line (false: dots alone, values known at those points only).
    pub line: bool,
    /// Points marked with dots.
    pub dots: bool,
}

/// One panel of curves.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvePanel {
    /// Panel title.
    pub title: String,
    /// x-axis description.
    pub x_desc: String,
    /// y-axis description.
    pub y_desc: String,
    /// The curves.
    pub curves: Vec<Curve>,
    /// Logarithmic axes (x, y).
    pub log: (bool, bool),
    /// A fixed y range (else the data's).
    pub y_range: Option<(f64, f64)>,
}

/// Curves with bands, one or more panels side by side, with a legend.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvesChart {
    /// Title.
    pub title: String,
    /// Panels.
    pub panels: Vec<CurvePanel>,
}

/// One bar with its interval.
#[derive(Debug, Clone, PartialEq)]
pub struct Bar {
    /// Legend label of its series.
    pub series: String,
    /// Value.
    pub value: f64,
    /// Interval (NaN: none).
    pub interval: (f64, f64),
    /// Colour.
    pub color: RGBColor,
}

/// Bars of one category, side by side.
#[derive(Debug, Clone, PartialEq)]
pub struct BarGroup {
    /// The category (a mechanism, a parameter).
    pub label: String,
    /// Its bars.
    pub bars: Vec<Bar>,
}

/// Horizontal bars with intervals, grouped by category.
#[derive(Debug, Clone, PartialEq)]
pub struct BarsChart {
    /// Title.
    pub title: String,
    /// Value axis description.
    pub x_desc: String,
    /// Categories, top to bottom.
    pub groups: Vec<BarGroup>,
    /// The value axis range.
    pub x_range: (f64, f64),
}

/// One sample in the (μ, K) plane.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleDot {
    /// μ.
    pub mu: f64,
    /// K.
    pub k: f64,
    /// `stable`, or the mechanism it fails by.
    pub outcome: String,
}

/// The samples over the plane of μ and K, with the collapse curve.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleMap {
    /// Title.
    pub title: String,
    /// The samples drawn.
    pub dots: Vec<SampleDot>,
    /// The collapse curve, per mechanism: (mechanism, points (μ, K)).
    pub curves: Vec<(String, Vec<(f64, f64)>)>,
    /// μ_min: below it no thickness stands.
    pub mu_min: Option<f64>,
    /// The samples are coloured by the mechanism of their largest load factor (`none`: they
    /// do not stand under their own weight), not by whether they stand.
    pub by_limit: bool,
    /// The y-axis description (K, or t/R_c).
    pub y_desc: String,
}

/// The window of a set of values with a margin; on a log axis, of their logarithms.
fn span(vals: impl Iterator<Item = f64>, log: bool) -> Option<(f64, f64)> {
    let (lo, hi) = vals
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .map(|v| if log { v.log10() } else { v })
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        return None;
    }
    let pad = if hi > lo { 0.04 * (hi - lo) } else { 0.5 };
    Some((lo - pad, hi + pad))
}

fn legend_of(panels: &[CurvePanel]) -> Vec<LegendItem> {
    let mut items: Vec<LegendItem> = Vec::new();
    for c in panels.iter().flat_map(|p| &p.curves) {
        if c.label.is_empty() || items.iter().any(|i| i.label == c.label) {
            continue;
        }
        let mark = if c.line {
            Mark::Line {
                color: c.color,
                width: 2.0,
                dashed: c.dashed,
            }
        } else {
            Mark::Dot(c.color)
        };
        items.push(LegendItem::new(c.label.clone(), mark));
    }
    let banded: Vec<RGBColor> = panels
        .iter()
        .flat_map(|p| &p.curves)
        .filter(|c| c.band.len() >= 2)
        .map(|c| c.color)
        .collect();
    if let Some(&c) = banded.first() {
        items.push(LegendItem::new(
            "95 % interval (shaded)",
            Mark::Swatch(style::over_white(c, 0.18)),
        ));
    }
    items
}

impl Figure for CurvesChart {
    fn size(&self) -> (u32, u32) {
        (440 * self.panels.len().max(1) as u32 + 60, 440)
    }

    fn panel_grid(&self) -> (usize, usize) {
        (1, self.panels.len().max(1))
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let area = style::title(root, ctx, &self.title)?;
        let area = above_legend(&area, ctx, &legend_of(&self.panels))?;
        let (rows, cols) = ctx.panel_grid(self.panel_grid());
        for (p, a) in self.panels.iter().zip(area.split_evenly((rows, cols))) {
            draw_curve_panel(&a, ctx, p)?;
        }
        Ok(())
    }
}

fn draw_curve_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    p: &CurvePanel,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (lx, ly) = p.log;
    let xs = p.curves.iter().flat_map(|c| c.points.iter().map(|q| q.0));
    let ys = p.curves.iter().flat_map(|c| {
        c.points
            .iter()
            .map(|q| q.1)
            .chain(c.band.iter().flat_map(|b| [b.1, b.2]))
    });
    let (Some((x0, x1)), Some((y0, y1))) = (
        span(xs, lx),
        p.y_range
            .map(|r| if ly { (r.0.log10(), r.1.log10()) } else { r })
            .or_else(|| span(ys, ly)),
    ) else {
        area.draw(&Text::new(
            "no values to draw".to_string(),
            (ctx.px(30.0), ctx.px(60.0)),
            ctx.font(14.0),
        ))?;
        return Ok(());
    };
    let tx = |v: f64| if lx { v.log10() } else { v };
    let ty = |v: f64| {
        if ly {
            if v > 0.0 { v.log10() } else { f64::NAN }
        } else {
            v
        }
    };
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, ctx.font(15.0))
        .margin(ctx.px(10.0))
        .margin_right(ctx.px(20.0))
        .x_label_area_size(ctx.px(48.0))
        .y_label_area_size(ctx.px(66.0))
        .build_cartesian_2d(x0..x1, y0..y1)?;
    super::draw_xy_axes(
        area,
        &mut chart,
        ctx,
        (&p.x_desc, &p.y_desc),
        (((x0, x1), (y0, y1)), (lx, ly)),
        6,
    )?;
    let t: Transforms = (&tx, &ty);
    draw_bands(&chart, p, t, (y0, y1))?;
    draw_lines(&mut chart, ctx, p, t, ((x0, x1), (y0, y1)))?;
    Ok(())
}

/// The transform of each axis (log10 on a logarithmic one).
type Transforms<'a> = (&'a dyn Fn(f64) -> f64, &'a dyn Fn(f64) -> f64);

/// The shaded band of each curve that has one.
fn draw_bands<DB: DrawingBackend>(
    chart: &super::XyChart<DB>,
    p: &CurvePanel,
    (tx, ty): Transforms,
    (y0, y1): (f64, f64),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    for c in &p.curves {
        if c.band.len() >= 2 {
            let upper = c.band.iter().map(|b| (tx(b.0), ty(b.2).clamp(y0, y1)));
            let lower = c
                .band
                .iter()
                .rev()
                .map(|b| (tx(b.0), ty(b.1).clamp(y0, y1)));
            let poly: Vec<(f64, f64)> = upper
                .chain(lower)
                .filter(|q| q.0.is_finite() && q.1.is_finite())
                .collect();
            chart
                .plotting_area()
                .draw(&Polygon::new(poly, c.color.mix(0.18).filled()))?;
        }
    }
    Ok(())
}

/// Each curve's line (clipped to the window) and dots.
fn draw_lines<DB: DrawingBackend>(
    chart: &mut super::XyChart<DB>,
    ctx: &PlotContext,
    p: &CurvePanel,
    (tx, ty): Transforms,
    ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    for c in &p.curves {
        let pts: Vec<(f64, f64)> = c.points.iter().map(|q| (tx(q.0), ty(q.1))).collect();
        let st = c
            .color
            .stroke_width(ctx.upx(if c.dashed { 1.4 } else { 2.0 }));
        let pieces = if c.line {
            clip_polyline(&pts, (x0, x1), (y0, y1))
        } else {
            Vec::new()
        };
        for piece in pieces {
            if c.dashed {
                chart.draw_series(DashedLineSeries::new(piece, ctx.upx(6.0), ctx.upx(4.0), st))?;
            } else {
                chart.draw_series(LineSeries::new(piece, st))?;
            }
        }
        if c.dots {
            chart.draw_series(
                pts.iter()
                    .filter(|q| q.0.is_finite() && q.1.is_finite() && q.1 >= y0 && q.1 <= y1)
                    .map(|&q| Circle::new(q, ctx.upx(3.0), c.color.filled())),
            )?;
        }
    }
    Ok(())
}

impl Figure for BarsChart {
    fn size(&self) -> (u32, u32) {
        let bars: usize = self.groups.iter().map(|g| g.bars.len().max(1)).sum();
        (
            720,
            (150 + 26 * bars + 14 * self.groups.len()).min(900) as u32,
        )
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let area = style::title(root, ctx, &self.title)?;
        let mut legend: Vec<LegendItem> = Vec::new();
        for b in self.groups.iter().flat_map(|g| &g.bars) {
            if !b.series.is_empty() && !legend.iter().any(|l| l.label == b.series) {
                legend.push(LegendItem::new(b.series.clone(), Mark::Swatch(b.color)));
            }
        }
        let area = if legend.len() > 1 {
            above_legend(&area, ctx, &legend)?
        } else {
            area
        };
        let slots: usize = self.groups.iter().map(|g| g.bars.len().max(1) + 1).sum();
        let (x0, x1) = self.x_range;
        let mut chart = ChartBuilder::on(&area)
            .margin(ctx.px(12.0))
            .margin_right(ctx.px(24.0))
            .x_label_area_size(ctx.px(46.0))
            .y_label_area_size(ctx.px(150.0))
            .build_cartesian_2d(x0..x1, 0.0..slots as f64)?;
        let fx = |v: &f64| format!("{:.*}", decimals_for(x1 - x0), v);
        chart
            .configure_mesh()
            .x_desc(self.x_desc.clone())
            .x_label_formatter(&fx)
            .y_labels(0)
            .x_labels(6)
            .label_style(ctx.font(12.5))
            .axis_desc_style(ctx.font(13.5))
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.08).stroke_width(1))
            .draw()?;
        let mut at = slots as f64;
        let label_font = ctx.font(13.0).pos(Pos::new(HPos::Right, VPos::Center));
        let value_font = ctx.font(11.0).pos(Pos::new(HPos::Left, VPos::Center));
        for g in &self.groups {
            let n = g.bars.len().max(1) as f64;
            let centre = at - 0.5 * n;
            let (px, py) = chart.backend_coord(&(x0, centre));
            area.draw(&Text::new(
                g.label.clone(),
                (px - ctx.px(10.0), py),
                label_font.clone(),
            ))?;
            for (i, b) in g.bars.iter().enumerate() {
                let top = at - i as f64 - 0.1;
                let bottom = at - i as f64 - 0.9;
                let v = if b.value.is_finite() {
                    b.value.clamp(x0, x1)
                } else {
                    x0
                };
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(x0.max(0.0).min(x1), bottom), (v, top)],
                    b.color.mix(0.85).filled(),
                )))?;
                let (lo, hi) = b.interval;
                if lo.is_finite() && hi.is_finite() {
                    let mid = 0.5 * (top + bottom);
                    let st = palette::INK.stroke_width(ctx.upx(1.4));
                    let (lo, hi) = (lo.clamp(x0, x1), hi.clamp(x0, x1));
                    chart.draw_series(LineSeries::new([(lo, mid), (hi, mid)], st))?;
                    for e in [lo, hi] {
                        chart
                            .draw_series(LineSeries::new([(e, mid - 0.25), (e, mid + 0.25)], st))?;
                    }
                }
                let end = if hi.is_finite() { hi.max(v).min(x1) } else { v };
                let (tx, ty) = chart.backend_coord(&(end, 0.5 * (top + bottom)));
                let text = if b.value.is_finite() {
                    format_value(b.value)
                } else {
                    "—".into()
                };
                area.draw(&Text::new(text, (tx + ctx.px(5.0), ty), value_font.clone()))?;
            }
            at -= n + 1.0;
        }
        Ok(())
    }
}

/// A value for a bar's label: three significant digits.
fn format_value(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 0.01 {
        format!("{v:.3}")
    } else {
        format!("{v:.2e}")
    }
}

/// The plotted ranges of μ and K (none without samples).
type Window = (Option<(f64, f64)>, Option<(f64, f64)>);

impl SampleMap {
    /// The legend: the samples' colours, the collapse curves and μ_min that fall in the
    /// plotted window.
    fn legend(&self, window: Window) -> Vec<LegendItem> {
        let mut legend = Vec::new();
        if !self.by_limit {
            legend.push(LegendItem::new("stands", Mark::Dot(palette::GREY)));
        }
        for m in ["rotational", "mixed", "sliding", "none"] {
            if self.dots.iter().any(|d| d.outcome == m) {
                let label = match (self.by_limit, m) {
                    (true, "none") => "no capacity (fails under its own weight)".to_string(),
                    (true, m) => format!("λ_max by {m} mechanism"),
                    (false, m) => format!("fails: {m}"),
                };
                legend.push(LegendItem::new(label, Mark::Dot(dot_color(m))));
            }
        }
        let inside = |(mu, k): (f64, f64)| match window {
            (Some((x0, x1)), Some((y0, y1))) => mu >= x0 && mu <= x1 && k >= y0 && k <= y1,
            _ => false,
        };
        for (m, _) in self
            .curves
            .iter()
            .filter(|(_, pts)| pts.iter().any(|&q| inside(q)))
        {
            legend.push(LegendItem::new(
                if self.by_limit {
                    format!("K_c(μ) under its own weight, {m}")
                } else {
                    format!("K_c(μ), {m}")
                },
                Mark::Line {
                    color: palette::mechanism(m),
                    width: 2.4,
                    dashed: false,
                },
            ));
        }
        let mu_min_shown = match (self.mu_min, window.0) {
            (Some(m), Some((x0, x1))) => m > x0 && m < x1,
            _ => false,
        };
        if mu_min_shown {
            legend.push(LegendItem::new(
                "μ_min",
                Mark::Line {
                    color: palette::SLIDING_LINE,
                    width: 1.6,
                    dashed: true,
                },
            ));
        }
        legend
    }
}

impl Figure for SampleMap {
    fn size(&self) -> (u32, u32) {
        (640, 520)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let area = style::title(root, ctx, &self.title)?;
        let window = (
            span(self.dots.iter().map(|d| d.mu), false),
            span(self.dots.iter().map(|d| d.k), false),
        );
        let legend = self.legend(window);
        let area = above_legend(&area, ctx, &legend)?;
        let (Some((x0, x1)), Some((y0, y1))) = (
            span(self.dots.iter().map(|d| d.mu), false),
            span(self.dots.iter().map(|d| d.k), false),
        ) else {
            return Ok(());
        };
        let mut chart = ChartBuilder::on(&area)
            .margin(ctx.px(12.0))
            .margin_right(ctx.px(20.0))
            .x_label_area_size(ctx.px(48.0))
            .y_label_area_size(ctx.px(66.0))
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let fx = |v: &f64| format!("{:.*}", decimals_for(x1 - x0), v);
        let fy = |v: &f64| format!("{:.*}", decimals_for(y1 - y0), v);
        chart
            .configure_mesh()
            .x_desc("friction coefficient μ")
            .y_desc(self.y_desc.clone())
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style(ctx.font(12.5))
            .axis_desc_style(ctx.font(13.5))
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.08).stroke_width(1))
            .draw()?;
        let r = if self.dots.len() > 1500 { 1.6 } else { 2.4 };
        // Standing samples first, so that the failing ones are never hidden under them.
        for pass in [true, false] {
            chart.draw_series(
                self.dots
                    .iter()
                    .filter(|d| (d.outcome == "stable") == pass)
                    .map(|d| {
                        Circle::new(
                            (d.mu, d.k),
                            ctx.upx(r),
                            dot_color(&d.outcome).mix(0.75).filled(),
                        )
                    }),
            )?;
        }
        if let Some(m) = self.mu_min.filter(|m| *m > x0 && *m < x1) {
            let st = palette::SLIDING_LINE.stroke_width(ctx.upx(1.6));
            chart.draw_series(DashedLineSeries::new(
                [(m, y0), (m, y1)],
                ctx.upx(6.0),
                ctx.upx(4.0),
                st,
            ))?;
        }
        for (m, pts) in &self.curves {
            let st = palette::mechanism(m).stroke_width(ctx.upx(2.4));
            for piece in clip_polyline(pts, (x0, x1), (y0, y1)) {
                chart.draw_series(LineSeries::new(piece, st))?;
            }
        }
        Ok(())
    }
}

fn dot_color(outcome: &str) -> RGBColor {
    match outcome {
        "stable" => palette::GREY,
        "none" => palette::INK,
        m => palette::mechanism(m),
    }
}
