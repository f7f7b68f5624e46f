//! Each sample's answer, read from its row of results.parquet, and the estimates of one grid
//! point from all of its samples.

use super::exact::{self, ExactSettings};
use crate::manifest::{Question, Sampling};
use crate::model::t_over_r_from_k;
use crate::sampling::{Z95, ecdf_band, indices, quantile_interval, wilson};
use crate::scene::{Find, Scene};
use crate::store::{self, EstimateRow};
use anyhow::Result;
use polars::prelude::DataFrame;

/// The mechanisms a sample may fail by, in display order (`none`: both domains empty).
pub const MECHANISMS: [&str; 4] = ["rotational", "mixed", "sliding", "none"];

/// Points of a stored fragility curve.
const CDF_POINTS: usize = 201;

/// The columns of one row of results.parquet that a sample's answer needs.
#[derive(Debug, Clone)]
pub struct Read {
    /// Case id.
    pub case_id: u64,
    status: Option<String>,
    outcome: Option<String>,
    regime: Option<String>,
    load_factor: Option<f64>,
    k_crit: Option<f64>,
    mechanism: Option<String>,
}

/// The rows of a block of results.parquet (a column the study's finds do not fill is not
/// stored, and reads as null).
pub fn answers(df: &DataFrame) -> Result<Vec<Read>> {
    let n = df.height();
    let s = |name: &str| -> Result<Vec<Option<String>>> {
        if df.column(name).is_err() {
            return Ok(vec![None; n]);
        }
        store::str_column(df, name)
    };
    let f = |name: &str| -> Result<Vec<Option<f64>>> {
        if df.column(name).is_err() {
            return Ok(vec![None; n]);
        }
        store::f64_column(df, name)
    };
    let ids = store::u64_column(df, "case_id")?;
    let (status, outcome, regime, mechanism) =
        (s("status")?, s("outcome")?, s("regime")?, s("mechanism")?);
    let (load_factor, k_crit) = (f("load_factor")?, f("k_crit")?);
    Ok((0..n)
        .map(|i| Read {
            case_id: ids[i],
            status: status[i].clone(),
            outcome: outcome[i].clone(),
            regime: regime[i].clone(),
            load_factor: load_factor[i],
            k_crit: k_crit[i],
            mechanism: mechanism[i].clone(),
        })
        .collect())
}

/// What one sample says.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Answer {
    /// The arch stands (at its λ; for λ_max and the margin: stands under its own weight).
    pub stands: Option<bool>,
    /// The mechanism it fails by (or of its λ_max).
    pub mechanism: Option<&'static str>,
    /// λ_max (0 when the arch does not stand under its own weight, +inf when unbounded).
    pub lambda_max: Option<f64>,
    /// The stability margin t/t_c − 1 (−1 when no thickness stands at the sample's μ).
    pub margin: Option<f64>,
    /// The analysis gave no answer.
    pub error: bool,
}

fn mechanism_name(s: Option<&str>) -> Option<&'static str> {
    MECHANISMS.into_iter().find(|m| Some(*m) == s)
}

/// The answer of a sample from its row.
fn answer(r: &Read, scene: &Scene) -> Answer {
    let failed = Answer {
        error: true,
        ..Answer::default()
    };
    if r.status.as_deref() != Some("ok") {
        return failed;
    }
    let outcome = r.outcome.as_deref();
    match scene.find {
        Find::State => match r.regime.as_deref() {
            Some("stable") => Answer {
                stands: Some(true),
                ..Answer::default()
            },
            Some(other) => Answer {
                stands: Some(false),
                mechanism: mechanism_name(Some(other)),
                ..Answer::default()
            },
            None => failed,
        },
        Find::LoadFactor => {
            let lambda = match (outcome, r.load_factor) {
                (Some("found"), Some(l)) => l,
                (Some("unbounded"), _) => f64::INFINITY,
                (Some("never_stands"), _) => 0.0,
                _ => return failed,
            };
            Answer {
                stands: Some(outcome != Some("never_stands")),
                mechanism: mechanism_name(r.mechanism.as_deref()),
                lambda_max: Some(lambda),
                ..Answer::default()
            }
        }
        Find::Thickness => {
            let t = t_over_r_from_k(scene.arch.k);
            let (margin, mechanism) = match (outcome, r.k_crit) {
                (Some("found"), Some(kc)) => (
                    t / t_over_r_from_k(kc) - 1.0,
                    mechanism_name(r.mechanism.as_deref()),
                ),
                // No thickness stands at the sample's μ: below μ_min the arch slides whatever
                // its thickness.
                (Some("never_stands"), _) => (-1.0, Some("sliding")),
                (Some("always_stands"), _) => (f64::INFINITY, None),
                _ => return failed,
            };
            Answer {
                stands: Some(margin >= 0.0),
                mechanism,
                margin: Some(margin),
                ..Answer::default()
            }
        }
        _ => failed,
    }
}

