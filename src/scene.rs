//! One scene (an arch, a friction coefficient, a load case) and the answer to one question
//! about it: the record shared by `archstudy solve --json` and the rows of results.parquet.

use crate::analysis::forms::{ArchModel, FormError};
use crate::analysis::kinematics::collapse_mechanism;
use crate::analysis::symmetric::{
    self, Critical, CriticalState, RotationalDomain, SlidingDomain, ThrustState,
};
use crate::analysis::{Hinge, Regime, SlidingJoint};
use crate::model::{Arch, ArchForm, Friction, Load, t_over_r_from_k};
use serde::Serialize;
use std::fmt;
use std::time::Instant;

mod general_route;

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
            ArchModel::new(probe, self.form, self.load).map(|_| ())
        } else {
            ArchModel::new(self.arch, self.form, self.load).map(|_| ())
        }
    }
}

/// A hinge as stored: angle and face name.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HingeRecord {
    /// Angle from the crown, degrees.
    pub angle_deg: f64,
    /// `intrados` or `extrados`.
    pub face: &'static str,
}

/// A sliding joint as stored: angle and sense.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlidingRecord {
    /// Angle from the crown, degrees.
    pub angle_deg: f64,
    /// `outward` or `inward`: how the crown-side part moves.
    pub sense: &'static str,
}

fn hinge_records(h: &[Hinge]) -> Vec<HingeRecord> {
    h.iter()
        .map(|h| HingeRecord {
            angle_deg: h.angle_deg,
            face: h.face.as_str(),
        })
        .collect()
}

fn sliding_records(s: &[SlidingJoint]) -> Vec<SlidingRecord> {
    s.iter()
        .map(|s| SlidingRecord {
            angle_deg: s.angle_deg,
            sense: s.sense.as_str(),
        })
        .collect()
}

