//! One scene (an arch, a friction coefficient, a load case) and the answer to one question
//! about it: the record shared by `archstudy solve --json` and the rows of results.parquet.

use crate::analysis::forms::{ArchModel, FormError};
use crate::analysis::symmetric::{self, RotationalDomain, SlidingDomain, ThrustState};
use crate::analysis::windows::WindowSettings;
use crate::model::{Arch, ArchForm, Friction, Load, t_over_r_from_k};
use serde::Serialize;
use std::fmt;
use std::time::Instant;

mod confirm;
mod gap_search;
mod general_route;
mod inputs;
mod solution;
mod summary;

pub use inputs::{Inputs, StateAnswer};
use solution::finite;
pub use solution::{Outcome, Solution};
pub use summary::summary;

/// What is asked of a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Find {
    /// The regime at (K, μ) and both thrust domains.
    #[default]
    State,
    /// The collapse thickness K_c at μ.
    Thickness,
    /// The smallest μ at which K stands.
    Friction,
    /// The minimum and maximum thrust states at (K, μ).
    Thrust,
    /// The critical values of the arch under self-weight: K_c at μ = ∞, the μ of the
    /// rotational/mixed bifurcation, μ_min and the K of the mixed/sliding bifurcation.
    Thresholds,
    /// The largest load factor λ of the live load at (K, μ), with its mechanism.
    #[serde(rename = "load_factor")]
    LoadFactor,
}

impl Find {
    /// All finds.
    pub const ALL: [Find; 6] = [
        Find::State,
        Find::Thickness,
        Find::Friction,
        Find::Thrust,
        Find::Thresholds,
        Find::LoadFactor,
    ];

    /// `state`, `thickness`, `friction`, `thrust`, `thresholds` or `load_factor`.
    pub fn as_str(self) -> &'static str {
        match self {
            Find::State => "state",
            Find::Thickness => "thickness",
            Find::Friction => "friction",
            Find::Thrust => "thrust",
            Find::Thresholds => "thresholds",
            Find::LoadFactor => "load_factor",
        }
    }

    /// Parses a find name (`load-factor` is accepted for `load_factor`).
    pub fn parse(s: &str) -> Option<Self> {
        let s = if s == "load-factor" { "load_factor" } else { s };
        Find::ALL.into_iter().find(|f| f.as_str() == s)
    }

    /// True when the find needs K as an input.
    pub fn needs_k(self) -> bool {
        !matches!(self, Find::Thickness | Find::Thresholds)
    }

    /// True when the find needs μ as an input.
    pub fn needs_mu(self) -> bool {
        !matches!(self, Find::Friction | Find::Thresholds)
    }
}

impl fmt::Display for Find {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A scene to analyse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene {
    /// The arch (its K is ignored by the `thickness` find).
    pub arch: Arch,
    /// Friction (ignored by the `friction` find).
    pub friction: Friction,
    /// The question.
    pub find: Find,
    /// Outline and joint planes (circular with radial joints by default).
    pub form: ArchForm,
    /// The load case: self-weight and a live part.
    pub load: Load,
    /// The given load factor λ of the live part (multiples of the total weight), for every
    /// find but `load_factor`, which finds it.
    pub lambda: f64,
}

impl Scene {
    /// A self-weight scene of a circular arch with radial joints (the paper's).
    pub fn new(arch: Arch, friction: Friction, find: Find) -> Self {
        Scene {
            arch,
            friction,
            find,
            form: ArchForm::default(),
            load: Load::SelfWeight,
            lambda: 0.0,
        }
    }

    /// True when the closed forms of the symmetric problem answer the scene: self-weight on a
    /// circular arch with radial joints, and a find other than `load_factor`. Every other
    /// scene goes through the general three-unknown formulation.
    pub fn uses_closed_forms(&self) -> bool {
        self.load == Load::SelfWeight
            && self.form.is_circular_radial()
            && self.find != Find::LoadFactor
    }

