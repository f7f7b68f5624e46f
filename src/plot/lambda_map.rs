//! The collapse load factor λ_max as a colour map over (μ, K), with the regions of each
//! collapse mechanism outlined by the located mechanism changes and named, a colour bar and,
//! when the grid has it, μ = ∞ as its own strip. The chart holds data already reduced to the
//! figure's resolution (a raster of a few hundred cells a side), whatever the grid's size.

use super::style::{self, LabelPlacer, LegendItem, Mark, clip_polyline, decimals_for, palette};
use super::{Figure, PlotContext, Window, XyChart as Chart};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// The μ = ∞ column of the grid along K, at the raster's K cells.
#[derive(Debug, Clone, PartialEq)]
pub struct LambdaStrip {
    /// λ at the centre of each K cell (NaN: no finite λ).
    pub lambda: Vec<f64>,
    /// The located mechanism changes along K at μ = ∞.
    pub changes: Vec<f64>,
}

/// What the λ map shows.
#[derive(Debug, Clone, PartialEq)]
pub struct LambdaMap {
    /// Title.
    pub title: String,
    /// The finite μ range and the K range of the grid.
    pub window: ((f64, f64), (f64, f64)),
    /// Raster cells along μ.
    pub nx: usize,
    /// Raster cells along K.
    pub ny: usize,
    /// λ at the centre of each raster cell, K-major (NaN: no finite λ).
    pub lambda: Vec<f64>,
    /// The collapse mechanism at the centre of each raster cell, K-major, as an index into
    /// `mechanisms` (None: no mechanism).
    pub mechanism: Vec<Option<u8>>,
    /// Mechanism names.
    pub mechanisms: Vec<String>,
    /// The located mechanism changes joined between neighbouring grid lines, (μ, K).
    pub boundaries: Vec<Vec<(f64, f64)>>,
    /// λ at the two ends of the colour scale.
    pub lambda_range: (f64, f64),
    /// A logarithmic colour scale (λ spans more than a factor of 30).
    pub log: bool,
    /// The grid's μ = ∞ column.
    pub infinite: Option<LambdaStrip>,
    /// The grid points of finite μ where the collapse (the first complete solution) comes
    /// before λ_max, (μ, K), ringed: the non-associative gap. Empty when none has one.
    pub gaps: Vec<(f64, f64)>,
}

/// Colour stops of the scale (viridis), from the smallest λ to the largest.
const SCALE: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (71, 44, 122),
    (59, 81, 139),
    (44, 113, 142),
    (33, 144, 141),
    (39, 173, 129),
    (92, 200, 99),
    (170, 220, 50),
    (253, 231, 37),
];

/// Fill where no finite λ exists.
const NO_VALUE: RGBColor = RGBColor(215, 215, 215);

/// Width of the μ = ∞ strip, its gap, the colour bar and its gap, design pixels. The strip
/// sits close to the plot, after a break in the μ axis, and the colour bar well apart from
/// it, so that the strip reads as a part of the map and not as a second colour bar.
const STRIP_WIDTH: f64 = 26.0;
const STRIP_GAP: f64 = 12.0;
const BAR_WIDTH: f64 = 16.0;
const BAR_GAP: f64 = 64.0;

impl LambdaMap {
    /// The place of λ on the colour scale, 0 at the smallest and 1 at the largest.
    pub fn scale_position(&self, lambda: f64) -> f64 {
        let (lo, hi) = self.lambda_range;
        let t = if self.log {
            (lambda.ln() - lo.ln()) / (hi.ln() - lo.ln())
        } else {
            (lambda - lo) / (hi - lo)
        };
        if t.is_finite() {
            t.clamp(0.0, 1.0)
        } else {
            0.5
        }
    }

