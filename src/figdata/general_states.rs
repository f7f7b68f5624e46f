//! The states drawn for a load case on the general route (a pointed arch, vertical joints or a
//! live load): each bifurcation of a state, thickness or friction study and each scene, on the
//! arch of its own group; for a `load_factor` load case, the collapse state of its weakest
//! case and of the weakest case of every other mechanism found (docs/report-files.md).

use super::general::{self, CrownForce, active_joint_parameter};
use super::{
    ArchGroup, Collector, SceneAt, blank_state, finite, joint_lists, suffix, weakest_position,
};
use crate::analysis::forms::ArchModel;
use crate::analysis::general::Settings;
use crate::analysis::kinematics::{
    ActiveJoint, FlowRule, LimitState, ModeStatus, mechanism_modes, work_equation,
};
use crate::analysis::statics::Condition;
use crate::analysis::{Face, Mechanism, Sense};
use crate::manifest::{LoadCase, Manifest};
use crate::model::{Friction, Load};
use crate::scene::Find;
use crate::store::{BifurcationGroup, BifurcationRow, LoadFactorCase, MechanismRow, StateRow};
use anyhow::Result;

/// What the general route draws for one load case.
pub(super) struct LoadCaseStates<'a> {
    /// The manifest.
    pub manifest: &'a Manifest,
    /// The load case.
    pub lc: &'a LoadCase,
    /// Its bifurcations, with their arch groups.
    pub bifurcations: Vec<(&'a BifurcationRow, Option<&'a BifurcationGroup>)>,
    /// Its load_factor cases (empty for other finds).
    pub cases: Vec<&'a LoadFactorCase>,
}

/// Two joints of a stored limit state under self-weight whose angles are each other's
/// mirror image to this many degrees are one symmetric pair (default 1e-3): a hinge where the
/// line of thrust touches a face tangentially is placed by the linear programmes only to
/// about the square root of their tolerance (mirrored hinges of the pointed arch differ by
/// up to 3e-6°), while distinct joints of a state lie degrees apart.
pub const MIRROR_TOL_DEG: f64 = 1e-3;

/// The friction of a stored μ (+inf: infinite).
fn friction(mu: f64) -> Friction {
    Friction::new(mu).unwrap_or(Friction::INFINITE)
}

/// The limit state's values in a row: crown force, moment, shear, λ of a live load, and the
/// mechanism with its joints when given.
fn fill(row: &mut StateRow, c: &CrownForce, mechanism: Option<&Mechanism>) {
    row.thrust_over_half_weight = finite(c.fx);
    row.crown_moment = finite(-c.m0);
    row.crown_shear = finite(c.fy);
    if row.load != "self_weight" {
        row.load_factor = finite(c.lambda);
    }
    if let Some(m) = mechanism {
        row.mechanism = Some(m.kind.as_str().into());
        row.joints = joint_lists(&m.hinges, &m.sliding_joints);
    }
}

