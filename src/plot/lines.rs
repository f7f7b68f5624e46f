//! Curves of one value against a parameter, one line per value of another parameter, each
//! point marked in the colour of its collapse mechanism: λ against K for a few μ, λ against
//! μ for a few K, the influence line λ against the position of a point load.

use super::style::{self, LabelPlacer, LegendItem, Mark, clip_polyline, palette};
use super::{Figure, PlotContext, XyChart};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One point of a line: abscissa, ordinate (NaN breaks the line) and the mechanism there.
#[derive(Debug, Clone, PartialEq)]
pub struct LinePoint {
    /// x.
    pub x: f64,
    /// y; NaN where there is no value (λ unbounded, no equilibrium).
    pub y: f64,
    /// `rotational`, `mixed`, `sliding`, or empty.
    pub mechanism: String,
    /// The collapse when it comes before y (the non-associative gap), drawn as a red bar
    /// from it up to y; NaN where there is no gap.
    pub collapse: f64,
}

/// One line, labelled at its right end.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Label, e.g. `μ = 0.4`.
    pub label: String,
    /// Its points, by increasing x.
    pub points: Vec<LinePoint>,
}

/// One panel.
#[derive(Debug, Clone, PartialEq)]
pub struct LinePanel {
    /// Panel title.
    pub title: String,
    /// x-axis description.
    pub x_desc: String,
    /// y-axis description.
    pub y_desc: String,
    /// The lines.
    pub lines: Vec<Line>,
    /// A logarithmic y axis (for values spanning more than a decade or two).
    pub log_y: bool,
    /// Points found between the lines' points (the least of an influence line refined
    /// between grid positions), drawn as open diamonds; empty for none.
    pub marks: Vec<(f64, f64)>,
}

impl LinePanel {
    /// The ordinate as drawn: log10 y on a logarithmic axis (NaN where y ≤ 0).
    fn y_of(&self, y: f64) -> f64 {
        if !self.log_y {
            y
        } else if y > 0.0 {
            y.log10()
        } else {
            f64::NAN
        }
    }
}

/// What the figure shows.
#[derive(Debug, Clone, PartialEq)]
pub struct LinesChart {
    /// Title.
    pub title: String,
    /// One or two panels, side by side.
    pub panels: Vec<LinePanel>,
}

/// The grey of line `i` of `n`: from near black to a light grey in equal steps, so that the
/// mechanism colours stay the only colours and no two lines of a panel share a grey.
fn line_grey(i: usize, n: usize) -> RGBColor {
    let (dark, light) = (30.0, 185.0);
    let f = if n > 1 {
        i as f64 / (n - 1) as f64
    } else {
        0.0
    };
    let g = (dark + (light - dark) * f.min(1.0)).round() as u8;
    RGBColor(g, g, g)
}

fn range(vals: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = vals
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        None
    } else if lo == hi {
        Some((lo - 0.5 * lo.abs().max(1e-3), hi + 0.5 * hi.abs().max(1e-3)))
    } else {
        Some((lo, hi))
    }
}

fn panel_window(p: &LinePanel) -> Option<((f64, f64), (f64, f64))> {
    let pts = || p.lines.iter().flat_map(|l| l.points.iter());
    let (x0, x1) = range(pts().filter(|q| q.y.is_finite()).map(|q| q.x))?;
    let (y0, y1) = range(
        pts()
            .flat_map(|q| [p.y_of(q.y), p.y_of(q.collapse)])
            .chain(p.marks.iter().map(|m| p.y_of(m.1))),
    )?;
    let y0 = if !p.log_y && y0 > 0.0 && y0 < 0.3 * y1 {
        0.0
    } else {
        y0
    };
    let pad = 0.06 * (y1 - y0);
    let xpad = 0.02 * (x1 - x0);
    Some(((x0 - xpad, x1 + xpad), (y0 - pad, y1 + pad)))
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    root: &DrawingArea<DB, Shift>,
    ctx: &PlotContext,
    (p, named_in_legend): (&LinePanel, bool),
) -> DrawResult<(), DB> {
    let Some(((x0, x1), (y0, y1))) = panel_window(p) else {
        area.draw(&Text::new(
            "no finite values in this study".to_string(),
            (ctx.px(30.0), ctx.px(60.0)),
            ctx.font(14.0),
        ))?;
        return Ok(());
    };
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, ctx.font(15.0))
        .margin(ctx.px(10.0))
        .margin_right(ctx.px(70.0))
        .x_label_area_size(ctx.px(48.0))
        .y_label_area_size(ctx.px(66.0))
        .build_cartesian_2d(x0..x1, y0..y1)?;
    super::frames::record(&chart, (x0, x1), (y0, y1), p.log_y);
    super::draw_xy_axes(
        root,
        &mut chart,
        ctx,
        (&p.x_desc, &p.y_desc),
        (((x0, x1), (y0, y1)), (false, p.log_y)),
        7,
    )?;
    for (i, l) in p.lines.iter().enumerate() {
        let grey = line_grey(i, p.lines.len());
        let pts: Vec<(f64, f64)> = l.points.iter().map(|q| (q.x, p.y_of(q.y))).collect();
        for piece in clip_polyline(&pts, (x0, x1), (y0, y1)) {
            chart.draw_series(LineSeries::new(piece, grey.stroke_width(ctx.upx(1.6))))?;
        }
    }
    draw_points(root, &chart, ctx, (p, named_in_legend))
}

