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

/// One drawn state: a bifurcation point, a scene of the manifest or the limit state of a
/// case.
#[derive(Debug, Clone, PartialEq, Default)]
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
    /// `circular` or `pointed`.
    pub shape: String,
    /// Eccentricity e of a pointed arch (0 for a circular one).
    pub eccentricity: f64,
    /// Orientation of the joints: `radial` or `vertical`.
    pub joint_orientation: String,
    /// True when the form asks for a keystone (`ArchForm::keystone`).
    pub keystone: bool,
    /// Kind of the load case: `self_weight`, `horizontal` or `point`.
    pub load: String,
    /// Position of the point load, degrees from the crown (`None` for other loads).
    pub at_deg: Option<f64>,
    /// Position of the point load as x/L when it was given so (`None` when given by its
    /// angle, for other loads, and in runs written before it was stored): the drawing
    /// places the load at this extrados point, which on the springing wedge of a
    /// vertical-joint arch the angle (±α there) does not name.
    pub at_x: Option<f64>,
    /// Width of a point load spread over the extrados, as a fraction of the span (`None`
    /// for other loads and for a concentrated one).
    pub load_width: Option<f64>,
    /// Load factor λ of the live load at the drawn state (`None` for self-weight alone).
    pub load_factor: Option<f64>,
    /// Regime of the scene at (scene_k, scene_mu).
    pub regime: Option<String>,
    /// Mechanism of the drawn state (`rotational/mixed` at a bifurcation).
    pub mechanism: Option<String>,
    /// Crown thrust of the drawn state over W_half.
    pub thrust_over_half_weight: Option<f64>,
    /// Crown moment of the drawn state over W_half·r.
    pub crown_moment: Option<f64>,
    /// Vertical force at the crown of the drawn state over W_half (zero for a symmetric
    /// state; `None` in runs stored before it was recorded).
    pub crown_shear: Option<f64>,
    /// The case of results.parquet the state is the limit state of (`None` for a
    /// bifurcation or a scene).
    pub case_id: Option<u32>,
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

/// One row of mechanisms.parquet: one mechanism at one bifurcation under one flow rule.
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismRow {
    /// The drawn state of the bifurcation in states.parquet (`bifurcation-1`, ...).
    pub state_id: String,
    /// Load case.
    pub load_case: String,
    /// Index of the bifurcation in bifurcations.parquet among those of its load case, from 1.
    pub bifurcation: u32,
    /// K and μ of the bifurcation.
    pub k: f64,
    /// μ of the bifurcation.
    pub mu: f64,
    /// `rotational`, `mixed` or `sliding` (of the velocity field), or `none`.
    pub mechanism: String,
    /// `non_associative` (pure sliding, the paper's) or `associative` (dilatancy tan φ).
    pub flow_rule: String,
    /// dL^(a) over W_half·r.
    pub work_loads: f64,
    /// dL^(r,n) over W_half·r: zero for pure sliding, μ R^n |dr^t| summed under the
    /// associative rule.
    pub work_normal: f64,
    /// dL^(r,t) over W_half·r.
    pub work_friction: f64,
    /// Relative residual of the virtual-work balance dL^(a) + dL^(r,n) + dL^(r,t) = 0
    /// (eq. 11; dL^(r,n) = 0 for the non-associative rule).
    pub work_residual: f64,
    /// Degrees of freedom of the compatibility system at the state.
    pub dof: u32,
    /// Sliding joints of the mechanism: angle from the crown, degrees.
    pub sliding_angles_deg: Vec<f64>,
    /// Their slip δr^t (normalised field).
    pub slip: Vec<f64>,
    /// Their normal separation (zero for pure sliding).
    pub dilatancy: Vec<f64>,
    /// The drawing (blocks before and after, hinges, slides, supports) as JSON.
    pub drawing_json: String,
}

