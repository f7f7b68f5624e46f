//! Figure 3 (the paper's Figs. 6 and 7): a state of the arch drawn to scale (equal scales in
//! x and y): the voussoirs when discrete, the line of thrust, hinges as dots on the intrados
//! or extrados and sliding joints with an arrow giving the sense of the crown-side part.

use super::style::{self, LabelPlacer, LegendItem, Mark, palette};
use super::{Figure, PlotContext, Window, XyChart as Chart};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// What a state drawing shows. Lengths over the intrados radius r.
#[derive(Debug, Clone, PartialEq)]
pub struct StateDrawing {
    /// Title.
    pub title: String,
    /// Lines under the title (values, already formatted).
    pub subtitle: Vec<String>,
    /// K = R/r.
    pub k: f64,
    /// Half-embrace angle, degrees.
    pub alpha_deg: f64,
    /// Joints between voussoirs, degrees from the crown (empty for the continuum).
    pub voussoir_joints_deg: Vec<f64>,
    /// The line of thrust (x, y over r), empty when it is not drawn.
    pub line_of_thrust: Vec<(f64, f64)>,
    /// Hinges: angle in degrees and face (`intrados` or `extrados`).
    pub hinges: Vec<(f64, String)>,
    /// Sliding joints: angle in degrees and sense (`outward` or `inward`).
    pub sliding: Vec<(f64, String)>,
    /// A note drawn in the middle (e.g. why no line of thrust is drawn).
    pub note: Option<String>,
}

fn at(radius: f64, theta_deg: f64) -> (f64, f64) {
    let t = theta_deg.to_radians();
    (radius * t.sin(), radius * t.cos())
}

fn arc(radius: f64, a0: f64, a1: f64, n: usize) -> Vec<(f64, f64)> {
    (0..=n)
        .map(|i| at(radius, a0 + (a1 - a0) * i as f64 / n as f64))
        .collect()
}

/// Data window: the arch with room around it for labels and supports.
fn window(d: &StateDrawing) -> ((f64, f64), (f64, f64)) {
    let pts: Vec<(f64, f64)> = arc(d.k, -d.alpha_deg, d.alpha_deg, 180)
        .into_iter()
        .chain(arc(1.0, -d.alpha_deg, d.alpha_deg, 180))
        .collect();
    let x1 = pts.iter().map(|p| p.0.abs()).fold(0.0, f64::max);
    let (y0, y1) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    let pad = 0.14 * d.k;
    ((-x1 - pad, x1 + pad), (y0 - pad, y1 + pad))
}

/// The plotting area of a [`Chart`].
type Plot<DB> = DrawingArea<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

impl Figure for StateDrawing {
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
        let top = self.draw_titles(&upper, ctx)?;
        let area = upper.margin(top, ctx.px(4.0), ctx.px(10.0), ctx.px(10.0));
        let w = self.equal_scales(area.dim_in_pixel());
        let ((x0, x1), (y0, y1)) = w;
        let chart = ChartBuilder::on(&area).build_cartesian_2d(x0..x1, y0..y1)?;
        let plot = chart.plotting_area();
        self.draw_arch(plot, ctx)?;
        self.draw_supports(plot, ctx)?;
        self.draw_sliding_joints(root, &chart, ctx)?;
        self.draw_line_of_thrust(root, &chart, ctx, w)?;
        self.draw_hinges(root, &chart, ctx)?;
        if let Some(note) = &self.note {
            let f = ctx.font(14.0).pos(Pos::new(HPos::Center, VPos::Center));
            let c = chart.backend_coord(&(0.0, 0.45));
            root.draw(&Text::new(note.clone(), c, f))?;
        }
        Ok(())
    }
}

