//! Figures for print: the column width, the typesetting of the text, and the PDF and PNG
//! made from the SVG.
//!
//! A paper figure is drawn once, as SVG, at the column width in CSS pixels (96 to the inch,
//! so one design pixel prints as 0.75 pt; the SVG's own unit is a third of that) with its
//! text at 8–9 pt. The SVG states its
//! printed size in inches; the PDF (svg2pdf) and the 300 dpi PNG (resvg) are converted from
//! that SVG, with a font database holding only the bundled DejaVu Sans, so the three files
//! carry the same text, in the same font, at the same places. The PDF keeps text as text,
//! with the font embedded as a subset.

use super::PlotError;
use crate::manifest::FigureWidth;
use resvg::{tiny_skia, usvg};
use std::fmt::Write as _;
use std::sync::{Arc, OnceLock};

/// CSS pixels to the inch: the design pixels of a paper figure.
pub const PX_PER_INCH: f64 = 96.0;
/// PostScript points per design pixel of a paper figure.
pub const PT_PER_PX: f64 = 72.0 / PX_PER_INCH;
/// SVG units per design pixel of a paper figure: plotters writes whole units, so a finer
/// unit keeps arcs and curves smooth in print (a step of 1/288 in).
pub const PAPER_SCALE: f64 = 3.0;
/// Resolution of the PNG of a paper figure, dots per inch.
pub const PAPER_PNG_DPI: f64 = 300.0;
/// The smallest and largest printed text of a paper figure, points.
pub const TEXT_PT: (f64, f64) = (8.0, 9.0);
/// plotters writes an SVG font size of its font size over this factor (the font's height
/// from descender to ascender in ems).
pub const PLOTTERS_EM: f64 = 1.24;
/// The font family every SVG names: the bundled font, then the generic family any viewer
/// resolves.
pub const FONT_FAMILY: &str = "DejaVu Sans, sans-serif";

/// The printed size in points of a plotters font of `size` design pixels in a paper figure.
pub fn printed_pt(size: f64) -> f64 {
    size / PLOTTERS_EM * PT_PER_PX
}

/// The plotters font sizes (design pixels) that print at [`TEXT_PT`].
pub fn font_range() -> (f64, f64) {
    (
        TEXT_PT.0 * PLOTTERS_EM / PT_PER_PX,
        TEXT_PT.1 * PLOTTERS_EM / PT_PER_PX,
    )
}

/// The narrowest panel of a paper figure, design pixels (a plot with its tick labels and
/// axis description at 8–9 pt needs about this much).
pub const MIN_PANEL_PX: f64 = 300.0;

/// The layout of a paper figure: its design size, and the columns of panels when fewer than
/// the screen design's fit the column width.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PaperLayout {
    /// Design size in pixels.
    pub size: (u32, u32),
    /// Panel columns, when fewer than the design's.
    pub panel_columns: Option<usize>,
}

/// The tallest a paper figure of three or more stacked panels is drawn, over its width: a
/// taller figure does not sit on a page with its caption and text around it.
pub const MAX_HEIGHT_OVER_WIDTH: f64 = 1.3;