/// The mechanisms table.
pub fn mechanisms_frame(rows: &[MechanismRow]) -> Result<DataFrame> {
    TableBuilder::new()
        .str(
            "state_id",
            rows.iter().map(|r| r.state_id.clone()).collect(),
        )
        .str(
            "load_case",
            rows.iter().map(|r| r.load_case.clone()).collect(),
        )
        .u64(
            "bifurcation",
            rows.iter().map(|r| u64::from(r.bifurcation)).collect(),
        )
        .f64("k", rows.iter().map(|r| r.k).collect())
        .f64("mu", rows.iter().map(|r| r.mu).collect())
        .str(
            "mechanism",
            rows.iter().map(|r| r.mechanism.clone()).collect(),
        )
        .str(
            "flow_rule",
            rows.iter().map(|r| r.flow_rule.clone()).collect(),
        )
        .f64("work_loads", rows.iter().map(|r| r.work_loads).collect())
        .f64("work_normal", rows.iter().map(|r| r.work_normal).collect())
        .f64(
            "work_friction",
            rows.iter().map(|r| r.work_friction).collect(),
        )
        .f64(
            "work_residual",
            rows.iter().map(|r| r.work_residual).collect(),
        )
        .u64("dof", rows.iter().map(|r| u64::from(r.dof)).collect())
        .list_f64(
            "sliding_angles_deg",
            rows.iter().map(|r| r.sliding_angles_deg.clone()).collect(),
        )
        .list_f64("slip", rows.iter().map(|r| r.slip.clone()).collect())
        .list_f64(
            "dilatancy",
            rows.iter().map(|r| r.dilatancy.clone()).collect(),
        )
        .str(
            "drawing_json",
            rows.iter().map(|r| r.drawing_json.clone()).collect(),
        )
        .finish()
}

