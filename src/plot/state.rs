//! Figure 3 (the paper's Figs. 6 and 7): a state of the arch drawn to scale (equal scales in
//! x and y): the voussoirs when discrete, the line of thrust, hinges as dots on the intrados
//! or extrados and sliding joints with an arrow giving the sense of the crown-side part.

use super::style::{self, LegendItem, Mark, palette};
use super::{Figure, PlotContext, Window, XyChart as Chart};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

mod labels;

pub use labels::{PixelMap, PlacedLabel, box_meets_polygon, boxes_meet};

/// A point over r.
pub type Xy = (f64, f64);

/// A joint of the drawn arch: its intrados and extrados ends and the angle that names it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawnJoint {
    /// Intrados end.
    pub intrados: Xy,
    /// Extrados end.
    pub extrados: Xy,
    /// Angle from the crown, degrees, positive to the right.
    pub angle_deg: f64,
}

impl DrawnJoint {
    /// Unit vector from the intrados end to the extrados end.
    pub fn along(&self) -> Xy {
        let (dx, dy) = (
            self.extrados.0 - self.intrados.0,
            self.extrados.1 - self.intrados.1,
        );
        let l = dx.hypot(dy).max(f64::MIN_POSITIVE);
        (dx / l, dy / l)
    }

    fn middle(&self) -> Xy {
        (
            0.5 * (self.intrados.0 + self.extrados.0),
            0.5 * (self.intrados.1 + self.extrados.1),
        )
    }
}

/// A hinge: the joint and the face the line of thrust touches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawnHinge {
    /// The joint.
    pub joint: DrawnJoint,
    /// True at the extrados, false at the intrados.
    pub extrados: bool,
}

impl DrawnHinge {
    /// The hinge point.
    pub fn point(&self) -> Xy {
        if self.extrados {
            self.joint.extrados
        } else {
            self.joint.intrados
        }
    }
}

/// A sliding joint with the motion of its crown-side part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawnSlide {
    /// The joint.
    pub joint: DrawnJoint,
    /// True when the crown-side part moves outward (toward the extrados).
    pub outward: bool,
    /// Unit vector across the joint toward its crown side.
    pub crown_side: Xy,
}

/// A support: the springing joint and the side the ground lies on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrawnSupport {
    /// Intrados end of the springing joint.
    pub intrados: Xy,
    /// Extrados end.
    pub extrados: Xy,
    /// Unit normal of the joint pointing into the ground.
    pub into_ground: Xy,
}

/// The live load of a state.
#[derive(Debug, Clone, PartialEq)]
pub enum DrawnLoad {
    /// A vertical point load at a point of the extrados.
    Point {
        /// Where it acts.
        at: Xy,
        /// Its label (λ).
        label: String,
    },
    /// A horizontal body force, drawn as arrows onto points spread over the arch.
    Horizontal {
        /// The points the arrows end at.
        at: Vec<Xy>,
        /// Its label (λ).
        label: String,
    },
    /// A vertical load spread over a length of the extrados (a patch load), drawn as
    /// arrows onto points spread over it, their tails joined by a bar.
    Patch {
        /// The points of the extrados the arrows end at, from left to right (the first and
        /// last are the patch's ends).
        at: Vec<Xy>,
        /// Its label (λ).
        label: String,
    },
}

impl DrawnLoad {
    /// The points the arrows end at.
    pub fn heads(&self) -> &[Xy] {
        match self {
            DrawnLoad::Point { at, .. } => std::slice::from_ref(at),
            DrawnLoad::Horizontal { at, .. } | DrawnLoad::Patch { at, .. } => at,
        }
    }

    /// The label (λ).
    pub fn label(&self) -> &str {
        match self {
            DrawnLoad::Point { label, .. }
            | DrawnLoad::Horizontal { label, .. }
            | DrawnLoad::Patch { label, .. } => label,
        }
    }

    /// True for arrows pointing down (a point or patch load).
    fn is_vertical(&self) -> bool {
        !matches!(self, DrawnLoad::Horizontal { .. })
    }
}