/// The layout of a paper figure of a chart whose screen design is `design` with panels in
/// `grid` (rows, columns): the column width, as many panel columns as fit at
/// [`MIN_PANEL_PX`], the panels keeping their proportions. A stack of three or more panels
/// taller than [`MAX_HEIGHT_OVER_WIDTH`] times the width takes more columns than fit at
/// [`MIN_PANEL_PX`], up to the design's grid (text keeps its printed size, [`font_range`]):
/// four mechanism panels in one column are 2×2 instead of 4×1.
pub fn paper_layout(design: (u32, u32), grid: (usize, usize), width: FigureWidth) -> PaperLayout {
    let w = (width.inches() * PX_PER_INCH).round();
    let (rows, cols) = (grid.0.max(1), grid.1.max(1));
    let fit = ((w / MIN_PANEL_PX).floor() as usize).max(1);
    let aspect = f64::from(design.1) / f64::from(design.0.max(1));
    // Text keeps its size when a figure narrows, so a panel narrower than its design gets
    // relatively taller (its legend wraps into more rows): by the square root of the
    // narrowing, at most 1.6 times.
    let taller = |panel_w: f64| {
        (f64::from(design.0) / cols as f64 / panel_w)
            .sqrt()
            .clamp(1.0, 1.6)
    };
    let layout = |h: f64, panel_columns: Option<usize>| PaperLayout {
        size: (w as u32, h.round().max(1.0) as u32),
        panel_columns,
    };
    if cols <= fit {
        return layout(w * aspect * taller(w / cols as f64), None);
    }
    // Stacked panels share one legend and are wider than designed: three quarters of the
    // design's proportions keep a stack of two within about half a page.
    let panel_aspect = aspect * cols as f64 / rows as f64;
    for c in fit..cols {
        let new_rows = (rows * cols).div_ceil(c);
        let h = new_rows as f64 * (w / c as f64) * panel_aspect * 0.75;
        if new_rows <= 2 || h <= MAX_HEIGHT_OVER_WIDTH * w {
            return layout(h, Some(c));
        }
    }
    layout(w * aspect * taller(w / cols as f64), None)
}

/// The grid (rows, columns) panels designed in `grid` take in a layout of `panel_columns`.
pub fn panel_grid(grid: (usize, usize), panel_columns: Option<usize>) -> (usize, usize) {
    match panel_columns {
        Some(c) if c < grid.1 => ((grid.0.max(1) * grid.1).div_ceil(c.max(1)), c.max(1)),
        _ => grid,
    }
}

/// The font database of the conversions: the bundled DejaVu Sans only, also as the generic
/// `sans-serif`; no system font is read. One face: svg2pdf writes the fonts of a PDF in an
/// order that changes from one process to the next, so a PDF with one font is the only
/// one a re-drawn run reproduces byte for byte (paper figures set no bold or italic,
/// [`single_face`]).
fn fontdb() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(dejavu::sans::regular().to_vec());
        db.set_sans_serif_family("DejaVu Sans");
        Arc::new(db)
    })
    .clone()
}

fn tree(svg: &str) -> Result<usvg::Tree, PlotError> {
    let opt = usvg::Options {
        fontdb: fontdb(),
        font_family: "DejaVu Sans".to_string(),
        ..usvg::Options::default()
    };
    usvg::Tree::from_str(svg, &opt).map_err(|e| PlotError(format!("cannot read the SVG: {e}")))
}

/// The PDF of a paper SVG: one page of the SVG's printed size, text as text in the embedded
/// (subset) font.
pub fn svg_to_pdf(svg: &str) -> Result<Vec<u8>, PlotError> {
    PaperSvg::parse(svg)?.pdf()
}

/// A paper SVG read once, for its PDF and its PNG.
pub struct PaperSvg(usvg::Tree);

impl PaperSvg {
    /// Reads a paper SVG.
    pub fn parse(svg: &str) -> Result<Self, PlotError> {
        tree(svg).map(PaperSvg)
    }

    /// The PDF ([`svg_to_pdf`]).
    pub fn pdf(&self) -> Result<Vec<u8>, PlotError> {
        pdf_of(&self.0)
    }

    /// The PNG ([`svg_to_png`]).
    pub fn png(&self) -> Result<Vec<u8>, PlotError> {
        png_of(&self.0)
    }
}

fn pdf_of(t: &usvg::Tree) -> Result<Vec<u8>, PlotError> {
    svg2pdf::to_pdf(
        t,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions {
            dpi: PX_PER_INCH as f32,
        },
    )
    .map(|pdf| canonical_pdf(&pdf))
    .map_err(|e| PlotError(format!("cannot convert the figure to PDF: {e}")))
}

