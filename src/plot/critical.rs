//! Figure 4: the critical curves K_c(μ) and μ_c(K), side by side, with the bifurcation
//! points and, for the paper's case, the paper's printed values as markers.

use super::style::{self, LabelPlacer, LegendItem, Mark, clip_polyline, decimals_for, palette};
use super::{Figure, PlotContext, XyChart};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// A marked point with a short label.
#[derive(Debug, Clone, PartialEq)]
pub struct PointMark {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// Label (already formatted), may be empty.
    pub label: String,
}

/// One panel: a curve against one parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct CriticalPanel {
    /// Panel title.
    pub title: String,
    /// x-axis description with unit or normalisation.
    pub x_desc: String,
    /// y-axis description.
    pub y_desc: String,
    /// The curve; NaN breaks it.
    pub curve: Vec<(f64, f64)>,
    /// Computed bifurcation points.
    pub bifurcations: Vec<PointMark>,
    /// The paper's printed values.
    pub paper: Vec<PointMark>,
    /// The top of the y axis when the curve rises beyond the range the study covers (it
    /// then runs off the top of the panel); `None` fits the axis to the curve.
    pub y_max: Option<f64>,
    /// Every interval of y in which the arch stands at each x, (x, from, to), shaded: the
    /// windows of K of a thickness find (`to` infinite for a window open at the end of the
    /// scan). Empty when the panel has none.
    pub windows: Vec<(f64, f64, f64)>,
    /// The collapse along the same path, the first complete solution (NaN breaks it), drawn
    /// dashed where it parts from the curve: the non-associative gap. Empty when the study
    /// has no gap.
    pub collapse: Vec<(f64, f64)>,
}

/// The shaded columns of the windows: each x spans half-way to its neighbours.
fn window_columns(windows: &[(f64, f64, f64)]) -> Vec<(f64, f64, f64, f64)> {
    let mut xs: Vec<f64> = windows.iter().map(|w| w.0).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let half = |i: usize| -> (f64, f64) {
        let left = if i > 0 { xs[i - 1] } else { f64::NAN };
        let right = if i + 1 < xs.len() {
            xs[i + 1]
        } else {
            f64::NAN
        };
        let lw = if left.is_nan() {
            right - xs[i]
        } else {
            xs[i] - left
        };
        let rw = if right.is_nan() {
            xs[i] - left
        } else {
            right - xs[i]
        };
        let (lw, rw) = (lw.max(0.0), rw.max(0.0));
        (xs[i] - lw / 2.0, xs[i] + rw / 2.0)
    };
    windows
        .iter()
        .filter_map(|&(x, a, b)| {
            let i = xs.iter().position(|v| *v == x)?;
            let (x0, x1) = if xs.len() == 1 { (x, x) } else { half(i) };
            Some((x0, x1, a, b))
        })
        .collect()
}

/// What the critical-curves figure shows.
#[derive(Debug, Clone, PartialEq)]
pub struct CriticalChart {
    /// Title.
    pub title: String,
    /// One or two panels.
    pub panels: Vec<CriticalPanel>,
}

fn range(vals: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = vals
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        None
    } else if lo == hi {
        Some((lo - 0.5 * lo.abs().max(1e-3), hi + 0.5 * hi.abs().max(1e-3)))
    } else {
        Some((lo, hi))
    }
}

fn panel_ranges(p: &CriticalPanel) -> Option<((f64, f64), (f64, f64))> {
    let marks = || p.bifurcations.iter().chain(&p.paper);
    let xs = p
        .curve
        .iter()
        .filter(|q| q.1.is_finite())
        .map(|q| q.0)
        .chain(marks().map(|m| m.x));
    let all_x = p.curve.iter().map(|q| q.0).chain(marks().map(|m| m.x));
    let ends = p.windows.iter().flat_map(|w| [w.1, w.2]);
    let ys = p
        .curve
        .iter()
        .chain(&p.collapse)
        .map(|q| q.1)
        .chain(marks().map(|m| m.y))
        .chain(ends);
    let (x0, x1) = range(all_x).or_else(|| range(xs))?;
    let (y0, y1) = range(ys)?;
    let y1 = p.y_max.filter(|&m| m > y0).map_or(y1, |m| y1.min(m));
    let pad = 0.08 * (y1 - y0);
    Some(((x0, x1), (y0 - pad, y1 + pad)))
}

