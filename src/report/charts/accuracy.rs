//! Figure 5: the error of the discrete arch against the continuum, against N and against
//! the solve time; also the accuracy rows the report's tables show.

use super::{Chart, FigureSpec};
use crate::figdata;
use crate::plot::accuracy::{AccuracyChart, AccuracySeries};
use crate::report::convergence::{ObservedOrder, observed_order};
use crate::report::data::RunData;
use std::collections::{BTreeMap, HashMap};

const ACCURACY_CAPTION: &str = "Error of each critical value of a discrete arch of N voussoirs against the continuum value at the same K, μ and load (largest error over the cases with that N), against N (points of one quantity joined in order of N) and against the median solve time per case (one point per N; a thresholds case finds all four quantities in one analysis, so they share its time). The legend gives each quantity's observed order of convergence, the least-squares slope of log|error| against log N over the larger counts. The error need not fall monotonically: it depends on how near a joint of the model lies to the continuum's hinge or sliding section, and a count whose joints include those of a smaller one (512, 1024, 2048, ...) can give the same value. The dashed line marks the median solve time of the continuum analyses (one line per find when the study has several), whose error is zero by definition.";

/// Label of a compared quantity.
pub fn quantity_label(q: &str) -> &'static str {
    match q {
        "k_crit" => "K_c",
        "mu_crit" => "μ_c",
        "thrust_min" => "H_min/W_half",
        "thrust_r_min" => "min Hʳ/W_half",
        "k_c_rotational" => "K_c (μ = ∞)",
        "mu_rotational_mixed" => "μ, rotational/mixed",
        "mu_min" => "μ_min",
        "k_mixed_sliding" => "K, mixed/sliding",
        "load_factor" => "λ (load factor)",
        _ => "value",
    }
}

/// One row of the accuracy data: quantity, N, largest |error|, largest relative error,
/// median solve time of the discrete cases and of their continuum references (µs).
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyRow {
    /// Results column compared.
    pub quantity: String,
    /// Voussoir count.
    pub voussoirs: u32,
    /// Cases compared.
    pub cases: usize,
    /// Largest |discrete − continuum|.
    pub max_abs_error: f64,
    /// Largest |discrete − continuum| / |continuum|.
    pub max_rel_error: f64,
    /// The discrete value when one case has this N (NaN otherwise).
    pub value: f64,
    /// The continuum value when one case has this N (NaN otherwise).
    pub continuum_value: f64,
    /// Median solve time of the discrete cases, µs.
    pub median_time_us: f64,
    /// Median solve time of the continuum references, µs.
    pub continuum_median_time_us: f64,
}

/// The accuracy rows of a run (empty without references).
pub fn accuracy_rows(data: &RunData) -> Vec<AccuracyRow> {
    if data.reference.is_empty() {
        return Vec::new();
    }
    let by_id: HashMap<u64, &crate::store::ResultRow> =
        data.results.iter().map(|r| (r.case_id, r)).collect();
    // Per (quantity, N): value, continuum value, solve time, continuum solve time.
    type Sample = (f64, f64, f64, f64);
    let mut groups: BTreeMap<(String, u32), Vec<Sample>> = BTreeMap::new();
    for rf in &data.reference {
        let Some(r) = by_id.get(&rf.case_id) else {
            continue;
        };
        let (Some(n), Some(cont)) = (r.voussoirs, rf.continuum_value) else {
            continue;
        };
        let Some(v) = r.value_of(&rf.quantity) else {
            continue;
        };
        groups.entry((rf.quantity.clone(), n)).or_default().push((
            v,
            cont,
            r.solve_time_us,
            rf.continuum_solve_time_us,
        ));
    }
    groups
        .into_iter()
        .map(|((q, n), v)| {
            let max_abs = v.iter().map(|x| (x.0 - x.1).abs()).fold(0.0, f64::max);
            let max_rel = v
                .iter()
                .map(|x| (x.0 - x.1).abs() / x.1.abs())
                .fold(0.0, f64::max);
            let (value, continuum_value) = match v.as_slice() {
                [one] => (one.0, one.1),
                _ => (f64::NAN, f64::NAN),
            };
            let mut t: Vec<f64> = v.iter().map(|x| x.2).collect();
            let mut tc: Vec<f64> = v.iter().map(|x| x.3).collect();
            t.sort_by(f64::total_cmp);
            tc.sort_by(f64::total_cmp);
            AccuracyRow {
                quantity: q,
                voussoirs: n,
                cases: v.len(),
                max_abs_error: max_abs,
                max_rel_error: max_rel,
                value,
                continuum_value,
                median_time_us: crate::report::format::quantile(&t, 0.5),
                continuum_median_time_us: crate::report::format::quantile(&tc, 0.5),
            }
        })
        .collect()
}