/// The samples of one grid point of one load case.
#[derive(Debug, Clone)]
pub struct Group {
    /// Index of the load case.
    pub load_case: usize,
    /// Index of the grid point.
    pub point: u64,
    /// Samples answered.
    pub ok: u64,
    /// Samples without an answer.
    pub errors: u64,
    /// Samples that do not stand.
    pub fails: u64,
    /// Of those, by mechanism ([`MECHANISMS`]).
    pub by_mechanism: [u64; 4],
    /// The mechanism of every answered λ_max (fragility), by [`MECHANISMS`].
    pub at_limit: [u64; 4],
    /// The output of every row (λ_max or the margin; NaN where none), in row order, for the
    /// fragility and sensitivity questions (empty for a probability).
    pub outputs: Vec<f64>,
    /// Whether the outputs are kept.
    keeps_outputs: bool,
    /// (n, failures among the first n rows) at n = 2, 4, 8, … (the run's own convergence).
    pub prefix: Vec<(u64, u64)>,
    /// The rows per base sample of a sensitivity design (d + 2), whose A block alone is
    /// counted in the shares.
    stride: Option<u64>,
}

impl Group {
    /// An empty group.
    pub fn new(load_case: usize, point: u64, s: &Sampling) -> Self {
        let keep = s.question != Question::Probability;
        Group {
            load_case,
            point,
            ok: 0,
            errors: 0,
            fails: 0,
            by_mechanism: [0; 4],
            at_limit: [0; 4],
            outputs: if keep {
                Vec::with_capacity(s.rows() as usize)
            } else {
                Vec::new()
            },
            keeps_outputs: keep,
            prefix: Vec::new(),
            stride: (s.question == Question::Sensitivity).then(|| s.params.len() as u64 + 2),
        }
    }

    /// Adds row `row` (rows arrive in order) and returns its answer.
    pub fn add(&mut self, row: u64, r: &Read, scene: &Scene) -> Answer {
        let a = answer(r, scene);
        if self.keeps_outputs {
            self.outputs
                .push(a.lambda_max.or(a.margin).unwrap_or(f64::NAN));
        }
        // The shares of a sensitivity design are those of its A block alone: the other
        // blocks reuse its columns and are not independent samples.
        if self.stride.is_some_and(|d| !row.is_multiple_of(d)) {
            return a;
        }
        if a.error {
            self.errors += 1;
        } else {
            self.ok += 1;
            if let (Some(_), Some(i)) = (
                a.lambda_max,
                MECHANISMS.iter().position(|m| Some(*m) == a.mechanism),
            ) {
                self.at_limit[i] += 1;
            }
            if a.stands == Some(false) {
                self.fails += 1;
                if let Some(i) = MECHANISMS.iter().position(|m| Some(*m) == a.mechanism) {
                    self.by_mechanism[i] += 1;
                }
            }
        }
        let n = row + 1;
        if n.is_power_of_two() && n >= 2 {
            self.prefix.push((n, self.fails));
        }
        a
    }

    /// The estimates of the group.
    pub fn estimates(&self, lc: &str, s: &Sampling, base: &Scene) -> Vec<EstimateRow> {
        let p = self.point;
        let mut out = vec![
            EstimateRow::value(lc, p, "samples", "", self.ok as f64),
            EstimateRow::value(lc, p, "errors", "", self.errors as f64),
        ];
        let share = |k: u64| wilson(k, self.ok, Z95);
        if self.ok > 0 {
            let i = share(self.fails);
            out.push(
                EstimateRow::value(lc, p, "probability", "", i.value).with_interval(i.lo, i.hi),
            );
            for (m, &k) in MECHANISMS.iter().zip(&self.by_mechanism) {
                let i = share(k);
                out.push(
                    EstimateRow::value(lc, p, "mechanism", m, i.value).with_interval(i.lo, i.hi),
                );
            }
        }
        if self.at_limit.iter().sum::<u64>() > 0 {
            for (m, &k) in MECHANISMS.iter().zip(&self.at_limit) {
                let i = share(k);
                out.push(
                    EstimateRow::value(lc, p, "limit_mechanism", m, i.value)
                        .with_interval(i.lo, i.hi),
                );
            }
        }
        match s.question {
            Question::Probability => out.push(exact_row(lc, p, s, base)),
            Question::Fragility => out.extend(self.fragility(lc)),
            Question::Sensitivity => out.extend(self.sensitivity(lc, s)),
        }
        out
    }

