//! The key results: thresholds from the collapse curve and the bifurcations, or the
//! critical values of a critical find, each beside the paper's printed value when the study
//! is the paper's case. Every value is one stored cell, named in its source.

use crate::report::data::RunData;
use crate::report::format::{self, diff, given, position_deg, value};
use crate::report::paper::{self, Printed};
use crate::scene::Find;
use crate::store::{BoundaryRow, ResultRow};
use serde::Serialize;

mod load_factor;

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

/// At most this many points of a collapse curve listed when it has no rotational K_c or
/// sliding μ_min to list.
const COLLAPSE_POINTS: usize = 6;

fn compare(v: f64, p: Option<Printed>) -> (String, String) {
    match p {
        Some(p) => (p.text.to_string(), diff(v - p.value)),
        None => ("—".into(), "—".into()),
    }
}

/// The key-results rows: thresholds from the collapse curve and the bifurcations, or the
/// critical values of a critical find. Every value is one stored cell, named in `source`.
/// The second value says why the table is empty, when it is.
pub fn key_results(data: &RunData) -> (Vec<KeyResult>, String) {
    if data.manifest.sampling.is_some() {
        let rows = super::uncertainty::key_results(data);
        let note = if rows.is_empty() {
            "no sample of this run gave an answer".to_string()
        } else {
            String::new()
        };
        return (rows, note);
    }
    let multi = data.manifest.load_cases.len() > 1;
    let mut rows = Rows {
        out: Vec::new(),
        paper: data.manifest.is_paper_case(),
    };
    for lc in &data.manifest.load_cases {
        let on = if multi {
            format!(" ({})", lc.name)
        } else {
            String::new()
        };
        let curve: Vec<(usize, &BoundaryRow)> = data
            .boundaries
            .iter()
            .flatten()
            .enumerate()
            .filter(|(_, b)| b.load_case == lc.name && b.on_collapse_curve)
            .collect();
        if data.manifest.find_of(&lc.name) == "load_factor" {
            rows.load_factor_summary(data, &lc.name, &on);
            rows.load_factor_changes(data, &lc.name, &on);
            continue;
        }
        // The collapse-curve rows do not say which arch they belong to: with a half-angle or
        // voussoir axis only the bifurcations, which name their arch, are listed.
        if crate::report::charts::single_model_of(data) {
            let before = rows.out.len();
            rows.rotational_collapse(&curve, &on);
            rows.sliding_collapse(&curve, &on);
            if rows.out.len() == before {
                rows.collapse_points(&curve, &on);
            }
        }
        rows.bifurcations(data, &lc.name, &on);
    }
    // Each of these reads every row: a study without their finds (a million-case state map)
    // skips them.
    let finds: Vec<&str> = (data.manifest.load_cases.iter())
        .map(|l| data.manifest.find_of(&l.name))
        .collect();
    let asks = |any: &[Find]| finds.is_empty() || any.iter().any(|f| finds.contains(&f.as_str()));
    if asks(&[Find::Thickness, Find::Friction, Find::LoadFactor]) {
        rows.critical_values(data);
    }
    if asks(&[Find::Thrust]) {
        rows.thrust_ranges(data);
    }
    if asks(&[Find::Thresholds]) {
        rows.continuum_values(data, multi);
    }
    let out = rows.out;
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

/// The rows so far, and whether the study is the paper's case (whose printed values stand
/// beside the computed ones).
struct Rows {
    out: Vec<KeyResult>,
    paper: bool,
}

/// The rows a key-results list gives of many: every one up to 30, else evenly spaced through
/// the study, about two dozen.
fn listed<T>(rows: &[T]) -> std::iter::StepBy<std::slice::Iter<'_, T>> {
    let step = if rows.len() <= 30 {
        1
    } else {
        rows.len().div_ceil(24)
    };
    rows.iter().step_by(step)
}

impl Rows {
    /// A computed value, beside the paper's printed one for the paper's case.
    fn push(&mut self, q: String, v: f64, p: Option<Printed>, src: String) {
        let (paper_text, d) = compare(v, if self.paper { p } else { None });
        self.out.push(KeyResult {
            quantity: q,
            value: value(v),
            paper: paper_text,
            difference: d,
            source: src,
        });
    }

