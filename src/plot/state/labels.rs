//! Where the angle labels of a state drawing go: next to their hinge or sliding joint, clear
//! of the masonry, of the hatched supports, of the hinge dots, of the load and of each other.
//! Placed in device pixels (text has a pixel size) and reported in data coordinates too, so
//! that the layout can be checked against the arch's geometry.

use super::{DrawnSupport, StateDrawing, Xy};
use crate::plot::style::{self, LabelPlacer, PixelBox, palette};
use crate::plot::{PlotContext, Window};
use plotters::style::RGBColor;

/// A linear map between data coordinates (over r) and device pixels, y pointing down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelMap {
    /// The data window ((x0, x1), (y0, y1)).
    pub window: Window,
    /// The pixel box it fills (left, top, right, bottom).
    pub pixels: PixelBox,
}

impl PixelMap {
    /// The device pixel of a data point.
    pub fn to_px(&self, p: Xy) -> (i32, i32) {
        let ((x0, x1), (y0, y1)) = self.window;
        let (l, t, r, b) = self.pixels;
        let fx = (p.0 - x0) / (x1 - x0);
        let fy = (p.1 - y0) / (y1 - y0);
        (
            l + (fx * f64::from(r - l)).round() as i32,
            b - (fy * f64::from(b - t)).round() as i32,
        )
    }

    /// The data point of a device pixel.
    pub fn to_data(&self, (px, py): (i32, i32)) -> Xy {
        let ((x0, x1), (y0, y1)) = self.window;
        let (l, t, r, b) = self.pixels;
        (
            x0 + f64::from(px - l) / f64::from(r - l) * (x1 - x0),
            y0 + f64::from(b - py) / f64::from(b - t) * (y1 - y0),
        )
    }

    /// A pixel box as a data box [x0, x1, y0, y1].
    pub fn data_box(&self, b: PixelBox) -> [f64; 4] {
        let (p, q) = (self.to_data((b.0, b.3)), self.to_data((b.2, b.1)));
        [p.0, q.0, p.1, q.1]
    }

    /// A data box [x0, x1, y0, y1] as a pixel box.
    fn pixel_box(&self, b: [f64; 4]) -> PixelBox {
        let (p, q) = (self.to_px((b[0], b[3])), self.to_px((b[1], b[2])));
        (p.0, p.1, q.0, q.1)
    }
}

/// An angle label, placed.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedLabel {
    /// The text ("28.2°").
    pub text: String,
    /// Its colour: ink for a hinge, the sliding colour for a sliding joint.
    pub color: RGBColor,
    /// Top-left corner, device pixels.
    pub top_left: (i32, i32),
    /// Its box in data coordinates, [x0, x1, y0, y1].
    pub data_box: [f64; 4],
}

impl DrawnSupport {
    /// The drawn support, in data coordinates: the ground line first (the springing joint
    /// extended by a quarter of its length at both ends), then the hatch strokes into the
    /// ground.
    pub fn hatching(&self) -> Vec<[Xy; 2]> {
        let (i, e) = (self.intrados, self.extrados);
        let (dx, dy) = (e.0 - i.0, e.1 - i.1);
        let thick = dx.hypot(dy).max(f64::MIN_POSITIVE);
        let along = (dx / thick, dy / thick);
        let ext = 0.25 * thick;
        let p0 = (i.0 - ext * along.0, i.1 - ext * along.1);
        let p1 = (e.0 + ext * along.0, e.1 + ext * along.1);
        let mut out = vec![[p0, p1]];
        let n = 9;
        let depth = 0.35 * thick;
        let out_dir = self.into_ground;
        for k in 0..=n {
            let f = f64::from(k) / f64::from(n);
            let q = (p0.0 + f * (p1.0 - p0.0), p0.1 + f * (p1.1 - p0.1));
            let q2 = (
                q.0 + depth * (out_dir.0 - 0.6 * along.0),
                q.1 + depth * (out_dir.1 - 0.6 * along.1),
            );
            out.push([q, q2]);
        }
        out
    }

