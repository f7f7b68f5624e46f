//! The tables of a sampling study: the uncertain parameters, the key results (probabilities
//! with their intervals, the exact probability, quantiles of λ_max, the dominant parameter),
//! the estimates of every grid point and the Sobol indices, and the reading notes that say
//! how the intervals are made.

use super::key_results::KeyResult;
use super::values::ValueTable;
use crate::report::charts::uncertainty::Estimates;
use crate::report::data::{RunData, SamplingView};
use crate::report::format::sig;
use crate::store::EstimateRow;

/// Key results of a sampling study shown per load case for at most this many grid points
/// (evenly spread over them when there are more).
const KEY_POINTS: usize = 12;

/// The points the key results list: every one, or KEY_POINTS spread evenly.
fn key_points(all: &[u64]) -> Vec<u64> {
    if all.len() <= KEY_POINTS {
        return all.to_vec();
    }
    let mut v: Vec<u64> = (0..KEY_POINTS)
        .map(|i| all[i * (all.len() - 1) / (KEY_POINTS - 1)])
        .collect();
    v.dedup();
    v
}

fn with_interval(r: &EstimateRow) -> String {
    match (r.lo, r.hi) {
        (Some(lo), Some(hi)) if r.value.is_finite() => {
            format!("{} [{}, {}]", sig(r.value, 4), sig(lo, 4), sig(hi, 4))
        }
        _ => sig(r.value, 4),
    }
}

fn row(quantity: String, value: String, source: &str) -> KeyResult {
    KeyResult {
        quantity,
        value,
        paper: "—".into(),
        difference: "—".into(),
        source: format!("estimates.parquet, quantity {source}"),
    }
}

/// The key results of a sampling study.
pub fn key_results(data: &RunData) -> Vec<KeyResult> {
    let Some(s) = &data.manifest.sampling else {
        return Vec::new();
    };
    let multi = data.manifest.load_cases.len() > 1;
    let mut out = Vec::new();
    for lc in &data.manifest.load_cases {
        let e = Estimates::of(data, &lc.name);
        for p in key_points(&e.points()) {
            let mut at = Vec::new();
            if multi {
                at.push(lc.name.clone());
            }
            let label = e.label(p);
            if !label.is_empty() {
                at.push(label);
            }
            let on = if at.is_empty() {
                String::new()
            } else {
                format!(" ({})", at.join(", "))
            };
            out.extend(point_rows(s, &e, p, &on));
        }
    }
    out
}

/// The key results of one grid point (`on` names it in the quantity).
fn point_rows(s: &SamplingView, e: &Estimates, p: u64, on: &str) -> Vec<KeyResult> {
    let mut out = Vec::new();
    if s.question != "fragility"
        && let Some(r) = e.one(p, "probability", "")
    {
        out.push(row(
            format!("P(collapse), 95 % interval{on}"),
            with_interval(r),
            "probability",
        ));
    }
    if let Some(r) = e.one(p, "exact_probability", "") {
        let value = if r.value.is_finite() {
            format!(
                "{} (± {})",
                sig(r.value, 10),
                sig(r.hi.unwrap_or(r.value) - r.value, 2)
            )
        } else {
            format!("none: {}", r.note)
        };
        out.push(row(
            format!("P(collapse), exact{on}"),
            value,
            "exact_probability",
        ));
    }
    let (quantity, what) = if s.question == "fragility" {
        ("limit_mechanism", "share of λ_max reached by a")
    } else {
        ("mechanism", "P(collapse by a")
    };
    for m in ["rotational", "mixed", "sliding", "none"] {
        if let Some(r) = e.one(p, quantity, m).filter(|r| r.value > 0.0) {
            let close = if s.question == "fragility" { "" } else { ")" };
            let quantity_text = if m == "none" {
                let what = what.trim_end_matches(" by a");
                format!("{what} with Hʳ and Hˢ empty{close}{on}")
            } else {
                format!("{what} {m} mechanism{close}{on}")
            };
            out.push(row(quantity_text, with_interval(r), quantity));
        }
    }
    for level in ["0.05", "0.5", "0.95"] {
        if let Some(r) = e.one(p, "quantile", level) {
            let pct = (level.parse::<f64>().unwrap_or(0.0) * 100.0).round();
            out.push(row(
                format!("λ_max, {pct} % quantile{on}"),
                with_interval(r),
                "quantile",
            ));
        }
    }
    let mut totals: Vec<&EstimateRow> = e
        .get(p, "total")
        .into_iter()
        .filter(|r| r.value.is_finite())
        .collect();
    totals.sort_by(|a, b| b.value.total_cmp(&a.value));
    if let Some(top) = totals.first() {
        // Parameters whose total index's interval reaches the largest one's are not
        // told apart by these samples.
        let tied: Vec<&str> = totals[1..]
            .iter()
            .filter(|r| r.hi.unwrap_or(r.value) >= top.lo.unwrap_or(top.value))
            .map(|r| r.parameter.as_str())
            .collect();
        let first = e.one(p, "first_order", &top.parameter);
        let (quantity, lead) = if tied.is_empty() {
            ("dominant parameter", top.parameter.clone())
        } else {
            (
                "dominant parameters (intervals overlap)",
                format!("{} and {}", top.parameter, tied.join(", ")),
            )
        };
        out.push(row(
            format!("{quantity}{on}"),
            format!(
                "{lead}: {} has total index {}, first order {}",
                top.parameter,
                with_interval(top),
                first.map_or("—".into(), with_interval)
            ),
            "total",
        ));
    }
    out
}