impl LoadCaseStates<'_> {
    /// The model at K with the point load at `at_deg` when given (a stored case's angle),
    /// else at the load case's own position or `at_x` (a group of an x/L axis).
    fn model(
        &self,
        group: ArchGroup,
        k: f64,
        (at_deg, at_x): (Option<f64>, Option<f64>),
    ) -> Result<Option<ArchModel>> {
        let arch = group.arch(self.manifest, k)?;
        let load = self.lc.load(at_deg, at_x);
        Ok(ArchModel::new(arch, group.form, load).ok())
    }

    /// True when the load case places its point load by x/L (its own `at_x` or the grid's
    /// x/L axis): a drawn state then takes the position as x/L, which names the load's own
    /// extrados point also on the springing wedge of a vertical-joint arch, where the stored
    /// angle is ±α.
    fn by_x(&self) -> bool {
        self.lc.at_x.is_some()
            || (self.manifest.grid.iter()).any(|a| a.name == crate::manifest::AxisName::AtX)
    }

    /// The position of a stored case as given: (None, x/L) when the load case places it by
    /// x/L and the case stores it, else (its angle, None).
    fn position_of(&self, c: &LoadFactorCase) -> (Option<f64>, Option<f64>) {
        match c.at_x {
            Some(x) if self.by_x() => (None, Some(x)),
            _ => (c.at_deg, None),
        }
    }

    fn lambda(&self) -> f64 {
        self.lc.lambda.unwrap_or(0.0)
    }

    /// Every state of the load case, their lines of thrust pushed to `out` and the collapse
    /// mechanisms of the cases' states to `mechs`.
    pub fn states(
        &self,
        out: &mut Collector,
        mechs: &mut Vec<MechanismRow>,
    ) -> Result<Vec<StateRow>> {
        let sfx = suffix(self.manifest, &self.lc.name);
        let mut rows = Vec::new();
        if self.lc.find == Find::LoadFactor {
            for (c, why) in chosen_cases(&self.cases) {
                let id = format!("case-{}{sfx}", c.row);
                rows.extend(self.case_state(id, (c, why), mechs)?);
            }
        } else {
            for (i, &(b, g)) in self.bifurcations.iter().enumerate() {
                let id = format!("bifurcation-{}{sfx}", i + 1);
                let index = u32::try_from(i + 1).unwrap_or(u32::MAX);
                rows.extend(self.bifurcation_state(id, (b, g), index, mechs)?);
            }
        }
        for group in super::arch_groups(self.manifest) {
            for (i, s) in self.manifest.scenes.iter().enumerate() {
                let id = format!("scene-{}{}{sfx}", i + 1, group.suffix(self.manifest));
                let at = SceneAt {
                    lc: self.lc,
                    group,
                    k: s.k,
                    mu: s.mu,
                };
                rows.extend(self.scene_state(id, &at)?);
            }
        }
        for r in &rows {
            out.push_line(r)?;
        }
        Ok(rows)
    }

    /// The limit state at a located bifurcation: the state of largest margin there (zero up
    /// to the tolerance), with the joints of both mechanisms as stored; its collapse
    /// mechanisms (numbered `index`) go to `mechs`.
    fn bifurcation_state(
        &self,
        id: String,
        (b, g): (&BifurcationRow, Option<&BifurcationGroup>),
        index: u32,
        mechs: &mut Vec<MechanismRow>,
    ) -> Result<Option<StateRow>> {
        let group = ArchGroup::of_bifurcation(self.manifest, g);
        let at = g.and_then(|g| g.at_deg).or(self.lc.at_deg);
        let at_x = g.and_then(|g| g.at_x);
        let Some(model) = self.model(group, b.k, (at, at_x))? else {
            return Ok(None);
        };
        let f = friction(b.mu);
        let Some(c) = general::limit_state_at(&model, f.angle(), self.lambda()) else {
            return Ok(None);
        };
        let mut row = blank_state(self.manifest, self.lc, group, id);
        row.source = "bifurcation".into();
        row.state = "bifurcation".into();
        (row.scene_k, row.scene_mu, row.k, row.mu) = (b.k, f.mu(), b.k, f.mu());
        row.t_over_r = b.t_over_r;
        row.at_deg = at.or_else(|| model.point_position().map(|(deg, _)| deg));
        row.at_x = if at.is_none() {
            at_x.or(row.at_x)
        } else {
            None
        };
        fill(&mut row, &c, None);
        row.mechanism = Some(super::bifurcation_name(&b.mechanism_a, &b.mechanism_b));
        row.joints = b.joints.clone();
        mechs.extend(bifurcation_mechanisms(&model, &row, &c, index));
        Ok(Some(row))
    }

    /// The collapse state at λ_max of a stored case, solved again for its whole crown state.
    fn case_state(
        &self,
        id: String,
        (c, why): (&LoadFactorCase, &str),
        mechs: &mut Vec<MechanismRow>,
    ) -> Result<Option<StateRow>> {
        let group = ArchGroup::of_case(self.manifest, c);
        let f = friction(c.mu);
        let position = match why {
            "weakest" => self.refined_position(group, c, f)?,
            _ => self.position_of(c),
        };
        let Some(model) = self.model(group, c.k, position)? else {
            return Ok(None);
        };
        let Some(collapse) = general::load_factor_collapse(&model, f.angle()) else {
            return Ok(None);
        };
        let (crown, mechanism) = (collapse.crown, collapse.mechanism.clone());
        mechs.extend(general::collapse_mechanism_row(
            &model,
            &collapse,
            (&id, &self.lc.name),
            f.mu(),
        ));
        let mut row = blank_state(self.manifest, self.lc, group, id);
        row.source = "case".into();
        row.state = why.into();
        (row.scene_k, row.scene_mu, row.k, row.mu) = (c.k, f.mu(), c.k, f.mu());
        row.t_over_r = crate::model::t_over_r_from_k(c.k);
        row.at_deg = position
            .0
            .or_else(|| model.point_position().map(|(deg, _)| deg))
            .or(c.at_deg);
        row.at_x = position.1;
        row.case_id = u32::try_from(c.row).ok();
        fill(&mut row, &crown, mechanism.as_ref());
        Ok(Some(row))
    }

    /// The position of the weakest case of a point load that moves over a grid axis of three
    /// positions or more (an influence line), refined between its neighbouring grid positions
    /// ([`weakest_position`]); the case's own position otherwise.
    fn refined_position(
        &self,
        group: ArchGroup,
        c: &LoadFactorCase,
        f: Friction,
    ) -> Result<(Option<f64>, Option<f64>)> {
        use crate::manifest::AxisName;
        let grid = self.position_of(c);
        let axis = (self.manifest.grid.iter()).find(|a| {
            (a.name == AxisName::AtDeg && grid.0.is_some())
                || (a.name == AxisName::AtX && grid.1.is_some())
        });
        // An influence line has three positions or more; two are two loads, not a line.
        let (Some(axis), Some(lambda)) = (axis.filter(|a| a.values.len() >= 3), c.load_factor)
        else {
            return Ok(grid);
        };
        let by_x = axis.name == AxisName::AtX;
        let at = if by_x { grid.1 } else { grid.0 }.unwrap_or(f64::NAN);
        let tol = self.manifest.boundary_tolerance;
        let Some(bracket) = weakest_position::bracket(&axis.values, at, tol) else {
            return Ok(grid);
        };
        let place = |p: f64| {
            if by_x {
                (None, Some(p))
            } else {
                (Some(p), None)
            }
        };
        let lambda_at = |p: f64| {
            let model = self.model(group, c.k, place(p)).ok()??;
            let lf = crate::analysis::general::load_factor(&model, f.angle(), &Settings::default());
            (lf.outcome == crate::analysis::general::Outcome::Solved).then_some(lf.lambda)
        };
        let (p, _) = weakest_position::refine(bracket, (at, lambda), tol, lambda_at);
        Ok(place(p))
    }

    /// A scene: under a load factor find, its collapse state at λ_max (the load at the
    /// position of the load case, else at the weakest position of its arch); otherwise its
    /// state of largest margin when it stands, else its collapse state at K_c(μ).
    fn scene_state(&self, id: String, at: &SceneAt<'_>) -> Result<Option<StateRow>> {
        let position = if self.lc.at_deg.is_some() || self.lc.at_x.is_some() {
            (self.lc.at_deg, self.lc.at_x)
        } else {
            // results.parquet stores α as given.
            let own =
                (self.cases.iter()).filter(|c| ArchGroup::of_case(self.manifest, c) == at.group);
            weakest(own.copied()).map_or((None, None), |c| self.position_of(c))
        };
        let Some(model) = self.model(at.group, at.k, position)? else {
            return Ok(None);
        };
        let f = friction(at.mu);
        let mut row = blank_state(self.manifest, self.lc, at.group, id);
        row.source = "scene".into();
        (row.scene_k, row.scene_mu, row.k, row.mu) = (at.k, f.mu(), at.k, f.mu());
        row.t_over_r = crate::model::t_over_r_from_k(at.k);
        row.at_deg = position.0;
        row.at_x = position.1;
        if position.0.is_none() && position.1.is_some() {
            row.at_deg = model.point_position().map(|(deg, _)| deg);
        }
        if self.lc.find == Find::LoadFactor {
            match general::load_factor_state(&model, f.angle()) {
                Some((c, m)) => {
                    row.state = "collapse".into();
                    fill(&mut row, &c, m.as_ref());
                }
                None => row.state = "no_load_factor".into(),
            }
            return Ok(Some(row));
        }
        let settings = Settings {
            lambda: self.lambda(),
            ..Settings::default()
        };
        let report = crate::analysis::general::regime(&model, f.angle(), &settings);
        row.regime = report.regime.map(|r| r.as_str().to_string());
        if let Some(c) = general::largest_margin_state(&model, f.angle(), self.lambda()) {
            row.state = "largest_margin".into();
            fill(&mut row, &c, None);
            return Ok(Some(row));
        }
        let make =
            |k: f64| ArchModel::new(model.arch().with_k(k), *model.form(), model.load()).ok();
        let critical = crate::analysis::general::thickness_with(
            make,
            model
                .form()
                .max_k_with_load(model.arch().half_angle, model.load()),
            None,
            f,
            &settings,
        );
        row.state = "no_equilibrium".into();
        if let Some(s) = critical.found()
            && let Some(k) = s.k
        {
            row.state = "collapse".into();
            row.k = k;
            row.t_over_r = crate::model::t_over_r_from_k(k);
            fill(
                &mut row,
                &CrownForce::of(&s.state.crown, self.lambda()),
                s.mechanism.as_ref(),
            );
        }
        Ok(Some(row))
    }
}