/// A PDF with the entries of its resource dictionaries in a fixed order. svg2pdf writes
/// them from a hash map, in an order that changes from one process to the next; a run
/// re-drawn must give the same bytes (verify compares them). Each run of lines
/// `/NAME N 0 R` outside streams is sorted by name; the lines are only permuted, so every
/// byte offset of the file stays valid.
pub fn canonical_pdf(pdf: &[u8]) -> Vec<u8> {
    let is_ref = |l: &[u8]| {
        let t = l.trim_ascii();
        let Some(rest) = t.strip_prefix(b"/") else {
            return false;
        };
        let parts: Vec<&[u8]> = rest.split(|&b| b == b' ').collect();
        parts.len() == 4
            && parts[0].iter().all(u8::is_ascii_alphanumeric)
            && parts[1].iter().all(u8::is_ascii_digit)
            && parts[2] == b"0"
            && parts[3] == b"R"
    };
    // Natural order: letters, then the number that follows (xo2 before xo10).
    let key = |l: &[u8]| {
        let name: Vec<u8> = l
            .trim_ascii()
            .split(|&b| b == b' ')
            .next()
            .unwrap_or(b"")
            .to_vec();
        let digits = name.iter().rev().take_while(|b| b.is_ascii_digit()).count();
        let (head, tail) = name.split_at(name.len() - digits);
        let n: u64 = std::str::from_utf8(tail)
            .ok()
            .and_then(|t| t.parse().ok())
            .unwrap_or(0);
        (head.to_vec(), n)
    };
    let mut out: Vec<u8> = Vec::with_capacity(pdf.len());
    let mut run: Vec<&[u8]> = Vec::new();
    let mut in_stream = false;
    let flush = |run: &mut Vec<&[u8]>, out: &mut Vec<u8>| {
        run.sort_by_key(|l| key(l));
        for l in run.drain(..) {
            out.extend_from_slice(l);
        }
    };
    for line in pdf.split_inclusive(|&b| b == b'\n') {
        let t = line.trim_ascii();
        if !in_stream && is_ref(line) {
            run.push(line);
            continue;
        }
        flush(&mut run, &mut out);
        if t == b"stream" {
            in_stream = true;
        } else if t == b"endstream" || t.starts_with(b"endstream") {
            in_stream = false;
        }
        out.extend_from_slice(line);
    }
    flush(&mut run, &mut out);
    out
}

/// The PNG of a paper SVG at [`PAPER_PNG_DPI`] for its printed size, anti-aliased, on white.
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, PlotError> {
    PaperSvg::parse(svg)?.png()
}

fn png_of(t: &usvg::Tree) -> Result<Vec<u8>, PlotError> {
    let s = (PAPER_PNG_DPI / PX_PER_INCH) as f32;
    let w = (t.size().width() * s).round() as u32;
    let h = (t.size().height() * s).round() as u32;
    let mut pixmap = tiny_skia::Pixmap::new(w.max(1), h.max(1))
        .ok_or_else(|| PlotError(format!("cannot allocate a {w} × {h} image")))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        t,
        tiny_skia::Transform::from_scale(s, s),
        &mut pixmap.as_mut(),
    );
    // Opaque on white: the premultiplied RGBA is plain RGB.
    let rgb: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    super::encode_png(&rgb, pixmap.width(), pixmap.height(), PAPER_PNG_DPI)
}

/// An SVG with every text in the regular face: bold and italic attributes removed (see
/// [`fontdb`]).
pub fn single_face(svg: &str) -> String {
    svg.replace(" font-weight=\"bold\"", "")
        .replace(" font-style=\"italic\"", "")
        .replace(" font-style=\"oblique\"", "")
}

/// Sets the printed size of an SVG written by plotters: `width` and `height` in inches, the
/// width exactly that of the column, for a design of `size` pixels (its viewBox is kept).
pub fn set_print_size(svg: &str, size: (u32, u32), width: FigureWidth) -> String {
    let win = width.inches();
    let hin = win * f64::from(size.1) / f64::from(size.0.max(1));
    let from = format!("width=\"{}\" height=\"{}\"", size.0, size.1);
    let to = format!("width=\"{win}in\" height=\"{hin:.4}in\"");
    svg.replacen(&from, &to, 1)
}