/// The answer for one scene: every key of `archstudy solve --json`, `null` where a value does
/// not exist (an empty domain, an unbounded end, a quantity the find does not produce).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Solution {
    /// The question asked.
    pub find: &'static str,
    /// K = R/r given (null for `thickness`).
    pub k: Option<f64>,
    /// t/R_c given (null for `thickness`).
    pub t_over_r: Option<f64>,
    /// μ given (null for infinite friction and for `friction`).
    pub mu: Option<f64>,
    /// True when μ is infinite.
    pub mu_infinite: bool,
    /// Half-embrace angle α in degrees.
    pub half_angle_deg: f64,
    /// `annular` or `centreline`.
    pub weight: &'static str,
    /// Voussoir count, null for the continuum.
    pub voussoirs: Option<u32>,
    /// `circular` or `pointed`.
    pub shape: &'static str,
    /// Eccentricity e of a pointed arch (null for a circular one).
    pub eccentricity: Option<f64>,
    /// `radial` or `vertical` joint planes.
    pub joints: &'static str,
    /// The load case kind: `self_weight`, `horizontal` or `point`.
    pub load: &'static str,
    /// Position of a point load, degrees from the crown (null for other loads).
    pub at_deg: Option<f64>,
    /// The given load factor λ of the live part (null for self-weight and for `load_factor`).
    pub lambda: Option<f64>,
    /// `found`, `never_stands` or `always_stands` for critical finds (`found` or `never_stands`
    /// for thrust; `found`, `unbounded` or `never_stands` for load_factor; `failed` or
    /// `not_converged` when the general route could not decide), null for state.
    pub outcome: Option<&'static str>,
    /// Regime (state find).
    pub regime: Option<&'static str>,
    /// Lower end of H^r over W_half.
    pub thrust_r_min: Option<f64>,
    /// Upper end of H^r over W_half.
    pub thrust_r_max: Option<f64>,
    /// Lower end of H^s over W_half.
    pub thrust_s_min: Option<f64>,
    /// Upper end of H^s over W_half.
    pub thrust_s_max: Option<f64>,
    /// Collapse thickness (thickness find).
    pub k_crit: Option<f64>,
    /// t/R_c at the collapse thickness.
    pub t_over_r_crit: Option<f64>,
    /// Critical friction (friction find).
    pub mu_crit: Option<f64>,
    /// `rotational`, `mixed` or `sliding` at the critical state.
    pub mechanism: Option<&'static str>,
    /// Crown thrust of the critical state over W_half.
    pub thrust_over_half_weight: Option<f64>,
    /// Crown moment m/(W_half·r) of the critical state: the line of thrust crosses the crown
    /// joint at height m/h over r (with h = thrust_over_half_weight).
    pub crown_moment: Option<f64>,
    /// Vertical force F_y/W_half at the crown of the critical state (general route only: zero
    /// under symmetric loading, null on the closed-form route).
    pub crown_shear: Option<f64>,
    /// Largest load factor λ (multiples of the total weight) of the live load (load_factor
    /// find); null when unbounded or when no λ ≥ 0 lets the arch stand.
    pub load_factor: Option<f64>,
    /// True when every λ ≥ 0 lets the arch stand (load_factor find).
    pub load_factor_unbounded: bool,
    /// Hinges of the critical state.
    pub hinges: Vec<HingeRecord>,
    /// Sliding joints of the critical state.
    pub sliding_joints: Vec<SlidingRecord>,
    /// dL^(a): work of the loads on the collapse mechanism of the critical state (eq. 11),
    /// over W_half·r for a field whose largest block-corner speed is 1.
    pub work_loads: Option<f64>,
    /// dL^(r,t) = −μ Σ R^n |dr^t| over the sliding joints of that mechanism (eq. 11), same units.
    pub work_friction: Option<f64>,
    /// |dL^(a) + dL^(r,t)| over the scale of the block works: about 0 when the state and its
    /// mechanism satisfy eq. (11).
    pub work_residual: Option<f64>,
    /// Degrees of freedom of the blocks between the active joints of the critical state (2 for
    /// a symmetric five-joint state: the collapse mechanism is its symmetric mode).
    pub mechanism_dof: Option<u32>,
    /// Collapse thickness at μ = ∞ (thresholds find).
    pub k_c_rotational: Option<f64>,
    /// μ of the rotational/mixed bifurcation: the critical friction at K_c (thresholds find).
    pub mu_rotational_mixed: Option<f64>,
    /// μ_min: below it H^s is empty for every K (thresholds find).
    pub mu_min: Option<f64>,
    /// K of the mixed/sliding bifurcation: the collapse thickness at μ_min (thresholds find).
    pub k_mixed_sliding: Option<f64>,
    /// Minimum admissible thrust over W_half (thrust find).
    pub thrust_min: Option<f64>,
    /// Maximum admissible thrust over W_half (null when unbounded).
    pub thrust_max: Option<f64>,
    /// Hinges of the minimum-thrust state.
    pub hinges_min: Vec<HingeRecord>,
    /// Hinges of the maximum-thrust state.
    pub hinges_max: Vec<HingeRecord>,
    /// Sliding joints of the minimum-thrust state.
    pub sliding_joints_min: Vec<SlidingRecord>,
    /// Sliding joints of the maximum-thrust state.
    pub sliding_joints_max: Vec<SlidingRecord>,
    /// Wall time of the analysis in microseconds.
    pub solve_time_us: f64,
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

