//! The view model of both reports: every number already formatted, so the templates only
//! lay out text. Built from the stored data of a run and the rendered figures.

use super::charts::{self as figures, FigureSpec};
use super::data::RunData;
use super::format::{self, diff, given, micros, millis, num, value};
use super::paper::{self, Printed};
use crate::store::BoundaryRow;
use serde::Serialize;
use std::collections::BTreeMap;

/// A label and a value.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Item {
    /// Label.
    pub label: String,
    /// Value (formatted).
    pub value: String,
}

fn item(label: impl Into<String>, value: impl Into<String>) -> Item {
    Item {
        label: label.into(),
        value: value.into(),
    }
}

/// A grid axis as described in the report.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct AxisRow {
    /// Parameter.
    pub name: String,
    /// Number of values.
    pub count: String,
    /// First value.
    pub first: String,
    /// Last value.
    pub last: String,
}

/// A row of the key-results table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct KeyResult {
    /// What the value is.
    pub quantity: String,
    /// The value as stored, formatted.
    pub value: String,
    /// The paper's printed value, or `—`.
    pub paper: String,
    /// value − paper, or `—`.
    pub difference: String,
    /// Where the value is stored: file, row and column.
    pub source: String,
}

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
    /// The SVG markup, inlined in the HTML report.
    pub svg: String,
    /// Anchor id.
    pub anchor: String,
}

/// A group of boundary points (same regimes on both sides, same search axis).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct BoundaryGroup {
    /// `low → high`.
    pub regimes: String,
    /// `K` or `μ`.
    pub axis: String,
    /// `yes` if on the collapse curve.
    pub collapse: String,
    /// Mechanism or `—`.
    pub mechanism: String,
    /// Number of points.
    pub points: String,
    /// μ range.
    pub mu_range: String,
    /// K range.
    pub k_range: String,
}

/// A point of the collapse curve in the condensed table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CollapsePoint {
    /// μ.
    pub mu: String,
    /// K.
    pub k: String,
    /// t/R_c.
    pub t_over_r: String,
    /// Mechanism.
    pub mechanism: String,
    /// H/W_half.
    pub thrust: String,
    /// Hinges.
    pub hinges: String,
    /// Sliding joints.
    pub sliding: String,
}

/// Solve-time statistics of a group of cases.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TimingRow {
    /// Which cases (model and find).
    pub group: String,
    /// Number of cases.
    pub cases: String,
    /// Median.
    pub median: String,
    /// 90th percentile.
    pub p90: String,
    /// Largest.
    pub max: String,
    /// Sum of all solve times (CPU time spent in analyses).
    pub total: String,
}

/// A row of the accuracy table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ErrorRow {
    /// Quantity.
    pub quantity: String,
    /// Voussoir count.
    pub voussoirs: String,
    /// Cases compared.
    pub cases: String,
    /// Largest absolute error.
    pub max_abs_error: String,
    /// Largest relative error.
    pub max_rel_error: String,
    /// Median solve time.
    pub median_time: String,
    /// Median solve time of the continuum.
    pub continuum_time: String,
}

/// One model of a convergence table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ConvergenceRow {
    /// Voussoir count, or `continuum`.
    pub voussoirs: String,
    /// The value.
    pub value: String,
    /// |value − continuum value| (`0` for the continuum).
    pub abs_error: String,
    /// Solve time of the case.
    pub time: String,
}

/// The convergence of one quantity to its continuum value.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ConvergenceTable {
    /// Quantity, as in the paper.
    pub quantity: String,
    /// The results column it comes from.
    pub column: String,
    /// One row per model, by N, then the continuum.
    pub rows: Vec<ConvergenceRow>,
    /// The observed order of convergence and the N range of its fit, or why there is none.
    pub order: String,
    /// Whether the error falls monotonically with N, and where it does not.
    pub monotone: String,
}

