//! The view model of both reports: every number already formatted, so the templates only
//! lay out text. Built from the stored data of a run and the rendered figures, one table at
//! a time (see [`super::tables`]).

use super::charts::FigureSpec;
use super::data::RunData;
use super::tables::{
    accuracy, boundaries, convergence, figures, key_results, mechanisms, notes, provenance, study,
    timing, values,
};
use serde::Serialize;

pub use super::tables::Item;
pub use super::tables::accuracy::ErrorRow;
pub use super::tables::boundaries::{BoundaryGroup, CollapsePoint};
pub use super::tables::convergence::{ConvergenceRow, ConvergenceTable};
pub use super::tables::figures::FigureView;
pub use super::tables::key_results::KeyResult;
pub use super::tables::mechanisms::{MechanismSection, MechanismTableRow};
pub use super::tables::study::AxisRow;
pub use super::tables::timing::TimingRow;

/// Everything both templates show.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ReportView {
    /// Title.
    pub title: String,
    /// Description (may be empty).
    pub description: String,
    /// Study name.
    pub name: String,
    /// The arch and the model.
    pub model: Vec<Item>,
    /// Grid axes.
    pub grid: Vec<AxisRow>,
    /// Load cases, as `name (kind)`.
    pub load_cases: Vec<String>,
    /// Cases and their outcomes.
    pub cases: Vec<Item>,
    /// True for the paper's case.
    pub paper_case: bool,
    /// True for a sampling study (uncertain parameters).
    pub sampling: bool,
    /// Key results.
    pub key_results: Vec<KeyResult>,
    /// Why the key results table is empty, when it is.
    pub key_results_note: String,
    /// What a reader would otherwise take for a defect: cases where no requested μ stands,
    /// unbounded load factors.
    pub reading_notes: Vec<String>,
    /// Figures.
    pub figures: Vec<FigureView>,
    /// True when the run located a boundary (the section is left out otherwise).
    pub has_boundaries: bool,
    /// Boundary points grouped.
    pub boundary_groups: Vec<BoundaryGroup>,
    /// Condensed collapse curve.
    pub collapse_points: Vec<CollapsePoint>,
    /// Note on the condensation.
    pub collapse_note: String,
    /// Solve-time statistics.
    pub timing: Vec<TimingRow>,
    /// Accuracy against the continuum.
    pub errors: Vec<ErrorRow>,
    /// Per quantity, when each voussoir count is one case: value, error and time per model.
    pub convergence: Vec<ConvergenceTable>,
    /// Values against the axes the study varies (bifurcations by arch, the values behind
    /// the error rows).
    pub value_tables: Vec<values::ValueTable>,
    /// Collapse mechanisms per bifurcation.
    pub mechanisms: Vec<MechanismSection>,
    /// Reproducibility facts.
    pub reproducibility: Vec<Item>,
    /// Stage timings.
    pub stages: Vec<Item>,
    /// Files of the run directory and what they hold.
    pub files: Vec<Item>,
    /// Every table above as CSV and LaTeX in tables/.
    pub tables: Vec<super::tables::export::TableFiles>,
}

/// Builds the view model.
pub fn build(data: &RunData, figs: &[FigureSpec], svgs: &[String]) -> ReportView {
    let m = &data.manifest;
    let (key_results, note) = key_results::key_results(data);
    let figures = figures::figure_views(figs, svgs);
    let boundaries = boundaries::boundary_tables(data);
    let mechanisms = mechanisms::mechanism_sections(data, &figures);
    ReportView {
        title: m
            .title
            .clone()
            .unwrap_or_else(|| format!("Study {}", m.name)),
        description: m.description.clone().unwrap_or_default().trim().to_string(),
        name: m.name.clone(),
        model: study::model(m),
        grid: study::grid(m),
        load_cases: study::load_cases(m),
        cases: study::cases(data),
        paper_case: m.is_paper_case(),
        sampling: m.sampling.is_some(),
        key_results,
        key_results_note: note,
        reading_notes: notes::notes(data),
        figures,
        has_boundaries: !boundaries.groups.is_empty(),
        boundary_groups: boundaries.groups,
        collapse_points: boundaries.collapse_points,
        collapse_note: boundaries.collapse_note,
        timing: timing::timing(data),
        errors: accuracy::errors(data),
        convergence: convergence::convergence(data),
        value_tables: values::value_tables(data),
        mechanisms,
        reproducibility: provenance::reproducibility(data),
        stages: provenance::stages(data),
        files: provenance::files(data),
        tables: Vec::new(),
    }
}
