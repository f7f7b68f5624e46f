//! What every chart shares: the bundled font, the palette, legends drawn below a chart,
//! clipping of polylines to a data window, label placement without overlaps and arrows.

use super::PlotContext;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::sync::Once;

/// Registers DejaVu Sans as `sans-serif` (once per process).
pub fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bundled fonts are valid TrueType; a failure would only make text invisible.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
        let _ = plotters::style::register_font("sans-serif", FontStyle::Bold, dejavu::sans::bold());
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Italic,
            dejavu::sans::oblique(),
        );
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Oblique,
            dejavu::sans::oblique(),
        );
    });
}

/// The bundled sans-serif font at `size` device pixels.
pub fn font(size: f64) -> TextStyle<'static> {
    font_with(size, FontStyle::Normal)
}

/// The bundled sans-serif font at `size` device pixels in a style (bold, italic).
pub fn font_with(size: f64, style: FontStyle) -> TextStyle<'static> {
    TextStyle::from(("sans-serif", size, style).into_font()).color(&BLACK)
}

/// Colours: regimes as light fills, mechanisms as strong lines (Okabe–Ito based, readable
/// by colour-blind readers and in greyscale by lightness).
pub mod palette {
    use plotters::style::RGBColor;
    /// Fill of the stable region.
    pub const STABLE: RGBColor = RGBColor(236, 246, 236);
    /// The windows of K in which an arch stands, on a critical-curve panel.
    pub const STABLE_WINDOW: RGBColor = RGBColor(200, 232, 200);
    /// Fill of the rotational region (H^r empty).
    pub const ROTATIONAL: RGBColor = RGBColor(252, 217, 168);
    /// Fill of the mixed region (domains disjoint).
    pub const MIXED: RGBColor = RGBColor(221, 196, 232);
    /// Fill of the sliding region (H^s empty).
    pub const SLIDING: RGBColor = RGBColor(181, 216, 240);
    /// Fill of the region where both domains are empty.
    pub const NONE: RGBColor = RGBColor(205, 205, 205);
    /// Rotational mechanism lines.
    pub const ROTATIONAL_LINE: RGBColor = RGBColor(213, 94, 0);
    /// Mixed mechanism lines.
    pub const MIXED_LINE: RGBColor = RGBColor(136, 46, 160);
    /// Sliding mechanism lines.
    pub const SLIDING_LINE: RGBColor = RGBColor(0, 114, 178);
    /// Neutral dark lines.
    pub const INK: RGBColor = RGBColor(30, 30, 30);
    /// Grey for secondary lines.
    pub const GREY: RGBColor = RGBColor(120, 120, 120);
    /// Bluish green (Okabe–Ito).
    pub const GREEN: RGBColor = RGBColor(0, 158, 115);
    /// Reddish purple (Okabe–Ito).
    pub const PURPLE: RGBColor = RGBColor(204, 121, 167);
    /// Vermillion (Okabe–Ito).
    pub const RED: RGBColor = RGBColor(213, 94, 0);
    /// Orange (Okabe–Ito).
    pub const ORANGE: RGBColor = RGBColor(230, 159, 0);
    /// Blue (Okabe–Ito).
    pub const BLUE: RGBColor = RGBColor(0, 114, 178);
    /// Sky blue (Okabe–Ito).
    pub const SKY: RGBColor = RGBColor(86, 180, 233);
    /// The non-associative gap and the collapse that opens it: a colour no mechanism and no
    /// regime uses.
    pub const GAP: RGBColor = RGBColor(0, 158, 115);
    /// Arch fill.
    pub const STONE: RGBColor = RGBColor(238, 230, 214);

    /// The line colour of a mechanism name.
    pub fn mechanism(name: &str) -> RGBColor {
        match name {
            "rotational" => ROTATIONAL_LINE,
            "mixed" => MIXED_LINE,
            "sliding" => SLIDING_LINE,
            _ => INK,
        }
    }