/// One mechanism at a bifurcation, as a table row.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct MechanismTableRow {
    /// μ of the bifurcation.
    pub mu: String,
    /// K of the bifurcation.
    pub k: String,
    /// Kind of the mechanism.
    pub mechanism: String,
    /// Flow rule at the sliding joints.
    pub flow_rule: String,
    /// dL^(a).
    pub work_loads: String,
    /// dL^(r,n).
    pub work_normal: String,
    /// dL^(r,t).
    pub work_friction: String,
    /// Relative residual of the work equation.
    pub work_residual: String,
    /// Dilatancy at each sliding joint, as `θ: value`.
    pub dilatancy: String,
}

/// The mechanisms at one bifurcation.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct MechanismSection {
    /// Heading.
    pub title: String,
    /// `Figure N`, or empty when the figure is missing.
    pub figure: String,
    /// Anchor of the figure.
    pub anchor: String,
    /// One row per mechanism and flow rule.
    pub rows: Vec<MechanismTableRow>,
}

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
    /// Key results.
    pub key_results: Vec<KeyResult>,
    /// Why the key results table is empty, when it is.
    pub key_results_note: String,
    /// Figures.
    pub figures: Vec<FigureView>,
    /// True when boundaries.parquet was found.
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
    /// Collapse mechanisms per bifurcation.
    pub mechanisms: Vec<MechanismSection>,
    /// Reproducibility facts.
    pub reproducibility: Vec<Item>,
    /// Stage timings.
    pub stages: Vec<Item>,
    /// Files of the run directory and what they hold.
    pub files: Vec<Item>,
}

fn axis_name(n: &str) -> &str {
    match n {
        "k" => "K = R/r",
        "t_over_r" => "t/R_c",
        "mu" => "μ",
        "half_angle_deg" => "half-angle α (°)",
        "voussoirs" => "voussoirs N",
        other => other,
    }
}

fn find_text(f: &str) -> &'static str {
    match f {
        "state" => "state: the regime and the domains Hʳ, Hˢ at every grid point",
        "thickness" => "thickness: the collapse thickness K_c at every grid point",
        "friction" => "friction: the critical friction μ_c at every grid point",
        "thrust" => "thrust: the minimum and maximum admissible thrusts at every grid point",
        "thresholds" => "thresholds: the critical values of the arch under self-weight",
        "load_factor" => {
            "load_factor: the largest load factor λ of the live load at every grid point"
        }
        _ => "unknown",
    }
}

/// The find of the study, or of each load case when they differ.
fn finds_text(m: &super::data::ManifestView) -> String {
    let finds: Vec<(&str, &str)> = m
        .load_cases
        .iter()
        .map(|l| (l.name.as_str(), m.find_of(&l.name)))
        .collect();
    match finds.first() {
        Some(&(_, f)) if finds.iter().all(|&(_, g)| g == f) => find_text(f).to_string(),
        None => find_text(&m.find).to_string(),
        Some(_) => finds
            .iter()
            .map(|(lc, f)| format!("load case {lc}: {}", find_text(f)))
            .collect::<Vec<_>>()
            .join("; "),
    }
}