    /// The box [x0, x1, y0, y1] around the hatching.
    pub fn hatching_box(&self) -> [f64; 4] {
        self.hatching().iter().flatten().fold(
            [
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ],
            |b, p| [b[0].min(p.0), b[1].max(p.0), b[2].min(p.1), b[3].max(p.1)],
        )
    }
}

/// Whether a point lies inside a closed polygon (even-odd rule).
fn inside(p: Xy, poly: &[Xy]) -> bool {
    let mut c = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + n - 1) % n]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < (b.0 - a.0) * (p.1 - a.1) / (b.1 - a.1) + a.0 {
            c = !c;
        }
    }
    c
}

/// Whether the segment a–b meets the box [x0, x1, y0, y1] (Liang–Barsky clipping).
fn segment_meets_box(a: Xy, b: Xy, bx: [f64; 4]) -> bool {
    crate::plot::style::clip_segment(a, b, (bx[0], bx[1]), (bx[2], bx[3])).is_some()
}

/// Whether the box [x0, x1, y0, y1] meets the closed polygon `poly` (its edges or inside).
pub fn box_meets_polygon(bx: [f64; 4], poly: &[Xy]) -> bool {
    let n = poly.len();
    if n < 3 {
        return false;
    }
    let corner = (bx[0], bx[2]);
    inside(corner, poly) || (0..n).any(|i| segment_meets_box(poly[i], poly[(i + 1) % n], bx))
}

/// Whether two data boxes [x0, x1, y0, y1] overlap.
pub fn boxes_meet(a: [f64; 4], b: [f64; 4]) -> bool {
    a[0] <= b[1] && b[0] <= a[1] && a[2] <= b[3] && b[2] <= a[3]
}

impl StateDrawing {
    /// The angle labels of the hinges and sliding joints for a plotting area of `area`
    /// device pixels: one per joint, on the right half when the state is symmetric.
    pub fn angle_labels(&self, ctx: &PlotContext, area: (u32, u32)) -> Vec<PlacedLabel> {
        style::register_fonts();
        let window = self.equal_scales(area, self.label_room(ctx));
        let pixels = (0, 0, area.0 as i32, area.1 as i32);
        self.place_angle_labels(ctx, PixelMap { window, pixels })
    }

    /// The angle labels for the map `map` of the plotting area.
    pub(super) fn place_angle_labels(&self, ctx: &PlotContext, map: PixelMap) -> Vec<PlacedLabel> {
        let mut placer = LabelPlacer::new(map.pixels);
        for h in &self.hinges {
            let p = map.to_px(h.point());
            let r = ctx.px(7.0);
            placer.block((p.0 - r, p.1 - r, p.0 + r, p.1 + r));
        }
        for b in self.load_boxes(map, ctx) {
            placer.block(b);
        }
        let pad = ctx.px(4.0);
        for s in &self.sliding {
            let (a, b) = self.sliding_arrow(s);
            let (a, b) = (map.to_px(a), map.to_px(b));
            placer.block((
                a.0.min(b.0) - pad,
                a.1.min(b.1) - pad,
                a.0.max(b.0) + pad,
                a.1.max(b.1) + pad,
            ));
        }
        for s in &self.supports {
            let b = map.pixel_box(s.hatching_box());
            placer.block((b.0 - pad, b.1 - pad, b.2 + pad, b.3 + pad));
        }
        let symmetric = self.is_symmetric();
        let font = ctx.font(12.5);
        let gap = 0.07 * self.scale();
        let mut wanted: Vec<(f64, Xy, RGBColor)> = Vec::new();
        for h in &self.hinges {
            let (n, p) = (h.joint.along(), h.point());
            let sign = if h.extrados { 1.0 } else { -1.0 };
            let anchor = (p.0 + sign * gap * n.0, p.1 + sign * gap * n.1);
            wanted.push((h.joint.angle_deg, anchor, palette::INK));
        }
        for s in &self.sliding {
            let (n, p) = (s.joint.along(), s.joint.extrados);
            let anchor = (p.0 + gap * n.0, p.1 + gap * n.1);
            wanted.push((s.joint.angle_deg, anchor, palette::SLIDING_LINE));
        }
        let mut labelled: Vec<f64> = Vec::new();
        let mut out = Vec::new();
        for (t, anchor, color) in wanted {
            if (symmetric && t < -1e-9) || labelled.iter().any(|&u| (u - t).abs() < 1e-6) {
                continue;
            }
            labelled.push(t);
            let text = format!("{t:.1}°");
            let (tw, th) = style::text_block_size(&font, std::slice::from_ref(&text), 1.0);
            let p = map.to_px(anchor);
            let clear = |&(x, y): &(i32, i32)| {
                let b = map.data_box((x - pad, y - pad, x + tw + pad, y + th + pad));
                !box_meets_polygon(b, &self.outline)
            };
            let near: Vec<(i32, i32)> = candidates(p, (tw, th), ctx)
                .into_iter()
                .chain(style::rings_around((p.0 - tw / 2, p.1 - th / 2), tw, th))
                .filter(clear)
                .collect();
            let at = placer
                .try_place(tw, th, &near)
                .unwrap_or_else(|| placer.place(tw, th, &[(p.0 - tw / 2, p.1 - th / 2)]));
            out.push(PlacedLabel {
                text,
                color,
                top_left: at,
                data_box: map.data_box((at.0, at.1, at.0 + tw, at.1 + th)),
            });
        }
        out
    }