impl Solution {
    fn empty(scene: &Scene) -> Self {
        let a = &scene.arch;
        let (k, t) = if scene.find.needs_k() {
            (Some(a.k), Some(a.t_over_r()))
        } else {
            (None, None)
        };
        let mu = if scene.find.needs_mu() {
            finite(scene.friction.mu())
        } else {
            None
        };
        Solution {
            find: scene.find.as_str(),
            k,
            t_over_r: t,
            mu,
            mu_infinite: scene.find.needs_mu() && scene.friction.is_infinite(),
            half_angle_deg: a.half_angle_deg(),
            weight: a.weight.as_str(),
            voussoirs: a.joints.voussoirs(),
            shape: scene.form.shape.as_str(),
            eccentricity: match scene.form.shape {
                crate::model::Shape::Pointed { eccentricity } => Some(eccentricity),
                crate::model::Shape::Circular => None,
            },
            joints: scene.form.joints.as_str(),
            load: scene.load.as_str(),
            at_deg: scene.load.at_deg(),
            lambda: (scene.load.is_live() && scene.find != Find::LoadFactor)
                .then_some(scene.lambda),
            outcome: None,
            regime: None,
            thrust_r_min: None,
            thrust_r_max: None,
            thrust_s_min: None,
            thrust_s_max: None,
            k_crit: None,
            t_over_r_crit: None,
            mu_crit: None,
            mechanism: None,
            thrust_over_half_weight: None,
            crown_moment: None,
            crown_shear: None,
            load_factor: None,
            load_factor_unbounded: false,
            hinges: Vec::new(),
            sliding_joints: Vec::new(),
            work_loads: None,
            work_friction: None,
            work_residual: None,
            mechanism_dof: None,
            k_c_rotational: None,
            mu_rotational_mixed: None,
            mu_min: None,
            k_mixed_sliding: None,
            thrust_min: None,
            thrust_max: None,
            hinges_min: Vec::new(),
            hinges_max: Vec::new(),
            sliding_joints_min: Vec::new(),
            sliding_joints_max: Vec::new(),
            solve_time_us: 0.0,
        }
    }

    fn set_critical(&mut self, c: &Critical) -> Option<CriticalState> {
        self.outcome = Some(c.outcome_str());
        let s = c.found()?.clone();
        self.mechanism = Some(s.mechanism.kind.as_str());
        self.thrust_over_half_weight = finite(s.thrust_over_half_weight);
        self.crown_moment = finite(s.crown_moment);
        self.hinges = hinge_records(&s.mechanism.hinges);
        self.sliding_joints = sliding_records(&s.mechanism.sliding_joints);
        Some(s)
    }

    /// The collapse mechanism of a found critical state and its work equation.
    fn set_mechanism(&mut self, arch: &Arch, s: &CriticalState) {
        let m = collapse_mechanism(arch, s);
        self.mechanism_dof = Some(m.mechanism_dof);
        if let Some(w) = m.work {
            self.work_loads = finite(w.work_loads);
            self.work_friction = finite(w.work_friction);
            self.work_residual = finite(w.work_residual);
        }
    }

    /// The regime, parsed back.
    pub fn regime(&self) -> Option<Regime> {
        self.regime.and_then(Regime::parse)
    }
}

/// The inputs of a scene with every output null (the row of a failed case).
pub fn solve_inputs_only(scene: &Scene) -> Solution {
    Solution::empty(scene)
}

/// The `state` answer from already computed domains (the separable grid path).
pub fn state_from_domains(scene: &Scene, rot: &RotationalDomain, sld: &SlidingDomain) -> Solution {
    let mut out = Solution::empty(scene);
    out.regime = Some(symmetric::regime_of(rot, sld).as_str());
    let (hr, hs) = (rot.interval, sld.interval);
    if !hr.is_empty() {
        out.thrust_r_min = finite(hr.lo);
        out.thrust_r_max = finite(hr.hi);
    }
    if !hs.is_empty() {
        out.thrust_s_min = finite(hs.lo);
        out.thrust_s_max = finite(hs.hi);
    }
    out
}

