//! Mechanism figures (paper Figs. 3–7): the arch to scale, the displaced blocks over it,
//! hinges as dots and sliding joints as arrows giving the sense of the crown-side part.
//!
//! The figure data ([`MechanismFigure`]) comes from the pure geometry of
//! [`crate::analysis::kinematics::outline`]; this file only maps it to pixels (1:1 aspect)
//! and draws it, to PNG or SVG by the extension of the path it is given.

use crate::analysis::Sense;
use crate::analysis::kinematics::{MOTION_TOL, MechanismDrawing};
use crate::analysis::statics::Point;
use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::Path;
use std::sync::OnceLock;

/// Name under which the bundled DejaVu Sans is registered with plotters.
const FONT: &str = "dejavu-sans";

/// Registers the bundled font once; false when it could not be parsed.
fn font_ready() -> bool {
    static READY: OnceLock<bool> = OnceLock::new();
    *READY.get_or_init(|| register_font(FONT, FontStyle::Normal, dejavu::sans::regular()).is_ok())
}

/// What a mechanism figure shows.
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismFigure {
    /// Title line (e.g. the family or the state).
    pub title: String,
    /// A second, smaller line (e.g. the hinge pattern, K, μ).
    pub subtitle: String,
    /// The geometry to draw.
    pub drawing: MechanismDrawing,
    /// The window (x_min, x_max, y_min, y_max, over r) to fit in the panel; `None`: the
    /// drawing's own bounds. Frames of an animation share one window, so that the arch
    /// keeps its scale while the blocks move.
    pub window: Option<[f64; 4]>,
}

/// Colours of the figure.
const ORIGINAL: RGBColor = RGBColor(150, 150, 150);
const FIXED_FILL: RGBColor = RGBColor(215, 215, 215);
const BLOCK_FILL: RGBAColor = RGBAColor(70, 130, 200, 0.35);
const BLOCK_EDGE: RGBColor = RGBColor(25, 70, 140);
const HINGE: RGBColor = RGBColor(200, 30, 30);
const SLIDE: RGBColor = RGBColor(230, 120, 0);
const GROUND: RGBColor = RGBColor(90, 90, 90);

/// The map from arch coordinates (over r) to pixels, with equal scales on both axes.
#[derive(Debug, Clone, Copy)]
struct Frame {
    scale: f64,
    x0: f64,
    y0: f64,
    px0: f64,
    py0: f64,
}

impl Frame {
    /// Fits `bounds` (x_min, x_max, y_min, y_max) into the pixel box (left, top, w, h).
    fn fit(bounds: [f64; 4], left: f64, top: f64, w: f64, h: f64) -> Self {
        let bw = (bounds[1] - bounds[0]).max(1e-9);
        let bh = (bounds[3] - bounds[2]).max(1e-9);
        let scale = (w / bw).min(h / bh);
        Frame {
            scale,
            x0: 0.5 * (bounds[0] + bounds[1]),
            y0: 0.5 * (bounds[2] + bounds[3]),
            px0: left + 0.5 * w,
            py0: top + 0.5 * h,
        }
    }

    fn px(&self, p: Point) -> (i32, i32) {
        (
            (self.px0 + self.scale * (p[0] - self.x0)).round() as i32,
            (self.py0 - self.scale * (p[1] - self.y0)).round() as i32,
        )
    }

    fn path(&self, pts: &[Point], close: bool) -> Vec<(i32, i32)> {
        let mut v: Vec<(i32, i32)> = pts.iter().map(|&p| self.px(p)).collect();
        if close && let Some(&first) = v.first() {
            v.push(first);
        }
        v
    }
}