    /// Checks that the form exists at this K and α and that a point load sits at a joint
    /// (the K of a `thickness` scene is not checked: the search stays where the form exists).
    pub fn check(&self) -> Result<(), FormError> {
        if self.find == Find::Thickness {
            let probe = self.arch.with_k(1.0 + 1e-9);
            ArchModel::check(probe, self.form, self.load)
        } else {
            ArchModel::check(self.arch, self.form, self.load)
        }
    }
}

/// The inputs of a scene with every output null (the row of a failed case).
pub fn solve_inputs_only(scene: &Scene) -> Solution {
    Solution::empty(scene)
}

/// The `state` answer from already computed domains (the separable grid path).
pub fn state_from_domains(scene: &Scene, rot: &RotationalDomain, sld: &SlidingDomain) -> Solution {
    let mut out = Solution::empty(scene);
    StateAnswer::of(rot, sld).fill(&mut out);
    out
}

/// Analyses one scene: the static limit of a critical find and the first complete solution
/// along its path ([`crate::analysis::gap`]). An answer for a whole range (`always_stands`,
/// `never_stands`, `unbounded`) is confirmed by the state find at the ends of that range
/// ([`confirm`]).
pub fn solve(scene: &Scene) -> Solution {
    solve_with(scene, true)
}

/// [`solve`] without the search for the first complete solution: the static limit alone, its
/// mechanism and its confirmation, with `gap` and the `collapse_*` keys null. For callers that
/// need the static limit only (it costs the search's time less).
pub fn solve_static(scene: &Scene) -> Solution {
    solve_with(scene, false)
}

fn solve_with(scene: &Scene, gap: bool) -> Solution {
    let start = Instant::now();
    let mut out = solve_route(scene);
    if gap {
        gap_search::record(scene, &mut out);
    }
    confirm::confirm(scene, &mut out, &confirm::ConfirmSettings::DEFAULT);
    out.name_springings_as_given();
    out.solve_time_us = start.elapsed().as_secs_f64() * 1e6;
    out
}

/// Analyses one scene by its route, without the confirmation of [`solve`].
fn solve_route(scene: &Scene) -> Solution {
    let mut out = Solution::with_position(scene);
    if !scene.uses_closed_forms() {
        general_route::solve(scene, &mut out);
        return out;
    }
    match scene.find {
        Find::State => {
            let d = symmetric::domains(&scene.arch, scene.friction);
            out = state_from_domains(scene, &d.rotational, &d.sliding);
        }
        Find::Thickness => {
            let c = symmetric::thickness(&scene.arch, scene.friction);
            let windows = symmetric::thickness_windows_with(
                &scene.arch,
                scene.friction,
                &c,
                &symmetric::Settings::DEFAULT,
                &WindowSettings::DEFAULT,
            );
            let Some(windows) = windows else {
                // The scan of K disagrees with the closed forms: the general route, which
                // reconciles its search with its own scan, answers.
                general_route::solve(scene, &mut out);
                return out;
            };
            out.set_windows(Some(&windows));
            if let Some(s) = out.set_critical(&c) {
                out.set_mechanism(&scene.arch, &s);
                out.k_crit = Some(s.k);
                out.t_over_r_crit = Some(t_over_r_from_k(s.k));
            }
        }
        Find::Friction => {
            let c = symmetric::friction(&scene.arch);
            if let Some(s) = out.set_critical(&c) {
                out.set_mechanism(&scene.arch, &s);
                out.mu_crit = Some(s.mu);
            }
        }
        Find::Thresholds => {
            let a = &scene.arch;
            let kc = symmetric::thickness(a, Friction::INFINITE);
            out.outcome = Some(Outcome::of_critical(&kc));
            if let Some(s) = kc.found() {
                out.k_c_rotational = Some(s.k);
                out.mu_rotational_mixed = symmetric::friction(&a.with_k(s.k)).found().map(|f| f.mu);
            }
            if let Some(m) = symmetric::sliding_threshold(a).found() {
                out.mu_min = Some(m.mu);
                out.k_mixed_sliding = Friction::new(m.mu)
                    .and_then(|f| symmetric::thickness(a, f).found().map(|s| s.k));
            }
        }
        Find::Thrust => {
            let states = symmetric::thrust(&scene.arch, scene.friction);
            out.outcome = Some(if states.is_some() {
                Outcome::Found
            } else {
                Outcome::NeverStands
            });
            if let Some((lo, hi)) = states {
                let rec = |s: &ThrustState| (finite(s.thrust_over_half_weight), s.hinges.clone());
                let (tmin, hmin) = rec(&lo);
                let (tmax, hmax) = rec(&hi);
                out.thrust_min = tmin;
                out.thrust_max = tmax;
                out.hinges_min = hmin;
                out.hinges_max = hmax;
                out.sliding_joints_min = lo.sliding_joints.clone();
                out.sliding_joints_max = hi.sliding_joints.clone();
            }
        }
        // Not reached: load_factor scenes take the general route.
        Find::LoadFactor => {}
    }
    out
}
