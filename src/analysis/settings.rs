//! Named tolerances and limits of every analysis route, one struct per route.
//!
//! Every default is the number the route has always used, so results do not depend on
//! whether a caller passes [`Settings::default`] or relies on a thin wrapper. Units follow
//! the normalisation of [`crate::analysis`]: thrusts over W_half, moments over W_half·r,
//! lengths over r, angles in radians unless a field says degrees.

/// Settings of the dense linear-programme solver ([`crate::analysis::lp`]); tolerances are
/// relative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LpSettings {
    /// Largest number of simplex steps (default 10 000; [`LpSettings::for_rows`] adds
    /// `iterations_per_row` per row).
    pub max_iterations: usize,
    /// Extra simplex steps allowed per row by [`LpSettings::for_rows`] (default 4).
    pub iterations_per_row: usize,
    /// A row is violated when its distance a·x − b over |a| exceeds
    /// `tol_feasibility`·(1 + |x|∞) (default 1e-13, relative).
    pub tol_feasibility: f64,
    /// Smallest normalised pivot |a_B| u_k / |a_r| accepted in the ratio test (default 1e-10).
    pub tol_pivot: f64,
    /// Tolerance on the multipliers y, relative to max |c| (default 1e-12).
    pub tol_dual: f64,
    /// A basis whose LU pivot falls below this times its largest entry is singular
    /// (default 1e-14, relative).
    pub tol_singular: f64,
    /// Consecutive degenerate steps before switching to Bland's rule (default 12).
    pub degenerate_steps_before_bland: usize,
}

impl LpSettings {
    /// The defaults: the values the solver has always used.
    pub const DEFAULT: Self = LpSettings {
        max_iterations: 10_000,
        iterations_per_row: 4,
        tol_feasibility: 1e-13,
        tol_pivot: 1e-10,
        tol_dual: 1e-12,
        tol_singular: 1e-14,
        degenerate_steps_before_bland: 12,
    };

    /// The defaults with an iteration limit scaled to `rows` (10 000 + 4·rows).
    pub fn for_rows(rows: usize) -> Self {
        Self::DEFAULT.scaled_to(rows)
    }

    /// These settings with `max_iterations` raised by `iterations_per_row` per row.
    pub fn scaled_to(&self, rows: usize) -> Self {
        LpSettings {
            max_iterations: self.max_iterations + self.iterations_per_row * rows,
            ..*self
        }
    }
}

