//! The study: the arch and the model, the grid axes, the load cases and the cases with
//! their outcomes.

use super::{Item, item};
use crate::report::data::{ManifestView, RunData};
use crate::report::format::given;
use serde::Serialize;
use std::collections::BTreeMap;

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
fn finds_text(m: &ManifestView) -> String {
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

/// The arch and the model: shape, joints, weight model, material, find and tolerance.
pub fn model(m: &ManifestView) -> Vec<Item> {
    vec![
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
    ]
}

/// The grid axes: parameter, number of values, first and last.
pub fn grid(m: &ManifestView) -> Vec<AxisRow> {
    m.grid
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
        .collect()
}

/// The load cases, as `name (kind)`, with the axes their find finds itself.
pub fn load_cases(m: &ManifestView) -> Vec<String> {
    // A load case whose find finds K or μ itself has one case per value of the other axes.
    m.load_cases
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
        .collect()
}

/// The number of cases, of failed cases and of cases per regime or outcome.
pub fn cases(data: &RunData) -> Vec<Item> {
    let info = &data.info;
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
    cases
}
