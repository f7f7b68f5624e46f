//! The drawn states of every arch the general route analyses (pointed arches, vertical
//! joints, live loads): the arch of a state row as an [`ArchModel`], its line of thrust from
//! the crown force, moment and load factor, and the limit states themselves, solved again
//! where the stored tables do not hold the whole crown state (the crown shear).

use super::curves::Samples;
use crate::analysis::forms::ArchModel;
use crate::analysis::general::{self, CrownState, Outcome, Settings};
use crate::analysis::kinematics::{
    FlowRule, LimitState, VelocityField, WorkEquation, drawing, mechanism_modes, work_equation,
};
use crate::analysis::statics::{ArchGeometry, Condition, joint_rows};
use crate::model::{Arch, ArchForm, Discretisation, JointOrientation, Load, Shape, WeightModel};
use crate::store::StateRow;
use anyhow::{Context, Result, anyhow};

/// Sections sampled per radian of a family of joints (about one every half degree).
const SECTIONS_PER_RADIAN: f64 = 115.0;

/// The statics of a drawn state: the crown force F₀ = (F_x, F_y) over W_half, the moment M₀
/// about the centre over W_half·r (m = −M₀ is the stored `crown_moment`) and λ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrownForce {
    /// F_x: the horizontal crown thrust.
    pub fx: f64,
    /// F_y: the vertical crown shear.
    pub fy: f64,
    /// M₀ about the centre.
    pub m0: f64,
    /// The load factor of the live load.
    pub lambda: f64,
}

impl CrownForce {
    /// The crown force of a general solution at load factor λ.
    pub fn of(c: &CrownState, lambda: f64) -> Self {
        CrownForce {
            fx: c.thrust_over_half_weight,
            fy: c.shear_over_half_weight,
            m0: c.moment_about_centre,
            lambda,
        }
    }

    /// The crown force stored in a state row (`None` when its thrust or moment is missing).
    pub fn of_row(s: &StateRow) -> Option<Self> {
        Some(CrownForce {
            fx: s.thrust_over_half_weight?,
            fy: s.crown_shear.unwrap_or(0.0),
            m0: -s.crown_moment?,
            lambda: s.load_factor.unwrap_or(0.0),
        })
    }
}

/// The load of a state row.
pub fn load_of_state(s: &StateRow) -> Load {
    match s.load.as_str() {
        "horizontal" => Load::Horizontal,
        "point" => {
            let width = s.load_width.unwrap_or(0.0);
            match s.at_x {
                Some(at_x) => Load::PointX { at_x, width },
                None => Load::Point {
                    at_deg: s.at_deg.unwrap_or(0.0),
                    width,
                },
            }
        }
        _ => Load::SelfWeight,
    }
}

/// The arch, form and load of a state row as the general statics models them: the geometry
/// every drawing of the state is taken from.
pub fn model_of_state(s: &StateRow) -> Result<ArchModel> {
    let voussoirs = s
        .voussoirs
        .map_or(Discretisation::Continuum, Discretisation::Voussoirs);
    let weight = WeightModel::parse(&s.weight).unwrap_or_default();
    let arch = Arch::new(s.k, s.half_angle_deg, weight, voussoirs)
        .with_context(|| format!("the arch of state {}", s.state_id))?;
    let form = ArchForm {
        shape: if s.shape == "pointed" {
            Shape::Pointed {
                eccentricity: s.eccentricity,
            }
        } else {
            Shape::Circular
        },
        joints: JointOrientation::parse(&s.joint_orientation).unwrap_or_default(),
        keystone: s.keystone,
    };
    ArchModel::new(arch, form, load_of_state(s))
        .map_err(|e| anyhow!("the arch of state {}: {e}", s.state_id))
}

/// The joint parameter named by a stored angle (degrees): a support (|angle| = α; the
/// supports of a vertical-joint arch lie just beyond α) or the angle itself (0 is the crown
/// joint).
pub fn joint_parameter(model: &ArchModel, angle_deg: f64) -> f64 {
    let alpha = model.arch().half_angle;
    let t = angle_deg.to_radians();
    if t.abs() >= alpha - 1e-9 {
        alpha.next_up().copysign(t)
    } else {
        t
    }
}