    /// Rotational collapse at the largest μ: K_c for friction large enough.
    fn rotational_collapse(&mut self, curve: &[(usize, &BoundaryRow)], on: &str) {
        let Some((i, b)) = curve
            .iter()
            .filter(|(_, b)| b.mechanism.as_deref() == Some("rotational"))
            .max_by(|a, b| a.1.mu.total_cmp(&b.1.mu))
        else {
            return;
        };
        let src = |c: &str| format!("boundaries.parquet row {i} {c}");
        self.push(
            format!("K_c, rotational collapse (μ = {}){on}", given(b.mu)),
            b.k,
            Some(paper::K_C),
            src("k"),
        );
        self.push(
            format!("t/R_c at K_c{on}"),
            b.t_over_r,
            None,
            src("t_over_r"),
        );
        if let Some(h) = b.thrust_over_half_weight {
            self.push(
                format!("H/W_half at K_c{on}"),
                h,
                None,
                src("thrust_over_half_weight"),
            );
        }
    }

    /// The located points of the collapse curve, up to [`COLLAPSE_POINTS`] spread along it,
    /// when neither a rotational K_c nor a sliding μ_min was listed: a sweep over μ at one K
    /// (or over K at one μ) reports the μ_c (or K_c) it located and its mechanism.
    fn collapse_points(&mut self, curve: &[(usize, &BoundaryRow)], on: &str) {
        let idx: Vec<f64> = (0..curve.len()).map(|i| i as f64).collect();
        for j in crate::report::charts::load_factor::spread(&idx, COLLAPSE_POINTS) {
            let (i, b) = curve[j as usize];
            let mech = b
                .mechanism
                .as_deref()
                .map_or(String::new(), |m| format!(", {m} collapse"));
            let (q, v, col) = if b.axis == "mu" {
                (format!("μ_c at K = {}{mech}{on}", given(b.k)), b.mu, "mu")
            } else {
                (format!("K_c at μ = {}{mech}{on}", given(b.mu)), b.k, "k")
            };
            self.push(q, v, None, format!("boundaries.parquet row {i} {col}"));
        }
    }

    /// Sliding collapse at the largest K: μ_min.
    fn sliding_collapse(&mut self, curve: &[(usize, &BoundaryRow)], on: &str) {
        if let Some((i, b)) = curve
            .iter()
            .filter(|(_, b)| b.mechanism.as_deref() == Some("sliding"))
            .max_by(|a, b| a.1.k.total_cmp(&b.1.k))
        {
            let src = format!("boundaries.parquet row {i} mu");
            self.push(
                format!("μ_min, sliding collapse (K = {}){on}", given(b.k)),
                b.mu,
                Some(paper::MU_MIN),
                src,
            );
        }
    }

