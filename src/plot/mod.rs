//! Figures: the only user of plotters. One file per chart; each chart is a data type (what
//! to draw, already in its final units) implementing [`Figure`], drawn for a
//! [`PlotContext`] (format and size). [`render`] returns the bytes of the file (SVG text or
//! a print-resolution PNG); the caller decides where they go.
//!
//! Text uses DejaVu Sans, bundled with the binary and registered under the generic family
//! `sans-serif`: PNG text never depends on the system's fonts, and the SVG names DejaVu Sans
//! with the generic family as fallback, so every viewer has a font for it. Symbols are
//! typeset in the SVG ([`paper::typeset`]): K_c with a subscript, H^r with a superscript.
//!
//! [`Format::Paper`] draws a figure for print at a column width ([`paper`]); its PDF and
//! PNG are converted from that SVG.

pub mod accuracy;
pub mod critical;
pub mod domains;
pub mod frames;
pub mod lambda_map;
pub mod lines;
pub mod mechanisms;
pub mod paper;
pub mod regime_map;
pub mod state;
mod style;
pub mod uncertainty;

use crate::manifest::FigureWidth;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

pub use style::{LegendItem, palette};

/// Output format of a figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// SVG, at the design size (for inlining in the HTML report).
    Svg,
    /// PNG, at [`PNG_SCALE`] times the design size with a 300 dpi tag.
    Png,
    /// SVG for print at a column width: no title (the caption carries it), text at 8–9 pt
    /// of the printed size, the size in inches ([`paper`]).
    Paper(FigureWidth),
}

impl Format {
    /// The file extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Svg | Format::Paper(_) => "svg",
            Format::Png => "png",
        }
    }
}

/// The most voussoir joints a figure draws: an arch of more voussoirs is drawn as its
/// outline, without its joints and the line's points on them (at a figure's resolution they
/// would merge into a band, and hundreds of thousands of lines are more than a PDF figure
/// can be converted from). Every joint is still analysed.
pub const MAX_DRAWN_JOINTS: usize = 2000;

/// Largest number of points of a line of thrust drawn: an arch of a million voussoirs has a
/// point on each joint, which no figure can show apart (and which made an 8.8 MB SVG); a line
/// with more is drawn through evenly spaced points of it, its ends kept.
pub const MAX_DRAWN_LINE_POINTS: usize = 4000;

/// `line` thinned to at most [`MAX_DRAWN_LINE_POINTS`] points, evenly spaced along its
/// indices, the first and the last kept.
pub fn thinned<T: Copy>(line: Vec<T>) -> Vec<T> {
    let n = line.len();
    if n <= MAX_DRAWN_LINE_POINTS {
        return line;
    }
    let step = (n - 1).div_ceil(MAX_DRAWN_LINE_POINTS - 1);
    let mut out: Vec<T> = line.iter().step_by(step).copied().collect();
    if !(n - 1).is_multiple_of(step) {
        out.push(line[n - 1]);
    }
    out
}

/// How much larger a PNG is than the design size: an 800 px design becomes 2400 px.
pub const PNG_SCALE: f64 = 3.0;
/// Print resolution written into PNGs, dots per inch.
pub const PNG_DPI: f64 = 300.0;

/// Where and how big a figure is drawn: format, design size and scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotContext {
    /// Output format.
    pub format: Format,
    /// Size in design pixels (the SVG's size).
    pub size: (u32, u32),
    /// Device pixels per design pixel.
    pub scale: f64,
    /// Whether the figure's title is drawn (not in paper figures, whose caption has it).
    pub titles: bool,
    /// The smallest and largest font size in design pixels, when fonts are held to a
    /// printed size (paper figures).
    pub font_range: Option<(f64, f64)>,
    /// Columns of panels, when a paper figure has room for fewer than its design.
    pub panel_columns: Option<usize>,
}

impl PlotContext {
    /// A context for a figure of the given design size.
    pub fn new(format: Format, size: (u32, u32)) -> Self {
        let scale = match format {
            Format::Svg => 1.0,
            Format::Png => PNG_SCALE,
            Format::Paper(_) => paper::PAPER_SCALE,
        };
        let paper = matches!(format, Format::Paper(_));
        PlotContext {
            format,
            size,
            scale,
            titles: !paper,
            font_range: paper.then(paper::font_range),
            panel_columns: None,
        }
    }

    /// The grid (rows, columns) of panels designed as `grid`, in this figure.
    pub fn panel_grid(&self, grid: (usize, usize)) -> (usize, usize) {
        paper::panel_grid(grid, self.panel_columns)
    }

    /// A font size in design pixels held to the printed range of paper figures.
    fn font_size(&self, size: f64) -> f64 {
        match self.font_range {
            Some((lo, hi)) => size.clamp(lo, hi),
            None => size,
        }
    }