/// Builds the view model.
pub fn build(data: &RunData, figs: &[FigureSpec], svgs: &[String]) -> ReportView {
    let m = &data.manifest;
    let info = &data.info;
    let model = vec![
        item(
            "shape",
            format!(
                "{}{}, half-embrace angle α = {}°",
                m.arch.shape,
                m.arch
                    .eccentricity
                    .map_or(String::new(), |e| format!(" (eccentricity {e})")),
                given(m.arch.half_angle_deg)
            ),
        ),
        item(
            "joints",
            format!(
                "{}, {}",
                m.arch.joints,
                m.arch.voussoir_count().map_or(
                    "continuum (every section a potential joint)".into(),
                    |n| format!("{n} voussoirs")
                )
            ),
        ),
        item(
            "weight model",
            match m.arch.weight.as_str() {
                "annular" => {
                    "annular: true weight of each annular sector at its centroid".to_string()
                }
                "centreline" => {
                    "centreline: weight per unit length of the centreline, on the centreline"
                        .to_string()
                }
                other => other.to_string(),
            },
        ),
        item(
            "material",
            "rigid voussoirs, no tension, infinite compressive strength, Coulomb friction μ = tan φ",
        ),
        item("find", finds_text(m)),
        item("boundary tolerance", format!("{:e}", m.boundary_tolerance)),
    ];
    let grid = m
        .grid
        .iter()
        .map(|a| {
            let g = |v: Option<&Option<f64>>| {
                v.map_or("—".into(), |x| given(x.unwrap_or(f64::INFINITY)))
            };
            AxisRow {
                name: axis_name(&a.name).to_string(),
                count: a.values.len().to_string(),
                first: g(a.values.first()),
                last: g(a.values.last()),
            }
        })
        .collect();
    // A load case whose find finds K or μ itself has one case per value of the other axes.
    let load_cases = m
        .load_cases
        .iter()
        .map(|l| {
            let found: &[&str] = match m.find_of(&l.name) {
                "thickness" => &["k", "t_over_r"],
                "friction" => &["mu"],
                "thresholds" => &["k", "t_over_r", "mu"],
                _ => &[],
            };
            let skipped: Vec<&str> = m
                .grid
                .iter()
                .filter(|a| found.contains(&a.name.as_str()))
                .map(|a| axis_name(&a.name))
                .collect();
            let mut d = format!("{} ({}", l.name, l.kind.replace('_', "-"));
            if !skipped.is_empty() {
                d.push_str(&format!(
                    "; its find, {}, finds {} itself",
                    m.find_of(&l.name),
                    skipped.join(" and ")
                ));
            }
            d.push(')');
            d
        })
        .collect();
    let mut by_outcome: BTreeMap<String, usize> = BTreeMap::new();
    for r in &data.results {
        let key = if &*r.status != "ok" {
            "failed".to_string()
        } else if let Some(g) = &r.regime {
            format!("regime {g}")
        } else if let Some(o) = &r.outcome {
            o.replace('_', " ")
        } else {
            "ok".to_string()
        };
        *by_outcome.entry(key).or_default() += 1;
    }
    let mut cases = vec![
        item("cases", info.cases.total.to_string()),
        item("failed", info.cases.error.to_string()),
    ];
    cases.extend(by_outcome.into_iter().map(|(k, v)| item(k, v.to_string())));
    let (key_results, note) = key_results(data);
    let figures: Vec<FigureView> = figs
        .iter()
        .zip(svgs)
        .enumerate()
        .map(|(i, (f, svg))| FigureView {
            number: i + 1,
            title: f.title.clone(),
            caption: f.caption.clone(),
            png: format!("plots/{}.png", f.stem),
            svg_path: format!("plots/{}.svg", f.stem),
            svg: svg.clone(),
            anchor: format!("fig-{}", f.stem),
        })
        .collect();
    let (groups, points, collapse_note) = boundary_tables(data);
    let mechanisms = mechanism_sections(data, &figures);
    ReportView {
        title: m
            .title
            .clone()
            .unwrap_or_else(|| format!("Study {}", m.name)),
        description: m.description.clone().unwrap_or_default().trim().to_string(),
        name: m.name.clone(),
        model,
        grid,
        load_cases,
        cases,
        paper_case: m.is_paper_case(),
        key_results,
        key_results_note: note,
        figures,
        has_boundaries: data.boundaries.is_some(),
        boundary_groups: groups,
        collapse_points: points,
        collapse_note,
        timing: timing(data),
        errors: errors(data),
        convergence: convergence(data),
        mechanisms,
        reproducibility: reproducibility(data),
        stages: stages(data),
        files: files(data),
    }
}

fn compare(v: f64, p: Option<Printed>) -> (String, String) {
    match p {
        Some(p) => (p.text.to_string(), diff(v - p.value)),
        None => ("—".into(), "—".into()),
    }
}

