//! The answer to one scene: the record shared by `archstudy solve --json` and the rows of
//! results.parquet. Its kinds (find, weight, regime, mechanism, outcome, faces, senses) are
//! enums; they become strings only where they are written (JSON, Parquet).

use super::{Find, Scene};
use crate::analysis::forms::ArchModel;
use crate::analysis::gap::{GapSearch, GapStatus};
use crate::analysis::kinematics::{ModeStatus, collapse_mechanism};
use crate::analysis::symmetric::{Critical, CriticalState};
use crate::analysis::windows::{Span, Windows};
use crate::analysis::{Hinge, MechanismKind, Regime, SlidingJoint};
use crate::model::{Arch, Load, WeightModel};
use serde::Serialize;
use std::fmt;

/// What became of an analysis that looks for a critical value, a thrust or a load factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// The value was found.
    Found,
    /// No admissible state exists (the arch cannot stand).
    NeverStands,
    /// The arch stands whatever the swept quantity (no critical value).
    AlwaysStands,
    /// Every load factor λ ≥ 0 lets the arch stand.
    Unbounded,
    /// The general route did not converge.
    NotConverged,
    /// The general route failed.
    Failed,
    /// The route answered for a whole range (`always_stands`, `never_stands`, `unbounded`)
    /// and the state find at an end of that range contradicted it: no answer is reported.
    Unconfirmed,
    /// The form does not exist for these inputs.
    Invalid,
    /// The find is not defined for this scene.
    Unsupported,
}

impl Outcome {
    /// Every outcome.
    pub const ALL: [Outcome; 9] = [
        Outcome::Found,
        Outcome::NeverStands,
        Outcome::AlwaysStands,
        Outcome::Unbounded,
        Outcome::NotConverged,
        Outcome::Failed,
        Outcome::Unconfirmed,
        Outcome::Invalid,
        Outcome::Unsupported,
    ];