    /// Size in device pixels.
    pub fn pixels(&self) -> (u32, u32) {
        (
            (f64::from(self.size.0) * self.scale).round() as u32,
            (f64::from(self.size.1) * self.scale).round() as u32,
        )
    }

    /// A length in design pixels as device pixels.
    pub fn px(&self, v: f64) -> i32 {
        (v * self.scale).round() as i32
    }

    /// A length in design pixels as device pixels, unsigned.
    pub fn upx(&self, v: f64) -> u32 {
        (v * self.scale).round().max(0.0) as u32
    }

    /// A font of `size` design pixels.
    pub fn font(&self, size: f64) -> TextStyle<'static> {
        style::font(self.font_size(size) * self.scale)
    }

    /// A bold or italic font of `size` design pixels.
    pub fn font_with(&self, size: f64, st: plotters::style::FontStyle) -> TextStyle<'static> {
        style::font_with(self.font_size(size) * self.scale, st)
    }
}

/// A chart with linear axes of floats, as every figure but the mechanisms draws on.
pub(crate) type XyChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The data ranges of a chart: (x0, x1) and (y0, y1).
pub(crate) type Window = ((f64, f64), (f64, f64));

/// The axes of an x–y chart over `window` with their descriptions: labels at plotters' key
/// points on a linear axis, and on a logarithmic one (`log`, whose data are log10 values)
/// the ticks of `style::log_ticks` drawn on `root`; `y_labels` labels on a linear y axis.
pub(crate) fn draw_xy_axes<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &mut XyChart<DB>,
    ctx: &PlotContext,
    (x_desc, y_desc): (&str, &str),
    (((x0, x1), (y0, y1)), (log_x, log_y)): (Window, (bool, bool)),
    y_labels: usize,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let fmt = |log: bool, span: f64| {
        move |v: &f64| {
            if log {
                String::new()
            } else {
                format!("{:.*}", style::decimals_for(span), v)
            }
        }
    };
    let (fx, fy) = (fmt(log_x, x1 - x0), fmt(log_y, y1 - y0));
    let tick = ctx.px(5.0);
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .x_labels(6)
        .y_labels(y_labels)
        .label_style(ctx.font(12.5))
        .axis_desc_style(ctx.font(13.5))
        .set_tick_mark_size(LabelAreaPosition::Bottom, if log_x { 0 } else { tick })
        .set_tick_mark_size(LabelAreaPosition::Left, if log_y { 0 } else { tick })
        .light_line_style(TRANSPARENT)
        .bold_line_style(if log_x || log_y {
            TRANSPARENT.stroke_width(1)
        } else {
            BLACK.mix(0.08).stroke_width(1)
        })
        .draw()?;
    let plot = chart.plotting_area().get_pixel_range();
    if log_x {
        let at = |v: f64| chart.backend_coord(&(v.log10(), y0)).0;
        let ticks = style::placed_log_ticks((10f64.powf(x0), 10f64.powf(x1)), at, ctx, true);
        style::draw_ticks(root, ctx, plot.clone(), style::AxisSide::Bottom, &ticks)?;
    }
    if log_y {
        let at = |v: f64| chart.backend_coord(&(x0, v.log10())).1;
        let ticks = style::placed_log_ticks((10f64.powf(y0), 10f64.powf(y1)), at, ctx, false);
        style::draw_ticks(root, ctx, plot, style::AxisSide::Left, &ticks)?;
    }
    Ok(())
}

/// The μ and K axes of a map over (μ, K), with faint grid lines where `grid_lines` (none
/// over a colour scale).
pub(crate) fn draw_mu_k_mesh<DB: DrawingBackend>(
    chart: &mut XyChart<DB>,
    ctx: &PlotContext,
    ((mu0, mu1), (k0, k1)): Window,
    grid_lines: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let fmt_mu = |v: &f64| format!("{:.*}", style::decimals_for(mu1 - mu0), v);
    let fmt_k = |v: &f64| format!("{:.*}", style::decimals_for(k1 - k0), v);
    let grid = if grid_lines {
        BLACK.mix(0.10).stroke_width(1)
    } else {
        TRANSPARENT.stroke_width(1)
    };
    // Only the labels at multiples of a round step that leaves half a label's width between
    // them: a narrow panel of small multiples labels 0.2, 0.4, ..., not 0.2, 0.3, ...
    let (xr, _) = chart.plotting_area().get_pixel_range();
    let (label_w, _) = style::text_block_size(&ctx.font(13.0), &[fmt_mu(&mu1)], 1.0);
    let fit = f64::from(xr.end - xr.start) / (1.5 * f64::from(label_w.max(1)));
    let step = style::round_step_at_least((mu1 - mu0) / fit.max(1.0));
    let fmt_mu_thinned = |v: &f64| {
        let q = v / step;
        if (q - q.round()).abs() < 1e-6 {
            fmt_mu(v)
        } else {
            String::new()
        }
    };
    chart
        .configure_mesh()
        .x_desc("friction coefficient μ")
        .y_desc("thickness ratio K = R/r")
        .x_label_formatter(&fmt_mu_thinned)
        .y_label_formatter(&fmt_k)
        .label_style(ctx.font(13.0))
        .axis_desc_style(ctx.font(14.0))
        .set_all_tick_mark_size(ctx.px(5.0))
        .light_line_style(TRANSPARENT)
        .bold_line_style(grid)
        .axis_style(BLACK.stroke_width(ctx.upx(1.0).max(1)))
        .draw()
}