impl Default for LpSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Settings of the general route ([`crate::analysis::general`]); tolerances are relative to
/// 1 + |x|∞ unless stated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneralSettings {
    /// Settings of the linear programme solver.
    pub lp: LpSettings,
    /// Largest number of exchange steps for a continuum (default 200).
    pub max_exchange_iterations: usize,
    /// The exchange stops when no joint violates a row by more than this distance
    /// (default 1e-13).
    pub tol_exchange: f64,
    /// When every violated joint is already a row, a residual up to this many times the LP
    /// feasibility tolerance counts as converged (default 10, a factor).
    pub lp_residual_factor: f64,
    /// Joints of the first exchange step, equally spaced over [−α, α], ends included
    /// (default 17).
    pub exchange_initial_joints: usize,
    /// Sampling intervals over [−α, α] in the search for the most violated joint
    /// (default 64).
    pub exchange_samples: usize,
    /// Local maxima of each condition refined per search (default 4).
    pub exchange_maxima: usize,
    /// Absolute tolerance of the 1-D refinement of a most violated joint, relative to
    /// max(α, `joint_search_min_span`) (default 1e-10).
    pub tol_joint_search: f64,
    /// Smallest half-angle, radians, that scales `tol_joint_search` (default 1e-3).
    pub joint_search_min_span: f64,
    /// A sampled local maximum of a joint's violation is refined unless even a generous
    /// bound on its rise between the neighbouring samples leaves it below −`tol_refine`
    /// (default 1e-6; keep it well above `tol_active`, so no active joint goes unrefined).
    pub tol_refine: f64,
    /// The refinement of a most violated joint stops when a short parabolic step changes
    /// the violation by no more than this (relative, default 1e-15; keep it well below
    /// `tol_exchange`): rounding then hides where the maximum lies any closer.
    pub tol_refine_flat: f64,
    /// Upper bound τ_cap of the margin, in units of x (default 1).
    pub margin_cap: f64,
    /// A margin ≥ −`tol_margin` counts as feasible: limit states are admissible
    /// (default 1e-12, absolute; keep it above `tol_exchange`).
    pub tol_margin: f64,
    /// A row is active when its distance to x is within this of the margin (default 1e-9).
    pub tol_active: f64,
    /// A margin solution is a limit state (and names a mechanism) when |τ| is within this
    /// (default 1e-6).
    pub tol_limit_state: f64,
    /// Extra relaxation of every row when testing which active rows are necessary
    /// (default 1e-14).
    pub tol_necessary_relax: f64,
    /// Two active joints within this (degrees, relative to 1 + |angle|) are one joint
    /// (default 1e-9).
    pub tol_same_joint: f64,
    /// A joint shorter than this (over r) has shrunk to a point: hinges on both of its faces
    /// are the thrust passing through it (default 1e-6).
    pub tol_point_joint: f64,
    /// Neighbouring joints of a voussoir arch closer than this (joint parameter, radians)
    /// that are active with one condition are one contact of the thrust line, which comes
    /// within `tol_active` of the boundary at all of them (their slack grows as the square of
    /// the spacing): only the joint it comes closest to is kept (default 1e-3, about 3,000
    /// voussoirs on a semicircle; coarser arches keep every active joint).
    pub band_joint_spacing: f64,
    /// K = 1 + this starts a thickness search (default 1e-12, dimensionless).
    pub k_search_offset: f64,
    /// K of the first upper bracket of a thickness search (default 1.5, dimensionless).
    pub k_search_start: f64,
    /// Largest K − 1 explored when bracketing a critical thickness (default 1e9).
    pub max_bracket: f64,
    /// Fraction of K_max − 1 kept clear of the end of a family of arches (default 1e-9).
    pub family_end_clearance: f64,
    /// Absolute tolerance of the root in K of a thickness search (default 1e-15).
    pub tol_thickness: f64,
    /// Absolute tolerance, radians, of the root in φ of a friction search (default 1e-16).
    pub tol_friction_angle: f64,
    /// Load factor λ held fixed in margins, regimes and critical values (default 0; a load
    /// parameter, not a tolerance).
    pub lambda: f64,
    /// Margins of an arch whose form and loads are mirror images about the crown's vertical
    /// are solved on its right half with zero crown shear, the symmetric unknowns (default
    /// true; a choice of route, not a tolerance): the same margin from half the joints.
    /// False solves every arch over all its joints in three unknowns.
    pub symmetric_half: bool,
}

impl GeneralSettings {
    /// The defaults: the values the general route has always used.
    pub const DEFAULT: Self = GeneralSettings {
        lp: LpSettings::DEFAULT,
        max_exchange_iterations: 200,
        tol_exchange: 1e-13,
        lp_residual_factor: 10.0,
        exchange_initial_joints: 17,
        exchange_samples: 64,
        exchange_maxima: 4,
        tol_joint_search: 1e-10,
        joint_search_min_span: 1e-3,
        tol_refine: 1e-6,
        tol_refine_flat: 1e-15,
        margin_cap: 1.0,
        tol_margin: 1e-12,
        tol_active: 1e-9,
        tol_limit_state: 1e-6,
        tol_necessary_relax: 1e-14,
        tol_same_joint: 1e-9,
        tol_point_joint: 1e-6,
        band_joint_spacing: 1e-3,
        k_search_offset: 1e-12,
        k_search_start: 1.5,
        max_bracket: 1e9,
        family_end_clearance: 1e-9,
        tol_thickness: 1e-15,
        tol_friction_angle: 1e-16,
        lambda: 0.0,
        symmetric_half: true,
    };
}

