//! Figure 2 (the paper's Fig. 2): against the joint angle, the thrust bounds of eqs. 2a/2b
//! with the crown thrust at the crown extrados and at the crown intrados, the bounds of
//! eqs. 4a/4b, and the domains H^r, H^s and their intersection as shaded bands.

use super::style::{self, LabelPlacer, LegendItem, Mark, clip_polyline, decimals_for, palette};
use super::{Figure, PlotContext, Window, XyChart as Chart};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Which family of bounds a curve belongs to (sets its colour).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoundFamily {
    /// Eqs. 2a/2b with the crown thrust at the crown extrados.
    CrownExtrados,
    /// Eqs. 2a/2b with the crown thrust at the crown intrados.
    CrownIntrados,
    /// Eqs. 4a/4b.
    Sliding,
}

impl BoundFamily {
    fn color(self) -> RGBColor {
        match self {
            BoundFamily::CrownExtrados => palette::RED,
            BoundFamily::CrownIntrados => palette::PURPLE,
            BoundFamily::Sliding => palette::BLUE,
        }
    }
}

/// One bound against the joint angle.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundCurve {
    /// Legend text.
    pub label: String,
    /// Points (θ in degrees, H/W_half); NaN where the bound does not exist.
    pub points: Vec<(f64, f64)>,
    /// Family (colour).
    pub family: BoundFamily,
    /// An upper bound (dashed) or a lower bound (solid).
    pub upper: bool,
}

/// What the domains figure shows.
#[derive(Debug, Clone, PartialEq)]
pub struct DomainsChart {
    /// Title.
    pub title: String,
    /// Half-embrace angle, degrees (the x range).
    pub alpha_deg: f64,
    /// The six bounds.
    pub curves: Vec<BoundCurve>,
    /// H^r (ends may be infinite), if not empty.
    pub h_r: Option<(f64, f64)>,
    /// H^s (ends may be infinite), if not empty.
    pub h_s: Option<(f64, f64)>,
    /// True for a discrete arch: bounds exist at the joints only (drawn as markers).
    pub discrete: bool,
    /// Crown thrusts marked across the figure (e.g. those of the states drawn beside it),
    /// each with its label.
    pub marks: Vec<(f64, String)>,
}

const R_ALPHA: f64 = 0.16;
const S_ALPHA: f64 = 0.20;
const BOTH_ALPHA: f64 = 0.30;

fn y_top(c: &DomainsChart) -> f64 {
    let ends = [c.h_r, c.h_s]
        .into_iter()
        .flatten()
        .flat_map(|(a, b)| [a, b])
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    let top = if ends > 0.0 { 1.6 * ends } else { 1.0 };
    let step = style::nice_step(top, 5);
    (top / step).ceil() * step
}

impl Figure for DomainsChart {
    fn size(&self) -> (u32, u32) {
        (820, 600)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let legend = self.legend();
        let upper = style::above_legend(root, ctx, &legend)?;
        let w = ((0.0, self.alpha_deg), (0.0, y_top(self)));
        let ((x0, x1), (y0, y1)) = w;
        let mut builder = ChartBuilder::on(&upper);
        if ctx.titles {
            builder.caption(&self.title, ctx.font(17.0));
        }
        let mut chart = builder
            .margin(ctx.px(10.0))
            .x_label_area_size(ctx.px(50.0))
            .y_label_area_size(ctx.px(72.0))
            .margin_right(ctx.px(120.0))
            .build_cartesian_2d(x0..x1, y0..y1)?;
        // Bands first, under everything.
        self.draw_bands(&mut chart, ctx, w)?;
        draw_mesh(&mut chart, ctx, w)?;
        self.draw_curves(&mut chart, ctx, w)?;
        self.draw_marks(root, &chart, ctx, w)?;
        self.draw_brackets(root, &chart, ctx, w)
    }
}