/// Reads mechanisms.parquet.
pub fn read_mechanisms(path: &Path) -> Result<Vec<MechanismRow>> {
    let df = read_parquet(path)?;
    let cx = || format!("in {}", path.display());
    let f = |name: &str| f64_column(&df, name).with_context(cx);
    let s = |name: &str| str_column(&df, name).with_context(cx);
    let (id, lc, mech, rule, json) = (
        s("state_id")?,
        s("load_case")?,
        s("mechanism")?,
        s("flow_rule")?,
        s("drawing_json")?,
    );
    let bif = u64_column(&df, "bifurcation").with_context(cx)?;
    let dof = u64_column(&df, "dof").with_context(cx)?;
    let (k, mu) = (f("k")?, f("mu")?);
    let (wl, wf, wr) = (f("work_loads")?, f("work_friction")?, f("work_residual")?);
    let wn = f("work_normal")?;
    let sa = list_f64_column(&df, "sliding_angles_deg").with_context(cx)?;
    let slip = list_f64_column(&df, "slip").with_context(cx)?;
    let dil = list_f64_column(&df, "dilatancy").with_context(cx)?;
    let nan = |v: Option<f64>| v.unwrap_or(f64::NAN);
    Ok((0..id.len())
        .map(|i| MechanismRow {
            state_id: id[i].clone().unwrap_or_default(),
            load_case: lc[i].clone().unwrap_or_default(),
            bifurcation: u32::try_from(bif[i]).unwrap_or(u32::MAX),
            k: nan(k[i]),
            mu: nan(mu[i]),
            mechanism: mech[i].clone().unwrap_or_default(),
            flow_rule: rule[i].clone().unwrap_or_default(),
            work_loads: nan(wl[i]),
            work_normal: nan(wn[i]),
            work_friction: nan(wf[i]),
            work_residual: nan(wr[i]),
            dof: u32::try_from(dof[i]).unwrap_or(u32::MAX),
            sliding_angles_deg: sa[i].clone(),
            slip: slip[i].clone(),
            dilatancy: dil[i].clone(),
            drawing_json: json[i].clone().unwrap_or_default(),
        })
        .collect())
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
        .str("shape", s(&|r| r.shape.clone()))
        .f64("eccentricity", f(&|r| r.eccentricity))
        .str("joint_orientation", s(&|r| r.joint_orientation.clone()))
        .bool("keystone", rows.iter().map(|r| r.keystone).collect())
        .str("load", s(&|r| r.load.clone()))
        .opt_f64("at_deg", o(&|r| r.at_deg))
        .opt_f64("at_x", o(&|r| r.at_x))
        .opt_f64("load_width", o(&|r| r.load_width))
        .opt_f64("load_factor", o(&|r| r.load_factor))
        .opt_str("regime", rows.iter().map(|r| r.regime.clone()).collect())
        .opt_str(
            "mechanism",
            rows.iter().map(|r| r.mechanism.clone()).collect(),
        )
        .opt_f64("thrust_over_half_weight", o(&|r| r.thrust_over_half_weight))
        .opt_f64("crown_moment", o(&|r| r.crown_moment))
        .opt_f64("crown_shear", o(&|r| r.crown_shear))
        .opt_u32("case_id", rows.iter().map(|r| r.case_id).collect())
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
    let arch = StateArchColumns::read(&df);
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
            shape: arch.shape[i].clone().unwrap_or_else(|| "circular".into()),
            eccentricity: arch.eccentricity[i].unwrap_or(0.0),
            joint_orientation: arch.joints[i].clone().unwrap_or_else(|| "radial".into()),
            keystone: arch.keystone[i].unwrap_or(false),
            load: arch.load[i].clone().unwrap_or_else(|| "self_weight".into()),
            at_deg: arch.at_deg[i],
            at_x: arch.at_x[i],
            load_width: arch.load_width[i],
            load_factor: arch.load_factor[i],
            regime: regime[i].clone(),
            mechanism: mech[i].clone(),
            thrust_over_half_weight: thrust[i],
            crown_moment: moment[i],
            crown_shear: arch.crown_shear[i],
            case_id: arch.case_id[i].map(|v| v as u32),
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

/// A numeric column that older run directories may lack: all null then.
fn f64_or_null(df: &DataFrame, name: &str) -> Vec<Option<f64>> {
    f64_column(df, name).unwrap_or_else(|_| vec![None; df.height()])
}

/// A string column that older run directories may lack: all null then.
/// The joint planes of a stored `joints` value (radial where the table has none).
fn joints_or_radial(v: &Option<String>) -> crate::model::JointOrientation {
    v.as_deref()
        .and_then(crate::model::JointOrientation::parse)
        .unwrap_or_default()
}

fn str_or_null(df: &DataFrame, name: &str) -> Vec<Option<String>> {
    str_column(df, name).unwrap_or_else(|_| vec![None; df.height()])
}

/// The columns of states.parquet naming the arch form and the load (absent from run
/// directories written before they were added: read as the semicircle under self-weight).
struct StateArchColumns {
    shape: Vec<Option<String>>,
    eccentricity: Vec<Option<f64>>,
    joints: Vec<Option<String>>,
    keystone: Vec<Option<bool>>,
    load: Vec<Option<String>>,
    at_deg: Vec<Option<f64>>,
    at_x: Vec<Option<f64>>,
    load_width: Vec<Option<f64>>,
    load_factor: Vec<Option<f64>>,
    crown_shear: Vec<Option<f64>>,
    case_id: Vec<Option<f64>>,
}

impl StateArchColumns {
    fn read(df: &DataFrame) -> Self {
        StateArchColumns {
            shape: str_or_null(df, "shape"),
            eccentricity: f64_or_null(df, "eccentricity"),
            joints: str_or_null(df, "joint_orientation"),
            keystone: super::bool_column(df, "keystone")
                .unwrap_or_else(|_| vec![None; df.height()]),
            load: str_or_null(df, "load"),
            at_deg: f64_or_null(df, "at_deg"),
            at_x: f64_or_null(df, "at_x"),
            load_width: f64_or_null(df, "load_width"),
            load_factor: f64_or_null(df, "load_factor"),
            crown_shear: f64_or_null(df, "crown_shear"),
            case_id: f64_or_null(df, "case_id"),
        }
    }
}

/// The arch group and load of one row of bifurcations.parquet: the columns that say on which
/// arch and under which load the bifurcation was found.
#[derive(Debug, Clone, PartialEq)]
pub struct BifurcationGroup {
    /// Half-embrace angle α, degrees (`None` when the table lacks the column).
    pub half_angle_deg: Option<f64>,
    /// Voussoir count: `Some(None)` for the continuum, `None` when the table lacks the column.
    pub voussoirs: Option<Option<u32>>,
    /// Position of the point load, degrees from the crown.
    pub at_deg: Option<f64>,
    /// Position of the point load given as x/L.
    pub at_x: Option<f64>,
    /// λ_max at the bifurcation (load_factor studies).
    pub load_factor: Option<f64>,
    /// `k` or `mu`: the grid edge along which a change of mechanism was located (general
    /// route), `None` on the symmetric collapse curve.
    pub axis: Option<String>,
    /// Eccentricity of a pointed arch (`None` for a circular one, and when the table lacks
    /// the column).
    pub eccentricity: Option<f64>,
    /// Joint planes (`None` when the table lacks the column).
    pub joints: Option<String>,
}

/// Reads the arch group and load of every row of bifurcations.parquet, in table order.
pub fn read_bifurcation_groups(path: &Path) -> Result<Vec<BifurcationGroup>> {
    Ok(bifurcation_groups_of_frame(&read_parquet(path)?))
}

/// The arch group and load of every row of a bifurcations frame, in table order.
pub fn bifurcation_groups_of_frame(df: &polars::prelude::DataFrame) -> Vec<BifurcationGroup> {
    let has = |name: &str| df.column(name).is_ok();
    let half = f64_or_null(df, "half_angle_deg");
    let nv = f64_or_null(df, "voussoirs");
    let at = f64_or_null(df, "at_deg");
    let at_x = f64_or_null(df, "at_x");
    let lf = f64_or_null(df, "load_factor");
    let has_voussoirs = has("voussoirs");
    let axis = str_or_null(df, "axis");
    let e = f64_or_null(df, "eccentricity");
    let joints = str_or_null(df, "joints");
    (0..df.height())
        .map(|i| BifurcationGroup {
            half_angle_deg: half[i],
            voussoirs: has_voussoirs.then(|| nv[i].map(|v| v as u32)),
            at_deg: at[i],
            at_x: at_x[i],
            load_factor: lf[i],
            axis: axis[i].clone(),
            eccentricity: e[i],
            joints: joints[i].clone(),
        })
        .collect()
}

impl LoadFactorCase {
    /// The arch of the case, as the arch axes vary it.
    pub fn arch(&self) -> RowArch {
        RowArch {
            half_angle_deg: self.half_angle_deg,
            voussoirs: self.voussoirs,
            eccentricity: self.eccentricity,
            joints: self.joints,
        }
    }
}

/// The arch of one row of results.parquet or boundaries.parquet: its half-angle, voussoir
/// count, eccentricity and joint planes (what varies along the arch axes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RowArch {
    /// Half-embrace angle α, degrees (90 when the table lacks the column).
    pub half_angle_deg: f64,
    /// Voussoir count, `None` for the continuum.
    pub voussoirs: Option<u32>,
    /// Eccentricity of a pointed arch, `None` for a circular one (or a table without the
    /// column).
    pub eccentricity: Option<f64>,
    /// Joint planes (radial when the table lacks the column).
    pub joints: crate::model::JointOrientation,
}