/// One panel: its curve, axes and marks, or a note when it has nothing to show.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    root: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    p: &CriticalPanel,
) -> DrawResult<(), DB> {
    let Some(((x0, x1), (y0, y1))) = panel_ranges(p) else {
        area.draw(&Text::new(
            "no critical values in this study".to_string(),
            (ctx.px(30.0), ctx.px(60.0)),
            ctx.font(14.0),
        ))?;
        return Ok(());
    };
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, ctx.font(15.0))
        .margin(ctx.px(10.0))
        .margin_right(ctx.px(24.0))
        .x_label_area_size(ctx.px(48.0))
        .y_label_area_size(ctx.px(66.0))
        .build_cartesian_2d(x0..x1, y0..y1)?;
    let fx = |v: &f64| format!("{:.*}", decimals_for(x1 - x0), v);
    let fy = |v: &f64| format!("{:.*}", decimals_for(y1 - y0), v);
    chart
        .configure_mesh()
        .x_desc(p.x_desc.clone())
        .y_desc(p.y_desc.clone())
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .x_labels(6)
        .y_labels(7)
        .label_style(ctx.font(12.5))
        .axis_desc_style(ctx.font(13.5))
        .set_all_tick_mark_size(ctx.px(5.0))
        .light_line_style(TRANSPARENT)
        .bold_line_style(BLACK.mix(0.08).stroke_width(1))
        .draw()?;
    for (a, b, lo, hi) in window_columns(&p.windows) {
        let (a, b) = (a.max(x0), b.min(x1));
        let (lo, hi) = (lo.max(y0), hi.min(y1));
        if b >= a && hi > lo {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(a, lo), (b, hi)],
                palette::STABLE_WINDOW.filled(),
            )))?;
        }
    }
    for piece in clip_polyline(&p.curve, (x0, x1), (y0, y1)) {
        chart.draw_series(LineSeries::new(
            piece,
            palette::INK.stroke_width(ctx.upx(2.2)),
        ))?;
    }
    for piece in clip_polyline(&p.collapse, (x0, x1), (y0, y1)) {
        chart.draw_series(DashedLineSeries::new(
            piece,
            ctx.upx(7.0),
            ctx.upx(4.0),
            palette::GAP.stroke_width(ctx.upx(2.0)),
        ))?;
    }
    draw_marks(root, &chart, ctx, p)
}

/// The bifurcations (dots) and the paper's values (diamonds), with their labels placed
/// off the markers.
fn draw_marks<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &XyChart<DB>,
    ctx: &PlotContext,
    p: &CriticalPanel,
) -> DrawResult<(), DB> {
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let mut placer = LabelPlacer::new((
        xr.start + ctx.px(3.0),
        yr.start + ctx.px(3.0),
        xr.end - ctx.px(3.0),
        yr.end - ctx.px(3.0),
    ));
    let all: Vec<(&PointMark, bool)> = p
        .bifurcations
        .iter()
        .map(|m| (m, false))
        .chain(p.paper.iter().map(|m| (m, true)))
        .collect();
    for (m, _) in &all {
        let c = chart.backend_coord(&(m.x, m.y));
        let r = ctx.px(8.0);
        placer.block((c.0 - r, c.1 - r, c.0 + r, c.1 + r));
    }
    let font = ctx.font(12.0);
    for (m, paper) in &all {
        let c = chart.backend_coord(&(m.x, m.y));
        if *paper {
            style::diamond(root, ctx, c, 7.0, palette::RED)?;
        } else {
            style::dot(root, ctx, c, 4.5, palette::INK)?;
        }
        if m.label.is_empty() {
            continue;
        }
        let (tw, th) = style::text_block_size(&font, std::slice::from_ref(&m.label), 1.0);
        let g = ctx.px(10.0);
        let cands = if *paper {
            [
                (c.0 + g, c.1 + g / 2),
                (c.0 - tw - g, c.1 + g / 2),
                (c.0 + g, c.1 - th - g / 2),
                (c.0 - tw - g, c.1 - th - g / 2),
                (c.0 + g, c.1 + 2 * g),
                (c.0 - tw / 2, c.1 + 2 * g),
            ]
        } else {
            [
                (c.0 + g, c.1 - th - g / 2),
                (c.0 - tw - g, c.1 - th - g / 2),
                (c.0 + g, c.1 + g / 2),
                (c.0 - tw - g, c.1 + g / 2),
                (c.0 + g, c.1 - th - 2 * g),
                (c.0 - tw / 2, c.1 - th - 2 * g),
            ]
        };
        let at = placer.place(tw, th, &cands);
        let color = if *paper { palette::RED } else { palette::INK };
        root.draw(&Text::new(
            m.label.clone(),
            at,
            font.color(&color).pos(Pos::new(HPos::Left, VPos::Top)),
        ))?;
    }
    Ok(())
}