/// The joint parameter of a hinge or sliding joint stored at `angle_deg` in a state row, for
/// the rows of `conditions`. On a vertical-joint arch |angle| = α names two sections: the
/// vertical section through the intrados springing (θ = ±α) and the radial support just
/// beyond it; the one meant is the one whose rows the state's crown force brings nearest to
/// equality (its rows are active there). Elsewhere as [`joint_parameter`].
pub fn active_joint_parameter(
    model: &ArchModel,
    s: &StateRow,
    angle_deg: f64,
    conditions: &[Condition],
) -> f64 {
    let support = joint_parameter(model, angle_deg);
    let alpha = model.arch().half_angle;
    let vertical = model.form().joints == JointOrientation::Vertical;
    let (Some(f), true) = (CrownForce::of_row(s), vertical && support.abs() > alpha) else {
        return support;
    };
    let section = alpha.copysign(support);
    let phi = s.mu.atan();
    // How far the state is from equality on the given rows of a joint, over |a|.
    let slack = |theta: f64| {
        joint_rows(model, theta, phi)
            .iter()
            .filter(|r| conditions.contains(&r.condition))
            .map(|r| {
                let used = r.a[0] * f.fx + r.a[1] * f.fy + r.a[2] * f.m0 + r.a_lambda * f.lambda;
                let n = (r.a[0] * r.a[0] + r.a[1] * r.a[1] + r.a[2] * r.a[2]).sqrt();
                (r.b - used).abs() / n.max(f64::MIN_POSITIVE)
            })
            .fold(f64::INFINITY, f64::min)
    };
    if slack(section) < slack(support) {
        section
    } else {
        support
    }
}

/// The parameters at which the line of thrust is evaluated: every family of joints sampled
/// about every half degree with its ends (both sides of a point load), the isolated joints
/// (a pointed arch's crown joint, the supports of vertical joints) and every joint of a
/// discrete arch, with the `extra` parameters (the state's hinges and sliding joints), in
/// increasing order.
fn sections(model: &ArchModel, extra: &[f64]) -> Vec<f64> {
    let mut t: Vec<f64> = Vec::new();
    for [lo, hi] in model.families() {
        let n = (((hi - lo) * SECTIONS_PER_RADIAN).ceil() as usize).max(1);
        t.extend((0..=n).map(|i| lo + (hi - lo) * i as f64 / n as f64));
        t.push(hi);
    }
    t.extend(model.isolated_joints());
    t.extend(model.discrete_joints().unwrap_or_default());
    t.extend(extra);
    t.sort_by(f64::total_cmp);
    t.dedup();
    t
}

/// The force F(θ) = F₀ + C_d + λ C_l over W_half and the moment M(θ) = M₀ + C_d^M + λ C_l^M
/// across joint θ (statics.rs).
fn joint_force(model: &ArchModel, c: &CrownForce, theta: f64) -> ([f64; 2], f64) {
    let d = model.dead_load(theta);
    let l = model.live_load(theta);
    let f = [c.fx + d.fx + c.lambda * l.fx, c.fy + d.fy + c.lambda * l.fy];
    (f, c.m0 + d.m + c.lambda * l.m)
}

/// The point where the line of thrust crosses joint θ: the point p of the joint's line with
/// M(θ) − p × F(θ) = 0, F = F₀ + C_d + λ C_l and M = M₀ + C_d^M + λ C_l^M (statics.rs);
/// `None` where the joint carries no compression.
pub fn thrust_point(model: &ArchModel, c: &CrownForce, theta: f64) -> Option<(f64, f64)> {
    let (f, m) = joint_force(model, c, theta);
    let j = model.joint(theta);
    let nu = j.normal();
    if f[0] * nu[0] + f[1] * nu[1] <= 0.0 {
        return None;
    }
    let cross = |p: [f64; 2]| p[0] * f[1] - p[1] * f[0];
    let (i, e) = (j.intrados, j.extrados);
    let s = (m - cross(i)) / cross([e[0] - i[0], e[1] - i[1]]);
    s.is_finite()
        .then(|| (i[0] + s * (e[0] - i[0]), i[1] + s * (e[1] - i[1])))
}