/// Reads the arch of every row of results.parquet or boundaries.parquet, in table order
/// (only those columns are read).
pub fn read_row_arches(path: &Path) -> Result<Vec<RowArch>> {
    let df = super::read_parquet_columns(
        path,
        &["half_angle_deg", "voussoirs", "eccentricity", "joints"],
    )?;
    let half = f64_or_null(&df, "half_angle_deg");
    let nv = f64_or_null(&df, "voussoirs");
    let e = f64_or_null(&df, "eccentricity");
    let joints = str_or_null(&df, "joints");
    Ok((0..df.height())
        .map(|i| RowArch {
            half_angle_deg: half[i].unwrap_or(90.0),
            voussoirs: nv[i].map(|v| v as u32),
            eccentricity: e[i],
            joints: joints_or_radial(&joints[i]),
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

/// One case of a load_factor study as its figures need it: the parameters that may vary and
/// the collapse load factor with its mechanism (from results.parquet).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadFactorCase {
    /// Row of results.parquet.
    pub row: usize,
    /// Load case.
    pub load_case: String,
    /// K = R/r.
    pub k: f64,
    /// μ (+inf for infinite friction).
    pub mu: f64,
    /// Half-embrace angle, degrees.
    pub half_angle_deg: f64,
    /// Voussoir count, `None` for the continuum.
    pub voussoirs: Option<u32>,
    /// Eccentricity of a pointed arch, `None` for a circular one.
    pub eccentricity: Option<f64>,
    /// Joint planes.
    pub joints: crate::model::JointOrientation,
    /// Position of the point load, degrees from the crown.
    pub at_deg: Option<f64>,
    /// Position of the point load as x/L (`None` in runs written before it was stored).
    pub at_x: Option<f64>,
    /// λ_max, multiples of the total weight (`None` when unbounded or not found).
    pub load_factor: Option<f64>,
    /// Collapse mechanism at λ_max.
    pub mechanism: Option<String>,
    /// The collapse, the first complete solution, when it comes before λ_max (a gap);
    /// `None` without a gap or in runs written before it was stored.
    pub collapse_below: Option<f64>,
    /// How many sliding joints of the mechanism at λ_max lie at the point load's joint
    /// (within [`AT_LOAD_TOL_DEG`]): two on the continuum are both sides of the load, a
    /// sliver of zero width punched through the arch.
    pub sliding_at_load: u8,
}

/// Joint angles within this of a point load's angle, degrees, are joints at the load: both
/// sides of a load on the continuum are joints whose angles differ in the last bits.
pub const AT_LOAD_TOL_DEG: f64 = 1e-9;

/// The columns of results.parquet read into [`LoadFactorCase`].
const LOAD_FACTOR_COLUMNS: [&str; 15] = [
    "load_case",
    "find",
    "k",
    "mu",
    "half_angle_deg",
    "voussoirs",
    "eccentricity",
    "joints",
    "at_deg",
    "at_x",
    "load_factor",
    "mechanism",
    "collapse_value",
    "gap_width",
    "sliding_angles_deg",
];

/// Reads the load_factor cases of results.parquet (rows of other finds are skipped).
pub fn read_load_factor_cases(path: &Path) -> Result<Vec<LoadFactorCase>> {
    let df = super::read_parquet_columns(path, &LOAD_FACTOR_COLUMNS)?;
    load_factor_cases_of_frame(&df, 0, path)
}

/// [`read_load_factor_cases`] a block of `block` rows at a time: `each` is given the
/// load_factor cases of each block in order (only the block's row groups are decoded), so
/// that a reduction of them holds one block.
pub fn read_load_factor_cases_in_blocks(
    path: &Path,
    block: usize,
    mut each: impl FnMut(Vec<LoadFactorCase>) -> Result<()>,
) -> Result<()> {
    super::read_parquet_in_blocks(path, &LOAD_FACTOR_COLUMNS, block, |offset, df| {
        each(load_factor_cases_of_frame(df, offset, path)?)
    })
}

/// The load_factor cases of a frame of results.parquet whose first row is `first_row`.
fn load_factor_cases_of_frame(
    df: &DataFrame,
    first_row: usize,
    path: &Path,
) -> Result<Vec<LoadFactorCase>> {
    let cx = || format!("in {}", path.display());
    let f = |name: &str| f64_column(df, name).with_context(cx);
    let s = |name: &str| str_column(df, name).with_context(cx);
    let (lc, find, mech) = (s("load_case")?, s("find")?, s("mechanism")?);
    let (k, mu, half) = (f("k")?, f("mu")?, f("half_angle_deg")?);
    let (nv, at, lf) = (f("voussoirs")?, f("at_deg")?, f("load_factor")?);
    let at_x = f64_or_null(df, "at_x");
    let e = f64_or_null(df, "eccentricity");
    let joints = str_or_null(df, "joints");
    let (collapse, width) = (
        f64_or_null(df, "collapse_value"),
        f64_or_null(df, "gap_width"),
    );
    let slides = super::list_f64_column(df, "sliding_angles_deg").with_context(cx)?;
    let at_load = |i: usize| -> u8 {
        let Some(a) = at[i] else { return 0 };
        let n = slides[i]
            .iter()
            .filter(|s| (*s - a).abs() <= AT_LOAD_TOL_DEG)
            .count();
        u8::try_from(n).unwrap_or(u8::MAX)
    };
    Ok((0..lc.len())
        .filter(|&i| find[i].as_deref() == Some("load_factor"))
        .map(|i| LoadFactorCase {
            row: first_row + i,
            load_case: lc[i].clone().unwrap_or_default(),
            k: k[i].unwrap_or(f64::NAN),
            mu: mu[i].unwrap_or(f64::NAN),
            half_angle_deg: half[i].unwrap_or(90.0),
            voussoirs: nv[i].map(|v| v as u32),
            eccentricity: e[i],
            joints: joints_or_radial(&joints[i]),
            at_deg: at[i],
            at_x: at_x[i],
            load_factor: lf[i],
            mechanism: mech[i].clone(),
            collapse_below: collapse[i].filter(|_| width[i].is_some_and(|w| w > 0.0)),
            sliding_at_load: at_load(i),
        })
        .collect())
}