/// The key-results rows: thresholds from the collapse curve and the bifurcations, or the
/// critical values of a critical find. Every value is one stored cell, named in `source`.
fn key_results(data: &RunData) -> (Vec<KeyResult>, String) {
    let paper = data.manifest.is_paper_case();
    let multi = data.manifest.load_cases.len() > 1;
    let mut out = Vec::new();
    let push = |out: &mut Vec<KeyResult>, q: String, v: f64, p: Option<Printed>, src: String| {
        let (paper_text, d) = compare(v, if paper { p } else { None });
        out.push(KeyResult {
            quantity: q,
            value: value(v),
            paper: paper_text,
            difference: d,
            source: src,
        });
    };
    for lc in &data.manifest.load_cases {
        let on = if multi {
            format!(" ({})", lc.name)
        } else {
            String::new()
        };
        let rows: Vec<(usize, &BoundaryRow)> = data
            .boundaries
            .iter()
            .flatten()
            .enumerate()
            .filter(|(_, b)| b.load_case == lc.name && b.on_collapse_curve)
            .collect();
        // Rotational collapse at the largest μ: K_c for friction large enough.
        if let Some((i, b)) = rows
            .iter()
            .filter(|(_, b)| b.mechanism.as_deref() == Some("rotational"))
            .max_by(|a, b| a.1.mu.total_cmp(&b.1.mu))
        {
            let src = |c: &str| format!("boundaries.parquet row {i} {c}");
            push(
                &mut out,
                format!("K_c, rotational collapse (μ = {}){on}", given(b.mu)),
                b.k,
                Some(paper::K_C),
                src("k"),
            );
            push(
                &mut out,
                format!("t/R_c at K_c{on}"),
                b.t_over_r,
                None,
                src("t_over_r"),
            );
            if let Some(h) = b.thrust_over_half_weight {
                push(
                    &mut out,
                    format!("H/W_half at K_c{on}"),
                    h,
                    None,
                    src("thrust_over_half_weight"),
                );
            }
        }
        // Sliding collapse at the largest K: μ_min.
        if let Some((i, b)) = rows
            .iter()
            .filter(|(_, b)| b.mechanism.as_deref() == Some("sliding"))
            .max_by(|a, b| a.1.k.total_cmp(&b.1.k))
        {
            let src = format!("boundaries.parquet row {i} mu");
            push(
                &mut out,
                format!("μ_min, sliding collapse (K = {}){on}", given(b.k)),
                b.mu,
                Some(paper::MU_MIN),
                src,
            );
        }
        for (i, b) in data
            .bifurcations
            .iter()
            .flatten()
            .enumerate()
            .filter(|(_, b)| b.load_case == lc.name)
        {
            let name = format!("{}/{}", b.mechanism_a, b.mechanism_b);
            let printed = paper::bifurcation(&b.mechanism_a, &b.mechanism_b);
            let src = |c: &str| format!("bifurcations.parquet row {i} {c}");
            push(
                &mut out,
                format!("μ at the {name} bifurcation{on}"),
                b.mu,
                printed.map(|p| p.0),
                src("mu"),
            );
            push(
                &mut out,
                format!("K at the {name} bifurcation{on}"),
                b.k,
                printed.map(|p| p.1),
                src("k"),
            );
            push(
                &mut out,
                format!("t/R_c at the {name} bifurcation{on}"),
                b.t_over_r,
                None,
                src("t_over_r"),
            );
            if let Some(h) = b.thrust_over_half_weight {
                push(
                    &mut out,
                    format!("H/W_half at the {name} bifurcation{on}"),
                    h,
                    None,
                    src("thrust_over_half_weight"),
                );
            }
            let sliding = &b.joints.sliding_angles_deg;
            if !sliding.is_empty() {
                let text = format::joints(sliding, &b.joints.sliding_senses);
                let is_min = printed.is_some_and(|p| p.0.text == paper::MU_MIN.text);
                out.push(KeyResult {
                    quantity: format!("sliding joints at the {name} bifurcation{on}"),
                    value: text,
                    paper: if paper && is_min {
                        paper::SLIDING_JOINTS_DEG.into()
                    } else {
                        "—".into()
                    },
                    difference: "—".into(),
                    source: src("sliding_angles_deg"),
                });
            }
            if !b.joints.hinge_angles_deg.is_empty() {
                out.push(KeyResult {
                    quantity: format!("hinges at the {name} bifurcation{on}"),
                    value: format::joints(&b.joints.hinge_angles_deg, &b.joints.hinge_faces),
                    paper: "—".into(),
                    difference: "—".into(),
                    source: src("hinge_angles_deg"),
                });
            }
        }
    }
    // Critical finds: the critical value of each case (about two dozen listed at most).
    let col_of = |r: &crate::store::ResultRow| match &*r.find {
        "thickness" => Some("k_crit"),
        "friction" => Some("mu_crit"),
        _ => None,
    };
    let found: Vec<(usize, &crate::store::ResultRow, &str)> = data
        .results
        .iter()
        .enumerate()
        .filter(|(_, r)| r.outcome.as_deref() == Some("found"))
        .filter_map(|(i, r)| Some((i, r, col_of(r)?)))
        .collect();
    let step = if found.len() <= 30 {
        1
    } else {
        found.len().div_ceil(24)
    };
    for &(i, r, col) in found.iter().step_by(step) {
        let (v, label) = if col == "k_crit" {
            (
                r.k_crit,
                format!("K_c at μ = {}", r.mu.map_or("—".into(), given)),
            )
        } else {
            (
                r.mu_crit,
                format!("μ_c at K = {}", r.k.map_or("—".into(), given)),
            )
        };
        let Some(v) = v else { continue };
        let model = r.voussoirs.map_or(String::new(), |n| format!(", N = {n}"));
        let printed = match (col, paper, r.mu) {
            ("k_crit", true, Some(mu)) if mu.is_infinite() => Some(paper::K_C),
            _ => None,
        };
        push(
            &mut out,
            format!("{label}{model}"),
            v,
            printed,
            format!("results.parquet row {i} {col}"),
        );
    }
    // The continuum's critical values of a thresholds or load-factor find (a study over the
    // voussoir count measures its models against these); the paper's printed values beside
    // the thresholds of its geometry.
    let paper_geometry = data.manifest.is_paper_geometry();
    for (i, r) in data.results.iter().enumerate().filter(|(_, r)| {
        r.voussoirs.is_none()
            && &*r.status == "ok"
            && matches!(&*r.find, "thresholds" | "load_factor")
    }) {
        let on = if multi {
            format!(" ({})", r.load_case)
        } else {
            String::new()
        };
        let cells: Vec<(String, Option<f64>, Option<Printed>, &str)> = if &*r.find == "thresholds" {
            vec![
                (
                    "K_c at μ = ∞".into(),
                    r.k_c_rotational,
                    Some(paper::K_C),
                    "k_c_rotational",
                ),
                (
                    "μ of the rotational/mixed bifurcation".into(),
                    r.mu_rotational_mixed,
                    Some(paper::MU_ROTATIONAL_MIXED),
                    "mu_rotational_mixed",
                ),
                (
                    "μ_min, sliding threshold".into(),
                    r.mu_min,
                    Some(paper::MU_MIN),
                    "mu_min",
                ),
                (
                    "K of the mixed/sliding bifurcation".into(),
                    r.k_mixed_sliding,
                    Some(paper::K_MIXED_SLIDING),
                    "k_mixed_sliding",
                ),
            ]
        } else {
            let at = match (r.k, r.t_over_r, r.mu) {
                (Some(k), Some(t), Some(mu)) => format!(
                    " at K = {} (t/R_c = {}), μ = {}",
                    format::short(k),
                    format::short(t),
                    given(mu)
                ),
                _ => String::new(),
            };
            vec![(
                format!("load factor λ{at}"),
                r.load_factor,
                None,
                "load_factor",
            )]
        };
        for (q, v, p, col) in cells {
            let Some(v) = v else { continue };
            let (paper_text, d) = compare(v, p.filter(|_| paper_geometry));
            out.push(KeyResult {
                quantity: format!("{q}, continuum{on}"),
                value: value(v),
                paper: paper_text,
                difference: d,
                source: format!("results.parquet row {i} {col}"),
            });
        }
        if out.len() > 40 {
            break;
        }
    }
    let note = if out.is_empty() {
        if data.boundaries.is_none() {
            "No boundaries were located in this run (boundaries.parquet is absent), so there are no thresholds to report.".into()
        } else {
            "The run located no collapse curve or bifurcation within the grid.".into()
        }
    } else {
        String::new()
    };
    (out, note)
}

