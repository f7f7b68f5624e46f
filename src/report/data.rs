//! Everything a report shows, read back from the run directory: run.json, results.parquet,
//! boundaries.parquet, bifurcations.parquet and the figure data. Nothing is recomputed.

use crate::output::RunLayout;
use crate::provenance::RunInfo;
use crate::store::{
    self, BifurcationRow, BoundaryRow, CurvePoint, MechanismRow, ReferenceRow, ResultRow, StateRow,
};
use anyhow::{Context, Result};
use serde::Deserialize;
use std::path::Path;

/// The arch block of the resolved manifest in run.json.
#[derive(Debug, Clone, Deserialize)]
pub struct ArchView {
    /// `circular` or `pointed`.
    pub shape: String,
    /// Eccentricity of a pointed arch (absent for a circular one).
    #[serde(default)]
    pub eccentricity: Option<f64>,
    /// Half-embrace angle, degrees.
    pub half_angle_deg: f64,
    /// `radial` or `vertical`.
    pub joints: String,
    /// `annular` or `centreline`.
    pub weight: String,
    /// `continuum` or a voussoir count.
    pub voussoirs: serde_json::Value,
    /// The crown inside one rigid block (absent: no keystone).
    #[serde(default)]
    pub keystone: bool,
}

impl ArchView {
    /// The arch with the form of one case or state (its shape, eccentricity and joints),
    /// the manifest's other options kept: the arch of a study whose form varies along an axis.
    pub fn with_form(&self, eccentricity: Option<f64>, joints: &str) -> ArchView {
        ArchView {
            shape: if eccentricity.is_some() {
                "pointed"
            } else {
                "circular"
            }
            .into(),
            eccentricity,
            joints: joints.to_string(),
            ..self.clone()
        }
    }

    /// The voussoir count, `None` for the continuum.
    pub fn voussoir_count(&self) -> Option<u32> {
        self.voussoirs.as_u64().map(|n| n as u32)
    }
}

/// A grid axis of the resolved manifest (JSON writes infinite μ as null).
#[derive(Debug, Clone, Deserialize)]
pub struct AxisView {
    /// `k`, `t_over_r`, `mu`, `half_angle_deg`, `eccentricity`, `joints` or `voussoirs`.
    pub name: String,
    /// Values; `None` stands for +inf. The names of a `joints` axis are read as their codes
    /// ([`crate::manifest::JOINTS_RADIAL`], [`crate::manifest::JOINTS_VERTICAL`]).
    #[serde(deserialize_with = "numbers_or_joint_names")]
    pub values: Vec<Option<f64>>,
}

fn numbers_or_joint_names<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> Result<Vec<Option<f64>>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Value {
        Number(Option<f64>),
        Name(String),
    }
    Vec::<Value>::deserialize(d)?
        .into_iter()
        .map(|v| match v {
            Value::Number(x) => Ok(x),
            Value::Name(n) => crate::model::JointOrientation::parse(&n)
                .map(|j| Some(crate::manifest::axis_value_of_joints(j)))
                .ok_or_else(|| serde::de::Error::custom(format!("unknown axis value {n:?}"))),
        })
        .collect()
}

/// A load case of the resolved manifest.
#[derive(Debug, Clone, Deserialize)]
pub struct LoadCaseView {
    /// Name.
    pub name: String,
    /// Kind, e.g. `self_weight`.
    pub kind: String,
    /// What its cases compute (absent in runs stored before load cases had their own find:
    /// the study's find then).
    #[serde(default)]
    pub find: Option<String>,
    /// Position of a point load as x/L of the span, when the load case gives it so.
    #[serde(default)]
    pub at_x: Option<f64>,
    /// Width of a patch load, a fraction of the extrados span (`None`: concentrated).
    #[serde(default)]
    pub width: Option<f64>,
}

/// A scene of the resolved manifest.
#[derive(Debug, Clone, Deserialize)]
pub struct SceneView {
    /// K.
    pub k: f64,
    /// μ (`None`: infinite).
    pub mu: Option<f64>,
}