/// The result of drawing on a backend.
type Drawn<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Draws the figure into a drawing area; the text in the fonts of `ctx` (a figure of the
/// report), or sized to the area (a figure of its own).
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    fig: &MechanismFigure,
    ctx: Option<&super::PlotContext>,
) -> Drawn<DB> {
    root.fill(&WHITE)?;
    let (w, h) = root.dim_in_pixel();
    let (w, h) = (f64::from(w), f64::from(h));
    let text = ctx.is_some() || font_ready();
    let fonts = match ctx {
        Some(c) => (c.font(13.5), c.font(12.5).color(&GROUND)),
        None => (
            (FONT, (0.045 * h).max(12.0)).into_font().color(&BLACK),
            (FONT, (0.032 * h).max(10.0)).into_font().color(&GROUND),
        ),
    };
    let margin = 0.03 * w.min(h);
    // On paper the text keeps its printed size: a narrow panel wraps its title and
    // subtitle into as many lines as they need.
    let room = (w - 2.0 * margin).max(1.0);
    let (titles, subtitles) = match ctx {
        Some(_) => (
            super::style::wrap(&fonts.0, &fig.title, room),
            super::style::wrap(&fonts.1, &fig.subtitle, room),
        ),
        None => (vec![fig.title.clone()], vec![fig.subtitle.clone()]),
    };
    let line_h =
        |f: &TextStyle, l: &[String]| f64::from(super::style::text_block_size(f, &l[..1], 1.2).1);
    let (h0, h1) = (line_h(&fonts.0, &titles), line_h(&fonts.1, &subtitles));
    let title_h = match ctx {
        None if text => 0.11 * h,
        None => 0.0,
        // The lines of text and a gap.
        Some(c) => (titles.len() as f64 * h0 + subtitles.len() as f64 * h1 + f64::from(c.px(8.0)))
            .max(f64::from(c.px(44.0)))
            .max(0.11 * h),
    };
    let d = &fig.drawing;
    let mut b = fig.window.unwrap_or_else(|| d.bounds());
    // Room for the ground hatching below the springings and for the arrows.
    let pad = 0.06 * (b[1] - b[0]).max(b[3] - b[2]);
    b = [b[0] - pad, b[1] + pad, b[2] - pad, b[3] + 0.5 * pad];
    let frame = Frame::fit(
        b,
        margin,
        title_h + margin,
        w - 2.0 * margin,
        h - title_h - 2.0 * margin,
    );
    let p = Panel {
        root,
        frame,
        drawing: d,
        size: (b[1] - b[0]).max(b[3] - b[2]),
        px: ctx.map_or(1.0, |c| c.scale),
    };
    p.draw_supports()?;
    p.draw_blocks()?;
    p.draw_slides()?;
    p.draw_hinges((0.012 * w.min(h)).max(3.0 * p.px) as i32)?;
    if text && ctx.is_some() {
        let mut y = 0.12 * f64::from(ctx.map_or(0, |c| c.px(44.0)));
        for (l, f, lh) in (titles.iter().map(|l| (l, &fonts.0, h0)))
            .chain(subtitles.iter().map(|l| (l, &fonts.1, h1)))
        {
            root.draw(&Text::new(l.clone(), (margin as i32, y as i32), f.clone()))?;
            y += lh;
        }
    } else if text {
        root.draw(&Text::new(
            fig.title.clone(),
            (margin as i32, (0.12 * title_h) as i32),
            fonts.0,
        ))?;
        root.draw(&Text::new(
            fig.subtitle.clone(),
            (margin as i32, (0.56 * title_h) as i32),
            fonts.1,
        ))?;
    }
    Ok(())
}

/// One mechanism drawn in a drawing area: the area, the map to its pixels, the geometry and
/// the size of the drawing (in r), which sets the length of ticks and arrows.
struct Panel<'a, DB: DrawingBackend> {
    root: &'a DrawingArea<DB, Shift>,
    frame: Frame,
    drawing: &'a MechanismDrawing,
    size: f64,
    /// Device pixels per design pixel.
    px: f64,
}

