//! Figure 1: the regime map over (μ, K) with a t/R_c axis beside K: coloured regions, the
//! collapse curve from the located boundary points with each segment named by its
//! mechanism, other regime boundaries, and the bifurcation points with their values.

use super::style::{
    self, LabelPlacer, LegendItem, Mark, PixelBox, clip_polyline, decimals_for, palette,
};
use super::{Figure, PlotContext};
use crate::model::{k_from_t_over_r, t_over_r_from_k};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::collections::BTreeMap;

/// A run of the collapse curve with one mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct CollapseSegment {
    /// `rotational`, `mixed` or `sliding`.
    pub mechanism: String,
    /// Points (μ, K) in order along the curve.
    pub points: Vec<(f64, f64)>,
}

/// A bifurcation point with the lines of its annotation.
#[derive(Debug, Clone, PartialEq)]
pub struct BifurcationMark {
    /// μ.
    pub mu: f64,
    /// K.
    pub k: f64,
    /// Annotation, one string per line (already formatted).
    pub lines: Vec<String>,
}

/// A located regime change on a grid line.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    /// The grid value of the other parameter (K for a change along μ).
    pub fixed: f64,
    /// Where the change is.
    pub at: f64,
    /// Regime on the smaller side.
    pub low: String,
    /// Regime on the larger side.
    pub high: String,
}

/// What the regime map shows.
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeMap {
    /// Title.
    pub title: String,
    /// Grid μ values, increasing, finite.
    pub mu: Vec<f64>,
    /// Grid K values, increasing.
    pub k: Vec<f64>,
    /// Regime names per grid point, K-major: `regimes[ik * mu.len() + imu]` (None: no
    /// value).
    pub regimes: Vec<Option<std::sync::Arc<str>>>,
    /// Located regime changes along μ at a grid K (every boundary point, so that the
    /// coloured regions meet where the boundaries were located, not half-way between grid
    /// points).
    pub crossings_along_mu: Vec<Crossing>,
    /// Located regime changes along K at a grid μ.
    pub crossings_along_k: Vec<Crossing>,
    /// The collapse curve, by mechanism.
    pub collapse: Vec<CollapseSegment>,
    /// Other regime boundaries (not on the collapse curve), as polylines (μ, K).
    pub other_boundaries: Vec<Vec<(f64, f64)>>,
    /// Bifurcation points.
    pub bifurcations: Vec<BifurcationMark>,
}

const REGIME_ORDER: [&str; 5] = ["stable", "rotational", "mixed", "sliding", "none"];

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
    let at = |i: usize, j: usize| m.regimes[j * nx + i].as_deref();
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
        let cells: Vec<usize> = (0..nx * ny)
            .filter(|&c| m.regimes[c].as_deref() == Some(name))
            .collect();
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

/// Ticks of t/R_c inside [t0, t1] at a nice step.
fn t_ticks(t0: f64, t1: f64) -> (Vec<f64>, usize) {
    let step = style::nice_step(t1 - t0, 6);
    let mut v = Vec::new();
    let mut t = (t0 / step).ceil() * step;
    while t <= t1 + 1e-12 {
        v.push(t);
        t += step;
    }
    (v, decimals_for(t1 - t0))
}