/// The smallest font size of a sub- or superscript of a paper figure, in its SVG units:
/// 7 pt printed.
pub fn min_script_size() -> f64 {
    MIN_SCRIPT_PT * PAPER_SCALE / PT_PER_PX
}

/// The smallest printed sub- or superscript of a paper figure, points.
pub const MIN_SCRIPT_PT: f64 = 7.0;

/// Typesets the text of an SVG written by plotters: one font family with a generic
/// fallback, `K_c` as K with a subscript c and `H^r` as H with a superscript r, a minus
/// sign for a hyphen before a number, `1e-3` as 10 with a superscript −3, and a zero
/// written as `0` (no `-0.000`). Scripts are 70 % of the text's size, and no smaller than
/// `min_script` SVG units.
pub fn typeset(svg: &str, min_script: f64) -> String {
    let svg = svg
        .replace("font-family=\"sans-serif\"", &family_attr())
        .replace("font-family=\"dejavu-sans\"", &family_attr());
    let mut out = String::with_capacity(svg.len() + svg.len() / 8);
    let mut rest = svg.as_str();
    while let Some(i) = rest.find("<text") {
        let Some(open_end) = rest[i..].find('>').map(|j| i + j + 1) else {
            break;
        };
        let Some(close) = rest[open_end..].find("</text>").map(|j| open_end + j) else {
            break;
        };
        let tag = &rest[i..open_end];
        out.push_str(&rest[..open_end]);
        let size = attr(tag, "font-size")
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(12.0);
        out.push_str(&typeset_text(
            rest[open_end..close].trim(),
            size,
            min_script,
        ));
        rest = &rest[close..];
    }
    out.push_str(rest);
    out
}

fn family_attr() -> String {
    format!("font-family=\"{FONT_FAMILY}\"")
}

fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let i = tag.find(&key)? + key.len();
    let j = tag[i..].find('"')? + i;
    Some(&tag[i..j])
}

/// A run of text at the baseline, lowered (subscript) or raised (superscript).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shift {
    /// On the baseline.
    Base,
    /// A subscript: `c` of `K_c`.
    Sub,
    /// A superscript: `r` of `H^r`, `−3` of `1e-3`.
    Sup,
}

/// The pieces of a text: plain runs and sub- and superscripts. `X_tok` is X with the
/// subscript tok when X is a single letter (so `self_weight` stays as it is), `X^tok` and
/// `X^(…)` a superscript, `1eN` is 10 with the superscript N, a zero however written is
/// `0`, and a hyphen before a number is a minus sign.
pub fn pieces(text: &str) -> Vec<(Shift, String)> {
    if is_zero(text) {
        return vec![(Shift::Base, "0".into())];
    }
    if let Some(e) = text.strip_prefix("1e")
        && e.parse::<i32>().is_ok()
    {
        return vec![
            (Shift::Base, "10".into()),
            (Shift::Sup, e.replace('-', "\u{2212}")),
        ];
    }
    let c: Vec<char> = text.chars().collect();
    let mut out: Vec<(Shift, String)> = Vec::new();
    let push = |s: Shift, ch: char, out: &mut Vec<(Shift, String)>| match out.last_mut() {
        Some((k, t)) if *k == s => t.push(ch),
        _ => out.push((s, ch.to_string())),
    };
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        let prev = i.checked_sub(1).map(|j| c[j]);
        let before = i.checked_sub(2).map(|j| c[j]);
        let next = c.get(i + 1).copied();
        let sub_len = c[i + 1..]
            .iter()
            .take_while(|x| x.is_alphanumeric())
            .count();
        // `t_over_r` is a name, not t with a subscript: nothing joins on after the token.
        if ch == '_'
            && prev.is_some_and(char::is_alphabetic)
            && !before.is_some_and(|b| b.is_alphanumeric() || b == '_')
            && sub_len > 0
            && c.get(i + 1 + sub_len) != Some(&'_')
        {
            for &x in &c[i + 1..i + 1 + sub_len] {
                push(Shift::Sub, x, &mut out);
            }
            i += 1 + sub_len;
            continue;
        }
        if ch == '^' && prev.is_some_and(|p| p.is_alphanumeric() || p == ')') {
            let n = superscript_len(&c[i + 1..]);
            if n > 0 {
                for &x in &c[i + 1..i + 1 + n] {
                    push(Shift::Sup, if x == '-' { '\u{2212}' } else { x }, &mut out);
                }
                i += 1 + n;
                continue;
            }
        }
        let minus = ch == '-'
            && next.is_some_and(|n| n.is_ascii_digit() || n == '.')
            && !prev.is_some_and(char::is_alphanumeric);
        push(Shift::Base, if minus { '\u{2212}' } else { ch }, &mut out);
        i += 1;
    }
    out
}

