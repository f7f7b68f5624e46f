//! The figure-data stage of a run: everything a figure needs that comes from evaluating the
//! statics, computed once at run time and stored (curves.parquet, states.parquet,
//! reference.parquet; schemas in docs/report-files.md), so that the report only reads.
//!
//! It runs after the results and the boundaries are stored, reads the bifurcations from
//! bifurcations.parquet (when present) and uses the manifest for the arch and the scenes.

pub mod curves;
pub mod mechanisms;
mod reference;
pub use reference::find_of_quantity;

use crate::analysis::symmetric;
use crate::manifest::{AxisName, Manifest};
use crate::model::{Arch, Friction};
use crate::output::RunLayout;
use crate::plan::Plan;
use crate::store::{self, BifurcationRow, CurvePoint, JointLists, StateRow};
use anyhow::{Context, Result};
use curves::Samples;

/// Figure id of the Fig. 2 curves of a state.
pub fn domains_figure(state_id: &str) -> String {
    format!("domains/{state_id}")
}

/// Figure id of the line of thrust of a state.
pub fn line_of_thrust_figure(state_id: &str) -> String {
    format!("line_of_thrust/{state_id}")
}

/// Figure id of the critical curves of a load case.
pub fn critical_figure(load_case: &str) -> String {
    format!("critical/{load_case}")
}

/// Series of K_c(μ) (x = μ, y = K) in the critical figure.
pub const K_CRIT_OF_MU: &str = "k_crit_of_mu";
/// Series of μ_c(K) (x = K, y = μ) in the critical figure.
pub const MU_CRIT_OF_K: &str = "mu_crit_of_k";
/// Series of the line of thrust (x, y over r).
pub const LINE_OF_THRUST: &str = "line_of_thrust";

/// Samples of each critical curve.
const CRITICAL_SAMPLES: usize = 161;

/// What the stage wrote.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FigureDataSummary {
    /// Drawn states.
    pub states: usize,
    /// Curve points.
    pub curve_points: usize,
    /// Continuum reference values.
    pub references: usize,
    /// Mechanisms at the bifurcations.
    pub mechanisms: usize,
}

struct Collector {
    points: Vec<CurvePoint>,
}

impl Collector {
    fn push(&mut self, figure: &str, series: &str, s: &Samples) {
        self.points.extend(s.iter().map(|&(x, y)| CurvePoint {
            figure: figure.to_string(),
            series: series.to_string(),
            x,
            y,
        }));
    }
}

fn suffix(manifest: &Manifest, load_case: &str) -> String {
    if manifest.load_cases.len() > 1 {
        format!("-{load_case}")
    } else {
        String::new()
    }
}

