//! Answers that claim something for a whole range of the swept quantity, confirmed by the
//! state find at the ends of that range before they are given.
//!
//! `always_stands`, `never_stands` and `unbounded` are statements about every K > 1, every
//! μ ≥ 0 or every λ ≥ 0. A route reaches them from one or two margins (at the lower end of a
//! search, or from a ray of a linear programme); a defect there would answer silently for a
//! whole range. Each is therefore checked against independent state finds (the regime of the
//! scene at the ends of the range): the arch must stand at both ends for `always_stands` and
//! `unbounded`, and at neither for `never_stands`. An answer that fails the check becomes
//! `unconfirmed`, with no value. A thickness find also scans the whole range for windows
//! ([`crate::analysis::windows`]), which confirms its answer at every step of the scan.

use super::{Find, Outcome, Scene, Solution, solve_route};
use crate::analysis::Regime;
use crate::model::Friction;

/// Where the ends of a range are taken.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConfirmSettings {
    /// The thinnest arch checked: K = 1 + this (default 1e-9, the thinnest arch every form
    /// is built for).
    pub k_offset: f64,
    /// The thickest arch checked when the find did not scan further (default 3, t/R_c = 1).
    pub k_far: f64,
    /// The load factor standing for "every λ" (default 1000 times the total weight).
    pub lambda_far: f64,
}

impl ConfirmSettings {
    /// The defaults.
    pub const DEFAULT: Self = ConfirmSettings {
        k_offset: 1e-9,
        k_far: 3.0,
        lambda_far: 1e3,
    };
}

impl Default for ConfirmSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Checks a whole-range answer in `out` against the state find at the ends of its range,
/// and replaces it by `unconfirmed` when either end disagrees.
pub(super) fn confirm(scene: &Scene, out: &mut Solution, settings: &ConfirmSettings) {
    let Some(outcome) = out.outcome else {
        return;
    };
    let stands = match outcome {
        Outcome::AlwaysStands | Outcome::Unbounded => true,
        Outcome::NeverStands => false,
        _ => return,
    };
    let ends: Vec<Scene> = match scene.find {
        Find::Thickness => {
            let far = out.k_windows_scanned_to.unwrap_or(settings.k_far);
            [1.0 + settings.k_offset, far]
                .into_iter()
                .map(|k| Scene {
                    arch: scene.arch.with_k(k),
                    ..*scene
                })
                .collect()
        }
        Find::Friction => [Friction::new(0.0), Some(Friction::INFINITE)]
            .into_iter()
            .flatten()
            .map(|friction| Scene { friction, ..*scene })
            .collect(),
        Find::LoadFactor => [0.0, settings.lambda_far]
            .into_iter()
            .map(|lambda| Scene { lambda, ..*scene })
            .collect(),
        _ => return,
    };
    let agrees = ends.into_iter().all(|end| {
        let state = solve_route(&Scene {
            find: Find::State,
            ..end
        });
        (state.regime == Some(Regime::Stable)) == stands
    });
    if !agrees {
        let empty = Solution::with_position(scene);
        *out = Solution {
            outcome: Some(Outcome::Unconfirmed),
            k_windows: std::mem::take(&mut out.k_windows),
            k_windows_scanned_to: out.k_windows_scanned_to,
            k_windows_resolution: out.k_windows_resolution,
            ..empty
        };
    }
}