/// Where the line of thrust turns at a point load: the point of the load's line of action
/// (the vertical through its point X) on the resultant line of the sections on the left of
/// the load, and the two joint parameters on either side of it (left, right). `None`
/// without a point load, at λ = 0, or where the left resultant is vertical or absent.
///
/// The resultant lines of the two sides meet on the load's line of action (the moment of
/// the load about any point of that line is zero), so the line of thrust is continuous there
/// with a kink; the two sides' crossings of the load's own joint differ (a radial joint is
/// not the load's line of action), and drawing both joined along the joint would show a
/// step that the statics does not have.
pub fn point_load_kink(model: &ArchModel, c: &CrownForce) -> Option<((f64, f64), [f64; 2])> {
    // The load's own point: on a keystone, or on the springing wedge of a vertical-joint arch,
    // it is not the extrados end of the joint at a.
    let (a, at) = model.point_load()?;
    if c.lambda == 0.0 {
        return None;
    }
    // The joint at a carries the load on its crown side (forms.rs, `split`).
    let sides = if a > 0.0 {
        [a.next_down(), a]
    } else if a < 0.0 {
        [a, a.next_up()]
    } else {
        [0.0, 0.0f64.next_up()]
    };
    let x = at[0];
    let p = thrust_point(model, c, sides[0])?;
    let (f, _) = joint_force(model, c, sides[0]);
    if f[0].abs() < f64::EPSILON * f[1].abs() {
        return None;
    }
    let q = (x, p.1 + (x - p.0) * f[1] / f[0]);
    Some((q, sides))
}

/// The line of thrust of a state: its crossing of every sampled section and of the joints
/// at `angles_deg` (its hinges and sliding joints, so that it passes through the hinges
/// exactly), from the left springing to the right one, NaN where a section carries no
/// compression. At a point load the line turns at [`point_load_kink`]: the crossings of the
/// sections between the kink and the load's joint lie on the resultant lines produced
/// beyond the kink and are left out, so the line runs from the last section before the kink
/// to the kink and on to the crossing of the first section after it.
pub fn line_of_thrust(model: &ArchModel, c: &CrownForce, angles_deg: &[f64]) -> Samples {
    let extra: Vec<f64> = angles_deg
        .iter()
        .map(|&a| joint_parameter(model, a))
        .collect();
    let points = sections(model, &extra)
        .into_iter()
        .map(|t| (t, thrust_point(model, c, t).unwrap_or((f64::NAN, f64::NAN))));
    let Some((q, [left, right])) = point_load_kink(model, c) else {
        return points.map(|(_, p)| p).collect();
    };
    let mut out = Vec::new();
    let mut turned = false;
    for (t, p) in points {
        if t >= right && !turned {
            out.push(q);
            turned = true;
        }
        let beyond = (t <= left && p.0 > q.0) || (t >= right && p.0 < q.0);
        if !beyond {
            out.push(p);
        }
    }
    out
}

/// The line's points on the joints between the voussoirs of a discrete arch (the supports
/// left out): the only sections where it must lie within the arch. Empty for the continuum.
pub fn line_on_joints(model: &ArchModel, c: &CrownForce) -> Samples {
    let joints = model.discrete_joints().unwrap_or_default();
    let inner = joints.len().saturating_sub(1);
    joints
        .iter()
        .take(inner)
        .skip(1)
        .filter_map(|&t| thrust_point(model, c, t))
        .collect()
}

/// The state of largest margin of an arch that stands: every row held with the same
/// distance to spare, its line of thrust as far inside the masonry as the arch allows.
pub fn largest_margin_state(model: &ArchModel, phi: f64, lambda: f64) -> Option<CrownForce> {
    let settings = Settings {
        lambda,
        ..Settings::default()
    };
    let m = general::margin(model, phi, general::RowSet::All, &settings);
    (m.outcome == Outcome::Solved && m.feasible(&settings))
        .then(|| CrownForce::of(&m.crown, lambda))
}

