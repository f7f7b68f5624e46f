//! Scenes answered by the general three-unknown formulation ([`crate::analysis::general`]):
//! every load case with a live part, every form other than the circular arch with radial
//! joints, and every `load_factor` question (docs/mechanics.md §1).

use super::{Find, Outcome as Answered, Scene, Solution, finite};
use crate::analysis::forms::ArchModel;
use crate::analysis::general::{
    self, ActiveRow, Critical, CrownState, LoadFactor, Outcome, RegimeReport, Settings,
    pattern_of_rows,
};
use crate::analysis::kinematics::{
    FlowRule, LimitState, ModeStatus, VelocityField, mechanism_modes, work_equation,
};
use crate::analysis::windows::WindowSettings;
use crate::analysis::{Mechanism, MechanismKind};

/// Records a limit state: mechanism, crown force and moment (m = −M₀, the crown joint lying
/// on x = 0), hinges and sliding joints.
fn set_state(out: &mut Solution, crown: &CrownState, mechanism: Option<&Mechanism>) {
    out.thrust_over_half_weight = finite(crown.thrust_over_half_weight);
    out.crown_moment = finite(-crown.moment_about_centre);
    out.crown_shear = finite(crown.shear_over_half_weight);
    if let Some(m) = mechanism {
        out.mechanism = Some(m.kind);
        out.hinges = m.hinges.clone();
        out.sliding_joints = m.sliding_joints.clone();
    }
}

/// The collapse mechanism of a limit state and its work equation (paper eqs. 9 and 11), as on
/// the closed-form route: `mechanism_dof` and the `work_*` columns. The pattern is that of the
/// active rows at their exact joint parameters (the two sides of a point load apart), on every
/// form. When the pattern leaves more than one admissible mechanism (a continuum mechanism
/// that is not unique: `mechanism_dof` > 1 or several extreme rays), the one reported is the
/// mechanism of the state's kind that satisfies the work equation best.
fn set_work(out: &mut Solution, model: &ArchModel, at: &StateAt, active: &[ActiveRow]) {
    let joints = pattern_of_rows(active);
    let Ok(modes) = mechanism_modes(model, &joints, FlowRule::NonAssociative, true) else {
        return;
    };
    out.mechanism_dof = Some(modes.dof);
    // A rigid pattern (too few active joints to move) has no mode to check.
    out.mechanism_admissible = Some(false);
    let state = LimitState {
        crown_force: [
            at.crown.thrust_over_half_weight,
            at.crown.shear_over_half_weight,
        ],
        crown_moment_origin: at.crown.moment_about_centre,
        load_factor: at.lambda,
        mu: at.mu,
    };
    let rank = |f: &VelocityField| (f.kind() != Some(at.kind), work_equation(model, &state, f));
    let best = modes.fields.iter().map(rank).min_by(|a, b| {
        a.0.cmp(&b.0)
            .then(a.1.work_residual.total_cmp(&b.1.work_residual))
    });
    if let Some((_, w)) = best {
        out.mechanism_admissible = Some(modes.status == ModeStatus::Admissible);
        out.work_loads = finite(w.work_loads);
        out.work_friction = finite(w.work_friction);
        out.work_residual = finite(w.work_residual);
    }
}

/// A limit state as the work equation needs it.
struct StateAt<'a> {
    crown: &'a CrownState,
    lambda: f64,
    mu: f64,
    kind: MechanismKind,
}

fn outcome_of(o: Outcome) -> Answered {
    match o {
        Outcome::Solved => Answered::Found,
        Outcome::Infeasible => Answered::NeverStands,
        Outcome::Unbounded => Answered::Unbounded,
        Outcome::NotConverged => Answered::NotConverged,
        Outcome::Failed(_) => Answered::Failed,
    }
}

fn set_critical(out: &mut Solution, c: &Critical) -> Option<general::LimitState> {
    out.outcome = Some(match c {
        Critical::Found(_) => Answered::Found,
        Critical::NeverStands => Answered::NeverStands,
        Critical::AlwaysStands => Answered::AlwaysStands,
        Critical::Failed(o) => outcome_of(*o),
    });
    let s = c.found()?.clone();
    set_state(out, &s.state.crown, s.mechanism.as_ref());
    Some(s)
}

/// The regime of the scene at its λ, by the feasibility of the rotational rows alone, the
/// sliding rows alone and all rows.
pub(crate) fn regime(model: &ArchModel, scene: &Scene) -> RegimeReport {
    let settings = Settings {
        lambda: scene.lambda,
        ..Settings::default()
    };
    general::regime(model, scene.friction.angle(), &settings)
}

/// The collapse load factor of the scene.
pub(crate) fn load_factor(model: &ArchModel, scene: &Scene) -> LoadFactor {
    general::load_factor(model, scene.friction.angle(), &Settings::default())
}

