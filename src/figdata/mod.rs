//! The figure-data stage of a run: everything a figure needs that comes from evaluating the
//! statics, computed once at run time and stored (curves.parquet, states.parquet,
//! reference.parquet; schemas in docs/report-files.md), so that the report only reads.
//!
//! It runs after the results and the boundaries are stored, reads the bifurcations from
//! bifurcations.parquet (when present) and uses the manifest for the arch and the scenes.

pub mod curves;
pub mod general;
mod general_states;
pub mod load_factors;
pub mod mechanisms;
mod reference;
pub mod sampled;
pub mod stand_limit;
pub mod weakest_position;
pub use general_states::mechanism_of_state;
pub use reference::find_of_quantity;

use crate::analysis::symmetric;
use crate::manifest::{AxisName, LoadCase, Manifest};
use crate::model::{Arch, Discretisation, Friction};
use crate::output::RunLayout;
use crate::scene::Find;
use crate::store::{self, BifurcationGroup, BifurcationRow, CurvePoint, JointLists, StateRow};
use anyhow::{Context, Result};
use curves::Samples;
use rayon::prelude::*;

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

/// Series of the collapse along decreasing K, the first complete solution K_col(μ) (x = μ,
/// y = K), in the critical figure: stored only when it differs from K_c(μ) somewhere.
pub const K_COLLAPSE_OF_MU: &str = "k_collapse_of_mu";

/// Series of the collapse along decreasing μ, μ_col(K) (x = K, y = μ), as
/// [`K_COLLAPSE_OF_MU`].
pub const MU_COLLAPSE_OF_K: &str = "mu_collapse_of_k";

/// Series of the samples of [`K_COLLAPSE_OF_MU`] whose first complete solution is the start of
/// the searched path itself (y: that start, the largest K searched): the arch can move at
/// every K searched, and the collapse curve is NaN there.
pub const K_COLLAPSE_AT_START: &str = "k_collapse_at_start";

/// The same for [`MU_COLLAPSE_OF_K`] (y: the largest μ searched).
pub const MU_COLLAPSE_AT_START: &str = "mu_collapse_at_start";
/// Series of μ_c(K) (x = K, y = μ) in the critical figure.
pub const MU_CRIT_OF_K: &str = "mu_crit_of_k";
/// Series of the line of thrust (x, y over r).
pub const LINE_OF_THRUST: &str = "line_of_thrust";
/// Series of the line's points on the joints between voussoirs (x, y over r).
pub const LINE_ON_JOINTS: &str = "line_on_joints";

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

    /// The line of thrust of a filled state row and its points on the voussoir joints, on
    /// the row's own arch under its own load (nothing when the row has no crown state).
    fn push_line(&mut self, row: &StateRow) -> Result<()> {
        let Some((line, on_joints)) = lines_of_state(row)? else {
            return Ok(());
        };
        let fig = line_of_thrust_figure(&row.state_id);
        self.push(&fig, LINE_OF_THRUST, &line);
        self.push(&fig, LINE_ON_JOINTS, &on_joints);
        Ok(())
    }
}

/// The line of thrust of a filled state row (through its hinges and sliding joints) and its
/// points on the voussoir joints, on the row's own arch under its own load; `None` when the
/// row has no crown state.
pub fn lines_of_state(row: &StateRow) -> Result<Option<(Samples, Samples)>> {
    let Some(c) = general::CrownForce::of_row(row) else {
        return Ok(None);
    };
    let model = general::model_of_state(row)?;
    let j = &row.joints;
    let angles: Vec<f64> = j
        .hinge_angles_deg
        .iter()
        .chain(&j.sliding_angles_deg)
        .copied()
        .collect();
    Ok(Some((
        general::line_of_thrust(&model, &c, &angles),
        general::line_on_joints(&model, &c),
    )))
}

fn suffix(manifest: &Manifest, load_case: &str) -> String {
    if manifest.load_cases.len() > 1 {
        format!("-{load_case}")
    } else {
        String::new()
    }
}

/// The arch of one group of cases: the manifest's arch with the values of its
/// `half_angle_deg`, `eccentricity`, `joints` and `voussoirs` axes, when it has them.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ArchGroup {
    /// Half-embrace angle α, degrees.
    half_angle_deg: f64,
    /// Continuum or N voussoirs.
    voussoirs: Discretisation,
    /// Outline and joint planes.
    form: crate::model::ArchForm,
}