impl Default for GeneralSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Settings of the symmetric two-unknown route ([`crate::analysis::symmetric`]): thrusts over
/// W_half, moments over W_half·r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetricSettings {
    /// Tolerance on margins for classification: a state within it of a limit is a limit
    /// state and counts as admissible (default 1e-12). Far below the 1e-9 to which critical
    /// values are reported, above the rounding of the inputs (a μ_min or K_c typed to 12
    /// digits lies within it).
    pub tol_margin: f64,
    /// A face of the arch counts as touched by the limit line of thrust, and an end of H^s
    /// as reached, within this relative distance when naming a mechanism (default 1e-9).
    pub tol_hinge: f64,
    /// Asymptotic slopes of Φ below this count as zero: Φ is constant (default 1e-13).
    pub tol_flat: f64,
    /// Absolute tolerance of a thrust found as a peak or a root of Φ (default 1e-15).
    pub tol_thrust: f64,
    /// Offset added to a margin on its plateau when locating a limit (default 1e-13).
    pub tol_plateau: f64,
    /// Absolute tolerance of the root in K or φ of a limit search (default 1e-15).
    pub tol_limit_root: f64,
    /// Absolute tolerance, radians, of the root in φ of the sliding threshold (default 1e-16).
    pub tol_friction_angle: f64,
    /// A joint within this many degrees of the crown is the crown (default 1e-12).
    pub tol_crown_deg: f64,
    /// Two mirrored joints within this many degrees are one joint (default 1e-9).
    pub tol_same_joint_deg: f64,
    /// K = 1 + this starts a thickness search (default 1e-12, dimensionless).
    pub k_search_offset: f64,
    /// K of the first upper bracket of a thickness search (default 1.5, dimensionless).
    pub k_search_start: f64,
    /// Largest |h| or K − 1 explored when looking for brackets (default 1e9).
    pub max_bracket: f64,
}

impl SymmetricSettings {
    /// The defaults: the values the symmetric route has always used.
    pub const DEFAULT: Self = SymmetricSettings {
        tol_margin: 1e-12,
        tol_hinge: 1e-9,
        tol_flat: 1e-13,
        tol_thrust: 1e-15,
        tol_plateau: 1e-13,
        tol_limit_root: 1e-15,
        tol_friction_angle: 1e-16,
        tol_crown_deg: 1e-12,
        tol_same_joint_deg: 1e-9,
        k_search_offset: 1e-12,
        k_search_start: 1.5,
        max_bracket: 1e9,
    };
}

impl Default for SymmetricSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Settings of the per-K-line analysis of symmetric self-weight state grids on forms other
/// than the circular arch with radial joints (pointed arches, vertical joints).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineSettings {
    /// Friction-angle step, radians, above the sliding threshold μ_s(K) at which a K line is
    /// tested for a mixed band when the mixed/sliding bifurcation is located (default 1e-11:
    /// above the margin noise of 1e-12, below the 1e-9 to which boundaries are located).
    pub band_friction_step: f64,
}

impl LineSettings {
    /// The defaults.
    pub const DEFAULT: Self = LineSettings {
        band_friction_step: 1e-11,
    };
}

