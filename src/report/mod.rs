//! The reports of a run: figures for print (plots/*.pdf, plots/*.svg, plots/*.png at a
//! column width), report.html (self-contained, screen figures inlined), report.md (figures
//! linked as PNGs) and every table as CSV and LaTeX (tables/). Everything is built from the
//! stored files of the run directory ([`data::load`]); nothing is recomputed. Templates are
//! embedded and rendered in strict mode; the view model holds formatted text only.

pub mod charts;
pub mod checks;
pub mod convergence;
pub mod data;
pub mod format;
pub mod live;
pub mod paper;
pub mod reduce;
pub mod tables;
pub mod view;

/// The chart builders under their former name.
pub use charts as figures;

use crate::output::{RunLayout, write_atomic};
use crate::plot::{self, Format};
use anyhow::{Context, Result};
use charts::FigureSpec;
use data::RunData;
use minijinja::value::Serde;
use minijinja::{Environment, UndefinedBehavior};
use rayon::prelude::*;
use std::path::Path;

const HTML_TEMPLATE: &str = include_str!("../../templates/report.html.j2");
const MD_TEMPLATE: &str = include_str!("../../templates/report.md.j2");

/// The figures of a run, drawn: their specs and SVG text (for inlining).
#[derive(Debug, Clone)]
pub struct DrawnFigures {
    /// What each figure is.
    pub specs: Vec<FigureSpec>,
    /// The SVG of each figure, in the same order.
    pub svgs: Vec<String>,
}

/// Draws every figure of a run: writes the paper figures plots/STEM.svg, plots/STEM.pdf and
/// plots/STEM.png at the manifest's column width, and returns the screen SVGs to inline.
pub fn draw_figures(data: &RunData, layout: &RunLayout) -> Result<DrawnFigures> {
    let dir = layout.plots();
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let width = data.manifest.figure_width();
    // Figures are independent: each group is built, then its figures rendered (screen SVG,
    // paper SVG, PDF, PNG), on all cores, in order.
    let render = |f: &FigureSpec| -> Result<String> {
        let context = || format!("figure {}", f.stem);
        let paper = f.render(Format::Paper(width)).with_context(context)?;
        write_atomic(&layout.plot(&f.stem, "svg"), &paper)?;
        let paper =
            plot::paper::PaperSvg::parse(&String::from_utf8_lossy(&paper)).with_context(context)?;
        let pdf = paper.pdf().with_context(context)?;
        write_atomic(&layout.plot(&f.stem, "pdf"), &pdf)?;
        let png = paper.png().with_context(context)?;
        write_atomic(&layout.plot(&f.stem, "png"), &png)?;
        let screen = f.render(Format::Svg).with_context(context)?;
        Ok(inline_svg(&String::from_utf8_lossy(&screen), &f.title))
    };
    let groups = charts::build_groups(data)
        .par_iter()
        .map(|g| -> Result<Vec<(FigureSpec, String)>> {
            let specs = g();
            let svgs = specs.par_iter().map(render).collect::<Result<Vec<_>>>()?;
            Ok(specs.into_iter().zip(svgs).collect())
        })
        .collect::<Result<Vec<_>>>()?;
    let (specs, svgs) = groups.into_iter().flatten().unzip();
    Ok(DrawnFigures { specs, svgs })
}

/// An SVG document made ready for inlining in HTML: scalable, with an accessible name.
fn inline_svg(svg: &str, title: &str) -> String {
    let label = title
        .replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;");
    svg.replacen(
        "<svg ",
        &format!("<svg class=\"figure\" role=\"img\" aria-label=\"{label}\" "),
        1,
    )
}

fn environment() -> Result<Environment<'static>> {
    let mut env = Environment::new();
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    env.set_syntax(
        minijinja::syntax::SyntaxConfig::builder()
            .trim_blocks(true)
            .lstrip_blocks(true)
            .build()?,
    );
    env.add_template("report.html.j2", HTML_TEMPLATE)?;
    env.add_template("report.md.j2", MD_TEMPLATE)?;
    Ok(env)
}

/// The HTML report of a view model; control characters and the invisible characters that
/// reorder or hide text (bidirectional overrides, zero-width characters) removed, wherever
/// they came from ([`tables::export::plain`]).
pub fn html(view: &view::ReportView) -> Result<String> {
    let env = environment()?;
    let s = env.get_template("report.html.j2")?.render(Serde(view))?;
    Ok(tables::export::plain(&s))
}