/// Boundary points grouped, and the collapse curve condensed to about 24 points.
fn boundary_tables(data: &RunData) -> (Vec<BoundaryGroup>, Vec<CollapsePoint>, String) {
    let Some(rows) = &data.boundaries else {
        return (Vec::new(), Vec::new(), String::new());
    };
    let mut groups: BTreeMap<(bool, String, String, String, String), Vec<&BoundaryRow>> =
        BTreeMap::new();
    for b in rows {
        groups
            .entry((
                !b.on_collapse_curve,
                b.mechanism.clone().unwrap_or_default(),
                b.regime_low.clone(),
                b.regime_high.clone(),
                b.axis.clone(),
            ))
            .or_default()
            .push(b);
    }
    let range = |v: Vec<f64>| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if (hi - lo).abs() <= 1e-12 * (1.0 + hi.abs()) {
            value(lo)
        } else {
            format!("{} – {}", format::short(lo), format::short(hi))
        }
    };
    let groups = groups
        .into_iter()
        .map(|((off, mech, lo, hi, axis), v)| BoundaryGroup {
            regimes: format!("{lo} → {hi}"),
            axis: if axis == "k" { "K".into() } else { "μ".into() },
            collapse: if off { "no".into() } else { "yes".into() },
            mechanism: if mech.is_empty() { "—".into() } else { mech },
            points: v.len().to_string(),
            mu_range: range(v.iter().map(|b| b.mu).collect()),
            k_range: range(v.iter().map(|b| b.k).collect()),
        })
        .collect();
    let mut curve: Vec<&BoundaryRow> = rows.iter().filter(|b| b.on_collapse_curve).collect();
    let (mu0, mu1, k0, k1) = curve.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), r| (a.min(r.mu), b.max(r.mu), c.min(r.k), d.max(r.k)),
    );
    let key = |r: &BoundaryRow| r.k / (k1 - k0).max(1e-12) - r.mu / (mu1 - mu0).max(1e-12);
    curve.sort_by(|a, b| key(a).total_cmp(&key(b)));
    let n = curve.len();
    let keep: Vec<usize> = if n <= 30 {
        (0..n).collect()
    } else {
        let mut k: Vec<usize> = (0..24).map(|i| i * (n - 1) / 23).collect();
        // Segment ends (mechanism changes) are kept too.
        for i in 1..n {
            if curve[i].mechanism != curve[i - 1].mechanism {
                k.push(i - 1);
                k.push(i);
            }
        }
        k.sort_unstable();
        k.dedup();
        k
    };
    let points = keep
        .iter()
        .map(|&i| {
            let b = curve[i];
            CollapsePoint {
                mu: value(b.mu),
                k: value(b.k),
                t_over_r: value(b.t_over_r),
                mechanism: b.mechanism.clone().unwrap_or_else(|| "—".into()),
                thrust: num(b.thrust_over_half_weight, format::VALUE_DECIMALS),
                hinges: format::joints(&b.joints.hinge_angles_deg, &b.joints.hinge_faces),
                sliding: format::joints(&b.joints.sliding_angles_deg, &b.joints.sliding_senses),
            }
        })
        .collect();
    let note = if keep.len() < n {
        format!(
            "{} of the {n} collapse-curve points, in order along the curve (every row is in boundaries.parquet).",
            keep.len()
        )
    } else {
        format!("All {n} collapse-curve points, in order along the curve.")
    };
    (groups, points, note)
}