impl Default for LineSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Settings of the kinematic (mechanism) analysis ([`crate::analysis::kinematics`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicsSettings {
    /// Relative rank tolerance of the compatibility system: a singular value below this times
    /// the largest one (or 1, whichever is larger) counts as zero (default 1e-9). The entries
    /// are unit vector components and lengths over r, so this is far above rounding (1e-15)
    /// and far below any genuine stiffness of joints a fraction of a degree apart.
    pub tol_rank: f64,
    /// A relative rotation or slip below this, on a field normalised to a largest
    /// block-corner speed of 1, counts as zero: the joint does not move (default 1e-9).
    pub tol_motion: f64,
    /// Two joints closer than this, radians (about 1e-9°), are the same joint (default 1e-11).
    pub tol_same_joint: f64,
    /// A joint up to this many degrees outside a springing is put on it (default 1e-9).
    pub tol_springing_deg: f64,
    /// A sliding joint of a mechanism is matched to a joint of a field within this many
    /// degrees (default 1e-7).
    pub tol_match_deg: f64,
    /// A direction satisfies a cone constraint g·c ≥ −this (default 1e-9).
    pub tol_cone: f64,
    /// Two unit rays closer than this (sum of component differences) are one ray
    /// (default 1e-6).
    pub tol_same_ray: f64,
    /// Below this rotation amplitude, radians, a displaced point uses the small-angle series
    /// (default 1e-8).
    pub small_rotation: f64,
    /// Largest number of SVD iterations of a null-space computation (default 500).
    pub max_svd_iterations: usize,
    /// A mechanism satisfies the work equation (eq. 11) when its relative residual
    /// |dL^(a) + dL^(r,t)| / scale is at most this (default 1e-6): the states come from
    /// linear programmes solved to about 1e-9 of their scale, so an exact mechanism of an
    /// exact state leaves a residual of that order, and a wrong one of order 1.
    pub tol_work: f64,
}

impl KinematicsSettings {
    /// The defaults: the values the kinematic analysis has always used.
    pub const DEFAULT: Self = KinematicsSettings {
        tol_rank: 1e-9,
        tol_motion: 1e-9,
        tol_same_joint: 1e-11,
        tol_springing_deg: 1e-9,
        tol_match_deg: 1e-7,
        tol_cone: 1e-9,
        tol_same_ray: 1e-6,
        small_rotation: 1e-8,
        max_svd_iterations: 500,
        tol_work: 1e-6,
    };
}

impl Default for KinematicsSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Settings of the arch geometries ([`crate::analysis::circular`], [`crate::analysis::forms`]):
/// series switches and rounding thresholds of their closed forms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeometrySettings {
    /// Below this |θ|, radians, θ cot θ and its derivative use their series (default 1e-4).
    pub series_switch: f64,
    /// Sliding-row coefficients (sines) below this are rounding noise of an exact zero
    /// (default 1e-14).
    pub tol_zero_coefficient: f64,
    /// The two end joints tie for the extrados minimum within this relative difference
    /// (default 1e-14).
    pub tol_tie: f64,
    /// Absolute tolerance, radians, of the interior joint where the sliding bound peaks
    /// (default 1e-16).
    pub tol_sliding_peak: f64,
    /// Largest Newton steps of θ cot θ = c (default 100).
    pub max_newton_steps: usize,
    /// A vertical-joint arch may reach this far, radians, past a half-angle of 90°
    /// (default 1e-12).
    pub tol_vertical_alpha: f64,
    /// Relative slack on |θ| ≤ α when checking the position of a point load (default 1e-15).
    pub tol_joint_range: f64,
    /// A patch load may reach this far, as a fraction of the span, past a springing: the
    /// rounding of a centre given in degrees (default 1e-12).
    pub tol_patch_span: f64,
}

impl GeometrySettings {
    /// The defaults: the values the geometries have always used.
    pub const DEFAULT: Self = GeometrySettings {
        series_switch: 1e-4,
        tol_zero_coefficient: 1e-14,
        tol_tie: 1e-14,
        tol_sliding_peak: 1e-16,
        max_newton_steps: 100,
        tol_vertical_alpha: 1e-12,
        tol_joint_range: 1e-15,
        tol_patch_span: 1e-12,
    };
}

impl Default for GeometrySettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Settings of the search for the first complete solution ([`crate::analysis::gap`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GapSettings {
    /// A row is tight at a vertex when |a·y − b| ≤ this·(1 + |y|∞), rows of unit length
    /// (default 1e-9).
    pub tol_tight: f64,
    /// Twists are positively dependent when the origin lies within this of their convex hull,
    /// unit twists (default 1e-9).
    pub tol_complete: f64,
    /// Weights below this do not move a joint; also the tolerance of the hull's own steps
    /// (default 1e-12).
    pub tol_hull: f64,
    /// A complete solution before the static limit by more than this·(1 + |limit|) along the
    /// path opens a gap; one closer is the static limit itself (default 1e-7).
    pub tol_gap: f64,
    /// A complete state on a thickness or friction path before its static limit starts a
    /// mechanism only when the loads do more work than this on it, over W_half·r at a
    /// largest block-corner speed of 1: a mechanism they do no work on (and which
    /// dissipates nothing) is a neutral configuration that nothing drives, as thick pointed
    /// arches show near their largest K. Rounding leaves such works near 1e-16; mechanisms
    /// that collapse an arch do work of order 1e-3 to 1 (default 1e-9).
    pub tol_driving_work: f64,
    /// Largest load factor searched (default 1e3, as the confirmation of unbounded answers).
    pub lambda_cap: f64,
    /// Largest |F_x|, |F_y|, |M₀| searched, over W_half and W_half·r (default 1e6).
    pub state_cap: f64,
    /// Largest number of vertices the walk visits (default 200 000).
    pub max_vertices: usize,
    /// Largest number of tight rows at a vertex whose triples are tried as edges (default 24).
    pub max_tight: usize,
    /// Joints sampled per family of a continuum before the exchange adds any (default 9,
    /// ends included).
    pub continuum_joints: usize,
    /// A discrete arch with more joints than this is walked on some of its joints first
    /// (`discrete_joints` of them, evenly spaced, the springings among them), and the joints
    /// where the walk's answer violates a row are added until it violates none, as on a
    /// continuum (default 65: a walk over every joint costs about the cube of their number).
    pub exchange_above: usize,
    /// Joints of a large discrete arch walked before the exchange adds any (default 17).
    pub discrete_joints: usize,
    /// Largest number of joints a walk takes: an exchange that would walk more fails rather
    /// than run on (default 401).
    pub max_walk_joints: usize,
    /// Largest number of polytopes a friction or thickness search walks, over all its
    /// exchange rounds; beyond it the search fails rather than run on (default 3000).
    pub max_slices: usize,
    /// Largest number of exchange rounds on a continuum (default 60).
    pub max_exchange_rounds: usize,
    /// Tolerance of the parameter of a complete solution located between two steps of a path,
    /// relative to 1 + |p| (default 1e-13).
    pub tol_path: f64,
    /// μ at which a friction path starts (default 1e3; μ = ∞ makes the Coulomb rows one).
    pub mu_start: f64,
    /// Step of a friction path in φ = atan μ, degrees, before halving (default 1: at 2° the
    /// semicircle with vertical joints loses, at K = 1.144, the vertex where its crown part
    /// starts to drop at μ = 2.094 and reports 1.962).
    pub phi_step_deg: f64,
    /// Step of a thickness path in K before halving (default 0.05).
    pub k_step: f64,
    /// Steps a path goes on beyond its static limit until its polytope is empty (default 200:
    /// sampled joints of a continuum stand a little further than the continuum).
    pub max_steps_beyond: usize,
    /// Two unit twists of tight rows are one plane when no component differs by more than
    /// this (the extrados hinge rows on the two sides of a point load, which acts at that
    /// point; default 1e-12: rounding of the same computation).
    pub tol_same_twist: f64,
    /// Four twists of a vertex cut off between two steps are tried as a complete event when
    /// their hull lies within this of the origin at the later step (default 1e-2: they move
    /// with K).
    pub tol_event: f64,
    /// The step of a path at its static limit stops this far short of it, relative to
    /// 1 + |limit| (default 1e-10; keep it well below `tol_gap`).
    pub end_offset: f64,
    /// A complete state solved on the continuum holds its rows to this, relative to
    /// 1 + |y|∞ (default 1e-13).
    pub tol_refine: f64,
    /// A friction path skips its steps down to this far (radians of atan μ) above the
    /// steepest resultant of its first polytope's vertices: above that angle no Coulomb row
    /// can be tight and every polytope is the first one (default 1e-6).
    pub friction_skip_margin: f64,
}

impl GapSettings {
    /// The defaults.
    pub const DEFAULT: Self = GapSettings {
        tol_tight: 1e-9,
        tol_complete: 1e-9,
        tol_hull: 1e-12,
        tol_gap: 1e-7,
        tol_driving_work: 1e-9,
        lambda_cap: 1e3,
        state_cap: 1e6,
        max_vertices: 200_000,
        max_tight: 24,
        continuum_joints: 9,
        exchange_above: 65,
        discrete_joints: 17,
        max_walk_joints: 401,
        max_slices: 3000,
        max_exchange_rounds: 60,
        tol_path: 1e-13,
        mu_start: 1e3,
        phi_step_deg: 1.0,
        k_step: 0.05,
        max_steps_beyond: 200,
        tol_same_twist: 1e-12,
        tol_event: 1e-2,
        tol_refine: 1e-13,
        end_offset: 1e-10,
        friction_skip_margin: 1e-6,
    };
}

impl Default for GapSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The settings of every analysis route.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Settings {
    /// The symmetric two-unknown route.
    pub symmetric: SymmetricSettings,
    /// The general three-unknown route (with its LP solver settings).
    pub general: GeneralSettings,
    /// The kinematic (mechanism) analysis.
    pub kinematics: KinematicsSettings,
    /// The arch geometries.
    pub geometry: GeometrySettings,
    /// The search for the first complete solution.
    pub gap: GapSettings,
}

impl Settings {
    /// The defaults of every route.
    pub const DEFAULT: Self = Settings {
        symmetric: SymmetricSettings::DEFAULT,
        general: GeneralSettings::DEFAULT,
        kinematics: KinematicsSettings::DEFAULT,
        geometry: GeometrySettings::DEFAULT,
        gap: GapSettings::DEFAULT,
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lp_iteration_limit_scales_with_rows() {
        assert_eq!(LpSettings::for_rows(0).max_iterations, 10_000);
        assert_eq!(LpSettings::for_rows(100).max_iterations, 10_400);
    }

    #[test]
    fn default_is_the_const_default() {
        assert_eq!(Settings::default(), Settings::DEFAULT);
    }
}