impl<DB: DrawingBackend> Panel<'_, DB> {
    /// A line width or radius of `n` design pixels in device pixels.
    fn w(&self, n: f64) -> u32 {
        (n * self.px).round().max(1.0) as u32
    }

    /// Supports: a ground line along each springing joint, hatched on the ground side.
    fn draw_supports(&self) -> Drawn<DB> {
        let (root, frame, size) = (self.root, &self.frame, self.size);
        for sup in &self.drawing.supports {
            let (i, e) = (sup.intrados, sup.extrados);
            let along = [e[0] - i[0], e[1] - i[1]];
            let len = along[0].hypot(along[1]).max(1e-12);
            let t = [along[0] / len, along[1] / len];
            let g = sup.into_ground;
            let ext = 0.3 * len + 0.02 * size;
            let a = [i[0] - ext * t[0], i[1] - ext * t[1]];
            let z = [e[0] + ext * t[0], e[1] + ext * t[1]];
            root.draw(&PathElement::new(
                vec![frame.px(a), frame.px(z)],
                GROUND.stroke_width(self.w(2.0)),
            ))?;
            let ticks = 8;
            let tick = 0.1 * (z[0] - a[0]).hypot(z[1] - a[1]);
            for k in 0..=ticks {
                let s = f64::from(k) / f64::from(ticks);
                let p = [a[0] + s * (z[0] - a[0]), a[1] + s * (z[1] - a[1])];
                let q = [
                    p[0] + tick * (g[0] - 0.6 * t[0]),
                    p[1] + tick * (g[1] - 0.6 * t[1]),
                ];
                root.draw(&PathElement::new(
                    vec![frame.px(p), frame.px(q)],
                    GROUND.stroke_width(self.w(1.0)),
                ))?;
            }
        }
        Ok(())
    }

    /// The arch before the displacement (dashed), then the fixed parts, then the displaced
    /// blocks, then the joints between voussoirs.
    fn draw_blocks(&self) -> Drawn<DB> {
        let (root, frame, d) = (self.root, &self.frame, self.drawing);
        for o in &d.outlines {
            root.draw(&DashedPathElement::new(
                frame.path(&o.original, true),
                self.w(6.0),
                self.w(4.0),
                ORIGINAL.stroke_width(self.w(1.0)),
            ))?;
        }
        for o in d.outlines.iter().filter(|o| o.fixed) {
            root.draw(&Polygon::new(
                frame.path(&o.original, false),
                FIXED_FILL.filled(),
            ))?;
            root.draw(&PathElement::new(
                frame.path(&o.original, true),
                GROUND.stroke_width(self.w(1.0)),
            ))?;
        }
        for o in d.outlines.iter().filter(|o| !o.fixed) {
            root.draw(&Polygon::new(
                frame.path(&o.displaced, false),
                BLOCK_FILL.filled(),
            ))?;
            root.draw(&PathElement::new(
                frame.path(&o.displaced, true),
                BLOCK_EDGE.stroke_width(self.w(2.0)),
            ))?;
        }
        let joints = if d.voussoir_joints.len() <= super::MAX_DRAWN_JOINTS {
            d.voussoir_joints.as_slice()
        } else {
            &[]
        };
        for [i, e] in joints {
            root.draw(&PathElement::new(
                vec![frame.px(*i), frame.px(*e)],
                BLOCK_EDGE.stroke_width(self.w(1.0)),
            ))?;
        }
        Ok(())
    }

    /// Sliding joints: an arrow along the joint on the crown side, in the direction the
    /// crown-side part moves relative to the springing-side part.
    fn draw_slides(&self) -> Drawn<DB> {
        let (root, frame, size) = (self.root, &self.frame, self.size);
        for s in &self.drawing.slides {
            // No arrow where the joint does not slip in this mode.
            let dir = match s.sense {
                Some(Sense::Outward) => 1.0,
                Some(Sense::Inward) => -1.0,
                None => 0.0,
            };
            // The arrow spans 70 % of the joint (so it stays inside the masonry), at least
            // 12 pixels, centred on the joint's middle.
            let (lo, hi) = joint_extent(
                self.drawing.outlines.iter().map(|o| o.original.as_slice()),
                s.centre,
                s.along,
            )
            .unwrap_or((-0.08 * size, 0.08 * size));
            let len = (0.7 * (hi - lo)).max(12.0 * self.px / frame.scale);
            let mid = [
                s.centre[0] + 0.5 * (lo + hi) * s.along[0],
                s.centre[1] + 0.5 * (lo + hi) * s.along[1],
            ];
            // Crown side: left of the joint for θ ≥ 0, i.e. against the normal (cos θ, −sin θ).
            let nrm = [s.along[1], -s.along[0]];
            let off = (0.045 * size)
                .min(0.5 * (hi - lo))
                .max(6.0 * self.px / frame.scale)
                * s.crown_side;
            let c = [mid[0] - off * nrm[0], mid[1] - off * nrm[1]];
            let (t0, t1) = if dir == 0.0 {
                (c, c)
            } else {
                (
                    [
                        c[0] - 0.5 * len * dir * s.along[0],
                        c[1] - 0.5 * len * dir * s.along[1],
                    ],
                    [
                        c[0] + 0.5 * len * dir * s.along[0],
                        c[1] + 0.5 * len * dir * s.along[1],
                    ],
                )
            };
            root.draw(&PathElement::new(
                vec![frame.px(t0), frame.px(t1)],
                SLIDE.stroke_width(self.w(2.0)),
            ))?;
            if dir != 0.0 {
                let head = 0.35 * len;
                let u = [dir * s.along[0], dir * s.along[1]];
                for side in [1.0, -1.0] {
                    let (ca, sa) = (0.94_f64, 0.34_f64 * side);
                    let back = [-(ca * u[0] - sa * u[1]), -(sa * u[0] + ca * u[1])];
                    let q = [t1[0] + head * back[0], t1[1] + head * back[1]];
                    root.draw(&PathElement::new(
                        vec![frame.px(t1), frame.px(q)],
                        SLIDE.stroke_width(self.w(2.0)),
                    ))?;
                }
            }
            // The joint itself, drawn on the arch.
            root.draw(&Circle::new(
                frame.px(s.centre),
                self.w(3.0),
                SLIDE.filled(),
            ))?;
        }
        Ok(())
    }

    /// Hinges of radius `r` pixels: filled where the joint rotates, hollow where it stays
    /// closed in this mode.
    fn draw_hinges(&self, r: i32) -> Drawn<DB> {
        let root = self.root;
        for hm in &self.drawing.hinges {
            let at = self.frame.px(hm.displaced);
            if hm.relative_rotation.abs() > MOTION_TOL {
                root.draw(&Circle::new(at, r, HINGE.filled()))?;
                root.draw(&Circle::new(at, r, BLACK.stroke_width(self.w(1.0))))?;
            } else {
                root.draw(&Circle::new(at, r, WHITE.filled()))?;
                root.draw(&Circle::new(at, r, ORIGINAL.stroke_width(self.w(2.0))))?;
            }
        }
        Ok(())
    }
}

