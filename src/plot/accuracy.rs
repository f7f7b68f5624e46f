//! Figure 5: speed against accuracy when a study varies the voussoir count: the error of each
//! critical value against the continuum value, against N and against solve time (log-log).

use super::style::{self, LegendItem, Mark, palette};
use super::{Figure, PlotContext};
use plotters::coord::Shift;
use plotters::prelude::*;

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

/// Tick labels at powers of ten only (the other ticks stay unlabelled).
fn sci(v: f64) -> String {
    let e = v.log10().round() as i32;
    if (v / 10f64.powi(e) - 1.0).abs() < 1e-9 {
        format!("1e{e}")
    } else {
        String::new()
    }
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
    let f = |v: &f64| sci(*v);
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("|error| against the continuum")
        .x_label_formatter(&f)
        .y_label_formatter(&f)
        .label_style(ctx.font(12.5))
        .axis_desc_style(ctx.font(13.5))
        .set_all_tick_mark_size(ctx.px(5.0))
        .light_line_style(BLACK.mix(0.04))
        .bold_line_style(BLACK.mix(0.10).stroke_width(1))
        .draw()?;
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
        area.draw(&Text::new(
            label.to_string(),
            (
                c.0 - area.get_base_pixel().0 + ctx.px(4.0),
                c.1 - area.get_base_pixel().1 + ctx.px(4.0 + 16.0 * i as f64),
            ),
            ctx.font(12.0).color(&palette::GREY),
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