    /// The fill of a regime name.
    pub fn regime(name: &str) -> RGBColor {
        match name {
            "stable" => STABLE,
            "rotational" => ROTATIONAL,
            "mixed" => MIXED,
            "sliding" => SLIDING,
            _ => NONE,
        }
    }
}

/// `c` at opacity `alpha` over white, as an opaque colour (for legend swatches of
/// translucent fills).
pub fn over_white(c: RGBColor, alpha: f64) -> RGBColor {
    over(c, alpha, WHITE)
}

/// `c` at opacity `alpha` over `base`.
pub fn over(c: RGBColor, alpha: f64, base: RGBColor) -> RGBColor {
    let m = |a: u8, b: u8| (f64::from(a) * alpha + f64::from(b) * (1.0 - alpha)).round() as u8;
    RGBColor(m(c.0, base.0), m(c.1, base.1), m(c.2, base.2))
}

/// How a legend entry is drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum Mark {
    /// A line sample.
    Line {
        /// Colour.
        color: RGBColor,
        /// Width in design pixels.
        width: f64,
        /// Dashed or solid.
        dashed: bool,
    },
    /// A filled square.
    Swatch(RGBColor),
    /// A filled dot with a white ring.
    Dot(RGBColor),
    /// An open diamond.
    Diamond(RGBColor),
    /// An open circle.
    Ring(RGBColor),
    /// An arrow.
    Arrow(RGBColor),
}

/// One legend entry.
#[derive(Debug, Clone, PartialEq)]
pub struct LegendItem {
    /// The text.
    pub label: String,
    /// The sample.
    pub mark: Mark,
}

impl LegendItem {
    /// An entry.
    pub fn new(label: impl Into<String>, mark: Mark) -> Self {
        LegendItem {
            label: label.into(),
            mark,
        }
    }
}

const LEGEND_FONT: f64 = 13.0;
const LEGEND_SAMPLE: f64 = 26.0;
const LEGEND_GAP: f64 = 18.0;
const LEGEND_ROW: f64 = 22.0;

fn text_width(ctx: &PlotContext, size: f64, s: &str) -> f64 {
    let f = ctx.font(size);
    f.font
        .box_size(s)
        .map(|(w, _)| f64::from(w) / ctx.scale)
        .unwrap_or(size * 0.6 * s.chars().count() as f64)
}

/// Rows of a legend laid out in `width` design pixels: item indices per row and row widths.
fn legend_rows(ctx: &PlotContext, items: &[LegendItem], width: f64) -> Vec<(Vec<usize>, f64)> {
    let mut rows: Vec<(Vec<usize>, f64)> = Vec::new();
    for (i, it) in items.iter().enumerate() {
        let w = LEGEND_SAMPLE + 6.0 + text_width(ctx, LEGEND_FONT, &it.label);
        match rows.last_mut() {
            Some((idx, rw)) if *rw + LEGEND_GAP + w <= width => {
                idx.push(i);
                *rw += LEGEND_GAP + w;
            }
            _ => rows.push((vec![i], w)),
        }
    }
    rows
}

/// Draws the legend in a strip along the bottom of `root` and returns the area above it,
/// where the chart goes.
pub fn above_legend<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    items: &[LegendItem],
) -> DrawResult<DrawingArea<DB, Shift>, DB> {
    let (w, h) = ctx.pixels();
    let lh = ctx.px(legend_height(ctx, items, f64::from(w) / ctx.scale - 20.0));
    let (upper, lower) = root.split_vertically(h as i32 - lh);
    draw_legend(&lower, ctx, items)?;
    Ok(upper)
}

/// Height in design pixels of a legend of `items` in `width` design pixels.
pub fn legend_height(ctx: &PlotContext, items: &[LegendItem], width: f64) -> f64 {
    if items.is_empty() {
        return 0.0;
    }
    legend_rows(ctx, items, width).len() as f64 * LEGEND_ROW + 10.0
}

