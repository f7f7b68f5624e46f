//! The figure data of a run (written by `figdata`, read by the report): curves.parquet,
//! states.parquet and reference.parquet. Schemas in docs/report-files.md.

use super::rows::JointLists;
use super::{
    TableBuilder, f64_column, list_f64_column, list_str_column, read_parquet, str_column,
    u64_column,
};
use anyhow::{Context as _, Result};
use polars::prelude::DataFrame;
use std::path::Path;

/// One point of a stored curve: figure id, series name and coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvePoint {
    /// The figure the curve belongs to, e.g. `domains/scene-1`.
    pub figure: String,
    /// The series within the figure, e.g. `h_min_r_extrados`.
    pub series: String,
    /// Abscissa (unit given by the figure, see docs/report-files.md).
    pub x: f64,
    /// Ordinate (NaN marks a break in the curve).
    pub y: f64,
}

/// One drawn state: a bifurcation point or a scene of the manifest.
#[derive(Debug, Clone, PartialEq)]
pub struct StateRow {
    /// Id, also the figure stem: `bifurcation-1`, `scene-1`, ...
    pub state_id: String,
    /// `bifurcation` or `scene`.
    pub source: String,
    /// What is drawn: `bifurcation`, `minimum_thrust`, `collapse` (the collapse state at the
    /// scene's μ, when the scene itself cannot stand) or `no_equilibrium`.
    pub state: String,
    /// Load-case name.
    pub load_case: String,
    /// K of the scene as listed in the manifest (the bifurcation's K otherwise).
    pub scene_k: f64,
    /// μ of the scene as listed (+inf for infinite friction).
    pub scene_mu: f64,
    /// K of the drawn state.
    pub k: f64,
    /// t/R_c of the drawn state.
    pub t_over_r: f64,
    /// μ of the drawn state (+inf for infinite friction).
    pub mu: f64,
    /// Half-embrace angle, degrees.
    pub half_angle_deg: f64,
    /// `annular` or `centreline`.
    pub weight: String,
    /// Voussoir count, `None` for the continuum.
    pub voussoirs: Option<u32>,
    /// Regime of the scene at (scene_k, scene_mu).
    pub regime: Option<String>,
    /// Mechanism of the drawn state (`rotational/mixed` at a bifurcation).
    pub mechanism: Option<String>,
    /// Crown thrust of the drawn state over W_half.
    pub thrust_over_half_weight: Option<f64>,
    /// Crown moment of the drawn state over W_half·r.
    pub crown_moment: Option<f64>,
    /// Hinges and sliding joints of the drawn state.
    pub joints: JointLists,
    /// Lower end of H^r over W_half at the scene.
    pub thrust_r_min: Option<f64>,
    /// Upper end of H^r over W_half at the scene.
    pub thrust_r_max: Option<f64>,
    /// Lower end of H^s over W_half at the scene.
    pub thrust_s_min: Option<f64>,
    /// Upper end of H^s over W_half at the scene.
    pub thrust_s_max: Option<f64>,
}

/// The continuum value of a quantity of one discrete case, for the accuracy figure.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceRow {
    /// The case of results.parquet.
    pub case_id: u64,
    /// The results column compared, e.g. `k_crit`.
    pub quantity: String,
    /// Its value for the continuum arch with the same K, μ, geometry and load.
    pub continuum_value: Option<f64>,
    /// Wall time of the continuum analysis, µs.
    pub continuum_solve_time_us: f64,
}

/// The curves table.
pub fn curves_frame(rows: &[CurvePoint]) -> Result<DataFrame> {
    TableBuilder::new()
        .str("figure", rows.iter().map(|r| r.figure.clone()).collect())
        .str("series", rows.iter().map(|r| r.series.clone()).collect())
        .f64("x", rows.iter().map(|r| r.x).collect())
        .f64("y", rows.iter().map(|r| r.y).collect())
        .finish()
}

/// Reads curves.parquet.
pub fn read_curves(path: &Path) -> Result<Vec<CurvePoint>> {
    let df = read_parquet(path)?;
    let cx = || format!("in {}", path.display());
    let figure = str_column(&df, "figure").with_context(cx)?;
    let series = str_column(&df, "series").with_context(cx)?;
    let x = f64_column(&df, "x").with_context(cx)?;
    let y = f64_column(&df, "y").with_context(cx)?;
    Ok((0..figure.len())
        .map(|i| CurvePoint {
            figure: figure[i].clone().unwrap_or_default(),
            series: series[i].clone().unwrap_or_default(),
            x: x[i].unwrap_or(f64::NAN),
            y: y[i].unwrap_or(f64::NAN),
        })
        .collect())
}