/// The resolved manifest as stored in run.json.
#[derive(Debug, Clone, Deserialize)]
pub struct ManifestView {
    /// Study name.
    pub name: String,
    /// Title.
    pub title: Option<String>,
    /// Description.
    pub description: Option<String>,
    /// Arch options.
    pub arch: ArchView,
    /// Grid axes in plan order.
    pub grid: Vec<AxisView>,
    /// Load cases.
    pub load_cases: Vec<LoadCaseView>,
    /// What each case computes.
    pub find: String,
    /// Scenes to draw.
    #[serde(default)]
    pub scenes: Vec<SceneView>,
    /// Boundary tolerance.
    pub boundary_tolerance: f64,
    /// Column width of the paper figures (`single`, `double`); runs written before the
    /// option have none and are drawn at the default.
    #[serde(default)]
    pub figure_width: Option<String>,
    /// The uncertain parameters of a sampling study.
    #[serde(default)]
    pub sampling: Option<SamplingView>,
}

/// An uncertain parameter of the resolved manifest.
#[derive(Debug, Clone, Deserialize)]
pub struct ParamView {
    /// `k`, `mu`, …
    pub name: String,
    /// `normal`, `uniform`, …
    pub distribution: String,
    /// The distribution in words, with its parameters.
    pub description: String,
}

/// The sampling of the resolved manifest.
#[derive(Debug, Clone, Deserialize)]
pub struct SamplingView {
    /// `probability`, `fragility` or `sensitivity`.
    pub question: String,
    /// The uncertain parameters.
    pub params: Vec<ParamView>,
    /// A correlation between two of them.
    #[serde(default)]
    pub correlation: Option<CorrelationView>,
    /// Samples.
    pub n: u64,
    /// `sobol`, `lhs` or `random`.
    pub method: String,
    /// Seed.
    pub seed: u64,
    /// Bootstrap resamples.
    pub bootstrap: u64,
    /// Parameters of distributions given as axes.
    #[serde(default)]
    pub axes: Vec<DistributionAxisView>,
}

/// A distribution's parameter given as an axis, in the resolved manifest.
#[derive(Debug, Clone, Deserialize)]
pub struct DistributionAxisView {
    /// Index of the uncertain parameter.
    pub param: usize,
    /// `mean`, `sd`, …
    pub field: String,
    /// Its values.
    pub values: Vec<f64>,
}

impl SamplingView {
    /// The grid points of a load case: the grid's, times the positions of the distribution
    /// axes.
    pub fn points(&self, m: &ManifestView) -> u64 {
        m.grid
            .iter()
            .map(|a| a.values.len() as u64)
            .product::<u64>()
            * self
                .axes
                .iter()
                .map(|a| a.values.len() as u64)
                .product::<u64>()
    }
}

/// A correlation of the resolved manifest.
#[derive(Debug, Clone, Deserialize)]
pub struct CorrelationView {
    /// Index of the first parameter.
    pub first: usize,
    /// Index of the second.
    pub second: usize,
    /// The correlation of their normal scores.
    pub value: f64,
}

/// A sample drawn over the (μ, K) plane, from samples.parquet.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleRow {
    /// Load case.
    pub load_case: String,
    /// μ.
    pub mu: f64,
    /// K.
    pub k: f64,
    /// `stable`, or the mechanism it fails by.
    pub outcome: String,
}

/// Samples of each load case drawn over the (μ, K) plane.
pub const SAMPLES_DRAWN: usize = 2000;

impl ManifestView {
    /// The column width of the paper figures.
    pub fn figure_width(&self) -> crate::manifest::FigureWidth {
        self.figure_width
            .as_deref()
            .and_then(crate::manifest::FigureWidth::parse)
            .unwrap_or_default()
    }
}