/// Draws a legend centred in `area` (rows wrap to its width).
pub fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    items: &[LegendItem],
) -> DrawResult<(), DB> {
    let (w, _) = area.dim_in_pixel();
    let width = f64::from(w) / ctx.scale;
    let font = ctx
        .font(LEGEND_FONT)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for (r, (idx, rw)) in legend_rows(ctx, items, width - 20.0).iter().enumerate() {
        let mut x = (width - rw) / 2.0;
        let y = 5.0 + LEGEND_ROW * (r as f64 + 0.5);
        for &i in idx {
            let it = &items[i];
            draw_mark(area, ctx, &it.mark, (x, y))?;
            area.draw(&Text::new(
                it.label.clone(),
                (ctx.px(x + LEGEND_SAMPLE + 6.0), ctx.px(y)),
                font.clone(),
            ))?;
            x += LEGEND_SAMPLE + 6.0 + text_width(ctx, LEGEND_FONT, &it.label) + LEGEND_GAP;
        }
    }
    Ok(())
}

fn draw_mark<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    mark: &Mark,
    (x, y): (f64, f64),
) -> DrawResult<(), DB> {
    let p = |a: f64, b: f64| (ctx.px(a), ctx.px(b));
    match mark {
        Mark::Line {
            color,
            width,
            dashed,
        } => {
            let st = color.stroke_width(ctx.upx(*width).max(1));
            if *dashed {
                for k in 0..3 {
                    let a = x + k as f64 * 9.5;
                    area.draw(&PathElement::new(vec![p(a, y), p(a + 6.0, y)], st))?;
                }
            } else {
                area.draw(&PathElement::new(
                    vec![p(x, y), p(x + LEGEND_SAMPLE, y)],
                    st,
                ))?;
            }
        }
        Mark::Swatch(c) => {
            area.draw(&Rectangle::new(
                [p(x + 3.0, y - 8.0), p(x + LEGEND_SAMPLE - 3.0, y + 8.0)],
                c.filled(),
            ))?;
            area.draw(&Rectangle::new(
                [p(x + 3.0, y - 8.0), p(x + LEGEND_SAMPLE - 3.0, y + 8.0)],
                palette::GREY.stroke_width(ctx.upx(1.0).max(1)),
            ))?;
        }
        Mark::Dot(c) => dot(area, ctx, p(x + LEGEND_SAMPLE / 2.0, y), 5.0, *c)?,
        Mark::Diamond(c) => diamond(area, ctx, p(x + LEGEND_SAMPLE / 2.0, y), 6.0, *c)?,
        Mark::Ring(c) => {
            let centre = p(x + LEGEND_SAMPLE / 2.0, y);
            area.draw(&Circle::new(
                centre,
                ctx.upx(3.5),
                c.stroke_width(ctx.upx(1.5)),
            ))?;
        }
        Mark::Arrow(c) => arrow(
            area,
            ctx,
            p(x + 2.0, y),
            p(x + LEGEND_SAMPLE - 2.0, y),
            *c,
            2.0,
        )?,
    }
    Ok(())
}

/// A filled dot of `r` design pixels with a white ring, at device point `c`.
pub fn dot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    c: (i32, i32),
    r: f64,
    color: RGBColor,
) -> DrawResult<(), DB> {
    area.draw(&Circle::new(c, ctx.upx(r + 1.5), WHITE.filled()))?;
    area.draw(&Circle::new(c, ctx.upx(r), color.filled()))
}

/// An open diamond of half-size `r` design pixels at device point `c`.
pub fn diamond<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    c: (i32, i32),
    r: f64,
    color: RGBColor,
) -> DrawResult<(), DB> {
    let d = ctx.px(r);
    let pts = vec![
        (c.0, c.1 - d),
        (c.0 + d, c.1),
        (c.0, c.1 + d),
        (c.0 - d, c.1),
        (c.0, c.1 - d),
    ];
    area.draw(&PathElement::new(pts, color.stroke_width(ctx.upx(2.0))))
}