impl Figure for RegimeMap {
    fn size(&self) -> (u32, u32) {
        (820, 640)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let legend = self.legend();
        let upper = style::above_legend(root, ctx, &legend)?;
        if self.mu.len() < 2 || self.k.len() < 2 {
            upper.draw(&Text::new(
                "The regime map needs at least two values of μ and of K.".to_string(),
                (ctx.px(20.0), ctx.px(60.0)),
                ctx.font(15.0),
            ))?;
            return Ok(());
        }
        let (mu0, mu1) = (self.mu[0], self.mu[self.mu.len() - 1]);
        let (k0, k1) = (self.k[0], self.k[self.k.len() - 1]);
        let mut chart = ChartBuilder::on(&upper)
            .caption(&self.title, ctx.font(17.0))
            .margin(ctx.px(10.0))
            .margin_right(ctx.px(86.0))
            .x_label_area_size(ctx.px(50.0))
            .y_label_area_size(ctx.px(72.0))
            .build_cartesian_2d(mu0..mu1, k0..k1)?;
        // Regions on a raster of about 2 design pixels, as runs of equal regime along each
        // row merged with identical runs of the rows above into one rectangle (few
        // elements, no seams between rows).
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let nxr = ((f64::from(xr.end - xr.start) / ctx.scale / 2.0).ceil() as usize).max(2);
        let nyr = ((f64::from(yr.end - yr.start) / ctx.scale / 2.0).ceil() as usize).max(2);
        let raster = self.raster(nxr, nyr);
        let me: Vec<f64> = (0..=nxr)
            .map(|i| mu0 + (mu1 - mu0) * i as f64 / nxr as f64)
            .collect();
        let ke: Vec<f64> = (0..=nyr)
            .map(|j| k0 + (k1 - k0) * j as f64 / nyr as f64)
            .collect();
        let px_mu = (mu1 - mu0) / f64::from((xr.end - xr.start).max(1));
        let px_k = (k1 - k0) / f64::from((yr.end - yr.start).max(1));
        let nx = nxr;
        let mut open: BTreeMap<(usize, usize, &str), usize> = BTreeMap::new();
        let mut rects = Vec::new();
        let mut close = |(i0, i1, name): (usize, usize, &str), j0: usize, j1: usize| {
            let x1 = (me[i1] + px_mu).min(mu1);
            let y1 = (ke[j1] + px_k).min(k1);
            rects.push(Rectangle::new(
                [(me[i0], ke[j0]), (x1, y1)],
                palette::regime(name).filled(),
            ));
        };
        for j in 0..=nyr {
            let mut runs = Vec::new();
            let mut i = 0;
            while j < nyr && i < nx {
                let r = raster[j * nx + i];
                let start = i;
                while i < nx && raster[j * nx + i] == r {
                    i += 1;
                }
                if let Some(name) = r {
                    runs.push((start, i, name));
                }
            }
            let ended: Vec<_> = open.keys().filter(|k| !runs.contains(k)).cloned().collect();
            for key in ended {
                if let Some(j0) = open.remove(&key) {
                    close(key, j0, j);
                }
            }
            for run in runs {
                open.entry(run).or_insert(j);
            }
        }
        chart.draw_series(rects)?;
        let fmt_mu = |v: &f64| format!("{:.*}", decimals_for(mu1 - mu0), v);
        let fmt_k = |v: &f64| format!("{:.*}", decimals_for(k1 - k0), v);
        chart
            .configure_mesh()
            .x_desc("friction coefficient μ")
            .y_desc("thickness ratio K = R/r")
            .x_label_formatter(&fmt_mu)
            .y_label_formatter(&fmt_k)
            .label_style(ctx.font(13.0))
            .axis_desc_style(ctx.font(14.0))
            .set_all_tick_mark_size(ctx.px(5.0))
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.10).stroke_width(1))
            .axis_style(BLACK.stroke_width(ctx.upx(1.0).max(1)))
            .draw()?;
        // The t/R_c axis at the right edge, ticks at round values of t/R_c.
        let (t0, t1) = (t_over_r_from_k(k0), t_over_r_from_k(k1));
        let (ticks, dec) = t_ticks(t0, t1);
        let x_axis = xr.end;
        let tick_font = ctx.font(13.0).pos(Pos::new(HPos::Left, VPos::Center));
        root.draw(&PathElement::new(
            vec![(x_axis, yr.start), (x_axis, yr.end)],
            BLACK.stroke_width(ctx.upx(1.0).max(1)),
        ))?;
        for t in &ticks {
            let (_, py) = chart.backend_coord(&(mu1, k_from_t_over_r(*t)));
            root.draw(&PathElement::new(
                vec![(x_axis, py), (x_axis + ctx.px(5.0), py)],
                BLACK.stroke_width(ctx.upx(1.0).max(1)),
            ))?;
            root.draw(&Text::new(
                format!("{t:.dec$}"),
                (x_axis + ctx.px(8.0), py),
                tick_font.clone(),
            ))?;
        }
        let desc = ctx
            .font(14.0)
            .transform(FontTransform::Rotate90)
            .pos(Pos::new(HPos::Center, VPos::Bottom));
        root.draw(&Text::new(
            "thickness t/R_c".to_string(),
            (x_axis + ctx.px(72.0), (yr.start + yr.end) / 2),
            desc,
        ))?;

        let window = ((mu0, mu1), (k0, k1));
        // Other regime boundaries: thin dashed lines.
        for line in &self.other_boundaries {
            for piece in clip_polyline(line, window.0, window.1) {
                chart.draw_series(DashedLineSeries::new(
                    piece,
                    ctx.upx(6.0),
                    ctx.upx(4.0),
                    palette::INK.mix(0.75).stroke_width(ctx.upx(1.2).max(1)),
                ))?;
            }
        }
        // The collapse curve.
        for seg in &self.collapse {
            let color = palette::mechanism(&seg.mechanism);
            for piece in clip_polyline(&seg.points, window.0, window.1) {
                chart.draw_series(LineSeries::new(piece, color.stroke_width(ctx.upx(3.2))))?;
            }
        }
        // Labels: bifurcations first (most important), then curve segments, then regions.
        let bounds: PixelBox = (
            xr.start + ctx.px(4.0),
            yr.start + ctx.px(4.0),
            xr.end - ctx.px(4.0),
            yr.end - ctx.px(4.0),
        );
        let mut placer = LabelPlacer::new(bounds);
        let pts: Vec<(i32, i32)> = self
            .bifurcations
            .iter()
            .map(|b| chart.backend_coord(&(b.mu, b.k)))
            .collect();
        for p in &pts {
            let r = ctx.px(9.0);
            placer.block((p.0 - r, p.1 - r, p.0 + r, p.1 + r));
        }
        // Keep labels off the curves: block a thin box around every piece of them.
        let pad = ctx.px(4.0);
        let curves = self
            .collapse
            .iter()
            .map(|s| &s.points)
            .chain(self.other_boundaries.iter());
        for line in curves {
            for piece in clip_polyline(line, window.0, window.1) {
                for w in piece.windows(2) {
                    let (a, b) = (chart.backend_coord(&w[0]), chart.backend_coord(&w[1]));
                    // Short pieces, so that a diagonal blocks a band and not its bounding box.
                    let n = ((a.0 - b.0).abs().max((a.1 - b.1).abs()) / pad.max(1)).max(1);
                    for i in 0..n {
                        let p = (a.0 + (b.0 - a.0) * i / n, a.1 + (b.1 - a.1) * i / n);
                        let q = (
                            a.0 + (b.0 - a.0) * (i + 1) / n,
                            a.1 + (b.1 - a.1) * (i + 1) / n,
                        );
                        placer.block((
                            p.0.min(q.0) - pad,
                            p.1.min(q.1) - pad,
                            p.0.max(q.0) + pad,
                            p.1.max(q.1) + pad,
                        ));
                    }
                }
            }
        }
        let ann_font = ctx.font(12.5);
        for (b, p) in self.bifurcations.iter().zip(&pts) {
            let (bw, bh) = style::text_block_size(&ann_font, &b.lines, 1.25);
            let g = ctx.px(14.0);
            let at = placer.place(
                bw,
                bh,
                &[
                    (p.0 + g, p.1 + g),
                    (p.0 + g, p.1 - g - bh),
                    (p.0 + g, p.1 - bh / 2),
                    (p.0 - g - bw, p.1 + g),
                    (p.0 - g - bw, p.1 - g - bh),
                    (p.0 + 3 * g, p.1 + 3 * g),
                    (p.0 + 3 * g, p.1 - 3 * g - bh),
                ],
            );
            // Leader line from the marker to the nearest corner of the box.
            let cx = if at.0 > p.0 { at.0 } else { at.0 + bw };
            let cy = if at.1 > p.1 { at.1 } else { at.1 + bh };
            root.draw(&PathElement::new(
                vec![*p, (cx, cy)],
                palette::INK.stroke_width(1),
            ))?;
            style::draw_text_block(root, ctx, &ann_font, &b.lines, at, Some(palette::GREY))?;
        }
        for p in &pts {
            style::dot(root, ctx, *p, 5.5, palette::INK)?;
        }
        let seg_font = ctx.font_with(13.0, FontStyle::Italic);
        for seg in &self.collapse {
            let inside: Vec<(f64, f64)> = seg
                .points
                .iter()
                .copied()
                .filter(|&(x, y)| x >= mu0 && x <= mu1 && y >= k0 && y <= k1)
                .collect();
            if inside.len() < 2 {
                continue;
            }
            let mid = chart.backend_coord(&inside[inside.len() / 2]);
            let text = format!("{} collapse", seg.mechanism);
            let color = palette::mechanism(&seg.mechanism);
            let (tw, th) = style::text_block_size(&seg_font, std::slice::from_ref(&text), 1.0);
            let g = ctx.px(8.0);
            let at = placer.place(
                tw,
                th,
                &[
                    (mid.0 - tw / 2, mid.1 - g - th),
                    (mid.0 + g, mid.1 - th / 2),
                    (mid.0 + g, mid.1 - g - th),
                    (mid.0 - tw / 2, mid.1 + g),
                    (mid.0 - g - tw, mid.1 - th / 2),
                    (mid.0 + g, mid.1 + g),
                    (mid.0 - tw / 2, mid.1 - 3 * g - th),
                    (mid.0 + 3 * g, mid.1 - th / 2),
                ],
            );
            root.draw(&Text::new(
                text,
                at,
                seg_font.color(&color).pos(Pos::new(HPos::Left, VPos::Top)),
            ))?;
        }
        let dxp = f64::from(xr.end - xr.start) / self.mu.len() as f64;
        let dyp = f64::from(yr.end - yr.start) / self.k.len() as f64;
        let reg_font = ctx.font_with(13.0, FontStyle::Bold);
        let sub_font = ctx.font(12.0);
        for (name, i, j, _) in label_cells(self, dxp, dyp) {
            let c = chart.backend_coord(&(self.mu[i], self.k[j]));
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
            // The name and its condition; else the name; else the name in a smaller font;
            // else that at the region's centre anyway (an unnamed region is worse than a
            // tight label).
            let small = ctx.font_with(10.5, FontStyle::Bold);
            let (w3, h3) = style::text_block_size(&small, &[l1.to_string()], 1.2);
            let top = Pos::new(HPos::Center, VPos::Top);
            if let Some(at) = placer.try_place(bw, bh, &cands(bw, bh)) {
                let mid = at.0 + bw / 2;
                root.draw(&Text::new(l1.to_string(), (mid, at.1), reg_font.pos(top)))?;
                root.draw(&Text::new(
                    l2.to_string(),
                    (mid, at.1 + h1),
                    sub_font.pos(top),
                ))?;
            } else if let Some(at) = placer.try_place(w1, h1, &cands(w1, h1)) {
                root.draw(&Text::new(
                    l1.to_string(),
                    (at.0 + w1 / 2, at.1),
                    reg_font.pos(top),
                ))?;
            } else {
                let at = placer
                    .try_place(w3, h3, &cands(w3, h3))
                    .unwrap_or_else(|| placer.place(w3, h3, &cands(w3, h3)[..1]));
                root.draw(&Text::new(
                    l1.to_string(),
                    (at.0 + w3 / 2, at.1),
                    small.pos(top),
                ))?;
            }
        }
        Ok(())
    }
}

