//! The labels of the regime map: the bifurcations' values, the collapse curve's mechanisms
//! and the regions' names, each placed where it fits best.

use super::{REGIME_ORDER, RegimeMap};
use crate::plot::style::{self, LabelPlacer, PixelBox, clip_polyline, palette};
use crate::plot::{PlotContext, Window, XyChart as Chart};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

fn region_label(regime: &str) -> [&'static str; 2] {
    match regime {
        "stable" => ["STABLE", "Hʳ ∩ Hˢ ≠ ∅"],
        "rotational" => ["ROTATIONAL", "Hʳ = ∅"],
        "mixed" => ["MIXED", "Hʳ ∩ Hˢ = ∅"],
        "sliding" => ["SLIDING", "Hˢ = ∅"],
        _ => ["NONE", "Hʳ = Hˢ = ∅"],
    }
}

/// For each regime, the cell farthest (in plot pixels) from any other regime or the border:
/// where its label fits best. Two-pass chamfer distance transform.
fn label_cells(m: &RegimeMap, dx: f64, dy: f64) -> Vec<(String, usize, usize, f64)> {
    let (nx, ny) = (m.mu.len(), m.k.len());
    // Each cell's regime as a small number (its place among the names met), compared
    // without reading the names again.
    let mut names: Vec<&str> = Vec::new();
    let codes: Vec<usize> = m
        .regimes
        .iter()
        .map(|r| match r.as_deref() {
            None => 0,
            Some(name) => {
                1 + names.iter().position(|&n| n == name).unwrap_or_else(|| {
                    names.push(name);
                    names.len() - 1
                })
            }
        })
        .collect();
    let at = |i: usize, j: usize| codes[j * nx + i];
    let mut d = vec![f64::INFINITY; nx * ny];
    let diag = dx.hypot(dy);
    for j in 0..ny {
        for i in 0..nx {
            let r = at(i, j);
            let border = i == 0 || j == 0 || i + 1 == nx || j + 1 == ny;
            let differs = |a: usize, b: usize| at(a, b) != r;
            let edge = border
                || differs(i - 1, j)
                || differs(i + 1, j)
                || differs(i, j - 1)
                || differs(i, j + 1);
            if edge {
                d[j * nx + i] = 0.5 * dx.min(dy);
            }
        }
    }
    let pass = |d: &mut Vec<f64>, i: usize, j: usize, di: isize, dj: isize| {
        let (ii, jj) = (i as isize + di, j as isize + dj);
        if ii < 0 || jj < 0 || ii >= nx as isize || jj >= ny as isize {
            return;
        }
        let step = if di != 0 && dj != 0 {
            diag
        } else if di != 0 {
            dx
        } else {
            dy
        };
        let cand = d[jj as usize * nx + ii as usize] + step;
        if cand < d[j * nx + i] {
            d[j * nx + i] = cand;
        }
    };
    for j in 0..ny {
        for i in 0..nx {
            for (di, dj) in [(-1, 0), (0, -1), (-1, -1), (1, -1)] {
                pass(&mut d, i, j, di, dj);
            }
        }
    }
    for j in (0..ny).rev() {
        for i in (0..nx).rev() {
            for (di, dj) in [(1, 0), (0, 1), (1, 1), (-1, 1)] {
                pass(&mut d, i, j, di, dj);
            }
        }
    }
    // Among the cells nearly as deep as the deepest, the one nearest the region's centroid
    // (a wide region has a whole ridge of deepest cells).
    let mut out = Vec::new();
    for name in REGIME_ORDER {
        let Some(code) = names.iter().position(|&n| n == name).map(|p| p + 1) else {
            continue;
        };
        let cells: Vec<usize> = (0..nx * ny).filter(|&c| codes[c] == code).collect();
        if cells.is_empty() {
            continue;
        }
        let n = cells.len() as f64;
        let cx = cells.iter().map(|&c| (c % nx) as f64).sum::<f64>() / n;
        let cy = cells.iter().map(|&c| (c / nx) as f64).sum::<f64>() / n;
        let deepest = cells.iter().map(|&c| d[c]).fold(0.0, f64::max);
        let off = |c: usize| ((c % nx) as f64 - cx).abs() * dx + ((c / nx) as f64 - cy).abs() * dy;
        if let Some(&c) = cells
            .iter()
            .filter(|&&c| d[c] >= 0.9 * deepest)
            .min_by(|&&a, &&b| off(a).total_cmp(&off(b)))
        {
            out.push((name.to_string(), c % nx, c / nx, d[c]));
        }
    }
    out
}