/// What a state drawing shows. Lengths over the intrados radius r.
#[derive(Debug, Clone, PartialEq)]
pub struct StateDrawing {
    /// Title.
    pub title: String,
    /// Lines under the title (values, already formatted).
    pub subtitle: Vec<String>,
    /// The outline of the arch: a closed polygon (intrados left to right, extrados back),
    /// first point not repeated.
    pub outline: Vec<Xy>,
    /// Joints between voussoirs (empty for the continuum).
    pub voussoir_joints: Vec<DrawnJoint>,
    /// The supports, left then right.
    pub supports: [DrawnSupport; 2],
    /// The line of thrust (x, y over r; NaN breaks it), empty when it is not drawn.
    pub line_of_thrust: Vec<Xy>,
    /// Its points on the joints between voussoirs.
    pub line_on_joints: Vec<Xy>,
    /// What the line of thrust is, for the legend (`line of thrust` when empty).
    pub line_label: String,
    /// A second line of thrust of the same arch (e.g. the maximum-thrust state beside the
    /// minimum-thrust one), drawn dashed; empty when there is none.
    pub other_line: Vec<Xy>,
    /// What the second line is, for the legend.
    pub other_line_label: String,
    /// Hinges.
    pub hinges: Vec<DrawnHinge>,
    /// Sliding joints.
    pub sliding: Vec<DrawnSlide>,
    /// The live load, if any.
    pub load: Option<DrawnLoad>,
    /// A note drawn in the middle (e.g. why no line of thrust is drawn).
    pub note: Option<String>,
}

