//! The list of figures: number, heading, caption, files and inlined SVG.

use crate::report::charts::FigureSpec;
use serde::Serialize;

/// A figure as placed in a report.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct FigureView {
    /// Number in the report.
    pub number: usize,
    /// Heading.
    pub title: String,
    /// Caption.
    pub caption: String,
    /// Relative path of the PNG.
    pub png: String,
    /// Relative path of the SVG.
    pub svg_path: String,
    /// Relative path of the PDF.
    pub pdf: String,
    /// The SVG markup, inlined in the HTML report.
    pub svg: String,
    /// Anchor id.
    pub anchor: String,
}

/// The figures as placed in a report, numbered from 1, with their SVG markup.
pub fn figure_views(figs: &[FigureSpec], svgs: &[String]) -> Vec<FigureView> {
    figs.iter()
        .zip(svgs)
        .enumerate()
        .map(|(i, (f, svg))| FigureView {
            number: i + 1,
            title: f.title.clone(),
            caption: f.caption.clone(),
            png: format!("plots/{}.png", f.stem),
            svg_path: format!("plots/{}.svg", f.stem),
            pdf: format!("plots/{}.pdf", f.stem),
            svg: svg.clone(),
            anchor: format!("fig-{}", f.stem),
        })
        .collect()
}