/// The value tables of a sampling study: its uncertain parameters and its estimates.
pub fn value_tables(data: &RunData) -> Vec<ValueTable> {
    let Some(s) = &data.manifest.sampling else {
        return Vec::new();
    };
    let mut out = vec![parameters_table(s)];
    let mut rows = Vec::new();
    let mut sobol = Vec::new();
    let mut quantiles = Vec::new();
    for lc in &data.manifest.load_cases {
        let e = Estimates::of(data, &lc.name);
        for p in e.points() {
            let label = e.label(p);
            let cell =
                |q: &str, param: &str| e.one(p, q, param).map_or("—".to_string(), with_interval);
            rows.push(vec![
                lc.name.clone(),
                if label.is_empty() {
                    "—".into()
                } else {
                    label.clone()
                },
                e.one(p, "samples", "")
                    .map_or("—".into(), |r| format!("{}", r.value)),
                cell("probability", ""),
                e.one(p, "exact_probability", "")
                    .filter(|r| r.value.is_finite())
                    .map_or("—".into(), |r| sig(r.value, 10)),
                cell("mechanism", "rotational"),
                cell("mechanism", "mixed"),
                cell("mechanism", "sliding"),
                cell("mechanism", "none"),
            ]);
            for param in &s.params {
                if let Some(f) = e.one(p, "first_order", &param.name) {
                    sobol.push(vec![
                        lc.name.clone(),
                        label.clone(),
                        param.name.clone(),
                        with_interval(f),
                        cell("total", &param.name),
                    ]);
                }
            }
            if e.one(p, "quantile", "0.5").is_some() {
                quantiles.push(vec![
                    lc.name.clone(),
                    label.clone(),
                    cell("quantile", "0.05"),
                    cell("quantile", "0.5"),
                    cell("quantile", "0.95"),
                    e.one(p, "mean", "").map_or("—".into(), |r| sig(r.value, 5)),
                ]);
            }
        }
    }
    out.push(probability_table(rows));
    // Whether a live load's capacity stands under its own weight says little; its table is
    // that of λ_max.
    let capacity_only = s.question == "fragility"
        || (s.question == "sensitivity"
            && data
                .manifest
                .load_cases
                .iter()
                .all(|l| l.kind != "self_weight"));
    if capacity_only {
        out.pop();
    }
    if !quantiles.is_empty() {
        out.push(ValueTable {
            title: "Quantiles of λ_max".into(),
            note: "The 5 %, 50 % and 95 % quantiles of the largest load factor, each with its \
                   distribution-free 95 % interval (order statistics), and the mean (— where some \
                   λ_max are unbounded)."
                .into(),
            headers: ["load case", "grid point", "5 %", "50 %", "95 %", "mean"]
                .map(String::from)
                .to_vec(),
            rows: quantiles,
        });
    }
    if !sobol.is_empty() {
        out.push(ValueTable {
            title: "Sobol indices".into(),
            note: "First-order and total Sobol indices with 95 % bootstrap intervals.".into(),
            headers: [
                "load case",
                "grid point",
                "parameter",
                "first order",
                "total",
            ]
            .map(String::from)
            .to_vec(),
            rows: sobol,
        });
    }
    out
}

/// The probability of collapse of every grid point (`rows` from [`value_tables`]).
fn probability_table(rows: Vec<Vec<String>>) -> ValueTable {
    ValueTable {
        title: "Probability of collapse".into(),
        note: "Per load case and grid point: the samples answered, the sampled probability that \
               the arch does not stand with its 95 % Wilson interval, the exact probability where \
               the mechanics gives it, and the probability of collapse by each mechanism."
            .into(),
        headers: [
            "load case",
            "grid point",
            "samples",
            "P(collapse)",
            "exact",
            "rotational",
            "mixed",
            "sliding",
            "Hʳ and Hˢ empty",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

/// The uncertain parameters and how they are sampled.
fn parameters_table(s: &SamplingView) -> ValueTable {
    ValueTable {
        title: "Uncertain parameters".into(),
        note: format!(
            "{} samples by {} (seed {}){}.",
            s.n,
            match s.method.as_str() {
                "sobol" => "scrambled Sobol points",
                "lhs" => "Latin hypercube sampling",
                _ => "random sampling",
            },
            s.seed,
            match &s.correlation {
                Some(c) => format!(
                    "; the normal scores of {} and {} correlated at {}",
                    s.params.get(c.first).map_or("?", |p| p.name.as_str()),
                    s.params.get(c.second).map_or("?", |p| p.name.as_str()),
                    c.value
                ),
                None => String::new(),
            }
        ),
        headers: vec!["parameter".into(), "distribution".into()],
        rows: s
            .params
            .iter()
            .map(|p| vec![p.name.clone(), p.description.clone()])
            .collect(),
    }
}

/// How the estimates of a sampling study are made, for the reading notes.
pub fn notes(data: &RunData) -> Vec<String> {
    let Some(s) = &data.manifest.sampling else {
        return Vec::new();
    };
    let mut out = vec![format!(
        "Every sample is one analysis of the arch at the sampled values ({} in all). An arch \
         that does not stand is one without an admissible state (the static limit); the \
         probabilities carry 95 % Wilson intervals, which hold for independent samples and are \
         conservative for scrambled Sobol and Latin hypercube points, whose error is smaller.",
        data.info.cases.total
    )];
    if data.info.cases.error > 0 {
        out.push(format!(
            "{} samples gave no answer and are left out of the estimates (their rows in \
             samples.parquet have status error).",
            data.info.cases.error
        ));
    }
    if s.question == "sensitivity" {
        out.push(
            "A Sobol index is estimated from n base samples and n·d mixed ones (the Saltelli \
             design); a small or negative first-order index within its interval of zero means \
             the parameter acts only through its interactions, or not at all."
                .into(),
        );
    }
    out
}