/// The critical value of the scene's find with its apex load shared freely between the
/// halves ([`ArchModel::with_shared_apex`]); `None` when the scene has no apex load or the
/// find has no critical value.
fn shared_apex_value(scene: &Scene, settings: &Settings) -> Option<f64> {
    let make = |k: f64| {
        ArchModel::new(scene.arch.with_k(k), scene.form, scene.load)
            .ok()
            .map(ArchModel::with_shared_apex)
    };
    if !make(scene.arch.k).is_some_and(|m| m.has_apex_load()) {
        return None;
    }
    let model = make(scene.arch.k)?;
    match scene.find {
        Find::Thickness => {
            let c = general::thickness_with(
                make,
                scene
                    .form
                    .max_k_with_load(scene.arch.half_angle, scene.load),
                None,
                scene.friction,
                settings,
            );
            c.found()?.k
        }
        Find::Friction => Some(general::friction(&model, settings).found()?.mu),
        Find::LoadFactor => {
            let lf = general::load_factor(&model, scene.friction.angle(), &Settings::default());
            (lf.outcome == Outcome::Solved).then_some(lf.lambda)
        }
        _ => None,
    }
}

/// Fills `out` for a scene of the general route.
pub(super) fn solve(scene: &Scene, out: &mut Solution) {
    solve_one(scene, out);
    if matches!(
        scene.find,
        Find::Thickness | Find::Friction | Find::LoadFactor
    ) {
        let settings = Settings {
            lambda: scene.lambda,
            ..Settings::default()
        };
        out.critical_apex_shared = shared_apex_value(scene, &settings).and_then(finite);
    }
}

/// Fills `out` for a scene of the general route, its apex load (if any) on the right half.
fn solve_one(scene: &Scene, out: &mut Solution) {
    let settings = Settings {
        lambda: scene.lambda,
        ..Settings::default()
    };
    if scene.find == Find::Thickness {
        let make = |k: f64| ArchModel::new(scene.arch.with_k(k), scene.form, scene.load).ok();
        // Over W_half the sliding rows of a circular arch with radial joints (a pointed one
        // with e = 0 included) do not depend on K; those of other forms do.
        let circular_radial = scene.form.joints == crate::model::JointOrientation::Radial
            && scene.form.shape.eccentricity() == 0.0;
        let reference = circular_radial.then_some(scene.arch.k);
        let (c, windows) = general::thickness_windows(
            make,
            scene
                .form
                .max_k_with_load(scene.arch.half_angle, scene.load),
            reference,
            scene.friction,
            &settings,
            &WindowSettings::DEFAULT,
        );
        out.set_windows(windows.as_ref());
        if let Some(s) = set_critical(out, &c)
            && let Some(k) = s.k
        {
            out.k_crit = Some(k);
            out.t_over_r_crit = Some(crate::model::t_over_r_from_k(k));
            let model = ArchModel::new(scene.arch.with_k(k), scene.form, scene.load);
            if let Ok(model) = &model {
                out.set_point_position(model);
            }
            if let (Some(m), Ok(model)) = (&s.mechanism, model) {
                let at = StateAt {
                    crown: &s.state.crown,
                    lambda: scene.lambda,
                    mu: s.mu,
                    kind: m.kind,
                };
                set_work(out, &model, &at, &s.state.active);
            }
        }
        return;
    }
    let Ok(model) = ArchModel::new(scene.arch, scene.form, scene.load) else {
        out.outcome = Some(Answered::Invalid);
        return;
    };
    match scene.find {
        Find::State => {
            out.regime = regime(&model, scene).regime;
        }
        Find::Friction => {
            let c = general::friction(&model, &settings);
            if let Some(s) = set_critical(out, &c) {
                out.mu_crit = Some(s.mu);
                if let Some(m) = &s.mechanism {
                    let at = StateAt {
                        crown: &s.state.crown,
                        lambda: scene.lambda,
                        mu: s.mu,
                        kind: m.kind,
                    };
                    set_work(out, &model, &at, &s.state.active);
                }
            }
        }
        Find::LoadFactor => {
            let lf = load_factor(&model, scene);
            out.outcome = Some(outcome_of(lf.outcome));
            match lf.outcome {
                Outcome::Solved => {
                    out.load_factor = finite(lf.lambda);
                    set_state(out, &lf.crown, lf.mechanism.as_ref());
                    if let Some(m) = &lf.mechanism {
                        let at = StateAt {
                            crown: &lf.crown,
                            lambda: lf.lambda,
                            mu: scene.friction.mu(),
                            kind: m.kind,
                        };
                        set_work(out, &model, &at, &lf.active);
                    }
                }
                Outcome::Unbounded => out.load_factor_unbounded = true,
                _ => {}
            }
        }
        // The extreme thrust states and the thresholds are defined for symmetric self-weight
        // on the circular arch with radial joints only.
        Find::Thrust | Find::Thresholds => out.outcome = Some(Answered::Unsupported),
        Find::Thickness => {}
    }
}