/// Where regime `r` ends on the edge from grid value `a` (regime `ra`) to `b` (regime `rb`)
/// at the other parameter's grid value `fixed`, as a fraction of the edge from `a`: the
/// located change out of `r` nearest to its corner, else half-way.
fn edge_fraction(
    located: &[Crossing],
    r: &str,
    (fixed, a, b): (f64, f64, f64),
    (ra, rb): (Option<&str>, Option<&str>),
) -> f64 {
    if ra == rb {
        return 0.5;
    }
    let tol = 1e-12 * (1.0 + fixed.abs());
    let on_edge = located
        .iter()
        .filter(|c| (c.fixed - fixed).abs() <= tol && c.at >= a.min(b) && c.at <= a.max(b));
    let frac = |c: &Crossing| ((c.at - a) / (b - a)).clamp(0.0, 1.0);
    let found = if ra == Some(r) {
        on_edge
            .filter(|c| c.low == r)
            .map(frac)
            .fold(None, |m: Option<f64>, f| Some(m.map_or(f, |m| m.min(f))))
    } else if rb == Some(r) {
        on_edge
            .filter(|c| c.high == r)
            .map(frac)
            .fold(None, |m: Option<f64>, f| Some(m.map_or(f, |m| m.max(f))))
    } else {
        None
    };
    found.unwrap_or(0.5)
}