    /// The colour of λ (grey where it is not finite).
    pub fn color(&self, lambda: f64) -> RGBColor {
        if !lambda.is_finite() {
            return NO_VALUE;
        }
        let t = self.scale_position(lambda) * (SCALE.len() - 1) as f64;
        let i = (t.floor() as usize).min(SCALE.len() - 2);
        let f = t - i as f64;
        let (a, b) = (SCALE[i], SCALE[i + 1]);
        let m = |x: u8, y: u8| (f64::from(x) + (f64::from(y) - f64::from(x)) * f).round() as u8;
        RGBColor(m(a.0, b.0), m(a.1, b.1), m(a.2, b.2))
    }

    /// The mechanism a cell is drawn with: none where it has no finite λ (drawn grey,
    /// whatever the classification of its place says).
    fn drawn_mechanism(&self, c: usize) -> Option<u8> {
        self.mechanism[c].filter(|_| self.lambda[c].is_finite())
    }

    /// For each mechanism, the raster cell (i, j) of finite λ farthest from another
    /// mechanism, from grey cells and from the border: where its name fits best (two-pass
    /// chamfer distance, in cells).
    pub fn label_cells(&self) -> Vec<(u8, usize, usize)> {
        let (nx, ny) = (self.nx, self.ny);
        let at = |i: usize, j: usize| self.drawn_mechanism(j * nx + i);
        let mut d = vec![f64::INFINITY; nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                let edge = i == 0 || j == 0 || i + 1 == nx || j + 1 == ny;
                let differs = || {
                    [(i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)]
                        .iter()
                        .any(|&(a, b)| at(a, b) != at(i, j))
                };
                if edge || differs() {
                    d[j * nx + i] = 0.0;
                }
            }
        }
        let mut relax = |i: usize, j: usize, di: isize, dj: isize| {
            let (a, b) = (i as isize + di, j as isize + dj);
            if a >= 0 && b >= 0 && (a as usize) < nx && (b as usize) < ny {
                let step = if di != 0 && dj != 0 { 1.414 } else { 1.0 };
                let c = d[b as usize * nx + a as usize] + step;
                if c < d[j * nx + i] {
                    d[j * nx + i] = c;
                }
            }
        };
        for j in 0..ny {
            for i in 0..nx {
                for (di, dj) in [(-1, 0), (0, -1), (-1, -1), (1, -1)] {
                    relax(i, j, di, dj);
                }
            }
        }
        for j in (0..ny).rev() {
            for i in (0..nx).rev() {
                for (di, dj) in [(1, 0), (0, 1), (1, 1), (-1, 1)] {
                    relax(i, j, di, dj);
                }
            }
        }
        let mut out = Vec::new();
        for m in 0..self.mechanisms.len() as u8 {
            let best = (0..nx * ny)
                .filter(|&c| self.drawn_mechanism(c) == Some(m))
                .max_by(|&a, &b| d[a].total_cmp(&d[b]).then(b.cmp(&a)));
            if let Some(c) = best {
                out.push((m, c % nx, c / nx));
            }
        }
        out
    }

    fn legend(&self) -> Vec<LegendItem> {
        let mut items = Vec::new();
        if !self.boundaries.is_empty() {
            items.push(LegendItem::new(
                "located change of the collapse mechanism",
                Mark::Line {
                    color: palette::INK,
                    width: 1.4,
                    dashed: false,
                },
            ));
        }
        let strip = self.infinite.iter().flat_map(|s| s.lambda.iter());
        if self.lambda.iter().chain(strip).any(|l| !l.is_finite()) {
            items.push(LegendItem::new("no finite λ", Mark::Swatch(NO_VALUE)));
        }
        if !self.gaps.is_empty() {
            items.push(LegendItem::new(
                "collapse before λ_max (a gap)",
                Mark::Dot(palette::GAP),
            ));
        }
        items
    }
}