/// An arrow from device point `a` to `b` with a filled head.
pub fn arrow<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    a: (i32, i32),
    b: (i32, i32),
    color: RGBColor,
    width: f64,
) -> DrawResult<(), DB> {
    let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
    let len = dx.hypot(dy).max(1.0);
    let (ux, uy) = (dx / len, dy / len);
    let head = f64::from(ctx.px(9.0)).min(0.6 * len);
    let half = 0.45 * head;
    let base = (f64::from(b.0) - ux * head, f64::from(b.1) - uy * head);
    area.draw(&PathElement::new(
        vec![a, (base.0.round() as i32, base.1.round() as i32)],
        color.stroke_width(ctx.upx(width).max(1)),
    ))?;
    let tri = vec![
        b,
        (
            (base.0 - uy * half).round() as i32,
            (base.1 + ux * half).round() as i32,
        ),
        (
            (base.0 + uy * half).round() as i32,
            (base.1 - ux * half).round() as i32,
        ),
    ];
    area.draw(&Polygon::new(tri, color.filled()))
}

/// The pieces of a polyline inside the window [x0, x1] × [y0, y1]: NaN points break it and
/// each segment is clipped (Liang–Barsky).
pub fn clip_polyline(pts: &[(f64, f64)], x: (f64, f64), y: (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let finish = |cur: &mut Vec<(f64, f64)>, out: &mut Vec<Vec<(f64, f64)>>| {
        if cur.len() >= 2 {
            out.push(std::mem::take(cur));
        } else {
            cur.clear();
        }
    };
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
            finish(&mut cur, &mut out);
            continue;
        }
        match clip_segment(a, b, x, y) {
            Some((p, q)) => {
                let joined = cur.last().is_some_and(|l| *l == p);
                if !joined {
                    finish(&mut cur, &mut out);
                    cur.push(p);
                }
                cur.push(q);
                if q != b {
                    finish(&mut cur, &mut out);
                }
            }
            None => finish(&mut cur, &mut out),
        }
    }
    finish(&mut cur, &mut out);
    out
}

/// `text` in lines no wider than `room` pixels in `font`, broken at spaces (a word wider
/// than `room` keeps a line of its own).
pub(crate) fn wrap(font: &TextStyle, text: &str, room: f64) -> Vec<String> {
    let width = |t: &str| f64::from(font.font.box_size(t).map_or(0, |b| b.0));
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(l) if width(&format!("{l} {word}")) <= room => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    if lines.is_empty() {
        lines.push(String::new());
    }
    lines
}

/// The part of the segment from `a` to `b` inside the box `x` × `y` (Liang–Barsky), `None`
/// when it misses the box.
pub(crate) fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    x: (f64, f64),
    y: (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a.0 - x.0),
        (dx, x.1 - a.0),
        (-dy, a.1 - y.0),
        (dy, y.1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            a
        } else if t == 1.0 {
            b
        } else {
            (a.0 + t * dx, a.1 + t * dy)
        }
    };
    Some((at(t0), at(t1)))
}

/// A box in device pixels: (x0, y0, x1, y1).
pub type PixelBox = (i32, i32, i32, i32);

fn overlaps(a: &PixelBox, b: &PixelBox) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Places text boxes without overlaps: each label tries its candidate positions in order
/// and takes the first that stays inside the bounds and clear of earlier boxes.
pub struct LabelPlacer {
    bounds: PixelBox,
    taken: Vec<PixelBox>,
}

impl LabelPlacer {
    /// A placer for the device-pixel box `bounds`.
    pub fn new(bounds: PixelBox) -> Self {
        LabelPlacer {
            bounds,
            taken: Vec::new(),
        }
    }

    /// Marks a box as occupied (a marker, a curve's neighbourhood).
    pub fn block(&mut self, b: PixelBox) {
        self.taken.push(b);
    }

    /// The first free position among `candidates` (top-left corners) for a `w` × `h` box,
    /// taken; `None` when every candidate is blocked or out of bounds.
    pub fn try_place(&mut self, w: i32, h: i32, candidates: &[(i32, i32)]) -> Option<(i32, i32)> {
        let b = candidates
            .iter()
            .map(|&(x, y)| (x, y, x + w, y + h))
            .find(|b| self.fits(b) && !self.taken.iter().any(|t| overlaps(t, b)))?;
        self.taken.push(b);
        Some((b.0, b.1))
    }