impl ManifestView {
    /// True for the paper's case: a semicircular arch with radial joints, annular weight, a
    /// continuum of joints and self-weight only (and no axis varying the arch).
    pub fn is_paper_case(&self) -> bool {
        self.sampling.is_none()
            && self.is_paper_geometry()
            && self.arch.voussoir_count().is_none()
            && !self
                .grid
                .iter()
                .any(|a| a.name == "voussoirs" || a.name == "half_angle_deg")
            && self.load_cases.iter().all(|l| l.kind == "self_weight")
    }

    /// What the cases of load case `lc` compute: its own find, else the study's.
    pub fn find_of(&self, lc: &str) -> &str {
        self.load_cases
            .iter()
            .find(|l| l.name == lc)
            .and_then(|l| l.find.as_deref())
            .unwrap_or(&self.find)
    }

    /// True for the paper's arch whatever its joints: semicircular, radial joints, annular
    /// weight and no half-angle axis (its continuum cases are the paper's).
    pub fn is_paper_geometry(&self) -> bool {
        self.arch.shape == "circular"
            && self.arch.joints == "radial"
            && (self.arch.half_angle_deg - 90.0).abs() < 1e-12
            && self.arch.weight == "annular"
            && !self.grid.iter().any(|a| {
                matches!(
                    a.name.as_str(),
                    "half_angle_deg" | "eccentricity" | "joints"
                )
            })
    }

    /// The axis of a name, if the grid has it.
    pub fn axis(&self, name: &str) -> Option<&AxisView> {
        self.grid.iter().find(|a| a.name == name)
    }

    /// True when the point loads of load case `lc` are placed by x/L (its own `at_x` or an
    /// `at_x` axis): their position is then the x/L given, while the joint angle found for
    /// it moves with K (or differs in its last bit from one K to the next).
    pub fn positions_by_x(&self, lc: &str) -> bool {
        self.axis("at_x").is_some()
            || self
                .load_cases
                .iter()
                .any(|l| l.name == lc && l.at_x.is_some())
    }
}

/// The position of a point load as the manifest gave it: x/L when placed by x/L
/// ([`ManifestView::positions_by_x`]), else the joint angle in degrees. Two cases whose
/// loads compare equal here carry the load at one position.
pub fn given_position(c: &store::LoadFactorCase, by_x: bool) -> Option<f64> {
    if by_x { c.at_x } else { c.at_deg }
}

/// The stored data of a run.
#[derive(Debug, Clone)]
pub struct RunData {
    /// run.json.
    pub info: RunInfo,
    /// The resolved manifest from run.json.
    pub manifest: ManifestView,
    /// The rows of results.parquet the figures are drawn from: every row, or those of the
    /// figure lattice when an axis is longer than the figures' resolution
    /// ([`FigureLattice`](super::reduce::FigureLattice)).
    pub results: Vec<ResultRow>,
    /// What the tables give over every row of results.parquet.
    pub totals: super::reduce::ResultTotals,
    /// boundaries.parquet (`None` when the run has none).
    pub boundaries: Option<Vec<BoundaryRow>>,
    /// bifurcations.parquet (`None` when the run has none).
    pub bifurcations: Option<Vec<BifurcationRow>>,
    /// curves.parquet (empty when absent).
    pub curves: Vec<CurvePoint>,
    /// states.parquet (empty when absent).
    pub states: Vec<StateRow>,
    /// reference.parquet (empty when absent).
    pub reference: Vec<ReferenceRow>,
    /// mechanisms.parquet (empty when absent).
    pub mechanisms: Vec<MechanismRow>,
    /// The load_factor cases of results.parquet with their position and mechanism, those of
    /// the figure lattice (every case when no axis is longer than the figures' resolution;
    /// empty when no load case finds a load factor).
    pub load_factors: Vec<store::LoadFactorCase>,
    /// The load_factor cases singled out over every case: the weakest, least and largest
    /// λ_max of each load case and arch group ([`crate::figdata::load_factors`]).
    pub load_factor_singled: Vec<store::LoadFactorCase>,
    /// The arch group, load position and λ of every row of bifurcations.parquet.
    pub bifurcation_groups: Vec<store::BifurcationGroup>,
    /// The arch of every row of results.parquet (empty unless the grid has a
    /// `half_angle_deg` or `voussoirs` axis).
    pub result_arches: Vec<store::RowArch>,
    /// The arch of every row of boundaries.parquet (empty as `result_arches`).
    pub boundary_arches: Vec<store::RowArch>,
    /// estimates.parquet of a sampling study (empty otherwise).
    pub estimates: Vec<store::EstimateRow>,
    /// The first samples of each load case's first grid point, when they spread over K and
    /// μ (empty otherwise).
    pub samples: Vec<SampleRow>,
}