impl Figure for LambdaMap {
    fn size(&self) -> (u32, u32) {
        (820, 640)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let upper = style::above_legend(root, ctx, &self.legend())?;
        let window = self.window;
        let ((mu0, mu1), (k0, k1)) = window;
        let strip = if self.infinite.is_some() {
            STRIP_GAP + STRIP_WIDTH
        } else {
            0.0
        };
        let mut builder = ChartBuilder::on(&upper);
        if ctx.titles {
            builder.caption(&self.title, ctx.font(17.0));
        }
        let mut chart = builder
            .margin(ctx.px(10.0))
            // Room above the plot for the μ = ∞ strip's heading.
            .margin_top(ctx.px(if strip > 0.0 { 30.0 } else { 10.0 }))
            .margin_right(ctx.px(strip + BAR_GAP + BAR_WIDTH + 96.0))
            .x_label_area_size(ctx.px(50.0))
            .y_label_area_size(ctx.px(72.0))
            .build_cartesian_2d(mu0..mu1, k0..k1)?;
        super::frames::record(&chart, (mu0, mu1), (k0, k1), false);
        self.draw_raster(&mut chart, window)?;
        super::draw_mu_k_mesh(&mut chart, ctx, window, false)?;
        for line in &self.boundaries {
            for piece in clip_polyline(line, (mu0, mu1), (k0, k1)) {
                // A white line with a dark core reads on every colour of the scale.
                chart.draw_series(LineSeries::new(
                    piece.clone(),
                    WHITE.stroke_width(ctx.upx(3.0)),
                ))?;
                chart.draw_series(LineSeries::new(
                    piece,
                    palette::INK.stroke_width(ctx.upx(1.0).max(1)),
                ))?;
            }
        }
        for &(mu, k) in &self.gaps {
            let c = chart.backend_coord(&(mu, k));
            root.draw(&Circle::new(
                c,
                ctx.upx(4.5),
                WHITE.stroke_width(ctx.upx(3.2)),
            ))?;
            root.draw(&Circle::new(
                c,
                ctx.upx(4.5),
                palette::GAP.stroke_width(ctx.upx(1.8)),
            ))?;
        }
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let mut x = xr.end;
        if let Some(s) = &self.infinite {
            x += ctx.px(STRIP_GAP);
            self.draw_strip(root, ctx, s, (x, x + ctx.px(STRIP_WIDTH)), yr.clone())?;
            x += ctx.px(STRIP_WIDTH);
        }
        x += ctx.px(BAR_GAP);
        self.draw_bar(root, ctx, (x, x + ctx.px(BAR_WIDTH)), yr)?;
        self.draw_names(root, &chart, ctx)
    }
}