    fn fits(&self, b: &PixelBox) -> bool {
        b.0 >= self.bounds.0 && b.1 >= self.bounds.1 && b.2 <= self.bounds.2 && b.3 <= self.bounds.3
    }

    /// The top-left corner for a `w` × `h` box among `candidates` (top-left corners); when
    /// every candidate is blocked, the free position nearest the first candidate (searched
    /// on rings around it, out to three box sizes); when there is none, the first candidate
    /// clamped into the bounds.
    pub fn place(&mut self, w: i32, h: i32, candidates: &[(i32, i32)]) -> (i32, i32) {
        if let Some(at) = self.try_place(w, h, candidates) {
            return at;
        }
        let (x, y) = candidates
            .first()
            .copied()
            .unwrap_or((self.bounds.0, self.bounds.1));
        if let Some(at) = self.try_place(w, h, &rings((x, y), w, h)) {
            return at;
        }
        self.force(w, h, (x, y))
    }

    /// Takes a `w` × `h` box at `(x, y)` clamped into the bounds, free or not: for a label
    /// that must stay where it is (a region's name inside its region).
    pub fn force(&mut self, w: i32, h: i32, (x, y): (i32, i32)) -> (i32, i32) {
        let x = x.clamp(self.bounds.0, (self.bounds.2 - w).max(self.bounds.0));
        let y = y.clamp(self.bounds.1, (self.bounds.3 - h).max(self.bounds.1));
        self.taken.push((x, y, x + w, y + h));
        (x, y)
    }
}

/// The smallest of 1, 2 and 5 times a power of ten that is at least `v` (> 0).
pub fn round_step_at_least(v: f64) -> f64 {
    if !(v > 0.0) || !v.is_finite() {
        return 1.0;
    }
    let p = 10f64.powf(v.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&s| s >= v * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// Positions on rings around `(x, y)`, nearest first: steps of a quarter of the box's
/// smaller side, out to three times its larger side, 16 directions a ring.
pub fn rings_around((x, y): (i32, i32), w: i32, h: i32) -> Vec<(i32, i32)> {
    rings((x, y), w, h)
}

/// Positions on rings around a point ([`rings_around`]).
fn rings((x, y): (i32, i32), w: i32, h: i32) -> Vec<(i32, i32)> {
    let step = (w.min(h) / 4).max(1);
    let reach = 3 * w.max(h);
    let mut out = Vec::new();
    let mut r = step;
    while r <= reach {
        for k in 0..16 {
            let a = f64::from(k) * std::f64::consts::PI / 8.0;
            out.push((
                x + (f64::from(r) * a.cos()).round() as i32,
                y + (f64::from(r) * a.sin()).round() as i32,
            ));
        }
        r += step;
    }
    out
}

/// Size in device pixels of lines of text in `font`.
pub fn text_block_size(font: &TextStyle, lines: &[String], line_gap: f64) -> (i32, i32) {
    let mut w = 0;
    let mut h = 0.0;
    for l in lines {
        let (lw, lh) = font.font.box_size(l).unwrap_or((0, 0));
        w = w.max(lw as i32);
        h += f64::from(lh) * line_gap;
    }
    (w, h.round() as i32)
}

/// Draws lines of text from a top-left corner on a white, lightly framed background.
pub fn draw_text_block<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    font: &TextStyle,
    lines: &[String],
    top_left: (i32, i32),
    frame: Option<RGBColor>,
) -> DrawResult<(), DB> {
    let gap = 1.25;
    let (w, h) = text_block_size(font, lines, gap);
    let pad = ctx.px(4.0);
    let (x, y) = top_left;
    if let Some(c) = frame {
        area.draw(&Rectangle::new(
            [(x - pad, y - pad), (x + w + pad, y + h + pad)],
            WHITE.mix(0.88).filled(),
        ))?;
        area.draw(&Rectangle::new(
            [(x - pad, y - pad), (x + w + pad, y + h + pad)],
            c.stroke_width(ctx.upx(1.0).max(1)),
        ))?;
    }
    let f = font.pos(Pos::new(HPos::Left, VPos::Top));
    let mut yy = f64::from(y);
    for l in lines {
        let (_, lh) = font.font.box_size(l).unwrap_or((0, 0));
        area.draw(&Text::new(l.clone(), (x, yy.round() as i32), f.clone()))?;
        yy += f64::from(lh) * gap;
    }
    Ok(())
}

/// Decimals that resolve ticks over a span of `span`.
pub fn decimals_for(span: f64) -> usize {
    let step = nice_step(span, 12);
    (-step.log10().floor()).max(0.0) as usize
}

/// Draws the legend along the bottom and the title at the top of `root`, and returns `n`
/// side-by-side areas for the panels of a chart between them (stacked when a paper figure
/// is too narrow for them side by side).
pub fn panel_areas<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    legend: &[LegendItem],
    heading: &str,
    n: usize,
) -> DrawResult<Vec<DrawingArea<DB, Shift>>, DB> {
    let upper = above_legend(root, ctx, legend)?;
    let upper = title(&upper, ctx, heading)?;
    Ok(upper.split_evenly(ctx.panel_grid((1, n.max(1)))))
}