fn base_arch(manifest: &Manifest, k: f64) -> Result<Arch> {
    let a = &manifest.arch;
    Arch::new(k, a.half_angle_deg, a.weight, a.voussoirs)
        .with_context(|| format!("the arch of the manifest with K = {k}"))
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// The state drawn for a bifurcation, with its line of thrust.
fn bifurcation_state(
    manifest: &Manifest,
    id: String,
    b: &BifurcationRow,
    out: &mut Collector,
) -> Result<StateRow> {
    let arch = base_arch(manifest, b.k)?;
    if let (Some(h), Some(m)) = (b.thrust_over_half_weight, b.crown_moment) {
        out.push(
            &line_of_thrust_figure(&id),
            LINE_OF_THRUST,
            &curves::line_of_thrust(&arch, h, m),
        );
    }
    Ok(StateRow {
        state_id: id,
        source: "bifurcation".into(),
        state: "bifurcation".into(),
        load_case: b.load_case.clone(),
        scene_k: b.k,
        scene_mu: b.mu,
        k: b.k,
        t_over_r: b.t_over_r,
        mu: b.mu,
        half_angle_deg: manifest.arch.half_angle_deg,
        weight: manifest.arch.weight.as_str().into(),
        voussoirs: manifest.arch.voussoirs.voussoirs(),
        regime: None,
        mechanism: Some(format!("{}/{}", b.mechanism_a, b.mechanism_b)),
        thrust_over_half_weight: b.thrust_over_half_weight,
        crown_moment: b.crown_moment,
        joints: b.joints.clone(),
        thrust_r_min: None,
        thrust_r_max: None,
        thrust_s_min: None,
        thrust_s_max: None,
    })
}

fn joint_lists(
    hinges: &[crate::analysis::Hinge],
    sl: &[crate::analysis::SlidingJoint],
) -> JointLists {
    JointLists {
        hinge_angles_deg: hinges.iter().map(|h| h.angle_deg).collect(),
        hinge_faces: hinges.iter().map(|h| h.face.as_str().to_string()).collect(),
        sliding_angles_deg: sl.iter().map(|s| s.angle_deg).collect(),
        sliding_senses: sl.iter().map(|s| s.sense.as_str().to_string()).collect(),
    }
}

/// The state drawn for a manifest scene: its minimum-thrust state when it stands, else the
/// collapse state at its μ (at K_c(μ)), else nothing; with the curves of Fig. 2.
fn scene_state(
    manifest: &Manifest,
    id: String,
    load_case: &str,
    k: f64,
    mu: f64,
    out: &mut Collector,
) -> Result<StateRow> {
    let arch = base_arch(manifest, k)?;
    let friction = Friction::new(mu).unwrap_or(Friction::INFINITE);
    let report = symmetric::state(&arch, friction);
    let (r, s) = (
        report.domains.rotational.interval,
        report.domains.sliding.interval,
    );
    let c = curves::domain_curves(&arch, friction);
    let fig = domains_figure(&id);
    out.push(&fig, "h_min_r_extrados", &c.h_min_r_extrados);
    out.push(&fig, "h_max_r_extrados", &c.h_max_r_extrados);
    out.push(&fig, "h_min_r_intrados", &c.h_min_r_intrados);
    out.push(&fig, "h_max_r_intrados", &c.h_max_r_intrados);
    out.push(&fig, "h_min_s", &c.h_min_s);
    out.push(&fig, "h_max_s", &c.h_max_s);
    let mut row = StateRow {
        state_id: id.clone(),
        source: "scene".into(),
        state: "no_equilibrium".into(),
        load_case: load_case.to_string(),
        scene_k: k,
        scene_mu: friction.mu(),
        k,
        t_over_r: arch.t_over_r(),
        mu: friction.mu(),
        half_angle_deg: manifest.arch.half_angle_deg,
        weight: manifest.arch.weight.as_str().into(),
        voussoirs: manifest.arch.voussoirs.voussoirs(),
        regime: Some(report.regime.as_str().into()),
        mechanism: None,
        thrust_over_half_weight: None,
        crown_moment: None,
        joints: JointLists::default(),
        thrust_r_min: (!r.is_empty()).then_some(r.lo).and_then(finite),
        thrust_r_max: (!r.is_empty()).then_some(r.hi).and_then(finite),
        thrust_s_min: (!s.is_empty()).then_some(s.lo).and_then(finite),
        thrust_s_max: (!s.is_empty()).then_some(s.hi).and_then(finite),
    };
    let (draw_arch, h, m) = match symmetric::thrust(&arch, friction) {
        Some((lo, _)) if lo.thrust_over_half_weight.is_finite() => {
            row.state = "minimum_thrust".into();
            row.mechanism = crate::analysis::MechanismKind::from_counts(
                lo.hinges.len(),
                lo.sliding_joints.len(),
            )
            .map(|k| k.as_str().to_string());
            row.joints = joint_lists(&lo.hinges, &lo.sliding_joints);
            (arch, lo.thrust_over_half_weight, lo.crown_moment)
        }
        _ => match symmetric::thickness(&arch, friction) {
            symmetric::Critical::Found(c) => {
                row.state = "collapse".into();
                row.k = c.k;
                row.t_over_r = crate::model::t_over_r_from_k(c.k);
                row.mechanism = Some(c.mechanism.kind.as_str().into());
                row.joints = joint_lists(&c.mechanism.hinges, &c.mechanism.sliding_joints);
                (arch.with_k(c.k), c.thrust_over_half_weight, c.crown_moment)
            }
            _ => (arch, f64::NAN, f64::NAN),
        },
    };
    row.thrust_over_half_weight = finite(h);
    row.crown_moment = finite(m);
    if h.is_finite() && m.is_finite() {
        out.push(
            &line_of_thrust_figure(&id),
            LINE_OF_THRUST,
            &curves::line_of_thrust(&draw_arch, h, m),
        );
    }
    Ok(row)
}

fn mu_range(manifest: &Manifest) -> Option<(f64, f64)> {
    let vals = manifest
        .grid
        .iter()
        .filter(|a| a.name == AxisName::Mu)
        .flat_map(|a| a.values.iter().copied())
        .filter(|v| v.is_finite());
    let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    (lo < hi).then_some((lo, hi))
}

/// The critical curves K_c(μ) and μ_c(K) of a state grid, over the ranges of its axes.
fn critical_curves(
    manifest: &Manifest,
    load_case: &str,
    bifurcations: &[BifurcationRow],
    out: &mut Collector,
) -> Result<()> {
    let Some((mu_lo, mu_hi)) = mu_range(manifest) else {
        return Ok(());
    };
    let k_range = manifest.k_values().and_then(|v| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo < hi).then_some((lo, hi))
    });
    let Some((k_lo, k_hi)) = k_range else {
        return Ok(());
    };
    let arch = base_arch(manifest, 0.5 * (k_lo + k_hi))?;
    let bif_mu: Vec<f64> = bifurcations.iter().map(|b| b.mu).collect();
    let bif_k: Vec<f64> = bifurcations.iter().map(|b| b.k).collect();
    let fig = critical_figure(load_case);
    let mus = curves::linspace_with(mu_lo, mu_hi, CRITICAL_SAMPLES, &bif_mu);
    out.push(
        &fig,
        K_CRIT_OF_MU,
        &curves::critical_thickness_curve(&arch, &mus),
    );
    let ks = curves::linspace_with(k_lo, k_hi, CRITICAL_SAMPLES, &bif_k);
    out.push(
        &fig,
        MU_CRIT_OF_K,
        &curves::critical_friction_curve(&arch, &ks),
    );
    Ok(())
}

