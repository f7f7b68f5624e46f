//! The study: the arch and the model, the grid axes, the load cases and the cases with
//! their outcomes.

use super::{Item, item};
use crate::report::data::{ManifestView, RunData};
use crate::report::format::given;
use serde::Serialize;

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
    if let Some(s) = &m.sampling {
        return match s.question.as_str() {
            "probability" => {
                "probability: whether the arch stands (at its λ under a live load) at \
                              every sample of the uncertain parameters, and by which mechanism it \
                              fails"
                    .into()
            }
            "fragility" => "fragility: the largest load factor λ_max of the live load at every \
                            sample of the uncertain parameters, and its distribution"
                .into(),
            _ => "sensitivity: the Sobol indices of the stability margin (self-weight) or of \
                  λ_max (a live load) to each uncertain parameter, from the Saltelli design"
                .into(),
        };
    }
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

/// A value of an axis as the report writes it: `continuum` for a voussoir axis's null, ∞
/// for another axis's.
fn axis_value(axis: &str, v: Option<f64>) -> String {
    match (axis, v) {
        ("voussoirs", None) => "continuum".into(),
        ("joints", Some(x)) => crate::manifest::joints_of_axis_value(x).as_str().into(),
        (_, None) => "∞".into(),
        (_, Some(x)) => given(x),
    }
}

/// An axis of the grid in words: `grid axis, 4 values from 60 to 90`, `grid axis, 25
/// values from 3 to 4096 and the continuum`.
fn axis_words(m: &ManifestView, name: &str) -> Option<String> {
    let a = m.axis(name)?;
    let finite: Vec<f64> = a.values.iter().flatten().copied().collect();
    let lo = finite.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mut range = match finite.len() {
        0 => String::new(),
        1 => given(lo),
        _ => format!("from {} to {}", given(lo), given(hi)),
    };
    if a.values.iter().any(Option::is_none) {
        let extra = axis_value(name, None);
        range = if range.is_empty() {
            extra
        } else {
            format!("{range} and the {extra}").replace("the ∞", "∞")
        };
    }
    Some(match a.values.len() {
        1 => format!("grid axis, one value: {range}"),
        n => format!("grid axis, {n} values: {range}"),
    })
}

/// The arch and the model: shape, joints, weight model, material, find and tolerance. A
/// half-angle or voussoir count that varies is described as the axis it is.
pub fn model(m: &ManifestView) -> Vec<Item> {
    let uncertain = |name: &str| {
        m.sampling
            .as_ref()
            .is_some_and(|s| s.params.iter().any(|p| p.name == name))
    };
    let alpha = axis_words(m, "half_angle_deg").map_or_else(
        || format!("half-embrace angle α = {}°", given(m.arch.half_angle_deg)),
        |w| format!("half-embrace angle α (°): {w}"),
    );
    let alpha = if uncertain("half_angle_deg") {
        "half-embrace angle α: uncertain (Uncertain parameters)".to_string()
    } else {
        alpha
    };
    let joints = axis_words(m, "voussoirs").map_or_else(
        || {
            m.arch
                .voussoir_count()
                .map_or("continuum (every section a potential joint)".into(), |n| {
                    format!("{n} voussoirs")
                })
        },
        |w| format!("voussoir count N: {w}"),
    );
    let joints = if uncertain("voussoirs") {
        "voussoir count N: uncertain (Uncertain parameters)".to_string()
    } else {
        joints
    };
    let eccentricity = match m.arch.eccentricity {
        _ if m.axis("eccentricity").is_some() => format!(
            " (eccentricity e: {})",
            axis_words(m, "eccentricity").unwrap_or_default()
        ),
        Some(e) if uncertain("eccentricity") => format!(" (eccentricity uncertain, nominal {e})"),
        Some(e) => format!(" (eccentricity {e})"),
        None => String::new(),
    };
    vec![
        item(
            "shape",
            format!(
                "{}{eccentricity}, {alpha}",
                m.arch.shape,
            ),
        ),
        item(
            "joints",
            match m.axis("joints") {
                Some(a) => format!(
                    "{} (grid axis), {joints}",
                    (a.values.iter().flatten())
                        .map(|&v| crate::manifest::joints_of_axis_value(v).as_str())
                        .collect::<Vec<_>>()
                        .join(" and ")
                ),
                None => format!("{}, {joints}", m.arch.joints),
            },
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
    ]
    .into_iter()
    .chain(
        m.sampling
            .is_none()
            .then(|| item("boundary tolerance", format!("{:e}", m.boundary_tolerance))),
    )
    .collect()
}

/// The grid axes: parameter, number of values, first and last.
pub fn grid(m: &ManifestView) -> Vec<AxisRow> {
    m.grid
        .iter()
        .map(|a| {
            let g = |v: Option<&Option<f64>>| v.map_or("—".into(), |x| axis_value(&a.name, *x));
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
            if let Some(w) = l.width.filter(|&w| w > 0.0) {
                d.push_str(&format!(
                    " spread over {} of the extrados span",
                    crate::report::format::given(w)
                ));
            }
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
    let by_outcome = &data.totals.by_outcome;
    let mut cases = vec![
        item("cases", info.cases.total.to_string()),
        item("failed", info.cases.error.to_string()),
    ];
    cases.extend(by_outcome.iter().map(|(k, v)| item(k, v.to_string())));
    cases
}