    /// The stored name, e.g. `never_stands`.
    pub fn as_str(self) -> &'static str {
        match self {
            Outcome::Found => "found",
            Outcome::NeverStands => "never_stands",
            Outcome::AlwaysStands => "always_stands",
            Outcome::Unbounded => "unbounded",
            Outcome::NotConverged => "not_converged",
            Outcome::Failed => "failed",
            Outcome::Unconfirmed => "unconfirmed",
            Outcome::Invalid => "invalid",
            Outcome::Unsupported => "unsupported",
        }
    }

    /// Parses a stored name.
    pub fn parse(s: &str) -> Option<Self> {
        Outcome::ALL.into_iter().find(|o| o.as_str() == s)
    }

    /// The outcome of a closed-form critical value.
    pub fn of_critical(c: &Critical) -> Self {
        match c {
            Critical::Found(_) => Outcome::Found,
            Critical::NeverStands => Outcome::NeverStands,
            Critical::AlwaysStands => Outcome::AlwaysStands,
        }
    }
}

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The answer for one scene: every key of `archstudy solve --json`, `null` where a value does
/// not exist (an empty domain, an unbounded end, a quantity the find does not produce).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Solution {
    /// The question asked.
    pub find: Find,
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
    /// The weight model.
    pub weight: WeightModel,
    /// Voussoir count, null for the continuum.
    pub voussoirs: Option<u32>,
    /// `circular` or `pointed`.
    pub shape: &'static str,
    /// Eccentricity e of a pointed arch (null for a circular one).
    pub eccentricity: Option<f64>,
    /// `radial` or `vertical` joint planes.
    pub joints: &'static str,
    /// True when the crown lies inside one block, the keystone: the form's keystone in the
    /// continuum, an odd voussoir count.
    pub keystone: bool,
    /// The load case kind: `self_weight`, `horizontal` or `point`.
    pub load: &'static str,
    /// Position of a point load, degrees from the crown (null for other loads).
    pub at_deg: Option<f64>,
    /// Position of a point load as x/L (null for other loads, and when α > 90°).
    pub at_x: Option<f64>,
    /// Width of a point load spread over the extrados, as a fraction of the extrados span
    /// (0 for a concentrated point load, null for other loads).
    pub load_width: Option<f64>,
    /// The given load factor λ of the live part (null for self-weight and for `load_factor`).
    pub lambda: Option<f64>,
    /// `found`, `never_stands` or `always_stands` for critical finds (`found` or `never_stands`
    /// for thrust; `found`, `unbounded` or `never_stands` for load_factor; `failed` or
    /// `not_converged` when the general route could not decide), null for state.
    pub outcome: Option<Outcome>,
    /// Regime (state find).
    pub regime: Option<Regime>,
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
    /// Every interval of K on which the arch stands, as [from, to] pairs in increasing K
    /// (thickness find): the first `from` is `k_crit`; `to` is null for a window that is open
    /// at the end of the scan. A window narrower than `k_windows_resolution` may be missed.
    pub k_windows: Vec<Span>,
    /// The largest K the window scan reached (thickness find).
    pub k_windows_scanned_to: Option<f64>,
    /// The step of the window scan in K (thickness find).
    pub k_windows_resolution: Option<f64>,
    /// Critical friction (friction find).
    pub mu_crit: Option<f64>,
    /// `rotational`, `mixed` or `sliding` at the critical state.
    pub mechanism: Option<MechanismKind>,
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
    pub hinges: Vec<Hinge>,
    /// Sliding joints of the critical state.
    pub sliding_joints: Vec<SlidingJoint>,
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
    /// True when the reported mechanism obeys every flow rule at the state: normality at each
    /// hinge (eq. 5) and slip in the sense of the friction force at each sliding joint (eq.
    /// 10), so that its work equation is a check of the state (`work_residual` ≤
    /// `KinematicsSettings::tol_work`). False when no mode of the state's pattern does (a
    /// rigid pattern has none, and no work equation: the `work_*` keys are then null): the
    /// state bounds the collapse of the static problem, but the pattern has no
    /// non-associative mechanism (docs/mechanics.md §1); the mode reported then slides in the
    /// right senses when one does, so that the work equation still holds.
    pub mechanism_admissible: Option<bool>,
    /// Which end of the non-associative gap the find's value is (critical finds): `no_gap` (the
    /// static limit is itself complete: a mechanism can start there and nowhere before it),
    /// `gap` (a complete solution comes first along the find's path: `collapse_value`),
    /// `no_complete_solution` (none within the searched range, `gap_searched_to`) or `failed`.
    pub gap: Option<GapStatus>,
    /// The first complete solution along the find's path (increasing λ, decreasing K,
    /// decreasing μ): the collapse, the conservative end of the gap. The static limit
    /// (`load_factor`, `k_crit`, `mu_crit`) is the other end: beyond it no equilibrium exists.
    pub collapse_value: Option<f64>,
    /// The width of the gap along the path: λ_max − λ_collapse, K_collapse − K_c or
    /// μ_collapse − μ_c (zero without a gap; +∞ when λ_max is unbounded).
    pub gap_width: Option<f64>,
    /// The end of the path that the search for a complete solution started from (λ: its
    /// largest value).
    pub gap_searched_to: Option<f64>,
    /// `rotational`, `mixed` or `sliding`: the mechanism of the first complete solution.
    pub collapse_mechanism: Option<MechanismKind>,
    /// Hinges of that mechanism (the face that stays closed).
    pub collapse_hinges: Vec<Hinge>,
    /// Sliding joints of that mechanism, with the sense of the crown-side part.
    pub collapse_sliding_joints: Vec<SlidingJoint>,
    /// Angles (degrees) of the joints that open at both faces in that mechanism (lift-off:
    /// they carry no force).
    pub collapse_lifted_joints: Vec<f64>,
    /// Crown thrust F_x/W_half of the complete solution's state.
    pub collapse_thrust_over_half_weight: Option<f64>,
    /// Crown shear F_y/W_half of that state.
    pub collapse_crown_shear: Option<f64>,
    /// Crown moment m/(W_half·r) of that state (as `crown_moment`).
    pub collapse_crown_moment: Option<f64>,
    /// dL^(a) of the complete solution's mechanism (largest block-corner speed 1).
    pub collapse_work_loads: Option<f64>,
    /// dL^(r,t) = −μ Σ N |δr^t| of that mechanism.
    pub collapse_work_friction: Option<f64>,
    /// |dL^(a) + dL^(r,n) + dL^(r,t)| over its largest term: eq. (11) holds at zero.
    pub collapse_work_residual: Option<f64>,
    /// Largest breach of a flow rule by that mechanism at that state (normality, no
    /// interpenetration, maximum dissipation), relative to the joint force: zero when every
    /// moving joint obeys them.
    pub collapse_flow_violation: Option<f64>,
    /// Fixed-λ thickness and friction finds with a live load: the first complete λ of the arch
    /// at the find's collapse value, when it lies below the scene's λ. The load rising from
    /// zero would have set that arch moving there, before λ was reached, so the find's
    /// collapse at λ lies beyond a collapse on the way up. Null otherwise.
    pub collapse_on_loading: Option<f64>,
    /// A point load at the apex of a pointed arch with radial joints sits on the crown joint
    /// between the halves, and its split between them is statically indeterminate: the
    /// critical value of the find (μ_c, K_c or λ_max) when the split is free (the most
    /// favourable one). The find's own value puts the whole load on the right half, the least
    /// favourable split; the two bound every split (docs/loads-and-geometries.md). Null for
    /// every other scene.
    pub critical_apex_shared: Option<f64>,
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
    pub hinges_min: Vec<Hinge>,
    /// Hinges of the maximum-thrust state.
    pub hinges_max: Vec<Hinge>,
    /// Sliding joints of the minimum-thrust state.
    pub sliding_joints_min: Vec<SlidingJoint>,
    /// Sliding joints of the maximum-thrust state.
    pub sliding_joints_max: Vec<SlidingJoint>,
    /// Wall time of the analysis in microseconds.
    pub solve_time_us: f64,
}