impl StateDrawing {
    /// The title and the subtitle lines; returns the height they take.
    fn draw_titles<DB: DrawingBackend>(
        &self,
        upper: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<i32, DB> {
        let (w, _) = ctx.pixels();
        let mut y = ctx.px(10.0);
        if ctx.titles {
            let title_font = ctx.font(17.0).pos(Pos::new(HPos::Center, VPos::Top));
            upper.draw(&Text::new(
                self.title.clone(),
                (w as i32 / 2, y),
                title_font,
            ))?;
            y = ctx.px(36.0);
        }
        let sub_font = ctx.font(13.5).pos(Pos::new(HPos::Center, VPos::Top));
        for line in &self.subtitle {
            upper.draw(&Text::new(
                line.clone(),
                (w as i32 / 2, y),
                sub_font.clone(),
            ))?;
            y += ctx.px(19.0);
        }
        Ok(y + ctx.px(6.0))
    }

    /// The data window widened in the direction with room to spare, so that x and y have
    /// equal scales in an area of `(aw, ah)` pixels.
    fn equal_scales(&self, (aw, ah): (u32, u32)) -> Window {
        let ((x0, x1), (y0, y1)) = window(self);
        let s = (f64::from(aw) / (x1 - x0)).min(f64::from(ah) / (y1 - y0));
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let (hw, hh) = (0.5 * f64::from(aw) / s, 0.5 * f64::from(ah) / s);
        ((cx - hw, cx + hw), (cy - hh, cy + hh))
    }

    /// The arch, outlined, with the joints between its voussoirs.
    fn draw_arch<DB: DrawingBackend>(
        &self,
        plot: &Plot<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let (k, a) = (self.k, self.alpha_deg);
        let mut outline = arc(k, -a, a, 360);
        outline.extend(arc(1.0, a, -a, 360));
        plot.draw(&Polygon::new(outline.clone(), palette::STONE.filled()))?;
        outline.push(outline[0]);
        let ink = palette::INK.stroke_width(ctx.upx(1.6));
        plot.draw(&PathElement::new(outline, ink))?;
        for &t in &self.voussoir_joints_deg {
            plot.draw(&PathElement::new(
                vec![at(1.0, t), at(k, t)],
                palette::INK.stroke_width(ctx.upx(1.0).max(1)),
            ))?;
        }
        Ok(())
    }

    /// Supports under the springings: a hatched strip beyond each springing joint.
    fn draw_supports<DB: DrawingBackend>(
        &self,
        plot: &Plot<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let (k, a) = (self.k, self.alpha_deg);
        let thick = k - 1.0;
        for side in [-1.0, 1.0] {
            let t = (side * a).to_radians();
            // Normal of the springing joint pointing away from the arch.
            let out = if side > 0.0 {
                (t.cos(), -t.sin())
            } else {
                (-t.cos(), t.sin())
            };
            let along = (t.sin(), t.cos());
            let ext = 0.25 * thick;
            let p0 = (along.0 * (1.0 - ext), along.1 * (1.0 - ext));
            let p1 = (along.0 * (k + ext), along.1 * (k + ext));
            plot.draw(&PathElement::new(
                vec![p0, p1],
                palette::INK.stroke_width(ctx.upx(2.0)),
            ))?;
            let n = 9;
            let depth = 0.35 * thick;
            for i in 0..=n {
                let f = i as f64 / n as f64;
                let q = (p0.0 + f * (p1.0 - p0.0), p0.1 + f * (p1.1 - p0.1));
                let q2 = (
                    q.0 + depth * (out.0 - 0.6 * along.0),
                    q.1 + depth * (out.1 - 0.6 * along.1),
                );
                plot.draw(&PathElement::new(
                    vec![q, q2],
                    palette::GREY.stroke_width(ctx.upx(1.0).max(1)),
                ))?;
            }
        }
        Ok(())
    }

    /// Sliding joints, each with an arrow on its crown side, radial, in the sense in which
    /// the crown side moves.
    fn draw_sliding_joints<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let k = self.k;
        let thick = k - 1.0;
        let plot = chart.plotting_area();
        for (t, sense) in &self.sliding {
            plot.draw(&PathElement::new(
                vec![at(1.0, *t), at(k, *t)],
                palette::SLIDING_LINE.stroke_width(ctx.upx(3.5)),
            ))?;
            let mid = 0.5 * (1.0 + k);
            let rad = t.to_radians();
            let tang = (rad.cos(), -rad.sin());
            let crown_side = if *t >= 0.0 { -1.0 } else { 1.0 };
            let off = 0.3 * thick.max(0.15);
            let c = at(mid, *t);
            let c = (
                c.0 + crown_side * off * tang.0,
                c.1 + crown_side * off * tang.1,
            );
            let dir = if sense == "outward" { 1.0 } else { -1.0 };
            // Half the joint, centred on it: the arrow stays inside the masonry and clear of
            // a hinge at either face, however thin the arch.
            let len = 0.5 * thick;
            let n = (rad.sin(), rad.cos());
            let a0 = (c.0 - dir * 0.5 * len * n.0, c.1 - dir * 0.5 * len * n.1);
            let a1 = (c.0 + dir * 0.5 * len * n.0, c.1 + dir * 0.5 * len * n.1);
            style::arrow(
                root,
                ctx,
                chart.backend_coord(&a0),
                chart.backend_coord(&a1),
                palette::SLIDING_LINE,
                2.2,
            )?;
        }
        Ok(())
    }