/// The active joints of a drawn state as stored (the hinges on their faces, the sliding
/// joints with their senses), at the joint parameters of its own arch, in increasing order.
fn stored_pattern(model: &ArchModel, row: &StateRow) -> Vec<ActiveJoint> {
    let j = &row.joints;
    let hinges = j
        .hinge_angles_deg
        .iter()
        .zip(&j.hinge_faces)
        .map(|(&a, f)| {
            let face = Face::parse(f).unwrap_or(Face::Intrados);
            let condition = match face {
                Face::Extrados => Condition::Extrados,
                Face::Intrados => Condition::Intrados,
            };
            ActiveJoint::hinge(active_joint_parameter(model, row, a, &[condition]), face)
        });
    let slides = [Condition::SlideOutward, Condition::SlideInward];
    let sliding = j
        .sliding_angles_deg
        .iter()
        .zip(&j.sliding_senses)
        .map(|(&a, s)| {
            let sense = Sense::parse(s).unwrap_or(Sense::Outward);
            ActiveJoint::sliding(active_joint_parameter(model, row, a, &slides), Some(sense))
        });
    let mut joints: Vec<ActiveJoint> = hinges.chain(sliding).collect();
    joints.sort_by(|a, b| a.theta.total_cmp(&b.theta));
    if matches!(model.load(), Load::SelfWeight) {
        mirror(&mut joints);
    }
    joints
}