/// `x` when finite, else null.
pub(super) fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// Relative distance from ±α within which a joint angle names a springing: a springing
/// found from α in radians reads 59.99999999999999° for α = 60° and is written as given.
pub const SPRINGING_NAME_REL: f64 = 1e-12;

impl Solution {
    /// Writes the joint angles of the springings as the half-angle given (60, not the
    /// 59.99999999999999 of a round trip through radians), within [`SPRINGING_NAME_REL`].
    pub fn name_springings_as_given(&mut self) {
        let alpha = self.half_angle_deg;
        let snap = |a: &mut f64| {
            if (a.abs() - alpha).abs() <= SPRINGING_NAME_REL * alpha {
                *a = alpha.copysign(*a);
            }
        };
        for h in self
            .hinges
            .iter_mut()
            .chain(&mut self.collapse_hinges)
            .chain(&mut self.hinges_min)
            .chain(&mut self.hinges_max)
        {
            snap(&mut h.angle_deg);
        }
        for j in self
            .sliding_joints
            .iter_mut()
            .chain(&mut self.collapse_sliding_joints)
            .chain(&mut self.sliding_joints_min)
            .chain(&mut self.sliding_joints_max)
        {
            snap(&mut j.angle_deg);
        }
        self.collapse_lifted_joints.iter_mut().for_each(snap);
    }

    /// Fills the position of a point load not given in its own terms (the angle of an x/L
    /// position, the x/L of an angle) from the model of the scene at its K.
    pub fn set_point_position(&mut self, model: &ArchModel) {
        if let Some((at_deg, at_x)) = model.point_position() {
            self.at_deg = self.at_deg.or(Some(at_deg));
            self.at_x = self.at_x.or(at_x);
        }
    }