impl Figure for CriticalChart {
    fn size(&self) -> (u32, u32) {
        if self.panels.len() > 1 {
            (1000, 520)
        } else {
            (820, 560)
        }
    }

    fn panel_grid(&self) -> (usize, usize) {
        (1, self.panels.len().max(1))
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let areas = style::panel_areas(root, ctx, &self.legend(), &self.title, self.panels.len())?;
        for (a, p) in areas.iter().zip(&self.panels) {
            draw_panel(a, root, ctx, p)?;
        }
        Ok(())
    }
}

impl CriticalChart {
    fn legend(&self) -> Vec<LegendItem> {
        let mut items = vec![LegendItem::new(
            "critical curve",
            Mark::Line {
                color: palette::INK,
                width: 2.2,
                dashed: false,
            },
        )];
        if self.panels.iter().any(|p| !p.collapse.is_empty()) {
            items.push(LegendItem::new(
                "collapse: first complete solution",
                Mark::Line {
                    color: palette::GAP,
                    width: 2.0,
                    dashed: true,
                },
            ));
        }
        if self.panels.iter().any(|p| !p.windows.is_empty()) {
            items.push(LegendItem::new(
                "K at which the arch stands",
                Mark::Swatch(palette::STABLE_WINDOW),
            ));
        }
        if self.panels.iter().any(|p| !p.bifurcations.is_empty()) {
            items.push(LegendItem::new(
                "bifurcation (this run)",
                Mark::Dot(palette::INK),
            ));
        }
        if self.panels.iter().any(|p| !p.paper.is_empty()) {
            items.push(LegendItem::new(
                "value printed in the paper",
                Mark::Diamond(palette::RED),
            ));
        }
        items
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn panel(y_max: Option<f64>) -> CriticalPanel {
        CriticalPanel {
            title: String::new(),
            x_desc: String::new(),
            y_desc: String::new(),
            // K_c(μ) of a pointed arch: 8.4 at low friction, 1.07 beyond the bifurcations.
            curve: vec![
                (0.15, 8.4),
                (0.25, 5.9),
                (0.26, 1.15),
                (0.32, 1.07),
                (0.8, 1.07),
            ],
            bifurcations: vec![PointMark {
                x: 0.26,
                y: 1.15,
                label: String::new(),
            }],
            paper: Vec::new(),
            y_max,
            windows: Vec::new(),
            collapse: Vec::new(),
        }
    }

    #[test]
    fn the_y_axis_stops_at_the_studys_range_and_is_fitted_otherwise() {
        let ((x0, x1), (y0, y1)) = panel_ranges(&panel(Some(1.4))).unwrap();
        assert_eq!((x0, x1), (0.15, 0.8));
        let pad = 0.08 * (1.4 - 1.07);
        assert!((y0 - (1.07 - pad)).abs() < 1e-12 && (y1 - (1.4 + pad)).abs() < 1e-12);
        let (_, (_, y1)) = panel_ranges(&panel(None)).unwrap();
        assert!((y1 - (8.4 + 0.08 * (8.4 - 1.07))).abs() < 1e-12);
        // Closed window ends widen the axis; open ones (infinite) do not.
        let mut w = panel(None);
        w.windows = vec![(0.5, 1.07, 1.2), (0.5, 9.5, f64::INFINITY)];
        let (_, (_, y1)) = panel_ranges(&w).unwrap();
        assert!((y1 - (9.5 + 0.08 * (9.5 - 1.07))).abs() < 1e-12);
        // A bound below the whole curve is ignored rather than emptying the panel.
        let (_, (_, y1)) = panel_ranges(&panel(Some(1.0))).unwrap();
        assert!(y1 > 8.4);
    }
}

#[cfg(test)]
mod window_tests {
    use super::window_columns;

    #[test]
    fn each_window_spans_half_way_to_its_neighbours() {
        let w = [(0.2, 1.5, 1.6), (0.4, 1.4, f64::INFINITY), (0.8, 1.3, 2.0)];
        let c = window_columns(&w);
        assert_eq!(c[0], (0.1, 0.30000000000000004, 1.5, 1.6));
        assert_eq!(
            c[1],
            (0.30000000000000004, 0.6000000000000001, 1.4, f64::INFINITY)
        );
        assert_eq!(c[2], (0.6000000000000001, 1.0, 1.3, 2.0));
    }
}