/// The points, in their mechanism's colour (small when there are many), and each line's
/// label at its last finite point.
fn draw_points<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &XyChart<DB>,
    ctx: &PlotContext,
    (p, named_in_legend): (&LinePanel, bool),
) -> DrawResult<(), DB> {
    let count: usize = p.lines.iter().map(|l| l.points.len()).sum();
    let r = if count > 400 { 1.8 } else { 3.2 };
    draw_gaps(root, chart, ctx, p, r)?;
    for l in &p.lines {
        for q in l.points.iter().filter(|q| p.y_of(q.y).is_finite()) {
            let c = chart.backend_coord(&(q.x, p.y_of(q.y)));
            let color = palette::mechanism(&q.mechanism);
            root.draw(&Circle::new(c, ctx.upx(r), color.filled()))?;
        }
    }
    for &(x, y) in p.marks.iter().filter(|m| p.y_of(m.1).is_finite()) {
        let c = chart.backend_coord(&(x, p.y_of(y)));
        style::diamond(root, ctx, c, r + 3.0, palette::INK)?;
    }
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let mut placer = LabelPlacer::new((xr.start, yr.start, xr.end + ctx.px(68.0), yr.end));
    // Every drawn point keeps labels off it: a label over another line's points reads as
    // naming that line.
    let rr = ctx.px(r);
    for (i, l) in p.lines.iter().enumerate() {
        for q in l.points.iter().filter(|q| p.y_of(q.y).is_finite()) {
            let c = chart.backend_coord(&(q.x, p.y_of(q.y)));
            placer.block((c.0 - rr, c.1 - rr, c.0 + rr, c.1 + rr));
        }
        // So does every gap bar: a label over one reads as crossing it out.
        let dx = gap_offset(ctx, i, p.lines.len());
        for (a, b, w) in l
            .points
            .iter()
            .filter_map(|q| gap_bar(chart, ctx, (p, q), (r, dx)))
        {
            placer.block((a.0 - w, a.1.min(b.1), a.0 + w, a.1.max(b.1)));
        }
    }
    let font = ctx.font(11.5);
    let mut placed: Vec<(String, (i32, i32))> = Vec::new();
    for l in &p.lines {
        let Some(last) = l.points.iter().rev().find(|q| p.y_of(q.y).is_finite()) else {
            continue;
        };
        let c = chart.backend_coord(&(last.x, p.y_of(last.y)));
        let (tw, th) = style::text_block_size(&font, std::slice::from_ref(&l.label), 1.0);
        let g = ctx.px(6.0);
        // Only right of the end: a label left of it reads as naming another line's point.
        let cands = [
            (c.0 + g, c.1 - th / 2),
            (c.0 + g, c.1 - th - g),
            (c.0 + g, c.1 + g),
        ];
        // Lines the legend names are labelled all or none: where one has no free place
        // right of its end, end labels would name some lines and not others.
        let at = match placer.try_place(tw, th, &cands) {
            Some(at) => at,
            None if named_in_legend => return Ok(()),
            None => placer.place(tw, th, &cands),
        };
        placed.push((l.label.clone(), at));
    }
    for (label, at) in placed {
        root.draw(&Text::new(
            label,
            at,
            font.color(&palette::INK)
                .pos(Pos::new(HPos::Left, VPos::Top)),
        ))?;
    }
    Ok(())
}