/// Drawing failed (a backend error, reported as text).
#[derive(Debug, thiserror::Error)]
#[error("cannot draw the figure: {0}")]
pub struct PlotError(pub String);

/// A chart: knows its design size and how to draw itself on any backend.
pub trait Figure {
    /// Design size in pixels (width, height).
    fn size(&self) -> (u32, u32);
    /// The panels as designed, (rows, columns); a paper figure narrower than the design
    /// stacks them in fewer columns ([`PlotContext::panel_grid`]).
    fn panel_grid(&self) -> (usize, usize) {
        (1, 1)
    }
    /// Draws the figure on `root` (the whole canvas, already filled white).
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB>;
}

fn err<E: std::fmt::Display>(e: E) -> PlotError {
    PlotError(e.to_string())
}

/// Renders a figure to the bytes of an SVG or PNG file.
pub fn render<F: Figure>(fig: &F, format: Format) -> Result<Vec<u8>, PlotError> {
    style::register_fonts();
    let layout = match format {
        Format::Paper(width) => paper::paper_layout(fig.size(), fig.panel_grid(), width),
        Format::Svg | Format::Png => paper::PaperLayout {
            size: fig.size(),
            panel_columns: None,
        },
    };
    let ctx = PlotContext {
        panel_columns: layout.panel_columns,
        ..PlotContext::new(format, layout.size)
    };
    let (w, h) = ctx.pixels();
    match format {
        Format::Svg | Format::Paper(_) => {
            let mut text = String::new();
            {
                let root = SVGBackend::with_string(&mut text, (w, h)).into_drawing_area();
                root.fill(&WHITE).map_err(err)?;
                fig.draw(&root, &ctx).map_err(err)?;
                root.present().map_err(err)?;
            }
            Ok(match format {
                Format::Paper(width) => paper::set_print_size(
                    &paper::single_face(&paper::typeset(&text, paper::min_script_size())),
                    (w, h),
                    width,
                ),
                _ => paper::typeset(&text, 0.0),
            }
            .into_bytes())
        }
        Format::Png => {
            let mut rgb = vec![0u8; 3 * w as usize * h as usize];
            {
                let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
                root.fill(&WHITE).map_err(err)?;
                fig.draw(&root, &ctx).map_err(err)?;
                root.present().map_err(err)?;
            }
            encode_png(&rgb, w, h, PNG_DPI)
        }
    }
}

/// Encodes an RGB buffer as PNG with a physical-size tag of `dpi` dots per inch.
fn encode_png(rgb: &[u8], w: u32, h: u32, dpi: f64) -> Result<Vec<u8>, PlotError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Default);
        let ppm = (dpi / 0.0254).round() as u32;
        enc.set_pixel_dims(Some(png::PixelDimensions {
            xppu: ppm,
            yppu: ppm,
            unit: png::Unit::Meter,
        }));
        let mut writer = enc.write_header().map_err(err)?;
        writer.write_image_data(rgb).map_err(err)?;
        writer.finish().map_err(err)?;
    }
    Ok(out)
}

#[cfg(test)]
mod thinning_tests {
    use super::{MAX_DRAWN_LINE_POINTS, thinned};

    #[test]
    fn a_long_line_is_thinned_to_the_limit_with_both_ends_kept() {
        for n in [
            10,
            MAX_DRAWN_LINE_POINTS,
            MAX_DRAWN_LINE_POINTS + 1,
            1_000_001,
            123_457,
        ] {
            let line: Vec<usize> = (0..n).collect();
            let t = thinned(line);
            assert!(t.len() <= MAX_DRAWN_LINE_POINTS, "{n}: {}", t.len());
            assert_eq!((t[0], *t.last().unwrap()), (0, n - 1), "{n}");
            assert!(t.windows(2).all(|w| w[0] < w[1]));
            if n <= MAX_DRAWN_LINE_POINTS {
                assert_eq!(t.len(), n);
            } else {
                assert!(t.len() > MAX_DRAWN_LINE_POINTS / 2, "{n}: {}", t.len());
            }
        }
    }
}