/// Bounds (x0, x1, y0, y1) of points.
fn bounds<'a>(pts: impl Iterator<Item = &'a Xy>) -> [f64; 4] {
    pts.fold(
        [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| [b[0].min(p.0), b[1].max(p.0), b[2].min(p.1), b[3].max(p.1)],
    )
}

impl StateDrawing {
    /// A length of the drawing's scale: the larger half-extent of the arch.
    fn scale(&self) -> f64 {
        let b = bounds(self.outline.iter());
        (0.5 * (b[1] - b[0])).max(b[3] - b[2]).max(1e-3)
    }

    /// Length of a load arrow, over r.
    fn arrow_length(&self) -> f64 {
        0.22 * self.scale()
    }

    /// The points a load arrow starts from.
    fn load_tails(&self) -> Vec<Xy> {
        let l = self.arrow_length();
        match &self.load {
            Some(DrawnLoad::Point { at, .. }) => vec![(at.0, at.1 + l)],
            Some(DrawnLoad::Horizontal { at, .. }) => at.iter().map(|p| (p.0 - l, p.1)).collect(),
            // Shorter arrows, their tails on one level above the patch's highest point.
            Some(DrawnLoad::Patch { at, .. }) => {
                let top = at.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
                at.iter().map(|p| (p.0, top + 0.6 * l)).collect()
            }
            None => Vec::new(),
        }
    }
}

/// Data window: the arch and its load with room around it for labels and supports.
fn window(d: &StateDrawing) -> ((f64, f64), (f64, f64)) {
    let tails = d.load_tails();
    let b = bounds(d.outline.iter().chain(&tails));
    let pad = 0.1 * d.scale();
    ((b[0] - pad, b[1] + pad), (b[2] - pad, b[3] + 1.3 * pad))
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
        let w = self.equal_scales(area.dim_in_pixel(), self.label_room(ctx));
        let ((x0, x1), (y0, y1)) = w;
        let chart = ChartBuilder::on(&area).build_cartesian_2d(x0..x1, y0..y1)?;
        let plot = chart.plotting_area();
        self.draw_arch(plot, ctx)?;
        self.draw_supports(plot, ctx)?;
        self.draw_sliding_joints(root, &chart, ctx)?;
        self.draw_line_of_thrust(root, &chart, ctx, w)?;
        self.draw_load(root, &chart, ctx)?;
        self.draw_hinges(root, &chart, ctx, w)?;
        if let Some(note) = &self.note {
            let f = ctx.font(14.0).pos(Pos::new(HPos::Center, VPos::Center));
            let b = bounds(self.outline.iter());
            let c = chart.backend_coord(&(0.5 * (b[0] + b[1]), b[2] + 0.35 * (b[3] - b[2])));
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
            // A title wider than the figure (a long arch description) wraps at spaces.
            let room = f64::from(w) - 2.0 * f64::from(ctx.px(8.0));
            for line in super::style::wrap(&title_font, &self.title, room) {
                upper.draw(&Text::new(line, (w as i32 / 2, y), title_font.clone()))?;
                y += ctx.px(22.0);
            }
            y += ctx.px(4.0);
        }
        let sub_font = ctx.font(13.5).pos(Pos::new(HPos::Center, VPos::Top));
        // A line wider than the figure (a single-column paper file) wraps at spaces.
        let room = f64::from(w) - 2.0 * f64::from(ctx.px(8.0));
        let lines: Vec<String> = self
            .subtitle
            .iter()
            .flat_map(|l| super::style::wrap(&sub_font, l, room))
            .collect();
        for line in lines {
            upper.draw(&Text::new(line, (w as i32 / 2, y), sub_font.clone()))?;
            y += ctx.px(19.0);
        }
        Ok(y + ctx.px(6.0))
    }

    /// The data window widened in the direction with room to spare, so that x and y have
    /// equal scales in an area of `(aw, ah)` pixels, with `room` pixels more on either side
    /// of the window in x.
    fn equal_scales(&self, (aw, ah): (u32, u32), room: i32) -> Window {
        let ((x0, x1), (y0, y1)) = window(self);
        let inner = (f64::from(aw) - 2.0 * f64::from(room)).max(0.5 * f64::from(aw));
        let s = (inner / (x1 - x0)).min(f64::from(ah) / (y1 - y0));
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let (hw, hh) = (0.5 * f64::from(aw) / s, 0.5 * f64::from(ah) / s);
        ((cx - hw, cx + hw), (cy - hh, cy + hh))
    }

    /// Pixels kept free beside the arch for the angle label of a hinge or sliding joint at a
    /// springing, which stands beyond the extrados above the ground line: the width of the
    /// widest such label and a gap; none when no label is there.
    fn label_room(&self, ctx: &PlotContext) -> i32 {
        let near = |p: Xy, q: Xy| (p.0 - q.0).abs() < 1e-9 && (p.1 - q.1).abs() < 1e-9;
        let at_support = |i: Xy| self.supports.iter().any(|s| near(s.intrados, i));
        let springing = (self.hinges.iter().map(|h| h.joint))
            .chain(self.sliding.iter().map(|s| s.joint))
            .any(|j| at_support(j.intrados));
        if !springing {
            return 0;
        }
        let text = ["−90.0°".to_string()];
        style::text_block_size(&ctx.font(12.5), &text, 1.0).0 + ctx.px(16.0)
    }

    /// The arch, outlined, with the joints between its voussoirs.
    fn draw_arch<DB: DrawingBackend>(
        &self,
        plot: &Plot<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        if self.outline.len() < 3 {
            return Ok(());
        }
        let mut outline = self.outline.clone();
        plot.draw(&Polygon::new(outline.clone(), palette::STONE.filled()))?;
        outline.push(outline[0]);
        let ink = palette::INK.stroke_width(ctx.upx(1.6));
        plot.draw(&PathElement::new(outline, ink))?;
        for j in &self.voussoir_joints {
            plot.draw(&PathElement::new(
                vec![j.intrados, j.extrados],
                palette::INK.stroke_width(ctx.upx(1.0).max(1)),
            ))?;
        }
        Ok(())
    }

    /// Supports under the springings: a hatched strip beyond each springing joint
    /// ([`DrawnSupport::hatching`]).
    fn draw_supports<DB: DrawingBackend>(
        &self,
        plot: &Plot<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        for s in &self.supports {
            for (k, [a, b]) in s.hatching().into_iter().enumerate() {
                let stroke = if k == 0 {
                    palette::INK.stroke_width(ctx.upx(2.0))
                } else {
                    palette::GREY.stroke_width(ctx.upx(1.0).max(1))
                };
                plot.draw(&PathElement::new(vec![a, b], stroke))?;
            }
        }
        Ok(())
    }

    /// Sliding joints, each with an arrow on its crown side, along the joint, in the sense in
    /// which the crown side moves.
    fn draw_sliding_joints<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let plot = chart.plotting_area();
        for s in &self.sliding {
            let j = &s.joint;
            plot.draw(&PathElement::new(
                vec![j.intrados, j.extrados],
                palette::SLIDING_LINE.stroke_width(ctx.upx(3.5)),
            ))?;
            let (a0, a1) = self.sliding_arrow(s);
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

    /// The arrow of a sliding joint, tail and head: along the joint on its crown side, in
    /// the sense the crown-side part moves relative to the springing-side part.
    fn sliding_arrow(&self, s: &DrawnSlide) -> (Xy, Xy) {
        let j = &s.joint;
        // Sized by the arch's thickness (the springing joint), not by the joint: a
        // vertical joint near a springing is much longer than the arch is thick.
        let s0 = &self.supports[1];
        let thick = (s0.extrados.0 - s0.intrados.0)
            .hypot(s0.extrados.1 - s0.intrados.1)
            .max(0.15);
        let off = 0.3 * thick;
        let m = j.middle();
        let dir = if s.outward { 1.0 } else { -1.0 };
        // Half the thickness, centred on the joint: the arrow stays inside the masonry
        // and clear of a hinge at either face, however thin the arch.
        let len = 0.5 * thick;
        let n = j.along();
        // A crown-side part narrower than two offsets (the wedge between the first joints
        // of a pointed arch, sliding on both) has no room for the arrows of both its
        // joints: each is drawn on its joint's line produced beyond the extrados, where
        // the two lines part. (The two sides of a point load's sliver are one joint drawn
        // twice: they keep their place.)
        let narrow = self.sliding.iter().any(|o| {
            let p = o.joint.middle();
            let d = (p.0 - m.0).hypot(p.1 - m.1);
            !std::ptr::eq(o, s) && d > 1e-6 * thick && d < 2.0 * off
        });
        let c = if narrow {
            let e = j.extrados;
            let out = 0.25 * thick + 0.5 * len;
            (e.0 + out * n.0, e.1 + out * n.1)
        } else {
            (m.0 + off * s.crown_side.0, m.1 + off * s.crown_side.1)
        };
        let a0 = (c.0 - dir * 0.5 * len * n.0, c.1 - dir * 0.5 * len * n.1);
        let a1 = (c.0 + dir * 0.5 * len * n.0, c.1 + dir * 0.5 * len * n.1);
        (a0, a1)
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
        if self.other_line.len() >= 2 {
            for piece in style::clip_polyline(&self.other_line, (x0, x1), (y0, y1)) {
                chart.plotting_area().draw(&DashedPathElement::new(
                    piece,
                    ctx.upx(7.0),
                    ctx.upx(4.0),
                    palette::BLUE.stroke_width(ctx.upx(2.0)),
                ))?;
            }
        }
        if self.line_of_thrust.len() >= 2 {
            for piece in style::clip_polyline(&self.line_of_thrust, (x0, x1), (y0, y1)) {
                chart.plotting_area().draw(&PathElement::new(
                    piece,
                    palette::RED.stroke_width(ctx.upx(2.4)),
                ))?;
            }
        }
        for p in &self.line_on_joints {
            if !(x0..=x1).contains(&p.0) || !(y0..=y1).contains(&p.1) {
                continue;
            }
            let c = chart.backend_coord(p);
            root.draw(&Circle::new(c, ctx.upx(3.5), WHITE.filled()))?;
            root.draw(&Circle::new(
                c,
                ctx.upx(3.5),
                palette::RED.stroke_width(ctx.upx(1.5)),
            ))?;
        }
        Ok(())
    }

    /// The live load: a vertical arrow onto its point, or arrows across the arch for a
    /// horizontal body force, with its label.
    fn draw_load<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let Some(load) = &self.load else {
            return Ok(());
        };
        let tails = self.load_tails();
        let (heads, label) = (load.heads(), load.label());
        if let (DrawnLoad::Patch { .. }, Some(first), Some(last)) =
            (load, tails.first(), tails.last())
        {
            root.draw(&PathElement::new(
                vec![chart.backend_coord(first), chart.backend_coord(last)],
                palette::GREEN.stroke_width(ctx.upx(2.6)),
            ))?;
        }
        for (t, h) in tails.iter().zip(heads) {
            style::arrow(
                root,
                ctx,
                chart.backend_coord(t),
                chart.backend_coord(h),
                palette::GREEN,
                2.6,
            )?;
        }
        if let Some(t) = tails.iter().max_by(|a, b| a.1.total_cmp(&b.1)) {
            // Right of the top of a vertical arrow; above the highest tail of horizontal ones.
            let p = chart.backend_coord(t);
            let (pos, at) = if load.is_vertical() {
                (
                    Pos::new(HPos::Left, VPos::Bottom),
                    (p.0 + ctx.px(6.0), p.1 - ctx.px(2.0)),
                )
            } else {
                (
                    Pos::new(HPos::Right, VPos::Center),
                    (p.0 - ctx.px(6.0), p.1),
                )
            };
            let f = ctx.font(13.0).color(&palette::GREEN).pos(pos);
            root.draw(&Text::new(label.to_string(), at, f))?;
        }
        Ok(())
    }

    /// Hinges as dots, then the angle of every hinge and sliding joint, placed clear of
    /// the masonry, the supports and the load ([`StateDrawing::angle_labels`]).
    fn draw_hinges<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
        window: Window,
    ) -> DrawResult<(), DB> {
        for h in &self.hinges {
            style::dot(
                root,
                ctx,
                chart.backend_coord(&h.point()),
                5.5,
                palette::INK,
            )?;
        }
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let map = PixelMap {
            window,
            pixels: (xr.start, yr.start, xr.end, yr.end),
        };
        let font = ctx.font(12.5);
        for l in self.place_angle_labels(ctx, map) {
            root.draw(&Text::new(
                l.text,
                l.top_left,
                font.color(&l.color).pos(Pos::new(HPos::Left, VPos::Top)),
            ))?;
        }
        Ok(())
    }

    /// True when every hinge and sliding joint has its mirror image.
    fn is_symmetric(&self) -> bool {
        let mirrored = |a: f64, b: f64| (a + b).abs() < 1e-6;
        self.hinges.iter().all(|h| {
            self.hinges
                .iter()
                .any(|g| mirrored(h.joint.angle_deg, g.joint.angle_deg) && h.extrados == g.extrados)
        }) && self.sliding.iter().all(|s| {
            self.sliding
                .iter()
                .any(|u| mirrored(s.joint.angle_deg, u.joint.angle_deg))
        })
    }
}