/// Where the line through `centre` along `along` leaves the arch on either side: the
/// parameters (negative, positive) of the nearest crossings with the blocks' outlines, the
/// ends of the joint through `centre`. Edges along the line (the joint's own faces) are
/// skipped.
fn joint_extent<'a>(
    outlines: impl Iterator<Item = &'a [Point]>,
    centre: Point,
    along: [f64; 2],
) -> Option<(f64, f64)> {
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for o in outlines {
        let n = o.len();
        for i in 0..n {
            let (p, q) = (o[i], o[(i + 1) % n]);
            let e = [q[0] - p[0], q[1] - p[1]];
            let den = cross(along, e);
            if den.abs() <= 1e-9 * e[0].hypot(e[1]) {
                continue;
            }
            let pc = [p[0] - centre[0], p[1] - centre[1]];
            let t = cross(pc, e) / den;
            let u = cross(pc, along) / den;
            if !(-1e-9..=1.0 + 1e-9).contains(&u) {
                continue;
            }
            if t > 1e-9 {
                hi = hi.min(t);
            } else if t < -1e-9 {
                lo = lo.max(t);
            }
        }
    }
    (lo.is_finite() && hi.is_finite()).then_some((lo, hi))
}

/// Mechanisms side by side (e.g. the non-associative mechanisms at a bifurcation and the
/// associative one), one panel each, for the report.
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismPanels {
    /// The panels, left to right.
    pub panels: Vec<MechanismFigure>,
}