/// Text from the manifest (title, description) made inert in Markdown, as report.html's
/// escaping makes it inert in HTML: `&`, `<`, `>` become entities, Markdown punctuation is
/// backslash-escaped (no code fence, link, emphasis or table cell can open), and a line
/// cannot start a heading, quote, list or rule. Line breaks are kept only when `multiline`.
pub fn markdown_text(text: &str, multiline: bool) -> String {
    let mut out = String::with_capacity(text.len() + 16);
    for (i, line) in text.lines().enumerate() {
        if i > 0 {
            out.push_str(if multiline { "\n" } else { " " });
        }
        let body = line.trim_start();
        out.push_str(&line[..line.len() - body.len()]);
        if body.starts_with(['#', '-', '+', '=']) {
            out.push('\\');
        }
        // (`>` becomes `&gt;`, which opens no quote.) `1.` or `1)` would open an ordered list: the mark after the digits is escaped.
        let digits = body.chars().take_while(char::is_ascii_digit).count();
        for (j, c) in body.chars().enumerate() {
            match c {
                '&' => out.push_str("&amp;"),
                '<' => out.push_str("&lt;"),
                '>' => out.push_str("&gt;"),
                '\\' | '`' | '*' | '_' | '[' | ']' | '|' | '~' => {
                    out.push('\\');
                    out.push(c);
                }
                '.' | ')' if digits > 0 && j == digits => {
                    out.push('\\');
                    out.push(c);
                }
                c => out.push(c),
            }
        }
    }
    out
}

/// The Markdown report of a view model; the title and description from the manifest are
/// escaped ([`markdown_text`]); control and invisible characters removed as in [`html`].
pub fn markdown(view: &view::ReportView) -> Result<String> {
    let env = environment()?;
    let mut view = view.clone();
    view.title = markdown_text(&view.title, false);
    view.description = markdown_text(&view.description, true);
    let mut s = tables::export::plain(&env.get_template("report.md.j2")?.render(Serde(&view))?);
    if !s.ends_with('\n') {
        s.push('\n');
    }
    Ok(s)
}

/// Writes report.html and report.md for drawn figures, and every table of them as CSV and
/// LaTeX in tables/.
pub fn write_reports(data: &RunData, figs: &DrawnFigures, layout: &RunLayout) -> Result<()> {
    let mut v = view::build(data, &figs.specs, &figs.svgs);
    v.tables = write_tables(&v, layout)?;
    write_atomic(&layout.report_html(), html(&v)?.as_bytes())?;
    write_atomic(&layout.report_md(), markdown(&v)?.as_bytes())?;
    Ok(())
}

/// Writes tables/STEM.csv and tables/STEM.tex for every table of a report; returns their
/// paths for the reports' links.
pub fn write_tables(
    v: &view::ReportView,
    layout: &RunLayout,
) -> Result<Vec<tables::export::TableFiles>> {
    let dir = layout.tables();
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut files = Vec::new();
    for t in tables::export::tables(v) {
        write_atomic(
            &layout.table(&t.stem, "csv"),
            tables::export::csv(&t).as_bytes(),
        )?;
        write_atomic(
            &layout.table(&t.stem, "tex"),
            tables::export::latex(&t).as_bytes(),
        )?;
        files.push(t.files());
    }
    Ok(files)
}

/// What re-rendering a run produced.
#[derive(Debug, Clone)]
pub struct ReportSummary {
    /// Figures drawn.
    pub figures: usize,
    /// report.html.
    pub html: std::path::PathBuf,
    /// report.md.
    pub markdown: std::path::PathBuf,
}

/// `archstudy report RUN_DIR`: re-renders every figure and both reports of a run directory
/// from its stored files.
pub fn render_run(dir: &Path) -> Result<ReportSummary> {
    let layout = RunLayout::at(dir);
    crate::output::refuse_symlinks_in(&layout)?;
    crate::output::sweep_temporaries(dir);
    let data = data::load(&layout)
        .with_context(|| format!("cannot read the run directory {}", dir.display()))?;
    let figs = draw_figures(&data, &layout)?;
    write_reports(&data, &figs, &layout)?;
    // The crate describes every file with its size: drawn again, the figures and reports
    // have other sizes, and the description is written again last, as a run writes it.
    let path = layout.manifest();
    let text = crate::output::read_regular_text(&path, crate::manifest::MAX_MANIFEST_BYTES)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let manifest = crate::manifest::parse(&text, &path)?;
    crate::citation::write_crate_metadata(&layout, &manifest, &data.info)?;
    Ok(ReportSummary {
        figures: figs.specs.len(),
        html: layout.report_html(),
        markdown: layout.report_md(),
    })
}

#[cfg(test)]
mod tests {
    use super::markdown_text;

    #[test]
    fn manifest_text_is_inert_in_markdown() {
        assert_eq!(
            markdown_text("<script>alert(1)</script> & more", false),
            "&lt;script&gt;alert(1)&lt;/script&gt; &amp; more"
        );
        // An unclosed code fence cannot swallow the rest of the report.
        assert_eq!(markdown_text("```rust\nopen", true), "\\`\\`\\`rust\nopen");
        assert_eq!(
            markdown_text("# H\n- item\n1. one\n> q", true),
            "\\# H\n\\- item\n1\\. one\n&gt; q"
        );
        assert_eq!(
            markdown_text("a | b *c* [l](u) _d_", false),
            "a \\| b \\*c\\* \\[l\\](u) \\_d\\_"
        );
        assert_eq!(markdown_text("two\nlines", false), "two lines");
        // Ordinary text is unchanged.
        let plain =
            "Semicircular arch with radial joints, K = R/r and mu, after \"Further remarks\".";
        assert_eq!(markdown_text(plain, true), plain);
    }
}