fn timing(data: &RunData) -> Vec<TimingRow> {
    let mut groups: BTreeMap<(Option<u32>, std::sync::Arc<str>), Vec<f64>> = BTreeMap::new();
    for r in data.results.iter().filter(|r| &*r.status == "ok") {
        groups
            .entry((r.voussoirs, r.find.clone()))
            .or_default()
            .push(r.solve_time_us);
    }
    groups
        .into_iter()
        .map(|((n, find), mut t)| {
            t.sort_by(f64::total_cmp);
            TimingRow {
                group: format!(
                    "{}, {find}",
                    n.map_or("continuum".to_string(), |n| format!("N = {n}"))
                ),
                cases: t.len().to_string(),
                median: micros(format::quantile(&t, 0.5)),
                p90: micros(format::quantile(&t, 0.9)),
                max: micros(t.last().copied().unwrap_or(f64::NAN)),
                total: millis(t.iter().sum::<f64>() / 1e3),
            }
        })
        .collect()
}

fn errors(data: &RunData) -> Vec<ErrorRow> {
    figures::accuracy_rows(data)
        .into_iter()
        .map(|r| ErrorRow {
            quantity: figures::quantity_label(&r.quantity).to_string(),
            voussoirs: r.voussoirs.to_string(),
            cases: r.cases.to_string(),
            max_abs_error: format!("{:.3e}", r.max_abs_error),
            max_rel_error: format!("{:.3e}", r.max_rel_error),
            median_time: micros(r.median_time_us),
            continuum_time: micros(r.continuum_median_time_us),
        })
        .collect()
}