/// Where along a collapse segment its label is tried, as fractions of its drawn length:
/// the middle first, then outwards.
const ALONG: [f64; 9] = [0.5, 0.4, 0.6, 0.3, 0.7, 0.2, 0.8, 0.1, 0.9];

/// The point at fraction `f` of the length of a polyline in pixels.
fn point_along(line: &[(i32, i32)], f: f64) -> (i32, i32) {
    let len = |a: (i32, i32), b: (i32, i32)| f64::from(a.0 - b.0).hypot(f64::from(a.1 - b.1));
    let total: f64 = line.windows(2).map(|w| len(w[0], w[1])).sum();
    let mut left = f * total;
    for w in line.windows(2) {
        let l = len(w[0], w[1]);
        if left <= l && l > 0.0 {
            let t = left / l;
            let at = |a: i32, b: i32| a + (f64::from(b - a) * t).round() as i32;
            return (at(w[0].0, w[1].0), at(w[0].1, w[1].1));
        }
        left -= l;
    }
    line[line.len() - 1]
}

/// The labels of the map, placed so that they do not overlap each other, the bifurcation
/// markers or the curves: bifurcations first (most important), then curve segments, then
/// regions.
pub(super) struct Labels<'a, 'c, DB: DrawingBackend> {
    map: &'a RegimeMap,
    chart: &'a Chart<'c, DB>,
    ctx: &'a PlotContext,
    window: Window,
    placer: LabelPlacer,
    /// The bifurcation points, in pixels.
    pts: Vec<(i32, i32)>,
}

impl<'a, 'c, DB: DrawingBackend> Labels<'a, 'c, DB> {
    /// A placer over the plotting area with the bifurcation markers and the curves blocked.
    pub(super) fn new(
        map: &'a RegimeMap,
        chart: &'a Chart<'c, DB>,
        ctx: &'a PlotContext,
        window: Window,
    ) -> Self {
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let bounds: PixelBox = (
            xr.start + ctx.px(4.0),
            yr.start + ctx.px(4.0),
            xr.end - ctx.px(4.0),
            yr.end - ctx.px(4.0),
        );
        let mut placer = LabelPlacer::new(bounds);
        let pts: Vec<(i32, i32)> = map
            .bifurcations
            .iter()
            .map(|b| chart.backend_coord(&(b.mu, b.k)))
            .collect();
        for p in &pts {
            let r = ctx.px(9.0);
            placer.block((p.0 - r, p.1 - r, p.0 + r, p.1 + r));
        }
        let mut labels = Labels {
            map,
            chart,
            ctx,
            window,
            placer,
            pts,
        };
        labels.block_curves();
        labels
    }

    /// Keeps labels off the curves: blocks a thin box around every piece of them.
    fn block_curves(&mut self) {
        let pad = self.ctx.px(4.0);
        let curves = self
            .map
            .collapse
            .iter()
            .map(|s| &s.points)
            .chain(self.map.other_boundaries.iter());
        for line in curves {
            for piece in clip_polyline(line, self.window.0, self.window.1) {
                for w in piece.windows(2) {
                    let (a, b) = (
                        self.chart.backend_coord(&w[0]),
                        self.chart.backend_coord(&w[1]),
                    );
                    // Short pieces, so that a diagonal blocks a band and not its bounding box.
                    let n = ((a.0 - b.0).abs().max((a.1 - b.1).abs()) / pad.max(1)).max(1);
                    for i in 0..n {
                        let p = (a.0 + (b.0 - a.0) * i / n, a.1 + (b.1 - a.1) * i / n);
                        let q = (
                            a.0 + (b.0 - a.0) * (i + 1) / n,
                            a.1 + (b.1 - a.1) * (i + 1) / n,
                        );
                        self.placer.block((
                            p.0.min(q.0) - pad,
                            p.1.min(q.1) - pad,
                            p.0.max(q.0) + pad,
                            p.1.max(q.1) + pad,
                        ));
                    }
                }
            }
        }
    }