impl DomainsChart {
    /// The domains as shaded bands: Hʳ, Hˢ and their intersection, edged.
    fn draw_bands<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<DB>,
        ctx: &PlotContext,
        ((x0, x1), (y0, y1)): Window,
    ) -> DrawResult<(), DB> {
        let clamp = |v: f64| v.clamp(y0, y1);
        let band = |r: (f64, f64), c: RGBColor, a: f64| {
            Rectangle::new([(x0, clamp(r.0)), (x1, clamp(r.1))], c.mix(a).filled())
        };
        if let Some(r) = self.h_r {
            chart.draw_series([band(r, palette::ORANGE, R_ALPHA)])?;
        }
        if let Some(s) = self.h_s {
            chart.draw_series([band(s, palette::SKY, S_ALPHA)])?;
        }
        if let Some(b) = self.intersection() {
            chart.draw_series([band(b, palette::GREEN, BOTH_ALPHA)])?;
            for y in [b.0, b.1] {
                if y.is_finite() && y >= y0 && y <= y1 {
                    chart.draw_series(LineSeries::new(
                        [(x0, y), (x1, y)],
                        palette::GREEN.stroke_width(ctx.upx(1.5)),
                    ))?;
                }
            }
        }
        Ok(())
    }

    /// The marked thrusts: dashed black lines across, each labelled at its left end.
    fn draw_marks<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
        ((x0, x1), (y0, y1)): Window,
    ) -> DrawResult<(), DB> {
        let font = ctx.font(12.5).pos(Pos::new(HPos::Left, VPos::Bottom));
        for (h, label) in &self.marks {
            if !(h.is_finite() && (y0..=y1).contains(h)) {
                continue;
            }
            let (a, b) = (
                chart.backend_coord(&(x0, *h)),
                chart.backend_coord(&(x1, *h)),
            );
            root.draw(&plotters::element::DashedPathElement::new(
                vec![a, b],
                ctx.upx(5.0),
                ctx.upx(3.0),
                palette::INK.stroke_width(ctx.upx(1.4)),
            ))?;
            root.draw(&Text::new(
                label.clone(),
                (a.0 + ctx.px(6.0), a.1 - ctx.px(3.0)),
                font.clone(),
            ))?;
        }
        Ok(())
    }

    /// The bounds against θ: lower bounds solid, upper bounds dashed, with dots at the
    /// joints of a discrete arch.
    fn draw_curves<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<DB>,
        ctx: &PlotContext,
        ((x0, x1), (y0, y1)): Window,
    ) -> DrawResult<(), DB> {
        for c in &self.curves {
            let color = c.family.color();
            let st = color.stroke_width(ctx.upx(2.0));
            for piece in clip_polyline(&c.points, (x0, x1), (y0, y1)) {
                if c.upper {
                    chart.draw_series(DashedLineSeries::new(
                        piece.clone(),
                        ctx.upx(7.0),
                        ctx.upx(4.0),
                        st,
                    ))?;
                } else {
                    chart.draw_series(LineSeries::new(piece.clone(), st))?;
                }
                if self.discrete {
                    chart.draw_series(
                        piece
                            .iter()
                            .map(|&p| Circle::new(p, ctx.upx(2.5), color.filled())),
                    )?;
                }
            }
        }
        Ok(())
    }

    /// Brackets at the right: which thrusts each domain admits, labelled in one column right
    /// of all brackets, each label at its bracket's middle.
    fn draw_brackets<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
        ((_, x1), (y0, y1)): Window,
    ) -> DrawResult<(), DB> {
        let clamp = |v: f64| v.clamp(y0, y1);
        let (w, _) = ctx.pixels();
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let mut placer = LabelPlacer::new((xr.end, yr.start, w as i32, yr.end));
        let brackets = [
            (self.h_r, "Hʳ", palette::ORANGE, 12.0),
            (self.h_s, "Hˢ", palette::SKY, 28.0),
            (self.intersection(), "Hʳ ∩ Hˢ", palette::GREEN, 44.0),
        ];
        let font = ctx.font(13.0).pos(Pos::new(HPos::Left, VPos::Center));
        let label_x = xr.end + ctx.px(60.0);
        for (range, label, color, off) in brackets {
            let Some((a, b)) = range else { continue };
            let ya = chart.backend_coord(&(x1, clamp(a))).1;
            let yb = chart.backend_coord(&(x1, clamp(b))).1;
            let x = xr.end + ctx.px(off);
            let tick = ctx.px(5.0);
            let st = color.stroke_width(ctx.upx(3.0));
            root.draw(&PathElement::new(
                vec![(x - tick, ya), (x, ya), (x, yb), (x - tick, yb)],
                st,
            ))?;
            let (tw, th) = style::text_block_size(&font, &[label.to_string()], 1.5);
            let mid = (ya + yb) / 2;
            let at = placer.place(
                tw,
                th,
                &[
                    (label_x, mid - th / 2),
                    (label_x, mid - th / 2 - th),
                    (label_x, mid + th / 2),
                    (label_x, mid - th / 2 - 2 * th),
                    (label_x, mid + th / 2 + th),
                ],
            );
            root.draw(&Text::new(
                label.to_string(),
                (at.0, at.1 + th / 2),
                font.color(&color.mix(1.0)),
            ))?;
        }
        Ok(())
    }
}

/// The axes and the grid lines of θ and H/W_half.
fn draw_mesh<DB: DrawingBackend>(
    chart: &mut Chart<DB>,
    ctx: &PlotContext,
    ((_, _), (y0, y1)): Window,
) -> DrawResult<(), DB> {
    let fx = |v: &f64| format!("{v:.0}");
    let fy = |v: &f64| format!("{:.*}", decimals_for(y1 - y0), v);
    chart
        .configure_mesh()
        .x_desc("joint angle θ from the crown (degrees)")
        .y_desc("crown thrust H / W_half")
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style(ctx.font(13.0))
        .axis_desc_style(ctx.font(14.0))
        .set_all_tick_mark_size(ctx.px(5.0))
        .light_line_style(TRANSPARENT)
        .bold_line_style(BLACK.mix(0.08).stroke_width(1))
        .draw()
}

impl DomainsChart {
    /// H^r ∩ H^s when not empty.
    fn intersection(&self) -> Option<(f64, f64)> {
        match (self.h_r, self.h_s) {
            (Some(r), Some(s)) if r.0.max(s.0) <= r.1.min(s.1) => {
                Some((r.0.max(s.0), r.1.min(s.1)))
            }
            _ => None,
        }
    }

    fn legend(&self) -> Vec<LegendItem> {
        let mut items: Vec<LegendItem> = self
            .curves
            .iter()
            .map(|c| {
                LegendItem::new(
                    c.label.clone(),
                    Mark::Line {
                        color: c.family.color(),
                        width: 2.0,
                        dashed: c.upper,
                    },
                )
            })
            .collect();
        let r = style::over_white(palette::ORANGE, R_ALPHA);
        let s = style::over_white(palette::SKY, S_ALPHA);
        let both = style::over(palette::GREEN, BOTH_ALPHA, style::over(s, 1.0, r));
        if self.h_r.is_some() {
            items.push(LegendItem::new("Hʳ", Mark::Swatch(r)));
        }
        if self.h_s.is_some() {
            items.push(LegendItem::new("Hˢ", Mark::Swatch(s)));
        }
        if self.intersection().is_some() {
            items.push(LegendItem::new("Hʳ ∩ Hˢ", Mark::Swatch(both)));
        }
        items
    }
}