/// Draws a title centred at the top of `area` and returns the area below it; a figure
/// without titles (for print: its caption has it) keeps the whole area.
pub fn title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    text: &str,
) -> Result<DrawingArea<DB, Shift>, DrawingAreaErrorKind<DB::ErrorType>> {
    if !ctx.titles {
        return Ok(area.margin(ctx.px(6.0), 0, 0, 0));
    }
    let (w, _) = area.dim_in_pixel();
    let f = ctx.font(17.0).pos(Pos::new(HPos::Center, VPos::Top));
    area.draw(&Text::new(
        text.to_string(),
        (w as i32 / 2, ctx.px(10.0)),
        f,
    ))?;
    Ok(area.margin(ctx.px(38.0), 0, 0, 0))
}

/// The ticks of a logarithmic axis over [lo, hi] (lo > 0), each with its label: every
/// power of ten, with 2 and 5 times each where the range spans less than about three
/// decades (so that it carries more than two or three labels), and every integer multiple where it spans less than one (so that a short axis
/// still carries three labels or more); every other power of ten beyond eight decades.
/// Powers of ten are written `1e-2` (typeset as 10 with the superscript −2), multiples
/// `2×10^-2`; ten to the 0 and 1 as `1` and `10`, their multiples as plain numbers.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return Vec::new();
    }
    let span = (hi / lo).log10();
    let mantissas: &[u32] = if span < 1.0 {
        &[1, 2, 3, 4, 5, 6, 7, 8, 9]
    } else if span < 3.2 {
        &[1, 2, 5]
    } else {
        &[1]
    };
    let every = if span > 8.0 { 2 } else { 1 };
    let (e0, e1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let mut out = Vec::new();
    for e in e0..=e1 {
        for &m in mantissas {
            if m == 1 && e.rem_euclid(every) != 0 {
                continue;
            }
            let v = f64::from(m) * 10f64.powi(e);
            // A relative slack, so that the ends of a range of whole decades are ticked.
            if v < lo * (1.0 - 1e-9) || v > hi * (1.0 + 1e-9) {
                continue;
            }
            let label = match (m, e) {
                (_, 0) => m.to_string(),
                (_, 1) => (10 * m).to_string(),
                (1, _) => format!("1e{e}"),
                _ => format!("{m}×10^{e}"),
            };
            out.push((v, label));
        }
    }
    out
}

/// The room a label of a logarithmic x axis needs (`2×10³` at the tick font), design pixels.
const LOG_LABEL_WIDTH: f64 = 46.0;
/// The room a label of a logarithmic y axis needs, design pixels.
const LOG_LABEL_HEIGHT: f64 = 18.0;