/// Under self-weight the arch and its load are symmetric, and so is a limit state: when every
/// joint of a stored state has a mirror image among them (same hinge face, sliding and
/// sense, at −θ to [`MIRROR_TOL_DEG`]), each pair is put exactly at ±θ, so that the
/// mechanism is sought among the symmetric fields, as on the semicircle.
fn mirror(joints: &mut [ActiveJoint]) {
    let tol = MIRROR_TOL_DEG.to_radians();
    let alike = |a: &ActiveJoint, b: &ActiveJoint| {
        a.hinge == b.hinge && a.slides == b.slides && a.sense == b.sense
    };
    let mut partner: Vec<Option<usize>> = vec![None; joints.len()];
    for i in 0..joints.len() {
        if joints[i].theta.abs() <= tol {
            partner[i] = Some(i);
            continue;
        }
        let found = (0..joints.len()).find(|&j| {
            j != i
                && (joints[i].theta + joints[j].theta).abs() <= tol
                && alike(&joints[i], &joints[j])
                && partner[j].is_none_or(|p| p == i)
        });
        match found {
            Some(j) => partner[i] = Some(j),
            None => return,
        }
    }
    let theta: Vec<f64> = (0..joints.len())
        .map(|i| {
            let j = partner[i].unwrap_or(i);
            0.5 * (joints[i].theta - joints[j].theta)
        })
        .collect();
    for (joint, t) in joints.iter_mut().zip(theta) {
        joint.theta = t;
    }
}

/// The collapse mechanisms at a located bifurcation, on its own arch, as on the semicircle:
/// the admissible modes of the pattern of both mechanisms' joints (two at a bifurcation)
/// under the paper's non-associative rule and, at finite μ, under the associative rule,
/// each with its work equation (eq. 11) at the limit state there and its drawing, as rows
/// of mechanisms.parquet numbered `index`. A rule whose pattern has no admissible mode adds
/// no row.
fn bifurcation_mechanisms(
    model: &ArchModel,
    row: &StateRow,
    c: &CrownForce,
    index: u32,
) -> Vec<MechanismRow> {
    let joints = stored_pattern(model, row);
    let state = LimitState {
        crown_force: [c.fx, c.fy],
        crown_moment_origin: c.m0,
        load_factor: c.lambda,
        mu: row.mu,
    };
    let mut rules = vec![FlowRule::NonAssociative];
    if row.mu.is_finite() {
        rules.push(FlowRule::Associative { tan_phi: row.mu });
    }
    let mut out = Vec::new();
    for rule in rules {
        // Only admissible modes are mechanisms: an inadmissible pattern's list holds its
        // least-violating mode, which breaches the flow rule.
        let Ok(modes) = mechanism_modes(model, &joints, rule, true) else {
            continue;
        };
        if modes.status != ModeStatus::Admissible {
            continue;
        }
        for f in &modes.fields {
            let w = work_equation(model, &state, f);
            out.push(general::mechanism_row(
                model,
                (f, &w),
                modes.dof,
                (&row.state_id, &row.load_case, index),
                row.mu,
            ));
        }
    }
    out
}

