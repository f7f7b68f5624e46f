//! The other end of the non-associative gap for every critical find: the first complete
//! solution along the find's path (increasing λ, decreasing K, decreasing μ), searched after
//! the static limit is known ([`crate::analysis::gap`]).

use super::{Find, Outcome, Scene, Solution};
use crate::analysis::forms::ArchModel;
use crate::analysis::gap::{self, Settings};
use crate::analysis::windows::WindowSettings;
use crate::model::{Friction, Load};
use std::f64::consts::FRAC_PI_2;

/// Searches for the first complete solution of a critical find whose static limit was found
/// (or, for the load factor, is unbounded) and records it in `out`.
pub(super) fn record(scene: &Scene, out: &mut Solution) {
    let settings = Settings::DEFAULT;
    let tol_work = crate::analysis::settings::KinematicsSettings::DEFAULT.tol_work;
    let model = |k: f64| ArchModel::new(scene.arch.with_k(k), scene.form, scene.load).ok();
    match scene.find {
        Find::LoadFactor => {
            let static_value = match out.outcome {
                Some(Outcome::Found) => out.load_factor,
                Some(Outcome::Unbounded) => Some(f64::INFINITY),
                _ => return,
            };
            let Some(m) = model(scene.arch.k) else {
                return;
            };
            let search = gap::first_complete_load_factor(&m, scene.friction.angle(), &settings);
            out.set_gap(&search, static_value, 1.0);
        }
        Find::Friction => {
            let (Some(mu_c), Some(m)) = (out.mu_crit, model(scene.arch.k)) else {
                return;
            };
            let search = gap::first_complete_friction(&m, scene.lambda, mu_c, &settings);
            out.set_gap(&search, Some(mu_c), -1.0);
            out.complete_at_static_limit(&search, tol_work);
            if let Some(mu) = out.collapse_value {
                let phi = Friction::new(mu).map_or(FRAC_PI_2, Friction::angle);
                out.collapse_on_loading = on_loading(scene, &m, phi, &settings);
            }
        }
        Find::Thickness => {
            let Some(k_c) = out.k_crit else {
                return;
            };
            let cap = scene
                .form
                .max_k_with_load(scene.arch.half_angle, scene.load);
            let start = out
                .k_windows_scanned_to
                .unwrap_or_else(|| WindowSettings::DEFAULT.upper_end(Some(k_c), cap));
            let search = gap::first_complete_thickness(
                &model,
                scene.friction.angle(),
                scene.lambda,
                k_c,
                start,
                &settings,
            );
            out.set_gap(&search, Some(k_c), -1.0);
            out.complete_at_static_limit(&search, tol_work);
            if let Some(m) = out.collapse_value.and_then(model) {
                out.collapse_on_loading = on_loading(scene, &m, scene.friction.angle(), &settings);
            }
        }
        _ => {}
    }
}

/// The first complete λ of the arch `m` at friction angle `phi` (the collapse value of a
/// fixed-λ find) when it lies below the find's λ: as the live load rose from zero to λ, that
/// arch would already have started to move there, so the find's collapse at λ is never
/// reached on that loading path. `None` without a live load, or when the arch carries the
/// load up to λ (within `tol_gap`·(1 + λ)).
fn on_loading(scene: &Scene, m: &ArchModel, phi: f64, settings: &Settings) -> Option<f64> {
    if scene.lambda <= 0.0 || scene.load == Load::SelfWeight {
        return None;
    }
    let search = gap::first_complete_load_factor(m, phi, settings);
    // A value within the tolerance of zero is zero: the arch moves under its weight alone.
    let first = search.first?.value;
    let first = if first < settings.tol_gap { 0.0 } else { first };
    (first < scene.lambda - settings.tol_gap * (1.0 + scene.lambda)).then_some(first)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::gap::{GapSearch, GapStatus};
    use crate::model::{Arch, ArchForm, Discretisation, WeightModel};

    /// A thickness find whose static limit carries an admissible mechanism, and a search that
    /// found no complete state: `met_nothing` says whether it walked through the limit.
    fn after(met_nothing: bool) -> Solution {
        let scene = Scene {
            arch: Arch::new(1.35, 90.0, WeightModel::Annular, Discretisation::Continuum).unwrap(),
            friction: Friction::new(0.35).unwrap(),
            find: Find::Thickness,
            form: ArchForm::default(),
            load: Load::SelfWeight,
            lambda: 0.0,
        };
        let mut out = crate::scene::solve_static(&scene);
        assert_eq!(out.mechanism_admissible, Some(true));
        let k_c = out.k_crit.unwrap();
        let search = GapSearch {
            status: GapStatus::NoCompleteSolution,
            first: None,
            static_limit: Some(k_c),
            range: [k_c, 1.5],
            vertices: 10,
            met_nothing,
        };
        out.set_gap(&search, Some(k_c), -1.0);
        out.complete_at_static_limit(&search, 1e-6);
        out
    }

    #[test]
    fn a_static_limit_is_the_collapse_only_when_the_walk_went_through_it_meeting_nothing() {
        let through = after(true);
        assert_eq!(through.gap, Some(GapStatus::NoGap));
        assert_eq!(through.collapse_value, through.k_crit);
        assert_eq!(through.gap_width, Some(0.0));
        assert_eq!(through.collapse_hinges, through.hinges);
        assert_eq!(through.collapse_work_loads, through.work_loads);
        assert_eq!(through.collapse_flow_violation, None);
        // A walk that met a complete state it could not finish says so, whatever the static
        // route's mechanism: a gap may lie before the limit.
        let stopped = after(false);
        assert_eq!(stopped.gap, Some(GapStatus::NoCompleteSolution));
        assert_eq!(stopped.collapse_value, None);
    }
}