/// The ticks of [`log_ticks`] over `(lo, hi)` at their pixels (`at` of each value), the 2
/// and 5 times of each decade left out when two neighbouring labels would run together on
/// a short axis (closer than a label's width on an x axis, `horizontal`, or its height on
/// a y axis): then the powers of ten alone are labelled.
pub fn placed_log_ticks(
    (lo, hi): (f64, f64),
    at: impl Fn(f64) -> i32,
    ctx: &PlotContext,
    horizontal: bool,
) -> Vec<(i32, String)> {
    let room = ctx.px(if horizontal {
        LOG_LABEL_WIDTH
    } else {
        LOG_LABEL_HEIGHT
    });
    let mut ticks: Vec<(i32, f64, String)> = log_ticks(lo, hi)
        .into_iter()
        .map(|(v, l)| (at(v), v, l))
        .collect();
    let crowded = ticks.windows(2).any(|w| (w[1].0 - w[0].0).abs() < room);
    let power_of_ten = |v: f64| (v.log10() - v.log10().round()).abs() < 1e-9;
    // An axis within one decade keeps its multiples: it would have one label or none.
    if crowded && ticks.iter().filter(|t| power_of_ten(t.1)).count() >= 2 {
        ticks.retain(|t| power_of_ten(t.1));
    }
    ticks.into_iter().map(|(p, _, l)| (p, l)).collect()
}

/// Which side of the plotting area an axis drawn by [`draw_ticks`] is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisSide {
    /// The y axis, at the left.
    Left,
    /// The x axis, at the bottom.
    Bottom,
}

/// Draws an axis's ticks on `area` (any part of the canvas): a tick mark, its label and a
/// faint grid line across the plotting area `plot` (absolute pixels, as
/// `plotting_area().get_pixel_range()` gives them) at each absolute pixel position of
/// `ticks`.
pub fn draw_ticks<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    plot: (std::ops::Range<i32>, std::ops::Range<i32>),
    side: AxisSide,
    ticks: &[(i32, String)],
) -> DrawResult<(), DB> {
    let (bx, by) = area.get_base_pixel();
    let (xr, yr) = plot;
    let ink = BLACK.stroke_width(ctx.upx(1.0).max(1));
    let grid = BLACK.mix(0.08).stroke_width(1);
    let (len, gap) = (ctx.px(5.0), ctx.px(8.0));
    for (p, label) in ticks {
        let (line, mark, at, pos) = match side {
            AxisSide::Left => (
                [(xr.start, *p), (xr.end, *p)],
                [(xr.start - len, *p), (xr.start, *p)],
                (xr.start - gap, *p),
                Pos::new(HPos::Right, VPos::Center),
            ),
            AxisSide::Bottom => (
                [(*p, yr.start), (*p, yr.end)],
                [(*p, yr.end), (*p, yr.end + len)],
                (*p, yr.end + gap),
                Pos::new(HPos::Center, VPos::Top),
            ),
        };
        let rel = |(x, y): (i32, i32)| (x - bx, y - by);
        area.draw(&PathElement::new(line.map(rel).to_vec(), grid))?;
        area.draw(&PathElement::new(mark.map(rel).to_vec(), ink))?;
        area.draw(&Text::new(label.clone(), rel(at), ctx.font(12.5).pos(pos)))?;
    }
    Ok(())
}