/// Analyses one scene.
pub fn solve(scene: &Scene) -> Solution {
    let start = Instant::now();
    let mut out = Solution::empty(scene);
    if !scene.uses_closed_forms() {
        general_route::solve(scene, &mut out);
        out.solve_time_us = start.elapsed().as_secs_f64() * 1e6;
        return out;
    }
    match scene.find {
        Find::State => {
            let d = symmetric::domains(&scene.arch, scene.friction);
            out = state_from_domains(scene, &d.rotational, &d.sliding);
        }
        Find::Thickness => {
            let c = symmetric::thickness(&scene.arch, scene.friction);
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
            out.outcome = Some(kc.outcome_str());
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
                "found"
            } else {
                "never_stands"
            });
            if let Some((lo, hi)) = states {
                let rec =
                    |s: &ThrustState| (finite(s.thrust_over_half_weight), hinge_records(&s.hinges));
                let (tmin, hmin) = rec(&lo);
                let (tmax, hmax) = rec(&hi);
                out.thrust_min = tmin;
                out.thrust_max = tmax;
                out.hinges_min = hmin;
                out.hinges_max = hmax;
                out.sliding_joints_min = sliding_records(&lo.sliding_joints);
                out.sliding_joints_max = sliding_records(&hi.sliding_joints);
            }
        }
        // Not reached: load_factor scenes take the general route.
        Find::LoadFactor => {}
    }
    out.solve_time_us = start.elapsed().as_secs_f64() * 1e6;
    out
}