impl StateDrawing {
    fn legend(&self) -> Vec<LegendItem> {
        let mut items = Vec::new();
        if self.line_of_thrust.len() >= 2 {
            let label = if self.line_label.is_empty() {
                "line of thrust"
            } else {
                self.line_label.as_str()
            };
            items.push(LegendItem::new(
                label,
                Mark::Line {
                    color: palette::RED,
                    width: 2.4,
                    dashed: false,
                },
            ));
            if !self.line_on_joints.is_empty() {
                items.push(LegendItem::new(
                    "its point on a joint",
                    Mark::Ring(palette::RED),
                ));
            }
        }
        if self.other_line.len() >= 2 {
            items.push(LegendItem::new(
                self.other_line_label.as_str(),
                Mark::Line {
                    color: palette::BLUE,
                    width: 2.0,
                    dashed: true,
                },
            ));
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
        match &self.load {
            Some(DrawnLoad::Point { .. }) => items.push(LegendItem::new(
                "point load λ·W_total",
                Mark::Arrow(palette::GREEN),
            )),
            Some(DrawnLoad::Horizontal { .. }) => items.push(LegendItem::new(
                "horizontal body force λ·weight",
                Mark::Arrow(palette::GREEN),
            )),
            Some(DrawnLoad::Patch { .. }) => items.push(LegendItem::new(
                "patch load λ·W_total, spread over the bar",
                Mark::Arrow(palette::GREEN),
            )),
            None => {}
        }
        items
    }
}