fn optional<T>(path: &Path, read: impl Fn(&Path) -> Result<T>) -> Result<Option<T>> {
    if path.exists() {
        read(path).map(Some)
    } else {
        Ok(None)
    }
}

/// A path that is not a readable run directory.
#[derive(Debug, thiserror::Error)]
#[error("{path} is not a run directory: {reason}")]
pub struct RunDirError {
    /// The path given.
    pub path: std::path::PathBuf,
    /// What is missing or unreadable.
    pub reason: String,
}

/// Reads run.json of a run directory.
pub fn load_info(layout: &RunLayout) -> Result<RunInfo> {
    let dir = &layout.dir;
    let not_run_dir = |reason: String| RunDirError {
        path: dir.clone(),
        reason,
    };
    if !dir.is_dir() {
        return Err(not_run_dir("it does not exist or is not a directory".into()).into());
    }
    let run_json = layout.run_json();
    let text = crate::output::read_regular_text(&run_json, crate::output::MAX_RUN_JSON_BYTES)
        .map_err(|e| {
        not_run_dir(format!(
            "cannot read {} ({e}); a run directory holds the run.json that `archstudy run` writes",
            run_json.display()
        ))
    })?;
    serde_json::from_str(&text).map_err(|e| {
        not_run_dir(format!(
            "{} is not a valid run.json ({e})",
            run_json.display()
        ))
        .into()
    })
}

/// The figure lattice of a run, from its manifest.yaml (every case when it cannot be read).
fn lattice_of(layout: &RunLayout) -> super::reduce::FigureLattice {
    std::fs::read_to_string(layout.manifest())
        .ok()
        .and_then(|text| crate::manifest::parse(&text, &layout.manifest()).ok())
        .map(|m| super::reduce::FigureLattice::of(&m))
        .unwrap_or_default()
}

/// The rows of results.parquet a report keeps (every row, or those of the figure lattice),
/// checked and counted as they were read ([`read_results`]).
#[derive(Debug)]
pub struct ResultsRead {
    results: Vec<ResultRow>,
    totals: super::reduce::ResultTotals,
    /// The lattice the rows were kept by.
    lattice: super::reduce::FigureLattice,
}

/// Reads results.parquet of a run directory a block at a time, checked against `total`
/// rows (run.json's count) and reduced to the figure lattice as it is read. It needs only
/// the run's manifest and results, so a run reads them while it locates the boundaries;
/// when `stop` says so, it ends at the next block with [`Stopped`](crate::progress::Stopped).
pub fn read_results(
    layout: &RunLayout,
    total: u64,
    stop: &(dyn Fn() -> bool + Sync),
) -> Result<ResultsRead> {
    if !layout.results().is_file() {
        return Err(RunDirError {
            path: layout.dir.clone(),
            reason: format!("{} is missing", layout.results().display()),
        }
        .into());
    }
    let lattice = lattice_of(layout);
    let file = layout.results();
    let stored = store::parquet_rows(&file)?;
    super::checks::check_result_count(&file, stored, total)?;
    // Each block's rows are built in place at the end of `results` (in parallel), checked
    // and counted there, then cut down to those of the figure lattice: the kept rows are
    // written once, into pages that the next block reuses when a row is dropped.
    let block_rows = super::reduce::READ_BLOCK_ROWS;
    let mut results = Vec::with_capacity(lattice.kept().min(stored) + stored.min(block_rows));
    let mut totals = super::reduce::ResultTotals::default();
    let every = lattice.keeps_every();
    store::append_results_in_blocks(&file, block_rows, &mut results, |offset, read, start| {
        if stop() {
            return Err(crate::progress::Stopped.into());
        }
        let block = &read[start..];
        let (checked, ()) = rayon::join(
            || super::checks::check_result_rows(&file, offset, block),
            || totals.add(block),
        );
        checked?;
        if !every {
            keep_from(read, start, |r| lattice.keeps(r.case_id));
        }
        Ok(())
    })?;
    totals.finish();
    Ok(ResultsRead {
        results,
        totals,
        lattice,
    })
}