/// The case of least finite λ_max.
fn weakest<'a>(cases: impl Iterator<Item = &'a LoadFactorCase>) -> Option<&'a LoadFactorCase> {
    cases
        .filter(|c| c.load_factor.is_some_and(f64::is_finite))
        .min_by(|a, b| {
            let (x, y) = (a.load_factor.unwrap_or(0.0), b.load_factor.unwrap_or(0.0));
            x.total_cmp(&y).then(a.row.cmp(&b.row))
        })
}

/// The cases whose collapse states are drawn: the weakest case of the load case (`weakest`:
/// at its weakest position when a point load moves) and, for every other mechanism among its
/// cases, the weakest case collapsing by it (`weakest_of_mechanism`).
pub(super) fn chosen_cases<'a>(
    cases: &[&'a LoadFactorCase],
) -> Vec<(&'a LoadFactorCase, &'static str)> {
    let Some(w) = weakest(cases.iter().copied()) else {
        return Vec::new();
    };
    let mut out = vec![(w, "weakest")];
    for kind in ["rotational", "mixed", "sliding"] {
        if w.mechanism.as_deref() == Some(kind) {
            continue;
        }
        let of_kind = cases
            .iter()
            .copied()
            .filter(|c| c.mechanism.as_deref() == Some(kind));
        if let Some(c) = weakest(of_kind) {
            out.push((c, "weakest_of_mechanism"));
        }
    }
    out
}

/// The collapse mechanism of a drawn limit or collapse state (its stored hinges and sliding
/// joints) under the paper's non-associative rule, with the arch model it moves on: the
/// mode of the state's own kind (`row.mechanism`) when the pattern has one, else its first
/// mode. `None` when the row has no active joints or the pattern no mode.
pub fn mechanism_of_state(
    row: &StateRow,
) -> Option<(ArchModel, crate::analysis::kinematics::VelocityField)> {
    let model = general::model_of_state(row).ok()?;
    let joints = stored_pattern(&model, row);
    if joints.is_empty() {
        return None;
    }
    let modes = mechanism_modes(&model, &joints, FlowRule::NonAssociative, true).ok()?;
    let kind = row
        .mechanism
        .as_deref()
        .and_then(crate::analysis::MechanismKind::parse);
    let mut fields = modes.fields;
    let pick = fields
        .iter()
        .position(|f| kind.is_none_or(|k| f.kind() == Some(k)))
        .unwrap_or(0);
    (pick < fields.len()).then(|| (model, fields.swap_remove(pick)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(row: usize, lambda: f64, mech: &str) -> LoadFactorCase {
        LoadFactorCase {
            row,
            load_case: "p".into(),
            k: 1.2,
            mu: 0.5,
            half_angle_deg: 90.0,
            voussoirs: None,
            eccentricity: None,
            joints: crate::model::JointOrientation::Radial,
            at_deg: Some(row as f64),
            at_x: None,
            load_factor: Some(lambda),
            mechanism: Some(mech.into()),
            collapse_below: None,
            sliding_at_load: 0,
        }
    }

    #[test]
    fn the_weakest_case_and_the_weakest_of_each_other_mechanism_are_drawn() {
        let cases = [
            case(0, 0.5, "mixed"),
            case(1, 0.2, "rotational"),
            case(2, 0.3, "rotational"),
            case(3, 0.4, "mixed"),
            case(4, f64::INFINITY, "sliding"),
        ];
        let refs: Vec<&LoadFactorCase> = cases.iter().collect();
        let chosen: Vec<(usize, &str)> = chosen_cases(&refs)
            .into_iter()
            .map(|(c, w)| (c.row, w))
            .collect();
        assert_eq!(chosen, vec![(1, "weakest"), (3, "weakest_of_mechanism")]);
    }
}
