//! The figures of a report: what each chart shows, built from the stored data of a run (no
//! analysis), with a filename stem, a title and a caption. One builder per chart, in the
//! module of the same name as the chart's file in `crate::plot`.

pub mod accuracy;
pub mod arch_axis;
pub mod critical;
pub mod critical_arches;
pub mod domains;
pub mod lambda_map;
pub mod load_factor;
pub mod mechanisms;
pub mod regime_map;
pub mod solution;
pub mod state;
pub mod uncertainty;

pub use accuracy::{AccuracyRow, accuracy_rows, orders, quantity_label, quantity_rank};
pub use mechanisms::{flow_rule_text, mechanisms_stem};

use super::data::RunData;
use super::format::given;
use crate::plot::accuracy::AccuracyChart;
use crate::plot::critical::CriticalChart;
use crate::plot::domains::DomainsChart;
use crate::plot::lambda_map::LambdaMap;
use crate::plot::lines::LinesChart;
use crate::plot::mechanisms::MechanismPanels;
use crate::plot::regime_map::{RegimeMap, RegimeMapPanels};
use crate::plot::state::StateDrawing;
use crate::plot::{self, Format};

/// A chart with its data.
#[derive(Debug, Clone)]
pub enum Chart {
    /// Figure 1.
    RegimeMap(RegimeMap),
    /// Figure 1 for every arch of an arch axis, side by side.
    RegimeMapPanels(RegimeMapPanels),
    /// Figure 2.
    Domains(DomainsChart),
    /// Figure 3.
    State(StateDrawing),
    /// Figure 4.
    Critical(CriticalChart),
    /// Figure 5.
    Accuracy(AccuracyChart),
    /// Mechanisms at a bifurcation, side by side.
    Mechanisms(MechanismPanels),
    /// Curves against a parameter, points coloured by mechanism (load factors).
    Lines(LinesChart),
    /// The collapse load factor as a colour over (μ, K), with the mechanisms' regions.
    LambdaMap(LambdaMap),
    /// Samples over (μ, K) with the collapse curve.
    SampleMap(crate::plot::uncertainty::SampleMap),
    /// Bars with intervals.
    Bars(crate::plot::uncertainty::BarsChart),
    /// Curves with bands.
    Curves(crate::plot::uncertainty::CurvesChart),
}

/// A figure of the report.
#[derive(Debug, Clone)]
pub struct FigureSpec {
    /// File stem in plots/ (filename-safe, unique).
    pub stem: String,
    /// Heading.
    pub title: String,
    /// Caption: what is shown and how to read it.
    pub caption: String,
    /// The chart.
    pub chart: Chart,
}

impl FigureSpec {
    /// The file bytes in a format.
    pub fn render(&self, format: Format) -> Result<Vec<u8>, plot::PlotError> {
        match &self.chart {
            Chart::RegimeMap(c) => plot::render(c, format),
            Chart::RegimeMapPanels(c) => plot::render(c, format),
            Chart::Domains(c) => plot::render(c, format),
            Chart::State(c) => plot::render(c, format),
            Chart::Critical(c) => plot::render(c, format),
            Chart::Accuracy(c) => plot::render(c, format),
            Chart::Mechanisms(c) => plot::render(c, format),
            Chart::Lines(c) => plot::render(c, format),
            Chart::LambdaMap(c) => plot::render(c, format),
            Chart::SampleMap(c) => plot::render(c, format),
            Chart::Bars(c) => plot::render(c, format),
            Chart::Curves(c) => plot::render(c, format),
        }
    }
}

/// A filename-safe form of a name.
pub fn safe(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

pub(super) fn mu_text(mu: f64) -> String {
    if mu.is_infinite() {
        "∞".into()
    } else {
        given(mu)
    }
}

/// The load case a figure is drawn for: the suffix of its file stem and of its title (both
/// empty when the study has one load case).
#[derive(Debug, Clone)]
pub struct LoadCaseFigure<'a> {
    /// The load case's name.
    pub name: &'a str,
    /// Suffix of the file stem: `-NAME`, or empty.
    pub stem_suffix: String,
    /// Suffix of the title: ` (load case NAME)`, or empty.
    pub title_suffix: String,
}

/// The load cases of a run as its figures name them, in manifest order.
pub fn load_case_figures(data: &RunData) -> Vec<LoadCaseFigure<'_>> {
    let multi = data.manifest.load_cases.len() > 1;
    (data.manifest.load_cases.iter())
        .map(|lc| LoadCaseFigure {
            name: &lc.name,
            stem_suffix: if multi {
                format!("-{}", safe(&lc.name))
            } else {
                String::new()
            },
            title_suffix: if multi {
                format!(" (load case {})", lc.name)
            } else {
                String::new()
            },
        })
        .collect()
}

/// All figures of a run, in report order.
pub fn build(data: &RunData) -> Vec<FigureSpec> {
    build_groups(data).iter().flat_map(|g| g()).collect()
}

/// Builds a group of figures of a run.
pub type FigureGroup<'a> = Box<dyn Fn() -> Vec<FigureSpec> + Send + Sync + 'a>;

/// The figures of [`build`] as groups in order, each built on its own: a million-case regime
/// map takes a while to build, and the other figures can be drawn meanwhile.
pub fn build_groups(data: &RunData) -> Vec<FigureGroup<'_>> {
    let mut out: Vec<FigureGroup<'_>> = Vec::new();
    for lc in load_case_figures(data) {
        if data.manifest.sampling.is_some() {
            out.push(Box::new(move || uncertainty::figures(data, &lc)));
            continue;
        }
        let lc = std::sync::Arc::new(lc);
        let group = |f: fn(&RunData, &LoadCaseFigure<'_>) -> Vec<FigureSpec>| -> FigureGroup<'_> {
            let lc = std::sync::Arc::clone(&lc);
            Box::new(move || f(data, &lc))
        };
        out.push(group(|d, lc| {
            regime_map::figure(d, lc).into_iter().collect()
        }));
        out.push(group(arch_axis::figures));
        out.push(group(|d, lc| critical::figure(d, lc).into_iter().collect()));
        out.push(group(|d, lc| {
            critical_arches::figure(d, lc).into_iter().collect()
        }));
        out.push(group(load_factor::figures));
        out.push(group(lambda_map::figures));
    }
    for s in &data.states {
        // Fig. 2 exists for the symmetric closed forms only (its curves are stored then).
        let fig2 = crate::figdata::domains_figure(&s.state_id);
        if s.source == "scene" && data.curves.iter().any(|c| c.figure == fig2) {
            out.push(Box::new(move || vec![domains::figure(data, s)]));
        }
    }
    for s in &data.states {
        out.push(Box::new(move || {
            let mut figs = vec![state::figure(data, s)];
            figs.extend(mechanisms::figure(data, s));
            figs
        }));
    }
    out.push(Box::new(|| accuracy::figure(data).into_iter().collect()));
    out
}

/// True when every case uses the manifest's arch (no arch axis: half-angle, eccentricity,
/// joints or voussoirs).
pub fn single_model_of(data: &RunData) -> bool {
    single_model(data)
}

pub(super) fn single_model(data: &RunData) -> bool {
    !(data.manifest.grid.iter())
        .any(|a| crate::manifest::AxisName::from_key(&a.name).is_some_and(|n| n.is_arch()))
}