/// Reads the stored files of a run directory: results.parquet a block at a time, checked and
/// reduced to the figure lattice as it is read.
pub fn load(layout: &RunLayout) -> Result<RunData> {
    load_with(layout, None)
}

/// [`load`], with results.parquet already read by [`read_results`] when `read` is given.
pub fn load_with(layout: &RunLayout, read: Option<ResultsRead>) -> Result<RunData> {
    let info = load_info(layout)?;
    let manifest: ManifestView =
        serde_json::from_value(info.manifest.clone()).with_context(|| {
            format!(
                "{}: the `manifest` object is not valid",
                layout.run_json().display()
            )
        })?;
    let ResultsRead {
        results,
        totals,
        lattice,
    } = match read {
        Some(r) => r,
        None => read_results(layout, info.cases.total, &|| false)?,
    };
    let file = layout.results();
    let (load_factors, load_factor_singled) = if manifest.sampling.is_none()
        && manifest
            .load_cases
            .iter()
            .any(|l| manifest.find_of(&l.name) == "load_factor")
    {
        let r = crate::figdata::load_factors::LoadFactorCases::read(&file, |id| lattice.keeps(id))?;
        let singled = r.singled();
        (r.kept, singled)
    } else {
        (Vec::new(), Vec::new())
    };
    let arch_axis = manifest.grid.iter().any(|a| {
        matches!(
            a.name.as_str(),
            "voussoirs" | "half_angle_deg" | "eccentricity" | "joints"
        )
    });
    let (result_arches, boundary_arches) = if arch_axis {
        // Rows are in case-id order (checked above): the arch of row i is case i's.
        let arches = store::read_row_arches(&layout.results())?;
        (
            arches
                .into_iter()
                .enumerate()
                .filter(|(i, _)| lattice.keeps(*i as u64))
                .map(|(_, a)| a)
                .collect(),
            optional(&layout.boundaries(), store::read_row_arches)?.unwrap_or_default(),
        )
    } else {
        (Vec::new(), Vec::new())
    };
    let samples = match &manifest.sampling {
        Some(s) => read_samples(layout, &manifest, s)?,
        None => Vec::new(),
    };
    let data = RunData {
        info,
        manifest,
        results,
        totals,
        boundaries: optional(&layout.boundaries(), store::read_boundaries)?,
        bifurcations: optional(&layout.bifurcations(), store::read_bifurcations)?,
        curves: optional(&layout.curves(), store::read_curves)?.unwrap_or_default(),
        states: optional(&layout.states(), store::read_states)?.unwrap_or_default(),
        reference: optional(&layout.reference(), store::read_reference)?.unwrap_or_default(),
        mechanisms: optional(&layout.mechanisms(), store::read_mechanisms)?.unwrap_or_default(),
        load_factors,
        load_factor_singled,
        bifurcation_groups: optional(&layout.bifurcations(), store::read_bifurcation_groups)?
            .unwrap_or_default(),
        result_arches,
        boundary_arches,
        estimates: optional(&layout.estimates(), store::read_estimates)?.unwrap_or_default(),
        samples,
    };
    super::checks::check_tables(&layout.dir, &data)?;
    Ok(data)
}

/// Keeps, of the rows from `start` on, those `keep` accepts, in order (the rows before
/// `start` are left as they are).
fn keep_from<T>(rows: &mut Vec<T>, start: usize, keep: impl Fn(&T) -> bool) {
    let mut kept = start;
    for i in start..rows.len() {
        if keep(&rows[i]) {
            rows.swap(kept, i);
            kept += 1;
        }
    }
    rows.truncate(kept);
}