impl LambdaMap {
    /// The raster as runs of equal colour along each row.
    fn draw_raster<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<DB>,
        ((mu0, mu1), (k0, k1)): Window,
    ) -> DrawResult<(), DB> {
        let (nx, ny) = (self.nx, self.ny);
        let (dm, dk) = ((mu1 - mu0) / nx as f64, (k1 - k0) / ny as f64);
        let mut rects = Vec::new();
        for j in 0..ny {
            let mut i = 0;
            while i < nx {
                let c = self.color(self.lambda[j * nx + i]);
                let start = i;
                while i < nx && self.color(self.lambda[j * nx + i]) == c {
                    i += 1;
                }
                // A little overlap with the next row and run, so that no seam shows.
                let x1 = (mu0 + dm * (i as f64 + 0.3)).min(mu1);
                let y1 = (k0 + dk * (j as f64 + 1.3)).min(k1);
                rects.push(Rectangle::new(
                    [(mu0 + dm * start as f64, k0 + dk * j as f64), (x1, y1)],
                    c.filled(),
                ));
            }
        }
        chart.draw_series(rects)?;
        Ok(())
    }

    /// The μ = ∞ strip between `x` columns, over the plot's rows `yr`.
    fn draw_strip<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
        s: &LambdaStrip,
        (x0, x1): (i32, i32),
        yr: std::ops::Range<i32>,
    ) -> DrawResult<(), DB> {
        let ny = s.lambda.len().max(1);
        let h = f64::from(yr.end - yr.start);
        let y = |f: f64| yr.end - (h * f).round() as i32;
        for (j, l) in s.lambda.iter().enumerate() {
            let (a, b) = (j as f64 / ny as f64, (j + 1) as f64 / ny as f64);
            root.draw(&Rectangle::new(
                [(x0, y(b) - 1), (x1, y(a))],
                self.color(*l).filled(),
            ))?;
        }
        let (k0, k1) = self.window.1;
        for k in s.changes.iter().filter(|k| **k >= k0 && **k <= k1) {
            let py = y((k - k0) / (k1 - k0));
            root.draw(&PathElement::new(
                vec![(x0, py), (x1, py)],
                WHITE.stroke_width(ctx.upx(3.0)),
            ))?;
            root.draw(&PathElement::new(
                vec![(x0, py), (x1, py)],
                palette::INK.stroke_width(ctx.upx(1.0).max(1)),
            ))?;
        }
        let frame = BLACK.stroke_width(ctx.upx(1.0).max(1));
        root.draw(&Rectangle::new([(x0, yr.start), (x1, yr.end)], frame))?;
        // A break in the μ axis between the plot and the strip: two slanted strokes across
        // the gap, on the axis.
        let gap = ctx.px(STRIP_GAP);
        let (d, lean) = (gap / 4, ctx.px(5.0));
        for x in [x0 - gap + d, x0 - d] {
            root.draw(&PathElement::new(
                vec![(x - lean / 2, yr.end + lean), (x + lean / 2, yr.end - lean)],
                BLACK.stroke_width(ctx.upx(1.2).max(1)),
            ))?;
        }
        root.draw(&Text::new(
            "∞".to_string(),
            ((x0 + x1) / 2, yr.end + ctx.px(8.0)),
            ctx.font(13.0).pos(Pos::new(HPos::Center, VPos::Top)),
        ))?;
        // Named over its top as well: a strip of colour beside a map could be read as a
        // second colour bar.
        root.draw(&Text::new(
            "μ = ∞".to_string(),
            ((x0 + x1) / 2, yr.start - ctx.px(6.0)),
            ctx.font(13.0).pos(Pos::new(HPos::Center, VPos::Bottom)),
        ))
    }

    /// The colour bar between `x` columns, over the plot's rows `yr`, with its ticks and the
    /// label λ_max.
    fn draw_bar<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
        (x0, x1): (i32, i32),
        yr: std::ops::Range<i32>,
    ) -> DrawResult<(), DB> {
        let (lo, hi) = self.lambda_range;
        let h = f64::from(yr.end - yr.start);
        let steps = 120;
        for s in 0..steps {
            let (a, b) = (s as f64 / steps as f64, (s + 1) as f64 / steps as f64);
            let mid = 0.5 * (a + b);
            let lambda = if self.log {
                lo * (hi / lo).powf(mid)
            } else {
                lo + (hi - lo) * mid
            };
            root.draw(&Rectangle::new(
                [
                    (x0, yr.end - (h * b).round() as i32 - 1),
                    (x1, yr.end - (h * a).round() as i32),
                ],
                self.color(lambda).filled(),
            ))?;
        }
        let frame = BLACK.stroke_width(ctx.upx(1.0).max(1));
        root.draw(&Rectangle::new([(x0, yr.start), (x1, yr.end)], frame))?;
        let ticks: Vec<(f64, String)> = if self.log {
            style::log_ticks(lo, hi)
        } else {
            let step = style::nice_step(hi - lo, 6);
            let dec = decimals_for(hi - lo);
            let mut t = (lo / step).ceil() * step;
            let mut v = Vec::new();
            while t <= hi + 1e-12 * hi.abs().max(1.0) {
                v.push((t, format!("{t:.dec$}")));
                t += step;
            }
            v
        };
        let font = ctx.font(12.5).pos(Pos::new(HPos::Left, VPos::Center));
        for (v, label) in ticks {
            let py = yr.end - (h * self.scale_position(v)).round() as i32;
            root.draw(&PathElement::new(
                vec![(x1, py), (x1 + ctx.px(4.0), py)],
                frame,
            ))?;
            root.draw(&Text::new(label, (x1 + ctx.px(7.0), py), font.clone()))?;
        }
        let desc = ctx
            .font(14.0)
            .transform(FontTransform::Rotate90)
            .pos(Pos::new(HPos::Center, VPos::Bottom));
        root.draw(&Text::new(
            "collapse load factor λ_max".to_string(),
            (x1 + ctx.px(70.0), (yr.start + yr.end) / 2),
            desc,
        ))
    }

    /// Each mechanism's name where its region is deepest, on a white ground.
    fn draw_names<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &Chart<DB>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let mut placer = LabelPlacer::new((xr.start, yr.start, xr.end, yr.end));
        let ((mu0, mu1), (k0, k1)) = self.window;
        let font = ctx.font_with(13.0, FontStyle::Bold);
        let pad = ctx.px(3.0);
        for (m, i, j) in self.label_cells() {
            let name = self.mechanisms[m as usize].to_uppercase();
            let c = chart.backend_coord(&(
                mu0 + (mu1 - mu0) * (i as f64 + 0.5) / self.nx as f64,
                k0 + (k1 - k0) * (j as f64 + 0.5) / self.ny as f64,
            ));
            let (w, h) = style::text_block_size(&font, std::slice::from_ref(&name), 1.0);
            let (bw, bh) = (w + 2 * pad, h + 2 * pad);
            let mut near = vec![(c.0 - bw / 2, c.1 - bh / 2)];
            near.extend(style::rings_around(near[0], bw, bh));
            let Some(at) = placer.try_place(bw, bh, &near) else {
                continue;
            };
            root.draw(&Rectangle::new(
                [at, (at.0 + bw, at.1 + bh)],
                WHITE.mix(0.85).filled(),
            ))?;
            root.draw(&Text::new(
                name,
                (at.0 + pad, at.1 + pad),
                font.color(&palette::mechanism(&self.mechanisms[m as usize]))
                    .pos(Pos::new(HPos::Left, VPos::Top)),
            ))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(log: bool, range: (f64, f64)) -> LambdaMap {
        LambdaMap {
            title: String::new(),
            window: ((0.0, 1.0), (1.0, 2.0)),
            nx: 1,
            ny: 1,
            lambda: vec![0.5],
            mechanism: vec![None],
            mechanisms: Vec::new(),
            boundaries: Vec::new(),
            lambda_range: range,
            log,
            infinite: None,
            gaps: Vec::new(),
        }
    }

    #[test]
    fn a_mechanism_is_named_inside_its_cells_of_finite_lambda() {
        // Ten by ten cells, all classified as mechanism 0, finite λ only in the 3 × 3 block of
        // the top-right corner: the name goes there, not into the grey middle.
        let mut m = map(false, (0.0, 1.0));
        (m.nx, m.ny) = (10, 10);
        m.mechanisms = vec!["mixed".into()];
        m.mechanism = vec![Some(0); 100];
        m.lambda = (0..100)
            .map(|c| {
                if c % 10 >= 7 && c / 10 >= 7 {
                    0.5
                } else {
                    f64::NAN
                }
            })
            .collect();
        let cells = m.label_cells();
        assert_eq!(cells.len(), 1);
        let (_, i, j) = cells[0];
        assert!(i >= 7 && j >= 7, "({i}, {j})");
    }

    #[test]
    fn colour_scale_places_lambda_by_its_logarithm_or_linearly() {
        let m = map(true, (0.01, 1.0));
        assert!((m.scale_position(0.1) - 0.5).abs() < 1e-12);
        assert!((m.scale_position(10f64.powf(-1.5)) - 0.25).abs() < 1e-12);
        // Below the scale: its lowest colour.
        assert_eq!(m.scale_position(1e-4), 0.0);
        assert_eq!(m.color(1e-4), m.color(0.01));
        assert_eq!(m.color(1.0), RGBColor(253, 231, 37));
        assert_eq!(m.color(f64::NAN), NO_VALUE);
        let m = map(false, (0.2, 0.6));
        assert!((m.scale_position(0.3) - 0.25).abs() < 1e-12);
        assert_eq!(m.color(0.2), RGBColor(68, 1, 84));
    }
}