/// The collapse state at λ_max of a live load at friction angle φ, with its mechanism;
/// `None` when λ_max is not a finite solved value.
pub fn load_factor_state(
    model: &ArchModel,
    phi: f64,
) -> Option<(CrownForce, Option<crate::analysis::Mechanism>)> {
    load_factor_collapse(model, phi).map(|c| (c.crown, c.mechanism))
}

/// A collapse state at λ_max with the active rows that name its mechanism.
pub struct Collapse {
    /// Crown force, moment and λ_max.
    pub crown: CrownForce,
    /// The mechanism named by the active rows.
    pub mechanism: Option<crate::analysis::Mechanism>,
    /// The active rows.
    pub active: Vec<general::ActiveRow>,
}

/// The collapse state at λ_max of a live load, with its active rows.
pub fn load_factor_collapse(model: &ArchModel, phi: f64) -> Option<Collapse> {
    let lf = general::load_factor(model, phi, &Settings::default());
    (lf.outcome == Outcome::Solved && lf.lambda.is_finite()).then(|| Collapse {
        crown: CrownForce::of(&lf.crown, lf.lambda),
        mechanism: lf.mechanism,
        active: lf.active,
    })
}

/// The collapse mechanism of a collapse state under the paper's non-associative rule: the
/// mode of the active rows' pattern of the state's own kind that meets the work equation
/// best (as the analysis reports it), with its work equation and its drawing, as a row of
/// mechanisms.parquet (`bifurcation` 0: the state of a case). `None` when the pattern has
/// no mode.
pub fn collapse_mechanism_row(
    model: &ArchModel,
    c: &Collapse,
    (state_id, load_case): (&str, &str),
    mu: f64,
) -> Option<crate::store::MechanismRow> {
    let kind = c.mechanism.as_ref()?.kind;
    let joints = general::pattern_of_rows(&c.active);
    let modes = mechanism_modes(model, &joints, FlowRule::NonAssociative, true).ok()?;
    let state = LimitState {
        crown_force: [c.crown.fx, c.crown.fy],
        crown_moment_origin: c.crown.m0,
        load_factor: c.crown.lambda,
        mu,
    };
    let rank = |f: &VelocityField| (f.kind() != Some(kind), work_equation(model, &state, f));
    let (field, w) = modes
        .fields
        .iter()
        .map(|f| (f, rank(f)))
        .min_by(|a, b| {
            (a.1.0.cmp(&b.1.0)).then(a.1.1.work_residual.total_cmp(&b.1.1.work_residual))
        })
        .map(|(f, (_, w))| (f, w))?;
    Some(mechanism_row(
        model,
        (field, &w),
        modes.dof,
        (state_id, load_case, 0),
        mu,
    ))
}

/// A row of mechanisms.parquet: one velocity field of a limit state with its work equation
/// (eq. 11; the whole balance under the associative rule), its slip and dilatancy at the
/// sliding joints and its drawing; `bifurcation` numbers the bifurcation it belongs to (0:
/// the state of a case).
pub fn mechanism_row(
    model: &ArchModel,
    (field, w): (&VelocityField, &WorkEquation),
    dof: u32,
    (state_id, load_case, bifurcation): (&str, &str, u32),
    mu: f64,
) -> crate::store::MechanismRow {
    let slides: Vec<_> = field.joints.iter().filter(|j| j.slips()).collect();
    crate::store::MechanismRow {
        state_id: state_id.to_string(),
        load_case: load_case.to_string(),
        bifurcation,
        k: model.arch().k,
        mu,
        mechanism: field.kind().map_or("none", |k| k.as_str()).to_string(),
        flow_rule: super::mechanisms::rule_name(field.rule).into(),
        work_loads: w.work_loads,
        work_normal: w.work_normal,
        work_friction: w.work_friction,
        work_residual: super::mechanisms::work_residual(field.rule, w),
        dof,
        sliding_angles_deg: slides.iter().map(|j| j.angle_deg()).collect(),
        slip: slides.iter().map(|j| j.slip).collect(),
        dilatancy: slides.iter().map(|j| j.dilatancy).collect(),
        drawing_json: serde_json::to_string(&drawing(
            model,
            field,
            super::mechanisms::DRAWING_AMPLITUDE,
        ))
        .unwrap_or_default(),
    }
}