/// Length of a superscript at the start of `c`: `(…)`, or an optional minus and a run of
/// letters and digits.
fn superscript_len(c: &[char]) -> usize {
    if c.first() == Some(&'(') {
        return c.iter().position(|&x| x == ')').map_or(0, |j| j + 1);
    }
    let sign = usize::from(c.first() == Some(&'-'));
    let n = c[sign..].iter().take_while(|x| x.is_alphanumeric()).count();
    if n == 0 { 0 } else { sign + n }
}

/// `-0`, `0.000`, `-0.0`: a zero however it is written.
fn is_zero(s: &str) -> bool {
    let t = s.strip_prefix('-').unwrap_or(s);
    let t = t.strip_prefix('\u{2212}').unwrap_or(t);
    let mut parts = t.splitn(2, '.');
    let int = parts.next().unwrap_or("");
    let frac = parts.next().unwrap_or("");
    int == "0" && frac.chars().all(|c| c == '0')
}

/// The SVG content of a text: plain runs as text, sub- and superscripts as `tspan`s at 70 %
/// of the size (at least `min_script`), lowered or raised by a fraction of `size`, the
/// baseline restored after.
fn typeset_text(text: &str, size: f64, min_script: f64) -> String {
    let p = pieces(text);
    if p.iter().all(|(k, _)| *k == Shift::Base) {
        return p.into_iter().map(|(_, t)| t).collect();
    }
    let offset = |k: Shift| match k {
        Shift::Base => 0.0,
        Shift::Sub => 0.22 * size,
        Shift::Sup => -0.38 * size,
    };
    let mut out = String::new();
    let mut at = 0.0;
    for (k, t) in p {
        let dy = offset(k) - at;
        at = offset(k);
        if k == Shift::Base {
            if dy == 0.0 {
                out.push_str(&t);
            } else {
                let _ = write!(out, "<tspan dy=\"{dy:.2}\">{t}</tspan>");
            }
        } else {
            let _ = write!(
                out,
                "<tspan dy=\"{dy:.2}\" font-size=\"{:.2}\">{t}</tspan>",
                (0.7 * size).max(min_script)
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symbols_are_typeset() {
        let p = pieces("K_c against μ_min");
        assert_eq!(
            p,
            vec![
                (Shift::Base, "K".into()),
                (Shift::Sub, "c".into()),
                (Shift::Base, " against μ".into()),
                (Shift::Sub, "min".into()),
            ]
        );
        assert_eq!(
            pieces("H^r, H^s"),
            vec![
                (Shift::Base, "H".into()),
                (Shift::Sup, "r".into()),
                (Shift::Base, ", H".into()),
                (Shift::Sup, "s".into()),
            ]
        );
        assert_eq!(
            pieces("t/R_c"),
            vec![(Shift::Base, "t/R".into()), (Shift::Sub, "c".into())]
        );
        // A name with an underscore is not a subscript.
        assert_eq!(
            pieces("self_weight"),
            vec![(Shift::Base, "self_weight".into())]
        );
        assert_eq!(
            pieces("1e-3"),
            vec![(Shift::Base, "10".into()), (Shift::Sup, "\u{2212}3".into())]
        );
        // A multiple of a power of ten on a short logarithmic axis.
        assert_eq!(
            pieces("2×10^-2"),
            vec![
                (Shift::Base, "2×10".into()),
                (Shift::Sup, "\u{2212}2".into())
            ]
        );
        assert_eq!(pieces("-0.0000"), vec![(Shift::Base, "0".into())]);
        assert_eq!(pieces("0.000"), vec![(Shift::Base, "0".into())]);
        assert_eq!(pieces("-0.25"), vec![(Shift::Base, "\u{2212}0.25".into())]);
        assert_eq!(pieces("K − 1"), vec![(Shift::Base, "K − 1".into())]);
    }

    #[test]
    fn text_elements_get_tspans_and_one_family() {
        let svg = "<svg width=\"100\" height=\"50\" viewBox=\"0 0 100 50\">\n<text x=\"1\" y=\"2\" font-family=\"sans-serif\" font-size=\"10\">\nK_c\n</text>\n</svg>";
        let t = typeset(svg, 0.0);
        assert!(t.contains("font-family=\"DejaVu Sans, sans-serif\""), "{t}");
        assert!(
            t.contains(">K<tspan dy=\"2.20\" font-size=\"7.00\">c</tspan></text>"),
            "{t}"
        );
        let sized = set_print_size(&t, (100, 50), FigureWidth::Single);
        assert!(
            sized.contains("width=\"3.5in\" height=\"1.7500in\""),
            "{sized}"
        );
    }

    #[test]
    fn resource_entries_are_sorted_in_place() {
        let pdf = b"<<\n  /XObject <<\n    /xo10 40 0 R\n    /xo2 12 0 R\n  >>\nstream\n/b 1 0 R\n/a 2 0 R\nendstream\n";
        let c = canonical_pdf(pdf);
        assert_eq!(c.len(), pdf.len());
        assert_eq!(
            String::from_utf8(c).unwrap(),
            "<<\n  /XObject <<\n    /xo2 12 0 R\n    /xo10 40 0 R\n  >>\nstream\n/b 1 0 R\n/a 2 0 R\nendstream\n"
        );
    }

    #[test]
    fn paper_text_prints_at_eight_to_nine_points() {
        let (lo, hi) = font_range();
        assert!((printed_pt(lo) - 8.0).abs() < 1e-12);
        assert!((printed_pt(hi) - 9.0).abs() < 1e-12);
        let one = paper_layout((820, 600), (1, 1), FigureWidth::Single);
        // 820 → 336 px: 1.56 times the design's proportion.
        assert_eq!(one.size, (336, 384));
        assert_eq!(one.panel_columns, None);
        assert_eq!(
            paper_layout((820, 600), (1, 1), FigureWidth::Double).size.0,
            691
        );
        // Two panels of 500 × 520 side by side: stacked in one column, each 336 wide.
        let two = paper_layout((1000, 520), (1, 2), FigureWidth::Single);
        assert_eq!(two.size, (336, 524));
        assert_eq!(two.panel_columns, Some(1));
        assert_eq!(panel_grid((1, 2), two.panel_columns), (2, 1));
        // Four mechanism panels of 440 × 290 in 2 × 2: stacked 4 × 1 they would be 664 px
        // (6.9 in) tall, twice the width; 2 × 2 at the column width they are 336 × 0.659 ×
        // 1.6 (the text of a panel half as wide as designed) = 354 px.
        let four = paper_layout((880, 580), (2, 2), FigureWidth::Single);
        assert_eq!(four.size, (336, 354));
        assert_eq!(four.panel_columns, None);
        assert!(f64::from(four.size.1) <= MAX_HEIGHT_OVER_WIDTH * f64::from(four.size.0));
        // Three panels in a row stack as three in one column while that stays low enough.
        let three = paper_layout((900, 150), (1, 3), FigureWidth::Single);
        assert_eq!(three.panel_columns, Some(1));
        // Two fit in two columns.
        let wide = paper_layout((1000, 520), (1, 2), FigureWidth::Double);
        assert_eq!(wide.panel_columns, None);
        assert_eq!(panel_grid((1, 2), None), (1, 2));
        let printed = min_script_size() * PT_PER_PX / PAPER_SCALE;
        assert!((printed - 7.0).abs() < 1e-12);
    }
}