impl RunData {
    /// The points of one series of one stored figure, in stored order.
    pub fn curve(&self, figure: &str, series: &str) -> Vec<(f64, f64)> {
        self.curves
            .iter()
            .filter(|c| c.figure == figure && c.series == series)
            .map(|c| (c.x, c.y))
            .collect()
    }

    /// The bifurcations of a load case.
    pub fn bifurcations_of(&self, load_case: &str) -> Vec<&BifurcationRow> {
        self.bifurcations
            .iter()
            .flatten()
            .filter(|b| b.load_case == load_case)
            .collect()
    }

    /// The boundary points of a load case.
    pub fn boundaries_of(&self, load_case: &str) -> Vec<&BoundaryRow> {
        self.boundaries
            .iter()
            .flatten()
            .filter(|b| b.load_case == load_case)
            .collect()
    }
}

/// The first [`SAMPLES_DRAWN`] samples of each load case's first grid point from
/// samples.parquet, when the samples spread over the thickness and μ.
fn read_samples(layout: &RunLayout, m: &ManifestView, s: &SamplingView) -> Result<Vec<SampleRow>> {
    let has = |n: &str| s.params.iter().any(|p| p.name == n);
    let thickness = if has("k") {
        "k"
    } else if has("t_over_r") {
        "t_over_r"
    } else {
        return Ok(Vec::new());
    };
    if !has("mu") || !layout.samples().is_file() {
        return Ok(Vec::new());
    }
    let per_point = if s.question == "sensitivity" {
        s.n * (s.params.len() as u64 + 2)
    } else {
        s.n
    };
    let points = s.points(m);
    let mut out = Vec::new();
    for (i, lc) in m.load_cases.iter().enumerate() {
        let first = i as u64 * points * per_point;
        let len = SAMPLES_DRAWN.min(per_point as usize);
        let df = store::read_parquet_rows(
            &layout.samples(),
            &[thickness, "mu", "stands", "mechanism", "block"],
            Some((first as usize, len)),
        )?;
        // A sensitivity design's samples are its A block; the others mix its columns.
        let block = if df.column("block").is_ok() {
            store::str_column(&df, "block")?
        } else {
            vec![None; df.height()]
        };
        let t = store::f64_column(&df, thickness)?;
        let mu = store::f64_column(&df, "mu")?;
        let stands = store::bool_column(&df, "stands")?;
        let mech = store::str_column(&df, "mechanism")?;
        // A sample that finds λ_max is drawn by the mechanism of its λ_max.
        let limit = s.question != "probability" && lc.kind != "self_weight";
        for j in 0..df.height() {
            let (Some(t), Some(mu), Some(st)) = (t[j], mu[j], stands[j]) else {
                continue;
            };
            if block[j].as_deref().is_some_and(|b| b != "A") {
                continue;
            }
            let outcome = match (st, limit) {
                (true, false) => "stable".to_string(),
                (false, true) => "none".to_string(),
                _ => mech[j].clone().unwrap_or_else(|| "none".into()),
            };
            let k = if thickness == "k" {
                t
            } else {
                crate::model::k_from_t_over_r(t)
            };
            out.push(SampleRow {
                load_case: lc.name.clone(),
                mu,
                k,
                outcome,
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::keep_from;

    #[test]
    fn rows_are_cut_back_to_those_kept_from_the_start_of_a_block_on() {
        let mut rows: Vec<u32> = (0..10).collect();
        // The rows before the block stay whatever `keep` says of them.
        keep_from(&mut rows, 3, |r| r % 2 == 0);
        assert_eq!(rows, [0, 1, 2, 4, 6, 8]);
        keep_from(&mut rows, 6, |_| false);
        assert_eq!(rows, [0, 1, 2, 4, 6, 8]);
        keep_from(&mut rows, 0, |&r| r > 3);
        assert_eq!(rows, [4, 6, 8]);
    }
}