    /// The line of thrust and, for a discrete arch, its pressure points at the joints: only
    /// there is the line bound to the section; within a voussoir it may leave it.
    fn draw_line_of_thrust<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
        ((x0, x1), (y0, y1)): Window,
    ) -> DrawResult<(), DB> {
        if self.line_of_thrust.len() >= 2 {
            for piece in style::clip_polyline(&self.line_of_thrust, (x0, x1), (y0, y1)) {
                chart.plotting_area().draw(&PathElement::new(
                    piece,
                    palette::RED.stroke_width(ctx.upx(2.4)),
                ))?;
            }
        }
        if !self.voussoir_joints_deg.is_empty() {
            for &(x, y) in &self.line_of_thrust {
                let t = x.atan2(y).to_degrees();
                if self
                    .voussoir_joints_deg
                    .iter()
                    .any(|j| (j - t).abs() < 1e-6)
                {
                    let c = chart.backend_coord(&(x, y));
                    root.draw(&Circle::new(c, ctx.upx(3.5), WHITE.filled()))?;
                    root.draw(&Circle::new(
                        c,
                        ctx.upx(3.5),
                        palette::RED.stroke_width(ctx.upx(1.5)),
                    ))?;
                }
            }
        }
        Ok(())
    }

    /// Hinges as dots, then the angle of every hinge and sliding joint.
    fn draw_hinges<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let k = self.k;
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let mut labels = AngleLabels {
            placer: LabelPlacer::new((xr.start, yr.start, xr.end, yr.end)),
            labelled: Vec::new(),
            symmetric: self.is_symmetric(),
            font: ctx.font(12.5),
        };
        let face_radius = |f: &str| if f == "intrados" { 1.0 } else { k };
        let hinge_px: Vec<(i32, i32)> = self
            .hinges
            .iter()
            .map(|(t, f)| chart.backend_coord(&at(face_radius(f), *t)))
            .collect();
        for p in &hinge_px {
            let r = ctx.px(7.0);
            labels.placer.block((p.0 - r, p.1 - r, p.0 + r, p.1 + r));
        }
        for p in &hinge_px {
            style::dot(root, ctx, *p, 5.5, palette::INK)?;
        }
        let gap = 0.09 * k;
        for (t, f) in &self.hinges {
            let r = if f == "intrados" { 1.0 - gap } else { k + gap };
            labels.draw(root, chart, ctx, (*t, r, palette::INK))?;
        }
        for (t, _) in &self.sliding {
            labels.draw(root, chart, ctx, (*t, k + gap, palette::SLIDING_LINE))?;
        }
        Ok(())
    }

    /// True when every hinge and sliding joint has its mirror image.
    fn is_symmetric(&self) -> bool {
        self.hinges.iter().all(|(t, f)| {
            self.hinges
                .iter()
                .any(|(u, g)| (u + t).abs() < 1e-6 && f == g)
        }) && self
            .sliding
            .iter()
            .all(|(t, _)| self.sliding.iter().any(|(u, _)| (u + t).abs() < 1e-6))
    }
}

/// The angle labels of the hinges and sliding joints: one per joint, on the right half when
/// the state is symmetric (else the left is labelled too).
struct AngleLabels {
    placer: LabelPlacer,
    /// Angles already labelled.
    labelled: Vec<f64>,
    symmetric: bool,
    font: TextStyle<'static>,
}

impl AngleLabels {
    /// Labels joint `t` (degrees) near radius `radius_out`, in `color`.
    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
        (t, radius_out, color): (f64, f64, RGBColor),
    ) -> DrawResult<(), DB> {
        if (self.symmetric && t < -1e-9) || self.labelled.iter().any(|&u| (u - t).abs() < 1e-6) {
            return Ok(());
        }
        self.labelled.push(t);
        let font = &self.font;
        let text = format!("{:.1}°", t);
        let (tw, th) = style::text_block_size(font, std::slice::from_ref(&text), 1.0);
        let p = chart.backend_coord(&at(radius_out, t));
        let cands = [
            (p.0 - tw / 2, p.1 - th / 2),
            (p.0, p.1 - th),
            (p.0 - tw, p.1 - th),
            (p.0, p.1),
            (p.0 - tw, p.1),
            (p.0 + ctx.px(8.0), p.1 - th / 2),
            (p.0 - tw - ctx.px(8.0), p.1 - th / 2),
        ];
        let pos = self.placer.place(tw, th, &cands);
        root.draw(&Text::new(
            text,
            pos,
            font.color(&color).pos(Pos::new(HPos::Left, VPos::Top)),
        ))?;
        Ok(())
    }
}

impl StateDrawing {
    fn legend(&self) -> Vec<LegendItem> {
        let mut items = Vec::new();
        if self.line_of_thrust.len() >= 2 {
            items.push(LegendItem::new(
                "line of thrust",
                Mark::Line {
                    color: palette::RED,
                    width: 2.4,
                    dashed: false,
                },
            ));
            if !self.voussoir_joints_deg.is_empty() {
                items.push(LegendItem::new(
                    "its point on a joint",
                    Mark::Ring(palette::RED),
                ));
            }
        }
        if !self.hinges.is_empty() {
            items.push(LegendItem::new(
                "hinge (angle from the crown)",
                Mark::Dot(palette::INK),
            ));
        }
        if !self.sliding.is_empty() {
            items.push(LegendItem::new(
                "sliding joint, arrow: motion of the crown side",
                Mark::Arrow(palette::SLIDING_LINE),
            ));
        }
        items
    }
}