/// Runs the stage: computes the figure data of a run and writes it into its directory.
pub fn run(plan: &Plan, layout: &RunLayout) -> Result<FigureDataSummary> {
    let manifest = &plan.manifest;
    let bifurcations = if layout.bifurcations().exists() {
        store::read_bifurcations(&layout.bifurcations())?
    } else {
        Vec::new()
    };
    let mut out = Collector { points: Vec::new() };
    let mut states = Vec::new();
    let mut mechs = Vec::new();
    // The drawings (an arc of a circle, a symmetric line of thrust, H^r and H^s) are those of
    // self-weight on the circular arch with radial joints: other forms and live loads get
    // none rather than wrong ones (docs/loads-and-geometries.md).
    let drawable = manifest.arch.form().is_circular_radial();
    for lc in manifest
        .load_cases
        .iter()
        .filter(|l| drawable && !l.kind.is_live())
    {
        let sfx = suffix(manifest, &lc.name);
        let bifs: Vec<&BifurcationRow> = bifurcations
            .iter()
            .filter(|b| b.load_case == lc.name)
            .collect();
        for (i, b) in bifs.iter().enumerate() {
            let id = format!("bifurcation-{}{sfx}", i + 1);
            let index = u32::try_from(i + 1).unwrap_or(u32::MAX);
            mechs.extend(mechanisms::bifurcation_mechanisms(
                &base_arch(manifest, b.k)?,
                b,
                &id,
                index,
            ));
            states.push(bifurcation_state(manifest, id, b, &mut out)?);
        }
        for (i, s) in manifest.scenes.iter().enumerate() {
            let id = format!("scene-{}{sfx}", i + 1);
            states.push(scene_state(manifest, id, &lc.name, s.k, s.mu, &mut out)?);
        }
        if lc.find == crate::scene::Find::State && single_model(manifest) {
            let own: Vec<BifurcationRow> = bifs.into_iter().cloned().collect();
            critical_curves(manifest, &lc.name, &own, &mut out)?;
        }
    }
    let refs = reference::continuum_references(plan, layout)?;
    store::write_parquet(&mut store::curves_frame(&out.points)?, &layout.curves())?;
    store::write_parquet(&mut store::states_frame(&states)?, &layout.states())?;
    store::write_parquet(&mut store::reference_frame(&refs)?, &layout.reference())?;
    store::write_parquet(&mut store::mechanisms_frame(&mechs)?, &layout.mechanisms())?;
    Ok(FigureDataSummary {
        states: states.len(),
        curve_points: out.points.len(),
        references: refs.len(),
        mechanisms: mechs.len(),
    })
}

/// True when every case uses the manifest's arch (no voussoir or half-angle axis).
pub fn single_model(manifest: &Manifest) -> bool {
    !manifest
        .grid
        .iter()
        .any(|a| matches!(a.name, AxisName::Voussoirs | AxisName::HalfAngleDeg))
}