    /// Each bifurcation's values in a box with a leader line to it, then its marker.
    pub(super) fn draw_bifurcations(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> DrawResult<(), DB> {
        let ctx = self.ctx;
        let ann_font = ctx.font(12.5);
        for (b, p) in self.map.bifurcations.iter().zip(&self.pts) {
            // The box is drawn with a padding round the text: the placer keeps it all free.
            let pad = ctx.px(4.0);
            let g = ctx.px(14.0);
            let box_of = |lines: &[String]| {
                let (tw, th) = style::text_block_size(&ann_font, lines, 1.25);
                (tw + 2 * pad, th + 2 * pad)
            };
            let near = |(bw, bh): (i32, i32)| {
                let mut c = vec![
                    (p.0 + g, p.1 + g),
                    (p.0 + g, p.1 - g - bh),
                    (p.0 + g, p.1 - bh / 2),
                    (p.0 - g - bw, p.1 + g),
                    (p.0 - g - bw, p.1 - g - bh),
                    (p.0 + 3 * g, p.1 + 3 * g),
                    (p.0 + 3 * g, p.1 - 3 * g - bh),
                ];
                c.extend(style::rings_around(c[0], bw, bh));
                c
            };
            // The full box where it fits; else the values on one line; else that line forced.
            let compact = std::slice::from_ref(&b.compact);
            let (full, short) = (box_of(&b.lines), box_of(compact));
            let (lines, (bw, bh), at) = match self.placer.try_place(full.0, full.1, &near(full)) {
                Some(at) => (&b.lines[..], full, at),
                None => {
                    let at = self.placer.place(short.0, short.1, &near(short));
                    (compact, short, at)
                }
            };
            // Leader line from the marker to the nearest corner of the box.
            let cx = if at.0 > p.0 { at.0 } else { at.0 + bw };
            let cy = if at.1 > p.1 { at.1 } else { at.1 + bh };
            root.draw(&PathElement::new(
                vec![*p, (cx, cy)],
                palette::INK.stroke_width(ctx.upx(1.0).max(1)),
            ))?;
            let text_at = (at.0 + pad, at.1 + pad);
            style::draw_text_block(root, ctx, &ann_font, lines, text_at, Some(palette::GREY))?;
        }
        for p in &self.pts {
            style::dot(root, ctx, *p, 5.5, palette::INK)?;
        }
        Ok(())
    }

    /// Each segment of the collapse curve named by its mechanism, beside the curve: at its
    /// middle if there is room, else at the nearest free place along it (never away from it:
    /// where no place beside the curve is free, the legend's line style names the segment).
    pub(super) fn draw_segments(&mut self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let ctx = self.ctx;
        let ((mu0, mu1), (k0, k1)) = self.window;
        let seg_font = ctx.font_with(13.0, FontStyle::Italic);
        for seg in &self.map.collapse {
            let inside: Vec<(i32, i32)> = seg
                .points
                .iter()
                .copied()
                .filter(|&(x, y)| x >= mu0 && x <= mu1 && y >= k0 && y <= k1)
                .map(|p| self.chart.backend_coord(&p))
                .collect();
            if inside.len() < 2 {
                continue;
            }
            let text = format!("{} collapse", seg.mechanism);
            let color = palette::mechanism(&seg.mechanism);
            let (tw, th) = style::text_block_size(&seg_font, std::slice::from_ref(&text), 1.0);
            let g = ctx.px(8.0);
            let beside = |c: (i32, i32)| {
                [
                    (c.0 - tw / 2, c.1 - g - th),
                    (c.0 + g, c.1 - th / 2),
                    (c.0 + g, c.1 - g - th),
                    (c.0 - tw / 2, c.1 + g),
                    (c.0 - g - tw, c.1 - th / 2),
                    (c.0 + g, c.1 + g),
                    (c.0 - g - tw, c.1 - g - th),
                    (c.0 - g - tw, c.1 + g),
                ]
            };
            let near: Vec<(i32, i32)> = ALONG
                .iter()
                .flat_map(|&f| beside(point_along(&inside, f)))
                .collect();
            let Some(at) = self.placer.try_place(tw, th, &near) else {
                continue;
            };
            root.draw(&Text::new(
                text,
                at,
                seg_font.color(&color).pos(Pos::new(HPos::Left, VPos::Top)),
            ))?;
        }
        Ok(())
    }

    /// Each region's name and condition at the cell where it fits best: the name and its
    /// condition; else the name; else the name in a smaller font; else that at the region's
    /// centre anyway (an unnamed region is worse than a tight label).
    pub(super) fn draw_regions(&mut self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let ctx = self.ctx;
        let (xr, yr) = self.chart.plotting_area().get_pixel_range();
        let dxp = f64::from(xr.end - xr.start) / self.map.mu.len() as f64;
        let dyp = f64::from(yr.end - yr.start) / self.map.k.len() as f64;
        let reg_font = ctx.font_with(13.0, FontStyle::Bold);
        let sub_font = ctx.font(12.0);
        for (name, i, j, _) in label_cells(self.map, dxp, dyp) {
            let c = self.chart.backend_coord(&(self.map.mu[i], self.map.k[j]));
            let [l1, l2] = region_label(&name);
            let (w1, h1) = style::text_block_size(&reg_font, &[l1.to_string()], 1.2);
            let (w2, h2) = style::text_block_size(&sub_font, &[l2.to_string()], 1.2);
            let g = ctx.px(6.0);
            let cands = |bw: i32, bh: i32| {
                [
                    (c.0 - bw / 2, c.1 - bh / 2),
                    (c.0 - bw / 2, c.1 - bh - g),
                    (c.0 - bw / 2, c.1 + g),
                    (c.0 + g, c.1 - bh / 2),
                    (c.0 - bw - g, c.1 - bh / 2),
                ]
            };
            let (bw, bh) = (w1.max(w2), h1 + h2);
            let small = ctx.font_with(10.5, FontStyle::Bold);
            let (w3, h3) = style::text_block_size(&small, &[l1.to_string()], 1.2);
            let top = Pos::new(HPos::Center, VPos::Top);
            if let Some(at) = self.placer.try_place(bw, bh, &cands(bw, bh)) {
                let mid = at.0 + bw / 2;
                root.draw(&Text::new(l1.to_string(), (mid, at.1), reg_font.pos(top)))?;
                root.draw(&Text::new(
                    l2.to_string(),
                    (mid, at.1 + h1),
                    sub_font.pos(top),
                ))?;
            } else if let Some(at) = self.placer.try_place(w1, h1, &cands(w1, h1)) {
                root.draw(&Text::new(
                    l1.to_string(),
                    (at.0 + w1 / 2, at.1),
                    reg_font.pos(top),
                ))?;
            } else if let Some(at) = self.placer.try_place(w3, h3, &cands(w3, h3)) {
                root.draw(&Text::new(
                    l1.to_string(),
                    (at.0 + w3 / 2, at.1),
                    small.pos(top),
                ))?;
            }
            // A region with no free place for its name is named by the colour legend alone:
            // a name over another label reads as neither.
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::point_along;

    #[test]
    fn a_point_along_a_polyline_is_at_its_fraction_of_the_length() {
        // An L of lengths 30 and 10: the middle lies on the first leg, 0.9 on the second.
        let l = [(0, 0), (30, 0), (30, 10)];
        assert_eq!(point_along(&l, 0.5), (20, 0));
        assert_eq!(point_along(&l, 0.9), (30, 6));
        assert_eq!(point_along(&l, 0.0), (0, 0));
        assert_eq!(point_along(&l, 1.0), (30, 10));
    }
}
