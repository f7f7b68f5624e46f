//! The key results of a load_factor load case: the weakest and strongest case, λ_max at a few
//! (K, μ) (at the weakest position of a moving point load), and a few of the located changes
//! of mechanism, each naming the values of the other axes. The full tables are
//! results.parquet and bifurcations.parquet.

use super::{Rows, group_text};
use crate::report::charts::load_factor::{spread, x_over_l};
use crate::report::data::{RunData, given_position};
use crate::report::format::compact;
use crate::report::format::{given, position_deg, short};
use crate::store::LoadFactorCase;

/// At most this many K and μ values in the table of λ.
const TABLE_SIDE: usize = 3;
/// At most this many changes of mechanism listed.
const CHANGES: usize = 6;

/// Where a case sits: K, μ, the load's position (angle and x/L), the arch axes and the
/// mechanism.
fn case_text(data: &RunData, c: &LoadFactorCase) -> String {
    let mut parts = vec![
        format!("K = {}", compact(c.k)),
        format!("μ = {}", compact(c.mu)),
    ];
    if data.manifest.positions_by_x(&c.load_case)
        && let Some(x) = c.at_x
    {
        let angle = c
            .at_deg
            .map_or(String::new(), |a| format!(" ({}°)", position_deg(a)));
        parts.push(format!("load at x/L = {}{angle}", given(x)));
    } else if let Some(a) = c.at_deg {
        let xl = c.at_x.unwrap_or_else(|| {
            let arch = (data.manifest.arch).with_form(c.eccentricity, c.joints.as_str());
            x_over_l(&arch, c.k, c.half_angle_deg, a)
        });
        parts.push(format!(
            "load at {}° (x/L = {})",
            position_deg(a),
            short(xl)
        ));
    }
    parts.extend(arch_parts(data, c));
    if let Some(m) = &c.mechanism {
        parts.push(format!("{m} collapse"));
    }
    parts.join(", ")
}

/// The case's values on the study's arch axes: `α = 60°`, `e = 0.2`, `vertical joints`,
/// `N = 9` or `continuum`.
fn arch_parts(data: &RunData, c: &LoadFactorCase) -> Vec<String> {
    let has = |n: &str| data.manifest.grid.iter().any(|a| a.name == n);
    let mut parts = Vec::new();
    if has("half_angle_deg") {
        parts.push(format!("α = {}°", given(c.half_angle_deg)));
    }
    if has("eccentricity") {
        parts.push(format!("e = {}", given(c.eccentricity.unwrap_or(0.0))));
    }
    if has("joints") {
        parts.push(format!("{} joints", c.joints.as_str()));
    }
    if has("voussoirs") {
        parts.push(
            c.voussoirs
                .map_or("continuum".into(), |n| format!("N = {n}")),
        );
    }
    parts
}

fn distinct(vals: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = vals.filter(|x| !x.is_nan()).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// Every bounded case of a load case, of every arch: those of the figure lattice and the
/// cases singled out over every case (in row order, each once), among which are the least
/// and largest λ_max of all cases.
fn study_cases<'a>(data: &'a RunData, lc: &str) -> Vec<&'a LoadFactorCase> {
    let mut bounded: Vec<&LoadFactorCase> = data
        .load_factors
        .iter()
        .chain(data.load_factor_singled.iter())
        .filter(|c| c.load_case == lc && c.load_factor.is_some())
        .collect();
    bounded.sort_by_key(|c| c.row);
    bounded.dedup_by_key(|c| c.row);
    bounded
}

/// The bounded cases of a load case summarised: one arch's (the continuum's when the study
/// has it, else the first half-angle and voussoir count's). Those of the figure lattice, and
/// with `singled` the cases singled out over every case too.
fn summary_cases<'a>(data: &'a RunData, lc: &str, singled: bool) -> Vec<&'a LoadFactorCase> {
    let bounded = study_cases(data, lc);
    let group = |c: &LoadFactorCase| c.arch();
    let chosen = bounded
        .iter()
        .find(|c| c.voussoirs.is_none())
        .or(bounded.first())
        .map(|c| group(c));
    let lattice = |c: &LoadFactorCase| {
        data.load_factors
            .binary_search_by_key(&c.row, |l| l.row)
            .is_ok()
    };
    bounded
        .into_iter()
        .filter(|c| Some(group(c)) == chosen && (singled || lattice(c)))
        .collect()
}

impl Rows {
    fn load_factor_row(&mut self, data: &RunData, label: String, c: &LoadFactorCase) {
        let Some(v) = c.load_factor else { return };
        self.push(
            format!("{label} ({})", case_text(data, c)),
            v,
            None,
            format!("results.parquet row {} load_factor", c.row),
        );
    }