/// The limit state at the located point of a collapse curve: the state of largest margin
/// there (zero up to the located tolerance, so it is the limit state), `None` when the
/// margin cannot be solved.
pub fn limit_state_at(model: &ArchModel, phi: f64, lambda: f64) -> Option<CrownForce> {
    let settings = Settings {
        lambda,
        ..Settings::default()
    };
    let m = general::margin(model, phi, general::RowSet::All, &settings);
    (m.outcome == Outcome::Solved).then(|| CrownForce::of(&m.crown, lambda))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::symmetric;
    use crate::model::Friction;

    fn row(k: f64, shape: &str, e: f64, joints: &str, load: &str) -> StateRow {
        StateRow {
            k,
            half_angle_deg: 90.0,
            weight: "annular".into(),
            shape: shape.into(),
            eccentricity: e,
            joint_orientation: joints.into(),
            load: load.into(),
            ..StateRow::default()
        }
    }

    #[test]
    fn general_line_equals_the_symmetric_line_of_the_semicircle() {
        // The collapse state at μ = ∞: crown extrados, haunch intrados, springing extrados.
        let arch = Arch::semicircular(1.5).unwrap();
        let s = symmetric::thickness(&arch, Friction::INFINITE);
        let s = s.found().unwrap();
        let model = model_of_state(&row(s.k, "circular", 0.0, "radial", "self_weight")).unwrap();
        let c = CrownForce {
            fx: s.thrust_over_half_weight,
            fy: 0.0,
            m0: -s.crown_moment,
            lambda: 0.0,
        };
        let line = line_of_thrust(&model, &c, &[]);
        let crown = thrust_point(&model, &c, 0.0).unwrap();
        assert!(
            crown.0.abs() < 1e-12 && (crown.1 - s.k).abs() < 1e-9,
            "{crown:?}"
        );
        let end = line[line.len() - 1];
        assert!((end.0.hypot(end.1) - s.k).abs() < 1e-9, "{end:?}");
        for (x, y) in line {
            let r = x.hypot(y);
            assert!(r > 1.0 - 1e-9 && r < s.k + 1e-9, "r = {r}");
        }
    }

    #[test]
    fn line_of_a_standing_pointed_arch_lies_inside_its_joints() {
        // Vertical joints near the springings are nearly flat: they need more friction.
        for (joints, mu) in [("radial", 0.6f64), ("vertical", 1.5)] {
            let r = row(1.3, "pointed", 0.3, joints, "self_weight");
            let model = model_of_state(&r).unwrap();
            let c = largest_margin_state(&model, mu.atan(), 0.0).unwrap();
            for t in sections(&model, &[]) {
                let p = thrust_point(&model, &c, t).unwrap();
                let j = model.joint(t);
                // p = I + s(E − I) with s strictly inside (0, 1).
                let (i, e) = (j.intrados, j.extrados);
                let s = ((p.0 - i[0]) * (e[0] - i[0]) + (p.1 - i[1]) * (e[1] - i[1]))
                    / ((e[0] - i[0]).powi(2) + (e[1] - i[1]).powi(2));
                assert!(s > 1e-3 && s < 1.0 - 1e-3, "{joints} θ = {t}: s = {s}");
            }
        }
    }

    #[test]
    fn line_of_thrust_turns_on_the_point_load_without_a_step() {
        // The collapse state at λ_max of the pointed arch of studies/influence-line.yaml
        // (e = 0.2, K = 1.3, μ = 0.5) with the load at −20°: its radial joint at −20° is
        // crossed at two points by the resultants of its two sides.
        for at in [-20.0, 35.0] {
            let mut r = row(1.3, "pointed", 0.2, "radial", "point");
            r.at_deg = Some(at);
            let model = model_of_state(&r).unwrap();
            let (c, _) = load_factor_state(&model, 0.5f64.atan()).unwrap();
            assert!(c.lambda > 0.1, "λ_max = {}", c.lambda);
            let ((qx, qy), [left, right]) = point_load_kink(&model, &c).unwrap();
            let a = f64::to_radians(at);
            let x = model.joint(a).extrados;
            // The kink lies on the load's line of action and on both sides' resultant lines.
            assert!((qx - x[0]).abs() < 1e-12, "{qx} vs {}", x[0]);
            for t in [left, right] {
                let p = thrust_point(&model, &c, t).unwrap();
                let (f, _) = joint_force(&model, &c, t);
                let cross = (qx - p.0) * f[1] - (qy - p.1) * f[0];
                assert!(cross.abs() < 1e-9, "θ = {t}: {cross}");
            }
            let (a_left, a_right) = (
                thrust_point(&model, &c, left).unwrap(),
                thrust_point(&model, &c, right).unwrap(),
            );
            let step = (a_left.0 - a_right.0).hypot(a_left.1 - a_right.1);
            assert!(step > 0.02, "the two crossings of the joint differ: {step}");
            let line = line_of_thrust(&model, &c, &[]);
            let k = line.iter().position(|&p| p == (qx, qy)).unwrap();
            // The step along the joint between them, as the line was drawn before, runs at
            // more than 45° to the force of either side.
            let (f_left, _) = joint_force(&model, &c, left);
            let (dx, dy) = (a_right.0 - a_left.0, a_right.1 - a_left.1);
            let cos = (dx * f_left[0] + dy * f_left[1]) / (step * f_left[0].hypot(f_left[1]));
            assert!(cos.abs() < 45f64.to_radians().cos(), "{cos}");
            // Near the kink every segment runs along the force of its side, within 15° (the
            // tangent of the crossings of radial sections is a few degrees off the
            // resultant, more over the short chord to the kink): no step along the joint, no
            // backward segment.
            for i in k.saturating_sub(4)..(k + 4).min(line.len() - 1) {
                let (p, q) = (line[i], line[i + 1]);
                let side = if i < k { left } else { right };
                let (f, _) = joint_force(&model, &c, side);
                let (dx, dy) = (q.0 - p.0, q.1 - p.1);
                let cos = (dx * f[0] + dy * f[1]) / (dx.hypot(dy) * f[0].hypot(f[1]));
                assert!(
                    cos > 15f64.to_radians().cos(),
                    "at {at}°, segment {i}: cos = {cos}"
                );
            }
            // It crosses the load's joint once, where the statics of the side beyond the kink
            // puts it: the crown side's crossing for a load on the extrados.
            let j = model.joint(a);
            let (i0, e0) = (j.intrados, j.extrados);
            let side_of =
                |p: (f64, f64)| (e0[0] - i0[0]) * (p.1 - i0[1]) - (e0[1] - i0[1]) * (p.0 - i0[0]);
            let crossings: Vec<(f64, f64)> = line
                .windows(2)
                .filter(|w| side_of(w[0]) * side_of(w[1]) < 0.0)
                .map(|w| {
                    let (s0, s1) = (side_of(w[0]), side_of(w[1]));
                    let u = s0 / (s0 - s1);
                    (
                        w[0].0 + u * (w[1].0 - w[0].0),
                        w[0].1 + u * (w[1].1 - w[0].1),
                    )
                })
                .filter(|p| (p.0 - x[0]).abs() < 0.5)
                .collect();
            let crown_side = if at < 0.0 { a_right } else { a_left };
            assert_eq!(crossings.len(), 1, "{crossings:?}");
            let d = (crossings[0].0 - crown_side.0).hypot(crossings[0].1 - crown_side.1);
            assert!(d < 1e-9, "at {at}°: {:?} vs {crown_side:?}", crossings[0]);
        }
    }
}