    /// Device-pixel boxes of the load's arrows and label, kept clear of the angle labels.
    fn load_boxes(&self, map: PixelMap, ctx: &PlotContext) -> Vec<PixelBox> {
        let Some(load) = &self.load else {
            return Vec::new();
        };
        let heads = load.heads();
        let pad = ctx.px(6.0);
        let mut out: Vec<PixelBox> = self
            .load_tails()
            .iter()
            .zip(heads)
            .map(|(t, h)| {
                let (a, b) = (map.to_px(*t), map.to_px(*h));
                (
                    a.0.min(b.0) - pad,
                    a.1.min(b.1) - pad,
                    a.0.max(b.0) + pad,
                    a.1.max(b.1) + pad,
                )
            })
            .collect();
        if let Some(t) = self.load_tails().iter().max_by(|a, b| a.1.total_cmp(&b.1)) {
            let p = map.to_px(*t);
            out.push(match &self.load {
                Some(l) if l.is_vertical() => {
                    (p.0 - pad, p.1 - ctx.px(30.0), p.0 + ctx.px(110.0), p.1)
                }
                _ => (
                    p.0 - ctx.px(110.0),
                    p.1 - ctx.px(12.0),
                    p.0,
                    p.1 + ctx.px(12.0),
                ),
            });
        }
        out
    }
}

/// Top-left corners tried first for a `tw` × `th` label near the pixel `p`: centred on it,
/// at its corners (above first, then lifted a little, which keeps a label at a springing
/// above the ground line) and sides, then a little farther out.
fn candidates(p: (i32, i32), (tw, th): (i32, i32), ctx: &PlotContext) -> Vec<(i32, i32)> {
    let far = ctx.px(14.0);
    let lift = ctx.px(8.0);
    vec![
        (p.0 - tw / 2, p.1 - th / 2),
        (p.0, p.1 - th),
        (p.0 - tw, p.1 - th),
        (p.0, p.1 - th - lift),
        (p.0 - tw, p.1 - th - lift),
        (p.0, p.1),
        (p.0 - tw, p.1),
        (p.0 + ctx.px(8.0), p.1 - th / 2),
        (p.0 - tw - ctx.px(8.0), p.1 - th / 2),
        (p.0 + far, p.1 + far / 2),
        (p.0 - tw - far, p.1 + far / 2),
        (p.0 + far, p.1 - th - far / 2),
        (p.0 - tw - far, p.1 - th - far / 2),
        (p.0 - tw / 2, p.1 + far),
        (p.0 - tw / 2, p.1 - th - far),
    ]
}