impl ArchGroup {
    fn of_manifest(manifest: &Manifest) -> Self {
        ArchGroup {
            half_angle_deg: manifest.arch.half_angle_deg,
            voussoirs: manifest.arch.voussoirs,
            form: manifest.arch.form(),
        }
    }

    /// The form of a stored row's columns (eccentricity, null for a circular arch, and joint
    /// planes), the manifest's keystone kept; the manifest's form where the table lacks them.
    fn form_of(
        manifest: &Manifest,
        e: Option<f64>,
        joints: Option<&str>,
    ) -> crate::model::ArchForm {
        let base = manifest.arch.form();
        let Some(joints) = joints.and_then(crate::model::JointOrientation::parse) else {
            return base;
        };
        crate::model::ArchForm {
            shape: match e {
                Some(eccentricity) => crate::model::Shape::Pointed { eccentricity },
                None => crate::model::Shape::Circular,
            },
            joints,
            ..base
        }
    }

    /// The group of a stored load_factor case.
    fn of_case(manifest: &Manifest, c: &store::LoadFactorCase) -> Self {
        ArchGroup {
            half_angle_deg: c.half_angle_deg,
            voussoirs: c
                .voussoirs
                .map_or(Discretisation::Continuum, Discretisation::Voussoirs),
            form: Self::form_of(manifest, c.eccentricity, Some(c.joints.as_str())),
        }
    }

    /// The group of a stored bifurcation: its own half-angle and voussoir count, the
    /// manifest's where the table does not have them.
    fn of_bifurcation(manifest: &Manifest, g: Option<&BifurcationGroup>) -> Self {
        let base = Self::of_manifest(manifest);
        let Some(g) = g else { return base };
        ArchGroup {
            half_angle_deg: g.half_angle_deg.unwrap_or(base.half_angle_deg),
            voussoirs: match g.voussoirs {
                Some(Some(n)) => Discretisation::Voussoirs(n),
                Some(None) => Discretisation::Continuum,
                None => base.voussoirs,
            },
            form: Self::form_of(manifest, g.eccentricity, g.joints.as_deref()),
        }
    }

    fn arch(&self, manifest: &Manifest, k: f64) -> Result<Arch> {
        Arch::new(k, self.half_angle_deg, manifest.arch.weight, self.voussoirs).with_context(|| {
            format!(
                "the arch of the study with K = {k}, α = {}°",
                self.half_angle_deg
            )
        })
    }

    /// The id suffix naming the values of the arch axes the study has (`-a65`, `-n9`).
    fn suffix(&self, manifest: &Manifest) -> String {
        let mut out = String::new();
        if has_axis(manifest, AxisName::HalfAngleDeg) {
            out.push_str(&format!("-a{}", self.half_angle_deg));
        }
        if has_axis(manifest, AxisName::Eccentricity) {
            out.push_str(&format!("-e{}", self.form.shape.eccentricity()));
        }
        if has_axis(manifest, AxisName::Joints) {
            out.push_str(&format!("-{}", self.form.joints.as_str()));
        }
        if has_axis(manifest, AxisName::Voussoirs) {
            match self.voussoirs.voussoirs() {
                Some(n) => out.push_str(&format!("-n{n}")),
                None => out.push_str("-continuum"),
            }
        }
        out
    }
}

fn has_axis(manifest: &Manifest, name: AxisName) -> bool {
    manifest.grid.iter().any(|a| a.name == name)
}