/// Piecewise-linear map of [0, 1] onto itself sending `c` to 1/2.
fn warp(x: f64, c: f64) -> f64 {
    if x <= c {
        0.5 * x / c.max(1e-12)
    } else {
        0.5 + 0.5 * (x - c) / (1.0 - c).max(1e-12)
    }
}

impl RegimeMap {
    /// The regime at every cell centre of an `nx` × `ny` raster over the grid's range, K-major.
    /// Within a grid cell whose corners differ, each regime gets the bilinear interpolation of
    /// ±1 at the corners, in coordinates warped so that on every edge the interpolation
    /// changes sign at the located boundary; the largest wins (marching squares with the
    /// boundaries where they were found).
    fn raster(&self, nx: usize, ny: usize) -> Vec<Option<&str>> {
        let (m, k) = (&self.mu, &self.k);
        let (mu0, mu1, k0, k1) = (m[0], m[m.len() - 1], k[0], k[k.len() - 1]);
        let cell = |v: &[f64], x: f64| v.partition_point(|&g| g <= x).clamp(1, v.len() - 1) - 1;
        let at = |i: usize, j: usize| self.regimes[j * m.len() + i].as_deref();
        let mut out = Vec::with_capacity(nx * ny);
        for jr in 0..ny {
            let kk = k0 + (k1 - k0) * (jr as f64 + 0.5) / ny as f64;
            let j = cell(k, kk);
            let t = (kk - k[j]) / (k[j + 1] - k[j]);
            for ir in 0..nx {
                let mm = mu0 + (mu1 - mu0) * (ir as f64 + 0.5) / nx as f64;
                let i = cell(m, mm);
                let s = (mm - m[i]) / (m[i + 1] - m[i]);
                let c = [at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)];
                if c.iter().all(|r| *r == c[0]) {
                    out.push(c[0]);
                    continue;
                }
                let (xs, ks) = (&self.crossings_along_mu, &self.crossings_along_k);
                let mut best = (f64::NEG_INFINITY, None);
                for r in c.iter().flatten() {
                    // Coordinates warped so that regime r's field changes sign where r ends.
                    let bottom = edge_fraction(xs, r, (k[j], m[i], m[i + 1]), (c[0], c[1]));
                    let top = edge_fraction(xs, r, (k[j + 1], m[i], m[i + 1]), (c[2], c[3]));
                    let left = edge_fraction(ks, r, (m[i], k[j], k[j + 1]), (c[0], c[2]));
                    let right = edge_fraction(ks, r, (m[i + 1], k[j], k[j + 1]), (c[1], c[3]));
                    let sw = warp(s, bottom + (top - bottom) * t);
                    let tw = warp(t, left + (right - left) * s);
                    let w = [
                        (1.0 - sw) * (1.0 - tw),
                        sw * (1.0 - tw),
                        (1.0 - sw) * tw,
                        sw * tw,
                    ];
                    let f: f64 = c
                        .iter()
                        .zip(w)
                        .map(|(q, wq)| if q == &Some(*r) { wq } else { -wq })
                        .sum();
                    if f > best.0 {
                        best = (f, Some(*r));
                    }
                }
                out.push(best.1);
            }
        }
        out
    }

    fn legend(&self) -> Vec<LegendItem> {
        let mut items = Vec::new();
        for name in REGIME_ORDER {
            if self.regimes.iter().any(|r| r.as_deref() == Some(name)) {
                let label = match name {
                    "none" => "none (no equilibrium)",
                    other => other,
                };
                items.push(LegendItem::new(label, Mark::Swatch(palette::regime(name))));
            }
        }
        for m in ["rotational", "mixed", "sliding"] {
            if self.collapse.iter().any(|s| s.mechanism == m) {
                items.push(LegendItem::new(
                    format!("{m} collapse"),
                    Mark::Line {
                        color: palette::mechanism(m),
                        width: 3.2,
                        dashed: false,
                    },
                ));
            }
        }
        if !self.other_boundaries.is_empty() {
            items.push(LegendItem::new(
                "other regime boundary",
                Mark::Line {
                    color: palette::INK,
                    width: 1.2,
                    dashed: true,
                },
            ));
        }
        if !self.bifurcations.is_empty() {
            items.push(LegendItem::new("bifurcation", Mark::Dot(palette::INK)));
        }
        items
    }
}
