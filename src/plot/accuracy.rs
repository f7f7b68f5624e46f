//! Figure 5: speed against accuracy when a study varies the voussoir count: the error of each
//! critical value against the continuum value, against N and against solve time (log-log).

use super::style::{self, LegendItem, Mark, palette};
use super::{Figure, PlotContext};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One compared quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracySeries {
    /// Legend text, e.g. `K_c, μ = inf`.
    pub label: String,
    /// (voussoir count, |error|), errors > 0 only.
    pub by_count: Vec<(f64, f64)>,
    /// (median solve time in µs, |error|), errors > 0 only.
    pub by_time: Vec<(f64, f64)>,
}

/// What the accuracy figure shows.
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyChart {
    /// Title.
    pub title: String,
    /// The series.
    pub series: Vec<AccuracySeries>,
    /// Median solve time of the continuum analyses, µs, with the label of its line (one per
    /// find of the study).
    pub continuum_times: Vec<(f64, String)>,
}

const COLORS: [RGBColor; 6] = [
    palette::BLUE,
    palette::RED,
    palette::GREEN,
    palette::PURPLE,
    palette::ORANGE,
    palette::SKY,
];

fn log_range(v: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = v
        .filter(|x| x.is_finite() && *x > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    if lo > hi {
        return None;
    }
    let lo = 10f64.powf(lo.log10().floor());
    let hi = 10f64.powf(hi.log10().ceil());
    Some(if lo == hi {
        (lo / 10.0, hi * 10.0)
    } else {
        (lo, hi)
    })
}

#[allow(clippy::too_many_arguments)]
fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    title: &str,
    x_desc: &str,
    series: &[(String, Vec<(f64, f64)>)],
    vlines: &[(f64, String)],
    joined: bool,
) -> DrawResult<(), DB> {
    let xs = series
        .iter()
        .flat_map(|s| s.1.iter().map(|p| p.0))
        .chain(vlines.iter().map(|v| v.0));
    let ys = series.iter().flat_map(|s| s.1.iter().map(|p| p.1));
    let (Some((x0, x1)), Some((y0, y1))) = (log_range(xs), log_range(ys)) else {
        area.draw(&Text::new(
            "all errors are zero or missing".to_string(),
            (ctx.px(30.0), ctx.px(60.0)),
            ctx.font(14.0),
        ))?;
        return Ok(());
    };
    let mut chart = ChartBuilder::on(area)
        .caption(title, ctx.font(15.0))
        .margin(ctx.px(10.0))
        .margin_right(ctx.px(24.0))
        .x_label_area_size(ctx.px(48.0))
        .y_label_area_size(ctx.px(66.0))
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    // Both axes are ticked by `style::log_ticks`, not at plotters' key points.
    let none = |_: &f64| String::new();
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("|error| against the continuum")
        .x_label_formatter(&none)
        .y_label_formatter(&none)
        .label_style(ctx.font(12.5))
        .axis_desc_style(ctx.font(13.5))
        .set_all_tick_mark_size(0)
        .light_line_style(TRANSPARENT)
        .bold_line_style(TRANSPARENT)
        .draw()?;
    let plot = chart.plotting_area().get_pixel_range();
    let xt = style::placed_log_ticks((x0, x1), |v| chart.backend_coord(&(v, y0)).0, ctx, true);
    let yt = style::placed_log_ticks((y0, y1), |v| chart.backend_coord(&(x0, v)).1, ctx, false);
    style::draw_ticks(area, ctx, plot.clone(), style::AxisSide::Bottom, &xt)?;
    style::draw_ticks(area, ctx, plot.clone(), style::AxisSide::Left, &yt)?;
    // Labels stacked from the top so that lines close together keep readable labels.
    for (i, (x, label)) in vlines.iter().enumerate() {
        let x = *x;
        chart.draw_series(DashedLineSeries::new(
            [(x, y0), (x, y1)],
            ctx.upx(6.0),
            ctx.upx(4.0),
            palette::GREY.stroke_width(ctx.upx(1.5)),
        ))?;
        let c = chart.backend_coord(&(x, y1));
        let font = ctx.font(12.0).color(&palette::GREY);
        let (w, _) = style::text_block_size(&font, std::slice::from_ref(label), 1.0);
        // Right of its line, or left of it where the label would leave the plot.
        let right = c.0 + ctx.px(4.0) + w <= plot.0.end;
        let (x_at, anchor) = if right {
            (c.0 + ctx.px(4.0), HPos::Left)
        } else {
            (c.0 - ctx.px(4.0), HPos::Right)
        };
        area.draw(&Text::new(
            label.to_string(),
            (
                x_at - area.get_base_pixel().0,
                c.1 - area.get_base_pixel().1 + ctx.px(4.0 + 16.0 * i as f64),
            ),
            font.pos(Pos::new(anchor, VPos::Top)),
        ))?;
    }
    for (i, (_, pts)) in series.iter().enumerate() {
        let c = COLORS[i % COLORS.len()];
        if joined {
            chart.draw_series(LineSeries::new(pts.clone(), c.stroke_width(ctx.upx(2.0))))?;
        }
        chart.draw_series(
            pts.iter()
                .map(|&p| Circle::new(p, ctx.upx(3.5), c.filled())),
        )?;
    }
    Ok(())
}

impl Figure for AccuracyChart {
    fn size(&self) -> (u32, u32) {
        (1000, 500)
    }

    fn panel_grid(&self) -> (usize, usize) {
        (1, 2)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let legend = self.legend();
        let upper = style::above_legend(root, ctx, &legend)?;
        let upper = style::title(&upper, ctx, &self.title)?;
        let areas = upper.split_evenly(ctx.panel_grid((1, 2)));
        let by_n: Vec<(String, Vec<(f64, f64)>)> = self
            .series
            .iter()
            .map(|s| (s.label.clone(), s.by_count.clone()))
            .collect();
        let by_t: Vec<(String, Vec<(f64, f64)>)> = self
            .series
            .iter()
            .map(|s| (s.label.clone(), s.by_time.clone()))
            .collect();
        panel(
            &areas[0],
            ctx,
            "(a) error against voussoir count",
            "voussoirs N",
            &by_n,
            &[],
            true,
        )?;
        panel(
            &areas[1],
            ctx,
            "(b) error against solve time",
            "median solve time per case (µs)",
            &by_t,
            &self.continuum_times,
            false,
        )?;
        Ok(())
    }
}

impl AccuracyChart {
    fn legend(&self) -> Vec<LegendItem> {
        let mut items: Vec<LegendItem> = self
            .series
            .iter()
            .enumerate()
            .map(|(i, s)| {
                LegendItem::new(
                    s.label.clone(),
                    Mark::Line {
                        color: COLORS[i % COLORS.len()],
                        width: 2.0,
                        dashed: false,
                    },
                )
            })
            .collect();
        if !self.continuum_times.is_empty() {
            items.push(LegendItem::new(
                "continuum solve time (error 0)",
                Mark::Line {
                    color: palette::GREY,
                    width: 1.5,
                    dashed: true,
                },
            ));
        }
        items
    }
}