/// Works, dilatancies and residuals below this are rounding: shown as 0 (or `< 1e-9`), so
/// that the report does not depend on the last bits of the platform's arithmetic.
const WORK_ZERO: f64 = 1e-9;

fn work_text(v: f64) -> String {
    if v.abs() < WORK_ZERO {
        "0".into()
    } else {
        format!("{v:.6}")
    }
}

fn mechanism_sections(data: &RunData, figures: &[FigureView]) -> Vec<MechanismSection> {
    let mut out: Vec<MechanismSection> = Vec::new();
    for s in data.states.iter().filter(|s| s.source == "bifurcation") {
        let rows: Vec<MechanismTableRow> = data
            .mechanisms
            .iter()
            .filter(|m| m.state_id == s.state_id)
            .map(|m| MechanismTableRow {
                mu: format::value(m.mu),
                k: format::value(m.k),
                mechanism: m.mechanism.clone(),
                flow_rule: figures::flow_rule_text(&m.flow_rule).to_string(),
                work_loads: work_text(m.work_loads),
                work_normal: work_text(m.work_normal),
                work_friction: work_text(m.work_friction),
                work_residual: if m.work_residual < WORK_ZERO {
                    "< 1e-9".into()
                } else {
                    format!("{:.1e}", m.work_residual)
                },
                dilatancy: if m.sliding_angles_deg.is_empty() {
                    "no sliding joint".into()
                } else {
                    m.sliding_angles_deg
                        .iter()
                        .zip(&m.dilatancy)
                        .map(|(a, d)| format!("{a:.2}°: {}", work_text(*d)))
                        .collect::<Vec<_>>()
                        .join("; ")
                },
            })
            .collect();
        if rows.is_empty() {
            continue;
        }
        let stem = figures::mechanisms_stem(&s.state_id);
        let fig = figures.iter().find(|f| f.anchor == format!("fig-{stem}"));
        out.push(MechanismSection {
            title: format!(
                "{} bifurcation, μ = {}, K = {}",
                s.mechanism.clone().unwrap_or_default().replace('/', " / "),
                format::short(s.mu),
                format::short(s.k)
            ),
            figure: fig.map_or(String::new(), |f| format!("Figure {}", f.number)),
            anchor: format!("fig-{stem}"),
            rows,
        });
    }
    out
}