/// The gap of every point that has one: a bar from the collapse (a short crossbar) up to the
/// point's value, in a colour no mechanism uses; the bars of the lines at one x are set a
/// little apart.
fn draw_gaps<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &XyChart<DB>,
    ctx: &PlotContext,
    p: &LinePanel,
    r: f64,
) -> DrawResult<(), DB> {
    let style = palette::GAP.stroke_width(ctx.upx(1.4));
    for (i, l) in p.lines.iter().enumerate() {
        let dx = gap_offset(ctx, i, p.lines.len());
        for (a, b, w) in l
            .points
            .iter()
            .filter_map(|q| gap_bar(chart, ctx, (p, q), (r, dx)))
        {
            root.draw(&PathElement::new(vec![a, b], style))?;
            root.draw(&PathElement::new(
                vec![(b.0 - w, b.1), (b.0 + w, b.1)],
                style,
            ))?;
        }
    }
    Ok(())
}

/// How far to the side, in pixels, the gap bars of line `i` of `n` are set.
fn gap_offset(ctx: &PlotContext, i: usize, n: usize) -> i32 {
    ctx.px((i as f64 - 0.5 * (n as f64 - 1.0)) * 3.0)
}

/// A gap bar in pixels: its top (the point's value), its bottom (the collapse) and the
/// half-width of the crossbar there.
type GapBar = ((i32, i32), (i32, i32), i32);

/// The gap bar of one point, `dx` pixels to the side; `None` without a gap.
fn gap_bar<DB: DrawingBackend>(
    chart: &XyChart<DB>,
    ctx: &PlotContext,
    (p, q): (&LinePanel, &LinePoint),
    (r, dx): (f64, i32),
) -> Option<GapBar> {
    let (top, bottom) = (p.y_of(q.y), p.y_of(q.collapse));
    if !top.is_finite() || !bottom.is_finite() {
        return None;
    }
    let shift = |c: (i32, i32)| (c.0 + dx, c.1);
    let (a, b) = (
        shift(chart.backend_coord(&(q.x, top))),
        shift(chart.backend_coord(&(q.x, bottom))),
    );
    Some((a, b, ctx.px(r + 1.5)))
}

impl Figure for LinesChart {
    fn size(&self) -> (u32, u32) {
        if self.panels.len() > 1 {
            (1040, 520)
        } else {
            (820, 540)
        }
    }

    fn panel_grid(&self) -> (usize, usize) {
        (1, self.panels.len().max(1))
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        ctx: &PlotContext,
    ) -> DrawResult<(), DB> {
        let areas = style::panel_areas(root, ctx, &self.legend(), &self.title, self.panels.len())?;
        for (a, p) in areas.iter().zip(&self.panels) {
            draw_panel(a, root, ctx, (p, self.shared_lines()))?;
        }
        Ok(())
    }
}

impl LinesChart {
    /// True when every panel draws the same lines (same labels, same order): the legend
    /// then names each line's shade.
    fn shared_lines(&self) -> bool {
        let labels = |p: &LinePanel| p.lines.iter().map(|l| l.label.clone()).collect::<Vec<_>>();
        self.panels
            .windows(2)
            .all(|w| labels(&w[0]) == labels(&w[1]))
    }

