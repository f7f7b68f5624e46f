//! Tables of values against the axes a study varies: the bifurcations of every arch of a
//! half-angle or voussoir axis, and the per-case values behind each error of a voussoir
//! study whose counts have more than one case.

use crate::report::charts::arch_axis::{arch_label, arches_of};
use crate::report::charts::regime_map::bifurcations_of_arch;
use crate::report::charts::{quantity_label, single_model};
use crate::report::data::RunData;
use crate::report::format::short;
use crate::store::ResultRow;
use serde::Serialize;
use std::collections::{BTreeMap, HashMap};

/// A table: a title, a note on how to read it, the column heads and the rows (formatted).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ValueTable {
    /// Heading.
    pub title: String,
    /// How to read it.
    pub note: String,
    /// Column heads.
    pub headers: Vec<String>,
    /// Rows, one string per column.
    pub rows: Vec<Vec<String>>,
}

/// The value tables of a run, in report order.
pub fn value_tables(data: &RunData) -> Vec<ValueTable> {
    let mut out = super::uncertainty::value_tables(data);
    out.extend(bifurcations_by_arch(data));
    out.extend(values_behind_errors(data));
    out
}

/// The bifurcations of every arch of an arch axis: μ, K and t/R_c per arch and pair of
/// mechanisms.
fn bifurcations_by_arch(data: &RunData) -> Option<ValueTable> {
    if single_model(data) {
        return None;
    }
    let multi = data.manifest.load_cases.len() > 1;
    let mut rows = Vec::new();
    for lc in &data.manifest.load_cases {
        if data.manifest.find_of(&lc.name) != "state" {
            continue;
        }
        for arch in arches_of(data, &lc.name) {
            for b in bifurcations_of_arch(data, &lc.name, Some(arch)) {
                let mut row = Vec::new();
                if multi {
                    row.push(lc.name.clone());
                }
                row.extend([
                    arch_label(data, arch),
                    crate::figdata::bifurcation_label(&b.mechanism_a, &b.mechanism_b),
                    short(b.mu),
                    short(b.k),
                    short(b.t_over_r),
                ]);
                rows.push(row);
            }
        }
    }
    if rows.is_empty() {
        return None;
    }
    let mut headers = Vec::new();
    if multi {
        headers.push("load case".to_string());
    }
    headers.extend(["arch", "mechanisms", "μ", "K", "t/R_c"].map(String::from));
    Some(ValueTable {
        title: "Bifurcations by arch".into(),
        note: "Every bifurcation of bifurcations.parquet with the arch it belongs to: where two collapse mechanisms meet on that arch's collapse curve.".into(),
        headers,
        rows,
    })
}

/// The values behind the error of each quantity and voussoir count, when a count has more
/// than one case (the error tables give the largest error over them): per case, the values
/// of the other axes, the discrete and continuum values and the error. At most a few
/// dozen rows per quantity: the counts and the other values spread over their ranges.
fn values_behind_errors(data: &RunData) -> Vec<ValueTable> {
    let rows = crate::report::charts::accuracy_rows(data);
    if rows.is_empty() || rows.iter().all(|r| r.cases == 1) {
        return Vec::new();
    }
    let by_id: HashMap<u64, &ResultRow> = data.results.iter().map(|r| (r.case_id, r)).collect();
    let mut by_q: BTreeMap<String, Vec<Case>> = BTreeMap::new();
    for rf in &data.reference {
        let Some(r) = by_id.get(&rf.case_id) else {
            continue;
        };
        let (Some(n), Some(value)) = (r.voussoirs, r.value_of(&rf.quantity)) else {
            continue;
        };
        by_q.entry(rf.quantity.clone()).or_default().push(Case {
            n,
            k: r.k,
            mu: r.mu,
            value,
            continuum: rf.continuum_value,
        });
    }
    by_q.into_iter()
        .filter_map(|(q, cases)| case_table(&q, cases))
        .collect()
}

/// One compared case: N, K, μ, discrete and continuum values.
struct Case {
    n: u32,
    k: Option<f64>,
    mu: Option<f64>,
    value: f64,
    continuum: Option<f64>,
}

/// Up to `max` of `v` (sorted, distinct), spread evenly from the first to the last.
fn spread<T: Copy>(v: &[T], max: usize) -> Vec<T> {
    if v.len() <= max {
        return v.to_vec();
    }
    (0..max)
        .map(|i| v[(i * (v.len() - 1)) / (max - 1)])
        .collect()
}

fn case_table(q: &str, mut cases: Vec<Case>) -> Option<ValueTable> {
    let key = |c: &Case| (c.k.unwrap_or(f64::NAN), c.mu.unwrap_or(f64::NAN));
    let mut counts: Vec<u32> = cases.iter().map(|c| c.n).collect();
    counts.sort_unstable();
    counts.dedup();
    let mut others: Vec<(f64, f64)> = cases.iter().map(key).collect();
    others.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    others.dedup_by(|a, b| a.0.total_cmp(&b.0).is_eq() && a.1.total_cmp(&b.1).is_eq());
    let (counts, others) = (spread(&counts, 6), spread(&others, 8));
    cases.retain(|c| {
        counts.contains(&c.n)
            && others
                .iter()
                .any(|o| o.0.total_cmp(&key(c).0).is_eq() && o.1.total_cmp(&key(c).1).is_eq())
    });
    cases.sort_by(|a, b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.total_cmp(&kb.0)
            .then(ka.1.total_cmp(&kb.1))
            .then(a.n.cmp(&b.n))
    });
    if cases.is_empty() {
        return None;
    }
    let opt = |v: Option<f64>| {
        v.map_or("—".to_string(), |x| {
            if x.is_infinite() {
                "∞".into()
            } else {
                short(x)
            }
        })
    };
    let rows: Vec<Vec<String>> = cases
        .iter()
        .map(|c| {
            vec![
                opt(c.k),
                opt(c.mu),
                c.n.to_string(),
                format!("{:.10}", c.value),
                c.continuum.map_or("—".into(), |v| format!("{v:.10}")),
                c.continuum
                    .map_or("—".into(), |v| format!("{:.3e}", c.value - v)),
            ]
        })
        .collect();
    let mut headers: Vec<String> = ["K", "μ", "N", "value", "continuum", "error"]
        .map(String::from)
        .to_vec();
    let mut rows = rows;
    // Leave out K or μ when the find finds it (no case gives one).
    for col in [1, 0] {
        if rows.iter().all(|r| r[col] == "—") {
            headers.remove(col);
            rows.iter_mut().for_each(|r| {
                r.remove(col);
            });
        }
    }
    Some(ValueTable {
        title: format!("{} by voussoir count and case", quantity_label(q)),
        note: format!(
            "The values of `{q}` behind its error rows (which give the largest error over the cases of each N): for up to six voussoir counts N and eight values of the other axes, spread over their ranges, the discrete value, the continuum value at the same K, μ and load (reference.parquet) and their difference. The full table is reference.parquet joined to results.parquet on case_id."
        ),
        headers,
        rows,
    })
}