    /// The inputs of a scene with every output null; a point load's position both as an
    /// angle and as x/L (but for a `thickness` scene, whose K is not yet known).
    pub fn with_position(scene: &Scene) -> Self {
        let mut s = Self::empty(scene);
        if scene.find != Find::Thickness
            && matches!(scene.load, Load::Point { .. } | Load::PointX { .. })
            && let Ok(model) = ArchModel::new(scene.arch, scene.form, scene.load)
        {
            s.set_point_position(&model);
        }
        s
    }

    /// The inputs of a scene with every output null.
    pub fn empty(scene: &Scene) -> Self {
        Self::of_inputs(super::Inputs::of(scene))
    }

    /// The row of a scene with these inputs and every output null.
    pub fn of_inputs(i: super::Inputs) -> Self {
        Solution {
            find: i.find,
            k: i.k,
            t_over_r: i.t_over_r,
            mu: i.mu,
            mu_infinite: i.mu_infinite,
            half_angle_deg: i.half_angle_deg,
            weight: i.weight,
            voussoirs: i.voussoirs,
            shape: i.shape,
            eccentricity: i.eccentricity,
            joints: i.joints,
            keystone: i.keystone,
            load: i.load,
            at_deg: i.at_deg,
            at_x: i.at_x,
            load_width: i.load_width,
            lambda: i.lambda,
            outcome: None,
            regime: None,
            thrust_r_min: None,
            thrust_r_max: None,
            thrust_s_min: None,
            thrust_s_max: None,
            k_crit: None,
            t_over_r_crit: None,
            k_windows: Vec::new(),
            k_windows_scanned_to: None,
            k_windows_resolution: None,
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
            mechanism_admissible: None,
            critical_apex_shared: None,
            gap: None,
            collapse_value: None,
            gap_width: None,
            gap_searched_to: None,
            collapse_mechanism: None,
            collapse_hinges: Vec::new(),
            collapse_sliding_joints: Vec::new(),
            collapse_lifted_joints: Vec::new(),
            collapse_thrust_over_half_weight: None,
            collapse_crown_shear: None,
            collapse_crown_moment: None,
            collapse_work_loads: None,
            collapse_work_friction: None,
            collapse_work_residual: None,
            collapse_flow_violation: None,
            collapse_on_loading: None,
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

    /// Records a critical value's outcome and, when found, its limit state.
    pub(super) fn set_critical(&mut self, c: &Critical) -> Option<CriticalState> {
        self.outcome = Some(Outcome::of_critical(c));
        let s = c.found()?.clone();
        self.mechanism = Some(s.mechanism.kind);
        self.thrust_over_half_weight = finite(s.thrust_over_half_weight);
        self.crown_moment = finite(s.crown_moment);
        self.hinges = s.mechanism.hinges.clone();
        self.sliding_joints = s.mechanism.sliding_joints.clone();
        Some(s)
    }

    /// The collapse mechanism of a found critical state and its work equation.
    pub(super) fn set_mechanism(&mut self, arch: &Arch, s: &CriticalState) {
        let m = collapse_mechanism(arch, s);
        self.mechanism_dof = Some(m.mechanism_dof);
        self.mechanism_admissible = m
            .field
            .is_some()
            .then_some(m.status == ModeStatus::Admissible);
        if let Some(w) = m.work {
            self.work_loads = finite(w.work_loads);
            self.work_friction = finite(w.work_friction);
            self.work_residual = finite(w.work_residual);
        }
    }

    /// Records the search for the first complete solution of a critical find: its status, the
    /// collapse value and its mechanism, the width of the gap to the static limit
    /// `static_value` along the path (`toward_static` is +1 when the path reaches the static
    /// limit by increasing its parameter, −1 otherwise).
    pub(super) fn set_gap(
        &mut self,
        search: &GapSearch,
        static_value: Option<f64>,
        toward_static: f64,
    ) {
        self.gap = Some(search.status);
        self.gap_searched_to = finite(search.range[1]);
        let Some(c) = &search.first else {
            return;
        };
        // Without a gap the collapse is the static limit itself.
        let v = match (search.status, static_value) {
            (GapStatus::NoGap, Some(s)) => s,
            _ => c.value,
        };
        self.collapse_value = finite(v);
        self.gap_width = static_value.map(|s| {
            if search.status == GapStatus::NoGap {
                0.0
            } else {
                toward_static * (s - v)
            }
        });
        let y = c.state.y;
        self.collapse_thrust_over_half_weight = finite(y[0]);
        self.collapse_crown_shear = finite(y[1]);
        self.collapse_crown_moment = finite(-y[2]);
        let m = &c.mechanism;
        if let Some(k) = &m.mechanism {
            self.collapse_mechanism = Some(k.kind);
            self.collapse_hinges = k.hinges.clone();
            self.collapse_sliding_joints = k.sliding_joints.clone();
        }
        self.collapse_lifted_joints = m.lifted_deg.clone();
        if self.collapse_mechanism.is_none() && !m.lifted_deg.is_empty() {
            // A mechanism of lift-offs alone (a whole part tipping away) turns about no hinge
            // and slides on no joint: it is rotational.
            self.collapse_mechanism = Some(MechanismKind::Rotational);
        }
        self.collapse_work_loads = finite(m.work.work_loads);
        self.collapse_work_friction = finite(m.work.work_friction);
        self.collapse_work_residual = finite(m.work.work_residual);
        self.collapse_flow_violation = finite(m.work.flow_violation);
    }

    /// A thickness or friction `search` that met no complete state on its way through its
    /// static limit, whose own mechanism obeys every flow rule there
    /// (`mechanism_admissible`, with its work equation): the static limit is itself a
    /// complete solution, and the first. The walk stops just short of the limit and steps
    /// past it, and a symmetric limit state, where more rows than a vertex holds meet at
    /// once, can be missed by both steps. `collapse_flow_violation` stays null: the static
    /// route checks that mechanism with its own tolerance.
    pub(super) fn complete_at_static_limit(&mut self, search: &GapSearch, tol_work: f64) {
        let Some(value) = search.static_limit else {
            return;
        };
        if !search.met_nothing
            || self.gap != Some(GapStatus::NoCompleteSolution)
            || self.mechanism_admissible != Some(true)
            || !self.work_residual.is_some_and(|r| r <= tol_work)
            || !value.is_finite()
        {
            return;
        }
        self.gap = Some(GapStatus::NoGap);
        self.collapse_value = Some(value);
        self.gap_width = Some(0.0);
        self.collapse_mechanism = self.mechanism;
        self.collapse_hinges = self.hinges.clone();
        self.collapse_sliding_joints = self.sliding_joints.clone();
        self.collapse_lifted_joints = Vec::new();
        self.collapse_thrust_over_half_weight = self.thrust_over_half_weight;
        self.collapse_crown_shear = self.crown_shear;
        self.collapse_crown_moment = self.crown_moment;
        self.collapse_work_loads = self.work_loads;
        self.collapse_work_friction = self.work_friction;
        self.collapse_work_residual = self.work_residual;
        self.collapse_flow_violation = None;
    }

    /// Records the windows of a thickness find.
    pub(super) fn set_windows(&mut self, w: Option<&Windows>) {
        let Some(w) = w else {
            return;
        };
        self.k_windows = w.windows.iter().map(|w| (w.from, w.to)).collect();
        self.k_windows_scanned_to = Some(w.scanned_to);
        self.k_windows_resolution = Some(w.resolution);
    }

    /// True when a thickness find found that a thicker arch than K_c fails again: more than
    /// one window, or one that closes before the end of the scan.
    pub fn fails_again(&self) -> bool {
        crate::analysis::windows::fails_again(&self.k_windows)
    }

    /// The regime (state find).
    pub fn regime(&self) -> Option<Regime> {
        self.regime
    }
}