    /// The mechanisms present, in a fixed order.
    fn legend(&self) -> Vec<LegendItem> {
        let present = |m: &str| {
            self.panels
                .iter()
                .flat_map(|p| &p.lines)
                .flat_map(|l| &l.points)
                .any(|q| q.mechanism == m && q.y.is_finite())
        };
        let mut items: Vec<LegendItem> = ["rotational", "mixed", "sliding"]
            .into_iter()
            .filter(|m| present(m))
            .map(|m| LegendItem::new(format!("{m} collapse"), Mark::Dot(palette::mechanism(m))))
            .collect();
        if (self.panels.iter())
            .flat_map(|p| &p.lines)
            .flat_map(|l| &l.points)
            .any(|q| q.collapse.is_finite() && q.y.is_finite())
        {
            items.push(LegendItem::new(
                "gap: from the collapse (first complete solution, crossbar) to the static limit",
                Mark::Line {
                    color: palette::GAP,
                    width: 1.4,
                    dashed: false,
                },
            ));
        }
        if self.panels.iter().any(|p| !p.marks.is_empty()) {
            items.push(LegendItem::new(
                "least λ_max refined between grid positions",
                Mark::Diamond(palette::INK),
            ));
        }
        // Each line's shade of grey, when every panel draws the same lines (an influence line
        // against angle and x/L); otherwise each line is named at its end.
        if let Some(p) = self.panels.first().filter(|_| self.shared_lines()) {
            items.extend(p.lines.iter().enumerate().map(|(i, l)| {
                LegendItem::new(
                    l.label.clone(),
                    Mark::Line {
                        color: line_grey(i, p.lines.len()),
                        width: 2.4,
                        dashed: false,
                    },
                )
            }));
        }
        items
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_line_of_a_panel_gets_its_own_grey() {
        // Five voussoir counts: five greys, darkest first, none repeated.
        let greys: Vec<u8> = (0..5).map(|i| line_grey(i, 5).0).collect();
        assert_eq!(greys, [30, 69, 108, 146, 185]);
        assert_eq!(line_grey(0, 1), RGBColor(30, 30, 30));
    }

    #[test]
    fn an_end_label_clears_the_gap_bar_at_its_line_end() {
        // Four lines; the last ends in a small gap, whose bar is set 4.5 px right of its point
        // and whose crossbar ran under the start of the label.
        let point = |x: f64, y: f64, collapse: f64| LinePoint {
            x,
            y,
            mechanism: "mixed".into(),
            collapse,
        };
        let lines = (0..4)
            .map(|i| {
                let top = 0.2 + 0.2 * i as f64;
                let gap = if i == 3 { top - 0.005 } else { f64::NAN };
                Line {
                    label: ["K = 1.1", "K = 1.2", "K = 1.3", "K = 1.4"][i].into(),
                    points: vec![point(0.4, top - 0.1, f64::NAN), point(1.0, top, gap)],
                }
            })
            .collect();
        let chart = LinesChart {
            title: "λ against μ".into(),
            panels: vec![LinePanel {
                title: String::new(),
                x_desc: "μ".into(),
                y_desc: "λ".into(),
                lines,
                log_y: false,
                marks: Vec::new(),
            }],
        };
        let svg =
            String::from_utf8(super::super::render(&chart, super::super::Format::Svg).unwrap())
                .unwrap();
        let number = |tag: &str, key: &str| -> f64 {
            let at = tag.find(&format!(" {key}=\"")).unwrap() + key.len() + 3;
            tag[at..].split('"').next().unwrap().parse().unwrap()
        };
        // The end label, drawn after the legend's entry of the same name.
        let label = svg
            .split('<')
            .rfind(|t| t.starts_with("text") && t.ends_with("K = 1.4"))
            .unwrap();
        // The label's box (its text starts at x; its top is y, as drawn with `dy` 0.76em) and
        // every gap bar's.
        let size = number(label, "font-size");
        let (x, y) = (number(label, "x"), number(label, "y"));
        let text = (x, y, x + 3.0 * size, y + size);
        let bars: Vec<(f64, f64, f64, f64)> = svg
            .split('<')
            .filter(|t| t.starts_with("polyline") && t.contains("stroke=\"#009E73\""))
            .map(|t| {
                let at = t.find("points=\"").unwrap() + 8;
                t[at..]
                    .split('"')
                    .next()
                    .unwrap()
                    .split_whitespace()
                    .map(|p| {
                        let (x, y) = p.split_once(',').unwrap();
                        (x.parse::<f64>().unwrap(), y.parse::<f64>().unwrap())
                    })
                    .fold(
                        (
                            f64::INFINITY,
                            f64::INFINITY,
                            f64::NEG_INFINITY,
                            f64::NEG_INFINITY,
                        ),
                        |b, (x, y)| (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y)),
                    )
            })
            .collect();
        assert!(bars.len() >= 2, "no gap bar drawn: {svg}");
        for bar in &bars {
            let apart = text.2 <= bar.0 || bar.2 <= text.0 || text.3 <= bar.1 || bar.3 <= text.1;
            assert!(apart, "label box {text:?} over the gap bar {bar:?}");
        }
    }
}