    fn fragility(&self, lc: &str) -> Vec<EstimateRow> {
        let p = self.point;
        let mut v: Vec<f64> = self
            .outputs
            .iter()
            .copied()
            .filter(|x| !x.is_nan())
            .collect();
        if v.is_empty() {
            return Vec::new();
        }
        v.sort_by(f64::total_cmp);
        let mut out = Vec::new();
        for (level, name) in [(0.05, "0.05"), (0.5, "0.5"), (0.95, "0.95")] {
            let q = quantile_interval(&v, level, Z95);
            out.push(
                EstimateRow::value(lc, p, "quantile", name, q.value).with_interval(q.lo, q.hi),
            );
        }
        let finite: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
        if !finite.is_empty() {
            // The curve at sample quantiles: evenly spread on a linear or a logarithmic axis,
            // each step of the empirical CDF where the samples are.
            let mut at: Vec<f64> = (0..CDF_POINTS)
                .map(|i| finite[i * (finite.len() - 1) / (CDF_POINTS - 1)])
                .collect();
            at.dedup();
            for (x, b) in at.iter().zip(ecdf_band(&v, &at, 0.95)) {
                out.push(
                    EstimateRow::value(lc, p, "fragility_cdf", "", b.value)
                        .with_interval(b.lo, b.hi)
                        .at(*x),
                );
            }
            // A mean of the finite values alone would say nothing where some are unbounded.
            if finite.len() == v.len() {
                let mean = finite.iter().sum::<f64>() / finite.len() as f64;
                out.push(EstimateRow::value(lc, p, "mean", "", mean));
            }
        }
        let unbounded = v.len() - finite.len();
        if unbounded > 0 {
            out.push(
                EstimateRow::value(lc, p, "unbounded", "", unbounded as f64 / v.len() as f64)
                    .noted("samples whose λ_max is unbounded (every λ ≥ 0 stands)"),
            );
        }
        out
    }

    fn sensitivity(&self, lc: &str, s: &Sampling) -> Vec<EstimateRow> {
        let p = self.point;
        let d = s.params.len();
        let stride = d + 2;
        let n = self.outputs.len() / stride;
        let col = |b: usize| -> Vec<f64> { (0..n).map(|j| self.outputs[j * stride + b]).collect() };
        let (ya, yb) = (col(0), col(1));
        let yab: Vec<Vec<f64>> = (0..d).map(|i| col(2 + i)).collect();
        let Some(ix) = indices(&ya, &yb, &yab, s.bootstrap as usize, s.seed) else {
            let why = if self.outputs.iter().any(|y| !y.is_finite()) {
                "some samples have no finite output (an analysis failed, or λ_max is unbounded)"
            } else {
                "the output does not vary over the samples"
            };
            return vec![EstimateRow::value(lc, p, "first_order", "", f64::NAN).noted(why)];
        };
        let mut out = vec![
            EstimateRow::value(lc, p, "mean", "", ix.mean),
            EstimateRow::value(lc, p, "sd", "", ix.variance.sqrt()),
        ];
        for (param, (f, t)) in s.params.iter().zip(ix.first.iter().zip(&ix.total)) {
            let name = param.name.as_str();
            out.push(
                EstimateRow::value(lc, p, "first_order", name, f.value).with_interval(f.lo, f.hi),
            );
            out.push(EstimateRow::value(lc, p, "total", name, t.value).with_interval(t.lo, t.hi));
        }
        out
    }
}

/// The exact probability of the point, or a row saying why there is none.
fn exact_row(lc: &str, p: u64, s: &Sampling, base: &Scene) -> EstimateRow {
    match exact::probability(s, base, &ExactSettings::DEFAULT) {
        Ok(e) => EstimateRow::value(lc, p, "exact_probability", "", e.value)
            .with_interval(e.value - e.error, e.value + e.error)
            .noted(format!(
                "adaptive Gauss–Kronrod quadrature over μ; thickness or friction finds: {}",
                e.evaluations
            )),
        Err(e) => EstimateRow::value(lc, p, "exact_probability", "", f64::NAN).noted(e.to_string()),
    }
}