/// Convergence tables, when the study varies only the voussoir count (one case per N).
fn convergence(data: &RunData) -> Vec<ConvergenceTable> {
    let rows = figures::accuracy_rows(data);
    if rows.is_empty() || rows.iter().any(|r| r.cases != 1) {
        return Vec::new();
    }
    let orders = figures::orders(&rows);
    let mut by_q: BTreeMap<(usize, String), Vec<&figures::AccuracyRow>> = BTreeMap::new();
    for r in &rows {
        by_q.entry((figures::quantity_rank(&r.quantity), r.quantity.clone()))
            .or_default()
            .push(r);
    }
    by_q.into_iter()
        .map(|((_, q), mut rs)| {
            rs.sort_by_key(|r| r.voussoirs);
            let mut out: Vec<ConvergenceRow> = rs
                .iter()
                .map(|r| ConvergenceRow {
                    voussoirs: r.voussoirs.to_string(),
                    value: format::value(r.value),
                    abs_error: format!("{:.3e}", r.max_abs_error),
                    time: micros(r.median_time_us),
                })
                .collect();
            if let Some(last) = rs.last() {
                out.push(ConvergenceRow {
                    voussoirs: "continuum".into(),
                    value: format::value(last.continuum_value),
                    abs_error: "0".into(),
                    time: micros(last.continuum_median_time_us),
                });
            }
            let o = orders.get(&q).and_then(Option::as_ref);
            let order = o.map_or(
                "not available: fewer than three non-zero errors".to_string(),
                |o| {
                    format!(
                        "{:.2} (least-squares slope of log|error| against log N over the {} largest counts, N = {} to {})",
                        o.order, o.points, o.n_from, o.n_to
                    )
                },
            );
            let monotone = match o {
                Some(o) if !o.rises_at.is_empty() => format!(
                    "not monotone: the error grows from the previous count at N = {}",
                    o.rises_at
                        .iter()
                        .map(u32::to_string)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                Some(_) => "the error falls monotonically with N".into(),
                None => String::new(),
            };
            ConvergenceTable {
                quantity: figures::quantity_label(&q).to_string(),
                column: q,
                rows: out,
                order,
                monotone,
            }
        })
        .collect()
}

fn reproducibility(data: &RunData) -> Vec<Item> {
    let i = &data.info;
    vec![
        item("manifest", i.manifest_path.clone()),
        item("manifest SHA-256", i.manifest_sha256.clone()),
        item("archstudy version", i.archstudy_version.clone()),
        item(
            "archstudy commit",
            i.git_commit.clone().unwrap_or_else(|| "unknown".into()),
        ),
        item("rustc", i.rustc_version.clone()),
        item("command line", i.command_line.join(" ")),
        item("threads", i.threads.to_string()),
        item("date", i.started_at.clone()),
        item(
            "separable grid path",
            if i.separable {
                "yes".to_string()
            } else {
                "no".to_string()
            },
        ),
    ]
}

fn stages(data: &RunData) -> Vec<Item> {
    let s = &data.info.stages;
    vec![
        item("plan", millis(s.plan_ms)),
        item("engine", millis(s.engine_ms)),
        item("store", millis(s.store_ms)),
        item("boundaries", millis(s.boundaries_ms)),
        item("figures", millis(s.plots_ms)),
    ]
}

fn files(data: &RunData) -> Vec<Item> {
    let mut v = vec![item(
        "results.parquet",
        "one row per case: inputs, regime or critical value, mechanism, solve time",
    )];
    if data.boundaries.is_some() {
        v.push(item(
            "boundaries.parquet",
            "regime boundaries located along the grid lines",
        ));
    }
    if data.bifurcations.is_some() {
        v.push(item(
            "bifurcations.parquet",
            "points where two collapse mechanisms coexist",
        ));
    }
    v.push(item(
        "curves.parquet, states.parquet, reference.parquet",
        "figure data: curves from the statics, drawn states, continuum references",
    ));
    v.push(item(
        "run.json, manifest.yaml",
        "provenance: the resolved manifest, versions, timings; the manifest as given",
    ));
    v.push(item("plots/", "every figure as SVG and as PNG (300 dpi)"));
    v
}