/// Position of a quantity in tables and legends: the order of the find's columns.
pub fn quantity_rank(q: &str) -> usize {
    [
        "k_crit",
        "mu_crit",
        "thrust_min",
        "thrust_r_min",
        "k_c_rotational",
        "mu_rotational_mixed",
        "mu_min",
        "k_mixed_sliding",
        "load_factor",
    ]
    .iter()
    .position(|c| *c == q)
    .unwrap_or(usize::MAX)
}

/// The observed order of convergence of each quantity, from its largest error per N.
pub fn orders(rows: &[AccuracyRow]) -> BTreeMap<String, Option<ObservedOrder>> {
    let mut pts: BTreeMap<String, Vec<(u32, f64)>> = BTreeMap::new();
    for r in rows {
        pts.entry(r.quantity.clone())
            .or_default()
            .push((r.voussoirs, r.max_abs_error));
    }
    pts.into_iter()
        .map(|(q, p)| (q, observed_order(&p)))
        .collect()
}

/// The speed-against-accuracy figure, when the run has continuum references.
pub fn figure(data: &RunData) -> Option<FigureSpec> {
    let a = accuracy(data)?;
    Some(FigureSpec {
        stem: "speed-accuracy".into(),
        title: "Speed against accuracy".into(),
        caption: ACCURACY_CAPTION.into(),
        chart: Chart::Accuracy(a),
    })
}

fn accuracy(data: &RunData) -> Option<AccuracyChart> {
    let rows = accuracy_rows(data);
    // One voussoir count gives one point per quantity: no line, no order, nothing to read
    // off a chart that the table does not say.
    let mut counts: Vec<u32> = rows.iter().map(|r| r.voussoirs).collect();
    counts.sort_unstable();
    counts.dedup();
    if counts.len() < 2 {
        return None;
    }
    let orders = orders(&rows);
    let mut by_q: BTreeMap<(usize, String), AccuracySeries> = BTreeMap::new();
    // Continuum solve times by find: one find's quantities come from one analysis.
    let mut cont_times: BTreeMap<&str, Vec<f64>> = BTreeMap::new();
    for r in &rows {
        let s = by_q
            .entry((quantity_rank(&r.quantity), r.quantity.clone()))
            .or_insert_with(|| AccuracySeries {
                label: match orders.get(&r.quantity).and_then(Option::as_ref) {
                    Some(o) => format!(
                        "{}: order {:.2} (N = {}–{})",
                        quantity_label(&r.quantity),
                        o.order,
                        o.n_from,
                        o.n_to
                    ),
                    None => quantity_label(&r.quantity).to_string(),
                },
                by_count: Vec::new(),
                by_time: Vec::new(),
            });
        if r.max_abs_error > 0.0 {
            s.by_count.push((f64::from(r.voussoirs), r.max_abs_error));
            s.by_time.push((r.median_time_us, r.max_abs_error));
        }
        let find = figdata::find_of_quantity(&r.quantity).unwrap_or("");
        cont_times
            .entry(find)
            .or_default()
            .push(r.continuum_median_time_us);
    }
    let several = cont_times.len() > 1;
    let continuum_times = cont_times
        .into_iter()
        .filter_map(|(find, mut t)| {
            t.sort_by(f64::total_cmp);
            let median = crate::report::format::quantile(&t, 0.5);
            let label = if several {
                format!("continuum, {}", find.replace('_', " "))
            } else {
                "continuum".to_string()
            };
            median.is_finite().then_some((median, label))
        })
        .collect();
    Some(AccuracyChart {
        title: "Discrete arch against the continuum".into(),
        series: by_q.into_values().collect(),
        continuum_times,
    })
}