/// A "nice" tick step for a range, giving about `n` ticks.
pub fn nice_step(span: f64, n: usize) -> f64 {
    let raw = span / n.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_round_step_is_one_two_or_five_times_a_power_of_ten() {
        assert_eq!(round_step_at_least(0.16), 0.2);
        assert_eq!(round_step_at_least(0.033), 0.05);
        assert_eq!(round_step_at_least(0.1), 0.1);
        assert_eq!(round_step_at_least(3.0), 5.0);
        assert_eq!(round_step_at_least(7.0), 10.0);
        assert_eq!(round_step_at_least(0.0), 1.0);
    }

    #[test]
    fn a_short_log_axis_labels_only_the_powers_of_ten() {
        let ctx = PlotContext::new(crate::plot::Format::Svg, (800, 600));
        // Three decades over 300 px: 2×10² would stand 30 px from 10², closer than a label.
        let at = |w: f64| move |v: f64| ((v / 10.0).log10() / 3.0 * w).round() as i32;
        let labels = |w: f64| -> Vec<String> {
            placed_log_ticks((10.0, 1e4), at(w), &ctx, true)
                .into_iter()
                .map(|t| t.1)
                .collect()
        };
        assert_eq!(labels(300.0), ["10", "1e2", "1e3", "1e4"]);
        // Over 1200 px the 2 and 5 times have room.
        assert_eq!(labels(1200.0).len(), 10);
        assert!(labels(1200.0).contains(&"2×10^2".to_string()));
        // Within one decade the multiples stay: without them the axis would have one label.
        let within = placed_log_ticks((2.0, 9.0), |v| (v * 5.0) as i32, &ctx, true);
        assert!(within.len() >= 3, "{within:?}");
    }

    #[test]
    fn log_ticks_label_every_decade_and_more_on_short_axes() {
        let labels =
            |lo, hi| -> Vec<String> { log_ticks(lo, hi).into_iter().map(|t| t.1).collect() };
        // Five decades: the powers of ten only.
        assert_eq!(
            labels(1e-3, 1e2),
            ["1e-3", "1e-2", "1e-1", "1", "10", "1e2"]
        );
        // From 0.15 to 80 (2.7 decades): 2 and 5 times each decade too, not 1 and 10 alone.
        assert_eq!(
            labels(0.15, 80.0),
            ["2×10^-1", "5×10^-1", "1", "2", "5", "10", "20", "50"]
        );
        // From 0.012 to 0.86 (under two decades): 2 and 5 times each decade too.
        let t = log_ticks(0.012, 0.86);
        let values: Vec<f64> = t.iter().map(|t| t.0).collect();
        let expected = [0.02, 0.05, 0.1, 0.2, 0.5];
        assert_eq!(values.len(), expected.len(), "{t:?}");
        for (v, e) in values.iter().zip(expected) {
            assert!((v - e).abs() < 1e-12 * e, "{v} against {e}");
        }
        assert_eq!(t[0].1, "2×10^-2");
        assert_eq!(t[2].1, "1e-1");
        // Inside one decade: every multiple.
        assert_eq!(
            labels(0.25, 0.8),
            [
                "3×10^-1", "4×10^-1", "5×10^-1", "6×10^-1", "7×10^-1", "8×10^-1"
            ]
        );
        // Ten decades: every other power of ten.
        assert_eq!(
            labels(1e-10, 1.0),
            ["1e-10", "1e-8", "1e-6", "1e-4", "1e-2", "1"]
        );
        assert!(log_ticks(0.0, 1.0).is_empty());
    }

    #[test]
    fn clipping_keeps_inside_pieces_and_breaks_at_nan() {
        let pts = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 2.0),
            (f64::NAN, 1.0),
            (0.5, 0.5),
            (0.6, 0.6),
        ];
        let out = clip_polyline(&pts, (-1.0, 1.0), (-1.0, 1.0));
        assert_eq!(out.len(), 2, "{out:?}");
        assert_eq!(out[0], vec![(0.0, 0.0), (1.0, 0.0)]);
        assert_eq!(out[1], vec![(0.5, 0.5), (0.6, 0.6)]);
    }

    #[test]
    fn placer_avoids_taken_boxes() {
        let mut p = LabelPlacer::new((0, 0, 100, 100));
        p.block((0, 0, 50, 50));
        assert_eq!(p.place(10, 10, &[(10, 10), (60, 10)]), (60, 10));
        // Every candidate blocked: the nearest free place around the first, not on top.
        let at = p.place(10, 10, &[(20, 20)]);
        assert!(
            !overlaps(&(at.0, at.1, at.0 + 10, at.1 + 10), &(0, 0, 50, 50)),
            "{at:?}"
        );
        assert!(
            !overlaps(&(at.0, at.1, at.0 + 10, at.1 + 10), &(60, 10, 70, 20)),
            "{at:?}"
        );
        let d = f64::from(at.0 - 20).hypot(f64::from(at.1 - 20));
        assert!(d <= 45.0, "{at:?} is {d} px away");
    }
}
