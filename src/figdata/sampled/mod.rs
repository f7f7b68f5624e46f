//! The figure data of a sampling study: results.parquet read a block at a time and each
//! sample's answer reduced, per load case and grid point, to what the question asks (the
//! probability of not standing and of each mechanism, the distribution of λ_max, the Sobol
//! indices of the margin), written to samples.parquet (every sample's values and answer) and
//! estimates.parquet (the estimates with their intervals, the exact probability where the
//! mechanics gives it, the convergence of the estimate with n), with the collapse curve
//! drawn under the samples in curves.parquet.

mod collapse;
pub use collapse::MU_MIN_SERIES;
mod convergence;
pub mod exact;
mod reduce;

use crate::manifest::{Manifest, ParamName, Question, Sampling};
use crate::output::RunLayout;
use crate::plan;
use crate::store::{self, EstimateRow, TableBuilder};
use anyhow::{Context, Result};
use polars::prelude::DataFrame;
pub use reduce::Answer;
use reduce::Group;

/// Figure id of the collapse curve under the samples of a load case.
pub fn samples_figure(load_case: &str) -> String {
    format!("samples/{load_case}")
}

/// Rows of results.parquet read at a time.
const READ_ROWS: usize = 1 << 16;

/// The columns of results.parquet a sample's answer is read from.
const ANSWER_COLUMNS: [&str; 7] = [
    "case_id",
    "status",
    "outcome",
    "regime",
    "load_factor",
    "k_crit",
    "mechanism",
];

/// What the stage wrote.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SampledSummary {
    /// Samples read.
    pub samples: u64,
    /// Estimate rows written.
    pub estimates: usize,
}

/// The grid points of each load case (every axis is spanned in a sampling study) and the id
/// of each load case's first case.
struct Layout {
    points: u64,
    rows: u64,
}

impl Layout {
    fn of(m: &Manifest, s: &Sampling) -> Self {
        Layout {
            points: m
                .grid
                .iter()
                .map(|a| a.values.len() as u64)
                .product::<u64>()
                * s.axis_points(),
            rows: s.rows(),
        }
    }

    /// (load case, point, row) of a case id.
    fn locate(&self, id: u64) -> (usize, u64, u64) {
        let per_lc = self.points * self.rows;
        let lc = id / per_lc;
        let rest = id % per_lc;
        (lc as usize, rest / self.rows, rest % self.rows)
    }
}

/// Runs the stage for a sampling study.
pub fn run(m: &Manifest, s: &Sampling, layout: &RunLayout) -> Result<SampledSummary> {
    let lay = Layout::of(m, s);
    let design = s.design();
    // The sampling of each grid point: its own distributions where a parameter is an axis.
    let at_point: Vec<Sampling> = (0..lay.points)
        .map(|p| s.at(&s.axis_position(p % s.axis_points())))
        .collect();
    let mut groups: Vec<Group> = (0..m.load_cases.len())
        .flat_map(|lc| (0..lay.points).map(move |p| (lc, p)))
        .map(|(lc, p)| Group::new(lc, p, s))
        .collect();
    let mut writer: Option<store::ParquetAppender> = None;
    let mut read = 0u64;
    store::read_parquet_in_blocks(&layout.results(), &ANSWER_COLUMNS, READ_ROWS, |_, df| {
        let answers = reduce::answers(df).context("reading the samples' answers")?;
        let Some(first) = answers.first().map(|a| a.case_id) else {
            return Ok(());
        };
        let slice = plan::build_slice(m.clone(), first..first + answers.len() as u64);
        let mut frame = SampleFrame::new(m, s);
        for (a, case) in answers.iter().zip(&slice.cases) {
            anyhow::ensure!(
                a.case_id == case.id,
                "results.parquet is not in plan order at case {}",
                a.case_id
            );
            let (lc, point, row) = lay.locate(a.case_id);
            let g = &mut groups[lc * lay.points as usize + point as usize];
            let values = at_point[point as usize].values(&design, row);
            let out = g.add(row, a, &case.scene);
            frame.push(m, (a, lc, point, row), &values, &out);
        }
        read += answers.len() as u64;
        let mut df = frame.finish()?;
        store::ParquetAppender::append_or_create(&mut writer, &layout.samples(), &mut df)
    })?;
    match writer {
        Some(w) => w.finish()?,
        None => store::write_parquet(&mut SampleFrame::new(m, s).finish()?, &layout.samples())?,
    }
    let mut rows = Vec::new();
    for g in &groups {
        let lc = &m.load_cases[g.load_case];
        let base = plan::build_slice(m.clone(), g.first_id(&lay)..g.first_id(&lay) + 1);
        let Some(case) = base.cases.first() else {
            continue;
        };
        rows.extend(grid_rows(m, s, lc.name.as_str(), g.point));
        rows.extend(g.estimates(&lc.name, &at_point[g.point as usize], &case.scene));
    }
    if s.question == Question::Probability {
        // The convergence of each load case at its point whose exact probability is nearest
        // ½ (where the estimate's error is largest; at 0 or 1 every estimate is exact).
        for (i, lc) in m.load_cases.iter().enumerate() {
            let exact = |g: &&Group| {
                rows.iter()
                    .find(|r| {
                        r.load_case == lc.name
                            && r.point == g.point
                            && r.quantity == "exact_probability"
                    })
                    .map(|r| r.value)
                    .filter(|v| *v > 0.0 && *v < 1.0)
            };
            let Some(g) = groups
                .iter()
                .filter(|g| g.load_case == i)
                .filter(|g| exact(g).is_some())
                .min_by(|a, b| {
                    let d = |g: &&Group| (exact(g).unwrap_or(0.0) - 0.5).abs();
                    d(a).total_cmp(&d(b))
                })
            else {
                continue;
            };
            let base = plan::build_slice(m.clone(), g.first_id(&lay)..g.first_id(&lay) + 1);
            if let Some(case) = base.cases.first() {
                let s = &at_point[g.point as usize];
                let conv = convergence::rows(s, &case.scene, &lc.name, g, &rows);
                rows.extend(conv);
            }
        }
    }
    store::write_parquet(&mut store::estimates_frame(&rows)?, &layout.estimates())?;
    Ok(SampledSummary {
        samples: read,
        estimates: rows.len(),
    })
}