/// The states table.
pub fn states_frame(rows: &[StateRow]) -> Result<DataFrame> {
    let s = |f: &dyn Fn(&StateRow) -> String| rows.iter().map(f).collect::<Vec<_>>();
    let f = |f: &dyn Fn(&StateRow) -> f64| rows.iter().map(f).collect::<Vec<_>>();
    let o = |f: &dyn Fn(&StateRow) -> Option<f64>| rows.iter().map(f).collect::<Vec<_>>();
    TableBuilder::new()
        .str("state_id", s(&|r| r.state_id.clone()))
        .str("source", s(&|r| r.source.clone()))
        .str("state", s(&|r| r.state.clone()))
        .str("load_case", s(&|r| r.load_case.clone()))
        .f64("scene_k", f(&|r| r.scene_k))
        .f64("scene_mu", f(&|r| r.scene_mu))
        .f64("k", f(&|r| r.k))
        .f64("t_over_r", f(&|r| r.t_over_r))
        .f64("mu", f(&|r| r.mu))
        .f64("half_angle_deg", f(&|r| r.half_angle_deg))
        .str("weight", s(&|r| r.weight.clone()))
        .opt_u32("voussoirs", rows.iter().map(|r| r.voussoirs).collect())
        .opt_str("regime", rows.iter().map(|r| r.regime.clone()).collect())
        .opt_str(
            "mechanism",
            rows.iter().map(|r| r.mechanism.clone()).collect(),
        )
        .opt_f64("thrust_over_half_weight", o(&|r| r.thrust_over_half_weight))
        .opt_f64("crown_moment", o(&|r| r.crown_moment))
        .list_f64(
            "hinge_angles_deg",
            rows.iter()
                .map(|r| r.joints.hinge_angles_deg.clone())
                .collect(),
        )
        .list_str(
            "hinge_faces",
            rows.iter().map(|r| r.joints.hinge_faces.clone()).collect(),
        )
        .list_f64(
            "sliding_angles_deg",
            rows.iter()
                .map(|r| r.joints.sliding_angles_deg.clone())
                .collect(),
        )
        .list_str(
            "sliding_senses",
            rows.iter()
                .map(|r| r.joints.sliding_senses.clone())
                .collect(),
        )
        .opt_f64("thrust_r_min", o(&|r| r.thrust_r_min))
        .opt_f64("thrust_r_max", o(&|r| r.thrust_r_max))
        .opt_f64("thrust_s_min", o(&|r| r.thrust_s_min))
        .opt_f64("thrust_s_max", o(&|r| r.thrust_s_max))
        .finish()
}

/// Reads states.parquet.
pub fn read_states(path: &Path) -> Result<Vec<StateRow>> {
    let df = read_parquet(path)?;
    let cx = || format!("in {}", path.display());
    let f = |name: &str| f64_column(&df, name).with_context(cx);
    let s = |name: &str| str_column(&df, name).with_context(cx);
    let (id, source, state, lc) = (s("state_id")?, s("source")?, s("state")?, s("load_case")?);
    let (sk, smu, k, t, mu) = (
        f("scene_k")?,
        f("scene_mu")?,
        f("k")?,
        f("t_over_r")?,
        f("mu")?,
    );
    let (half, weight, nv) = (f("half_angle_deg")?, s("weight")?, f("voussoirs")?);
    let (regime, mech) = (s("regime")?, s("mechanism")?);
    let (thrust, moment) = (f("thrust_over_half_weight")?, f("crown_moment")?);
    let ha = list_f64_column(&df, "hinge_angles_deg").with_context(cx)?;
    let hf = list_str_column(&df, "hinge_faces").with_context(cx)?;
    let sa = list_f64_column(&df, "sliding_angles_deg").with_context(cx)?;
    let ss = list_str_column(&df, "sliding_senses").with_context(cx)?;
    let (rmin, rmax, smin, smax) = (
        f("thrust_r_min")?,
        f("thrust_r_max")?,
        f("thrust_s_min")?,
        f("thrust_s_max")?,
    );
    let nan = |v: Option<f64>| v.unwrap_or(f64::NAN);
    Ok((0..id.len())
        .map(|i| StateRow {
            state_id: id[i].clone().unwrap_or_default(),
            source: source[i].clone().unwrap_or_default(),
            state: state[i].clone().unwrap_or_default(),
            load_case: lc[i].clone().unwrap_or_default(),
            scene_k: nan(sk[i]),
            scene_mu: nan(smu[i]),
            k: nan(k[i]),
            t_over_r: nan(t[i]),
            mu: nan(mu[i]),
            half_angle_deg: nan(half[i]),
            weight: weight[i].clone().unwrap_or_default(),
            voussoirs: nv[i].map(|v| v as u32),
            regime: regime[i].clone(),
            mechanism: mech[i].clone(),
            thrust_over_half_weight: thrust[i],
            crown_moment: moment[i],
            joints: JointLists {
                hinge_angles_deg: ha[i].clone(),
                hinge_faces: hf[i].clone(),
                sliding_angles_deg: sa[i].clone(),
                sliding_senses: ss[i].clone(),
            },
            thrust_r_min: rmin[i],
            thrust_r_max: rmax[i],
            thrust_s_min: smin[i],
            thrust_s_max: smax[i],
        })
        .collect())
}

/// The reference table.
pub fn reference_frame(rows: &[ReferenceRow]) -> Result<DataFrame> {
    TableBuilder::new()
        .u64("case_id", rows.iter().map(|r| r.case_id).collect())
        .str(
            "quantity",
            rows.iter().map(|r| r.quantity.clone()).collect(),
        )
        .opt_f64(
            "continuum_value",
            rows.iter().map(|r| r.continuum_value).collect(),
        )
        .f64(
            "continuum_solve_time_us",
            rows.iter().map(|r| r.continuum_solve_time_us).collect(),
        )
        .finish()
}

/// Reads reference.parquet.
pub fn read_reference(path: &Path) -> Result<Vec<ReferenceRow>> {
    let df = read_parquet(path)?;
    let cx = || format!("in {}", path.display());
    let id = u64_column(&df, "case_id").with_context(cx)?;
    let q = str_column(&df, "quantity").with_context(cx)?;
    let v = f64_column(&df, "continuum_value").with_context(cx)?;
    let t = f64_column(&df, "continuum_solve_time_us").with_context(cx)?;
    Ok((0..id.len())
        .map(|i| ReferenceRow {
            case_id: id[i],
            quantity: q[i].clone().unwrap_or_default(),
            continuum_value: v[i],
            continuum_solve_time_us: t[i].unwrap_or(f64::NAN),
        })
        .collect())
}