impl MechanismPanels {
    /// Rows and columns: one row up to two panels, else two rows (the non-associative
    /// mechanisms above, the associative ones below).
    fn grid(&self) -> (usize, usize) {
        let n = self.panels.len().max(1);
        if n <= 2 { (1, n) } else { (2, n.div_ceil(2)) }
    }
}

/// Design size of one panel, pixels.
const PANEL_SIZE: (u32, u32) = (440, 290);

impl super::Figure for MechanismPanels {
    fn size(&self) -> (u32, u32) {
        let (rows, cols) = self.grid();
        (PANEL_SIZE.0 * cols as u32, PANEL_SIZE.1 * rows as u32)
    }

    fn panel_grid(&self) -> (usize, usize) {
        self.grid()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &super::PlotContext,
    ) -> super::DrawResult<(), DB> {
        let areas = root.split_evenly(ctx.panel_grid(self.grid()));
        for (a, f) in areas.iter().zip(&self.panels) {
            draw(a, f, Some(ctx))?;
        }
        Ok(())
    }
}

/// Renders a mechanism figure of `size` pixels to `path`: SVG when the extension is `svg`,
/// PNG otherwise. Writes only that file.
pub fn render_mechanism(path: &Path, size: (u32, u32), fig: &MechanismFigure) -> Result<()> {
    let svg = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    let err = |e: String| anyhow!("cannot draw {}: {e}", path.display());
    if svg {
        let root = SVGBackend::new(path, size).into_drawing_area();
        draw(&root, fig, None).map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    } else {
        let root = BitMapBackend::new(path, size).into_drawing_area();
        draw(&root, fig, None).map_err(|e| err(e.to_string()))?;
        root.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::circular::CircularArch;
    use crate::analysis::kinematics::{drawing, families};
    use crate::model::Arch;

    #[test]
    fn draws_every_family_to_png_and_svg() {
        let dir = tempfile::tempdir().unwrap();
        let geom = CircularArch::new(Arch::semicircular(1.25).unwrap());
        for f in families(&geom).unwrap() {
            let fig = MechanismFigure {
                title: f.template.id.to_string(),
                subtitle: f.template.description.to_string(),
                drawing: drawing(&geom, &f.modes.fields[0], 0.08),
                window: None,
            };
            for ext in ["png", "svg"] {
                let path = dir.path().join(format!("{}.{ext}", f.template.id));
                render_mechanism(&path, (400, 260), &fig).unwrap();
                let bytes = std::fs::read(&path).unwrap();
                assert!(bytes.len() > 1000, "{}", path.display());
            }
        }
    }

    #[test]
    fn a_bad_path_names_itself() {
        let geom = CircularArch::new(Arch::semicircular(1.25).unwrap());
        let f = &families(&geom).unwrap()[0];
        let fig = MechanismFigure {
            title: String::new(),
            subtitle: String::new(),
            drawing: drawing(&geom, &f.modes.fields[0], 0.08),
            window: None,
        };
        let path = Path::new("/nonexistent-dir/x.png");
        let err = render_mechanism(path, (100, 80), &fig).unwrap_err();
        assert!(format!("{err:#}").contains("/nonexistent-dir/x.png"));
    }
}