/// Every arch of the study: the manifest's, or one per value of its arch axes.
fn arch_groups(manifest: &Manifest) -> Vec<ArchGroup> {
    let base = ArchGroup::of_manifest(manifest);
    let values = |name: AxisName| -> Option<Vec<f64>> {
        manifest
            .grid
            .iter()
            .find(|a| a.name == name)
            .map(|a| a.values.clone())
    };
    let halves = values(AxisName::HalfAngleDeg).unwrap_or_else(|| vec![base.half_angle_deg]);
    let counts: Vec<Discretisation> = values(AxisName::Voussoirs).map_or_else(
        || vec![base.voussoirs],
        |v| {
            v.iter()
                .map(|&n| {
                    if n.is_finite() {
                        Discretisation::Voussoirs(n as u32)
                    } else {
                        Discretisation::Continuum
                    }
                })
                .collect()
        },
    );
    let forms = manifest.forms();
    let mut out = Vec::new();
    for &half_angle_deg in &halves {
        for &form in &forms {
            for &voussoirs in &counts {
                out.push(ArchGroup {
                    half_angle_deg,
                    voussoirs,
                    form,
                });
            }
        }
    }
    out
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// A state row with the arch and load of its case filled in and nothing drawn yet.
fn blank_state(manifest: &Manifest, lc: &LoadCase, group: ArchGroup, id: String) -> StateRow {
    let form = group.form;
    StateRow {
        state_id: id,
        source: String::new(),
        state: String::new(),
        load_case: lc.name.clone(),
        scene_k: f64::NAN,
        scene_mu: f64::NAN,
        k: f64::NAN,
        t_over_r: f64::NAN,
        mu: f64::NAN,
        half_angle_deg: group.half_angle_deg,
        weight: manifest.arch.weight.as_str().into(),
        voussoirs: group.voussoirs.voussoirs(),
        shape: form.shape.as_str().into(),
        eccentricity: form.shape.eccentricity(),
        joint_orientation: form.joints.as_str().into(),
        keystone: form.keystone,
        load: lc.kind.as_str().into(),
        at_deg: lc.at_deg,
        at_x: lc.at_x,
        load_width: lc.width,
        load_factor: lc.lambda,
        regime: None,
        mechanism: None,
        thrust_over_half_weight: None,
        crown_moment: None,
        crown_shear: None,
        case_id: None,
        joints: JointLists::default(),
        thrust_r_min: None,
        thrust_r_max: None,
        thrust_s_min: None,
        thrust_s_max: None,
    }
}

/// The state drawn for a bifurcation, on the arch of its own group, with its line of thrust.
fn bifurcation_state(
    manifest: &Manifest,
    lc: &LoadCase,
    id: String,
    (b, g): (&BifurcationRow, Option<&BifurcationGroup>),
    out: &mut Collector,
) -> Result<StateRow> {
    let group = ArchGroup::of_bifurcation(manifest, g);
    let mut row = blank_state(manifest, lc, group, id);
    row.source = "bifurcation".into();
    row.state = "bifurcation".into();
    (row.scene_k, row.scene_mu, row.k, row.mu) = (b.k, b.mu, b.k, b.mu);
    row.t_over_r = b.t_over_r;
    row.mechanism = Some(bifurcation_name(&b.mechanism_a, &b.mechanism_b));
    row.thrust_over_half_weight = b.thrust_over_half_weight;
    row.crown_moment = b.crown_moment;
    row.joints = b.joints.clone();
    row.crown_shear = row.thrust_over_half_weight.map(|_| 0.0);
    if let Some(g) = g {
        row.at_deg = g.at_deg.or(row.at_deg);
        row.load_factor = g.load_factor.or(row.load_factor);
    }
    out.push_line(&row)?;
    Ok(row)
}

/// The stored lists of a set of hinges and sliding joints.
pub fn joint_lists(
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

/// Where a scene is drawn: its load case, arch group and (K, μ) as listed.
struct SceneAt<'a> {
    lc: &'a LoadCase,
    group: ArchGroup,
    k: f64,
    mu: f64,
}

/// The state drawn for a manifest scene: its minimum-thrust state when it stands, else the
/// collapse state at its μ (at K_c(μ)), else nothing; with the curves of Fig. 2.
fn scene_state(
    manifest: &Manifest,
    id: String,
    at: &SceneAt<'_>,
    out: &mut Collector,
) -> Result<StateRow> {
    let arch = at.group.arch(manifest, at.k)?;
    let friction = Friction::new(at.mu).unwrap_or(Friction::INFINITE);
    let report = symmetric::state(&arch, friction);
    let (r, s) = (
        report.domains.rotational.interval,
        report.domains.sliding.interval,
    );
    let c = curves::domain_curves(&arch, friction);
    let fig = domains_figure(&id);
    for name in curves::DOMAIN_SERIES {
        out.push(&fig, name, &c.series(name));
    }
    let mut row = blank_state(manifest, at.lc, at.group, id.clone());
    row.source = "scene".into();
    row.state = "no_equilibrium".into();
    (row.scene_k, row.k) = (at.k, at.k);
    (row.scene_mu, row.mu) = (friction.mu(), friction.mu());
    row.t_over_r = arch.t_over_r();
    row.regime = Some(report.regime.as_str().into());
    row.thrust_r_min = (!r.is_empty()).then_some(r.lo).and_then(finite);
    row.thrust_r_max = (!r.is_empty()).then_some(r.hi).and_then(finite);
    row.thrust_s_min = (!s.is_empty()).then_some(s.lo).and_then(finite);
    row.thrust_s_max = (!s.is_empty()).then_some(s.hi).and_then(finite);
    let (h, m) = scene_drawn_state(&arch, friction, &mut row);
    row.thrust_over_half_weight = finite(h);
    row.crown_moment = finite(m);
    row.crown_shear = row.thrust_over_half_weight.map(|_| 0.0);
    out.push_line(&row)?;
    Ok(row)
}

/// The state a scene draws: its minimum-thrust state, else its collapse state at K_c(μ);
/// fills the row's state, K, mechanism and joints and returns the thrust and moment.
fn scene_drawn_state(arch: &Arch, friction: Friction, row: &mut StateRow) -> (f64, f64) {
    match symmetric::thrust(arch, friction) {
        Some((lo, _)) if lo.thrust_over_half_weight.is_finite() => {
            row.state = "minimum_thrust".into();
            row.mechanism = crate::analysis::MechanismKind::from_counts(
                lo.hinges.len(),
                lo.sliding_joints.len(),
            )
            .map(|k| k.as_str().to_string());
            row.joints = joint_lists(&lo.hinges, &lo.sliding_joints);
            (lo.thrust_over_half_weight, lo.crown_moment)
        }
        _ => match symmetric::thickness(arch, friction) {
            symmetric::Critical::Found(c) => {
                row.state = "collapse".into();
                row.k = c.k;
                row.t_over_r = crate::model::t_over_r_from_k(c.k);
                row.mechanism = Some(c.mechanism.kind.as_str().into());
                row.joints = joint_lists(&c.mechanism.hinges, &c.mechanism.sliding_joints);
                (c.thrust_over_half_weight, c.crown_moment)
            }
            _ => (f64::NAN, f64::NAN),
        },
    }
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

/// The collapse value of a self-weight find at one sample of a critical curve (NaN where none
/// was found), whether it comes before the static limit, and the start of the path when it
/// is met there.
fn collapse_sample(
    arch: &Arch,
    form: crate::model::ArchForm,
    find: Find,
    k: f64,
    mu: f64,
) -> (f64, bool, Option<f64>) {
    let Some(friction) = Friction::new(mu) else {
        return (f64::NAN, false, None);
    };
    let sol = crate::scene::solve(&crate::scene::Scene {
        arch: arch.with_k(k),
        friction,
        find,
        form,
        load: crate::model::Load::SelfWeight,
        lambda: 0.0,
    });
    let value = sol.collapse_value.unwrap_or(f64::NAN);
    let start = sol
        .gap_searched_to
        .filter(|&s| (value - s).abs() <= 1e-9 * s.abs().max(1.0));
    (
        value,
        sol.gap == Some(crate::analysis::gap::GapStatus::Gap),
        start,
    )
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
    let arch = ArchGroup::of_manifest(manifest).arch(manifest, 0.5 * (k_lo + k_hi))?;
    let bif_mu: Vec<f64> = bifurcations.iter().map(|b| b.mu).collect();
    let bif_k: Vec<f64> = bifurcations.iter().map(|b| b.k).collect();
    let fig = critical_figure(load_case);
    let form = manifest.arch.form();
    let mus = curves::linspace_with(mu_lo, mu_hi, CRITICAL_SAMPLES, &bif_mu);
    let k_of_mu: Samples = (mus.par_iter())
        .map(|&mu| (mu, symmetric::collapse_thickness(&arch, form, mu)))
        .collect();
    out.push(&fig, K_CRIT_OF_MU, &k_of_mu);
    let ks = curves::linspace_with(k_lo, k_hi, CRITICAL_SAMPLES, &bif_k);
    let mu_of_k: Samples = (ks.par_iter())
        .map(|&k| (k, symmetric::critical_friction(&arch, form, k)))
        .collect();
    out.push(&fig, MU_CRIT_OF_K, &mu_of_k);
    // The circular arch with radial joints has no gap under self-weight (the paper's
    // scenes); the other forms may: their collapse beside the static limit.
    if !form.is_circular_radial() {
        type Sample = (f64, (f64, bool, Option<f64>));
        let mut push = |series: [&str; 2], samples: Vec<Sample>| {
            if !samples.iter().any(|s| s.1.1) {
                return;
            }
            let curve: Samples = (samples.iter())
                .map(|&(x, (y, _, start))| (x, if start.is_some() { f64::NAN } else { y }))
                .collect();
            out.push(&fig, series[0], &curve);
            let at_start: Samples = (samples.iter())
                .filter_map(|&(x, (_, _, start))| Some((x, start?)))
                .collect();
            out.push(&fig, series[1], &at_start);
        };
        // At a bifurcation two limit states meet and one of them is marginal over a range of
        // the other parameter (K_c(μ) jumps there): which complete state the search meets
        // first is a matter of rounding, so the collapse is not sampled there (its curve is
        // broken where the critical curve jumps).
        let sample = |find: Find, x: f64, bifs: &[f64], (k, mu): (f64, f64)| -> Sample {
            if bifs.iter().any(|&b| curves::merged(b, x)) {
                (x, (f64::NAN, false, None))
            } else {
                (x, collapse_sample(&arch, form, find, k, mu))
            }
        };
        push(
            [K_COLLAPSE_OF_MU, K_COLLAPSE_AT_START],
            (mus.par_iter())
                .map(|&mu| sample(Find::Thickness, mu, &bif_mu, (k_hi, mu)))
                .collect(),
        );
        push(
            [MU_COLLAPSE_OF_K, MU_COLLAPSE_AT_START],
            (ks.par_iter())
                .map(|&k| sample(Find::Friction, k, &bif_k, (k, 0.0)))
                .collect(),
        );
    }
    Ok(())
}

/// The states of a self-weight load case on the circular arch with radial joints: every
/// bifurcation with its mechanisms, and every scene on every arch of the study.
fn symmetric_states(
    manifest: &Manifest,
    lc: &LoadCase,
    bifs: &[(&BifurcationRow, Option<&BifurcationGroup>)],
    (states, mechs): (&mut Vec<StateRow>, &mut Vec<store::MechanismRow>),
    out: &mut Collector,
) -> Result<()> {
    let sfx = suffix(manifest, &lc.name);
    for (i, &(b, g)) in bifs.iter().enumerate() {
        let id = format!("bifurcation-{}{sfx}", i + 1);
        let index = u32::try_from(i + 1).unwrap_or(u32::MAX);
        let arch = ArchGroup::of_bifurcation(manifest, g).arch(manifest, b.k)?;
        mechs.extend(mechanisms::bifurcation_mechanisms(&arch, b, &id, index));
        states.push(bifurcation_state(manifest, lc, id, (b, g), out)?);
    }
    for group in arch_groups(manifest) {
        for (i, s) in manifest.scenes.iter().enumerate() {
            let id = format!("scene-{}{}{sfx}", i + 1, group.suffix(manifest));
            let at = SceneAt {
                lc,
                group,
                k: s.k,
                mu: s.mu,
            };
            states.push(scene_state(manifest, id, &at, out)?);
        }
    }
    Ok(())
}

/// Runs the stage: computes the figure data of a run and writes it into its directory.
pub fn run(manifest: &Manifest, layout: &RunLayout) -> Result<FigureDataSummary> {
    if let Some(s) = &manifest.sampling {
        return run_sampled(manifest, s, layout);
    }
    let bifurcations = if layout.bifurcations().exists() {
        store::read_bifurcations(&layout.bifurcations())?
    } else {
        Vec::new()
    };
    let groups = if layout.bifurcations().exists() {
        store::read_bifurcation_groups(&layout.bifurcations())?
    } else {
        Vec::new()
    };
    let mut out = Collector { points: Vec::new() };
    let mut states = Vec::new();
    let mut mechs = Vec::new();
    let (load_factor_cases, every_case) = if manifest
        .load_cases
        .iter()
        .any(|l| l.find == Find::LoadFactor)
    {
        // The states drawn are those of the weakest cases: singled out while results.parquet
        // is read a block at a time, not every case held. A grid coarse enough for its cells
        // to show in the λ map keeps every case, for where the arch starts to stand.
        let small = store::parquet_rows(&layout.results())? <= stand_limit::MAX_POINTS;
        let read = load_factors::LoadFactorCases::read(&layout.results(), |_| small)?;
        (read.singled(), read.kept)
    } else {
        (Vec::new(), Vec::new())
    };
    // Self-weight on the circular arch with radial joints has the symmetric closed forms
    // (H^r, H^s and the paper's Fig. 2); every other form and load is drawn from the general
    // statics of its own arch.
    let symmetric = manifest.arch.form().is_circular_radial() && !manifest.forms_vary();
    for lc in &manifest.load_cases {
        let bifs: Vec<(&BifurcationRow, Option<&BifurcationGroup>)> = bifurcations
            .iter()
            .enumerate()
            .filter(|(_, b)| b.load_case == lc.name)
            .map(|(i, b)| (b, groups.get(i)))
            .collect();
        let every: Vec<&store::LoadFactorCase> = every_case.iter().collect();
        stand_limit::push(manifest, lc, &every, &mut out);
        if !symmetric || lc.kind.is_live() || lc.find == Find::LoadFactor {
            let general = general_states::LoadCaseStates {
                manifest,
                lc,
                bifurcations: bifs,
                cases: load_factor_cases
                    .iter()
                    .filter(|c| c.load_case == lc.name)
                    .collect(),
            };
            states.extend(general.states(&mut out, &mut mechs)?);
            continue;
        }
        symmetric_states(manifest, lc, &bifs, (&mut states, &mut mechs), &mut out)?;
        if lc.find == Find::State && single_model(manifest) {
            let own: Vec<BifurcationRow> = bifs.into_iter().map(|(b, _)| b.clone()).collect();
            critical_curves(manifest, &lc.name, &own, &mut out)?;
        }
    }
    // Self-weight on other forms: their critical curves too, from the general route.
    for lc in (manifest.load_cases.iter()).filter(|l| !symmetric && !l.kind.is_live()) {
        let own: Vec<BifurcationRow> = (bifurcations.iter())
            .filter(|b| b.load_case == lc.name)
            .cloned()
            .collect();
        if lc.find == Find::State && single_model(manifest) {
            critical_curves(manifest, &lc.name, &own, &mut out)?;
        }
    }
    let refs = reference::continuum_references(manifest, layout)?;
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

/// The stage for a sampling study: samples.parquet and estimates.parquet from the results,
/// the collapse curves under the samples, and no drawn states.
fn run_sampled(
    manifest: &Manifest,
    s: &crate::manifest::Sampling,
    layout: &RunLayout,
) -> Result<FigureDataSummary> {
    let summary = sampled::run(manifest, s, layout)?;
    let points = sampled::curves(manifest, s);
    store::write_parquet(&mut store::curves_frame(&points)?, &layout.curves())?;
    store::write_parquet(&mut store::states_frame(&[])?, &layout.states())?;
    store::write_parquet(&mut store::reference_frame(&[])?, &layout.reference())?;
    store::write_parquet(&mut store::mechanisms_frame(&[])?, &layout.mechanisms())?;
    Ok(FigureDataSummary {
        curve_points: points.len(),
        references: summary.estimates,
        ..FigureDataSummary::default()
    })
}

/// True when every case uses the manifest's arch (no arch axis: half-angle, eccentricity,
/// joints or voussoirs).
pub fn single_model(manifest: &Manifest) -> bool {
    !manifest.grid.iter().any(|a| a.name.is_arch())
}

/// The name of a bifurcation between two collapse mechanisms, in the order of the paper's
/// regimes (rotational, mixed, sliding): "rotational/mixed", "mixed/sliding", whichever
/// mechanism the boundary search names first.
pub fn bifurcation_name(a: &str, b: &str) -> String {
    // MechanismKind is ordered as the regimes; a name it does not know comes last.
    fn key(m: &str) -> (bool, Option<crate::analysis::MechanismKind>, &str) {
        let kind = crate::analysis::MechanismKind::parse(m);
        (kind.is_none(), kind, m)
    }
    let (first, second) = if key(a) <= key(b) { (a, b) } else { (b, a) };
    format!("{first}/{second}")
}

/// [`bifurcation_name`] spaced for a label or a table: "rotational / mixed".
pub fn bifurcation_label(a: &str, b: &str) -> String {
    bifurcation_name(a, b).replace('/', " / ")
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_bifurcation_is_named_in_the_order_of_the_regimes_whichever_way_it_was_found() {
        use super::bifurcation_name as name;
        assert_eq!(name("mixed", "rotational"), "rotational/mixed");
        assert_eq!(name("rotational", "mixed"), "rotational/mixed");
        assert_eq!(name("sliding", "mixed"), "mixed/sliding");
        assert_eq!(name("sliding", "rotational"), "rotational/sliding");
    }
}