/// A short readable summary of a solution (the output of `archstudy solve` without `--json`).
pub fn summary(s: &Solution) -> String {
    use std::fmt::Write;
    let mut o = String::new();
    let opt = |x: Option<f64>| x.map_or("none".to_string(), |v| format!("{v:.10}"));
    let mu = if s.mu_infinite {
        "inf".to_string()
    } else {
        opt(s.mu)
    };
    let n = s
        .voussoirs
        .map_or("continuum".to_string(), |n| format!("{n} voussoirs"));
    let _ = writeln!(
        o,
        "arch: half-angle {}°, {} weight, {}; K = {}, t/R_c = {}, μ = {}",
        s.half_angle_deg,
        s.weight,
        n,
        opt(s.k),
        opt(s.t_over_r),
        mu
    );
    if s.shape != "circular" || s.joints != "radial" || s.load != "self_weight" {
        let mut form = s.shape.to_string();
        if let Some(e) = s.eccentricity {
            form.push_str(&format!(" (e = {e})"));
        }
        let mut load = match s.at_deg {
            Some(a) => format!("self-weight and a point load at {a}°"),
            None if s.load == "horizontal" => "self-weight and a horizontal load".to_string(),
            None => "self-weight".to_string(),
        };
        if let Some(l) = s.lambda {
            load.push_str(&format!(", λ = {l}"));
        }
        let _ = writeln!(o, "form: {form}, {} joints; load: {load}", s.joints);
    }
    let hinges = |h: &[HingeRecord]| {
        h.iter()
            .map(|h| format!("{:.4}° {}", h.angle_deg, h.face))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let sliding = |h: &[SlidingRecord]| {
        h.iter()
            .map(|h| format!("{:.4}° {}", h.angle_deg, h.sense))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match s.find {
        "state" => {
            let _ = writeln!(o, "regime: {}", s.regime.unwrap_or("?"));
            let _ = writeln!(
                o,
                "H^r/W_half: [{}, {}]",
                opt(s.thrust_r_min),
                opt(s.thrust_r_max)
            );
            let _ = writeln!(
                o,
                "H^s/W_half: [{}, {}]",
                opt(s.thrust_s_min),
                opt(s.thrust_s_max)
            );
        }
        _ => {
            let outcome = s.outcome.unwrap_or("");
            match (s.find, outcome) {
                ("thickness", "never_stands") => {
                    let _ = writeln!(
                        o,
                        "no collapse thickness: the arch cannot stand at this μ for any K"
                    );
                }
                ("thickness", "always_stands") => {
                    let _ = writeln!(o, "no collapse thickness: the arch stands for every K > 1");
                }
                ("friction", "never_stands") => {
                    let _ = writeln!(
                        o,
                        "no critical friction: the arch cannot stand at this K for any μ"
                    );
                }
                ("friction", "always_stands") => {
                    let _ = writeln!(o, "critical friction 0: the arch stands without friction");
                }
                ("load_factor", "unbounded") => {
                    let _ = writeln!(
                        o,
                        "load factor unbounded: the arch carries every multiple of the live load"
                    );
                }
                ("load_factor", "never_stands") => {
                    let _ = writeln!(o, "no load factor: the arch cannot stand under this load");
                }
                (_, "invalid") => {
                    let _ = writeln!(o, "no answer: the form does not exist for these inputs");
                }
                (_, "unsupported") => {
                    let _ = writeln!(
                        o,
                        "no answer: this find is defined for self-weight on a circular arch with radial joints only"
                    );
                }
                (_, "failed" | "not_converged") => {
                    let _ = writeln!(o, "no answer: the analysis {}", outcome.replace('_', " "));
                }
                _ => {}
            }
            if s.find == "thresholds" {
                let _ = writeln!(o, "K_c (μ = ∞) = {}", opt(s.k_c_rotational));
                let _ = writeln!(
                    o,
                    "μ at the rotational/mixed bifurcation = {}",
                    opt(s.mu_rotational_mixed)
                );
                let _ = writeln!(o, "μ_min = {}", opt(s.mu_min));
                let _ = writeln!(
                    o,
                    "K at the mixed/sliding bifurcation = {}",
                    opt(s.k_mixed_sliding)
                );
            }
            if let Some(k) = s.k_crit {
                let _ = writeln!(
                    o,
                    "K_c = {k:.12} ≈ {k:.4}  (t/R_c = {:.12})",
                    s.t_over_r_crit.unwrap_or(f64::NAN)
                );
            }
            if let Some(m) = s.mu_crit {
                let _ = writeln!(o, "μ_c = {m:.12} ≈ {m:.3}");
            }
            if let Some(l) = s.load_factor {
                let _ = writeln!(
                    o,
                    "λ_max = {l:.12} ≈ {l:.4} (multiples of the total weight)"
                );
            }
            if let Some(m) = s.mechanism {
                let _ = writeln!(o, "mechanism: {m}");
            }
            if let Some(h) = s.thrust_over_half_weight {
                let _ = writeln!(o, "H/W_half = {h:.12} ≈ {h:.3}");
            }
            if let Some(v) = s.crown_shear
                && v != 0.0
            {
                let _ = writeln!(o, "V/W_half at the crown = {v:.12}");
            }
            if !s.hinges.is_empty() {
                let _ = writeln!(o, "hinges: {}", hinges(&s.hinges));
            }
            if !s.sliding_joints.is_empty() {
                let _ = writeln!(o, "sliding joints: {}", sliding(&s.sliding_joints));
            }
            if let (Some(dof), Some(a), Some(f), Some(r)) = (
                s.mechanism_dof,
                s.work_loads,
                s.work_friction,
                s.work_residual,
            ) {
                let _ = writeln!(
                    o,
                    "work equation: dL(a) = {a:.6e}, dL(r,t) = {f:.6e}, residual {r:.1e} \
                     (mechanism dof {dof})"
                );
            }
            if s.find == "thrust" {
                if s.outcome == Some("never_stands") {
                    let _ = writeln!(o, "no admissible state: the arch cannot stand");
                } else {
                    let _ = writeln!(
                        o,
                        "H_min/W_half = {}  hinges: {}",
                        opt(s.thrust_min),
                        hinges(&s.hinges_min)
                    );
                    if !s.sliding_joints_min.is_empty() {
                        let _ = writeln!(o, "  sliding: {}", sliding(&s.sliding_joints_min));
                    }
                    let _ = writeln!(
                        o,
                        "H_max/W_half = {}  hinges: {}",
                        opt(s.thrust_max),
                        hinges(&s.hinges_max)
                    );
                    if !s.sliding_joints_max.is_empty() {
                        let _ = writeln!(o, "  sliding: {}", sliding(&s.sliding_joints_max));
                    }
                }
            }
        }
    }
    let _ = writeln!(o, "solve time: {:.1} µs", s.solve_time_us);
    o
}