/// The collapse curves drawn under the samples of each load case (x = μ, y = K).
pub fn curves(m: &Manifest, s: &Sampling) -> Vec<store::CurvePoint> {
    collapse::curves(m, s)
}

impl Group {
    /// The id of the group's first case.
    fn first_id(&self, lay: &Layout) -> u64 {
        (self.load_case as u64 * lay.points + self.point) * lay.rows
    }
}

/// The grid values of a point, one `grid` row per axis.
fn grid_rows(m: &Manifest, s: &Sampling, load_case: &str, point: u64) -> Vec<EstimateRow> {
    // The grid axes, then the distribution axes inside them: the point's odometer.
    let axes: Vec<(String, &[f64])> = (m.grid.iter())
        .map(|a| (a.name.as_str().to_string(), &a.values[..]))
        .chain(s.axes.iter().map(|a| (s.axis_name(a), &a.values[..])))
        .collect();
    let mut rest = point;
    let mut out = Vec::new();
    for (name, values) in axes.iter().rev() {
        let n = values.len() as u64;
        let v = values[(rest % n) as usize];
        rest /= n;
        out.push(EstimateRow::value(load_case, point, "grid", name, v));
    }
    out.reverse();
    out
}

/// The rows of samples.parquet for one block of results.
struct SampleFrame {
    params: Vec<ParamName>,
    /// Columns of λ_max and of the margin, when the question gives them.
    outputs: (bool, bool),
    sensitivity: Option<usize>,
    case_id: Vec<u64>,
    load_case: Vec<String>,
    point: Vec<u64>,
    sample: Vec<u64>,
    block: Vec<Option<String>>,
    values: Vec<Vec<f64>>,
    stands: Vec<Option<bool>>,
    mechanism: Vec<Option<&'static str>>,
    lambda_max: Vec<Option<f64>>,
    margin: Vec<Option<f64>>,
    status: Vec<&'static str>,
}

impl SampleFrame {
    fn new(m: &Manifest, s: &Sampling) -> Self {
        let finds = |f: crate::scene::Find| {
            m.load_cases
                .iter()
                .any(|lc| s.question.scene_find(lc.kind) == f)
        };
        SampleFrame {
            params: s.params.iter().map(|p| p.name).collect(),
            outputs: (
                finds(crate::scene::Find::LoadFactor),
                finds(crate::scene::Find::Thickness),
            ),
            sensitivity: (s.question == Question::Sensitivity).then_some(s.params.len()),
            case_id: Vec::new(),
            load_case: Vec::new(),
            point: Vec::new(),
            sample: Vec::new(),
            block: Vec::new(),
            values: vec![Vec::new(); s.params.len()],
            stands: Vec::new(),
            mechanism: Vec::new(),
            lambda_max: Vec::new(),
            margin: Vec::new(),
            status: Vec::new(),
        }
    }

    fn push(
        &mut self,
        m: &Manifest,
        (a, lc, point, row): (&reduce::Read, usize, u64, u64),
        values: &[f64],
        out: &Answer,
    ) {
        self.case_id.push(a.case_id);
        self.load_case.push(m.load_cases[lc].name.clone());
        self.point.push(point);
        match self.sensitivity {
            Some(d) => {
                let b = (row % (d as u64 + 2)) as usize;
                self.sample.push(row / (d as u64 + 2));
                self.block.push(Some(match b {
                    0 => "A".to_string(),
                    1 => "B".to_string(),
                    i => format!("AB_{}", self.params[i - 2].as_str()),
                }));
            }
            None => {
                self.sample.push(row);
                self.block.push(None);
            }
        }
        for (col, &v) in self.values.iter_mut().zip(values) {
            col.push(v);
        }
        self.stands.push(out.stands);
        self.mechanism.push(out.mechanism);
        self.lambda_max.push(out.lambda_max);
        self.margin.push(out.margin);
        self.status.push(if out.error { "error" } else { "ok" });
    }

    fn finish(self) -> Result<DataFrame> {
        let mut t = TableBuilder::new()
            .u64("case_id", self.case_id)
            .str("load_case", self.load_case)
            .u64("point", self.point)
            .u64("sample", self.sample);
        if self.sensitivity.is_some() {
            t = t.opt_str("block", self.block);
        }
        for (p, v) in self.params.iter().zip(self.values) {
            t = t.f64(p.as_str(), v);
        }
        t = t
            .opt_bool("stands", self.stands)
            .opt_str("mechanism", self.mechanism);
        if self.outputs.0 {
            t = t.opt_f64("lambda_max", self.lambda_max);
        }
        if self.outputs.1 {
            t = t.opt_f64("margin", self.margin);
        }
        t.str("status", self.status).finish()
    }
}