    /// The weakest and strongest case of the whole study (every arch of its half-angle and
    /// voussoir axes), and λ_max at up to 3 × 3 (K, μ) of the grid: at the weakest position
    /// when a point load moves. With a half-angle or voussoir axis the table is of the
    /// continuum when the study has it (the convergence table gives every count), else of
    /// the first arch. Each case is listed once.
    pub(super) fn load_factor_summary(&mut self, data: &RunData, lc: &str, on: &str) {
        let all = study_cases(data, lc);
        let lambda = |c: &&LoadFactorCase| c.load_factor.unwrap_or(f64::NAN);
        let (Some(lo), Some(hi)) = (
            all.iter().min_by(|a, b| lambda(a).total_cmp(&lambda(b))),
            all.iter().max_by(|a, b| lambda(a).total_cmp(&lambda(b))),
        ) else {
            return;
        };
        // The table of λ over (K, μ): of the figure lattice.
        let cases = summary_cases(data, lc, false);
        let mut listed = std::collections::BTreeSet::new();
        if lo.row != hi.row {
            self.load_factor_row(data, format!("smallest λ_max of the study{on}"), lo);
            self.load_factor_row(data, format!("largest λ_max of the study{on}"), hi);
            listed.extend([lo.row, hi.row]);
        }
        let by_x = data.manifest.positions_by_x(lc);
        let moving = distinct(cases.iter().filter_map(|c| given_position(c, by_x))).len() > 1;
        if moving {
            self.refined_weakest(data, lc, on);
        }
        let ks = spread(&distinct(cases.iter().map(|c| c.k)), TABLE_SIDE);
        let mus = spread(&distinct(cases.iter().map(|c| c.mu)), TABLE_SIDE);
        for &k in &ks {
            for &mu in &mus {
                let weakest = cases
                    .iter()
                    .filter(|c| c.k == k && c.mu == mu)
                    .min_by(|a, b| lambda(a).total_cmp(&lambda(b)));
                let label = if moving {
                    format!("λ_max at the weakest load position{on}")
                } else {
                    format!("λ_max{on}")
                };
                if let Some(c) = weakest
                    && listed.insert(c.row)
                {
                    self.load_factor_row(data, label, c);
                }
            }
        }
    }

    /// The weakest position of a moving point load refined between the grid's positions:
    /// the drawn state of the study's weakest case (states.parquet), with the grid's own.
    fn refined_weakest(&mut self, data: &RunData, lc: &str, on: &str) {
        let Some((i, st)) = (data.states.iter().enumerate())
            .find(|(_, s)| s.load_case == lc && s.state == "weakest" && s.source == "case")
        else {
            return;
        };
        let (Some(v), Some(a)) = (st.load_factor, st.at_deg) else {
            return;
        };
        let grid = study_cases(data, lc)
            .into_iter()
            .find(|c| st.case_id.is_some_and(|id| id as usize == c.row));
        // A refined position is not a grid value: to a tenth of a thousandth.
        let place = match st.at_x {
            Some(x) => format!("x/L = {x:.6} ({a:.4}°)"),
            None => format!("{a:.4}°"),
        };
        let against =
            grid.and_then(|c| Some((c.load_factor?, given_position(c, st.at_x.is_some())?)));
        let against = against.map_or(String::new(), |(l, p)| {
            let p = if st.at_x.is_some() {
                given(p)
            } else {
                format!("{}°", position_deg(p))
            };
            format!("; the grid's weakest: {} at {p}", short(l))
        });
        let arch: String = grid
            .map(|c| arch_parts(data, c))
            .unwrap_or_default()
            .iter()
            .map(|p| format!(", {p}"))
            .collect();
        self.push(
            format!(
                "λ_max at the weakest load position refined between grid points{on} (K = {}, μ = {}{arch}, load at {place}{against})",
                compact(st.k),
                compact(st.mu),
            ),
            v,
            None,
            format!("states.parquet row {i} load_factor, at_deg"),
        );
    }

    /// A few of the changes of collapse mechanism located over (K, μ), spread over the table.
    pub(super) fn load_factor_changes(&mut self, data: &RunData, lc: &str, on: &str) {
        let rows: Vec<usize> = data
            .bifurcations
            .iter()
            .flatten()
            .enumerate()
            .filter(|(_, b)| b.load_case == lc)
            .map(|(i, _)| i)
            .collect();
        let idx: Vec<f64> = (0..rows.len()).map(|i| i as f64).collect();
        let total = rows.len();
        for j in spread(&idx, CHANGES) {
            let i = rows[j as usize];
            let Some(b) = data.bifurcations.as_ref().and_then(|v| v.get(i)) else {
                continue;
            };
            let g = data.bifurcation_groups.get(i);
            let extra = g.map_or(String::new(), |g| group_text(data, g));
            let along_mu = g.and_then(|g| g.axis.as_deref()) == Some("mu");
            let (q, v, col) = if along_mu {
                (format!("μ at K = {}", compact(b.k)), b.mu, "mu")
            } else {
                (format!("K at μ = {}", compact(b.mu)), b.k, "k")
            };
            self.push(
                format!(
                    "{q} where the collapse changes from {} to {}{extra}{on} ({} of {total} located)",
                    b.mechanism_a,
                    b.mechanism_b,
                    j as usize + 1
                ),
                v,
                None,
                format!("bifurcations.parquet row {i} {col}"),
            );
        }
    }
}