    /// Each bifurcation of a load case: μ, K, t/R_c, thrust, sliding joints and hinges.
    fn bifurcations(&mut self, data: &RunData, lc: &str, on: &str) {
        for (i, b) in data
            .bifurcations
            .iter()
            .flatten()
            .enumerate()
            .filter(|(_, b)| b.load_case == lc)
        {
            let arch = data
                .bifurcation_groups
                .get(i)
                .map_or(String::new(), |g| group_text(data, g));
            let name = crate::figdata::bifurcation_name(&b.mechanism_a, &b.mechanism_b);
            let on = format!("{arch}{on}");
            let on = on.as_str();
            let printed = paper::bifurcation(&b.mechanism_a, &b.mechanism_b);
            let src = |c: &str| format!("bifurcations.parquet row {i} {c}");
            self.push(
                format!("μ at the {name} bifurcation{on}"),
                b.mu,
                printed.map(|p| p.0),
                src("mu"),
            );
            self.push(
                format!("K at the {name} bifurcation{on}"),
                b.k,
                printed.map(|p| p.1),
                src("k"),
            );
            self.push(
                format!("t/R_c at the {name} bifurcation{on}"),
                b.t_over_r,
                None,
                src("t_over_r"),
            );
            if let Some(h) = b.thrust_over_half_weight {
                self.push(
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
                self.out.push(KeyResult {
                    quantity: format!("sliding joints at the {name} bifurcation{on}"),
                    value: text,
                    paper: if self.paper && is_min {
                        paper::SLIDING_JOINTS_DEG.into()
                    } else {
                        "—".into()
                    },
                    difference: "—".into(),
                    source: src("sliding_angles_deg"),
                });
            }
            if !b.joints.hinge_angles_deg.is_empty() {
                self.out.push(KeyResult {
                    quantity: format!("hinges at the {name} bifurcation{on}"),
                    value: format::joints(&b.joints.hinge_angles_deg, &b.joints.hinge_faces),
                    paper: "—".into(),
                    difference: "—".into(),
                    source: src("hinge_angles_deg"),
                });
            }
        }
    }

    /// Thrust finds: the range of admissible crown thrusts of each case that stands (about two
    /// dozen listed at most, evenly through the study).
    fn thrust_ranges(&mut self, data: &RunData) {
        let found: Vec<(usize, &ResultRow)> = (data.results.iter().enumerate())
            .filter(|(_, r)| &*r.find == "thrust" && r.outcome.as_deref() == Some("found"))
            .collect();
        for &(i, r) in listed(&found) {
            let (Some(lo), Some(hi)) = (r.thrust_min, r.thrust_max) else {
                continue;
            };
            self.out.push(KeyResult {
                quantity: format!(
                    "admissible crown thrust H/W_half at {} (minimum to maximum)",
                    where_(data, i, r)
                ),
                value: format!("{} to {}", value(lo), value(hi)),
                paper: "—".into(),
                difference: "—".into(),
                source: format!("results.parquet row {i} thrust_min, thrust_max"),
            });
        }
    }

    /// Critical finds: the critical value of each case (about two dozen listed at most).
    fn critical_values(&mut self, data: &RunData) {
        let col_of = |r: &ResultRow| match &*r.find {
            "thickness" => Some("k_crit"),
            "friction" => Some("mu_crit"),
            _ => None,
        };
        let found: Vec<(usize, &ResultRow, &str)> = data
            .results
            .iter()
            .enumerate()
            .filter(|(_, r)| r.outcome.as_deref() == Some("found"))
            .filter_map(|(i, r)| Some((i, r, col_of(r)?)))
            .collect();
        for &(i, r, col) in listed(&found) {
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
            // Which arch and load case: rows of different arches or load cases would read alike.
            let parts: Vec<String> = arch_of(data, i)
                .into_iter()
                .chain(case_of(data, r))
                .collect();
            let model = if parts.is_empty() {
                r.voussoirs.map_or(String::new(), |n| format!(", N = {n}"))
            } else {
                format!(" ({})", parts.join(", "))
            };
            let printed = match (col, self.paper, r.mu) {
                ("k_crit", true, Some(mu)) if mu.is_infinite() => Some(paper::K_C),
                _ => None,
            };
            self.push(
                format!("{label}{model}"),
                v,
                printed,
                format!("results.parquet row {i} {col}"),
            );
        }
        self.fails_again(data);
        self.gaps(data);
    }

    /// Critical finds in which a complete solution comes before the static limit (a gap), or
    /// none comes at all: how many, and the widest gap relative to its static limit.
    fn gaps(&mut self, data: &RunData) {
        let critical = data.results.iter().filter(|r| r.gap.is_some()).count();
        let with = |status: &str| -> Vec<(usize, &ResultRow)> {
            data.results
                .iter()
                .enumerate()
                .filter(|(_, r)| r.gap.as_deref() == Some(status))
                .collect()
        };
        let gaps = with("gap");
        let relative = |r: &ResultRow| {
            let limit = r.load_factor.or(r.k_crit).or(r.mu_crit);
            match (limit, r.gap_width) {
                (Some(l), Some(w)) if l != 0.0 => w / l.abs(),
                (None, _) => f64::INFINITY,
                _ => 0.0,
            }
        };
        if let Some(&(i, widest)) = gaps
            .iter()
            .max_by(|a, b| relative(a.1).total_cmp(&relative(b.1)))
        {
            let limit = widest.load_factor.or(widest.k_crit).or(widest.mu_crit);
            let at = where_(data, i, widest);
            self.out.push(KeyResult {
                quantity: format!(
                    "finds in which the arch can start to move before its static limit (a gap: {} of {critical}); the widest at {at}: collapse (first complete solution) against static limit",
                    gaps.len(),
                ),
                value: format!(
                    "{} against {}",
                    widest.collapse_value.map_or("—".into(), value),
                    limit.map_or("unbounded".into(), value)
                ),
                paper: "—".into(),
                difference: "—".into(),
                source: format!("results.parquet row {i} collapse_value, gap_width"),
            });
        }
        let none = with("no_complete_solution");
        if let Some(&(i, first)) = none.first() {
            self.out.push(KeyResult {
                quantity: format!(
                    "finds with no complete solution up to the static limit ({} of {critical}): no mechanism obeying the flow rules can start before it; the first at {}",
                    none.len(),
                    where_(data, i, first)
                ),
                value: "—".into(),
                paper: "—".into(),
                difference: "—".into(),
                source: format!("results.parquet row {i} gap"),
            });
        }
    }

    /// Thickness finds in which a thicker arch than K_c fails again: how many, and the first
    /// with its windows.
    fn fails_again(&mut self, data: &RunData) {
        let again: Vec<(usize, &ResultRow)> = data
            .results
            .iter()
            .enumerate()
            .filter(|(_, r)| r.fails_again())
            .collect();
        let Some(&(i, first)) = again.first() else {
            return;
        };
        let windows = first
            .k_windows
            .iter()
            .map(|&(a, b)| match b {
                Some(b) => format!("[{}, {}]", value(a), value(b)),
                None => format!("[{}, end of scan]", value(a)),
            })
            .collect::<Vec<_>>()
            .join(", ");
        let at = first.mu.map_or("—".into(), given);
        self.out.push(KeyResult {
            quantity: format!(
                "cases in which a thicker arch than K_c fails again ({} of {}); first at μ = {at}: stands for K in",
                again.len(),
                data.results.iter().filter(|r| &*r.find == "thickness").count()
            ),
            value: windows,
            paper: "—".into(),
            difference: "—".into(),
            source: format!("results.parquet row {i} k_windows_from, k_windows_to"),
        });
    }

    /// The continuum's critical values of a thresholds or load-factor find (a study over the
    /// voussoir count measures its models against these); the paper's printed values beside
    /// the thresholds of its geometry.
    fn continuum_values(&mut self, data: &RunData, multi: bool) {
        let paper_geometry = data.manifest.is_paper_geometry();
        for (i, r) in data.results.iter().enumerate().filter(|(_, r)| {
            r.voussoirs.is_none() && &*r.status == "ok" && &*r.find == "thresholds"
        }) {
            let on = if multi {
                format!(" ({})", r.load_case)
            } else {
                String::new()
            };
            for (q, v, p, col) in continuum_cells(r) {
                let Some(v) = v else { continue };
                let (paper_text, d) = compare(v, p.filter(|_| paper_geometry));
                self.out.push(KeyResult {
                    quantity: format!("{q}, continuum{on}"),
                    value: value(v),
                    paper: paper_text,
                    difference: d,
                    source: format!("results.parquet row {i} {col}"),
                });
            }
            if self.out.len() > 40 {
                break;
            }
        }
    }
}

/// The values of the arch axes and the load position of a bifurcation, as ` (α = 70°, N = 9)`,
/// for the axes the study has (empty without them).
fn group_text(data: &RunData, g: &crate::store::BifurcationGroup) -> String {
    let has = |n: &str| data.manifest.grid.iter().any(|a| a.name == n);
    let mut parts = Vec::new();
    if has("half_angle_deg")
        && let Some(a) = g.half_angle_deg
    {
        parts.push(format!("α = {}°", given(a)));
    }
    if has("eccentricity") {
        parts.push(format!("e = {}", given(g.eccentricity.unwrap_or(0.0))));
    }
    if has("joints")
        && let Some(j) = &g.joints
    {
        parts.push(format!("{j} joints"));
    }
    if has("voussoirs") {
        parts.push(match g.voussoirs.flatten() {
            Some(n) => format!("N = {n}"),
            None => "continuum".into(),
        });
    }
    match (g.at_x, g.at_deg) {
        (Some(x), _) => parts.push(format!("load at x/L = {}", given(x))),
        (None, Some(a)) => parts.push(format!("load at {}°", position_deg(a))),
        (None, None) => {}
    }
    if parts.is_empty() {
        String::new()
    } else {
        format!(" ({})", parts.join(", "))
    }
}

/// A quantity of a continuum case: label, stored value, the paper's printed value and the
/// column it comes from.
type Cell = (String, Option<f64>, Option<Printed>, &'static str);

/// The quantities of a continuum thresholds or load-factor case.
fn continuum_cells(r: &ResultRow) -> Vec<Cell> {
    if &*r.find == "thresholds" {
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
    }
}

/// Where a case of a critical find lies: its given K and μ; the one a find searches for is
/// named as found.
/// Where row `i` of results.parquet lies: its arch on the study's arch axes, the given K
/// and μ (a thickness find has no K of its own, a friction find no μ), and its load case when
/// the study has several.
fn where_(data: &RunData, i: usize, r: &ResultRow) -> String {
    (arch_of(data, i).into_iter())
        .chain(r.k.map(|k| format!("K = {}", given(k))))
        .chain(r.mu.map(|m| format!("μ = {}", given(m))))
        .chain(case_of(data, r))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Row `i`'s arch on the study's arch axes; `None` without them.
fn arch_of(data: &RunData, i: usize) -> Option<String> {
    let a = data
        .result_arches
        .get(i)
        .filter(|_| data.result_arches.len() == data.results.len())?;
    Some(crate::report::charts::arch_axis::arch_label(data, *a)).filter(|l| !l.is_empty())
}

/// Row `r`'s load case when the study has several.
fn case_of(data: &RunData, r: &ResultRow) -> Option<String> {
    (data.manifest.load_cases.len() > 1).then(|| format!("load case {}", r.load_case))
}
